#ifndef mpm_grid_q1_shape_functions_h
#define mpm_grid_q1_shape_functions_h

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/grid/bilinear_cell_map.h>
#include <mpm/grid/parallelepiped_map.h>

#include <array>

namespace MPM
{
  using namespace dealii;

  /**
   * Values and real-space gradients of the 2^dim bilinear (trilinear)
   * shape functions of an isoparametric cell at one point, in deal.II's
   * vertex order. This is the kernel of particle-to-grid and grid-to-
   * particle; it is evaluated once per point and step and reused by every
   * transfer of that step. It gives the same numbers as FE_Q(1) with
   * MappingQ1, at a fraction of the cost of an FEValues object per cell.
   */
  template <int dim>
  struct Q1ShapeFunctions
  {
    static constexpr unsigned int n_vertices = GeometryInfo<dim>::vertices_per_cell;

    std::array<double, n_vertices>         value;
    std::array<Tensor<1, dim>, n_vertices> gradient;

  private:
    /**
     * Reference gradients of N0 ... N3 at @p xi (2D).
     */
    static std::array<std::array<double, 2>, 4>
    reference_gradients_2d(const Point<dim> &xi)
    {
      const double x = xi[0], y = xi[1];
      const double ox = 1. - x, oy = 1. - y;
      return {{{{-oy, -ox}}, {{oy, -x}}, {{-y, ox}}, {{y, x}}}};
    }

    /**
     * Values at @p xi and gradients J^{-T} times the reference gradients,
     * for the Jacobian @p j (2D). Written out in scalars: through Tensor,
     * the inverse Jacobian was stored as a pair and read back as halves, a
     * store-forwarding stall that was a third of this function's time in
     * the flume.
     */
    void
    set_2d(const Point<dim> &xi, const std::array<std::array<double, 2>, 2> &j)
    {
      const double x = xi[0], y = xi[1];
      const double ox = 1. - x, oy = 1. - y;
      value        = {{ox * oy, x * oy, ox * y, x * y}};
      const auto g = reference_gradients_2d(xi);
      const double inverse_determinant =
        1.0 / (j[0][0] * j[1][1] - j[1][0] * j[0][1]);
      // J^{-T}.
      const double t00 = j[1][1] * inverse_determinant;
      const double t01 = -j[1][0] * inverse_determinant;
      const double t10 = -j[0][1] * inverse_determinant;
      const double t11 = j[0][0] * inverse_determinant;
      for (unsigned int i = 0; i < 4; ++i)
        {
          gradient[i][0] = t00 * g[i][0] + t01 * g[i][1];
          gradient[i][1] = t10 * g[i][0] + t11 * g[i][1];
        }
    }

  public:
    /**
     * The values alone at reference point @p xi (where the gradients of
     * the mesh functions are not needed: CPDI's domain corners), the same
     * numbers as reinit()'s.
     */
    static std::array<double, n_vertices>
    values_at(const Point<dim> &xi)
    {
      std::array<double, n_vertices> N;
      if constexpr (dim == 2)
        {
          const double x = xi[0], y = xi[1];
          const double ox = 1. - x, oy = 1. - y;
          N = {{ox * oy, x * oy, ox * y, x * y}};
        }
      else
        for (unsigned int i = 0; i < n_vertices; ++i)
          {
            double v = 1;
            for (unsigned int d = 0; d < dim; ++d)
              v *= ((i >> d) & 1) ? xi[d] : 1. - xi[d];
            N[i] = v;
          }
      return N;
    }

    /**
     * Evaluate at reference point @p xi of the quadrilateral whose map
     * is @p map (2D). The Jacobian comes from the map's edge vectors,
     * [b + d eta, c + d xi]: four products instead of sixteen, and
     * relative to the cell's first vertex, so without the cancellation of
     * summing absolute vertex coordinates (the same numbers as the other
     * reinit() up to round-off).
     */
    void
    reinit(const BilinearCellMap &map, const Point<dim> &xi)
    {
      if constexpr (dim == 2)
        set_2d(xi, map.jacobian(xi));
      else
        {
          (void)map;
          (void)xi;
          Assert(false, ExcMessage("BilinearCellMap is 2D only."));
        }
    }

