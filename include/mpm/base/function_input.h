#ifndef mpm_base_function_input_h
#define mpm_base_function_input_h

#include <deal.II/base/exceptions.h>

#include <mpm/base/input_error.h>

#include <exception>
#include <sstream>
#include <string>

namespace MPM
{
  /**
   * Run @p parse_and_evaluate, which parses a function of the parameter
   * file and evaluates it once: whatever the parser throws becomes an
   * InputError that begins with @p what (the parameter and its text),
   * not a parser error deep in the run (some malformed constants throw
   * an exception that is not a std::exception, found by the fuzzer).
   */
  template <typename Callable>
  void
  parse_function_or_throw(const std::string &what,
                          const Callable    &parse_and_evaluate)
  {
    try
      {
        parse_and_evaluate();
      }
    catch (const dealii::ExceptionBase &e)
      {
        // deal.II's own text, without its source location and stack
        // trace.
        std::ostringstream info;
        e.print_info(info);
        throw InputError(what + " cannot be evaluated:\n" + info.str());
      }
    catch (const std::exception &e)
      {
        throw InputError(what + " cannot be evaluated: " + e.what());
      }
    catch (...)
      {
        throw InputError(what + " cannot be parsed.");
      }
  }
} // namespace MPM

#endif
