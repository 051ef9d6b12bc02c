#!/usr/bin/python3
"""Render a growshell .vtu surface (ASCII, triangles) to a PNG with matplotlib.

usage: render_surface.py INPUT.vtu OUTPUT.png [--field bending_density] [--elev 25 --azim -60]
Needs Debian's python3-matplotlib (apt-get install python3-matplotlib).
"""
import argparse
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402


def read_array(text, name=None, components=None):
    if name:
        pattern = r'<DataArray[^>]*Name="%s"[^>]*>(.*?)</DataArray>' % re.escape(name)
    else:
        pattern = r'<DataArray[^>]*NumberOfComponents="%d"[^>]*>(.*?)</DataArray>' % components
    match = re.search(pattern, text, re.S)
    if not match:
        raise SystemExit("no array %s in file" % (name or "points"))
    return np.array(match.group(1).split(), dtype=float)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--field", default="bending_density")
    parser.add_argument("--elev", type=float, default=25.0)
    parser.add_argument("--azim", type=float, default=-60.0)
    args = parser.parse_args()
    text = open(args.input).read()
    points = read_array(text, components=3).reshape(-1, 3)
    cells = read_array(text, name="connectivity").astype(int).reshape(-1, 3)
    values = read_array(text, name=args.field)
    fig = plt.figure(figsize=(7, 6))
    ax = fig.add_subplot(111, projection="3d")
    colors = plt.cm.viridis((values - values.min()) / max(np.ptp(values), 1e-300))
    poly = Poly3DCollection(points[cells], facecolors=colors, edgecolors="none")
    ax.add_collection3d(poly)
    lo, hi = points.min(axis=0), points.max(axis=0)
    centre, half = (lo + hi) / 2, (hi - lo).max() / 2
    for axis, c in zip("xyz", centre):
        getattr(ax, "set_%slim" % axis)(c - half, c + half)
    ax.view_init(elev=args.elev, azim=args.azim)
    ax.set_title("%s (%s)" % (args.input.split("/")[-1], args.field))
    fig.savefig(args.output, dpi=90)


if __name__ == "__main__":
    main()
