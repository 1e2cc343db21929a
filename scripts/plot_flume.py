#!/usr/bin/env python3
"""Plot a run of prm/flume_usgs.prm (the USGS flume, doc/flume.md):
  flume_runout.png   front and tail (distance s along the bed from the
                     break in slope) against time, from report.txt;
  flume_velocity.png mean velocity magnitude and components against time,
                     from report.txt, with the paper's peak (0.45 m/s at
                     0.6 s) and levelling-off time (1.55 s) marked;
  flume_points.png   initial and final point positions, coloured by the
                     initial distance along the bed (as the paper's
                     Figure 10), over the bed.
Usage: /usr/bin/python3 scripts/plot_flume.py [OUTPUT_FOLDER [DOC_FOLDER]]
(defaults output-flume and the repository's doc/)."""
import base64
import math
import os
import re
import struct
import sys
import zlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# The distance s along the bed, as the flume postprocessor measures it.
from flume_pore_pressure import bed_frame  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "output-flume"
doc = sys.argv[2] if len(sys.argv) > 2 else os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "doc")

# --- report.txt: the flume table and the bed geometry -----------------------
report = open(os.path.join(out, "report.txt")).read()
theta = math.radians(float(re.search(r"incline ([0-9.e+-]+) deg", report).group(1)))
radius = float(re.search(r"arc radius ([0-9.e+-]+) m", report).group(1))
table = report.split("## flume: final deposit")[0]
rows = np.array([list(map(float, l.split())) for l in table.splitlines()
                 if l.startswith(" ") and len(l.split()) == 8])
t, s_front, s_tail, v_mean, vx, vy = (rows[:, 0], rows[:, 1], rows[:, 2],
                                      rows[:, 5], rows[:, 6], rows[:, 7])

fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(t, s_front, "o-", ms=3, label="front")
ax.plot(t, s_tail, "s-", ms=3, label="tail")
ax.axhline(0, color="k", lw=0.6)
ax.axhspan(-radius * theta / 2, radius * theta / 2, color="0.85",
           label="arc (curved section)")
ax.set_xlabel("time (s)")
ax.set_ylabel("distance along the bed s (m), 0 = break in slope")
ax.legend()
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(os.path.join(doc, "flume_runout.png"), dpi=120)

fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(t, v_mean, "-", label="mean |v|")
ax.plot(t, vx, "--", label="mean v_x")
ax.plot(t, vy, ":", label="mean v_y")
ax.plot([0.6], [0.45], "k*", ms=10, label="paper: peak 0.45 m/s at 0.6 s")
ax.axvline(1.55, color="k", lw=0.6, ls="--", label="paper: levels off at 1.55 s")
ax.set_xlabel("time (s)")
ax.set_ylabel("velocity (m/s)")
ax.legend(fontsize=8)
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(os.path.join(doc, "flume_velocity.png"), dpi=120)


# --- particles: deal.II's compressed binary VTU ------------------------------
def read_array(text, name):
    """One DataArray of a deal.II .vtu: base64 of a zlib header (4 uint32:
    blocks, block size, last block size, compressed sizes) and the data."""
    m = re.search(r'<DataArray type="Float32"' +
                  (r' Name="%s"' % name if name else "") +
                  r'[^>]*>\s*([^<]*)<', text)
    raw = m.group(1).strip()
    header = base64.b64decode(raw[:24])
    n_blocks = struct.unpack("<I", header[:4])[0]
    header_len = 4 * (3 + n_blocks)
    header_chars = 4 * math.ceil(header_len / 3)
    header = base64.b64decode(raw[:header_chars])
    sizes = struct.unpack("<%dI" % n_blocks, header[12:12 + 4 * n_blocks])
    data = base64.b64decode(raw[header_chars:])
    out_bytes, pos = b"", 0
    for size in sizes:
        out_bytes += zlib.decompress(data[pos:pos + size])
        pos += size
    return np.frombuffer(out_bytes, dtype="<f4")


def read_points(index):
    pvtu = os.path.join(out, "particles_%05d.pvtu" % index)
    pieces = re.findall(r'<Piece Source="([^"]+)"', open(pvtu).read())
    xs, ids = [], []
    for piece in pieces:
        text = open(os.path.join(out, piece)).read()
        points = text.split("<Points>")[1]
        xs.append(read_array(points, None).reshape(-1, 3)[:, :2])
        ids.append(read_array(text, "id"))
    x, i = np.concatenate(xs), np.concatenate(ids)
    order = np.argsort(i)
    return x[order], i[order]


n_outputs = len(re.findall(r"<DataSet", open(os.path.join(out, "particles.pvd")).read()))
x0, id0 = read_points(0)
x1, id1 = read_points(n_outputs - 1)
colour0 = bed_frame(x0[:, 0], x0[:, 1], theta, radius)[0]
colour1 = colour0[np.searchsorted(id0, id1)]

fig, ax = plt.subplots(figsize=(10, 3.6))
d = radius * math.tan(theta / 2)
arc = np.linspace(0, theta, 30)
bed_x = np.concatenate([[-0.8 * math.cos(theta)], d - radius * np.sin(arc[::-1]), [0.6]])
bed_y = np.concatenate([[0.8 * math.sin(theta)], radius - radius * np.cos(arc[::-1]), [0]])
ax.plot(bed_x, bed_y, "k-", lw=1)
ax.scatter(x0[:, 0], x0[:, 1], c=colour0, s=1, cmap="jet", alpha=0.25)
sc = ax.scatter(x1[:, 0], x1[:, 1], c=colour1, s=1, cmap="jet")
fig.colorbar(sc, ax=ax, label="initial s (m)")
ax.set_aspect("equal")
ax.set_xlim(-0.55, 0.5)
ax.set_ylim(-0.02, 0.32)
ax.set_xlabel("x (m)")
ax.set_ylabel("y (m)")
ax.set_title("initial (faint) and final (t = %s s) material points" %
             re.findall(r'timestep="([^"]+)"', open(os.path.join(out, "particles.pvd")).read())[-1])
fig.tight_layout()
fig.savefig(os.path.join(doc, "flume_points.png"), dpi=120)
print("wrote flume_runout.png, flume_velocity.png, flume_points.png to", doc)
