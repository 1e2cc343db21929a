// The non-local average of the regularised softening (NonlocalGrid,
// 'Strain softening/Nonlocal radius'; doc/slope_stability.md): the sums of
// w V v and w V at the nodes of a uniform grid of spacing R / 4,
// interpolated to the points. Checked:
// - a constant field is averaged to itself (to round-off), in 2D and 3D,
//   on points with uneven volumes;
// - against the exact pair sum sum_q w(|x_p - x_q|) V_q v_q / sum_q w V_q
//   for a smooth field and for a localised one (a band of width R / 2, the
//   case the regularisation exists for): the largest difference over the
//   points, as a fraction of the field's range, is what the grid costs in
//   accuracy;
// - the grid depends on the radius alone: points moved by a multiple of
//   the grid spacing have the same averages (to round-off), so the
//   operator does not follow the box the points fill;
// - a point far from all others (more than R) keeps its own value;
// - add_points() (the sums by rows of nodes, a slab of rows per thread)
//   gives the same averages on one and two threads, bit for bit, and those
//   of add() point by point to round-off.

#include <deal.II/base/multithread_info.h>

#include <mpm/material_points/nonlocal_averaging.h>

#include "unit_test_tools.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <random>
#include <vector>

namespace unit_nonlocal_averaging
{
  using namespace dealii;
  using namespace UnitTest;

  template <int dim>
  struct Cloud
  {
    std::vector<Point<dim>> x;
    std::vector<double>     volume;
    std::vector<double>     value;
  };

  /// A jittered lattice of spacing h over [0, L]^dim, volumes h^dim times
  /// 0.5 to 1.5.
  template <int dim>
  Cloud<dim>
  make_cloud(const double h, const double L, const unsigned int seed)
  {
    std::mt19937                           random(seed);
    std::uniform_real_distribution<double> unit(0., 1.);
    Cloud<dim>                             cloud;
    const unsigned int                     n = static_cast<unsigned int>(L / h);
    const unsigned int total = static_cast<unsigned int>(std::pow(n, dim));
    for (unsigned int i = 0; i < total; ++i)
      {
        Point<dim>   x;
        unsigned int rest = i;
        for (unsigned int d = 0; d < dim; ++d)
          {
            x[d] = (rest % n + 0.2 + 0.6 * unit(random)) * h;
            rest /= n;
          }
        cloud.x.push_back(x);
        cloud.volume.push_back(std::pow(h, dim) * (0.5 + unit(random)));
        cloud.value.push_back(0);
      }
    return cloud;
  }

