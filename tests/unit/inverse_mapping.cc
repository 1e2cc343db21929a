// Inverse of the bilinear map of a quadrilateral: the closed form, Newton
// and deal.II's MappingQ1 on cells from a rectangle to aspect ratio 1000 and
// interior angles of 10 and 172 degrees, and a nearly degenerate cell
// (179.99 degrees).
//
// For each cell and method: round trips |xi(x(xi)) - xi| and
// |x(xi(x)) - x| / h (h the cell diameter) on random points of the cell,
// points on edges and vertices (inside, on the boundary to 1e-12) and points
// 1e-8 h outside each edge (outside, not clamped), and the largest
// difference between the methods. Errors are printed as pass/fail against
// 1e-12 and their order of magnitude only; numdiff's default absolute
// tolerance (1e-10) lets the magnitude differ between machines while the
// pass/fail text must match.
//
// Two FAILs are kept as documented behaviour. deal.II's: 9.4's MappingQ1
// puts the edge point xi = (1, 1 - 1e-10) of the rotated distorted cell
// 1.6e-12 outside the cell (see doc/point_location.md). And the closed form
// without its polish on the nearly degenerate cell (angle 179.99 degrees):
// the reason the closed form polishes a root whose Jacobian is small. In
// 3D, where deal.II has no closed form, its Newton stops at an estimated
// error of 1e-11 and is checked against 1e-10. The closed form (with the
// polish) and our Newton pass everywhere.
//
// 3D closed form: hexahedra extruded along one reference direction (terrain
// columns: vertical edges over a rectangular or a general quadrilateral
// cross-section, a wavy bottom and top; the same along x and along
// reference direction 0; vertical to one ulp of the coordinates only) are
// recognised and inverted without iteration, to round-off, inside and up
// to half a cell outside; a parallelepiped and a distorted hexahedron are
// not, and get Newton's numbers bit for bit.

#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <mpm/base/input_error.h>
#include <mpm/grid/extruded_cell_map.h>
#include <mpm/grid/inverse_mapping.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "unit_test_tools.h"

namespace unit_inverse_mapping
{
  using namespace dealii;
  using namespace MPM;

  using Vertices = std::array<Point<2>, 4>;

  struct Shape
  {
    std::string name;
    Vertices    vertices;
  };

  /**
   * Uniform in [0,1) from the 53 high bits of mt19937_64, so the points are
   * the same with every standard library (std::uniform_real_distribution
   * is not specified bit for bit).
   */
  double
  uniform(std::mt19937_64 &generator)
  {
    return (generator() >> 11) * 0x1.0p-53;
  }

  Point<2>
  rotate(const Point<2> &p, const double degrees, const Point<2> &shift)
  {
    const double a = degrees * M_PI / 180.;
    return Point<2>(std::cos(a) * p[0] - std::sin(a) * p[1] + shift[0],
                    std::sin(a) * p[0] + std::cos(a) * p[1] + shift[1]);
  }

  Vertices
  rotate(const Vertices &v, const double degrees, const Point<2> &shift)
  {
    Vertices w;
    for (unsigned int i = 0; i < 4; ++i)
      w[i] = rotate(v[i], degrees, shift);
    return w;
  }

  Point<2>
  polar(const double length, const double degrees)
  {
    const double a = degrees * M_PI / 180.;
    return Point<2>(length * std::cos(a), length * std::sin(a));
  }

