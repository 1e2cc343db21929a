#ifndef mpm_transfer_transfer_scheme_h
#define mpm_transfer_transfer_scheme_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <mpm/base/plugin_registry.h>

#include <memory>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  template <int dim>
  class ParticleGridWeights;
  template <int dim>
  class BoundaryConditions;
  class NodalFields;

  /**
   * A velocity transfer scheme ('Transfer/Scheme'): how point velocities
   * reach the grid and come back, the choice that decides how much kinetic
   * energy the transfers themselves remove (doc/transfers.md). One class
   * per scheme, in its own file in source/transfer/, registered with
   * MPM_REGISTER_TRANSFER_SCHEME: 'flip/pic blend' (FlipPicBlend), 'xpic'
   * (Xpic), 'apic' (Apic).
   *
   * The hooks a scheme has on the step (doc/algorithm.md):
   *  - slots on the points (n_point_properties(), after the material
   *    state), completed at the start of a run by initialize_points();
   *  - its own nodal fields (add_nodal_fields());
   *  - a filter of the velocity the points brought to the nodes, before
   *    the nodal update (filter_brought_velocity());
   *  - the point update: the FLIP share of the blend (flip_fraction());
   *    APIC's affine part is applied by the particle-grid weights, which
   *    ask Apic for its arithmetic.
   *
   * No scheme touches the nodal update: the velocity the points bring
   * (after a filter) is what the walls and friction act on, and the points
   * receive only the constrained end-of-step grid velocity. So no scheme
   * lets material cross a wall or slide more than friction allows.
   *
   * A scheme's parameters are entries of the subsection 'Transfer'
   * (declared by VelocityTransfer, shared among the schemes); its creator
   * reads them there.
   */
  template <int dim>
  class TransferScheme
  {
  public:
    virtual ~TransferScheme() = default;

    /**
     * The share of a point's own velocity change the point update keeps
     * (FLIP) for a step of length @p dt; the rest is the interpolated grid
     * velocity (PIC). 0: the point takes the grid velocity.
     */
    virtual double
    flip_fraction(const double dt) const
    {
      (void)dt;
      return 0.;
    }

    /// Property slots the scheme keeps per point.
    virtual unsigned int
    n_point_properties() const
    {
      return 0;
    }

    virtual std::vector<std::string>
    point_property_names() const
    {
      return {};
    }

    /// Register the scheme's own nodal vectors with @p nodal, so that
    /// they follow the partition and are zeroed with the step's fields.
    virtual void
    add_nodal_fields(NodalFields &nodal)
    {
      (void)nodal;
    }

    /// Whether filter_brought_velocity() changes anything.
    virtual bool
    filters_brought_velocity() const
    {
      return false;
    }

    /**
     * Replace the velocity the points brought to the nodes
     * (@p nodal.momentum / mass, and the constrained @p nodal.velocity)
     * before the nodal update, with the step's @p weights and the walls
     * @p boundary_conditions.
     */
    virtual void
    filter_brought_velocity(ParticleGridWeights<dim>       &weights,
                            const BoundaryConditions<dim> &boundary_conditions,
                            NodalFields                   &nodal)
    {
      (void)weights;
      (void)boundary_conditions;
      (void)nodal;
    }

    /**
     * Whether the points carry an affine velocity field v_p + C_p (x - x_p)
     * with C_p (row-major) in the scheme's first dim * dim slots (APIC).
     * What the rest of the code asks of a scheme that does: the point
     * generator writes each point's initial velocity gradient there, MUSL
     * updates the stress from the remapped velocity, the pore water may
     * follow the same affine transfer, and the run's angular momentum adds
     * affine_angular_momentum().
     */
    virtual bool
    carries_affine_velocity() const
    {
      return false;
    }

    /**
     * The angular momentum per unit mass of what a point carries beyond
     * its velocity (APIC: its affine part), read from the scheme's slots
     * @p slots; only called if carries_affine_velocity().
     */
    virtual Tensor<1, 3>
    affine_angular_momentum_of_point(const double *slots) const
    {
      (void)slots;
      return Tensor<1, 3>();
    }

    /// Whether initialize_points() does anything (then the Simulator
    /// prepares the first step's weights for it).
    virtual bool
    initializes_points() const
    {
      return false;
    }

    /**
     * At the start of a run (not on resume): complete the scheme's slots
     * (from @p first_slot) of every point under the first step's
     * @p weights.
     */
    virtual void
    initialize_points(const ParticleGridWeights<dim> &weights,
                      const unsigned int              first_slot) const
    {
      (void)weights;
      (void)first_slot;
    }
  };


  /// The registry of transfer schemes: a creator reads the entries of
  /// 'Transfer'.
  template <int dim>
  using TransferSchemeRegistry = PluginRegistry<TransferScheme<dim>>;
} // namespace MPM

/**
 * Register the transfer scheme @p classname (templated on dim, with a
 * constructor from the ParameterHandler in subsection 'Transfer') under
 * @p name, for 2D and 3D.
 */
#define MPM_REGISTER_TRANSFER_SCHEME(classname, name, description)         \
  MPM_REGISTER_PLUGIN(MPM::TransferSchemeRegistry<2>,                      \
                      name,                                                \
                      description,                                         \
                      nullptr,                                             \
                      [](dealii::ParameterHandler &prm) {                  \
                        return std::unique_ptr<MPM::TransferScheme<2>>(    \
                          std::make_unique<classname<2>>(prm));            \
                      })                                                   \
  MPM_REGISTER_PLUGIN(MPM::TransferSchemeRegistry<3>,                      \
                      name,                                                \
                      description,                                         \
                      nullptr,                                             \
                      [](dealii::ParameterHandler &prm) {                  \
                        return std::unique_ptr<MPM::TransferScheme<3>>(    \
                          std::make_unique<classname<3>>(prm));            \
                      })

#endif
