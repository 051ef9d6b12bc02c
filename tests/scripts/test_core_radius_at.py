#!/usr/bin/python3
"""scripts/core_radius_at.py: R_c interpolated at one excess angle for every completed point
of a sweep, a point whose trace stops short named as such, and bad input refused with exit
status 2. Run by ctest (core_radius_at)."""

import json
import os
import tempfile

from script_checks import Checks, run_script


def run(*args):
    return run_script("core_radius_at.py", *args)


def main():
    check = Checks()

    with tempfile.TemporaryDirectory() as root:
        points = []
        # R_c = h (1 + 0.1 phi_e) on a trace to 4; the second point stops at 2.
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
        r = run(root, "3.25")
        check(r.returncode == 0, "run failed: " + r.stderr)
        lines = r.stdout.splitlines()
        check(len(lines) == 2, "one line per completed point:\n" + r.stdout)
        check("thickness=0.02: h = 0.02, R_c(3.25) = 0.02650 m, R_c/h = 1.325" in r.stdout,
              "interpolated value:\n" + r.stdout)
        check("thickness=0.01: h = 0.01, the trace does not reach phi_e = 3.25" in r.stdout,
              "short trace:\n" + r.stdout)
        r = run(root, "three")
        check(r.returncode == 2 and "PHI must be a number" in r.stderr, "bad PHI: " + r.stderr)
        r = run(os.path.join(root, "none"), "3")
        check(r.returncode == 2 and "sweep.json is missing" in r.stderr, "no sweep: " + r.stderr)

    check.finish()


if __name__ == "__main__":
    main()
