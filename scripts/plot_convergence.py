#!/usr/bin/env python3
"""The vibrating bar's centre-of-mass velocity error against the cells per
metre, linear and CPDI weights, regular and 30 %-distorted meshes
(doc/convergence_bar.csv from scripts/convergence_sweep.sh); unstable runs
are marked at the top. Left: error against n; right: error against the wall
time of the steps (cost). Third panel: the self-weight column at large
strain (doc/convergence_column.csv): the L2 error of sigma_yy against the
cells across the column, both weights.
Usage: plot_convergence.py BAR_CSV COLUMN_CSV PNG"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
column_rows = list(csv.DictReader(open(sys.argv[2])))
fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(16, 4.2))
styles = {("linear", "0"): ("C0", "o-"), ("linear", "0.3"): ("C0", "s--"),
          ("cpdi", "0"): ("C3", "o-"), ("cpdi", "0.3"): ("C3", "s--")}
top = 0.5
for (weights, distortion), (colour, style) in styles.items():
    ok = [r for r in rows if r["weights"] == weights and r["distortion"] == distortion
          and r["status"] == "ok"]
    bad = [r for r in rows if r["weights"] == weights and r["distortion"] == distortion
           and r["status"] != "ok"]
    label = f"{weights}, distortion {float(distortion):.0%}"
    n = [float(r["n"]) for r in ok]
    err = [float(r["max_vcm_error"]) for r in ok]
    wall = [float(r["step_wall_s"]) for r in ok]
    ax1.loglog(n, err, style, color=colour, label=label)
    ax2.loglog(wall, err, style, color=colour, label=label)
    if bad:
        ax1.loglog([float(r["n"]) for r in bad], [top] * len(bad), "x", color=colour,
                   markersize=10, label=f"{label}: unstable")
ax1.set_xlabel("cells per metre n")
ax1.set_ylabel("max |v_cm error| / (2 v0 / pi)")
ax1.set_title("vibrating bar: error under refinement")
ax1.grid(True, which="both", alpha=0.3)
ax1.legend(fontsize=7)
ax2.set_xlabel("wall time of the steps (s, one core)")
ax2.set_ylabel("max |v_cm error| / (2 v0 / pi)")
ax2.set_title("error against cost")
ax2.grid(True, which="both", alpha=0.3)
for weights, colour in (("linear", "C0"), ("cpdi", "C3")):
    ok = [r for r in column_rows if r["weights"] == weights and r["status"] == "ok"
          and r["l2_error"]]
    ax3.loglog([float(r["n"]) for r in ok], [float(r["l2_error"]) for r in ok], "o-",
               color=colour, label=weights)
ns = [5, 80]
ax3.loglog(ns, [0.05 * (5 / n) for n in ns], "k:", label="first order")
ax3.set_xlabel("cells across the column")
ax3.set_ylabel("L2 error of sigma_yy / exact")
ax3.set_title("self-weight column, 21 % settlement")
ax3.grid(True, which="both", alpha=0.3)
ax3.legend(fontsize=7)
fig.tight_layout()
fig.savefig(sys.argv[3], dpi=110)
