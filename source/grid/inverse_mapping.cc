#include <deal.II/base/tensor.h>

#include <deal.II/fe/mapping_q1.h>

#include <mpm/base/input_error.h>
#include <mpm/grid/inverse_mapping.h>

#include <cmath>
#include <limits>

namespace MPM
{
  std::string
  inverse_mapping_type_selection()
  {
    return "closed form|newton|deal.II";
  }


  InverseMappingType
  parse_inverse_mapping_type(const std::string &name)
  {
    if (name == "closed form")
      return InverseMappingType::closed_form;
    if (name == "newton")
      return InverseMappingType::newton;
    if (name == "deal.II")
      return InverseMappingType::dealii;
    throw InputError("Unknown inverse mapping '" + name + "'; choose one of " +
                     inverse_mapping_type_selection() + ".");
  }


  std::string
  to_string(const InverseMappingType type)
  {
    switch (type)
      {
        case InverseMappingType::closed_form:
          return "closed form";
        case InverseMappingType::newton:
          return "newton";
        case InverseMappingType::dealii:
          return "deal.II";
      }
    return "";
  }


  namespace
  {
    /**
     * The 2D cross product u x v = u_0 v_1 - u_1 v_0.
     */
    inline double
    cross(const Tensor<1, 2> &u, const Tensor<1, 2> &v)
    {
      return u[0] * v[1] - u[1] * v[0];
    }

    /**
     * Infinity-norm distance of @p xi from the unit square (0 inside).
     */
    inline double
    distance_to_unit_square(const Point<2> &xi)
    {
      double distance = 0;
      for (unsigned int d = 0; d < 2; ++d)
        distance = std::max({distance, -xi[d], xi[d] - 1.});
      return distance;
    }

