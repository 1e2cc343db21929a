#!/usr/bin/env bash
# Speed against error: runs scenes with one parameter varied at a time from
# the shipped case (command-line overrides of the scene's .prm), and records
# for each run the wall time of the steps, the particle-steps per second,
# the peak memory (resident set, from /usr/bin/time) and the error against
# the scene's reference:
#   vibrating_bar       analytical centre-of-mass velocity (max error / amplitude)
#   self_weight_column  analytical sigma_yy (whole-column relative L2 error)
#   sliding_block       analytical sliding speed (max relative error, t >= 0.1 s)
#   spinning_body       a freely spinning elastic square: the fraction of its
#                       kinetic energy lost in 0.2 s (exact: none)
#   flume               final front position of the finest run (CFL 0.25,
#                       3 x 3 points per cell); opt-in, about 25 min
# Besides the numerical parameters (cell size, points per cell, CFL number,
# update scheme, FLIP fraction), each scene is run with the other weight
# function (linear / CPDI), the other transfer schemes (XPIC, APIC; APIC
# under MUSL, where it is stable with linear weights), volumetric strain
# averaging where the scene has a volumetric stress, and on 2 threads (the
# same error, bit for bit: only the time moves).
# Writes doc/speed_error.csv and doc/speed_error.png (error against wall
# time, one panel per scene, one curve per parameter). Release build, one
# core (MPM_THREADS threads, default 1). A run stopped by the stability check is recorded as "unstable".
# Usage: scripts/speed_error_sweep.sh [scene ...]
#   (default: vibrating_bar self_weight_column sliding_block spinning_body;
#   add flume)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(vibrating_bar self_weight_column sliding_block spinning_body)
out="output-speed-error"
mkdir -p "$out"
csv="$MPM_ROOT/doc/speed_error.csv"
echo "scene,parameter,value,points,steps,step_wall_s,particle_steps_per_s,peak_memory_MB,error,error_measure" > "$csv"

# run SCENE PARAMETER VALUE PRM ERROR_LINE_PREFIX ERROR_MEASURE [--set ...]
run() {
  local scene="$1" parameter="$2" value="$3" prm="$4" prefix="$5" measure="$6"
  shift 6
  local name="$scene-$parameter-$value"
  name="${name// /_}"
  if ! /usr/bin/time -f "%M" -o "$out/$name.mem" "$MPM_BUILD_DIR/mpm" "$prm" --threads "${MPM_THREADS:-1}" "$@" \
      --set "Output/Write particles=false" --set "Output/Write mesh=false" \
      --set "Output/Directory=$out/$name" > "$out/$name.log" 2>&1; then
    printf "%s,%s,%s,,,,,,unstable,%s\n" "$scene" "$parameter" "$value" "$measure" | tee -a "$csv"
    return 0
  fi
  local done_line error memory
  done_line=$(grep '^Done:' "$out/$name.log")
  if [ "$prefix" = "final front" ]; then
    error=$(grep '^final front' "$out/$name/report.txt" | sed -E 's/final front: s = ([-0-9.e+]+) m.*/\1/')
  else
    error=$(grep -F "$prefix" "$out/$name/report.txt" | head -1 | sed -E 's/.*: //')
  fi
  memory=$(awk '{ printf "%.1f", $1 / 1024 }' "$out/$name.mem")
  printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n" "$scene" "$parameter" "$value" \
    "$(echo "$done_line" | awk '{print $4}')" "$(echo "$done_line" | awk '{print $2}')" \
    "$(echo "$done_line" | sed -E 's/.*\(steps ([0-9.e+-]+) s\).*/\1/')" \
    "$(echo "$done_line" | sed -E 's/.*, ([0-9.e+-]+) particle-steps.*/\1/')" \
    "$memory" "$error" "$measure" | tee -a "$csv"
}

