/**
 * The `mpm` executable: reads one or more parameter files (later ones
 * override earlier ones; two passes, so that the
 * user-named subsections - materials, regions, boundaries - can be
 * declared), applies command line overrides and runs the simulation, or
 * with --material-point-driver the material-point driver on the same
 * parameters.
 */
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <mpm/base/input_deck.h>
#include <mpm/base/input_error.h>
#include <mpm/solver/run_from_command_line.h>

#include <iostream>


int
main(int argc, char **argv)
{
  using namespace dealii;
  using namespace MPM;
  try
    {
      // Threads per rank: the cores available to the process divided
      // among the ranks on its node, unless --threads says otherwise.
      Utilities::MPI::MPI_InitFinalize mpi(argc,
                                           argv,
                                           numbers::invalid_unsigned_int);
      try
        {
          const CommandLine cl = parse_command_line(argc, argv);
          if (cl.n_threads > 0)
            MultithreadInfo::set_thread_limit(cl.n_threads);
          if (cl.show_help ||
              (cl.parameter_files.empty() && !cl.print_parameters))
            {
              std::cout << usage();
              return cl.show_help ? 0 : 1;
            }

          ParameterHandler dim_prm;
          declare_dimension(dim_prm);
          for (const auto &file : cl.parameter_files)
            parse_parameter_file(dim_prm, file, true);
          apply_overrides(dim_prm, cl.overrides, true);
          return dim_prm.get_integer("Dimension") == 2 ?
                   run_from_command_line<2>(cl, MPI_COMM_WORLD) :
                   run_from_command_line<3>(cl, MPI_COMM_WORLD);
        }
      catch (const InputError &e)
        {
          std::cerr << "\nInput error: " << e.what() << "\n\n";
          return 2;
        }
    }
  catch (const std::exception &e)
    {
      std::cerr << "\nError: " << e.what() << "\n\n";
      return 1;
    }
  catch (...)
    {
      std::cerr << "\nUnknown error.\n\n";
      return 1;
    }
}
