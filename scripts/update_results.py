#!/usr/bin/python3
"""Fills the tables of docs/results.md from the sweeps that made them.

Each table in the page sits between two markers:

    <!-- sweep DIR keys=KEY1,KEY2,... -->
    ...the table, rewritten by this script...
    <!-- end sweep -->

(`keys=... compare=no` leaves out the error columns, for a sweep over physical parameters.)

DIR is the sweep's directory (growshell sweep --out DIR, relative to the repository root);
KEYs are results.json keys (nested ones joined by '.', e.g. mesh.unknowns). The table has a
row per point with its parameters, its status and the keys, and, for each key, two error
columns where they apply: the difference from the finest point of the same mesh family (the
point with the most unknowns), and at the finest points, the difference between families.

A power law fitted over a sweep sits between

    <!-- fit DIR x=PARAM y=KEY limit=L [where=PARAM=VALUE] -->
    ...one line, rewritten...
    <!-- end fit -->

and states y - L = A x^p with A and p from a least-squares line through (log x, log(y - L))
over the completed points with y > L, and the largest relative misfit. `where=` keeps only
the points whose swept parameter PARAM has the value VALUE (e.g. where=mesh.family=gmsh_d4,
to fit one mesh family of a sweep over two).

Usage: scripts/update_results.py [--root DIR] [PAGE]   (default docs/results.md)
       scripts/update_results.py --check [--root DIR] [PAGE]   exit 1 if the page is not up to date
--root is the directory the sweep paths are relative to (default: the repository root).
A sweep directory that is missing, or a sweep.json without the keys, is an error naming it;
the page is then left as it was. The page is written atomically.
"""

import json
import math
import os
import re
import sys
import tempfile

MARKER = re.compile(r"<!-- sweep (\S+) keys=(\S+)( compare=no)? -->\n(.*?)<!-- end sweep -->", re.S)
FIT = re.compile(r"<!-- fit (\S+) x=(\S+) y=(\S+) limit=(\S+)(?: where=([^=\s]+)=(\S+))? -->\n(.*?)"
                 r"<!-- end fit -->", re.S)


def fail(message):
    sys.stderr.write("update_results.py: " + message + "\n")
    sys.exit(2)


def lookup(results, key):
    value = results
    for part in key.split("."):
        if not isinstance(value, dict) or part not in value:
            return None
        value = value[part]
    return value


def formatted(value):
    if value is None:
        return "—"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, float):
        if value != 0 and (abs(value) < 1e-3 or abs(value) >= 1e5):
            return "%.3e" % value
        return "%.6g" % value
    return str(value)


def load_sweep(root, directory):
    path = os.path.join(root, directory, "sweep.json")
    if not os.path.isfile(path):
        fail("%s is missing: run the sweep the page names (its command is above the table)" % path)
    with open(path) as f:
        return path, json.load(f)


def power_law(root, directory, x_key, y_key, limit, where=None):
    path, sweep = load_sweep(root, directory)
    xs, ys = [], []
    for p in sweep["points"]:
        if p["status"] != "completed" or p["results"] is None:
            continue
        if where and str(p["params"].get(where[0])) != where[1]:
            continue
        x, y = p["params"].get(x_key), lookup(p["results"], y_key)
        if isinstance(x, (int, float)) and isinstance(y, (int, float)) and y > limit and x > 0:
            xs.append(math.log(x))
            ys.append(math.log(y - limit))
    if len(xs) < 3:
        among = " and %s = %s" % where if where else ""
        fail("%s: fewer than 3 completed points with %s > %g%s to fit" % (path, y_key, limit, among))
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    p = sum((a - mx) * (b - my) for a, b in zip(xs, ys)) / sum((a - mx) ** 2 for a in xs)
    log_a = my - p * mx
    misfit = max(abs(math.exp(log_a + p * a) / math.exp(b) - 1) for a, b in zip(xs, ys))
    y = y_key if limit == 0 else "%s − %g" % (y_key, limit)
    return ("%s = A %s^p with A = %.4g, p = %.3f (least squares over %d points; largest "
            "relative misfit of %s: %.1f %%)\n" % (y, x_key, math.exp(log_a), p, n, y, 100 * misfit))


