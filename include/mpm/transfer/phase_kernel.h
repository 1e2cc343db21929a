#ifndef mpm_transfer_phase_kernel_h
#define mpm_transfer_phase_kernel_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/geometry_info.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/grid/nodal_vector.h>
#include <mpm/grid/q1_shape_functions.h>

#include <array>
#include <utility>

namespace MPM
{
  using namespace dealii;

  /**
   * What a component other than the solid skeleton's own passes maps
   * between the points and the grid, through the weights of the step
   * (ParticleGridWeights::map_phase(), update_phase_points()): a second
   * phase (PoreWater), or a load the points carry to the nodes
   * (SideWallFriction). The passes loop over the entries of every weight
   * function and the kernel says, per point and weight set, what it adds
   * to its nodal fields and what it does with the nodal values
   * interpolated back. The dry passes do not know it: a scene without such
   * a component pays nothing for it.
   *
   * The calls are virtual per entry: a two-phase step pays a call per
   * point and pass, small beside its arithmetic.
   */
  template <int dim>
  class PhaseKernel
  {
  public:
    static constexpr unsigned int n_vertices =
      GeometryInfo<dim>::vertices_per_cell;
    using VertexValues = std::array<Tensor<1, dim>, n_vertices>;

    /// Nodal fields a particle-to-grid pass of a phase may add to.
    static constexpr unsigned int max_targets = 9;
    /// Nodal fields a grid-to-particle pass of a phase may read.
    static constexpr unsigned int max_sources = 3;

    using Targets = std::array<NodalVector *, max_targets>;
    using Sums    = std::array<VertexValues, max_targets>;
    using Sources = std::array<const NodalVector *, max_sources>;

    virtual ~PhaseKernel() = default;

    /// The nodal fields the particle-to-grid pass adds to (nullptr:
    /// unused); each is summed over the ranks afterwards.
    virtual Targets
    grid_targets() = 0;

    /**
     * Whether the kernel's velocity is affine about each point, as APIC's:
     * add_to_grid() then gets the offsets of the cell's vertices from the
     * point's affine centre, and update_point() the affine fit of its first
     * source (ParticleGridWeights::map_phase()). false by default: the
     * passes then compute neither.
     */
    virtual bool
    needs_affine() const
    {
      return false;
    }

    /**
     * Add the share of the point with properties @p props at its weights
     * @p sf (values and gradients at the vertices of one cell) to the
     * per-vertex @p sums of grid_targets(). @p offsets: x_i - xbar_p for
     * the cell's vertices (the skeleton's APIC offsets) if needs_affine(),
     * else zero.
     */
    virtual void
    add_to_grid(const double                *props,
                const Q1ShapeFunctions<dim> &sf,
                const VertexValues          &offsets,
                Sums                        &sums) const = 0;

    /// The nodal fields whose values and gradients update_point() reads.
    virtual Sources
    grid_sources() = 0;

    /**
     * Update the point with properties @p props from the @p values and
     * @p gradients at it of grid_sources() (sum_i N_i u_i and
     * sum_i u_i (x) grad N_i over all its weights) and, if needs_affine(),
     * the affine fit @p affine of the first source about the point (APIC's
     * C = B D^-1 where the weights' second moment D is bounded below, else
     * the gradient; zero otherwise).
     */
    virtual void
    update_point(double                                        *props,
                 const std::array<Tensor<1, dim>, max_sources> &values,
                 const std::array<Tensor<2, dim>, max_sources> &gradients,
                 const Tensor<2, dim> &affine) const = 0;

    /**
     * Whether the update takes, beside the point's own values, the mean
     * over the points of its own cell of a scalar rate (cell_rate()):
     * then update_point_with_cell_mean() is called instead of
     * update_point(). false by default: the passes then do exactly what
     * they do for update_point().
     */
    virtual bool
    averages_over_cells() const
    {
      return false;
    }

    /**
     * With averages_over_cells(): whether the cells' means are averaged
     * again over patches before update_point_with_cell_mean() takes them,
     * each vertex taking the weighted mean of the cells around it and each
     * cell the mean of its vertices (as the skeleton's 'Volumetric strain
     * averaging = patch'). A rate whose cell means alternate in sign from
     * cell to cell (the checkerboard that a pressure constant per cell
     * cannot feel through its nodal forces) then has no mean to leave.
     */
    virtual bool
    averages_over_patches() const
    {
      return false;
    }

    /// A point's rate for the cell mean and its weight (e.g. its volume).
    virtual std::pair<double, double>
    cell_rate(const double                                  *props,
              const std::array<Tensor<1, dim>, max_sources> &values,
              const std::array<Tensor<2, dim>, max_sources> &gradients) const
    {
      (void)props;
      (void)values;
      (void)gradients;
      return {0., 0.};
    }

    /// update_point() with the weighted mean @p cell_mean of cell_rate()
    /// over the points of the point's own cell.
    virtual void
    update_point_with_cell_mean(
      double                                        *props,
      const std::array<Tensor<1, dim>, max_sources> &values,
      const std::array<Tensor<2, dim>, max_sources> &gradients,
      const Tensor<2, dim>                          &affine,
      const double                                   cell_mean) const
    {
      (void)cell_mean;
      update_point(props, values, gradients, affine);
    }

    /**
     * After update_point_with_cell_mean() for every point of one cell: a
     * last look at the cell's points together, with their positions
     * @p positions and the cell's volume @p cell_volume (e.g. a field
     * fitted over the cell, or the share of the cell the points fill).
     * Nothing by default.
     */
    virtual void
    finish_cell(const ArrayView<double *const>    &props,
                const ArrayView<const Point<dim>> &positions,
                const double                       cell_volume) const
    {
      (void)props;
      (void)positions;
      (void)cell_volume;
    }
  };
} // namespace MPM

#endif
