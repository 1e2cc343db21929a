#!/usr/bin/env bash
# A/B timing of two builds of mpm on a noisy machine: the saved build in
# DIR (a copy of build/release/mpm and build/release/libmpm-core.so, made
# before a change; mpm's RUNPATH lets LD_LIBRARY_PATH pick DIR's library)
# against the current build/release, run alternately N times on the same
# case, one at a time. Prints every run's wall time of the steps (mpm's
# 'Done' line), the minima and their ratio, and whether the two runs'
# statistics files are identical (a change meant to keep the arithmetic
# must leave them identical to the last digit). On MPM_THREADS threads
# (default 1).
#
# The virtual machines this code was tuned on drifted by up to 25 % within
# minutes (doc/performance.md): single runs cannot show a change of a few
# percent; the minimum over alternating runs can.
#
# Usage:
#   mkdir -p /some/dir && cp build/release/{mpm,libmpm-core.so} /some/dir
#   ... change, rebuild build/release ...
#   scripts/compare_builds.sh /some/dir [END_TIME (s, default 0.1)] [N (default 6)] [PRM (default prm/flume_usgs.prm)]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
base="$(cd "${1:?usage: compare_builds.sh DIR [END_TIME] [N] [PRM]}" && pwd)"
end_time="${2:-0.1}"
n="${3:-6}"
prm="$(realpath "${4:-$root/prm/flume_usgs.prm}")"
current="$root/build/release"
for f in "$base/mpm" "$base/libmpm-core.so" "$current/mpm"; do
  [ -f "$f" ] || { echo "compare_builds.sh: missing $f" >&2; exit 1; }
done
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# run NAME BIN_DIR: one run, prints the wall time of the steps.
run() {
  local name="$1" dir="$2"
  (cd "$(dirname "$prm")" &&
     LD_LIBRARY_PATH="$dir" "$dir/mpm" "$prm" --threads "${MPM_THREADS:-1}" \
       --set "Time stepping/End time=$end_time" \
       --set "Output/Directory=$work/$name" > "$work/$name.log" 2>&1) ||
    { echo "compare_builds.sh: the $name run failed, see its log:" >&2; tail -5 "$work/$name.log" >&2; exit 1; }
  sed -n 's/^Done: .*(steps \([0-9.e+-]*\) s).*/\1/p' "$work/$name.log"
}

base_times=()
current_times=()
for i in $(seq "$n"); do
  base_times+=("$(run base "$base")")
  current_times+=("$(run current "$current")")
done
min() { printf '%s\n' "$@" | sort -g | head -1; }
b=$(min "${base_times[@]}")
c=$(min "${current_times[@]}")
echo "case: $prm to t = $end_time s, $n alternating runs each (wall time of the steps, s)"
echo "  saved ($base): ${base_times[*]}"
echo "  current ($current): ${current_times[*]}"
awk -v b="$b" -v c="$c" 'BEGIN { printf "  minima: %s -> %s s, ratio %.3f\n", b, c, c / b }'
if cmp -s "$work/base/statistics" "$work/current/statistics"; then
  echo "  statistics: identical"
else
  echo "  statistics: differ"
fi
