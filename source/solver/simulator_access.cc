#include <mpm/solver/simulator.h>
#include <mpm/solver/simulator_access.h>

namespace MPM
{
  template <int dim>
  SimulatorAccess<dim>::SimulatorAccess(Simulator<dim> &simulator)
      : simulator(&simulator)
  {
  }


  template <int dim>
  const BackgroundGrid<dim> &
  SimulatorAccess<dim>::get_grid() const
  {
    return simulator->grid;
  }


  template <int dim>
  const CellDofTable<dim> &
  SimulatorAccess<dim>::get_cell_dofs() const
  {
    return simulator->cell_dofs;
  }


  template <int dim>
  const PeriodicNodeGroups &
  SimulatorAccess<dim>::get_periodic_nodes() const
  {
    return simulator->periodic_nodes;
  }


  template <int dim>
  Particles::ParticleHandler<dim> &
  SimulatorAccess<dim>::get_particle_handler() const
  {
    return simulator->particle_handler;
  }


  template <int dim>
  PointUpdate<dim> &
  SimulatorAccess<dim>::get_point_update() const
  {
    return simulator->point_update;
  }


  template <int dim>
  NodalFields &
  SimulatorAccess<dim>::get_nodal_fields() const
  {
    return simulator->nodal;
  }


  template <int dim>
  const VelocityTransfer<dim> &
  SimulatorAccess<dim>::get_transfer() const
  {
    return simulator->transfer;
  }


  template <int dim>
  const TimeSteppingParameters<dim> &
  SimulatorAccess<dim>::get_time_stepping() const
  {
    return simulator->time_stepping;
  }


  template <int dim>
  unsigned int
  SimulatorAccess<dim>::get_step() const
  {
    return simulator->step;
  }


  template <int dim>
  double
  SimulatorAccess<dim>::get_time_step() const
  {
    return simulator->time_step;
  }


  template <int dim>
  TimerOutput &
  SimulatorAccess<dim>::get_timer() const
  {
    return simulator->timer;
  }


  template class SimulatorAccess<2>;
  template class SimulatorAccess<3>;
} // namespace MPM
