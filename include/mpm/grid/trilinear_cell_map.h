#ifndef mpm_grid_trilinear_cell_map_h
#define mpm_grid_trilinear_cell_map_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/grid/inverse_mapping.h>
#include <mpm/grid/newton_inverse_map.h>

#include <array>
#include <cmath>

namespace MPM
{
  using namespace dealii;

  /**
   * The trilinear (isoparametric) map of one hexahedron in monomial form,
   *   x(xi) = v0 + b1 xi + b2 eta + b4 zeta + b3 xi eta + b5 xi zeta
   *              + b6 eta zeta + b7 xi eta zeta,
   * (b_i named by the vertex whose bits they start from, deal.II's vertex
   * order), and its inverse by Newton's iteration from a given start.
   *
   * What it is for: locating a point that moved a fraction of a cell since
   * the last step in a cell that is not a parallelepiped (terrain), where
   * inverse_map_newton() starts from the cell's centre and evaluates the
   * map vertex by vertex. Here the map and its Jacobian are a few products
   * of the coefficients, and Newton starts from the point's last reference
   * coordinates: two or three steps instead of four or five. The
   * iteration is inverse_map_newton()'s (internal::newton_inverse_map()),
   * so the two agree to round-off of the converged root. Cheap to construct (the coefficients are seven sums of vertex
   * differences): callers build one per cell on the stack.
   */
  class TrilinearCellMap
  {
  public:
    /**
     * The coefficients of the trilinear map of the hexahedron with
     * vertices @p v (deal.II's order) in monomial form: b[i] multiplies
     * the product of the reference coordinates whose bits i has (b[0] is
     * unused: v0 is the origin). Each is formed from differences of edge
     * vectors, so that it is exactly zero where the cell has no such
     * term (a parallelepiped's b3, b5, b6, b7; an extruded cell's
     * off-axis parts, ExtrudedCellMap).
     */
    static std::array<Tensor<1, 3>, 8>
    monomial_coefficients(const std::array<Point<3>, 8> &v)
    {
      std::array<Tensor<1, 3>, 8> b;
      b[1] = v[1] - v[0];
      b[2] = v[2] - v[0];
      b[4] = v[4] - v[0];
      b[3] = (v[3] - v[1]) - (v[2] - v[0]);
      b[5] = (v[5] - v[1]) - (v[4] - v[0]);
      b[6] = (v[6] - v[2]) - (v[4] - v[0]);
      b[7] = ((v[7] - v[6]) - (v[5] - v[4])) - ((v[3] - v[2]) - (v[1] - v[0]));
      return b;
    }

    /// The map of the hexahedron with @p vertices in deal.II's order.
    explicit TrilinearCellMap(const std::array<Point<3>, 8> &v)
      : TrilinearCellMap(v[0], monomial_coefficients(v))
    {}

    /**
     * The map x(xi) - v0 at @p xi (@p value) and its Jacobian dx/dxi
     * (@p jacobian[a][d] = dx_a / dxi_d).
     */
    void
    evaluate(const Point<3>  &xi,
             Tensor<1, 3>    &value,
             Tensor<2, 3>    &jacobian) const
    {
      const double x = xi[0], y = xi[1], z = xi[2];
      const Tensor<1, 3> d_x = b1 + b3 * y + b5 * z + b7 * (y * z);
      const Tensor<1, 3> d_y = b2 + b3 * x + b6 * z + b7 * (x * z);
      const Tensor<1, 3> d_z = b4 + b5 * x + b6 * y + b7 * (x * y);
      value = b1 * x + b2 * y + b4 * z + b3 * (x * y) + b5 * (x * z) +
              b6 * (y * z) + b7 * (x * y * z);
      for (unsigned int a = 0; a < 3; ++a)
        {
          jacobian[a][0] = d_x[a];
          jacobian[a][1] = d_y[a];
          jacobian[a][2] = d_z[a];
        }
    }

    /**
     * Reference coordinates of @p x by Newton's iteration from @p start
     * (the point's reference coordinates of the last step: within a few
     * hundredths of the root). A start farther than one cell from the
     * unit cube is not a start: the iteration then begins as
     * inverse_map_newton() does, with the affine map of the centre.
     */
    InverseMappingResult<3>
    inverse(const Point<3> &x, const Point<3> &start) const
    {
      return internal::newton_inverse_map<3>(
        [this](const Point<3> &xi, Tensor<1, 3> &value, Tensor<2, 3> &J) {
          evaluate(xi, value, J);
        },
        x - origin,
        near_unit_cell(start),
        start,
        1e-10,
        20);
    }

  private:
    TrilinearCellMap(const Point<3>                    &v0,
                     const std::array<Tensor<1, 3>, 8> &b)
      : origin(v0)
      , b1(b[1])
      , b2(b[2])
      , b4(b[4])
      , b3(b[3])
      , b5(b[5])
      , b6(b[6])
      , b7(b[7])
    {}

    static bool
    near_unit_cell(const Point<3> &xi)
    {
      for (unsigned int d = 0; d < 3; ++d)
        if (!(xi[d] >= -1. && xi[d] <= 2.))
          return false;
      return true;
    }

    Point<3>     origin;
    Tensor<1, 3> b1, b2, b4, b3, b5, b6, b7;
  };
} // namespace MPM

#endif
