// Unit test of the Drucker-Prager model (tension positive, sigma_m =
// tr(sigma) / 3): input checks and the fits, the elastic step, random trial
// stresses (admissibility, the flow rule and the multipliers written out
// again from the stress change, idempotency), the apex and the tension
// cap, and element paths against their closed forms: drained triaxial
// compression (compression fit, through MaterialPointDriver), plane-strain
// biaxial compression (plane-strain fit, driven here because the driver
// has no biaxial path), simple shear and undrained triaxial compression.
// Each line prints the value, its reference and the error relative to the
// reference; the tolerance of each check is stated where it is made.

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <mpm/base/input_error.h>
#include <mpm/materials/drucker_prager.h>
#include <mpm/materials/linear_elastic.h>
#include <mpm/materials/material_point_driver.h>

#include "unit_test_tools.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>

namespace unit_drucker_prager
{
  using namespace dealii;
  using namespace UnitTest;
  using MPM::MaterialModels::DruckerPrager;

  constexpr double degree = M_PI / 180;

  struct Parameters
  {
    double      E   = 1e7;
    double      nu  = 0.3;
    double      phi = 30;
    double      psi = 0;
    double      c   = 0;
    double      T   = 0;
    std::string fit = "compression";

    double
    G() const
    {
      return E / (2 * (1 + nu));
    }

    double
    K() const
    {
      return E / (3 * (1 - 2 * nu));
    }
  };

  // The fits written out again from de Souza Neto, Peric and Owen (2008),
  // eqs. (6.119)-(6.122), in the tan form for plane strain: (eta, xi).
  std::pair<double, double>
  fit_coefficients(const std::string &fit, const double angle_degrees)
  {
    const double a = angle_degrees * degree;
    if (fit == "compression")
      return {6 * std::sin(a) / (std::sqrt(3.) * (3 - std::sin(a))),
              6 * std::cos(a) / (std::sqrt(3.) * (3 - std::sin(a)))};
    if (fit == "extension")
      return {6 * std::sin(a) / (std::sqrt(3.) * (3 + std::sin(a))),
              6 * std::cos(a) / (std::sqrt(3.) * (3 + std::sin(a)))};
    const double t = std::tan(a);
    return {3 * t / std::sqrt(9 + 12 * t * t), 3 / std::sqrt(9 + 12 * t * t)};
  }

  std::unique_ptr<DruckerPrager>
  make_model(const Parameters &p)
  {
    ParameterHandler prm;
    DruckerPrager::declare_parameters(prm);
    prm.set("Young's modulus", p.E);
    prm.set("Poisson's ratio", p.nu);
    prm.set("Friction angle", p.phi);
    prm.set("Dilation angle", p.psi);
    prm.set("Cohesion", p.c);
    prm.set("Tension cutoff", p.T);
    prm.set("Fit to Mohr-Coulomb", p.fit);
    auto model = std::make_unique<DruckerPrager>();
    model->parse_parameters(prm);
    return model;
  }

  double
  mean(const SymmetricTensor<2, 3> &s)
  {
    return trace(s) / 3;
  }

  double
  root_j2(const SymmetricTensor<2, 3> &s)
  {
    const SymmetricTensor<2, 3> d = deviator(s);
    return std::sqrt(0.5 * scalar_product(d, d));
  }

  // The cone function, from the test's own coefficients.
  double
  yield(const SymmetricTensor<2, 3> &s, const Parameters &p)
  {
    const auto [eta, xi] = fit_coefficients(p.fit, p.phi);
    return root_j2(s) + eta * mean(s) - xi * p.c;
  }

  double
  max_abs(const SymmetricTensor<2, 3> &s)
  {
    double m = 0;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        m = std::max(m, std::abs(s[i][j]));
    return m;
  }

  SymmetricTensor<2, 3>
  diagonal(const double a, const double b, const double c)
  {
    SymmetricTensor<2, 3> s;
    s[0][0] = a;
    s[1][1] = b;
    s[2][2] = c;
    return s;
  }

  std::string
  case_name(const DruckerPrager::Return r)
  {
    switch (r)
      {
        case DruckerPrager::Return::elastic:
          return "elastic";
        case DruckerPrager::Return::cone:
          return "cone";
        case DruckerPrager::Return::tension_cap:
          return "tension cap";
        case DruckerPrager::Return::cap_edge:
          return "cap edge / apex";
      }
    return "?";
  }

  // Return a stress with a zero strain increment (the stress is its own
  // trial stress); gives the plastic shear strain added.
  double
  return_stress(const DruckerPrager &model, SymmetricTensor<2, 3> &stress)
  {
    double state = 0;
    model.update_stress(SymmetricTensor<2, 3>(),
                        stress,
                        ArrayView<double>(&state, 1),
                        1.);
    return state;
  }

  DruckerPrager::Return
  case_of(const DruckerPrager &model, const SymmetricTensor<2, 3> &trial)
  {
    double m = mean(trial), q = root_j2(trial);
    return model.return_invariants(m, q);
  }

