#ifndef mpm_transfer_particle_grid_weights_h
#define mpm_transfer_particle_grid_weights_h

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/timer.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/base/plugin_registry.h>
#include <mpm/grid/background_grid.h>
#include <mpm/grid/cell_dof_table.h>
#include <mpm/grid/nodal_vector.h>
#include <mpm/grid/periodic_node_groups.h>
#include <mpm/grid/q1_shape_functions.h>
#include <mpm/material_points/point_update.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/solver/simulator_access.h>
#include <mpm/solver/time_stepping.h>
#include <mpm/transfer/phase_kernel.h>
#include <mpm/transfer/velocity_transfer.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The particle-grid weights ('Transfer/Particle-grid weights'): how a
   * point's mass, momentum and force reach the nodes and how nodal
   * values come back to it. The Simulator's step (doc/algorithm.md) calls
   * these passes in the order of its update scheme; the nodal update
   * between them is the same for every weight. Each pass reads a point's
   * data and weights once for every purpose of that pass.
   *
   * The velocity transfer scheme (VelocityTransfer: FLIP/PIC blend, XPIC,
   * APIC) is orthogonal: every implementation supports every scheme,
   * asking VelocityTransfer for the per-point arithmetic and PointUpdate
   * for the point's new velocity, position and stress.
   *
   * The passes are written once, in ParticleGridPasses, over what a
   * weight function provides: LinearWeights (the mesh's own functions at
   * the point) and CpdiWeights (the functions averaged over each point's
   * deforming domain). A new weight function is a new class derived from
   * ParticleGridPasses, registered with MPM_REGISTER_PARTICLE_GRID_WEIGHTS
   * (doc/extending.md).
   *
   * Every pass loops over the active cells (the cells holding points, or
   * with CPDI the cells holding points' corners) and, per cell, over its
   * entries of shape_functions: only what holds material takes part.
   *
   * The weights reach the points, the mesh, the step's nodal fields and
   * the time step through SimulatorAccess, so they see what the
   * Simulator parses and updates after creating them.
   */
  template <int dim>
  class ParticleGridWeights : public SimulatorAccess<dim>
  {
  public:
    static constexpr unsigned int n_vertices =
      GeometryInfo<dim>::vertices_per_cell;
    /// One value per vertex of a cell.
    using VertexValues = std::array<Tensor<1, dim>, n_vertices>;

    explicit ParticleGridWeights(Simulator<dim> &simulator);

    virtual ~ParticleGridWeights() = default;

    /// 'Transfer/Particle-grid weights' and every implementation's own
    /// parameters.
    static void
    declare_parameters(ParameterHandler &prm);

    /// The weights named in @p prm (ParticleGridWeightsRegistry), with
    /// their parameters.
    static std::unique_ptr<ParticleGridWeights<dim>>
    create(ParameterHandler &prm, Simulator<dim> &simulator);

    /**
     * Whether a point's second moment under these weights is bounded
     * below (CPDI: by its domain's), so that APIC's fit C_p = B_p D_p^-1
     * to the end-of-step grid velocity is stable under USF and USL. With
     * linear weights D_p vanishes on cell edges: measured unstable above
     * CFL 0.05 (doc/transfers.md).
     */
    virtual bool
    second_moment_bounded_below() const
    {
      return false;
    }

    /**
     * How far the material of a point (properties @p props) reaches from
     * its position along the unit vector @p n: where its domain ends
     * (WallGap measures the material's gap to a wall with it). Without a
     * domain of their own (linear weights), half the side of a square
     * (cube) of the point's volume.
     */
    virtual double
    reach_along(const double *props, const Tensor<1, dim> &n) const
    {
      (void)n;
      return 0.5 * std::pow(props[PropertyLayout<dim>::volume], 1. / dim);
    }

    /// Property slots the weights keep per point, from @p first_slot
    /// (set_first_property_slot()); CPDI's domain.
    virtual unsigned int
    n_point_properties() const
    {
      return 0;
    }

    virtual std::vector<std::string>
    point_property_names() const
    {
      return {};
    }

    /// Where the weights' slots start, and where the transfer scheme's
    /// slots (APIC's C_p) are.
    void
    set_property_slots(const unsigned int transfer_slot,
                       const unsigned int first_slot)
    {
      this->transfer_slot = transfer_slot;
      own_slot            = first_slot;
    }

    /**
     * Everything that depends on the partition of the mesh among ranks;
     * called after the nodal fields are set up (at the start and after
     * every repartition).
     */
    virtual void
    setup_partition();

    /**
     * Start a step: zero the step's nodal fields @p nodal where the
     * previous step wrote them (its touched entries), then prepare() this
     * step's weights. One call, because the order matters: zeroed after
     * prepare(), the entries the previous step touched and this one does
     * not would keep their old sums. Returns the shortest edge of this
     * rank's active cells (for the time step).
     */
    double
    begin_step(NodalFields &nodal)
    {
      nodal.zero([this](NodalVector &v) { zero_touched_entries(v); });
      return prepare();
    }

    /**
     * Particle to grid: nodal mass and momentum (with APIC's affine part)
     * and, if @p with_forces, the nodal forces (gravity and the
     * divergence of the stress) in the same pass.
     */
    virtual void
    map_mass_and_momentum(const bool with_forces) = 0;

    /// Particle to grid: the nodal forces alone (USF, after its stress
    /// update).
    virtual void
    map_forces() = 0;

    /**
     * Grid to particle: every point's new velocity and position
     * (PointUpdate::advance()) from the nodal acceleration and end-of-step
     * velocity; APIC's new C_p. With @p remap_momentum (MUSL) the points'
     * new momentum is mapped back into the nodal momentum in the same
     * pass. Returns this rank's largest squared point speed.
     */
    virtual double
    update_points_from_grid(const bool remap_momentum) = 0;

    /**
     * Strain, stress and volume of every point from the velocity gradient
     * of @p velocity; with @p set_affine (MUSL with APIC and linear
     * weights) that gradient also becomes the point's C_p.
     */
    virtual void
    update_stress(const NodalVector &velocity, const bool set_affine) = 0;

    /**
     * XPIC's round trip: interpolate the nodal velocity @p velocity to the
     * points and project their momentum back with the same weights into
     * @p momentum (zeroed first).
     */
    virtual void
    round_trip(const NodalVector &velocity, NodalVector &momentum) = 0;

    /**
     * APIC: each point's second moment D_p under this step's weights, in
     * the order of point_properties() (after prepare()).
     */
    virtual void
    second_moments(std::vector<Tensor<2, dim>> &D) const = 0;

    /**
     * Particle to grid for a phase other than the skeleton (PoreWater):
     * every point's share at each of its weight sets, as @p kernel says
     * (PhaseKernel::add_to_grid()), added to the kernel's nodal fields and
     * summed over the ranks.
     */
    virtual void
    map_phase(PhaseKernel<dim> &kernel) = 0;

    /**
     * Grid to particle for such a phase: the values and gradients at each
     * point of the kernel's nodal fields, handed to
     * PhaseKernel::update_point(). Before the points move to other cells
     * (the weights of the step).
     */
    virtual void
    update_phase_points(PhaseKernel<dim> &kernel) = 0;

    /// The properties of this rank's points, in the order of the passes
    /// (valid from prepare() until the points move between cells).
    const std::vector<double *> &
    point_properties() const
    {
      return points;
    }

    /// Local element indices of the nodal vectors this step touches.
    const std::vector<unsigned int> &
    active_dofs() const
    {
      return touched_dofs;
    }

    /**
     * Zero the entries of @p v that the points of this step wrote: this
     * rank's active nodes, the owned entries other ranks added to, the
     * ghosts (the cost is independent of the size of the empty mesh).
     */
    void
    zero_touched_entries(NodalVector &v) const;

  protected:
    /**
     * The step's weights (begin_step()): the active cells, each point's
     * (or corner's) shape functions grouped by cell, the points'
     * properties and the nodal entries the step touches. Returns the
     * shortest edge of this rank's active cells.
     */
    virtual double
    prepare() = 0;

    /**
     * A cell with material in it this step: its number of entries in
     * shape_functions (points, or CPDI corners) and the local element
     * indices of its nodal degrees of freedom, as [vertex][component].
     */
    struct ActiveCell
    {
      unsigned int                                          n_points;
      std::array<std::array<unsigned int, dim>, n_vertices> dofs;
      /// The cell's vertices (BackgroundGrid::cell_vertices()).
      const std::array<Point<dim>, n_vertices> *vertices = nullptr;
      /// The cell's bilinear map (2D; nullptr in 3D).
      const BilinearCellMap *map = nullptr;
      /// The cell's affine map if it is a parallelepiped (3D; nullptr
      /// otherwise and in 2D).
      const ParallelepipedMap *parallelepiped = nullptr;
      /// BackgroundGrid::cell_size() of the cell.
      double size = 0;
      /// The index of the cell's first entry in shape_functions (its
      /// entries are consecutive).
      unsigned int first_entry = 0;
      /// Weights whose entries are the points: the cell's first point in
      /// the ParticleHandler (the others follow it).
      typename Particles::ParticleHandler<dim>::particle_iterator
        first_point;
      /**
       * Bit i set: vertex i of the cell is also a vertex of a cell in
       * another chunk of this step (finish_active_cells()), so that the
       * cell's sums there are added after the threaded loop, in the order
       * of the cells.
       */
      unsigned char vertices_shared_with_other_chunks = 0;
      /// If it has such vertices: its index in cells_on_chunk_borders.
      unsigned int border_index = 0;
    };

    /// Start collecting this step's active cells and nodal entries.
    void
    clear_active_cells();

    /// Append the cell with active_cell_index() @p cell_index with @p n
    /// entries (after those of the cells added before) to active_cells;
    /// @p first_point is its first point if the entries are the points.
    void
    add_active_cell(
      const unsigned int cell_index,
      const unsigned int n,
      const typename Particles::ParticleHandler<dim>::particle_iterator
        &first_point = {});

    /**
     * Done adding active cells: cut them into the chunks of the threaded
     * loops (cell_chunk_size), mark the vertices that cells of different
     * chunks share, and return the shortest edge among the cells.
     */
    double
    finish_active_cells();

    /**
     * Active cells per chunk of the threaded loops of this step
     * (for_each_chunk(), chunk_size_for()). Any cut gives the same results
     * (ParticleGridPasses).
     */
    unsigned int cell_chunk_size = 1;

    /// The active cells with vertices_shared_with_other_chunks, in order.
    std::vector<unsigned int> cells_on_chunk_borders;

    /// The values of @p v at the vertices of @p cell.
    static VertexValues
    read_nodes(const ActiveCell &cell, const NodalVector &v)
    {
      VertexValues values;
      for (unsigned int i = 0; i < n_vertices; ++i)
        for (unsigned int c = 0; c < dim; ++c)
          values[i][c] = v.local_element(cell.dofs[i][c]);
      return values;
    }

    /// Add the per-vertex sums @p values of one cell's points to @p v.
    static void
    add_to_nodes(const ActiveCell   &cell,
                 const VertexValues &values,
                 NodalVector        &v)
    {
      for (unsigned int i = 0; i < n_vertices; ++i)
        for (unsigned int c = 0; c < dim; ++c)
          v.local_element(cell.dofs[i][c]) += values[i][c];
    }

    /// Sum what every rank added to the entries of @p v (compress),
    /// give every rank the sums at its ghost nodes, and give the copies
    /// of a periodic node their sum (PeriodicNodeGroups).
    void
    add_contributions_of_all_ranks(NodalVector &v) const
    {
      v.compress(VectorOperation::add);
      v.update_ghost_values();
      this->get_periodic_nodes().sum(v);
    }

    /**
     * Add one weight set's share of a point to a cell's per-vertex sums
     * (particle-to-grid): mass N_i m to @p mass, momentum N_i m v_i to
     * @p momentum, with v_i = v the point's velocity, or with APIC (@p C
     * not null) its affine field there, v + C dx_i (@p dx the vertices'
     * offsets from the point's affine centre).
     */
    static void
    add_mass_and_momentum(const std::array<double, n_vertices> &N,
                          const double                          m,
                          const Tensor<1, dim>                 &v,
                          const Tensor<2, dim>                 *C,
                          const VertexValues                   *dx,
                          VertexValues                         &mass,
                          VertexValues                         &momentum)
    {
      for (unsigned int i = 0; i < n_vertices; ++i)
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

    /**
     * x_i - x_p for the vertices of @p cell and the point whose shape
     * functions are @p sf (APIC's affine transfer).
     */
    static VertexValues
    vertex_offsets(const ActiveCell &cell, const Q1ShapeFunctions<dim> &sf)
    {
      // x_p = sum_j N_j x_j (the isoparametric map), so x_i - x_p needs no
      // point location; relative to vertex 0 to avoid cancellation far
      // from the origin.
      const auto    &x = *cell.vertices;
      Tensor<1, dim> xp;
      for (unsigned int j = 1; j < x.size(); ++j)
        xp += sf.value[j] * (x[j] - x[0]);
      VertexValues dx;
      for (unsigned int i = 0; i < x.size(); ++i)
        dx[i] = (x[i] - x[0]) - xp;
      return dx;
    }

    /// Whether the velocity transfer is APIC (points carry C_p).
    bool
    affine() const
    {
      return this->get_transfer().scheme().carries_affine_velocity();
    }

    /// The first slot of the transfer scheme's point data (APIC's C_p).
    unsigned int transfer_slot = 0;
    /// The first slot of the weights' own point data.
    unsigned int own_slot = 0;

    std::vector<ActiveCell>            active_cells;
    std::vector<Q1ShapeFunctions<dim>> shape_functions;
    /**
     * Each point's properties in the ParticleHandler's pool: the passes
     * read them without walking the handler's iterators (which look up
     * the cell's particle list for every point). Valid from prepare()
     * until points are moved between cells or ranks: no point is added
     * or removed in between, so the pool does not move.
     */
    std::vector<double *> points;

  private:
    double                     shortest_edge = 0;
    std::vector<unsigned int>  touched_dofs;
    /// Periodic boundaries only: per local entry, whether this step
    /// touches it (while finish_active_cells() adds the copies).
    std::vector<bool>          is_touched;
    /**
     * Per local nodal entry (by a vertex's first component): untouched
     * outside finish_active_cells(); there, the chunk of the cells that
     * touch it, or shared_by_chunks.
     */
    std::vector<unsigned int>     chunk_of_dof;
    static constexpr unsigned int shared_by_chunks =
      numbers::invalid_unsigned_int;
    static constexpr unsigned int untouched = shared_by_chunks - 1;
  };

  /**
   * The registry of particle-grid weights: a creator receives the
   * parameters (at the top level; the weights' entries are in 'Transfer')
   * and the Simulator the weights belong to (their SimulatorAccess).
   */
  template <int dim>
  using ParticleGridWeightsRegistry =
    PluginRegistry<ParticleGridWeights<dim>, Simulator<dim> &>;
} // namespace MPM

/**
 * Register the particle-grid weights @p classname (templated on dim, with
 * a constructor (Simulator<dim> &, ParameterHandler &)) under
 * @p name ('Transfer/Particle-grid weights'), for 2D and 3D.
 */
#define MPM_REGISTER_PARTICLE_GRID_WEIGHTS(classname, name, description)     \
  MPM_REGISTER_PLUGIN(MPM::ParticleGridWeightsRegistry<2>,                   \
                      name,                                                  \
                      description,                                           \
                      nullptr,                                               \
                      [](dealii::ParameterHandler &prm,                      \
                         MPM::Simulator<2>        &simulator) {                     \
                        return std::unique_ptr<MPM::ParticleGridWeights<2>>( \
                          std::make_unique<classname<2>>(simulator, prm));   \
                      })                                                     \
  MPM_REGISTER_PLUGIN(MPM::ParticleGridWeightsRegistry<3>,                   \
                      name,                                                  \
                      description,                                           \
                      nullptr,                                               \
                      [](dealii::ParameterHandler &prm,                      \
                         MPM::Simulator<3>        &simulator) {                     \
                        return std::unique_ptr<MPM::ParticleGridWeights<3>>( \
                          std::make_unique<classname<3>>(simulator, prm));   \
                      })

#endif
