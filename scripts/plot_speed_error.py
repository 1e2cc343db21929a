#!/usr/bin/env python3
"""Error against wall time from doc/speed_error.csv (scripts/speed_error_sweep.sh):
one panel per scene, one curve per varied parameter, each point labelled
with its value. Usage: plot_speed_error.py CSV PNG"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
scenes = list(dict.fromkeys(r["scene"] for r in rows))
fig, axes = plt.subplots(1, len(scenes), figsize=(5.5 * len(scenes), 4.5), squeeze=False)
for ax, scene in zip(axes[0], scenes):
    scene_rows = [r for r in rows if r["scene"] == scene]
    for parameter in dict.fromkeys(r["parameter"] for r in scene_rows):
        sel = [r for r in scene_rows
               if r["parameter"] == parameter and r["error"] not in ("", "unstable")]
        t = [float(r["step_wall_s"]) for r in sel]
        e = [abs(float(r["error"])) for r in sel]
        ax.loglog(t, e, "o-", label=parameter)
        for r, x, y in zip(sel, t, e):
            ax.annotate(r["value"], (x, y), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.set_title(scene, fontsize=10)
    ax.set_xlabel("wall time of the steps (s, one core)")
    ax.set_ylabel(scene_rows[0]["error_measure"])
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
fig.suptitle("error against cost, one parameter varied at a time from each shipped case")
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
print("wrote", sys.argv[2])