  double
  relative(const double value, const double reference)
  {
    return (value - reference) / std::abs(reference);
  }

  // "value, reference R, relative error e": the line every comparison
  // prints.
  void
  compare(const std::string &what,
          const double       value,
          const double       reference,
          const double       tolerance)
  {
    const double e = relative(value, reference);
    std::cout << "    " << what << " = " << value << ", reference " << reference
              << ", relative error " << flush_to_zero(e, 1e-12) << '\n';
    std::ostringstream tol;
    tol << tolerance;
    check(std::abs(e) <= tolerance, what + " (|error| <= " + tol.str() + ")");
  }


  void
  test_input()
  {
    std::cout << "(0) input checks and fits\n";
    const auto expect_error = [](const Parameters &p) {
      try
        {
          make_model(p);
          check(false, "accepted invalid input");
        }
      catch (const MPM::InputError &e)
        {
          std::cout << "    rejected: " << e.what() << '\n';
        }
    };
    Parameters p;
    p.E = 0;
    expect_error(p);
    p    = Parameters();
    p.nu = 0.5;
    expect_error(p);
    p     = Parameters();
    p.phi = 90;
    expect_error(p);
    p     = Parameters();
    p.phi = 0;
    expect_error(p);
    p     = Parameters();
    p.psi = 35;
    expect_error(p);
    p   = Parameters();
    p.c = 1e4;
    p.T = 1.01e4 / std::tan(30 * degree);
    expect_error(p);
    // Negative values are refused by the patterns already.
    try
      {
        ParameterHandler prm;
        DruckerPrager::declare_parameters(prm);
        prm.set("Cohesion", -1.);
        check(false, "accepted a negative cohesion");
      }
    catch (const ExceptionBase &)
      {
        std::cout << "    rejected: drucker prager/Cohesion = -1 (pattern)\n";
      }

    p      = Parameters();
    p.c    = 1e4;
    p.T    = 1e4 / std::tan(30 * degree);
    auto m = make_model(p);
    std::cout << "    T = c cot(phi) accepted; default K0 = " << m->default_k0()
              << ", reference 1 - sin(30 deg) = " << 1 - std::sin(30 * degree)
              << '\n';
    check(m->default_k0() == 1 - std::sin(30 * degree), "K0 = 1 - sin(phi)");

    // The fits: the model's coefficients against the formulas of the
    // book (the plane-strain one in its tan form), and the apex xi c / eta
    // at c cot(phi) for every fit. Tolerance 1e-14: two roundings apart.
    for (const std::string fit : {"compression", "extension", "plane strain"})
      {
        p.fit                = fit;
        p.psi                = 10;
        m                    = make_model(p);
        const auto [eta, xi] = fit_coefficients(fit, 30);
        const double eta_bar = fit_coefficients(fit, 10).first;
        const double e =
          std::max({std::abs(relative(m->friction_coefficient(), eta)),
                    std::abs(relative(m->cohesion_coefficient(), xi)),
                    std::abs(relative(m->dilation_coefficient(), eta_bar))});
        const double apex = m->cohesion_intercept() / m->friction_coefficient();
        const double e_apex = relative(apex, 1e4 / std::tan(30 * degree));
        std::cout << "    " << fit << " (phi 30, psi 10): eta = " << eta
                  << ", xi = " << xi << ", eta_bar = " << eta_bar
                  << "; max relative error " << flush_to_zero(e, 1e-14)
                  << "; apex xi c / eta = " << apex
                  << ", relative to c cot(phi) " << flush_to_zero(e_apex, 1e-14)
                  << '\n';
        check(e <= 1e-14 && std::abs(e_apex) <= 1e-14,
              fit + " fit coefficients and apex");
      }
  }


  void
  test_elastic()
  {
    std::cout << "(1) elastic increment vs linear elastic\n";
    const Parameters p;
    const auto       dp = make_model(p);
    ParameterHandler prm;
    MPM::MaterialModels::LinearElastic::declare_parameters(prm);
    prm.set("Young's modulus", p.E);
    prm.set("Poisson's ratio", p.nu);
    MPM::MaterialModels::LinearElastic le;
    le.parse_parameters(prm);

    SymmetricTensor<2, 3> de;
    de[0][0]                   = -2e-4;
    de[1][1]                   = 1e-4;
    de[0][1]                   = 3e-4;
    de[1][2]                   = -1e-4;
    SymmetricTensor<2, 3> s_dp = diagonal(-1e5, -1e5, -1e5), s_le = s_dp;
    double                state = 0;
    dp->update_stress(de, s_dp, ArrayView<double>(&state, 1), 1.);
    le.update_stress(de, s_le, ArrayView<double>(), 1.);
    std::cout << "    max |difference| = " << max_abs(s_dp - s_le)
              << ", plastic shear strain = " << state << ", reference 0 0\n";
    check(max_abs(s_dp - s_le) == 0 && state == 0,
          "identical to linear elastic, no plastic strain");
    check(dp->p_wave_modulus() == le.p_wave_modulus() &&
            dp->strain_energy_density(s_dp) == le.strain_energy_density(s_le),
          "p-wave modulus and energy density of linear elasticity");
  }


