#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <mpm/boundary_conditions/node_frames.h>

#include <algorithm>
#include <cmath>

namespace MPM
{
  namespace
  {
    /**
     * Tangent of the 2D local frame: the outward normal turned by +90
     * degrees, so that on a bed with outward normal (0, -1) the tangent is
     * +x.
     */
    template <int dim>
    Tensor<1, dim>
    tangent_2d(const Tensor<1, dim> &n)
    {
      Tensor<1, dim> t;
      t[0] = -n[1];
      t[1] = n[0];
      return t;
    }

    /// Normals closer than this angle are merged at a corner node.
    const double merge_cosine = std::cos(10. * M_PI / 180.);


    /**
     * For the boundaries with a rate-dependent basal law: each node's
     * share of the wall area, int_wall N_i dA (one-point rule per face,
     * as the normals), in @p area[s], and of the mesh volume,
     * int N_i dV over every cell at the node, in @p volume; summed over
     * ranks.
     */
    template <int dim>
    void
    compute_wall_shares(const BackgroundGrid<dim>            &grid,
                        const std::vector<BoundarySpec<dim>> &specs,
                        const PeriodicNodeGroups             *periodic_nodes,
                        std::vector<NodalVector>             &area,
                        NodalVector                          &volume)
    {
      FEFaceValues<dim> face_values(grid.mapping,
                                    grid.fe,
                                    QGauss<dim - 1>(1),
                                    update_JxW_values);
      FEValues<dim>     cell_values(grid.mapping,
                                grid.fe,
                                QGauss<dim>(2),
                                update_values | update_JxW_values);
      for (const auto &cell : grid.dof_handler.active_cell_iterators())
        {
          if (!cell->is_locally_owned())
            continue;
          cell_values.reinit(cell);
          for (const unsigned int v : cell->vertex_indices())
            {
              const unsigned int i = grid.fe.component_to_system_index(0, v);
              double             integral = 0;
              for (const unsigned int q :
                   cell_values.quadrature_point_indices())
                integral += cell_values.shape_value(i, q) * cell_values.JxW(q);
              volume(cell->vertex_dof_index(v, 0)) += integral;
            }
          for (const unsigned int f : cell->face_indices())
            {
              if (!cell->face(f)->at_boundary())
                continue;
              const types::boundary_id id = cell->face(f)->boundary_id();
              for (unsigned int s = 0; s < specs.size(); ++s)
                if (area[s].size() > 0 &&
                    std::find(specs[s].ids.begin(), specs[s].ids.end(), id) !=
                      specs[s].ids.end())
                  {
                    face_values.reinit(cell, f);
                    const auto   face  = cell->face(f);
                    const double share = face_values.JxW(0) / face->n_vertices();
                    for (unsigned int v = 0; v < face->n_vertices(); ++v)
                      area[s](face->vertex_dof_index(v, 0)) += share;
                  }
            }
        }
      for (auto &a : area)
        if (a.size() > 0)
          {
            a.compress(VectorOperation::add);
            a.update_ghost_values();
            if (periodic_nodes != nullptr)
              periodic_nodes->sum(a);
          }
      volume.compress(VectorOperation::add);
      volume.update_ghost_values();
      if (periodic_nodes != nullptr)
        periodic_nodes->sum(volume);
    }
  } // namespace


