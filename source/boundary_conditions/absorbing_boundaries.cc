#include <mpm/boundary_conditions/absorbing_boundaries.h>
#include <mpm/boundary_conditions/boundary_face_areas.h>

#include <algorithm>
#include <map>

namespace MPM
{
  template <int dim>
  void
  AbsorbingBoundaries<dim>::setup(const BackgroundGrid<dim>            &grid,
                                  const std::vector<BoundarySpec<dim>> &specs,
                                  const NodalVector                    &layout,
                                  const PeriodicNodeGroups *periodic_nodes)
  {
    nodes.clear();
    // The absorbing boundary that covers the mesh boundary id @p id, or
    // nullptr.
    const auto spec_of =
      [&specs](const types::boundary_id id) -> const BoundarySpec<dim> * {
      for (const auto &s : specs)
        if (s.type == BoundaryType::absorbing &&
            std::find(s.ids.begin(), s.ids.end(), id) != s.ids.end())
          return &s;
      return nullptr;
    };
    has_absorbing = std::any_of(specs.begin(), specs.end(), [](const auto &s) {
      return s.type == BoundaryType::absorbing;
    });
    if (!has_absorbing)
      return;

    // The dashpot matrices, column by column: column c of C_i at the
    // entries of node i's velocity components.
    std::array<NodalVector, dim> column;
    for (auto &v : column)
      {
        v.reinit(layout);
        v = 0;
      }
    for_each_boundary_face(
      grid,
      [&](const types::boundary_id id) { return spec_of(id) != nullptr; },
      update_values | update_JxW_values | update_normal_vectors,
      [&](const auto              &cell,
          const unsigned int       f,
          const types::boundary_id id,
          const FEFaceValues<dim> &face_values) {
        const BoundarySpec<dim> &spec = *spec_of(id);
        for (unsigned int v = 0; v < cell->face(f)->n_vertices(); ++v)
          {
            const unsigned int cell_vertex =
              GeometryInfo<dim>::face_to_cell_vertices(f, v);
            const unsigned int i = vertex_shape_function(grid, cell_vertex);
            Tensor<2, dim>     dashpot;
            for (unsigned int q = 0; q < face_values.n_quadrature_points; ++q)
              {
                const Tensor<1, dim> n = face_values.normal_vector(q);
                const double         w =
                  face_values.shape_value(i, q) * face_values.JxW(q);
                dashpot +=
                  w *
                  (spec.tangential_impedance * unit_symmetric_tensor<dim>() +
                   (spec.normal_impedance - spec.tangential_impedance) *
                     outer_product(n, n));
              }
            for (unsigned int r = 0; r < dim; ++r)
              for (unsigned int c = 0; c < dim; ++c)
                column[c](cell->vertex_dof_index(cell_vertex, r)) +=
                  dashpot[r][c];
          }
      });
    for (auto &v : column)
      {
        v.compress(VectorOperation::add);
        v.update_ghost_values();
        if (periodic_nodes != nullptr)
          periodic_nodes->sum(v);
      }

    // The nodes of the absorbing faces this rank sees (owned and ghost
    // cells: the nodal update runs on ghost nodes too), in the order of
    // their local entries.
    const auto                  &partitioner = *layout.get_partitioner();
    std::map<unsigned int, Node> node_at;
    for (const auto &cell : grid.dof_handler.active_cell_iterators())
      {
        if (cell->is_artificial())
          continue;
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              spec_of(cell->face(f)->boundary_id()) != nullptr)
            for (unsigned int v = 0; v < cell->face(f)->n_vertices(); ++v)
              {
                const unsigned int cell_vertex =
                  GeometryInfo<dim>::face_to_cell_vertices(f, v);
                Node node;
                for (unsigned int c = 0; c < dim; ++c)
                  node.local_dofs[c] = partitioner.global_to_local(
                    cell->vertex_dof_index(cell_vertex, c));
                for (unsigned int r = 0; r < dim; ++r)
                  for (unsigned int c = 0; c < dim; ++c)
                    node.dashpot[r][c] =
                      column[c].local_element(node.local_dofs[r]);
                node_at.emplace(node.local_dofs[0], node);
              }
      }
    for (const auto &[entry, node] : node_at)
      nodes.push_back(node);
  }


  template <int dim>
  void
  AbsorbingBoundaries<dim>::apply(const NodalVector &mass,
                                  const NodalVector &velocity,
                                  NodalVector       &acceleration,
                                  const double       dt) const
  {
    for (const Node &node : nodes)
      {
        const double m = mass.local_element(node.local_dofs[0]);
        if (!(m > 0))
          continue;
        Tensor<1, dim> u, v;
        for (unsigned int c = 0; c < dim; ++c)
          {
            u[c] = velocity.local_element(node.local_dofs[c]);
            v[c] = u[c] + dt * acceleration.local_element(node.local_dofs[c]);
          }
        // (m I + dt C) v_new = m (u + dt a).
        const Tensor<2, dim> system =
          unit_symmetric_tensor<dim>() + (dt / m) * node.dashpot;
        v = invert(system) * v;
        for (unsigned int c = 0; c < dim; ++c)
          acceleration.local_element(node.local_dofs[c]) = (v[c] - u[c]) / dt;
      }
  }


  template class AbsorbingBoundaries<2>;
  template class AbsorbingBoundaries<3>;
} // namespace MPM
