#!/usr/bin/env python3
"""The column collapse report's measures of the deposit's runout, recomputed
from the final deposit profile that every report.txt holds, so that reports
written before the postprocessor printed them (commit 52efd0b) can be
compared with newer ones (doc/column_collapse.md, "Which scheme converges
to what"). Same definitions as source/postprocess/column_collapse.cc:
  first empty bin  - the connected deposit's end (L - L0)/L0,
  q95, q99         - x within which 95 % / 99 % of the point volume lies,
  thicker than 1 cm - the last bin at least 1 cm thick, interpolated
                      towards the next bin.
Usage: scripts/deposit_runouts.py report.txt [report.txt ...]
"""
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


def measures(path, threshold=0.01):
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
    last = max((b for b, t in enumerate(ts) if t >= threshold), default=-1)
    front = 0.0
    if last >= 0:
        front = (last + 0.5) * bw
        if last + 1 < len(ts):
            front += bw * (ts[last] - threshold) / (ts[last] - ts[last + 1])
    out["thicker_than_1cm"] = (front - L0) / L0
    return out


if __name__ == "__main__":
    print("report, connected, q95, q99, thicker_than_1cm")
    for path in sys.argv[1:]:
        m = measures(path)
        print(f"{path}, {m['connected']:.4f}, {m['q95']:.4f}, {m['q99']:.4f}, "
              f"{m['thicker_than_1cm']:.4f}")
