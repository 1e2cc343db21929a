// CPDI weights (CpdiWeights, PointDomains): each point's domain corners
// located in the patch of its cell, weighed, and summed into the point's
// weights on each cell they lie in (prepare()); the passes are
// ParticleGridPasses'.

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>
#include <deal.II/grid/grid_tools.h>

#include <mpm/grid/inverse_mapping.h>
#include <mpm/grid/trilinear_cell_map.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/parallel/thread_chunks.h>
#include <mpm/base/input_error.h>
#include <mpm/transfer/cpdi_weights.h>
#include <mpm/transfer/particle_grid_passes.templates.h>

#include <algorithm>
#include <iterator>
#include <limits>
#include <sstream>

namespace MPM
{
  namespace
  {
    /// The outcome of CpdiWeights' search of a corner by its direction:
    /// found in a cell, in none of the patch, or left to the ordered
    /// search.
    enum class Search
    {
      found,
      outside,
      undecided
    };


    /// Whether @p x lies in the bounding box of @p vertices enlarged by
    /// @p margin times its size: the cheap rejection before an inverse
    /// map (most candidate cells of a corner do not contain it, and the
    /// inverse map of a non-affine cell is dearest for points outside).
    template <int dim>
    bool
    in_bounding_box(
      const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>
                       &vertices,
      const Point<dim> &x,
      const double      margin)
    {
      for (unsigned int d = 0; d < dim; ++d)
        {
          double lo = vertices[0][d], hi = lo;
          for (unsigned int v = 1; v < vertices.size(); ++v)
            {
              lo = std::min(lo, vertices[v][d]);
              hi = std::max(hi, vertices[v][d]);
            }
          const double slack = margin * (hi - lo) + 1e-12 * (hi - lo);
          if (x[d] < lo - slack || x[d] > hi + slack)
            return false;
        }
      return true;
    }


    /// Whether the cell with @p vertices (and, in 2D, @p map; in 3D,
    /// @p parallelepiped and @p extruded, the grid's maps of the cell,
    /// nullptr where it has none) contains @p x, and its reference
    /// coordinates @p xi there.
    template <int dim>
    bool
    cell_contains(
      const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>
                            &vertices,
      const BilinearCellMap   *map,
      const ParallelepipedMap *parallelepiped,
      const ExtrudedCellMap   *extruded,
      const Point<dim>        &x,
      Point<dim>              &xi)
    {
      if constexpr (dim == 2)
        {
          (void)extruded;
          // A parallelogram's inverse map is Cramer's rule: cheaper than any
          // test before it (what the edge test below rejects, points farther
          // out than contains()' tolerance, 1e-12 of the cell, rejects).
          if (map->is_parallelogram())
            return map->contains(x, xi);
          // The bilinear cell is the convex quadrilateral of its straight
          // edges: outside one edge's line (by more than round-off) is
          // outside the cell, four cross products instead of the inverse
          // map, which is dearest for the points outside a non-affine cell.
          const Point<2> *v[4] = {&vertices[0],
                                  &vertices[1],
                                  &vertices[3],
                                  &vertices[2]};
          const Tensor<1, 2> d1 = *v[2] - *v[0], d2 = *v[3] - *v[1];
          const double orientation = d1[0] * d2[1] - d1[1] * d2[0] > 0 ? 1. : -1.;
          for (unsigned int e = 0; e < 4; ++e)
            {
              const Tensor<1, 2> edge = *v[(e + 1) % 4] - *v[e];
              const double side = orientation * (edge[0] * (x[1] - (*v[e])[1]) -
                                                 edge[1] * (x[0] - (*v[e])[0]));
              if (side < -1e-10 * edge.norm_square())
                return false;
            }
          return map->contains(x, xi);
        }
      else
        {
          (void)map;
          // A parallelepiped: one product (ParallelepipedMap).
          if (parallelepiped != nullptr && parallelepiped->is_affine())
            {
              xi = parallelepiped->inverse(x);
              return inside_unit_cell(xi);
            }
          if (!in_bounding_box<dim>(vertices, x, 0.))
            return false;
          // An extruded cell (terrain) in closed form, any other by
          // Newton's iteration.
          InverseMappingResult<dim> result;
          if (extruded != nullptr)
            result = extruded->inverse(x);
          if (!result.success)
            result = inverse_map_newton<dim>(vertices, x);
          if (!result.success || !inside_unit_cell(result.xi))
            return false;
          xi = result.xi;
          return true;
        }
    }
  } // namespace


  template <int dim>
  CpdiWeights<dim>::CpdiWeights(Simulator<dim>   &simulator,
                                ParameterHandler &prm)
      : ParticleGridPasses<dim, CpdiWeights<dim>>(simulator)
  {
    point_domains.parse_parameters(prm);
  }


