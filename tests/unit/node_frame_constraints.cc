// Unit test of the boundary conditions in node frames.
//
// 1. Tilted slip wall: a 4 x 4 mesh of the unit square, rotated as a whole
//    by several angles, with a slip condition on its bottom edge. Every
//    node gets the velocity v = 1 t + 0.5 n (t, n the wall's tangent and
//    outward normal). The orthogonal projection of BoundaryConditions must
//    remove the normal part and keep the tangential part exactly;
//    AffineConstraints::distribute() on the same constraints (an oblique
//    projection: it overwrites the pivot component) changes the tangential
//    velocity on every wall that is not axis-aligned. Both are printed.
// 2. Coulomb friction in the node frame (frictional_acceleration): static,
//    kinetic, stopping instead of reversing, and a node leaving the wall,
//    each against the value the rule of doc/algorithm.md gives.
// 3. Friction at a 3D edge node (edge_frictional_acceleration): a
//    frictional bed against a slip side wall must act along the edge as
//    the one-normal rule acts on a bed alone, whatever the velocity into
//    the side wall; no friction where the bed pulls.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/boundary_conditions/boundary_conditions.h>
#include <mpm/boundary_conditions/coulomb_friction.h>
#include <mpm/boundary_conditions/wall_friction.h>
#include <mpm/grid/background_grid.h>
#include <mpm/grid/nodal_vector.h>

#include "unit_test_tools.h"

#include <cmath>
#include <iomanip>
#include <iostream>

namespace unit_node_frame_constraints
{
  using namespace dealii;
  using namespace UnitTest;

  void
  tilted_slip_wall(const double angle_degrees)
  {
    const MPI_Comm   comm = MPI_COMM_WORLD;
    ParameterHandler prm;
    MPM::BackgroundGrid<2>::declare_parameters(prm);
    MPM::BoundaryConditions<2>::declare_parameters(prm, {"bed"});
    prm.parse_input_from_string(
      "subsection Mesh\n"
      "  set Generator arguments = {4, 4} : 0, 0 : 1, 1 : true\n"
      "  set Scene rotation angle = " +
      std::to_string(angle_degrees) +
      "\n"
      "end\n"
      "subsection Boundary conditions\n"
      "  set List of boundaries = bed\n"
      "  subsection bed\n"
      "    set Boundary ids = 2\n"
      "    set Type = slip\n"
      "  end\n"
      "end\n");

    MPM::BackgroundGrid<2> grid(comm);
    grid.parse_parameters(prm, ".");
    grid.create();
    MPM::BoundaryConditions<2> bc;
    bc.parse_parameters(prm);

    MPM::NodalVector velocity(grid.locally_owned_dofs,
                              grid.locally_relevant_dofs,
                              comm);
    bc.setup(grid, velocity);

    // The wall's frame in the mesh: the bottom edge's outward normal (0, -1)
    // and tangent (1, 0), rotated with the scene.
    const Tensor<1, 2> n  = grid.to_mesh_frame(Tensor<1, 2>({0., -1.}));
    const Tensor<1, 2> t  = grid.to_mesh_frame(Tensor<1, 2>({1., 0.}));
    const Tensor<1, 2> v0 = 1.0 * t + 0.5 * n;
    for (unsigned int i = 0; i < velocity.locally_owned_size(); i += 2)
      {
        velocity.local_element(i)     = v0[0];
        velocity.local_element(i + 1) = v0[1];
      }
    MPM::NodalVector oblique(velocity);

    bc.project_velocity(velocity);
    bc.constraints().distribute(oblique);

    double max_normal = 0, max_tangential = 0;
    double max_normal_distribute = 0, max_tangential_distribute = 0;
    for (const auto &node : bc.constrained_nodes())
      {
        const Tensor<1, 2> v({velocity.local_element(node.local_dofs[0]),
                              velocity.local_element(node.local_dofs[1])});
        const Tensor<1, 2> w({oblique.local_element(node.local_dofs[0]),
                              oblique.local_element(node.local_dofs[1])});
        max_normal     = std::max(max_normal, std::abs(v * n));
        max_tangential = std::max(max_tangential, std::abs(v * t - 1.));
        max_normal_distribute =
          std::max(max_normal_distribute, std::abs(w * n));
        max_tangential_distribute =
          std::max(max_tangential_distribute, std::abs(w * t - 1.));
      }
    std::cout << "wall at " << std::setw(6) << angle_degrees << " deg, "
              << bc.constrained_nodes().size() << " nodes, v = 1 t + 0.5 n\n"
              << "  projection:   max |v.n| = "
              << flush_to_zero(max_normal, 1e-13)
              << ", max |v.t - 1| = " << flush_to_zero(max_tangential, 1e-13)
              << '\n'
              << "  distribute(): max |v.n| = "
              << flush_to_zero(max_normal_distribute, 1e-13)
              << ", max |v.t - 1| = "
              << flush_to_zero(max_tangential_distribute, 1e-13) << '\n';
    check(bc.constrained_nodes().size() == 5, "the 5 nodes of the bottom edge");
    check(max_normal < 1e-14 && max_tangential < 1e-14,
          "projection removes v.n and keeps v.t to round-off");
    const bool axis_aligned =
      std::abs(std::remainder(angle_degrees, 90.)) < 1e-12;
    check(axis_aligned ? max_tangential_distribute < 1e-14 :
                         max_tangential_distribute > 1e-3,
          axis_aligned ? "distribute() agrees on an axis-aligned wall" :
                         "distribute() changes v.t on a tilted wall");
  }


