#!/usr/bin/env bash
# Throughput in 3D on one core (Release): particle-steps per second of the
# MPM step in the 3D landslide (prm/landslide_valley_3d.prm: Mohr-Coulomb,
# MUSL, FLIP 0.98, node-frame friction on the terrain), with about 1e4,
# 1e5 and 1e6 points (mesh refined 0, 1, 2 times; 3 or 4 points per cell
# per direction), over its first 0.2 s (the mass starts to slide). The rate
# counts only the steps (mpm's 'Done' line), not the set-up, whose wall
# time is listed too. Then the 3D block, prm/throughput_3d.prm (a cube of
# 2 x 2 x 2 points per hexahedron on a fixed floor, the mesh as large as
# the block), linear elastic (USF, FLIP) and Mohr-Coulomb (MUSL,
# PIC) with about 1e4 and 1e5 points, max(20, 1.2e7 / points) steps.
# On MPM_THREADS threads (default 1). Writes doc/throughput_3d.csv and
# doc/throughput_3d_block.csv.
# Usage: scripts/throughput_3d.sh [all | landslide | block] (default all)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
out="output-throughput-3d"
mkdir -p "$out"
cases="${1:-all}"
csv="$MPM_ROOT/doc/throughput_3d.csv"
if [ "$cases" != block ]; then
echo "refinements,points_per_cell,cells,points,steps,total_wall_s,step_wall_s,particle_steps_per_s" > "$csv"
for setting in "0 3" "1 3" "2 4"; do
  read -r refinements ppc <<< "$setting"
  name="landslide-r$refinements-p$ppc"
  "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/landslide_valley_3d.prm" --threads "${MPM_THREADS:-1}" \
    --set "Mesh/Global refinements=$refinements" \
    --set "Material points/slide/Points per cell=$ppc" \
    --set "Time stepping/End time=0.2" \
    --set "Output/Write particles=false" \
    --set "Output/Write mesh=false" \
    --set "Output/Write point file=false" \
    --set "Output/Directory=$out/$name" > "$out/$name.log" 2>&1
  cells=$(grep -o '3D, [0-9]* cells' "$out/$name.log" | awk '{print $2}')
  grep '^Done:' "$out/$name.log" | awk -v r="$refinements" -v p="$ppc" -v c="$cells" '{
    s = $0; sub(/.*wall time /, "", s); total = s + 0
    t = $0; sub(/.*\(steps /, "", t); steps_wall = t + 0
    u = $0; sub(/.* s\), /, "", u); rate = u + 0
    printf "%s,%s,%s,%s,%s,%s,%s,%s\n", r, p, c, $4, $2, total, steps_wall, rate }' | tee -a "$csv"
done
fi
[ "$cases" = landslide ] && exit 0

block_csv="$MPM_ROOT/doc/throughput_3d_block.csv"
echo "model,points,cells,steps,step_wall_s,particle_steps_per_s,shape_functions_s,particle_to_grid_s,nodal_update_s,grid_to_particle_s,stress_update_s,locate_points_s" > "$block_csv"
for model in "linear elastic" "mohr coulomb"; do
  for n in 12 23; do
    scheme=USF; flip=1
    if [ "$model" = "mohr coulomb" ]; then scheme=MUSL; flip=0; fi
    points=$(( 8 * n * n * n ))
    steps=$(awk -v n="$points" 'BEGIN { s = int(1.2e7 / n); print (s < 20 ? 20 : s) }')
    # dt = 0.5 h / c with c = 86.5 m/s (E 1e7, nu 0.3, rho 1800).
    end_time=$(awk -v n="$n" -v s="$steps" 'BEGIN { print s * 0.5 / n / 86.49 * 0.999 }')
    name="block-3d-$model-$points"
    "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/throughput_3d.prm" --threads "${MPM_THREADS:-1}" \
      --set "Mesh/Generator arguments={$n, $n, $n} : 0, 0, 0 : 1, 1, 1 : true" \
      --set "Material points/block/Box=0, 0, 0 : 1, 1, 1" \
      --set "Materials/block/Model=$model" \
      --set "Time stepping/Update scheme=$scheme" \
      --set "Transfer/FLIP fraction=$flip" \
      --set "Time stepping/End time=$end_time" \
      --set "Output/Write particles=false" \
      --set "Output/Write mesh=false" \
      --set "Output/Directory=$out/$name" > "$out/$name.log" 2>&1
    awk -v model="$model" -v cells="$(( n * n * n ))" '
      /^Done:/ { n_steps = $2; n_points = $4
                 stepping = $0; sub(/.*\(steps /, "", stepping); sub(/ s\).*/, "", stepping) }
      /^\| / { split($0, f, "|"); name = f[2]; gsub(/^ +| +$/, "", name)
               t = f[4]; gsub(/[ s]/, "", t); sec[name] = t }
      END { printf "%s,%d,%d,%d,%.4g,%.4g,%s,%s,%s,%s,%s,%s\n", model, n_points, cells, n_steps,
              stepping, n_steps * n_points / stepping, sec["shape functions"], sec["particle to grid"],
              sec["nodal update"], sec["grid to particle"], sec["stress update"], sec["locate points"] }' \
      "$out/$name.log" | tee -a "$block_csv"
  done
done
