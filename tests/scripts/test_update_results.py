#!/usr/bin/python3
"""scripts/update_results.py: fills a page's sweep tables and power-law fits from sweep.json,
leaves the rest of the page alone, reports a missing sweep by name without touching the page,
and --check tells a stale page from a current one. Run by ctest (update_results)."""

import json
import math
import os
import tempfile

from script_checks import Checks, run_script


def point(index, params, family, unknowns, phi_max, status="completed"):
    results = {"mesh": {"family": family, "unknowns": unknowns}, "phi_max": phi_max}
    return {"index": index, "directory": "point_%03d" % index, "params": params, "status": status,
            "reason": "reached the parameter bound", "results": results}


def run(*args):
    return run_script("update_results.py", *args)


def main():
    check = Checks()

    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, "runs", "mesh"))
        os.makedirs(os.path.join(root, "runs", "h"))
        mesh = {"parameters": [{"key": "mesh.family", "values": ["rings", "gmsh"]},
                               {"key": "mesh.size_slope", "values": ["0.2", "0.1"]}],
                "points": [point(0, {"mesh.family": "rings", "mesh.size_slope": 0.2}, "rings", 100, 4.1),
                           point(1, {"mesh.family": "rings", "mesh.size_slope": 0.1}, "rings", 400, 4.0),
                           point(2, {"mesh.family": "gmsh", "mesh.size_slope": 0.2}, "gmsh", 120, 4.3),
                           point(3, {"mesh.family": "gmsh", "mesh.size_slope": 0.1}, "gmsh", 480, 4.05)]}
        with open(os.path.join(root, "runs", "mesh", "sweep.json"), "w") as f:
            json.dump(mesh, f)
        # phi_max - 2.57 = 3 h^0.5 exactly.
        # A second family in the same sweep, phi_max - 2.57 = 2 h^0.25, fitted apart by where=.
        hs = [0.04, 0.02, 0.01, 0.005]
        thick = {"parameters": [{"key": "thickness", "values": [str(h) for h in hs]}],
                 "points": [point(i, {"thickness": h}, "rings", 100, 2.57 + 3 * math.sqrt(h))
                            for i, h in enumerate(hs)]}
        both = {"parameters": [{"key": "mesh.family", "values": ["rings", "gmsh_d4"]},
                               {"key": "thickness", "values": [str(h) for h in hs]}],
                "points": [point(i, {"mesh.family": "rings", "thickness": h}, "rings", 100,
                                 2.57 + 3 * math.sqrt(h)) for i, h in enumerate(hs)] +
                          [point(4 + i, {"mesh.family": "gmsh_d4", "thickness": h}, "gmsh_d4", 100,
                                 2.57 + 2 * h ** 0.25) for i, h in enumerate(hs)]}
        os.makedirs(os.path.join(root, "runs", "both"))
        with open(os.path.join(root, "runs", "both", "sweep.json"), "w") as f:
            json.dump(both, f)
        with open(os.path.join(root, "runs", "h", "sweep.json"), "w") as f:
            json.dump(thick, f)
        page = os.path.join(root, "page.md")
        text = ("# Page\n\nprose stays\n\n<!-- sweep runs/mesh keys=phi_max -->\nold\n"
                "<!-- end sweep -->\n\n<!-- fit runs/h x=thickness y=phi_max limit=2.57 -->\n"
                "old\n<!-- end fit -->\n\n"
                "<!-- fit runs/both x=thickness y=phi_max limit=2.57 where=mesh.family=gmsh_d4 -->\n"
                "old\n<!-- end fit -->\n\n<!-- sweep runs/h keys=phi_max compare=no -->\n"
                "<!-- end sweep -->\n\nmore prose\n")
        with open(page, "w") as f:
            f.write(text)
        check(run("--check", "--root", root, page).returncode == 1, "--check on a stale page is not 1")
        r = run("--root", root, page)
        check(r.returncode == 0, "update failed: " + r.stderr)
        with open(page) as f:
            new = f.read()
        check(new.startswith("# Page\n\nprose stays\n") and new.endswith("\n\nmore prose\n"),
              "the prose around the markers changed:\n" + new)
        check("| rings | 0.2 | 100 | completed | 4.1 | +1.00e-01 |" in new, "rings 0.2 row:\n" + new)
        check("| gmsh | 0.1 | 480 | completed | 4.05 |  |" in new, "finest gmsh row:\n" + new)
        check("Finest rings minus finest gmsh: phi_max -5.00e-02." in new, "family difference:\n" + new)
        check("A = 3, p = 0.500 (least squares over 4 points" in new, "power law:\n" + new)
        check("where=mesh.family=gmsh_d4 -->\nphi_max − 2.57 = A thickness^p with A = 2, p = 0.250 "
              "(least squares over 4 points" in new, "power law of one family:\n" + new)
        check("old" not in new, "the old table text is still there")
        check("| 0.005 | 100 | completed | 2.78213 |\n" in new, "compare=no row:\n" + new)
        check(run("--check", "--root", root, page).returncode == 0, "--check on a current page is not 0")
        # A sweep that is missing is named, and the page is left as it was.
        with open(page, "w") as f:
            f.write(text.replace("runs/mesh", "runs/none"))
        r = run("--root", root, page)
        with open(page) as f:
            after = f.read()
        check(r.returncode == 2 and "runs/none/sweep.json is missing" in r.stderr,
              "missing sweep: rc %d, %s" % (r.returncode, r.stderr))
        check(after == text.replace("runs/mesh", "runs/none"), "a failed update changed the page")

    check.finish()


if __name__ == "__main__":
    main()
