"""scripts/econe_branches_at.py on a small synthetic econe_contact directory: the relative
energies, S4 defects and gammas it prints are the linear interpolations of the records (the
symmetric branch joined below its first sample by the contact-free cone), a branch that was
not traced is left out, and bad input is refused with a message that names the problem."""

import json
import os
import tempfile

from script_checks import (Checks, check_refuses_other_directories, run_script,
                           write_contact_branch)

def branch(path, rows):
    """rows: (phi, energy, s4_defect, gamma, negative); the energy split over E_s, E_b and P."""
    write_contact_branch(path, [
        {"phi_e": phi, "E_stretch": energy / 2, "E_bend": energy / 4, "E_penalty": energy / 4,
         "Eb_hat": 3, "gamma": gamma, "n_negative": negative, "s4_defect": defect}
        for phi, energy, defect, gamma, negative in rows])


def main():
    check = Checks()
    with tempfile.TemporaryDirectory() as d:
        check_refuses_other_directories(check, "econe_branches_at.py", d, "6", status=2)
        with open(os.path.join(d, "results.json"), "w") as f:
            json.dump({"study": "econe_contact"}, f)
        no_branch = run_script("econe_branches_at.py", d, "6")
        check(no_branch.returncode == 2 and "symmetric/branch.csv" in no_branch.stderr,
              f"a directory without the symmetric branch is refused: {no_branch.stderr!r}")

        # The contact-free cone (E_s + E_b only) below the symmetric branch's first sample.
        os.makedirs(os.path.join(d, "cone"))
        with open(os.path.join(d, "cone", "branch.csv"), "w") as f:
            f.write("phi_e,E_stretch,E_bend,Eb_hat,n_negative\n")
            f.write("5.0,0.5,0.5,3,0\n6.0,0.5,0.5,3,0\n6.5,1.0,1.0,3,0\n")
        branch(os.path.join(d, "symmetric", "branch.csv"),
               [(6.5, 2.0, 0.0, float("nan"), 0), (7.5, 4.0, 0.0, 1.5708, 1)])
        # Written as traced: down from 7.0, then up.
        branch(os.path.join(d, "turned", "branch.csv"),
               [(7.0, 2.97, 0.01, 1.5, 0), (5.0, 0.99, 0.0, float("nan"), 0),
                (7.5, 3.96, 0.03, 1.4, 0)])
        bad = run_script("econe_branches_at.py", d, "six")
        check(bad.returncode == 2 and "number" in bad.stderr,
              f"an angle that is not a number is refused: {bad.stderr!r}")
        out = run_script("econe_branches_at.py", d, "5.5", "7.25", "8")
        check(out.returncode == 0, f"it runs: {out.stderr!r}")
        rows = [line for line in out.stdout.splitlines() if line.startswith("| ") and
                not line.startswith("| φe")]
        # At 5.5 the cone gives E_sym = 1.0 and the turned branch 0.99 + 0.5 * (2.97 - 0.99) / 2.
        turned_55 = 0.99 + (5.5 - 5.0) / 2.0 * (2.97 - 0.99)
        check(len(rows) == 3, f"one row per angle for the turned branch only: {out.stdout!r}")
        if len(rows) == 3:
            check(f"{100 * (turned_55 - 1.0) / 1.0:+.3f} %" in rows[0],
                  f"the relative energy at 5.5 against the cone: {rows[0]!r}")
            # At 7.25: E_sym = 3.5, turned 2.97 + 0.5 * 0.99 = 3.465; S4 0.02, gamma 1.45.
            check("-1.000 %" in rows[1] and "0.0200" in rows[1] and "1.4500" in rows[1],
                  f"the values at 7.25: {rows[1]!r}")
            check("—" in rows[2], f"an angle beyond the branches: {rows[2]!r}")
    check.finish()


if __name__ == "__main__":
    main()