  // (a) Random trial stresses. For each returned stress: admissible; on
  // the surface that was active; the stress change sigma_trial - sigma is
  // C : (plastic strain) with the plastic strain of the flow rule, written
  // out again here from the change itself: its deviator parallel to the
  // returned deviator (radial return), its volumetric part K eta_bar times
  // the multiplier on the cone and at least that at the cap (non-negative
  // cap multiplier); the plastic shear strain the model adds equals
  // sqrt(2/3) |dev(change)| / (2 G); a second return changes nothing.
  void
  test_random()
  {
    std::cout << "(2) 20000 random trial stresses, four parameter sets\n";
    std::vector<Parameters> sets(4);
    sets[0].psi = 0; // sand, compression fit, apex at 0
    sets[1].c   = 2e4;
    sets[1].T   = 1e4;
    sets[1].psi = 10;
    sets[1].fit = "plane strain";
    sets[2].c   = 2e4;
    sets[2].phi = 40;
    sets[2].psi = 40;
    sets[2].T   = 2e4 / std::tan(40 * degree);
    sets[2].fit = "extension";
    sets[3].c   = 5e4;
    sets[3].phi = 10;
    sets[3].psi = 5;
    sets[3].fit = "compression";

    std::mt19937_64                        generator(7);
    std::uniform_real_distribution<double> diag(-3e5, 1.5e5), off(-1e5, 1e5);
    double max_f = 0, max_cap = 0, max_surface = 0, max_coaxial = 0,
           max_flow = 0, min_cap_multiplier = 0, max_shear = 0, max_second = 0;
    std::map<std::pair<unsigned int, std::string>, unsigned int> cases;
    for (unsigned int k = 0; k < sets.size(); ++k)
      {
        const Parameters &p     = sets[k];
        const auto        model = make_model(p);
        const auto [eta, xi]    = fit_coefficients(p.fit, p.phi);
        const double eta_bar    = fit_coefficients(p.fit, p.psi).first;
        const double T          = std::min(p.T, xi * p.c / eta);
        for (unsigned int n = 0; n < 5000; ++n)
          {
            SymmetricTensor<2, 3> trial;
            for (unsigned int i = 0; i < 3; ++i)
              {
                trial[i][i] = diag(generator);
                for (unsigned int j = i + 1; j < 3; ++j)
                  trial[i][j] = off(generator);
              }
            // Some hydrostatic trial stresses: the deviator is zero.
            if (n % 50 == 0)
              trial = mean(trial) * unit_symmetric_tensor<3>();
            const double scale = max_abs(trial) + p.c;
            const auto   r     = case_of(*model, trial);
            ++cases[{k, case_name(r)}];
            SymmetricTensor<2, 3> stress = trial;
            const double          shear  = return_stress(*model, stress);
            max_f   = std::max(max_f, yield(stress, p) / scale);
            max_cap = std::max(max_cap, (mean(stress) - T) / scale);

            SymmetricTensor<2, 3> again       = stress;
            const double          shear_again = return_stress(*model, again);
            max_second                        = std::max(
              {max_second, max_abs(again - stress) / scale, shear_again});
            if (r == DruckerPrager::Return::elastic)
              {
                max_second = std::max(max_second, max_abs(stress - trial));
                continue;
              }

            // On the boundary of the admissible set.
            const double on_cone = std::abs(yield(stress, p)) / scale;
            const double on_cap  = std::abs(mean(stress) - T) / scale;
            max_surface          = std::max(max_surface,
                                   r == DruckerPrager::Return::cone ?
                                              on_cone :
                                            r == DruckerPrager::Return::tension_cap ?
                                              on_cap :
                                              std::max(on_cone, on_cap));

            const SymmetricTensor<2, 3> change  = trial - stress;
            const SymmetricTensor<2, 3> s_trial = deviator(trial),
                                        s       = deviator(stress);
            // s = alpha s_trial with alpha in [0, 1].
            const double s_trial_2 = scalar_product(s_trial, s_trial);
            const double alpha =
              s_trial_2 > 0 ? scalar_product(s, s_trial) / s_trial_2 : 0.;
            max_coaxial = std::max({max_coaxial,
                                    max_abs(s - alpha * s_trial) / scale,
                                    std::max(0., alpha - 1),
                                    std::max(0., -alpha)});
            // Multipliers from the change: the cone's from the deviatoric
            // part, dgamma = (sqrt(J2_trial) - sqrt(J2)) / G; the
            // volumetric plastic strain dm / K is eta_bar dgamma from the
            // cone plus the cap's multiplier.
            const double dgamma = (root_j2(trial) - root_j2(stress)) / p.G();
            const double cap_multiplier =
              mean(change) / p.K() - eta_bar * dgamma;
            const double strain_scale = scale / p.K();
            if (r == DruckerPrager::Return::cone)
              max_flow =
                std::max(max_flow, std::abs(cap_multiplier) / strain_scale);
            else
              min_cap_multiplier =
                std::min(min_cap_multiplier, cap_multiplier / strain_scale);
            if (r == DruckerPrager::Return::tension_cap)
              max_flow = std::max(max_flow, std::abs(dgamma) / strain_scale);
            const SymmetricTensor<2, 3> dev_change = deviator(change);
            const double                shear_reference =
              std::sqrt(2. / 3. * scalar_product(dev_change, dev_change)) /
              (2 * p.G());
            max_shear =
              std::max(max_shear,
                       std::abs(shear - shear_reference) / strain_scale);
          }
      }
    // Tolerances: 1e-10 relative to the largest trial stress component,
    // the model's own yield tolerance; rounding gives about 1e-16.
    std::cout << "    max f / scale = " << flush_to_zero(max_f)
              << ", max (sigma_m - T) / scale = " << flush_to_zero(max_cap)
              << " (<= 1e-10 required)\n";
    check(max_f <= 1e-10 && max_cap <= 1e-10,
          "all returned stresses admissible");
    std::cout
      << "    max distance of a plastic return from its surface / scale = "
      << flush_to_zero(max_surface) << " (<= 1e-10)\n";
    check(max_surface <= 1e-10, "plastic returns end on the active surface");
    std::cout << "    max |dev(sigma) - alpha dev(sigma_trial)| / scale, alpha "
                 "outside [0, 1] = "
              << flush_to_zero(max_coaxial) << " (<= 1e-10)\n";
    check(max_coaxial <= 1e-10, "radial return in the deviatoric plane");
    std::cout << "    cone: max |dm / K - eta_bar dgamma| / (scale / K), cap: "
                 "max |dgamma| = "
              << flush_to_zero(max_flow)
              << "; edge and cap: min cap multiplier / (scale / K) = "
              << flush_to_zero(min_cap_multiplier) << " (|.| <= 1e-10)\n";
    check(max_flow <= 1e-10 && min_cap_multiplier >= -1e-10,
          "flow rule of the potential, non-negative multipliers");
    std::cout << "    max |plastic shear strain - sqrt(2/3) |dev(change)| / "
                 "(2G)| / (scale / K) = "
              << flush_to_zero(max_shear) << " (<= 1e-10)\n";
    check(max_shear <= 1e-10, "plastic shear strain from the stress change");
    std::cout << "    max change when a returned stress is returned again "
                 "(stress / scale, plastic strain) = "
              << max_second << ", reference 0\n";
    check(max_second == 0, "return is idempotent, elastic steps exact");
    std::cout << "    cases taken (set 0: sand, compression fit | 1: c 20 kPa, "
                 "T 10 kPa, psi 10, plane strain | 2: associated, extension, "
                 "T = apex | 3: c 50 kPa, phi 10, psi 5):\n";
    for (const auto &[key, count] : cases)
      std::cout << "      " << key.first << ' ' << std::left << std::setw(18)
                << key.second << std::right << count << '\n';
    bool all_cases = true;
    for (const std::string name : {"elastic", "cone", "cap edge / apex"})
      for (unsigned int k = 0; k < sets.size(); ++k)
        all_cases = all_cases && cases[{k, name}] > 0;
    all_cases = all_cases && cases[{1, "tension cap"}] > 0;
    check(all_cases, "every case reached");
  }


