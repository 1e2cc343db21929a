#ifndef mpm_base_input_error_h
#define mpm_base_input_error_h

#include <deal.II/base/utilities.h>

#include <cerrno>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace MPM
{
  /**
   * The error thrown for anything the user can fix in the input: a
   * parameter out of range, a file that does not exist, a region that lies
   * outside the mesh. main() prints the message (without deal.II's stack
   * trace, which would only distract from it) and exits with a non-zero code.
   * Messages name the parameter (as "Subsection/Entry") or the file, and the
   * accepted range.
   */
  class InputError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /**
   * Throw an InputError with @p message unless @p condition holds.
   */
  inline void
  check_input(const bool condition, const std::string &message)
  {
    if (!condition)
      throw InputError(message);
  }

  /**
   * The number written in @p text (surrounding blanks allowed), or an
   * InputError that quotes it after @p where (e.g. "Mesh/Generator
   * arguments = '...': "). For entries whose pattern is Anything and that
   * the code splits itself: deal.II's Utilities::string_to_double() aborts
   * there with a stack trace that names no parameter.
   */
  inline double
  parse_number(const std::string &text, const std::string &where)
  {
    const std::string trimmed = dealii::Utilities::trim(text);
    char             *end     = nullptr;
    errno     = 0;
    const double value =
      trimmed.empty() ? 0. : std::strtod(trimmed.c_str(), &end);
    check_input(!trimmed.empty() && errno == 0 &&
                  end == trimmed.c_str() + trimmed.size(),
                where + "'" + trimmed + "' is not a number.");
    return value;
  }
} // namespace MPM

#endif