  template <int dim>
  std::vector<double>
  grid_averages(const Cloud<dim> &cloud, const double radius)
  {
    Point<dim> lower = cloud.x[0], upper = cloud.x[0];
    for (const auto &x : cloud.x)
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] = std::min(lower[d], x[d]);
          upper[d] = std::max(upper[d], x[d]);
        }
    MPM::NonlocalGrid<dim> grid;
    grid.reinit(lower, upper, radius, "the test field");
    for (unsigned int p = 0; p < cloud.x.size(); ++p)
      grid.add(cloud.x[p], cloud.volume[p], cloud.value[p]);
    std::vector<double> averages;
    for (const auto &x : cloud.x)
      averages.push_back(grid.average(x));
    return averages;
  }

  template <int dim>
  std::vector<double>
  pair_averages(const Cloud<dim> &cloud, const double radius)
  {
    std::vector<double> averages;
    for (const auto &x : cloud.x)
      {
        double numerator = 0, denominator = 0;
        for (unsigned int q = 0; q < cloud.x.size(); ++q)
          {
            const double r2 = x.distance_square(cloud.x[q]);
            if (r2 >= radius * radius)
              continue;
            const double w = std::pow(1 - r2 / (radius * radius), 2);
            numerator += w * cloud.volume[q] * cloud.value[q];
            denominator += w * cloud.volume[q];
          }
        averages.push_back(numerator / denominator);
      }
    return averages;
  }

  double
  max_difference(const std::vector<double> &a, const std::vector<double> &b)
  {
    double m = 0;
    for (unsigned int i = 0; i < a.size(); ++i)
      m = std::max(m, std::abs(a[i] - b[i]));
    return m;
  }

  template <int dim>
  void
  check_constant(const double h, const double L, const double radius)
  {
    auto cloud = make_cloud<dim>(h, L, 1);
    for (auto &v : cloud.value)
      v = 0.3;
    const auto          averages = grid_averages(cloud, radius);
    std::vector<double> constant(averages.size(), 0.3);
    const double        error = max_difference(averages, constant);
    std::cout << "  " << dim << "D, " << cloud.x.size()
              << " points, R = " << radius << ": constant 0.3, largest error "
              << flush_to_zero(error, 1e-14) << '\n';
    check(error < 1e-14, "a constant field is averaged to itself");
  }

  void
  check_against_pair_sum()
  {
    const double h = 0.05, L = 2, radius = 0.3;
    auto         cloud = make_cloud<2>(h, L, 2);
    // Smooth: v = sin(2 pi x / L) cos(2 pi y / L).
    for (unsigned int p = 0; p < cloud.x.size(); ++p)
      cloud.value[p] = std::sin(2 * M_PI * cloud.x[p][0] / L) *
                       std::cos(2 * M_PI * cloud.x[p][1] / L);
    double smooth = max_difference(grid_averages(cloud, radius),
                                   pair_averages(cloud, radius)) /
                    2;
    // Localised: a band |y - x| < R / 4 with v = 1, 0 elsewhere.
    for (unsigned int p = 0; p < cloud.x.size(); ++p)
      cloud.value[p] =
        std::abs(cloud.x[p][1] - cloud.x[p][0]) < radius / 4 ? 1. : 0.;
    double band = max_difference(grid_averages(cloud, radius),
                                 pair_averages(cloud, radius));
    std::cout << std::setprecision(3) << "  grid against the pair sum, "
              << cloud.x.size() << " points, R = 6 h:\n"
              << "    smooth field, largest difference / range: " << smooth
              << '\n'
              << "    band of width R / 2, largest difference / range: " << band
              << '\n';
    check(smooth < 0.01, "smooth field: within 1 % of its range");
    check(band < 0.05, "band of width R / 2: within 5 % of its range");
  }

  void
  check_translation()
  {
    const double radius = 0.3, spacing = radius / 4;
    auto         cloud = make_cloud<2>(0.05, 1, 3);
    for (unsigned int p = 0; p < cloud.x.size(); ++p)
      cloud.value[p] = cloud.x[p][0] > 0.5 ? 1. : 0.2;
    const auto before = grid_averages(cloud, radius);
    // Move by a whole number of spacings; add a far point that enlarges
    // the box the points fill.
    Tensor<1, 2> shift;
    shift[0] = 7 * spacing, shift[1] = -3 * spacing;
    for (auto &x : cloud.x)
      x += shift;
    cloud.x.push_back(Point<2>(40, 40));
    cloud.volume.push_back(1);
    cloud.value.push_back(5);
    auto         after = grid_averages(cloud, radius);
    const double far   = after.back();
    after.pop_back();
    const double change = max_difference(before, after);
    std::cout << "  moved by (7, -3) spacings with a far point added: "
                 "largest change "
              << flush_to_zero(change, 1e-12) << ", far point's average " << far
              << '\n';
    check(change < 1e-12, "the averages do not depend on the box");
    check(std::abs(far - 5) < 1e-14, "a lone point keeps its value");
  }
  /// add_points() (row order, slabs on the threads) against add() point
  /// by point, on one and on two threads.
  void
  check_threads()
  {
    const double radius = 0.3;
    auto         cloud  = make_cloud<2>(0.02, 2, 4);
    for (unsigned int p = 0; p < cloud.x.size(); ++p)
      cloud.value[p] = std::abs(cloud.x[p][1] - 1) < 0.1 ? 1. : 0.01;
    const auto                       one_by_one = grid_averages(cloud, radius);
    std::vector<std::vector<double>> by_threads;
    for (const unsigned int threads : {1u, 2u})
      {
        MultithreadInfo::set_thread_limit(threads);
        MPM::NonlocalGrid<2> grid;
        grid.reinit(Point<2>(0, 0), Point<2>(2, 2), radius, "the test field");
        grid.add_points(cloud.x, cloud.volume, cloud.value);
        std::vector<double> averages;
        for (const auto &x : cloud.x)
          averages.push_back(grid.average(x));
        by_threads.push_back(averages);
      }
    MultithreadInfo::set_thread_limit();
    const double round_off = max_difference(by_threads[0], one_by_one);
    std::cout << "  " << cloud.x.size()
              << " points added by rows on 1 and 2 threads: "
              << (by_threads[0] == by_threads[1] ? "identical" : "DIFFERENT")
              << ", against one by one " << flush_to_zero(round_off, 1e-13)
              << '\n';
    check(by_threads[0] == by_threads[1],
          "the same averages on 1 and 2 threads, bit for bit");
    check(round_off < 1e-13, "the same sums as one by one, to round-off");
  }

  int
  run(int /*argc*/, char ** /*argv*/)
  {
    std::cout << "Constant fields:\n";
    check_constant<2>(0.05, 1, 0.2);
    check_constant<3>(0.1, 1, 0.35);
    std::cout << "Accuracy of the grid:\n";
    check_against_pair_sum();
    std::cout << "Independence of the box:\n";
    check_translation();
    std::cout << "Threads:\n";
    check_threads();
    return summary();
  }
} // namespace unit_nonlocal_averaging

MPM_UNIT_TEST_REGISTER(nonlocal_averaging)
