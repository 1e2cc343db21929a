#ifndef mpm_boundary_conditions_surface_tractions_h
#define mpm_boundary_conditions_surface_tractions_h

#include <mpm/boundary_conditions/boundary_spec.h>
#include <mpm/grid/background_grid.h>
#include <mpm/grid/nodal_vector.h>
#include <mpm/grid/periodic_node_groups.h>

#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The loads of the boundaries of 'Type = traction' (a surcharge, a
   * foundation's pressure) and 'Type = absorbing' (the static reaction
   * of the ground the boundary stands for): a traction t (force per area, the
   * scene's frame) on the mesh faces of the boundary, which acts on the nodes
   * as the force int_face N_i t dA. The boundary is otherwise free. The load is
   * carried by what is at the nodes: at a node without material it acts on
   * nothing (the material has left the face), so it is added only at nodes with
   * mass. With pore water, the skeleton carries it: the face drains (the
   * water's pressure there is zero).
   */
  template <int dim>
  class SurfaceTractions
  {
  public:
    /**
     * The nodal forces of the tractions of @p specs on the mesh and DoF
     * numbering of @p grid, in the layout of the ghosted vector
     * @p layout, summed over ranks (and over periodic copies).
     */
    void
    setup(const BackgroundGrid<dim>            &grid,
          const std::vector<BoundarySpec<dim>> &specs,
          const NodalVector                    &layout,
          const PeriodicNodeGroups             *periodic_nodes);

    /// Whether any boundary has a non-zero traction.
    bool
    any() const
    {
      return has_load;
    }

    /// Add the traction forces to @p force at the local entries
    /// @p active_dofs that have mass (@p mass > 0).
    void
    add_to(const NodalVector               &mass,
           const std::vector<unsigned int> &active_dofs,
           NodalVector                     &force) const;

  private:
    bool        has_load = false;
    NodalVector nodal_force;
  };
} // namespace MPM

#endif
