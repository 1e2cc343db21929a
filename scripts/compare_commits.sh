#!/usr/bin/env bash
# The headline cases of doc/performance.md run by an older commit's build
# and by build/release, alternately, on one thread: what a series of
# changes gained, measured on the same day (this machine's speed drifts by
# 10-35 % within the hour and by 2x between days, so figures of different
# days cannot be compared; doc/performance.md).
#
# OLD_ROOT is a source tree of the older commit with its Release build in
# OLD_ROOT/build, e.g.
#   git worktree add /tmp/old eecfac5
#   cmake -S /tmp/old -B /tmp/old/build -DCMAKE_BUILD_TYPE=Release
#   cmake --build /tmp/old/build -j2 --target mpm
# Each build runs its own tree's parameter file (the shipped file as that
# commit shipped it); a file the old tree does not have is taken from this
# tree. --threads 1 is passed to a build that knows the option.
#
# Prints, per case, the minima over N runs of each build of the wall time
# of the steps (mpm's 'Done' line), the particle-steps per second of the
# minimum, and the ratio old / new (above 1: the current build is faster).
#
# Usage: scripts/compare_commits.sh OLD_ROOT [N (default 3)] [CASE ...]
# Cases (default all but flume): block_le block_mc block_cpdi block_le_1e6
# block_mc_1e6 block3d_le block3d_mc landslide landslide_apic_cpdi flume_0.3
# flume_0.3_apic_cpdi flume (the blend's cases name it: an older tree's
# files may ship another transfer).
set -euo pipefail
# The shared helpers only (mpm_done_figures); both builds exist already.
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
old_root="$(cd "${1:?usage: compare_commits.sh OLD_ROOT [N] [CASE ...]}" && pwd)"
n="${2:-3}"
shift $(( $# >= 2 ? 2 : 1 ))
cases=("$@")
[ ${#cases[@]} -gt 0 ] || cases=(block_le block_mc block_cpdi block_le_1e6 block_mc_1e6
  block3d_le block3d_mc landslide flume_0.3 flume_0.3_apic_cpdi)
for f in "$old_root/build/mpm" "$root/build/release/mpm"; do
  [ -x "$f" ] || { echo "compare_commits.sh: missing $f" >&2; exit 1; }
done
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# The cases: the 2D block of scripts/throughput_benchmark.sh (2 x 2 points
# per cell, the block's cells only) with its numbers of steps (241 at 1e5
# points, 24 at 1e6), the 3D block of scripts/throughput_3d.sh (123
# steps), the landslide refined once (0.3 s), the shipped flume.
block2d() { # CELLS END MODEL SCHEME FLIP WEIGHTS
  echo "throughput.prm|Mesh/Generator arguments={$1, $1} : 0, 0 : 1, 1 : true|Material points/block/Box=0, 0 : 1, 1|Materials/block/Model=$3|Time stepping/Update scheme=$4|Transfer/FLIP fraction=$5|Transfer/Particle-grid weights=$6|Time stepping/End time=$2"
}
block3d() { # MODEL SCHEME FLIP
  echo "throughput_3d.prm|Mesh/Generator arguments={23, 23, 23} : 0, 0, 0 : 1, 1, 1 : true|Material points/block/Box=0, 0, 0 : 1, 1, 1|Materials/block/Model=$1|Time stepping/Update scheme=$2|Transfer/FLIP fraction=$3|Time stepping/End time=0.0309"
}
# The transfers, written out: the shipped granular files changed from the
# blend to APIC + CPDI (commit 37fff68), so each case names its own.
blend="Transfer/Scheme=flip/pic blend|Transfer/FLIP fraction=0.98|Transfer/Particle-grid weights=linear"
apic_cpdi="Transfer/Scheme=apic|Transfer/Particle-grid weights=cpdi"
spec() {
  case "$1" in
    block_le) block2d 158 0.0088 "linear elastic" USF 1 linear ;;
    block_mc) block2d 158 0.0088 "mohr coulomb" MUSL 0 linear ;;
    block_cpdi) block2d 158 0.0088 "linear elastic" USF 1 cpdi ;;
    block_le_1e6) block2d 500 0.000277 "linear elastic" USF 1 linear ;;
    block_mc_1e6) block2d 500 0.000277 "mohr coulomb" MUSL 0 linear ;;
    block3d_le) block3d "linear elastic" USF 1 ;;
    block3d_mc) block3d "mohr coulomb" MUSL 0 ;;
    landslide) echo "landslide_valley_3d.prm|Mesh/Global refinements=1|Material points/slide/Points per cell=3|Time stepping/End time=0.3|Output/Write point file=false|$blend|Transfer/FLIP fraction time step=0.023" ;;
    landslide_apic_cpdi) echo "landslide_valley_3d.prm|Mesh/Global refinements=1|Material points/slide/Points per cell=3|Time stepping/End time=0.3|Output/Write point file=false|$apic_cpdi" ;;
    flume_0.3) echo "flume_usgs.prm|Time stepping/End time=0.3|$blend|Transfer/FLIP fraction time step=3.3e-5" ;;
    flume_0.3_apic_cpdi) echo "flume_usgs.prm|Time stepping/End time=0.3|$apic_cpdi" ;;
    flume) echo "flume_usgs.prm|$blend|Transfer/FLIP fraction time step=3.3e-5" ;;
    *) echo "compare_commits.sh: unknown case '$1'" >&2; exit 1 ;;
  esac
}

# run TREE BUILD_DIR CASE NAME: one run; prints "steps points seconds".
run() {
  local tree="$1" build="$2" name="$4" prm args=() threads=()
  IFS='|' read -r -a fields <<< "$(spec "$3")"
  prm="$tree/prm/${fields[0]}"
  [ -f "$prm" ] || prm="$root/prm/${fields[0]}"
  for f in "${fields[@]:1}"; do args+=(--set "$f"); done
  "$build/mpm" --help 2>&1 | grep -q -- "--threads" && threads=(--threads 1)
  (cd "$(dirname "$prm")" &&
     LD_LIBRARY_PATH="$build" "$build/mpm" "$prm" "${threads[@]}" "${args[@]}" \
       --set "Output/Write particles=false" --set "Output/Write mesh=false" \
       --set "Output/Directory=$work/$name" > "$work/$name.log" 2>&1) ||
    { echo "compare_commits.sh: the run $name failed, see its log:" >&2; tail -5 "$work/$name.log" >&2; exit 1; }
  mpm_done_figures "$work/$name.log"
}

printf '%-22s %8s %10s %10s %12s %12s %7s\n' case points "old (s)" "new (s)" "old (p-s/s)" "new (p-s/s)" "old/new"
for c in "${cases[@]}"; do
  old_min="" new_min="" steps="" points=""
  for i in $(seq "$n"); do
    read -r steps points t <<< "$(run "$old_root" "$old_root/build" "$c" "$c-old-$i")"
    old_min=$(printf '%s\n' $old_min "$t" | sort -g | head -1)
    read -r steps points t <<< "$(run "$root" "$root/build/release" "$c" "$c-new-$i")"
    new_min=$(printf '%s\n' $new_min "$t" | sort -g | head -1)
  done
  awk -v c="$c" -v p="$points" -v s="$steps" -v o="$old_min" -v w="$new_min" 'BEGIN {
    printf "%-22s %8d %10.3g %10.3g %12.3g %12.3g %7.2f\n", c, p, o, w, p * s / o, p * s / w, o / w }'
done
