#include <mpm/base/input_error.h>
#include <mpm/base/units.h>
#include <mpm/materials/mu_i_rheology.h>

#include <cmath>

namespace MPM
{
  namespace MaterialModels
  {
    namespace
    {
      std::string
      mu_i_parameter(const std::string &entry)
      {
        return "mu(I)/" + entry;
      }
    } // namespace


    void
    MuIRheology::declare_parameters(ParameterHandler &prm)
    {
      IsotropicElasticity::declare_parameters(prm);
      prm.declare_entry("Static friction angle",
                        "20.9",
                        Patterns::Double(0, 90),
                        "phi_s in degrees, mu_s = tan(phi_s): the friction of "
                        "slow (quasi-static) shearing. The default is Jop, "
                        "Forterre and Pouliquen's (2006) glass beads.");
      prm.declare_entry("Dynamic friction angle",
                        "32.76",
                        Patterns::Double(0, 90),
                        "phi_2 in degrees, mu_2 = tan(phi_2) >= mu_s: the "
                        "friction approached at large inertial numbers.");
      prm.declare_entry("Reference inertial number",
                        "0.279",
                        Patterns::Double(0),
                        "I_0 > 0: the inertial number at which mu is halfway "
                        "between mu_s and mu_2.");
      prm.declare_entry("Grain diameter",
                        "0.0005",
                        Patterns::Double(0),
                        "d in m, > 0.");
      prm.declare_entry("Grain density",
                        "2450",
                        Patterns::Double(0),
                        "rho_s in kg/m^3, > 0: the density of the grains "
                        "themselves (not the bulk density of the material), "
                        "in I = gamma_dot d / sqrt(p / rho_s).");
    }


    void
    MuIRheology::parse_parameters(ParameterHandler &prm)
    {
      elasticity.parse_parameters(prm, "mu(I)");
      const double phi_s = prm.get_double("Static friction angle");
      const double phi_2 = prm.get_double("Dynamic friction angle");
      check_input(phi_s > 0 && phi_s < 90,
                  mu_i_parameter("Static friction angle") + " = " +
                    std::to_string(phi_s) + " degrees: must lie in (0, 90).");
      check_input(phi_2 >= phi_s && phi_2 < 90,
                  mu_i_parameter("Dynamic friction angle") + " = " +
                    std::to_string(phi_2) +
                    " degrees: must lie in [static friction angle = " +
                    std::to_string(phi_s) + ", 90).");
      mu_s                      = std::tan(phi_s * degree);
      mu_2                      = std::tan(phi_2 * degree);
      reference_inertial_number = prm.get_double("Reference inertial number");
      grain_diameter            = prm.get_double("Grain diameter");
      grain_density             = prm.get_double("Grain density");
      check_input(reference_inertial_number > 0,
                  mu_i_parameter("Reference inertial number") + " = " +
                    std::to_string(reference_inertial_number) +
                    ": must be > 0.");
      check_input(grain_diameter > 0,
                  mu_i_parameter("Grain diameter") + " = " +
                    std::to_string(grain_diameter) + " m: must be > 0.");
      check_input(grain_density > 0,
                  mu_i_parameter("Grain density") + " = " +
                    std::to_string(grain_density) + " kg/m^3: must be > 0.");
    }


    void
    MuIRheology::update_stress(const SymmetricTensor<2, 3> &strain_increment,
                               SymmetricTensor<2, 3>       &stress,
                               const ArrayView<double>     &state,
                               const double                 time_step) const
    {
      AssertIndexRange(1, state.size());
      SymmetricTensor<2, 3> trial = stress;
      elasticity.add_stress_increment(strain_increment, trial);
      const double p = -trace(trial) / 3;
      state[1]       = 0;
      if (!(p > 0))
        {
          // Separated grains carry nothing.
          stress = SymmetricTensor<2, 3>();
          return;
        }
      const SymmetricTensor<2, 3> s   = deviator(trial);
      const double                tau = std::sqrt(0.5 * (s * s));
      if (tau <= mu_s * p)
        {
          stress = trial;
          return;
        }
      // tau - G dgamma - mu(k dgamma) p = 0 for dgamma in (0, upper]: the
      // left side g is convex and decreasing, g(0) > 0 and g(upper) <= 0 at
      // the rate-independent solution upper = (tau - mu_s p) / G. Newton
      // from 0 climbs to the root monotonically.
      const double G     = elasticity.shear_modulus;
      const double k     = grain_diameter / (time_step * std::sqrt(p / grain_density));
      const double upper = (tau - mu_s * p) / G;
      double       dgamma = 0;
      for (unsigned int i = 0; i < 50; ++i)
        {
          const double I = k * dgamma;
          const double g = tau - G * dgamma - friction(I) * p;
          const double dmu_dI = (mu_2 - mu_s) * reference_inertial_number /
                                ((reference_inertial_number + I) *
                                 (reference_inertial_number + I));
          const double step = g / (G + p * dmu_dI * k);
          dgamma            = std::min(upper, dgamma + step);
          if (std::abs(step) <= 1e-14 * upper)
            break;
        }
      stress = (1 - G * dgamma / tau) * s - p * unit_symmetric_tensor<3>();
      state[0] += dgamma;
      state[1] = k * dgamma;
    }


    double
    MuIRheology::strain_energy_density(const SymmetricTensor<2, 3> &stress) const
    {
      return elasticity.strain_energy_density(stress);
    }


    double
    MuIRheology::p_wave_modulus() const
    {
      return elasticity.p_wave_modulus();
    }


    double
    MuIRheology::default_k0() const
    {
      return 1 - std::sin(std::atan(mu_s));
    }


    unsigned int
    MuIRheology::n_state_variables() const
    {
      return 2;
    }


    std::vector<std::string>
    MuIRheology::state_variable_names() const
    {
      return {"plastic_shear_strain", "inertial_number"};
    }


    void
    MuIRheology::initialize_state(const ArrayView<double> &state) const
    {
      AssertIndexRange(1, state.size());
      state[0] = 0;
      state[1] = 0;
    }
  } // namespace MaterialModels
} // namespace MPM

MPM_REGISTER_MATERIAL_MODEL(
  MPM::MaterialModels::MuIRheology,
  "mu(I)",
  "Dense granular flow with rate-dependent friction mu(I) (Jop, Forterre "
  "and Pouliquen 2006), elastic - viscoplastic, no dilation, no cohesion.")
