#!/usr/bin/env python3
"""Error against wall time from doc/speed_error.csv (scripts/speed_error_sweep.sh):
one curve per varied parameter, each point labelled with its value.
Usage: plot_speed_error.py CSV PNG"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
for column, ax, label in [("vcm_error", axes[0], "max |v_cm error| / (2 v0 / pi)"),
                          ("period_error", axes[1], "|period error| / period")]:
    for parameter in dict.fromkeys(r["parameter"] for r in rows):
        sel = [r for r in rows
               if r["parameter"] == parameter and r[column] not in ("", "unstable")]
        t = [float(r["step_wall_s"]) for r in sel]
        e = [abs(float(r[column])) for r in sel]
        ax.loglog(t, e, "o-", label=parameter)
        for r, x, y in zip(sel, t, e):
            ax.annotate(r["value"], (x, y), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel("wall time of the steps (s, one core)")
    ax.set_ylabel(label)
    ax.grid(True, which="both", alpha=0.3)
axes[0].legend(fontsize=8)
fig.suptitle("vibrating bar: error against cost, one parameter varied at a time from 26 cells, 2x2 points, CFL 0.5, USF, FLIP")
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=120)
print("wrote", sys.argv[2])
