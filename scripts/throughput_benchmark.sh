#!/usr/bin/env bash
# Throughput (Release): particle-steps per second of the MPM step for linear
# elastic and Mohr-Coulomb from 1e3 to 1e6 points (prm/throughput.prm: a
# block of 2 x 2 points per cell on a fixed floor), split by the timer
# sections; then the same block with CPDI weights, and the same 1e4 points
# in a mesh with 100 times the cells (empty cells must cost nothing). The
# rate counts only the steps (mpm's 'Done' line), not the set-up; the last
# column is mpm's 'Peak memory' (the resident set's high-water mark,
# libraries included: the memory per point is the difference between two
# sizes over the difference of their points). Each case runs MPM_REPEATS
# times (default 3) and the run with the median rate is kept; MPM_THREADS
# lists the threads per run (default "1"; e.g. "1 2").
# Writes doc/throughput.csv.
# Usage: scripts/throughput_benchmark.sh [particle-steps per run, default 2.4e7]
# (each run takes max(20, that / points) steps: 2-3 s of stepping on one
# core of the machines in doc/performance.md, long enough to time)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
work="${1:-2.4e7}"
out="output-throughput"
mkdir -p "$out"
csv="$MPM_ROOT/doc/throughput.csv"
echo "model,points,cells,mesh_factor,threads,steps,step_wall_s,particle_steps_per_s,shape_functions_s,particle_to_grid_s,nodal_update_s,grid_to_particle_s,stress_update_s,locate_points_s,peak_memory_MiB" > "$csv"

# run_once MODEL POINTS MESH_FACTOR WEIGHTS THREADS: the block has POINTS points
# (2 x 2 per cell, side 1 m); the mesh is MESH_FACTOR times the block's
# cells per side, twice as wide as the block at least; WEIGHTS the
# particle-grid weights (linear, or cpdi: then the model column reads
# "MODEL (cpdi)"), on THREADS threads.
run_once() {
  local model="$1" points="$2" factor="$3" weights="$4" threads="$5"
  # Linear elastic: USF with FLIP. Mohr-Coulomb: the flume's MUSL with PIC
  # (with USF and FLIP the slumping block gains energy and the stability
  # check stops it at 0.8 s; doc/performance.md).
  local scheme=USF flip=1
  if [ "$model" = "mohr coulomb" ]; then scheme=MUSL; flip=0; fi
  local block_cells mesh_cells side h end_time name steps
  steps=$(awk -v w="$work" -v n="$points" 'BEGIN { s = int(w / n); print (s < 20 ? 20 : s) }')
  block_cells=$(awk -v n="$points" 'BEGIN { printf "%d", sqrt(n / 4) + 0.5 }')
  mesh_cells=$(( block_cells * factor ))
  side="$factor"
  # dt = 0.5 h / c with c = 86.5 m/s (E 1e7, nu 0.3, rho 1800).
  h=$(awk -v c="$block_cells" 'BEGIN { print 1 / c }')
  end_time=$(awk -v h="$h" -v s="$steps" 'BEGIN { print s * 0.5 * h / 86.49 * 0.999 }')
  name="$model-$points-$factor-$weights-$threads"
  "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/throughput.prm" --threads "$threads" \
    --set "Mesh/Generator arguments={$mesh_cells, $mesh_cells} : 0, 0 : $side, $side : true" \
    --set "Material points/block/Box=0, 0 : 1, 1" \
    --set "Materials/block/Model=$model" \
    --set "Time stepping/Update scheme=$scheme" \
    --set "Transfer/FLIP fraction=$flip" \
    --set "Transfer/Particle-grid weights=$weights" \
    --set "Time stepping/End time=$end_time" \
    --set "Output/Directory=$out/$name" > "$out/$name.log"
  local label="$model"
  [ "$weights" = linear ] || label="$model ($weights)"
  awk -v model="$label" -v points="$points" -v cells="$(( mesh_cells * mesh_cells ))" \
      -v factor="$factor" -v threads="$threads" '
    /^Done:/ { n_steps = $2; n_points = $4
               stepping = $0; sub(/.*\(steps /, "", stepping); sub(/ s\).*/, "", stepping) }
    /^Peak memory:/ { memory = $3 }
    /^\| / {
      split($0, f, "|"); name = f[2]; gsub(/^ +| +$/, "", name)
      t = f[4]; gsub(/[ s]/, "", t)
      sec[name] = t
    }
    END {
      # The wall time of the steps (printed by mpm), including the work
      # between the timed sections.
      rate = n_steps * n_points / stepping
      printf "%s,%d,%d,%d,%d,%d,%.4g,%.4g,%s,%s,%s,%s,%s,%s,%s\n", model, n_points, cells, factor,
        threads, n_steps, stepping, rate, sec["shape functions"], sec["particle to grid"],
        sec["nodal update"], sec["grid to particle"], sec["stress update"], sec["locate points"],
        memory
    }' "$out/$name.log"
}

# run MODEL POINTS MESH_FACTOR [WEIGHTS]: MPM_REPEATS runs for each number of
# threads in MPM_THREADS; the one with the median rate goes to the table.
run() {
  local weights="${4:-linear}" threads lines
  for threads in ${MPM_THREADS:-1}; do
    lines=$(for r in $(seq "${MPM_REPEATS:-3}"); do
      run_once "$1" "$2" "$3" "$weights" "$threads"
    done | sort -t, -k8,8g)
    echo "$lines" | awk -v n="$(echo "$lines" | wc -l)" 'NR == int((n + 1) / 2)' | tee -a "$csv"
  done
}

for model in "linear elastic" "mohr coulomb"; do
  for points in ${MPM_THROUGHPUT_POINTS:-1000 10000 100000 1000000}; do
    run "$model" "$points" 2
  done
done
# CPDI weights (doc/convergence.md): the same block, linear elastic.
for points in ${MPM_THROUGHPUT_POINTS:-1000 10000 100000 1000000}; do
  run "linear elastic" "$points" 2 cpdi
done
# Empty mesh: the same 1e4 points in a mesh with 100 times the cells.
run "linear elastic" 10000 20
run "mohr coulomb" 10000 20
