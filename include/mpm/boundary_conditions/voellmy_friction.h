#ifndef mpm_boundary_conditions_voellmy_friction_h
#define mpm_boundary_conditions_voellmy_friction_h

#include <mpm/boundary_conditions/basal_law.h>

namespace MPM
{
  /**
   * 'Basal law = voellmy': tau = mu sigma_n + rho g v^2 / xi (Voellmy
   * 1955, as used for snow avalanches and debris flows, e.g. RAMMS): the
   * Coulomb part plus a turbulent drag growing with the square of the
   * sliding speed v, with xi (m/s^2) the turbulence coefficient (typically
   * 100-2000 m/s^2 for debris flows; smaller is more drag).
   *
   * At a sliding wall node the drag per unit mass is
   * k v^2, k = g (A_i / V_i) / xi (WallNodeGeometry: the density cancels,
   * rho_i V_i being the node's lumped mass), integrated by backward Euler
   * over the step: v' = v - dt k v'^2, i.e. v' = 2 v / (1 + sqrt(1 + 4 dt k
   * v)): never negative, stable at any time step.
   *
   * A rigid block of thickness h on a plane at theta (mu < tan theta)
   * obeys dv/dt = a - g v^2 / (xi h), a = g (sin theta - mu cos theta),
   * and tends to the terminal speed v_inf = sqrt(a xi h / g):
   * v = v_inf tanh(t / T), s = v_inf T ln cosh(t / T), T = v_inf / a.
   */
  template <int dim>
  class VoellmyFriction : public BasalLaw<dim>
  {
  public:
    /// 'Turbulence coefficient' xi.
    static void
    declare_parameters(ParameterHandler &prm);

    VoellmyFriction(ParameterHandler &prm, const double mu);

    /// For unit tests: the law with @p mu and @p xi.
    VoellmyFriction(const double mu, const double xi);

    bool
    rate_dependent() const override
    {
      return true;
    }

    double
    sliding_speed(const double            speed,
                  const double            dt,
                  const WallNodeGeometry &node) const override;

    std::pair<double, double>
    rigid_block_motion(const double t,
                       const double g,
                       const double theta,
                       const double thickness) const override;

    std::string
    description() const override;

  private:
    double xi;
  };
} // namespace MPM

#endif
