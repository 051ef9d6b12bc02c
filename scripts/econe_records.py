"""The branch records of an econe_contact study (DIR/cone, DIR/symmetric, DIR/skewed,
DIR/turned: branch.csv) as the scripts that read them share them: the study's directory and
results.json from the command line, the rows as floats, a row's total energy, a value between
the two samples that bracket an excess angle, and the special points marked on a figure. Used
by plot_econe_contact.py, plot_contact_angle.py and econe_branches_at.py."""

import csv
import json
import math
import pathlib
import sys


def econe_study(usage, fail):
    """(directory, results) of the econe_contact study named by the one command-line argument:
    exits with `usage` for no argument or --help, calls fail(message) for a directory that is
    not such a study's output (no results.json, or another study's)."""
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        sys.exit(usage)
    directory = pathlib.Path(sys.argv[1])
    if not directory.is_dir():
        fail(f"{directory} is not a directory")
    results_path = directory / "results.json"
    if not results_path.is_file():
        fail(f"{directory} has no results.json (not a finished econe_contact study?)")
    results = json.loads(results_path.read_text())
    if results.get("study") != "econe_contact":
        fail(f"{results_path} is not an econe_contact study's (study: {results.get('study')})")
    return directory, results


def study_label(results):
    """'h = H m, FAMILY mesh, size_slope S' of a study's results.json, for a figure's title."""
    mesh = results.get("mesh", {})
    slope = mesh.get("size_slope")
    size = f", size_slope {slope:g}" if slope is not None else ""
    return f"h = {results.get('thickness'):g} m, {mesh.get('family')} mesh{size}"


def save_figure(fig, directory, name):
    """Writes the figure to directory/name (PNG, 120 dpi) whole, then renamed into place: a
    reader never sees half a figure."""
    temporary = directory / f".{name}.tmp"
    fig.savefig(temporary, dpi=120, format="png")
    temporary.replace(directory / name)


def mark_special_points(top, axes, results, at_top):
    """Marks first contact and phi_e^crit by stability and by energy (results.json) on every axis
    of `axes` as vertical lines, labelled with their phi_e on `top`, the labels stacked down
    from its top edge (at_top) or up from its bottom edge. A phi_e^crit by energy met only at
    the skewed trace's lowest sample is an upper bound."""
    bound = results.get("phi_crit_energy_criterion") == "lowest_sample"
    against = results.get("phi_crit_energy_reference", "symmetric")
    marks = [("phi_first_contact", "first contact", "=", "tab:green"),
             ("phi_crit_stability", r"$\phi_e^{crit}$ (stability)", "=", "tab:purple"),
             ("phi_crit_energy", r"$\phi_e^{crit}$ (energy vs " + against + ")",
              r"$\leq$" if bound else "=", "black")]
    for row, (key, label, relation, colour) in enumerate(marks):
        value = results.get(key)
        if not (isinstance(value, (int, float)) and math.isfinite(value)):
            continue
        for axis in axes:
            axis.axvline(value, color=colour, linestyle=":", linewidth=1.2)
        # Labels of marks in the right half end at their line, so that they stay inside.
        low, high = top.get_xlim()
        right = value > 0.5 * (low + high)
        top.annotate(f"{label} {relation} {value:.4f}", (value, 1.0 if at_top else 0.0),
                     xycoords=("data", "axes fraction"),
                     xytext=(-3 if right else 3, -12 - 12 * row if at_top else 4 + 12 * row),
                     textcoords="offset points", ha="right" if right else "left", fontsize=8,
                     color=colour)


def read_rows(path, columns, fail):
    """The rows of the CSV file `path` (a pathlib.Path) as dicts of `columns` to floats, in the
    file's order; [] if there is no such file. Calls fail(message) if a column is missing."""
    if not path.is_file():
        return []
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for column in columns:
        if rows and column not in rows[0]:
            fail(f"{path} has no column '{column}'")
    return [{c: float(r[c]) for c in columns} for r in rows]


def total_energy(row):
    """E_s + E_b (+ the penalty, on a branch with contact) of a row, J."""
    return row["E_stretch"] + row["E_bend"] + row.get("E_penalty", 0.0)


def bracket(rows, phi):
    """The first two consecutive rows of `rows` (by increasing phi_e) with distinct phi_e
    between which phi lies, or None."""
    for a, b in zip(rows, rows[1:]):
        if a["phi_e"] <= phi <= b["phi_e"] and a["phi_e"] != b["phi_e"]:
            return a, b
    return None


def value_at(rows, phi, value):
    """value(row) at phi, linear in phi_e between the rows that bracket it; None outside."""
    pair = bracket(rows, phi)
    if pair is None:
        return None
    a, b = pair
    t = (phi - a["phi_e"]) / (b["phi_e"] - a["phi_e"])
    return value(a) + t * (value(b) - value(a))
