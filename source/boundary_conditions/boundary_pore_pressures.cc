#include <mpm/base/function_input.h>
#include <mpm/boundary_conditions/boundary_face_areas.h>
#include <mpm/boundary_conditions/boundary_pore_pressures.h>

#include <algorithm>
#include <regex>

namespace MPM
{
  namespace
  {
    /// Whether the function expression @p expression names the time t (as
    /// a name of its own, not inside another name or a number's exponent).
    bool
    names_time(const std::string &expression)
    {
      static const std::regex name("[A-Za-z_][A-Za-z0-9_]*");
      for (auto it = std::sregex_iterator(expression.begin(),
                                          expression.end(),
                                          name);
           it != std::sregex_iterator();
           ++it)
        {
          const auto start = it->position();
          // A name that follows a digit or '.' is part of a number (1e5).
          const bool in_number =
            start > 0 && (std::isdigit(expression[start - 1]) ||
                          expression[start - 1] == '.');
          if (!in_number && it->str() == "t")
            return true;
        }
      return false;
    }
  } // namespace


  template <int dim>
  void
  BoundaryPorePressures<dim>::setup(
    const BackgroundGrid<dim>            &grid,
    const std::vector<BoundarySpec<dim>> &specs,
    const NodalVector                    &layout,
    const PeriodicNodeGroups             *periodic_nodes)
  {
    functions.clear();
    face_points.clear();
    time_dependent = false;
    periodic       = periodic_nodes;
    // The function of each boundary with a pressure (spec_function: its
    // index, or none).
    std::vector<unsigned int> spec_function(specs.size(),
                                            numbers::invalid_unsigned_int);
    for (unsigned int s = 0; s < specs.size(); ++s)
      if (!specs[s].pore_pressure.empty())
        {
          const std::string &expression = specs[s].pore_pressure;
          auto function = std::make_unique<FunctionParser<dim>>(1);
          parse_function_or_throw(
            "Boundary conditions/" + specs[s].name + "/Pore pressure = '" +
              expression + "'",
            [&]() {
              function->initialize(dim == 2 ? "x,y,t" : "x,y,z,t",
                                   expression,
                                   {{"_pi", numbers::PI}, {"_e", numbers::E}},
                                   true);
              function->value(Point<dim>());
            });
          time_dependent = time_dependent || names_time(expression);
          spec_function[s] = functions.size();
          functions.push_back(std::move(function));
        }
    if (functions.empty())
      {
        nodal_force.reinit(0);
        return;
      }
    // The function of a boundary id (the first boundary naming it).
    const auto function_of = [&](const types::boundary_id id) {
      for (unsigned int s = 0; s < specs.size(); ++s)
        if (spec_function[s] != numbers::invalid_unsigned_int &&
            std::find(specs[s].ids.begin(), specs[s].ids.end(), id) !=
              specs[s].ids.end())
          return spec_function[s];
      return numbers::invalid_unsigned_int;
    };
    for_each_boundary_face(
      grid,
      [&](const types::boundary_id id) {
        return function_of(id) != numbers::invalid_unsigned_int;
      },
      update_values | update_JxW_values | update_quadrature_points |
        update_normal_vectors,
      [&](const auto               &cell,
          const unsigned int        f,
          const types::boundary_id  id,
          const FEFaceValues<dim>  &face_values) {
        for (unsigned int q = 0; q < face_values.n_quadrature_points; ++q)
          {
            FacePoint point;
            point.boundary = function_of(id);
            point.x = grid.to_scene_frame(face_values.quadrature_point(q));
            for (unsigned int v = 0; v < vertices_per_face; ++v)
              {
                const unsigned int cell_vertex =
                  GeometryInfo<dim>::face_to_cell_vertices(f, v);
                for (unsigned int c = 0; c < dim; ++c)
                  point.dofs[v][c] = cell->vertex_dof_index(cell_vertex, c);
                point.weight[v] =
                  face_values.shape_value(
                    vertex_shape_function(grid, cell_vertex), q) *
                  face_values.JxW(q) * face_values.normal_vector(q);
              }
            face_points.push_back(point);
          }
      });
    nodal_force.reinit(layout);
    assemble(0);
  }


  template <int dim>
  void
  BoundaryPorePressures<dim>::assemble(const double time)
  {
    for (auto &function : functions)
      function->set_time(time);
    nodal_force = 0;
    for (const FacePoint &point : face_points)
      {
        // Once per quadrature point.
        const double p = functions[point.boundary]->value(point.x);
        for (unsigned int v = 0; v < vertices_per_face; ++v)
          for (unsigned int c = 0; c < dim; ++c)
            nodal_force(point.dofs[v][c]) -= p * point.weight[v][c];
      }
    nodal_force.compress(VectorOperation::add);
    nodal_force.update_ghost_values();
    if (periodic != nullptr)
      periodic->sum(nodal_force);
    assembled_time = time;
  }


  template <int dim>
  const NodalVector *
  BoundaryPorePressures<dim>::forces_at(const double time)
  {
    if (functions.empty())
      return nullptr;
    if (time_dependent && time != assembled_time)
      assemble(time);
    return &nodal_force;
  }


  template class BoundaryPorePressures<2>;
  template class BoundaryPorePressures<3>;
} // namespace MPM