def table(root, directory, keys, compare=True):
    path, sweep = load_sweep(root, directory)
    parameters = [p["key"] for p in sweep["parameters"]]
    points = sweep["points"]
    for p in points:
        if p["status"] == "pending":
            fail("%s: point %s has not run yet (growshell sweep ... --resume)" % (path, p["directory"]))
    done = [p for p in points if p["results"] is not None]
    for key in keys:
        if done and all(lookup(p["results"], key) is None and key.split(".")[0] not in p["results"]
                        for p in done):
            fail("%s: no point has the key %s" % (path, key))

    # The finest point of each family: the most unknowns.
    def family(p):
        return lookup(p["results"], "mesh.family") if p["results"] else None

    finest = {}
    for p in done:
        f = family(p)
        if f not in finest or lookup(p["results"], "mesh.unknowns") > lookup(finest[f]["results"], "mesh.unknowns"):
            finest[f] = p

    header = parameters + ["unknowns", "status"]
    for key in keys:
        header += [key, "Δ finest"] if compare else [key]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for p in points:
        row = [formatted(p["params"][k]) for k in parameters]
        r = p["results"]
        row.append(formatted(lookup(r, "mesh.unknowns")) if r else "—")
        row.append(p["status"] + ("" if p["status"] == "completed" else " (" + (p["reason"] or "") + ")"))
        for key in keys:
            value = lookup(r, key) if r else None
            row.append(formatted(value))
            if not compare:
                continue
            ref = lookup(finest[family(p)]["results"], key) if r else None
            if isinstance(value, (int, float)) and isinstance(ref, (int, float)) and not isinstance(value, bool) \
                    and finest[family(p)] is not p:
                row.append("%+.2e" % (value - ref))
            else:
                row.append("")
        lines.append("| " + " | ".join(row) + " |")
    families = sorted(f for f in finest if f is not None)
    if compare and len(families) == 2:
        a, b = (finest[f]["results"] for f in families)
        diffs = []
        for key in keys:
            va, vb = lookup(a, key), lookup(b, key)
            if isinstance(va, (int, float)) and isinstance(vb, (int, float)) and not isinstance(va, bool):
                diffs.append("%s %+.2e" % (key, vb - va))
        lines.append("")
        lines.append("Finest %s minus finest %s: %s." % (families[1], families[0], ", ".join(diffs) or "—"))
    return "\n".join(lines) + "\n"


def render(root, page):
    with open(page) as f:
        text = f.read()

    def replace(match):
        directory, keys, no_compare = match.group(1), match.group(2).split(","), match.group(3)
        return "<!-- sweep %s keys=%s%s -->\n%s<!-- end sweep -->" % (
            directory, match.group(2), no_compare or "", table(root, directory, keys, not no_compare))

    def replace_fit(match):
        directory, x_key, y_key, limit = match.group(1), match.group(2), match.group(3), match.group(4)
        where = (match.group(5), match.group(6)) if match.group(5) else None
        return "<!-- fit %s x=%s y=%s limit=%s%s -->\n%s<!-- end fit -->" % (
            directory, x_key, y_key, limit, " where=%s=%s" % where if where else "",
            power_law(root, directory, x_key, y_key, float(limit), where))

    return text, FIT.sub(replace_fit, MARKER.sub(replace, text))


def main(argv):
    check = "--check" in argv
    args = [a for a in argv if a != "--check"]
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    if "--root" in args:
        i = args.index("--root")
        if i + 1 >= len(args):
            fail("--root needs a directory")
        root = args[i + 1]
        del args[i:i + 2]
    page = args[0] if args else os.path.join(root, "docs", "results.md")
    old, new = render(root, page)
    if check:
        sys.exit(0 if old == new else 1)
    if new != old:
        fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(page)), prefix=".results.")
        with os.fdopen(fd, "w") as f:
            f.write(new)
        os.replace(tmp, page)
    print("updated %s (%d tables)" % (page, len(MARKER.findall(new))))


if __name__ == "__main__":
    main(sys.argv[1:])
