#ifndef mpm_boundary_conditions_boundary_conditions_h
#define mpm_boundary_conditions_boundary_conditions_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/affine_constraints.h>

#include <mpm/boundary_conditions/absorbing_boundaries.h>
#include <mpm/boundary_conditions/boundary_pore_pressures.h>
#include <mpm/boundary_conditions/boundary_spec.h>
#include <mpm/boundary_conditions/surface_tractions.h>
#include <mpm/boundary_conditions/wall_constraints.h>
#include <mpm/boundary_conditions/wall_gap.h>
#include <mpm/boundary_conditions/wall_node_states.h>
#include <mpm/grid/background_grid.h>
#include <mpm/grid/nodal_vector.h>

#include <array>
#include <functional>
#include <optional>
#include <set>
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
   * boundary ids of the mesh and has a type (BoundaryType):
   *  - free:     no constraint;
   *  - fixed:    zero velocity (no-slip);
   *  - slip:     zero normal velocity, free tangential velocity;
   *  - friction: no penetration (unilateral contact: the normal velocity is
   *              removed only while the node moves into the wall, a node
   *              moving away from it is free) and a basal law (BasalLaw:
   *              Coulomb, Voellmy, ...) on the tangential velocity while
   *              the node is pressed into the wall. Unilateral, because a
   *              bilateral constraint would also hold nodes that the
   *              material pulls off the wall; friction, acting only where
   *              the wall pushes, would then see more than the body's
   *              weight (measured: 25 % too slow a block at mu = 0.3, see
   *              doc/validation.md). With 'Wall contact = gap' a node
   *              holds the material only while the material also touches
   *              the wall around it (WallGap);
   *  - velocity: prescribed velocity, given by its normal and tangential
   *              components in the local frame (2D);
   *  - traction: free, loaded by a traction (SurfaceTractions);
   *  - absorbing: free, with a viscous dashpot that absorbs the waves
   *              arriving at it (AbsorbingBoundaries) and a traction.
   *
   * The pieces, one file each: the node frames (compute_node_frames(): the
   * geometry of the walls and the corner rule), the constraints
   * (make_wall_constraints(): AffineConstraints rows n . v = b) and their
   * orthogonal projections in each node's frame (make_projections()), the
   * node-level friction (WallFriction) with the basal laws as plugins, and
   * here the parameters, the contact state and the loops over the nodes.
   *
   * The frame of a node: its outward normal is the area-weighted average of
   * the outward normals of the node's boundary faces with the boundary's
   * ids (so a node on a curved bed gets the averaged normal), or a normal
   * given in the parameter file. A node on several boundaries (a corner)
   * follows this rule: a fixed boundary wins, then a prescribed velocity;
   * otherwise the normals of all its slip/friction boundaries are
   * constrained, normals within 10 degrees of each other being merged into
   * their average. In 2D two different normals leave no free direction, so
   * such a corner node is fixed; in 3D so is a node with three. A 3D node
   * with two normals (an edge where, e.g., a frictional bed meets a slip
   * side wall) slides along the edge: its contact is bilateral, and if one
   * of its walls is frictional, its basal law acts on the velocity along
   * the edge with that wall's normal reaction (without it a 3D channel two
   * cells wide lost two thirds of its bed friction). Unilateral contact is
   * for nodes with one (possibly merged) normal.
   *
   * The constraints are applied as an orthogonal projection in each node's
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
    using ConstrainedNode = MPM::ConstrainedNode<dim>;

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
     * With periodic boundaries, @p periodic_nodes are the copies of the
     * nodes (their frames are made alike).
     */
    void
    setup(const BackgroundGrid<dim> &grid,
          const NodalVector         &layout,
          const PeriodicNodeGroups  *periodic_nodes = nullptr);

    /**
     * The gravity of the scene, whose magnitude basal laws may refer to
     * (Voellmy's rho g v^2 / xi); before setup().
     */
    void
    set_gravity(const Tensor<1, dim> &gravity)
    {
      gravity_magnitude = gravity.norm();
    }

    /// Whether a material carries pore water; before setup(), which then
    /// lays out the water's own walls (has_separate_water_walls()).
    void
    set_pore_water(const bool saturated)
    {
      with_pore_water = saturated;
    }

    /**
     * Which frictional (unilateral) nodes a projection holds on their wall.
     */
    enum class Contact
    {
      /// Those moving into it (v . n > 0, n outward): the rule for a
      /// velocity whose forces are not known yet.
      by_velocity,
      /// Those moving into it, and those the last nodal update
      /// (constrain_updated_velocity()) held; a node that stuck in that
      /// update is set to rest (its tangential velocity too). The rule for
      /// the velocities from which strain rates are computed: a node gets
      /// the motion the wall allowed it while the points moved.
      as_last_update
    };

    /**
     * v <- P v + q at every constrained node: apply the constraints to a
     * nodal velocity field (local elements of a ghosted vector). A
     * frictional node is projected by the rule @p contact.
     *
     * Why the strain rate needs the second rule: a node resting on its
     * wall is held there by the nodal update (gravity presses it in), but
     * the velocity the points bring back to it is a mass-weighted mean of
     * their velocities, which also holds its neighbours' velocities. When
     * the material above rebounds, that mean points away from the wall;
     * left free, the node then shows a strain rate (compression) that no
     * point's motion made, and never the opposite one, since a node moving
     * into the wall is held. The ratchet pumped strain energy into an
     * elastic block resting on a frictional floor until the stability
     * monitor stopped it (within 100-200 steps with MUSL and USF, in 2D
     * and 3D). Likewise a node that stuck by friction brings back a
     * tangential velocity it did not have (FLIP points keep their own):
     * counted in the strain, it made friction create energy.
     */
    void
    project_velocity(NodalVector  &velocity,
                     const Contact contact = Contact::by_velocity) const;

    /**
     * The walls' hold on the pore water's velocity (PoreWater): as
     * project_velocity() (Contact::by_velocity) on the impermeable walls,
     * a fixed one holding the water's normal velocity alone; a 'Drainage
     * = drained' wall lets the water through.
     */
    void
    project_water_velocity(NodalVector &velocity) const;

    /**
     * With pore water (set_pore_water()): whether its walls are not the
     * skeleton's, because a wall is 'Drainage = drained' (the water
     * passes) or fixed (the water seeps along it: the water has no shear
     * stress for a no-slip condition to act on).
     */
    bool
    has_separate_water_walls() const
    {
      return separate_water_walls;
    }

    /**
     * At the nodes where the last nodal update held the skeleton on a
     * wall that lets the water through (a drained wall) or along (a
     * fixed one): in the directions held for the
     * skeleton and free for the water, P_w - P_s (the water's walls being
     * a subset of the skeleton's), replace @p velocity by
     * @p velocity_against_wall (PoreWater::finish_velocity()).
     */
    void
    drain_at_walls(const NodalVector &velocity_against_wall,
                   NodalVector       &velocity) const;

    /// Whether find_contact() measures anything ('Wall contact = gap'
    /// and a frictional wall).
    bool
    contact_by_gap() const
    {
      return wall_gap.measures();
    }

    /**
     * Measure where the material touches the frictional walls (WallGap)
     * from the points of this step, located in their cells; collective.
     */
    void
    find_contact(const Particles::ParticleHandler<dim> &particles,
                 const typename WallGap<dim>::Reach    &reach)
    {
      wall_gap.update(particles, reach);
    }

    /**
     * The projection of the nodal update (the new nodal velocity after the
     * forces, friction included): Contact::by_velocity, recording which
     * frictional nodes it held for the next projections with
     * Contact::as_last_update. Only a node whose new velocity would enter
     * the wall is held: the wall can only push.
     */
    void
    constrain_updated_velocity(NodalVector &velocity);

    /**
     * The frictional nodes' contact state and remembered normal forces of
     * this rank's nodes (owned and ghost), by location, and setting them
     * from such states (of any ranks; nodes not named are free and
     * remember nothing). Kept through a new setup() and written to
     * checkpoints, so that a resumed or repartitioned run continues bit
     * for bit.
     */
    WallNodeStates<dim>
    wall_node_states() const;

    void
    set_wall_node_states(const WallNodeStates<dim> &states);

    /**
     * The basal laws of the frictional walls on the nodal acceleration, in
     * each frictional node's frame (WallFriction), given the velocity at
     * the start of the step (already projected) and the step dt. Nodes
     * with zero mass are skipped. With pore water (@p water), the Coulomb
     * part acts on the effective normal force (Terzaghi): the mixture's
     * reaction less p A, the pore pressure on the node's wall area. The
     * mixture's reaction is the skeleton's plus the water's after the
     * drag, m_w v_w'.n / dt (the drag shares the phases' pushes on the
     * wall, their sum it does not change). p A is the water's own push
     * without the drag, R_w0 = m_w v_w.n / dt + F_w.n, which the water's
     * momentum balance makes n_i p A: p A = R_w0 / n_i, the pressure on
     * the wall itself, not the nodal average of the points' pressures
     * (half a cell above it). On a drained wall the water passes, the
     * pressure is the wall's 'Pore pressure' (0 without one), whose push
     * the phases' forces hold already, and the effective normal force is
     * the skeleton's reaction plus the drag's normal force on the water
     * within the step (the share of the skeleton's push the drag moved
     * to the water). At a 3D edge node each wall's friction takes its own
     * effective normal force: the phases' pushes split onto the two
     * walls' normals (edge_pore_water_relief()). Where the law has a
     * normal-stress memory (NormalStressMemory), the Coulomb part takes
     * the remembered normal force N_m of the node instead of the present
     * one (remembered_normal_reaction(); at a 3D edge node each wall's
     * own, remembered_edge_normal_impulses()).
     */
    /**
     * The pore water at the nodes, for friction in effective stress: its
     * nodal porosity n_i, mass, the velocity it brought, its force (its
     * own pressure and weight, without the drag) and its new velocity
     * (with the drag) before the walls hold it; and what that force lacks
     * of the pore pressure on a wall of outward normal n through the
     * node of the given dofs where the pressure is not hydrostatic
     * (PoreWater::excess_wall_push()).
     */
    struct PoreWaterAtNodes
    {
      const NodalVector &porosity;
      const NodalVector &mass;
      const NodalVector &brought_velocity;
      const NodalVector &force;
      const NodalVector &new_velocity;
      std::function<double(const std::array<unsigned int, dim> &,
                           const Tensor<1, dim> &)>
        excess_push;
    };

    void
    apply_friction(const NodalVector      &mass,
                   const NodalVector      &velocity,
                   NodalVector            &acceleration,
                   const double            dt,
                   const PoreWaterAtNodes *water = nullptr);

    /**
     * What a frictional wall node took in the last nodal update
     * (apply_friction()), for the 'wall tractions' postprocessor: the
     * bed's stresses as a basal force plate and a pore-pressure sensor
     * would read them. Forces over the node's share of the wall, A =
     * int_wall N_i dA, give stresses.
     */
    struct WallTraction
    {
      /// The node's mesh vertex and the wall's unit outward normal.
      Point<dim>     location;
      Tensor<1, dim> normal;
      /// The node's share of its walls' area A (m^2 in 3D, m in 2D).
      double area = 0;
      /// The effective normal force the Coulomb part took (N; the
      /// remembered one with a 'Normal stress memory length'), the pore
      /// water's push p A on an impermeable wall (its excess over the
      /// still water's in a 'Submerged' scene; NaN on a drained wall and
      /// 0 without pore water), and the wall's tangential force on the
      /// material (N, against its slip).
      double effective_normal_force = 0;
      double pore_pressure_force    = 0;
      double tangential_force       = 0;
      /// The node's tangential speed after the update (m/s).
      double slip_speed = 0;
      /// Whether the material pushed on the wall, and whether it stuck.
      bool in_contact = false;
      bool stuck      = false;
    };

    /**
     * Keep each frictional node's WallTraction from the next nodal update
     * on (a diagnostic, off unless a postprocessor asks: the walls' own
     * state is not changed by it).
     */
    void
    record_wall_tractions() const
    {
      recording_tractions = true;
    }

    /**
     * The WallTraction of each frictional node this rank owns (3D edge
     * nodes, held by two walls, are left out; of a periodic node's copies,
     * one), from the last nodal update since record_wall_tractions().
     */
    const std::vector<WallTraction> &
    wall_tractions() const
    {
      return recorded_tractions;
    }

    /// The names of the boundaries with a 'Pore pressure'.
    std::vector<std::string>
    pore_pressure_boundaries() const
    {
      std::vector<std::string> names;
      for (const auto &s : specs)
        if (!s.pore_pressure.empty())
          names.push_back(s.name);
      return names;
    }

    /**
     * The nodal forces of the boundaries' prescribed pore pressures at
     * time @p time (BoundaryPorePressures), or nullptr if no boundary has
     * one.
     */
    const NodalVector *
    pore_pressure_forces(const double time)
    {
      return pore_pressures.forces_at(time);
    }

    /**
     * Add the forces of the boundaries' tractions ('Type = traction') to
     * @p force at the local entries @p active_dofs with mass
     * (SurfaceTractions).
     */
    void
    add_traction_forces(const NodalVector               &mass,
                        const std::vector<unsigned int> &active_dofs,
                        NodalVector                     &force) const
    {
      tractions.add_to(mass, active_dofs, force);
    }

    /**
     * The dashpots of the absorbing boundaries ('Type = absorbing',
     * AbsorbingBoundaries) on the nodal acceleration @p acceleration,
     * implicitly over the step @p dt from the brought velocity
     * @p velocity, at the nodes with mass, with the input motions at the
     * time @p time.
     */
    void
    apply_absorbing(const NodalVector &mass,
                    const NodalVector &velocity,
                    NodalVector       &acceleration,
                    const double       dt,
                    const double       time) const
    {
      absorbing.apply(mass, velocity, acceleration, dt, time);
    }

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
     * The basal law of the boundary called @p name (nullptr unless it is
     * of type friction); InputError if there is no such boundary.
     */
    const BasalLaw<dim> *
    basal_law(const std::string &name) const;

    /**
     * Throw an InputError if a boundary id named in the parameter file does
     * not occur in the mesh.
     */
    void
    check_boundary_ids(const BackgroundGrid<dim> &grid) const;

    /**
     * The mesh boundary ids that a boundary condition other than 'free'
     * covers: material may rest against them.
     */
    std::set<types::boundary_id>
    constrained_boundary_ids() const
    {
      std::set<types::boundary_id> ids;
      for (const auto &spec : specs)
        if (is_wall(spec.type))
          ids.insert(spec.ids.begin(), spec.ids.end());
      return ids;
    }

    /**
     * Whether a boundary can do work on the material (a prescribed,
     * non-zero velocity): the energy of the scene is then not bounded by
     * what it had at the start.
     */
    bool
    does_work() const;

    /// Whether a wall has 'Type = friction' (a basal law) without a
    /// normal-stress memory (NormalStressMemory).
    bool
    has_frictional_wall_without_memory() const;

  private:
    /// wall_area on the mesh of @p grid.
    void
    compute_frictional_wall_area(const BackgroundGrid<dim> &grid,
                                 const NodalVector         &layout,
                                 const PeriodicNodeGroups  *periodic_nodes);

    std::vector<BoundarySpec<dim>> specs;
    double                         gravity_magnitude = 0;
    AffineConstraints<double>    normal_constraints;
    std::vector<ConstrainedNode> nodes;
    /// What the last nodal update did to each frictional node.
    using ContactState = typename WallNodeStates<dim>::Contact;
    std::vector<ContactState> contact_state;
    /// The normal force N_m (N) each frictional node of a wall with a
    /// normal-stress memory remembers (at a 3D edge node, its first
    /// wall's); -1 where it remembers none (not in contact).
    std::vector<double> remembered_normal_force;
    /// At each 3D edge node, the normal force its second wall remembers
    /// (as remembered_normal_force; -1 elsewhere).
    std::vector<double> remembered_edge_force;
    /// Whether a wall of the 3D edge node @p node has a law with a
    /// normal-stress memory.
    static bool
    edge_has_memory(const ConstrainedNode &node);
    /**
     * At the 3D edge node @p k (velocity @p v, acceleration @p a before
     * the walls' resistance), the normal
     * impulse per unit mass each wall's Coulomb part takes, @p impulses:
     * the present effective one, max(0, -lambda_j - dt relief_j) with
     * the pore water's @p relief (WallFriction::edge_frictional_
     * acceleration()), or, for a wall whose law has a normal-stress
     * memory, N_m,j dt / m, its remembered normal force updated here as
     * remembered_normal_reaction() does on one wall, with the speed
     * along the edge as the slip (the walls hold an edge node in every
     * step: it relaxes wherever the wall pushed in the last step);
     * forgotten where the wall does not push. False where the walls make
     * no edge (parallel normals).
     */
    bool
    remembered_edge_normal_impulses(const unsigned int           k,
                                    const Tensor<1, dim>        &v,
                                    const Tensor<1, dim>        &a,
                                    const NodalVector           &mass,
                                    const double                 dt,
                                    const std::array<double, 2> &relief,
                                    std::array<double, 2>       &impulses);
    /**
     * The normal reaction per unit mass that the Coulomb part of the
     * frictional node @p k takes (velocity @p v and acceleration @p a
     * before the wall's resistance, @p held by the last update): the
     * remembered normal force N_m over the node's mass, N_m updated here
     * from the present normal force, @p effective_reaction (or the
     * wall's whole push) times the mass: NormalStressMemory::relax(), or
     * the present force at first contact. Where the node does not push on
     * its wall, N_m is forgotten and @p effective_reaction returned.
     */
    std::optional<double>
    remembered_normal_reaction(const unsigned int           k,
                               const Tensor<1, dim>        &v,
                               const Tensor<1, dim>        &a,
                               const NodalVector           &mass,
                               const double                 dt,
                               const bool                   held,
                               const std::optional<double> &effective_reaction);
    /// Where the material touches the frictional walls.
    WallGap<dim> wall_gap;
    /// The loads of the boundaries of Type = traction and absorbing.
    SurfaceTractions<dim> tractions;
    /// The dashpots of the boundaries of Type = absorbing.
    AbsorbingBoundaries<dim>   absorbing;
    BoundaryPorePressures<dim> pore_pressures;
    /// Whether a material is saturated (set_pore_water()).
    bool with_pore_water = false;
    /// Whether the pore water's walls differ from the skeleton's
    /// (has_separate_water_walls()), and then their projections: the
    /// impermeable walls, each holding the water's normal velocity.
    bool                         separate_water_walls = false;
    std::vector<ConstrainedNode> water_nodes;
    /// For each node of nodes: its index in water_nodes, or
    /// numbers::invalid_unsigned_int (the water is free there).
    std::vector<unsigned int> water_node_of_node;
    /// Whether the pore water passes a wall of normal @p n at node @p k
    /// (an index of nodes): a drained wall, whose water is not held along
    /// @p n.
    bool
    water_drains_along(const unsigned int k, const Tensor<1, dim> &n) const;
    /// The pore water at one constrained node (PoreWaterAtNodes read).
    struct NodeWater
    {
      double         m_w = 0, n_i = 0;
      Tensor<1, dim> v_w, v_w_new, F_w;
    };
    static NodeWater
    node_water(const ConstrainedNode &node, const PoreWaterAtNodes &water);
    /**
     * apply_friction()'s relief (per unit skeleton mass @p m_s and time)
     * of one wall, from the water's pushes on it: its own @p own (without
     * the drag), @p after the drag, and the drag's force @p drag on it.
     * Impermeable: p A - R_w with p A = own / n_i; drained: -drag.
     */
    static double
    pore_water_relief(const bool   drains,
                      const double own,
                      const double after,
                      const double drag,
                      const double n_i,
                      const double m_s);
    /// apply_friction()'s pore-water relief at the 3D edge node @p k, for
    /// each of its two walls (per unit skeleton mass and time).
    std::array<double, 2>
    edge_pore_water_relief(const unsigned int      k,
                           const PoreWaterAtNodes &water,
                           const NodalVector      &mass,
                           const double            dt) const;
    /// Each frictional wall node's share of its walls' area, A_i =
    /// int_wall N_i dA (zero elsewhere): what turns the pore pressure on
    /// the wall into a nodal force (apply_friction()).
    NodalVector wall_area;
    /// record_wall_tractions(), wall_tractions(): a diagnostic that const
    /// observers switch on.
    mutable bool              recording_tractions = false;
    std::vector<WallTraction> recorded_tractions;
    /// Per node: a periodic copy of a node of lower global index.
    std::vector<bool> periodic_copy;
  };
} // namespace MPM

#endif
