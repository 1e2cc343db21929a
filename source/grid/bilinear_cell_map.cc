#include <mpm/grid/bilinear_cell_map.h>

#include <algorithm>
#include <limits>

namespace MPM
{
  bool
  BilinearCellMap::polish(const Tensor<1, 2> &r, Point<2> &xi) const
  {
    // Written out for 2x2: J = [b + d eta, c + d xi], same singularity test
    // as for a general Jacobian, without its square roots.
    const double x = xi[0], y = xi[1];
    const auto   residual = b * x + c * y + d * (x * y) - r;
    const double j00 = b[0] + d[0] * y, j10 = b[1] + d[1] * y;
    const double j01 = c[0] + d[0] * x, j11 = c[1] + d[1] * x;
    const double det = j00 * j11 - j01 * j10;
    if (!(det * det >
          1e-28 * (j00 * j00 + j10 * j10) * (j01 * j01 + j11 * j11)))
      return false;
    xi[0] -= (j11 * residual[0] - j01 * residual[1]) / det;
    xi[1] -= (j00 * residual[1] - j10 * residual[0]) / det;
    return true;
  }


  InverseMappingResult<2>
  BilinearCellMap::inverse_general(const Point<2> &x,
                                   const bool      newton_polish) const
  {
    const Tensor<1, 2> r = x - origin;
    InverseMappingResult<2> result;
    result.xi = Point<2>(std::numeric_limits<double>::quiet_NaN(),
                         std::numeric_limits<double>::quiet_NaN());
    if (affine)
      {
        result.xi      = affine_inverse(r);
        result.success = true;
        return result;
      }

    const double B = B_of_cell - cross(r, d);
    const double C = cross(u, r);

    double discriminant = B * B - 4. * A * C;
    if (discriminant < 0)
      {
        // A slightly negative discriminant is round-off around a double
        // root (singular Jacobian at the solution); anything more means
        // that no point of the plane maps to x.
        if (discriminant >= -1e-14 * (B * B + 4. * std::abs(A * C)))
          discriminant = 0;
        else
          return result;
      }

    // Roots without cancellation: q = -(B + sign(B) sqrt(disc)) / 2, roots
    // C / q and q / A. The first is the root that stays finite as A -> 0
    // (the linear, parallelogram, case -C/B), the second goes to infinity
    // then; neither divides by zero.
    const double sqrt_discriminant = std::sqrt(discriminant);
    const double q = -0.5 * (B + std::copysign(sqrt_discriminant, B));
    double       roots[2];
    unsigned int n_roots = 0;
    if (q != 0)
      {
        roots[n_roots++] = C / q;
        if (A != 0)
          roots[n_roots++] = q / A;
      }
    else if (A != 0)
      // B = 0 and disc = 0, so C = 0 as well: double root at 0.
      roots[n_roots++] = 0;
    else
      // A = B = 0: the map does not determine this coordinate (degenerate
      // cell).
      return result;

    // For each root, the other coordinate from the remaining linear
    // equation (r - w t) = (u + d t) s, solved in the least-squares sense:
    // this uses both components and needs no choice of which one to
    // divide by. Of the roots, the one whose reference point is inside or
    // nearest to the unit square wins, then the one nearest its centre.
    double best_distance = std::numeric_limits<double>::infinity();
    double best_centre   = std::numeric_limits<double>::infinity();
    for (unsigned int k = 0; k < n_roots; ++k)
      {
        const double t = roots[k];
        if (!std::isfinite(t))
          continue;
        const Tensor<1, 2> e      = u + d * t;
        const Tensor<1, 2> rhs    = r - w * t;
        const double       e_norm = e * e;
        if (!(e_norm > 0))
          continue;
        const double   s  = (rhs * e) / e_norm;
        const Point<2> xi = solve_for_eta ? Point<2>(s, t) : Point<2>(t, s);
        double         distance = 0;
        for (unsigned int i = 0; i < 2; ++i)
          distance = std::max({distance, -xi[i], xi[i] - 1.});
        const double centre =
          std::max(std::abs(xi[0] - 0.5), std::abs(xi[1] - 0.5));
        if (distance < best_distance ||
            (distance == best_distance && centre < best_centre))
          {
            best_distance = distance;
            best_centre   = centre;
            result.xi     = xi;
          }
        // A root inside the unit square is the answer: the map of a convex
        // cell (which the mesh check guarantees) is one-to-one on the
        // square, so the other root lies outside and could not win.
        if (best_distance == 0)
          break;
      }
    if (!std::isfinite(best_distance))
      return result;
    result.success = true;
    if (newton_polish && needs_polish(sqrt_discriminant, B) &&
        polish(r, result.xi))
      result.n_iterations = 1;
    return result;
  }
} // namespace MPM
