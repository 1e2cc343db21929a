// Unit test of the Mohr-Coulomb model (tension positive): the elastic step,
// a simple shear test to failure, the apex, the edges and the tension
// cutoff, no plastic volume change for psi = 0, random trial stresses
// (admissibility and invariance under a rotation of the frame) and
// idempotency of a return. Each line prints the value and its reference.

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <mpm/base/input_error.h>
#include <mpm/materials/linear_elastic.h>
#include <mpm/materials/mohr_coulomb.h>

#include "unit_test_tools.h"

#include <array>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <string>

namespace unit_mohr_coulomb
{
  using namespace dealii;
  using namespace UnitTest;
  using MPM::MaterialModels::MohrCoulomb;

  struct Parameters
  {
    double E   = 2e6;
    double nu  = 0.3;
    double phi = 40;
    double psi = 0;
    double c   = 0;
    double T   = 0;
  };

  std::unique_ptr<MohrCoulomb>
  make_model(const Parameters &p)
  {
    ParameterHandler prm;
    MohrCoulomb::declare_parameters(prm);
    prm.set("Young's modulus", p.E);
    prm.set("Poisson's ratio", p.nu);
    prm.set("Friction angle", p.phi);
    prm.set("Dilation angle", p.psi);
    prm.set("Cohesion", p.c);
    prm.set("Tension cutoff", p.T);
    auto model = std::make_unique<MohrCoulomb>();
    model->parse_parameters(prm);
    return model;
  }

  std::array<double, 3>
  principal(const SymmetricTensor<2, 3> &s)
  {
    const auto e =
      eigenvectors(s, SymmetricTensorEigenvectorMethod::ql_implicit_shifts);
    return {{e[0].first, e[1].first, e[2].first}};
  }

  // The yield functions written out again, independently of the model:
  // the Mohr-Coulomb function and the tension cutoff, the larger of both.
  double
  yield(const SymmetricTensor<2, 3> &stress, const Parameters &p)
  {
    const auto   s   = principal(stress);
    const double phi = p.phi * M_PI / 180;
    const double f_mc =
      (s[0] - s[2]) + (s[0] + s[2]) * std::sin(phi) - 2 * p.c * std::cos(phi);
    return std::max(f_mc, s[0] - p.T);
  }

