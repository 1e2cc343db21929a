#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <mpm/boundary_conditions/surface_tractions.h>

#include <algorithm>

namespace MPM
{
  template <int dim>
  void
  SurfaceTractions<dim>::setup(const BackgroundGrid<dim>            &grid,
                               const std::vector<BoundarySpec<dim>> &specs,
                               const NodalVector                    &layout,
                               const PeriodicNodeGroups *periodic_nodes)
  {
    has_load = std::any_of(specs.begin(), specs.end(), [](const auto &s) {
      return s.type == BoundaryType::traction && s.traction.norm() > 0;
    });
    if (!has_load)
      {
        nodal_force.reinit(0);
        return;
      }
    nodal_force.reinit(layout);
    nodal_force = 0;
    FEFaceValues<dim> face_values(grid.mapping,
                                  grid.fe,
                                  QGauss<dim - 1>(2),
                                  update_values | update_JxW_values);
    for (const auto &cell : grid.dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        for (const unsigned int f : cell->face_indices())
          {
            if (!cell->face(f)->at_boundary())
              continue;
            const types::boundary_id id = cell->face(f)->boundary_id();
            for (const auto &spec : specs)
              {
                if (spec.type != BoundaryType::traction ||
                    std::find(spec.ids.begin(), spec.ids.end(), id) ==
                      spec.ids.end())
                  continue;
                face_values.reinit(cell, f);
                const Tensor<1, dim> t = grid.to_mesh_frame(spec.traction);
                for (unsigned int v = 0; v < cell->face(f)->n_vertices(); ++v)
                  {
                    // int_face N_v dA, with the shape function of the
                    // face's vertex v (component 0 of the FE system).
                    const unsigned int cell_vertex =
                      GeometryInfo<dim>::face_to_cell_vertices(f, v);
                    const unsigned int i =
                      grid.fe.component_to_system_index(0, cell_vertex);
                    double weight = 0;
                    for (unsigned int q = 0; q < face_values.n_quadrature_points;
                         ++q)
                      weight += face_values.shape_value(i, q) *
                                face_values.JxW(q);
                    for (unsigned int c = 0; c < dim; ++c)
                      nodal_force(cell->vertex_dof_index(cell_vertex, c)) +=
                        weight * t[c];
                  }
              }
          }
      }
    nodal_force.compress(VectorOperation::add);
    nodal_force.update_ghost_values();
    if (periodic_nodes != nullptr)
      periodic_nodes->sum(nodal_force);
  }


  template <int dim>
  void
  SurfaceTractions<dim>::add_to(const NodalVector               &mass,
                                const std::vector<unsigned int> &active_dofs,
                                NodalVector                     &force) const
  {
    if (!has_load)
      return;
    for (const unsigned int i : active_dofs)
      if (mass.local_element(i) > 0)
        force.local_element(i) += nodal_force.local_element(i);
  }


  template class SurfaceTractions<2>;
  template class SurfaceTractions<3>;
} // namespace MPM
