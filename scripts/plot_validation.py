#!/usr/bin/python3
"""Tables and figures of docs/validation.md and the accuracy-cost table of docs/performance.md
from the runs of scripts/validation_runs.sh.

usage: plot_validation.py RUNS_DIR [--figures docs/figures]

Reads RUNS_DIR/<name>/{branch.csv,events.json,contact_profile.csv,cost.json} and
RUNS_DIR/<name>.log; writes PNG figures and prints the markdown tables. Needs Debian's
python3-numpy and python3-matplotlib. Missing runs are skipped (a table cell shows '-').
"""
import argparse
import csv
import json
import math
import os
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

PHI_STAR = 2.57       # h -> 0 maximum of Eb_hat (brief; scripts/econe_limit.py: 2.5651)
PHI_KISS_0 = 7.08     # h -> 0 self-contact (brief; scripts/econe_limit.py: 7.0801)
THICKNESSES = [0.04, 0.02, 0.01, 0.005, 0.002, 0.001]


def tag(h):
    return {0.04: "04", 0.02: "02", 0.01: "01", 0.005: "005", 0.002: "002", 0.001: "001"}[h]


def read_branch(run):
    path = os.path.join(run, "branch.csv")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]} if rows else None


def read_events(run):
    path = os.path.join(run, "events.json")
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return json.load(f)


def event(run, kind):
    for e in read_events(run):
        if e["kind"] == kind:
            return e["phi_e"]
    return None


def first_crossing(run):
    """Midpoint of the first bracket of saved states across which the mid-surface starts to
    cross itself (contact_profile.csv), for runs without a located midsurface_contact event."""
    path = os.path.join(run, "contact_profile.csv")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    for a, b in zip(rows, rows[1:]):
        if a["crosses"] == "0" and b["crosses"] == "1":
            return 0.5 * (float(a["phi_e"]) + float(b["phi_e"]))
    return None


def midsurface(run):
    return event(run, "midsurface_contact") or first_crossing(run)


def thickness(run):
    with open(os.path.join(run, "scene.json")) as f:
        t = json.load(f)["thickness"]
    return t if isinstance(t, (int, float)) else t["center"]


def band_crossing(run, band, distance):
    """First phi_e where the gap of samples at reference radius >= band reaches distance
    (linear interpolation between the saved states), from contact_profile.csv."""
    path = os.path.join(run, "contact_profile.csv")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        rows = list(csv.DictReader(f))
    key = "gap_%g" % band
    if not rows or key not in rows[0]:
        return None
    for a, b in zip(rows, rows[1:]):
        pa, pb = float(a["phi_e"]), float(b["phi_e"])
        ga, gb = float(a[key]) - distance, float(b[key]) - distance
        if ga > 0 >= gb and pb > pa:
            return pa + ga / (ga - gb) * (pb - pa)
    return None


def wall_seconds(runs_dir, name):
    path = os.path.join(runs_dir, name, "cost.json")
    if os.path.exists(path):
        with open(path) as f:
            return json.load(f)["wall_seconds"]
    log = os.path.join(runs_dir, name + ".log")
    if os.path.exists(log):
        m = re.search(r"wall=(\d+)", open(log).read())
        if m:
            return float(m.group(1))
    return None


def value_at(branch, phi, key):
    """key interpolated at phi on the cone (the last crossing of phi is not needed: the
    n = 2 branch is monotone in phi_e up to contact)."""
    p = branch["phi_e"]
    for i in range(1, len(p)):
        if p[i - 1] <= phi <= p[i]:
            t = (phi - p[i - 1]) / (p[i] - p[i - 1])
            return branch[key][i - 1] + t * (branch[key][i] - branch[key][i - 1])
    return None


