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
      bulk_modulus = elasticity.lambda + 2. / 3. * elasticity.shear_modulus;
      prepare_cone(given_strength);
      shear_strain_per_root_j2 =
        1. / (std::sqrt(3.) * elasticity.shear_modulus);
    }


    void
    DruckerPrager::prepare_cone(const FrictionalStrength &strength)
    {
      std::tie(cone.eta, xi) = cone_coefficients(fit, strength.friction_angle);
      cone.eta_bar = cone_coefficients(fit, strength.dilation_angle).first;
      cone.xi_c    = xi * strength.cohesion;

      // xi c / eta is the apex as the return sees it (equal to c cot(phi)
      // up to rounding); clamping to it makes the edge radius below
      // non-negative and zero at the apex.
      cone.tension_cutoff =
        std::min(strength.tension_cutoff, cone.xi_c / cone.eta);
      cone.edge_root_j2 =
        std::max(0., cone.xi_c - cone.eta * cone.tension_cutoff);
      cone.set_multiplier_factor(elasticity.shear_modulus, bulk_modulus);
    }


    void
    DruckerPrager::set_strength_reduction(const double factor)
    {
      Assert(factor > 0, ExcMessage("The strength reduction factor must be > 0."));
      prepare_cone(given_strength.reduced(factor));
    }


    DruckerPrager::Return
    DruckerPrager::return_invariants(double &mean_stress,
                                     double &root_j2) const
    {
      return return_invariants(
        cone, elasticity.shear_modulus, bulk_modulus, mean_stress, root_j2);
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
      elasticity.add_stress_increment(strain_increment, stress);
      double root_decrease = 0;
      if (return_to_cone(cone,
                         elasticity.shear_modulus,
                         bulk_modulus,
                         stress,
                         root_decrease) == Return::elastic)
        return;
      // The deviatoric plastic strain is the deviatoric stress change over
      // 2 G, of norm sqrt(2) (root - new_root) / (2 G).
      state[0] += root_decrease * shear_strain_per_root_j2;
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
