#ifndef mpm_solver_simulator_h
#define mpm_solver_simulator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/boundary_conditions/boundary_conditions.h>
#include <mpm/boundary_conditions/side_wall_friction.h>
#include <mpm/grid/background_grid.h>
#include <mpm/grid/cell_dof_table.h>
#include <mpm/grid/nodal_vector.h>
#include <mpm/material_points/nonlocal_averaging.h>
#include <mpm/material_points/point_generator.h>
#include <mpm/material_points/point_properties.h>
#include <mpm/material_points/point_relocation.h>
#include <mpm/material_points/point_update.h>
#include <mpm/materials/material_library.h>
#include <mpm/output/output_writer.h>
#include <mpm/parallel/load_balancing.h>
#include <mpm/phases/pore_water.h>
#include <mpm/postprocess/postprocessor.h>
#include <mpm/restart/checkpointing.h>
#include <mpm/solver/lost_points.h>
#include <mpm/solver/rest_criterion.h>
#include <mpm/solver/simulator_access.h>
#include <mpm/solver/stability_monitor.h>
#include <mpm/solver/statistics.h>
#include <mpm/solver/statistics_file.h>
#include <mpm/solver/time_step_bounds.h>
#include <mpm/solver/time_stepping.h>
#include <mpm/transfer/particle_grid_weights.h>
#include <mpm/transfer/velocity_transfer.h>

