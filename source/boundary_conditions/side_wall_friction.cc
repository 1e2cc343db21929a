#include <mpm/base/input_error.h>
#include <mpm/boundary_conditions/side_wall_friction.h>
#include <mpm/material_points/property_layout.h>

#include <cmath>

namespace MPM
{
  template <int dim>
  void
  SideWallFriction<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    prm.enter_subsection("Side walls");
    prm.declare_entry(
      "Channel width",
      "0",
      Patterns::Double(0),
      "2D only: the width W (m) of the channel between two side walls "
      "parallel to the scene's plane (a laboratory collapse or flume), which "
      "resist the in-plane motion with Coulomb friction 'Friction "
      "coefficient' times the material's out-of-plane stress -sigma_zz (the "
      "effective stress of a saturated material): a force (2 mu_w / W) "
      "max(0, -sigma_zz) per unit volume, applied at the nodes like wall "
      "friction (doc/boundary_conditions.md, 'Side-wall friction'). 0: no "
      "side walls.");
    prm.declare_entry("Friction coefficient",
                      "0",
                      Patterns::Double(0),
                      "Coulomb friction coefficient mu_w of the side walls "
                      "(with 'Channel width' > 0).");
    prm.leave_subsection();
    prm.leave_subsection();
  }


  template <int dim>
  void
  SideWallFriction<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    prm.enter_subsection("Side walls");
    width                = prm.get_double("Channel width");
    friction_coefficient = prm.get_double("Friction coefficient");
    prm.leave_subsection();
    prm.leave_subsection();
    const bool walls = width > 0 && friction_coefficient > 0;
    check_input(!walls || dim == 2,
                "'Boundary conditions/Side walls': side walls with friction "
                "stand for the walls of a channel that a 2D scene leaves "
                "out; in 3D mesh the walls and give them 'Type = "
                "friction'.");
    check_input(!(friction_coefficient > 0 && width == 0),
                "'Boundary conditions/Side walls/Friction coefficient' is "
                "set but 'Channel width' is 0: give the channel's width (m), "
                "or set the coefficient to 0.");
    factor = walls ? 2 * friction_coefficient / width : 0.;
  }


  template <int dim>
  void
  SideWallFriction<dim>::initialize(NodalFields &nodal)
  {
    if (active())
      nodal.add(capacity, NodalFields::Ghosts::summed);
  }


  template <int dim>
  typename SideWallFriction<dim>::Targets
  SideWallFriction<dim>::grid_targets()
  {
    Targets targets{};
    targets[0] = &capacity;
    return targets;
  }


  template <int dim>
  void
  SideWallFriction<dim>::add_to_grid(const double                *props,
                                     const Q1ShapeFunctions<dim> &sf,
                                     const VertexValues &,
                                     Sums &sums) const
  {
    using Layout = PropertyLayout<dim>;
    // sigma_zz: the third of the stored components (xx, yy, zz, ...).
    const double sigma_n = std::max(0., -props[Layout::stress + 2]);
    if (sigma_n == 0)
      return;
    const double load = factor * sigma_n * props[Layout::volume];
    for (unsigned int i = 0; i < PhaseKernel<dim>::n_vertices; ++i)
      for (unsigned int c = 0; c < dim; ++c)
        sums[0][i][c] += sf.value[i] * load;
  }


  template <int dim>
  void
  SideWallFriction<dim>::apply(const NodalVector               &mass,
                               NodalVector                     &velocity,
                               const std::vector<unsigned int> &active_dofs,
                               const double                     dt) const
  {
    // Each node once, at its first component's entry (the components of
    // a node are consecutive entries); every node's own entries only, so
    // the loop could run on threads as it is.
    for (const unsigned int i : active_dofs)
      {
        if (i % dim != 0)
          continue;
        const double m = mass.local_element(i);
        const double L = capacity.local_element(i);
        if (m <= 0 || L <= 0)
          continue;
        Tensor<1, dim> trial;
        for (unsigned int c = 0; c < dim; ++c)
          trial[c] = velocity.local_element(i + c);
        const double speed         = trial.norm();
        const double speed_removed = dt * L / m;
        const double scale =
          speed <= speed_removed ? 0. : 1. - speed_removed / speed;
        for (unsigned int c = 0; c < dim; ++c)
          velocity.local_element(i + c) = scale * trial[c];
      }
  }


  template class SideWallFriction<2>;
  template class SideWallFriction<3>;
} // namespace MPM
