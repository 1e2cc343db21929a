#!/usr/bin/env python3
"""The figures of doc/slope_stability.md.
Usage: plot_slope_stability.py srm PNG CSV [CSV...]
         crest displacement at the end of each constant-F run against F
         (the CSVs of scripts/strength_reduction.sh, labelled by file name)
       plot_slope_stability.py runout PNG OUTPUT_DIR:STEP[:TITLE] ...
         the points of those particle files (particles_STEP.*.vtu of the
         run's output folder) coloured by their plastic shear strain
       plot_slope_stability.py band PNG OUTPUT_DIR:LABEL ...
         shear stress against gamma and the plastic shear strain across
         the layer from the reports of prm/shear_band_softening.prm runs
         (a label containing "non-local" is drawn solid, others dashed)"""
import base64
import glob
import re
import struct
import sys
import zlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def read_vtu(path):
    """The binary (zlib, base64) data arrays of a deal.II .vtu file."""
    text = open(path).read()
    arrays = {}
    for m in re.finditer(r"<DataArray([^>]*)>(.*?)</DataArray>", text, re.S):
        attributes, body = m.group(1), m.group(2).strip()
        if 'format="binary"' not in attributes:
            continue
        name = re.search(r'Name="([^"]*)"', attributes)
        name = name.group(1) if name else "points"
        dtype = {"Float32": np.float32, "Float64": np.float64, "Int32": np.int32,
                 "UInt8": np.uint8}[re.search(r'type="([^"]*)"', attributes).group(1)]
        components = re.search(r'NumberOfComponents="(\d+)"', attributes)
        components = int(components.group(1)) if components else 1
        n_blocks = struct.unpack("<I", base64.b64decode(body[:8])[:4])[0]
        header_chars = 4 * ((4 * (3 + n_blocks) + 2) // 3)
        header = struct.unpack("<%dI" % (3 + n_blocks), base64.b64decode(body[:header_chars]))
        data, position, chunks = base64.b64decode(body[header_chars:]), 0, []
        for size in header[3:]:
            chunks.append(zlib.decompress(data[position:position + size]))
            position += size
        values = np.frombuffer(b"".join(chunks), dtype=dtype)
        arrays[name] = values.reshape(-1, components) if components > 1 else values
    return arrays


def srm(png, csvs):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for csv in csvs:
        rows = [l.strip().split(",") for l in open(csv)][1:]
        rows.sort(key=lambda r: float(r[0]))
        F = np.array([float(r[0]) for r in rows])
        d = np.array([float(r[2]) for r in rows])
        failed = np.array([r[1] == "failed" for r in rows])
        label = re.sub(r".*slope_stability_(.*)\.csv", r"\1", csv)
        refinements = re.search(r"_r(\d+)$", label)
        if refinements:  # meshes/slope.msh refined r times
            label = "%g m cells" % (1 / 2 ** int(refinements.group(1)))
        line, = ax.semilogy(F, d, "-", label=label)
        ax.semilogy(F[failed], d[failed], "x", color=line.get_color())
        ax.semilogy(F[~failed], d[~failed], "o", mfc="none", color=line.get_color())
    ax.axvline(1.380, color="k", ls="--", lw=1, label="Bishop & Morgenstern 1.380")
    ax.axvline(1.4, color="0.5", ls=":", lw=1, label="Griffiths & Lane FE 1.4")
    ax.set_xlabel("strength reduction factor F")
    ax.set_ylabel("crest displacement after 10 s (m)")
    ax.set_title("Griffiths & Lane (1999) example 1: o at rest, x still moving")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def runout(png, specs):
    fig, axes = plt.subplots(len(specs), 1, figsize=(10, 1.9 * len(specs) + 0.6), squeeze=False)
    for ax, spec in zip(axes[:, 0], specs):
        parts = spec.split(":")
        out_dir, step = parts[0], int(parts[1])
        files = sorted(glob.glob(f"{out_dir}/particles_{step:05d}.*.vtu"))
        points, strain = [], []
        for f in files:
            a = read_vtu(f)
            points.append(a["points"])
            strain.append(a["plastic_shear_strain"])
        p, k = np.concatenate(points), np.concatenate(strain)
        sc = ax.scatter(p[:, 0], p[:, 1], c=np.log10(1e-4 + k), s=1.5, cmap="viridis",
                        vmin=-4, vmax=0, rasterized=True)
        ax.set_aspect("equal")
        ax.set_xlim(-30, 60)
        ax.set_ylim(0, 11)
        ax.set_title(parts[2] if len(parts) > 2 else spec, fontsize=9)
    axes[-1, 0].set_xlabel("x (m)")
    fig.colorbar(sc, ax=axes[:, 0].tolist(), label="log10(1e-4 + plastic shear strain)")
    fig.savefig(png, dpi=110)


def read_band_report(path):
    """The stress curve and the plastic shear strain profile of a
    'simple shear' report with Closed form = false."""
    curve, profile, section = [], [], None
    for line in open(path):
        if line.startswith("## simple shear of a yielding layer"):
            section = "curve"
        elif line.startswith("## at gamma"):
            section = "profile"
        elif line.startswith("#") or not line.strip():
            continue
        elif section == "curve" and len(line.split()) == 4:
            curve.append([float(v) for v in line.split()])
        elif section == "profile" and len(line.split()) == 2:
            profile.append([float(v) for v in line.split()])
    return np.array(curve), np.array(profile)


def band(png, specs):
    """Shear stress against gamma and the plastic shear strain across the
    layer for OUTPUT_DIR:LABEL pairs (prm/shear_band_softening.prm)."""
    figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    for spec in specs:
        folder, label = spec.split(":", 1)
        curve, profile = read_band_report(folder + "/report.txt")
        style = "-" if "non-local" in label else "--"
        line, = left.plot(curve[:, 0], curve[:, 1] / 1e3, style, label=label)
        right.plot(profile[:, 1], profile[:, 0], style, color=line.get_color(), label=label)
    left.set_xlabel("gamma = top displacement / H")
    left.set_ylabel("mean shear stress (kPa)")
    left.grid(alpha=0.3)
    left.legend(fontsize=7)
    right.set_xlabel("plastic shear strain at gamma = 0.1 (bin mean)")
    right.set_ylabel("y (m)")
    right.set_ylim(0.2, 0.9)
    right.grid(alpha=0.3)
    figure.tight_layout()
    figure.savefig(png, dpi=110)


if __name__ == "__main__":
    mode, png = sys.argv[1:3]
    {"srm": srm, "runout": runout, "band": band}[mode](png, sys.argv[3:])
