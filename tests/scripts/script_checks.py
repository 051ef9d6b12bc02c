"""What the tests of scripts/ share: running one of the scripts as the user would, and
collecting the checks that failed, so that a test reports all of them before it exits."""

import os
import subprocess
import sys

SCRIPTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts")


def run_script(name, *args):
    """Runs scripts/NAME with ARGS under this Python; returns the CompletedProcess (text)."""
    return subprocess.run([sys.executable, os.path.join(SCRIPTS, name)] + list(args),
                          capture_output=True, text=True)


class Checks:
    """check(condition, what) records `what` when condition is false; finish() prints every
    failure and exits 1 if there was one, else 0."""

    def __init__(self):
        self.failures = []

    def __call__(self, condition, what):
        if not condition:
            self.failures.append(what)

    def finish(self):
        for f in self.failures:
            print("FAILED:", f)
        sys.exit(1 if self.failures else 0)


# The columns of an econe_contact study's branch records with contact (DIR/symmetric, skewed,
# turned, wound: branch.csv), and the value a synthetic row has where a test does not set one.
CONTACT_DEFAULTS = {"phi_e": 0, "E_stretch": 0, "E_bend": 0, "E_penalty": 0, "Eb_hat": 3.0,
                    "area": 3.2, "min_distance": 0.05, "active_pairs": 0, "contact_force": 0,
                    "gamma": "nan", "n_negative": 0, "dE_dphi": 0, "arclength": 0,
                    "corrector_iterations": 1, "s4_defect": 0.01, "chord_up": 0.2,
                    "chord_down": 0.2}


def write_contact_branch(path, rows):
    """Writes path (creating its folder) as a branch record with contact: one line per dict of
    `rows`, its columns over CONTACT_DEFAULTS."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(",".join(CONTACT_DEFAULTS) + "\n")
        for row in rows:
            values = {**CONTACT_DEFAULTS, **row}
            f.write(",".join(str(values[c]) for c in CONTACT_DEFAULTS) + "\n")


def check_refuses_other_directories(check, script, directory, *args, status=None):
    """`script` DIRECTORY ARGS refuses, by name, a directory without results.json and one with
    another study's (with exit status `status` where given, else any but 0); leaves
    directory/results.json a cone_branch study's."""
    def refused(run):
        return run.returncode != 0 if status is None else run.returncode == status
    missing = run_script(script, directory, *args)
    check(refused(missing) and "results.json" in missing.stderr,
          f"{script}: a directory without results.json is refused by name: {missing.stderr!r}")
    with open(os.path.join(directory, "results.json"), "w") as f:
        f.write('{"study": "cone_branch"}')
    other = run_script(script, directory, *args)
    check(refused(other) and "not an econe_contact" in other.stderr,
          f"{script}: another study's directory is refused: {other.stderr!r}")


def check_figure_drawn(check, drawn, directory, name):
    """After a plotting script ran (`drawn`, its CompletedProcess): directory/name was written
    whole (over 10 kB, no temporary left). Returns False, with a note, where matplotlib is
    missing and the figure is not checked."""
    if "needs matplotlib" in drawn.stderr:
        print("matplotlib missing: the figure itself is not checked")
        return False
    figure = os.path.join(directory, name)
    check(drawn.returncode == 0, f"{name} is drawn: {drawn.stderr!r}")
    check(os.path.isfile(figure) and os.path.getsize(figure) > 10000, f"{name} is written")
    check(not os.path.exists(os.path.join(directory, f".{name}.tmp")),
          f"no temporary of {name} is left")
    return True