    /**
     * Value (relative to vertex 0) and Jacobian of the multilinear map at
     * @p xi, for vertices given relative to vertex 0. Working relative to
     * vertex 0 keeps the round-off proportional to the cell size rather
     * than to the distance of the cell from the origin.
     */
    template <int dim>
    inline void
    evaluate_map(
      const std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell>
                       &relative_vertices,
      const Point<dim> &xi,
      Tensor<1, dim>   &value,
      Tensor<2, dim>   &jacobian)
    {
      value    = Tensor<1, dim>();
      jacobian = Tensor<2, dim>();
      for (unsigned int i = 1; i < GeometryInfo<dim>::vertices_per_cell; ++i)
        {
          // Vertex i sits at reference coordinate d = bit d of i.
          double factor[dim], dfactor[dim];
          for (unsigned int d = 0; d < dim; ++d)
            {
              const bool upper = (i >> d) & 1;
              factor[d]        = upper ? xi[d] : 1. - xi[d];
              dfactor[d]       = upper ? 1. : -1.;
            }
          double n = 1;
          for (unsigned int d = 0; d < dim; ++d)
            n *= factor[d];
          value += n * relative_vertices[i];
          for (unsigned int d = 0; d < dim; ++d)
            {
              double g = dfactor[d];
              for (unsigned int e = 0; e < dim; ++e)
                if (e != d)
                  g *= factor[e];
              for (unsigned int a = 0; a < dim; ++a)
                jacobian[a][d] += relative_vertices[i][a] * g;
            }
        }
    }

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
     * Whether @p jacobian is too close to singular to be inverted: its
     * determinant is below round-off relative to the product of its
     * column lengths (so the test does not depend on the cell size).
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
          scale *= std::sqrt(column);
        }
      const double det = determinant(jacobian);
      return !(std::abs(det) > 1e-14 * scale);
    }
  } // namespace


  template <int dim>
  Point<dim>
  map_unit_to_real(
    const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>
                     &vertices,
    const Point<dim> &xi)
  {
    std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell> relative;
    for (unsigned int i = 0; i < GeometryInfo<dim>::vertices_per_cell; ++i)
      relative[i] = vertices[i] - vertices[0];
    Tensor<1, dim> value;
    Tensor<2, dim> jacobian;
    evaluate_map<dim>(relative, xi, value, jacobian);
    return vertices[0] + value;
  }


  InverseMappingResult<2>
  inverse_map_closed_form(const std::array<Point<2>, 4> &vertices,
                          const Point<2>                &x,
                          const bool                     newton_polish)
  {
    // x(xi, eta) = v0 + b xi + c eta + d xi eta in deal.II's reference
    // cell. d is formed from two edge vectors so that it is exactly zero for
    // an exact parallelogram.
    const Tensor<1, 2> b = vertices[1] - vertices[0];
    const Tensor<1, 2> c = vertices[2] - vertices[0];
    const Tensor<1, 2> d = (vertices[3] - vertices[2]) - b;
    const Tensor<1, 2> r = x - vertices[0];

    // A parallelogram (d zero up to round-off in the vertex coordinates,
    // which structured and slope-aligned meshes consist of) has an affine
    // map: x - v0 = b xi + c eta is solved exactly by Cramer's rule, at a
    // third of the cost of the general case and without the Newton polish.
    // Neglecting d of 1e-14 |b, c| errs by less than 1e-14 in xi.
    const double area = cross(b, c);
    if (d.norm_square() <= 1e-28 * (b.norm_square() + c.norm_square()) &&
        area != 0)
      {
        InverseMappingResult<2> affine;
        affine.xi      = Point<2>(cross(r, c) / area, cross(b, r) / area);
        affine.success = true;
        return affine;
      }

    // Crossing r - c eta = (b + d eta) xi with (b + d eta) eliminates xi:
    //   (c x d) eta^2 + (c x b - r x d) eta + b x r = 0,
    // and crossing r - b xi = (c + d xi) eta with (c + d xi) eliminates eta:
    //   (b x d) xi^2 + (b x c - r x d) xi + c x r = 0.
    // Both share the area term b x c in the linear coefficient; solve the
    // one whose leading coefficient is smaller, i.e. which is closer to
    // linear: its second root is farther away and the wanted root better
    // conditioned. For a trapezoid with d parallel to b, b x d = 0 and the
    // xi equation is exactly linear.
    const double cd            = cross(c, d);
    const double bd            = cross(b, d);
    const bool   solve_for_eta = std::abs(cd) <= std::abs(bd);
    const double rd            = cross(r, d);
    double       A, B, C;
    if (solve_for_eta)
      {
        A = cd;
        B = cross(c, b) - rd;
        C = cross(b, r);
      }
    else
      {
        A = bd;
        B = cross(b, c) - rd;
        C = cross(c, r);
      }

    InverseMappingResult<2> result;
    result.xi = Point<2>(std::numeric_limits<double>::quiet_NaN(),
                         std::numeric_limits<double>::quiet_NaN());

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
    // equation (r - c eta) = (b + d eta) xi (or the one with xi and eta
    // exchanged), solved in the least-squares sense: this uses both
    // components and needs no choice of which one to divide by.
    double best_distance = std::numeric_limits<double>::infinity();
    double best_centre   = std::numeric_limits<double>::infinity();
    for (unsigned int k = 0; k < n_roots; ++k)
      {
        const double t = roots[k];
        if (!std::isfinite(t))
          continue;
        const Tensor<1, 2> e      = solve_for_eta ? b + d * t : c + d * t;
        const Tensor<1, 2> rhs    = solve_for_eta ? r - c * t : r - b * t;
        const double       e_norm = e * e;
        if (!(e_norm > 0))
          continue;
        const double   s  = (rhs * e) / e_norm;
        const Point<2> xi = solve_for_eta ? Point<2>(s, t) : Point<2>(t, s);
        const double   distance = distance_to_unit_square(xi);
        const double   centre =
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
        // square, so the other root lies outside and could not win. The
        // first root, C / q, is the one inside for all but strongly
        // non-parallel cells: skipping the second saves a third of the
        // cost of the most common case (a point that stayed in its cell).
        if (best_distance == 0)
          break;
      }
    if (!std::isfinite(best_distance))
      return result;
    result.success = true;

    // The root's error is round-off in A, B, C amplified by
    // 1 / |dQ/dt| = 1 / sqrt(disc) at the root, about
    // eps (|A| + |B| + |C|) / sqrt(disc) for t in [0, 1]. sqrt(disc) is
    // the Jacobian determinant at the point up to a factor of the cell's
    // scale, so it is only small (and the polish only worth its cost, a
    // third of the whole) near a corner of a nearly degenerate cell; at a
    // quarter of |A| + |B| or more the error stays below about 12 eps.
    if (newton_polish &&
        sqrt_discriminant < 0.25 * (std::abs(A) + std::abs(B)))
      {
        // Written out for 2x2 (this step is a third of the cost of the
        // closed form): J = [b + d eta, c + d xi], same singularity test
        // as is_singular() without its square roots.
        const double xi = result.xi[0], eta = result.xi[1];
        const auto   residual = b * xi + c * eta + d * (xi * eta) - r;
        const double j00 = b[0] + d[0] * eta, j10 = b[1] + d[1] * eta;
        const double j01 = c[0] + d[0] * xi, j11 = c[1] + d[1] * xi;
        const double det = j00 * j11 - j01 * j10;
        if (det * det >
            1e-28 * (j00 * j00 + j10 * j10) * (j01 * j01 + j11 * j11))
          {
            result.xi[0] -= (j11 * residual[0] - j01 * residual[1]) / det;
            result.xi[1] -= (j00 * residual[1] - j10 * residual[0]) / det;
            result.n_iterations = 1;
          }
      }
    return result;
  }


  template <int dim>
  InverseMappingResult<dim>
  inverse_map_newton(
    const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>
                      &vertices,
    const Point<dim>  &x,
    const double       step_tolerance,
    const unsigned int max_iterations)
  {
    std::array<Tensor<1, dim>, GeometryInfo<dim>::vertices_per_cell> relative;
    for (unsigned int i = 0; i < GeometryInfo<dim>::vertices_per_cell; ++i)
      relative[i] = vertices[i] - vertices[0];
    const Tensor<1, dim> r = x - vertices[0];

    InverseMappingResult<dim> result;

    // Initial guess: the affine map with the value and Jacobian of the
    // cell's map at the centre (exact for parallelograms).
    Point<dim> xi;
    for (unsigned int d = 0; d < dim; ++d)
      xi[d] = 0.5;
    Tensor<1, dim> value;
    Tensor<2, dim> jacobian;
    evaluate_map<dim>(relative, xi, value, jacobian);
    if (is_singular(jacobian))
      return result;
    xi += invert(jacobian) * (r - value);

    evaluate_map<dim>(relative, xi, value, jacobian);
    Tensor<1, dim> residual = value - r;
    for (unsigned int iteration = 1; iteration <= max_iterations; ++iteration)
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
            evaluate_map<dim>(relative, trial, trial_value, trial_jacobian);
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


  template <int dim>
  InverseMappingResult<dim>
  inverse_map_dealii(const Mapping<dim>                               &mapping,
                     const typename Triangulation<dim>::cell_iterator &cell,
                     const Point<dim>                                 &x)
  {
    InverseMappingResult<dim> result;
    try
      {
        result.xi      = mapping.transform_real_to_unit_cell(cell, x);
        result.success = true;
      }
    catch (const typename Mapping<dim>::ExcTransformationFailed &)
      {
        for (unsigned int d = 0; d < dim; ++d)
          result.xi[d] = std::numeric_limits<double>::quiet_NaN();
      }
    return result;
  }


  template <int dim>
  InverseMapping<dim>::InverseMapping(const InverseMappingType type,
                                      const Mapping<dim>      &mapping)
    : mapping_type(type)
    , mapping(&mapping)
  {
    check_input(dim == 2 || type != InverseMappingType::closed_form,
                "The closed form inverse mapping exists only in 2D; choose "
                "'newton' or 'deal.II'.");
  }


  template <int dim>
  InverseMappingResult<dim>
  InverseMapping<dim>::transform_real_to_unit_cell(
    const typename Triangulation<dim>::cell_iterator &cell,
    const Point<dim>                                 &x) const
  {
    if (mapping_type == InverseMappingType::dealii)
      return inverse_map_dealii<dim>(*mapping, cell, x);
    std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell> vertices;
    for (unsigned int v = 0; v < GeometryInfo<dim>::vertices_per_cell; ++v)
      vertices[v] = cell->vertex(v);
    return transform_real_to_unit_cell(vertices, x);
  }


  template <int dim>
  InverseMappingResult<dim>
  InverseMapping<dim>::transform_real_to_unit_cell(
    const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>
                     &vertices,
    const Point<dim> &x) const
  {
    switch (mapping_type)
      {
        case InverseMappingType::closed_form:
          if constexpr (dim == 2)
            return inverse_map_closed_form(vertices, x);
          break;
        case InverseMappingType::newton:
          return inverse_map_newton<dim>(vertices, x);
        case InverseMappingType::dealii:
          break;
      }
    Assert(false,
           ExcMessage("This inverse mapping needs a cell, not its vertices."));
    return InverseMappingResult<dim>();
  }


  template Point<2>
  map_unit_to_real(const std::array<Point<2>, 4> &, const Point<2> &);
  template Point<3>
  map_unit_to_real(const std::array<Point<3>, 8> &, const Point<3> &);
  template InverseMappingResult<2>
  inverse_map_newton(const std::array<Point<2>, 4> &,
                     const Point<2> &,
                     const double,
                     const unsigned int);
  template InverseMappingResult<3>
  inverse_map_newton(const std::array<Point<3>, 8> &,
                     const Point<3> &,
                     const double,
                     const unsigned int);
  template InverseMappingResult<2>
  inverse_map_dealii(const Mapping<2> &,
                     const Triangulation<2>::cell_iterator &,
                     const Point<2> &);
  template InverseMappingResult<3>
  inverse_map_dealii(const Mapping<3> &,
                     const Triangulation<3>::cell_iterator &,
                     const Point<3> &);
  template class InverseMapping<2>;
  template class InverseMapping<3>;
} // namespace MPM
