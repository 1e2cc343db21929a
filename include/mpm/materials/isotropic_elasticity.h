#ifndef mpm_materials_isotropic_elasticity_h
#define mpm_materials_isotropic_elasticity_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <string>

namespace MPM
{
  using namespace dealii;

  /**
   * Isotropic linear elasticity, sigma = lambda tr(eps) I + 2 mu eps, as
   * the material models use it: linear elasticity is all of it, an
   * elastoplastic model its elastic part. One place for the parameters
   * (Young's modulus, Poisson's ratio, with their checks), the stiffness,
   * its inverse and the stored energy.
   */
  struct IsotropicElasticity
  {
    /**
     * Declare "Young's modulus" and "Poisson's ratio" in the current
     * subsection (the model's own).
     */
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Read and check the two entries; error messages name them as
     * "<model>/<entry>".
     */
    void
    parse_parameters(ParameterHandler &prm, const std::string &model);

    /**
     * stress += C : strain, with C : eps = lambda tr(eps) I + 2 mu eps,
     * component by component and without temporaries. Shared by every
     * model's elastic predictor, so that an elastic step of an
     * elasto-plastic model gives the linear elastic stress to the last bit.
     */
    void
    add_stress_increment(const SymmetricTensor<2, 3> &strain,
                         SymmetricTensor<2, 3>       &stress) const
    {
      const double lambda_trace =
        lambda * (strain[0][0] + strain[1][1] + strain[2][2]);
      const double two_mu = 2 * shear_modulus;
      for (unsigned int a = 0; a < 3; ++a)
        {
          stress[a][a] += lambda_trace + two_mu * strain[a][a];
          for (unsigned int b = a + 1; b < 3; ++b)
            stress[a][b] += two_mu * strain[a][b];
        }
    }

    /// C^{-1} : sigma = (1 + nu)/E sigma - nu/E tr(sigma) I.
    SymmetricTensor<2, 3>
    strain(const SymmetricTensor<2, 3> &stress) const
    {
      return (1 + poisson_ratio) / youngs_modulus * stress -
             poisson_ratio / youngs_modulus * trace(stress) *
               unit_symmetric_tensor<3>();
    }

    /// 1/2 sigma : C^{-1} : sigma.
    double
    strain_energy_density(const SymmetricTensor<2, 3> &stress) const
    {
      const double tr = trace(stress);
      return 0.5 * ((1 + poisson_ratio) / youngs_modulus * (stress * stress) -
                    poisson_ratio / youngs_modulus * tr * tr);
    }

    /// lambda + 2 mu: the modulus of the P-wave speed in the CFL condition.
    double
    p_wave_modulus() const
    {
      return lambda + 2 * shear_modulus;
    }

    double youngs_modulus = 0;
    double poisson_ratio  = 0;
    double lambda         = 0;
    double shear_modulus  = 0;
  };
} // namespace MPM

#endif