    /**
     * Evaluate at reference point @p xi of the parallelepiped whose
     * affine map is @p map (3D; map.is_affine()): the real gradients from
     * the cell's constant inverse Jacobian, without a Jacobian and its
     * inverse per point. The same numbers as the reinit() from the
     * vertices up to round-off (the trilinear Jacobian at xi sums eight
     * vertex terms; this one is the cell's three edge vectors).
     */
    void
    reinit(const ParallelepipedMap &map, const Point<dim> &xi)
    {
      if constexpr (dim == 3)
        {
          Assert(map.is_affine(), ExcInternalError());
          std::array<Tensor<1, dim>, n_vertices> reference_gradient;
          set_values_and_reference_gradients(xi, reference_gradient);
          const Tensor<2, dim> inverse_transpose =
            transpose(map.jacobian_inverse());
          for (unsigned int i = 0; i < n_vertices; ++i)
            gradient[i] = inverse_transpose * reference_gradient[i];
        }
      else
        {
          (void)map;
          (void)xi;
          Assert(false, ExcMessage("ParallelepipedMap is 3D only."));
        }
    }

    /**
     * Evaluate at reference point @p xi of the cell with @p vertices.
     */
    void
    reinit(const std::array<Point<dim>, n_vertices> &vertices,
           const Point<dim>                         &xi)
    {
      if constexpr (dim == 2)
        {
          // The same operations in the same order as the general code
          // below (so the same bits), in scalars (see set_2d()).
          const auto g = reference_gradients_2d(xi);
          std::array<std::array<double, 2>, 2> j;
          for (unsigned int a = 0; a < 2; ++a)
            for (unsigned int b = 0; b < 2; ++b)
              j[a][b] = vertices[0][a] * g[0][b] + vertices[1][a] * g[1][b] +
                        vertices[2][a] * g[2][b] + vertices[3][a] * g[3][b];
          set_2d(xi, j);
          return;
        }
      std::array<Tensor<1, dim>, n_vertices> reference_gradient;
      set_values_and_reference_gradients(xi, reference_gradient);
      // Jacobian J_ab = dx_a / dxi_b; real gradients are J^{-T} times the
      // reference gradients.
      Tensor<2, dim> jacobian;
      for (unsigned int i = 0; i < n_vertices; ++i)
        jacobian += outer_product(vertices[i], reference_gradient[i]);
      const Tensor<2, dim> inverse_transpose = transpose(invert(jacobian));
      for (unsigned int i = 0; i < n_vertices; ++i)
        gradient[i] = inverse_transpose * reference_gradient[i];
    }

  private:
    /// The values at @p xi into value, and the reference gradients (any
    /// dim; the 2D reinit()s use their scalar form).
    void
    set_values_and_reference_gradients(
      const Point<dim>                       &xi,
      std::array<Tensor<1, dim>, n_vertices> &reference_gradient)
    {
      for (unsigned int i = 0; i < n_vertices; ++i)
        {
          // Vertex i sits at reference coordinate d = bit d of i.
          double factor[dim], dfactor[dim];
          for (unsigned int d = 0; d < dim; ++d)
            {
              const bool upper = (i >> d) & 1;
              factor[d]        = upper ? xi[d] : 1. - xi[d];
              dfactor[d]       = upper ? 1. : -1.;
            }
          double v = 1;
          for (unsigned int d = 0; d < dim; ++d)
            v *= factor[d];
          value[i] = v;
          for (unsigned int d = 0; d < dim; ++d)
            {
              double g = dfactor[d];
              for (unsigned int e = 0; e < dim; ++e)
                if (e != d)
                  g *= factor[e];
              reference_gradient[i][d] = g;
            }
        }
    }
  };
} // namespace MPM

#endif