  double
  mean(const SymmetricTensor<2, 3> &s)
  {
    return trace(s) / 3;
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

  // A rotation from a unit quaternion.
  Tensor<2, 3>
  rotation(double q0, double q1, double q2, double q3)
  {
    const double n = std::sqrt(q0 * q0 + q1 * q1 + q2 * q2 + q3 * q3);
    q0 /= n, q1 /= n, q2 /= n, q3 /= n;
    Tensor<2, 3> R;
    R[0][0] = 1 - 2 * (q2 * q2 + q3 * q3);
    R[0][1] = 2 * (q1 * q2 - q0 * q3);
    R[0][2] = 2 * (q1 * q3 + q0 * q2);
    R[1][0] = 2 * (q1 * q2 + q0 * q3);
    R[1][1] = 1 - 2 * (q1 * q1 + q3 * q3);
    R[1][2] = 2 * (q2 * q3 - q0 * q1);
    R[2][0] = 2 * (q1 * q3 - q0 * q2);
    R[2][1] = 2 * (q2 * q3 + q0 * q1);
    R[2][2] = 1 - 2 * (q1 * q1 + q2 * q2);
    return R;
  }

  SymmetricTensor<2, 3>
  rotate(const SymmetricTensor<2, 3> &s, const Tensor<2, 3> &R)
  {
    return symmetrize(Tensor<2, 3>(R * Tensor<2, 3>(s) * transpose(R)));
  }

  // Return a stress with a zero strain increment: the stress is its own
  // trial stress. Gives the accumulated plastic shear strain.
  double
  return_stress(const MohrCoulomb &model, SymmetricTensor<2, 3> &stress)
  {
    double state = 0;
    model.update_stress(SymmetricTensor<2, 3>(),
                        stress,
                        ArrayView<double>(&state, 1),
                        1.);
    return state;
  }

  std::string
  set_name(const unsigned int set)
  {
    if (set == 0)
      return "elastic";
    static const char *names[] = {"shear_13",
                                  "shear_12",
                                  "shear_23",
                                  "tension_1",
                                  "tension_2",
                                  "tension_3",
                                  "fallback"};
    std::string        name;
    for (unsigned int k = 0; k < 7; ++k)
      if (set & (1u << k))
        name += (name.empty() ? "" : "+") + std::string(names[k]);
    return name;
  }

  unsigned int
  active_set(const MohrCoulomb &model, const SymmetricTensor<2, 3> &trial)
  {
    auto s = principal(trial);
    return model.return_principal(s);
  }


  void
  test_input_errors()
  {
    std::cout << "(0) input checks\n";
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
    p.nu = 0.5;
    expect_error(p);
    p   = Parameters();
    p.E = 0;
    expect_error(p);
    p     = Parameters();
    p.psi = 45;
    expect_error(p);
    p   = Parameters();
    p.T = 100;
    expect_error(p);
    p      = Parameters();
    p.c    = 1e4;
    p.T    = 1e4 / std::tan(40 * M_PI / 180);
    auto m = make_model(p);
    std::cout << "    T = c cot(phi) accepted; default K0 = " << m->default_k0()
              << ", reference 1 - sin(40 deg) = "
              << 1 - std::sin(40 * M_PI / 180) << '\n';
  }


  void
  test_elastic()
  {
    std::cout << "(1) elastic increment vs linear elastic\n";
    const Parameters p;
    const auto       mc = make_model(p);

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
    SymmetricTensor<2, 3> s_mc = diagonal(-1e5, -1e5, -1e5), s_le = s_mc;
    double                state = 0;
    mc->update_stress(de, s_mc, ArrayView<double>(&state, 1), 1.);
    le.update_stress(de, s_le, ArrayView<double>(), 1.);
    std::cout << "    sigma_xx = " << s_mc[0][0] << ", linear elastic "
              << s_le[0][0] << "; sigma_xy = " << s_mc[0][1]
              << ", linear elastic " << s_le[0][1]
              << "; sigma_zz = " << s_mc[2][2] << ", linear elastic "
              << s_le[2][2] << '\n';
    std::cout << "    max |difference| = " << max_abs(s_mc - s_le)
              << ", plastic shear strain = " << state << '\n';
    check(max_abs(s_mc - s_le) == 0 && state == 0,
          "identical to linear elastic, no plastic strain");
    std::cout << "    p-wave modulus " << mc->p_wave_modulus()
              << ", linear elastic " << le.p_wave_modulus()
              << "; energy density " << mc->strain_energy_density(s_mc)
              << ", linear elastic " << le.strain_energy_density(s_le) << '\n';
  }


  void
  test_simple_shear()
  {
    std::cout << "(2) simple shear from p = -100 kPa, 200 steps of "
                 "gamma = 1e-3 (E 2 MPa, nu 0.3, phi 40, psi 0, c 0)\n";
    const Parameters p;
    const auto       model   = make_model(p);
    const double     G       = p.E / (2 * (1 + p.nu));
    const double     sin_phi = std::sin(p.phi * M_PI / 180);

    SymmetricTensor<2, 3> stress = diagonal(-1e5, -1e5, -1e5);
    SymmetricTensor<2, 3> de;
    de[0][1]                   = 0.5e-3;
    double       state         = 0;
    unsigned int first_plastic = 0;
    for (unsigned int step = 1; step <= 200; ++step)
      {
        model->update_stress(de, stress, ArrayView<double>(&state, 1), 1.);
        if (state > 0 && first_plastic == 0)
          first_plastic = step;
      }
    const auto   s   = principal(stress);
    const double tau = 1e5 * sin_phi;
    std::cout << "    first plastic step " << first_plastic
              << ", reference ceil(p sin(phi) / (G gamma)) = "
              << std::ceil(tau / G / 1e-3) << '\n';
    std::cout << "    principal stresses " << s[0] << ' ' << s[1] << ' ' << s[2]
              << "; sigma_xy = " << stress[0][1]
              << ", reference -p sin(phi) = " << tau << '\n';
    const double f_rel = yield(stress, p) / std::abs(mean(stress));
    std::cout << "    f / |p| = " << flush_to_zero(f_rel) << '\n';
    check(std::abs(f_rel) < 1e-10, "on the yield surface");
    const double ratio = s[2] / s[0], reference = (1 + sin_phi) / (1 - sin_phi);
    std::cout << "    sigma_3 / sigma_1 = " << ratio
              << ", reference (1 + sin phi) / (1 - sin phi) = " << reference
              << '\n';
    check(std::abs(ratio - reference) < 1e-8 * reference, "principal ratio");
    std::cout << "    mean stress " << mean(stress)
              << ", reference -100000 (psi = 0, isochoric shear)\n";
    check(std::abs(mean(stress) + 1e5) < 1e-6, "mean stress unchanged");
    const double state_ref = (0.2 - tau / G) / std::sqrt(3.);
    std::cout << "    plastic shear strain " << state
              << ", reference (0.2 - tau / G) / sqrt(3) = " << state_ref
              << '\n';
    check(std::abs(state - state_ref) < 1e-8, "accumulated plastic strain");
  }


  void
  test_apex()
  {
    std::cout << "(3) apex return\n";
    Parameters            p;
    const auto            sand           = make_model(p);
    SymmetricTensor<2, 3> a              = diagonal(1e4, 5e3, -2e3);
    a[0][1]                              = 3e3;
    a[1][2]                              = -1e3;
    const SymmetricTensor<2, 3> trials[] = {a,
                                            diagonal(1e4, 1e4, 1e4),
                                            diagonal(5e4, -1e3, -1e3)};
    for (auto stress : trials)
      {
        const unsigned int set = active_set(*sand, stress);
        return_stress(*sand, stress);
        std::cout << "    c = 0, trial (" << set_name(set)
                  << "): max |sigma_ij| = " << max_abs(stress)
                  << ", reference 0\n";
        check(max_abs(stress) == 0, "exactly zero stress");
      }
    // A large tensile strain increment from a compressed state.
    SymmetricTensor<2, 3> stress = diagonal(-1e5, -1e5, -1e5), de;
    de[0][0]                     = 0.2;
    de[0][1]                     = 0.05;
    double state                 = 0;
    sand->update_stress(de, stress, ArrayView<double>(&state, 1), 1.);
    std::cout << "    c = 0, tensile increment 0.2 from -100 kPa: max "
                 "|sigma_ij| = "
              << max_abs(stress) << ", reference 0\n";
    check(max_abs(stress) == 0, "exactly zero stress");

    p.c                    = 1e4;
    p.T                    = 5e3;
    const auto cohesive    = make_model(p);
    stress                 = diagonal(1e5, 1e5, 1e5);
    const unsigned int set = active_set(*cohesive, stress);
    return_stress(*cohesive, stress);
    std::cout << "    c = 10 kPa, T = 5 kPa (" << set_name(set)
              << "): sigma = " << stress[0][0] << ' ' << stress[1][1] << ' '
              << stress[2][2] << ", reference T = 5000\n";
    check(max_abs(stress - diagonal(5e3, 5e3, 5e3)) == 0, "exactly T I");
  }


  void
  test_edges()
  {
    std::cout << "(4) edge and tension returns (trials rotated out of the "
                 "principal frame)\n";
    const Tensor<2, 3> R = rotation(0.9, 0.2, -0.3, 0.4);
    struct Case
    {
      std::string           name;
      Parameters            p;
      SymmetricTensor<2, 3> trial;
      unsigned int          expected;
    };
    Parameters cohesive;
    cohesive.c         = 2e4;
    cohesive.T         = 1e4;
    cohesive.psi       = 10;
    const Case cases[] = {
      {"triaxial compression", Parameters(), diagonal(-5e4, -5e4, -3e5), 1 | 4},
      {"triaxial compression, far",
       Parameters(),
       diagonal(-1e4, -1e4, -1e6),
       1 | 4},
      {"triaxial extension", Parameters(), diagonal(-5e4, -3e5, -3e5), 1 | 2},
      {"triaxial extension, far",
       Parameters(),
       diagonal(-1e4, -1e6, -1e6),
       1 | 2},
      {"compression, c = 20 kPa, psi = 10",
       cohesive,
       diagonal(0, 0, -3e5),
       1 | 4},
      {"tension plane, c = 20 kPa", cohesive, diagonal(3e4, 0, 0), 8},
      {"tension and main plane, c = 20 kPa",
       cohesive,
       diagonal(6e4, 5e3, -5e4),
       1 | 8},
      {"tension corner and compression edge, c = 20 kPa",
       cohesive,
       diagonal(2e5, 5e4, -1e5),
       1 | 4 | 8}};
    for (const auto &c : cases)
      {
        const auto            model  = make_model(c.p);
        SymmetricTensor<2, 3> stress = rotate(c.trial, R);
        const unsigned int    set    = active_set(*model, stress);
        return_stress(*model, stress);
        const auto   s     = principal(stress);
        const double scale = std::abs(mean(c.trial));
        std::cout << "    " << c.name << ": " << set_name(set) << ", expected "
                  << set_name(c.expected) << '\n'
                  << "      principal stresses " << s[0] << ' ' << s[1] << ' '
                  << s[2] << ", f / |p_trial| = "
                  << flush_to_zero(yield(stress, c.p) / scale) << '\n';
        if (c.expected & 4)
          std::cout << "      (s1 - s2) / |p_trial| = "
                    << flush_to_zero((s[0] - s[1]) / scale)
                    << ", reference 0\n";
        if (c.expected & 2)
          std::cout << "      (s2 - s3) / |p_trial| = "
                    << flush_to_zero((s[1] - s[2]) / scale)
                    << ", reference 0\n";
        if (c.expected & 8)
          std::cout << "      s1 = " << s[0] << ", reference T = " << c.p.T
                    << '\n';
        if (c.expected & 16)
          std::cout << "      s2 = " << s[1] << ", reference T = " << c.p.T
                    << '\n';
        check(set == c.expected && std::abs(yield(stress, c.p)) < 1e-10 * scale,
              "expected case, on the surface");
      }
  }


  void
  test_no_dilation()
  {
    std::cout << "(5) psi = 0: mean stress changes only elastically\n";
    const Parameters      p;
    const auto            model = make_model(p);
    const double          K     = p.E / (3 * (1 - 2 * p.nu));
    SymmetricTensor<2, 3> de;
    de[0][0]                     = -1e-3;
    de[1][1]                     = -2e-3;
    de[0][1]                     = 0.05;
    SymmetricTensor<2, 3> stress = diagonal(-1e5, -1e5, -1e5);
    SymmetricTensor<2, 3> trial =
      stress +
      diagonal(1, 1, 1) * (K - 2. / 3 * p.E / (2 * (1 + p.nu))) * trace(de) +
      p.E / (1 + p.nu) * de;
    const unsigned int set   = active_set(*model, trial);
    double             state = 0;
    model->update_stress(de, stress, ArrayView<double>(&state, 1), 1.);
    std::cout << "    " << set_name(set) << ", plastic shear strain " << state
              << "; mean stress " << mean(stress)
              << ", elastic prediction -1e5 + K tr(de) = "
              << -1e5 + K * trace(de) << '\n';
    check(state > 0 &&
            std::abs(mean(stress) - (-1e5 + K * trace(de))) < 1e-10 * 1e5,
          "no plastic volume change");

    Parameters dilatant = p;
    dilatant.psi        = 10;
    const auto model2   = make_model(dilatant);
    stress              = diagonal(-1e5, -1e5, -1e5);
    state               = 0;
    model2->update_stress(de, stress, ArrayView<double>(&state, 1), 1.);
    std::cout << "    psi = 10 for comparison: mean stress " << mean(stress)
              << " (dilation lowers the compression)\n";
  }


  void
  test_random()
  {
    std::cout << "(6) 10000 random trial stresses, three parameter sets\n";
    Parameters sets[3];
    sets[1].phi = 30;
    sets[1].psi = 10;
    sets[1].c   = 2e4;
    sets[1].T   = 1e4;
    sets[2].phi = 35;
    sets[2].psi = 35;
    sets[2].c   = 1e4;
    sets[2].T   = 1e4 / std::tan(35 * M_PI / 180);
    std::unique_ptr<MohrCoulomb> models[3];
    for (unsigned int i = 0; i < 3; ++i)
      models[i] = make_model(sets[i]);

    // mt19937 is specified bit for bit; the distributions of <random> are
    // not, so map its output to [a, b) by hand.
    std::mt19937 rng(42);
    const auto   uniform = [&rng](const double a, const double b) {
      return a + (b - a) * (rng() / 4294967296.);
    };

    double max_f = 0, max_rotation = 0, max_repeat = 0;
    std::map<unsigned int, unsigned int> count;
    for (unsigned int n = 0; n < 10000; ++n)
      {
        const unsigned int    m = n % 3;
        SymmetricTensor<2, 3> trial;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = i; j < 3; ++j)
            trial[i][j] = uniform(-1e5, 1e5);
        const double shift = uniform(-2e5, 1e5);
        for (unsigned int i = 0; i < 3; ++i)
          trial[i][i] += shift;
        const double scale = max_abs(trial);

        ++count[m * 1000 + active_set(*models[m], trial)];
        SymmetricTensor<2, 3> stress = trial;
        return_stress(*models[m], stress);
        max_f = std::max(max_f, yield(stress, sets[m]) / scale);

        const Tensor<2, 3>    R       = rotation(uniform(-1, 1),
                                        uniform(-1, 1),
                                        uniform(-1, 1),
                                        uniform(-1, 1));
        SymmetricTensor<2, 3> rotated = rotate(trial, R);
        return_stress(*models[m], rotated);
        max_rotation =
          std::max(max_rotation, max_abs(rotated - rotate(stress, R)) / scale);

        SymmetricTensor<2, 3> again = stress;
        return_stress(*models[m], again);
        max_repeat = std::max(max_repeat, max_abs(again - stress));
      }
    std::cout << "    max f / max|sigma_trial| = " << flush_to_zero(max_f)
              << " (<= 1e-10 required)\n";
    check(max_f <= 1e-10, "all returned stresses admissible");
    std::cout << "    max |R sigma R^T - return(R sigma_trial R^T)| / "
                 "max|sigma_trial| = "
              << flush_to_zero(max_rotation, 1e-9) << " (<= 1e-9 required)\n";
    check(max_rotation <= 1e-9, "invariant under rotation of the frame");
    std::cout << "    (7) max |change| when a returned stress is returned "
                 "again = "
              << max_repeat << ", reference 0\n";
    check(max_repeat == 0, "return is idempotent");
    std::cout << "    cases taken (set: c = 0 sand | c = 20 kPa, T = 10 kPa, "
                 "psi = 10 | associated, T = c cot phi):\n";
    bool fallback = false;
    for (const auto &[key, n] : count)
      {
        std::cout << "      " << key / 1000 << ' ' << std::setw(32) << std::left
                  << set_name(key % 1000) << std::right << n << '\n';
        fallback = fallback || (key % 1000) & MohrCoulomb::fallback;
      }
    check(!fallback, "no fallback");
  }


  void
  test_idempotent()
  {
    std::cout << "(7) a returned stress returned again with zero increment\n";
    const Parameters      p;
    const auto            model  = make_model(p);
    SymmetricTensor<2, 3> stress = diagonal(-5e4, -5e4, -3e5);
    stress[0][2]                 = 4e4;
    return_stress(*model, stress);
    SymmetricTensor<2, 3> again = stress;
    const double          state = return_stress(*model, again);
    std::cout << "    edge return: max |change| = " << max_abs(again - stress)
              << ", plastic strain added = " << state << ", reference 0 0\n";
    check(max_abs(again - stress) == 0 && state == 0, "unchanged");
  }


  int
  run(int /*argc*/, char ** /*argv*/)
  {
    std::cout << "# numdiff: -a 1e-9 -r 1e-5\n";
    std::cout << std::setprecision(6);
    test_input_errors();
    test_elastic();
    test_simple_shear();
    test_apex();
    test_edges();
    test_no_dilation();
    test_random();
    test_idempotent();
    return UnitTest::summary();
  }
} // namespace unit_mohr_coulomb

MPM_UNIT_TEST_REGISTER(mohr_coulomb)
