#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <mpm/base/input_deck.h>
#include <mpm/base/input_error.h>

#include <cstdlib>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

namespace MPM
{
  namespace
  {
    /**
     * The "Additional information" part of a deal.II exception, which is
     * what tells the user which line and entry of the file was wrong; the
     * rest (source file and line inside deal.II, stack trace) is noise for
     * a user of the program.
     */
    std::string
    exception_info(const ExceptionBase &e)
    {
      std::ostringstream s;
      e.print_info(s);
      std::string text = Utilities::trim(s.str());
      return text.empty() ? std::string(e.what()) : text;
    }
  } // namespace


  std::string
  usage()
  {
    return "Usage: mpm [--print-parameters|--material-point-driver] "
           "[input.prm [more.prm ...]] "
           "[--set \"Subsection/Entry=value\"]... [--threads N]\n"
           "  input.prm             parameter file to run; further files "
           "override its entries\n"
           "  --set PATH=VALUE      override one parameter after reading the "
           "file (repeatable)\n"
           "  --material-point-driver\n"
           "                        take one point of a material of "
           "input.prm along the path of\n"
           "                        'Material point driver' (doc/materials.md) "
           "instead of running the scene\n"
           "  --print-parameters    print every parameter with its "
           "documentation and default\n"
           "                        (or the values of input.prm if given) "
           "and exit\n"
           "  --threads N           threads per MPI rank (default: the cores "
           "available to the\n"
           "                        process divided among the ranks on its "
           "node); the results\n"
           "                        are the same, bit for bit, for any N\n"
           "  --help                this text\n";
  }


  namespace
  {
    /**
     * The value of the command line option @p name at argv[@p i], given as
     * "NAME VALUE" (then @p i moves to VALUE) or "NAME=VALUE"; none if
     * @p arg is another option. A missing value is an InputError that
     * says what @p expected.
     */
    std::optional<std::string>
    option_value(const std::string &arg,
                 const std::string &name,
                 int               &i,
                 const int          argc,
                 char             **argv,
                 const std::string &expected)
    {
      if (arg == name)
        {
          check_input(i + 1 < argc, name + " needs an argument: " + expected + ".");
          return std::string(argv[++i]);
        }
      if (arg.rfind(name + "=", 0) == 0)
        return arg.substr(name.size() + 1);
      return std::nullopt;
    }
  } // namespace


  CommandLine
  parse_command_line(int argc, char **argv)
  {
    CommandLine cl;
    for (int i = 1; i < argc; ++i)
      {
        const std::string arg = argv[i];
        if (arg == "--print-parameters")
          cl.print_parameters = true;
        else if (arg == "--material-point-driver")
          cl.material_point_driver = true;
        else if (arg == "--help" || arg == "-h")
          cl.show_help = true;
        else if (const auto assignment =
                   option_value(arg, "--set", i, argc, argv, "\"Subsection/Entry=value\""))
          {
            const auto eq = assignment->find('=');
            check_input(eq != std::string::npos && eq > 0,
                        "--set \"" + *assignment +
                          "\": expected \"Subsection/Entry=value\".");
            cl.overrides.emplace_back(Utilities::trim(assignment->substr(0, eq)),
                                      Utilities::trim(assignment->substr(eq + 1)));
          }
        else if (const auto value = option_value(
                   arg, "--threads", i, argc, argv, "a number of threads (>= 1)"))
          {
            char      *end = nullptr;
            const long n   = std::strtol(value->c_str(), &end, 10);
            check_input(!value->empty() && *end == '\0' && n >= 1 && n <= 4096,
                        "--threads " + *value +
                          ": expected a number of threads from 1 to 4096.");
            cl.n_threads = static_cast<unsigned int>(n);
          }
        else if (!arg.empty() && arg[0] == '-')
          throw InputError("Unknown command line option '" + arg + "'.\n" +
                           usage());
        else
          cl.parameter_files.push_back(arg);
      }
    return cl;
  }


  void
  apply_overrides(
    ParameterHandler                                       &prm,
    const std::vector<std::pair<std::string, std::string>> &overrides,
    const bool                                              ignore_undeclared)
  {
    for (const auto &[path, value] : overrides)
      {
        // An override is parsed as the small parameter file it stands for,
        // so that it meets the same checks (declared entry, pattern) as
        // the file itself.
        std::vector<std::string> parts =
          Utilities::split_string_list(path, '/');
        std::string text;
        for (unsigned int i = 0; i + 1 < parts.size(); ++i)
          text += "subsection " + Utilities::trim(parts[i]) + "\n";
        text += "set " + Utilities::trim(parts.back()) + " = " + value + "\n";
        for (unsigned int i = 0; i + 1 < parts.size(); ++i)
          text += "end\n";
        try
          {
            prm.parse_input_from_string(text, "", ignore_undeclared);
          }
        catch (const ExceptionBase &e)
          {
            throw InputError("--set \"" + path + "=" + value +
                             "\": " + exception_info(e));
          }
      }
  }


  template <int dim>
  Point<dim>
  parse_point(const std::string &text, const std::string &parameter)
  {
    const auto parts = Utilities::split_string_list(text, ',');
    const std::string expected = parameter + " = '" + text + "': expected " +
                                 std::to_string(dim) +
                                 " comma separated numbers.";
    check_input(parts.size() == dim, expected);
    Point<dim> p;
    for (unsigned int d = 0; d < dim; ++d)
      {
        std::size_t end = 0;
        try
          {
            p[d] = std::stod(parts[d], &end);
          }
        catch (const std::exception &)
          {
            end = 0;
          }
        check_input(end > 0 && end == parts[d].size(), expected);
      }
    return p;
  }

  template Point<2>
  parse_point<2>(const std::string &, const std::string &);
  template Point<3>
  parse_point<3>(const std::string &, const std::string &);


  void
  declare_dimension(dealii::ParameterHandler &prm)
  {
    prm.declare_entry("Dimension",
                      "2",
                      dealii::Patterns::Integer(2, 3),
                      "Spatial dimension of the scene.");
  }


  std::vector<std::string>
  split_name_list(const std::string &list, const std::string &parameter_name)
  {
    std::vector<std::string> names;
    std::set<std::string>    seen;
    for (const auto &n : Utilities::split_string_list(list, ','))
      {
        const std::string name = Utilities::trim(n);
        if (name.empty())
          continue;
        check_input(seen.insert(name).second,
                    "Parameter '" + parameter_name + "' lists '" + name +
                      "' twice; names must be unique.");
        names.push_back(name);
      }
    return names;
  }


  void
  parse_parameter_file(ParameterHandler  &prm,
                       const std::string &file_name,
                       const bool         skip_undefined)
  {
    {
      std::ifstream in(file_name);
      check_input(static_cast<bool>(in),
                  "Cannot open the parameter file '" + file_name + "'.");
    }
    try
      {
        prm.parse_input(file_name, "", skip_undefined, false);
      }
    catch (const ExceptionBase &e)
      {
        throw InputError("In parameter file '" + file_name +
                         "': " + exception_info(e));
      }
  }


  std::string
  directory_of(const std::string &file_name)
  {
    const auto slash = file_name.find_last_of('/');
    return slash == std::string::npos ? std::string() :
                                        file_name.substr(0, slash + 1);
  }


  std::string
  resolve_path(const std::string &directory, const std::string &file_name)
  {
    if (file_name.empty() || file_name[0] == '/')
      return file_name;
    return directory + file_name;
  }
} // namespace MPM
