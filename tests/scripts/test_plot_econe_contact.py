"""scripts/plot_econe_contact.py on a small synthetic econe_contact directory: the figure is
written (where matplotlib is installed), and a directory that is not such a study's output is
refused with a message that names what is missing."""

import json
import os
import tempfile

from script_checks import (Checks, check_figure_drawn, check_refuses_other_directories,
                           run_script)

HEADER = ("phi_e,E_stretch,E_bend,E_penalty,Eb_hat,area,min_distance,active_pairs,contact_force,"
          "gamma,n_negative,dE_dphi,arclength,corrector_iterations,s4_defect,chord_up,chord_down")


def branch(path, rows, contact=True):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        if contact:
            f.write(HEADER + "\n")
            for phi, energy, negative in rows:
                f.write(f"{phi},{energy / 2},{energy / 2},0,3.0,3.2,0.05,0,0,nan,{negative},"
                        "0,0,1,0.01,0.2,0.2\n")
        else:
            f.write("phi_e,E_stretch,E_bend,Eb_hat,n_negative\n")
            for phi, energy, negative in rows:
                f.write(f"{phi},{energy / 2},{energy / 2},3.0,{negative}\n")


def redraw(check, d, results, what):
    """Writes `results` as d/results.json, removes the figure, draws it again and checks it."""
    with open(os.path.join(d, "results.json"), "w") as f:
        json.dump(results, f)
    figure = os.path.join(d, "econe_contact.png")
    os.remove(figure)
    drawn = run_script("plot_econe_contact.py", d)
    check(drawn.returncode == 0 and os.path.isfile(figure), f"{what}: {drawn.stderr!r}")


def main():
    check = Checks()
    with tempfile.TemporaryDirectory() as d:
        check_refuses_other_directories(check, "plot_econe_contact.py", d)
        results = {"study": "econe_contact", "thickness": 0.04, "exclusion_radius": 0.32,
                   "mesh": {"family": "rings", "size_slope": 0.1}, "phi_branch": 0.017,
                   "phi_first_contact": 6.55, "phi_crit_stability": 7.03,
                   "phi_crit_energy": 6.3, "phi_crit_energy_criterion": "stabilised_below"}
        with open(os.path.join(d, "results.json"), "w") as f:
            json.dump(results, f)
        branch(os.path.join(d, "cone", "branch.csv"),
               [(0.0, 0.0, 0), (3.0, 0.8, 0), (6.0, 0.75, 0), (6.5, 0.74, 0)], contact=False)
        branch(os.path.join(d, "symmetric", "branch.csv"),
               [(6.5, 0.74, 0), (7.0, 0.737, 0), (7.3, 0.736, 1)])
        # Written as traced: down from the relaxed state, then up.
        branch(os.path.join(d, "skewed", "branch.csv"),
               [(7.2, 0.733, 0), (6.4, 0.738, 0), (5.8, 0.75, 1), (7.3, 0.732, 0)])
        drawn = run_script("plot_econe_contact.py", d)
        if check_figure_drawn(check, drawn, d, "econe_contact.png"):
            # With the turned branch (written as traced: down, then up) and phi_crit_energy
            # measured against it.
            branch(os.path.join(d, "turned", "branch.csv"),
                   [(6.5, 0.734, 0), (5.2, 0.79, 0), (6.9, 0.731, 0), (7.3, 0.730, 0)])
            results["phi_crit_energy_reference"] = "turned"
            redraw(check, d, results, "the figure with the turned branch is drawn")
            # With the winding (its jumps marked) and a three-fold cone of compare_modes.
            branch(os.path.join(d, "wound", "branch.csv"),
                   [(7.35, 0.735, 0), (7.4, 0.74, 0), (7.45, 0.76, 0)])
            branch(os.path.join(d, "cone_n3", "branch.csv"),
                   [(0.0, 0.0, 0), (0.034, 0.0, 0), (3.0, 0.9, 2), (7.3, 0.8, 2)], contact=False)
            results["wound"] = {"jumps": [7.4], "start_branch": "turned"}
            results["wound_csv"] = "wound/branch.csv"
            results["compared_modes"] = [{"mode": 3, "csv": "cone_n3/branch.csv",
                                          "phi_branch": 0.034}]
            redraw(check, d, results, "the figure with the winding and the n = 3 cone is drawn")
            # A compared mode whose record lacks a column is refused by name.
            with open(os.path.join(d, "cone_n3", "branch.csv"), "w") as f:
                f.write("phi_e,E_stretch\n1,2\n")
            broken = run_script("plot_econe_contact.py", d)
            check(broken.returncode != 0 and "cone_n3" in broken.stderr,
                  f"a broken n = 3 record is refused by name: {broken.stderr!r}")
    check.finish()


if __name__ == "__main__":
    main()