  void
  test_apex()
  {
    std::cout << "(3) apex and tension cap\n";
    Parameters            sand;
    const auto            model          = make_model(sand);
    SymmetricTensor<2, 3> a              = diagonal(1e4, 5e3, -2e3);
    a[0][1]                              = 3e3;
    a[1][2]                              = -1e3;
    const SymmetricTensor<2, 3> trials[] = {a,
                                            diagonal(1e4, 1e4, 1e4),
                                            diagonal(5e4, -1e3, -1e3)};
    for (auto stress : trials)
      {
        const auto r = case_of(*model, stress);
        return_stress(*model, stress);
        std::cout << "    c = 0, trial in tension (" << case_name(r)
                  << "): max |sigma_ij| = " << max_abs(stress)
                  << ", reference 0\n";
        check(r == DruckerPrager::Return::cap_edge && max_abs(stress) == 0,
              "apex return, exactly zero stress");
      }
    // A large tensile increment from a compressed state.
    SymmetricTensor<2, 3> stress = diagonal(-1e5, -1e5, -1e5), de;
    de[0][0]                     = 0.2;
    de[0][1]                     = 0.05;
    double state                 = 0;
    model->update_stress(de, stress, ArrayView<double>(&state, 1), 1.);
    std::cout << "    c = 0, tensile increment 0.2 from -100 kPa: max "
                 "|sigma_ij| = "
              << max_abs(stress) << ", reference 0\n";
    check(max_abs(stress) == 0, "exactly zero stress");

    // Cohesive, T at the apex: the apex stress c cot(phi) I.
    Parameters p        = sand;
    p.c                 = 1e4;
    p.T                 = 1e4 / std::tan(30 * degree);
    p.psi               = 20;
    const auto cohesive = make_model(p);
    stress              = 1e5 * unit_symmetric_tensor<3>() + a;
    const auto r        = case_of(*cohesive, stress);
    return_stress(*cohesive, stress);
    const double apex = p.c / std::tan(30 * degree);
    const double e = max_abs(stress - apex * unit_symmetric_tensor<3>()) / apex;
    std::cout << "    c = 10 kPa, T = c cot(phi) (" << case_name(r)
              << "): sigma_xx = " << stress[0][0]
              << ", sigma_xy = " << flush_to_zero(stress[0][1], 1e-9 * apex)
              << ", reference apex c cot(phi) = " << apex
              << ", max relative error " << flush_to_zero(e, 1e-14) << '\n';
    check(r == DruckerPrager::Return::cap_edge && e <= 1e-14,
          "apex stress (tolerance 1e-14: rounding of cot)");

    // T below the apex: the cap keeps the deviator, the edge shrinks it to
    // xi c - eta T.
    p.T                         = 5e3;
    const auto capped           = make_model(p);
    const auto [eta, xi]        = fit_coefficients(p.fit, p.phi);
    SymmetricTensor<2, 3> small = diagonal(3e4, 2.8e4, 2.9e4);
    small[0][1]                 = 500;
    SymmetricTensor<2, 3> trial = small;
    auto                  rc    = case_of(*capped, small);
    double                added = return_stress(*capped, small);
    const double          e_cap =
      std::max(std::abs(relative(mean(small), p.T)),
               max_abs(deviator(small) - deviator(trial)) / p.T);
    std::cout << "    c = 10 kPa, T = 5 kPa, small deviator (" << case_name(rc)
              << "): sigma_m = " << mean(small)
              << ", reference T = 5000; deviator kept; relative error "
              << flush_to_zero(e_cap, 1e-14) << ", plastic shear strain "
              << added << '\n';
    check(rc == DruckerPrager::Return::tension_cap && e_cap <= 1e-14 &&
            added == 0,
          "tension cap: sigma_m = T, deviator unchanged, no shear strain");
    SymmetricTensor<2, 3> large = 5e5 * unit_symmetric_tensor<3>() + a * 20;
    rc                          = case_of(*capped, large);
    return_stress(*capped, large);
    const double edge   = xi * p.c - eta * p.T;
    const double e_edge = std::max(std::abs(relative(mean(large), p.T)),
                                   std::abs(relative(root_j2(large), edge)));
    std::cout << "    c = 10 kPa, T = 5 kPa, large deviator (" << case_name(rc)
              << "): sigma_m = " << mean(large)
              << ", sqrt(J2) = " << root_j2(large)
              << ", reference T, xi c - eta T = " << edge << "; relative error "
              << flush_to_zero(e_edge, 1e-14) << '\n';
    check(rc == DruckerPrager::Return::cap_edge && e_edge <= 1e-14,
          "edge of cone and cap");
  }


