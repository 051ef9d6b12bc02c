#!/usr/bin/python3
"""Accuracy against cost of the cone study: the error of phi_e^max, E_b-hat^max and
phi_e^kiss against a reference run, against the wall time, for the points of one or more
sweeps (growshell sweep) that vary one knob each (mesh size, core floor, quadrature degree,
tolerance, step, corrector). Writes PREFIX.md (a Markdown table) and PREFIX.png (error
against wall time, log-log, one panel per quantity, the default run marked), and prints the
cost exponent p of wall ~ unknowns^p over the points of the sweep named by --size-sweep.

usage: scripts/plot_accuracy_cost.py PREFIX --reference RUN_DIR --default RUN_DIR
                                     [--size-sweep SWEEP_DIR] SWEEP_DIR [SWEEP_DIR ...]

RUN_DIR is a study directory (results.json, e.g. a sweep's point_NNN); SWEEP_DIR a sweep's
directory (sweep.csv). The reference is the most resolved run; the default is the run of the
scene as shipped, marked on the plot. Needs matplotlib for the PNG (Debian:
python3-matplotlib); the table is written without it.
"""
import csv
import json
import math
import os
import sys

QUANTITIES = [("phi_max", r"$\varphi_e^{max}$", False),
              ("eb_hat_max", r"$\hat E_b^{max}$ (relative)", True),
              ("phi_kiss", r"$\varphi_e^{kiss}$", False)]


def fail(message):
    sys.exit(f"plot_accuracy_cost.py: {message}")


def read_results(directory):
    path = os.path.join(directory, "results.json")
    if not os.path.isfile(path):
        fail(f"{directory} has no results.json (not a finished study?)")
    with open(path) as f:
        return json.load(f)


def read_sweep(directory):
    path = os.path.join(directory, "sweep.csv")
    if not os.path.isfile(path):
        fail(f"{directory} has no sweep.csv (not a sweep's directory?)")
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(directory, "sweep.json")) as f:
        keys = [p["key"] for p in json.load(f)["parameters"]]
    points = []
    for row in rows:
        if row.get("status") != "completed":
            continue
        label = ", ".join(f"{k} = {row[k]}" for k in keys)
        points.append({"label": label, "directory": os.path.join(directory, row["directory"]),
                       "sweep": os.path.basename(os.path.normpath(directory)),
                       "unknowns": int(float(row["mesh.unknowns"])),
                       "wall": float(row["wall_seconds"]),
                       **{q: float(row[q]) if row.get(q) not in (None, "") else math.nan
                          for q, _, _ in QUANTITIES}})
    return points


def error(value, reference, relative):
    e = abs(value - reference)
    return e / abs(reference) if relative else e


def main(argv):
    args = argv[1:]
    if len(args) < 5 or "--reference" not in args or "--default" not in args:
        fail("usage: plot_accuracy_cost.py PREFIX --reference RUN_DIR --default RUN_DIR "
             "[--size-sweep SWEEP_DIR] SWEEP_DIR [SWEEP_DIR ...]")
    prefix = args.pop(0)
    options = {}
    for flag in ("--reference", "--default", "--size-sweep"):
        if flag in args:
            i = args.index(flag)
            if i + 1 >= len(args):
                fail(f"{flag} needs a directory")
            options[flag] = args[i + 1]
            del args[i:i + 2]
    sweeps = args
    if not sweeps:
        fail("give at least one sweep directory")
    reference = read_results(options["--reference"])
    default_dir = os.path.normpath(options["--default"])
    points = [p for s in sweeps for p in read_sweep(s)]
    if not points:
        fail("no completed point in the sweeps")
    reference_dir = os.path.normpath(options["--reference"])
    for p in points:
        p["errors"] = {q: error(p[q], reference[q], rel) for q, _, rel in QUANTITIES}
        p["default"] = os.path.normpath(p["directory"]) == default_dir
        p["reference"] = os.path.normpath(p["directory"]) == reference_dir

    lines = ["| sweep | run | unknowns | wall (s) | " +
             " | ".join(f"error of {q}" for q, _, _ in QUANTITIES) + " |",
             "|---|---|---:|---:|" + "---:|" * len(QUANTITIES)]
    for p in sorted(points, key=lambda p: (p["sweep"], p["wall"])):
        mark = " (default)" if p["default"] else " (reference)" if p["reference"] else ""
        lines.append(f"| {p['sweep']} | {p['label']}{mark} | {p['unknowns']} | {p['wall']:.1f} | " +
                     " | ".join(f"{p['errors'][q]:.1e}" for q, _, _ in QUANTITIES) + " |")
    exponent = None
    if "--size-sweep" in options:
        size = read_sweep(options["--size-sweep"])
        if len(size) >= 2:
            xs = [math.log(p["unknowns"]) for p in size]
            ys = [math.log(p["wall"]) for p in size]
            mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
            exponent = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / \
                sum((x - mx) ** 2 for x in xs)
            lines.append("")
            lines.append(f"Cost exponent over {options['--size-sweep']}: wall ~ unknowns^{exponent:.2f}")
    lines.append("")
    lines.append(f"Reference: {options['--reference']} (phi_max {reference['phi_max']:.6f}, "
                 f"eb_hat_max {reference['eb_hat_max']:.6f}, phi_kiss {reference['phi_kiss']:.6f})")
    with open(prefix + ".md", "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    if exponent is not None:
        print(f"cost exponent: {exponent:.2f}")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("plot_accuracy_cost.py: no matplotlib, table only", file=sys.stderr)
        return
    figure, axes = plt.subplots(1, len(QUANTITIES), figsize=(5 * len(QUANTITIES), 4.2))
    sweeps_seen = sorted({p["sweep"] for p in points})
    markers = "osD^vP<>"
    for ax, (q, label, _) in zip(axes, QUANTITIES):
        for k, s in enumerate(sweeps_seen):
            mine = sorted((p for p in points if p["sweep"] == s and not p["reference"]),
                          key=lambda p: p["wall"])
            ax.loglog([p["wall"] for p in mine], [max(p["errors"][q], 1e-12) for p in mine],
                      markers[k % len(markers)] + "-", label=s, alpha=0.8)
        for p in points:
            if p["default"]:
                ax.loglog([p["wall"]], [max(p["errors"][q], 1e-12)], "*", color="black",
                          markersize=14, label="default", zorder=5)
        ax.set_xlabel("wall time (s)")
        ax.set_ylabel(f"error of {label}")
        ax.grid(True, which="both", alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    unique = dict(zip(labels, handles))
    axes[0].legend(unique.values(), unique.keys(), fontsize=8)
    title = "cone study at h = 0.04: error against wall time"
    if exponent is not None:
        title += f" (wall ~ unknowns^{exponent:.2f})"
    figure.suptitle(title)
    figure.tight_layout()
    figure.savefig(prefix + ".png", dpi=110)
    print(f"wrote {prefix}.md, {prefix}.png")


if __name__ == "__main__":
    main(sys.argv)
