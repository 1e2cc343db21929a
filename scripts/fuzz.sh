#!/usr/bin/env bash
# Fuzz the parameter file reader and the Gmsh mesh reader path (libFuzzer,
# clang, AddressSanitizer) for a bounded time each, starting from the
# shipped .prm files and meshes. A crash leaves its input in
# build/fuzz/artifacts/ and makes this script fail; turn such an input into
# a regression test (tests/bad_input_*.prm or a mesh in tests/).
# Usage: scripts/fuzz.sh [seconds per target, default 300]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_install_packages
seconds="${1:-300}"
dir="$MPM_ROOT/build/fuzz"
if [ ! -f "$dir/CMakeCache.txt" ]; then
  cmake -S "$MPM_ROOT" -B "$dir" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release -DMPM_FUZZ=ON
fi
cmake --build "$dir" -j2 --target prm_fuzzer mesh_fuzzer
mkdir -p "$dir/artifacts" "$dir/corpus-prm" "$dir/corpus-mesh" "$dir/run"
for f in "$MPM_ROOT"/prm/*.prm; do cp "$f" "$dir/corpus-prm/prm-$(basename "$f")"; done
for f in "$MPM_ROOT"/tests/*.prm; do cp "$f" "$dir/corpus-prm/test-$(basename "$f")"; done
cp "$MPM_ROOT"/meshes/*.msh "$dir/corpus-mesh/"
# MPI's own allocations are not ours to judge; timeouts count as failures.
export ASAN_OPTIONS=detect_leaks=0
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
status=0
for target in prm mesh; do
  echo "== ${target}_fuzzer for $seconds s"
  (cd "$dir/run" && "$dir/fuzz/${target}_fuzzer" -max_total_time="$seconds" -timeout=20 \
     -rss_limit_mb=4096 -artifact_prefix="$dir/artifacts/${target}-" \
     "$dir/corpus-$target" 2>&1 | tail -5) || status=1
done
ls "$dir/artifacts"
exit $status
