#ifndef mpm_grid_newton_inverse_map_h
#define mpm_grid_newton_inverse_map_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/grid/inverse_mapping.h>

#include <algorithm>
#include <cmath>

namespace MPM
{
  namespace internal
  {
    /// The largest absolute component of @p t.
    template <int dim>
    inline double
    max_abs(const Tensor<1, dim> &t)
    {
      double m = 0;
      for (unsigned int d = 0; d < dim; ++d)
        m = std::max(m, std::abs(t[d]));
      return m;
    }

    /**
     * Whether @p jacobian is too close to singular to be inverted: |det J|
     * at most 1e-14 times the product of its column lengths (compared
     * squared, so the test does not depend on the cell size and takes no
     * square root).
     */
    template <int dim>
    inline bool
    is_singular(const Tensor<2, dim> &jacobian)
    {
      double scale = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          double column = 0;
          for (unsigned int a = 0; a < dim; ++a)
            column += jacobian[a][d] * jacobian[a][d];
          scale *= column;
        }
      const double det = determinant(jacobian);
      return !(det * det > 1e-28 * scale);
    }

    /**
     * Newton's iteration for the reference coordinates of the point @p r
     * (relative to the map's origin) of a cell whose map is
     * @p evaluate(xi, value, jacobian) (value relative to the same origin),
     * the algorithm of inverse_map_newton() (see there): from @p start if
     * @p use_start, else from the affine map of the cell's centre; steps
     * halved while they increase the residual; converged when a step is at
     * most @p step_tolerance in every reference coordinate. Written once
     * for inverse_map_newton() (the map vertex by vertex) and
     * TrilinearCellMap (the map in monomial form, started from the last
     * step's reference coordinates).
     */
    template <int dim, typename Evaluate>
    InverseMappingResult<dim>
    newton_inverse_map(const Evaluate       &evaluate,
                       const Tensor<1, dim> &r,
                       const bool            use_start,
                       const Point<dim>     &start,
                       const double          step_tolerance,
                       const unsigned int    max_iterations)
    {
      InverseMappingResult<dim> result;
      Point<dim>                xi = start;
      Tensor<1, dim>            value;
      Tensor<2, dim>            jacobian;
      if (!use_start)
        {
          for (unsigned int d = 0; d < dim; ++d)
            xi[d] = 0.5;
          evaluate(xi, value, jacobian);
          if (is_singular(jacobian))
            return result;
          xi += invert(jacobian) * (r - value);
        }
      evaluate(xi, value, jacobian);
      Tensor<1, dim> residual = value - r;
      for (unsigned int iteration = 1; iteration <= max_iterations;
           ++iteration)
        {
          result.n_iterations = iteration;
          if (is_singular(jacobian))
            return result;
          const Tensor<1, dim> step = -(invert(jacobian) * residual);
          if (!(max_abs(step) <= 1e6))
            // Diverging, or NaN: the point is very far from this cell.
            return result;
          if (max_abs(step) <= step_tolerance)
            {
              result.xi      = xi + step;
              result.success = true;
              return result;
            }
          // Halve the step while it increases the residual.
          double         alpha = 1;
          Point<dim>     trial;
          Tensor<1, dim> trial_value;
          Tensor<2, dim> trial_jacobian;
          for (unsigned int k = 0; k <= 10; ++k, alpha *= 0.5)
            {
              trial = xi + alpha * step;
              evaluate(trial, trial_value, trial_jacobian);
              if ((trial_value - r).norm_square() <= residual.norm_square())
                break;
            }
          xi       = trial;
          value    = trial_value;
          jacobian = trial_jacobian;
          residual = value - r;
        }
      result.xi = xi;
      return result;
    }
  } // namespace internal
} // namespace MPM

#endif
