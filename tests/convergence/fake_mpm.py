#!/usr/bin/env python3
"""A stand-in for mpm with known convergence, for the test of
scripts/convergence.py: with 'Mesh/Global refinements = k' (cell size
h = 2^-k) it reports quantities whose error is exactly C h^p, an
oscillating one, one that does not change and one whose differences grow,
a statistics file and the 'Done:' line. '--print-parameters' gives the
scene's own refinement level, 1, and its CFL number, 0.5; the second-order
quantity also has a time-step error 4 (CFL - 0.5) h, zero at the scene's
own CFL number. With 'Material points/block/Points per cell = n' (2 in
the scene) the first-order quantity has a points-per-cell error
0.25 (n - 2) h and the point count grows as n^2."""
import os
import sys

args = sys.argv[1:]
if "--print-parameters" in args:
    print("subsection Mesh\n  set Global refinements = 1\nend\n"
          "subsection Time stepping\n  set Time step selection = cfl\n"
          "  set CFL number = 0.5\nend\n"
          "subsection Material points\n  set List of regions = block\n"
          "  subsection block\n    set Points per cell = 2\n  end\nend")
    sys.exit(0)
settings = dict(a.split("=", 1) for a in args if "=" in a and "/" in a.split("=")[0])
k = int(settings["Mesh/Global refinements"])
out = settings["Output/Directory"]
os.makedirs(out, exist_ok=True)
h = 2.0 ** -k
cfl = float(settings.get("Time stepping/CFL number", 0.5))
n = int(settings.get("Material points/block/Points per cell", 2))
with open(os.path.join(out, "report.txt"), "w") as report:
    report.write("# fake report\n## known orders: h = 2^-k\n")
    report.write(f"second order, 3 + 2 h^2: {3 + 2 * h * h + 4 * (cfl - 0.5) * h!r}\n")
    report.write(f"first order (m), 1 - 0.5 h: {1 - 0.5 * h + 0.25 * (n - 2) * h!r} m  exact: 1\n")
    report.write(f"oscillating: {1 + (-1) ** k * h!r}\n")
    report.write(f"unchanged: 7\n")
    report.write(f"growing: {2.0 ** k!r}\n")
    report.write("# time  value\n    0    1\n")
with open(os.path.join(out, "statistics"), "w") as stats:
    stats.write("# Columns: 1 time (s), 2 step, 3 mean speed (m/s), 4-5 centre of mass (m). Energies per unit thickness in 2D.\n")
    for i, t in enumerate((0.0, 0.5, 1.0)):
        stats.write(f"{t} {i} {t * (1 - t) + h} {0.5} {0.25 + h ** 1.5}\n")
print(f"Done: {2 ** k * 10} steps, {4 ** k * 25 * n * n} points, wall time {k + 1.5} s (steps {k + 1.0} s), 1e6 particle-steps/s in the steps")
