#!/usr/bin/env bash
# Shared set-up for run.sh and test.sh: install what is missing (as root),
# then configure and build one build type in build/<type>.
# Usage: source scripts/setup.sh; mpm_setup Release|Debug
set -euo pipefail

MPM_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# libgdal-dev is optional for the code (GeoTIFF input and output; ESRI ASCII
# grids work without it), installed here so that the GeoTIFF tests run;
# gdal-bin converts GeoTIFF rasters for scripts/plot_hazard_rasters.py.
MPM_PACKAGES=(libdeal.ii-dev cmake g++ make numdiff ccache gmsh openmpi-bin python3-matplotlib libgdal-dev gdal-bin)

mpm_install_packages() {
  local missing=()
  for p in "${MPM_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  if [ "$(id -u)" -eq 0 ]; then
    echo "Installing missing Debian packages: ${missing[*]}"
    apt-get update -q
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
  else
    echo "Missing Debian packages. Install them with:" >&2
    echo "  sudo apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
}

# mpm_setup BUILD_TYPE [TARGET...]: configure (once) and build the targets
# (default: mpm, the solver, which every script needs; 'all' adds the unit
# tests) in build/<build_type lowercase>.
# With MPM_PREBUILT_DIR set in the environment, that build is used as it is
# (nothing is built: a long sweep keeps its executable while the sources
# change).
mpm_setup() {
  local type="$1"
  shift
  local targets=("$@")
  [ ${#targets[@]} -gt 0 ] || targets=(mpm)
  if [ -n "${MPM_PREBUILT_DIR:-}" ]; then
    [ -x "$MPM_PREBUILT_DIR/mpm" ] || { echo "MPM_PREBUILT_DIR=$MPM_PREBUILT_DIR holds no mpm executable" >&2; exit 1; }
    MPM_BUILD_DIR="$MPM_PREBUILT_DIR"
    return 0
  fi
  local dir="$MPM_ROOT/build/${type,,}"
  mpm_install_packages
  if [ ! -f "$dir/CMakeCache.txt" ]; then
    cmake -S "$MPM_ROOT" -B "$dir" -DCMAKE_BUILD_TYPE="$type"
  fi
  cmake --build "$dir" -j2 --target "${targets[@]}"
  MPM_BUILD_DIR="$dir"
}

# mpm_done_figures LOG: "steps points seconds" from the 'Done' line of an
# mpm log (seconds: the wall time of the steps alone, what the benchmark
# scripts compare); nothing if the run did not finish.
mpm_done_figures() {
  sed -n 's/^Done: \([0-9]*\) steps, \([0-9]*\) points, .*(steps \([0-9.e+-]*\) s).*/\1 \2 \3/p' "$1"
}

# mpm_benchmark_header: the line a benchmark's output starts with (date,
# commit, cores, processor), so that its figures can be dated in doc/.
mpm_benchmark_header() {
  echo "# $(date -u +%F), commit $(git -C "$MPM_ROOT" rev-parse --short HEAD), $(nproc) cores: $(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //')"
}