  std::vector<Shape>
  shapes()
  {
    std::vector<Shape> s;
    // deal.II order: v0 = x(0,0), v1 = x(1,0), v2 = x(0,1), v3 = x(1,1).
    s.push_back({"rectangle", {{{3, 5}, {5, 5}, {3, 6}, {5, 6}}}});
    s.push_back({"rotated rectangle",
                 rotate(Vertices{{{0, 0}, {2, 0}, {0, 1}, {2, 1}}},
                        30,
                        Point<2>(-1, 2))});
    s.push_back({"parallelogram", {{{0, 0}, {2, 0.5}, {0.7, 1}, {2.7, 1.5}}}});
    s.push_back(
      {"trapezoid, parallel xi edges", {{{0, 0}, {2, 0}, {0.5, 1}, {1.5, 1}}}});
    s.push_back({"trapezoid, parallel eta edges",
                 {{{0, 0}, {1, 0.5}, {0, 2}, {1, 1.5}}}});
    s.push_back(
      {"general convex quad", {{{0, 0}, {1.2, 0.1}, {0.2, 0.9}, {1.1, 1.3}}}});
    // Interior angles 10 (v0), 165 (v1), about 12.6 (v3) and 172.4 (v2)
    // degrees.
    {
      const Point<2> v0(0, 0), v1(1, 0);
      const Point<2> v2 = v0 + polar(1.0, 10);
      const Point<2> v3 = v1 + polar(0.8, 15);
      s.push_back({"distorted, angles 10-172 deg", {{v0, v1, v2, v3}}});
      s.push_back({"distorted, rotated and shifted",
                   rotate(Vertices{{v0, v1, v2, v3}}, 123, Point<2>(7, -3))});
    }
    // Nearly degenerate: the interior angle at v2 is 179.99 degrees (v2
    // 6.2e-5 off the middle of the diagonal v0-v3), so the Jacobian almost
    // vanishes there and the closed form's root is ill-conditioned near
    // that corner. This is the case the polish is for, and where the
    // closed form applies it: without it a point on an edge near v2 maps
    // 1e-12 outside the cell (27 of 28 inside, FAIL below), with it all
    // 28 are inside.
    {
      const double delta = std::tan(0.5 * 1e-2 * M_PI / 180) * std::sqrt(0.5);
      s.push_back(
        {"nearly degenerate, angle 179.99 deg",
         {{{0, 0},
           {1, 0},
           {0.5 - delta * std::sqrt(0.5), 0.5 + delta * std::sqrt(0.5)},
           {1, 1}}}});
    }
    // Aspect ratio 1000, slightly non-rectangular so the map is bilinear.
    const Vertices thin_x{{{0, 0}, {1000, 0}, {0, 1}, {1000, 1.5}}};
    const Vertices thin_y{{{0, 0}, {1, 0}, {0.2, 1000}, {1.5, 1000}}};
    s.push_back({"thin, long in x", thin_x});
    s.push_back({"thin, long in y", thin_y});
    s.push_back(
      {"thin, long in x, rotated 37 deg", rotate(thin_x, 37, Point<2>(5, 5))});
    s.push_back(
      {"thin, long in y, rotated 37 deg", rotate(thin_y, 37, Point<2>(5, 5))});
    return s;
  }

  /**
   * "pass (~1e-16)": pass/fail against @p limit and the order of magnitude.
   */
  std::string
  verdict(const double error, const double limit = 1e-12)
  {
    std::string magnitude = "0";
    if (error > 0)
      magnitude =
        "1e" + std::to_string(static_cast<int>(std::floor(std::log10(error))));
    if (!std::isfinite(error))
      magnitude = "inf";
    return std::string(error <= limit ? "pass" : "FAIL") + " (~" + magnitude +
           ")";
  }

  double
  diameter(const Vertices &v)
  {
    return std::max(v[0].distance(v[3]), v[1].distance(v[2]));
  }

  /**
   * The three methods on one cell, behind one interface.
   */
  class Methods
  {
  public:
    explicit Methods(const Vertices &vertices)
        : vertices(vertices)
    {
      GridGenerator::general_cell(triangulation,
                                  std::vector<Point<2>>(vertices.begin(),
                                                        vertices.end()));
    }

    static constexpr unsigned int n = 4;

    static std::string
    name(const unsigned int m)
    {
      const char *names[n] = {"closed form",
                              "closed form, no polish",
                              "newton",
                              "deal.II"};
      return names[m];
    }

    InverseMappingResult<2>
    operator()(const unsigned int m, const Point<2> &x) const
    {
      switch (m)
        {
          case 0:
            return inverse_map_closed_form(vertices, x);
          case 1:
            return inverse_map_closed_form(vertices, x, false);
          case 2:
            return inverse_map_newton<2>(vertices, x);
          default:
            return inverse_map_dealii<2>(mapping,
                                         triangulation.begin_active(),
                                         x);
        }
    }

  private:
    Vertices         vertices;
    Triangulation<2> triangulation;
    MappingQ1<2>     mapping;
  };


