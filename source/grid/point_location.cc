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
    return locate_point_by<dim>(
      [&](const typename Triangulation<dim>::active_cell_iterator &cell,
          const Point<dim>                                        &y) {
        return inverse_mapping.transform_real_to_unit_cell(cell, y);
      },
      candidates,
      x,
      tolerance);
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
