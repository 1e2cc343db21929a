#ifndef mpm_grid_point_location_h
#define mpm_grid_point_location_h

#include <deal.II/base/point.h>

#include <deal.II/grid/tria.h>

#include <mpm/grid/inverse_mapping.h>

#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The cell that owns a point and the point's reference coordinates in it.
   * @p found is false if no candidate cell contains the point.
   */
  template <int dim>
  struct PointLocation
  {
    typename Triangulation<dim>::active_cell_iterator cell;
    Point<dim>                                        xi;
    bool                                              found = false;
  };

  /**
   * Which of the @p candidates cells owns the point @p x.
   *
   * A cell contains x if the inverse mapping succeeds and
   * inside_unit_cell(xi, tolerance) holds, so a point on an edge or vertex
   * is contained in every cell that shares it. To give every point exactly
   * one owner, independently of the order of the candidates and of the
   * cell the point came from, the rule is: <b>the owner is the cell with
   * the lowest active cell index among the candidates that contain x</b>.
   * Active cell indices are the same on every process of a
   * parallel::distributed::Triangulation only for locally relevant cells,
   * which is where the candidates of a point location come from.
   *
   * Cost: one inverse mapping per candidate, except that a candidate which
   * contains x with a margin of more than 1e-8 in every reference
   * coordinate is returned at once: no other cell of a conforming mesh can
   * contain such a point within the 1e-12 tolerance unless it is 1e4 times
   * larger than this one. The caller should therefore put the most likely
   * cell (the point's previous cell) first.
   */
  template <int dim>
  PointLocation<dim>
  locate_point(
    const InverseMapping<dim> &inverse_mapping,
    const std::vector<typename Triangulation<dim>::active_cell_iterator>
                     &candidates,
    const Point<dim> &x,
    const double      tolerance = reference_cell_tolerance);

  /**
   * locate_point() with the inverse map of a candidate given by
   * @p invert(cell, x) (an InverseMappingResult<dim>), for callers that
   * keep each cell's map (PointRelocation: BackgroundGrid's vertices and
   * extruded cells' maps, instead of reading the vertices through the
   * triangulation for every candidate).
   */
  template <int dim, typename Invert>
  PointLocation<dim>
  locate_point_by(
    const Invert &invert,
    const std::vector<typename Triangulation<dim>::active_cell_iterator>
                     &candidates,
    const Point<dim> &x,
    const double      tolerance = reference_cell_tolerance)
  {
    constexpr double   interior_margin = 1e-8;
    PointLocation<dim> location;
    for (const auto &cell : candidates)
      {
        const InverseMappingResult<dim> result = invert(cell, x);
        if (!result.success || !inside_unit_cell(result.xi, tolerance))
          continue;
        if (!location.found ||
            cell->active_cell_index() < location.cell->active_cell_index())
          {
            location.cell  = cell;
            location.xi    = result.xi;
            location.found = true;
          }
        bool interior = true;
        for (unsigned int d = 0; d < dim; ++d)
          interior = interior && result.xi[d] > interior_margin &&
                     result.xi[d] < 1. - interior_margin;
        if (interior)
          return location;
      }
    return location;
  }
} // namespace MPM

#endif
