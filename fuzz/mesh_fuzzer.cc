// libFuzzer target: the mesh reader path. The input is written to a file
// and read as a Gmsh mesh by BackgroundGrid (deal.II's GridIn, then the
// checks and set-up of the background mesh: cell sizes, degrees of
// freedom). Every outcome but a crash is fine: a bad mesh must end in an
// exception, never in a segmentation fault, an abort or a hang.
// Built and run by scripts/fuzz.sh.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/grid/background_grid.h>

#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <fstream>
#include <string>

using namespace dealii;
using namespace MPM;

extern "C" int
LLVMFuzzerInitialize(int *argc, char ***argv)
{
  static Utilities::MPI::MPI_InitFinalize mpi(*argc, *argv, 1);
  return 0;
}

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  {
    std::ofstream out("fuzz_input.msh", std::ios::binary);
    out.write(reinterpret_cast<const char *>(data), size);
  }
  try
    {
      ParameterHandler prm;
      BackgroundGrid<2>::declare_parameters(prm);
      prm.parse_input_from_string("subsection Mesh\n"
                                  "  set Source    = gmsh\n"
                                  "  set Gmsh file = fuzz_input.msh\n"
                                  "end\n");
      BackgroundGrid<2> grid(MPI_COMM_WORLD);
      grid.parse_parameters(prm, "./");
      grid.create();
    }
  catch (const std::exception &e)
    {
      // MPM_FUZZ_VERBOSE=1 shows the messages (to check the seeds pass).
      if (std::getenv("MPM_FUZZ_VERBOSE"))
        std::cerr << e.what() << '\n';
      // A clear error is the expected answer to a bad mesh.
    }
  return 0;
}
