#!/usr/bin/python3
"""Render a growshell .vtu surface (triangles; appended raw binary or ASCII) to a PNG with matplotlib.

usage: render_surface.py INPUT.vtu OUTPUT.png [--field bending_density] [--elev 25 --azim -60]
                         [--phi PHI_E]
                         [--views "ELEV,AZIM;ELEV,AZIM;..."] [--contact CONTACT.vtu] [--log]
                         [--alpha 0.85]
  --contact  a contact-proxy snapshot of the same state (an econe_contact study's *_contact.vtu):
             its points in contact are drawn in red, sized by their contact force, over the
             surface (also where a layer hides them: wound-up shapes touch between layers)
  --log      colour by log10 of the field (bending energy concentrates at the apex)
  --views    several views side by side (overrides --elev/--azim)
  --phi      the state's excess angle (rad), for the title
  --alpha    opacity of the surface
Needs Debian's python3-matplotlib (apt-get install python3-matplotlib).
"""
import argparse
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402


TYPES = {"Float64": "<f8", "Int64": "<i8", "UInt8": "u1"}

# The fields growshell writes, with their meaning and units (libshell/io/shell_snapshot.hpp).
FIELD_LABELS = {
    "bending_density": "bending energy density $U_b$ (1/m$^2$)",
    "stretching_density": "stretching energy density $U_s$ (1)",
    "element": "element index",
}


def read_array(data, name=None, components=None):
    """One DataArray of a .vtu file's bytes: inline ASCII, or appended raw (VTK XML 1.0 with
    UInt64 headers, as growshell writes it)."""
    if name:
        key = rb'Name="%s"' % re.escape(name).encode()
    else:
        key = rb'NumberOfComponents="%d"' % components
    tag = re.search(rb'<DataArray([^>]*' + key + rb'[^>]*)(/?)>', data)
    if not tag:
        raise SystemExit("no array %s in file" % (name or "points"))
    attributes = tag.group(1)
    offset = re.search(rb'offset="([0-9]+)"', attributes)
    if offset is None:  # ASCII: the numbers up to </DataArray>
        end = data.index(b"</DataArray>", tag.end())
        return np.array(data[tag.end():end].split(), dtype=float)
    kind = re.search(rb'type="([A-Za-z0-9]+)"', attributes).group(1).decode()
    start = data.index(b"_", data.index(b'<AppendedData encoding="raw">')) + 1
    at = start + int(offset.group(1))
    size = int(np.frombuffer(data, dtype="<u8", count=1, offset=at)[0])
    dtype = np.dtype(TYPES[kind])
    return np.frombuffer(data, dtype=dtype, count=size // dtype.itemsize, offset=at + 8).astype(float)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--field", default="bending_density")
    parser.add_argument("--elev", type=float, default=25.0)
    parser.add_argument("--azim", type=float, default=-60.0)
    parser.add_argument("--contact")
    parser.add_argument("--log", action="store_true")
    parser.add_argument("--views")
    parser.add_argument("--alpha", type=float, default=0.85)
    parser.add_argument("--phi", type=float,
                        help="the state's excess angle (rad), shown in the title")
    args = parser.parse_args()
    text = open(args.input, "rb").read()
    points = read_array(text, components=3).reshape(-1, 3)
    cells = read_array(text, name="connectivity").astype(int).reshape(-1, 3)
    values = read_array(text, name=args.field)
    if args.views:
        views = [tuple(float(v) for v in view.split(",")) for view in args.views.split(";")]
    else:
        views = [(args.elev, args.azim)]
    if args.log:
        values = np.log10(np.maximum(values, values[values > 0].min() if (values > 0).any() else 1e-300))
    norm = matplotlib.colors.Normalize(vmin=values.min(), vmax=values.max())
    colors = plt.cm.viridis(norm(values))
    touching = None
    if args.contact:
        ctext = open(args.contact, "rb").read()
        cpoints = read_array(ctext, components=3).reshape(-1, 3)
        force = read_array(ctext, name="contact_force")
        touching = force > 0
    fig = plt.figure(figsize=(7 * len(views), 6))
    for k, (elev, azim) in enumerate(views):
        ax = fig.add_subplot(1, len(views), k + 1, projection="3d")
        # Draw in the order added (surface, then contact points), not by depth, so that contact
        # between layers stays visible.
        ax.computed_zorder = False
        poly = Poly3DCollection(points[cells], facecolors=colors, edgecolors="none",
                                alpha=args.alpha)
        ax.add_collection3d(poly)
        if touching is not None and touching.any():
            size = 4 + 40 * force[touching] / force[touching].max()
            ax.scatter(cpoints[touching, 0], cpoints[touching, 1], cpoints[touching, 2], s=size,
                       c="red", depthshade=False, label="in contact")
            ax.legend(loc="upper right")
        lo, hi = points.min(axis=0), points.max(axis=0)
        centre, half = (lo + hi) / 2, (hi - lo).max() / 2
        for axis, c in zip("xyz", centre):
            getattr(ax, "set_%slim" % axis)(c - half, c + half)
        ax.view_init(elev=elev, azim=azim)
        for axis in "xyz":
            getattr(ax, "set_%slabel" % axis)("%s (m)" % axis)
        phi = "" if args.phi is None else r"$\phi_e$ = %.4g rad, " % args.phi
        ax.set_title("%s\n%sview elev %g°, azim %g°" % (args.input.split("/")[-1], phi, elev, azim),
                     fontsize=10)
    name = FIELD_LABELS.get(args.field, args.field)
    bar = fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap="viridis"), ax=fig.axes,
                       shrink=0.7, pad=0.02)
    bar.set_label(("log10 of " if args.log else "") + name)
    fig.savefig(args.output, dpi=90)


if __name__ == "__main__":
    main()
