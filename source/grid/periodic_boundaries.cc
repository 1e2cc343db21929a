#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/lac/affine_constraints.h>

#include <mpm/base/input_error.h>
#include <mpm/grid/periodic_boundaries.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

namespace MPM
{
  template <int dim>
  void
  PeriodicBoundaries<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry(
      "Periodic boundaries",
      "",
      Patterns::Anything(),
      "Pairs of boundary ids that are periodic, separated by ';', each as "
      "'first id, second id, direction' with the direction x, y or z (of "
      "the parameter file's frame), e.g. '0, 1, x' for a rectangle from "
      "subdivided_hyper_rectangle with colorize = true. Each boundary must "
      "be a plane normal to the direction, and the faces of the two must "
      "match after a translation along it. The nodes of the two boundaries "
      "become one, and a material point that leaves through one enters "
      "through the other. A periodic boundary takes no boundary condition. "
      "Empty: none.");
  }


  template <int dim>
  void
  PeriodicBoundaries<dim>::parse_parameters(ParameterHandler &prm)
  {
    pairs.clear();
    const std::string text = prm.get("Periodic boundaries");
    for (const std::string &entry : Utilities::split_string_list(text, ';'))
      {
        if (entry.empty())
          continue;
        const std::vector<std::string> fields =
          Utilities::split_string_list(entry, ',');
        const std::string where = "Mesh/Periodic boundaries: the entry '" +
                                  entry + "' ";
        check_input(fields.size() == 3,
                    where + "must have the form 'first id, second id, "
                            "direction' (e.g. '0, 1, x').");
        Pair pair;
        try
          {
            const int a = Utilities::string_to_int(fields[0]);
            const int b = Utilities::string_to_int(fields[1]);
            check_input(a >= 0 && b >= 0 && a != b,
                        where + "needs two different, non-negative boundary "
                                "ids.");
            pair.first  = a;
            pair.second = b;
          }
        catch (const InputError &)
          {
            throw;
          }
        catch (...)
          {
            throw InputError(where + "does not start with two boundary ids.");
          }
        const std::string direction = fields[2];
        const std::string names     = dim == 2 ? "xy" : "xyz";
        check_input(direction.size() == 1 &&
                      names.find(direction[0]) != std::string::npos,
                    where + "has the direction '" + direction +
                      "'; it must be one of x, y" + (dim == 3 ? ", z" : "") +
                      ".");
        pair.direction = names.find(direction[0]);
        for (const Pair &other : pairs)
          check_input(other.first != pair.first && other.first != pair.second &&
                        other.second != pair.first &&
                        other.second != pair.second,
                      where + "names a boundary id of another pair.");
        pairs.push_back(pair);
      }
  }


  template <int dim>
  void
  PeriodicBoundaries<dim>::apply_to_coarse_mesh(
    parallel::distributed::Triangulation<dim> &triangulation)
  {
    if (pairs.empty())
      return;
    using CellIterator = typename Triangulation<dim>::cell_iterator;
    std::vector<GridTools::PeriodicFacePair<CellIterator>> all_matched;
    for (Pair &pair : pairs)
      {
        const std::string name = "Mesh/Periodic boundaries: the pair " +
                                 std::to_string(pair.first) + ", " +
                                 std::to_string(pair.second);
        // Each boundary a plane x_d = const, on every rank's coarse mesh
        // (p4est keeps the whole coarse mesh on every rank).
        std::array<double, 2> low{{std::numeric_limits<double>::max(),
                                   std::numeric_limits<double>::max()}};
        std::array<double, 2> high{{-std::numeric_limits<double>::max(),
                                    -std::numeric_limits<double>::max()}};
        std::array<unsigned int, 2> n_faces{{0, 0}};
        double                      extent = 0;
        for (const auto &cell : triangulation.cell_iterators_on_level(0))
          {
            extent = std::max(extent, cell->diameter());
            for (const unsigned int f : cell->face_indices())
              if (cell->face(f)->at_boundary())
                for (unsigned int k = 0; k < 2; ++k)
                  if (cell->face(f)->boundary_id() ==
                      (k == 0 ? pair.first : pair.second))
                    {
                      ++n_faces[k];
                      for (const unsigned int v : cell->face(f)->vertex_indices())
                        {
                          const double s = cell->face(f)->vertex(v)[pair.direction];
                          low[k]         = std::min(low[k], s);
                          high[k]        = std::max(high[k], s);
                        }
                    }
          }
        for (unsigned int k = 0; k < 2; ++k)
          {
            const unsigned int id = k == 0 ? pair.first : pair.second;
            check_input(n_faces[k] > 0,
                        name + ": the mesh has no boundary with id " +
                          std::to_string(id) + ".");
            check_input(high[k] - low[k] <= 1e-10 * extent,
                        name + ": boundary " + std::to_string(id) +
                          " is not a plane normal to the direction " +
                          std::string(1, "xyz"[pair.direction]) +
                          " (its coordinate along it varies from " +
                          std::to_string(low[k]) + " to " +
                          std::to_string(high[k]) + ").");
          }
        check_input(std::abs(low[0] - low[1]) > 1e-10 * extent,
                    name + ": the two boundaries lie in the same plane.");
        pair.lower = std::min(low[0], low[1]);
        pair.upper = std::max(low[0], low[1]);

        std::vector<GridTools::PeriodicFacePair<CellIterator>> matched;
        try
          {
            GridTools::collect_periodic_faces(
              triangulation, pair.first, pair.second, pair.direction, matched);
          }
        catch (const ExceptionBase &e)
          {
            std::ostringstream s;
            e.print_info(s);
            throw InputError(name + ": the faces of the two boundaries do "
                                    "not match after a translation along " +
                             std::string(1, "xyz"[pair.direction]) + " (" +
                             Utilities::trim(s.str()) + ").");
          }
        check_input(matched.size() == n_faces[0] && matched.size() == n_faces[1],
                    name + ": the faces of the two boundaries do not match "
                           "one to one after a translation along " +
                      std::string(1, "xyz"[pair.direction]) + " (" +
                      std::to_string(n_faces[0]) + " and " +
                      std::to_string(n_faces[1]) + " faces, " +
                      std::to_string(matched.size()) + " matched).");
        all_matched.insert(all_matched.end(), matched.begin(), matched.end());
      }
    triangulation.add_periodicity(all_matched);
    set_rotation(unit_symmetric_tensor<dim>());
  }


  template <int dim>
  void
  PeriodicBoundaries<dim>::set_rotation(const Tensor<2, dim> &rotation)
  {
    for (Pair &pair : pairs)
      {
        Tensor<1, dim> e;
        e[pair.direction] = 1;
        // A plane x_d = c in the scene frame is n . x = c in the mesh
        // frame, n = R e_d: lower and upper hold for both.
        pair.normal = rotation * e;
        pair.period = (pair.upper - pair.lower) * pair.normal;
      }
  }


  template <int dim>
  std::vector<std::vector<types::global_dof_index>>
  PeriodicBoundaries<dim>::node_groups(
    const DoFHandler<dim> &dof_handler,
    const IndexSet        &locally_relevant_dofs) const
  {
    std::vector<std::vector<types::global_dof_index>> groups;
    if (pairs.empty())
      return groups;
    AffineConstraints<double> constraints(locally_relevant_dofs);
    for (const Pair &pair : pairs)
      DoFTools::make_periodicity_constraints(
        dof_handler, pair.first, pair.second, pair.direction, constraints);
    // The identities dof = other dof, joined into classes (union-find over
    // the indices that appear).
    std::map<types::global_dof_index, types::global_dof_index> parent;
    const auto find = [&parent](types::global_dof_index i) {
      while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
      return i;
    };
    const auto add = [&parent](const types::global_dof_index i) {
      parent.emplace(i, i);
    };
    for (const auto &line : constraints.get_lines())
      for (const auto &entry : line.entries)
        {
          add(line.index);
          add(entry.first);
          const auto a = find(line.index), b = find(entry.first);
          if (a != b)
            parent[std::max(a, b)] = std::min(a, b);
        }
    std::map<types::global_dof_index, std::vector<types::global_dof_index>>
      classes;
    for (const auto &[i, p] : parent)
      classes[find(i)].push_back(i);
    for (auto &[root, members] : classes)
      {
        std::sort(members.begin(), members.end());
        if (std::any_of(members.begin(), members.end(), [&](const auto i) {
              return locally_relevant_dofs.is_element(i);
            }))
          groups.push_back(members);
      }
    return groups;
  }


  template <int dim>
  std::vector<types::boundary_id>
  PeriodicBoundaries<dim>::boundary_ids() const
  {
    std::vector<types::boundary_id> ids;
    for (const Pair &pair : pairs)
      {
        ids.push_back(pair.first);
        ids.push_back(pair.second);
      }
    return ids;
  }


  template class PeriodicBoundaries<2>;
  template class PeriodicBoundaries<3>;
} // namespace MPM
