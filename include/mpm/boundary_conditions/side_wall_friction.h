#ifndef mpm_boundary_conditions_side_wall_friction_h
#define mpm_boundary_conditions_side_wall_friction_h

#include <deal.II/base/parameter_handler.h>

#include <mpm/grid/nodal_vector.h>
#include <mpm/transfer/phase_kernel.h>

#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * Coulomb friction on the two side walls of a channel that a 2D
   * (plane-strain) scene stands for: the walls are the planes z = +-W/2,
   * parallel to the scene's plane, so they are not in the mesh. A laboratory
   * column collapse or flume runs in such a channel, and the walls' friction
   * slows the flow (Jop, Forterre and Pouliquen 2005, J. Fluid Mech. 541:
   * their depth-averaged wall stress mu_w p over the channel width).
   *
   * Across the width the flow is taken as a plug: each wall carries the
   * material's out-of-plane stress, sigma_n = max(0, -sigma_zz) (the
   * plane-strain stress every point stores), and resists the in-plane motion
   * with the shear stress mu_w sigma_n. Per unit volume of material that is
   * a force of magnitude (2 mu_w / W) sigma_n against the velocity. It acts
   * where Coulomb friction at a wall acts, on the nodes, and the same way:
   * the particle-to-grid pass sums each node's capacity
   * L_i = sum_p N_ip V_p (2 mu_w / W) sigma_n,p (a pass through the
   * PhaseKernel seam: a scene without side walls pays nothing), and the
   * nodal update reduces the node's in-plane velocity v* (after the
   * mesh's walls have constrained it) by at most dt L_i / m_i along it,
   * stopping the node if that is more than |v*|
   * (backward Euler of Coulomb's law: no reversal within a step, static
   * friction at rest). So a layer at rest stays at rest, and the walls only
   * ever remove kinetic energy.
   *
   * With pore water sigma_zz is the effective stress the points store
   * (Terzaghi: the water's pressure pushes on the walls without friction),
   * and the friction acts on the skeleton's nodal velocity after the
   * coupled solve with the water, as a mesh wall's Coulomb friction does;
   * the water follows through the next step's drag. A 3D scene meshes its
   * side walls and gives them 'Type = friction'.
   */
  template <int dim>
  class SideWallFriction : public PhaseKernel<dim>
  {
  public:
    using typename PhaseKernel<dim>::Targets;
    using typename PhaseKernel<dim>::VertexValues;
    using typename PhaseKernel<dim>::Sums;
    using typename PhaseKernel<dim>::Sources;

    /// The subsection 'Boundary conditions/Side walls'.
    static void
    declare_parameters(ParameterHandler &prm);

    /// Throws InputError for a negative width or coefficient, and for side
    /// walls in 3D.
    void
    parse_parameters(ParameterHandler &prm);

    /// Whether the scene has side walls with friction.
    bool
    active() const
    {
      return factor > 0;
    }

    /// Registers the walls' nodal field with @p nodal (only if active()).
    void
    initialize(NodalFields &nodal);

    Targets
    grid_targets() override;

    /// The point's share of its nodes' capacities L_i (in every component).
    void
    add_to_grid(const double                *props,
                const Q1ShapeFunctions<dim> &sf,
                const VertexValues          &offsets,
                Sums                        &sums) const override;

    /// None: the walls update no point.
    Sources
    grid_sources() override
    {
      return Sources{};
    }

    void
    update_point(
      double *,
      const std::array<Tensor<1, dim>, PhaseKernel<dim>::max_sources> &,
      const std::array<Tensor<2, dim>, PhaseKernel<dim>::max_sources> &,
      const Tensor<2, dim> &) const override
    {
    }

    /**
     * The walls' friction on the nodes @p active_dofs (local entries, all
     * components of each node): each node's @p velocity, the end-of-step
     * velocity the mesh's walls have constrained (the trial velocity of
     * the walls' Coulomb law), is slowed by dt L_i / m_i along itself, or
     * stopped. A node's components are consecutive entries (CellDofTable
     * checks it).
     */
    void
    apply(const NodalVector               &mass,
          NodalVector                     &velocity,
          const std::vector<unsigned int> &active_dofs,
          const double                     dt) const;

  private:
    /// Channel width W (m) and the walls' friction coefficient mu_w.
    double width = 0, friction_coefficient = 0;
    /// 2 mu_w / W (1/m); 0 without side walls.
    double factor = 0;
    /// Each node's capacity L_i (N per m of the scene's thickness), in
    /// every component's entry.
    NodalVector capacity;
  };
} // namespace MPM

#endif
