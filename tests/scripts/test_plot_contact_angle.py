"""scripts/plot_contact_angle.py on a small synthetic econe_contact directory: the energy ratio
f = E_s / E_b it prints at each branch's highest sample and the hard constraints' gamma it
takes from results.json are the numbers written there, the figure is written (where matplotlib
is installed), and a directory that is not such a study's output is refused by name."""

import json
import os
import tempfile

from script_checks import (Checks, check_figure_drawn, check_refuses_other_directories,
                           run_script, write_contact_branch)

def branch(path, rows):
    """rows: (phi_e, E_stretch, E_bend, gamma, n_negative)."""
    write_contact_branch(path, [
        {"phi_e": phi, "E_stretch": stretch, "E_bend": bend, "gamma": gamma,
         "n_negative": negative, "active_pairs": 4, "contact_force": 0.1}
        for phi, stretch, bend, gamma, negative in rows])


def main():
    check = Checks()
    with tempfile.TemporaryDirectory() as d:
        check_refuses_other_directories(check, "plot_contact_angle.py", d)
        results = {"study": "econe_contact", "thickness": 0.005,
                   "mesh": {"family": "rings", "size_slope": 0.1},
                   "phi_first_contact": 6.57, "phi_crit_stability": 7.067,
                   "symmetric_csv": "symmetric/branch.csv", "skewed_csv": "skewed/branch.csv",
                   "turned_csv": None, "wound_csv": None,
                   "hard_contact": [
                       {"branch": "skewed", "phi_e": 7.2, "converged": True, "hard_gamma": 1.52},
                       {"branch": "skewed", "phi_e": 7.1, "converged": True, "hard_gamma": 1.55},
                       {"branch": "symmetric", "phi_e": 7.1, "converged": False,
                        "hard_gamma": 1.0}]}
        with open(os.path.join(d, "results.json"), "w") as f:
            json.dump(results, f)
        empty = run_script("plot_contact_angle.py", d)
        check(empty.returncode != 0 and "no samples with contact" in empty.stderr,
              f"a study without samples with contact is refused: {empty.stderr!r}")
        branch(os.path.join(d, "symmetric", "branch.csv"),
               [(6.6, 0.002, 0.1, 1.5708, 0), (7.0, 0.003, 0.1, 1.56, 0),
                (7.3, 0.004, 0.1, 1.50, 1)])
        # Written as traced: down from the relaxed state, then up; the highest is not last.
        branch(os.path.join(d, "skewed", "branch.csv"),
               [(7.1, 0.002, 0.08, 1.54, 0), (7.0, 0.002, 0.09, 1.55, 0),
                (7.4, 0.001, 0.08, 1.45, 0), (7.2, 0.002, 0.08, 1.50, 0)])
        drawn = run_script("plot_contact_angle.py", d)
        lines = drawn.stdout.splitlines()
        check("symmetric: f = 0.04 at phi_e = 7.3" in lines,
              f"the symmetric branch's f at its top, 0.004 / 0.1: {drawn.stdout!r}")
        check("skewed: f = 0.0125 at phi_e = 7.4; gamma (hard constraints) 1.5500 at 7.1000; "
              "1.5200 at 7.2000" in lines,
              f"the skewed branch's f at its top (not its last row) and its converged hard "
              f"gammas by phi_e: {drawn.stdout!r}")
        check_figure_drawn(check, drawn, d, "contact_angle.png")
        # A branch record without the gamma column is refused by name.
        with open(os.path.join(d, "skewed", "branch.csv"), "w") as f:
            f.write("phi_e,E_stretch,E_bend,n_negative\n7,1,2,0\n")
        broken = run_script("plot_contact_angle.py", d)
        check(broken.returncode != 0 and "skewed" in broken.stderr and "gamma" in broken.stderr,
              f"a broken skewed record is refused by name: {broken.stderr!r}")
    check.finish()


if __name__ == "__main__":
    main()
