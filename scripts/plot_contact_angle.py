#!/usr/bin/python3
"""The contact angle and the energy ratio of an econe_contact study (the paper's Fig. 5):
writes DIR/contact_angle.png.

usage: scripts/plot_contact_angle.py DIR

DIR is an econe_contact study's output directory (growshell run). Top: gamma(phi_e), the angle
between the two contact planes (physics.md), of each branch traced with contact (symmetric,
skewed, turned against the mesh, and the winding beyond them): as a line, gamma from the
penalty's pair forces at every sample (the "gamma" column of BRANCH/branch.csv), which reads
low (docs/results.md); as filled markers, gamma from Ipopt's multipliers under the hard
constraints at the points of study.hard_contact_at (results.json's hard_contact, "hard_gamma"),
the value to report. Bottom: the energy ratio f = E_s / E_b (stretching over bending energy)
of the same branches, on a logarithmic axis. First contact and phi_e^crit (by stability and by
energy) are marked with their phi_e. Stable samples (n_negative = 0) solid, unstable dashed.
Prints, per branch, f at its highest sample (results.json's energy_ratio_f) and the hard
constraints' gamma at each checked point. Needs matplotlib (Debian: python3-matplotlib).
"""
import math
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from plot_study import pyplot, stability_runs  # noqa: E402
from econe_records import (econe_study, mark_special_points, read_rows, save_figure,  # noqa: E402
                           study_label)

COLUMNS = ["phi_e", "E_stretch", "E_bend", "gamma", "n_negative"]
COLOURS = {"symmetric": "tab:blue", "skewed": "tab:red", "turned": "tab:orange",
           "wound": "tab:brown"}
NAMES = {"symmetric": "symmetric", "skewed": "skewed", "turned": "turned against the mesh",
         "wound": "winding"}


def fail(message):
    sys.exit(f"plot_contact_angle.py: {message}")


def finite(value):
    return isinstance(value, (int, float)) and math.isfinite(value)


def branch_rows(directory, results):
    """(key, rows by increasing phi_e) of each branch with contact that has samples."""
    paths = [("symmetric", results.get("symmetric_csv")), ("skewed", results.get("skewed_csv")),
             ("turned", results.get("turned_csv")), ("wound", results.get("wound_csv"))]
    out = []
    for key, relative in paths:
        if not relative:
            continue
        rows = read_rows(directory / relative, COLUMNS, fail)
        if key in ("skewed", "turned"):  # written as traced: down, then up from the start
            rows.sort(key=lambda r: r["phi_e"])
        if rows:
            out.append((key, rows))
    return out


def main():
    directory, results = econe_study(__doc__, fail)
    branches = branch_rows(directory, results)
    if not branches:
        fail(f"{directory} has no samples with contact (symmetric/branch.csv is empty)")
    hard = {}
    for check in results.get("hard_contact", []):
        if check.get("converged") and finite(check.get("hard_gamma")):
            hard.setdefault(check["branch"], []).append((check["phi_e"], check["hard_gamma"]))
    for key, rows in branches:
        top_row = max(rows, key=lambda r: r["phi_e"])
        ratio = top_row["E_stretch"] / top_row["E_bend"] if top_row["E_bend"] else math.nan
        points = "; ".join(f"{g:.4f} at {p:.4f}" for p, g in sorted(hard.get(key, [])))
        print(f"{key}: f = {ratio:.6g} at phi_e = {top_row['phi_e']:.6g}"
              + (f"; gamma (hard constraints) {points}" if points else ""))
    plt = pyplot(fail)

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 8), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 2]})
    for key, rows in branches:
        colour = COLOURS[key]
        labelled = False
        for first, last, stable in stability_runs([r["n_negative"] for r in rows]):
            run = rows[first:last + 1]
            style = "-" if stable else "--"
            label = None if labelled else f"{NAMES[key]} (penalty's forces)"
            labelled = True
            angle = [(r["phi_e"], r["gamma"]) for r in run if math.isfinite(r["gamma"])]
            top.plot([p for p, _ in angle], [g for _, g in angle], style, color=colour,
                     linewidth=1.0, alpha=0.7, label=label)
            ratio = [(r["phi_e"], r["E_stretch"] / r["E_bend"]) for r in run
                     if r["E_bend"] > 0.0 and r["E_stretch"] > 0.0]
            bottom.plot([p for p, _ in ratio], [f for _, f in ratio], style, color=colour,
                        linewidth=1.5)
        bottom.plot([], [], "-", color=colour, linewidth=1.5, label=NAMES[key])
    for key, points in hard.items():
        points.sort()
        top.plot([p for p, _ in points], [g for _, g in points], "o-",
                 color=COLOURS.get(key, "black"), markersize=6, linewidth=2.0,
                 label=f"{NAMES.get(key, key)} (hard constraints)")
    top.axhline(math.pi / 2, color="gray", linewidth=0.8, linestyle="-.")
    top.annotate(r"$\pi/2$", (0.0, math.pi / 2), xycoords=("axes fraction", "data"),
                 xytext=(3, 3), textcoords="offset points", fontsize=8, color="gray")
    top.plot([], [], "k-", label="stable")
    top.plot([], [], "k--", label="unstable")
    mark_special_points(top, (top, bottom), results, at_top=False)
    top.set_title(f"contact angle and energy ratio: {study_label(results)}", fontsize=10)
    top.set_ylabel(r"angle between the contact planes $\gamma$ (rad)")
    bottom.set_ylabel(r"energy ratio $f = E_s / E_b$")
    bottom.set_yscale("log")
    bottom.set_xlabel(r"excess angle $\phi_e$ (rad)")
    for axis in (top, bottom):
        axis.grid(True, alpha=0.3)
    top.legend(loc="center left", fontsize=8)
    bottom.legend(loc="best", fontsize=8)
    fig.tight_layout()
    save_figure(fig, directory, "contact_angle.png")


if __name__ == "__main__":
    main()
