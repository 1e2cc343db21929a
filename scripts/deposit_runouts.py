#!/usr/bin/env python3
"""The column collapse report's measures of the deposit's runout, recomputed
from the final deposit profile that every report.txt holds, so that reports
written before the postprocessor printed them (commit 52efd0b) can be
compared with newer ones, and the deposit's end can be read at other
thicknesses than the report's (doc/column_collapse.md, "Which measure
compares with the experiments"). Same definitions as
source/postprocess/column_collapse.cc:
  first empty bin   - the connected deposit's end (L - L0)/L0,
  q95, q99          - x within which 95 % / 99 % of the point volume lies,
  thicker than T    - the last bin at least T thick, interpolated towards
                      the next bin (the report's 'Front thickness', 1 cm),
and one the report does not give:
  surface toe       - the deposit's surface where it is between LO and HI
                      times the deposit's largest thickness, beyond the
                      thickest bin (a least-squares line through those
                      bins' thicknesses), extrapolated
                      to zero thickness: the end of the deposit's body
                      without the thin sheet ahead of it.
Usage: scripts/deposit_runouts.py [--thresholds T1,T2,...] [--toe-window LO,HI]
                                  report.txt [report.txt ...]
  (defaults: --thresholds 0.01 --toe-window 0.1,0.5)
"""
import argparse
import re
import sys


def profile(path):
    xs, ts, width, on = [], [], None, False
    for line in open(path):
        m = re.match(r"## column collapse: L0 = ([0-9.eE+-]+) m", line)
        if m:
            width = float(m.group(1))
        if "final deposit" in line:
            on = True
            continue
        if on and not line.startswith("#"):
            parts = line.split()
            if len(parts) == 2:
                xs.append(float(parts[0]))
                ts.append(float(parts[1]))
    if width is None or len(xs) < 2:
        sys.exit(f"{path}: no column collapse deposit profile")
    return width, xs, ts


def end_thicker_than(ts, bw, threshold):
    """x where the deposit's last bin at least @p threshold thick ends
    (interpolated towards the next bin, as the postprocessor does)."""
    last = max((b for b, t in enumerate(ts) if t >= threshold), default=-1)
    if last < 0:
        return 0.0
    front = (last + 0.5) * bw
    if last + 1 < len(ts):
        front += bw * (ts[last] - threshold) / (ts[last] - ts[last + 1])
    return front


def surface_toe(xs, ts, lo, hi):
    """x where the straight line fitted (least squares) through the bins
    beyond the thickest whose thickness lies between @p lo and @p hi times
    the largest meets
    zero thickness; None if fewer than two bins qualify."""
    top = max(ts)
    peak = ts.index(top)
    sel = [(x, t) for x, t in zip(xs[peak:], ts[peak:])
           if lo * top <= t <= hi * top]
    if len(sel) < 2:
        return None
    n = len(sel)
    mx = sum(x for x, _ in sel) / n
    mt = sum(t for _, t in sel) / n
    sxx = sum((x - mx) ** 2 for x, _ in sel)
    slope = sum((x - mx) * (t - mt) for x, t in sel) / sxx
    if slope >= 0:
        return None
    return mx - mt / slope


def measures(path, thresholds=(0.01,), toe_window=(0.1, 0.5)):
    L0, xs, ts = profile(path)
    bw = xs[1] - xs[0]
    total = sum(ts) * bw
    first_empty = next((b for b, t in enumerate(ts) if t <= 0), len(ts))
    out = {"connected": (first_empty * bw - L0) / L0}
    for q in (0.95, 0.99):
        below, x_q = 0.0, len(ts) * bw
        for b, t in enumerate(ts):
            if t > 0 and below + t * bw >= q * total:
                x_q = (b + (q * total - below) / (t * bw)) * bw
                break
            below += t * bw
        out[f"q{round(100 * q)}"] = (x_q - L0) / L0
    for threshold in thresholds:
        out[f"thicker_than_{threshold:g}"] = (
            end_thicker_than(ts, bw, threshold) - L0) / L0
    toe = surface_toe(xs, ts, *toe_window)
    out["surface_toe"] = float("nan") if toe is None else (toe - L0) / L0
    return out


if __name__ == "__main__":
    parser = argparse.ArgumentParser(
        description="Deposit runouts (L - L0)/L0 from column collapse reports.")
    parser.add_argument("--thresholds", default="0.01",
                        help="deposit thicknesses (m) whose end is reported")
    parser.add_argument("--toe-window", default="0.1,0.5",
                        help="LO,HI: the surface fitted for the toe, as "
                             "fractions of the deposit's largest thickness")
    parser.add_argument("reports", nargs="+")
    args = parser.parse_args()
    thresholds = [float(t) for t in args.thresholds.split(",")]
    window = tuple(float(w) for w in args.toe_window.split(","))
    if len(window) != 2 or not 0 <= window[0] < window[1] <= 1:
        sys.exit(f"--toe-window {args.toe_window}: want LO,HI with 0 <= LO < HI <= 1")
    names = ["connected", "q95", "q99"] + \
        [f"thicker_than_{t:g}" for t in thresholds] + ["surface_toe"]
    print("report, " + ", ".join(names))
    for path in args.reports:
        m = measures(path, thresholds, window)
        print(f"{path}, " + ", ".join(f"{m[n]:.4f}" for n in names))
