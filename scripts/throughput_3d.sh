#!/usr/bin/env bash
# Throughput in 3D (Release): particle-steps per second of the MPM step,
# split by the timer sections.
# - The 3D landslide (prm/landslide_valley_3d.prm as shipped: Mohr-Coulomb,
#   MUSL, APIC on CPDI weights (doc/three_d.md's table was measured when
#   it shipped the FLIP/PIC blend 0.98), node-frame friction on the
#   terrain, cells that are not
#   parallelepipeds) with about 1e4, 1e5 and 1.6e6 points (mesh refined 0,
#   1, 2 times; 3, 3, 4 points per cell per direction), from the release
#   until 3.2, 0.3 and 0.2 s: at least 2 s of stepping per case on the
#   machines of doc/performance.md (the mass starts to slide; the rate of
#   the whole 12 s run is in doc/three_d.md).
# - The 3D block (prm/throughput_3d.prm: a cube of 2 x 2 x 2 points per
#   hexahedron on a fixed floor, the mesh as large as the block), linear
#   elastic (USF, FLIP) and Mohr-Coulomb (MUSL, PIC) with about 1e4 and 1e5
#   points, max(20, 1.2e7 / points) steps; then linear elastic with CPDI
#   weights ("linear elastic (cpdi)": hexahedral domains, whose corners on
#   the mesh's walls are moved onto them).
# The rate counts only the steps (mpm's 'Done' line), not the set-up, whose
# wall time is listed too; the peak memory is mpm's 'Peak memory' line (the
# resident set's high-water mark, libraries included: the memory per point
# is the difference between two sizes over the difference of their
# points). Each case runs MPM_REPEATS times (default 3) and the run with
# the median rate is kept; MPM_THREADS lists the threads per
# run (default "1"; e.g. "1 2"). "untimed" is the share of the steps' wall
# time in no timer section. Writes doc/throughput_3d.csv (landslide) and
# doc/throughput_3d_block.csv.
# Usage: scripts/throughput_3d.sh [all | landslide | block] (default all)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
out="output-throughput-3d"
mkdir -p "$out"
cases="${1:-all}"
sections_header="shape_functions_s,particle_to_grid_s,nodal_update_s,grid_to_particle_s,stress_update_s,locate_points_s,untimed_share,peak_memory_MiB"

# summarise LOG PREFIX: PREFIX, then steps, points, set-up and steps' wall
# time, rate and the timer sections of one run's log, as one CSV line whose
# 6th field from the prefix on is the rate.
summarise() {
  awk -v prefix="$2" '
    /^Done:/ { n_steps = $2; n_points = $4
               total = $0; sub(/.*wall time /, "", total); total += 0
               stepping = $0; sub(/.*\(steps /, "", stepping); sub(/ s\).*/, "", stepping) }
    /^Peak memory:/ { memory = $3 }
    /^\| / { split($0, f, "|"); name = f[2]; gsub(/^ +| +$/, "", name)
             t = f[4]; gsub(/[ s]/, "", t); sec[name] = t
             if (name != "setup" && name != "Section" && name != "Total wallclock time elapsed since start") timed += t }
    END { printf "%s,%d,%d,%.4g,%.4g,%.4g,%s,%s,%s,%s,%s,%s,%.3f,%s\n", prefix, n_steps, n_points,
            total - stepping, stepping, n_steps * n_points / stepping,
            sec["shape functions"], sec["particle to grid"], sec["nodal update"],
            sec["grid to particle"], sec["stress update"], sec["locate points"],
            (stepping - timed) / stepping, memory }' "$1"
}

# median FIELD: of the CSV lines on standard input, the one with the median
# value of FIELD.
median() {
  local lines
  lines=$(sort -t, -k"$1,$1"g)
  echo "$lines" | awk -v n="$(echo "$lines" | wc -l)" 'NR == int((n + 1) / 2)'
}

# run_mpm PRM NAME THREADS [mpm arguments...]: one run of prm/PRM without
# output files, its log in $out/NAME.log.
run_mpm() {
  local prm="$1" name="$2" threads="$3"
  shift 3
  "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/$prm" --threads "$threads" "$@" \
    --set "Output/Write particles=false" \
    --set "Output/Write mesh=false" \
    --set "Output/Directory=$out/$name" > "$out/$name.log" 2>&1
}

if [ "$cases" != block ]; then
  csv="$MPM_ROOT/doc/throughput_3d.csv"
  echo "refinements,points_per_cell,cells,threads,steps,points,setup_wall_s,step_wall_s,particle_steps_per_s,$sections_header" > "$csv"
  for setting in "0 3 3.2" "1 3 0.3" "2 4 0.2"; do
    read -r refinements ppc end_time <<< "$setting"
    for threads in ${MPM_THREADS:-1}; do
      for r in $(seq "${MPM_REPEATS:-3}"); do
        name="landslide-r$refinements-p$ppc-t$threads-$r"
        run_mpm landslide_valley_3d.prm "$name" "$threads" \
          --set "Mesh/Global refinements=$refinements" \
          --set "Material points/slide/Points per cell=$ppc" \
          --set "Time stepping/End time=$end_time" \
          --set "Output/Write point file=false"
        cells=$(grep -o '3D, [0-9]* cells' "$out/$name.log" | awk '{print $2}')
        summarise "$out/$name.log" "$refinements,$ppc,$cells,$threads"
      done | median 9 | tee -a "$csv"
    done
  done
fi
[ "$cases" = landslide ] && exit 0

block_csv="$MPM_ROOT/doc/throughput_3d_block.csv"
echo "model,cells,threads,steps,points,setup_wall_s,step_wall_s,particle_steps_per_s,$sections_header" > "$block_csv"
for case in "linear elastic:linear" "mohr coulomb:linear" "linear elastic:cpdi"; do
  model="${case%:*}" weights="${case#*:}"
  label="$model"
  [ "$weights" = linear ] || label="$model ($weights)"
  for n in 12 23; do
    scheme=USF; flip=1
    if [ "$model" = "mohr coulomb" ]; then scheme=MUSL; flip=0; fi
    points=$(( 8 * n * n * n ))
    steps=$(awk -v n="$points" 'BEGIN { s = int(1.2e7 / n); print (s < 20 ? 20 : s) }')
    # dt = 0.5 h / c with c = 86.5 m/s (E 1e7, nu 0.3, rho 1800).
    end_time=$(awk -v n="$n" -v s="$steps" 'BEGIN { print s * 0.5 / n / 86.49 * 0.999 }')
    for threads in ${MPM_THREADS:-1}; do
      for r in $(seq "${MPM_REPEATS:-3}"); do
        name="block-3d-$model-$weights-$points-t$threads-$r"
        run_mpm throughput_3d.prm "$name" "$threads" \
          --set "Mesh/Generator arguments={$n, $n, $n} : 0, 0, 0 : 1, 1, 1 : true" \
          --set "Material points/block/Box=0, 0, 0 : 1, 1, 1" \
          --set "Materials/block/Model=$model" \
          --set "Transfer/Particle-grid weights=$weights" \
          --set "Time stepping/Update scheme=$scheme" \
          --set "Transfer/FLIP fraction=$flip" \
          --set "Time stepping/End time=$end_time"
        summarise "$out/$name.log" "$label,$(( n * n * n )),$threads"
      done | median 8 | tee -a "$block_csv"
    done
  done
done
