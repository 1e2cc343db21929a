#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>

#include <mpm/grid/point_location.h>
#include <mpm/grid/trilinear_cell_map.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/material_points/point_relocation.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <utility>

namespace MPM
{
  template <int dim>
  void
  PointRelocation<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Material points");
    prm.declare_entry(
      "Point location",
      "incremental",
      Patterns::Selection("incremental|sort"),
      "How points are found in the mesh after each step: 'incremental' "
      "updates each point's reference coordinates in its old cell and moves "
      "only the points that left it (a point that enters a neighbouring "
      "rank's cell is sent there; deal.II's full sort only when a point "
      "goes beyond the ghost layer); 'sort' calls "
      "ParticleHandler::sort_particles_into_subdomains_and_cells() every "
      "step. Both give the same cells and coordinates to round-off.");
    prm.declare_entry("Inverse mapping",
                      "closed form",
                      Patterns::Selection(inverse_mapping_type_selection()),
                      "Inverse of the isoparametric map used by 'Point "
                      "location = incremental': 'closed form' (bilinear "
                      "quadrilaterals; in 3D parallelepipeds and cells "
                      "extruded along one direction, such as terrain "
                      "columns, and Newton's iteration for any other "
                      "hexahedron; doc/point_location.md), 'newton' "
                      "(Newton's iteration, in 3D for every cell that is "
                      "not a parallelepiped), or deal.II's MappingQ1 "
                      "('deal.II').");
    prm.declare_entry(
      "Wall overshoot tolerance",
      "0.25",
      Patterns::Double(0, 1),
      "A point that crossed a wall of its cell (a face on a boundary whose "
      "type is not 'free') in a step, by at most this fraction of the "
      "cell's width across the wall, is put back onto the wall instead of "
      "having left the mesh. The mesh conforms to the ground, and a point "
      "sliding along it moves with nodal velocities tangent to the nodes' "
      "averaged normals, not to the faces between them: past a node where "
      "the ground turns away, or on a twisted face, it dips below the "
      "surface by a fraction of a millimetre to millimetres (a 3D slide at "
      "10 m/s lost 76 points so, doc/boundary_conditions.md). The number "
      "of points put back and the largest distance are reported at the end "
      "of the run. 0: every point beyond a wall has left the mesh ('Points "
      "leaving the mesh').");
    prm.leave_subsection();
  }


  template <int dim>
  void
  PointRelocation<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Material points");
    incremental  = prm.get("Point location") == "incremental";
    inverse_type = parse_inverse_mapping_type(prm.get("Inverse mapping"));
    overshoot_tolerance = prm.get_double("Wall overshoot tolerance");
    prm.leave_subsection();
  }


  template <int dim>
  void
  PointRelocation<dim>::initialize(const BackgroundGrid<dim> &background_grid)
  {
    grid            = &background_grid;
    inverse_mapping = std::make_unique<InverseMapping<dim>>(inverse_type,
                                                            grid->mapping);
    cache           = std::make_unique<GridTools::Cache<dim>>(
      grid->triangulation, grid->mapping);
    const auto sets = GridTools::vertex_to_cell_map(grid->triangulation);
    cells_at_vertex.assign(sets.size(), {});
    for (unsigned int v = 0; v < sets.size(); ++v)
      cells_at_vertex[v].assign(sets[v].begin(), sets[v].end());
  }


  template <int dim>
  void
  PointRelocation<dim>::relocate(
    Particles::ParticleHandler<dim> &particle_handler)
  {
    if (!incremental)
      {
        if (!grid->periodic_boundaries.empty())
          for (auto &point : particle_handler)
            {
              Point<dim> x = point.get_location();
              if (wrap(x, point.get_properties().data()))
                point.set_location(x);
            }
        particle_handler.sort_particles_into_subdomains_and_cells();
        ++stats.n_full_sorts;
        return;
      }

    // 1. Every point in its old cell, cell by cell.
    const bool by_vertices = inverse_type != InverseMappingType::dealii;
    for (auto it = particle_handler.begin(); it != particle_handler.end();)
      {
        const CellIterator cell   = it->get_surrounding_cell();
        const auto         points = particle_handler.particles_in_cell(cell);
        if (can_locate_while_moving())
          {
            // The same in-cell test as the grid-to-particle pass makes.
            const BilinearCellMap &map = grid->bilinear_map(cell);
            Located                located;
            for (auto point = points.begin(); point != points.end(); ++point)
              locate_in_cell(map, point, point->get_location(), located);
            add_located(located);
            it = points.end();
            continue;
          }
        const auto &vertices = grid->cell_vertices(cell);
        // A parallelepiped (3D) is inverted by one product instead of
        // Newton's iteration (not with 'Inverse mapping = deal.II'), an
        // extruded hexahedron (terrain) in closed form with 'closed form'
        // (ExtrudedCellMap). Any other hexahedron by Newton's iteration
        // from each point's last reference coordinates (TrilinearCellMap).
        const ParallelepipedMap *affine_map   = nullptr;
        const ExtrudedCellMap   *extruded_map = nullptr;
        std::optional<TrilinearCellMap> trilinear_map;
        if constexpr (dim == 3)
          if (inverse_type == InverseMappingType::newton ||
              inverse_type == InverseMappingType::closed_form)
            {
              const unsigned int index = cell->active_cell_index();
              if (grid->parallelepiped_map(index).is_affine())
                affine_map = &grid->parallelepiped_map(index);
              else
                {
                  if (inverse_type == InverseMappingType::closed_form)
                    extruded_map = grid->extruded_map(index);
                  if (extruded_map == nullptr)
                    trilinear_map.emplace(vertices);
                }
            }
        for (auto point = points.begin(); point != points.end(); ++point)
          {
            const Point<dim> x = point->get_location();
            InverseMappingResult<dim> result;
            if constexpr (dim == 3)
              {
                if (affine_map != nullptr)
                  {
                    result.xi      = affine_map->inverse(x);
                    result.success = true;
                  }
                else
                  {
                    if (extruded_map != nullptr)
                      result = extruded_map->inverse(x);
                    else
                      result = trilinear_map->inverse(
                        x, point->get_reference_location());
                  }
              }
            if (!result.success)
              result =
                by_vertices ?
                  inverse_mapping->transform_real_to_unit_cell(vertices, x) :
                  inverse_mapping->transform_real_to_unit_cell(cell, x);
            if (result.success && inside_unit_cell(result.xi))
              point->set_reference_location(result.xi);
            else
              leavers_of_this_step.push_back(point);
          }
        stats.n_points_mapped += static_cast<unsigned int>(
          std::distance(points.begin(), points.end()));
        it = points.end();
      }

    relocate_leavers(particle_handler);
  }


  template <int dim>
  bool
  PointRelocation<dim>::wrap(Point<dim> &x, const double *properties)
  {
    const Tensor<1, dim> shift = grid->periodic_boundaries.wrap(x);
    if (shift.norm_square() == 0)
      return false;
    ++stats.n_points_wrapped;
    stats.wrapped_mass_shift += properties[PropertyLayout<dim>::mass] * shift;
    return true;
  }


  template <int dim>
  void
  PointRelocation<dim>::relocate_leavers(
    Particles::ParticleHandler<dim> &particle_handler)
  {
    // Step 1 (relocate(), or locate_in_cell() from the grid-to-particle
    // pass) saw every point of this rank since the last call.
    Assert(stats.n_points_mapped - n_mapped_at_last_relocation ==
             particle_handler.n_locally_owned_particles(),
           ExcMessage("relocate_leavers() needs every point of this rank "
                      "located in its old cell first (relocate() or "
                      "locate_in_cell() for each point): " +
                      std::to_string(stats.n_points_mapped -
                                     n_mapped_at_last_relocation) +
                      " of " +
                      std::to_string(
                        particle_handler.n_locally_owned_particles()) +
                      " were."));
    n_mapped_at_last_relocation = stats.n_points_mapped;
    const MPI_Comm comm = grid->triangulation.get_communicator();
    // Taken over from step 1, which starts empty in the next step.
    const std::vector<ParticleIterator> leavers =
      std::exchange(leavers_of_this_step, {});
    const auto n_before = particle_handler.n_locally_owned_particles();
    struct Move
    {
      Point<dim>            location;
      Point<dim>            reference_location;
      types::particle_index id;
      CellIterator          cell;
      unsigned int          first_property;
    };
    std::vector<ParticleIterator> lost;
    std::vector<Move>   moves;
    // Per destination rank: the points that moved into its cells.
    std::map<unsigned int, std::vector<double>> sends;
    std::vector<double> properties;
    bool                need_full_sort = false;

    // 2. The points that left: first the cells around the old one, then
    //    the whole mesh. A candidate's map as the grid keeps it: its
    //    bilinear map ('closed form' in 2D) or an extruded cell's closed
    //    form ('closed form' in 3D), else the inverse mapping of its
    //    vertices: the same numbers as through the cell, without reading
    //    the vertices through the triangulation (an artificial cell, which
    //    the grid keeps no vertices of, through the cell).
    const bool by_vertices = inverse_type != InverseMappingType::dealii;
    const auto invert_in   = [&](const CellIterator &cell,
                               const Point<dim>   &y) {
      if (!by_vertices || cell->is_artificial())
        return inverse_mapping->transform_real_to_unit_cell(cell, y);
      const unsigned int index = cell->active_cell_index();
      if constexpr (dim == 2)
        if (inverse_type == InverseMappingType::closed_form)
          return grid->bilinear_map(index).inverse(y);
      if constexpr (dim == 3)
        if (inverse_type == InverseMappingType::closed_form)
          {
            // What inverse_map_closed_form() does, with the grid's map
            // instead of one built from the vertices for each candidate.
            if (const ExtrudedCellMap *extruded = grid->extruded_map(index))
              {
                const InverseMappingResult<dim> result = extruded->inverse(y);
                if (result.success)
                  return result;
              }
            return inverse_map_newton<dim>(grid->cell_vertices(index), y);
          }
      return inverse_mapping->transform_real_to_unit_cell(
        grid->cell_vertices(index), y);
    };
    std::vector<CellIterator> candidates;
    for (const auto &point : leavers)
      {
        const CellIterator old_cell = point->get_surrounding_cell();
        Point<dim>         x        = point->get_location();
        // Out through a periodic boundary: in through its partner (found
        // by the search of the whole mesh below).
        if (wrap(x, point->get_properties().data()))
          ParticleIterator(point)->set_location(x);
        candidates.clear();
        for (const unsigned int v : old_cell->vertex_indices())
          for (const auto &c : cells_at_vertex[old_cell->vertex_index(v)])
            if (c != old_cell &&
                std::find(candidates.begin(), candidates.end(), c) ==
                  candidates.end())
              candidates.push_back(c);
        PointLocation<dim> location =
          locate_point_by<dim>(invert_in, candidates, x);
        // Just beyond a wall of its old cell: put back onto it (before the
        // search of the whole mesh, which costs milliseconds a point in a
        // mesh of 1e4 cells and would find a cell there only if the mesh
        // folded back within a fraction of a cell behind the wall: a point
        // through a wall that thin should not have passed either).
        if (!location.found &&
            put_back_onto_wall(old_cell, invert_in, candidates, x, location))
          ParticleIterator(point)->set_location(x);
        if (!location.found)
          {
            const auto found = GridTools::find_active_cell_around_point(
              *cache, x, old_cell, {}, reference_cell_tolerance);
            if (found.first.state() == IteratorState::valid)
              {
                location.cell  = found.first;
                location.xi    = found.second;
                location.found = true;
              }
          }
        if (!location.found)
          {
            // Neither next to its old cell, nor just beyond a wall of it,
            // nor anywhere in the mesh (every rank's triangulation covers
            // the whole domain): the point left the domain. Reported
            // below, unless deal.II's sort takes over (it reports them
            // itself).
            lost.push_back(point);
            continue;
          }
        if (location.cell->is_ghost())
          {
            // Into a cell of a neighbouring rank: sent there, with the
            // cell's id, its reference coordinates and all properties.
            auto &buffer = sends[location.cell->subdomain_id()];
            for (unsigned int d = 0; d < dim; ++d)
              buffer.push_back(x[d]);
            for (unsigned int d = 0; d < dim; ++d)
              buffer.push_back(location.xi[d]);
            buffer.push_back(static_cast<double>(point->get_id()));
            for (const unsigned int b : location.cell->id().template to_binary<dim>())
              buffer.push_back(b);
            const auto p = point->get_properties();
            buffer.insert(buffer.end(), p.begin(), p.end());
            continue;
          }
        if (!location.cell->is_locally_owned())
          {
            // Beyond the ghost layer: only deal.II's sort finds the owner.
            need_full_sort = true;
            break;
          }
        moves.push_back({x,
                         location.xi,
                         point->get_id(),
                         location.cell,
                         static_cast<unsigned int>(properties.size())});
        const auto p = point->get_properties();
        properties.insert(properties.end(), p.begin(), p.end());
      }

    // 3. One reduction decides for every rank whether deal.II's full sort
    //    is needed (a point went beyond the ghost layer), whether any rank
    //    moved points, whether any sends points to another rank, whether
    //    any lost points and whether any wants its storage reordered: the
    //    branches below call collective functions (the sort,
    //    some_to_some(), update_cached_numbers()) that every rank must
    //    enter.
    const bool reorder_wanted =
      n_moved_since_reorder + leavers.size() > reorder_fraction * n_before;
    const std::array<unsigned int, 5> local_flags{
      {need_full_sort ? 1u : 0u,
       leavers.empty() ? 0u : 1u,
       sends.empty() ? 0u : 1u,
       lost.empty() ? 0u : 1u,
       reorder_wanted ? 1u : 0u}};
    std::array<unsigned int, 5> global_flags{};
    Utilities::MPI::max(ArrayView<const unsigned int>(local_flags),
                        comm,
                        ArrayView<unsigned int>(global_flags));
    if (global_flags[0] != 0)
      {
        particle_handler.sort_particles_into_subdomains_and_cells();
        ++stats.n_full_sorts;
        return;
      }
    if (global_flags[1] == 0)
      return;
    // Only the points that crossed to a neighbour travel (point to point),
    // not a sort of every point.
    std::map<unsigned int, std::vector<double>> received;
    if (global_flags[2] != 0)
      {
        for (const auto &[rank, buffer] : sends)
          stats.n_points_sent +=
            buffer.size() / (2 * dim + 5 + particle_handler.n_properties_per_particle());
        received = Utilities::MPI::some_to_some(comm, sends);
      }
    // Reported as deal.II's sort would report them, so that the owner of
    // the signal decides (error or removal).
    for (const auto &point : lost)
      particle_handler.signals.particle_lost(point,
                                             point->get_surrounding_cell());
    const unsigned int n_properties =
      particle_handler.n_properties_per_particle();
    // The lost points are among the leavers: removed, not re-inserted.
    // Removed the way deal.II's remove_particles() removes a list in the
    // order of iteration (backwards, one by one, so that the iterators
    // still to be removed stay valid; the same points end up in the same
    // slots), but without the recount of all points that follows there
    // (see below).
    for (auto point = leavers.rbegin(); point != leavers.rend(); ++point)
      particle_handler.remove_particle(*point);
    for (const auto &m : moves)
      particle_handler.insert_particle(
        m.location,
        m.reference_location,
        m.id,
        m.cell,
        ArrayView<const double>(properties.data() + m.first_property,
                                n_properties));
    const unsigned int record = 2 * dim + 5 + n_properties;
    for (const auto &[rank, buffer] : received)
      for (std::size_t r = 0; r + record <= buffer.size(); r += record)
        {
          const double *b = buffer.data() + r;
          Point<dim>    x, xi;
          for (unsigned int d = 0; d < dim; ++d)
            {
              x[d]  = b[d];
              xi[d] = b[dim + d];
            }
          const auto id = static_cast<types::particle_index>(b[2 * dim]);
          CellId::binary_type binary;
          for (unsigned int k = 0; k < 4; ++k)
            binary[k] = static_cast<unsigned int>(b[2 * dim + 1 + k]);
          const CellIterator cell(
            grid->triangulation.create_cell_iterator(CellId(binary)));
          particle_handler.insert_particle(
            x,
            xi,
            id,
            cell,
            ArrayView<const double>(b + 2 * dim + 5, n_properties));
        }
    stats.n_points_moved += moves.size();
    n_moved_since_reorder += leavers.size();
    // On every rank if one wants it: the reordering (clear_particles()
    // and insert_particle()) leaves deal.II's local count wrong until the
    // collective recount below.
    if (global_flags[4] != 0)
      {
        const auto start = std::chrono::steady_clock::now();
        reorder_storage(particle_handler);
        stats.reorder_seconds += std::chrono::duration<double>(
                                   std::chrono::steady_clock::now() - start)
                                   .count();
      }
    // remove_particle() and insert_particle() keep the local number of
    // points; the global number (a sum over the ranks that deal.II caches)
    // changes only if a point left the domain. Only then (and after a
    // reordering) are the cached numbers recounted:
    // update_cached_numbers() walks all points and does three reductions,
    // and deal.II's remove_particles() calls it every step, a twentieth
    // of the flume's run time when points change cell in nearly every
    // step. (Its maximum number of points per cell is left stale; nothing
    // here uses it.)
    if (global_flags[3] != 0 || global_flags[4] != 0)
      particle_handler.update_cached_numbers();
    Assert(global_flags[2] != 0 || global_flags[3] != 0 ||
             particle_handler.n_locally_owned_particles() == n_before,
           ExcInternalError());
  }


  template <int dim>
  template <typename InverseMap>
  bool
  PointRelocation<dim>::put_back_onto_wall(
    const CellIterator              &old_cell,
    const InverseMap                &invert_in,
    const std::vector<CellIterator> &candidates,
    Point<dim>                      &x,
    PointLocation<dim>              &location)
  {
    if (walls.empty() || overshoot_tolerance == 0)
      return false;
    // The reference coordinates of x in @p cell with those beyond a wall
    // face of the cell (face f lies at xi_{f/2} = f % 2) set back onto the
    // face; the largest such overshoot (0: beyond no wall). False if the
    // map cannot be inverted there.
    const auto onto_walls_of =
      [&](const CellIterator &cell, Point<dim> &xi, double &overshoot) {
        const InverseMappingResult<dim> result = invert_in(cell, x);
        if (!result.success)
          return false;
        xi        = result.xi;
        overshoot = 0;
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              walls.count(cell->face(f)->boundary_id()) != 0)
            {
              const unsigned int d     = f / 2;
              const double       bound = f % 2;
              const double beyond = f % 2 == 0 ? bound - xi[d] : xi[d] - bound;
              if (beyond > 0)
                {
                  overshoot = std::max(overshoot, beyond);
                  xi[d]     = bound;
                }
            }
        return true;
      };
    const auto put_back = [&](const Point<dim> &y, const double overshoot) {
      ++stats.n_points_put_back;
      stats.largest_put_back = std::max(stats.largest_put_back, (y - x).norm());
      stats.largest_put_back_fraction =
        std::max(stats.largest_put_back_fraction, overshoot);
      x = y;
      return true;
    };

    // Beyond a wall of its old cell: onto that wall, in the old cell or,
    // if the point also crossed into a neighbour along the wall, in the
    // neighbour the wall's continuation reaches.
    Point<dim> xi;
    double     overshoot = 0;
    if (old_cell->at_boundary() && onto_walls_of(old_cell, xi, overshoot) &&
        overshoot > 0 && overshoot <= overshoot_tolerance)
      {
        const Point<dim> y = map_unit_to_real<dim>(
          grid->cell_vertices(old_cell->active_cell_index()), xi);
        if (inside_unit_cell(xi))
          {
            location.cell  = old_cell;
            location.xi    = xi;
            location.found = true;
          }
        else
          location = locate_point_by<dim>(invert_in, candidates, y);
        if (location.found)
          return put_back(y, overshoot);
      }

    // Beyond the wall of a neighbour: where the ground turns up between
    // the old cell and the neighbour (a concave kink), the old cell's wall
    // continued passes below the neighbour's, and a point that slid across
    // the kink and dipped below the neighbour's wall is found by neither.
    // Onto the wall of the neighbour whose walls alone it crossed, by the
    // least overshoot.
    double best_overshoot = std::numeric_limits<double>::max();
    for (const CellIterator &cell : candidates)
      if (cell->at_boundary() && onto_walls_of(cell, xi, overshoot) &&
          overshoot > 0 && overshoot <= overshoot_tolerance &&
          overshoot < best_overshoot && inside_unit_cell(xi))
        {
          best_overshoot = overshoot;
          location.cell  = cell;
          location.xi    = xi;
          location.found = true;
        }
    if (!location.found)
      return false;
    return put_back(map_unit_to_real<dim>(grid->cell_vertices(
                                            location.cell->active_cell_index()),
                                          location.xi),
                    best_overshoot);
  }


  template <int dim>
  void
  PointRelocation<dim>::prepare_for_checkpoint(
    Particles::ParticleHandler<dim> &particle_handler)
  {
    reorder_storage(particle_handler);
    // clear_particles() and insert_particle() leave deal.II's local count
    // to be recounted (as after the reordering in relocate_leavers()).
    particle_handler.update_cached_numbers();
  }


  template <int dim>
  void
  PointRelocation<dim>::reorder_storage(
    Particles::ParticleHandler<dim> &particle_handler)
  {
    struct Record
    {
      Point<dim>            location;
      Point<dim>            reference_location;
      types::particle_index id;
      CellIterator          cell;
    };
    const unsigned int n_properties =
      particle_handler.n_properties_per_particle();
    std::vector<Record> records;
    std::vector<double> properties;
    records.reserve(particle_handler.n_locally_owned_particles());
    properties.reserve(particle_handler.n_locally_owned_particles() *
                       n_properties);
    for (const auto &point : particle_handler)
      {
        records.push_back({point.get_location(),
                           point.get_reference_location(),
                           point.get_id(),
                           point.get_surrounding_cell()});
        const auto p = point.get_properties();
        properties.insert(properties.end(), p.begin(), p.end());
      }
    // With every slot free, the property pool starts again from an empty
    // array, and the points inserted in the order of iteration get
    // consecutive slots. The order of iteration itself does not change
    // (cell by cell, in each cell in the order of insertion): the results
    // are the same to the last bit.
    particle_handler.clear_particles();
    particle_handler.reserve(records.size());
    for (std::size_t r = 0; r < records.size(); ++r)
      particle_handler.insert_particle(
        records[r].location,
        records[r].reference_location,
        records[r].id,
        records[r].cell,
        ArrayView<const double>(properties.data() + r * n_properties,
                                n_properties));
    n_moved_since_reorder = 0;
    ++stats.n_reorders;
  }


  template class PointRelocation<2>;
  template class PointRelocation<3>;
} // namespace MPM
