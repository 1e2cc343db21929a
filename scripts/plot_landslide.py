#!/usr/bin/env python3
"""Map of the 3D landslide of prm/landslide_valley_3d.prm: ground contours
from the elevation model, the released layer's footprint, and the deposit
(points_end.txt of the run, coloured by the height above the ground
model), with the centre of mass path from the statistics file.
Usage: plot_landslide.py DEM.asc OUTPUT_DIR PNG"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

dem_file, out_dir, png = sys.argv[1:4]
header = {}
with open(dem_file) as f:
    for _ in range(6):
        key, value = f.readline().split()
        header[key.lower()] = float(value)
    z = np.loadtxt(f)[::-1]  # rows from the south
nx, ny, h = int(header["ncols"]), int(header["nrows"]), header["cellsize"]
x0, y0 = header["xllcenter"], header["yllcenter"]
X, Y = np.meshgrid(x0 + h * np.arange(nx), y0 + h * np.arange(ny))

points = np.loadtxt(f"{out_dir}/points_end.txt")
stats = np.array([l.split() for l in open(f"{out_dir}/statistics") if not l.startswith("#")],
                 dtype=float)


def ground(x, y):
    i = np.clip((x - x0) / h, 0, nx - 1.000001)
    j = np.clip((y - y0) / h, 0, ny - 1.000001)
    i0, j0 = i.astype(int), j.astype(int)
    fi, fj = i - i0, j - j0
    return ((1 - fi) * (1 - fj) * z[j0, i0] + fi * (1 - fj) * z[j0, i0 + 1]
            + (1 - fi) * fj * z[j0 + 1, i0] + fi * fj * z[j0 + 1, i0 + 1])


height = points[:, 2] - ground(points[:, 0], points[:, 1])
fig, ax = plt.subplots(figsize=(10, 6.2))
levels = np.arange(np.floor(z.min()), np.ceil(z.max()) + 1, 1.0)
cs = ax.contour(X, Y, z, levels=levels, colors="0.6", linewidths=0.6)
ax.clabel(cs, levels[::4], fontsize=7, fmt="%.0f m")
ax.add_patch(plt.Rectangle((8, 12), 12, 16, fill=False, ls="--", color="C0",
                           label="released layer (2 m thick)"))
sc = ax.scatter(points[:, 0], points[:, 1], c=height, s=2, cmap="viridis",
                label="deposit (material points)")
fig.colorbar(sc, ax=ax, label="height of the point above the ground (m)")
ax.plot(stats[:, 12], stats[:, 13], "r-", lw=1.5, label="centre of mass path")
ax.set_aspect("equal")
ax.set_xlabel("x (m)")
ax.set_ylabel("y (m)")
ax.set_title("3D landslide on a terrain-following hexahedral mesh (prm/landslide_valley_3d.prm)")
ax.legend(loc="upper right", fontsize=8)
fig.tight_layout()
fig.savefig(png, dpi=110)
