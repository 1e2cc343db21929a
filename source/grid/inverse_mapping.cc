#include <deal.II/base/tensor.h>

#include <deal.II/fe/mapping_q1.h>

#include <mpm/base/input_error.h>
#include <mpm/grid/bilinear_cell_map.h>
#include <mpm/grid/inverse_mapping.h>
#include <mpm/grid/newton_inverse_map.h>
#include <mpm/grid/extruded_cell_map.h>

#include <cmath>
#include <limits>

namespace MPM
{
  std::string
  inverse_mapping_type_selection()
  {
    return "closed form|newton|deal.II";
  }


  InverseMappingType
  parse_inverse_mapping_type(const std::string &name)
  {
    if (name == "closed form")
      return InverseMappingType::closed_form;
    if (name == "newton")
      return InverseMappingType::newton;
    if (name == "deal.II")
      return InverseMappingType::dealii;
    throw InputError("Unknown inverse mapping '" + name + "'; choose one of " +
                     inverse_mapping_type_selection() + ".");
  }


  std::string
  to_string(const InverseMappingType type)
  {
    switch (type)
      {
        case InverseMappingType::closed_form:
          return "closed form";
        case InverseMappingType::newton:
          return "newton";
        case InverseMappingType::dealii:
          return "deal.II";
      }
    return "";
  }


  namespace
  {
    /**
     * Value (relative to vertex 0) and Jacobian of the multilinear map at
     * @p xi, for vertices given relative to vertex 0. Working relative to
     * vertex 0 keeps the round-off proportional to the cell size rather
     * than to the distance of the cell from the origin.
     */
    template <int dim>
    inline void
    evaluate_map(
      const std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell>
                       &relative_vertices,
      const Point<dim> &xi,
      Tensor<1, dim>   &value,
      Tensor<2, dim>   &jacobian)
    {
      value    = Tensor<1, dim>();
      jacobian = Tensor<2, dim>();
      for (unsigned int i = 1; i < GeometryInfo<dim>::vertices_per_cell; ++i)
        {
          // Vertex i sits at reference coordinate d = bit d of i.
          double factor[dim], dfactor[dim];
          for (unsigned int d = 0; d < dim; ++d)
            {
              const bool upper = (i >> d) & 1;
              factor[d]        = upper ? xi[d] : 1. - xi[d];
              dfactor[d]       = upper ? 1. : -1.;
            }
          double n = 1;
          for (unsigned int d = 0; d < dim; ++d)
            n *= factor[d];
          value += n * relative_vertices[i];
          for (unsigned int d = 0; d < dim; ++d)
            {
              double g = dfactor[d];
              for (unsigned int e = 0; e < dim; ++e)
                if (e != d)
                  g *= factor[e];
              for (unsigned int a = 0; a < dim; ++a)
                jacobian[a][d] += relative_vertices[i][a] * g;
            }
        }
    }

  } // namespace


  template <int dim>
  Point<dim>
  map_unit_to_real(
    const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>
                     &vertices,
    const Point<dim> &xi)
  {
    std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell> relative;
    for (unsigned int i = 0; i < GeometryInfo<dim>::vertices_per_cell; ++i)
      relative[i] = vertices[i] - vertices[0];
    Tensor<1, dim> value;
    Tensor<2, dim> jacobian;
    evaluate_map<dim>(relative, xi, value, jacobian);
    return vertices[0] + value;
  }


  InverseMappingResult<2>
  inverse_map_closed_form(const std::array<Point<2>, 4> &vertices,
                          const Point<2>                &x,
                          const bool                     newton_polish)
  {
    return BilinearCellMap(vertices).inverse(x, newton_polish);
  }


  InverseMappingResult<3>
  inverse_map_closed_form(const std::array<Point<3>, 8> &vertices,
                          const Point<3>                &x)
  {
    // Any other cell as with 'newton' (the same numbers).
    const ExtrudedCellMap map(vertices);
    if (map.is_extruded())
      {
        const InverseMappingResult<3> result = map.inverse(x);
        if (result.success)
          return result;
      }
    return inverse_map_newton<3>(vertices, x);
  }


