// Throughput of the inverse mapping and of point location.
//
// 1. Points per second of each inverse mapping (closed form with and
//    without the Newton polish, Newton, deal.II's MappingQ1) on single
//    cells of several shapes, 1e6 random points inside each cell.
// 2. Points per second of deal.II's
//    ParticleHandler::sort_particles_into_subdomains_and_cells() on a
//    distorted 100 x 100 mesh with 16 points per cell after every point has
//    moved by a random displacement of up to 0.2 h per coordinate, so that
//    a fraction of them (printed) changes cell; and, on the same moved
//    points, of locating them with locate_point() (previous cell first,
//    then the cells sharing a vertex with it) for each inverse mapping.
//    The latter only finds cell and reference coordinates; sort_particles
//    also moves the particles in storage.
//
// Usage: inverse_mapping_benchmark [points per shape (default 1e6)]
// Run on one core (one MPI rank); each figure is the best of 3 repetitions.

#include <deal.II/base/mpi.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <deal.II/particles/generators.h>
#include <deal.II/particles/particle_handler.h>

#include <mpm/grid/inverse_mapping.h>
#include <mpm/grid/point_location.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <set>
#include <string>
#include <vector>

using namespace dealii;
using namespace MPM;

namespace
{
  using Vertices = std::array<Point<2>, 4>;

  double
  uniform(std::mt19937_64 &generator)
  {
    return (generator() >> 11) * 0x1.0p-53;
  }

  Vertices
  rotate(const Vertices &v, const double degrees)
  {
    const double a = degrees * M_PI / 180.;
    Vertices     w;
    for (unsigned int i = 0; i < 4; ++i)
      w[i] = Point<2>(std::cos(a) * v[i][0] - std::sin(a) * v[i][1] + 5,
                      std::sin(a) * v[i][0] + std::cos(a) * v[i][1] + 5);
    return w;
  }

  /**
   * Best of three wall-clock times of @p f, in seconds.
   */
  double
  best_time(const std::function<void()> &f)
  {
    double best = 1e300;
    for (unsigned int repetition = 0; repetition < 3; ++repetition)
      {
        const auto start = std::chrono::steady_clock::now();
        f();
        const std::chrono::duration<double> elapsed =
          std::chrono::steady_clock::now() - start;
        best = std::min(best, elapsed.count());
      }
    return best;
  }


  void
  benchmark_single_cells(const unsigned int n_points)
  {
    const double s10 = std::sin(10 * M_PI / 180),
                 c10 = std::cos(10 * M_PI / 180);
    const double s15 = std::sin(15 * M_PI / 180),
                 c15 = std::cos(15 * M_PI / 180);
    const Vertices thin{{{0, 0}, {1000, 0}, {0, 1}, {1000, 1.5}}};
    const std::vector<std::pair<std::string, Vertices>> shapes = {
      {"rectangle", {{{3, 5}, {5, 5}, {3, 6}, {5, 6}}}},
      {"parallelogram", {{{0, 0}, {2, 0.5}, {0.7, 1}, {2.7, 1.5}}}},
      {"general convex quad", {{{0, 0}, {1.2, 0.1}, {0.2, 0.9}, {1.1, 1.3}}}},
      {"distorted 10-172 deg",
       {{{0, 0}, {1, 0}, {c10, s10}, {1 + 0.8 * c15, 0.8 * s15}}}},
      {"thin 1000:1, rotated", rotate(thin, 37)}};

    std::printf("1. Inverse mapping of %u random points per cell, "
                "million points per second\n",
                n_points);
    std::printf("%-24s %12s %12s %12s %12s\n",
                "shape",
                "closed form",
                "(no polish)",
                "newton",
                "deal.II");
    for (const auto &[name, vertices] : shapes)
      {
        std::mt19937_64       generator(1);
        std::vector<Point<2>> x(n_points);
        for (auto &p : x)
          p =
            map_unit_to_real(vertices,
                             Point<2>(uniform(generator), uniform(generator)));
        Triangulation<2> triangulation;
        GridGenerator::general_cell(triangulation,
                                    std::vector<Point<2>>(vertices.begin(),
                                                          vertices.end()));
        const MappingQ1<2> mapping;
        const auto         cell = triangulation.begin_active();

        double              checksum = 0;
        std::vector<double> rate;
        // Each method is timed through its own lambda, inlined into the
        // loop, so that no call indirection is added to the fast methods.
        const auto time_method = [&](const auto &method) {
          const double t = best_time([&]() {
            for (const auto &p : x)
              {
                const auto r = method(p);
                checksum += r.xi[0] + r.xi[1];
              }
          });
          rate.push_back(n_points / t / 1e6);
        };
        time_method([&](const Point<2> &p) {
          return inverse_map_closed_form(vertices, p);
        });
        time_method([&](const Point<2> &p) {
          return inverse_map_closed_form(vertices, p, false);
        });
        time_method([&](const Point<2> &p) {
          return inverse_map_newton<2>(vertices, p);
        });
        time_method([&](const Point<2> &p) {
          return inverse_map_dealii<2>(mapping, cell, p);
        });
        std::printf("%-24s %12.2f %12.2f %12.2f %12.2f\n",
                    name.c_str(),
                    rate[0],
                    rate[1],
                    rate[2],
                    rate[3]);
        if (!std::isfinite(checksum))
          std::printf("  (non-finite checksum)\n");
      }
    std::printf("\n");
  }


