#!/usr/bin/env python3
"""A synthetic valley as an ESRI ASCII grid (the terrain of
prm/landslide_valley_3d.prm): a hillside dipping at 30 degrees towards +x
that bends over a radius of about 8 m into a valley floor dipping at
5 degrees, with a gully along y = 20 m that is deepest on the hillside.

    z(x, y) = z0 - s2 x + (s1 - s2) R ln(1 + exp((xc - x) / R)) - gully
    gully   = d exp(-((y - yc) / w)^2) / (1 + exp((x - xc) / R))

s1 = tan 30, s2 = tan 5, xc = 30 m, R = 8 m, d = 1.5 m, w = 5 m; 61 x 41
nodes 1 m apart (x 0-60 m, y 0-40 m). Pure standard library.
Usage: make_valley_dem.py [OUTPUT.asc]   (default meshes/valley.asc)"""
import math
import os
import sys

s1, s2 = math.tan(math.radians(30)), math.tan(math.radians(5))
xc, radius, z0 = 30.0, 8.0, 10.0
depth, yc, width = 1.5, 20.0, 5.0
ncols, nrows, cellsize = 61, 41, 1.0


def elevation(x, y):
    hillside = z0 - s2 * x + (s1 - s2) * radius * math.log1p(math.exp((xc - x) / radius))
    gully = depth * math.exp(-((y - yc) / width) ** 2) / (1 + math.exp((x - xc) / radius))
    return hillside - gully


out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "meshes", "valley.asc")
with open(out, "w") as f:
    # Node values: 'center' header, so the node (0, 0) is at (0, 0).
    f.write(f"ncols {ncols}\nnrows {nrows}\nxllcenter 0\nyllcenter 0\n"
            f"cellsize {cellsize}\nNODATA_value -9999\n")
    for row in range(nrows):
        y = (nrows - 1 - row) * cellsize  # the first row is the northernmost
        f.write(" ".join(f"{elevation(i * cellsize, y):.4f}" for i in range(ncols)) + "\n")
print(f"wrote {out}")
