// Unit test of the objective stress rate (ObjectiveStressRate): the
// rotation keeps the stress's invariants (it is exactly orthogonal, for
// any step), the plane-strain path (2D) gives the 3D rotation's result
// for an in-plane spin, a step of 'none' changes nothing, and the rotation
// is the Jaumann rate to first order: (sigma' - sigma) / dt -> W sigma -
// sigma W. The closed-form simple shear is checked through the
// material-point driver (tests/material_point_simple_shear_*.prm).

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <mpm/materials/objective_stress_rate.h>

#include "unit_test_tools.h"

#include <cmath>
#include <iostream>

namespace unit_objective_stress_rate
{
  using namespace dealii;
  using namespace UnitTest;
  using MPM::ObjectiveStressRate;

  ObjectiveStressRate
  make(const std::string &type)
  {
    ParameterHandler prm;
    ObjectiveStressRate::declare_parameters(prm);
    prm.set("Objective stress rate", type);
    ObjectiveStressRate rate;
    rate.parse_parameters(prm);
    return rate;
  }


  SymmetricTensor<2, 3>
  some_stress()
  {
    SymmetricTensor<2, 3> s;
    s[0][0] = -3.1e5, s[1][1] = -1.2e5, s[2][2] = -0.7e5;
    s[0][1] = 4.4e4, s[0][2] = -2.3e4, s[1][2] = 1.9e4;
    return s;
  }


  double
  norm_of(const SymmetricTensor<2, 3> &s)
  {
    return s.norm();
  }


  int
  run(int /*argc*/, char ** /*argv*/)
  {
    std::cout << "# numdiff: -a 1e-9 -r 1e-5\n";
    const ObjectiveStressRate   jaumann = make("jaumann"), none = make("none");
    const SymmetricTensor<2, 3> sigma = some_stress();

    std::cout
      << "invariants after a rotation by a large step (dt |W| = 1.5):\n";
    {
      Tensor<2, 3> L;
      L[0][1] = 2.0, L[1][0] = -1.0, L[0][2] = 0.7, L[2][1] = -0.4;
      SymmetricTensor<2, 3> rotated = sigma;
      jaumann.rotate<3>(rotated, L, 1.0);
      const double d1 =
        std::abs(first_invariant(rotated) - first_invariant(sigma)) /
        norm_of(sigma);
      const double d2 =
        std::abs(second_invariant(rotated) - second_invariant(sigma)) /
        std::pow(norm_of(sigma), 2);
      const double d3 =
        std::abs(third_invariant(rotated) - third_invariant(sigma)) /
        std::pow(norm_of(sigma), 3);
      std::cout << "  changed: "
                << (norm_of(rotated - sigma) > 0.1 * norm_of(sigma) ? "yes" :
                                                                      "no")
                << '\n';
      check(d1 < 1e-14 && d2 < 1e-14 && d3 < 1e-14,
            "I1, I2, I3 kept to 1e-14 (3D)");
    }

    std::cout << "plane strain against 3D, in-plane spin:\n";
    {
      Tensor<2, 2> L2;
      L2[0][1] = 0.8, L2[1][0] = -0.3, L2[0][0] = 0.2;
      Tensor<2, 3> L3;
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int j = 0; j < 2; ++j)
          L3[i][j] = L2[i][j];
      SymmetricTensor<2, 3> a = sigma, b = sigma;
      jaumann.rotate<2>(a, L2, 0.4);
      jaumann.rotate<3>(b, L3, 0.4);
      check(norm_of(a - b) < 1e-14 * norm_of(sigma),
            "the 2D rotation is the 3D one to 1e-14");
    }

    std::cout << "'none':\n";
    {
      Tensor<2, 3> L;
      L[0][1]                 = 2.0;
      SymmetricTensor<2, 3> s = sigma;
      none.rotate<3>(s, L, 1.0);
      check(s == sigma, "the stress is unchanged");
    }

    std::cout << "first order: (Q sigma Q^T - sigma) / dt against W sigma - "
                 "sigma W:\n";
    {
      Tensor<2, 3> L;
      L[0][1] = 2.0, L[1][0] = -1.0, L[0][2] = 0.7, L[2][1] = -0.4,
      L[1][2]                     = 0.3;
      const Tensor<2, 3> W        = 0.5 * (L - transpose(L));
      const Tensor<2, 3> s        = sigma;
      const Tensor<2, 3> exact    = W * s - s * W;
      double             previous = 0;
      for (const double dt : {1e-2, 5e-3, 2.5e-3})
        {
          SymmetricTensor<2, 3> rotated = sigma;
          jaumann.rotate<3>(rotated, L, dt);
          const Tensor<2, 3> rate  = (Tensor<2, 3>(rotated) - s) / dt;
          const double       error = (rate - exact).norm() / exact.norm();
          std::cout << "  dt = " << dt << ": relative error "
                    << flush_to_zero(error, 1e-12) << '\n';
          if (previous > 0)
            check(error < 0.55 * previous,
                  "the error halves with dt (first order)");
          previous = error;
        }
    }
    return summary();
  }
} // namespace unit_objective_stress_rate

MPM_UNIT_TEST_REGISTER(objective_stress_rate)
