#ifndef mpm_phases_pore_water_h
#define mpm_phases_pore_water_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/particles/particle_handler.h>

#include <mpm/boundary_conditions/boundary_conditions.h>
#include <mpm/grid/background_grid.h>
#include <mpm/grid/nodal_vector.h>
#include <mpm/material_points/point_generator.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/materials/material_library.h>
#include <mpm/phases/nodal_pressure_rate.h>
#include <mpm/transfer/phase_kernel.h>

#include <memory>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;


  /**
   * The water in the pores of saturated materials ('Materials/NAME/
   * Porosity' > 0): the single-point, two-phase (v-w) formulation of the
   * explicit MPM of Bandara and Soga (2015), as the paper's group has it
   * (mpm_explicit_twophase): every point of a saturated material carries,
   * besides the skeleton's mass, velocity and effective stress, the water's
   * velocity v_w, the pore pressure p (compression positive) and the
   * porosity n (doc/pore_water.md). Per step:
   *
   *  - particle to grid (map_to_grid()): water mass n rho_w V N_i and
   *    momentum; the water's force n p V grad N_i + N_i m_w g; the share of
   *    the pore pressure the skeleton carries, (1 - n) p V grad N_i (the
   *    skeleton's force of the dry passes holds its effective stress);
   *    the drag coefficient N_i V n^2 mu / k;
   *  - at each node, the two momentum equations with the drag implicit
   *    (couple()), m_s (v_s' - v_s) / dt = F_s + Q (v_w' - v_s') and
   *    m_w (v_w' - v_w) / dt = F_w - Q (v_w' - v_s'), solved as a 2 x 2
   *    system per component: unconditionally stable in the drag, so
   *    that a low permeability does not shorten the step. The skeleton's
   *    solution enters the dry nodal update as its force (friction and
   *    walls act on it as on a dry skeleton); the water is held by the
   *    walls' normal constraints (impermeable walls);
   *  - grid to particle (update_points()): v_w by the FLIP/PIC share of
   *    the transfer scheme (PIC under APIC), then p from the water's
   *    balance dp = -(K_w / n) ((1 - n) div v_s + n div v_w) dt, with
   *    the end-of-step nodal velocities; n follows the point's volume in
   *    the skeleton's stress update, its grains keeping their volume
   *    (PointUpdate::update_porosity()).
   *
   * A boundary without a wall drains, and so does a free surface inside
   * the mesh: the weak form has no pressure term there, which is p = 0; a
   * boundary with a 'Pore pressure' adds the term of its p_b
   * (BoundaryPorePressures). The points of a nearly empty cell ('Free
   * surface volume fraction') are drained outright (finish_cell_pressures()):
   * a lone point's water is not held by the step's wave speed. Local damping
   * acts on the mixture in couple().
   */
  template <int dim>
  class PoreWater : public PhaseKernel<dim>
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    /**
     * Whether any material of @p materials is saturated: only then does
     * the scene have the water's point slots, nodal fields and passes.
     * Registers the nodal fields with @p nodal.
     */
    void
    initialize(const MaterialLibrary &materials, NodalFields &nodal);

    bool
    active() const
    {
      return is_active;
    }

    /// The names of the water's point slots (PointProperties).
    std::vector<std::string>
    point_property_names() const;

    void
    set_first_slot(const unsigned int slot)
    {
      first_slot = slot;
      nodal_rate.set_slots(
        {volumetric_rate_slot(), pressure_slot(), porosity_slot()});
    }

    /// @name Where a point keeps the water's data (from its first slot).
    /// @{
    unsigned int
    velocity_slot() const
    {
      return first_slot;
    }

    unsigned int
    pressure_slot() const
    {
      return first_slot + dim;
    }

    unsigned int
    porosity_slot() const
    {
      return first_slot + dim + 1;
    }

    /// The water's affine matrix C_w (dim x dim, row by row): its velocity
    /// about the point is v_w + C_w (x - xbar_p) (affine_transfer()).
    unsigned int
    affine_slot() const
    {
      return first_slot + dim + 2;
    }

    /// The point's own volumetric rate of this step, with 'Pressure rate
    /// averaging = node' (NodalPressureRate).
    unsigned int
    volumetric_rate_slot() const
    {
      return affine_slot() + (affine ? dim * dim : 0);
    }
    /// @}

    /**
     * The water of new points: the porosity of their material, the
     * pore pressure 'Initial pore pressure' at their position (scene
     * frame, @p grid converts), the skeleton's velocity.
     */
    void
    initialize_points(Particles::ParticleHandler<dim> &particles,
                      const BackgroundGrid<dim>       &grid) const;

    /**
     * The water's density and 'Initial pore pressure', for the geostatic
     * stress of saturated materials (PointGenerator::generate()); empty
     * if no material is saturated.
     */
    InitialPoreWater<dim>
    initial_state() const
    {
      if (!is_active)
        return {};
      return {water_density,
              [this](const Point<dim> &x) {
                return initial_pressure->value(x);
              },
              submerged ? water_density : 0.};
    }

    /**
     * The fastest wave the explicit step must resolve among the saturated
     * materials: fastest_wave_speed() of each.
     */
    double
    max_wave_speed(const MaterialLibrary &materials) const;

    /**
     * The fastest P wave of a saturated material of P-wave modulus @p M,
     * dry density @p rho_d and porosity @p n: the fast wave of the two
     * phases without drag (Biot's fast wave at high frequency), which is
     * faster than the undrained wave sqrt((M + K_w / n) / (rho_d + n
     * rho_w)), the water's own and the skeleton's (6.5 % above the
     * undrained one on tests/infinite_slope_saturated.prm). With it the
     * step is stable where the drag couples the phases weakly too; where
     * it couples them rigidly the undrained wave would do.
     */
    double
    fastest_wave_speed(const double M,
                       const double rho_d,
                       const double n) const;

    /**
     * Whether the water's velocity goes by APIC's affine transfer: 'Water
     * velocity transfer = affine' and @p affine_skeleton, the skeleton's
     * transfer carries an affine velocity (APIC, whose offsets about each
     * point's affine centre the passes hand over). Else the water takes the
     * skeleton's FLIP share.
     */
    void
    set_skeleton_transfer(const bool affine_skeleton)
    {
      affine = affine_requested && affine_skeleton;
    }

    bool
    affine_transfer() const
    {
      return affine;
    }

    /// The step's time step, FLIP share and gravity (mesh frame).
    void
    set_step(const double dt, const double flip, const Tensor<1, dim> &g)
    {
      time_step        = dt;
      flip_fraction    = flip;
      gravity          = g;
      nodal_rate.set_time_step(dt);
    }

    /**
     * With 'Pressure rate averaging = node', the kernel that updates the
     * pore pressures from the rates averaged at the nodes, to be run
     * (map_phase(), compute_nodal_rates(), update_phase_points()) after
     * update_phase_points() with this kernel, which then leaves the
     * pressures alone; else nullptr.
     */
    NodalPressureRate<dim> *
    nodal_pressure_rate()
    {
      return rate_averaging == RateAveraging::node ? &nodal_rate : nullptr;
    }

    /**
     * 'Pressure projection = cell linear': the pore pressures of the
     * saturated points @p props of one cell, at @p positions, replaced by
     * their volume-weighted least-squares linear fit over the cell.
     */
    void
    project_cell_pressures(const ArrayView<double *const>    &props,
                           const ArrayView<const Point<dim>> &positions) const;

    /**
     * The water's and the skeleton's new nodal velocity with the drag
     * implicit, at the nodes @p active_dofs (local elements): on return
     * nodal.force holds the skeleton's force that gives its new velocity
     * from the momentum it brought (the drag included), and the water's
     * new velocity is in its own field. @p boundary_forces (or nullptr):
     * the forces of the boundaries' prescribed pore pressures
     * (BoundaryPorePressures), shared by the phases as the nodal porosity
     * says. @p local_damping: Cundall's coefficient alpha, applied here
     * to the mixture, and to the skeleton alone at nodes without water
     * (the dry nodal update then damps no more). After
     * map_phase() with this kernel.
     */
    void
    couple(NodalFields                     &nodal,
           const std::vector<unsigned int> &active_dofs,
           const NodalVector               *boundary_forces,
           const double                     local_damping);

    /**
     * The water at the nodes after couple() and before finish_velocity(): its
     * nodal porosity m_w / (rho_w sum N V), mass, brought velocity, force
     * and new velocity. A frictional wall's Coulomb resistance acts on the
     * effective normal force with them (BoundaryConditions::
     * apply_friction()).
     */
    typename BoundaryConditions<dim>::PoreWaterAtNodes
    at_nodes() const
    {
      return {nodal_porosity,
              mass,
              velocity,
              force,
              velocity_new,
              [this](const std::array<unsigned int, dim> &dofs,
                     const Tensor<1, dim>                &normal) {
                return excess_wall_push(dofs, normal);
              }};
    }

    /**
     * What the water's nodal force at the node of @p dofs lacks of the
     * pore pressure's push n_i p A on a wall of outward normal @p normal
     * through it, where the pressure is not hydrostatic.
     *
     * By parts, sum_q V_q n_q (p_q grad N_i + N_i grad p_q) is the wall's
     * integral of N_i n p, and the nodal force holds only the first term
     * (and the water's weight): the push lacks G.n = sum_q N_i V_q n_q
     * (grad p_q - rho_w g).n, zero for hydrostatic water, the excess
     * gradient's weight over the half cell above the wall otherwise (a
     * layer sliding under an excess pore pressure of 0.8 of its buoyant
     * weight, two cells thick, slid 16 % slow without it). The points'
     * own pressure gradients are not known: within a cell they share one
     * pressure rate, and the differences between them are an earlier
     * state's, sheared with the flow (the cells' linear fits, tried, were
     * noise in a flowing sheet). So the gradient normal to the wall is
     * taken from the state at the node: the pore pressure keeps its
     * share r = p / (p - sigma'_nn) of the total normal stress over the
     * half cell, whose gradient is the mixture's weight rho g.n (a layer
     * parallel to the wall, at rest normal to it): grad p.n = r rho g.n,
     * with p, sigma' and rho the saturated points' averages at the node
     * (weights N V, sum_q N V n_q = n_i sum_q N V). Exact for hydrostatic
     * water (r = rho_w / rho) and for an excess pressure proportional to
     * the depth. With 'Submerged' p is the excess over the still water's,
     * and grad p.n = r (rho - rho_w) g.n.
     */
    double
    excess_wall_push(const std::array<unsigned int, dim> &dofs,
                     const Tensor<1, dim>                &normal) const;

    /**
     * The water's new velocity at the walls, at the nodes @p active_dofs:
     * at a drained wall, in the directions the wall holds the skeleton
     * but not the water, from the water's momentum balance with the drag
     * against the skeleton as the wall holds it (nodal.velocity_new), not
     * against the skeleton couple() let move with the water into the wall
     * (that drained a layer's base to a suction of the full load); then
     * held by the impermeable walls. Elsewhere couple()'s solution stays:
     * friction's impulse on the skeleton reaches the water through the
     * next step's drag (recomputing the water against the skeleton after
     * friction would take momentum from the water that no force gives
     * back, measured: a saturated layer sliding on its bed 40 % slower).
     */
    void
    finish_velocity(const NodalFields               &nodal,
                    const std::vector<unsigned int> &active_dofs,
                    const BoundaryConditions<dim>   &boundary_conditions);

    /// The skeleton's end-of-step nodal velocity, which update_point()
    /// reads for the volume change.
    void
    set_skeleton_velocity(const NodalVector &velocity)
    {
      skeleton_velocity = &velocity;
    }

    /// @name PhaseKernel.
    /// @{
    typename PhaseKernel<dim>::Targets
    grid_targets() override;

    bool
    needs_affine() const override
    {
      return affine;
    }

    void
    add_to_grid(const double                                  *props,
                const Q1ShapeFunctions<dim>                   &sf,
                const typename PhaseKernel<dim>::VertexValues &offsets,
                typename PhaseKernel<dim>::Sums &sums) const override;

    typename PhaseKernel<dim>::Sources
    grid_sources() override;

    void
    update_point(
      double                                                          *props,
      const std::array<Tensor<1, dim>, PhaseKernel<dim>::max_sources> &values,
      const std::array<Tensor<2, dim>, PhaseKernel<dim>::max_sources>
                           &gradients,
      const Tensor<2, dim> &affine_fit) const override;

    /// With 'Pressure rate averaging = cell', or 'Pressure projection =
    /// cell linear' or a 'Free surface volume fraction' where this pass
    /// updates the pressures.
    bool
    averages_over_cells() const override
    {
      return rate_averaging == RateAveraging::cell ||
             rate_averaging == RateAveraging::patch ||
             ((project_pressure || free_surface_fraction > 0) &&
              rate_averaging != RateAveraging::node);
    }

    /// With 'Pressure rate averaging = patch'.
    bool
    averages_over_patches() const override
    {
      return rate_averaging == RateAveraging::patch;
    }

    void
    finish_cell(const ArrayView<double *const>    &props,
                const ArrayView<const Point<dim>> &positions,
                const double                       cell_volume) const override;

    /// What finish_cell() does with the pressures of one cell's points,
    /// in whichever pass updates them: drained if they fill less than
    /// 'Free surface volume fraction' of the cell's volume @p cell_volume,
    /// else projected ('Pressure projection').
    void
    finish_cell_pressures(const ArrayView<double *const>    &props,
                          const ArrayView<const Point<dim>> &positions,
                          const double                       cell_volume) const;

    /// The point's volumetric rate (1 - n) div v_s + n div v_w and its
    /// volume (0 for a dry point).
    std::pair<double, double>
    cell_rate(
      const double                                                    *props,
      const std::array<Tensor<1, dim>, PhaseKernel<dim>::max_sources> &values,
      const std::array<Tensor<2, dim>, PhaseKernel<dim>::max_sources>
        &gradients) const override;

    /// update_point() with the pressure's volumetric rate @p cell_mean
    /// (update_point(): the point's own, cell_rate()).
    void
    update_point_with_cell_mean(
      double                                                          *props,
      const std::array<Tensor<1, dim>, PhaseKernel<dim>::max_sources> &values,
      const std::array<Tensor<2, dim>, PhaseKernel<dim>::max_sources>
                           &gradients,
      const Tensor<2, dim> &affine_fit,
      const double          cell_mean) const override;
    /// @}

    /// @name The water's parameters.
    /// @{
    double
    density() const
    {
      return water_density;
    }

    /// The water of the point with properties @p props, n rho_w V (0 for
    /// a dry point).
    double
    water_mass(const double *props) const
    {
      return props[porosity_slot()] * water_density *
             props[PropertyLayout<dim>::volume];
    }

    /**
     * The water the point with properties @p props held at the start,
     * rho_w n0 V0 = rho_w n0 m / rho_d (0 for a dry point): its grains
     * keep their volume, (1 - n) V = (1 - n0) V0
     * (PointUpdate::update_porosity()). The point's water, water_mass(),
     * changes with its pores: water drawn in through a drained face as the
     * skeleton dilates, pushed out as it compacts. The energies weigh this
     * water instead: the weight of water that appears at a point had no
     * potential energy to release, and weighing it would add m g y with
     * y from the coordinates' arbitrary origin (weighed so, a permeable
     * flume "creates" the potential energy of the water its dilating
     * skeleton draws in, 0.27 m above the origin, and the energy check
     * stops it).
     */
    double
    carried_water_mass(const double *props) const
    {
      if (props[porosity_slot()] == 0)
        return 0.;
      const unsigned int material =
        static_cast<unsigned int>(props[PropertyLayout<dim>::material_id]);
      return water_density * material_porosity[material] *
             props[PropertyLayout<dim>::mass] / material_dry_density[material];
    }

    double
    get_bulk_modulus() const
    {
      return bulk_modulus;
    }

    double
    get_viscosity() const
    {
      return viscosity;
    }

    /**
     * 'Submerged': the scene lies in still water, the points' pore
     * pressure is the excess over its hydrostatic pressure, the water
     * carries no weight and the skeleton its buoyant weight (rho_d - (1 -
     * n) rho_w) V g.
     */
    bool
    is_submerged() const
    {
      return submerged;
    }

    /// The still water's weight that the point with properties @p props
    /// displaces with its skeleton, (1 - n) rho_w V, with 'Submerged'
    /// (0 otherwise, and for a dry point).
    double
    displaced_water_mass(const double *props) const
    {
      const double n = props[porosity_slot()];
      return submerged && n > 0 ?
               (1 - n) * water_density * props[PropertyLayout<dim>::volume] :
               0.;
    }
    /// @}

  private:
    bool is_active = false;

    double      water_density    = 1000;
    double      bulk_modulus     = 2.2e9;
    double      viscosity        = 1e-3;
    /// 'Permeability law = kozeny-carman'.
    bool        kozeny_carman    = false;
    /// 'Submerged': the pore pressure is the excess over still water's.
    bool                                 submerged                   = false;
    std::string initial_pressure_expression = "0";
    std::unique_ptr<FunctionParser<dim>> initial_pressure;

    /// Per material: its porosity at the start (0: dry) and its
    /// intrinsic permeability.
    std::vector<double> material_porosity;
    /// Each material's 'Density' (the dry density (1 - n0) rho_s of a
    /// saturated one): a point's grains fill (1 - n0) m / rho_d.
    std::vector<double> material_dry_density;
    std::vector<double> material_permeability;

    unsigned int first_slot = 0;

    double         time_step     = 0;
    double         flip_fraction = 0;
    /// 'Water velocity transfer = affine', and whether it is in effect
    /// (set_skeleton_transfer()).
    bool affine_requested = false, affine = false;
    /// 'Pressure rate averaging': the volumetric rate of a point's
    /// pressure is its own, its cell's mean, or interpolated from the
    /// nodes' means (NodalPressureRate).
    enum class RateAveraging
    {
      none,
      cell,
      patch,
      node
    };
    RateAveraging          rate_averaging = RateAveraging::cell;
    NodalPressureRate<dim> nodal_rate;
    /// 'Pressure projection = cell linear'.
    bool               project_pressure = false;
    /// 'Free surface volume fraction' (0: none).
    double             free_surface_fraction = 0;
    /// 'Wall pore pressure = excess gradient' (excess_wall_push()).
    bool               wall_excess_gradient = false;
    Tensor<1, dim> gravity;
    const NodalVector *skeleton_velocity = nullptr;

    /// The water's nodal fields (mass in each component's entry).
    NodalVector mass, momentum, force, skeleton_pressure_force, drag;
    /// sum N V over the saturated points, and the nodal porosity
    /// m_w / (rho_w sum N V) (at_nodes()), in every component.
    NodalVector volume_sums, nodal_porosity;
    /// The saturated points' state at the nodes that excess_wall_push()
    /// reads, sum N V of: the effective stress (SymmetricTensor's
    /// independent components, in its own order), the pore pressure and
    /// the mixture's density, packed dim to a field.
    static constexpr unsigned int n_stress_values =
      SymmetricTensor<2, dim>::n_independent_components;
    static constexpr unsigned int n_wall_state_values = n_stress_values + 2;
    std::array<NodalVector, (n_wall_state_values + dim - 1) / dim>
      wall_state_sums;
    /// Brought (p / m) and end-of-step velocity.
    NodalVector velocity, velocity_new;
    /// The water's new velocity by its balance against the skeleton's
    /// final velocity (finish_velocity(), drained walls only).
    NodalVector velocity_against_held_skeleton;
  };
} // namespace MPM

#endif
