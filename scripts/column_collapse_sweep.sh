#!/usr/bin/env bash
# Granular column collapse (prm/column_collapse.prm) for aspect ratios
# a = H0/L0 = 0.5 ... 6 (Release build): the runout (L_inf - L0)/L0 and the
# final height against a, in doc/column_collapse.csv, and the plot
# doc/column_collapse.png with the scaling laws (doc/column_collapse.md).
# Usage: scripts/column_collapse_sweep.sh [aspect ratios, default "0.5 1 2 3 4 6"] [extra mpm arguments...]
# Environment: MPM_CELL_SIZE (m, default 0.005), MPM_SWEEP_NAME (default:
# the shipped file, written to doc/column_collapse.csv; another name writes
# doc/column_collapse_NAME.csv), MPM_SWEEP_APPEND=1 (add the rows to that CSV
# instead of starting it anew: one more a on a mesh run before). The shipped file runs the default transfer
# (APIC on CPDI weights); the cheaper FLIP/PIC blend of doc/column_collapse.md,
# "Other transfers":
#   MPM_SWEEP_NAME=blend scripts/column_collapse_sweep.sh "0.5 1 2 3 4 6" \
#     --set "Transfer/Scheme=flip/pic blend" --set "Transfer/FLIP fraction=0.98" \
#     --set "Transfer/FLIP fraction time step=6e-5" --set "Transfer/Particle-grid weights=linear"
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
ratios="${1:-0.5 1 2 3 4 6}"
shift || true
name_suffix="${MPM_SWEEP_NAME:+_$MPM_SWEEP_NAME}"
out="output-column-collapse-sweep$name_suffix"
mkdir -p "$out"
csv="$MPM_ROOT/doc/column_collapse$name_suffix.csv"
[ -n "${MPM_SWEEP_APPEND:-}" ] && [ -s "$csv" ] ||
  echo "a,runout,final_height_over_L0,stop_time_s,mean_speed_end,lube_2005,points,wall_s,deposit_runout,volume_end_over_start,connected_runout,runout_95_percent_volume,runout_99_percent_volume" > "$csv"
L0=0.1
h="${MPM_CELL_SIZE:-0.005}"
for a in $ratios; do
  # Column L0 x H0 against the wall at x = 0; the mesh reaches past the
  # runout and above the column (5 mm cells); long enough to come to rest.
  read -r H0 W H nx ny end_time < <(awk -v a="$a" -v L="$L0" -v h="$h" 'BEGIN {
    H0 = a * L; W = L * (3 + 2 * a); H = H0 + 0.05
    printf "%g %g %g %d %d %g\n", H0, W, H, W / h + 0.5, H / h + 0.5, (1.2 > 0.6 + 0.25 * a ? 1.2 : 0.6 + 0.25 * a) }')
  name="a-$a"
  "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/column_collapse.prm" \
    --set "Mesh/Generator arguments={$nx, $ny} : 0, 0 : $W, $H : true" \
    --set "Material points/column/Box=0, 0 : $L0, $H0" \
    --set "Postprocess/column collapse/Initial width=$L0" \
    --set "Postprocess/column collapse/Initial height=$H0" \
    --set "Time stepping/End time=$end_time" \
    --set "Output/Write particles=false" \
    --set "Output/Directory=$out/$name" "$@" > "$out/$name.log"
  report="$out/$name/report.txt"
  value() { grep "^$1" "$report" | sed -E 's/.*: *//; s/ .*//'; }
  stop=$(grep -E "^mean speed below" "$report" | sed -E 's/.*t = ([0-9.e+-]+) s on/\1/' || true)
  done_line=$(grep '^Done:' "$out/$name.log")
  printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n" "$a" "$(value 'runout (')" "$(value 'final height H_inf/L0')" \
    "${stop:-not stopped}" "$(value 'mean speed at the end')" "$(value 'Lube et al. 2005')" \
    "$(echo "$done_line" | awk '{print $4}')" \
    "$(echo "$done_line" | sed -E 's/.*wall time ([0-9.e+-]+) s.*/\1/')" \
    "$(value 'runout of the deposit')" "$(value 'total point volume')" \
    "$(value 'runout of the connected deposit')" "$(value 'runout holding 95 %')" \
    "$(value 'runout holding 99 %')" | tee -a "$csv"
done
/usr/bin/python3 "$MPM_ROOT/scripts/plot_column_collapse.py" "$csv" "$MPM_ROOT/doc/column_collapse$name_suffix.png"
