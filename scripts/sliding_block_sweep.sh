#!/usr/bin/env bash
# The paper's Figure 5: the sliding block (prm/sliding_block.prm) for
# mu = 0, 0.1, ..., 0.5 and a sticking case (mu = 0.6 > tan 30), started at
# rest in its settled sliding state (a first run of 0.3 s writes it), then
# the plot doc/sliding_block.png and the table doc/sliding_block_errors.txt.
# Usage: scripts/sliding_block_sweep.sh [output folder, default output-sliding-block-sweep]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
out="${1:-output-sliding-block-sweep}"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
tan30=0.5773502691896258
for mu in 0 0.1 0.2 0.3 0.4 0.5 0.6; do
  # The block starts in the stress of a rigid block sliding with friction mu,
  # or in static equilibrium (shear = tan 30 x normal) if it sticks; that
  # run ("rigid-mu-*", 0.8 s) shows the elastic block's start-up offset.
  # The figure's runs ("mu-*") start at rest from the stress state that
  # the block reaches after sliding 0.3 s (doc/validation.md).
  stress_mu=$(awk -v m="$mu" -v t="$tan30" 'BEGIN { print (m < t ? m : t) }')
  common=(--set "Boundary conditions/bed/Friction coefficient=$mu"
          --set "Material points/block/Initial stress function/Function constants=rho=1800, g=9.81, th=0.5235987755982988, mu=$stress_mu"
          --set "Postprocess/sliding block/Error from time=0"
          --set "Output/Output interval=0.02")
  "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/sliding_block.prm" "${common[@]}" \
    --set "Output/Directory=$out/rigid-mu-$mu" > "$out/rigid-mu-$mu.log"
  "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/sliding_block.prm" "${common[@]}" \
    --set "Time stepping/End time=0.3" --set "Output/Write point file=true" \
    --set "Output/Directory=$out/settling-mu-$mu" > "$out/settling-mu-$mu.log"
  "$MPM_BUILD_DIR/mpm" "$MPM_ROOT/prm/sliding_block.prm" "${common[@]}" \
    --set "Material points/block/Type=file" \
    --set "Material points/block/Point file=$out/settling-mu-$mu/points_end.txt" \
    --set "Material points/block/Initial stress=file" \
    --set "Output/Directory=$out/mu-$mu" > "$out/mu-$mu.log"
  # The report gives the relative speed error of a sliding block; for
  # mu >= tan 30 the block sticks (exact speed 0) and it gives the absolute
  # one ("max abs speed error ...") instead.
  rigid=$(sed -n 's/^max relative speed error.*: //p' "$out/rigid-mu-$mu/report.txt")
  if [ -z "$rigid" ]; then
    rigid="sticks (mu >= tan 30 deg), max abs speed error $(sed -n 's/^max abs speed error.*: //p' "$out/rigid-mu-$mu/report.txt") m/s"
  fi
  echo "mu = $mu: rigid-block start: $rigid; settled start: $(tail -2 "$out/mu-$mu/report.txt" | tr '\n' ' ')"
done
/usr/bin/python3 "$MPM_ROOT/scripts/plot_sliding_block.py" "$out" "$MPM_ROOT/doc"
