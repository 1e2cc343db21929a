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

  /**
   * The nodal fields of one explicit step: what particle-to-grid writes
   * (mass, momentum, force), what the nodal update makes of them
   * (velocity at the start of the step, end-of-step velocity, and the
   * acceleration consistent with the constrained velocity change), and
   * what grid-to-particle reads. Mass is lumped and stored in each
   * component's entry.
   */
  struct NodalFields
  {
    NodalVector mass;
    NodalVector momentum;
    NodalVector force;
    /// Constrained nodal velocity at the start of the step.
    NodalVector velocity;
    /// Constrained nodal velocity at the end of the step.
    NodalVector velocity_new;
    NodalVector acceleration;
  };
} // namespace MPM

#endif
