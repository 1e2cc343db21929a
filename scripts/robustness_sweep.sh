#!/usr/bin/env bash
# The code's defaults on scenes no test names, and the shipped files as
# shipped: each run on one thread (Release), and for each whether it reached
# its end time, how many points it started and ended with, the warnings it
# printed, its steps and wall time (doc/robustness.md, "Variants without a
# test"). A lost point or a stop by the 'Stability' checks ends a run with a
# non-zero exit: the row says 'stopped' and the log's last line says why.
#
# Usage: scripts/robustness_sweep.sh [variants|shipped|all (default)] [CSV]
# Writes the table to CSV (default doc/robustness_sweep.csv) and each run's
# log and output to output-robustness-sweep/. MPM_SWEEP_ONLY=REGEX runs only
# the cases whose name matches (e.g. 'dam-break' or 'shipped-flume'); its
# CSV defaults to output-robustness-sweep/robustness_sweep.csv.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
which="${1:-all}"
out="output-robustness-sweep"
mkdir -p "$out"
# A subset (MPM_SWEEP_ONLY) does not overwrite the doc's table.
if [ -n "${MPM_SWEEP_ONLY:-}" ]; then
  csv="${2:-$out/robustness_sweep.csv}"
else
  csv="${2:-$MPM_ROOT/doc/robustness_sweep.csv}"
fi
echo "name,file,settings,end_time_s,reached_s,result,points_start,points_end,warnings,steps,wall_s" > "$csv"

# run NAME FILE END_TIME [SETTING ...]: one run; SETTING is 'path=value'.
run() {
  local name="$1" file="$2" end="$3"
  shift 3
  [[ -z "${MPM_SWEEP_ONLY:-}" || "$name" =~ $MPM_SWEEP_ONLY ]] || return 0
  local args=() settings=""
  for s in "$@"; do
    args+=(--set "$s")
    settings="${settings:+$settings; }$s"
  done
  [ -n "$end" ] && args+=(--set "Time stepping/End time=$end")
  local log="$out/$name.log" rc=0
  "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/$file" --threads 1 "${args[@]}" \
    --set "Output/Directory=$out/$name" --set "Output/Write particles=false" > "$log" 2>&1 || rc=$?
  local start_points end_points steps wall reached result warnings
  start_points=$(grep -m1 -E "^dealii-mpm: " "$log" | sed -E 's/.* ([0-9]+) material points.*/\1/' || true)
  warnings=$(grep -c "^Warning" "$log" || true)
  # The last statistics row: the end time, the time at rest where the file
  # stops there, or the last output before a stop.
  reached=$(awk '!/^#/ && NF {t = $1} END {print t}' "$out/$name/statistics" 2>/dev/null || true)
  if [ "$rc" -eq 0 ]; then
    local done_line
    done_line=$(grep '^Done:' "$log")
    steps=$(echo "$done_line" | awk '{print $2}')
    end_points=$(echo "$done_line" | awk '{print $4}')
    wall=$(echo "$done_line" | sed -E 's/.*wall time ([0-9.e+-]+) s.*/\1/')
    result="end reached"
  else
    steps="" end_points="" wall=""
    result="stopped (exit $rc): $(grep -v '^\s*$' "$log" | tail -1 | tr ',' ';' | cut -c1-160)"
  fi
  printf '%s,%s,"%s",%s,%s,"%s",%s,%s,%s,%s,%s\n' "$name" "$file" "$settings" "${end:-as shipped}" "$reached" \
    "$result" "$start_points" "$end_points" "$warnings" "$steps" "$wall" | tee -a "$csv"
}

if [ "$which" = variants ] || [ "$which" = all ]; then
  # The column collapse (a = 2, 5 mm cells, 3 x 3 points per cell, the
  # code's default path) changed one input at a time.
  cc=column_collapse.prm
  run cc-a0.5 $cc 0.6 "Material points/column/Box=0, 0 : 0.2, 0.1"
  run cc-a3 $cc 0.8 "Material points/column/Box=0, 0 : 0.05, 0.15"
  run cc-a8-2p5mm $cc 0.6 "Mesh/Global refinements=1" "Material points/column/Box=0, 0 : 0.025, 0.2"
  run cc-cfl0.9 $cc 0.8 "Time stepping/CFL number=0.9"
  run cc-usf $cc 0.8 "Time stepping/Update scheme=USF"
  run cc-usl $cc 0.8 "Time stepping/Update scheme=USL"
  run cc-drucker-prager $cc 0.8 "Materials/sand/Model=drucker prager"
  run cc-mu-i $cc 0.8 "Materials/sand/Model=mu(I)"
  run cc-cam-clay $cc 0.8 "Materials/sand/Model=modified cam clay" "Materials/sand/modified cam clay/Initial preconsolidation pressure=5e3"
  run cc-linear-elastic $cc 0.8 "Materials/sand/Model=linear elastic"
  run cc-1x1-points $cc 0.8 "Material points/column/Points per cell=1"
  run cc-4x4-points $cc 0.5 "Material points/column/Points per cell=4"
  run cc-no-averaging $cc 0.8 "Time stepping/Volumetric strain averaging=none"
  run cc-linear-weights $cc 0.8 "Transfer/Particle-grid weights=linear"
  run slope-runout-0p25m slope_runout.prm 3 "Mesh/Global refinements=1"
  # The dam break to its own end time: its front leaves the open end of
  # the tank soon after (x = 1.1 m at 0.49 s on a / 20 cells).
  run dam-break-r1 dam_break.prm "" "Mesh/Global refinements=1"
  run dam-break-r2 dam_break.prm "" "Mesh/Global refinements=2"
  run submerged-collapse-2p5mm submerged_collapse.prm 1 "Mesh/Global refinements=1"
  run landslide-3d-r1 landslide_valley_3d.prm 3 "Mesh/Global refinements=1" "Output/Write point file=false"
fi

if [ "$which" = shipped ] || [ "$which" = all ]; then
  # Every shipped file as shipped (the throughput blocks left out: they are
  # benchmarks), to its own end time; the saturated flume to 0.3 s (its
  # whole run is half an hour).
  for f in "$MPM_ROOT"/prm/*.prm; do
    b=$(basename "$f")
    case "$b" in
      throughput*.prm) continue ;;
      flume_usgs_saturated.prm) run "shipped-${b%.prm}" "$b" 0.3 ;;
      *) run "shipped-${b%.prm}" "$b" "" ;;
    esac
  done
fi
