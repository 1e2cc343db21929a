// HDF5 output of the material points ('Output/Particle format = hdf5'):
// OutputWriter writes three points with known positions and properties;
// reading the file back with deal.II's HDF5 wrappers gives the same
// positions (property values to single precision: deal.II's patches
// store data as float), and particles.xdmf names the file, the
// number of points and each property.

#include <deal.II/base/hdf5.h>
#include <deal.II/base/mpi.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/output/output_writer.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "unit_test_tools.h"

namespace unit_hdf5_output
{
  using namespace dealii;
  using namespace MPM;
  using UnitTest::check;

  int
  run(int argc, char **argv)
  {
    Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
    const MPI_Comm                   comm = MPI_COMM_WORLD;

    parallel::distributed::Triangulation<2> triangulation(comm);
    GridGenerator::subdivided_hyper_cube(triangulation, 2);
    MappingQ1<2>                  mapping;
    Particles::ParticleHandler<2> particles(triangulation, mapping, 2);
    const std::vector<Point<2>>   locations{Point<2>(0.1, 0.2),
                                          Point<2>(0.7, 0.3),
                                          Point<2>(0.4, 0.9)};
    particles.insert_particles(locations);
    for (auto &p : particles)
      {
        p.get_properties()[0] = 10. + p.get_id();
        p.get_properties()[1] = p.get_location()[0] * p.get_location()[1];
      }

    ParameterHandler prm;
    OutputWriter<2>::declare_parameters(prm);
    prm.parse_input_from_string("subsection Output\n"
                                "  set Directory = hdf5\n"
                                "  set Particle format = hdf5\n"
                                "end\n");
    OutputWriter<2> writer;
    writer.parse_parameters(prm);
    writer.initialize(comm);
    writer.write_particles(particles, {"mass", "product"}, 0.25, 7, comm);

    std::cout << "HDF5 file of 3 points with properties mass, product:\n";
    HDF5::File file("hdf5/particles_00007.h5",
                    HDF5::File::FileAccessMode::open);
    const auto nodes = file.open_dataset("nodes").read<std::vector<double>>();
    const auto mass  = file.open_dataset("mass").read<std::vector<double>>();
    const auto product =
      file.open_dataset("product").read<std::vector<double>>();
    check(nodes.size() == 6 && mass.size() == 3 && product.size() == 3,
          "3 points: 6 coordinates, 3 values per property");
    // The file's order is the handler's; match by the mass, which is 10 + id.
    bool same = nodes.size() == 6 && mass.size() == 3 && product.size() == 3;
    for (unsigned int i = 0; same && i < 3; ++i)
      {
        const unsigned int id = static_cast<unsigned int>(mass[i] - 10 + 0.5);
        // deal.II's patches hold data in single precision: positions are
        // exact, property values to float round-off.
        const double exact = locations[id][0] * locations[id][1];
        same = same && id < 3 && nodes[2 * i] == locations[id][0] &&
               nodes[2 * i + 1] == locations[id][1] &&
               std::abs(product[i] - exact) <= 1e-7 * exact;
        std::cout << "    point " << id << " at (" << nodes[2 * i] << ", "
                  << nodes[2 * i + 1] << "), product " << product[i] << '\n';
      }
    check(same, "positions read back exactly, values to single precision");

    std::ifstream      xdmf("hdf5/particles.xdmf");
    std::ostringstream text;
    text << xdmf.rdbuf();
    const std::string s = text.str();
    check(s.find("particles_00007.h5:/nodes") != std::string::npos &&
            s.find("Time Value=\"0.25\"") != std::string::npos &&
            s.find("NumberOfElements=\"3\"") != std::string::npos &&
            s.find("particles_00007.h5:/product") != std::string::npos,
          "particles.xdmf names the file, the time, the points and properties");
    return UnitTest::summary();
  }
} // namespace unit_hdf5_output

MPM_UNIT_TEST_REGISTER(hdf5_output)
