#ifndef mpm_transfer_particle_grid_passes_h
#define mpm_transfer_particle_grid_passes_h

#include <mpm/grid/cell_dof_table.h>
#include <mpm/transfer/particle_grid_weights.h>

#include <array>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The particle-grid passes, written once for every weight function.
   *
   * A weight function (the template argument @p Weights, derived from this
   * class: LinearWeights, CpdiWeights) provides only what is its own: in
   * prepare(), the step's *entries*, grouped by the active cell they lie
   * in. An entry is one point's weights on one cell's vertices: the values
   * w_i and gradients grad w_i in shape_functions (for linear weights the
   * mesh functions at the point, for CPDI their averages over the part of
   * the point's domain whose corners lie in that cell), so that a point's
   * weights, summed over its entries, are a partition of unity. The
   * passes do the rest with the same arithmetic for every weight function
   * (mass w_i m_p, force -V_p sigma_p grad w_i + w_i m_p g, velocity
   * gradient sum_i v_i (x) grad w_i), and ask, entry by entry, these
   * inline hooks (not virtual: each weight's passes are compiled with its
   * own):
   *
   * - `static constexpr bool entries_are_points`: whether entry k is point
   *   k (one entry per point, in the order of the points). The passes then
   *   finish each point inside its cell's loop instead of summing its
   *   entries first.
   * - `unsigned int point_of_entry(k)`: whose entry k is (index into
   *   point_properties()).
   * - `VertexValues node_offsets(cell, k)`: x_i - xbar_p for the vertices of
   *   entry k's cell, about the point's affine centre (APIC).
   * - `void deform_with_point(p, props, grad_v, volume_factor)`: whatever
   *   the weights keep on point p that deforms with it (CPDI's domain), after
   *   its stress update, which reduced the point's volume by
   *   @p volume_factor beyond the deformation (PointUpdate::update_stress()).
   * - `const BilinearCellMap *cell_map_of_point(p)` (only if the entries are
   *   not the points): the map of point p's own cell (2D).
   *
   * A weight function whose entries are not its points also fills
   * point_cell_begin, point_cell_first_point and point_cell_size in
   * prepare() (the points grouped by their own cell: for volumetric
   * averaging, the cell size of the stress update, and the points'
   * updates on the available threads).
   *
   * The velocity transfer scheme enters through TransferScheme and Apic:
   * with APIC, each entry maps its point's affine field v_p + C_p dx_i, and
   * the point's new C_p is fitted to the end-of-step grid velocity,
   * C_p = B_p D_p^{-1} summed over its entries (Apic::fit_affine()). Under
   * MUSL at points whose second moment can vanish (Weights::fit_is_stable()
   * false: every point with linear weights, a point whose CPDI domain is
   * shrunk below half its size) C_p is instead the velocity gradient of the
   * MUSL remap (update_stress()) and the point's remap is PIC's: fitted
   * there, C_p was measured unstable (doc/transfers.md).
   *
   * Each pass loops over the active cells and their entries, reads a
   * cell's nodal values once for all its entries and adds its sums to the
   * nodes once.
   *
   * Threads (`mpm --threads N`): the cells are worked on in fixed chunks
   * (for_active_cells(), for_each_chunk()); each cell's sums are added to
   * the nodes in the order of the cells and each chunk's findings
   * (PointUpdate::Findings) are taken over in chunk order, so that a run
   * gives the same numbers, bit for bit, on any number of threads. Where
   * the entries are not the points, the sums over a point's entries
   * (which lie in several cells) stay on one thread.
   */
  template <int dim, class Weights>
  class ParticleGridPasses : public ParticleGridWeights<dim>
  {
  public:
    using typename ParticleGridWeights<dim>::VertexValues;
    using ParticleGridWeights<dim>::n_vertices;

    explicit ParticleGridPasses(Simulator<dim> &simulator)
        : ParticleGridWeights<dim>(simulator)
    {}

    void
    map_mass_and_momentum(const bool with_forces) override;

    void
    map_forces() override;

    double
    update_points_from_grid(const bool remap_momentum) override;

    void
    update_stress(const NodalVector &velocity, const bool set_affine) override;

    void
    round_trip(const NodalVector &velocity, NodalVector &momentum) override;

    void
    second_moments(std::vector<Tensor<2, dim>> &D) const override;

    void
    map_phase(PhaseKernel<dim> &kernel) override;

    void
    update_phase_points(PhaseKernel<dim> &kernel) override;

  protected:
    using typename ParticleGridWeights<dim>::ActiveCell;

    /**
     * The first point (index into point_properties()) of each cell holding
     * points, and one past the last: filled by prepare() of weights whose
     * entries are not the points.
     */
    std::vector<unsigned int> point_cell_begin;
    /// The ParticleHandler's iterator to the first point of each of those
    /// cells.
    std::vector<typename Particles::ParticleHandler<dim>::particle_iterator>
      point_cell_first_point;
    /// BackgroundGrid::cell_size() of each of those cells.
    std::vector<double> point_cell_size;

  private:
    /**
     * Call @p body(c, chunk, sums) for every active cell c (chunk: the
     * index of its chunk of cell_chunk_size cells, for the body's
     * per-chunk results), on the available threads, and add the cell's
     * per-vertex sums[f] to *targets[f] (skipped where nullptr): at the
     * vertices of cells of one chunk by that chunk's thread, at vertices
     * that cells of several chunks share after the threaded loop; in the
     * order of the cells either way, so that the nodal values are bit for
     * bit those of one thread, for any cut into chunks.
     */
    template <std::size_t n_targets, typename Body>
    void
    for_active_cells(const std::array<NodalVector *, n_targets> &targets,
                     const Body                                 &body);

    /**
     * Call @p body(c, chunk) for every cell c holding points (the points
     * grouped by their own cell: point_cell_begin), in chunks of
     * cell_chunk_size cells on the available threads, with chunk_findings
     * sized for the chunks (weights whose entries are not the points).
     */
    template <typename Body>
    void
    for_point_cells(const Body &body);

    /// for_active_cells()'s sums of the cells on chunk borders (by
    /// border_index).
    std::vector<VertexValues> cell_sums;
    /// What the point updates of each chunk of cells found.
    std::vector<typename PointUpdate<dim>::Findings> chunk_findings;
    /// Per chunk: the velocity gradients of one cell's points (volumetric
    /// averaging).
    std::vector<std::vector<Tensor<2, dim>>> chunk_gradients;

    /**
     * 'Volumetric strain averaging = patch' (and a phase kernel's
     * PhaseKernel::averages_over_patches()), for the @p n_cells cells of
     * this step's loop: cell c's sums of w_p r_p and w_p over its points
     * [begin, end) = @p points_of(c), {r_p, w_p} = @p rate_of(p) (the
     * skeleton's: tr(grad v_p) and V_p), in cell_rate_sums; each vertex's
     * weighted
     * mean over the cells around it (on every rank: the sums go through
     * patch_sums, a nodal vector); each cell's mean of its vertices' means
     * in cell_patch_means[c]. @p dofs_of(c) gives cell c's vertex entries
     * (CellDofTable's), looked up once. Sums in the order of the cells, so
     * the same on any number of threads.
     */
    template <typename PointsOf, typename DofsOf, typename RateOf>
    void
    patch_mean_rates(const unsigned int n_cells,
                     const PointsOf    &points_of,
                     const DofsOf      &dofs_of,
                     const RateOf      &rate_of);

    /// patch_mean_rates() over the cells that hold points, in the order
    /// the passes go through them (cell_patch_means[c] is that order's
    /// c-th cell): active_cells where the weights' entries are the points,
    /// the cells of point_cell_begin where they are not.
    template <typename RateOf>
    void
    patch_mean_rates_over_point_cells(const RateOf &rate_of);

    using VertexDofs = typename CellDofTable<dim>::VertexDofs;
    std::vector<const VertexDofs *>    patch_cell_dofs;
    NodalVector                        patch_sums;
    std::vector<std::array<double, 2>> cell_rate_sums;
    std::vector<double>                cell_patch_means;

    /// Take over chunk_findings (in chunk order); the largest squared
    /// speed among them.
    double
    record_chunk_findings();

    /// The weight function's hooks.
    const Weights &
    weights() const
    {
      return static_cast<const Weights &>(*this);
    }

    Weights &
    weights()
    {
      return static_cast<Weights &>(*this);
    }

    /// What APIC's fit C_p = B_p D_p^{-1} sums over a point's entries.
    struct AffineFitSums
    {
      Tensor<2, dim> B, D, gradient;
      /// The largest |x_i - xbar_p|^2 of the point's nodes.
      double node_scale = 0;
    };

    /**
     * Add entry @p k (in @p cell, with the nodal velocities @p v_node) to
     * its point's @p sums.
     */
    void
    add_to_affine_fit(const ActiveCell   &cell,
                      const unsigned int  k,
                      const VertexValues &v_node,
                      AffineFitSums      &sums) const;

    /**
     * What the particle-to-grid passes read of a point: its mass, volume,
     * velocity and the in-plane (dim x dim) part of its stress.
     */
    struct PointTransferData
    {
      double         mass;
      double         volume;
      Tensor<1, dim> velocity;
      Tensor<2, dim> stress;

      /// From the point's properties @p props (the volume and stress
      /// only if @p with_stress).
      static PointTransferData
      read(const double *props, const bool with_stress);

      /// The dim x dim part of the stress in @p props: the only part that
      /// exerts in-plane forces.
      static Tensor<2, dim>
      in_plane_stress(const double *props);
    };

    /**
     * Where the entries are not the points: each point's PointTransferData
     * copied from its properties (in the order of the points, on the
     * available threads) into point_transfer_data, which the entries then
     * read. A cell's entries belong to the points of the cells around it,
     * whose properties lie far apart in the ParticleHandler's storage (a
     * record of 26 doubles for a 2D linear-elastic point with CPDI, more
     * with a material's state): read entry by entry, most of a
     * particle-to-grid pass waited for them (doc/performance.md). The copy
     * is read from records of 8 doubles (2D; 14 in 3D), in the same order;
     * the arithmetic is the same.
     */
    void
    gather_point_transfer_data(const bool with_stress);

    /// gather_point_transfer_data()'s copy, by point.
    std::vector<PointTransferData> point_transfer_data;

    /// Entry @p k's share of the forces of its point (mass @p m, volume
    /// @p V, in-plane stress @p sigma), -V sigma grad w_i + w_i m g, added
    /// to @p forces at its cell's vertices.
    void
    add_entry_forces(const unsigned int    k,
                     const double          m,
                     const double          V,
                     const Tensor<2, dim> &sigma,
                     const Tensor<1, dim> &gravity,
                     VertexValues         &forces) const;

    /// Entry @p k's share of its point's velocity gradient, sum_i v_i (x)
    /// grad w_i, from its cell's nodal velocities @p v_node.
    Tensor<2, dim>
    entry_velocity_gradient(const unsigned int  k,
                            const VertexValues &v_node) const
    {
      const auto    &sf = this->shape_functions[k];
      Tensor<2, dim> grad_v;
      for (unsigned int i = 0; i < n_vertices; ++i)
        grad_v += outer_product(v_node[i], sf.gradient[i]);
      return grad_v;
    }

    /// Each point's velocity gradient (stress update: summed over its
    /// entries for weights whose entries are not the points; per entry
    /// with 'Volumetric strain averaging = patch' for the others).
    std::vector<Tensor<2, dim>> point_gradients;
    /// Per-point sums over the entries: interpolated acceleration and
    /// velocity.
    std::vector<Tensor<1, dim>> point_sum_a, point_sum_v;
    /// APIC: per-point sums for the fit, and the affine matrix each point
    /// hands to the grid (weights whose entries are not the points).
    std::vector<AffineFitSums>  point_affine_fit;
    std::vector<Tensor<2, dim>> point_affine, point_second_moment;
    /// APIC: whether update_points_from_grid() fitted each point's affine
    /// matrix (weights whose entries are not the points).
    std::vector<unsigned char> point_fitted;
    /// update_phase_points(): per point and source field, the sums of
    /// the values and gradients over its entries (weights whose entries
    /// are not the points).
    std::vector<Tensor<1, dim>> phase_values;
    std::vector<Tensor<2, dim>> phase_gradients;
    /// A kernel's affine fit of its first source over each point's entries
    /// (PhaseKernel::needs_affine(); weights whose entries are not the
    /// points).
    std::vector<AffineFitSums> phase_affine_sums;

    /// One point's values and gradients of a phase kernel's sources, and
    /// the affine fit of the first (PhaseKernel::update_point()).
    struct PhasePointSums
    {
      std::array<Tensor<1, dim>, PhaseKernel<dim>::max_sources> values;
      std::array<Tensor<2, dim>, PhaseKernel<dim>::max_sources> gradients;
      Tensor<2, dim>                                            affine;
    };
    /// Per chunk: one cell's points' sums and positions
    /// (update_phase_points_of_cell()).
    struct PhaseCellScratch
    {
      std::vector<PhasePointSums> sums;
      std::vector<Point<dim>>     positions;
    };
    std::vector<PhaseCellScratch> chunk_phase_scratch;

    /**
     * The points this->points[first, first + scratch.sums.size()) of one
     * cell, whose sums are in @p scratch and the first of which is
     * @p first_point in the ParticleHandler, updated by @p kernel with the
     * mean of their rates (PhaseKernel::averages_over_cells()) or, if
     * given, @p patch_mean (PhaseKernel::averages_over_patches()), then
     * shown to it together with their positions
     * (PhaseKernel::finish_cell()).
     */
    void
    update_phase_points_of_cell(
      const PhaseKernel<dim>                                     &kernel,
      const unsigned int                                          first,
      typename Particles::ParticleHandler<dim>::particle_iterator first_point,
      PhaseCellScratch                                           &scratch,
      const double *patch_mean = nullptr) const;
    /// update_phase_points() with patch means on weights whose entries
    /// are the points: every point's sums, by entry.
    std::vector<PhasePointSums> phase_point_sums;
  };
} // namespace MPM

#endif
