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
passes a phi_e twice (a fold), the first pair of samples around it counts
(scripts/econe_records.py).

Exit status 2 with a message naming the problem for a directory without results.json or
symmetric/branch.csv, another study's directory, or a PHI that is not a number.
"""

import json
import math
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from econe_records import bracket, read_rows, total_energy, value_at  # noqa: E402

CONE = ["phi_e", "E_stretch", "E_bend"]
CONTACT = CONE + ["E_penalty", "s4_defect", "gamma", "n_negative"]


def fail(message):
    sys.stderr.write("econe_branches_at.py: " + message + "\n")
    sys.exit(2)


def sorted_rows(path, columns):
    return sorted(read_rows(path, columns, fail), key=lambda r: r["phi_e"])


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
    symmetric = sorted_rows(directory / "symmetric" / "branch.csv", CONTACT)
    if not symmetric:
        fail(f"{directory} has no symmetric/branch.csv samples")
    cone = [r for r in sorted_rows(directory / "cone" / "branch.csv", CONE)
            if r["phi_e"] < symmetric[0]["phi_e"]]
    reference = cone + symmetric
    branches = [(name, sorted_rows(directory / name / "branch.csv", CONTACT))
                for name in ("skewed", "turned")]
    print("| φe | branch | (E − E_sym)/E_sym | S4 defect | γ | negative |")
    print("|---|---|---|---|---|---|")
    for phi in angles:
        e_sym = value_at(reference, phi, total_energy)
        for name, rows in branches:
            if not rows:
                continue
            pair = bracket(rows, phi)
            if pair is None or e_sym is None:
                print(f"| {phi:g} | {name} | — | — | — | — |")
                continue
            a, b = pair
            e = value_at(rows, phi, total_energy)
            defect = value_at(rows, phi, lambda r: r["s4_defect"])
            gamma = value_at(rows, phi, lambda r: r["gamma"])
            nearer = a if abs(a["phi_e"] - phi) <= abs(b["phi_e"] - phi) else b
            gamma_text = f"{gamma:.4f}" if math.isfinite(gamma) else "—"
            print(f"| {phi:g} | {name} | {100.0 * (e - e_sym) / e_sym:+.3f} % | {defect:.4f} "
                  f"| {gamma_text} | {int(nearer['n_negative'])} |")


if __name__ == "__main__":
    main()
