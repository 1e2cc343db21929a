#ifndef mpm_grid_bilinear_cell_map_h
#define mpm_grid_bilinear_cell_map_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/grid/inverse_mapping.h>

#include <array>
#include <cmath>

namespace MPM
{
  using namespace dealii;

  /**
   * The bilinear (isoparametric) map of one quadrilateral,
   *   x(xi, eta) = v0 + b xi + c eta + d xi eta,
   * in deal.II's reference cell and vertex order (v0 = x(0,0),
   * v1 = x(1,0), v2 = x(0,1), v3 = x(1,1)), stored in the form in which
   * every step uses it: its closed-form inverse (doc/point_location.md)
   * for every material point, and its Jacobian for the shape function
   * gradients.
   *
   * The background mesh does not move, so everything that depends only on
   * the cell (the edge vectors, the choice of which coordinate's quadratic
   * to solve, the quadratic's cell-only coefficients, whether the cell is
   * a parallelogram) is computed once per cell by the constructor;
   * BackgroundGrid keeps one per cell. What is left per point is inverse():
   * one square root and two divisions on a few products, inlined into the
   * loops over the points. Computing the cell's part per point (as a
   * function of the four vertices) was more than a third of the cost of
   * the inverse map in the flume.
   *
   * inverse() is bit for bit the algorithm of inverse_map_closed_form(),
   * which is built on it; the uncommon cases (the first root outside
   * the cell, a negative discriminant, a degenerate cell) go to
   * inverse_general(), out of line.
   */
  class BilinearCellMap
  {
  public:
    BilinearCellMap() = default;

    /**
     * The map of the cell with @p vertices in deal.II's order.
     */
    explicit BilinearCellMap(const std::array<Point<2>, 4> &vertices)
      : origin(vertices[0])
      , b(vertices[1] - vertices[0])
      , c(vertices[2] - vertices[0])
      // Formed from two edge vectors so that it is exactly zero for an
      // exact parallelogram.
      , d((vertices[3] - vertices[2]) - b)
      , area(cross(b, c))
    {
      // A parallelogram (d zero up to round-off in the vertex coordinates,
      // which structured and slope-aligned meshes consist of) has an affine
      // map: x - v0 = b xi + c eta is solved exactly by Cramer's rule.
      // Neglecting d of 1e-14 |b, c| errs by less than 1e-14 in xi.
      affine =
        d.norm_square() <= 1e-28 * (b.norm_square() + c.norm_square()) &&
        area != 0;
      // Crossing r - c eta = (b + d eta) xi with (b + d eta) eliminates xi:
      //   (c x d) eta^2 + (c x b - r x d) eta + b x r = 0,
      // and crossing r - b xi = (c + d xi) eta with (c + d xi) eliminates
      // eta:
      //   (b x d) xi^2 + (b x c - r x d) xi + c x r = 0.
      // Solve the one whose leading coefficient is smaller, i.e. which is
      // closer to linear: its second root is farther away and the wanted
      // root better conditioned. For a trapezoid with d parallel to b,
      // b x d = 0 and the xi equation is exactly linear. With u the edge
      // along the solved-for coordinate's partner and w the other, both
      // read A t^2 + (w x u - r x d) t + u x r = 0.
      const double cd = cross(c, d);
      const double bd = cross(b, d);
      solve_for_eta   = std::abs(cd) <= std::abs(bd);
      u               = solve_for_eta ? b : c;
      w               = solve_for_eta ? c : b;
      A               = solve_for_eta ? cd : bd;
      B_of_cell       = cross(w, u);
    }

    /**
     * Reference coordinates of @p x: the closed-form inverse of the map,
     * with the Newton polish where the root is ill-conditioned if
     * @p newton_polish (see inverse_map_closed_form(), whose contract this
     * is).
     */
    InverseMappingResult<2>
    inverse(const Point<2> &x, const bool newton_polish = true) const
    {
      const Tensor<1, 2>      r = x - origin;
      InverseMappingResult<2> result;
      if (affine)
        {
          result.xi      = affine_inverse(r);
          result.success = true;
          return result;
        }
      if (first_root_inside(r, newton_polish, result.xi, result.n_iterations))
        {
          result.success = true;
          return result;
        }
      return inverse_general(x, newton_polish);
    }

