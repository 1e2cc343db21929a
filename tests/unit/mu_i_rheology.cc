// Unit test of the mu(I) rheology (tension positive): steady simple shear
// at imposed shear rates must settle at tau / p = mu(I(gamma_dot)) with the
// pressure unchanged (no dilation); a step below the static friction is
// elastic; separated grains (p <= 0) carry nothing; bad input is refused.
// Each line prints the value and its reference.

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <mpm/base/input_error.h>
#include <mpm/materials/linear_elastic.h>
#include <mpm/materials/mu_i_rheology.h>

#include "unit_test_tools.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>

namespace unit_mu_i_rheology
{
  using namespace dealii;
  using namespace UnitTest;
  using MPM::MaterialModels::MuIRheology;

  constexpr double E = 2e6, nu = 0.3, d = 5e-4, rho_s = 2450, I0 = 0.279;
  constexpr double phi_s = 20.9, phi_2 = 32.76;

  std::unique_ptr<MuIRheology>
  make_model(const double static_angle  = phi_s,
             const double dynamic_angle = phi_2,
             const double diameter      = d)
  {
    ParameterHandler prm;
    MuIRheology::declare_parameters(prm);
    prm.set("Young's modulus", E);
    prm.set("Poisson's ratio", nu);
    prm.set("Static friction angle", static_angle);
    prm.set("Dynamic friction angle", dynamic_angle);
    prm.set("Reference inertial number", I0);
    prm.set("Grain diameter", diameter);
    prm.set("Grain density", rho_s);
    auto model = std::make_unique<MuIRheology>();
    model->parse_parameters(prm);
    return model;
  }


  void
  test_steady_shear()
  {
    std::cout << "steady simple shear at p = 1 kPa:\n";
    const auto   model = make_model();
    const double p     = 1000;
    for (const double rate : {0.1, 10., 100., 1000.})
      {
        const double          dt = 1e-5;
        SymmetricTensor<2, 3> stress;
        for (unsigned int a = 0; a < 3; ++a)
          stress[a][a] = -p;
        double state[2] = {0, 0};
        // Simple shear increments: de_xy = gamma_dot dt / 2.
        SymmetricTensor<2, 3> de;
        de[0][1] = 0.5 * rate * dt;
        // Long enough for the elastic loading to reach yield and settle
        // (G = 0.77 MPa: yield after tau / (G gamma_dot) s).
        const unsigned int n_steps = static_cast<unsigned int>(
          std::max(2e3, 5 * 1e3 / (7.7e5 * rate * dt)));
        for (unsigned int n = 0; n < n_steps; ++n)
          model->update_stress(de, stress, ArrayView<double>(state, 2), dt);
        const double I     = rate * d / std::sqrt(p / rho_s);
        const double ratio = stress[0][1] / (-trace(stress) / 3);
        std::cout << "  gamma_dot = " << rate << " 1/s: I = " << I
                  << ", tau / p = " << ratio
                  << ", mu(I) = " << model->friction(I)
                  << ", reported I = " << state[1] << '\n';
        check(std::abs(ratio - model->friction(I)) < 1e-8,
              "tau / p = mu(I) in steady shear");
        check(std::abs(state[1] - I) < 1e-8 * (1 + I),
              "the reported inertial number is the imposed one");
        check(std::abs(-trace(stress) / 3 - p) < 1e-9 * p,
              "the pressure is unchanged (no dilation)");
      }
  }


  void
  test_elastic_and_separated()
  {
    std::cout << "below the static friction, and in tension:\n";
    const auto                         model = make_model();
    MPM::MaterialModels::LinearElastic elastic;
    {
      ParameterHandler prm;
      MPM::MaterialModels::LinearElastic::declare_parameters(prm);
      prm.set("Young's modulus", E);
      prm.set("Poisson's ratio", nu);
      elastic.parse_parameters(prm);
    }
    SymmetricTensor<2, 3> s_mu, s_le;
    for (unsigned int a = 0; a < 3; ++a)
      s_mu[a][a] = s_le[a][a] = -1000;
    SymmetricTensor<2, 3> de;
    de[0][1]        = 1e-5; // tau = 2 G de_xy = 15 Pa << mu_s p = 382 Pa
    double state[2] = {0, 0};
    model->update_stress(de, s_mu, ArrayView<double>(state, 2), 1e-4);
    elastic.update_stress(de, s_le, ArrayView<double>(), 1e-4);
    std::cout << "  sigma_xy = " << s_mu[0][1] << ", linear elastic "
              << s_le[0][1] << '\n';
    check((s_mu - s_le).norm() == 0, "an elastic step is linear elastic");
    check(state[0] == 0, "no plastic strain");

    SymmetricTensor<2, 3> tension;
    tension[0][0] = 10;
    model->update_stress(SymmetricTensor<2, 3>(),
                         tension,
                         ArrayView<double>(state, 2),
                         1e-4);
    check(tension.norm() == 0, "separated grains (p <= 0) carry nothing");
  }


  void
  test_input_errors()
  {
    std::cout << "input errors:\n";
    const auto refused = [](const double s, const double dy, const double dd) {
      try
        {
          make_model(s, dy, dd);
        }
      catch (const MPM::InputError &e)
        {
          std::cout << "  " << e.what() << '\n';
          return true;
        }
      return false;
    };
    check(refused(30, 20, d), "dynamic friction below static refused");
    check(refused(0, 20, d), "zero static friction refused");
    check(refused(20, 30, 0), "zero grain diameter refused");
  }


  int
  run(int /*argc*/, char ** /*argv*/)
  {
    std::cout << "# numdiff: -a 1e-9 -r 1e-5\n";
    std::cout << std::setprecision(6);
    test_steady_shear();
    test_elastic_and_separated();
    test_input_errors();
    return UnitTest::summary();
  }
} // namespace unit_mu_i_rheology

MPM_UNIT_TEST_REGISTER(mu_i_rheology)
