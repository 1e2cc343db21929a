#ifndef mpm_tests_unit_test_tools_h
#define mpm_tests_unit_test_tools_h

// What every unit test in this folder shares: checks that print what they
// check and count failures, round-off printed as 0, the summary line whose
// exit code ctest sees, and the registry through which the one executable
// `unit_tests NAME` runs the test NAME.
//
// The tests are one executable (built as a unity build) rather than one per
// file: each executable would parse deal.II's headers on its own, and the
// seventeen of them took about two minutes of a fresh Debug build. Each test
// runs in its own process all the same (ctest starts `unit_tests NAME`), so a
// test that initialises MPI still does it once per process.

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
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

  /// A test's body: what `main(argc, argv)` would be in an executable of
  /// its own; its return value is the process's exit code.
  using TestFunction = int (*)(int argc, char **argv);

  /// Every test of the executable, by name (the file's name without .cc).
  inline std::map<std::string, TestFunction> &
  registry()
  {
    static std::map<std::string, TestFunction> tests;
    return tests;
  }

  /// Registers a test at static initialisation (MPM_UNIT_TEST_REGISTER).
  struct Registration
  {
    Registration(const std::string &name, const TestFunction function)
    {
      if (!registry().emplace(name, function).second)
        {
          std::cerr << "unit test '" << name << "' is registered twice\n";
          std::abort();
        }
    }
  };
} // namespace UnitTest

/// Registers `unit_NAME::run` as the test NAME; after the test's namespace,
/// at the end of tests/unit/NAME.cc.
#define MPM_UNIT_TEST_REGISTER(NAME)                        \
  namespace                                                 \
  {                                                         \
    const UnitTest::Registration                            \
      unit_##NAME##_registration(#NAME, &unit_##NAME::run); \
  }

#endif
