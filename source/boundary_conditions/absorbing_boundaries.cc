#include <mpm/base/function_input.h>
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
    input_velocities.clear();
    // R, column by column: R e_c.
    for (unsigned int c = 0; c < dim; ++c)
      {
        Tensor<1, dim> e;
        e[c]                        = 1;
        const Tensor<1, dim> column = grid.to_mesh_frame(e);
        for (unsigned int r = 0; r < dim; ++r)
          rotation[r][c] = column[r];
      }
    // The boundary that covers the mesh boundary id @p id (the first
    // naming it), if it is absorbing.
    const auto absorbing_spec_of = [&specs](const types::boundary_id id) {
      for (unsigned int s = 0; s < specs.size(); ++s)
        if (std::find(specs[s].ids.begin(), specs[s].ids.end(), id) !=
            specs[s].ids.end())
          return specs[s].type == BoundaryType::absorbing ?
                   s :
                   numbers::invalid_unsigned_int;
      return numbers::invalid_unsigned_int;
    };
    const bool has_absorbing =
      std::any_of(specs.begin(), specs.end(), [](const auto &s) {
        return s.type == BoundaryType::absorbing;
      });
    if (!has_absorbing)
      return;

    // The nodes of the absorbing faces this rank sees (owned and ghost
    // cells: the nodal update runs on ghost nodes too), by their first
    // local entry.
    const auto                  &partitioner = *layout.get_partitioner();
    std::map<unsigned int, Node> node_at;
    for (const auto &cell : grid.dof_handler.active_cell_iterators())
      {
        if (cell->is_artificial())
          continue;
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              absorbing_spec_of(cell->face(f)->boundary_id()) !=
                numbers::invalid_unsigned_int)
            for (unsigned int v = 0; v < cell->face(f)->n_vertices(); ++v)
              {
                const unsigned int cell_vertex =
                  GeometryInfo<dim>::face_to_cell_vertices(f, v);
                Node node;
                for (unsigned int c = 0; c < dim; ++c)
                  node.local_dofs[c] = partitioner.global_to_local(
                    cell->vertex_dof_index(cell_vertex, c));
                node_at.emplace(node.local_dofs[0], node);
              }
      }

    // Each absorbing boundary's dashpot matrices, column by column
    // (column c of C_i at the entries of node i's velocity components),
    // summed over ranks and periodic copies; added to its nodes', and
    // kept apart where the boundary brings an input motion.
    for (unsigned int s = 0; s < specs.size(); ++s)
      {
        const BoundarySpec<dim> &spec = specs[s];
        if (spec.type != BoundaryType::absorbing)
          continue;
        std::array<NodalVector, dim> column;
        for (auto &v : column)
          {
            v.reinit(layout);
            v = 0;
          }
        for_each_boundary_face(
          grid,
          [&](const types::boundary_id id) {
            return absorbing_spec_of(id) == s;
          },
          update_values | update_JxW_values | update_normal_vectors,
          [&](const auto        &cell,
              const unsigned int f,
              const types::boundary_id,
              const FEFaceValues<dim> &face_values) {
            for (unsigned int v = 0; v < cell->face(f)->n_vertices(); ++v)
              {
                const unsigned int cell_vertex =
                  GeometryInfo<dim>::face_to_cell_vertices(f, v);
                const unsigned int i = vertex_shape_function(grid, cell_vertex);
                Tensor<2, dim>     dashpot;
                for (unsigned int q = 0; q < face_values.n_quadrature_points;
                     ++q)
                  {
                    const Tensor<1, dim> n = face_values.normal_vector(q);
                    const double         w =
                      face_values.shape_value(i, q) * face_values.JxW(q);
                    dashpot +=
                      w * (spec.tangential_impedance *
                             unit_symmetric_tensor<dim>() +
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
        unsigned int function = numbers::invalid_unsigned_int;
        if (!spec.input_velocity.empty())
          {
            auto velocity = std::make_unique<FunctionParser<1>>(dim);
            parse_function_or_throw(
              "Boundary conditions/" + spec.name +
                "/Absorbing input velocity = '" + spec.input_velocity + "'",
              [&]() {
                velocity->initialize("t",
                                     spec.input_velocity,
                                     std::map<std::string, double>(),
                                     false);
                velocity->value(Point<1>());
              });
            function = input_velocities.size();
            input_velocities.push_back(std::move(velocity));
          }
        for (auto &[entry, node] : node_at)
          {
            Tensor<2, dim> dashpot;
            for (unsigned int r = 0; r < dim; ++r)
              for (unsigned int c = 0; c < dim; ++c)
                dashpot[r][c] = column[c].local_element(node.local_dofs[r]);
            node.dashpot += dashpot;
            if (function != numbers::invalid_unsigned_int && dashpot.norm() > 0)
              node.inputs.push_back({function, dashpot});
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
                                  const double       dt,
                                  const double       time) const
  {
    // The input motions at this time, in the mesh's frame.
    std::vector<Tensor<1, dim>> input(input_velocities.size());
    for (unsigned int k = 0; k < input.size(); ++k)
      {
        Vector<double> value(dim);
        input_velocities[k]->vector_value(Point<1>(time), value);
        for (unsigned int c = 0; c < dim; ++c)
          input[k][c] = value[c];
        input[k] = rotation * input[k];
      }
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
        // (m I + dt C) v_new = m (u + dt a) + dt sum C_in 2 v_in.
        for (const Input &in : node.inputs)
          v += (2 * dt / m) * (in.dashpot * input[in.function]);
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