  void
  test_shape(const Shape &shape)
  {
    const Vertices &v = shape.vertices;
    const double    h = diameter(v);
    Methods         methods(v);
    std::cout << shape.name << '\n';

    // Random points of the cell.
    const unsigned int    n_points = 2000;
    std::mt19937_64       generator(42);
    std::vector<Point<2>> xi_exact(n_points), x(n_points);
    for (unsigned int k = 0; k < n_points; ++k)
      {
        xi_exact[k] = Point<2>(uniform(generator), uniform(generator));
        x[k]        = map_unit_to_real(v, xi_exact[k]);
      }

    std::vector<std::vector<Point<2>>> xi(Methods::n,
                                          std::vector<Point<2>>(n_points));
    for (unsigned int m = 0; m < Methods::n; ++m)
      {
        double       error_xi = 0, error_x = 0;
        unsigned int failures = 0;
        for (unsigned int k = 0; k < n_points; ++k)
          {
            const auto result = methods(m, x[k]);
            xi[m][k]          = result.xi;
            if (!result.success)
              {
                ++failures;
                continue;
              }
            for (unsigned int d = 0; d < 2; ++d)
              error_xi =
                std::max(error_xi, std::abs(result.xi[d] - xi_exact[k][d]));
            error_x =
              std::max(error_x,
                       map_unit_to_real(v, result.xi).distance(x[k]) / h);
          }
        std::cout << "  " << Methods::name(m) << ": |xi(x(xi)) - xi| "
                  << verdict(error_xi) << ", |x(xi(x)) - x|/h "
                  << verdict(error_x) << ", failures " << failures << '\n';
      }

    // Agreement between methods (the closed form with polish against the
    // others).
    for (unsigned int m = 1; m < Methods::n; ++m)
      {
        double difference = 0;
        for (unsigned int k = 0; k < n_points; ++k)
          for (unsigned int d = 0; d < 2; ++d)
            difference =
              std::max(difference, std::abs(xi[0][k][d] - xi[m][k][d]));
        std::cout << "  closed form vs " << Methods::name(m) << ": "
                  << verdict(difference) << '\n';
      }

    // Points on edges and vertices: reference points with one coordinate 0
    // or 1, mapped to real space (vertices exactly).
    std::vector<Point<2>> on_boundary;
    std::vector<Point<2>> on_boundary_xi;
    for (unsigned int i = 0; i < 4; ++i)
      {
        on_boundary.push_back(v[i]);
        on_boundary_xi.push_back(Point<2>(i & 1, (i >> 1) & 1));
      }
    for (const double s : {1e-10, 0.25, 1. / 3, 0.5, 0.9, 1 - 1e-10})
      for (unsigned int face = 0; face < 4; ++face)
        {
          // face 0: xi = 0, 1: xi = 1, 2: eta = 0, 3: eta = 1
          const Point<2> p =
            (face < 2) ? Point<2>(face, s) : Point<2>(s, face - 2);
          on_boundary_xi.push_back(p);
          on_boundary.push_back(map_unit_to_real(v, p));
        }
    // Points 1e-8 h outside each edge, along the outward normal of the
    // (straight) edge.
    std::vector<Point<2>> outside;
    const unsigned int edge_vertices[4][2] = {{0, 2}, {3, 1}, {1, 0}, {2, 3}};
    for (unsigned int face = 0; face < 4; ++face)
      {
        const Point<2>     a = v[edge_vertices[face][0]];
        const Point<2>     b = v[edge_vertices[face][1]];
        const Tensor<1, 2> t = b - a;
        // Counter-clockwise cell, edges traversed clockwise: outward normal
        // is the tangent rotated by +90 degrees.
        Tensor<1, 2> normal;
        normal[0] = -t[1] / t.norm();
        normal[1] = t[0] / t.norm();
        for (const double s : {0., 0.1, 0.5, 0.9, 1.})
          outside.push_back(a + s * t + 1e-8 * h * normal);
      }

    for (unsigned int m = 0; m < Methods::n; ++m)
      {
        unsigned int n_inside       = 0;
        double       boundary_error = 0;
        for (unsigned int k = 0; k < on_boundary.size(); ++k)
          {
            const auto result = methods(m, on_boundary[k]);
            if (result.success && inside_unit_cell(result.xi))
              ++n_inside;
            for (unsigned int d = 0; d < 2; ++d)
              if (on_boundary_xi[k][d] == 0 || on_boundary_xi[k][d] == 1)
                boundary_error =
                  std::max(boundary_error,
                           std::abs(result.xi[d] - on_boundary_xi[k][d]));
          }
        unsigned int n_outside = 0;
        for (const auto &p : outside)
          {
            const auto result = methods(m, p);
            if (!(result.success && inside_unit_cell(result.xi)))
              ++n_outside;
          }
        std::cout << "  " << Methods::name(m) << ": on edges/vertices "
                  << n_inside << " of " << on_boundary.size()
                  << " inside, boundary coordinate " << verdict(boundary_error)
                  << "; 1e-8 h outside: " << n_outside << " of "
                  << outside.size() << " outside\n";
      }
  }

