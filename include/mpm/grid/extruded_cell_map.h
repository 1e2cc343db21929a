#ifndef mpm_grid_extruded_cell_map_h
#define mpm_grid_extruded_cell_map_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/grid/bilinear_cell_map.h>
#include <mpm/grid/inverse_mapping.h>
#include <mpm/grid/trilinear_cell_map.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace MPM
{
  using namespace dealii;

  /**
   * The closed-form inverse of the trilinear map of a hexahedron that is
   * extruded: along one reference direction r its edges are parallel to
   * one coordinate axis k. Terrain-following meshes (Mesh/Source =
   * terrain: vertical columns over the elevation model's grid) and 2D
   * quadrilateral meshes extruded in Gmsh consist of such cells. Then the
   * two other coordinates of the map do not depend on xi_r: they are the
   * bilinear map of the cell's cross-section in the two other reference
   * directions, whose closed-form inverse (BilinearCellMap) gives those two
   * reference coordinates; and x_k is linear in xi_r,
   *   x_k - v0_k = base(s, t) + xi_r height(s, t),
   * which one division solves. Exact to round-off like Newton's converged
   * root, inside the cell and outside it, for one square root (none where
   * the cross-section is a parallelogram, as over an elevation model's
   * grid) and one division, where Newton's iteration (TrilinearCellMap)
   * takes two to four steps with a 3 x 3 solve each: in the 3D landslide
   * on terrain, locating the points took a fifth of the step.
   *
   * A parallelepiped is not marked extruded (is_extruded() false): its
   * callers invert it with ParallelepipedMap, as before this class. Neither
   * is a cell whose edges along every direction lean by more than a few
   * units of round-off of its vertex coordinates (a refined terrain mesh's
   * new vertices are averages of old ones and may miss a column's line by
   * an ulp; neglecting that errs by as much in x). BackgroundGrid keeps
   * one per extruded cell.
   */
  class ExtrudedCellMap
  {
  public:
    ExtrudedCellMap() = default;

    /// The map of the hexahedron with @p v in deal.II's order.
    explicit ExtrudedCellMap(const std::array<Point<3>, 8> &v)
    {
      // The map in monomial form, x(xi) = v0 + sum_i b_i prod_{d in i}
      // xi_d.
      const std::array<Tensor<1, 3>, 8> b =
        TrilinearCellMap::monomial_coefficients(v);
      double magnitude = 0;
      for (unsigned int a = 0; a < 3; ++a)
        magnitude = std::max(magnitude, std::abs(v[0][a]));
      for (unsigned int i = 1; i < 8; ++i)
        for (unsigned int a = 0; a < 3; ++a)
          magnitude = std::max(magnitude, std::abs(b[i][a]));
      const double tolerance = 64 * 2.3e-16 * magnitude;
      bool         parallelepiped = true;
      for (const unsigned int i : {3u, 5u, 6u, 7u})
        for (unsigned int a = 0; a < 3; ++a)
          if (!(std::abs(b[i][a]) <= tolerance))
            parallelepiped = false;
      if (parallelepiped)
        return;
      // The direction of deal.II's vertical edges first (terrain meshes).
      for (const unsigned int r : {2u, 0u, 1u})
        {
          const Tensor<1, 3> &edge = b[1u << r];
          unsigned int        k    = 0;
          for (unsigned int a = 1; a < 3; ++a)
            if (std::abs(edge[a]) > std::abs(edge[k]))
              k = a;
          if (!(std::abs(edge[k]) > tolerance))
            continue;
          bool extruded = true;
          for (unsigned int i = 1; i < 8 && extruded; ++i)
            if (i & (1u << r))
              for (unsigned int a = 0; a < 3; ++a)
                if (a != k && !(std::abs(b[i][a]) <= tolerance))
                  extruded = false;
          if (!extruded)
            continue;
          // The other reference directions p < q and axes h0 < h1.
          const unsigned int p  = r == 0 ? 1 : 0;
          const unsigned int q  = r == 2 ? 1 : 2;
          const unsigned int h0 = k == 0 ? 1 : 0;
          const unsigned int h1 = k == 2 ? 1 : 2;
          // The cross-section xi_r = 0: its vertices in the 2D order of
          // (p, q). (A degenerate one fails in inverse(), and the callers
          // then try Newton's iteration, as for any other cell.)
          std::array<Point<2>, 4> section;
          for (unsigned int j = 0; j < 4; ++j)
            {
              const unsigned int i = ((j & 1) << p) | (((j >> 1) & 1) << q);
              section[j]           = Point<2>(v[i][h0], v[i][h1]);
            }
          cross_section = BilinearCellMap(section);
          // base(s, t) and height(s, t) along k, with s, t the reference
          // coordinates of p, q: the coefficients of 1, s, t, s t.
          const auto coefficient = [&](const unsigned int in_p,
                                       const unsigned int in_q,
                                       const unsigned int in_r) {
            const unsigned int i = (in_p << p) | (in_q << q) | (in_r << r);
            return b[i][k];
          };
          column_base   = {{coefficient(1, 0, 0),
                            coefficient(0, 1, 0),
                            coefficient(1, 1, 0)}};
          column_height = {{coefficient(0, 0, 1),
                            coefficient(1, 0, 1),
                            coefficient(0, 1, 1),
                            coefficient(1, 1, 1)}};
          origin_k      = v[0][k];
          direction     = r;
          axis          = k;
          directions    = {{static_cast<unsigned char>(p),
                            static_cast<unsigned char>(q)}};
          axes          = {{static_cast<unsigned char>(h0),
                            static_cast<unsigned char>(h1)}};
          return;
        }
    }

    /**
     * Whether the cell is extruded and not a parallelepiped (see the
     * class documentation); inverse() only for those.
     */
    bool
    is_extruded() const
    {
      return direction < 3;
    }

    /**
     * Reference coordinates of @p x (is_extruded() cells): s, t from the
     * cross-section, then xi_r. Fails only where the cross-section's
     * closed form does (far outside the cell, or a degenerate cell).
     */
    InverseMappingResult<3>
    inverse(const Point<3> &x) const
    {
      InverseMappingResult<3>       result;
      const InverseMappingResult<2> section =
        cross_section.inverse(Point<2>(x[axes[0]], x[axes[1]]));
      if (!section.success)
        return result;
      const double s = section.xi[0], t = section.xi[1];
      const double base =
        column_base[0] * s + column_base[1] * t + column_base[2] * (s * t);
      const double height = column_height[0] + column_height[1] * s +
                            column_height[2] * t + column_height[3] * (s * t);
      const double zeta = (x[axis] - origin_k - base) / height;
      if (!std::isfinite(zeta))
        return result;
      result.xi[directions[0]] = s;
      result.xi[directions[1]] = t;
      result.xi[direction]     = zeta;
      result.success           = true;
      return result;
    }

  private:
    BilinearCellMap       cross_section;
    std::array<double, 3> column_base   = {{0, 0, 0}};
    std::array<double, 4> column_height = {{0, 0, 0, 0}};
    double                origin_k      = 0;
    /// The reference direction r and axis k of the extrusion (3: the cell
    /// is not extruded), the two other directions and axes, ascending.
    unsigned char                direction  = 3;
    unsigned char                axis       = 3;
    std::array<unsigned char, 2> directions = {{0, 0}};
    std::array<unsigned char, 2> axes       = {{0, 0}};
  };
} // namespace MPM

#endif
