#!/usr/bin/python3
"""The branches of an econe_contact study side by side at given excess angles.

Usage: scripts/econe_branches_at.py DIR PHI [PHI ...]

DIR is an econe_contact study's output directory (growshell run). For each PHI, and each of
the skewed and the turned branch (skewed/branch.csv, turned/branch.csv; a branch the study did
not trace is left out), prints a Markdown row: the branch's total energy E = E_s + E_b + penalty
relative to the symmetric branch's at the same phi_e, (E - E_sym) / E_sym, its S4 defect, the
angle gamma between its contact planes (NaN without two contact zones) and its negative count.
The symmetric branch below its first sample with contact is the contact-free cone
(cone/branch.csv). Values are interpolated linearly in phi_e between the two samples around
PHI (the negative count is the nearer sample's); "—" where a branch does not reach PHI. A
branch traced both ways (down from its start, then up) is sorted by phi_e first; where it
passes a phi_e twice (a fold), the first pair of samples around it counts.

Exit status 2 with a message naming the problem for a directory without results.json or
symmetric/branch.csv, another study's directory, or a PHI that is not a number.
"""

import csv
import json
import math
import pathlib
import sys


def fail(message):
    sys.stderr.write("econe_branches_at.py: " + message + "\n")
    sys.exit(2)


def read_rows(path):
    if not path.is_file():
        return []
    with open(path, newline="") as f:
        rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]
    rows.sort(key=lambda r: r["phi_e"])
    return rows


def energy(row):
    return row["E_stretch"] + row["E_bend"] + row.get("E_penalty", 0.0)


def around(rows, phi):
    """The first two consecutive rows whose phi_e bracket phi, or None."""
    for a, b in zip(rows, rows[1:]):
        if a["phi_e"] <= phi <= b["phi_e"]:
            return a, b
    return None


def interpolate(a, b, phi, value):
    if b["phi_e"] == a["phi_e"]:
        return value(a)
    t = (phi - a["phi_e"]) / (b["phi_e"] - a["phi_e"])
    return value(a) + t * (value(b) - value(a))


def main():
    if len(sys.argv) < 3 or sys.argv[1] in ("-h", "--help"):
        sys.exit(__doc__)
    directory = pathlib.Path(sys.argv[1])
    results_path = directory / "results.json"
    if not results_path.is_file():
        fail(f"{directory} has no results.json (not an econe_contact study's directory?)")
    study = json.loads(results_path.read_text()).get("study")
    if study != "econe_contact":
        fail(f"{results_path} is not an econe_contact study's (study: {study})")
    try:
        angles = [float(a) for a in sys.argv[2:]]
    except ValueError:
        fail(f"the excess angles must be numbers: {' '.join(sys.argv[2:])}")
    if not all(math.isfinite(a) for a in angles):
        fail(f"the excess angles must be finite: {' '.join(sys.argv[2:])}")
    symmetric = read_rows(directory / "symmetric" / "branch.csv")
    if not symmetric:
        fail(f"{directory} has no symmetric/branch.csv samples")
    cone = [r for r in read_rows(directory / "cone" / "branch.csv")
            if r["phi_e"] < symmetric[0]["phi_e"]]
    reference = cone + symmetric
    branches = [(name, read_rows(directory / name / "branch.csv"))
                for name in ("skewed", "turned")]
    print("| φe | branch | (E − E_sym)/E_sym | S4 defect | γ | negative |")
    print("|---|---|---|---|---|---|")
    for phi in angles:
        ref = around(reference, phi)
        for name, rows in branches:
            if not rows:
                continue
            pair = around(rows, phi)
            if pair is None or ref is None:
                print(f"| {phi:g} | {name} | — | — | — | — |")
                continue
            a, b = pair
            e_sym = interpolate(*ref, phi, energy)
            e = interpolate(a, b, phi, energy)
            defect = interpolate(a, b, phi, lambda r: r["s4_defect"])
            gamma = interpolate(a, b, phi, lambda r: r["gamma"])
            nearer = a if abs(a["phi_e"] - phi) <= abs(b["phi_e"] - phi) else b
            gamma_text = f"{gamma:.4f}" if math.isfinite(gamma) else "—"
            print(f"| {phi:g} | {name} | {100.0 * (e - e_sym) / e_sym:+.3f} % | {defect:.4f} "
                  f"| {gamma_text} | {int(nearer['n_negative'])} |")


if __name__ == "__main__":
    main()
