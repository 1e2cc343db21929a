// The unit tests' executable: `unit_tests NAME [arguments]` runs the test
// registered as NAME (tests/unit/NAME.cc) and exits with its code;
// `unit_tests` alone lists the tests.

#include "unit_test_tools.h"

int
main(int argc, char **argv)
{
  const auto &tests = UnitTest::registry();
  const auto  test  = (argc > 1 ? tests.find(argv[1]) : tests.end());
  if (test == tests.end())
    {
      if (argc > 1)
        std::cerr << "unit_tests: no test named '" << argv[1] << "'\n";
      std::cerr << "Usage: unit_tests NAME [arguments]; the tests:\n";
      for (const auto &[name, function] : tests)
        std::cerr << "  " << name << '\n';
      return 1;
    }
  // The test sees its own name as the program's.
  return test->second(argc - 1, argv + 1);
}
