// Cost of one Mohr-Coulomb stress update (elastic predictor, plane-strain
// principal stresses, return mapping, plastic strain), in nanoseconds per
// call, on states like the flume's.
//
// The states come from material points driven from zero stress along
// plane-strain strain paths (a steady simple shear of 3e-5 to 1e-4 per
// increment, a steady volume change of -3e-5 to 3e-5, noise of 1e-5) with
// the flume's sand (E 2 MPa, nu 0.3, phi 40, psi 0, c 0, tension cutoff 0).
// After 300 increments the mix of returns of the next one is the flume's
// (counted there over its first 0.25 s): about 63 % on the main plane,
// 36 % on the main plane with the tension cutoff of s1, 1 % elastic. The
// benchmark times that next increment of every point, many times over
// (the same inputs each time), and prints the minimum over the
// repetitions with the mix of returns taken.
//
// Why a separate benchmark: it isolates the model from the rest of the
// step. The virtual machines this code was tuned on drift by up to 25 %
// within minutes, and even the minimum of one run of this benchmark moves
// with them (46-60 ns for the same build in session 6): compare two builds
// of the library by running this executable alternately with
// LD_LIBRARY_PATH pointing at each (the RUNPATH lets it override), several
// times, and compare the minima (session 6: 58.3 ns for session 5's
// library, 46.4 ns for session 6's, best of three runs each).
//
// Usage: mohr_coulomb_benchmark [points (default 50000)]

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <mpm/materials/isotropic_elasticity.h>
#include <mpm/materials/mohr_coulomb.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <map>
#include <random>
#include <string>
#include <vector>

using namespace dealii;
using MPM::MaterialModels::MohrCoulomb;

namespace
{
  struct Input
  {
    SymmetricTensor<2, 3> strain_increment;
    SymmetricTensor<2, 3> stress;
    double                plastic_strain = 0;
  };

  /**
   * A strain path: a steady simple shear with a steady volume change, each
   * chosen per point, and noise on every increment, as a point of a
   * flowing granular mass sees: sheared points at some confinement sit on
   * the main plane, points that dilate lose their confinement and go to
   * the tension cutoff (the sand near the free surface).
   */
  struct Path
  {
    double shear;
    double volumetric;

    SymmetricTensor<2, 3>
    increment(std::mt19937_64 &generator) const
    {
      std::normal_distribution<double> noise(0., 1e-5);
      SymmetricTensor<2, 3>            e;
      e[0][0] = 0.5 * volumetric + noise(generator);
      e[1][1] = 0.5 * volumetric + noise(generator);
      e[0][1] = shear + noise(generator);
      return e;
    }
  };
} // namespace


int
main(int argc, char **argv)
{
  const unsigned int n_points =
    argc > 1 ? static_cast<unsigned int>(std::atof(argv[1])) : 50000;

  ParameterHandler prm;
  MohrCoulomb::declare_parameters(prm);
  prm.set("Young's modulus", 2e6);
  prm.set("Poisson's ratio", 0.3);
  prm.set("Friction angle", 40.);
  prm.set("Dilation angle", 0.);
  prm.set("Cohesion", 0.);
  prm.set("Tension cutoff", 0.);
  MohrCoulomb model;
  model.parse_parameters(prm);
  // The model's elastic part, for the trial stresses of the mix below.
  MPM::IsotropicElasticity elasticity;
  elasticity.parse_parameters(prm, "mohr coulomb");

  // Load every point along its own random path, then keep its next
  // increment as the timed input.
  std::mt19937_64                        generator(2026);
  std::uniform_real_distribution<double> shear(3e-5, 1e-4);
  std::uniform_real_distribution<double> volumetric(-3e-5, 3e-5);
  std::vector<Input>                     inputs(n_points);
  for (Input &input : inputs)
    {
      const Path path{shear(generator), volumetric(generator)};
      for (unsigned int k = 0; k < 300; ++k)
        model.update_stress(path.increment(generator),
                            input.stress,
                            ArrayView<double>(&input.plastic_strain, 1), 1.);
      input.strain_increment = path.increment(generator);
    }

  // The mix of returns (set bits of the active planes, 0 = elastic), from
  // the principal values of each trial stress.
  std::map<unsigned int, unsigned int> mix;
  for (const Input &input : inputs)
    {
      SymmetricTensor<2, 3> trial = input.stress;
      elasticity.add_stress_increment(input.strain_increment, trial);
      const double c = 0.5 * (trial[0][0] + trial[1][1]);
      const double h = 0.5 * (trial[0][0] - trial[1][1]);
      const double r = std::sqrt(h * h + trial[0][1] * trial[0][1]);
      std::array<double, 3> s{{c + r, c - r, trial[2][2]}};
      std::sort(s.begin(), s.end(), std::greater<double>());
      ++mix[model.return_principal(s)];
    }

  double best = 1e30, checksum = 0;
  for (unsigned int repetition = 0; repetition < 30; ++repetition)
    {
      const auto start = std::chrono::steady_clock::now();
      for (const Input &input : inputs)
        {
          SymmetricTensor<2, 3> stress         = input.stress;
          double                plastic_strain = input.plastic_strain;
          model.update_stress(input.strain_increment,
                              stress,
                              ArrayView<double>(&plastic_strain, 1), 1.);
          checksum += stress[1][1] + plastic_strain;
        }
      best = std::min(best,
                      std::chrono::duration<double>(
                        std::chrono::steady_clock::now() - start)
                        .count());
    }

  std::cout << "Mohr-Coulomb stress update, " << n_points
            << " points on random plane-strain paths (flume sand)\n"
            << "returns taken (bits of the active planes: 1 main plane s1-s3, "
               "2 and 4 the other shear planes, 8/16/32 the tension cutoffs "
               "of s1/s2/s3; 0 elastic):\n";
  for (const auto &[bits, count] : mix)
    std::cout << "  " << std::setw(3) << bits << ": " << std::fixed
              << std::setprecision(1) << 100. * count / n_points << " %\n";
  std::cout << std::defaultfloat << std::setprecision(4)
            << "time per update (minimum over 30 repetitions): "
            << best / n_points * 1e9 << " ns  (checksum " << checksum
            << ")\n";
}
