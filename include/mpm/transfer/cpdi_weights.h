#ifndef mpm_transfer_cpdi_weights_h
#define mpm_transfer_cpdi_weights_h

#include <mpm/transfer/particle_grid_passes.h>
#include <mpm/transfer/point_domains.h>

#include <string>

namespace MPM
{
  using namespace dealii;

  /**
   * 'Particle-grid weights = cpdi': each point acts on the nodes through
   * the 2^dim corners of its domain (PointDomains has the domain and the
   * arithmetic of its weights), w_i = sum_c alpha_c N_i(x_c) and grad w_i =
   * sum_c N_i(x_c) beta_c. The corners that lie in the same cell make one
   * entry of the passes (ParticleGridPasses): the point's weights on that
   * cell's vertices, summed over those corners. A domain within one cell
   * is one entry, as a point with linear weights is; one across a cell
   * edge is two.
   */
  template <int dim>
  class CpdiWeights : public ParticleGridPasses<dim, CpdiWeights<dim>>
  {
  public:
    using typename ParticleGridWeights<dim>::VertexValues;
    using ParticleGridWeights<dim>::n_vertices;

    /// With the domains' parameters from @p prm.
    CpdiWeights(Simulator<dim> &simulator, ParameterHandler &prm);

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

    /// The farthest corner of the point's domain along @p n (the domain
    /// as the material deformed it, before any shrinking at a wall).
    double
    reach_along(const double *props, const Tensor<1, dim> &n) const override;

    /// Each cell's patch: where the corners of its points may lie.
    void
    setup_partition() override;

  protected:
    /**
     * Locates each point's corners in its cell's patch (shrinking the
     * domain where a corner left it: PointDomains), computes the corners'
     * alpha_c and beta_c, and makes the entries: the corners of a point
     * that lie in one cell, their weights summed, grouped by cell.
     */
    double
    prepare() override;

  private:
    friend class ParticleGridPasses<dim, CpdiWeights<dim>>;
    using typename ParticleGridWeights<dim>::ActiveCell;
    using CellIterator = typename Triangulation<dim>::active_cell_iterator;

    /// @name The hooks of ParticleGridPasses: an entry is a point's
    /// corners in one cell, the entries grouped by cell.
    /// @{
    static constexpr bool entries_are_points = false;

    unsigned int
    point_of_entry(const unsigned int k) const
    {
      return entry_point[k];
    }

    /// The offsets x_i - xbar_p of the nodes of @p cell from the affine
    /// centre of the point of entry @p k (APIC).
    VertexValues
    node_offsets(const ActiveCell &cell, const unsigned int k) const
    {
      VertexValues dx;
      const auto  &x = *cell.vertices;
      for (unsigned int i = 0; i < n_vertices; ++i)
        dx[i] = (x[i] - x[0]) - entry_centre[k];
      return dx;
    }

    /// The domain of point @p p deforms with the point: D_c <- (I + dt
    /// grad v) D_c (PointDomains::deformed_domain(), its stretch limited
    /// relative to the point's cell's), and shrinks about it if the
    /// point's volume was reduced by @p volume_factor < 1 (its material's
    /// 'Minimum density').
    void
    deform_with_point(const unsigned int    p,
                      double               *props,
                      const Tensor<2, dim> &grad_v,
                      const double          volume_factor) const;

    const BilinearCellMap *
    cell_map_of_point(const unsigned int p) const
    {
      return point_cell_map[p];
    }

    /**
     * Whether APIC may fit the affine matrix of the point with properties
     * @p props to the end-of-step grid velocity (C_p = B_p D_p^-1) under
     * MUSL: where its domain has at least half its size. A domain shrunk
     * further (its corners beyond a wall, or a lone point dilated far
     * beyond its cell and scaled down to fit its patch) gives nearly the
     * linear weights, whose second moment vanishes towards cell edges:
     * there the fit amplified a resting point's velocities into C_p of
     * 1e4 1/s, which the base's normal constraint turned into an upward
     * kick (the collapse at CFL 0.9, doc/transfers.md). Such a point takes
     * C_p from the remapped velocity, as with linear weights.
     */
    bool
    fit_is_stable(const double *props) const
    {
      return props[this->own_slot + PointDomains<dim>::scale_slot] >=
             minimum_fit_scale;
    }

    /// The smallest domain scale at which fit_is_stable().
    static constexpr double minimum_fit_scale = 0.5;
    /// @}

    PointDomains<dim> point_domains;

    /// The search of a cell's points' corners in its patch (defined in
    /// cpdi_weights.cc).
    class PatchSearch;

    /// prepare(), 1: the cells holding points (point_cells) with their
    /// first points and sizes.
    void
    collect_point_cells();

    /**
     * prepare(), 2: the corners of the points of point_cells[@p pc]
     * located (PatchSearch), their domains shrunk where a corner left the
     * patch, weighed (alpha_c, beta_c) and stored in located_corners, the
     * hints updated. Returns the message of an inverted domain (empty if
     * none). Safe on several threads for different cells.
     */
    std::string
    locate_corners_of_cell(const unsigned int pc);

