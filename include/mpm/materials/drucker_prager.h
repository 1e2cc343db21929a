#ifndef mpm_materials_drucker_prager_h
#define mpm_materials_drucker_prager_h

#include <mpm/materials/frictional_strength.h>
#include <mpm/materials/isotropic_elasticity.h>
#include <mpm/materials/material_model.h>

#include <utility>

namespace MPM
{
  namespace MaterialModels
  {
    /**
     * Linear elastic - perfectly plastic Drucker-Prager model with a
     * tension cap on the mean stress and non-associated flow through a
     * dilation angle ("drucker prager" in the parameter file). Plane strain
     * in 2D (the zz stress evolves like the others).
     *
     * With the mean stress sigma_m = tr(sigma) / 3 (tension positive, the
     * sign convention of the code; sigma_m = -p for the pressure p) and
     * J2 = 1/2 s : s of the deviator s, the admissible set is
     *   f = sqrt(J2) + eta sigma_m - xi c <= 0,
     *   sigma_m <= T,
     * a circular cone around the hydrostatic axis with its apex at
     * sigma_m = xi c / eta = c cot(phi), cut by the plane sigma_m = T
     * (0 <= T <= c cot(phi)). The plastic potential of the cone is f with
     * eta_bar (eta with psi in place of phi) and without the constant, so
     * that psi = 0 gives no plastic volume change; the cap flows
     * associatively (purely volumetric: it opens the material).
     *
     * Why a second frictional model beside Mohr-Coulomb: the cone is smooth
     * around the hydrostatic axis, so the return needs only the two
     * invariants (sigma_m, sqrt(J2)) of the trial stress, no principal
     * stresses and no choice among edges and corners; the stress update is
     * cheaper and its result does not depend on how nearly equal two
     * principal stresses are. The price is the fit: a circular cone meets
     * the Mohr-Coulomb pyramid only along some meridians, chosen by 'Fit to
     * Mohr-Coulomb' (de Souza Neto, Peric and Owen, Computational Methods
     * for Plasticity, 2008, section 6.4.3):
     * - compression: the outer cone through the triaxial compression
     *   meridian, eta = 6 sin(phi) / (sqrt(3) (3 - sin(phi))),
     *   xi = 6 cos(phi) / (sqrt(3) (3 - sin(phi))): the Mohr-Coulomb
     *   strength in triaxial compression, more than it elsewhere;
     * - extension: the inner cone through the triaxial extension meridian,
     *   the same with 3 + sin(phi): the Mohr-Coulomb strength in triaxial
     *   extension, less than it elsewhere;
     * - plane strain: eta = 3 tan(phi) / sqrt(9 + 12 tan^2(phi)),
     *   xi = 3 / sqrt(9 + 12 tan^2(phi)): the Mohr-Coulomb plane-strain
     *   collapse load for associated flow (psi = phi). In general a
     *   plane-strain limit has the Mohr circle radius R = k (xi c / eta -
     *   sigma_c), k = eta sqrt(1 - eta_bar^2 / 3) / (1 - eta eta_bar / 3),
     *   against Mohr-Coulomb's k = sin(phi): for psi < phi the cone is
     *   weaker (psi = 0: k = eta, 5 % less sigma_1 / sigma_3 at phi = 30),
     *   and the outer cone is much stronger (no plane-strain limit at all
     *   for phi above 36.9 degrees with associated flow).
     * Every fit puts the apex at c cot(phi), where the Mohr-Coulomb apex
     * lies.
     *
     * The return (de Souza Neto et al., section 8.3.1) is exact and without
     * iterations: for perfect plasticity the cone is a straight line in the
     * (sigma_m, sqrt(J2)) plane and the elastic return direction is
     * (K eta_bar, G) per unit multiplier, so the multiplier of a return to
     * the cone is f_trial / (G + K eta eta_bar). If that return would cross
     * the cap (sigma_m > T) the stress goes to the cap (sigma_m = T, the
     * deviator kept) when its sqrt(J2) fits under the cone there, else to
     * the edge where cone and cap meet (sigma_m = T, sqrt(J2) = xi c -
     * eta T), which is the apex of the cone when T = c cot(phi). The three
     * cases partition the region outside the admissible set, so the first
     * that applies is the answer. The returned deviator is the trial one
     * scaled, so the stress stays coaxial with the trial stress in any
     * dimension.
     *
     * State: the accumulated equivalent plastic shear strain
     * sqrt(2/3 e_p : e_p) (e_p the deviatoric plastic strain increment), as
     * in MohrCoulomb, so that the outputs of both models read alike.
     */
    class DruckerPrager : public FrictionalModel
    {
    public:
      /**
       * Which return a stress update took: what return_invariants() gives
       * back, public so that the unit test can count the cases.
       */
      enum class Return
      {
        elastic,
        /// The smooth cone.
        cone,
        /// The tension cap sigma_m = T inside the cone.
        tension_cap,
        /// The circle where cone and cap meet; the apex if T = c cot(phi).
        cap_edge
      };

