#!/usr/bin/env python3
"""Draw the hazard rasters of a run (postprocessor 'hazard rasters') over a
hillshade of its elevation model: maximum flow height, maximum speed,
maximum pressure and deposit thickness, one panel each, in map
coordinates.

Usage: plot_hazard_rasters.py OUTPUT_DIRECTORY DEM [FIGURE.png]
(ESRI ASCII grids; GeoTIFF DEM and rasters through gdal_translate)
(default figure: OUTPUT_DIRECTORY/hazard_rasters.png). Needs numpy and
matplotlib (Debian: python3-matplotlib)."""
import os
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.colors import LightSource


def read_esri_ascii(name):
    """Values (rows from the north, NaN for NODATA) and the extent of the
    cells: (x_min, x_max, y_min, y_max). A raster in another format
    (GeoTIFF) is converted by GDAL's gdal_translate first, if installed."""
    if not name.lower().endswith(".asc"):
        import shutil
        import subprocess
        import tempfile
        if shutil.which("gdal_translate") is None:
            sys.exit(f"{name}: not an ESRI ASCII grid, and gdal_translate "
                     "(Debian: gdal-bin) is not installed to convert it")
        converted = tempfile.mkdtemp() + "/raster.asc"
        subprocess.run(["gdal_translate", "-q", "-of", "AAIGrid", name, converted], check=True)
        name = converted
    header = {}
    with open(name) as f:
        while True:
            position = f.tell()
            line = f.readline()
            words = line.split()
            if not words:
                continue
            if words[0][0].isdigit() or words[0][0] in "-+.":
                f.seek(position)
                break
            header[words[0].lower()] = float(words[1])
        values = np.loadtxt(f)
    n_x, n_y, cell = int(header["ncols"]), int(header["nrows"]), header["cellsize"]
    if "xllcenter" in header:
        x0, y0 = header["xllcenter"] - cell / 2, header["yllcenter"] - cell / 2
    else:
        x0, y0 = header["xllcorner"], header["yllcorner"]
    values = values.reshape(n_y, n_x)
    if "nodata_value" in header:
        values = np.where(values == header["nodata_value"], np.nan, values)
    return values, (x0, x0 + n_x * cell, y0, y0 + n_y * cell)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    directory, dem_file = sys.argv[1], sys.argv[2]
    figure_file = sys.argv[3] if len(sys.argv) > 3 else directory + "/hazard_rasters.png"
    dem, dem_extent = read_esri_ascii(dem_file)
    cell = (dem_extent[1] - dem_extent[0]) / dem.shape[1]
    shade = LightSource(azdeg=315, altdeg=45).hillshade(dem, vert_exag=2, dx=cell, dy=cell)
    panels = [
        ("max_flow_height", "maximum flow height (m)", 1, "viridis"),
        ("max_speed", "maximum speed (m/s)", 1, "plasma"),
        ("max_pressure", "maximum pressure (kPa)", 1e-3, "inferno"),
        ("deposit_thickness", "deposit thickness (m)", 1, "viridis"),
    ]
    # Map coordinates shown relative to the DEM's lower-left corner, which
    # the axis labels state (UTM values would not fit on the ticks).
    x_ref, y_ref = dem_extent[0], dem_extent[2]
    shifted = lambda e: (e[0] - x_ref, e[1] - x_ref, e[2] - y_ref, e[3] - y_ref)
    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5), constrained_layout=True)
    for ax, (name, label, scale, colours) in zip(axes.flat, panels):
        file = f"{directory}/{name}.asc"
        if not os.path.exists(file):
            file = f"{directory}/{name}.tif"
        values, extent = read_esri_ascii(file)
        values = values * scale
        # Where the flow never was (0) the hillshade shows through.
        masked = np.ma.masked_where(~(values > 1e-3 * np.nanmax(values)), values)
        ax.imshow(shade, extent=shifted(dem_extent), cmap="gray", vmin=0, vmax=1)
        ax.contour(dem[::-1], extent=shifted(dem_extent), levels=10, colors="k",
                   linewidths=0.4, alpha=0.5)
        image = ax.imshow(masked, extent=shifted(extent), cmap=colours, alpha=0.85)
        fig.colorbar(image, ax=ax, shrink=0.85, label=label)
        ax.set_title(label)
        ax.set_xlabel(f"easting - {x_ref:.0f} (m)")
        ax.set_ylabel(f"northing - {y_ref:.0f} (m)")
        ax.set_aspect("equal")
    fig.savefig(figure_file, dpi=110)
    print(f"wrote {figure_file}")


if __name__ == "__main__":
    main()
