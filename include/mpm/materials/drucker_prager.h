#ifndef mpm_materials_drucker_prager_h
#define mpm_materials_drucker_prager_h

#include <deal.II/base/symmetric_tensor.h>

#include <mpm/materials/frictional_strength.h>
#include <mpm/materials/isotropic_elasticity.h>
#include <mpm/materials/material_model.h>

#include <algorithm>
#include <cmath>
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

      /**
       * A Drucker-Prager cone as the return sees it: sqrt(J2) + eta sigma_m
       * <= xi c, the tension cap sigma_m <= T, the edge where the two meet
       * and the dilation slope eta_bar of the flow rule. DruckerPrager's
       * cone follows from its parameters (prepare_cone()); a model whose
       * strength follows its state (the critical state one) makes one per
       * step and returns to it with return_to_cone().
       */
      struct Cone
      {
        double eta            = 0;
        double eta_bar        = 0;
        double xi_c           = 0;
        double tension_cutoff = 0;
        /// sqrt(J2) on the edge where cone and cap meet: xi c - eta T.
        double edge_root_j2 = 0;
        /// 1 / (G + K eta eta_bar): multiplier of a return to the cone per
        /// unit of f_trial (set_multiplier_factor()).
        double multiplier_factor = 0;

        /// multiplier_factor for the shear and bulk moduli @p G and @p K.
        void
        set_multiplier_factor(const double G, const double K)
        {
          multiplier_factor = 1. / (G + K * eta * eta_bar);
        }
      };

      /**
       * The return in the invariants to @p cone with the shear and bulk
       * moduli @p G and @p K: on input the trial mean stress
       * @p mean_stress and @p root_j2 = sqrt(J2) of the trial stress, on
       * output the returned ones (return_invariants()).
       */
      static inline Return
      return_invariants(const Cone  &cone,
                        const double G,
                        const double K,
                        double      &mean_stress,
                        double      &root_j2);

      /**
       * The trial stress @p stress returned to @p cone (in place; radial
       * in the deviatoric plane, so coaxial with the trial stress), with
       * the shear and bulk moduli @p G and @p K. Returns the case and, in
       * @p root_decrease, the decrease of sqrt(J2) (the plastic shear
       * strain's increment times sqrt(3) G; 0 if elastic).
       */
      static inline Return
      return_to_cone(const Cone            &cone,
                     const double           G,
                     const double           K,
                     SymmetricTensor<2, 3> &stress,
                     double                &root_decrease);

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
        return cone.eta;
      }

      /// The cone's intercept xi c: sqrt(J2) at sigma_m = 0.
      double
      cohesion_intercept() const
      {
        return cone.xi_c;
      }

      /// The tension cap T on the mean stress.
      double
      mean_stress_cutoff() const
      {
        return cone.tension_cutoff;
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
        return cone.eta_bar;
      }

      /// The slope and intercept coefficient (eta, xi) of @p fit for the
      /// angle @p angle (radians); with psi in place of phi, eta is eta_bar.
      static std::pair<double, double>
      cone_coefficients(const Fit fit, const double angle);

      /// The plane-strain fit's slope for an angle of tangent @p t:
      /// 3 t / sqrt(9 + 12 t^2), cone_coefficients() without its
      /// trigonometry (for a model whose angle follows its state).
      static double
      plane_strain_slope(const double t)
      {
        return 3 * t / std::sqrt(9 + 12 * t * t);
      }

      /// Divide the strength (FrictionalStrength::reduced()) and fit the
      /// cone to it again.
      void
      set_strength_reduction(const double factor) override;

    private:
      /**
       * Set the cone's coefficients, tension cap and edge from @p strength
       * (the given one or a reduced one).
       */
      void
      prepare_cone(const FrictionalStrength &strength);

      IsotropicElasticity elasticity;
      Fit                 fit = Fit::plane_strain;
      /// The cone of the fit (of the reduced strength), set by
      /// prepare_cone().
      Cone   cone;
      double xi           = 0;
      double bulk_modulus = 0;
      /// 1 / (sqrt(3) G): the equivalent plastic shear strain per unit
      /// decrease of sqrt(J2).
      double shear_strain_per_root_j2 = 0;
    };


    /*
     * Inline, not in the shared library's drucker_prager.cc: an exported
     * function is called through the PLT with its arguments in memory,
     * which made the Drucker-Prager update slower than the Mohr-Coulomb
     * one.
     */
    inline DEAL_II_ALWAYS_INLINE DruckerPrager::Return
    DruckerPrager::return_invariants(const Cone  &cone,
                                     const double G,
                                     const double K,
                                     double      &mean_stress,
                                     double      &root_j2)
    {
      const double mean = mean_stress;
      const double root = root_j2;
      const double f    = root + cone.eta * mean - cone.xi_c;
      const double tol =
        yield_relative_tolerance * (std::abs(mean) + root + cone.xi_c);
      if (f <= tol && mean <= cone.tension_cutoff + tol)
        return Return::elastic;

      if (f > tol)
        {
          // The cone: the elastic return direction in (sigma_m, sqrt(J2))
          // is (K eta_bar, G) per unit multiplier, and f is linear along
          // it.
          const double multiplier = f * cone.multiplier_factor;
          const double new_mean   = mean - K * cone.eta_bar * multiplier;
          if (new_mean <= cone.tension_cutoff)
            {
              mean_stress = new_mean;
              // Non-negative but for rounding: new_mean <= T <= apex.
              root_j2 = std::max(0., root - G * multiplier);
              return Return::cone;
            }
        }

      // The cone return would cross the cap (or only the cap is violated):
      // the mean stress goes to T, the deviator stays if it fits under the
      // cone there, else it shrinks to the edge (the apex for T = c
      // cot(phi), where a hydrostatic trial stress counts as an apex
      // return). Both multipliers of the edge are then non-negative: the
      // cone's because root >= edge_root_j2, the cap's because the cone
      // return alone would have ended above T.
      mean_stress = cone.tension_cutoff;
      if (root < cone.edge_root_j2)
        return Return::tension_cap;
      root_j2 = cone.edge_root_j2;
      return Return::cap_edge;
    }


    inline DEAL_II_ALWAYS_INLINE DruckerPrager::Return
                                 DruckerPrager::return_to_cone(const Cone            &cone,
                                  const double           G,
                                  const double           K,
                                  SymmetricTensor<2, 3> &stress,
                                  double                &root_decrease)
    {
      // The invariants written out: deal.II's deviator() and
      // second_invariant() build temporaries, and this is the whole cost
      // of an elastic step.
      const SymmetricTensor<2, 3> &trial = stress;
      const double mean = (trial[0][0] + trial[1][1] + trial[2][2]) * (1. / 3.);
      const double d00  = trial[0][0] - mean;
      const double d11  = trial[1][1] - mean;
      const double d22  = trial[2][2] - mean;
      const double j2   = 0.5 * (d00 * d00 + d11 * d11 + d22 * d22) +
                        trial[0][1] * trial[0][1] + trial[0][2] * trial[0][2] +
                        trial[1][2] * trial[1][2];
      const double root = std::sqrt(j2);

      double       new_mean = mean, new_root = root;
      const Return result = return_invariants(cone, G, K, new_mean, new_root);
      root_decrease       = 0;
      if (result == Return::elastic)
        return result;

      // The returned deviator is the trial one scaled (radial return in
      // the deviatoric plane), so the stress stays coaxial with the trial
      // stress. root = 0 only for a purely hydrostatic trial stress, whose
      // deviator is zero anyway.
      const double scale = root > 0 ? new_root / root : 0.;
      stress[0][1] *= scale;
      stress[0][2] *= scale;
      stress[1][2] *= scale;
      stress[0][0]  = new_mean + scale * d00;
      stress[1][1]  = new_mean + scale * d11;
      stress[2][2]  = new_mean + scale * d22;
      root_decrease = root - new_root;
      return result;
    }
  } // namespace MaterialModels
} // namespace MPM

#endif
