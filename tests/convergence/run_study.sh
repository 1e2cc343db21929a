#!/usr/bin/env bash
# Test driver of scripts/convergence.py (tests/CMakeLists.txt): runs a
# three-level study in the current folder with the given mpm executable and
# arguments and prints its CSV without the wall times (they vary), the
# commas as blanks (numdiff compares numbers between blanks). The
# first line sets the comparison's tolerances (run_test.cmake): round-off
# in the runs moves an observed order by about 1e-4.
# Usage: run_study.sh MPM CASE.prm [convergence.py arguments ...]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
mpm="$1"
shift
/usr/bin/python3 "$here/../../scripts/convergence.py" "$@" --mpm "$mpm" --out study --no-plot > study.log
echo "# numdiff: -a 1e-6 -r 1e-3"
grep -v '^cost: wall time' study/convergence.csv | tr ',' ' '
