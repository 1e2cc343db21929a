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
  CpdiWeights<dim>::CpdiWeights(const TransferContext<dim> &context,
                                ParameterHandler           &prm)
    : ParticleGridPasses<dim, CpdiWeights<dim>>(context)
  {
    point_domains.parse_parameters(prm);
  }


  template <int dim>
  void
  CpdiWeights<dim>::setup_partition()
  {
    ParticleGridPasses<dim, CpdiWeights<dim>>::setup_partition();
    const auto &triangulation = this->context.grid.triangulation;
    const bool  periodic = !this->context.grid.periodic_boundaries.empty();
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
          const auto &grid = this->context.grid;
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


  template <int dim>
  double
  CpdiWeights<dim>::prepare()
  {
    auto       &particle_handler = this->context.particle_handler;
    const auto &grid             = this->context.grid;
    const unsigned int step      = this->context.step;
    const unsigned int domain_slot = this->own_slot;
    auto       &point_properties = this->points;
    auto       &shape_functions  = this->shape_functions;
    TimerOutput::Scope     t(this->context.timer, "shape functions");
    constexpr unsigned int n_corners = PointDomains<dim>::n_corners;
    using CellIterator = typename Triangulation<dim>::active_cell_iterator;
    using Layout       = PropertyLayout<dim>;
    const unsigned int n_points =
      particle_handler.n_locally_owned_particles();
    point_properties.resize(n_points);
    point_cell_map.resize(n_points);

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

    // The cells holding points, with their first points.
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
        this->point_cell_size.push_back(this->context.grid.cell_size(cell));
        point_cells.push_back(cell);
        this->point_cell_first_point.push_back(points.begin());
        n_counted += static_cast<unsigned int>(
          std::distance(points.begin(), points.end()));
        it = points.end();
      }
    this->point_cell_begin.push_back(n_counted);
    AssertThrow(n_counted == n_points, ExcInternalError());

    // Each point's corners, cell by cell on the available threads (a
    // cell's points on one thread: each tries its previous point's cells
    // first). An inverted domain stops the run with the first such point
    // in the order of the points, whatever the number of threads.
    const unsigned int n_point_cells = point_cells.size();
    const unsigned int chunk_size    = chunk_size_for(n_point_cells);
    std::vector<std::string> inverted(chunk_count(n_point_cells, chunk_size));
    for_each_chunk(
      n_point_cells,
      chunk_size,
      [&](const unsigned int chunk,
          const unsigned int first_cell,
          const unsigned int last_cell) {
        for (unsigned int pc = first_cell;
             pc < last_cell && inverted[chunk].empty();
             ++pc)
          {
            const CellIterator &cell  = point_cells[pc];
            unsigned int        p     = this->point_cell_begin[pc];
            const unsigned int  p_end = this->point_cell_begin[pc + 1];
            const auto         &patch = cell_patches[cell->active_cell_index()];
            // The patch's geometry, looked up once for the cell's points
            // when the first of them searches the patch (with the hints most
            // points of a cell that is not a parallelogram never do), and
            // where each corner was found for the previous point (the points
            // of a cell are alike: tried first).
            std::array<const std::array<Point<dim>, n_corners> *, 64>
                                                      patch_vertices;
            std::array<const BilinearCellMap *, 64>   patch_maps;
            std::array<const ParallelepipedMap *, 64> patch_parallelepipeds;
            std::array<const ExtrudedCellMap *, 64>   patch_extruded;
            // (vertices_of() and the like read them: a corner's search
            // looks them up first.)
            bool patch_looked_up = false;
            const auto look_up_patch = [&]() {
              AssertThrow(patch.size() <= 64, ExcInternalError());
              for (unsigned int i = 0; i < patch.size(); ++i)
                {
                  patch_vertices[i] = &grid.cell_vertices(patch[i]);
                  patch_maps[i] =
                    dim == 2 ? &grid.bilinear_map(patch[i]) : nullptr;
                  patch_parallelepipeds[i] =
                    dim == 3 ? &grid.parallelepiped_map(patch[i]) : nullptr;
                  patch_extruded[i] = grid.extruded_map(patch[i]);
                }
              patch_looked_up = true;
            };
            const auto vertices_of = [&](const unsigned int i) {
              return patch_vertices[i];
            };
            const auto map_of = [&](const unsigned int i) {
              return patch_maps[i];
            };
            const auto parallelepiped_of = [&](const unsigned int i) {
              return patch_parallelepipeds[i];
            };
            const auto extruded_of = [&](const unsigned int i) {
              return patch_extruded[i];
            };
            // Periodic boundaries: each patch cell's image.
            const unsigned char *image_of =
              cell_patch_images.empty() ?
                nullptr :
                cell_patch_images[cell->active_cell_index()].data();
            // The shift of the patch's cell @p i (its image's from the cell).
            const auto shift_of = [&](const unsigned int i) {
              return image_shifts[image_of[i]];
            };
            // @p y in the frame of the patch's cell @p i (where its image
            // lies, the cell itself).
            const auto in_cell_frame = [&](const unsigned int i,
                                           const Point<dim>  &y) {
              return image_of == nullptr ? y : y - shift_of(i);
            };
            // Hints where the cell is not a parallelogram (parallelepiped):
            // in a mesh of those, the ordered search from the previous
            // point's cells finds nearly every corner at its first test, and
            // each test is Cramer's rule; corners on the cells' edges (where
            // points of a regular arrangement put them) are not accepted by
            // a hint unless it names that same cell, and the hints cost
            // more than they save (the throughput block: 5 % slower with).
            bool use_hints;
            if constexpr (dim == 2)
              use_hints = !grid.bilinear_map(cell).is_parallelogram();
            else
              use_hints =
                !grid.parallelepiped_map(cell->active_cell_index()).is_affine();
            std::array<unsigned int, n_corners> last_found;
            last_found.fill(0);
            // Where the patch's cells lie (an affine cell only).
            const auto &directions =
              cell_patch_directions[cell->active_cell_index()];
            const bool regular_patch =
              !directions.empty() &&
              std::find(directions.begin(), directions.end(), mixed_direction) ==
                directions.end();
            auto point = this->point_cell_first_point[pc];
            for (; p < p_end; ++point, ++p)
              {
                double *props       = point->get_properties().data();
                point_properties[p] = props;
                const unsigned int hint_index = point->get_local_index();
                CornerHint &hint    = corner_hints[hint_index];
                const bool  hinted  = use_hints && hint.cell == cell->active_cell_index();
                point_cell_map[p] =
                  dim == 2 ? &grid.bilinear_map(cell) : nullptr;
                // A point without a domain yet (new, or read from a file) gets
                // the one of PointDomains::initial_domain().
                auto D = PointDomains<dim>::read(props + domain_slot);
                if (D[0].norm_square() == 0)
                  {
                    D = PointDomains<dim>::initial_domain(
                      grid.cell_vertices(cell),
                      point->get_reference_location(),
                      props[Layout::volume]);
                    PointDomains<dim>::write(D, props + domain_slot);
                    props[domain_slot + PointDomains<dim>::scale_slot] = 1;
                  }
                const Point<dim> x_p = point->get_location();
                std::array<Point<dim>, n_corners> x;
                // Where each corner lies: its cell's position in the patch.
                std::array<unsigned char, n_corners> corner_cell;
                // Its active_cell_index() and periodic image.
                std::array<unsigned int, n_corners>  corner_index;
                std::array<unsigned char, n_corners> corner_image;
                // Where the ordered search found corner @p c: the patch's
                // cell @p i.
                const auto found_in = [&](const unsigned int c,
                                          const unsigned int i) {
                  corner_cell[c]  = i;
                  corner_index[c] = patch[i];
                  corner_image[c] = image_of == nullptr ? 0 : image_of[i];
                };
                std::array<Point<dim>, n_corners>    xi;
                // The search of corner @p c through the cells of its direction
                // (cell_patch_directions), in a cell whose map is affine. It
                // decides only where the ordered search below would give the
                // same: a corner strictly inside a cell (farther than
                // corner_hint_margin from its faces in reference coordinates)
                // lies in no other cell of the patch, and in a regular patch
                // a corner that is clearly in one direction (its reference
                // coordinates in the point's cell that far from 0 and 1) lies
                // in no cell of another direction. Otherwise (a corner on or
                // next to a face, which may belong to several cells: the
                // first the ordered search tries) it is undecided.
                const auto directed_search = [&](const unsigned int c) {
                  constexpr double margin = corner_hint_margin;
                  if (cell_contains<dim>(*vertices_of(0),
                                         map_of(0),
                                         parallelepiped_of(0),
                                         extruded_of(0),
                                         in_cell_frame(0, x[c]),
                                         xi[c]))
                    {
                      if (!inside_unit_cell(xi[c], -margin))
                        return Search::undecided;
                      found_in(c, 0);
                      last_found[c] = 0;
                      return Search::found;
                    }
                  // The corner's direction from the cell (as the codes of
                  // cell_patch_directions).
                  unsigned int direction = 0;
                  for (unsigned int d = 0, stride = 1; d < dim;
                       ++d, stride *= 3)
                    if (xi[c][d] > 1 + margin)
                      direction += 2 * stride;
                    else if (xi[c][d] > margin && xi[c][d] < 1 - margin)
                      direction += stride;
                    else if (!(xi[c][d] < -margin))
                      return Search::undecided;
                  for (unsigned int i = 1; i < patch.size(); ++i)
                    if (directions[i] == direction &&
                        cell_contains<dim>(*vertices_of(i),
                                           map_of(i),
                                           parallelepiped_of(i),
                                           extruded_of(i),
                                           in_cell_frame(i, x[c]),
                                           xi[c]))
                      {
                        if (!inside_unit_cell(xi[c], -margin))
                          return Search::undecided;
                        found_in(c, i);
                        last_found[c] = i;
                        return Search::found;
                      }
                  return regular_patch ? Search::outside : Search::undecided;
                };
                // Whether every corner of the domain scaled by s about x_p
                // lies in the patch (and where).
                const auto locate_corners = [&](const double s) {
                  for (unsigned int c = 0; c < n_corners; ++c)
                    x[c] = x_p + s * D[c];
                  // First each corner in the cell it lay in in the last
                  // step (CornerHint; by its index, without reading the
                  // patch), all corners side by side: in 2D their
                  // closed-form inverse maps overlap.
                  std::array<bool, n_corners> hit{};
                  if (hinted)
                    {
                      // @p x[c] in the frame of the hinted cell of corner @p c.
                      const auto hinted_frame = [&](const unsigned int c) {
                        return hint.image[c] == 0 ?
                                 x[c] :
                                 x[c] - image_shifts[hint.image[c]];
                      };
                      if constexpr (dim == 2)
                        {
                          std::array<const BilinearCellMap *, n_corners> maps;
                          std::array<Point<dim>, n_corners>              z;
                          for (unsigned int c = 0; c < n_corners; ++c)
                            {
                              maps[c] = &grid.bilinear_map(hint.cell_index[c]);
                              z[c]    = hinted_frame(c);
                            }
                          BilinearCellMap::contains(maps, z, xi, hit);
                        }
                      else
                        for (unsigned int c = 0; c < n_corners; ++c)
                          {
                            const unsigned int k = hint.cell_index[c];
                            if (grid.parallelepiped_map(k).is_affine())
                              hit[c] =
                                cell_contains<dim>(grid.cell_vertices(k),
                                                   nullptr,
                                                   &grid.parallelepiped_map(k),
                                                   nullptr,
                                                   hinted_frame(c),
                                                   xi[c]);
                            else
                              {
                                // In closed form if the cell is extruded,
                                // else by Newton's iteration from the
                                // corner's last reference coordinates
                                // (TrilinearCellMap).
                                InverseMappingResult<dim> result;
                                if (const ExtrudedCellMap *extruded =
                                      grid.extruded_map(k))
                                  result = extruded->inverse(hinted_frame(c));
                                if (!result.success)
                                  result =
                                    TrilinearCellMap(grid.cell_vertices(k))
                                      .inverse(hinted_frame(c),
                                               corner_hint_xi[hint_index][c]);
                                hit[c] = result.success &&
                                         inside_unit_cell(result.xi);
                                xi[c] = result.xi;
                              }
                          }
                      for (unsigned int c = 0; c < n_corners; ++c)
                        // Accepted where the ordered search below would test
                        // this cell first (a corner on an edge belongs to
                        // the first cell tried that holds it), or where no
                        // other cell can hold the corner.
                        if (hit[c] &&
                            (hint.patch_position[c] == last_found[c] ||
                             inside_unit_cell(xi[c], -corner_hint_margin)))
                          {
                            corner_cell[c]  = hint.patch_position[c];
                            corner_index[c] = hint.cell_index[c];
                            corner_image[c] = hint.image[c];
                            last_found[c]   = corner_cell[c];
                          }
                        else
                          hit[c] = false;
                    }
                  for (unsigned int c = 0; c < n_corners; ++c)
                    {
                      if (hit[c])
                        continue;
                      if (!patch_looked_up)
                        look_up_patch();
                      bool found = false;
                      const unsigned int n_patch = patch.size();
                      const Search search =
                        directions.empty() ? Search::undecided :
                                             directed_search(c);
                      if (search == Search::found)
                        continue;
                      for (unsigned int j = 0;
                           search == Search::undecided && j <= n_patch;
                           ++j)
                        {
                          // The previous point's cell of this corner first.
                          const unsigned int i =
                            j == 0 ? last_found[c] :
                                     (j - 1 == last_found[c] ? 0 : j - 1);
                          if (j > 0 && j - 1 == 0 && last_found[c] == 0)
                            continue;
                          if (cell_contains<dim>(*vertices_of(i),
                                                 map_of(i),
                                                 parallelepiped_of(i),
                                                 extruded_of(i),
                                                 in_cell_frame(i, x[c]),
                                                 xi[c]))
                            {
                              found_in(c, i);
                              last_found[c] = i;
                              found         = true;
                              break;
                            }
                        }
                      // Outside every cell of the patch (beyond a wall, or
                      // a domain built from the Jacobian at the point that
                      // pokes out of a distorted boundary cell by
                      // O(distortion * size^2)): the domain is shrunk
                      // below. Not moved onto the nearest cell: a domain
                      // with a corner moved has its centroid off the point,
                      // and S+ v, the velocity of the centroid, then keeps
                      // a component towards the wall however close the
                      // point comes: the top corner of a sheared layer
                      // crept through the driven top (doc/transfers.md,
                      // "Domains at walls").
                      if (!found)
                        return false;
                    }
                  return true;
                };
                // The scale s of the domain about the point: 1 unless a corner
                // left the patch (beyond the mesh or a wall, or past the
                // neighbours). Then the whole domain is shrunk about the point,
                // so that it stays centred on it: a point next to a wall moves
                // with the wall's nodes, as with linear weights, instead of
                // being pulled through it by its far corners. The scale is kept
                // from step to step (the last slot) and tried to be doubled
                // every 8th step, so a point resting against a wall pays for
                // one try most steps, not a bisection.
                double &scale = props[domain_slot + PointDomains<dim>::scale_slot];
                const double grown =
                  step % 8 == 0 ? std::min(1., 2 * scale) : scale;
                if (locate_corners(grown))
                  scale = grown;
                else if (!(scale < grown && locate_corners(scale)))
                  {
                    double inside = 0, outside = std::min(scale, grown);
                    for (unsigned int i = 0; i < 10; ++i)
                      {
                        const double s = 0.5 * (inside + outside);
                        (locate_corners(s) ? inside : outside) = s;
                      }
                    scale = inside;
                    if (inside == 0 || !locate_corners(inside))
                      {
                        // The point sits on the patch's edge: a domain a
                        // millionth of its size in its own cell, its corners'
                        // reference coordinates extrapolated if they are just
                        // outside (the limit is the linear weights).
                        scale = 1e-6;
                        for (unsigned int c = 0; c < n_corners; ++c)
                          {
                            x[c] = x_p + scale * D[c];
                            found_in(c, 0);
                            if constexpr (dim == 2)
                              xi[c] = grid.bilinear_map(cell).inverse(x[c]).xi;
                            else
                              xi[c] = inverse_map_closed_form(
                                        grid.cell_vertices(cell), x[c])
                                        .xi;
                          }
                      }
                  }
                if (use_hints)
                  {
                    hint.cell = cell->active_cell_index();
                    for (unsigned int c = 0; c < n_corners; ++c)
                      {
                        hint.patch_position[c] = corner_cell[c];
                        hint.cell_index[c]     = corner_index[c];
                        hint.image[c]          = corner_image[c];
                      }
                    if constexpr (dim == 3)
                      corner_hint_xi[hint_index] = xi;
                  }
                std::array<double, n_corners>         alpha;
                std::array<Tensor<1, dim>, n_corners> beta;
                const Tensor<2, dim> R = PointDomains<dim>::affine_part(D);
                if (PointDomains<dim>::is_parallelepiped(D, R))
                  PointDomains<dim>::parallelepiped_weights(scale * R,
                                                            alpha,
                                                            beta);
                else if (!PointDomains<dim>::corner_weights(x, alpha, beta))
                  {
                    std::ostringstream s;
                    s << "The CPDI domain of material point " << point->get_id()
                      << " at (" << x_p << ") is inverted (domain vectors "
                      << R << " as a parallelogram): the material it represents has turned inside "
                      << "out; reduce the time step.";
                    inverted[chunk] = s.str();
                    break;
                  }
                // The affine centre (see entry_centre).
                if (affine)
                  {
                    Tensor<1, dim> shift;
                    for (unsigned int c = 0; c < n_corners; ++c)
                      shift += alpha[c] * (x[c] - x_p);
                    point_centre[p] = x_p + shift;
                  }
                for (unsigned int c = 0; c < n_corners; ++c)
                  {
                    unsigned char first = 0;
                    while (corner_cell[first] != corner_cell[c])
                      ++first;
                    corners[std::size_t(p) * n_corners + c] = {
                      corner_index[c],
                      first,
                      corner_image[c],
                      xi[c],
                      alpha[c],
                      beta[c]};
                  }
              }
          }
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
  CpdiWeights<dim>::deform_with_point(double               *props,
                                      const Tensor<2, dim> &grad_v,
                                      const double          volume_factor) const
  {
    // The domain deforms with the point: D_c <- (I + dt grad v) D_c.
    const auto D = PointDomains<dim>::read(props + this->own_slot);
    auto       deformed =
      point_domains.deformed_domain(D, this->context.time_step * grad_v);
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
  template class CpdiWeights<2>;
  template class CpdiWeights<3>;
} // namespace MPM

MPM_REGISTER_PARTICLE_GRID_WEIGHTS(MPM::CpdiWeights,
                                   "cpdi",
                                   "the mesh functions averaged over each "
                                   "point's deforming parallelogram domain "
                                   "(Sadeghirad et al. 2011).")
