#!/usr/bin/python3
"""scripts/branch_column_at.py: a branch.csv column interpolated at given excess angles for
every completed point of a sweep (divided by h on request), "—" where a trace stops short, and
bad input refused with exit status 2. Run by ctest (branch_column_at)."""

import json
import os
import tempfile

from script_checks import Checks, run_script


def run(*args):
    return run_script("branch_column_at.py", *args)


def main():
    check = Checks()
    with tempfile.TemporaryDirectory() as root:
        points = []
        # core_radius = h (1 + 0.1 phi_e) on a trace to 4; the second point stops at 2.
        for i, (h, end) in enumerate([(0.02, 4.0), (0.01, 2.0)]):
            d = os.path.join(root, "point_%03d" % i)
            os.makedirs(d)
            with open(os.path.join(d, "branch.csv"), "w") as f:
                f.write("phi_e,E_stretch,core_radius\n")
                phi = 0.0
                while phi <= end + 1e-12:
                    f.write("%.17g,0,%.17g\n" % (phi, h * (1 + 0.1 * phi)))
                    phi += 0.5
            points.append({"index": i, "directory": "point_%03d" % i,
                           "params": {"thickness": h}, "status": "completed",
                           "results": {"thickness": h}})
        points.append({"index": 2, "directory": "point_002", "params": {"thickness": 0.005},
                       "status": "pending", "results": None})
        with open(os.path.join(root, "sweep.json"), "w") as f:
            json.dump({"points": points}, f)
        r = run(root, "core_radius", "1.5", "3.25")
        check(r.returncode == 0, "run failed: " + r.stderr)
        check(r.stdout.splitlines() == [
            "| thickness | core_radius at 1.5 | core_radius at 3.25 |", "|---|---|---|",
            "| 0.02 | 0.0230 | 0.0265 |", "| 0.01 | 0.0115 | — |"], "table:\n" + r.stdout)
        r = run("--over-thickness", root, "core_radius", "3.25")
        check("| 0.02 | 1.3250 |" in r.stdout, "divided by h:\n" + r.stdout)
        r = run(root, "core_radius", "three")
        check(r.returncode == 2 and "every PHI must be a number" in r.stderr, "bad PHI: " + r.stderr)
        r = run(root, "chord_up", "3")
        check(r.returncode == 2 and "has no column chord_up" in r.stderr, "no column: " + r.stderr)
        r = run(os.path.join(root, "none"), "core_radius", "3")
        check(r.returncode == 2 and "sweep.json is missing" in r.stderr, "no sweep: " + r.stderr)
    check.finish()


if __name__ == "__main__":
    main()
