// libFuzzer target: the parameter file reader. The input is written to a
// file and read as `mpm` reads its parameter files (two passes: the name
// lists, then everything), then the Simulator parses it (materials, regions,
// boundary conditions, time stepping, output, postprocessors). Every outcome
// but a crash is fine: bad input must end in an exception (InputError or a
// deal.II error), never in a segmentation fault, an abort or a hang.
// Built and run by scripts/fuzz.sh.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/base/input_deck.h>
#include <mpm/solver/simulator.h>

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
  const std::string file = "fuzz_input.prm";
  {
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char *>(data), size);
  }
  try
    {
      ParameterHandler names_prm;
      Simulator<2>::declare_name_lists(names_prm);
      parse_parameter_file(names_prm, file, true);
      const auto names = Simulator<2>::read_name_lists(names_prm);

      ParameterHandler prm;
      Simulator<2>::declare_parameters(prm, names);
      parse_parameter_file(prm, file, false);

      Simulator<2> simulator(MPI_COMM_WORLD);
      simulator.parse_parameters(prm, "./");
    }
  catch (const std::exception &e)
    {
      // MPM_FUZZ_VERBOSE=1 shows the messages (to check the seeds pass).
      if (std::getenv("MPM_FUZZ_VERBOSE"))
        std::cerr << e.what() << '\n';
      // A clear error is the expected answer to bad input.
    }
  return 0;
}
