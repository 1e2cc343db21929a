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
  void
  SimulatorAccess<dim>::initialize_simulator(Simulator<dim> &simulator)
  {
    Assert(this->simulator == nullptr || this->simulator == &simulator,
           ExcMessage("This component already belongs to another run."));
    this->simulator = &simulator;
  }


  template <int dim>
  const BackgroundGrid<dim> &
  SimulatorAccess<dim>::get_grid() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->grid;
  }


  template <int dim>
  const CellDofTable<dim> &
  SimulatorAccess<dim>::get_cell_dofs() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->cell_dofs;
  }


  template <int dim>
  const PeriodicNodeGroups &
  SimulatorAccess<dim>::get_periodic_nodes() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->periodic_nodes;
  }


  template <int dim>
  const Particles::ParticleHandler<dim> &
  SimulatorAccess<dim>::get_particle_handler() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->particle_handler;
  }


  template <int dim>
  Particles::ParticleHandler<dim> &
  SimulatorAccess<dim>::get_mutable_particle_handler() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->particle_handler;
  }


  template <int dim>
  PointUpdate<dim> &
  SimulatorAccess<dim>::get_point_update() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->point_update;
  }


  template <int dim>
  NodalFields &
  SimulatorAccess<dim>::get_nodal_fields() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->nodal;
  }


  template <int dim>
  const VelocityTransfer<dim> &
  SimulatorAccess<dim>::get_transfer() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->transfer;
  }


  template <int dim>
  const TimeSteppingParameters<dim> &
  SimulatorAccess<dim>::get_time_stepping() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->time_stepping;
  }


  template <int dim>
  unsigned int
  SimulatorAccess<dim>::get_step() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->step;
  }


  template <int dim>
  double
  SimulatorAccess<dim>::get_time_step() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->time_step;
  }


  template <int dim>
  TimerOutput &
  SimulatorAccess<dim>::get_timer() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->timer;
  }


  template <int dim>
  double
  SimulatorAccess<dim>::get_time() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->time;
  }


  template <int dim>
  const MaterialLibrary &
  SimulatorAccess<dim>::get_materials() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->materials;
  }


  template <int dim>
  const PoreWater<dim> &
  SimulatorAccess<dim>::get_pore_water() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->pore_water;
  }


  template <int dim>
  const BoundaryConditions<dim> &
  SimulatorAccess<dim>::get_boundary_conditions() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->boundary_conditions;
  }


  template <int dim>
  MPI_Comm
  SimulatorAccess<dim>::get_mpi_communicator() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->mpi_communicator;
  }


  template <int dim>
  const std::string &
  SimulatorAccess<dim>::get_output_directory() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->output_writer.directory();
  }


  template <int dim>
  GlobalStatistics<dim>
  SimulatorAccess<dim>::compute_statistics() const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->compute_statistics();
  }


  template <int dim>
  std::pair<Tensor<1, 3>, double>
  SimulatorAccess<dim>::spin_angular_momentum(
    const Point<dim>     &centre,
    const Tensor<1, dim> &mean_velocity) const
  {
    Assert(simulator != nullptr, ExcNotInitialized());
    return simulator->spin_angular_momentum(centre, mean_velocity);
  }


  template class SimulatorAccess<2>;
  template class SimulatorAccess<3>;
} // namespace MPM
