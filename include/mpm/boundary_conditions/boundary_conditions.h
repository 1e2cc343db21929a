#ifndef mpm_boundary_conditions_boundary_conditions_h
#define mpm_boundary_conditions_boundary_conditions_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/affine_constraints.h>

#include <mpm/grid/background_grid.h>
#include <mpm/grid/nodal_vector.h>

#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * Kinematic boundary conditions acting on the nodes of the background
   * mesh, each in the node's own frame (normal and tangential to the
   * ground), as in the paper: transform to the local frame, constrain,
   * correct for friction, transform back.
   *
   * The parameter file lists named boundaries; each covers one or more
   * boundary ids of the mesh and has a type:
   *  - free:     no constraint;
   *  - fixed:    zero velocity (no-slip);
   *  - slip:     zero normal velocity, free tangential velocity;
   *  - friction: no penetration (unilateral contact: the normal velocity is
   *              removed only while the node moves into the wall, a node
   *              moving away from it is free) and Coulomb friction with
   *              coefficient mu on the tangential velocity while the node is
   *              pressed into the wall. Unilateral, because a bilateral
   *              constraint would also hold nodes that the material pulls
   *              off the wall; friction, acting only where the wall pushes,
   *              would then see more than the body's weight (measured:
   *              25 % too slow a block at mu = 0.3, see doc/validation.md);
   *  - velocity: prescribed velocity, given by its normal and tangential
   *              components in the local frame (2D).
   *
   * The frame of a node: its outward normal is the area-weighted average of
   * the outward normals of the node's boundary faces with the boundary's
   * ids (so a node on a curved bed gets the averaged normal), or a normal
   * given in the parameter file. A node on several boundaries (a corner)
   * follows this rule: a fixed boundary wins, then a prescribed velocity;
   * otherwise the normals of all its slip/friction boundaries are
   * constrained, normals within 10 degrees of each other being merged into
   * their average. In 2D two different normals leave no free direction, so
   * such a corner node is fixed. Friction acts only at nodes with a single
   * (possibly merged) normal.
   *
   * The normal constraints are held in an AffineConstraints object (rows
   * n . v = b, as VectorTools::compute_no_normal_flux_constraints makes
   * them). They are applied as an orthogonal projection in each node's
   * frame, v <- P v + q with P = I - N^T (N N^T)^{-1} N: the normal
   * component is removed and the tangential one kept exactly. This is what
   * condensing the lumped-mass system does. AffineConstraints::distribute()
   * would instead overwrite the pivot component, an oblique projection that
   * changes the tangential velocity on a tilted wall.
   */
  template <int dim>
  class BoundaryConditions
  {
  public:
    /**
     * A node that carries a constraint, in the numbering of the local
     * elements of a ghosted vector.
     */
    struct ConstrainedNode
    {
      /// Local element index of each velocity component.
      std::array<unsigned int, dim> local_dofs;
      /// Orthogonal projector onto the admissible velocities.
      Tensor<2, dim> projector;
      /// Particular solution of the inhomogeneous constraints.
      Tensor<1, dim> offset;
      /// Coulomb friction at this node?
      bool frictional = false;
      /// Unit outward normal of the node's frame.
      Tensor<1, dim> normal;
      /// Friction coefficient.
      double friction_coefficient = 0;
    };

    static void
    declare_name_list(ParameterHandler &prm);

    static std::vector<std::string>
    read_name_list(ParameterHandler &prm);

    static void
    declare_parameters(ParameterHandler               &prm,
                       const std::vector<std::string> &names);

    void
    parse_parameters(ParameterHandler &prm);

    /**
     * Compute the node frames, the AffineConstraints and the per-node
     * projectors for the current mesh and DoF numbering; @p layout is a
     * ghosted vector whose local element numbering the nodes will use.
     */
    void
    setup(const BackgroundGrid<dim> &grid, const NodalVector &layout);

    /**
     * v <- P v + q at every constrained node: apply the constraints to a
     * nodal velocity field (local elements of a ghosted vector). A
     * frictional node is projected only if it moves into its wall
     * (v . n > 0, n outward).
     */
    void
    project_velocity(NodalVector &velocity) const;

    /**
     * Coulomb friction on the nodal acceleration, in each frictional node's
     * frame, given the velocity at the start of the step (already
     * projected) and the step dt. Nodes with zero mass are skipped.
     */
    void
    apply_friction(const NodalVector &mass,
                   const NodalVector &velocity,
                   NodalVector       &acceleration,
                   const double       dt) const;

    /**
     * Friction in the local frame of one node: returns the corrected
     * acceleration for velocity @p v and acceleration @p a (global frame),
     * outward unit normal @p n and coefficient @p mu. Coulomb's law by
     * backward Euler: with the normal reaction per unit mass r = v.n/dt +
     * a.n (friction only if r > 0) and the trial tangential velocity
     * v_t* = v_t + dt a_t, the node sticks (v_t' = 0) if |v_t*| <= mu r dt,
     * else v_t' = v_t* (1 - mu r dt / |v_t*|). This is the static rule at
     * rest (stick while |a_t| <= mu r), the kinetic rule when sliding
     * (a_t reduced by mu r, stopping rather than reversing), and friction
     * never reverses the motion. The normal component is left for the
     * projection. Exposed for unit tests.
     */
    static Tensor<1, dim>
    frictional_acceleration(const Tensor<1, dim> &v,
                            const Tensor<1, dim> &a,
                            const Tensor<1, dim> &n,
                            const double          mu,
                            const double          dt);

    const AffineConstraints<double> &
    constraints() const
    {
      return normal_constraints;
    }

    const std::vector<ConstrainedNode> &
    constrained_nodes() const
    {
      return nodes;
    }

    bool
    empty() const
    {
      return specs.empty();
    }

    /**
     * Friction coefficient of the boundary called @p name (0 unless it is
     * of type friction); InputError if there is no such boundary.
     */
    double
    friction_coefficient(const std::string &name) const;

    /**
     * Throw an InputError if a boundary id named in the parameter file does
     * not occur in the mesh.
     */
    void
    check_boundary_ids(const BackgroundGrid<dim> &grid) const;

    /**
     * Whether a boundary can do work on the material (a prescribed,
     * non-zero velocity): the energy of the scene is then not bounded by
     * what it had at the start.
     */
    bool
    does_work() const;

  private:
    enum class Type
    {
      free,
      fixed,
      slip,
      friction,
      velocity
    };

    struct Spec
    {
      std::string                     name;
      std::vector<types::boundary_id> ids;
      Type                            type = Type::free;
      double                          friction_coefficient = 0;
      bool                            normal_from_mesh     = true;
      Tensor<1, dim>                  given_normal;
      Tensor<1, dim>                  local_velocity;
    };

    std::vector<Spec>            specs;
    AffineConstraints<double>    normal_constraints;
    std::vector<ConstrainedNode> nodes;
  };
} // namespace MPM

#endif
