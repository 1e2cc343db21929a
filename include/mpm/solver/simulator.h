#ifndef mpm_solver_simulator_h
#define mpm_solver_simulator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/boundary_conditions/boundary_conditions.h>
#include <mpm/grid/background_grid.h>
#include <mpm/grid/nodal_vector.h>
#include <mpm/grid/q1_shape_functions.h>
#include <mpm/material_points/point_generator.h>
#include <mpm/material_points/point_relocation.h>
#include <mpm/materials/material_library.h>
#include <mpm/output/output_writer.h>
#include <mpm/parallel/load_balancing.h>
#include <mpm/postprocess/postprocessor.h>
#include <mpm/restart/checkpointing.h>
#include <mpm/solver/stability_monitor.h>
#include <mpm/solver/statistics.h>
#include <mpm/solver/time_stepping.h>
#include <mpm/transfer/point_domains.h>
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
   *  6. grid-to-particle: velocity with a FLIP/PIC blend, position with
   *     v_new;
   *  7. USL: stress update from v_new; MUSL: point momenta mapped to the
   *     grid again and the stress updated from that velocity;
   *  8. points that left their cell are relocated.
   *
   * Only cells that hold material points take part: every loop runs over
   * the points, grouped by cell, and over the nodes of those cells.
   */
  template <int dim>
  class Simulator
  {
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

    void
    parse_parameters(ParameterHandler &prm, const std::string &input_directory);

    /**
     * Set up the scene and run it to the end time.
     */
    void
    run();

    /**
     * @name Access for postprocessors and tests.
     * @{
     */
    const Particles::ParticleHandler<dim> &
    get_particle_handler() const
    {
      return particle_handler;
    }

    const MaterialLibrary &
    get_materials() const
    {
      return materials;
    }

    const BackgroundGrid<dim> &
    get_grid() const
    {
      return grid;
    }

    const BoundaryConditions<dim> &
    get_boundary_conditions() const
    {
      return boundary_conditions;
    }

    const TimeSteppingParameters<dim> &
    get_time_stepping() const
    {
      return time_stepping;
    }

    double
    get_time() const
    {
      return time;
    }

    unsigned int
    get_step() const
    {
      return step;
    }

    double
    get_time_step() const
    {
      return time_step;
    }

    MPI_Comm
    get_mpi_communicator() const
    {
      return mpi_communicator;
    }

    /**
     * Sums over all points and ranks.
     */
    GlobalStatistics<dim>
    compute_statistics() const;

    /**
     * Kinetic, strain and gravitational potential energy of the point with
     * properties @p props at @p x: the terms of compute_statistics()'s
     * sums, and what a removed point takes away.
     */
    std::array<double, 3>
    energy_of_point(const double *props, const Point<dim> &x) const;

    /**
     * Angular momentum about the centre of mass @p centre of the points
     * moving with mean velocity @p mean_velocity (3 components; only z in
     * 2D), and its scale sum_p m_p |x_p - centre| |v_p|.
     * With APIC it includes the affine part of each point's velocity field,
     * m_p sum_i N_i dx_i x (C_p dx_i), the part of the grid's angular
     * momentum that the point carries (VelocityTransfer::update_affine()).
     * Summed over all ranks.
     */
    std::pair<Tensor<1, 3>, double>
    spin_angular_momentum(const Point<dim>     &centre,
                          const Tensor<1, dim> &mean_velocity) const;
    /** @} */

  private:
    /**
     * A cell that holds material points, with what the transfers need of
     * it: its number of points and the local element indices of its nodal
     * degrees of freedom, as [vertex][component].
     */
    struct ActiveCell
    {
      unsigned int                                  n_points;
      std::array<std::array<unsigned int, dim>,
                 GeometryInfo<dim>::vertices_per_cell> dofs;
      /// The cell's vertices (BackgroundGrid::cell_vertices()).
      const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>
        *vertices = nullptr;
      /// The cell's bilinear map (2D; nullptr in 3D), with which the
      /// grid-to-particle pass locates the points it moves.
      const BilinearCellMap *map = nullptr;
    };

    void
    setup();

    /**
     * Everything that depends on the partition of the mesh among ranks:
     * the nodal vectors and their ghost layout, the boundary nodes' frames
     * and constraints, the point relocation's cell neighbourhoods. Called
     * by setup() and after every repartition.
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

    void
    prepare_transfer();

    void
    zero_nodal_fields();

    /**
     * Zero the entries of @p v that the points of this step wrote: this
     * rank's active nodes, the owned entries other ranks added to, the
     * ghosts. Used by zero_nodal_fields() and by MUSL's momentum remap.
     */
    void
    zero_touched_entries(NodalVector &v) const;

    /**
     * Flag the nodal velocity and acceleration vectors as holding valid
     * ghost entries (each rank computes them for its ghost nodes too).
     */
    void
    mark_locally_computed_fields();

    /**
     * Particle to grid: nodal mass and momentum and, if @p with_forces,
     * the nodal forces (gravity and the divergence of the stress) in the
     * same pass over the points. USL and MUSL update the stress after the
     * forces are mapped, so for them one pass reads each point's data and
     * shape functions once instead of twice; USF maps the forces after its
     * stress update, with map_forces().
     */
    void
    map_mass_and_momentum(const bool with_forces);

    /**
     * Add one point's forces (gravity and the divergence of its stress,
     * with its shape functions @p sf) to the sums @p forces over the
     * vertices of its cell.
     */
    void
    add_point_forces(
      const double                *props,
      const Q1ShapeFunctions<dim> &sf,
      const Tensor<1, dim>        &gravity,
      std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell>
        &forces) const;

    /**
     * Add the per-vertex sums @p values of one cell's points to the
     * nodal vector @p v (at each vertex, component c to the entry of
     * component c).
     */
    void
    add_to_nodes(
      const ActiveCell &cell,
      const std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell>
                  &values,
      NodalVector &v) const
    {
      for (unsigned int i = 0; i < GeometryInfo<dim>::vertices_per_cell; ++i)
        for (unsigned int c = 0; c < dim; ++c)
          v.local_element(cell.dofs[i][c]) += values[i][c];
    }

    /**
     * Add one weight set's share of a point to a cell's per-vertex sums
     * (particle-to-grid): mass N_i m to @p mass, momentum N_i m v_i to
     * @p momentum, with v_i = v the point's velocity, or with APIC (@p C
     * not null) its affine field there, v + C dx_i (@p dx the vertices'
     * offsets from the point's affine centre). Shared by the linear-weight
     * pass (one set per point) and the CPDI pass (one per corner, m the
     * corner's share alpha_c m_p).
     */
    static void
    add_mass_and_momentum(
      const std::array<double, GeometryInfo<dim>::vertices_per_cell> &N,
      const double                                                    m,
      const Tensor<1, dim>                                           &v,
      const Tensor<2, dim>                                           *C,
      const std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell>
        *dx,
      std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell> &mass,
      std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell>
        &momentum)
    {
      for (unsigned int i = 0; i < GeometryInfo<dim>::vertices_per_cell; ++i)
        {
          const double         mi = N[i] * m;
          const Tensor<1, dim> vi = C ? v + *C * (*dx)[i] : v;
          for (unsigned int c = 0; c < dim; ++c)
            {
              mass[i][c] += mi;
              momentum[i][c] += mi * vi[c];
            }
        }
    }

    /// Sum what every rank added to the entries of @p v (compress) and
    /// give every rank the sums at its ghost nodes.
    static void
    add_contributions_of_all_ranks(NodalVector &v)
    {
      v.compress(VectorOperation::add);
      v.update_ghost_values();
    }

    void
    compute_nodal_velocity(NodalVector &velocity_out);

    /**
     * x_i - x_p for the vertices of @p cell and the point whose shape
     * functions are @p sf (APIC's affine transfer).
     */
    std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell>
    vertex_offsets(const ActiveCell &cell, const Q1ShapeFunctions<dim> &sf) const
    {
      // x_p = sum_j N_j x_j (the isoparametric map), so x_i - x_p needs no
      // point location; relative to vertex 0 to avoid cancellation far
      // from the origin.
      const auto    &x = *cell.vertices;
      Tensor<1, dim> xp;
      for (unsigned int j = 1; j < x.size(); ++j)
        xp += sf.value[j] * (x[j] - x[0]);
      std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell> dx;
      for (unsigned int i = 0; i < x.size(); ++i)
        dx[i] = (x[i] - x[0]) - xp;
      return dx;
    }

    /**
     * XPIC(m): replace the brought nodal velocity (nodal_momentum / mass)
     * by sum_k c_k (P S S+)^{k-1} u, u the constrained brought velocity,
     * S+ the interpolation to the points, S their mass-weighted projection
     * back, P the wall constraints (VelocityTransfer::filter_coefficients()).
     * Each order costs one pass over the points that reads only their
     * masses and shape functions.
     */
    void
    filter_brought_velocity();

    /**
     * APIC, at the start of a run: complete each point's affine slots
     * (its C_p, the initial velocity gradient, written by the
     * PointGenerator) with the energy and angular momentum of its affine
     * part under the first step's weights.
     */
    void
    initialize_affine_matrices();

    /// XPIC's round trip S S+ of round_trip_velocity into
    /// round_trip_momentum with linear weights (CPDI: round_trip_cpdi()).
    void
    round_trip();

    void
    map_forces();

    void
    update_nodal_kinematics();

    /**
     * Grid to particle: new point velocities and positions. With
     * @p remap_momentum (MUSL) the same pass maps the points' new momentum
     * back to the nodes (into nodal_momentum), which MUSL's stress update
     * takes its velocity from: a separate pass would read every point and
     * its shape functions again.
     */
    void
    update_points_from_grid(const bool remap_momentum);

    /**
     * Strain increment, stress and volume of every point from the velocity
     * gradient of @p nodal_velocity; with @p set_affine that gradient also
     * becomes the points' APIC matrix (MUSL).
     */
    void
    update_stress(const NodalVector &nodal_velocity,
                  const bool         set_affine = false);

    /**
     * One point's part of grid to particle, the same for every weight:
     * its new velocity from the interpolated nodal acceleration @p a and
     * end-of-step velocity @p v_new (FLIP/PIC blend), its new position
     * (located in its cell, whose 2D map is @p map, if the relocation does
     * that while moving), the largest speed @p v_max2 so far and the
     * blow-up check.
     */
    void
    advance_point(
      typename Particles::ParticleHandler<dim>::particle_iterator point,
      double                                                           *props,
      const Tensor<1, dim>                                             &a,
      const Tensor<1, dim>                                             &v_new,
      const BilinearCellMap                                            *map,
      double &v_max2);

    /// The largest point speed on all ranks from this rank's @p v_max2;
    /// stops the run if a point became non-finite. Collective.
    void
    set_max_point_speed(const double v_max2);

    /**
     * Replace the trace of the velocity gradients @p grad_v of @p n points
     * (properties @p props) by their volume-weighted mean, keeping the
     * deviatoric parts ('Time stepping/Volumetric strain averaging').
     */
    void
    average_volumetric_part(double *const     *props,
                            Tensor<2, dim>     *grad_v,
                            const unsigned int n) const;

    /// One point's strain, stress and volume from its velocity gradient.
    void
    update_point_stress(double *props, const Tensor<2, dim> &grad_v);

    /**
     * @name CPDI's passes (source/solver/cpdi_transfer.cc)
     *
     * With 'Particle-grid weights = cpdi' each point acts through the
     * 2^dim corners of its domain (PointDomains): the entries of
     * active_cells and shape_functions are the corners, grouped by the
     * cell they lie in, with corner_point, corner_alpha and corner_beta
     * saying whose corner each is and how it weighs.
     */
    /// @{
    void
    prepare_cpdi_transfer();

    void
    map_mass_and_momentum_cpdi(const bool with_forces);

    void
    map_forces_cpdi();

    void
    update_points_from_grid_cpdi(const bool remap_momentum);

    void
    update_stress_cpdi(const NodalVector &velocity);

    /// XPIC's round trip S S+ of round_trip_velocity into
    /// round_trip_momentum through the corners.
    void
    round_trip_cpdi();

    /// APIC: the offsets x_i - xbar_p of the nodes of @p cell from the
    /// affine centre of the point of corner @p k.
    std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell>
    corner_node_offsets(const ActiveCell &cell, const unsigned int k) const;
    /// @}

    void
    relocate_points();

    void
    write_output(const bool force);

    std::vector<std::string>
    property_names() const;

    MPI_Comm           mpi_communicator;
    ConditionalOStream pcout;
    std::string        input_directory;
    std::string        parameters_text;

    BackgroundGrid<dim>             grid;
    MaterialLibrary                 materials;
    PointGenerator<dim>             point_generator;
    PointRelocation<dim>            point_relocation;
    BoundaryConditions<dim>         boundary_conditions;
    TimeSteppingParameters<dim>     time_stepping;
    VelocityTransfer<dim>           transfer;
    PointDomains<dim>               point_domains;
    /// The first property slot of the point domains (CPDI).
    unsigned int                    domain_slot = 0;
    /// The first property slot of the transfer's own point data.
    unsigned int                    transfer_slot = 0;
    OutputWriter<dim>               output_writer;
    LoadBalancing<dim>              load_balancing;
    StabilityMonitor<dim>           stability_monitor;
    /// This rank's first point with a non-finite value this step, if any.
    std::string                     first_bad_point;
    Checkpointing<dim>              checkpointing;
    unsigned int                    n_repartitions = 0;
    std::vector<std::unique_ptr<Postprocessor<dim>>> postprocessors;
    std::vector<std::string>        postprocessor_names;
    bool                            error_on_lost_points = true;

    Particles::ParticleHandler<dim> particle_handler;

    /// Lumped nodal mass (the same value in each component's entry).
    NodalVector nodal_mass;
    NodalVector nodal_momentum;
    NodalVector nodal_force;
    /// Constrained nodal velocity at the start of the step.
    NodalVector nodal_velocity;
    /// Constrained nodal velocity at the end of the step.
    NodalVector nodal_velocity_new;
    NodalVector nodal_acceleration;
    /// XPIC's filtered velocity and the round trip's iterate and sums.
    NodalVector filtered_velocity;
    NodalVector round_trip_velocity;
    NodalVector round_trip_momentum;

    /**
     * The local indices into the nodal vectors of each locally owned
     * cell's vertex DoFs (dim per vertex), by active_cell_index(); set up
     * with the nodal vectors.
     */
    std::vector<std::array<std::array<unsigned int, dim>,
                           GeometryInfo<dim>::vertices_per_cell>>
                                       local_dofs_of_cells;
    std::vector<ActiveCell>            active_cells;
    std::vector<Q1ShapeFunctions<dim>> shape_functions;
    /**
     * Each point's properties in the ParticleHandler's pool, in the order
     * of shape_functions: the particle-to-grid and stress passes read them
     * without walking the handler's iterators (which look up the cell's
     * particle list for every point). Valid from prepare_transfer() until
     * points are moved between cells or ranks in relocate_points(): no
     * point is added or removed in between, so the pool does not move.
     */
    std::vector<double *> point_properties;
    /// CPDI: each corner's point (index into point_properties), alpha_c
    /// and beta_c (PointDomains), in the order of shape_functions.
    std::vector<unsigned int>   corner_point;
    std::vector<double>         corner_alpha;
    std::vector<Tensor<1, dim>> corner_beta;
    /**
     * CPDI with APIC: each corner's offset x_c - xbar_p from its point's
     * affine centre xbar_p = x_p + sum_c alpha_c (x_c - x_p), the mean of
     * the weights' centres, about which sum_i w_ip (x_i - xbar_p) = 0 (so
     * the affine part adds no momentum); xbar_p = x_p unless a corner was
     * moved onto a cell.
     */
    std::vector<Tensor<1, dim>> corner_offset;
    /// CPDI: a corner located by prepare_cpdi_transfer(), before the
    /// corners are grouped by cell.
    struct LocatedCorner
    {
      typename Triangulation<dim>::active_cell_iterator cell;
      unsigned int                                      point;
      Point<dim>                                        xi;
      double                                            alpha;
      Tensor<1, dim>                                    beta;
      /// x_c - x_p minus the point's mean corner offset (APIC).
      Tensor<1, dim>                                    offset;
    };
    std::vector<LocatedCorner> located_corners;
    /// CPDI: each active cell's slot among the cells holding corners
    /// (invalid_unsigned_int between steps).
    std::vector<unsigned int> corner_slot_of_cell;
    /// CPDI: each point's cell map (2D), and per-point sums of a pass.
    std::vector<const BilinearCellMap *> point_cell_map;
    std::vector<Tensor<1, dim>>          point_sum_a, point_sum_b;
    std::vector<Tensor<2, dim>>          point_sum_gradient;
    /// CPDI with APIC: each point's B_p and D_p (VelocityTransfer), the
    /// largest |x_i - x_p|^2 of its nodes, and the affine matrix it hands
    /// to the grid this step.
    std::vector<Tensor<2, dim>>          point_sum_B, point_sum_D,
      point_affine;
    std::vector<double>                  point_node_scale;
    /// CPDI: the first point (index into point_properties) of each cell
    /// holding points, and one past the last.
    std::vector<unsigned int>            point_cell_begin;
    /// CPDI: the cells a corner of a point in each locally owned cell may
    /// lie in (by active_cell_index(); the cell itself first).
    std::vector<std::vector<typename Triangulation<dim>::active_cell_iterator>>
      cell_patches;
    /// Local element indices touched by the points of this step.
    std::vector<unsigned int>          active_dofs;
    std::vector<unsigned char>         dof_is_active;

    double       time      = 0;
    double       time_step = 0;
    unsigned int step      = 0;
    double       max_point_speed = 0;
    /// Shortest edge among the cells that hold points this step (all ranks).
    double       active_cell_size = 0;
    unsigned int output_index    = 0;

    /// Points removed because they left the mesh (Points leaving the mesh
    /// = remove), and their mass.
    types::particle_index n_lost_points = 0;
    double                lost_mass     = 0;
    /// Energy the removed points carried (this rank's share; see
    /// GlobalStatistics::removed_energy).
    double                lost_energy   = 0;
    std::vector<std::string> lost_point_descriptions;

    std::ofstream      statistics_file;
    /// Bytes of the statistics file at the checkpoint a run resumed from.
    std::uint64_t      statistics_length = 0;
    mutable TimerOutput timer;
  };
} // namespace MPM

#endif
