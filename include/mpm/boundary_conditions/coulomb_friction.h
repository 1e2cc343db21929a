#ifndef mpm_boundary_conditions_coulomb_friction_h
#define mpm_boundary_conditions_coulomb_friction_h

#include <mpm/boundary_conditions/basal_law.h>

namespace MPM
{
  /**
   * 'Basal law = coulomb': tau = mu sigma_n, the rate-independent part
   * alone (BasalLaw). A rigid block on a plane inclined at theta slides
   * with a = g (sin theta - mu cos theta) while mu < tan theta, and stays
   * at rest otherwise.
   */
  template <int dim>
  class CoulombFriction : public BasalLaw<dim>
  {
  public:
    /// No parameters besides the boundary's 'Friction coefficient'.
    static void
    declare_parameters(ParameterHandler &prm);

    CoulombFriction(ParameterHandler &prm, const double mu);

    /// For unit tests: the law with coefficient @p mu.
    explicit CoulombFriction(const double mu);

    std::pair<double, double>
    rigid_block_motion(const double t,
                       const double g,
                       const double theta,
                       const double thickness) const override;

    std::string
    description() const override;
  };
} // namespace MPM

#endif
