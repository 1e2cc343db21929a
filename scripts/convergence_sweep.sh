#!/usr/bin/env bash
# Convergence under mesh refinement, linear against CPDI weights (one core,
# Release; doc/convergence.md):
#  1. the vibrating bar (prm/vibrating_bar.prm, 2 x 2 points per cell) with
#     n = 1, 2, 4, 8, 16 cells per metre, on the regular mesh and with every
#     interior vertex moved by up to 30 % of its shortest edge: the largest
#     centre-of-mass velocity error, the period error, whether it ran to the
#     end, and the particle-steps per second (the cost of each weight);
#  2. the self-weight column at large strain (tests/self_weight_column_
#     large_cpdi.prm: rho0 g H0 / E = 0.5, 21 % settlement) with n = 5, 10,
#     20, 40, 80 cells across its 0.1 m width: the whole-column L2 error of
#     sigma_yy against the exact finite-strain solution and the column
#     height's error relative to the settlement (about 5 minutes);
#  3. with the argument 'locking': volumetric locking, the a = 2 collapse
#     (5 mm) and the flume (prm/flume_usgs.prm) with 1, 2 and 3 points per
#     cell per direction, 'Volumetric strain averaging' none and cell
#     (doc/locking.csv; about 15 minutes), instead of 4.;
#  4. with the argument 'collapse': the a = 2 granular column collapse
#     (prm/column_collapse.prm as shipped) on 5, 2.5 and 1.25 mm meshes
#     (about 1.5 hours with 2 x 2 points per cell, the shipped file's 3 x 3
#     have 2.25 times as many; 'collapse-quick' stops at 2.5 mm).
# Writes doc/convergence_bar.csv, doc/convergence_column.csv (and
# doc/convergence_collapse.csv) and
# doc/convergence.png.
# Usage: scripts/convergence_sweep.sh [collapse|collapse-quick|locking|column]
# ('column': only 2., then the plot)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
out="output-convergence"
mkdir -p "$out"

# The numbers of a finished run: field "name: value" of the report, and the
# 'Done:' line of the log.
report_value() { grep "^$2" "$1" 2>/dev/null | sed -E 's/.*: *//; s/ .*//' || true; }
done_field() {  # log, awk program on the Done line
  grep '^Done:' "$1" | awk "$2" || true
}

csv="$MPM_ROOT/doc/convergence_bar.csv"
column_csv="$MPM_ROOT/doc/convergence_column.csv"
if [ "${1:-}" != locking ] && [ "${1:-}" != column ]; then
echo "weights,distortion,n,points,max_vcm_error,period_error,status,steps,step_wall_s,particle_steps_per_s" > "$csv"
for distortion in 0 0.3; do
  for n in 1 2 4 8 16; do
    for weights in linear cpdi; do
      name="bar-$weights-d$distortion-n$n"
      status=ok
      "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/vibrating_bar.prm" \
        --set "Mesh/Generator arguments={$((26 * n)), $n} : 0, 0 : 26, 1 : true" \
        --set "Mesh/Random vertex perturbation=$distortion" \
        --set "Transfer/Particle-grid weights=$weights" \
        --set "Output/Output interval=100" \
        --set "Output/Write particles=false" \
        --set "Output/Directory=$out/$name" > "$out/$name.log" 2>&1 || status=unstable
      report="$out/$name/report.txt"
      if [ "$status" = ok ]; then
        printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n" "$weights" "$distortion" "$n" \
          "$(done_field "$out/$name.log" '{print $4}')" \
          "$(report_value "$report" 'max |v_cm error|')" \
          "$(report_value "$report" 'period relative error')" "$status" \
          "$(done_field "$out/$name.log" '{print $2}')" \
          "$(done_field "$out/$name.log" '{s = $0; sub(/.*\(steps /, "", s); sub(/ s\).*/, "", s); print s}')" \
          "$(done_field "$out/$name.log" '{s = $0; sub(/.* s\), /, "", s); sub(/ particle-steps.*/, "", s); print s}')" | tee -a "$csv"
      else
        step=$(grep -o 'unstable by step [0-9]*' "$out/$name.log" | awk '{print $4}')
        printf "%s,%s,%s,,,,unstable at step %s,,,\n" "$weights" "$distortion" "$n" "$step" | tee -a "$csv"
      fi
    done
  done
done

fi

# The self-weight column at large strain: base prm + the large-strain test.
if [ "${1:-}" != locking ]; then
echo "weights,n,points,l2_error,height_error_over_settlement,status,steps,step_wall_s,particle_steps_per_s" > "$column_csv"
for n in 5 10 20 40 80; do
  for weights in linear cpdi; do
    name="column-$weights-n$n"
    status=ok
    "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/tests/self_weight_column_h1.prm" \
      "$MPM_ROOT/tests/self_weight_column_large_cpdi.prm" \
      --set "Mesh/Generator arguments={$n, $((n * 5 / 2))} : 0, 0 : 0.1, 0.25 : true" \
      --set "Transfer/Particle-grid weights=$weights" \
      --set "Output/Directory=$out/$name" > "$out/$name.log" 2>&1 || status=failed
    report="$out/$name/report.txt"
    printf "%s,%s,%s,%s,%s,%s,%s,%s,%s\n" "$weights" "$n" \
      "$(done_field "$out/$name.log" '{print $4}')" \
      "$(report_value "$report" 'whole column relative L2 error')" \
      "$(grep '^column height' "$report" 2>/dev/null | sed -E 's/.*settlement: *//' || true)" "$status" \
      "$(done_field "$out/$name.log" '{print $2}')" \
      "$(done_field "$out/$name.log" '{s = $0; sub(/.*\(steps /, "", s); sub(/ s\).*/, "", s); print s}')" \
      "$(done_field "$out/$name.log" '{s = $0; sub(/.* s\), /, "", s); sub(/ particle-steps.*/, "", s); print s}')" | tee -a "$column_csv"
  done
