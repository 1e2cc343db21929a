#ifndef mpm_solver_step_scheme_h
#define mpm_solver_step_scheme_h

#include <deal.II/base/parameter_handler.h>

#include <mpm/base/plugin_registry.h>

#include <memory>
#include <string>

namespace MPM
{
  using namespace dealii;

  /**
   * The operations of one time step that a StepScheme puts in order: the
   * particle-grid passes, the nodal update and the stress update, as the
   * Simulator implements them (doc/algorithm.md). The Simulator prepares
   * the step before them (the weights, the wall contact, the time step)
   * and relocates the points after them; what lies between is the
   * scheme's.
   */
  class StepOperations
  {
  public:
    /// The two nodal velocities of a step.
    enum class NodalVelocity
    {
      /// p / m of the momenta on the grid (before the nodal update, or
      /// remapped from the updated points).
      brought,
      /// After the nodal update (forces, friction, wall constraints).
      updated
    };

    virtual ~StepOperations() = default;

    /// Particle to grid: mass and momentum, and with @p with_forces the
    /// internal and gravity forces from the points' stress now.
    virtual void
    map_mass_and_momentum(const bool with_forces) = 0;

    /// Particle to grid: the forces alone (after a stress update).
    virtual void
    map_forces() = 0;

    /// The nodal velocity p / m of the momenta on the grid, constrained
    /// for the strain rate, into @p target.
    virtual void
    compute_nodal_velocity(const NodalVelocity target) = 0;

    /// The points' stress, strain, volume and state from the strain rate
    /// of the nodal velocity @p source (non-local variables averaged
    /// first); with @p set_affine, APIC's affine matrix from the same
    /// velocity gradient.
    virtual void
    update_stress(const NodalVelocity source, const bool set_affine) = 0;

    /// The transfer scheme's filter of the brought velocity (XPIC), if it
    /// has one.
    virtual void
    filter_brought_velocity() = 0;

    /// Forces, basal laws and wall constraints: the updated nodal
    /// velocity from the brought one.
    virtual void
    update_nodal_kinematics() = 0;

    /// Grid to particle: the points' velocity and position; with
    /// @p remap_momentum their new momenta to the grid again (MUSL).
    virtual void
    update_points_from_grid(const bool remap_momentum) = 0;

    /// Whether the transfer scheme keeps an affine matrix per point
    /// (APIC).
    virtual bool
    has_affine_transfer() const = 0;
  };


  /**
   * When in a step the stress is updated, and from which velocity: the
   * order of one step's operations ('Time stepping/Update scheme'). Each
   * scheme is a plugin in its own file (source/solver/step_schemes/),
   * registered by name (MPM_REGISTER_STEP_SCHEME); a new one (a two-phase
   * step, an implicit stress update) is added beside them without touching
   * the Simulator (doc/extending.md).
   */
  class StepScheme
  {
  public:
    virtual ~StepScheme() = default;

    /// One step's operations, in the scheme's order.
    virtual void
    advance(StepOperations &operations) const = 0;

    /// Whether the stress is updated from the velocity remapped from the
    /// updated points (MUSL), the velocity from which APIC's affine matrix
    /// is then taken as well.
    virtual bool
    updates_stress_from_remap() const
    {
      return false;
    }
  };


  /// The registry of step schemes: a creator receives the scheme's
  /// subsection (if it declared parameters).
  using StepSchemeRegistry = PluginRegistry<StepScheme>;
} // namespace MPM

/**
 * Register the step scheme @p classname (a constructor taking the
 * ParameterHandler; no parameters of its own yet) under @p name.
 */
#define MPM_REGISTER_STEP_SCHEME(classname, name, description)   \
  MPM_REGISTER_PLUGIN(MPM::StepSchemeRegistry,                   \
                      name,                                      \
                      description,                               \
                      nullptr,                                   \
                      [](dealii::ParameterHandler &prm) {        \
                        return std::unique_ptr<MPM::StepScheme>( \
                          std::make_unique<classname>(prm));     \
                      })

#endif
