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
#include <mpm/materials/material_point_driver.h>
#include <mpm/solver/simulator.h>

#include <fstream>
#include <iostream>

namespace
{
  using namespace dealii;
  using namespace MPM;

  template <int dim>
  int
  run(const CommandLine &cl, const MPI_Comm comm)
  {
    // Pass 1: the lists of names that decide which subsections exist.
    ParameterHandler names_prm;
    Simulator<dim>::declare_name_lists(names_prm);
    for (const auto &file : cl.parameter_files)
      parse_parameter_file(names_prm, file, true);
    apply_overrides(names_prm, cl.overrides, true);
    const auto names = Simulator<dim>::read_name_lists(names_prm);

    // Pass 2: everything, strictly.
    ParameterHandler prm;
    Simulator<dim>::declare_parameters(prm, names);
    MaterialPointDriver::declare_parameters(prm);
    for (const auto &file : cl.parameter_files)
      parse_parameter_file(prm, file, false);
    apply_overrides(prm, cl.overrides, false);

    if (cl.print_parameters)
      {
        if (Utilities::MPI::this_mpi_process(comm) == 0)
          prm.print_parameters(std::cout, ParameterHandler::PRM);
        return 0;
      }

    if (cl.material_point_driver)
      {
        // One material point, no mesh: on the first rank only.
        MaterialPointDriver driver;
        driver.parse_parameters(prm);
        if (Utilities::MPI::this_mpi_process(comm) == 0)
          driver.run();
        return 0;
      }

    Simulator<dim> simulator(comm);
    simulator.parse_parameters(prm,
                               cl.parameter_files.empty() ?
                                 std::string(".") :
                                 directory_of(cl.parameter_files.front()));
    simulator.run();
    return 0;
  }
} // namespace


int
main(int argc, char **argv)
{
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
                   run<2>(cl, MPI_COMM_WORLD) :
                   run<3>(cl, MPI_COMM_WORLD);
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