  /**
   * Newton is written for any dim: round trip on a distorted hexahedron,
   * against deal.II's MappingQ1 in 3D.
   */
  void
  test_newton_3d()
  {
    std::array<Point<3>, 8> v;
    std::mt19937_64         generator(5);
    for (unsigned int i = 0; i < 8; ++i)
      for (unsigned int d = 0; d < 3; ++d)
        v[i][d] = ((i >> d) & 1) + 0.2 * (uniform(generator) - 0.5) + d;
    Triangulation<3> triangulation;
    GridGenerator::general_cell(triangulation,
                                std::vector<Point<3>>(v.begin(), v.end()));
    MappingQ1<3> mapping;
    double       error_xi = 0, error_x = 0, difference = 0, error_dealii = 0;
    unsigned int failures = 0;
    for (unsigned int k = 0; k < 1000; ++k)
      {
        Point<3> xi;
        for (unsigned int d = 0; d < 3; ++d)
          xi[d] = uniform(generator);
        const Point<3> x      = map_unit_to_real(v, xi);
        const auto     newton = inverse_map_newton<3>(v, x);
        const auto     dealii =
          inverse_map_dealii<3>(mapping, triangulation.begin_active(), x);
        failures += !newton.success + !dealii.success;
        for (unsigned int d = 0; d < 3; ++d)
          {
            error_xi = std::max(error_xi, std::abs(newton.xi[d] - xi[d]));
            error_dealii =
              std::max(error_dealii, std::abs(dealii.xi[d] - xi[d]));
            difference =
              std::max(difference, std::abs(newton.xi[d] - dealii.xi[d]));
          }
        error_x = std::max(error_x, map_unit_to_real(v, newton.xi).distance(x));
      }
    // deal.II's Newton stops once its estimated error |J^-1 f| < 1e-11, so
    // it is held to 1e-10, not 1e-12.
    std::cout << "distorted hexahedron (3D)\n  newton: |xi(x(xi)) - xi| "
              << verdict(error_xi) << ", |x(xi(x)) - x|/h "
              << verdict(error_x / v[0].distance(v[7])) << ", failures "
              << failures << "\n  deal.II: |xi(x(xi)) - xi| against 1e-10 "
              << verdict(error_dealii, 1e-10)
              << "\n  newton vs deal.II against 1e-10: "
              << verdict(difference, 1e-10) << '\n';
  }

  /**
   * A hexahedron extruded along reference direction @p r and axis @p k:
   * the cross-section's vertices @p section in the two other axes, the
   * coordinate along k of each vertex from a wavy bottom at xi_r = 0 and a
   * wavy top at xi_r = 1.
   */
  std::array<Point<3>, 8>
  extruded_cell(const std::array<Point<2>, 4> &section,
                const unsigned int             r,
                const unsigned int             k,
                const double                   offset)
  {
    const unsigned int      p = r == 0 ? 1 : 0, q = r == 2 ? 1 : 2;
    const unsigned int      h0 = k == 0 ? 1 : 0, h1 = k == 2 ? 1 : 2;
    std::array<Point<3>, 8> v;
    for (unsigned int i = 0; i < 8; ++i)
      {
        const unsigned int j   = ((i >> p) & 1) | (((i >> q) & 1) << 1);
        const bool         top = (i >> r) & 1;
        v[i][h0]               = section[j][0];
        v[i][h1]               = section[j][1];
        v[i][k] = offset + 0.3 * j - 0.1 * j * j + (top ? 1.5 + 0.2 * j : 0);
      }
    return v;
  }

