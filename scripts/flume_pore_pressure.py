#!/usr/bin/env python3
"""Pore pressure at the front of a saturated flume flow against its body
(doc/pore_water.md, "A debris flow: loose against dense sand").

Usage: flume_pore_pressure.py OUTDIR [OUTDIR ...]

OUTDIR is the output directory of a run of prm/flume_usgs_saturated.prm
(or a file like it: the `flume` postprocessor, particle output with the
pore pressure). For each particle output it prints the foremost point's
and the 95 % point's distance s along the bed (as the postprocessor
measures it) and, for the points of the basal band (centres within
BAND = 6 mm of the bed, a fixed physical band whatever the mesh) of the
front (the leading 10 % of the points by s) and of the body (the rest):
the mean pore pressure and the median of p / (p - sigma'_n), the pore
pressure over the total normal stress on the bed's plane (sigma'_n the
effective normal stress, compression negative): 1 where the sand is
liquefied, about rho_w / rho_sat under hydrostatic pressure. Points
whose total normal stress is less than MIN_LOAD = 10 Pa of compression
(the weight of about half a millimetre of saturated sand: a point at a
thin front, or lifted off the bed) carry no such ratio and are left out
of the median.
"""
import math
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_slope_stability import read_vtu  # noqa: E402

BAND = 0.006
MIN_LOAD = 10.0
FRONT_SHARE = 0.1


def bed_frame(x, y, theta, radius):
    """s along the bed (from the arc's midpoint), the normal distance from
    the bed and the bed's unit normal at the nearest bed point."""
    d, half = radius * math.tan(theta / 2), radius * theta / 2
    u = np.array([math.cos(theta), -math.sin(theta)])
    t1 = -d * u
    along = (x - t1[0]) * u[0] + (y - t1[1]) * u[1]
    psi = np.clip(np.arctan2(-(x - d), -(y - radius)), 0, theta)
    s = np.where(along <= 0, -half + along,
                 np.where(x >= d, half + x - d, half - radius * psi))
    on_incline, on_runout = along <= 0, x >= d
    # The arc's centre is at (d, radius): the bed's normal points to it.
    cx, cy = x - d, y - radius
    r = np.hypot(cx, cy)
    nx = np.where(on_incline, math.sin(theta), np.where(on_runout, 0., -cx / r))
    ny = np.where(on_incline, math.cos(theta), np.where(on_runout, 1., -cy / r))
    height = np.where(on_incline, (x - t1[0]) * nx + (y - t1[1]) * ny,
                      np.where(on_runout, y, radius - r))
    return s, height, nx, ny


def main(out):
    report = open(os.path.join(out, "report.txt")).read()
    theta = math.radians(float(re.search(r"incline ([0-9.e+-]+) deg", report).group(1)))
    radius = float(re.search(r"arc radius ([0-9.e+-]+) m", report).group(1))
    pvd = open(os.path.join(out, "particles.pvd")).read()
    print("# %s: basal band %g m, front = the leading %d %% of the points" %
          (out, BAND, round(100 * FRONT_SHARE)))
    print("# t (s)  foremost s (m)  95 % s (m) | front: basal p (Pa)  p/(p-s'n) |"
          " body: basal p (Pa)  p/(p-s'n)")
    for t, name in re.findall(r'timestep="([^"]*)"[^>]*file="([^"]*)"', pvd):
        pieces = re.findall(r'Source="([^"]*)"', open(os.path.join(out, name)).read())
        arrays = [read_vtu(os.path.join(out, os.path.dirname(name), p)) for p in pieces]
        a = {k: np.concatenate([b[k] for b in arrays]) for k in
             ("points", "pore_pressure", "stress_xx", "stress_xy", "stress_yy", "volume")}
        x, y = a["points"][:, 0].astype(float), a["points"][:, 1].astype(float)
        s, height, nx, ny = bed_frame(x, y, theta, radius)
        p = a["pore_pressure"].astype(float)
        sigma_n = a["stress_xx"] * nx * nx + 2 * a["stress_xy"] * nx * ny + a["stress_yy"] * ny * ny
        order = np.argsort(s)
        volume = np.cumsum(a["volume"][order]) / a["volume"].sum()
        s95 = s[order][np.searchsorted(volume, 0.95)]
        cut = s[order][int((1 - FRONT_SHARE) * len(s))]
        row = "%7.3f  %14.4f  %10.4f" % (float(t), s.max(), s95)
        for part in (s >= cut, s < cut):
            basal = part & (height < BAND)
            loaded = basal & (p - sigma_n >= MIN_LOAD)
            if loaded.any():
                ratio = p[loaded] / (p[loaded] - sigma_n[loaded])
                row += " | %17.1f  %9.2f" % (p[basal].mean(), np.median(ratio))
            else:
                row += " | %17s  %9s" % ("-", "-")
        print(row)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    for directory in sys.argv[1:]:
        main(directory)