vibrating_bar() {
  # Shipped: 26 cells of 1 m, 2 x 2 points per cell, CFL 0.5, USF, FLIP.
  # With the linear weights, as when doc/performance.md's figures were
  # made (the prm ships CPDI since; doc/convergence.md compares the two).
  local prm="$MPM_ROOT/prm/vibrating_bar.prm" e="max |v_cm error|" m="max v_cm error / amplitude"
  # bar_refinement PARAMETER WEIGHTS: the bar on 13 to 208 cells along it.
  bar_refinement() {
    local n h rows top
    for n in 13 26 52 104 208; do
      h=$(awk -v n="$n" 'BEGIN { print 26 / n }')
      rows=$(awk -v h="$h" 'BEGIN { r = int(1 / h + 0.5); print (r < 1 ? 1 : r) }')
      top=$(awk -v h="$h" -v r="$rows" 'BEGIN { print h * r }')
      run vibrating_bar "$1" "$h" "$prm" "$e" "$m" --set "Transfer/Particle-grid weights=$2" \
        --set "Mesh/Generator arguments={$n, $rows} : 0, 0 : 26, $top : true"
    done
  }
  bar_refinement "cell size (m)" linear
  for v in 1 2 3 4; do run vibrating_bar "points per cell" "$v" "$prm" "$e" "$m" --set "Transfer/Particle-grid weights=linear" --set "Material points/bar/Points per cell=$v"; done
  for v in 0.1 0.2 0.4 0.8; do run vibrating_bar "CFL number" "$v" "$prm" "$e" "$m" --set "Transfer/Particle-grid weights=linear" --set "Time stepping/CFL number=$v"; done
  for v in USF USL MUSL; do run vibrating_bar "update scheme" "$v" "$prm" "$e" "$m" --set "Transfer/Particle-grid weights=linear" --set "Time stepping/Update scheme=$v"; done
  for v in 0 0.5 0.9 1; do run vibrating_bar "FLIP fraction" "$v" "$prm" "$e" "$m" --set "Transfer/Particle-grid weights=linear" --set "Transfer/FLIP fraction=$v"; done
  # The shipped weights: CPDI converges under refinement where the linear
  # weights above go unstable (doc/convergence.md).
  bar_refinement "cell size CPDI (m)" cpdi
  transfer_schemes vibrating_bar "$prm" "$e" "$m" --set "Transfer/Particle-grid weights=linear"
  MPM_THREADS=2 run vibrating_bar "threads" 2 "$prm" "$e" "$m" --set "Transfer/Particle-grid weights=linear"
}

# transfer_schemes SCENE PRM ERROR_LINE_PREFIX ERROR_MEASURE [--set ...]:
# the scene with XPIC(2) and with APIC under MUSL (value names the scheme).
transfer_schemes() {
  local scene="$1" prm="$2" e="$3" m="$4"
  shift 4
  run "$scene" "transfer scheme" "xpic" "$prm" "$e" "$m" "$@" --set "Transfer/Scheme=xpic"
  run "$scene" "transfer scheme" "apic MUSL" "$prm" "$e" "$m" "$@" --set "Transfer/Scheme=apic" \
    --set "Time stepping/Update scheme=MUSL"
}

self_weight_column() {
  # Shipped (tests/self_weight_column_h1.prm): h = 0.01 m, 2 x 2 points
  # per cell, CFL 0.5, USF, FLIP, local damping 0.3.
  local prm="$MPM_ROOT/tests/self_weight_column_h1.prm" e="whole column relative L2" m="L2 error of sigma_yy / rho g H"
  local n
  for n in 5 10 20 40; do
    run self_weight_column "cell size (m)" "$(awk -v n="$n" 'BEGIN { print 0.1 / n }')" "$prm" "$e" "$m" \
      --set "Mesh/Generator arguments={$n, $((n * 5 / 2))} : 0, 0 : 0.1, 0.25 : true"
  done
  for v in 1 2 3 4; do run self_weight_column "points per cell" "$v" "$prm" "$e" "$m" --set "Material points/column/Points per cell=$v"; done
  for v in 0.1 0.25 0.5 0.9; do run self_weight_column "CFL number" "$v" "$prm" "$e" "$m" --set "Time stepping/CFL number=$v"; done
  for v in USF MUSL; do run self_weight_column "update scheme" "$v" "$prm" "$e" "$m" --set "Time stepping/Update scheme=$v"; done
  for v in 0 1; do run self_weight_column "FLIP fraction" "$v" "$prm" "$e" "$m" --set "Transfer/FLIP fraction=$v"; done
  run self_weight_column "weights" "cpdi" "$prm" "$e" "$m" --set "Transfer/Particle-grid weights=cpdi"
  run self_weight_column "volumetric averaging" "cell" "$prm" "$e" "$m" --set "Time stepping/Volumetric strain averaging=cell"
  transfer_schemes self_weight_column "$prm" "$e" "$m"
  MPM_THREADS=2 run self_weight_column "threads" 2 "$prm" "$e" "$m"
}

sliding_block() {
  # Shipped (prm/sliding_block.prm, mu = 0.1): Gmsh mesh of 0.25 m quads,
  # 4 x 4 points per cell, CFL 0.5, USF, PIC.
  local prm="$MPM_ROOT/prm/sliding_block.prm" e="max relative speed error" m="max relative speed error (t >= 0.1 s)"
  for v in 1 2 3 4 6; do run sliding_block "points per cell" "$v" "$prm" "$e" "$m" --set "Material points/block/Points per cell=$v"; done
  for v in 0.1 0.25 0.5 0.9; do run sliding_block "CFL number" "$v" "$prm" "$e" "$m" --set "Time stepping/CFL number=$v"; done
  for v in USF USL MUSL; do run sliding_block "update scheme" "$v" "$prm" "$e" "$m" --set "Time stepping/Update scheme=$v"; done
  for v in 0 0.5 1; do run sliding_block "FLIP fraction" "$v" "$prm" "$e" "$m" --set "Transfer/FLIP fraction=$v"; done
  run sliding_block "weights" "cpdi" "$prm" "$e" "$m" --set "Transfer/Particle-grid weights=cpdi"
  transfer_schemes sliding_block "$prm" "$e" "$m"
  MPM_THREADS=2 run sliding_block "threads" 2 "$prm" "$e" "$m"
}