      /// How the cone is fitted to the Mohr-Coulomb pyramid.
      enum class Fit
      {
        compression,
        extension,
        plane_strain
      };

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

      /**
       * The return in the invariants: on input the trial mean stress
       * @p mean_stress and @p root_j2 = sqrt(J2) of the trial stress, on
       * output the returned ones. The returned deviator is the trial one
       * times root_j2 (output) / root_j2 (input).
       */
      Return
      return_invariants(double &mean_stress, double &root_j2) const;

      /// The cone's slope eta (of the chosen fit).
      double
      friction_coefficient() const
      {
        return eta;
      }

      /// The cone's intercept xi c: sqrt(J2) at sigma_m = 0.
      double
      cohesion_intercept() const
      {
        return xi_c;
      }

      /// The tension cap T on the mean stress.
      double
      mean_stress_cutoff() const
      {
        return tension_cutoff;
      }

      /// The cone's intercept coefficient xi and the dilation slope
      /// eta_bar, for a test's closed forms.
      double
      cohesion_coefficient() const
      {
        return xi;
      }

      double
      dilation_coefficient() const
      {
        return eta_bar;
      }

      /// The slope and intercept coefficient (eta, xi) of @p fit for the
      /// angle @p angle (radians); with psi in place of phi, eta is eta_bar.
      static std::pair<double, double>
      cone_coefficients(const Fit fit, const double angle);

      /// Divide the strength (FrictionalStrength::reduced()) and fit the
      /// cone to it again.
      void
      set_strength_reduction(const double factor) override;

    private:
      /**
       * The body of return_invariants(), inlined into update_stress(): the
       * public function is exported from the shared library and so called
       * through the PLT with its arguments in memory, which made the
       * Drucker-Prager update slower than the Mohr-Coulomb one.
       */
      inline Return
      return_invariants_inline(double &mean_stress, double &root_j2) const;

      /**
       * Set the cone's coefficients, tension cap and edge from @p strength
       * (the given one or a reduced one).
       */
      void
      prepare_cone(const FrictionalStrength &strength);

      IsotropicElasticity elasticity;
      Fit                 fit            = Fit::plane_strain;
      /// The tension cap on the mean stress (of the reduced strength).
      double tension_cutoff = 0;

      /// eta, xi, eta_bar of the fit and xi c, set by prepare_cone().
      double eta     = 0;
      double xi      = 0;
      double eta_bar = 0;
      double xi_c    = 0;
      /// sqrt(J2) on the edge where cone and cap meet: xi c - eta T.
      double edge_root_j2 = 0;
      double bulk_modulus = 0;
      /// 1 / (G + K eta eta_bar): multiplier of a return to the cone per
      /// unit of f_trial.
      double cone_multiplier_factor = 0;
      /// 1 / (sqrt(3) G): the equivalent plastic shear strain per unit
      /// decrease of sqrt(J2).
      double shear_strain_per_root_j2 = 0;
    };
  } // namespace MaterialModels
} // namespace MPM

#endif
