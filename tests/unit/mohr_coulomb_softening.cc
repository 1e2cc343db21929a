// Unit test of Mohr-Coulomb with strain softening, point by point against
// the closed form of a drained triaxial compression (lateral stresses held
// at -p0 by the material-point driver; tension positive in the code,
// compression positive in the comments below).
//
// On the triaxial compression edge (s1 = s2 = -p0 > s3 = -sigma_a) the
// consistency condition gives the axial stress as a function of the
// accumulated plastic shear strain kappa alone:
//   sigma_a(kappa) = p0 N + 2 c sqrt(N),  N = (1 + sin phi) / (1 - sin phi),
// with phi(kappa), c(kappa) the softened strength. The flow of the two
// planes of the edge, dgamma ((1 + s, 0, -(1 - s)) + (0, 1 + s, -(1 - s)))
// with s = sin psi, gives per unit kappa (kappa = sum sqrt(2/3 |de_p|^2))
//   axial compressive plastic strain  3 (1 - s) / (3 - s),
//   plastic dilation                  6 s / (3 - s),
// and the elastic strains are (sigma_a - p0) / E axially and
// -(1 - 2 nu) (sigma_a - p0) / E in volume. So with kappa read from the
// point's state the axial strain and the volume change of each step are
// known in closed form (the integrals over kappa tabulated on a fine grid,
// independently of the model). Checks:
// - consistency: the returned stress lies on the surface of its own kappa
//   (the return is implicit in kappa), to round-off;
// - the strains against the closed form; they converge at first order in
//   the step (the dilation angle is taken at each step's final kappa, a
//   backward Euler rule), and vanish where psi is constant;
// - the residual stress ratio is reached; peak and residual are exact;
// - a residual strength above the peak is an input error;
// - with 'Nonlocal radius' (the driver's single point is a homogeneous
//   body: kappa* = kappa) the return is explicit in kappa: the stress lies
//   off its own surface by one step's softening, an error that halves with
//   the step; the strains and the residual strength are as above. Both
//   regularisations at once are an input error.

#include <mpm/base/input_error.h>
#include <mpm/materials/material_point_driver.h>

