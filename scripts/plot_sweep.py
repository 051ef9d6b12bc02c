#!/usr/bin/python3
"""The key results of a sweep against its parameter: writes DIR/sweep.png.

usage: scripts/plot_sweep.py DIR [--keys KEY1,KEY2,...]

DIR is a sweep's directory (growshell sweep --out DIR). The x axis is the first parameter
whose values are all numbers (e.g. thickness, geometry.inner_radius, mesh.min_spacing); the
other parameters' values give one line each. Without a numeric parameter the points are
spaced evenly and labelled with their values. One panel per results.json key: by default
those of phi_branch, phi_max, eb_hat_max, phi_gap_h, phi_kiss, phi_crit_energy and
phi_crit_stability that some point has as a number. A completed point is a filled marker, one
that ended early an open one (its value is where it got to); failed points are left out.
Needs matplotlib (Debian: python3-matplotlib).
"""
import argparse
import json
import os
import pathlib
import sys

DEFAULT_KEYS = ["phi_branch", "phi_max", "eb_hat_max", "phi_gap_h", "phi_kiss",
                "phi_crit_energy", "phi_crit_stability"]
LABELS = {
    "phi_branch": r"$\varphi_e$ at the first branch point (rad)",
    "phi_max": r"$\varphi_e^{max}$ (rad)",
    "eb_hat_max": r"$\hat{E}_b^{max}$ (1/m$^2$)",
    "phi_gap_h": r"$\varphi_e$ at first contact (rad)",
    "phi_kiss": r"$\varphi_e^{kiss}$ (rad)",
    "phi_crit_energy": r"$\varphi_e^{crit}$, energy crossing (rad)",
    "phi_crit_stability": r"$\varphi_e^{crit}$, loss of stability (rad)",
    "thickness": "thickness h (m)",
    "geometry.inner_radius": r"inner radius $R_i$ (m)",
    "geometry.radius": "radius R (m)",
    "mesh.min_spacing": "core floor (m)",
    "mesh.size_slope": "element size per distance from the centre",
    "growth.smoothing_radius": r"growth smoothing radius $\varepsilon$ (m)",
}


def fail(message):
    sys.exit(f"plot_sweep.py: {message}")


def is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def lookup(results, key):
    value = results
    for part in key.split("."):
        if not isinstance(value, dict) or part not in value:
            return None
        value = value[part]
    return value if is_number(value) else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("directory", type=pathlib.Path)
    parser.add_argument("--keys", help="comma-separated results.json keys (default: see above)")
    args = parser.parse_args()
    path = args.directory / "sweep.json"
    if not path.is_file():
        fail(f"{args.directory} has no sweep.json (not a sweep's directory?)")
    with open(path) as f:
        sweep = json.load(f)
    parameters = [p["key"] for p in sweep.get("parameters", [])]
    points = [p for p in sweep.get("points", []) if p.get("status") in ("completed", "ended_early")]
    if not parameters:
        fail(f"{path} names no parameters")
    keys = args.keys.split(",") if args.keys else [
        k for k in DEFAULT_KEYS if any(lookup(p.get("results"), k) is not None for p in points)]
    if not keys:
        fail(f"{path}: no point has any of {', '.join(args.keys.split(',') if args.keys else DEFAULT_KEYS)}")

    numeric = [k for k in parameters
               if all(is_number(p["params"].get(k)) for p in sweep["points"])]
    x_key = numeric[0] if numeric else None
    others = [k for k in parameters if k != x_key]
    if x_key is None:  # even spacing, labelled by the parameter values
        labels = {}
        for p in sweep["points"]:
            labels.setdefault(json.dumps(p["params"][parameters[0]]), len(labels))

    def x_of(point):
        if x_key is not None:
            return point["params"][x_key]
        return labels[json.dumps(point["params"][parameters[0]])]

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(len(keys), 1, figsize=(6.4, 2.6 * len(keys)), sharex=True,
                             squeeze=False)
    groups = {}
    for p in points:
        groups.setdefault(tuple(json.dumps(p["params"].get(k)) for k in others), []).append(p)
    for axis, key in zip(axes[:, 0], keys):
        for group, members in sorted(groups.items()):
            members = sorted(members, key=x_of)
            label = ", ".join(f"{k} = {json.loads(v)}" for k, v in zip(others, group)) or None
            xs = [x_of(p) for p in members if lookup(p["results"], key) is not None]
            ys = [lookup(p["results"], key) for p in members if lookup(p["results"], key) is not None]
            if not xs:
                continue
            line, = axis.plot(xs, ys, "-", label=label)
            for p in members:
                y = lookup(p["results"], key)
                if y is None:
                    continue
                done = p["status"] == "completed"
                axis.plot([x_of(p)], [y], "o", color=line.get_color(),
                          markerfacecolor=line.get_color() if done else "none")
        axis.set_ylabel(LABELS.get(key, key), fontsize=8)
        axis.grid(True, alpha=0.3)
        if len(groups) > 1:
            axis.legend(fontsize=7)
    bottom = axes[-1, 0]
    if x_key is not None:
        bottom.set_xlabel(LABELS.get(x_key, x_key))
    else:
        bottom.set_xticks(list(labels.values()))
        bottom.set_xticklabels([json.loads(v) for v in labels], rotation=20)
        bottom.set_xlabel(parameters[0])
    axes[0, 0].set_title(f"sweep {args.directory.name}: open markers ended early", fontsize=9)
    fig.tight_layout()
    temporary = args.directory / ".sweep.png.tmp"
    fig.savefig(temporary, dpi=120, format="png")
    os.replace(temporary, args.directory / "sweep.png")


if __name__ == "__main__":
    main()