    /// Each entry's point (index into points), in the order of
    /// shape_functions.
    std::vector<unsigned int> entry_point;
    /**
     * APIC: each entry's xbar_p - x_0, its point's affine centre xbar_p =
     * x_p + sum_c alpha_c (x_c - x_p) (the mean of the weights' centres,
     * about which sum_i w_ip (x_i - xbar_p) = 0, so the affine part adds no
     * momentum; xbar_p = x_p for a parallelogram domain)
     * relative to the first vertex x_0 of the entry's cell.
     */
    std::vector<Tensor<1, dim>> entry_centre;
    /// A corner located by prepare(), before the corners are grouped into
    /// entries.
    struct LocatedCorner
    {
      /// The active_cell_index() of the cell the corner lies in.
      unsigned int cell;
      /// The point's first corner in the same cell (this corner's, if it
      /// is the first): the corners of one entry.
      unsigned char  first_in_cell;
      /// The periodic image of the cell the corner lies in (index into
      /// image_shifts; 0: the cell itself).
      unsigned char  image;
      Point<dim>     xi;
      double         alpha;
      Tensor<1, dim> beta;
    };
    /// n_corners per point, in the order of the points.
    std::vector<LocatedCorner> located_corners;
    /// Each point's affine centre xbar_p (APIC).
    std::vector<Point<dim>> point_centre;
    /// The entry each of located_corners adds to.
    std::vector<unsigned int> entry_of_corner;
    /// The cells holding points this step (their first points are
    /// point_cell_first_point).
    std::vector<typename Triangulation<dim>::active_cell_iterator>
      point_cells;
    /// Each active cell's slot among the cells holding corners
    /// (invalid_unsigned_int between steps).
    std::vector<unsigned int> corner_slot_of_cell;
    /// Each point's cell map (2D).
    std::vector<const BilinearCellMap *> point_cell_map;
    /// PointDomains::cell_stretch2() of each locally owned cell (by
    /// active_cell_index()) and of each point's cell.
    std::vector<double> cell_stretch2, point_cell_stretch2;
    /// The cells a corner of a point in each locally owned cell may lie in
    /// (their active_cell_index(), by active_cell_index(); the cell itself
    /// first).
    std::vector<std::vector<unsigned int>> cell_patches;
    /**
     * Periodic boundaries only (else empty): for each cell of each patch,
     * the periodic image in which it neighbours the patch's cell, as an
     * index into image_shifts. A cell across a periodic boundary is a
     * neighbour shifted by the period: a corner x beyond the boundary is
     * located in it at x - shift, and the cell's nodes (the copies of the
     * nodes near x, PeriodicNodeGroups) take its weights.
     */
    std::vector<std::vector<unsigned char>> cell_patch_images;
    /// The shifts of the periodic images (the first: none).
    std::vector<Tensor<1, dim>> image_shifts;

    /**
     * For each locally owned cell whose map is affine (a parallelogram or
     * parallelepiped; else empty), where each cell of its patch lies
     * relative to it: in the cell's reference coordinates, the patch
     * cell's bounding box lies below (k_d = 0), within (1) or above (2)
     * [0, 1] in each coordinate d (to 1e-10), coded as sum_d k_d 3^d, or
     * mixed_direction if it straddles 0 or 1 (a coarser neighbour, a
     * distorted one). A corner outside the cell goes first to the cells
     * of its own direction (the corner's reference coordinates in the
     * point's cell tell it): usually one, the neighbour it crossed into,
     * instead of the ordered search through up to 27 cells. Where no cell
     * of the patch is mixed, a corner in a direction where no cell holds
     * it lies outside the patch.
     */
    std::vector<std::vector<unsigned char>> cell_patch_directions;
    static constexpr unsigned char mixed_direction = 255;

    /**
     * Where each point's corners lay in the last step: its cell then (the
     * active_cell_index()) and each corner's cell as a position in that
     * cell's patch. A point's corners move by a fraction of a cell per step,
     * so the last step's cell is tried first; it is accepted without the
     * ordered search only if it holds the corner strictly inside (farther
     * than corner_hint_margin from its faces in reference coordinates),
     * where no other cell of the patch holds it and the ordered search
     * would find the same cell, or if it is the cell the ordered search
     * tries first (the previous point's): a hint changes the cost, never
     * the result. Kept only for points in cells that are not
     * parallelograms (parallelepipeds), where the ordered search is dear.
     */
    struct CornerHint
    {
      unsigned int cell = numbers::invalid_unsigned_int;
      /// Each corner's cell: its active_cell_index() and periodic image
      /// (what the hit needs, without reading the patch), and its
      /// position in the patch (where the ordered search of the cell's
      /// next point starts).
      std::array<unsigned int, PointDomains<dim>::n_corners>  cell_index;
      std::array<unsigned char, PointDomains<dim>::n_corners> image;
      std::array<unsigned char, PointDomains<dim>::n_corners> patch_position;
    };
    /**
     * The hints by the points' local index in the ParticleHandler
     * (Particles::ParticleAccessor::get_local_index(), sized by the
     * property pool's slots). A point re-inserted into another slot (when
     * it changes cell or the storage is put back in cell order) finds
     * another point's hint or none: it pays for the ordered search once.
     * Cleared by setup_partition() (a hint is valid for its cell's patch);
     * not checkpointed: the first step after a restart searches.
     */
    std::vector<CornerHint> corner_hints;
    /**
     * 3D only (else empty): each hinted corner's reference coordinates in
     * its cell in the last step, where Newton's iteration on a cell that
     * is not a parallelepiped starts (TrilinearCellMap).
     */
    std::vector<std::array<Point<dim>, PointDomains<dim>::n_corners>>
      corner_hint_xi;
    /// Margin of a hint's acceptance (see CornerHint), in reference
    /// coordinates: far above the round-off of the inverse maps and their
    /// tolerance (reference_cell_tolerance) for cells of a patch whose
    /// sizes differ by up to a factor 1e4.
    static constexpr double corner_hint_margin = 1e-8;
  };
} // namespace MPM

#endif