spinning_body() {
  # tests/spinning_body_pic.prm: a 0.4 m elastic square spinning at 2 rad/s,
  # 2 x 2 points in 0.05 m cells, CFL 0.5, MUSL, PIC; no gravity, no wall,
  # so its kinetic energy should stay. The error is the largest energy
  # change over 0.2 s relative to the initial energy (doc/transfers.md).
  local prm="$MPM_ROOT/tests/spinning_body_pic.prm" e="max energy change" m="energy lost in 0.2 s / initial energy"
  local v
  for v in 0 0.98 1; do run spinning_body "FLIP fraction" "$v" "$prm" "$e" "$m" --set "Transfer/FLIP fraction=$v"; done
  transfer_schemes spinning_body "$prm" "$e" "$m"
  run spinning_body "transfer scheme" "apic+cpdi" "$prm" "$e" "$m" --set "Transfer/Scheme=apic" \
    --set "Transfer/Particle-grid weights=cpdi"
  for v in 0.25 0.9; do
    run spinning_body "CFL number apic+cpdi" "$v" "$prm" "$e" "$m" --set "Transfer/Scheme=apic" \
      --set "Transfer/Particle-grid weights=cpdi" --set "Time stepping/CFL number=$v"
  done
  MPM_THREADS=2 run spinning_body "threads" 2 "$prm" "$e" "$m" --set "Transfer/Scheme=apic" \
    --set "Transfer/Particle-grid weights=cpdi"
}

flume() {
  # prm/flume_usgs.prm as shipped: 5 mm mesh, 3 x 3 points per cell, CFL
  # 0.5, MUSL, APIC on CPDI weights (the flume rows of doc/speed_error.csv
  # were measured when it shipped the FLIP/PIC blend, FLIP fraction 0.98
  # per 3.3e-5 s: rerunning this gives the default path's rows). No
  # analytical reference: the error is the distance of
  # the final front from that of the finest run (CFL 0.25), which runs
  # first and is not itself plotted.
  local prm="$MPM_ROOT/prm/flume_usgs.prm" reference front_of
  front_of() { grep '^final front' "$out/$1/report.txt" | sed -E 's/final front: s = ([-0-9.e+]+) m.*/\1/'; }
  "$MPM_BUILD_DIR/mpm" "$prm" --set "Time stepping/CFL number=0.25" \
    --set "Output/Write particles=false" --set "Output/Write mesh=false" \
    --set "Output/Directory=$out/flume-reference" > "$out/flume-reference.log" 2>&1
  reference=$(front_of flume-reference)
  local v
  for v in 0.5 0.8; do
    run flume "CFL number" "$v" "$prm" "final front" "final front: |s - s(CFL 0.25)| (m)" --set "Time stepping/CFL number=$v"
  done
  for v in 2 4; do
    run flume "points per cell" "$v" "$prm" "final front" "final front: |s - s(CFL 0.25)| (m)" --set "Material points/sand/Points per cell=$v"
  done
  run flume "transfer scheme" "apic+cpdi" "$prm" "final front" "final front: |s - s(CFL 0.25)| (m)" \
    --set "Transfer/Scheme=apic" --set "Transfer/Particle-grid weights=cpdi"
  MPM_THREADS=2 run flume "threads" 2 "$prm" "final front" "final front: |s - s(CFL 0.25)| (m)"
  # The error column holds the front's s; turn it into the distance from
  # the reference.
  awk -F, -v OFS=, -v r="$reference" '$1 == "flume" && $9 != "unstable" && $9 != "" {
      d = $9 - r; $9 = (d < 0 ? -d : d) } { print }' "$csv" > "$csv.tmp" && mv "$csv.tmp" "$csv"
}

for scene in "${scenes[@]}"; do
  case "$scene" in
    vibrating_bar | self_weight_column | sliding_block | spinning_body | flume) "$scene" ;;
    *) echo "unknown scene '$scene' (vibrating_bar, self_weight_column, sliding_block, spinning_body, flume)" >&2; exit 2 ;;
  esac
done
/usr/bin/python3 "$MPM_ROOT/scripts/plot_speed_error.py" "$csv" "$MPM_ROOT/doc/speed_error.png"
