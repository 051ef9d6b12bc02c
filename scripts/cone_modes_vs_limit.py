#!/usr/bin/env python3
"""The softest modes of traced symmetric cones against the h -> 0 cone's.

usage: cone_modes_vs_limit.py [--csv NAME] RUN_DIR...

Reads RUN_DIR/NAME (default mode_sectors.csv), written by `cone_mode_sectors RUN_DIR --at ...`
on a cone traced in the mirror subspace of a mesh with the cone's symmetry (rings, gmsh_d4): the
lowest modes of each symmetry class of the group D2d (A1, B2, A2, B1, E), and RUN_DIR/scene.json.
For the lowest B2, E and B1 modes it prints, at each state:
  λ (N/m^3)   the sheet's eigenvalue, second variation per integral of |dx|^2 dA
  L_eff       λ R^4 / (2 D λ_limit): for a cone x = r u(s) whose curve u has the second
              variation λ_limit of ../shared/docs/physics.md ("Stability of the h -> 0 cone"),
              the bending energy (D/2) ln(R/r_c) W and the norm (R^4/4) ∫|du|^2 ds give
              λ = 2 D ln(R/r_c) λ_limit / R^4, so L_eff is the cone's effective ln(R/r_c): one
              value for every mode when the sheet's modes are the limit's
  ratios      E/B2 and B1/B2, against the limit's, which need no normalisation
and the pattern's turn (A2, zero on a perfect disc). The limit's eigenvalues between the
tabulated excess angles are interpolated linearly (and extrapolated up to 0.1 beyond them). Prints a markdown table; exits 1 naming the
first file that is missing or lacks a column.
"""
import csv
import json
import math
import sys
from pathlib import Path

# ../shared/docs/physics.md, "Stability of the h -> 0 cone": phi_e, λ1 (B2), λ2 = λ3 (E), λ4 (B1).
LIMIT = [(4.0, 2.549, 4.472, 24.80), (5.0, 2.082, 2.995, 15.75), (6.0, 1.744, 2.110, 10.58),
         (6.4, 1.635, 1.856, 9.148), (7.0, 1.494, 1.548, 7.453), (7.07, 1.480, 1.517, 7.284)]


def limit_at(phi):
    """(λ_B2, λ_E, λ_B1) of the h -> 0 cone at phi: linear between the table's rows, and
    within 0.1 beyond its ends along its first or last interval; None further out."""
    if not LIMIT[0][0] - 0.1 <= phi <= LIMIT[-1][0] + 0.1:
        return None
    pairs = list(zip(LIMIT, LIMIT[1:]))
    row0, row1 = next(((a, b) for a, b in pairs if phi <= b[0]), pairs[-1])
    t = (phi - row0[0]) / (row1[0] - row0[0])
    return tuple(a + t * (b - a) for a, b in zip(row0[1:], row1[1:]))


def main(argv):
    args = list(argv[1:])
    name = "mode_sectors.csv"
    if len(args) >= 2 and args[0] == "--csv":
        name, args = args[1], args[2:]
    if not args or any(a.startswith("-") for a in args):
        print(__doc__, file=sys.stderr)
        return 2
    print("| mesh | size_slope | h | φe | λ B2 | λ E | λ B1 | turn (A2) | L_eff B2 | L_eff E | L_eff B1 "
          "| E/B2 (limit) | B1/B2 (limit) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for run in map(Path, args):
        try:
            scene = json.loads((run / "scene.json").read_text())
            with open(run / name, newline="") as f:
                rows = list(csv.DictReader(f))
            by_phi = {}
            for row in rows:
                lowest = by_phi.setdefault(float(row["phi_e"]), {})
                value = float(row["lambda"])
                if row["class"] not in lowest or value < lowest[row["class"]]:
                    lowest[row["class"]] = value
        except (OSError, ValueError, KeyError) as error:
            print(f"cone_modes_vs_limit.py: {run / name}: {error}", file=sys.stderr)
            return 1
        h = scene["thickness"]
        nu = scene["material"]["poisson_ratio"]
        bending_stiffness = scene["material"]["youngs_modulus"] * h**3 / (12 * (1 - nu**2))
        radius = scene["geometry"]["radius"]
        for phi, lowest in sorted(by_phi.items()):
            b2, e, b1 = (lowest.get(c, math.nan) for c in ("B2", "E", "B1"))
            limit = limit_at(phi)
            cells = [scene["mesh"]["family"], f"{scene['mesh']['size_slope']:g}", f"{h:g}", f"{phi:.3f}", f"{b2:.4g}", f"{e:.4g}",
                     f"{b1:.4g}", f"{lowest.get('A2', math.nan):.2g}"]
            for value, index in ((b2, 0), (e, 1), (b1, 2)):
                cells.append(f"{value * radius**4 / (2 * bending_stiffness * limit[index]):.2f}"
                             if limit else "—")
            cells.append(f"{e / b2:.3f} ({limit[1] / limit[0]:.3f})" if limit else f"{e / b2:.3f}")
            cells.append(f"{b1 / b2:.2f} ({limit[2] / limit[0]:.2f})" if limit else f"{b1 / b2:.2f}")
            print("| " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
