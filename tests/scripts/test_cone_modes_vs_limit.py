"""scripts/cone_modes_vs_limit.py on a small synthetic cone_mode_sectors table: the lowest
mode of each class is taken, L_eff is lambda R^4 / (2 D lambda_limit) with the limit's
eigenvalue interpolated between physics.md's rows, the ratios stand beside the limit's, and a
missing table is named."""

import json
import os
import tempfile

from script_checks import Checks, run_script


def main():
    check = Checks()
    with tempfile.TemporaryDirectory() as d:
        usage = run_script("cone_modes_vs_limit.py")
        check(usage.returncode == 2, f"without a directory it prints its usage: {usage.returncode}")
        scene = {"thickness": 0.04, "geometry": {"radius": 1.0},
                 "material": {"youngs_modulus": 1e4, "poisson_ratio": 0.3},
                 "mesh": {"family": "rings", "size_slope": 0.1}}
        with open(os.path.join(d, "scene.json"), "w") as f:
            json.dump(scene, f)
        missing = run_script("cone_modes_vs_limit.py", d)
        check(missing.returncode == 1 and "mode_sectors.csv" in missing.stderr,
              f"a missing table is named: {missing.stderr!r}")
        with open(os.path.join(d, "mode_sectors.csv"), "w") as f:
            f.write("phi_e,sector,class,lambda,s4_parity,peak_radius,lambda_pinned\n")
            # At 5.5, halfway between the limit's rows at 5 and 6: B2 (2.082 + 1.744) / 2 = 1.913,
            # E (2.995 + 2.110) / 2 = 2.5525, B1 (15.75 + 10.58) / 2 = 13.165.
            for row in ("5.5,even_even,B2,1.0,-1,1,0.8", "5.5,even_even,B2,3.0,-1,1,2.5",
                        "5.5,even_even,A1,9.0,1,1,9.0", "5.5,odd_odd,A2,-0.002,1,1,-0.001",
                        "5.5,odd_odd,B1,5.0,-1,1,2.0", "5.5,even_odd,E,1.5,0,1,1.2"):
                f.write(row + "\n")
        out = run_script("cone_modes_vs_limit.py", d)
        check(out.returncode == 0, f"it runs: {out.stderr!r}")
        rows = [line.split("|")[1:-1] for line in out.stdout.splitlines()
                if line.startswith("| rings")]
        check(len(rows) == 1, f"one row for the one state: {out.stdout!r}")
        if rows:
            cells = [c.strip() for c in rows[0]]
            stiffness = 1e4 * 0.04**3 / (12 * (1 - 0.3**2))
            expected = {
                "λ B2": "1", "λ E": "1.5", "λ B1": "5", "turn": "-0.002",
                "L_eff B2": f"{1.0 / (2 * stiffness * 1.913):.2f}",
                "L_eff E": f"{1.5 / (2 * stiffness * 2.5525):.2f}",
                "L_eff B1": f"{5.0 / (2 * stiffness * 13.165):.2f}",
                "E/B2": f"1.500 ({2.5525 / 1.913:.3f})",
                "B1/B2": f"5.00 ({13.165 / 1.913:.2f})",
            }
            got = dict(zip(["λ B2", "λ E", "λ B1", "turn", "L_eff B2", "L_eff E", "L_eff B1",
                            "E/B2", "B1/B2"], cells[4:]))
            for key, value in expected.items():
                check(got.get(key) == value, f"{key}: {got.get(key)!r}, expected {value!r}")
            check(cells[:4] == ["rings", "0.1", "0.04", "5.500"],
                  f"the mesh, its size_slope, h and phi_e lead the row: {cells[:4]}")
    check.finish()


if __name__ == "__main__":
    main()
