// Unit test: the node frames of the flume's bed (meshes/flume.msh, read as
// prm/flume_usgs.prm reads it). The bed (boundary id 1: incline at 31.4
// degrees, arc of radius 0.1 m, horizontal runout) is a frictional boundary
// with normals from the mesh. Checks that
//  - every bed node is a frictional constrained node with one normal;
//  - each node's normal is the length-weighted average of the outward
//    normals of its two bed faces, i.e. perpendicular to the chord between
//    its neighbours along the bed (one face at the two ends);
//  - on the incline and the runout that is the exact bed normal, and on the
//    arc it is within a fraction of a degree of the radial direction.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/dofs/dof_tools.h>

#include <mpm/boundary_conditions/boundary_conditions.h>
#include <mpm/grid/background_grid.h>
#include <mpm/grid/nodal_vector.h>
#include <mpm/postprocess/flume.h>

#include "unit_test_tools.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>

namespace unit_flume_bed_normals
{
  using namespace dealii;
  using namespace UnitTest;

  double
  angle_degrees(const Tensor<1, 2> &a, const Tensor<1, 2> &b)
  {
    return std::atan2(std::abs(a[0] * b[1] - a[1] * b[0]), a * b) * 180 / M_PI;
  }


  int
  run(int argc, char **argv)
  {
    Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
    const MPI_Comm                   comm = MPI_COMM_WORLD;

    ParameterHandler prm;
    MPM::BackgroundGrid<2>::declare_parameters(prm);
    MPM::BoundaryConditions<2>::declare_parameters(prm, {"bed"});
    prm.enter_subsection("flume");
    MPM::Postprocessors::Flume<2>::declare_parameters(prm);
    prm.leave_subsection();
    prm.parse_input_from_string("subsection Mesh\n"
                                "  set Source = gmsh\n"
                                "  set Gmsh file = meshes/flume.msh\n"
                                "end\n"
                                "subsection Boundary conditions\n"
                                "  set List of boundaries = bed\n"
                                "  subsection bed\n"
                                "    set Boundary ids = 1\n"
                                "    set Type = friction\n"
                                "    set Friction coefficient = 0.52\n"
                                "    set Normal = mesh\n"
                                "  end\n"
                                "end\n");
    MPM::BackgroundGrid<2> grid(comm);
    grid.parse_parameters(prm, MPM_SOURCE_DIR "/");
    grid.create();
    MPM::BoundaryConditions<2> bc;
    bc.parse_parameters(prm);
    MPM::NodalVector layout(grid.locally_owned_dofs,
                            grid.locally_relevant_dofs,
                            comm);
    bc.setup(grid, layout);
    // The bed's geometry, as the flume postprocessor has it (its defaults
    // are the flume of meshes/flume.geo).
    MPM::Postprocessors::Flume<2> flume;
    prm.enter_subsection("flume");
    flume.parse_parameters(prm);
    prm.leave_subsection();

    std::map<types::global_dof_index, Point<2>> support_points;
    DoFTools::map_dofs_to_support_points(grid.mapping,
                                         grid.dof_handler,
                                         support_points);

    // Bed nodes sorted by the distance s along the bed.
    struct BedNode
    {
      double       s, height;
      Point<2>     x;
      Tensor<1, 2> normal;
      bool         frictional;
    };
    std::vector<BedNode> bed;
    for (const auto &node : bc.constrained_nodes())
      {
        const Point<2> x = support_points.at(
          layout.get_partitioner()->local_to_global(node.local_dofs[0]));
        const auto [s, h] = flume.bed_coordinates(x[0], x[1]);
        bed.push_back({s, h, x, node.normal, node.frictional});
      }
    std::sort(bed.begin(), bed.end(), [](const BedNode &a, const BedNode &b) {
      return a.s < b.s;
    });

    const double       theta = 31.4 * M_PI / 180, radius = 0.1;
    const double       half = radius * theta / 2;
    const Point<2>     centre(radius * std::tan(theta / 2), radius);
    const Tensor<1, 2> normal_incline({-std::sin(theta), -std::cos(theta)});
    const Tensor<1, 2> normal_runout({0., -1.});

    unsigned int n_frictional = 0, n_incline = 0, n_arc = 0, n_runout = 0;
    double       max_height = 0, max_chord_error = 0;
    double       max_incline = 0, max_runout = 0, max_arc = 0;
    for (std::size_t i = 0; i < bed.size(); ++i)
      {
        const auto &b = bed[i];
        n_frictional += b.frictional;
        max_height = std::max(max_height, std::abs(b.height));
        // Length-weighted average of the faces' outward normals: the chord
        // from the previous to the next node turned by -90 degrees.
        const Point<2> &a = bed[i > 0 ? i - 1 : i].x;
        const Point<2> &c = bed[i + 1 < bed.size() ? i + 1 : i].x;
        Tensor<1, 2>    chord_normal({c[1] - a[1], -(c[0] - a[0])});
        chord_normal /= chord_normal.norm();
        max_chord_error =
          std::max(max_chord_error, (b.normal - chord_normal).norm());
        if (b.s < -half - 1e-9)
          {
            ++n_incline;
            max_incline =
              std::max(max_incline, angle_degrees(b.normal, normal_incline));
          }
        else if (b.s > half + 1e-9)
          {
            ++n_runout;
            max_runout =
              std::max(max_runout, angle_degrees(b.normal, normal_runout));
          }
        else
          {
            ++n_arc;
            Tensor<1, 2> radial = b.x - centre;
            max_arc = std::max(max_arc, angle_degrees(b.normal, radial));
          }
      }

    std::cout << std::setprecision(4) << "flume bed: " << bed.size()
              << " constrained nodes (" << n_incline << " on the incline, "
              << n_arc << " on the arc incl. its ends, " << n_runout
              << " on the runout), " << n_frictional << " frictional\n"
              << "  s from " << bed.front().s << " to " << bed.back().s
              << " m, max |height above the bed| "
              << (max_height < 1e-12 ? 0. : max_height) << " m\n"
              << "  max |n - chord normal| "
              << (max_chord_error < 1e-12 ? 0. : max_chord_error) << '\n'
              << "  max angle to the exact normal (deg): incline "
              << (max_incline < 1e-9 ? 0. : max_incline) << ", runout "
              << (max_runout < 1e-9 ? 0. : max_runout) << ", arc (radial) "
              << max_arc << '\n';
    check(n_frictional == bed.size(),
          "every bed node is frictional with one normal");
    check(max_height < 1e-12, "every constrained node lies on the bed");
    check(max_chord_error < 1e-12,
          "each normal is the average of its two faces' normals");
    check(max_incline < 1e-9 && max_runout < 1e-9,
          "exact normals on the incline and the runout");
    check(n_arc >= 5 && max_arc < 1.,
          "arc nodes within 1 degree of the radial direction");

    return UnitTest::summary();
  }
} // namespace unit_flume_bed_normals

MPM_UNIT_TEST_REGISTER(flume_bed_normals)
