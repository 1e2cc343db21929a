#include <mpm/boundary_conditions/coulomb_friction.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace MPM
{
  template <int dim>
  void
  CoulombFriction<dim>::declare_parameters(ParameterHandler &)
  {}


  template <int dim>
  CoulombFriction<dim>::CoulombFriction(ParameterHandler &, const double mu)
    : BasalLaw<dim>(mu)
  {}


  template <int dim>
  CoulombFriction<dim>::CoulombFriction(const double mu)
    : BasalLaw<dim>(mu)
  {}


  template <int dim>
  std::pair<double, double>
  CoulombFriction<dim>::rigid_block_motion(const double t,
                                           const double g,
                                           const double theta,
                                           const double) const
  {
    const double a =
      std::max(0., g * (std::sin(theta) - this->mu * std::cos(theta)));
    return {a * t, 0.5 * a * t * t};
  }


  template <int dim>
  std::string
  CoulombFriction<dim>::description() const
  {
    std::ostringstream s;
    s << "Coulomb friction, mu = " << this->mu;
    return s.str();
  }


  template class CoulombFriction<2>;
  template class CoulombFriction<3>;
} // namespace MPM

MPM_REGISTER_BASAL_LAW(MPM::CoulombFriction,
                       "coulomb",
                       "tau = mu sigma_n (the boundary's 'Friction "
                       "coefficient'): sticks while the tangential force is "
                       "below mu times the normal force.")
