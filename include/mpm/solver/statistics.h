#ifndef mpm_solver_statistics_h
#define mpm_solver_statistics_h

#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/particles/property_pool.h>

namespace MPM
{
  using namespace dealii;

  /**
   * Global sums over all material points (and all ranks) at one instant.
   */
  template <int dim>
  struct GlobalStatistics
  {
    double                time = 0;
    double                time_step = 0;
    unsigned int          step = 0;
    types::particle_index n_points = 0;
    double                mass = 0;
    double                volume = 0;
    Tensor<1, dim>        momentum;
    Tensor<1, dim>        mean_velocity;
    double                kinetic_energy = 0;
    double                strain_energy  = 0;
    double                gravitational_potential_energy = 0;
    /// Kinetic + strain + potential energy that the points removed so far
    /// ('Points leaving the mesh = remove') carried when they left.
    double                removed_energy = 0;
    double                mean_speed     = 0;
    double                max_speed      = 0;
    Tensor<1, dim>        centre_of_mass;
    /// With pore water: the water's mass sum n rho_w V, momentum sum
    /// n rho_w V v_w, and the mean pore pressure over the saturated
    /// points' volume (the fields above are the skeleton's, but for the
    /// energies, which hold both phases).
    double                water_mass = 0;
    Tensor<1, dim>        water_momentum;
    double                mean_pore_pressure = 0;
  };
} // namespace MPM

#endif
