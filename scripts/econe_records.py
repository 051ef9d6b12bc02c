"""The branch records of an econe_contact study (DIR/cone, DIR/symmetric, DIR/skewed,
DIR/turned: branch.csv) as the scripts that read them share them: the rows as floats, a row's
total energy, and a value between the two samples that bracket an excess angle. Used by
plot_econe_contact.py and econe_branches_at.py."""

import csv


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
