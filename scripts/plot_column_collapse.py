#!/usr/bin/env python3
"""Runout and final height of the granular column collapse against the aspect
ratio (doc/column_collapse.csv from scripts/column_collapse_sweep.sh), with
the runout law of Lube et al. 2005 as commonly quoted (doc/column_collapse.md).
Usage: plot_column_collapse.py CSV PNG"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
a = [float(r["a"]) for r in rows]
runout = [float(r["runout"]) for r in rows]
height = [float(r["final_height_over_L0"]) for r in rows]

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
grid = [0.3 + 0.01 * i for i in range(800)]
grid = [x for x in grid if x <= 8]
lube = [1.2 * x if x < 2.3 else 1.9 * x ** (2 / 3) for x in grid]
ax1.loglog(grid, lube, "k-", label="Lube et al. 2005 (as quoted): 1.2 a; 1.9 a^(2/3)")
ax1.loglog(a, runout, "o", color="C3", label="dealii-mpm (Mohr-Coulomb, phi 32, mu 0.62)")
ax1.set_xlabel("aspect ratio a = H0 / L0")
ax1.set_ylabel("runout (L_inf - L0) / L0")
ax1.legend(fontsize=8)
ax1.grid(True, which="both", alpha=0.3)
ax2.plot(a, height, "o-", color="C3")
ax2.set_xlabel("aspect ratio a = H0 / L0")
ax2.set_ylabel("final height H_inf / L0")
ax2.grid(True, alpha=0.3)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
print("wrote", sys.argv[2])
