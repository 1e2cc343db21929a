#ifndef mpm_base_input_error_h
#define mpm_base_input_error_h

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
} // namespace MPM

#endif