  std::string
  driver_text(const Parameters  &p,
              const std::string &path,
              const double       p0,
              const double       final_strain,
              const unsigned int n_steps)
  {
    std::ostringstream s;
    // The closed forms below are of the model alone, in fixed axes: no
    // objective rotation of the stress (simple shear rotates it).
    s << std::setprecision(17) << "subsection Materials\n"
      << "  set Objective stress rate = none\n"
      << "  set List of materials = sand\n"
      << "  subsection sand\n"
      << "    set Density = 2000\n"
      << "    set Model = drucker prager\n"
      << "    subsection drucker prager\n"
      << "      set Young's modulus = " << p.E << "\n"
      << "      set Poisson's ratio = " << p.nu << "\n"
      << "      set Friction angle = " << p.phi << "\n"
      << "      set Dilation angle = " << p.psi << "\n"
      << "      set Cohesion = " << p.c << "\n"
      << "      set Tension cutoff = " << p.T << "\n"
      << "      set Fit to Mohr-Coulomb = " << p.fit << "\n"
      << "    end\n"
      << "  end\n"
      << "end\n"
      << "subsection Material point driver\n"
      << "  set Path = " << path << "\n"
      << "  set Confining pressure = " << p0 << "\n"
      << "  set Final strain = " << final_strain << "\n"
      << "  set Number of steps = " << n_steps << "\n"
      << "end\n";
    return s.str();
  }


