#ifndef mpm_tests_unit_test_tools_h
#define mpm_tests_unit_test_tools_h

// What every unit test in this folder shares: checks that print what they
// check and count failures, round-off printed as 0, and the summary line
// whose exit code ctest sees.

#include <cmath>
#include <iostream>
#include <string>

namespace UnitTest
{
  inline unsigned int n_failed = 0;

  /// Print "ok"/"FAILED" and @p what; count a failure.
  inline void
  check(const bool ok, const std::string &what)
  {
    std::cout << "    " << (ok ? "ok" : "FAILED") << ": " << what << '\n';
    if (!ok)
      ++n_failed;
  }

  /// Values below the tolerance of a check are printed as 0: rounding
  /// residues differ from machine to machine.
  inline double
  flush_to_zero(const double x, const double below = 1e-10)
  {
    return std::abs(x) < below ? 0. : x;
  }

  /// The last line of a test's output, and its exit code.
  inline int
  summary()
  {
    std::cout << (n_failed == 0 ? "all checks passed" : "SOME CHECKS FAILED")
              << '\n';
    return n_failed == 0 ? 0 : 1;
  }
} // namespace UnitTest

#endif
