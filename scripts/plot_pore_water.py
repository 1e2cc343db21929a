#!/usr/bin/env python3
"""Figures of the pore-water cases (doc/pore_water.md, doc/slope_stability.md).

Usage:
  plot_pore_water.py consolidation PNG OUTDIR
      The points' excess pore pressure against depth at the report's time
      factors T (output of prm/terzaghi_consolidation.prm, whose output
      interval falls on them), against Terzaghi's series.
  plot_pore_water.py dam_break PNG REPORT:LABEL [REPORT:LABEL ...]
      The surge front Z against T of the `dam break` postprocessor's
      reports, against Martin and Moyce's (1952) measurements.
  plot_pore_water.py slope_pore_pressure PNG CSV:H [CSV:H ...]
      The factor of safety of prm/infinite_slope_pore_pressure.prm bisected
      on cells of size H (scripts/strength_reduction.sh's CSV files) against
      Davis' closed form in effective stress at the bed and at the bottom
      cells' centres, depth H_layer - H / 2.
"""
import math
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from plot_slope_stability import read_vtu


def terzaghi(z, T, terms=200):
    """u / u0 at depth z / H below the drained surface, time factor T."""
    u = np.zeros_like(z)
    for m in range(terms):
        M = (2 * m + 1) * math.pi / 2
        u += 2 / M * np.sin(M * z) * math.exp(-M * M * T)
    return u


def consolidation(png, out_dir):
    report = open(f"{out_dir}/report.txt").read()
    header = re.search(r"H = ([0-9.e+-]+) m, u0 = ([0-9.e+-]+) Pa, c_v = ([0-9.e+-]+) m\^2/s",
                       report)
    H, u0, cv = (float(v) for v in header.groups())
    factors = [float(t) for t in re.findall(r"^U at T = ([0-9.e+-]+):", report, re.M)]
    pvd = open(f"{out_dir}/particles.pvd").read()
    entries = [(float(t), f) for t, f in
               re.findall(r'timestep="([^"]*)"[^>]*file="([^"]*)"', pvd)]
    times = np.array([t for t, _ in entries])
    fig, ax = plt.subplots(figsize=(5.5, 5))
    z = np.linspace(0, 1, 200)
    for k, T in enumerate(factors):
        t = T * H * H / cv
        i = int(np.argmin(abs(times - t)))
        points = read_vtu(f"{out_dir}/" + entries[i][1].replace(".pvtu", ".0.vtu"))
        depth = (H - points["points"][:, 1]) / H
        colour = "C%d" % k
        ax.plot(terzaghi(z, T), z, "-", color=colour, lw=1)
        ax.plot(points["pore_pressure"] / u0, depth, "o", ms=3, mfc="none", color=colour,
                label="T = %g" % T)
    ax.plot([], [], "k-", lw=1, label="Terzaghi's series")
    ax.invert_yaxis()
    ax.set_xlim(0, 1.05)
    ax.set_xlabel("excess pore pressure u / u0")
    ax.set_ylabel("depth below the drained surface z / H")
    ax.set_title("Terzaghi consolidation: points (o), series (lines)", fontsize=10)
    ax.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def dam_break(png, specs):
    fig, ax = plt.subplots(figsize=(6, 4.5))
    measured = None
    for k, spec in enumerate(specs):
        path, label = spec.split(":", 1)
        rows = re.findall(r"^Z at T = ([0-9.]+): ([0-9.]+) \(measured ([0-9.]+)",
                          open(path).read(), re.M)
        T = [float(r[0]) for r in rows]
        ax.plot(T, [float(r[1]) for r in rows], "o-", ms=4, color="C%d" % k, label=label)
        measured = (T, [float(r[2]) for r in rows])
    ax.plot(measured[0], measured[1], "ks", ms=5, mfc="none",
            label="Martin and Moyce (1952), measured")
    ax.set_xlabel("T = t sqrt(2 g / a)")
    ax.set_ylabel("surge front Z = x / a")
    ax.set_title("Water dam break, n^2 = 2", fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def davis_strength_reduction(c, phi, sigma_n, tau):
    """F with (c / F) cos(phi_F) + sigma_n sin(phi_F) = tau,
    tan(phi_F) = tan(phi) / F (Davis 1968, psi = 0, strength reduced)."""
    def excess(F):
        phi_F = math.atan(math.tan(phi) / F)
        return c / F * math.cos(phi_F) + sigma_n * math.sin(phi_F) - tau
    low, high = 0.2, 10.0
    for _ in range(200):
        mid = 0.5 * (low + high)
        if excess(low) * excess(mid) <= 0:
            high = mid
        else:
            low = mid
    return 0.5 * (low + high)


def slope_pore_pressure(png, specs):
    # prm/infinite_slope_pore_pressure.prm: H = 5 m, 20 degrees, rho_sat
    # 2000, rho_w 1000, c' = 20 kPa, phi' = 30 degrees, artesian excess
    # 10 kPa at the bed (linear to zero at the surface).
    g, H, theta, c, phi, dp = 9.81, 5.0, math.radians(20), 2e4, math.radians(30), 1e4

    def closed_form(depth):
        sigma_n = 1000 * g * math.cos(theta) * depth - dp * depth / H
        tau = 2000 * g * math.sin(theta) * depth
        return davis_strength_reduction(c, phi, sigma_n, tau)

    fig, ax = plt.subplots(figsize=(6, 4.5))
    sizes = []
    for spec in specs:
        path, h = spec.rsplit(":", 1)
        h = float(h)
        sizes.append(h)
        rows = [line.strip().split(",") for line in open(path)][1:]
        stable = max(float(r[0]) for r in rows if r[1] == "stable")
        failed = min(float(r[0]) for r in rows if r[1] == "failed")
        ax.plot([h, h], [stable, failed], "-", color="C0", lw=3)
        ax.plot(h, stable, "o", color="C0", mfc="none")
        ax.plot(h, failed, "x", color="C0")
    ax.plot([], [], "-", color="C0", lw=3, label="bisected: o stands, x fails")
    h = np.linspace(0, 1.1 * max(sizes), 100)
    ax.plot(h, [closed_form(H - s / 2) for s in h], "k--", lw=1,
            label="closed form at the bottom cells' centres, H - h/2")
    ax.axhline(closed_form(H), color="k", lw=1, label="closed form at the bed: %.4f" % closed_form(H))
    ax.set_xlim(0, 1.1 * max(sizes))
    ax.set_xlabel("cell size h (m)")
    ax.set_ylabel("factor of safety F")
    ax.set_title("Saturated infinite slope, artesian excess 10 kPa", fontsize=10)
    ax.legend(fontsize=8, loc="upper left")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    kind, png, rest = sys.argv[1], sys.argv[2], sys.argv[3:]
    if kind == "consolidation":
        consolidation(png, rest[0])
    elif kind == "dam_break":
        dam_break(png, rest)
    elif kind == "slope_pore_pressure":
        slope_pore_pressure(png, rest)
    else:
        sys.exit(__doc__)