  // (b) Drained triaxial compression, compression fit, c = 0: the cone
  // meets the Mohr-Coulomb pyramid on the compression meridian, so failure
  // is at sigma_yy / sigma_xx = (1 + sin phi) / (1 - sin phi). Before it
  // the point is elastic with the lateral stresses constant: sigma_yy =
  // -p0 - E eps_a, volumetric strain -(1 - 2 nu) eps_a. After it the
  // stress stays and the strain is plastic: per unit multiplier the axial
  // strain is -1/sqrt(3) + eta_bar / 3 (s_yy / (2 sqrt(J2)) = -1/sqrt(3) on
  // the compression meridian) and the volumetric strain eta_bar, so
  // d eps_v / d eps_a = 3 eta_bar / (sqrt(3) - eta_bar) and the plastic
  // shear strain grows by dgamma / sqrt(3).
  void
  test_drained_triaxial()
  {
    std::cout << "(4) drained triaxial compression through the driver "
                 "(compression fit, phi 30, c 0, E 10 MPa, nu 0.3, p0 100 "
                 "kPa, eps_a to 0.05 in 500 steps)\n";
    const double p0 = 1e5, sin_phi = std::sin(30 * degree);
    const double ratio = (1 + sin_phi) / (1 - sin_phi);
    for (const double psi : {0., 10.})
      {
        Parameters p;
        p.psi             = psi;
        const auto driver = MPM::MaterialPointDriver::from_text(
          driver_text(p, "drained triaxial", p0, 0.05, 500));
        const auto   history = driver.run_path();
        const auto  &records = history.records;
        const double eps_y   = p0 * (ratio - 1) / p.E;
        std::cout << "  psi = " << psi << ":\n";
        // Elastic part: every step before the first plastic one, which
        // is the first past the yield strain 0.02 (step 201).
        unsigned int first_plastic = 0;
        for (const auto &r : records)
          if (r.state[0] > 0)
            {
              first_plastic = r.step;
              break;
            }
        double e_elastic = 0, e_volume = 0;
        for (const auto &r : records)
          if (r.step < first_plastic)
            {
              e_elastic = std::max(
                e_elastic,
                std::abs(r.stress[1][1] - (-p0 - p.E * r.path_strain)) / p0);
              e_volume = std::max(e_volume,
                                  std::abs(r.volumetric_strain +
                                           (1 - 2 * p.nu) * r.path_strain) /
                                    eps_y);
            }
        const unsigned int first_reference =
          static_cast<unsigned int>(std::floor(500 * eps_y / 0.05 + 1e-9)) + 1;
        std::cout << "    first plastic step " << first_plastic
                  << ", reference the first past eps_y = " << eps_y << ": "
                  << first_reference << "; before it max |sigma_yy - (-p0 - "
                  << "E eps_a)| / p0 = " << flush_to_zero(e_elastic, 1e-12)
                  << ", max |eps_v + (1 - 2 nu) eps_a| / eps_y = "
                  << flush_to_zero(e_volume, 1e-12)
                  << " (<= 1e-9: the driver's lateral-stress iteration)\n";
        check(first_plastic == first_reference && e_elastic <= 1e-9 &&
                e_volume <= 1e-9,
              "elastic part: sigma_yy = -p0 - E eps_a up to eps_y");
        // Tolerance 1e-10: the failure stress is reached exactly (a
        // perfectly plastic return), only the driver's iteration on the
        // lateral stress (1e-12 relative) separates it from the closed form.
        const auto &last = records.back();
        compare("final sigma_yy [Pa]", last.stress[1][1], -ratio * p0, 1e-10);
        compare("final sigma_xx [Pa]", last.stress[0][0], -p0, 1e-10);
        const auto [eta, xi] = fit_coefficients(p.fit, p.phi);
        const double eta_bar = fit_coefficients(p.fit, psi).first;
        (void)eta, (void)xi;
        const double slope = 3 * eta_bar / (std::sqrt(3.) - eta_bar);
        const auto  &mid   = records[350];
        const double measured_slope =
          (last.volumetric_strain - mid.volumetric_strain) /
          (last.path_strain - mid.path_strain);
        const double ev_reference =
          -(1 - 2 * p.nu) * eps_y + slope * (0.05 - eps_y);
        compare("final volumetric strain",
                last.volumetric_strain,
                ev_reference,
                1e-8);
        std::cout << "    d eps_v / d eps_a after failure = "
                  << flush_to_zero(measured_slope, 1e-12)
                  << ", reference 3 eta_bar / (sqrt(3) - eta_bar) = " << slope
                  << '\n';
        const double dgamma_per_strain = 1 / (1 / std::sqrt(3.) - eta_bar / 3);
        compare("final plastic shear strain",
                last.state[0],
                dgamma_per_strain / std::sqrt(3.) * (0.05 - eps_y),
                1e-8);
      }
  }