  template <int dim>
  void
  CpdiWeights<dim>::setup_partition()
  {
    ParticleGridPasses<dim, CpdiWeights<dim>>::setup_partition();
    const auto &triangulation = this->get_grid().triangulation;
    const bool  periodic      = !this->get_grid().periodic_boundaries.empty();
    // With periodic boundaries, each vertex's periodic copies and the
    // shift from it to each: from the pairs of periodic faces (matched
    // vertex by vertex, the faces' centres differing by the shift), then
    // the copies of the copies (a vertex on two periodic planes has three).
    std::vector<std::vector<std::pair<unsigned int, Tensor<1, dim>>>> copies;
    if (periodic)
      {
        copies.resize(triangulation.n_vertices());
        const auto add_copy = [&](const unsigned int v,
                                  const unsigned int w,
                                  const Tensor<1, dim> &shift) {
          if (v == w)
            return false;
          for (const auto &[u, t] : copies[v])
            if (u == w)
              return false;
          copies[v].emplace_back(w, shift);
          return true;
        };
        for (const auto &[face, other] : triangulation.get_periodic_face_map())
          {
            const auto &[cell, f]             = face;
            const auto &[other_cell, other_f] = other.first;
            if (!cell->is_active() || !other_cell->is_active() ||
                cell->is_artificial() || other_cell->is_artificial())
              continue;
            const auto           a     = cell->face(f);
            const auto           b     = other_cell->face(other_f);
            const Tensor<1, dim> shift = b->center() - a->center();
            for (const unsigned int i : a->vertex_indices())
              {
                unsigned int j_best = 0;
                double       best   = std::numeric_limits<double>::max();
                for (const unsigned int j : b->vertex_indices())
                  {
                    const double d =
                      (b->vertex(j) - a->vertex(i) - shift).norm_square();
                    if (d < best)
                      {
                        best   = d;
                        j_best = j;
                      }
                  }
                add_copy(a->vertex_index(i), b->vertex_index(j_best), shift);
                add_copy(b->vertex_index(j_best), a->vertex_index(i), -shift);
              }
          }
        for (unsigned int round = 1; round < dim; ++round)
          for (unsigned int v = 0; v < copies.size(); ++v)
            for (std::size_t k = 0; k < copies[v].size(); ++k)
              {
                const auto [w, s] = copies[v][k];
                for (std::size_t l = 0; l < copies[w].size(); ++l)
                  {
                    const auto [u, t] = copies[w][l];
                    add_copy(v, u, s + t);
                  }
              }
      }
    image_shifts.assign(1, Tensor<1, dim>());
    const auto image_of = [this](const Tensor<1, dim> &shift) {
      for (unsigned int i = 0; i < image_shifts.size(); ++i)
        if ((image_shifts[i] - shift).norm() <=
            1e-9 * std::max(1., shift.norm()))
          return i;
      image_shifts.push_back(shift);
      AssertThrow(image_shifts.size() < 256, ExcInternalError());
      return static_cast<unsigned int>(image_shifts.size() - 1);
    };
    // Each cell's patch: itself first, then the non-artificial cells
    // sharing a vertex with it (where the corners may lie), and with
    // periodic boundaries those sharing a periodic copy of a vertex, in
    // their image next to the cell.
    const auto  sets = GridTools::vertex_to_cell_map(triangulation);
    cell_patches.assign(triangulation.n_active_cells(), {});
    cell_patch_images.assign(periodic ? triangulation.n_active_cells() : 0,
                             {});
    corner_slot_of_cell.assign(triangulation.n_active_cells(),
                               numbers::invalid_unsigned_int);
    cell_patch_directions.assign(triangulation.n_active_cells(), {});
    cell_stretch2.assign(triangulation.n_active_cells(), 1.);
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        cell_stretch2[cell->active_cell_index()] =
          PointDomains<dim>::cell_stretch2(
            this->get_grid().cell_vertices(cell->active_cell_index()));
    // The hints name cells of these patches by position and index.
    corner_hints.clear();
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const unsigned int index = cell->active_cell_index();
          auto              &patch = cell_patches[index];
          std::vector<unsigned char> images;
          const auto add = [&](const unsigned int neighbour,
                               const unsigned int image) {
            for (unsigned int i = 0; i < patch.size(); ++i)
              if (patch[i] == neighbour && (!periodic || images[i] == image))
                return;
            patch.push_back(neighbour);
            if (periodic)
              images.push_back(image);
          };
          add(index, 0);
          for (const unsigned int v : cell->vertex_indices())
            {
              for (const auto &neighbour : sets[cell->vertex_index(v)])
                if (!neighbour->is_artificial())
                  add(neighbour->active_cell_index(), 0);
              if (periodic)
                for (const auto &[w, shift] : copies[cell->vertex_index(v)])
                  {
                    // A cell at the copy w = v + shift lies next to this
                    // one shifted back by the shift.
                    const unsigned int image = image_of(-shift);
                    for (const auto &neighbour : sets[w])
                      if (!neighbour->is_artificial())
                        add(neighbour->active_cell_index(), image);
                  }
            }
          if (periodic)
            cell_patch_images[index] = images;

          // Where the patch's cells lie relative to this one, if its map is
          // affine (cell_patch_directions).
          const auto &grid = this->get_grid();
          bool        affine;
          if constexpr (dim == 2)
            affine = grid.bilinear_map(index).is_parallelogram();
          else
            affine = grid.parallelepiped_map(index).is_affine();
          if (!affine)
            continue;
          const auto reference_coordinates = [&](const Point<dim> &y) {
            if constexpr (dim == 2)
              return grid.bilinear_map(index).inverse(y, false).xi;
            else
              return grid.parallelepiped_map(index).inverse(y);
          };
          constexpr double margin     = 1e-10;
          auto            &directions = cell_patch_directions[index];
          directions.resize(patch.size());
          for (unsigned int i = 0; i < patch.size(); ++i)
            {
              Point<dim> lo, hi;
              for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell;
                   ++v)
                {
                  Point<dim> y = grid.cell_vertices(patch[i])[v];
                  if (periodic)
                    y += image_shifts[images[i]];
                  const Point<dim> eta = reference_coordinates(y);
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      lo[d] = v == 0 ? eta[d] : std::min(lo[d], eta[d]);
                      hi[d] = v == 0 ? eta[d] : std::max(hi[d], eta[d]);
                    }
                }
              unsigned int code  = 0;
              bool         mixed = false;
              for (unsigned int d = 0, stride = 1; d < dim; ++d, stride *= 3)
                if (lo[d] >= 1 - margin)
                  code += 2 * stride;
                else if (lo[d] >= -margin && hi[d] <= 1 + margin)
                  code += stride;
                else if (!(hi[d] <= margin))
                  mixed = true;
              directions[i] = mixed ? mixed_direction : code;
            }
        }
  }


  /**
   * The search for the corners of the points of one cell in that cell's
   * patch (prepare(): one per cell holding points, on the thread that
   * works on the cell). A corner is tried
   *  1. in the cell it lay in in the last step (CornerHint: only where the
   *     point's cell is not a parallelogram or parallelepiped), accepted
   *     only where the ordered search would give the same cell;
   *  2. in the cells of its direction from the point's cell
   *     (cell_patch_directions: an affine cell), where that decides;
   *  3. in every cell of the patch in order, the previous point's cell of
   *     this corner first (the points of a cell are alike).
   * 1 and 2 change the cost of the search, never its result: a corner on
   * a face shared by several cells belongs to the first cell 3 tries.
   */
  template <int dim>
  class CpdiWeights<dim>::PatchSearch
  {
  public:
    static constexpr unsigned int n_corners = PointDomains<dim>::n_corners;
    using Offsets = typename PointDomains<dim>::Offsets;

    /// Where a point's corners lie: their positions, the cells holding
    /// them (position in the patch, active_cell_index(), periodic image)
    /// and their reference coordinates there.
    struct Corners
    {
      std::array<Point<dim>, n_corners>    x;
      std::array<Point<dim>, n_corners>    xi;
      std::array<unsigned char, n_corners> position;
      std::array<unsigned int, n_corners>  index;
      std::array<unsigned char, n_corners> image;
    };

    PatchSearch(const CpdiWeights<dim> &weights, const CellIterator &cell);

    /// Whether this cell's points keep hints (a cell that is not a
    /// parallelogram or parallelepiped: in a mesh of those, search 3 finds
    /// nearly every corner at its first test, each test is Cramer's rule,
    /// and corners on the cells' edges, where points of a regular
    /// arrangement put them, are not accepted by a hint unless it names
    /// that same cell: the hints cost more than they save there, 5 % of
    /// the throughput block).
    const bool use_hints;

    /**
     * Whether every corner x_p + s D_c lies in the patch, and if so where
     * (@p corners). @p hint: the point's hint if it was made in this cell
     * (else nullptr); @p hint_xi (3D): its corners' last reference
     * coordinates, where Newton's iteration starts.
     */
    bool
    locate(const Point<dim>                        &x_p,
           const Offsets                           &D,
           const double                             s,
           const CornerHint                        *hint,
           const std::array<Point<dim>, n_corners> *hint_xi,
           Corners                                 &corners);

    /// The corners x_p + s D_c placed in the point's own cell, their
    /// reference coordinates extrapolated if they lie just outside it (a
    /// point on the patch's edge, with s tiny: the limit is the linear
    /// weights).
    void
    place_in_own_cell(const Point<dim> &x_p,
                      const Offsets    &D,
                      const double      s,
                      Corners          &corners) const;

  private:
    const BackgroundGrid<dim>        &grid;
    const CellIterator                cell;
    const std::vector<unsigned int>  &patch;
    const std::vector<Tensor<1, dim>> &image_shifts;
    /// Periodic boundaries: each patch cell's image (else nullptr).
    const unsigned char              *image_of;
    /// cell_patch_directions of the cell (empty unless it is affine).
    const std::vector<unsigned char> &directions;
    /// Whether no cell of the patch is mixed_direction.
    const bool                        regular_patch;
    /// Where search 2 or 3 (or an accepted hint) found each corner of the
    /// cell's last point: tried first.
    std::array<unsigned int, n_corners> last_found;

    /// The patch cells' geometry, looked up when the first of the cell's
    /// points needs search 2 or 3 (with hints most points of a cell that is
    /// not a parallelogram never do).
    bool looked_up = false;
    std::array<const std::array<Point<dim>, n_corners> *, 64> vertices;
    std::array<const BilinearCellMap *, 64>                   maps;
    std::array<const ParallelepipedMap *, 64>                 parallelepipeds;
    std::array<const ExtrudedCellMap *, 64>                   extruded;

    void
    look_up();

    /// @p y in the frame of the patch's cell @p i (where its image lies,
    /// the cell itself).
    Point<dim>
    in_frame(const unsigned int i, const Point<dim> &y) const
    {
      return image_of == nullptr ? y : y - image_shifts[image_of[i]];
    }

    /// Whether the patch's cell @p i holds corner @p c (then its reference
    /// coordinates are in corners.xi[c]).
    bool
    holds(const unsigned int i, const unsigned int c, Corners &corners) const
    {
      return cell_contains<dim>(*vertices[i],
                                maps[i],
                                parallelepipeds[i],
                                extruded[i],
                                in_frame(i, corners.x[c]),
                                corners.xi[c]);
    }

    /// Corner @p c found in the patch's cell @p i.
    void
    found_in(const unsigned int c, const unsigned int i, Corners &corners)
    {
      corners.position[c] = i;
      corners.index[c]    = patch[i];
      corners.image[c]    = image_of == nullptr ? 0 : image_of[i];
      last_found[c]       = i;
    }

    /// Search 1 for every corner, side by side (in 2D their closed-form
    /// inverse maps overlap): @p hit, which it decided.
    void
    try_hints(const CornerHint                        &hint,
              const std::array<Point<dim>, n_corners> *hint_xi,
              Corners                                 &corners,
              std::array<bool, n_corners>             &hit);

    /**
     * Search 2 for corner @p c. It decides only where search 3 would give
     * the same: a corner strictly inside a cell (farther than
     * corner_hint_margin from its faces in reference coordinates) lies in
     * no other cell of the patch, and in a regular patch a corner that is
     * clearly in one direction (its reference coordinates in the point's
     * cell that far from 0 and 1) lies in no cell of another direction.
     * Otherwise (a corner on or next to a face) it is undecided.
     */
    Search
    directed(const unsigned int c, Corners &corners);

    /// Search 3 for corner @p c: whether any cell of the patch holds it.
    bool
    ordered(const unsigned int c, Corners &corners);
  };


  template <int dim>
  CpdiWeights<dim>::PatchSearch::PatchSearch(const CpdiWeights<dim> &weights,
                                             const CellIterator     &cell)
      : use_hints(dim == 2 ?
                    !weights.get_grid().bilinear_map(cell).is_parallelogram() :
                    !weights.get_grid()
                       .parallelepiped_map(cell->active_cell_index())
                       .is_affine())
      , grid(weights.get_grid())
      , cell(cell)
      , patch(weights.cell_patches[cell->active_cell_index()])
      , image_shifts(weights.image_shifts)
      , image_of(weights.cell_patch_images.empty() ?
                   nullptr :
                   weights.cell_patch_images[cell->active_cell_index()].data())
      , directions(weights.cell_patch_directions[cell->active_cell_index()])
      , regular_patch(!directions.empty() &&
                      std::find(directions.begin(),
                                directions.end(),
                                mixed_direction) == directions.end())
  {
    last_found.fill(0);
  }


  template <int dim>
  void
  CpdiWeights<dim>::PatchSearch::look_up()
  {
    AssertThrow(patch.size() <= 64, ExcInternalError());
    for (unsigned int i = 0; i < patch.size(); ++i)
      {
        vertices[i]        = &grid.cell_vertices(patch[i]);
        maps[i]            = dim == 2 ? &grid.bilinear_map(patch[i]) : nullptr;
        parallelepipeds[i] = dim == 3 ? &grid.parallelepiped_map(patch[i]) : nullptr;
        extruded[i]        = grid.extruded_map(patch[i]);
      }
    looked_up = true;
  }


  template <int dim>
  bool
  CpdiWeights<dim>::PatchSearch::locate(
    const Point<dim>                        &x_p,
    const Offsets                           &D,
    const double                             s,
    const CornerHint                        *hint,
    const std::array<Point<dim>, n_corners> *hint_xi,
    Corners                                 &corners)
  {
    for (unsigned int c = 0; c < n_corners; ++c)
      corners.x[c] = x_p + s * D[c];
    std::array<bool, n_corners> hit{};
    if (hint != nullptr)
      try_hints(*hint, hint_xi, corners, hit);
    for (unsigned int c = 0; c < n_corners; ++c)
      {
        if (hit[c])
          continue;
        if (!looked_up)
          look_up();
        const Search search =
          directions.empty() ? Search::undecided : directed(c, corners);
        if (search == Search::found)
          continue;
        // Outside every cell of the patch (beyond a wall, or a domain
        // built from the Jacobian at the point that pokes out of a
        // distorted boundary cell by O(distortion * size^2)): the caller
        // shrinks the domain. Not moved onto the nearest cell: a domain
        // with a corner moved has its centroid off the point, and S+ v,
        // the velocity of the centroid, then keeps a component towards the
        // wall however close the point comes: the top corner of a sheared
        // layer crept through the driven top (doc/transfers.md, "Domains
        // at walls").
        if (search == Search::outside || !ordered(c, corners))
          return false;
      }
    return true;
  }


  template <int dim>
  void
  CpdiWeights<dim>::PatchSearch::try_hints(
    const CornerHint                        &hint,
    const std::array<Point<dim>, n_corners> *hint_xi,
    Corners                                 &corners,
    std::array<bool, n_corners>             &hit)
  {
    // Corner @p c in the frame of its hinted cell.
    const auto hinted_frame = [&](const unsigned int c) {
      return hint.image[c] == 0 ? corners.x[c] :
                                  corners.x[c] - image_shifts[hint.image[c]];
    };
    if constexpr (dim == 2)
      {
        (void)hint_xi;
        std::array<const BilinearCellMap *, n_corners> hinted_maps;
        std::array<Point<dim>, n_corners>              z;
        for (unsigned int c = 0; c < n_corners; ++c)
          {
            hinted_maps[c] = &grid.bilinear_map(hint.cell_index[c]);
            z[c]           = hinted_frame(c);
          }
        BilinearCellMap::contains(hinted_maps, z, corners.xi, hit);
      }
    else
      for (unsigned int c = 0; c < n_corners; ++c)
        {
          const unsigned int k = hint.cell_index[c];
          if (grid.parallelepiped_map(k).is_affine())
            hit[c] = cell_contains<dim>(grid.cell_vertices(k),
                                        nullptr,
                                        &grid.parallelepiped_map(k),
                                        nullptr,
                                        hinted_frame(c),
                                        corners.xi[c]);
          else
            {
              // In closed form if the cell is extruded, else by Newton's
              // iteration from the corner's last reference coordinates
              // (TrilinearCellMap).
              InverseMappingResult<dim> result;
              if (const ExtrudedCellMap *map = grid.extruded_map(k))
                result = map->inverse(hinted_frame(c));
              if (!result.success)
                result = TrilinearCellMap(grid.cell_vertices(k))
                           .inverse(hinted_frame(c), (*hint_xi)[c]);
              hit[c] = result.success && inside_unit_cell(result.xi);
              corners.xi[c] = result.xi;
            }
        }
    for (unsigned int c = 0; c < n_corners; ++c)
      // Accepted where search 3 would test this cell first (a corner on an
      // edge belongs to the first cell tried that holds it), or where no
      // other cell can hold the corner.
      if (hit[c] &&
          (hint.patch_position[c] == last_found[c] ||
           inside_unit_cell(corners.xi[c], -corner_hint_margin)))
        {
          corners.position[c] = hint.patch_position[c];
          corners.index[c]    = hint.cell_index[c];
          corners.image[c]    = hint.image[c];
          last_found[c]       = corners.position[c];
        }
      else
        hit[c] = false;
  }


  template <int dim>
  Search
  CpdiWeights<dim>::PatchSearch::directed(const unsigned int c,
                                          Corners           &corners)
  {
    constexpr double margin = corner_hint_margin;
    Point<dim>      &xi     = corners.xi[c];
    if (holds(0, c, corners))
      {
        if (!inside_unit_cell(xi, -margin))
          return Search::undecided;
        found_in(c, 0, corners);
        return Search::found;
      }
    // The corner's direction from the cell (as the codes of
    // cell_patch_directions).
    unsigned int direction = 0;
    for (unsigned int d = 0, stride = 1; d < dim; ++d, stride *= 3)
      if (xi[d] > 1 + margin)
        direction += 2 * stride;
      else if (xi[d] > margin && xi[d] < 1 - margin)
        direction += stride;
      else if (!(xi[d] < -margin))
        return Search::undecided;
    for (unsigned int i = 1; i < patch.size(); ++i)
      if (directions[i] == direction && holds(i, c, corners))
        {
          if (!inside_unit_cell(xi, -margin))
            return Search::undecided;
          found_in(c, i, corners);
          return Search::found;
        }
    return regular_patch ? Search::outside : Search::undecided;
  }


  template <int dim>
  bool
  CpdiWeights<dim>::PatchSearch::ordered(const unsigned int c,
                                         Corners           &corners)
  {
    // The previous point's cell of this corner first, then the others in
    // the order of the patch.
    const unsigned int first = last_found[c];
    if (holds(first, c, corners))
      {
        found_in(c, first, corners);
        return true;
      }
    for (unsigned int i = 0; i < patch.size(); ++i)
      if (i != first && holds(i, c, corners))
        {
          found_in(c, i, corners);
          return true;
        }
    return false;
  }


  template <int dim>
  void
  CpdiWeights<dim>::PatchSearch::place_in_own_cell(const Point<dim> &x_p,
                                                   const Offsets    &D,
                                                   const double      s,
                                                   Corners &corners) const
  {
    for (unsigned int c = 0; c < n_corners; ++c)
      {
        corners.x[c]        = x_p + s * D[c];
        corners.position[c] = 0;
        corners.index[c]    = patch[0];
        corners.image[c]    = image_of == nullptr ? 0 : image_of[0];
        if constexpr (dim == 2)
          corners.xi[c] = grid.bilinear_map(cell).inverse(corners.x[c]).xi;
        else
          corners.xi[c] =
            inverse_map_closed_form(grid.cell_vertices(cell), corners.x[c]).xi;
      }
  }


  template <int dim>
  void
  CpdiWeights<dim>::collect_point_cells()
  {
    auto &particle_handler = this->get_mutable_particle_handler();
    this->point_cell_begin.clear();
    this->point_cell_size.clear();
    point_cells.clear();
    this->point_cell_first_point.clear();
    unsigned int n_counted = 0;
    for (auto it = particle_handler.begin(); it != particle_handler.end();)
      {
        const CellIterator cell   = it->get_surrounding_cell();
        const auto         points = particle_handler.particles_in_cell(cell);
        this->point_cell_begin.push_back(n_counted);
        this->point_cell_size.push_back(this->get_grid().cell_size(cell));
        point_cells.push_back(cell);
        this->point_cell_first_point.push_back(points.begin());
        n_counted += static_cast<unsigned int>(
          std::distance(points.begin(), points.end()));
        it = points.end();
      }
    this->point_cell_begin.push_back(n_counted);
    AssertThrow(n_counted == particle_handler.n_locally_owned_particles(),
                ExcInternalError());
  }


  template <int dim>
  std::string
  CpdiWeights<dim>::locate_corners_of_cell(const unsigned int pc)
  {
    constexpr unsigned int n_corners = PointDomains<dim>::n_corners;
    using Layout                     = PropertyLayout<dim>;
    const auto         &grid          = this->get_grid();
    const unsigned int domain_slot   = this->own_slot;
    const CellIterator &cell         = point_cells[pc];
    // Every 8th step a shrunk domain tries to grow back (below).
    const bool                    try_growing = this->get_step() % 8 == 0;
    PatchSearch         search(*this, cell);
    typename PatchSearch::Corners corners;
    auto point = this->point_cell_first_point[pc];
    for (unsigned int p = this->point_cell_begin[pc];
         p < this->point_cell_begin[pc + 1];
         ++point, ++p)
      {
        double *props          = point->get_properties().data();
        this->points[p]        = props;
        point_cell_map[p]      = dim == 2 ? &grid.bilinear_map(cell) : nullptr;
        point_cell_stretch2[p] = cell_stretch2[cell->active_cell_index()];
        const unsigned int hint_index = point->get_local_index();
        CornerHint        &hint       = corner_hints[hint_index];
        const CornerHint  *own_hint =
          search.use_hints && hint.cell == cell->active_cell_index() ? &hint :
                                                                        nullptr;
        const auto *hint_xi =
          dim == 3 ? &corner_hint_xi[hint_index] : nullptr;
        // A point without a domain yet (new, or read from a file) gets the
        // one of PointDomains::initial_domain().
        auto D = PointDomains<dim>::read(props + domain_slot);
        if (D[0].norm_square() == 0)
          {
            D = PointDomains<dim>::initial_domain(
              grid.cell_vertices(cell),
              point->get_reference_location(),
              props[Layout::volume],
              point_domains.initial_domain_size());
            PointDomains<dim>::write(D, props + domain_slot);
            props[domain_slot + PointDomains<dim>::scale_slot] = 1;
          }
        const Point<dim> x_p    = point->get_location();
        const auto       locate = [&](const double s) {
          return search.locate(x_p, D, s, own_hint, hint_xi, corners);
        };
        // The scale s of the domain about the point: 1 unless a corner
        // left the patch (beyond the mesh or a wall, or past the
        // neighbours). Then the whole domain is shrunk about the point, so
        // that it stays centred on it: a point next to a wall moves with
        // the wall's nodes, as with linear weights, instead of being pulled
        // through it by its far corners. The scale is kept from step to
        // step (the last slot) and tried to be doubled every 8th step, so
        // a point resting against a wall pays for one try most steps, not
        // a bisection.
        double &scale = props[domain_slot + PointDomains<dim>::scale_slot];
        const double grown = try_growing ? std::min(1., 2 * scale) : scale;
        if (locate(grown))
          scale = grown;
        else if (!(scale < grown && locate(scale)))
          {
            double inside = 0, outside = std::min(scale, grown);
            for (unsigned int i = 0; i < 10; ++i)
              {
                const double s = 0.5 * (inside + outside);
                (locate(s) ? inside : outside) = s;
              }
            scale = inside;
            if (inside == 0 || !locate(inside))
              {
                // The point sits on the patch's edge: a domain a millionth
                // of its size.
                scale = 1e-6;
                search.place_in_own_cell(x_p, D, scale, corners);
              }
          }
        if (search.use_hints)
          {
            hint.cell           = cell->active_cell_index();
            hint.patch_position = corners.position;
            hint.cell_index     = corners.index;
            hint.image          = corners.image;
            if constexpr (dim == 3)
              corner_hint_xi[hint_index] = corners.xi;
          }
        std::array<double, n_corners>         alpha;
        std::array<Tensor<1, dim>, n_corners> beta;
        const Tensor<2, dim> R = PointDomains<dim>::affine_part(D);
        if (PointDomains<dim>::is_parallelepiped(D, R))
          PointDomains<dim>::parallelepiped_weights(scale * R, alpha, beta);
        else if (!PointDomains<dim>::corner_weights(corners.x, alpha, beta))
          {
            std::ostringstream s;
            s << "The CPDI domain of material point " << point->get_id()
              << " at (" << x_p << ") is inverted (domain vectors " << R
              << " as a parallelogram): the material it represents has "
                 "turned inside out; reduce the time step.";
            return s.str();
          }
        // The affine centre (see entry_centre).
        if (this->affine())
          {
            Tensor<1, dim> shift;
            for (unsigned int c = 0; c < n_corners; ++c)
              shift += alpha[c] * (corners.x[c] - x_p);
            point_centre[p] = x_p + shift;
          }
        for (unsigned int c = 0; c < n_corners; ++c)
          {
            unsigned char first = 0;
            while (corners.position[first] != corners.position[c])
              ++first;
            located_corners[std::size_t(p) * n_corners + c] = {
              corners.index[c],
              first,
              corners.image[c],
              corners.xi[c],
              alpha[c],
              beta[c]};
          }
      }
    return {};
  }


  template <int dim>
  double
  CpdiWeights<dim>::prepare()
  {
    auto &particle_handler = this->get_mutable_particle_handler();
    const auto            &grid             = this->get_grid();
    auto       &shape_functions  = this->shape_functions;
    TimerOutput::Scope     t(this->get_timer(), "shape functions");
    constexpr unsigned int n_corners = PointDomains<dim>::n_corners;
    const unsigned int n_points =
      particle_handler.n_locally_owned_particles();
    this->points.resize(n_points);
    point_cell_map.resize(n_points);
    point_cell_stretch2.resize(n_points);
    // This step's corners, n_corners per point in the order of the points
    // (reused storage).
    auto &corners = located_corners;
    corners.resize(std::size_t(n_points) * n_corners);
    const bool affine = this->affine();
    if (affine)
      point_centre.resize(n_points);
    corner_hints.resize(particle_handler.get_property_pool().n_slots());
    if (dim == 3)
      corner_hint_xi.resize(corner_hints.size());

    collect_point_cells();

    // Each point's corners, cell by cell on the available threads (a
    // cell's points on one thread: each tries its previous point's cells
    // first). An inverted domain stops the run with the first such point
    // in the order of the points, whatever the number of threads.
    const unsigned int n_point_cells = point_cells.size();
    const unsigned int chunk_size    = chunk_size_for(n_point_cells);
    std::vector<std::string> inverted(chunk_count(n_point_cells, chunk_size));
    for_each_chunk(n_point_cells,
                   chunk_size,
                   [&](const unsigned int chunk,
                       const unsigned int first_cell,
                       const unsigned int last_cell) {
                     for (unsigned int pc = first_cell;
                          pc < last_cell && inverted[chunk].empty();
                          ++pc)
                       inverted[chunk] = locate_corners_of_cell(pc);
                   });

    for (const std::string &message : inverted)
      if (!message.empty())
        throw std::runtime_error(message);

    // The entries (a point's corners in one cell) grouped by cell: a
    // counting sort in the order in which the cells were first touched, so
    // that each pass adds to a cell's nodes once for all entries in it.
    // slot_of_cell (as long as the mesh, set up with the nodal fields) is
    // reset below for the touched cells only: no per-step cost in the size
    // of the mesh.
    auto &slot_of_cell = corner_slot_of_cell;
    std::vector<unsigned int> touched;
    std::vector<unsigned int> count;
    for (std::size_t j = 0; j < corners.size(); ++j)
      if (corners[j].first_in_cell == j % n_corners)
        {
          unsigned int &slot = slot_of_cell[corners[j].cell];
          if (slot == numbers::invalid_unsigned_int)
            {
              slot = touched.size();
              touched.push_back(corners[j].cell);
              count.push_back(0);
            }
          ++count[slot];
        }
    std::vector<unsigned int> next(touched.size() + 1, 0);
    for (unsigned int s = 0; s < touched.size(); ++s)
      next[s + 1] = next[s] + count[s];
    const unsigned int n_entries = next.back();
    shape_functions.resize(n_entries);
    entry_point.resize(n_entries);
    if (affine)
      entry_centre.resize(n_entries);
    // Each corner's entry (a corner after the first in its cell joins the
    // first's), then (on the available threads, point by point) the
    // entries' weights, summed over their corners in the corners' order.
    entry_of_corner.resize(corners.size());
    for (std::size_t j = 0; j < corners.size(); ++j)
      {
        const std::size_t first =
          j - j % n_corners + corners[j].first_in_cell;
        entry_of_corner[j] =
          first == j ?
            next[slot_of_cell[corners[j].cell]]++ :
            entry_of_corner[first];
      }
    for_each_chunk(
      n_points,
      chunk_size_for(n_points),
      [&](const unsigned int, const unsigned int first, const unsigned int last) {
        for (unsigned int p = first; p < last; ++p)
          for (unsigned int c = 0; c < n_corners; ++c)
            {
              const std::size_t    j      = std::size_t(p) * n_corners + c;
              const LocatedCorner &corner = corners[j];
              const unsigned int   k      = entry_of_corner[j];
              auto                &w      = shape_functions[k];
              if (corner.first_in_cell == c)
                {
                  w.value.fill(0.);
                  w.gradient.fill(Tensor<1, dim>());
                  entry_point[k] = p;
                  if (affine)
                    {
                      entry_centre[k] =
                        point_centre[p] - grid.cell_vertices(corner.cell)[0];
                      // The cell's image lies by its shift from the cell.
                      if (corner.image != 0)
                        entry_centre[k] -= image_shifts[corner.image];
                    }
                }
              const auto N = Q1ShapeFunctions<dim>::values_at(corner.xi);
              for (unsigned int i = 0; i < n_vertices; ++i)
                {
                  w.value[i] += corner.alpha * N[i];
                  w.gradient[i] += N[i] * corner.beta;
                }
            }
      });
    for (const unsigned int cell : touched)
      slot_of_cell[cell] = numbers::invalid_unsigned_int;

    this->clear_active_cells();
    for (unsigned int s = 0; s < touched.size(); ++s)
      this->add_active_cell(touched[s], count[s]);
    return this->finish_active_cells();
  }


  template <int dim>
  void
  CpdiWeights<dim>::deform_with_point(const unsigned int    p,
                                      double               *props,
                                      const Tensor<2, dim> &grad_v,
                                      const double          volume_factor) const
  {
    // The domain deforms with the point: D_c <- (I + dt grad v) D_c.
    const auto D = PointDomains<dim>::read(props + this->own_slot);
    auto       deformed =
      point_domains.deformed_domain(D,
                                    this->get_time_step() * grad_v,
                                    point_cell_stretch2[p]);
    // Its area (volume) stays the point's.
    if (volume_factor != 1.)
      {
        const double shrink = std::pow(volume_factor, 1. / dim);
        for (auto &offset : deformed)
          offset *= shrink;
      }
    PointDomains<dim>::write(deformed, props + this->own_slot);
  }


  template class ParticleGridPasses<2, CpdiWeights<2>>;
  template class ParticleGridPasses<3, CpdiWeights<3>>;
  template <int dim>
  double
  CpdiWeights<dim>::reach_along(const double         *props,
                                const Tensor<1, dim> &n) const
  {
    const auto D = PointDomains<dim>::read(props + this->own_slot);
    if (D[0].norm_square() == 0)
      return ParticleGridWeights<dim>::reach_along(props, n);
    double reach = 0;
    for (const auto &offset : D)
      reach = std::max(reach, offset * n);
    return reach;
  }


  template class CpdiWeights<2>;
  template class CpdiWeights<3>;
} // namespace MPM

MPM_REGISTER_PARTICLE_GRID_WEIGHTS(MPM::CpdiWeights,
                                   "cpdi",
                                   "the mesh functions averaged over each "
                                   "point's deforming parallelogram domain "
                                   "(Sadeghirad et al. 2011).")
