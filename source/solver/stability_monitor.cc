#include <mpm/solver/stability_monitor.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace MPM
{
  template <int dim>
  void
  StabilityMonitor<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stability");
    prm.declare_entry("Energy growth factor",
                      "2",
                      Patterns::Double(0),
                      "Stop the run when the mechanical energy (kinetic + "
                      "strain) exceeds this many times the energy the scene "
                      "can have released "
                      "(initial kinetic + strain energy + gravitational "
                      "potential energy released since the start); 0 = no "
                      "energy check. Off by itself when a boundary has a "
                      "prescribed velocity. Non-finite values always stop "
                      "the run.");
    prm.declare_entry("Energy check interval",
                      "100",
                      Patterns::Integer(1),
                      "Steps between two energy checks (each costs a loop "
                      "over the points and a reduction).");
    prm.leave_subsection();
  }


  template <int dim>
  void
  StabilityMonitor<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Stability");
    growth_factor = prm.get_double("Energy growth factor");
    interval      = prm.get_integer("Energy check interval");
    prm.leave_subsection();
  }


  template <int dim>
  void
  StabilityMonitor<dim>::initialize(const GlobalStatistics<dim> &start,
                                    const bool external_work)
  {
    energy_check_on          = growth_factor > 0 && !external_work;
    initial_energy           = start.kinetic_energy + start.strain_energy;
    initial_potential_energy = start.gravitational_potential_energy;
  }


  template <int dim>
  std::string
  StabilityMonitor<dim>::check_energy(const GlobalStatistics<dim> &now) const
  {
    // What the remaining points can have: the initial energy and the
    // potential energy released, less what removed points took away
    // ('Points leaving the mesh = remove'; without it a block that lost
    // its lowest points, which had released the most, stopped as
    // "energy is being created").
    const double available =
      initial_energy +
      std::max(0.,
               initial_potential_energy - now.gravitational_potential_energy -
                 now.removed_energy);
    // Friction, plasticity and damping only dissipate, so kinetic plus
    // strain energy stays below what is available, up to MPM's energy
    // errors (percents). The strain energy counts as well as the kinetic
    // one: an instability held down by damping (the cell-crossing noise
    // on distorted meshes, doc/robustness.md) grows mostly as strain
    // energy.
    const double reference = std::max(available, 1e-300);
    const double mechanical = now.kinetic_energy + now.strain_energy;
    if (mechanical <= growth_factor * reference)
      return "";
    std::ostringstream s;
    s << "the kinetic + strain energy " << now.kinetic_energy << " + "
      << now.strain_energy
      << " J exceeds 'Stability/Energy growth factor' = " << growth_factor
      << " times the energy the scene can have released, " << reference
      << " J (initial kinetic + strain energy + potential energy released"
      << (now.removed_energy != 0 ? ", less the energy of the removed points" :
                                    "")
      << "): energy is being created.";
    return s.str();
  }


  template <int dim>
  std::string
  StabilityMonitor<dim>::advice(const double time_step,
                                const double wave_speed,
                                const double cell_size,
                                const bool   adaptive)
  {
    const double       cfl = time_step * wave_speed / cell_size;
    std::ostringstream s;
    s << "The last step was dt = " << time_step
      << " s, a CFL number of " << cfl << " for the elastic wave speed c = "
      << wave_speed << " m/s on the shortest edge h = " << cell_size
      << " m of the cells holding points. ";
    if (cfl > 0.5)
      s << "The explicit step is stable only below about 1, and a margin is "
           "needed for large deformation: rerun with 'Time stepping/CFL "
           "number = 0.5' or less"
        << (adaptive ? "." : " (set 'Time step selection = cfl', or 'Time "
                             "step' to at most ");
    if (cfl > 0.5 && !adaptive)
      s << 0.5 * cell_size / wave_speed << " s).";
    else
      s << "That is within the elastic stability limit: check the materials "
           "(stiffness, density) and the boundary conditions; if they are "
           "right, try 'Time stepping/CFL number = "
        << 0.5 * cfl << "' (half the present step).";
    return s.str();
  }


  template class StabilityMonitor<2>;
  template class StabilityMonitor<3>;
} // namespace MPM