  void
  test_extruded_3d()
  {
    struct Case
    {
      std::string             name;
      std::array<Point<3>, 8> vertices;
      bool                    extruded;
    };
    const std::array<Point<2>, 4> rectangle = {
      {{50, 20}, {52, 20}, {50, 21.5}, {52, 21.5}}};
    const std::array<Point<2>, 4> quad = {
      {{0, 0}, {1.2, 0.1}, {0.2, 0.9}, {1.1, 1.3}}};
    std::vector<Case> cases;
    cases.push_back({"terrain column over a rectangle (r = 2, z)",
                     extruded_cell(rectangle, 2, 2, 120),
                     true});
    cases.push_back({"column over a general quadrilateral (r = 2, z)",
                     extruded_cell(quad, 2, 2, 0),
                     true});
    cases.push_back({"extruded along x, reference direction 0",
                     extruded_cell(quad, 0, 0, 3),
                     true});
    {
      // The top's x one ulp off the column (a refined mesh's averages).
      auto v  = extruded_cell(rectangle, 2, 2, 120);
      v[5][0] = std::nextafter(v[5][0], 100.);
      cases.push_back({"terrain column, top vertex one ulp off", v, true});
    }
    {
      auto v = extruded_cell(rectangle, 2, 2, 120);
      v[6][1] += 1e-3;
      cases.push_back({"column leaning by 1e-3 (not extruded)", v, false});
    }
    {
      std::array<Point<3>, 8> v;
      for (unsigned int i = 0; i < 8; ++i)
        for (unsigned int d = 0; d < 3; ++d)
          v[i][d] = ((i >> d) & 1) * (1. + d);
      cases.push_back({"box (a parallelepiped: not marked)", v, false});
    }
    {
      std::array<Point<3>, 8> v;
      std::mt19937_64         generator(5);
      for (unsigned int i = 0; i < 8; ++i)
        for (unsigned int d = 0; d < 3; ++d)
          v[i][d] = ((i >> d) & 1) + 0.2 * (uniform(generator) - 0.5) + d;
      cases.push_back({"distorted hexahedron (not extruded)", v, false});
    }
    std::cout << "3D closed form\n";
    for (const auto &c : cases)
      {
        const ExtrudedCellMap map(c.vertices);
        std::mt19937_64       generator(7);
        double                error_xi = 0, difference = 0;
        unsigned int          failures = 0, n_differ = 0;
        for (unsigned int n = 0; n < 2000; ++n)
          {
            // Inside, then up to half a cell outside.
            const double spread = n < 1000 ? 1 : 2;
            Point<3>     xi;
            for (unsigned int d = 0; d < 3; ++d)
              xi[d] = spread * uniform(generator) - 0.5 * (spread - 1);
            const Point<3> x      = map_unit_to_real(c.vertices, xi);
            const auto     closed = inverse_map_closed_form(c.vertices, x);
            const auto     newton = inverse_map_newton<3>(c.vertices, x);
            failures += !closed.success;
            for (unsigned int d = 0; d < 3; ++d)
              {
                error_xi = std::max(error_xi, std::abs(closed.xi[d] - xi[d]));
                difference =
                  std::max(difference, std::abs(closed.xi[d] - newton.xi[d]));
              }
            n_differ += !(closed.xi == newton.xi);
          }
        std::cout << "  " << c.name << ": extruded "
                  << (map.is_extruded() ? "yes" : "no")
                  << (map.is_extruded() == c.extruded ? "" : " (WRONG)")
                  << ", |xi(x(xi)) - xi| " << verdict(error_xi)
                  << ", against Newton " << verdict(difference) << ", failures "
                  << failures;
        if (!c.extruded)
          std::cout << ", bits differ from Newton's in " << n_differ
                    << " of 2000";
        std::cout << '\n';
      }
  }


  int
  run(int /*argc*/, char ** /*argv*/)
  {
    for (const std::string name : {"closed form", "newton", "deal.II"})
      std::cout << "parse '" << name << "' -> '"
                << to_string(parse_inverse_mapping_type(name)) << "'\n";
    try
      {
        parse_inverse_mapping_type("Newton");
      }
    catch (const InputError &error)
      {
        std::cout << "parse 'Newton': " << error.what() << '\n';
      }

    for (const auto &shape : shapes())
      test_shape(shape);

    test_newton_3d();
    test_extruded_3d();
    // The comparison of the output is the check.
    return 0;
  }
} // namespace unit_inverse_mapping

MPM_UNIT_TEST_REGISTER(inverse_mapping)
