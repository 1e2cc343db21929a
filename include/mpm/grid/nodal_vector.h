#ifndef mpm_grid_nodal_vector_h
#define mpm_grid_nodal_vector_h

#include <deal.II/lac/la_parallel_vector.h>

namespace MPM
{
  /**
   * The vector type of every nodal field (mass, momentum, force, velocity).
   * deal.II's own distributed vector: its local elements are contiguous
   * (owned entries first, then ghosts), so the hot loops index it with
   * precomputed local indices, and compress(add) sums the contributions
   * of neighbouring ranks to shared nodes.
   */
  using NodalVector = dealii::LinearAlgebra::distributed::Vector<double>;
} // namespace MPM

#endif
