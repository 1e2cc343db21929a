// CPDI's domain arithmetic (PointDomains): for parallelogram, general
// (one corner pulled in, as at a boundary) and 3D domains, the corner
// weights alpha_c sum to 1 and are 2^-dim on parallelepipeds, the beta_c sum
// to 0 and reproduce the identity, sum_c beta_c (x) x_c = I (so a linear
// velocity field gets its exact gradient), and the domain's volume is
// 2^dim det R. A domain stretched beyond the limit is reset to a square of
// the same volume with the same rotation; an inverted one is refused.

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <mpm/transfer/point_domains.h>

#include "unit_test_tools.h"

#include <algorithm>
#include <cmath>
#include <iostream>

namespace unit_point_domains
{
  using namespace dealii;
  using namespace MPM;
  using UnitTest::check;
  using UnitTest::flush_to_zero;

  template <int dim>
  void
  check_domain(const std::string                                          &name,
               const std::array<Point<dim>, PointDomains<dim>::n_corners> &x,
               const bool parallelepiped)
  {
    std::cout << name << ":\n";
    std::array<double, PointDomains<dim>::n_corners>         alpha;
    std::array<Tensor<1, dim>, PointDomains<dim>::n_corners> beta;
    const bool ok = PointDomains<dim>::corner_weights(x, alpha, beta);
    check(ok, "corner weights computed");
    double         sum_alpha = 0, alpha_error = 0;
    Tensor<1, dim> sum_beta;
    Tensor<2, dim> identity;
    for (unsigned int c = 0; c < x.size(); ++c)
      {
        sum_alpha += alpha[c];
        sum_beta += beta[c];
        identity += outer_product(beta[c], x[c]);
        alpha_error = std::max(alpha_error, std::abs(alpha[c] - 1. / x.size()));
      }
    std::cout << "    alpha:";
    for (const double a : alpha)
      std::cout << ' ' << flush_to_zero(a);
    std::cout
      << "\n    |sum alpha - 1| = " << flush_to_zero(sum_alpha - 1)
      << ", |sum beta| = " << flush_to_zero(sum_beta.norm())
      << ", |sum beta x - I| = "
      << flush_to_zero(
           (identity - Tensor<2, dim>(unit_symmetric_tensor<dim>())).norm())
      << '\n';
    check(std::abs(sum_alpha - 1) < 1e-12, "alpha sums to 1");
    check(sum_beta.norm() < 1e-12, "beta sums to 0");
    check((identity - Tensor<2, dim>(unit_symmetric_tensor<dim>())).norm() <
            1e-12,
          "sum_c beta_c (x) x_c = I");
    if (parallelepiped)
      check(alpha_error < 1e-12, "alpha = 2^-dim on a parallelepiped");
  }


  /// The parallelepiped's closed-form weights against corner_weights().
  template <int dim>
  void
  check_closed_form(
    const Tensor<2, dim>                                       &R,
    const std::array<Point<dim>, PointDomains<dim>::n_corners> &x)
  {
    constexpr unsigned int        n = PointDomains<dim>::n_corners;
    std::array<double, n>         alpha, alpha_closed;
    std::array<Tensor<1, dim>, n> beta, beta_closed;
    PointDomains<dim>::corner_weights(x, alpha, beta);
    PointDomains<dim>::parallelepiped_weights(R, alpha_closed, beta_closed);
    double difference = 0;
    for (unsigned int c = 0; c < n; ++c)
      difference = std::max({difference,
                             std::abs(alpha[c] - alpha_closed[c]),
                             (beta[c] - beta_closed[c]).norm() * R.norm()});
    check(difference < 1e-12,
          dim == 2 ? "closed form for a parallelogram = quadrature" :
                     "closed form for a parallelepiped (3D) = quadrature");
  }


