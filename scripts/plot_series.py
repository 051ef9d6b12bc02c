#!/usr/bin/python3
"""A series study's figure: writes DIR/series.png.

usage: scripts/plot_series.py DIR

DIR is a series study directory (growshell run SCENE.json --out DIR with study.kind
"series"). One panel per key of study.series_report: the key's value in each point's
results.json against the varying scene key, every point marked and labelled with its value;
points that did not complete are drawn hollow, and points without the value are left out and
listed under the panel. Units follow the names: keys starting with phi_ are excess angles in
radians, thickness and geometry.* lengths in metres. Needs matplotlib (Debian:
python3-matplotlib).
"""
import json
import pathlib
import sys


def fail(message):
    sys.exit(f"plot_series.py: {message}")


def label(key):
    """Axis label of a scene or results key, with its unit where the name tells it."""
    if key.startswith("phi_"):
        return f"{key} (rad)"
    if key == "thickness" or key.startswith("geometry.") or key.endswith("_radius"):
        return f"{key} (m)"
    if key.startswith("eb_hat"):
        return f"{key} (1/m$^2$)"
    return key


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        sys.exit(__doc__)
    directory = pathlib.Path(sys.argv[1])
    results_file = directory / "results.json"
    if not results_file.is_file():
        fail(f"{results_file} is missing: run the study first")
    try:
        results = json.loads(results_file.read_text())
    except json.JSONDecodeError as e:
        fail(f"{results_file} is not valid JSON ({e})")
    if results.get("study") != "series":
        fail(f"{results_file} is not a series study's (its study is {results.get('study')!r})")
    key, report, points = results.get("key"), results.get("report", []), results.get("points", [])
    if not key or not report:
        fail(f"{results_file} names no varying key or no reported key")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(report), figsize=(4.8 * len(report), 4.2), squeeze=False)
    for ax, name in zip(axes[0], report):
        xs = [p["value"] for p in points if p.get(name) is not None]
        ys = [p[name] for p in points if p.get(name) is not None]
        done = [p.get("status") == "completed" for p in points if p.get(name) is not None]
        ax.plot(xs, ys, "-", color="C0", lw=1)
        ax.plot([x for x, d in zip(xs, done) if d], [y for y, d in zip(ys, done) if d], "o",
                color="C0", label="completed")
        if not all(done):
            ax.plot([x for x, d in zip(xs, done) if not d], [y for y, d in zip(ys, done) if not d],
                    "o", mfc="none", color="C3", label="ended early")
        for x, y in zip(xs, ys):
            ax.annotate(f"{y:.4g}", (x, y), textcoords="offset points", xytext=(4, 4), fontsize=8)
        missing = [f"{p['value']:g}" for p in points if p.get(name) is None]
        ax.set_xlabel(label(key) + (f"\nno value at {', '.join(missing)}" if missing else ""))
        ax.set_ylabel(label(name))
        ax.set_title(f"{name} against {key}")
        ax.legend(fontsize=8)
    fig.suptitle(f"series of {results.get('of', '?')} studies: {results.get('end', '')}"[:120],
                 fontsize=9)
    fig.tight_layout()
    out = directory / "series.png"
    tmp = directory / ".series.png.tmp"
    fig.savefig(tmp, dpi=120, format="png")
    tmp.replace(out)


if __name__ == "__main__":
    main()
