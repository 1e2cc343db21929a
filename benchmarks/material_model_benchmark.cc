// Cost of one stress update of any registered material model, in
// nanoseconds per call, on a realistic mix of elastic and plastic states:
// the figure to compare models by (doc/materials.md, "Cost per stress update").
//
// Usage: material_model_benchmark case.prm [points (default 50000)] [3d]
//
// case.prm sets 'Materials' (the first material of the list, or the one
// named by 'Material point driver/Material', is the one timed) and
// 'Material point driver/Confining pressure' p0 > 0; it is read like the
// driver's input (MaterialPointDriver::from_text()), so any driver case
// runs here too. benchmarks/material_*.prm are the shipped cases.
//
// The states: every point starts from -p0 I and follows its own
// plane-strain path of 300 increments, a steady simple shear (total tensor
// shear strain up to 3 p0 / M, M the P-wave modulus, so that about two
// thirds of the points reach a frictional limit), a steady volume change
// (up to +-1.5 p0 / M in total, so that dilating points lose most of their
// confinement and reach the apex or the tension limit) and noise on every
// increment. The timed increment is the path's next one for half the
// points and an increment of the same size in a random plane-strain
// direction for the other half (unloading as well as loading), so that
// points on the yield surface leave it as they do in a flow. The
// benchmark times that increment of all points, through the MaterialModel
// interface as the MPM step calls it, many times over (the same inputs
// each time), and prints the median and the minimum over the repetitions
// with the fraction of points whose update was plastic (its stress differs
// from the elastic trial stress, with the elastic constants probed from
// the model).
//
// With '3d' every increment also gets out-of-plane shear noise (yz, xz),
// so that the stresses are general 3D ones: what a 3D run costs a model
// that needs principal stresses (Mohr-Coulomb's eigenvectors) and does not
// cost one that needs only invariants (Drucker-Prager).
//
// Why the median: the virtual machines this code runs on drift by up to
// 25 % within minutes (mohr_coulomb_benchmark.cc); compare models from
// runs made one after the other.

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <mpm/materials/material_point_driver.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;

namespace
{
  double
  max_abs(const SymmetricTensor<2, 3> &s)
  {
    double m = 0;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        m = std::max(m, std::abs(s[i][j]));
    return m;
  }

  /// A plane-strain strain increment of the given parts.
  SymmetricTensor<2, 3>
  plane_strain(const double xx, const double yy, const double xy)
  {
    SymmetricTensor<2, 3> e;
    e[0][0] = xx;
    e[1][1] = yy;
    e[0][1] = xy;
    return e;
  }
} // namespace


