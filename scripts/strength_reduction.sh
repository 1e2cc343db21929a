#!/usr/bin/env bash
# The factor of safety of a slope by shear strength reduction
# (doc/slope_stability.md): runs PRM (a file with the 'slope stability'
# postprocessor, e.g. prm/slope_stability.prm) with constant strength
# reduction factors F ('Materials/Strength reduction factor') and bisects F
# between LOW (must come out stable) and HIGH (must fail) until the bracket
# is narrower than TOL. Each run's answer is the postprocessor's: failed if
# the crest point has not come to rest by the end of the run.
# Every run is a line of the CSV (F, answer, crest displacement, crest
# speed, points, wall time); the last line of the output is the bracket.
# Usage: scripts/strength_reduction.sh PRM LOW HIGH [TOL=0.005] [extra mpm arguments...]
# Environment: MPM_SRM_NAME (default: the prm file's name): the output
#   folder output-srm-NAME and the CSV doc/slope_stability_NAME.csv;
#   MPM_SRM_FACTORS="1.3 1.35 ...": run just these factors (the curve of
#   crest displacement against F) instead of the bisection.
# Example (the three meshes of doc/slope_stability.md):
#   for r in 0 1 2; do MPM_SRM_NAME=srm_r$r scripts/strength_reduction.sh \
#     prm/slope_stability.prm 1.2 1.6 0.005 --set "Mesh/Global refinements=$r"; done
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
mpm_setup Release
[ $# -ge 3 ] || { sed -n 2,21p "$0"; exit 1; }
prm="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
low="$2"; high="$3"; tol="${4:-0.005}"
shift 3; [ $# -gt 0 ] && shift
name="${MPM_SRM_NAME:-$(basename "$prm" .prm)}"
out="output-srm-$name"
csv="$MPM_ROOT/doc/slope_stability_$name.csv"
mkdir -p "$out"
echo "F,answer,crest_displacement_m,crest_speed_m_per_s,points,wall_s" > "$csv"

# run F: prints 'failed' or 'stable' and appends the CSV line.
run() {
  local F="$1" dir="$out/F-$1"
  shift
  "$MPM_BUILD_DIR/mpm" "$prm" \
    --set "Materials/Strength reduction factor=$F" \
    --set "Output/Write particles=false" \
    --set "Output/Directory=$dir" "$@" > "$dir.log" 2>&1 ||
    { echo "mpm failed for F = $F, see $dir.log" >&2; exit 1; }
  local report="$dir/report.txt" answer speed displacement done_line
  answer=$(grep -oE "^slope (failed|stable)" "$report" | awk '{print $2}')
  speed=$(grep -E "^slope (failed|stable)" "$report" | sed -E 's/.* moves at ([^ ]+) m\/s.*/\1/')
  displacement=$(grep "^crest displacement at the end" "$report" | sed -E 's/.*: //')
  done_line=$(grep '^Done:' "$dir.log")
  echo "$F,$answer,$displacement,$speed,$(echo "$done_line" | awk '{print $4}'),$(echo "$done_line" | sed -E 's/.*wall time ([0-9.e+-]+) s.*/\1/')" >> "$csv"
  echo "F = $F: $answer (crest displacement $displacement m, speed $speed m/s)" >&2
  echo "$answer"
}

# answer F: run F and print its answer; a run that gave none (mpm failed
# inside the command substitution) stops the script.
answer() {
  local a
  a=$(run "$@") || true
  case "$a" in
    stable|failed) echo "$a" ;;
    *) echo "no answer for F = $1 (see $out/F-$1.log)" >&2; exit 1 ;;
  esac
}

if [ -n "${MPM_SRM_FACTORS:-}" ]; then
  for F in $MPM_SRM_FACTORS; do answer "$F" "$@" > /dev/null; done
  exit 0
fi
result=$(answer "$low" "$@")
[ "$result" = stable ] || { echo "F = $low already fails: lower LOW" >&2; exit 1; }
result=$(answer "$high" "$@")
[ "$result" = failed ] || { echo "F = $high is still stable: raise HIGH" >&2; exit 1; }
while awk -v a="$low" -v b="$high" -v t="$tol" 'BEGIN { exit !(b - a > t) }'; do
  mid=$(awk -v a="$low" -v b="$high" 'BEGIN { printf "%.6g", (a + b) / 2 }')
  result=$(answer "$mid" "$@")
  if [ "$result" = stable ]; then low="$mid"; else high="$mid"; fi
done
echo "factor of safety in [$low, $high] ($(basename "$prm") $*)"