  template <int dim>
  InverseMappingResult<dim>
  inverse_map_newton(
    const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>
                      &vertices,
    const Point<dim>  &x,
    const double       step_tolerance,
    const unsigned int max_iterations)
  {
    std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell> relative;
    for (unsigned int i = 0; i < GeometryInfo<dim>::vertices_per_cell; ++i)
      relative[i] = vertices[i] - vertices[0];
    // From the affine map with the value and Jacobian of the cell's map at
    // the centre (exact for parallelograms).
    return internal::newton_inverse_map<dim>(
      [&relative](const Point<dim>     &xi,
                  Tensor<1, dim>       &value,
                  Tensor<2, dim>       &jacobian) {
        evaluate_map<dim>(relative, xi, value, jacobian);
      },
      x - vertices[0],
      false,
      Point<dim>(),
      step_tolerance,
      max_iterations);
  }


  template <int dim>
  InverseMappingResult<dim>
  inverse_map_dealii(const Mapping<dim>                               &mapping,
                     const typename Triangulation<dim>::cell_iterator &cell,
                     const Point<dim>                                 &x)
  {
    InverseMappingResult<dim> result;
    try
      {
        result.xi      = mapping.transform_real_to_unit_cell(cell, x);
        result.success = true;
      }
    catch (const typename Mapping<dim>::ExcTransformationFailed &)
      {
        for (unsigned int d = 0; d < dim; ++d)
          result.xi[d] = std::numeric_limits<double>::quiet_NaN();
      }
    return result;
  }


  template <int dim>
  InverseMapping<dim>::InverseMapping(const InverseMappingType type,
                                      const Mapping<dim>      &mapping)
    : mapping_type(type)
    , mapping(&mapping)
  {}


  template <int dim>
  InverseMappingResult<dim>
  InverseMapping<dim>::transform_real_to_unit_cell(
    const typename Triangulation<dim>::cell_iterator &cell,
    const Point<dim>                                 &x) const
  {
    if (mapping_type == InverseMappingType::dealii)
      return inverse_map_dealii<dim>(*mapping, cell, x);
    std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell> vertices;
    for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell; ++v)
      vertices[v] = cell->vertex(v);
    return transform_real_to_unit_cell(vertices, x);
  }


  template <int dim>
  InverseMappingResult<dim>
  InverseMapping<dim>::transform_real_to_unit_cell(
    const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>
                     &vertices,
    const Point<dim> &x) const
  {
    switch (mapping_type)
      {
        case InverseMappingType::closed_form:
          return inverse_map_closed_form(vertices, x);
        case InverseMappingType::newton:
          return inverse_map_newton<dim>(vertices, x);
        case InverseMappingType::dealii:
          break;
      }
    Assert(false,
           ExcMessage("This inverse mapping needs a cell, not its vertices."));
    return InverseMappingResult<dim>();
  }


  template Point<2>
  map_unit_to_real(const std::array<Point<2>, 4> &, const Point<2> &);
  template Point<3>
  map_unit_to_real(const std::array<Point<3>, 8> &, const Point<3> &);
  template InverseMappingResult<2>
  inverse_map_newton(const std::array<Point<2>, 4> &,
                     const Point<2> &,
                     const double,
                     const unsigned int);
  template InverseMappingResult<3>
  inverse_map_newton(const std::array<Point<3>, 8> &,
                     const Point<3> &,
                     const double,
                     const unsigned int);
  template InverseMappingResult<2>
  inverse_map_dealii(const Mapping<2> &,
                     const Triangulation<2>::cell_iterator &,
                     const Point<2> &);
  template InverseMappingResult<3>
  inverse_map_dealii(const Mapping<3> &,
                     const Triangulation<3>::cell_iterator &,
                     const Point<3> &);
  template class InverseMapping<2>;
  template class InverseMapping<3>;
} // namespace MPM