def fmt(v, digits=4):
    return "-" if v is None else ("%.*f" % (digits, v))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs")
    ap.add_argument("--figures", default=os.path.join(os.path.dirname(__file__), "..", "docs", "figures"))
    args = ap.parse_args()
    R = args.runs
    os.makedirs(args.figures, exist_ok=True)
    run = lambda name: os.path.join(R, name)  # noqa: E731

    # ---- first contact by three criteria, per thickness and mesh ----------------------
    print("## First contact (n = 2 disc)\n")
    print("| h | mesh | gap = h anywhere (r_ex = πh/2) | gap = h at the rim (r ≥ 0.9R) | mid-surface contact |")
    print("|---|---|---|---|---|")
    kiss = {}
    for h in THICKNESSES:
        for mesh in ["p2_r24", "p2_r36", "p3_r24", "p3_r36", "p3_r48"]:
            name = "h%s_%s" % (tag(h), mesh)
            if not os.path.exists(os.path.join(run(name), "branch.csv")):
                continue
            strict = band_crossing(run(name), 0, h) or event(run(name), "contact")
            rim = band_crossing(run(name), 0.9, h)
            mid = midsurface(run(name))
            if strict is None and rim is None and mid is None:
                continue  # a run that did not get onto the cone (see its log)
            kiss.setdefault(h, []).append((mesh, strict, rim, mid))
            print("| %g | %s | %s | %s | %s |" % (h, mesh, fmt(strict, 3), fmt(rim, 3), fmt(mid, 4)))
    print()

    # h -> 0: mid-surface contact against 7.08 - a / ln(R / (c h)), with c = R_c / h measured.
    hs, mids, rims = [], [], []
    for h, rows in sorted(kiss.items(), reverse=True):
        finest = [r for r in rows if r[3] is not None]
        if finest:
            hs.append(h)
            mids.append(finest[-1][3])
            rims.append(finest[-1][2])
    core_ratio = None

    # ---- core radius R_c(h) at phi_e = 3 ----------------------------------------------
    print("## Core radius at phi_e = 3\n")
    print("| h | mesh | R_c | R_c / h |")
    print("|---|---|---|---|")
    rc_h, rc = [], []
    for h in THICKNESSES:
        finest = None
        for mesh in ["p3_r24", "p3_r36", "p3_r48"]:
            b = read_branch(run("h%s_%s" % (tag(h), mesh)))
            if b is None or "core_radius" not in b:
                continue
            v = value_at(b, 3.0, "core_radius")
            if v is None:
                continue
            print("| %g | %s | %.5f | %.3f |" % (h, mesh, v, v / h))
            finest = v
        if finest is not None:
            rc_h.append(h)
            rc.append(finest)
    if rc:
        slope = float(np.dot(rc_h, rc) / np.dot(rc_h, rc_h))
        core_ratio = slope
        print("\nleast-squares R_c = %.3f h (through the origin, finest mesh per h)\n" % slope)
        plt.figure(figsize=(4.5, 3.5))
        plt.loglog(rc_h, rc, "o", label="R_c (half the stretching energy)")
        hh = np.array([min(rc_h), max(rc_h)])
        plt.loglog(hh, slope * hh, "-", label="%.2f h" % slope)
        plt.xlabel("h / R")
        plt.ylabel("R_c / R at φe = 3")
        plt.legend()
        plt.tight_layout()
        plt.savefig(os.path.join(args.figures, "core_radius_vs_h.png"), dpi=120)
        plt.close()

    if hs:
        c = core_ratio or 1.2
        x = np.array([1.0 / math.log(1.0 / (c * h)) for h in hs])
        y = np.array(mids)
        a_fixed = float(np.dot(x, PHI_KISS_0 - y) / np.dot(x, x))
        A = np.vstack([np.ones_like(x), -x]).T
        (phi_inf, a_free), *_ = np.linalg.lstsq(A, y, rcond=None)
        res_fixed = y - (PHI_KISS_0 - a_fixed * x)
        res_free = y - (phi_inf - a_free * x)
        print("mid-surface contact: 7.08 - a / ln(R / (%.2f h)) with a = %.3f (largest residual "
              "%.4f); free fit: phi_inf = %.3f, a = %.3f (largest residual %.4f)\n"
              % (c, a_fixed, np.abs(res_fixed).max(), phi_inf, a_free, np.abs(res_free).max()))
        plt.figure(figsize=(5, 3.8))
        plt.semilogx(hs, mids, "o", label="mid-surface contact")
        if any(r is not None for r in rims):
            plt.semilogx([h for h, r in zip(hs, rims) if r], [r for r in rims if r], "s", label="gap = h at the rim")
        hh = np.geomspace(1e-4, 0.05, 100)
        plt.semilogx(hh, PHI_KISS_0 - a_fixed / np.log(1 / (c * hh)), "-",
                     label="7.08 − %.2f / ln(R/(%.2f h))" % (a_fixed, c))
        plt.axhline(PHI_KISS_0, color="k", lw=0.6)
        plt.errorbar([0.04], [7.12], yerr=[0.01], fmt="x", color="r", label="paper (h = 0.04)")
        plt.xlabel("h / R")
        plt.ylabel("φe at first contact")
        plt.legend(fontsize=7)
        plt.tight_layout()
        plt.savefig(os.path.join(args.figures, "kiss_vs_h.png"), dpi=120)
        plt.close()

    # ---- phi_e^max(h) ------------------------------------------------------------------
    print("## Maximum of Eb_hat\n")
    print("| h | mesh | φe^max |")
    print("|---|---|---|")
    pm_h, pm = [], []
    for h in THICKNESSES:
        best = None
        for mesh in ["p3_r24", "p3_r36", "p3_r48"]:
            v = event(run("h%s_%s" % (tag(h), mesh)), "eb_max") if os.path.exists(run("h%s_%s" % (tag(h), mesh))) else None
            if v is not None:
                print("| %g | %s | %.4f |" % (h, mesh, v))
                best = v
        if best is not None:
            pm_h.append(h)
            pm.append(best)
    if len(pm) >= 3:
        lh, ld = np.log(pm_h), np.log(np.array(pm) - PHI_STAR)
        power, logA = np.polyfit(lh, ld, 1)
        c = core_ratio or 1.2
        x = np.array([1.0 / math.log(1.0 / (c * h)) for h in pm_h])
        a_log = float(np.dot(x, np.array(pm) - PHI_STAR) / np.dot(x, x))
        res_pow = np.array(pm) - (PHI_STAR + math.exp(logA) * np.array(pm_h) ** power)
        res_log = np.array(pm) - (PHI_STAR + a_log * x)
        print("\npower fit: phi_max - 2.57 = %.3f h^%.3f (rms residual %.4f); log fit: "
              "phi_max - 2.57 = %.3f / ln(R / (%.2f h)) (rms residual %.4f)\n"
              % (math.exp(logA), power, math.sqrt(np.mean(res_pow ** 2)), a_log, c,
                 math.sqrt(np.mean(res_log ** 2))))
        plt.figure(figsize=(5, 3.8))
        plt.loglog(pm_h, np.array(pm) - PHI_STAR, "o", label="φe^max − 2.57")
        hh = np.geomspace(min(pm_h) / 2, 0.05, 100)
        plt.loglog(hh, math.exp(logA) * hh ** power, "-", label="%.2f h^%.3f" % (math.exp(logA), power))
        plt.loglog(hh, a_log / np.log(1 / (c * hh)), "--", label="%.2f / ln(R/(%.2f h))" % (a_log, c))
        plt.xlabel("h / R")
        plt.ylabel("φe^max − φe*")
        plt.legend(fontsize=8)
        plt.tight_layout()
        plt.savefig(os.path.join(args.figures, "phi_max_vs_h.png"), dpi=120)
        plt.close()

    # ---- n = 3 against n = 2 ------------------------------------------------------------
    b2, b3 = read_branch(run("h02_p3_r24")), read_branch(run("mode3_h02_r24"))
    if b2 is not None and b3 is not None:
        plt.figure(figsize=(5, 3.8))
        plt.plot(b2["phi_e"], b2["Eb_hat"], label="n = 2")
        plt.plot(b3["phi_e"], b3["Eb_hat"], label="n = 3")
        plt.xlabel("φe")
        plt.ylabel("Ê_b (1/m²)")
        plt.title("h = 0.02, graded 24 rings")
        plt.legend()
        plt.tight_layout()
        plt.savefig(os.path.join(args.figures, "eb_hat_n2_n3.png"), dpi=120)
        plt.close()
        print("## n = 3 against n = 2 (h = 0.02)\n")
        print("| φe | Ê_b n = 2 | Ê_b n = 3 | E_total n = 2 (J) | E_total n = 3 (J) |")
        print("|---|---|---|---|---|")
        for phi in [0.5, 1, 2, 3, 4, 5, 6, 7]:
            e2, e3 = value_at(b2, phi, "Eb_hat"), value_at(b3, phi, "Eb_hat")
            t2 = None if e2 is None else value_at(b2, phi, "E_stretch") + value_at(b2, phi, "E_bend")
            t3 = None if e3 is None else value_at(b3, phi, "E_stretch") + value_at(b3, phi, "E_bend")
            print("| %g | %s | %s | %s | %s |" % (phi, fmt(e2, 3), fmt(e3, 3), fmt(t2, 5), fmt(t3, 5)))
        print()

    # ---- rings ------------------------------------------------------------------------
    print("## Rings (h = 0.02)\n")
    print("| R_i | layers | gap = h anywhere | gap = h at the rim | mid-surface contact | φe^max |")
    print("|---|---|---|---|---|---|")
    for ri in ["010", "025", "050"]:
        for layers in [16, 24, 32]:
            name = "ring%s_l%d" % (ri, layers)
            if not os.path.exists(os.path.join(run(name), "branch.csv")):
                continue
            print("| %s | %d | %s | %s | %s | %s |" % (
                "0." + ri[1:] if ri != "010" else "0.1", layers,
                fmt(band_crossing(run(name), 0, 0.02) or event(run(name), "contact"), 3),
                fmt(band_crossing(run(name), 0.9, 0.02), 3),
                fmt(midsurface(run(name)), 4), fmt(event(run(name), "eb_max"), 4)))
    print()

    # ---- accuracy against cost (h = 0.02) ----------------------------------------------
    print("## Accuracy against cost (h = 0.02, flat to mid-surface contact)\n")
    print("| mesh | unknowns | wall (s) | mid-surface contact | error | φe^max | error |")
    print("|---|---|---|---|---|---|---|")
    ref_mid = midsurface(run("h02_p3_r48"))
    ref_max = event(run("h02_p3_r48"), "eb_max")
    pts = {"p3": [], "p1": []}
    for g in ["p3", "p1"]:
        for rings in [12, 16, 24, 36, 48]:
            name = "h02_%s_r%d" % (g, rings)
            if not os.path.exists(os.path.join(run(name), "branch.csv")):
                continue
            mid, mx, wall = midsurface(run(name)), event(run(name), "eb_max"), wall_seconds(R, name)
            unknowns = None
            log = run(name) + ".log"
            if os.path.exists(log):
                m = re.search(r"(\d+) unknowns", open(log).read())
                unknowns = m.group(1) if m else None
            err = None if (mid is None or ref_mid is None) else abs(mid - ref_mid)
            errm = None if (mx is None or ref_max is None) else abs(mx - ref_max)
            print("| %s %d rings | %s | %s | %s | %s | %s | %s |" % (
                "graded p = 3" if g == "p3" else "uniform", rings, unknowns or "-", fmt(wall, 0),
                fmt(mid, 4), fmt(err, 4), fmt(mx, 4), fmt(errm, 4)))
            if err is not None and wall is not None and name != "h02_p3_r48":
                pts[g].append((wall, max(err, 1e-4)))
    if any(pts.values()):
        plt.figure(figsize=(5, 3.8))
        for g, label in [("p3", "graded (p = 3)"), ("p1", "uniform")]:
            if pts[g]:
                w, e = zip(*pts[g])
                plt.loglog(w, e, "o-", label=label)
        plt.xlabel("wall time (s), 1 thread")
        plt.ylabel("|φe error| of mid-surface contact")
        plt.legend()
        plt.tight_layout()
        plt.savefig(os.path.join(args.figures, "accuracy_cost.png"), dpi=120)
        plt.close()


if __name__ == "__main__":
    main()