  void
  benchmark_particle_location()
  {
    const unsigned int                      n_cells_1d = 100;
    parallel::distributed::Triangulation<2> triangulation(MPI_COMM_WORLD);
    GridGenerator::subdivided_hyper_cube(triangulation, n_cells_1d);
    GridTools::transform(
      [](const Point<2> &p) {
        return Point<2>(p[0] + 0.02 * std::sin(M_PI * p[0]) *
                                 std::sin(6 * M_PI * p[1]),
                        p[1] + 0.02 * std::sin(6 * M_PI * p[0]) *
                                 std::sin(M_PI * p[1]));
      },
      triangulation);
    const double h = 1. / n_cells_1d;

    const MappingQ1<2>            mapping;
    Particles::ParticleHandler<2> particle_handler(triangulation, mapping);
    std::vector<Point<2>>         reference_locations;
    for (unsigned int j = 0; j < 4; ++j)
      for (unsigned int i = 0; i < 4; ++i)
        reference_locations.emplace_back((i + 0.5) / 4, (j + 0.5) / 4);
    Particles::Generators::regular_reference_locations(triangulation,
                                                       reference_locations,
                                                       particle_handler,
                                                       mapping);
    const unsigned int n_particles = particle_handler.n_global_particles();

    // Displacements, by particle id, up to 0.2 h per coordinate, turned
    // around where they would leave the unit square. Points sit 1/8 of a
    // cell from the nearest edges, so about a sixth of them change cell.
    std::vector<Tensor<1, 2>> displacement(n_particles);
    std::mt19937_64           generator(7);
    for (auto &d : displacement)
      for (unsigned int c = 0; c < 2; ++c)
        d[c] = (2 * uniform(generator) - 1) * 0.2 * h;
    for (const auto &particle : particle_handler)
      for (unsigned int c = 0; c < 2; ++c)
        {
          const double y =
            particle.get_location()[c] + displacement[particle.get_id()][c];
          if (y < 0 || y > 1)
            displacement[particle.get_id()][c] *= -1;
        }

    // Candidate cells of a point that left its cell: those around the
    // vertex of the old cell nearest to the point's (extrapolated)
    // reference coordinates in the old cell, which contain every cell a
    // point can reach by crossing one edge or one vertex; if not found
    // there, all cells sharing a vertex with the old cell. Set up once per
    // mesh, not timed.
    const auto vertex_to_cells = GridTools::vertex_to_cell_map(triangulation);
    std::vector<std::vector<Triangulation<2>::active_cell_iterator>>
      cells_at_vertex(triangulation.n_vertices());
    for (unsigned int v = 0; v < triangulation.n_vertices(); ++v)
      cells_at_vertex[v].assign(vertex_to_cells[v].begin(),
                                vertex_to_cells[v].end());
    std::vector<std::vector<Triangulation<2>::active_cell_iterator>>
      cells_around(triangulation.n_active_cells());
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        std::set<Triangulation<2>::active_cell_iterator> around;
        for (const unsigned int v : cell->vertex_indices())
          for (const auto &other : vertex_to_cells[cell->vertex_index(v)])
            around.insert(other);
        cells_around[cell->active_cell_index()].assign(around.begin(),
                                                       around.end());
      }

