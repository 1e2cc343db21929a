#include <mpm/base/input_error.h>
#include <mpm/base/plugin_registry.h>
#include <mpm/base/units.h>
#include <mpm/materials/drucker_prager.h>
#include <mpm/materials/frictional_strength.h>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace MPM
{
  namespace MaterialModels
  {
    namespace
    {
      std::string
      drucker_prager_parameter(const std::string &entry)
      {
        return "drucker prager/" + entry;
      }
    } // namespace


    std::pair<double, double>
    DruckerPrager::cone_coefficients(const Fit fit, const double angle)
    {
      const double s = std::sin(angle);
      const double c = std::cos(angle);
      switch (fit)
        {
          case Fit::compression:
            return {6 * s / (std::sqrt(3.) * (3 - s)),
                    6 * c / (std::sqrt(3.) * (3 - s))};
          case Fit::extension:
            return {6 * s / (std::sqrt(3.) * (3 + s)),
                    6 * c / (std::sqrt(3.) * (3 + s))};
          case Fit::plane_strain:
          default:
            {
              // 3 tan / sqrt(9 + 12 tan^2) multiplied through by cos, so
              // that phi near 90 degrees loses no digits.
              const double root = std::sqrt(9 * c * c + 12 * s * s);
              return {3 * s / root, 3 * c / root};
            }
        }
    }


    void
    DruckerPrager::declare_parameters(ParameterHandler &prm)
    {
      IsotropicElasticity::declare_parameters(prm);
      prm.declare_entry("Friction angle",
                        "30",
                        Patterns::Double(0, 90),
                        "Internal friction angle phi in degrees, in (0, 90), "
                        "of the Mohr-Coulomb material the cone is fitted to.");
      prm.declare_entry(
        "Dilation angle",
        "0",
        Patterns::Double(0, 90),
        "Dilation angle psi in degrees, in [0, friction angle]; 0 gives "
        "plastic shearing without volume change (critical state sand), "
        "psi = phi associated flow. The dilation slope eta_bar is eta of "
        "the same fit with psi in place of phi.");
      prm.declare_entry("Cohesion",
                        "0",
                        Patterns::Double(0),
                        "Cohesion c in Pa, >= 0; 0 for dry sand.");
      prm.declare_entry(
        "Tension cutoff",
        "0",
        Patterns::Double(0),
        "The largest mean stress tr(sigma) / 3 the material carries, in Pa "
        "(tension positive), >= 0 and at most c cot(phi), the apex of the "
        "cone; 0 for a cohesionless material.");
      prm.declare_entry(
        "Fit to Mohr-Coulomb",
        "plane strain",
        Patterns::Selection("compression|extension|plane strain"),
        "Which Mohr-Coulomb strength the cone reproduces. 'compression': "
        "the outer cone, the Mohr-Coulomb strength in triaxial compression "
        "(stronger elsewhere). 'extension': the inner cone, the strength in "
        "triaxial extension (weaker elsewhere). 'plane strain': the "
        "Mohr-Coulomb plane-strain collapse load for associated flow, the "
        "default because every 2D run is plane strain.");
    }


    void
    DruckerPrager::parse_parameters(ParameterHandler &prm)
    {
      elasticity.parse_parameters(prm, "drucker prager");
      const double phi_degrees = prm.get_double("Friction angle");
      const double psi_degrees = prm.get_double("Dilation angle");
      const double cohesion    = prm.get_double("Cohesion");
      const double given_tension_cutoff = prm.get_double("Tension cutoff");
      fit = select_choice<Fit>(prm.get("Fit to Mohr-Coulomb"),
                               {{"compression", Fit::compression},
                                {"extension", Fit::extension},
                                {"plane strain", Fit::plane_strain}},
                               drucker_prager_parameter("Fit to Mohr-Coulomb"));
      check_frictional_strength("drucker prager",
                                phi_degrees,
                                psi_degrees,
                                cohesion,
                                given_tension_cutoff,
                                "the apex of the Drucker-Prager cone");

      given_strength.friction_angle = phi_degrees * degree;
      given_strength.dilation_angle = psi_degrees * degree;
      given_strength.cohesion       = cohesion;
      given_strength.tension_cutoff = given_tension_cutoff;
      prepare_cone(given_strength);

      bulk_modulus = elasticity.lambda + 2. / 3. * elasticity.shear_modulus;
      cone_multiplier_factor =
        1. / (elasticity.shear_modulus + bulk_modulus * eta * eta_bar);
      shear_strain_per_root_j2 =
        1. / (std::sqrt(3.) * elasticity.shear_modulus);
    }


    void
    DruckerPrager::prepare_cone(const FrictionalStrength &strength)
    {
      std::tie(eta, xi) = cone_coefficients(fit, strength.friction_angle);
      eta_bar = cone_coefficients(fit, strength.dilation_angle).first;
      xi_c    = xi * strength.cohesion;

      // xi c / eta is the apex as the return sees it (equal to c cot(phi)
      // up to rounding); clamping to it makes the edge radius below
      // non-negative and zero at the apex.
      tension_cutoff = std::min(strength.tension_cutoff, xi_c / eta);
      edge_root_j2   = std::max(0., xi_c - eta * tension_cutoff);
    }


    void
    DruckerPrager::set_strength_reduction(const double factor)
    {
      Assert(factor > 0, ExcMessage("The strength reduction factor must be > 0."));
      prepare_cone(given_strength.reduced(factor));
      cone_multiplier_factor =
        1. / (elasticity.shear_modulus + bulk_modulus * eta * eta_bar);
    }


    inline DEAL_II_ALWAYS_INLINE DruckerPrager::Return
    DruckerPrager::return_invariants_inline(double &mean_stress,
                                            double &root_j2) const
    {
      const double mean = mean_stress;
      const double root = root_j2;
      const double f    = root + eta * mean - xi_c;
      const double tol =
        yield_relative_tolerance * (std::abs(mean) + root + xi_c);
      if (f <= tol && mean <= tension_cutoff + tol)
        return Return::elastic;

      if (f > tol)
        {
          // The cone: the elastic return direction in (sigma_m, sqrt(J2))
          // is (K eta_bar, G) per unit multiplier, and f is linear along
          // it.
          const double multiplier = f * cone_multiplier_factor;
          const double new_mean =
            mean - bulk_modulus * eta_bar * multiplier;
          if (new_mean <= tension_cutoff)
            {
              mean_stress = new_mean;
              // Non-negative but for rounding: new_mean <= T <= apex.
              root_j2 = std::max(0.,
                                 root - elasticity.shear_modulus * multiplier);
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
      mean_stress = tension_cutoff;
      if (root < edge_root_j2)
        return Return::tension_cap;
      root_j2 = edge_root_j2;
      return Return::cap_edge;
    }


    DruckerPrager::Return
    DruckerPrager::return_invariants(double &mean_stress,
                                     double &root_j2) const
    {
      return return_invariants_inline(mean_stress, root_j2);
    }


    void
    DruckerPrager::update_stress(const SymmetricTensor<2, 3> &strain_increment,
                                 SymmetricTensor<2, 3>       &stress,
                                 const ArrayView<double>     &state,
                                 const double) const
    {
      AssertIndexRange(0, state.size());
      // The same elastic predictor as LinearElastic, so that an elastic
      // step gives the same stress to the last bit.
      SymmetricTensor<2, 3> trial = stress;
      elasticity.add_stress_increment(strain_increment, trial);

      // The invariants written out: deal.II's deviator() and
      // second_invariant() build temporaries, and this is the whole cost
      // of an elastic step.
      const double mean = (trial[0][0] + trial[1][1] + trial[2][2]) * (1. / 3.);
      const double d00  = trial[0][0] - mean;
      const double d11  = trial[1][1] - mean;
      const double d22  = trial[2][2] - mean;
      const double j2   = 0.5 * (d00 * d00 + d11 * d11 + d22 * d22) +
                        trial[0][1] * trial[0][1] + trial[0][2] * trial[0][2] +
                        trial[1][2] * trial[1][2];
      const double root = std::sqrt(j2);

      double new_mean = mean, new_root = root;
      if (return_invariants_inline(new_mean, new_root) == Return::elastic)
        {
          stress = trial;
          return;
        }

      // The returned deviator is the trial one scaled (radial return in
      // the deviatoric plane), so the stress stays coaxial with the trial
      // stress. root = 0 only for a purely hydrostatic trial stress, whose
      // deviator is zero anyway.
      const double scale = root > 0 ? new_root / root : 0.;
      stress[0][0]       = new_mean + scale * d00;
      stress[1][1]       = new_mean + scale * d11;
      stress[2][2]       = new_mean + scale * d22;
      stress[0][1]       = scale * trial[0][1];
      stress[0][2]       = scale * trial[0][2];
      stress[1][2]       = scale * trial[1][2];

      // The deviatoric plastic strain is the deviatoric stress change over
      // 2 G, of norm sqrt(2) (root - new_root) / (2 G).
      state[0] += (root - new_root) * shear_strain_per_root_j2;
    }


    double
    DruckerPrager::strain_energy_density(
      const SymmetricTensor<2, 3> &stress) const
    {
      return elasticity.strain_energy_density(stress);
    }


    double
    DruckerPrager::p_wave_modulus() const
    {
      return elasticity.p_wave_modulus();
    }
  } // namespace MaterialModels
} // namespace MPM

MPM_REGISTER_MATERIAL_MODEL(
  MPM::MaterialModels::DruckerPrager,
  "drucker prager",
  "Elastic - perfectly plastic Drucker-Prager cone fitted to Mohr-Coulomb, "
  "with a tension cap on the mean stress and non-associated flow (plane "
  "strain in 2D).")