  // Plane-strain biaxial compression, driven here: eps_zz = 0, sigma_xx
  // held at -p0 by a bracketing secant on eps_xx each step, eps_yy
  // prescribed. At the limit the plastic strain has no zz part:
  // s_zz = -2 sqrt(J2) eta_bar / 3; with the Mohr circle radius R = (s_xx
  // - s_yy) / 2 and centre sigma_c = (sigma_xx + sigma_yy) / 2 the cone
  // becomes R = k (xi c - eta sigma_c) / eta with
  //   k = eta sqrt(1 - eta_bar^2 / 3) / (1 - eta eta_bar / 3),
  // and for c = 0 sigma_yy / sigma_xx = (1 + k) / (1 - k). Mohr-Coulomb
  // has k = sin(phi); the plane-strain fit gives k = sin(phi) exactly for
  // psi = phi.
  double
  biaxial_limit(const Parameters  &p,
                const double       p0,
                const double       strain,
                const unsigned int n_steps,
                double            &max_residual)
  {
    const auto            model  = make_model(p);
    SymmetricTensor<2, 3> stress = -p0 * unit_symmetric_tensor<3>();
    double                state  = 0;
    const double          d      = strain / n_steps;
    max_residual                 = 0;
    for (unsigned int n = 0; n < n_steps; ++n)
      {
        const auto residual =
          [&](const double x, SymmetricTensor<2, 3> &s, double &st) {
            s  = stress;
            st = state;
            SymmetricTensor<2, 3> de;
            de[0][0] = x;
            de[1][1] = -d;
            model->update_stress(de, s, ArrayView<double>(&st, 1), 1.);
            return s[0][0] + p0;
          };
        SymmetricTensor<2, 3> s;
        double                st;
        double                lo = -10 * d, hi = 10 * d;
        double f_lo = residual(lo, s, st), f_hi = residual(hi, s, st);
        double x = 0, f = 0;
        int    side = 0;
        for (unsigned int it = 0; it < 200; ++it)
          {
            x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
            f = residual(x, s, st);
            if (std::abs(f) <= 1e-12 * p0 || hi - lo < 1e-16 * d)
              break;
            if (f < 0)
              {
                lo = x, f_lo = f;
                if (side == -1)
                  f_hi *= 0.5;
                side = -1;
              }
            else
              {
                hi = x, f_hi = f;
                if (side == 1)
                  f_lo *= 0.5;
                side = 1;
              }
          }
        max_residual = std::max(max_residual, std::abs(f) / p0);
        stress       = s;
        state        = st;
      }
    return stress[1][1];
  }


  void
  test_plane_strain()
  {
    std::cout << "(5) plane-strain biaxial compression (sigma_xx = -p0 = "
                 "-100 kPa, eps_zz = 0, eps_yy to -0.4 in 4000 steps; phi "
                 "30, c 0)\n";
    const double p0 = 1e5, sin_phi = std::sin(30 * degree);
    const double mc = -p0 * (1 + sin_phi) / (1 - sin_phi);
    struct Case
    {
      std::string fit;
      double      psi;
      double      tolerance;
    };
    // Tolerance 1e-6: the limit is approached exponentially as the zz
    // stress settles (the non-associated and the compression-fit cases
    // are still 3e-4 and 7e-3 away at eps_yy = -0.1, 5e-7 and 5e-9 at -0.2);
    // at -0.4 the remaining difference is rounding.
    for (const Case &c : {Case{"plane strain", 30., 1e-6},
                          Case{"plane strain", 0., 1e-6},
                          Case{"compression", 30., 1e-6}})
      {
        Parameters p;
        p.fit                 = c.fit;
        p.psi                 = c.psi;
        double       residual = 0;
        const double syy      = biaxial_limit(p, p0, 0.4, 4000, residual);
        const auto [eta, xi]  = fit_coefficients(p.fit, p.phi);
        (void)xi;
        const double eta_bar = fit_coefficients(p.fit, p.psi).first;
        const double k =
          eta * std::sqrt(1 - eta_bar * eta_bar / 3) / (1 - eta * eta_bar / 3);
        const double reference = -p0 * (1 + k) / (1 - k);
        std::cout << "  " << c.fit << " fit, psi = " << c.psi
                  << " (lateral stress residual / p0 <= "
                  << (residual <= 1e-12 ? "1e-12" : "MORE THAN 1e-12")
                  << "):\n";
        compare("limit sigma_yy [Pa] vs (1 + k) / (1 - k) closed form",
                syy,
                reference,
                c.tolerance);
        std::cout << "    k = " << k << ", Mohr-Coulomb sin(phi) = " << sin_phi
                  << "; sigma_yy relative to the Mohr-Coulomb plane-strain "
                     "limit "
                  << mc << ": " << flush_to_zero(relative(syy, mc), 1e-9)
                  << '\n';
        if (c.fit == "plane strain" && c.psi == 30.)
          check(std::abs(relative(syy, mc)) <= 1e-6,
                "plane-strain fit, associated: Mohr-Coulomb plane-strain "
                "collapse (|error| <= 1e-6)");
      }
  }


