#ifndef mpm_boundary_conditions_absorbing_boundaries_h
#define mpm_boundary_conditions_absorbing_boundaries_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/tensor.h>

#include <mpm/boundary_conditions/boundary_spec.h>
#include <mpm/grid/background_grid.h>
#include <mpm/grid/nodal_vector.h>
#include <mpm/grid/periodic_node_groups.h>

#include <array>
#include <memory>
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
   * An input motion (a compliant base, Joyner and Chen 1975): where the
   * boundary has an 'Absorbing input velocity' v_in(t), the velocity a
   * wave coming in from beyond the boundary would give the ground there,
   * the dashpot acts on the difference, t = C_face (2 v_in - v): the
   * incoming wave enters, and what comes back from the mesh leaves. (On a
   * boundary at rest, v = v_in + v_reflected: 2 v_in - v = v_in -
   * v_reflected, the incoming wave's traction minus the outgoing one's.)
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

    /**
     * At each absorbing node with mass (@p mass > 0): replace the
     * acceleration @p acceleration by the one that takes the node from
     * @p velocity (the velocity the points brought) to the velocity of
     * the implicit dashpot step of length @p dt, with the input motions
     * at the time @p time (the step's forces').
     */
    void
    apply(const NodalVector &mass,
          const NodalVector &velocity,
          NodalVector       &acceleration,
          const double       dt,
          const double       time) const;

  private:
    /// An input motion's share of a node's dashpot: the function's index
    /// in input_velocities and the dashpot matrix of its faces.
    struct Input
    {
      unsigned int   function;
      Tensor<2, dim> dashpot;
    };
    /// One node of an absorbing face: its velocity components' local
    /// element indices, its dashpot matrix C_i (N s/m) and the shares of
    /// it whose faces bring an input motion.
    struct Node
    {
      std::array<unsigned int, dim> local_dofs;
      Tensor<2, dim>                dashpot;
      std::vector<Input>            inputs;
    };
    std::vector<Node> nodes;
    /// The boundaries' 'Absorbing input velocity', functions of t (the
    /// parser's one coordinate).
    std::vector<std::unique_ptr<FunctionParser<1>>> input_velocities;
    /// The scene's rotation into the mesh's frame (the input velocities
    /// are given in the scene's).
    Tensor<2, dim> rotation;
  };
} // namespace MPM

#endif
