#!/usr/bin/python3
"""A branch.csv column of every completed point of a sweep, at given excess angles.

Each value is interpolated linearly in phi_e between the two samples of the point's
branch.csv around the angle (the cone's samples; the flat branch is not in branch.csv). For
example the core radius R_c (column core_radius: the reference radius within which half the
stretching energy lies) or the fold-pair chords (chord_up, chord_down: the smallest distance
between the two up-folds, and the two down-folds, over the distance from the apex), whose
h -> 0 values the symmetric cone is checked against (docs/results.md).

Usage: scripts/branch_column_at.py [--over-thickness] SWEEP_DIR COLUMN PHI [PHI ...]
Prints a Markdown table: a row per completed point, its swept parameters and the column at
each PHI ("—" where the trace does not reach it); --over-thickness divides the values by the
point's thickness h (e.g. R_c / h). Exit status 2 with a message naming the problem for a
directory without sweep.json, a PHI that is not a number, or a column branch.csv lacks.
"""

import csv
import json
import os
import sys


def fail(message):
    sys.stderr.write("branch_column_at.py: " + message + "\n")
    sys.exit(2)


def value_at(rows, column, phi):
    """The column interpolated at phi between consecutive rows, or None."""
    for a, b in zip(rows, rows[1:]):
        pa, pb = float(a["phi_e"]), float(b["phi_e"])
        if pa <= phi <= pb and pb > pa:
            t = (phi - pa) / (pb - pa)
            return float(a[column]) * (1 - t) + float(b[column]) * t
    return None


def main(argv):
    args = argv[1:]
    over_thickness = "--over-thickness" in args
    args = [a for a in args if a != "--over-thickness"]
    if len(args) < 3:
        fail("usage: branch_column_at.py [--over-thickness] SWEEP_DIR COLUMN PHI [PHI ...]")
    directory, column = args[0], args[1]
    try:
        phis = [float(p) for p in args[2:]]
    except ValueError:
        fail("every PHI must be a number, got %s" % " ".join(args[2:]))
    path = os.path.join(directory, "sweep.json")
    if not os.path.isfile(path):
        fail("%s is missing: not a sweep directory" % path)
    with open(path) as f:
        sweep = json.load(f)
    points = [p for p in sweep["points"] if p["status"] == "completed" and p.get("results")]
    keys = list(points[0]["params"]) if points else []
    unit = "%s / h" % column if over_thickness else column
    print("| " + " | ".join(keys + ["%s at %g" % (unit, phi) for phi in phis]) + " |")
    print("|" + "---|" * (len(keys) + len(phis)))
    for p in points:
        with open(os.path.join(directory, p["directory"], "branch.csv")) as f:
            rows = list(csv.DictReader(f))
        if rows and column not in rows[0]:
            fail("%s/branch.csv has no column %s" % (p["directory"], column))
        scale = p["results"]["thickness"] if over_thickness else 1.0
        cells = [str(p["params"][k]) for k in keys]
        for phi in phis:
            v = value_at(rows, column, phi)
            cells.append("—" if v is None else "%.4f" % (v / scale))
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv)