    std::printf("2. Point location on a distorted %u x %u mesh, 16 points "
                "per cell (%u points), displacement up to 0.2 h\n",
                n_cells_1d,
                n_cells_1d,
                n_particles);

    double                   best_sort      = 1e300;
    double                   best_locate[3] = {1e300, 1e300, 1e300};
    unsigned int             n_crossing = 0, n_not_found = 0, n_fallback = 0;
    double                   sign     = 1;
    const InverseMappingType types[3] = {InverseMappingType::closed_form,
                                         InverseMappingType::newton,
                                         InverseMappingType::dealii};
    for (unsigned int repetition = 0; repetition < 3; ++repetition)
      {
        // Move: out and back alternately, so each repetition sees the
        // same number of crossings.
        for (auto &particle : particle_handler)
          particle.set_location(particle.get_location() +
                                sign * displacement[particle.get_id()]);
        sign = -sign;

        for (unsigned int m = 0; m < 3; ++m)
          {
            const InverseMapping<2> inverse(types[m], mapping);
            unsigned int            crossing = 0, not_found = 0, fallback = 0;
            const auto              start = std::chrono::steady_clock::now();
            for (const auto &cell : triangulation.active_cell_iterators())
              for (const auto &particle :
                   particle_handler.particles_in_cell(cell))
                {
                  const Point<2> x = particle.get_location();
                  const auto r = inverse.transform_real_to_unit_cell(cell, x);
                  if (r.success && inside_unit_cell(r.xi))
                    continue;
                  ++crossing;
                  const unsigned int nearest_vertex =
                    r.success ? (r.xi[0] > 0.5) + 2 * (r.xi[1] > 0.5) : 0;
                  auto location = locate_point(
                    inverse,
                    cells_at_vertex[cell->vertex_index(nearest_vertex)],
                    x);
                  if (!location.found)
                    {
                      ++fallback;
                      location =
                        locate_point(inverse,
                                     cells_around[cell->active_cell_index()],
                                     x);
                    }
                  not_found += !location.found;
                }
            const std::chrono::duration<double> elapsed =
              std::chrono::steady_clock::now() - start;
            best_locate[m] = std::min(best_locate[m], elapsed.count());
            n_crossing     = crossing;
            n_not_found    = not_found;
            n_fallback     = fallback;
          }

        const auto start = std::chrono::steady_clock::now();
        particle_handler.sort_particles_into_subdomains_and_cells();
        const std::chrono::duration<double> elapsed =
          std::chrono::steady_clock::now() - start;
        best_sort = std::min(best_sort, elapsed.count());
      }
    std::printf("   points that changed cell: %u (%.1f %%), not found around "
                "the nearest vertex: %u, nor around the old cell: %u, "
                "points left: %u\n",
                n_crossing,
                100. * n_crossing / n_particles,
                n_fallback,
                n_not_found,
                static_cast<unsigned int>(
                  particle_handler.n_global_particles()));
    std::printf("   %-58s %8.2f million points/s\n",
                "ParticleHandler::sort_particles_into_subdomains_and_cells",
                n_particles / best_sort / 1e6);
    for (unsigned int m = 0; m < 3; ++m)
      std::printf("   %-58s %8.2f million points/s\n",
                  ("locate_point, " + to_string(types[m])).c_str(),
                  n_particles / best_locate[m] / 1e6);
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int               n_points =
    (argc > 1) ? static_cast<unsigned int>(std::stod(argv[1])) : 1000000;
  benchmark_single_cells(n_points);
  benchmark_particle_location();
}
