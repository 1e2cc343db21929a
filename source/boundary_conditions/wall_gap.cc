#include <deal.II/base/mpi.h>

#include <mpm/boundary_conditions/wall_gap.h>
#include <mpm/material_points/property_layout.h>

#include <cmath>
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
    counts.reinit(layout);
    in_contact.assign(nodes.size(), 1);
    frictional.assign(nodes.size(), 0);
    node_count_dofs.assign(nodes.size(), {{0, 0}});
    if (!active)
      return;
    std::map<unsigned int, unsigned int> node_of_dof;
    for (unsigned int k = 0; k < nodes.size(); ++k)
      if (nodes[k].frictional)
        {
          node_of_dof[nodes[k].local_dofs[0]] = k;
          frictional[k]                       = 1;
          node_count_dofs[k]                  = {
                             {nodes[k].local_dofs[0], nodes[k].local_dofs[1]}};
        }
    const auto &partitioner = *layout.get_partitioner();
    for (const auto &cell : grid.dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              frictional_ids.count(cell->face(f)->boundary_id()))
            {
              const auto face = cell->face(f);
              WallFace   w;
              w.cell   = cell;
              w.centre = face->center();
              // The face's outward normal: from the face's own vertices,
              // pointing away from the cell's centre.
              Tensor<1, dim> n;
              if (dim == 2)
                {
                  const Tensor<1, dim> t = face->vertex(1) - face->vertex(0);
                  n[0]                   = t[1];
                  n[1]                   = -t[0];
                }
              else
                {
                  const Tensor<1, dim> d0 = face->vertex(3) - face->vertex(0);
                  const Tensor<1, dim> d1 = face->vertex(2) - face->vertex(1);
                  n                       = cross_product_3d(d0, d1);
                }
              n /= n.norm();
              if ((w.centre - cell->center()) * n < 0)
                n = -n;
              w.normal = n;
              for (const unsigned int v : face->vertex_indices())
                {
                  const unsigned int dof =
                    partitioner.global_to_local(face->vertex_dof_index(v, 0));
                  if (node_of_dof.count(dof))
                    w.nodes.push_back(node_of_dof[dof]);
                }
              if (!w.nodes.empty())
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
        for (const unsigned int k : w.nodes)
          {
            counts.local_element(node_count_dofs[k][0]) += n_near;
            counts.local_element(node_count_dofs[k][1]) += n_touching;
          }
      }
    counts.compress(VectorOperation::add);
    counts.update_ghost_values();
    for (unsigned int k = 0; k < in_contact.size(); ++k)
      {
        const auto &d = node_count_dofs[k];
        in_contact[k] = !frictional[k] || counts.local_element(d[0]) == 0 ||
                        counts.local_element(d[1]) > 0;
      }
  }


  template class WallGap<2>;
  template class WallGap<3>;
} // namespace MPM
