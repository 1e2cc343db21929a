#ifndef mpm_solver_run_from_command_line_h
#define mpm_solver_run_from_command_line_h

#include <deal.II/base/mpi.h>

#include <mpm/base/input_deck.h>

namespace MPM
{
  /**
   * What `mpm` does with its command line @p cl once the scene's dimension
   * is known: read the parameter files and overrides in two passes (the
   * lists of names that decide which subsections exist, then every entry,
   * strictly), then print the parameters, run the material-point driver
   * or run the simulation on @p comm. Returns the exit code.
   *
   * In the library, not in source/main.cc, so that the executable's own
   * file does not parse the Simulator's headers (about 20 s of a build's
   * critical path: the executable is compiled after the library).
   */
  template <int dim>
  int
  run_from_command_line(const CommandLine &cl, const MPI_Comm comm);
} // namespace MPM

#endif
