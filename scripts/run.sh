#!/usr/bin/env bash
# Set up everything (packages, Release build) and run one simulation.
# Usage: scripts/run.sh [file.prm] [extra mpm arguments, e.g. --set "Time stepping/End time=0.5"]
# The flume's figures (scripts/plot_flume.py) are written into its output
# directory.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
prm="${1:-$MPM_ROOT/prm/sliding_block.prm}"
shift || true
# Meshes and point files are found relative to the .prm file; output goes
# to its Output/Directory relative to the current directory.
"$MPM_BUILD_DIR/mpm" "$prm" "$@"
# Cases with a plotting script get their figures in their output directory.
parameters=$("$MPM_BUILD_DIR/mpm" --print-parameters "$prm" "$@")
outdir=$(echo "$parameters" | sed -nE 's/^ *set Directory *= *([^#]*[^ #]).*/\1/p' | head -1)
postprocessors=$(echo "$parameters" | sed -nE 's/^ *set List of postprocessors *= *([^#]*).*/\1/p')
if [[ "$postprocessors" == *"hazard rasters"* ]] && [ -x /usr/bin/python3 ]; then
  # The elevation model, relative to the first .prm file's folder.
  dem=$(echo "$parameters" | sed -nE 's/^ *set Elevation model *= *([^#]*[^ #]).*/\1/p' | head -1)
  [[ "$dem" == /* ]] || dem="$(dirname "$prm")/$dem"
  /usr/bin/python3 "$MPM_ROOT/scripts/plot_hazard_rasters.py" "$outdir" "$dem" || echo "(plotting failed: is python3-matplotlib installed?)"
fi
if [[ "$postprocessors" == *flume* ]] && python3_plot=/usr/bin/python3 && [ -x "$python3_plot" ]; then
  "$python3_plot" "$MPM_ROOT/scripts/plot_flume.py" "$outdir" "$outdir" || echo "(plotting failed: is python3-matplotlib installed?)"
fi
