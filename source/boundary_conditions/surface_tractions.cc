#include <mpm/boundary_conditions/boundary_face_areas.h>
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
      return carries_traction(s.type) && s.traction.norm() > 0;
    });
    if (!has_load)
      {
        nodal_force.reinit(0);
        return;
      }
    nodal_force.reinit(layout);
    nodal_force = 0;
    const auto loads = [&specs](const types::boundary_id id) {
      return std::any_of(specs.begin(), specs.end(), [id](const auto &s) {
        return carries_traction(s.type) &&
               std::find(s.ids.begin(), s.ids.end(), id) != s.ids.end();
      });
    };
    for_each_boundary_face_node_area(
      grid,
      loads,
      [&](const auto        &cell,
          const unsigned int cell_vertex,
          const types::boundary_id id,
          const double       area) {
        for (const auto &spec : specs)
          if (carries_traction(spec.type) &&
              std::find(spec.ids.begin(), spec.ids.end(), id) != spec.ids.end())
            {
              const Tensor<1, dim> t = grid.to_mesh_frame(spec.traction);
              for (unsigned int c = 0; c < dim; ++c)
                nodal_force(cell->vertex_dof_index(cell_vertex, c)) +=
                  area * t[c];
            }
      });
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
