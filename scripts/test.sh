#!/usr/bin/env bash
# Set up everything (packages, a Debug build of the solver and the unit
# tests, a Release build of the solver) and run the
# regression test suite with ctest: every test in the Debug build, which
# keeps deal.II's assertions, except those labelled 'slow', which run in the
# Release build (see tests/CMakeLists.txt).
# Usage: scripts/test.sh [extra ctest arguments, e.g. -R bar]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Debug all
debug_dir="$MPM_BUILD_DIR"
mpm_setup Release
release_dir="$MPM_BUILD_DIR"
status=0
(cd "$debug_dir" && ctest --output-on-failure -j2 -LE slow "$@") || status=1
(cd "$release_dir" && ctest --output-on-failure -j2 -L slow "$@") || status=1
exit $status