    /**
     * Whether @p x lies in the cell (inside_unit_cell() of its reference
     * coordinates, with the default tolerance), and if so its reference
     * coordinates @p xi: the same as inverse() followed by
     * inside_unit_cell(), for the loops over the points, which only need
     * to know whether a point stayed in its cell. (Through the result
     * struct, GCC copied the success flag and the iteration count as one
     * 8-byte word right after writing them separately: a store-forwarding
     * stall on every point.)
     */
    bool
    contains(const Point<2> &x, Point<2> &xi) const
    {
      const Tensor<1, 2> r = x - origin;
      if (affine)
        {
          xi = affine_inverse(r);
          return inside_unit_cell(xi);
        }
      unsigned int n_iterations = 0;
      if (first_root_inside(r, true, xi, n_iterations))
        return n_iterations == 0 || inside_unit_cell(xi);
      const auto result = inverse_general(x, true);
      xi                = result.xi;
      return result.success && inside_unit_cell(xi);
    }

    /**
     * contains() for @p n points, each with the map of its own cell: the
     * same arithmetic and the same answers (@p inside, @p xi), but the
     * common case of the closed form is computed for all @p n points
     * before any of them is decided, so that their square roots and
     * divisions (a chain of about 50 cycles each) run side by side
     * instead of one after the other; the same for the divisions of
     * Cramer's rule in parallelograms. The uncommon cases (a root outside
     * the unit square, a polish) go through contains().
     * For the four corners of a CPDI domain, each tested in the cell it
     * most likely lies in.
     */
    template <std::size_t n>
    static void
    contains(const std::array<const BilinearCellMap *, n> &maps,
             const std::array<Point<2>, n>                &x,
             std::array<Point<2>, n>                      &xi,
             std::array<bool, n>                          &inside)
    {
      // Parallelograms: Cramer's rule for all of them, then the decisions
      // (contains()' arithmetic).
      bool all_parallelograms = true;
      for (std::size_t k = 0; k < n; ++k)
        if (maps[k]->affine)
          xi[k] = maps[k]->affine_inverse(x[k] - maps[k]->origin);
        else
          all_parallelograms = false;
      for (std::size_t k = 0; k < n; ++k)
        if (maps[k]->affine)
          inside[k] = inside_unit_cell(xi[k]);
      if (all_parallelograms)
        return;
      std::array<double, n>       B, C, sqrt_discriminant, q;
      std::array<bool, n>         common;
      std::array<Tensor<1, 2>, n> r;
      std::array<Point<2>, n>     root;
      for (std::size_t k = 0; k < n; ++k)
        {
          const BilinearCellMap &m = *maps[k];
          r[k]                     = x[k] - m.origin;
          B[k]                     = m.B_of_cell - cross(r[k], m.d);
          C[k]                     = cross(m.u, r[k]);
          const double discriminant = B[k] * B[k] - 4. * m.A * C[k];
          common[k] = !m.affine && discriminant >= 0;
          sqrt_discriminant[k] = std::sqrt(common[k] ? discriminant : 0.);
        }
      for (std::size_t k = 0; k < n; ++k)
        {
          const BilinearCellMap &m = *maps[k];
          q[k] = -0.5 * (B[k] + std::copysign(sqrt_discriminant[k], B[k]));
          common[k] = common[k] && q[k] != 0;
          const double       t = C[k] / (common[k] ? q[k] : 1.);
          const Tensor<1, 2> e = m.u * q[k] + m.d * C[k];
          const Tensor<1, 2> rhs    = r[k] * q[k] - m.w * C[k];
          const double       e_norm = e * e;
          common[k] = common[k] && std::isfinite(t) && e_norm > 0;
          const double s = (rhs * e) / (common[k] ? e_norm : 1.);
          root[k] = m.solve_for_eta ? Point<2>(s, t) : Point<2>(t, s);
        }
      for (std::size_t k = 0; k < n; ++k)
        if (maps[k]->affine)
          continue;
        else if (common[k] && root[k][0] >= 0 && root[k][0] <= 1 &&
                 root[k][1] >= 0 && root[k][1] <= 1 &&
                 !maps[k]->needs_polish(sqrt_discriminant[k], B[k]))
          {
            xi[k]     = root[k];
            inside[k] = true;
          }
        else
          inside[k] = maps[k]->contains(x[k], xi[k]);
    }

    /// Whether the cell is a parallelogram (its map affine, its inverse
    /// Cramer's rule).
    bool
    is_parallelogram() const
    {
      return affine;
    }

    /**
     * The Jacobian dx/dxi of the map at @p xi, as
     * {{dx/dxi, dx/deta}, {dy/dxi, dy/deta}}.
     */
    std::array<std::array<double, 2>, 2>
    jacobian(const Point<2> &xi) const
    {
      return {{{{b[0] + d[0] * xi[1], c[0] + d[0] * xi[0]}},
               {{b[1] + d[1] * xi[1], c[1] + d[1] * xi[0]}}}};
    }

