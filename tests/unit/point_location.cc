// Ownership of points on shared edges and vertices: on a distorted 3 x 3
// mesh, a point on an interior edge or vertex is contained (to 1e-12 in
// reference coordinates) in every cell that shares it, and locate_point()
// gives it to the one with the lowest active cell index, whatever the order
// of the candidate cells. Points 1e-8 outside the mesh are not found.

#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <mpm/grid/point_location.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>

#include "unit_test_tools.h"

namespace unit_point_location
{
  using namespace dealii;
  using namespace MPM;

  int
  run(int /*argc*/, char ** /*argv*/)
  {
    Triangulation<2> triangulation;
    GridGenerator::subdivided_hyper_cube(triangulation, 3);
    // A smooth distortion that keeps the boundary x = 0 .. 1, y = 0 .. 1 in
    // place (so "outside" is easy to construct) and makes the interior
    // cells general quadrilaterals.
    GridTools::transform(
      [](const Point<2> &p) {
        return Point<2>(p[0] + 0.08 * std::sin(M_PI * p[0]) *
                                 std::sin(2 * M_PI * p[1]),
                        p[1] + 0.06 * std::sin(2 * M_PI * p[0]) *
                                 std::sin(M_PI * p[1]));
      },
      triangulation);

    MappingQ1<2>                                        mapping;
    std::vector<Triangulation<2>::active_cell_iterator> candidates;
    for (const auto &cell : triangulation.active_cell_iterators())
      candidates.push_back(cell);
    auto reversed = candidates;
    std::reverse(reversed.begin(), reversed.end());

    for (const auto type : {InverseMappingType::closed_form,
                            InverseMappingType::newton,
                            InverseMappingType::dealii})
      {
        const InverseMapping<2> inverse(type, mapping);
        std::cout << to_string(type) << '\n';

        // Every vertex: the cells that contain it, and the owner.
        for (unsigned int v = 0; v < triangulation.n_vertices(); ++v)
          {
            const Point<2>           &x = triangulation.get_vertices()[v];
            std::vector<unsigned int> containing;
            for (const auto &cell : candidates)
              {
                const auto r = inverse.transform_real_to_unit_cell(cell, x);
                if (r.success && inside_unit_cell(r.xi))
                  containing.push_back(cell->active_cell_index());
              }
            const auto forward  = locate_point(inverse, candidates, x);
            const auto backward = locate_point(inverse, reversed, x);
            std::cout << "  vertex " << v << ": in cells";
            for (const unsigned int c : containing)
              std::cout << ' ' << c;
            std::cout << "; owner "
                      << (forward.found ? forward.cell->active_cell_index() :
                                          -1)
                      << (forward.cell == backward.cell ? "" :
                                                          " (order dependent!)")
                      << '\n';
          }

        // Midpoints of interior edges (on the straight edge between the two
        // vertices) and points 1e-8 outside the unit square.
        unsigned int n_edge_points = 0, n_two_cells = 0, n_lowest = 0;
        for (const auto &cell : candidates)
          for (const unsigned int f : cell->face_indices())
            if (!cell->at_boundary(f))
              {
                const Point<2>            x = cell->face(f)->center();
                std::vector<unsigned int> containing;
                for (const auto &c : candidates)
                  {
                    const auto r = inverse.transform_real_to_unit_cell(c, x);
                    if (r.success && inside_unit_cell(r.xi))
                      containing.push_back(c->active_cell_index());
                  }
                const auto location = locate_point(inverse, reversed, x);
                ++n_edge_points;
                n_two_cells += (containing.size() == 2);
                n_lowest +=
                  (location.found &&
                   location.cell->active_cell_index() ==
                     *std::min_element(containing.begin(), containing.end()));
              }
        std::cout << "  interior edge midpoints (each seen from both cells): "
                  << n_edge_points << ", in exactly two cells: " << n_two_cells
                  << ", owned by the lower index: " << n_lowest << '\n';

        unsigned int n_outside = 0, n_not_found = 0;
        for (const double s : {0., 0.3, 0.5, 1.})
          for (const Point<2> x : {Point<2>(-1e-8, s),
                                   Point<2>(1 + 1e-8, s),
                                   Point<2>(s, -1e-8),
                                   Point<2>(s, 1 + 1e-8)})
            {
              ++n_outside;
              n_not_found += !locate_point(inverse, candidates, x).found;
            }
        std::cout << "  points 1e-8 outside the mesh: " << n_outside
                  << ", not found: " << n_not_found << '\n';
      }
    // The comparison of the output is the check.
    return 0;
  }
} // namespace unit_point_location

MPM_UNIT_TEST_REGISTER(point_location)
