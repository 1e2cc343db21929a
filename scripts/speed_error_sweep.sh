#!/usr/bin/env bash
# Speed against error: the vibrating bar (prm/vibrating_bar.prm, analytical
# centre-of-mass velocity) with one parameter varied at a time from the
# shipped case - cell size, points per cell, CFL number, update scheme, FLIP
# fraction - recording the wall time of the steps and the errors. Writes
# doc/speed_error.csv and doc/speed_error.png (error against wall time, one
# curve per parameter). Release build, one core.
# Usage: scripts/speed_error_sweep.sh
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
out="output-speed-error"
mkdir -p "$out"
csv="$MPM_ROOT/doc/speed_error.csv"
echo "parameter,value,cell_size_m,points_per_cell,cfl,scheme,flip,points,steps,step_wall_s,vcm_error,period_error" > "$csv"

# run PARAMETER VALUE CELLS_ALONG PPC CFL SCHEME FLIP
run() {
  local parameter="$1" value="$2" n="$3" ppc="$4" cfl="$5" scheme="$6" flip="$7"
  local h rows name
  h=$(awk -v n="$n" 'BEGIN { print 26 / n }')
  rows=$(awk -v h="$h" 'BEGIN { r = int(1 / h + 0.5); print (r < 1 ? 1 : r) }')
  local top
  top=$(awk -v h="$h" -v r="$rows" 'BEGIN { print h * r }')
  name="$parameter-$value"
  "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/vibrating_bar.prm" \
    --set "Mesh/Generator arguments={$n, $rows} : 0, 0 : 26, $top : true" \
    --set "Material points/bar/Points per cell=$ppc" \
    --set "Time stepping/CFL number=$cfl" \
    --set "Time stepping/Update scheme=$scheme" \
    --set "Time stepping/FLIP fraction=$flip" \
    --set "Output/Write particles=false" --set "Output/Write mesh=false" \
    --set "Output/Directory=$out/$name" > "$out/$name.log" 2>&1 || {
    # Stopped by the stability check (or another error): recorded, not fatal.
    printf "%s,%s,%s,%s,%s,%s,%s,,,,unstable,unstable\n" "$parameter" "$value" "$h" "$ppc" "$cfl" "$scheme" "$flip" | tee -a "$csv"
    return 0
  }
  local report="$out/$name/report.txt" done_line
  done_line=$(grep '^Done:' "$out/$name.log")
  printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n" "$parameter" "$value" "$h" "$ppc" "$cfl" "$scheme" "$flip" \
    "$(echo "$done_line" | awk '{print $4}')" "$(echo "$done_line" | awk '{print $2}')" \
    "$(echo "$done_line" | sed -E 's/.*\(steps ([0-9.e+-]+) s\).*/\1/')" \
    "$(grep '^max |v_cm error|' "$report" | sed -E 's/.*: //')" \
    "$(grep '^period relative error' "$report" | sed -E 's/.*: //')" | tee -a "$csv"
}

# The shipped case: 26 cells of 1 m, 2 x 2 points per cell, CFL 0.5, USF, FLIP.
for n in 13 26 52 104 208; do run "cell size" "$n" "$n" 2 0.5 USF 1; done
for ppc in 1 2 3 4; do run "points per cell" "$ppc" 26 "$ppc" 0.5 USF 1; done
for cfl in 0.1 0.2 0.4 0.8; do run "CFL number" "$cfl" 26 2 "$cfl" USF 1; done
for scheme in USF USL MUSL; do run "update scheme" "$scheme" 26 2 0.5 "$scheme" 1; done
for flip in 0 0.5 0.9 1; do run "FLIP fraction" "$flip" 26 2 0.5 USF "$flip"; done
/usr/bin/python3 "$MPM_ROOT/scripts/plot_speed_error.py" "$csv" "$MPM_ROOT/doc/speed_error.png"
