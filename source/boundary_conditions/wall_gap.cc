#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <mpm/boundary_conditions/wall_gap.h>

#include <map>
#include <set>

namespace MPM
{
  template <int dim>
  void
  WallGap<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    prm.declare_entry(
      "Wall contact",
      "velocity",
      Patterns::Selection("velocity|gap"),
      "When a node of a frictional wall holds the material: 'velocity' "
      "whenever the node moves into the wall, wherever the material is; "
      "'gap' only while, besides, the material around the node touches the "
      "wall (a point in the wall cells around the node whose domain ends "
      "within 'Contact gap tolerance' of the wall), so that material that "
      "has left the wall falls back onto it (doc/boundary_conditions.md, "
      "'Contact by gap': converges where 'velocity' lifts a decelerated "
      "block off the bed, but not yet shown better on the shipped scenes).");
    prm.declare_entry(
      "Contact gap tolerance",
      "0.1",
      Patterns::Double(0),
      "For Wall contact = gap: the largest gap between a point's domain and "
      "the wall, as a fraction of the domain's reach towards the wall, at "
      "which the point still touches the wall.");
    prm.leave_subsection();
  }


  template <int dim>
  void
  WallGap<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    by_gap    = prm.get("Wall contact") == "gap";
    tolerance = prm.get_double("Contact gap tolerance");
    prm.leave_subsection();
  }


  template <int dim>
  void
  WallGap<dim>::setup(const BackgroundGrid<dim>               &grid,
                      const std::vector<BoundarySpec<dim>>    &specs,
                      const NodalVector                       &layout,
                      const std::vector<ConstrainedNode<dim>> &nodes)
  {
    std::set<types::boundary_id> frictional_ids;
    for (const auto &s : specs)
      if (s.type == BoundaryType::friction)
        frictional_ids.insert(s.ids.begin(), s.ids.end());
    active = by_gap && !frictional_ids.empty();
    faces.clear();
    wall_nodes.clear();
    counts.reinit(layout);
    in_contact.assign(nodes.size(), 1);
    if (!active)
      return;
    std::map<unsigned int, unsigned int> wall_node_of_dof;
    for (unsigned int k = 0; k < nodes.size(); ++k)
      if (nodes[k].frictional)
        {
          wall_node_of_dof[nodes[k].local_dofs[0]] = wall_nodes.size();
          wall_nodes.push_back(
            {k, nodes[k].local_dofs[0], nodes[k].local_dofs[1]});
        }
    // Each wall face's plane: the mapping's point and outward normal at
    // the face's centre (as the node frames take them,
    // compute_node_frames()).
    FEFaceValues<dim> face_values(grid.mapping,
                                  grid.fe,
                                  QGauss<dim - 1>(1),
                                  update_quadrature_points |
                                    update_normal_vectors);
    const auto       &partitioner = *layout.get_partitioner();
    for (const auto &cell : grid.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              frictional_ids.count(cell->face(f)->boundary_id()))
            {
              face_values.reinit(cell, f);
              WallFace w;
              w.cell   = cell;
              w.centre = face_values.quadrature_point(0);
              w.normal = face_values.normal_vector(0);
              for (const unsigned int v : cell->face(f)->vertex_indices())
                {
                  const auto it =
                    wall_node_of_dof.find(partitioner.global_to_local(
                      cell->face(f)->vertex_dof_index(v, 0)));
                  if (it != wall_node_of_dof.end())
                    w.wall_nodes.push_back(it->second);
                }
              if (!w.wall_nodes.empty())
                faces.push_back(w);
            }
    active =
      Utilities::MPI::logical_or(!faces.empty(), layout.get_mpi_communicator());
  }


  template <int dim>
  void
  WallGap<dim>::update(const Particles::ParticleHandler<dim> &particles,
                       const Reach                           &reach)
  {
    if (!active)
      return;
    counts = 0;
    for (const auto &w : faces)
      {
        unsigned int n_near = 0, n_touching = 0;
        for (const auto &point : particles.particles_in_cell(w.cell))
          {
            const double r   = reach(point.get_properties().data(), w.normal);
            const double gap = (w.centre - point.get_location()) * w.normal - r;
            ++n_near;
            if (gap <= tolerance * r)
              ++n_touching;
          }
        for (const unsigned int j : w.wall_nodes)
          {
            counts.local_element(wall_nodes[j].near_dof) += n_near;
            counts.local_element(wall_nodes[j].touching_dof) += n_touching;
          }
      }
    counts.compress(VectorOperation::add);
    counts.update_ghost_values();
    for (const auto &node : wall_nodes)
      in_contact[node.k] = counts.local_element(node.near_dof) == 0 ||
                           counts.local_element(node.touching_dof) > 0;
  }


  template class WallGap<2>;
  template class WallGap<3>;
} // namespace MPM
