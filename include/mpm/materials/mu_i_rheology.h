#ifndef mpm_materials_mu_i_rheology_h
#define mpm_materials_mu_i_rheology_h

#include <mpm/materials/isotropic_elasticity.h>
#include <mpm/materials/material_model.h>

namespace MPM
{
  namespace MaterialModels
  {
    /**
     * Dense granular flow with rate-dependent friction, the mu(I) rheology
     * (GDR MiDi 2004; Jop, Forterre and Pouliquen 2006) in an elastic -
     * viscoplastic Drucker-Prager form ("mu(I)" in the parameter file).
     *
     * Why: a rate-independent friction (Mohr-Coulomb) stops a granular
     * flow as soon as the driving stress falls below its one friction
     * limit. Real grains resist more when sheared fast (inertial number
     * I = gamma_dot d / sqrt(p / rho_s) large) and less as they slow down,
     * which changes how long a flow takes to come to rest (doc/flume.md,
     * "Time to rest").
     *
     * The update: elastic trial stress; with p = -tr(sigma)/3 (compression
     * positive) and tau = sqrt(s : s / 2) of its deviator s:
     * - p <= 0: the grains separate, sigma = 0 (no cohesion, no tension);
     * - tau <= mu_s p: elastic;
     * - otherwise the deviator is scaled back along itself (no dilation)
     *   by the plastic shear strain increment dgamma that solves
     *   tau - G dgamma = mu(I) p, I = (dgamma / dt) d / sqrt(p / rho_s),
     *   mu(I) = mu_s + (mu_2 - mu_s) I / (I_0 + I): the friction of the
     *   shear rate the step produces, a scalar equation whose left side
     *   minus its right decreases strictly in dgamma (Newton from the rate-
     *   independent solution, which brackets it).
     * In steady simple shear at rate gamma_dot this gives tau / p =
     * mu(I(gamma_dot)) (unit test). With mu_2 = mu_s it is rate-independent
     * Drucker-Prager with tau / p <= mu_s (a circular cone, not the
     * Mohr-Coulomb hexagon: in simple shear tan(phi_s) = mu_s is the ratio
     * of shear to mean stress, not of shear to normal stress on the plane).
     *
     * State: the accumulated plastic shear strain and the inertial number
     * of the last step (output).
     */
    class MuIRheology : public MaterialModel
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm) override;

      void
      update_stress(const SymmetricTensor<2, 3> &strain_increment,
                    SymmetricTensor<2, 3>       &stress,
                    const ArrayView<double>     &state,
                    const double                 time_step) const override;

      double
      strain_energy_density(const SymmetricTensor<2, 3> &stress) const override;

      double
      p_wave_modulus() const override;

      /// 1 - sin(phi_s) (Jaky) with tan(phi_s) = mu_s.
      double
      default_k0() const override;

      unsigned int
      n_state_variables() const override;

      std::vector<std::string>
      state_variable_names() const override;

      void
      initialize_state(const ArrayView<double> &state) const override;

      /// mu(I).
      double
      friction(const double inertial_number) const
      {
        return mu_s + (mu_2 - mu_s) * inertial_number /
                        (reference_inertial_number + inertial_number);
      }

    private:
      IsotropicElasticity elasticity;
      double              mu_s                      = 0;
      double              mu_2                      = 0;
      double              reference_inertial_number = 0;
      double              grain_diameter            = 0;
      double              grain_density             = 0;
    };
  } // namespace MaterialModels
} // namespace MPM

#endif
