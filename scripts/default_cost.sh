#!/usr/bin/env bash
# What the default transfer (APIC on CPDI weights under MUSL) costs against
# the cheaper FLIP/PIC blend on linear weights, side by side: each case run
# alternately on both paths, one thread, the minimum over N runs of the wall
# time of the steps (mpm's 'Done' line), and the ratio default / blend
# against the most it may cost (the flume 1.3, the 2D throughput block 2,
# the 3D landslide 1.5). Release build.
#
# Cases: flume      prm/flume_usgs.prm to 0.3 s (CFL 0.5);
#        block      prm/throughput.prm, 1e5 points (158 x 158 cells, 2 x 2
#                   points per cell, linear elastic, 241 steps);
#        landslide  prm/landslide_valley_3d.prm refined once, 3 x 3 x 3
#                   points per cell, to 0.3 s.
# The default includes the cell's mean volumetric strain rate ('Volumetric
# strain averaging = cell'). The blend: FLIP 0.98 per the file's CFL 0.5
# step ('FLIP fraction time step') on linear weights under MUSL, without
# the averaging, as the granular files shipped it; on the block the paper
# code's path (FLIP 1 on linear weights under USF).
#
# Usage: scripts/default_cost.sh [N (default 3)] [CASE ...]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
n="${1:-3}"
shift || true
cases=("$@")
[ ${#cases[@]} -gt 0 ] || cases=(flume block landslide)
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

default="Transfer/Scheme=apic|Transfer/Particle-grid weights=cpdi|Time stepping/Update scheme=MUSL|Time stepping/Volumetric strain averaging=cell"
blend="Transfer/Scheme=flip/pic blend|Transfer/FLIP fraction=0.98|Transfer/Particle-grid weights=linear|Time stepping/Update scheme=MUSL|Time stepping/Volumetric strain averaging=none"
# spec CASE PATH: the prm file and its settings, '|'-separated; then the bound.
spec() {
  case "$1" in
    flume) echo "flume_usgs.prm|Time stepping/End time=0.3|${2/FLIPDT/3.3e-5}" ;;
    block) echo "throughput.prm|Mesh/Generator arguments={158, 158} : 0, 0 : 1, 1 : true|Material points/block/Box=0, 0 : 1, 1|Materials/block/Model=linear elastic|Time stepping/End time=0.0088|$2" ;;
    landslide) echo "landslide_valley_3d.prm|Mesh/Global refinements=1|Material points/slide/Points per cell=3|Time stepping/End time=0.3|Output/Write point file=false|${2/FLIPDT/0.023}" ;;
    *) echo "default_cost.sh: unknown case '$1'" >&2; exit 1 ;;
  esac
}
bound() { case "$1" in flume) echo 1.3 ;; block) echo 2 ;; landslide) echo 1.5 ;; esac; }

# run CASE PATH_SETTINGS NAME: prints "steps points seconds".
run() {
  local args=()
  IFS='|' read -r -a fields <<< "$(spec "$1" "$2")"
  for f in "${fields[@]:1}"; do args+=(--set "$f"); done
  "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/${fields[0]}" --threads 1 "${args[@]}" \
    --set "Output/Write particles=false" --set "Output/Write mesh=false" \
    --set "Output/Directory=$work/$3" > "$work/$3.log" 2>&1 ||
    { echo "default_cost.sh: the run $3 failed, see its log:" >&2; tail -5 "$work/$3.log" >&2; exit 1; }
  mpm_done_figures "$work/$3.log"
}

mpm_benchmark_header
printf '%-10s %8s %14s %14s %12s %12s %8s %6s\n' case points "blend (s)" "default (s)" "blend p-s/s" "default p-s/s" ratio bound
for c in "${cases[@]}"; do
  flip_blend="$blend|Transfer/FLIP fraction time step=FLIPDT"
  [ "$c" = block ] && flip_blend="Transfer/Scheme=flip/pic blend|Transfer/FLIP fraction=1|Transfer/Particle-grid weights=linear|Time stepping/Update scheme=USF|Time stepping/Volumetric strain averaging=none"
  b_min="" d_min=""
  for i in $(seq "$n"); do
    read -r b_steps points t <<< "$(run "$c" "$flip_blend" "$c-blend-$i")"
    b_min=$(printf '%s\n' $b_min "$t" | sort -g | head -1)
    read -r d_steps points t <<< "$(run "$c" "$default" "$c-default-$i")"
    d_min=$(printf '%s\n' $d_min "$t" | sort -g | head -1)
  done
  awk -v c="$c" -v p="$points" -v bs="$b_steps" -v ds="$d_steps" -v b="$b_min" -v d="$d_min" -v bound="$(bound "$c")" 'BEGIN {
    printf "%-10s %8d %14.3g %14.3g %12.3g %12.3g %8.2f %6s\n", c, p, b, d, p * bs / b, p * ds / d, d / b, bound }'
done