  private:
    /**
     * Cramer's rule for a parallelogram: x - v0 = b xi + c eta.
     */
    Point<2>
    affine_inverse(const Tensor<1, 2> &r) const
    {
      return Point<2>(cross(r, c) / area, cross(b, r) / area);
    }

    /**
     * The common case of the closed form: the root that stays finite as
     * A -> 0, C / q, is the one inside the cell (it is for all but
     * strongly non-parallel cells, and for every point that stayed in its
     * cell). If that root's reference point lies in the closed unit
     * square, stores it in @p xi (polished where ill-conditioned, if
     * @p newton_polish; then @p n_iterations = 1) and returns true; otherwise
     * returns false and the caller goes to inverse_general().
     */
    bool
    first_root_inside(const Tensor<1, 2> &r,
                      const bool          newton_polish,
                      Point<2>           &xi,
                      unsigned int       &n_iterations) const
    {
      const double B            = B_of_cell - cross(r, d);
      const double C            = cross(u, r);
      const double discriminant = B * B - 4. * A * C;
      if (!(discriminant >= 0))
        return false;
      const double sqrt_discriminant = std::sqrt(discriminant);
      const double q = -0.5 * (B + std::copysign(sqrt_discriminant, B));
      if (q == 0)
        return false;
      const double t = C / q;
      // The other coordinate from (r - w t) = (u + d t) s, in the
      // least-squares sense, s = (r - w t).(u + d t) / |u + d t|^2, with
      // both vectors multiplied by q (t = C / q): the same quotient, but
      // independent of the division for t, so that the two divisions run
      // side by side instead of one after the other (this chain of
      // square root and divisions is most of the cost of the inverse map).
      // inverse_general() forms the quotient unscaled, for both roots; the
      // two can differ in the last bit, which matters only for a point
      // within round-off of an edge, inside the tolerance either way.
      const Tensor<1, 2> e      = u * q + d * C;
      const Tensor<1, 2> rhs    = r * q - w * C;
      const double       e_norm = e * e;
      if (!(std::isfinite(t) && e_norm > 0))
        return false;
      const double s = (rhs * e) / e_norm;
      xi             = solve_for_eta ? Point<2>(s, t) : Point<2>(t, s);
      if (!(xi[0] >= 0 && xi[0] <= 1 && xi[1] >= 0 && xi[1] <= 1))
        return false;
      if (newton_polish && needs_polish(sqrt_discriminant, B) &&
          polish(r, xi))
        n_iterations = 1;
      return true;
    }

    /**
     * The 2D cross product u x v = u_0 v_1 - u_1 v_0.
     */
    static double
    cross(const Tensor<1, 2> &u, const Tensor<1, 2> &v)
    {
      return u[0] * v[1] - u[1] * v[0];
    }

    /**
     * The root's error is round-off in A, B, C amplified by
     * 1 / |dQ/dt| = 1 / sqrt(disc) at the root, about
     * eps (|A| + |B| + |C|) / sqrt(disc) for t in [0, 1]. sqrt(disc) is
     * the Jacobian determinant at the point up to a factor of the cell's
     * scale, so it is only small (and the polish only worth its cost)
     * near a corner of a nearly degenerate cell; at a quarter of |A| + |B|
     * or more the error stays below about 12 eps.
     */
    bool
    needs_polish(const double sqrt_discriminant, const double B) const
    {
      return sqrt_discriminant < 0.25 * (std::abs(A) + std::abs(B));
    }

    /**
     * One Newton step on the map from @p xi towards @p r = x - v0; false
     * (and no step) where the Jacobian is singular.
     */
    bool
    polish(const Tensor<1, 2> &r, Point<2> &xi) const;

    /**
     * Every case of the closed form: both roots, the one inside or nearest
     * to the unit square, the clamp of a discriminant that is negative by
     * round-off, and failure.
     */
    InverseMappingResult<2>
    inverse_general(const Point<2> &x, const bool newton_polish) const;

    Point<2>     origin;
    Tensor<1, 2> b, c, d;
    double       area          = 0;
    bool         affine        = false;
    bool         solve_for_eta = true;
    /// The edge vectors of the solved-for quadratic (b and c, in the order
    /// solve_for_eta selects), its leading coefficient and the cell's part
    /// of its linear coefficient.
    Tensor<1, 2> u, w;
    double       A         = 0;
    double       B_of_cell = 0;
  };
} // namespace MPM

#endif
