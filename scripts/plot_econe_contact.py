#!/usr/bin/python3
"""The two e-cone branches of an econe_contact study: writes DIR/econe_contact.png.

usage: scripts/plot_econe_contact.py DIR

DIR is an econe_contact study's output directory (growshell run). Top: E_b-hat against phi_e
of the contact-free cone (cone/branch.csv), the symmetric branch with contact
(symmetric/branch.csv), the skewed branch (skewed/branch.csv) and, where the study traced it,
the cone turned against the mesh (turned/branch.csv) and the winding beyond the skewed branch
(wound/branch.csv, study.wind_to: strict minima only, its jumps marked) and the n-fold cones
of study.compare_modes (cone_nN/branch.csv, without contact), stable samples
(n_negative = 0) solid and unstable ones dashed. Bottom: the total energy of each branch
relative to the symmetric branch's at the same phi_e, (E - E_sym) / E_sym, so that the crossing
shows, and the turned cone's lies below it (the n-fold cones, tens of per cent above, are drawn
on top only, their least excess over the two-fold cone in the legend). The special values of results.json (first contact, phi_e^crit by stability and by
energy) are marked with their phi_e. Needs matplotlib (Debian: python3-matplotlib).
"""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from plot_study import pyplot, stability_runs  # noqa: E402
from econe_records import (econe_study, mark_special_points, read_rows, save_figure,  # noqa: E402
                           study_label, total_energy, value_at)


def fail(message):
    sys.exit(f"plot_econe_contact.py: {message}")


def main():
    directory, results = econe_study(__doc__, fail)
    base = ["phi_e", "E_stretch", "E_bend", "Eb_hat", "n_negative"]
    cone = [r for r in read_rows(directory / "cone" / "branch.csv", base, fail)
            if r["phi_e"] >= (results.get("phi_branch") or 0.0)]
    contact = base + ["E_penalty"]
    symmetric = read_rows(directory / "symmetric" / "branch.csv", contact, fail)
    skewed = read_rows(directory / "skewed" / "branch.csv", contact, fail)
    turned = read_rows(directory / "turned" / "branch.csv", contact, fail)
    wound_csv = results.get("wound_csv")
    wound = read_rows(directory / wound_csv, contact, fail) if wound_csv else []
    others = []
    for entry in results.get("compared_modes", []):
        rows = [r for r in read_rows(directory / entry["csv"], base, fail)
                if r["phi_e"] >= (entry.get("phi_branch") or 0.0)]
        above = entry.get("lowest_energy_above_two_fold")
        note = f", at least {100 * above:.0f} % above" if isinstance(above, (int, float)) else ""
        others.append((f"{entry['mode']}-fold cone, without contact{note}", rows))
    if not cone and not symmetric:
        fail(f"{directory} has neither cone/branch.csv nor symmetric/branch.csv samples")
    # The skewed branch is written as traced: down from the relaxed state, then up from it.
    skewed.sort(key=lambda r: r["phi_e"])
    turned.sort(key=lambda r: r["phi_e"])
    plt = pyplot(fail)

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 8), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 2]})
    reference = cone + symmetric
    branches = [("cone without contact", cone, "tab:gray"),
                ("symmetric, with contact", symmetric, "tab:blue"),
                ("skewed, with contact", skewed, "tab:red"),
                ("turned against the mesh, with contact", turned, "tab:orange"),
                ("grown on from the "
                 + (results.get("wound") or {}).get("start_branch", "skewed")
                 + " cone (winding)", wound, "tab:brown")]
    palette = ["tab:green", "tab:cyan", "tab:pink", "tab:olive"]
    branches += [(name, rows, palette[k % len(palette)]) for k, (name, rows) in enumerate(others)]
    # The other cones lie tens of per cent above the two-fold one: in the bottom panel they
    # would hide the per-cent differences it is there for, so they are drawn on top only.
    top_only = {name for name, _ in others}
    for name, rows, color in branches:
        labelled = False
        for first, last, stable in stability_runs([r["n_negative"] for r in rows]):
            run = rows[first:last + 1]
            label = None
            if not labelled:
                label = name
                labelled = True
            style = "-" if stable else "--"
            top.plot([r["phi_e"] for r in run], [r["Eb_hat"] for r in run], style, color=color,
                     linewidth=1.5, label=label)
            points = [(r["phi_e"], value_at(reference, r["phi_e"], total_energy), total_energy(r))
                      for r in run]
            points = [(p, (e - s) / s) for p, s, e in points if s]
            if points and name not in top_only:
                bottom.plot([p for p, _ in points], [v for _, v in points], style, color=color,
                            linewidth=1.5)
    for jump in (results.get("wound") or {}).get("jumps", []):
        top.axvline(jump, color="tab:brown", linestyle=":", linewidth=0.8)
        top.annotate(f"jump {jump:.3f}", (jump, 0.0), xycoords=("data", "axes fraction"),
                     xytext=(2, 4), textcoords="offset points", fontsize=7, color="tab:brown",
                     rotation=90)
    top.plot([], [], "k-", label="stable")
    top.plot([], [], "k--", label="unstable")
    mark_special_points(top, (top, bottom), results, at_top=True)
    radius = results.get("exclusion_radius", float("nan")) / results.get("thickness", 1)
    top.set_title(f"e-cone through contact: {study_label(results)}, exclusion radius "
                  f"{radius:.3g} h", fontsize=10)
    top.set_ylabel(r"normalised bending energy $\hat{E}_b$ (1/m$^2$)")
    bottom.set_ylabel(r"$(E - E_{sym}) / E_{sym}$, $E = E_s + E_b + E_{penalty}$")
    bottom.set_xlabel(r"excess angle $\phi_e$ (rad)")
    bottom.axhline(0.0, color="tab:blue", linewidth=0.8)
    for axis in (top, bottom):
        axis.grid(True, alpha=0.3)
    top.legend(loc="best", fontsize=8)
    fig.tight_layout()
    save_figure(fig, directory, "econe_contact.png")


if __name__ == "__main__":
    main()
