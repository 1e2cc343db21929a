#ifndef mpm_solver_simulator_access_h
#define mpm_solver_simulator_access_h

#include <deal.II/base/timer.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/solver/statistics.h>

#include <array>
#include <string>
#include <utility>

namespace MPM
{
  using namespace dealii;

  template <int dim>
  class Simulator;
  template <int dim>
  class BackgroundGrid;
  template <int dim>
  class CellDofTable;
  template <int dim>
  class PointUpdate;
  template <int dim>
  struct TimeSteppingParameters;
  template <int dim>
  class VelocityTransfer;
  template <int dim>
  class PoreWater;
  template <int dim>
  class BoundaryConditions;
  class MaterialLibrary;
  class NodalFields;
  class PeriodicNodeGroups;

  /**
   * The one way for a component of a run to reach the run's state, as
   * ASPECT's SimulatorAccess: a component that needs the points, the
   * mesh, the step's nodal fields or the time derives from this class
   * and asks for them by name, instead of being handed a bundle of
   * references to what its constructor happened to need. The Simulator
   * owns everything; a SimulatorAccess only points at it, so what the
   * Simulator parses or updates after creating a component (the time
   * step, the nodal fields of a new partition) is what the component
   * sees.
   *
   * The getters are defined out of line (source/solver/simulator_access.cc)
   * so that this header does not need the Simulator's: a component's
   * header includes this one, and simulator.h includes the components'.
   * A pass that reads a value per point reads it once, before its loop.
   *
   * Mutable access is given to what a component of the step writes: the
   * points (get_mutable_particle_handler(): the particle-grid passes
   * update their properties; every other component reads them through
   * get_particle_handler()), the nodal
   * fields, the point update's findings and the timer.
   *
   * Two ways to attach, as in ASPECT: a component the Simulator creates
   * during its set-up (the particle-grid weights) receives it in its
   * constructor; a plugin that must also exist without a run (a
   * postprocessor whose geometry a unit test reads) is default-constructed
   * and attached by initialize_simulator() before its first use.
   */
  template <int dim>
  class SimulatorAccess
  {
  public:
    /// Attached to @p simulator, whose lifetime must cover this object's.
    explicit SimulatorAccess(Simulator<dim> &simulator);

    /// Not attached: initialize_simulator() must come before any getter.
    SimulatorAccess() = default;

    virtual ~SimulatorAccess() = default;

    /// Attach to @p simulator (once), whose lifetime must cover this
    /// object's.
    void
    initialize_simulator(Simulator<dim> &simulator);

    /// @name The mesh
    /// @{
    const BackgroundGrid<dim> &
    get_grid() const;

    /// The nodal-vector entries of each cell's vertices (every
    /// non-artificial cell of this rank's partition).
    const CellDofTable<dim> &
    get_cell_dofs() const;

    /// The nodal entries that periodic boundaries make one node.
    const PeriodicNodeGroups &
    get_periodic_nodes() const;
    /// @}

    /// @name The points and the nodes
    /// @{
    /// The material points, to read (postprocessors, diagnostics).
    const Particles::ParticleHandler<dim> &
    get_particle_handler() const;

    /// The material points, to change: only the parts of the step that
    /// write the points' properties (the particle-grid weights and
    /// passes).
    Particles::ParticleHandler<dim> &
    get_mutable_particle_handler() const;

    /// A point's new velocity, position and stress from its interpolated
    /// grid values, and what the updates found (PointUpdate::record()).
    PointUpdate<dim> &
    get_point_update() const;

    /// The step's nodal fields, the phases' included.
    NodalFields &
    get_nodal_fields() const;

    /// The velocity transfer scheme ('Transfer/Scheme').
    const VelocityTransfer<dim> &
    get_transfer() const;
    /// @}

    /// @name Time
    /// @{
    /// 'Time stepping', with gravity in the mesh's frame once the run is
    /// set up.
    const TimeSteppingParameters<dim> &
    get_time_stepping() const;

    /// The number of steps done.
    unsigned int
    get_step() const;

    /// The step's time step (s).
    double
    get_time_step() const;

    /// The simulated time (s).
    double
    get_time() const;

    /// The run's timer sections (rank 0's wall times).
    TimerOutput &
    get_timer() const;
    /// @}

    /// @name The scene
    /// @{
    /// The materials of 'Materials'.
    const MaterialLibrary &
    get_materials() const;

    /// The pore water of saturated materials (PoreWater::active()).
    const PoreWater<dim> &
    get_pore_water() const;

    /// The walls and their laws of 'Boundary conditions'.
    const BoundaryConditions<dim> &
    get_boundary_conditions() const;

    MPI_Comm
    get_mpi_communicator() const;

    /// 'Output/Directory', ending in '/'.
    const std::string &
    get_output_directory() const;
    /// @}

    /// @name Sums over all points and ranks (collective)
    /// @{
    /// Simulator::compute_statistics().
    GlobalStatistics<dim>
    compute_statistics() const;

    /// Simulator::spin_angular_momentum().
    std::pair<Tensor<1, 3>, double>
    spin_angular_momentum(const Point<dim>     &centre,
                          const Tensor<1, dim> &mean_velocity) const;
    /// @}

  private:
    Simulator<dim> *simulator = nullptr;
  };
} // namespace MPM

#endif
