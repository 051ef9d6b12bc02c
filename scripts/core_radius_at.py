#!/usr/bin/python3
"""The core radius R_c of every completed point of a sweep at one excess angle.

R_c is the branch.csv column core_radius: the reference radius within which half the
stretching energy lies (docs/guide/programs.md). It is interpolated linearly in phi_e between
the two samples around PHI on the cone, and printed per point with R_c / h.

Usage: scripts/core_radius_at.py SWEEP_DIR PHI
Prints one line per completed point: its swept parameters, h, R_c (m) and R_c / h. A point
whose trace does not reach PHI is listed as such. Exit status 2 with a message naming the
problem for a directory without sweep.json or a PHI that is not a number.
"""

import csv
import json
import os
import sys


def fail(message):
    sys.stderr.write("core_radius_at.py: " + message + "\n")
    sys.exit(2)


def core_radius_at(rows, phi):
    """R_c interpolated at phi between consecutive rows of branch.csv, or None."""
    for a, b in zip(rows, rows[1:]):
        pa, pb = float(a["phi_e"]), float(b["phi_e"])
        if pa <= phi <= pb and pb > pa:
            t = (phi - pa) / (pb - pa)
            return float(a["core_radius"]) * (1 - t) + float(b["core_radius"]) * t
    return None


def main(argv):
    if len(argv) != 3:
        fail("usage: core_radius_at.py SWEEP_DIR PHI")
    directory = argv[1]
    try:
        phi = float(argv[2])
    except ValueError:
        fail("PHI must be a number, got '%s'" % argv[2])
    path = os.path.join(directory, "sweep.json")
    if not os.path.isfile(path):
        fail("%s is missing: not a sweep directory" % path)
    with open(path) as f:
        sweep = json.load(f)
    for p in sweep["points"]:
        if p["status"] != "completed" or not p.get("results"):
            continue
        with open(os.path.join(directory, p["directory"], "branch.csv")) as f:
            rows = list(csv.DictReader(f))
        params = ", ".join("%s=%s" % kv for kv in p["params"].items())
        h = p["results"]["thickness"]
        rc = core_radius_at(rows, phi)
        if rc is None:
            print("%s: h = %g, the trace does not reach phi_e = %g" % (params, h, phi))
        else:
            print("%s: h = %g, R_c(%g) = %.5f m, R_c/h = %.3f" % (params, h, phi, rc, rc / h))


if __name__ == "__main__":
    main(sys.argv)
