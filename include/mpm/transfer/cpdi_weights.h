#ifndef mpm_transfer_cpdi_weights_h
#define mpm_transfer_cpdi_weights_h

#include <mpm/transfer/particle_grid_passes.h>
#include <mpm/transfer/point_domains.h>

namespace MPM
{
  using namespace dealii;

  /**
   * 'Particle-grid weights = cpdi': each point acts on the nodes through
   * the 2^dim corners of its domain (PointDomains has the domain and the
   * arithmetic of its weights). The entries of the passes
   * (ParticleGridPasses) are the corners, grouped by the cell they lie in,
   * with corner_point, corner_alpha and corner_beta saying whose corner
   * each is and how it weighs; a pass sums over the corners cell by cell
   * and then visits the points.
   */
  template <int dim>
  class CpdiWeights : public ParticleGridPasses<dim, CpdiWeights<dim>>
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

  protected:
    /**
     * Locates each point's corners in its cell's patch (shrinking the
     * domain where a corner left it: PointDomains), computes the corners'
     * alpha_c and beta_c, and groups the corners by cell.
     */
    double
    prepare() override;

  private:
    friend class ParticleGridPasses<dim, CpdiWeights<dim>>;
    using typename ParticleGridWeights<dim>::ActiveCell;
    using CellIterator = typename Triangulation<dim>::active_cell_iterator;

    /// @name The hooks of ParticleGridPasses: the entries are the corners
    /// of the points' domains, grouped by the cell they lie in.
    /// @{
    static constexpr bool entries_are_points = false;

    unsigned int
    point_of_entry(const unsigned int k) const
    {
      return corner_point[k];
    }

    /// alpha_c: the corner's share of the domain.
    double
    share_of_entry(const unsigned int k) const
    {
      return corner_alpha[k];
    }

    /// The offsets x_i - xbar_p of the nodes of @p cell from the affine
    /// centre of the point of corner @p k (APIC).
    VertexValues
    node_offsets(const ActiveCell &cell, const unsigned int k) const;

    /// N_i(x_c) (-V sigma beta_c + alpha_c m g).
    void
    add_entry_forces(const unsigned int    k,
                     const double         *props,
                     const Tensor<1, dim> &gravity,
                     VertexValues         &forces) const;

    /// grad v_p = sum_i v_i (x) grad w_i = sum_c v(x_c) (x) beta_c.
    Tensor<2, dim>
    entry_velocity_gradient(const unsigned int k,
                            const VertexValues &,
                            const Tensor<1, dim> &v) const
    {
      return outer_product(v, corner_beta[k]);
    }

    /// The domain deforms with the point: D_c <- (I + dt grad v) D_c.
    void
    deform_with_point(double *props, const Tensor<2, dim> &grad_v) const;

    const BilinearCellMap *
    cell_map_of_point(const unsigned int p) const
    {
      return point_cell_map[p];
    }
    /// @}

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
    /// Where each of located_corners goes among the entries.
    std::vector<unsigned int> entry_of_corner;
    /// The cells holding points this step, and each one's first point.
    std::vector<typename Triangulation<dim>::active_cell_iterator>
      point_cells;
    std::vector<typename Particles::ParticleHandler<dim>::particle_iterator>
      first_point_of_cell;
    /// Each active cell's slot among the cells holding corners
    /// (invalid_unsigned_int between steps).
    std::vector<unsigned int> corner_slot_of_cell;
    /// Each point's cell map (2D).
    std::vector<const BilinearCellMap *> point_cell_map;
    /// The cells a corner of a point in each locally owned cell may lie in
    /// (by active_cell_index(); the cell itself first).
    std::vector<std::vector<CellIterator>> cell_patches;
  };
} // namespace MPM

#endif
