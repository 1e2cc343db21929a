#ifndef mpm_boundary_conditions_absorbing_boundaries_h
#define mpm_boundary_conditions_absorbing_boundaries_h

#include <deal.II/base/tensor.h>

#include <mpm/boundary_conditions/boundary_spec.h>
#include <mpm/grid/background_grid.h>
#include <mpm/grid/nodal_vector.h>
#include <mpm/grid/periodic_node_groups.h>

#include <array>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The viscous boundaries of 'Type = absorbing' (Lysmer and Kuhlemeyer
   * 1969): a dashpot on the boundary's faces, traction
   * t = -(rho c_p (v . n) n + rho c_s (v - (v . n) n)), which absorbs a
   * plane P or S wave that meets the face head-on, so that a finite mesh
   * stands for ground that goes on beyond it (a slope shaken by an
   * earthquake, a wave that must not come back from the mesh's bottom).
   *
   * At the nodes the faces' dashpots add up to a matrix per node,
   * C_i = sum over the faces of int_face N_i (Z_s I + (Z_p - Z_s) n n^T)
   * dA (Z_p = rho c_p, Z_s = rho c_s the boundary's impedances), the
   * consistent assembly, so that a node where two absorbing faces meet
   * (a corner of the mesh) damps each face's normal motion with its own
   * impedance. The force -C_i v acts implicitly in the nodal update,
   * (m_i I + dt C_i) v_new = m_i (u + dt a): a light node (little
   * material at the boundary) with a large C_i would take an explicit
   * dashpot's step past zero and flip its velocity, the implicit one only
   * brings it towards rest, at any step.
   *
   * The dashpot acts on the nodes that hold material (as a traction
   * does); with pore water, on the skeleton (the face drains, as a free
   * boundary does). It is exact for plane waves at normal incidence; a
   * wave at an angle is partly reflected (Lysmer and Kuhlemeyer: a few
   * per cent of its energy for incidence within 30 degrees of the
   * normal). Under gravity a body on an absorbing boundary sinks unless
   * the boundary's 'Traction' carries its weight (the static reaction).
   */
  template <int dim>
  class AbsorbingBoundaries
  {
  public:
    /**
     * The dashpot matrices of @p specs' absorbing boundaries at the nodes
     * of @p grid, in the layout of the ghosted vector @p layout, summed
     * over ranks (and over periodic copies): the entries of every locally
     * relevant node, ghosts included.
     */
    void
    setup(const BackgroundGrid<dim>            &grid,
          const std::vector<BoundarySpec<dim>> &specs,
          const NodalVector                    &layout,
          const PeriodicNodeGroups             *periodic_nodes);

    /// Whether a boundary is absorbing.
    bool
    any() const
    {
      return !nodes.empty() || has_absorbing;
    }

    /**
     * At each absorbing node with mass (@p mass > 0): replace the
     * acceleration @p acceleration by the one that takes the node from
     * @p velocity (the velocity the points brought) to the velocity of
     * the implicit dashpot step of length @p dt.
     */
    void
    apply(const NodalVector &mass,
          const NodalVector &velocity,
          NodalVector       &acceleration,
          const double       dt) const;

  private:
    /// One node of an absorbing face: its velocity components' local
    /// element indices and its dashpot matrix C_i (N s/m).
    struct Node
    {
      std::array<unsigned int, dim> local_dofs;
      Tensor<2, dim>                dashpot;
    };
    bool              has_absorbing = false;
    std::vector<Node> nodes;
  };
} // namespace MPM

#endif
