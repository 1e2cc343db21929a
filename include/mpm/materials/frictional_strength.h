#ifndef mpm_materials_frictional_strength_h
#define mpm_materials_frictional_strength_h

#include <mpm/base/input_error.h>
#include <mpm/base/units.h>
#include <mpm/materials/material_model.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace MPM
{
  namespace MaterialModels
  {
    /**
     * Relative tolerance of the frictional models' yield checks (and of
     * Mohr-Coulomb's acceptance tests of a candidate return): far above
     * the rounding of the invariants or of the spectral decomposition (a
     * few eps times the stress), so that a returned stress is recognised
     * as admissible and a second return with a zero increment leaves it
     * untouched; far below anything physical.
     */
    constexpr double yield_relative_tolerance = 1e-10;


    /**
     * The input checks of the Mohr-Coulomb strength parameters, which every
     * frictional model reads ('mohr coulomb', 'drucker prager'): friction
     * angle phi in (0, 90) degrees, dilation angle psi in [0, phi],
     * cohesion c >= 0, and a tension cutoff T in [0, c cot(phi)] (rounding
     * in a value copied from a calculator accepted: the caller clamps).
     * Above c cot(phi) the tension surface would lie beyond the apex and
     * never be reached: an input mistake, not a harmless no-op. Errors
     * name "<model>/<entry>"; @p apex_description says what c cot(phi) is
     * for the model.
     */
    inline void
    check_frictional_strength(const std::string &model,
                              const double       phi_degrees,
                              const double       psi_degrees,
                              const double       cohesion,
                              const double       tension_cutoff,
                              const std::string &apex_description)
    {
      const auto name_of = [&](const std::string &entry) {
        return model + "/" + entry;
      };
      check_input(phi_degrees > 0 && phi_degrees < 90,
                  name_of("Friction angle") + " = " +
                    std::to_string(phi_degrees) +
                    " degrees: must lie in (0, 90).");
      check_input(psi_degrees >= 0 && psi_degrees <= phi_degrees,
                  name_of("Dilation angle") + " = " +
                    std::to_string(psi_degrees) +
                    " degrees: must lie in [0, friction angle = " +
                    std::to_string(phi_degrees) + "].");
      check_input(cohesion >= 0,
                  name_of("Cohesion") + " = " + std::to_string(cohesion) +
                    " Pa: must be >= 0.");
      const double apex = cohesion / std::tan(phi_degrees * degree);
      check_input(
        tension_cutoff >= 0 && tension_cutoff <= apex * (1 + 1e-6) + 1e-12,
        name_of("Tension cutoff") + " = " + std::to_string(tension_cutoff) +
          " Pa: must lie in [0, c cot(phi) = " + std::to_string(apex) +
          " Pa], " + apex_description + ".");
    }


    /**
     * A Mohr-Coulomb strength: friction angle phi and dilation angle psi
     * (radians), cohesion c and tension cutoff T (Pa, T <= c cot(phi)).
     */
    struct FrictionalStrength
    {
      double friction_angle = 0;
      double dilation_angle = 0;
      double cohesion       = 0;
      double tension_cutoff = 0;

      /**
       * The strength divided by the strength reduction factor @p factor
       * (the shear strength reduction method of slope stability; Griffiths
       * and Lane 1999): tan(phi_F) = tan(phi) / F, c_F = c / F and
       * T_F = T / F, so that the apex c cot(phi) stays where it is. The
       * dilation angle is kept as given unless it exceeds phi_F, where it
       * becomes phi_F (flow never more dilatant than associated; the
       * convention of Plaxis and FLAC; with psi = 0, as in Griffiths and
       * Lane, it does not enter). F = 1 returns the strength bit for bit.
       */
      FrictionalStrength
      reduced(const double factor) const
      {
        if (factor == 1.)
          return *this;
        FrictionalStrength r;
        r.friction_angle = std::atan(std::tan(friction_angle) / factor);
        r.dilation_angle = std::min(dilation_angle, r.friction_angle);
        r.cohesion       = cohesion / factor;
        r.tension_cutoff = tension_cutoff / factor;
        return r;
      }
    };
    /**
     * What the frictional models ('mohr coulomb', 'drucker prager') share:
     * a Mohr-Coulomb strength as given in the parameter file, which
     * 'Materials/Strength reduction factor' divides
     * (set_strength_reduction(), each model's own), Jaky's K0 from its
     * friction angle, and one state variable, the accumulated equivalent
     * plastic shear strain.
     */
    class FrictionalModel : public MaterialModel
    {
    public:
      bool
      has_frictional_strength() const final
      {
        return true;
      }

      /**
       * Jaky's 1 - sin(phi) for normally consolidated sand: the elastic
       * nu / (1 - nu) would put a loose sand column at rest far from its
       * real lateral stress, and both models should start a scene from
       * the same state.
       */
      double
      default_k0() const final
      {
        return 1 - std::sin(given_strength.friction_angle);
      }

      /**
       * The accumulated plastic shear strain, and with a non-local
       * regularisation (nonlocal_variable()) the regularised one that sets
       * the strength.
       */
      unsigned int
      n_state_variables() const final
      {
        return nonlocal_state ? 2 : 1;
      }

      std::vector<std::string>
      state_variable_names() const final
      {
        if (nonlocal_state)
          return {"plastic_shear_strain", "nonlocal_plastic_shear_strain"};
        return {"plastic_shear_strain"};
      }

      void
      initialize_state(const ArrayView<double> &state) const final
      {
        AssertIndexRange(n_state_variables() - 1, state.size());
        for (unsigned int i = 0; i < n_state_variables(); ++i)
          state[i] = 0;
      }

    protected:
      /// The strength as given (the peak strength of a softening model).
      FrictionalStrength given_strength;
      /// Whether the points carry a regularised plastic shear strain
      /// (state variable 1) besides their own.
      bool nonlocal_state = false;
    };

  } // namespace MaterialModels
} // namespace MPM

#endif