  int
  run(int /*argc*/, char ** /*argv*/)
  {
    std::cout.precision(6);
    {
      // A sheared, rotated parallelogram about x_p.
      Tensor<2, 2> R;
      R[0][0] = 0.3, R[0][1] = 0.1, R[1][0] = -0.05, R[1][1] = 0.2;
      const Point<2>          x_p(1.5, -0.7);
      std::array<Point<2>, 4> x;
      for (unsigned int c = 0; c < 4; ++c)
        x[c] = x_p + R * PointDomains<2>::corner_signs(c);
      check_domain<2>("parallelogram", x, true);
      check_closed_form<2>(R, x);
      // One corner pulled halfway in (a corner outside the patch).
      x[3] = x_p + 0.5 * R * PointDomains<2>::corner_signs(3);
      check_domain<2>("parallelogram with corner 3 pulled in", x, false);
      // Two corners pulled in differently.
      x[1] = x_p + 0.125 * R * PointDomains<2>::corner_signs(1);
      check_domain<2>("and corner 1 pulled in further", x, false);
      // Inverted: refused.
      std::swap(x[1], x[2]);
      std::array<double, 4>       alpha;
      std::array<Tensor<1, 2>, 4> beta;
      std::cout << "inverted domain:\n";
      check(!PointDomains<2>::corner_weights(x, alpha, beta),
            "an inverted domain is refused");
    }
    {
      Tensor<2, 3> R;
      R[0][0] = 0.3, R[0][1] = 0.1, R[1][1] = 0.2, R[2][0] = 0.05,
      R[2][2] = 0.25, R[1][2] = -0.04;
      const Point<3>          x_p(0.2, 0.4, -1);
      std::array<Point<3>, 8> x;
      for (unsigned int c = 0; c < 8; ++c)
        x[c] = x_p + R * PointDomains<3>::corner_signs(c);
      check_domain<3>("parallelepiped (3D)", x, true);
      check_closed_form<3>(R, x);
      x[5] = x_p + 0.5 * R * PointDomains<3>::corner_signs(5);
      check_domain<3>("parallelepiped with corner 5 pulled in (3D)", x, false);
    }
    {
      std::cout << "initial domain and deformation:\n";
      // A distorted cell; a point at the centre of sub-cell (1, 0) of 2 x 2,
      // with the volume the point generator gives it (det J times 1/4).
      const std::array<Point<2>, 4> vertices = {{Point<2>(0, 0),
                                                 Point<2>(1.1, 0.1),
                                                 Point<2>(0.2, 0.9),
                                                 Point<2>(1.3, 1.2)}};
      const Point<2>                xi(0.75, 0.25);
      Tensor<2, 2>                  J;
      J[0][0] = (vertices[1][0] - vertices[0][0]) * (1 - xi[1]) +
                (vertices[3][0] - vertices[2][0]) * xi[1];
      J[1][0] = (vertices[1][1] - vertices[0][1]) * (1 - xi[1]) +
                (vertices[3][1] - vertices[2][1]) * xi[1];
      J[0][1] = (vertices[2][0] - vertices[0][0]) * (1 - xi[0]) +
                (vertices[3][0] - vertices[1][0]) * xi[0];
      J[1][1] = (vertices[2][1] - vertices[0][1]) * (1 - xi[0]) +
                (vertices[3][1] - vertices[1][1]) * xi[0];
      const double V = determinant(J) / 4;
      const auto   D = PointDomains<2>::initial_domain(vertices, xi, V);
      // Its corners are those of the sub-cell: x(0.5, 0), x(1, 0), x(0.5,
      // 0.5), x(1, 0.5) minus x(xi).
      const auto map = [&](const double a, const double b) {
        return Point<2>((1 - a) * (1 - b) * vertices[0] +
                        a * (1 - b) * vertices[1] + (1 - a) * b * vertices[2] +
                        a * b * vertices[3]);
      };
      const Point<2>          x_p          = map(xi[0], xi[1]);
      const Point<2>          sub_cell[4]  = {map(0.5, 0),
                                              map(1, 0),
                                              map(0.5, 0.5),
                                              map(1, 0.5)};
      double                  corner_error = 0;
      std::array<Point<2>, 4> corners;
      for (unsigned int c = 0; c < 4; ++c)
        {
          corners[c] = x_p + D[c];
          corner_error =
            std::max(corner_error, (corners[c] - sub_cell[c]).norm());
        }
      std::cout << "    initial domain corners - sub-cell corners: "
                << flush_to_zero(corner_error) << '\n';
      check(
        corner_error < 1e-12,
        "initial domain of a sub-cell centre is the sub-cell (distorted cell)");
      check_domain<2>("initial domain in a distorted cell", corners, false);
      // 'CPDI domain size' 1.5: the image of the reference square 1.5
      // times as wide about the point, xi +- 1.5 / 4.
      {
        const auto D_large =
          PointDomains<2>::initial_domain(vertices, xi, V, 1.5);
        double large_error = 0;
        for (unsigned int c = 0; c < 4; ++c)
          {
            const Point<2> expected = map(xi[0] + ((c & 1) ? 0.375 : -0.375),
                                          xi[1] + ((c & 2) ? 0.375 : -0.375));
            large_error =
              std::max(large_error, (x_p + D_large[c] - expected).norm());
          }
        std::cout << "    domain size 1.5: corners - those of the reference "
                     "square 1.5 times as wide: "
                  << flush_to_zero(large_error) << '\n';
        check(large_error < 1e-12,
              "'CPDI domain size' scales the reference square about the "
              "point");
      }
      Tensor<2, 2> R = PointDomains<2>::affine_part(D);

      ParameterHandler prm;
      PointDomains<2>::declare_parameters(prm);
      prm.enter_subsection("Transfer");
      prm.set("CPDI stretch limit", "2");
      prm.leave_subsection();
      PointDomains<2> domains;
      domains.parse_parameters(prm);

      // A small deformation: (I + dt grad v) R.
      Tensor<2, 2> dt_grad_v;
      dt_grad_v[0][1]        = 0.1;
      const auto small       = domains.deformed_domain(D, dt_grad_v, 1.);
      double     small_error = 0;
      for (unsigned int c = 0; c < 4; ++c)
        small_error =
          std::max(small_error, (small[c] - (D[c] + dt_grad_v * D[c])).norm());
      check(small_error < 1e-15 * R.norm(),
            "a small deformation is applied as is");
      // A large stretch of a rotated square: reset to the square of the
      // same area with the same rotation.
      const double theta = 0.4;
      Tensor<2, 2> Q;
      Q[0][0] = std::cos(theta), Q[0][1] = -std::sin(theta);
      Q[1][0] = std::sin(theta), Q[1][1] = std::cos(theta);
      const Tensor<2, 2> square = 0.01 * Q;
      Tensor<2, 2>       stretch;
      stretch[0][0] = 4, stretch[1][1] = 0.25 - 1;
      stretch[0][0] -= 1;
      // (I + stretch) = diag(4, 1/4) in the rotated frame: area kept.
      const Tensor<2, 2> dt_grad = Q * stretch * transpose(Q);
      const Tensor<2, 2> reset =
        PointDomains<2>::affine_part(domains.deformed_domain(
          PointDomains<2>::parallelepiped(square), dt_grad, 1.));
      std::cout << "    reset domain / (0.01 Q) - 1: "
                << flush_to_zero((reset - square).norm() / square.norm())
                << '\n';
      check((reset - square).norm() < 1e-10 * square.norm(),
            "a domain stretched 16:1 is reset to the square of its area, "
            "same rotation");

      // The limit is relative to the cell's own shape: a square cell (also
      // turned) has stretch 1, a cell four times as wide as high stretch 2
      // (squared: 4), and the domain such a cell gives a point (stretch 2,
      // at the bare limit) stays as it is under a small compression.
      const std::array<Point<2>, 4> square_cell = {{Point<2>(0, 0),
                                                    Point<2>(0.1, 0),
                                                    Point<2>(0, 0.1),
                                                    Point<2>(0.1, 0.1)}};
      std::array<Point<2>, 4>       turned_cell;
      for (unsigned int v = 0; v < 4; ++v)
        turned_cell[v] = Point<2>(Q * square_cell[v]);
      const std::array<Point<2>, 4> flat_cell = {{Point<2>(0, 0),
                                                  Point<2>(0.4, 0),
                                                  Point<2>(0, 0.1),
                                                  Point<2>(0.4, 0.1)}};
      std::cout
        << "    cell_stretch2 of a square, a turned square, a 4:1 cell: "
        << PointDomains<2>::cell_stretch2(square_cell) << ", "
        << PointDomains<2>::cell_stretch2(turned_cell) << ", "
        << PointDomains<2>::cell_stretch2(flat_cell) << '\n';
      check(PointDomains<2>::cell_stretch2(square_cell) == 1 &&
              PointDomains<2>::cell_stretch2(turned_cell) == 1,
            "a square cell, turned or not, has stretch 1");
      check(std::abs(PointDomains<2>::cell_stretch2(flat_cell) - 4) < 1e-12,
            "a 4:1 cell has squared stretch 4");
      const auto flat_domain =
        PointDomains<2>::initial_domain(flat_cell,
                                        Point<2>(0.25, 0.25),
                                        0.4 * 0.1 / 4);
      Tensor<2, 2> squeeze;
      squeeze[1][1] = -1e-4;
      const auto kept =
        domains.deformed_domain(flat_domain,
                                squeeze,
                                PointDomains<2>::cell_stretch2(flat_cell));
      const auto reset_flat = domains.deformed_domain(flat_domain, squeeze, 1.);
      std::cout << "    4:1 cell's domain squeezed by 1e-4: width "
                << 2 * PointDomains<2>::affine_part(kept)[0][0]
                << " (limit relative to the cell), "
                << 2 * PointDomains<2>::affine_part(reset_flat)[0][0]
                << " (bare limit)\n";
      check(std::abs(2 * PointDomains<2>::affine_part(kept)[0][0] - 0.2) <
              1e-12,
            "a 4:1 cell's domain keeps its shape under a small deformation");
    }
    return UnitTest::summary();
  }
} // namespace unit_point_domains

MPM_UNIT_TEST_REGISTER(point_domains)
