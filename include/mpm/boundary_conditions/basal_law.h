#ifndef mpm_boundary_conditions_basal_law_h
#define mpm_boundary_conditions_basal_law_h

#include <deal.II/base/parameter_handler.h>

#include <mpm/base/plugin_registry.h>
#include <mpm/boundary_conditions/normal_stress_memory.h>

#include <memory>
#include <string>
#include <utility>

namespace MPM
{
  using namespace dealii;

  /**
   * What a basal law may know of one wall node besides its velocity: the
   * share of the wall the node stands for and the gravity that the law's
   * parameters may refer to.
   */
  struct WallNodeGeometry
  {
    /**
     * A_i / V_i: the node's share of the wall area, A_i = int_wall N_i dA,
     * over its share of the mesh volume, V_i = int N_i dV (over the cells
     * at the node). A traction t on the wall acts on the node as the force
     * A_i t; the node's lumped mass is m_i = rho_i V_i with rho_i the
     * material's density where the node's cells are full and less where
     * they are partly filled. So A_i t / m_i = (A_i / V_i) t / rho_i: a
     * traction proportional to the density, as Voellmy's rho g v^2 / xi,
     * acts on the node per unit mass through A_i / V_i alone, and its
     * total over the wall's nodes is that traction over the wetted area.
     * Zero where no law needs it.
     */
    double area_per_volume = 0;
    /// |g| (m/s^2).
    double gravity = 0;
  };


  /**
   * A basal law ('Boundary conditions/NAME/Basal law'): the tangential
   * resistance of a frictional wall (Type = friction) to the material
   * sliding on it, applied in each wall node's frame by
   * WallFriction::frictional_acceleration(). It has two parts, integrated
   * by backward Euler over a step, so that the resistance never reverses
   * the motion whatever the time step:
   *
   *  - the rate-independent part, Coulomb friction mu sigma_n: the
   *    tangential velocity change per unit mass the wall can exert in a
   *    step, mu r dt, with r > 0 the normal reaction per unit mass. A node
   *    whose trial tangential speed (without the wall's resistance) is
   *    below it sticks; above, it slides on with its speed reduced by it.
   *  - an optional rate-dependent part (rate_dependent()), which then
   *    acts on the sliding node's remaining speed: sliding_speed().
   *
   * Every law is a plugin: a class derived from this one in its own file
   * in source/boundary_conditions/, registered at its end with
   * MPM_REGISTER_BASAL_LAW. Its parameters are declared in its own
   * subsection of the boundary's subsection; the Coulomb coefficient mu is
   * the boundary's 'Friction coefficient', shared by every law.
   */
  template <int dim>
  class BasalLaw
  {
  public:
    explicit BasalLaw(const double friction_coefficient)
      : mu(friction_coefficient)
    {}

    virtual ~BasalLaw() = default;

    /// mu, the coefficient of the rate-independent (Coulomb) part.
    double
    friction_coefficient() const
    {
      return mu;
    }

    /**
     * The tangential velocity change per unit mass the rate-independent
     * part can exert: mu @p reaction @p dt (@p reaction the normal
     * reaction per unit mass; at a 3D edge node the normal impulse per
     * unit mass with @p dt = 1).
     */
    double
    static_capacity(const double reaction, const double dt) const
    {
      return mu * reaction * dt;
    }

    /// How the normal force of static_capacity() follows the wall's
    /// present one (the boundary's 'Normal stress memory length').
    const NormalStressMemory &
    normal_stress_memory() const
    {
      return memory;
    }

    void
    set_normal_stress_memory(const NormalStressMemory &m)
    {
      memory = m;
    }

    /// Whether sliding_speed() does anything (then the wall nodes'
    /// WallNodeGeometry is computed).
    virtual bool
    rate_dependent() const
    {
      return false;
    }

    /**
     * The tangential speed of a sliding node at the end of the step under
     * the rate-dependent part, by backward Euler, from @p speed, its speed
     * after the rate-independent part (> 0). Never negative and never
     * above @p speed.
     */
    virtual double
    sliding_speed(const double            speed,
                  const double            dt,
                  const WallNodeGeometry &node) const
    {
      (void)dt;
      (void)node;
      return speed;
    }

    /**
     * The reference solution of this law: speed and distance after a time
     * @p t of a rigid block of thickness @p thickness (normal to the bed)
     * released from rest on a plane inclined at @p theta (radians) under
     * gravity @p g. Used by the 'sliding block' postprocessor.
     */
    virtual std::pair<double, double>
    rigid_block_motion(const double t,
                       const double g,
                       const double theta,
                       const double thickness) const = 0;

    /// One line for reports: the law and its parameters.
    virtual std::string
    description() const = 0;

  protected:
    const double mu;

  private:
    NormalStressMemory memory;
  };


  /**
   * The registry of basal laws: a creator receives the law's subsection
   * and the boundary's friction coefficient mu.
   */
  template <int dim>
  using BasalLawRegistry = PluginRegistry<BasalLaw<dim>, double>;
} // namespace MPM

/**
 * Register the basal law @p classname (templated on dim, with a static
 * declare_parameters(ParameterHandler &) and a constructor
 * (ParameterHandler &, double mu)) under @p name, for 2D and 3D.
 */
#define MPM_REGISTER_BASAL_LAW(classname, name, description)                \
  MPM_REGISTER_PLUGIN(                                                      \
    MPM::BasalLawRegistry<2>,                                               \
    name,                                                                   \
    description,                                                            \
    &classname<2>::declare_parameters,                                      \
    [](dealii::ParameterHandler &prm, const double mu) {                    \
      return std::unique_ptr<MPM::BasalLaw<2>>(                             \
        std::make_unique<classname<2>>(prm, mu));                           \
    })                                                                      \
  MPM_REGISTER_PLUGIN(                                                      \
    MPM::BasalLawRegistry<3>,                                               \
    name,                                                                   \
    description,                                                            \
    &classname<3>::declare_parameters,                                      \
    [](dealii::ParameterHandler &prm, const double mu) {                    \
      return std::unique_ptr<MPM::BasalLaw<3>>(                             \
        std::make_unique<classname<3>>(prm, mu));                           \
    })

#endif
