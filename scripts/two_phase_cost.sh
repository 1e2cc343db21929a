#!/usr/bin/env bash
# What the pore water costs (doc/pore_water.md, "Cost"): three measurements,
# one thread, Release build.
#
#  cost       The same scene with and without its water, run alternately N
#             times: the minimum wall time of the steps (mpm's 'Done'
#             line), the particle-steps per second, the cost per
#             particle-step with water over the dry one (the issue's bound:
#             at most 2) and the steps each needs (the water's fast P wave
#             against the skeleton's, at the same CFL number).
#             consolidation: prm/terzaghi_consolidation.prm widened to a
#               square of 40 x 40 cells (6,400 points) to t = 0.1 s;
#             flume: prm/flume_usgs_saturated.prm (5,078 points, affine
#               water, Mohr-Coulomb skeleton) to t = 0.1 s.
#             Dry: the same file with 'Porosity = 0' (the skeleton alone,
#             its dry density) and no initial pore pressure.
#  rheology   What the dense suspension's rheology costs: the loose
#             submerged collapse (prm/submerged_collapse.prm, 1,044
#             points) to t = 0.2 s with its 'Fluid viscosity' against
#             the same with 0 (the critical-state skeleton alone), run
#             alternately N times; the same columns as 'cost'.
#  stability  The largest stable step against the bound the code takes
#             (CFL 1 on the two phases' fast wave): the consolidation file,
#             with its permeability and with a thousand times it, at fixed
#             steps of 0.5 ... 2 times the step of CFL 1, to T = 0.3; the
#             saturated flume at CFL 0.5 ... 1 to 0.1 s. Prints whether the
#             run finished or where and why it stopped, and the
#             consolidation's error at T = 0.05.
#  error      Error against wall time for the consolidation: the shipped
#             one-cell-wide column on 10 ... 160 cells over H to T = 1.01,
#             for each 'Pressure rate averaging' (node, the file's; patch,
#             the code's default; cell): largest error at T = 0.05 and 0.2,
#             T at U = 0.5 and 0.9 against the series, wall time; then
#             'node' with a skeleton ten times stiffer and the same c_v
#             (M = 1e9 Pa, k = 5e-12 m^2), whose inertia weighs less.
#
# Usage: scripts/two_phase_cost.sh [N (default 3)] [PART ...]
#        (parts: cost rheology stability error; default all four)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
n="${1:-3}"
shift || true
parts=("$@")
[ ${#parts[@]} -gt 0 ] || parts=(cost rheology stability error)
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# run NAME PRM SETTING...: runs mpm on one thread into $work/NAME; the log
# is $work/NAME.log. Returns mpm's exit code.
run() {
  local name="$1" prm="$2" f
  shift 2
  local args=()
  for f in "$@"; do args+=(--set "$f"); done
  "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/$prm" --threads 1 "${args[@]}" \
    --set "Output/Write particles=false" --set "Output/Write mesh=false" \
    --set "Output/Directory=$work/$name" > "$work/$name.log" 2>&1
}
# last_step NAME: the step a run ended in (finished or stopped).
last_step() {
  awk '!/^#/ { s = $2 } END { print s }' "$work/$1/statistics"
}
# outcome NAME: "finished" or why the run stopped.
outcome() {
  if grep -q '^Done:' "$work/$1.log"; then
    echo finished
  else
    echo "stopped $(grep -m1 -o 'At step [0-9]*' "$work/$1.log" | sed 's/At step/at step/'): $(grep -m1 -o 'energy[a-z ]*created\|[Nn]on-finite[a-z ]*\|left the mesh' "$work/$1.log" | head -1 || echo "see the log")"
  fi
}
# compare CASE LABEL_A LABEL_B: runs the function CASE-A / CASE-B
# alternately N times and prints a row of the cost table (min wall times).
compare() {
  local c="$1" a_min="" b_min="" i t a_steps b_steps points
  for i in $(seq "$n"); do
    "$c-$2" "$c-$2-$i"
    read -r a_steps points t <<< "$(mpm_done_figures "$work/$c-$2-$i.log")"
    a_min=$(printf '%s\n' $a_min "$t" | sort -g | head -1)
    "$c-$3" "$c-$3-$i"
    read -r b_steps points t <<< "$(mpm_done_figures "$work/$c-$3-$i.log")"
    b_min=$(printf '%s\n' $b_min "$t" | sort -g | head -1)
  done
  awk -v c="$c" -v p="$points" -v as="$a_steps" -v bs="$b_steps" -v a="$a_min" -v b="$b_min" 'BEGIN {
    printf "%-14s %7d %9d %9d %10.3g %10.3g %12.3g %12.3g %10.2f %11.2f\n",
           c, p, as, bs, a, b, p * as / a, p * bs / b, (b / bs) / (a / as), b / a }'
}
# The runs compare() alternates: NAME is the output directory.
consolidation-dry() { run "$1" terzaghi_consolidation.prm "${consolidation_wide[@]}" "Time stepping/End time=0.1" "${dry_consolidation[@]}"; }
consolidation-wet() { run "$1" terzaghi_consolidation.prm "${consolidation_wide[@]}" "Time stepping/End time=0.1" "Postprocess/List of postprocessors="; }
flume-dry() { run "$1" flume_usgs_saturated.prm "Time stepping/End time=0.1" "${dry_flume[@]}"; }
flume-wet() { run "$1" flume_usgs_saturated.prm "Time stepping/End time=0.1" "Postprocess/List of postprocessors=flume"; }
suspension-off() { run "$1" submerged_collapse.prm "Time stepping/End time=0.2" "Materials/beads/critical state drucker prager/Fluid viscosity=0"; }
suspension-on() { run "$1" submerged_collapse.prm "Time stepping/End time=0.2"; }

# report NAME KEY: the value after "KEY: " in the run's report.
report() {
  sed -n "s/^$2: \([-0-9.e+]*\).*/\1/p" "$work/$1/report.txt" 2>/dev/null | head -1
}
# error_row LABEL CELLS SETTING...: the consolidation's one-cell-wide
# column on CELLS cells over H to T = 1.01 with the settings; prints a row
# of the 'error' table.
error_row() {
  local label="$1" cells="$2" name width steps points t
  shift 2
  name="error-${label//[ ,]/_}-$cells"
  width=$(awk -v c="$cells" 'BEGIN { printf "%.10g", 1 / c }')
  run "$name" terzaghi_consolidation.prm "Mesh/Generator arguments={1, $cells} : 0, 0 : $width, 1 : true" \
    "Material points/layer/Box=0, 0 : $width, 1" "$@"
  read -r steps points t <<< "$(mpm_done_figures "$work/$name.log")"
  printf '%-8s %6d %8d %10.3g %14s %14s %10s %10s\n' "$label" "$cells" "$steps" "$t" \
    "$(report "$name" 'max |u - u_T| \/ u0 at T = 0.05')" "$(report "$name" 'max |u - u_T| \/ u0 at T = 0.2')" \
    "$(report "$name" 'T at U = 0.5')" "$(report "$name" 'T at U = 0.9')"
}

mpm_benchmark_header

consolidation_wide=("Mesh/Generator arguments={40, 40} : 0, 0 : 1, 1 : true"
                    "Material points/layer/Box=0, 0 : 1, 1")
dry_consolidation=("Materials/soil/Porosity=0" "Pore water/Initial pore pressure=0"
                   "Postprocess/List of postprocessors=")
dry_flume=("Materials/sand/Porosity=0" "Pore water/Initial pore pressure=0"
           "Postprocess/List of postprocessors=flume")

for part in "${parts[@]}"; do
  case "$part" in
    cost)
      echo
      echo "## Cost per particle-step, water against dry (min of $n alternating runs)"
      printf '%-14s %7s %9s %9s %10s %10s %12s %12s %10s %11s\n' case points "dry steps" "wet steps" "dry (s)" "wet (s)" "dry p-s/s" "wet p-s/s" "per p-s" "whole run"
      compare consolidation dry wet
      compare flume dry wet
      ;;
    rheology)
      echo
      echo "## The suspension's rheology: with its fluid viscosity against without (min of $n alternating runs)"
      printf '%-14s %7s %9s %9s %10s %10s %12s %12s %10s %11s\n' case points "off steps" "on steps" "off (s)" "on (s)" "off p-s/s" "on p-s/s" "per p-s" "whole run"
      compare suspension off on
      ;;
    stability)
      echo
      echo "## Largest stable step against the bound (CFL 1 on the two phases' fast P wave)"
      echo "(consolidation: the file's k = 1.4e-11 m^2 (c_v = 1 m^2/s), and a permeable layer, k = 1.4e-8 m^2; fixed"
      echo " steps, multiples of the step at CFL 1, to t = 0.3 s; the flume: CFL number, to t = 0.1 s)"
      printf '%-24s %-12s %7s %12s %-34s %14s\n' case step steps "dt (s)" outcome "max err T=0.05"
      for k in 1.4e-11 1.4e-8; do
        run "stability-$k-cfl1" terzaghi_consolidation.prm "Time stepping/End time=0.06" "Time stepping/CFL number=1" "Materials/soil/Permeability=$k"
        dt1=$(awk 'NR == 3 { print $3 }' "$work/stability-$k-cfl1/statistics")
        for f in 0.5 0.9 1 1.2 1.3 1.4 1.5 2; do
          name="stability-$k-$f"
          dt=$(awk -v a="$dt1" -v f="$f" 'BEGIN { printf "%.6g", a * f }')
          run "$name" terzaghi_consolidation.prm "Time stepping/End time=0.3" "Time stepping/Time step selection=fixed" \
            "Time stepping/Time step=$dt" "Materials/soil/Permeability=$k" || true
          printf '%-24s %-12s %7s %12s %-34s %14s\n' "consolidation, k $k" "$f x CFL 1" "$(last_step "$name")" "$dt" \
            "$(outcome "$name")" "$([ "$k" = 1.4e-11 ] && report "$name" 'max |u - u_T| \/ u0 at T = 0.05')"
        done
      done
      for s in 0.5 0.7 0.9 1; do
        name="flume-cfl$s"
        run "$name" flume_usgs_saturated.prm "Time stepping/End time=0.1" "Time stepping/CFL number=$s" || true
        printf '%-24s %-12s %7s %12s %-34s %14s\n' flume "CFL $s" "$(last_step "$name")" \
          "$(awk 'NR == 3 { print $3 }' "$work/$name/statistics")" "$(outcome "$name")" ""
      done
      ;;
    error)
      echo
      echo "## Consolidation: error against wall time (one cell wide, 2 x 2 points per cell, CFL 0.5, to T = 1.01)"
      printf '%-8s %6s %8s %10s %14s %14s %10s %10s\n' averaging cells steps "wall (s)" "err T=0.05" "err T=0.2" "T50" "T90"
      for averaging in node patch cell; do
        for cells in 10 20 40 80 160; do
          error_row "$averaging" "$cells" "Pore water/Pressure rate averaging=$averaging"
        done
      done
      # The same c_v with a skeleton ten times stiffer (M = 1e9 Pa, k =
      # 5e-12 m^2): the layer's inertia, what Terzaghi's quasi-static
      # theory leaves out, weighs less.
      for cells in 20 40 80 160; do
        error_row "node, M x 10" "$cells" "Materials/soil/linear elastic/Young's modulus=1e9" \
          "Materials/soil/Permeability=5e-12"
      done
      echo "(series: T50 = 0.1967, T90 = 0.8481)"
      ;;
    *) echo "two_phase_cost.sh: unknown part '$part' (cost, rheology, stability, error)" >&2; exit 1 ;;
  esac
done