int
main(int argc, char **argv)
{
  if (argc < 2)
    {
      std::cerr << "usage: material_model_benchmark case.prm [points] [3d]\n";
      return 1;
    }
  const std::string  file     = argv[1];
  const unsigned int n_points =
    argc > 2 ? static_cast<unsigned int>(std::atof(argv[2])) : 50000;
  const bool three_d = argc > 3 && std::string(argv[3]) == "3d";

  std::ifstream in(file);
  if (!in)
    {
      std::cerr << "cannot read " << file << '\n';
      return 1;
    }
  std::stringstream text;
  text << in.rdbuf();

  const auto  driver = MPM::MaterialPointDriver::from_text(text.str());
  const auto &model  = *driver.material().model;

  // p0, from the driver's own subsection (the rest of the file skipped).
  ParameterHandler driver_prm;
  MPM::MaterialPointDriver::declare_parameters(driver_prm);
  driver_prm.parse_input_from_string(text.str(), "", true);
  driver_prm.enter_subsection("Material point driver");
  const double p0 = driver_prm.get_double("Confining pressure");
  driver_prm.leave_subsection();
  if (!(p0 > 0))
    {
      std::cerr << file
                << ": 'Material point driver/Confining pressure' must be "
                   "> 0 (the points start from -p0 I).\n";
      return 1;
    }

  const unsigned int n_state = model.n_state_variables();
  const unsigned int width   = std::max(1u, n_state);
  // A non-local model's regularised variable: each point stands for a
  // homogeneous body, so it is the point's own (as in the material-point
  // driver); the averaging over neighbours is the MPM step's cost, not the
  // model's.
  const auto *const nonlocal = model.nonlocal_variable();
  const auto        update   = [&](const SymmetricTensor<2, 3> &increment,
                            SymmetricTensor<2, 3>       &stress,
                            double                      *state) {
    if (nonlocal != nullptr)
      state[nonlocal->nonlocal_variable] = state[nonlocal->local_variable];
    model.update_stress(increment,
                        stress,
                        ArrayView<double>(state, n_state),
                        1.);
  };

  // The elastic constants, probed by a small compression from -p0 I
  // (elastic for any frictional model): lambda + 2 mu and lambda.
  double lambda = 0, mu = 0;
  {
    std::vector<double>   state(width, 0.);
    SymmetricTensor<2, 3> stress = -p0 * unit_symmetric_tensor<3>();
    model.initialize_state(ArrayView<double>(state.data(), n_state));
    const double delta = 1e-9;
    update(plane_strain(-delta, 0, 0), stress, state.data());
    const double m = (-p0 - stress[0][0]) / delta;
    lambda         = (-p0 - stress[1][1]) / delta;
    mu             = 0.5 * (m - lambda);
  }
  const double strain_scale = p0 / (lambda + 2 * mu);

  // Load every point along its own path; keep the next increment.
  const unsigned int                     n_load = 300;
  std::mt19937_64                        generator(2026);
  std::uniform_real_distribution<double> unit(0., 1.), signed_unit(-1., 1.);
  std::normal_distribution<double>       normal(0., 1.);
  std::vector<SymmetricTensor<2, 3>>     stresses(n_points), increments(n_points);
  std::vector<double>                    states(std::size_t(n_points) * width, 0.);
  for (unsigned int i = 0; i < n_points; ++i)
    {
      const double shear      = 3 * strain_scale / n_load * unit(generator);
      const double volumetric =
        1.5 * strain_scale / n_load * signed_unit(generator);
      const double noise = 0.1 * 3 * strain_scale / n_load;
      const auto   next  = [&]() {
        SymmetricTensor<2, 3> e =
          plane_strain(0.5 * volumetric + noise * normal(generator),
                       0.5 * volumetric + noise * normal(generator),
                       shear + noise * normal(generator));
        if (three_d)
          {
            e[1][2] = noise * normal(generator);
            e[0][2] = noise * normal(generator);
          }
        return e;
      };
      double *state = &states[std::size_t(i) * width];
      model.initialize_state(ArrayView<double>(state, n_state));
      stresses[i] = -p0 * unit_symmetric_tensor<3>();
      for (unsigned int k = 0; k < n_load; ++k)
        update(next(), stresses[i], state);

      increments[i] = next();
      if (unit(generator) < 0.5)
        {
          // Same size, random direction (plane strain unless 3d).
          const double size = increments[i].norm();
          SymmetricTensor<2, 3> e =
            plane_strain(normal(generator), normal(generator), normal(generator));
          if (three_d)
            {
              e[1][2] = normal(generator);
              e[0][2] = normal(generator);
            }
          increments[i] = e * (size / e.norm());
        }
    }

  // Which updates are plastic: the stress differs from the elastic trial.
  unsigned int n_plastic = 0;
  for (unsigned int i = 0; i < n_points; ++i)
    {
      SymmetricTensor<2, 3> trial = stresses[i], stress = stresses[i];
      const SymmetricTensor<2, 3> &e = increments[i];
      trial += lambda * trace(e) * unit_symmetric_tensor<3>() + 2 * mu * e;
      std::vector<double> state(states.begin() + std::size_t(i) * width,
                                states.begin() + std::size_t(i + 1) * width);
      update(e, stress, state.data());
      if (max_abs(stress - trial) > 1e-9 * (max_abs(trial) + p0))
        ++n_plastic;
    }

  // The timed loop: one update of every point from the stored state.
  const unsigned int  n_repetitions = 31;
  std::vector<double> times;
  double              checksum = 0;
  std::vector<double> state(width);
  for (unsigned int repetition = 0; repetition <= n_repetitions; ++repetition)
    {
      const auto start = std::chrono::steady_clock::now();
      for (unsigned int i = 0; i < n_points; ++i)
        {
          SymmetricTensor<2, 3> stress = stresses[i];
          for (unsigned int k = 0; k < width; ++k)
            state[k] = states[std::size_t(i) * width + k];
          update(increments[i], stress, state.data());
          checksum += stress[1][1] + state[0];
        }
      const double seconds = std::chrono::duration<double>(
                               std::chrono::steady_clock::now() - start)
                               .count();
      // The first pass warms the caches and the branch predictors.
      if (repetition > 0)
        times.push_back(seconds / n_points * 1e9);
    }
  std::sort(times.begin(), times.end());

  std::cout << "material model benchmark: " << file << ", material '"
            << driver.material().name << "', " << n_points
            << " points from p0 = " << p0 << " Pa, " << n_load
            << (three_d ? " 3D" : " plane-strain") << " increments each\n"
            << std::fixed << std::setprecision(1)
            << "plastic updates in the timed increment: "
            << 100. * n_plastic / n_points << " %\n"
            << "ns per update: median " << times[times.size() / 2]
            << ", minimum " << times.front() << " (over " << n_repetitions
            << " repetitions)\n"
            << std::defaultfloat << std::setprecision(6)
            << "(checksum " << checksum << ")\n";
  return 0;
}
