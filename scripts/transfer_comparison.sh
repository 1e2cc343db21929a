#!/usr/bin/env bash
# The velocity transfers side by side on the two granular scenes
# (doc/transfers.md): the USGS flume (peak mean speed and its time, time to
# rest, final front) and the column collapse at a = 2 (runout against
# Lube et al. 2005, time to rest), each with the wall time on one core.
# Every scheme on linear weights (the rows of doc/transfers.md, "The flume
# and the collapse at a = 2, per scheme on linear weights"), and the
# default, APIC on CPDI weights, last.
# Usage: scripts/transfer_comparison.sh [output folder]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
out="${1:-output-transfer-comparison}"
mkdir -p "$out"
schemes=(
  "pic|--set|Transfer/Scheme=flip/pic blend|--set|Transfer/FLIP fraction=0"
  "flip0.9|--set|Transfer/Scheme=flip/pic blend|--set|Transfer/FLIP fraction=0.9"
  "flip0.95|--set|Transfer/Scheme=flip/pic blend|--set|Transfer/FLIP fraction=0.95"
  "flip0.98|--set|Transfer/Scheme=flip/pic blend|--set|Transfer/FLIP fraction=0.98"
  "flip0.99|--set|Transfer/Scheme=flip/pic blend|--set|Transfer/FLIP fraction=0.99"
  "xpic2|--set|Transfer/Scheme=xpic|--set|Transfer/XPIC order=2"
  "xpic5|--set|Transfer/Scheme=xpic|--set|Transfer/XPIC order=5"
  "apic|--set|Transfer/Scheme=apic"
  "apic_cpdi|--set|Transfer/Scheme=apic|--set|Transfer/Particle-grid weights=cpdi"
)
wall() { grep -o 'wall time [0-9.e+-]* s' "$1" | awk '{print $3}'; }
field() { grep "^$2" "$1" 2>/dev/null | sed -E "s|$3|\1|" || true; }
echo "scheme | flume peak (m/s) | at (s) | rest from (s) | final front s (m) | wall (s) | collapse a=2 runout | / Lube | rest from (s) | wall (s)"
for entry in "${schemes[@]}"; do
  IFS='|' read -r -a parts <<< "$entry"
  name="${parts[0]}"
  # Linear weights, the blend's per-step fraction of the shipped files'
  # former blend, unless the row sets them.
  args=(--set "Transfer/Particle-grid weights=linear" --set "Transfer/FLIP fraction time step=0"
        "${parts[@]:1}")
  "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/flume_usgs.prm" "${args[@]}" \
    --set "Output/Write particles=false" --set "Output/Directory=$out/flume-$name" \
    > "$out/flume-$name.log" 2>&1 || true
  # 2 x 2 points per cell, those of doc/transfers.md's table (the shipped
  # file has 3 x 3).
  "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/column_collapse.prm" "${args[@]}" \
    --set "Material points/column/Points per cell=2" --set "Output/Write particles=false" --set "Output/Directory=$out/collapse-$name" \
    > "$out/collapse-$name.log" 2>&1 || true
  f="$out/flume-$name/report.txt"
  c="$out/collapse-$name/report.txt"
  if [ -f "$f" ]; then
    flume="$(field "$f" 'peak mean speed' '.*: ([0-9.e+-]+) m/s.*') | $(field "$f" 'peak mean speed' '.*t = ([0-9.e+-]+) s.*') | $(field "$f" 'mean speed below' '.*t = ([0-9.e+-]+) s on.*') | $(field "$f" 'final front' '^final front: s = ([0-9.e+-]+) m.*') | $(wall "$out/flume-$name.log")"
  else
    flume="stopped: $(grep -o 'left the mesh\|unstable' "$out/flume-$name.log" | head -1) | | | |"
  fi
  if [ -f "$c" ]; then
    runout=$(field "$c" 'runout' '.*: *([0-9.e+-]+).*')
    collapse="$runout | $(awk -v r="$runout" 'BEGIN{printf "%.2f", r/2.4}') | $(field "$c" 'mean speed below' '.*t = ([0-9.e+-]+) s on.*') | $(wall "$out/collapse-$name.log")"
  else
    collapse="stopped: $(grep -o 'left the mesh\|unstable' "$out/collapse-$name.log" | head -1) | | |"
  fi
  echo "$name | $flume | $collapse"
done
