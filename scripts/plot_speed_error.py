#!/usr/bin/env python3
"""Error against wall time from doc/speed_error.csv (scripts/speed_error_sweep.sh):
one panel per scene, one curve per varied parameter, each point labelled
with its value. Usage: plot_speed_error.py CSV PNG"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
scenes = list(dict.fromkeys(r["scene"] for r in rows))
# Two panels a row, so that the figure stays readable at page width.
n_columns = 2
n_rows = math.ceil(len(scenes) / n_columns)
fig, axes = plt.subplots(n_rows, n_columns, figsize=(11, 4.3 * n_rows), squeeze=False)
for ax in axes.flat[len(scenes):]:
    ax.set_visible(False)
for ax, scene in zip(axes.flat, scenes):
    scene_rows = [r for r in rows if r["scene"] == scene]
    for parameter in dict.fromkeys(r["parameter"] for r in scene_rows):
        sel = [r for r in scene_rows
               if r["parameter"] == parameter and r["error"] not in ("", "unstable")]
        t = [float(r["step_wall_s"]) for r in sel]
        e = [abs(float(r["error"])) for r in sel]
        ax.loglog(t, e, "o-", label=parameter)
        for r, x, y in zip(sel, t, e):
            ax.annotate(r["value"], (x, y), fontsize=8, xytext=(3, 3), textcoords="offset points")
    ax.set_title(scene.replace("_", " "), fontsize=11)
    ax.set_xlabel("wall time of the steps (s, one core)")
    ax.set_ylabel(scene_rows[0]["error_measure"])
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
fig.suptitle("error against cost, one parameter varied at a time from each shipped case",
             fontsize=12)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=110)
print("wrote", sys.argv[2])
