#!/usr/bin/env python3
"""Runout and final height of the granular column collapse against the aspect
ratio (doc/column_collapse.csv from scripts/column_collapse_sweep.sh), with
the runout law of Lube et al. 2005 as commonly quoted (doc/column_collapse.md).
Filled markers: the front point; open markers: the deposit thicker than 1 cm.
Usage: plot_column_collapse.py CSV PNG [LABEL [CSV2 LABEL2 ...]]
(LABEL names the run of CSV in the legend; further CSV / LABEL pairs add
series, e.g. the same sweep on a finer mesh.)"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

if len(sys.argv) < 3:
    sys.exit(__doc__)
png = sys.argv[2]
series = [(sys.argv[1], sys.argv[3] if len(sys.argv) > 3 else
           "dealii-mpm (Mohr-Coulomb, phi 32, mu 0.62)")]
series += list(zip(sys.argv[4::2], sys.argv[5::2]))

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
grid = [0.3 + 0.01 * i for i in range(800)]
grid = [x for x in grid if x <= 8]
lube = [1.2 * x if x < 2.3 else 1.9 * x ** (2 / 3) for x in grid]
ax1.loglog(grid, lube, "k-", label="Lube et al. 2005 (as quoted): 1.2 a; 1.9 a^(2/3)")
for i, (name, label) in enumerate(series):
    rows = sorted(csv.DictReader(open(name)), key=lambda r: float(r["a"]))
    a = [float(r["a"]) for r in rows]
    colour = f"C{3 + i}"
    ax1.loglog(a, [float(r["runout"]) for r in rows], "o", color=colour,
               label=f"{label}: front point")
    deposit = [(x, float(r["deposit_runout"])) for x, r in zip(a, rows)
               if r.get("deposit_runout") not in (None, "")]
    if deposit:
        ax1.loglog([x for x, _ in deposit], [y for _, y in deposit], "o",
                   mfc="none", color=colour, label=f"{label}: thicker than 1 cm")
    ax2.plot(a, [float(r["final_height_over_L0"]) for r in rows], "o-",
             color=colour, label=label)
ax1.set_xlabel("aspect ratio a = H0 / L0")
ax1.set_ylabel("runout (L_inf - L0) / L0")
ax1.legend(fontsize=7)
ax1.grid(True, which="both", alpha=0.3)
ax2.set_xlabel("aspect ratio a = H0 / L0")
ax2.set_ylabel("final height H_inf / L0")
ax2.grid(True, alpha=0.3)
if len(series) > 1:
    ax2.legend(fontsize=7)
fig.tight_layout()
fig.savefig(png, dpi=120)
print("wrote", png)
