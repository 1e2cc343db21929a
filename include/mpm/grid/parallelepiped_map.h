#ifndef mpm_grid_parallelepiped_map_h
#define mpm_grid_parallelepiped_map_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>

namespace MPM
{
  using namespace dealii;

  /**
   * The trilinear map of a hexahedron when the hexahedron is a
   * parallelepiped: then the map is affine, x = x_0 + J xi, and its inverse
   * is one product, xi = J^{-1} (x - x_0), instead of Newton's iteration
   * (inverse_map_newton(), which costs about a third of a 3D step when
   * every point is located in its old cell each step). Structured and
   * extruded meshes consist of such cells; for the others is_affine() is
   * false and the callers use Newton. The 3D counterpart of
   * BilinearCellMap's parallelogram case; BackgroundGrid keeps one per cell.
   */
  class ParallelepipedMap
  {
  public:
    ParallelepipedMap() = default;

    /// The map of the hexahedron with @p vertices in deal.II's order.
    explicit ParallelepipedMap(const std::array<Point<3>, 8> &vertices)
      : origin(vertices[0])
    {
      Tensor<2, 3> J;
      double       scale = 0;
      for (unsigned int d = 0; d < 3; ++d)
        {
          const Tensor<1, 3> edge = vertices[1u << d] - vertices[0];
          for (unsigned int e = 0; e < 3; ++e)
            J[e][d] = edge[e];
          scale += edge.norm_square();
        }
      // Every vertex where the affine map puts it (to round-off in the
      // vertex coordinates, as BilinearCellMap's parallelogram test).
      affine = determinant(J) != 0;
      for (unsigned int i = 1; i < 8 && affine; ++i)
        {
          Tensor<1, 3> offset = vertices[i] - vertices[0];
          for (unsigned int d = 0; d < 3; ++d)
            if ((i >> d) & 1)
              for (unsigned int e = 0; e < 3; ++e)
                offset[e] -= J[e][d];
          affine = offset.norm_square() <= 1e-28 * scale;
        }
      if (affine)
        inverse_jacobian = invert(J);
    }

    /// Whether the cell is a parallelepiped (its map affine).
    bool
    is_affine() const
    {
      return affine;
    }

    /**
     * J^{-1}, the inverse of the constant Jacobian dx/dxi (only if
     * is_affine()): the real gradients of the cell's shape functions are
     * J^{-T} times their reference gradients at every point of the cell
     * (Q1ShapeFunctions::reinit()).
     */
    const Tensor<2, 3> &
    jacobian_inverse() const
    {
      return inverse_jacobian;
    }

    /// The reference coordinates of @p x (only if is_affine()).
    Point<3>
    inverse(const Point<3> &x) const
    {
      return Point<3>(inverse_jacobian * (x - origin));
    }

  private:
    Point<3>     origin;
    Tensor<2, 3> inverse_jacobian;
    bool         affine = false;
  };
} // namespace MPM

#endif
