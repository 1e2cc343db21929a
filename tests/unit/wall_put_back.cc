// A material point that dipped below the ground by a little is put back
// onto it (PointRelocation::put_back_onto_wall()), also where the ground
// turns up between its old cell and the next (a concave kink): there the
// point lies beyond the neighbour's wall but not beyond any wall of its old
// cell, in the wedge between the neighbour's ground and the old cell's
// ground continued. Before the neighbour's walls were tried, such a point
// had left the mesh: the 3D landslide (prm/landslide_valley_3d.prm on the
// 2 m terrain, 0.5 m cells) stopped at 4.9 s on a point just below the
// terrain at a node of the terrain's 2 m grid (with the neighbours tried it
// ran to 12 s, 3,728 points put back, the farthest by 0.26 mm). Two cells, the ground flat under the left one and rising at
// 0.4 under the right one; each case starts with one point in the left
// cell, moves it and relocates it.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/grid/background_grid.h>
#include <mpm/material_points/point_relocation.h>

#include "unit_test_tools.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>

namespace unit_wall_put_back
{
  using namespace dealii;
  using namespace UnitTest;

  int
  run(int argc, char **argv)
  {
    Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
    const MPI_Comm                   comm = MPI_COMM_WORLD;

    // The ground (physical tag 2): (0, 0) - (1, 0) - (2, 0.4); the other
    // faces untagged (boundary id 0, not a wall here).
    {
      std::ofstream msh("kink.msh");
      msh << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
          << "$Nodes\n6\n1 0 0 0\n2 1 0 0\n3 2 0.4 0\n"
          << "4 0 1 0\n5 1 1 0\n6 2 1.4 0\n$EndNodes\n"
          << "$Elements\n4\n1 1 2 2 1 1 2\n2 1 2 2 1 2 3\n"
          << "3 3 2 0 1 1 2 5 4\n4 3 2 0 1 2 3 6 5\n$EndElements\n";
    }
    ParameterHandler prm;
    MPM::BackgroundGrid<2>::declare_parameters(prm);
    MPM::PointRelocation<2>::declare_parameters(prm);
    prm.parse_input_from_string("subsection Mesh\n"
                                "  set Source = gmsh\n"
                                "  set Gmsh file = kink.msh\n"
                                "end\n");
    MPM::BackgroundGrid<2> grid(comm);
    grid.parse_parameters(prm, "./");
    grid.create();

    const auto ground_y = [](const double x) {
      return x <= 1 ? 0. : 0.4 * (x - 1);
    };
    // Move a point from (0.9, 0.05) in the left cell to @p x and relocate.
    const auto move_to = [&](const Point<2> &x) {
      MPM::PointRelocation<2> relocation;
      relocation.parse_parameters(prm);
      relocation.initialize(grid);
      relocation.set_walls({2});
      Particles::ParticleHandler<2> particles(grid.triangulation,
                                              grid.mapping,
                                              1);
      unsigned int                  n_lost = 0;
      particles.signals.particle_lost.connect(
        [&](const auto &, const auto &) { ++n_lost; });
      const auto             left_cell = grid.triangulation.begin_active();
      Particles::Particle<2> point(Point<2>(0.9, 0.05), Point<2>(0.9, 0.05), 0);
      auto                   it = particles.insert_particle(point, left_cell);
      it->set_location(x);
      relocation.relocate(particles);
      std::cout << "  moved to (" << x << "): ";
      if (particles.n_locally_owned_particles() == 0)
        {
          std::cout << "left the mesh (" << n_lost << " lost)\n";
          return std::make_tuple(false, Point<2>(), 0u, 0ull);
        }
      const auto         p = particles.begin();
      const Point<2>     y = p->get_location();
      const unsigned int c = p->get_surrounding_cell()->active_cell_index();
      std::cout << std::setprecision(6) << "at (" << y << ") in cell " << c
                << ", " << relocation.statistics().n_points_put_back
                << " put back\n";
      return std::make_tuple(true,
                             y,
                             c,
                             relocation.statistics().n_points_put_back);
    };

    std::cout << "a point that stayed above the ground\n";
    {
      const auto [kept, y, cell, n_put_back] = move_to(Point<2>(1.2, 0.3));
      check(kept && cell == 1 && n_put_back == 0 &&
              (y - Point<2>(1.2, 0.3)).norm() == 0,
            "found in the right cell, not moved");
    }
    std::cout << "below its own cell's ground, by 0.01\n";
    {
      const auto [kept, y, cell, n_put_back] = move_to(Point<2>(0.95, -0.01));
      check(kept && cell == 0 && n_put_back == 1 &&
              std::abs(y[1] - ground_y(y[0])) < 1e-12 &&
              std::abs(y[0] - 0.95) < 1e-12,
            "put back onto the left cell's ground, straight up");
    }
    std::cout << "past the concave kink, 0.01 below the right cell's "
                 "ground, above the left cell's continued\n";
    {
      const auto [kept, y, cell, n_put_back] = move_to(Point<2>(1.05, 0.01));
      check(kept && cell == 1 && n_put_back == 1 &&
              std::abs(y[1] - ground_y(y[0])) < 1e-12 &&
              (y - Point<2>(1.05, 0.01)).norm() < 0.011,
            "put back onto the right cell's ground, by about 0.01");
    }
    std::cout << "past the kink and far below the ground (0.5, beyond "
                 "'Wall overshoot tolerance' 0.25)\n";
    {
      const auto [kept, y, cell, n_put_back] = move_to(Point<2>(1.05, -0.5));
      (void)y;
      (void)cell;
      (void)n_put_back;
      check(!kept, "left the mesh");
    }
    return summary();
  }
} // namespace unit_wall_put_back

MPM_UNIT_TEST_REGISTER(wall_put_back)
