#!/usr/bin/python3
"""The paper's Fig. 2 from a thickness_series study: writes DIR/thickness_series.png.

usage: scripts/plot_thickness_series.py DIR

DIR is a thickness_series study directory (growshell run SCENE.json --out DIR with
study.kind "thickness_series"). Left: the normalised bending energy E_b-hat against the excess
angle for every thickness, each from its point_NNN/branch.csv, with its maximum marked and
labelled with phi_e^max. Right: phi_e^max - L against h on logarithmic axes (L the series'
phi_max_limit, 2.57 by default) with the fitted power law A h^p of results.json. Needs
matplotlib (Debian: python3-matplotlib).
"""
import csv
import json
import pathlib
import sys


def fail(message):
    sys.exit(f"plot_thickness_series.py: {message}")


def read_branch(path):
    """(phi_e, E_b-hat) of the samples in a branch.csv."""
    phi, eb = [], []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            try:
                phi.append(float(row["phi_e"]))
                eb.append(float(row["Eb_hat"]))
            except (KeyError, ValueError):
                continue
    return phi, eb


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
    if results.get("study") != "thickness_series":
        fail(f"{results_file} is not a thickness_series study's")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    limit = results.get("phi_max_limit", 2.57)
    hs, excess = [], []
    for point in results.get("points", []):
        h = point["thickness"]
        branch = directory / point["branch_csv"]
        if branch.is_file():
            phi, eb = read_branch(branch)
            if phi:
                line, = left.plot(phi, eb, lw=1.2, label=f"h = {h:g} m")
                if point.get("phi_max") is not None and point.get("eb_hat_max") is not None:
                    left.plot([point["phi_max"]], [point["eb_hat_max"]], "o", color=line.get_color())
                    left.annotate(f"{point['phi_max']:.3f}", (point["phi_max"], point["eb_hat_max"]),
                                  textcoords="offset points", xytext=(4, 4), fontsize=8)
        if point.get("status") == "completed" and point.get("phi_max") is not None:
            if point["phi_max"] > limit:
                hs.append(h)
                excess.append(point["phi_max"] - limit)
    left.axvline(limit, color="0.6", ls=":", lw=1)
    left.set_xlabel(r"excess angle $\varphi_e$ (rad)")
    left.set_ylabel(r"$\hat{E}_b$ (1/m$^2$)")
    left.set_title(r"$\hat{E}_b(\varphi_e)$; dots: $\varphi_e^{max}$")
    left.legend(fontsize=8)

    right.loglog(hs, excess, "o", label="traced")
    fit = results.get("phi_max_fit")
    if fit and hs:
        lo, hi = min(hs), max(hs)
        xs = [lo * (hi / lo) ** (k / 50) for k in range(51)] if hi > lo else [lo]
        right.loglog(xs, [fit["amplitude"] * x ** fit["exponent"] for x in xs], "-",
                     label=(f"{fit['amplitude']:.3g} h^{fit['exponent']:.3f} "
                            f"(misfit {100 * fit['max_relative_misfit']:.1f} %)"))
    right.set_xlabel("thickness h (m)")
    right.set_ylabel(rf"$\varphi_e^{{max}} - {limit:g}$ (rad)")
    right.set_title(r"approach of $\varphi_e^{max}$ to its $h \to 0$ value")
    right.legend(fontsize=8)
    fig.tight_layout()
    out = directory / "thickness_series.png"
    tmp = directory / ".thickness_series.png.tmp"
    fig.savefig(tmp, dpi=130, format="png")
    tmp.replace(out)


if __name__ == "__main__":
    main()