done

fi

if [ "${1:-}" = locking ]; then
  lcsv="$MPM_ROOT/doc/locking.csv"
  echo "scene,points_per_cell,averaging,runout_or_peak,final_height_or_peak_time,rest_time_s,front_m,volume_end_over_start,status,step_wall_s" > "$lcsv"
  for ppc in 1 2 3; do
    for averaging in none cell; do
      name="locking-collapse-p$ppc-$averaging"
      status=ok
      "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/column_collapse.prm" \
        --set "Material points/column/Points per cell=$ppc" \
        --set "Time stepping/Volumetric strain averaging=$averaging" \
        --set "Output/Write particles=false" \
        --set "Output/Directory=$out/$name" > "$out/$name.log" 2>&1 || status=failed
      report="$out/$name/report.txt"
      stop=$(grep -E "^mean speed below" "$report" 2>/dev/null | sed -E 's/.*t = ([0-9.e+-]+) s on/\1/' || true)
      printf "collapse,%s,%s,%s,%s,%s,%s,%s,%s,%s\n" "$ppc" "$averaging" \
        "$(report_value "$report" 'runout of the deposit')" \
        "$(report_value "$report" 'final height H_inf/L0')" "${stop:-}" \
        "$(report_value "$report" 'runout (L_inf')" \
        "$(report_value "$report" 'total point volume')" "$status" \
        "$(done_field "$out/$name.log" '{s = $0; sub(/.*\(steps /, "", s); sub(/ s\).*/, "", s); print s}')" | tee -a "$lcsv"
      name="locking-flume-p$ppc-$averaging"
      status=ok
      "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/flume_usgs.prm" \
        --set "Material points/sand/Points per cell=$ppc" \
        --set "Time stepping/Volumetric strain averaging=$averaging" \
        --set "Output/Write particles=false" \
        --set "Output/Directory=$out/$name" > "$out/$name.log" 2>&1 || status=failed
      report="$out/$name/report.txt"
      peak=$(grep '^peak mean speed' "$report" 2>/dev/null || true)
      rest=$(grep '^front within' "$report" 2>/dev/null | sed -E 's/.*from t = ([0-9.e+-]+) s.*/\1/' || true)
      front=$(grep '^final front' "$report" 2>/dev/null | sed -E 's/final front: s = ([0-9.e+-]+) m.*/\1/' || true)
      printf "flume,%s,%s,%s,%s,%s,%s,,%s,%s\n" "$ppc" "$averaging" \
        "$(echo "$peak" | sed -E 's/.*: ([0-9.e+-]+) m\/s.*/\1/')" \
        "$(echo "$peak" | sed -E 's/.*t = ([0-9.e+-]+) s.*/\1/')" "${rest:-}" "${front:-}" "$status" \
        "$(done_field "$out/$name.log" '{s = $0; sub(/.*\(steps /, "", s); sub(/ s\).*/, "", s); print s}')" | tee -a "$lcsv"
    done
  done
  exit 0
fi

if [ "${1:-}" = collapse ] || [ "${1:-}" = collapse-quick ]; then
  meshes="0.005 0.0025 0.00125"
  [ "$1" = collapse-quick ] && meshes="0.005 0.0025"
  ccsv="$MPM_ROOT/doc/convergence_collapse.csv"
  echo "weights,h,runout,final_height_over_L0,stop_time_s,status,points,step_wall_s" > "$ccsv"
  L0=0.1; a=2
  for h in $meshes; do
    for weights in linear cpdi; do
      read -r H0 W H nx ny < <(awk -v a="$a" -v L="$L0" -v h="$h" 'BEGIN {
        H0 = a * L; W = L * (3 + 2 * a); H = H0 + 0.05
        printf "%g %g %g %d %d\n", H0, W, H, W / h + 0.5, H / h + 0.5 }')
      name="collapse-$weights-h$h"
      status=ok
      "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/column_collapse.prm" \
        --set "Mesh/Generator arguments={$nx, $ny} : 0, 0 : $W, $H : true" \
        --set "Transfer/Particle-grid weights=$weights" \
        --set "Output/Write particles=false" \
        --set "Output/Directory=$out/$name" > "$out/$name.log" 2>&1 || status=failed
      report="$out/$name/report.txt"
      stop=$(grep -E "^mean speed below" "$report" 2>/dev/null | sed -E 's/.*t = ([0-9.e+-]+) s on/\1/' || true)
      printf "%s,%s,%s,%s,%s,%s,%s,%s\n" "$weights" "$h" \
        "$(report_value "$report" 'runout')" \
        "$(report_value "$report" 'final height H_inf/L0')" "${stop:-}" "$status" \
        "$(done_field "$out/$name.log" '{print $4}')" \
        "$(done_field "$out/$name.log" '{s = $0; sub(/.*\(steps /, "", s); sub(/ s\).*/, "", s); print s}')" | tee -a "$ccsv"
    done
  done
fi
/usr/bin/python3 "$MPM_ROOT/scripts/plot_convergence.py" "$csv" "$column_csv" "$MPM_ROOT/doc/convergence.png"