  template <int dim>
  std::vector<NodeFrame<dim>>
  compute_node_frames(const BackgroundGrid<dim>            &grid,
                      const NodalVector                    &layout,
                      const std::vector<BoundarySpec<dim>> &specs,
                      const double                          gravity,
                      const PeriodicNodeGroups             *periodic_nodes)
  {
    std::vector<NodeFrame<dim>> frames;
    if (specs.empty())
      return frames;

    // 1. For each boundary: the face-size weighted sum of the outward
    //    normals of its faces at each node, and the nodes it touches,
    //    summed over ranks so that nodes on partition boundaries agree.
    std::vector<NodalVector> normal_sum(specs.size(), layout);
    std::vector<NodalVector> touches(specs.size(), layout);
    for (auto &v : normal_sum)
      v = 0;
    for (auto &v : touches)
      v = 0;

    FEFaceValues<dim> fe_face_values(grid.mapping,
                                     grid.fe,
                                     QGauss<dim - 1>(1),
                                     update_normal_vectors | update_JxW_values);
    for (const auto &cell : grid.dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        for (const unsigned int f : cell->face_indices())
          {
            if (!cell->face(f)->at_boundary())
              continue;
            const types::boundary_id id = cell->face(f)->boundary_id();
            bool                     reinitialized = false;
            for (unsigned int s = 0; s < specs.size(); ++s)
              {
                if (std::find(specs[s].ids.begin(), specs[s].ids.end(), id) ==
                    specs[s].ids.end())
                  continue;
                if (!reinitialized)
                  fe_face_values.reinit(cell, f);
                reinitialized           = true;
                const Tensor<1, dim> nA = fe_face_values.normal_vector(0) *
                                          fe_face_values.JxW(0);
                for (unsigned int v = 0; v < cell->face(f)->n_vertices(); ++v)
                  for (unsigned int c = 0; c < dim; ++c)
                    {
                      const auto dof = cell->face(f)->vertex_dof_index(v, c);
                      normal_sum[s](dof) += nA[c];
                      touches[s](dof) += 1;
                    }
              }
          }
      }
    for (unsigned int s = 0; s < specs.size(); ++s)
      {
        normal_sum[s].compress(VectorOperation::add);
        normal_sum[s].update_ghost_values();
        touches[s].compress(VectorOperation::add);
        touches[s].update_ghost_values();
        // A periodic node's copies see the faces of both sides.
        if (periodic_nodes != nullptr)
          {
            periodic_nodes->sum(normal_sum[s]);
            periodic_nodes->sum(touches[s]);
          }
      }

    // The wall shares of the nodes of rate-dependent basal laws.
    std::vector<NodalVector> wall_area(specs.size());
    NodalVector              cell_volume;
    bool                     rate_dependent = false;
    for (unsigned int s = 0; s < specs.size(); ++s)
      if (specs[s].type == BoundaryType::friction &&
          specs[s].law->rate_dependent())
        {
          wall_area[s].reinit(layout);
          wall_area[s] = 0;
          rate_dependent = true;
        }
    if (rate_dependent)
      {
        cell_volume.reinit(layout);
        cell_volume = 0;
        compute_wall_shares(grid, specs, periodic_nodes, wall_area, cell_volume);
      }
    const auto geometry_of = [&](const std::vector<unsigned int> &walls,
                                 const unsigned int               local0) {
      WallNodeGeometry g;
      if (!rate_dependent)
        return g;
      double area = 0;
      for (const unsigned int s : walls)
        if (wall_area[s].size() > 0)
          area += wall_area[s].local_element(local0);
      const double volume = cell_volume.local_element(local0);
      g.area_per_volume   = volume > 0 ? area / volume : 0.;
      g.gravity           = gravity;
      return g;
    };

    // 2. The constraint normals of each locally relevant node, by the
    //    corner rule.
    std::vector<bool> visited(layout.locally_owned_size() +
                                layout.get_partitioner()->n_ghost_indices(),
                              false);

    for (const auto &cell : grid.dof_handler.active_cell_iterators())
      {
        if (cell->is_artificial())
          continue;
        for (const unsigned int v : cell->vertex_indices())
          {
            NodeFrame<dim> nc;
            nc.location = cell->vertex(v);
            for (unsigned int c = 0; c < dim; ++c)
              nc.dofs[c] = cell->vertex_dof_index(v, c);
            const unsigned int local0 =
              layout.get_partitioner()->global_to_local(nc.dofs[0]);
            if (visited[local0])
              continue;
            visited[local0] = true;

            bool                        fixed = false, prescribed = false;
            Tensor<1, dim>              prescribed_velocity;
            std::vector<Tensor<1, dim>> cluster_sum;
            // Per cluster of merged normals: its frictional boundary of
            // largest friction coefficient (nullptr: none), and the
            // boundaries merged into it.
            std::vector<const BasalLaw<dim> *>     cluster_law;
            std::vector<std::vector<unsigned int>> cluster_walls;
            for (unsigned int s = 0; s < specs.size(); ++s)
              {
                if (touches[s].local_element(local0) == 0 ||
                    !is_wall(specs[s].type))
                  continue;
                Tensor<1, dim> weighted;
                for (unsigned int c = 0; c < dim; ++c)
                  weighted[c] = normal_sum[s].local_element(
                    layout.get_partitioner()->global_to_local(nc.dofs[c]));
                if (!specs[s].normal_from_mesh)
                  weighted = grid.to_mesh_frame(specs[s].given_normal) *
                             std::max(weighted.norm(), 1e-300);
                const BasalLaw<dim> *law =
                  specs[s].type == BoundaryType::friction ? specs[s].law.get() :
                                                            nullptr;
                if (specs[s].type == BoundaryType::fixed)
                  fixed = true;
                else if (weighted.norm() == 0)
                  fixed = true; // opposite faces cancel: a knife edge
                else if (specs[s].type == BoundaryType::velocity)
                  {
                    const Tensor<1, dim> n = weighted / weighted.norm();
                    prescribed          = true;
                    prescribed_velocity = specs[s].local_velocity[0] * n +
                                          specs[s].local_velocity[1] *
                                            tangent_2d(n);
                  }
                else
                  {
                    const Tensor<1, dim> n = weighted / weighted.norm();
                    bool                 merged = false;
                    for (unsigned int k = 0; k < cluster_sum.size(); ++k)
                      if (std::abs(n * cluster_sum[k]) >
                          merge_cosine * cluster_sum[k].norm())
                        {
                          cluster_sum[k] += weighted;
                          cluster_walls[k].push_back(s);
                          if (law != nullptr &&
                              (cluster_law[k] == nullptr ||
                               law->friction_coefficient() >
                                 cluster_law[k]->friction_coefficient()))
                            cluster_law[k] = law;
                          merged = true;
                          break;
                        }
                    if (!merged)
                      {
                        cluster_sum.push_back(weighted);
                        cluster_law.push_back(law);
                        cluster_walls.push_back({s});
                      }
                  }
              }

            if (!fixed && !prescribed && cluster_sum.size() >= dim)
              fixed = true;
            if (fixed || prescribed)
              {
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    Tensor<1, dim> e;
                    e[c] = 1;
                    nc.normals.push_back(e);
                    nc.values.push_back(fixed ? 0. : prescribed_velocity[c]);
                  }
              }
            else if (cluster_sum.size() > 0)
              {
                for (const auto &n : cluster_sum)
                  {
                    nc.normals.push_back(n / n.norm());
                    nc.values.push_back(0.);
                  }
                if (cluster_sum.size() == 1 && cluster_law[0] != nullptr)
                  {
                    nc.frictional = true;
                    nc.law        = cluster_law[0];
                    nc.geometry   = geometry_of(cluster_walls[0], local0);
                  }
                else if (cluster_sum.size() == 2 &&
                         (cluster_law[0] != nullptr ||
                          cluster_law[1] != nullptr))
                  {
                    // A 3D edge (2D nodes with two normals are fixed).
                    nc.edge_friction = true;
                    for (unsigned int j = 0; j < 2; ++j)
                      {
                        nc.edge_normals[j] =
                          cluster_sum[j] / cluster_sum[j].norm();
                        nc.edge_laws[j] = cluster_law[j];
                        nc.edge_geometry[j] =
                          geometry_of(cluster_walls[j], local0);
                      }
                  }
              }
            if (!nc.normals.empty())
              frames.push_back(nc);
          }
      }
    return frames;
  }


  template std::vector<NodeFrame<2>>
  compute_node_frames(const BackgroundGrid<2> &,
                      const NodalVector &,
                      const std::vector<BoundarySpec<2>> &,
                      const double,
                      const PeriodicNodeGroups *);
  template std::vector<NodeFrame<3>>
  compute_node_frames(const BackgroundGrid<3> &,
                      const NodalVector &,
                      const std::vector<BoundarySpec<3>> &,
                      const double,
                      const PeriodicNodeGroups *);
} // namespace MPM