#include "unit_test_tools.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace unit_mohr_coulomb_softening
{
  using namespace dealii;
  using namespace UnitTest;
  using MPM::MaterialPointDriver;

  constexpr double degree = M_PI / 180.;

  struct Case
  {
    double E = 1e7, nu = 0.3, p0 = 1e5;
    double phi_peak = 35, phi_residual = 25;
    double psi_peak = 0, psi_residual = 0;
    double c_peak = 0, c_residual = 0;
    double kappa_peak = 0.01, kappa_residual = 0.05;
    double final_strain = 0.15;
    /// Regularisation: 'Reference cell size' and the driver's 'Cell size'
    /// (0: not regularised).
    double reference_cell_size = 0, cell_size = 0;
    /// 'Nonlocal radius' (0: local). The driver's point is a homogeneous
    /// body, so the regularised strain is its own: the return is then
    /// explicit in kappa (the strength of the step before).
    double nonlocal_radius = 0;

    /// The softening strains are those of the reference cell: a point in
    /// a cell of size h softens as if its kappa were kappa h / h_ref.
    double
    kappa_scale() const
    {
      return reference_cell_size > 0 && cell_size > 0 ?
               cell_size / reference_cell_size :
               1.;
    }
  };

  std::string
  parameters(const Case &c, const unsigned int n_steps)
  {
    std::ostringstream s;
    s << std::setprecision(17);
    s << "subsection Materials\n"
      << "  set List of materials = clay\n"
      << "  subsection clay\n"
      << "    set Model = mohr coulomb\n"
      << "    subsection mohr coulomb\n"
      << "      set Young's modulus = " << c.E << "\n"
      << "      set Poisson's ratio = " << c.nu << "\n"
      << "      set Friction angle = " << c.phi_peak << "\n"
      << "      set Dilation angle = " << c.psi_peak << "\n"
      << "      set Cohesion = " << c.c_peak << "\n"
      << "      subsection Strain softening\n"
      << "        set Enabled = true\n"
      << "        set Residual friction angle = " << c.phi_residual << "\n"
      << "        set Residual dilation angle = " << c.psi_residual << "\n"
      << "        set Residual cohesion = " << c.c_residual << "\n"
      << "        set Peak plastic shear strain = " << c.kappa_peak << "\n"
      << "        set Residual plastic shear strain = " << c.kappa_residual
      << "\n"
      << "        set Reference cell size = " << c.reference_cell_size << "\n"
      << "        set Nonlocal radius = " << c.nonlocal_radius << "\n"
      << "      end\n"
      << "    end\n"
      << "  end\n"
      << "end\n"
      << "subsection Material point driver\n"
      << "  set Path = drained triaxial\n"
      << "  set Confining pressure = " << c.p0 << "\n"
      << "  set Final strain = " << c.final_strain << "\n"
      << "  set Number of steps = " << n_steps << "\n"
      << "  set Cell size = " << c.cell_size << "\n"
      << "end\n";
    return s.str();
  }

  /// The softened value of a parameter at kappa (linear, as documented).
  double
  soften(const Case  &c,
         const double peak,
         const double residual,
         const double kappa)
  {
    const double w = std::clamp((kappa * c.kappa_scale() - c.kappa_peak) /
                                  (c.kappa_residual - c.kappa_peak),
                                0.,
                                1.);
    return peak + w * (residual - peak);
  }

  /// sigma_a(kappa) on the compression edge, compression positive.
  double
  axial_stress(const Case &c, const double kappa)
  {
    const double phi = soften(c, c.phi_peak, c.phi_residual, kappa) * degree;
    const double coh = soften(c, c.c_peak, c.c_residual, kappa);
    const double N   = (1 + std::sin(phi)) / (1 - std::sin(phi));
    return c.p0 * N + 2 * coh * std::sqrt(N);
  }

  /**
   * The integral of f(sin psi(k)) dk from 0 to kappa, tabulated once by
   * the trapezoidal rule on a grid of 1e-6 (error of order 1e-12, far
   * below what is checked) and interpolated linearly.
   */
  class Integral
  {
  public:
    Integral(const Case &c, const std::function<double(double)> &f)
    {
      values.resize(n + 1);
      double previous = f(std::sin(c.psi_peak * degree));
      for (unsigned int i = 1; i <= n; ++i)
        {
          const double s =
            std::sin(soften(c, c.psi_peak, c.psi_residual, i * h) * degree);
          const double value = f(s);
          values[i]          = values[i - 1] + 0.5 * h * (previous + value);
          previous           = value;
        }
    }

    double
    operator()(const double kappa) const
    {
      const unsigned int i = std::min<unsigned int>(kappa / h, n - 1);
      const double       w = kappa / h - i;
      return (1 - w) * values[i] + w * values[i + 1];
    }

  private:
    static constexpr unsigned int n = 200000;
    static constexpr double       h = 1e-6;
    std::vector<double>           values;
  };

  struct Errors
  {
    double consistency = 0; // max |sigma_a - sigma_a(kappa)| / p0 (plastic)
    double axial       = 0; // max |eps_a - closed form|
    double volumetric  = 0; // max |eps_v - closed form|
    double final_kappa = 0;
    double final_ratio = 0; // sigma_a / p0 at the end
    unsigned int plastic_records = 0;
  };

  Errors
  run(const Case &c, const unsigned int n_steps)
  {
    const MaterialPointDriver driver =
      MaterialPointDriver::from_text(parameters(c, n_steps));
    const auto     history = driver.run_path();
    const Integral axial_plastic(c, [](double s) {
      return 3 * (1 - s) / (3 - s);
    });
    const Integral volumetric_plastic(c,
                                      [](double s) { return 6 * s / (3 - s); });
    Errors         e;
    for (const auto &r : history.records)
      {
        const double kappa   = r.state[0];
        const double sigma_a = -r.stress[1][1];
        const double eps_a   = -r.strain[1][1];
        const double eps_v   = r.volumetric_strain;
        if (kappa > 0)
          {
            ++e.plastic_records;
            e.consistency =
              std::max(e.consistency,
                       std::abs(sigma_a - axial_stress(c, kappa)) / c.p0);
          }
        const double elastic   = (sigma_a - c.p0) / c.E;
        const double a_plastic = axial_plastic(kappa);
        const double v_plastic = volumetric_plastic(kappa);
        e.axial = std::max(e.axial, std::abs(eps_a - elastic - a_plastic));
        e.volumetric =
          std::max(e.volumetric,
                   std::abs(eps_v - (-(1 - 2 * c.nu) * elastic + v_plastic)));
      }
    e.final_kappa = history.records.back().state[0];
    e.final_ratio = -history.records.back().stress[1][1] / c.p0;
    return e;
  }

  /**
   * Three step sizes of one case. The implicit return puts the stress on
   * the surface of its own kappa (checked); its strains converge at first
   * order where they are not exact. A non-local case (on the driver's
   * homogeneous point kappa* = kappa) returns at the strength of kappa_n,
   * off its own surface by the softening of one step: that consistency
   * error must halve with the step. Both: strains within 2e-4 of the closed
   * form and the residual strength reached.
   */
  void
  report(const std::string &name, const Case &c)
  {
    const bool explicit_return = c.nonlocal_radius > 0;
    std::cout << name << '\n';
    Errors previous;
    for (const unsigned int n : {750u, 1500u, 3000u})
      {
        const Errors e = run(c, n);
        std::cout << "  steps " << n << ": plastic records "
                  << e.plastic_records << ", consistency error "
                  << flush_to_zero(e.consistency, 1e-11)
                  << ", axial strain error " << flush_to_zero(e.axial, 1e-12)
                  << ", volumetric strain error "
                  << flush_to_zero(e.volumetric, 1e-12) << '\n';
        if (!explicit_return)
          check(e.consistency < 1e-9,
                "the stress lies on the surface of its own kappa (< 1e-9 p0)");
        check(e.axial < 2e-4 && e.volumetric < 2e-4,
              "strains within 2e-4 of the closed form");
        // The error that converges: the consistency of the explicit
        // return, the strains of the implicit one (where not exact).
        const double error = explicit_return ? e.consistency : e.axial;
        const double previous_error =
          explicit_return ? previous.consistency : previous.axial;
        if (n > 750 && (explicit_return || previous_error > 1e-10))
          {
            const double ratio = previous_error / error;
            std::cout << (explicit_return ?
                            "    consistency error ratio to half the steps: " :
                            "    axial error ratio to half the steps: ")
                      << std::setprecision(3) << ratio << std::setprecision(6)
                      << '\n';
            check(ratio > 1.8 && ratio < 2.2,
                  explicit_return ?
                    "the explicit strength is first order in the step "
                    "(ratio 1.8-2.2)" :
                    "first order in the step (ratio 1.8-2.2)");
          }
        if (n == 3000)
          {
            const double residual = axial_stress(c, c.kappa_residual) / c.p0;
            std::cout << "  final kappa " << e.final_kappa
                      << ", final sigma_a / p0 " << e.final_ratio
                      << " (residual " << residual << ")\n";
            if (explicit_return)
              check(e.consistency < 1e-2,
                    "on 3000 steps within 1e-2 p0 of its own surface");
            check(e.final_kappa > c.kappa_residual / c.kappa_scale() &&
                    std::abs(e.final_ratio - residual) < 1e-10 * residual,
                  "the residual strength is reached");
          }
        previous = e;
      }
  }


  int
  run(int /*argc*/, char ** /*argv*/)
  {
    std::cout << "# numdiff: -a 1e-9 -r 1e-4\n";
    std::cout << std::setprecision(6);

    // Friction softening, no dilation: the axial plastic strain is kappa
    // itself, so the strains are exact as well.
    Case friction;
    report("friction 35 -> 25 deg, psi 0, c 0", friction);

    // Friction and dilation: psi 10 -> 0 deg.
    Case dilation;
    dilation.psi_peak = 10;
    report("friction 35 -> 25 deg, psi 10 -> 0 deg, c 0", dilation);

    // Cohesion and friction, from kappa = 0.
    Case cohesion;
    cohesion.phi_peak     = 30;
    cohesion.phi_residual = 20;
    cohesion.c_peak       = 2e4;
    cohesion.c_residual   = 2e3;
    cohesion.kappa_peak   = 0;
    report("friction 30 -> 20 deg, c 20 -> 2 kPa, psi 0", cohesion);

    // The same, regularised, in a cell twice the reference size: the
    // softening strains halve (peak at kappa = 0 stays 0).
    Case regularised                = cohesion;
    regularised.reference_cell_size = 0.5;
    regularised.cell_size           = 1;
    report("regularised: cell size 1 m, reference 0.5 m: friction 30 -> 20 "
           "deg, c 20 -> 2 kPa over kappa 0 -> 0.025",
           regularised);

    // The same with the non-local regularisation: on one point (a
    // homogeneous body) kappa* = kappa, the strength of the step before.
    Case nonlocal            = cohesion;
    nonlocal.nonlocal_radius = 2;
    report("non-local (R = 2 m) on a homogeneous point: friction 30 -> 20 "
           "deg, c 20 -> 2 kPa, psi 0",
           nonlocal);

    std::cout << "input errors\n";
    for (const auto &[entry, value] :
         std::vector<std::pair<std::string, std::string>>{
           {"Residual friction angle", "40"},
           {"Residual cohesion", "1"},
           {"Residual plastic shear strain", "0.005"}})
      {
        std::string text = parameters(Case(), 10);
        const auto  at   = text.find("set " + entry + " = ");
        text.replace(at,
                     text.find('\n', at) - at,
                     "set " + entry + " = " + value);
        bool thrown = false;
        try
          {
            MaterialPointDriver::from_text(text);
          }
        catch (const MPM::InputError &error)
          {
            thrown = std::string(error.what()).find(entry) != std::string::npos;
          }
        check(thrown, entry + " = " + value + " is an input error naming it");
      }
    {
      // Two regularisations of the same softening.
      Case both                = cohesion;
      both.reference_cell_size = 0.5;
      both.nonlocal_radius     = 2;
      bool thrown              = false;
      try
        {
          MaterialPointDriver::from_text(parameters(both, 10));
        }
      catch (const MPM::InputError &error)
        {
          const std::string what = error.what();
          thrown = what.find("Nonlocal radius") != std::string::npos &&
                   what.find("Reference cell size") != std::string::npos;
        }
      check(thrown,
            "Reference cell size and Nonlocal radius both > 0 is an input "
            "error naming both");
    }
    return summary();
  }
} // namespace unit_mohr_coulomb_softening

MPM_UNIT_TEST_REGISTER(mohr_coulomb_softening)