#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The explicit MPM solver with lumped mass. One step (see do_time_step()
   * and doc/algorithm.md):
   *
   *  1. particle-to-grid: nodal mass and momentum;
   *  2. nodal velocity v = p / m, constrained by the boundary conditions;
   *  3. USF only: stress update from the strain rate of this velocity;
   *  4. particle-to-grid: internal force -V sigma grad N and gravity m N g;
   *  5. nodal update: a = f / m, Coulomb friction in each wall node's frame,
   *     v_new = v + dt a, constrained again;
   *  6. grid-to-particle: velocity by the transfer scheme (FLIP/PIC blend,
   *     XPIC, APIC), position with v_new;
   *  7. USL: stress update from v_new; MUSL: point momenta mapped to the
   *     grid again and the stress updated from that velocity;
   *  8. points that left their cell are relocated.
   *
   * The order of 1-7 is the StepScheme's ('Time stepping/Update scheme'),
   * which calls the operations the Simulator offers it (StepOperations).
   * The particle-grid passes (1, 3, 4, 6, 7) are the ParticleGridWeights'
   * chosen in the parameter file; the nodal steps (2, 5) are the
   * Simulator's. Only cells that hold material points take part: every
   * loop runs over the points, grouped by cell, and over the nodes of
   * those cells.
   */
  template <int dim>
  class Simulator : private StepOperations
  {
    /// The components' way to the run's state (doc/extending.md).
    friend class SimulatorAccess<dim>;

  public:
    /**
     * Names of the user-named subsections (materials, point regions,
     * boundaries), known after the first parsing pass.
     */
    struct NameLists
    {
      std::vector<std::string> materials;
      std::vector<std::string> regions;
      std::vector<std::string> boundaries;
    };

    /**
     * First parsing pass: the entries that decide which subsections exist.
     */
    static void
    declare_name_lists(ParameterHandler &prm);

    static NameLists
    read_name_lists(ParameterHandler &prm);

    /**
     * Second pass: every parameter of a run.
     */
    static void
    declare_parameters(ParameterHandler &prm, const NameLists &names);

    explicit Simulator(const MPI_Comm comm);

    ~Simulator();

    void
    parse_parameters(ParameterHandler &prm, const std::string &input_directory);

    /**
     * Set up the scene and run it to the end time.
     */
    void
    run();

  private:
    /**
     * @name Sums over the points, for the run and its components
     * (SimulatorAccess).
     * @{
     */

    /**
     * Sums over all points and ranks.
     */
    GlobalStatistics<dim>
    compute_statistics() const;

    /**
     * Kinetic, strain and gravitational potential energy of the point with
     * properties @p props at @p x: the terms of compute_statistics()'s
     * sums, and what a removed point takes away. A saturated point's
     * water is in them (its kinetic energy, the energy of its compression
     * and its weight's potential); the drag's dissipation and the water
     * that drained out of the points are not.
     */
    std::array<double, 3>
    energy_of_point(const double *props, const Point<dim> &x) const;

    /**
     * The sum over all points and ranks of each point's mass times the
     * shifts periodic boundaries gave it (PointRelocation::Statistics),
     * over the whole run, restarts included. Collective.
     */
    Tensor<1, dim>
    wrapped_mass_shift() const;

    /**
     * Angular momentum about the centre of mass @p centre of the points
     * moving with mean velocity @p mean_velocity (3 components; only z in
     * 2D), and its scale sum_p m_p |x_p - centre| |v_p|.
     * With APIC it includes the affine part of each point's velocity field,
     * m_p sum_i N_i dx_i x (C_p dx_i), the part of the grid's angular
     * momentum that the point carries (Apic::update_affine()).
     * Summed over all ranks.
     */
    std::pair<Tensor<1, 3>, double>
    spin_angular_momentum(const Point<dim>     &centre,
                          const Tensor<1, dim> &mean_velocity) const;
    /** @} */

    /// The run's set-up (simulator_setup.cc): setup_scene(),
    /// setup_time_step_bounds(), setup_nodal_fields(),
    /// setup_point_properties(), create_points(), then the first
    /// statistics and the output files.
    void
    setup();

    /// The mesh, gravity, the walls and the phases, with the checks of
    /// their combination.
    void
    setup_scene();

    /// What limits the step (TimeStepBounds): the materials' waves, and
    /// the pore water's where a material is saturated.
    void
    setup_time_step_bounds();

    /// The points' property slots (fixed, material state, the transfer
    /// scheme's, the weights', the pore water's) and the particle handler
    /// that holds them.
    void
    setup_point_properties();

    /**
     * The material points: generated from 'Material points', or read from
     * the checkpoint on a resumed run (returns the checkpoint's serialized
     * state, else an empty string); then what the first step needs of them
     * (pore water, balanced partition, the transfer scheme's slots).
     */
    std::string
    create_points();

    /**
     * Everything that depends on the partition of the mesh among ranks:
     * the nodal vectors and their ghost layout, the boundary nodes' frames
     * and constraints, the point relocation's cell neighbourhoods, the
     * weights' cell patches. Called by setup() and after every repartition.
     */
    void
    setup_nodal_fields();

    /**
     * Stop the run because it became unstable (@p reason; @p during_step:
     * found inside the step, not after it): write one last
     * output for inspection, then throw with the step, time, the first bad
     * point (or the fastest one) and what to change. Collective.
     */
    [[noreturn]] void
    stop_on_blow_up(const std::string &reason, const bool during_step);

    /**
     * Write a checkpoint of the run (Checkpointing); collective.
     */
    void
    write_checkpoint();

    /**
     * The simulator's state that is not in the mesh or the points: time,
     * step, statistics so far, the output writer's and the postprocessors'
     * records. serialize_state() is the same on every rank.
     */
    std::string
    serialize_state() const;

    void
    deserialize_state(const std::string &state);

    /**
     * Repartition the mesh by the cells' weights (LoadBalancing) and move
     * the points with their cells; a collective call.
     */
    void
    repartition();

    void
    do_time_step();

    double
    compute_time_step() const;

    /// The step's particle-grid weights, with the step's nodal fields
    /// zeroed (ParticleGridWeights::begin_step()), and the shortest edge
    /// of the cells holding material, on all ranks.
    void
    prepare_transfer();

    /// Nodal velocity p / m, constrained for the strain rate.
    void
    compute_nodal_velocity(NodalVector &velocity_out);

    /// @name The operations of a step, in the order of the StepScheme.
    /// @{
    void
    map_mass_and_momentum(const bool with_forces) override;

    void
    map_forces() override;

    void
    compute_nodal_velocity(const NodalVelocity target) override;

    void
    update_stress(const NodalVelocity source, const bool set_affine) override;

    void
    filter_brought_velocity() override;

    /// Friction, the step's nodal velocity change and the wall
    /// constraints (doc/algorithm.md).
    void
    update_nodal_kinematics() override;

    void
    update_points_from_grid(const bool remap_momentum) override;

    bool
    has_affine_transfer() const override;

    /// nodal.velocity or nodal.velocity_new.
    NodalVector &
    nodal_velocity(const NodalVelocity which);
    /// @}

    /// Call @p body(i) for each nodal entry i the step's points touch,
    /// on the available threads (for_each_chunk()).
    template <typename Body>
    void
    for_each_active_dof(const Body &body) const;

    /// The largest point speed on all ranks from this rank's @p v_max2;
    /// stops the run if a point became non-finite. Collective.
    void
    set_max_point_speed(const double v_max2);

    /// The points' speed by @p measure on all ranks: sqrt(sum m v^2 /
    /// sum m), sum m |v| / sum m, or the largest (reduced by the
    /// grid-to-particle pass already: no loop). Collective.
    double
    point_speed(const RestCriterion::Measure measure) const;

    /// The largest P-wave speed on all ranks over the points whose
    /// material's stiffness depends on the state, from their stress and
    /// state now (the set-up's, for step 0). Collective.
    double
    compute_max_state_wave_speed() const;

    void
    relocate_points();

    /**
     * The regularised state variables of the points of non-local
     * materials (NonlocalAveraging), from the points' positions and local
     * variables now; called before every stress update. Costs nothing
     * without such materials.
     */
    void
    average_nonlocal_variables();

    void
    write_output(const bool force);

    /// The end-of-run report of the postprocessors (report.txt, and on
    /// the screen), with the run's warnings and why it stopped.
    void
    write_report() const;

    /// The end-of-run summary on the screen: @p wall seconds in all,
    /// @p steps_wall of them in the @p steps_this_run steps (the
    /// throughput), the peak memory, and what the volume bound, the load
    /// balancing and the point location did. Collective.
    void
    print_run_summary(const double       wall,
                      const double       steps_wall,
                      const unsigned int steps_this_run) const;

    /// The names of the material state slots of the points (the model's
    /// if the scene has one material, else state_0, state_1, ...).
    std::vector<std::string>
    state_variable_names() const;

    MPI_Comm           mpi_communicator;
    ConditionalOStream pcout;
    std::string        input_directory;
    std::string        parameters_text;

    BackgroundGrid<dim>             grid;
    MaterialLibrary                 materials;
    /// The water in the pores of saturated materials.
    PoreWater<dim>                  pore_water;
    PointGenerator<dim>             point_generator;
    PointRelocation<dim>            point_relocation;
    BoundaryConditions<dim>         boundary_conditions;
    /// The friction of a 2D channel's side walls (not in the mesh).
    SideWallFriction<dim>           side_walls;
    TimeSteppingParameters<dim>     time_stepping;
    VelocityTransfer<dim>           transfer;
    /// The first property slot of the transfer scheme's point data.
    unsigned int                    transfer_slot = 0;
    OutputWriter<dim>               output_writer;
    LoadBalancing<dim>              load_balancing;
    StabilityMonitor<dim>           stability_monitor;
    RestCriterion                   rest_criterion;
    Checkpointing<dim>              checkpointing;
    unsigned int                    n_repartitions = 0;
    std::vector<std::unique_ptr<Postprocessor<dim>>> postprocessors;
    std::vector<std::string>        postprocessor_names;
    /// The points that left the mesh ('Points leaving the mesh').
    LostPoints<dim>                 lost_points;

    Particles::ParticleHandler<dim> particle_handler;
    /// The slots of the points' property arrays, by owner and name.
    PointProperties                 point_properties;

    NodalFields nodal;

    /// The nodal-vector entries of each cell's vertices.
    CellDofTable<dim> cell_dofs;
    /// The nodal entries that 'Mesh/Periodic boundaries' make one node.
    PeriodicNodeGroups periodic_nodes;

    /// A point's velocity, position and stress from its interpolated
    /// grid values.
    PointUpdate<dim> point_update;
    /// The regularised state variables of non-local materials, set before
    /// every stress update (average_nonlocal_variables()).
    NonlocalAveraging<dim> nonlocal_averaging;
    /// The particle-grid weights ('Transfer/Particle-grid weights').
    std::unique_ptr<ParticleGridWeights<dim>> weights;

    double       time      = 0;
    double       time_step = 0;
    unsigned int step      = 0;
    /// The points' largest speed at the start of step
    /// max_point_speed_step (the CFL step reads it; asserted): left by the
    /// previous step's grid-to-particle pass, or by the set-up.
    double       max_point_speed      = 0;
    unsigned int max_point_speed_step = 0;
    /// The largest P-wave speed over the points of materials whose
    /// stiffness depends on the state, at the start of the same step
    /// (0 if there are none): left by the previous step's stress update
    /// (PointUpdate::take_max_state_wave_speed()) or by the set-up; kept in
    /// the checkpoint.
    double       max_state_wave_speed = 0;
    /// The components' wave speeds that bound the step.
    TimeStepBounds time_step_bounds;
    /// Shortest edge among the cells that hold points this step (all ranks).
    double       active_cell_size = 0;
    unsigned int output_index    = 0;

    /// wrapped_mass_shift() of the run before it was resumed (rank 0).
    Tensor<1, dim>        wrapped_mass_shift_before_restart;

    /// Warnings about the input found in the set-up, repeated in the
    /// report.
    std::vector<std::string> warnings;

    StatisticsFile<dim> statistics_file;
    /// Bytes of the statistics file at the checkpoint a run resumed from.
    std::uint64_t      statistics_length = 0;
    mutable TimerOutput timer;
  };
} // namespace MPM

#endif
