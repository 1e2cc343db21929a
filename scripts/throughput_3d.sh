#!/usr/bin/env bash
# Throughput in 3D on one core (Release): particle-steps per second of the
# MPM step in the 3D landslide (prm/landslide_valley_3d.prm: Mohr-Coulomb,
# MUSL, FLIP 0.98, node-frame friction on the terrain), with about 1e4,
# 1e5 and 1e6 points (mesh refined 0, 1, 2 times; 3 or 4 points per cell
# per direction), over its first 0.2 s (the mass starts to slide). The rate
# counts only the steps (mpm's 'Done' line), not the set-up, whose wall
# time is listed too. On MPM_THREADS threads (default 1). Writes
# doc/throughput_3d.csv.
# Usage: scripts/throughput_3d.sh
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
out="output-throughput-3d"
mkdir -p "$out"
csv="$MPM_ROOT/doc/throughput_3d.csv"
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
