#!/usr/bin/env bash
# Set up everything (packages, Release build) and run one simulation.
# Usage: scripts/run.sh [file.prm] [extra mpm arguments, e.g. --set "Time stepping/End time=0.5"]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
prm="${1:-$MPM_ROOT/prm/sliding_block.prm}"
shift || true
# Meshes and point files are found relative to the .prm file; output goes
# to its Output/Directory relative to the current directory.
exec "$MPM_BUILD_DIR/mpm" "$prm" "$@"
