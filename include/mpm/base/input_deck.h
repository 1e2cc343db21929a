#ifndef mpm_base_input_deck_h
#define mpm_base_input_deck_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <string>
#include <utility>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * What the user asked for on the command line of the `mpm` executable:
   *
   *   mpm [--print-parameters] [input.prm] [--set "Subsection/Entry=value"]...
   *
   * The `--set` overrides are applied after the file has been read, in the
   * order given, so that parameter sweeps need no copies of the file.
   */
  struct CommandLine
  {
    /// Parameter files in the order given: later files override earlier
    /// ones, as --set does (a test or a sweep states only what differs
    /// from a shipped case). Relative file names inside them (meshes,
    /// point files) are resolved against the directory of the first.
    std::vector<std::string>                         parameter_files;
    std::vector<std::pair<std::string, std::string>> overrides;
    bool                                             print_parameters = false;
    /// --material-point-driver: run MaterialPointDriver instead of a scene.
    bool                                             material_point_driver = false;
    bool                                             show_help        = false;
    /// --threads N: threads per MPI rank; 0 if not given (then deal.II's
    /// default, the cores available to the process divided among the
    /// ranks on its node).
    unsigned int                                     n_threads        = 0;
  };

  /**
   * Parse argc/argv; throws InputError on malformed arguments.
   */
  CommandLine
  parse_command_line(int argc, char **argv);

  /**
   * Usage text of the `mpm` executable.
   */
  std::string
  usage();

  /**
   * Apply "path/to/Entry=value" overrides to @p prm. With
   * @p ignore_undeclared, overrides of entries @p prm does not know are
   * skipped (used in the first of the two parsing passes, see
   * Simulator::read_parameters); otherwise they are an InputError.
   */
  void
  apply_overrides(
    ParameterHandler                                       &prm,
    const std::vector<std::pair<std::string, std::string>> &overrides,
    const bool                                              ignore_undeclared);

  /**
   * Declare 'Dimension' (2 or 3): read first, on its own, to choose the
   * Simulator's dimension, then again with every other entry.
   */
  void
  declare_dimension(dealii::ParameterHandler &prm);

  /**
   * Split a comma separated list of names ("sand, block") into its trimmed,
   * non-empty entries. Names must be unique; duplicates are an InputError
   * naming @p parameter_name.
   */
  std::vector<std::string>
  split_name_list(const std::string &list, const std::string &parameter_name);

  /**
   * The @p dim comma separated numbers of @p text (a point, a normal, a
   * velocity given in a parameter file). Anything else is an InputError
   * naming @p parameter and what was expected.
   */
  template <int dim>
  dealii::Point<dim>
  parse_point(const std::string &text, const std::string &parameter);

  /**
   * Read @p file_name into @p prm. Problems (file missing, unknown
   * subsection or entry, a value that does not match its pattern) become an
   * InputError that names the file, the line and the entry.
   */
  void
  parse_parameter_file(ParameterHandler  &prm,
                       const std::string &file_name,
                       const bool         skip_undefined);

  /**
   * The directory of @p file_name (with a trailing '/'), or "" if it has
   * none. Relative file names in a .prm file (meshes, point files) are read
   * relative to the .prm file's own directory, so that a case runs from
   * anywhere.
   */
  std::string
  directory_of(const std::string &file_name);

  /**
   * @p file_name if it is absolute, otherwise @p directory + @p file_name.
   */
  std::string
  resolve_path(const std::string &directory, const std::string &file_name);
} // namespace MPM

#endif