  // Simple shear through the driver, psi = 0, c = 20 kPa: the mean stress
  // stays at -p0 (no volume change at all), and at the limit the deviator
  // is pure xy shear, so sigma_xy = xi c + eta p0 for any fit.
  void
  test_simple_shear()
  {
    std::cout << "(6) simple shear through the driver (plane-strain fit, phi "
                 "30, psi 0, c 20 kPa, p0 100 kPa, gamma to 0.1 in 400 "
                 "steps)\n";
    Parameters p;
    p.fit               = "plane strain";
    p.c                 = 2e4;
    const double p0     = 1e5;
    const auto   driver = MPM::MaterialPointDriver::from_text(
      driver_text(p, "simple shear", p0, 0.1, 400));
    const auto  history  = driver.run_path();
    const auto &last     = history.records.back();
    const auto [eta, xi] = fit_coefficients(p.fit, p.phi);
    // Tolerance 1e-12: the limit is reached in one return and kept.
    compare("final sigma_xy [Pa]",
            last.stress[0][1],
            xi * p.c + eta * p0,
            1e-12);
    compare("final mean stress [Pa]", mean(last.stress), -p0, 1e-12);
    // The elastic part: sigma_xy = G gamma up to gamma_y = tau / G.
    const double gamma_y = (xi * p.c + eta * p0) / p.G();
    double       e       = 0;
    for (const auto &r : history.records)
      if (r.path_strain < gamma_y)
        e = std::max(e, std::abs(r.stress[0][1] - p.G() * r.path_strain) / p0);
    std::cout << "    elastic part: max |sigma_xy - G gamma| / p0 = "
              << flush_to_zero(e, 1e-12) << " (<= 1e-12)\n";
    check(e <= 1e-12, "elastic part of simple shear");
    compare("final plastic shear strain",
            last.state[0],
            (0.1 - gamma_y) / std::sqrt(3.),
            1e-10);
  }


  // (d) Undrained triaxial compression with psi = 0: no volume change,
  // elastic or plastic, so the mean stress stays at -p0; the deviator
  // grows elastically (sqrt(J2) = sqrt(3) G eps_a) until the cone,
  // sqrt(J2) = xi c + eta p0, and stays there.
  void
  test_undrained()
  {
    std::cout << "(7) undrained triaxial compression through the driver "
                 "(compression fit, phi 30, psi 0, c 20 kPa, p0 100 kPa, "
                 "eps_a to 0.05 in 500 steps)\n";
    Parameters p;
    p.c                 = 2e4;
    const double p0     = 1e5;
    const auto   driver = MPM::MaterialPointDriver::from_text(
      driver_text(p, "undrained triaxial", p0, 0.05, 500));
    const auto history    = driver.run_path();
    const auto [eta, xi]  = fit_coefficients(p.fit, p.phi);
    const double limit    = xi * p.c + eta * p0;
    const double eps_y    = limit / (std::sqrt(3.) * p.G());
    double       max_mean = 0, max_elastic = 0, max_f_after = 0;
    unsigned int first_plastic = 0;
    for (const auto &r : history.records)
      {
        max_mean = std::max(max_mean, std::abs(mean(r.stress) + p0) / p0);
        if (r.path_strain < eps_y)
          max_elastic =
            std::max(max_elastic,
                     std::abs(root_j2(r.stress) -
                              std::sqrt(3.) * p.G() * r.path_strain) /
                       p0);
        else
          {
            if (first_plastic == 0)
              first_plastic = r.step;
            max_f_after =
              std::max(max_f_after, std::abs(yield(r.stress, p)) / p0);
          }
      }
    std::cout << "    max |sigma_m + p0| / p0 over the path = "
              << flush_to_zero(max_mean, 1e-12) << " (<= 1e-12)\n";
    check(max_mean <= 1e-12, "mean stress constant");
    std::cout << "    elastic part: max |sqrt(J2) - sqrt(3) G eps_a| / p0 = "
              << flush_to_zero(max_elastic, 1e-12) << " (<= 1e-12)\n";
    check(max_elastic <= 1e-12, "elastic part");
    std::cout << "    first step at or past eps_y = " << eps_y << ": "
              << first_plastic << ", reference ceil(500 eps_y / 0.05) = "
              << std::ceil(500 * eps_y / 0.05) << "; max |f| / p0 from there = "
              << flush_to_zero(max_f_after, 1e-12) << " (<= 1e-12)\n";
    check(max_f_after <= 1e-12, "reaches the cone and stays on it");
    compare("final sqrt(J2) [Pa]",
            root_j2(history.records.back().stress),
            limit,
            1e-12);
  }


  int
  run(int /*argc*/, char ** /*argv*/)
  {
    std::cout << "# numdiff: -a 1e-9 -r 1e-6\n" << std::setprecision(8);
    test_input();
    test_elastic();
    test_random();
    test_apex();
    test_drained_triaxial();
    test_plane_strain();
    test_simple_shear();
    test_undrained();
    return summary();
  }
} // namespace unit_drucker_prager

MPM_UNIT_TEST_REGISTER(drucker_prager)
