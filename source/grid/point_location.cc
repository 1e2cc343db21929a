#include <mpm/grid/point_location.h>

namespace MPM
{
  template <int dim>
  PointLocation<dim>
  locate_point(
    const InverseMapping<dim> &inverse_mapping,
    const std::vector<typename Triangulation<dim>::active_cell_iterator>
                     &candidates,
    const Point<dim> &x,
    const double      tolerance)
  {
    constexpr double   interior_margin = 1e-8;
    PointLocation<dim> location;
    for (const auto &cell : candidates)
      {
        const auto result =
          inverse_mapping.transform_real_to_unit_cell(cell, x);
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


  template PointLocation<2>
  locate_point(const InverseMapping<2> &,
               const std::vector<Triangulation<2>::active_cell_iterator> &,
               const Point<2> &,
               const double);
  template PointLocation<3>
  locate_point(const InverseMapping<3> &,
               const std::vector<Triangulation<3>::active_cell_iterator> &,
               const Point<3> &,
               const double);
} // namespace MPM
