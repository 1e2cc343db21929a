#ifndef mpm_transfer_cpdi_weights_h
#define mpm_transfer_cpdi_weights_h

#include <mpm/transfer/particle_grid_weights.h>
#include <mpm/transfer/point_domains.h>

namespace MPM
{
  using namespace dealii;

  /**
   * 'Particle-grid weights = cpdi': each point acts on the nodes through
   * the 2^dim corners of its domain (PointDomains has the domain and the
   * arithmetic of its weights). The entries of active_cells and
   * shape_functions are the corners, grouped by the cell they lie in, with
   * corner_point, corner_alpha and corner_beta saying whose corner each is
   * and how it weighs; a pass sums over the corners cell by cell and then
   * visits the points. LinearWeights are the same passes with one "corner"
   * per point at the point itself, alpha = 1 and the mesh functions'
   * gradient in place of beta, kept apart so that the cheap path keeps
   * its per-cell layout.
   */
  template <int dim>
  class CpdiWeights : public ParticleGridWeights<dim>
  {
  public:
    using typename ParticleGridWeights<dim>::VertexValues;
    using ParticleGridWeights<dim>::n_vertices;

    /// With the domains' parameters from @p prm.
    CpdiWeights(const TransferContext<dim> &context, ParameterHandler &prm);

    bool
    second_moment_bounded_below() const override
    {
      return true;
    }

    /// The corner offsets and the shrink scale (PointDomains).
    unsigned int
    n_point_properties() const override
    {
      return point_domains.n_point_properties();
    }

    std::vector<std::string>
    point_property_names() const override
    {
      return point_domains.point_property_names();
    }

    /// Each cell's patch: where the corners of its points may lie.
    void
    setup_partition() override;

    /**
     * Locates each point's corners in its cell's patch (shrinking the
     * domain where a corner left it: PointDomains), computes the corners'
     * alpha_c and beta_c, and groups the corners by cell.
     */
    double
    prepare() override;

    void
    map_mass_and_momentum(const bool with_forces) override;

    void
    map_forces() override;

    double
    update_points_from_grid(const bool remap_momentum) override;

    /// Also deforms the domains with the points' velocity gradients.
    void
    update_stress(const NodalVector &velocity, const bool set_affine) override;

    void
    round_trip(const NodalVector &velocity, NodalVector &momentum) override;

    void
    second_moments(std::vector<Tensor<2, dim>> &D) const override;

  private:
    using typename ParticleGridWeights<dim>::ActiveCell;
    using CellIterator = typename Triangulation<dim>::active_cell_iterator;

    /// APIC: the offsets x_i - xbar_p of the nodes of @p cell from the
    /// affine centre of the point of corner @p k.
    VertexValues
    corner_node_offsets(const ActiveCell &cell, const unsigned int k) const;

    PointDomains<dim> point_domains;

    /// Each corner's point (index into points), alpha_c and beta_c
    /// (PointDomains), in the order of shape_functions.
    std::vector<unsigned int>   corner_point;
    std::vector<double>         corner_alpha;
    std::vector<Tensor<1, dim>> corner_beta;
    /**
     * APIC: each corner's offset x_c - xbar_p from its point's affine
     * centre xbar_p = x_p + sum_c alpha_c (x_c - x_p), the mean of the
     * weights' centres, about which sum_i w_ip (x_i - xbar_p) = 0 (so the
     * affine part adds no momentum); xbar_p = x_p unless a corner was
     * moved onto a cell.
     */
    std::vector<Tensor<1, dim>> corner_offset;
    /// A corner located by prepare(), before the corners are grouped by
    /// cell.
    struct LocatedCorner
    {
      CellIterator   cell;
      unsigned int   point;
      Point<dim>     xi;
      double         alpha;
      Tensor<1, dim> beta;
      /// x_c - x_p minus the point's mean corner offset (APIC).
      Tensor<1, dim> offset;
    };
    std::vector<LocatedCorner> located_corners;
    /// Each active cell's slot among the cells holding corners
    /// (invalid_unsigned_int between steps).
    std::vector<unsigned int> corner_slot_of_cell;
    /// Each point's cell map (2D), and per-point sums of a pass.
    std::vector<const BilinearCellMap *> point_cell_map;
    std::vector<Tensor<1, dim>>          point_sum_a, point_sum_b;
    std::vector<Tensor<2, dim>>          point_sum_gradient;
    /// APIC: each point's B_p and D_p (VelocityTransfer), the largest
    /// |x_i - x_p|^2 of its nodes, and the affine matrix it hands to the
    /// grid this step.
    std::vector<Tensor<2, dim>> point_sum_B, point_sum_D, point_affine;
    std::vector<double>         point_node_scale;
    /// The first point (index into points) of each cell holding points,
    /// and one past the last.
    std::vector<unsigned int> point_cell_begin;
    /// The cells a corner of a point in each locally owned cell may lie in
    /// (by active_cell_index(); the cell itself first).
    std::vector<std::vector<CellIterator>> cell_patches;
  };
} // namespace MPM

#endif
