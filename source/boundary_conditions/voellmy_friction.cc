#include <mpm/boundary_conditions/voellmy_friction.h>

#include <cmath>
#include <sstream>

namespace MPM
{
  template <int dim>
  void
  VoellmyFriction<dim>::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Turbulence coefficient",
                      "500",
                      Patterns::Double(0),
                      "xi (m/s^2) of the turbulent term rho g v^2 / xi of "
                      "the basal shear stress: smaller is more drag (debris "
                      "flows and avalanches: 100-2000 m/s^2). Must be > 0.");
  }


  template <int dim>
  VoellmyFriction<dim>::VoellmyFriction(ParameterHandler &prm, const double mu)
    : BasalLaw<dim>(mu)
    , xi(prm.get_double("Turbulence coefficient"))
  {
    std::ostringstream message;
    message << "voellmy/Turbulence coefficient must be > 0 (it divides the "
               "turbulent drag), not "
            << xi << ".";
    check_input(xi > 0, message.str());
  }


  template <int dim>
  VoellmyFriction<dim>::VoellmyFriction(const double mu, const double xi)
    : BasalLaw<dim>(mu)
    , xi(xi)
  {}


  template <int dim>
  double
  VoellmyFriction<dim>::sliding_speed(const double            speed,
                                      const double            dt,
                                      const WallNodeGeometry &node) const
  {
    // v' = v - dt k v'^2, the root that is >= 0, in the form without
    // cancellation for small dt k v.
    const double k_dt = dt * node.gravity * node.area_per_volume / xi;
    return 2 * speed / (1 + std::sqrt(1 + 4 * k_dt * speed));
  }


  template <int dim>
  std::pair<double, double>
  VoellmyFriction<dim>::rigid_block_motion(const double t,
                                           const double g,
                                           const double theta,
                                           const double thickness) const
  {
    const double a = g * (std::sin(theta) - this->mu * std::cos(theta));
    if (a <= 0)
      return {0., 0.};
    const double v_inf = std::sqrt(a * xi * thickness / g);
    const double T     = v_inf / a;
    // ln cosh(x) = x + log1p(exp(-2x)) - ln 2: no overflow at large x.
    const double x = t / T;
    return {v_inf * std::tanh(x),
            v_inf * T * (x + std::log1p(std::exp(-2 * x)) - std::log(2.))};
  }


  template <int dim>
  std::string
  VoellmyFriction<dim>::description() const
  {
    std::ostringstream s;
    s << "Voellmy friction, mu = " << this->mu << ", xi = " << xi
      << " m/s^2";
    return s.str();
  }


  template class VoellmyFriction<2>;
  template class VoellmyFriction<3>;
} // namespace MPM

MPM_REGISTER_BASAL_LAW(MPM::VoellmyFriction,
                       "voellmy",
                       "tau = mu sigma_n + rho g v^2 / xi: Coulomb friction "
                       "plus a turbulent drag (subsection 'voellmy': "
                       "'Turbulence coefficient' xi).")
