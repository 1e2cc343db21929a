// Shear strength reduction ('Materials/Strength reduction factor', the
// method of slope stability analysis; doc/slope_stability.md): with the
// factor F, c and tan(phi) of 'mohr coulomb' and 'drucker prager' are
// divided by F. Checked by the material-point driver on a drained triaxial
// compression path against the closed form of the reduced strength,
// sigma_a = p0 N_F + 2 c_F sqrt(N_F), N_F = (1 + sin phi_F) / (1 - sin
// phi_F), tan(phi_F) = tan(phi) / F, c_F = c / F (Drucker-Prager fitted to
// triaxial compression has the Mohr-Coulomb strength on this path), with a
// softening Mohr-Coulomb at its residual strength as well; F = 1 gives
// back the unreduced strength bit for bit; the dilation angle is capped
// at the reduced friction angle; a factor <= 0 and a reduction of a scene
// without a frictional material are input errors.

#include <mpm/base/input_error.h>
#include <mpm/materials/frictional_strength.h>
#include <mpm/materials/material_point_driver.h>

#include "unit_test_tools.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

namespace unit_strength_reduction
{
  using namespace dealii;
  using namespace UnitTest;
  using MPM::MaterialPointDriver;

  constexpr double degree = M_PI / 180.;
  constexpr double p0     = 1e5;
  constexpr double phi    = 30;
  constexpr double c      = 2e4;

  std::string
  parameters(const std::string &model,
             const std::string &factor,
             const std::string &extra = "")
  {
    std::ostringstream s;
    s << "subsection Materials\n"
      << "  set List of materials = soil\n"
      << "  set Strength reduction factor = " << factor << "\n"
      << "  subsection soil\n"
      << "    set Model = " << model << "\n"
      << "    subsection " << model << "\n"
      << "      set Young's modulus = 1e7\n"
      << "      set Poisson's ratio = 0.3\n";
    if (model != "linear elastic")
      s << "      set Friction angle = " << phi << "\n"
        << "      set Dilation angle = 0\n"
        << "      set Cohesion = " << c << "\n";
    s << extra << "    end\n"
      << "  end\n"
      << "end\n"
      << "subsection Material point driver\n"
      << "  set Path = drained triaxial\n"
      << "  set Confining pressure = " << p0 << "\n"
      << "  set Final strain = 0.1\n"
      << "  set Number of steps = 200\n"
      << "end\n";
    return s.str();
  }

  /// Axial stress (compression positive) at failure of friction angle
  /// @p phi_degrees and cohesion @p cohesion.
  double
  failure_stress(const double phi_degrees, const double cohesion)
  {
    const double s = std::sin(phi_degrees * degree);
    const double N = (1 + s) / (1 - s);
    return p0 * N + 2 * cohesion * std::sqrt(N);
  }

  double
  final_axial_stress(const std::string &text)
  {
    const auto history = MaterialPointDriver::from_text(text).run_path();
    return -history.records.back().stress[1][1];
  }


  int
  run(int /*argc*/, char ** /*argv*/)
  {
    std::cout << "# numdiff: -a 1e-9 -r 1e-6\n" << std::setprecision(10);
    const std::string dp_fit = "      set Fit to Mohr-Coulomb = compression\n";
    const std::string softening =
      "      subsection Strain softening\n"
      "        set Enabled = true\n"
      "        set Residual friction angle = 20\n"
      "        set Residual cohesion = 5000\n"
      "        set Peak plastic shear strain = 0\n"
      "        set Residual plastic shear strain = 0.01\n"
      "      end\n";
    for (const double F : {1., 1.25, 1.5, 2.})
      {
        const double phi_F = std::atan(std::tan(phi * degree) / F) / degree;
        const double exact = failure_stress(phi_F, c / F);
        const double mc =
          final_axial_stress(parameters("mohr coulomb", std::to_string(F)));
        const double dp = final_axial_stress(
          parameters("drucker prager", std::to_string(F), dp_fit));
        // Residual phi 20, c 5 kPa, reduced by F as well.
        const double exact_residual =
          failure_stress(std::atan(std::tan(20 * degree) / F) / degree,
                         5000 / F);
        const double mc_softened = final_axial_stress(
          parameters("mohr coulomb", std::to_string(F), softening));
        std::cout << "F = " << F << ": phi_F = " << phi_F
                  << " deg; sigma_a / p0 exact " << exact / p0
                  << ", mohr coulomb error "
                  << flush_to_zero((mc - exact) / p0, 1e-12)
                  << ", drucker prager (compression fit) error "
                  << flush_to_zero((dp - exact) / p0, 1e-12)
                  << "; residual exact " << exact_residual / p0
                  << ", softening mohr coulomb error "
                  << flush_to_zero((mc_softened - exact_residual) / p0, 1e-12)
                  << '\n';
        check(std::abs(mc - exact) < 1e-10 * p0 &&
                std::abs(dp - exact) < 1e-10 * p0 &&
                std::abs(mc_softened - exact_residual) < 1e-10 * p0,
              "the reduced strengths are reached (1e-10 p0)");
      }

    // F = 1 through a function of t: the model is not touched.
    check(final_axial_stress(parameters("mohr coulomb", "1")) ==
            final_axial_stress(parameters("mohr coulomb", "1 + 0 * t")),
          "F = 1 as a function gives the unreduced result bit for bit");

    MPM::MaterialModels::FrictionalStrength strength;
    strength.friction_angle = 30 * degree;
    strength.dilation_angle = 25 * degree;
    strength.cohesion       = 1e4;
    strength.tension_cutoff = 1e4;
    const auto reduced      = strength.reduced(2);
    std::cout << "phi 30, psi 25, F = 2: phi_F = "
              << reduced.friction_angle / degree
              << ", psi_F = " << reduced.dilation_angle / degree << '\n';
    check(reduced.dilation_angle == reduced.friction_angle &&
            std::abs(reduced.cohesion - 5e3) < 1e-12 &&
            std::abs(reduced.tension_cutoff - 5e3) < 1e-12,
          "psi is capped at phi_F; c and T are halved");

    std::cout << "input errors\n";
    const auto input_error = [](const std::string &text,
                                const std::string &needle) {
      try
        {
          MaterialPointDriver::from_text(text);
        }
      catch (const MPM::InputError &error)
        {
          std::cout << "  " << error.what() << '\n';
          return std::string(error.what()).find(needle) != std::string::npos;
        }
      return false;
    };
    check(input_error(parameters("mohr coulomb", "1 - t - 1"),
                      "Strength reduction factor"),
          "a factor <= 0 is an input error naming the parameter");
    check(input_error(parameters("linear elastic", "1.5"),
                      "no material has a frictional strength"),
          "a reduction without a frictional material is an input error");
    check(input_error(parameters("mohr coulomb", "1 +* t"),
                      "Strength reduction factor"),
          "a malformed expression is an input error naming the parameter");
    return summary();
  }
} // namespace unit_strength_reduction

MPM_UNIT_TEST_REGISTER(strength_reduction)