  void
  friction(const std::string  &what,
           const Tensor<1, 2> &v,
           const Tensor<1, 2> &a,
           const double        mu,
           const Tensor<1, 2> &expected)
  {
    // Wall: outward normal (0, -1), so pressing into it is a_y < 0.
    const double       dt = 0.01;
    const Tensor<1, 2> n({0., -1.});
    const Tensor<1, 2> result = MPM::WallFriction::frictional_acceleration<2>(
      v, a, n, MPM::CoulombFriction<2>(mu), {}, dt);
    std::cout << "friction, " << what << ": v = (" << v << "), a = (" << a
              << "), mu = " << mu << ", dt = " << dt << "\n  a' = ("
              << flush_to_zero(result[0], 1e-13) << ", "
              << flush_to_zero(result[1], 1e-13) << "), expected (" << expected
              << ")\n";
    check((result - expected).norm() < 1e-12, what);
  }

  void
  edge_friction(const std::string  &what,
                const Tensor<1, 3> &v,
                const Tensor<1, 3> &a,
                const Tensor<1, 3> &expected,
                const Tensor<1, 3> &side_normal = Tensor<1, 3>({0., 1., 0.}))
  {
    const double                      dt = 0.01;
    const MPM::CoulombFriction<3>     bed_law(0.5);
    const std::array<Tensor<1, 3>, 2> n{
      {Tensor<1, 3>({0., 0., -1.}), side_normal}};
    const Tensor<1, 3> result =
      MPM::WallFriction::edge_frictional_acceleration<3>(
        v, a, n, {{&bed_law, nullptr}}, {}, dt);
    std::cout << "edge friction, " << what << ": v = (" << v << "), a = (" << a
              << "), mu = 0.5 (bed), 0 (side wall (" << side_normal
              << ")), dt = " << dt << "\n  a' = ("
              << flush_to_zero(result[0], 1e-12) << ", "
              << flush_to_zero(result[1], 1e-12) << ", "
              << flush_to_zero(result[2], 1e-12) << "), expected (" << expected
              << ")\n";
    check((result - expected).norm() < 1e-10, what);
  }


  int
  run(int argc, char **argv)
  {
    Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
    for (const double angle : {0., 15., 30., 45., 60., 90., 137., -71.})
      tilted_slip_wall(angle);

    // Normal reaction per unit mass r = v.n/dt + a.n = 10: capacity mu r = 5.
    friction("static, demand 3 below capacity 5: stays at rest",
             Tensor<1, 2>(),
             Tensor<1, 2>({3., -10.}),
             0.5,
             Tensor<1, 2>({0., -10.}));
    friction("static, demand 8 above capacity 5: moves with 8 - 5",
             Tensor<1, 2>(),
             Tensor<1, 2>({8., -10.}),
             0.5,
             Tensor<1, 2>({3., -10.}));
    friction("kinetic, sliding at 1 m/s: a_t reduced by mu r",
             Tensor<1, 2>({1., 0.}),
             Tensor<1, 2>({2., -10.}),
             0.5,
             Tensor<1, 2>({-3., -10.}));
    friction("kinetic, would reverse 0.01 m/s within the step: stops",
             Tensor<1, 2>({0.01, 0.}),
             Tensor<1, 2>({0., -10.}),
             0.5,
             Tensor<1, 2>({-1., -10.}));
    friction("leaving the wall (a.n < 0): no friction",
             Tensor<1, 2>({1., 0.}),
             Tensor<1, 2>({2., 10.}),
             0.5,
             Tensor<1, 2>({2., 10.}));

    // Bed reaction r = v.n/dt + a.n = 10 (capacity mu r dt = 0.05 m/s);
    // along the edge (x) as the one-normal rule, across it (y, into the
    // side wall) untouched: the projection removes it.
    edge_friction("sliding along the edge, pressed into the side wall",
                  Tensor<1, 3>({1., 0., 0.}),
                  Tensor<1, 3>({2., 0.7, -10.}),
                  Tensor<1, 3>({-3., 0.7, -10.}));
    edge_friction("static along the edge, demand 3 below capacity 5",
                  Tensor<1, 3>(),
                  Tensor<1, 3>({3., -4., -10.}),
                  Tensor<1, 3>({0., -4., -10.}));
    edge_friction("the bed pulls (a.n < 0): no friction",
                  Tensor<1, 3>({1., 0., 0.}),
                  Tensor<1, 3>({2., 0.7, 10.}),
                  Tensor<1, 3>({2., 0.7, 10.}));
    // A side wall leaning by 30 degrees (normal (0, cos 30, sin 30)), the
    // node pushed into it: the edge is still x, and the wall's impulse has a
    // downward part that the bed must take as well. Trial w = (1.02, 0.05,
    // -0.1); on the edge y and z vanish: 0.05 + l_side cos 30 = 0 and
    // -0.1 - l_bed + l_side sin 30 = 0, so -l_bed = 0.1 + 0.05 tan 30.
    {
      const double c = std::cos(M_PI / 6), s30 = std::sin(M_PI / 6);
      const double capacity = 0.5 * (0.1 + 0.05 * s30 / c);
      edge_friction("sliding along the edge of a leaning side wall",
                    Tensor<1, 3>({1., 0., 0.}),
                    Tensor<1, 3>({2., 5., -10.}),
                    Tensor<1, 3>({(1.02 - capacity - 1.) / 0.01, 5., -10.}),
                    Tensor<1, 3>({0., c, s30}));
    }

    return UnitTest::summary();
  }
} // namespace unit_node_frame_constraints

MPM_UNIT_TEST_REGISTER(node_frame_constraints)
