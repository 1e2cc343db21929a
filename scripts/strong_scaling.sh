#!/usr/bin/env bash
# Strong scaling: one case on 1, 2, ... ranks (Release build), with the wall
# time, the particle-steps per second, the speed-up and whether the reports
# agree with the 1-rank run (numdiff). Each rank runs MPM_THREADS threads
# (default 1: the scaling over ranks alone). Writes doc/strong_scaling.txt.
# Usage: scripts/strong_scaling.sh [prm, default prm/flume_usgs.prm] [max ranks, default 2] [extra mpm arguments ...]
# e.g.   scripts/strong_scaling.sh prm/flume_usgs.prm 2 --set "Time stepping/End time=0.5"
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
prm="${1:-$MPM_ROOT/prm/flume_usgs.prm}"
max_ranks="${2:-2}"
shift $(( $# >= 2 ? 2 : $# ))
out="output-strong-scaling"
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
table="$MPM_ROOT/doc/strong_scaling.txt"
{
  echo "# $(basename "$prm") $* (threads per rank: ${MPM_THREADS:-1})"
  echo "# machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
  echo "# ranks  wall (s)  particle-steps/s  speed-up  report vs 1 rank"
} > "$table"
wall1=""
for (( n = 1; n <= max_ranks; n *= 2 )); do
  mpirun -np "$n" --oversubscribe "$MPM_BUILD_DIR/mpm" "$prm" --threads "${MPM_THREADS:-1}" "$@" \
    --set "Output/Directory=$out/np$n" --set "Output/Write particles=false" > "$out/np$n.log"
  done_line=$(grep '^Done:' "$out/np$n.log")
  wall=$(echo "$done_line" | sed -E 's/.*wall time ([0-9.e+-]+) s.*/\1/')
  rate=$(echo "$done_line" | sed -E 's/.* s, ([0-9.e+-]+) particle-steps.*/\1/')
  [ -z "$wall1" ] && wall1="$wall"
  same="reference"
  if [ "$n" -gt 1 ]; then
    if numdiff -q -a 1e-8 -r 1e-6 "$out/np1/report.txt" "$out/np$n/report.txt" > /dev/null; then
      same="agrees (numdiff -a 1e-8 -r 1e-6)"
    else
      same="DIFFERS"
    fi
  fi
  printf "%7d  %8.1f  %16s  %8.2f  %s\n" "$n" "$wall" "$rate" \
    "$(awk -v a="$wall1" -v b="$wall" 'BEGIN { print a / b }')" "$same" | tee -a "$table"
done
