#!/usr/bin/env python3
"""Plot the sliding-block sweep (scripts/sliding_block_sweep.sh): mean speed
against time for each mu with the analytical lines (the paper's Figure 5),
and the relative speed error; write the error table beside the plot.
Usage: plot_sliding_block.py SWEEP_FOLDER DOC_FOLDER"""
import glob
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

sweep, doc = sys.argv[1], sys.argv[2]
runs = []
for report in glob.glob(os.path.join(sweep, "mu-*", "report.txt")):
    text = open(report).read()
    mu = float(re.search(r"mu = ([0-9.e-]+),", text).group(1))
    a = float(re.search(r"= ([0-9.e-]+) m/s\^2", text).group(1))
    rows = [list(map(float, l.split())) for l in text.splitlines()
            if l and l[0] == " "]
    runs.append((mu, a, rows))
runs.sort()

fig, (ax, ax_err) = plt.subplots(1, 2, figsize=(11, 4.2))
table = ["# mu  a exact (m/s^2)  max |rel speed error| t>=0.1 s  "
         "at t=0.8 s  (sticking: abs speed m/s, abs distance m)"]
for mu, a, rows in runs:
    t = [r[0] for r in rows]
    v = [r[1] for r in rows]
    line, = ax.plot(t, v, "o", ms=3, label=f"mu = {mu:g}")
    ax.plot(t, [a * x for x in t], "-", color=line.get_color(), lw=0.8)
    late = [r for r in rows if r[0] >= 0.1 - 1e-9]
    if a > 0:
        errors = [abs(r[3]) for r in late]
        ax_err.semilogy([r[0] for r in late], [max(e, 1e-16) for e in errors],
                        "-", color=line.get_color(), label=f"mu = {mu:g}")
        table.append(f"{mu:4g}  {a:8.4f}  {max(errors):10.3e}  "
                     f"{abs(late[-1][3]):10.3e}")
    else:
        table.append(f"{mu:4g}  {a:8.4f}  sticks: max speed "
                     f"{max(r[1] for r in late):.2e} m/s, distance at 0.8 s "
                     f"{late[-1][4]:.2e} m")
ax.set_xlabel("time (s)")
ax.set_ylabel("mean speed of the block (m/s)")
ax.set_title("Sliding block, 30 deg: MPM (points), analytical (lines)")
ax.legend(fontsize=8)
ax_err.set_xlabel("time (s)")
ax_err.set_ylabel("|relative speed error|")
ax_err.axhline(1e-4, color="k", ls=":", lw=0.8)
ax_err.set_title("relative error of the mean speed (target 1e-4 dotted)")
ax_err.legend(fontsize=8)
fig.tight_layout()
fig.savefig(os.path.join(doc, "sliding_block.png"), dpi=120)
with open(os.path.join(doc, "sliding_block_errors.txt"), "w") as f:
    f.write("\n".join(table) + "\n")
print("\n".join(table))
