#!/usr/bin/python3
"""E_b-hat against phi_e of a cone_branch study: writes DIR/eb_hat.png.

usage: scripts/plot_study.py DIR

DIR is a study's output directory (growshell run, trace_disc): branch.csv gives the branch
(its stable samples, n_negative = 0, solid; the unstable ones dashed), events.json the special
points and events (marked and labelled with their phi_e), results.json or scene.json the
thickness and the mesh for the title. Needs matplotlib (Debian: python3-matplotlib).
"""
import csv
import json
import math
import os
import pathlib
import re
import sys

# Events drawn, in legend order: (kind, marker, label).
KINDS = [
    ("branch_point", "o", "branch point"),
    ("fold", "s", "fold"),
    ("eb_max", "^", r"$\hat{E}_b$ maximum"),
    ("contact", "v", "gap = contact distance"),
    ("midsurface_contact", "X", "mid-surface contact"),
    ("symmetry_lost", "D", "S4 symmetry lost"),
]


def fail(message):
    sys.exit(f"plot_study.py: {message}")


def read_branch(directory):
    path = directory / "branch.csv"
    if not path.is_file():
        fail(f"{directory} has no branch.csv (not a study's output directory?)")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for column in ("phi_e", "Eb_hat", "n_negative"):
        if rows and column not in rows[0]:
            fail(f"{path} has no column '{column}'")
    phi = [float(r["phi_e"]) for r in rows]
    eb = [float(r["Eb_hat"]) for r in rows]
    negative = [int(float(r["n_negative"])) for r in rows]
    if not phi:
        fail(f"{path} has no samples yet")
    return phi, eb, negative


def read_events(directory):
    path = directory / "events.json"
    if not path.is_file():
        return []
    # The C++ writer prints a non-finite number as nan / inf, which JSON lacks.
    text = re.sub(r"(?<![\w\"])-?(nan|inf)(?![\w\"])", "NaN", path.read_text())
    try:
        return json.loads(text)
    except json.JSONDecodeError as e:
        print(f"plot_study.py: {path} is not valid JSON ({e}); plotting without events",
              file=sys.stderr)
        return []


def describe(directory):
    """Title: the thickness and the mesh, from results.json or else scene.json."""
    results = directory / "results.json"
    if results.is_file():
        r = json.loads(results.read_text())
        mesh = r.get("mesh", {})
        slope = mesh.get("size_slope")
        size = f", size_slope {slope:g}" if slope is not None else ""
        return (f"cone branch: h = {r.get('thickness'):g} m, {mesh.get('family')} mesh{size}, "
                f"{mesh.get('elements')} elements")
    scene = directory / "scene.json"
    if scene.is_file():
        s = json.loads(scene.read_text())
        h = s.get("thickness")
        h = f"{h:g} m" if isinstance(h, (int, float)) else json.dumps(h)
        mesh = s.get("mesh", {})
        size = (f", size_slope {mesh.get('size_slope'):g}"
                if mesh.get("family") in ("rings", "gmsh") else "")
        return f"cone branch: h = {h}, {mesh.get('family')} mesh{size}"
    return f"cone branch: {directory}"


def eb_at(phi_event, phi, eb):
    """E_b-hat at phi_e on the branch: linear between the first pair of consecutive samples
    that brackets it, else at the nearest sample."""
    for k in range(len(phi) - 1):
        a, b = phi[k], phi[k + 1]
        if min(a, b) <= phi_event <= max(a, b) and a != b:
            t = (phi_event - a) / (b - a)
            return eb[k] + t * (eb[k + 1] - eb[k])
    nearest = min(range(len(phi)), key=lambda k: abs(phi[k] - phi_event))
    return eb[nearest]


def stability_runs(negative):
    """Runs of consecutive samples with the same stability: (first, last, stable), the last
    index shared with the next run so that the curve stays connected."""
    runs, first = [], 0
    for k in range(1, len(negative) + 1):
        if k == len(negative) or (negative[k] == 0) != (negative[first] == 0):
            runs.append((first, min(k, len(negative) - 1), negative[first] == 0))
            first = k
    return runs


def pyplot(fail):
    """matplotlib.pyplot with the Agg backend (files only), or fail(message) naming the Debian
    package that provides it."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        fail("needs matplotlib (Debian: apt-get install python3-matplotlib)")
    return plt


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        sys.exit(__doc__)
    directory = pathlib.Path(sys.argv[1])
    if not directory.is_dir():
        fail(f"{directory} is not a directory")
    phi, eb, negative = read_branch(directory)
    events = read_events(directory)
    plt = pyplot(fail)

    fig, ax = plt.subplots(figsize=(8, 5))
    labelled = set()
    for first, last, stable in stability_runs(negative):
        label = "stable (n_negative = 0)" if stable else "unstable (n_negative > 0)"
        ax.plot(phi[first:last + 1], eb[first:last + 1], "-" if stable else "--",
                color="tab:blue" if stable else "tab:red", linewidth=1.6,
                label=None if label in labelled else label)
        labelled.add(label)
    for n, (kind, marker, label) in enumerate(KINDS):
        points = [e for e in events if e.get("kind") == kind
                  and isinstance(e.get("phi_e"), (int, float)) and math.isfinite(e["phi_e"])]
        for i, e in enumerate(points):
            y = eb_at(e["phi_e"], phi, eb)
            ax.plot([e["phi_e"]], [y], marker, color=f"C{n + 2}", markersize=7,
                    markeredgecolor="black", label=label if i == 0 else None, zorder=3)
            ax.annotate(f"{e['phi_e']:.5g}", (e["phi_e"], y), textcoords="offset points",
                        xytext=(6, 8 if i % 2 == 0 else -14), fontsize=8)
    ax.set_xlabel(r"excess angle $\phi_e$ (rad)")
    ax.set_ylabel(r"normalised bending energy $\hat{E}_b$ (1/m$^2$)")
    ax.set_title(describe(directory))
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    # Written whole, then renamed: a reader never sees half a figure.
    temporary = directory / ".eb_hat.png.tmp"
    fig.savefig(temporary, dpi=120, format="png")
    os.replace(temporary, directory / "eb_hat.png")


if __name__ == "__main__":
    main()
