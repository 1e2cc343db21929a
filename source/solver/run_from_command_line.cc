// The `mpm` executable's work once the dimension is known
// (include/mpm/solver/run_from_command_line.h).

#include <deal.II/base/parameter_handler.h>

#include <mpm/materials/material_point_driver.h>
#include <mpm/solver/run_from_command_line.h>
#include <mpm/solver/simulator.h>

namespace MPM
{
  template <int dim>
  int
  run_from_command_line(const CommandLine &cl, const MPI_Comm comm)
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


  template int
  run_from_command_line<2>(const CommandLine &, const MPI_Comm);
  template int
  run_from_command_line<3>(const CommandLine &, const MPI_Comm);
} // namespace MPM
