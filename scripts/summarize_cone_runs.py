#!/usr/bin/python3
"""Table of the traces made by scripts/symmetric_cone_runs.sh (Markdown, to stdout).

For every run directory DIR/NAME with a branch.csv: thickness, mesh family and size slope (from NAME),
elements and unknowns (from NAME.log), the first branch point, phi_e^max and E_b-hat there,
first contact (gap = h anywhere), mid-surface contact, the largest S4 defect between phi_e = 0.1
and first contact (or the end), the first sample past phi_e = 0.1 with a negative eigenvalue, the
symmetry_lost event
and the wall time ("unfinished": no cost.json, the run was stopped or is still going). usage: scripts/summarize_cone_runs.py DIR
"""
import csv
import json
import pathlib
import re
import sys


def event(events, kind, nth=0):
    found = [e for e in events if e.get("kind") == kind]
    return found[nth] if len(found) > nth else None


def fmt(value, digits=5):
    return "—" if value is None else f"{value:.{digits}f}"


def summarize(run: pathlib.Path):
    rows = list(csv.DictReader(open(run / "branch.csv")))
    events = json.load(open(run / "events.json")) if (run / "events.json").exists() else []
    log = (run.parent / (run.name + ".log")).read_text() if (run.parent / (run.name + ".log")).exists() else ""
    size = re.search(r"(\d+) elements, (\d+) unknowns", log)
    match = re.match(r"h(\d+)_(\w+)_c([\d.]+)", run.name)
    contact = event(events, "contact")
    end = contact["phi_e"] if contact else float("inf")
    early = [r for r in rows if 0.1 <= float(r["phi_e"]) < end]
    defect = max((float(r["s4_defect"]) for r in early), default=None)
    unstable = next((float(r["phi_e"]) for r in rows
                     if float(r["phi_e"]) >= 0.1 and int(r["n_negative"]) > 0), None)
    cost = json.load(open(run / "cost.json")) if (run / "cost.json").exists() else {}
    eb = event(events, "eb_max")
    eb_value = None
    if eb:
        nearest = min(rows, key=lambda r: abs(float(r["phi_e"]) - eb["phi_e"]))
        eb_value = float(nearest["Eb_hat"])
    return {
        "h": "0." + match.group(1) if match else "",
        "family": match.group(2) if match else run.name,
        "slope": match.group(3) if match else "",
        "elements": size.group(1) if size else "",
        "unknowns": size.group(2) if size else "",
        "branch": (event(events, "branch_point") or {}).get("phi_e"),
        "phi_max": eb["phi_e"] if eb else None,
        "eb_hat": eb_value,
        "contact": contact["phi_e"] if contact else None,
        "midsurface": (event(events, "midsurface_contact") or {}).get("phi_e"),
        "defect": defect,
        "unstable": unstable,
        "lost": (event(events, "symmetry_lost") or {}).get("phi_e"),
        "last": float(rows[-1]["phi_e"]) if rows else None,
        "wall": cost.get("wall_seconds"),
    }


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    top = pathlib.Path(sys.argv[1])
    runs = sorted(p for p in top.iterdir() if (p / "branch.csv").exists())
    if not runs:
        sys.exit(f"summarize_cone_runs.py: no run with a branch.csv under {top}")
    print("| h | mesh | size_slope | elements | unknowns | first branch point | φe^max | Ê_b^max | "
          "gap = h | mid-surface contact | max S4 defect before contact | first negative "
          "eigenvalue (φe ≥ 0.1) | symmetry_lost | last φe | wall (s) |")
    print("|" + "---|" * 15)
    for run in runs:
        s = summarize(run)
        wall = "unfinished" if s["wall"] is None else f"{s['wall']:.0f}"
        defect = "—" if s["defect"] is None else f"{s['defect']:.1e}"
        print(f"| {s['h']} | {s['family']} | {s['slope']} | {s['elements']} | {s['unknowns']} | "
              f"{fmt(s['branch'], 6)} | {fmt(s['phi_max'], 4)} | {fmt(s['eb_hat'], 4)} | "
              f"{fmt(s['contact'], 4)} | {fmt(s['midsurface'], 4)} | {defect} | "
              f"{fmt(s['unstable'], 3) if s['unstable'] is not None else 'none'} | "
              f"{fmt(s['lost'], 3)} | {fmt(s['last'], 3)} | {wall} |")


if __name__ == "__main__":
    main()
