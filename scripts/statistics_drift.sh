#!/usr/bin/env bash
# How far a change of arithmetic (a summation order, a shortcut) moves a
# run: the same case with the saved build in DIR (a copy of
# build/release/mpm and build/release/libmpm-core.so made before the
# change, as for compare_builds.sh) and with the current build/release,
# the statistics written every step, and for each of a few steps the
# largest relative difference over the statistics' columns (each column
# relative to its largest magnitude in the run). A change at round-off
# starts near 1e-16 and grows only as fast as the case amplifies
# perturbations.
#
# PRM may be a test's .prm with a "# base: FILE" line (the chain of bases
# is read first, as tests/run_test.cmake does).
#
# Usage: scripts/statistics_drift.sh DIR PRM [END_TIME] [--set ...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
base="$(cd "${1:?usage: statistics_drift.sh DIR PRM [END_TIME] [--set ...]}" && pwd)"
prm="$(realpath "${2:?usage: statistics_drift.sh DIR PRM [END_TIME] [--set ...]}")"
shift 2
end=()
if [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; then end=(--set "Time stepping/End time=$1"); shift; fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# The chain of "# base:" files, the first base first.
chain=("$prm")
while base_file=$(sed -n 's/^# base:[ ]*//p' "${chain[0]}" | head -1) && [ -n "$base_file" ]; do
  chain=("$(dirname "${chain[0]}")/$base_file" "${chain[@]}")
done
cat "${chain[@]}" > "$work/case.prm"
for build in base current; do
  dir="$base"; [ "$build" = current ] && dir="$root/build/release"
  (cd "$(dirname "$prm")" &&
     LD_LIBRARY_PATH="$dir" "$dir/mpm" "$work/case.prm" --threads 1 "${end[@]}" "$@" \
       --set "Output/Output interval=0" --set "Output/Write particles=false" \
       --set "Output/Directory=$work/$build" > "$work/$build.log" 2>&1) ||
    { echo "statistics_drift.sh: the $build run failed:" >&2; tail -5 "$work/$build.log" >&2; exit 1; }
done
python3 - "$work/base/statistics" "$work/current/statistics" <<'PY'
import sys
def read(name):
    return [list(map(float, l.split())) for l in open(name) if l.strip() and not l.startswith('#')]
a, b = read(sys.argv[1]), read(sys.argv[2])
n = min(len(a), len(b))
if len(a) != len(b):
    print(f"different numbers of steps: {len(a)} and {len(b)} lines; comparing the first {n}")
scale = [max(abs(r[j]) for r in a[:n]) or 1. for j in range(len(a[0]))]
names = {}
for l in open(sys.argv[1]):
    if l.startswith('# Columns:'):
        import re
        for m in re.finditer(r'(\d+)(?:-(\d+))? ([^,]+)', l[len('# Columns:'):]):
            first, last = int(m.group(1)), int(m.group(2) or m.group(1))
            for c in range(first, last + 1):
                names[c] = m.group(3).strip() + (f" {c - first + 1}" if last > first else "")
print("step  time  largest relative difference (its column), kinetic energy, centre of mass y")
ke = next((c for c, n in names.items() if n.startswith('kinetic')), 8) - 1
cy = next((c for c, n in names.items() if n.startswith('centre of mass') and n.endswith(' 2')), 13) - 1
shown = sorted(set([1, 2, 5, 10] + [int(n * f) for f in (0.1, 0.25, 0.5, 0.75, 0.8, 0.85, 0.9, 0.95)] + [n - 1]))
for i in shown:
    if i >= n: continue
    d = [abs(a[i][j] - b[i][j]) / scale[j] for j in range(2, len(a[i]))]
    j = max(range(len(d)), key=lambda k: d[k])
    rel = lambda c: abs(a[i][c] - b[i][c]) / scale[c]
    print(f"{int(a[i][1]):6d} {a[i][0]:.6g} {d[j]:.2e} ({names.get(j + 3, j + 3)}) {rel(ke):.2e} {rel(cy):.2e}")
PY
