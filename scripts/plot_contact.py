#!/usr/bin/python3
"""Figures of a trace_contact run: the normalised bending energy of the symmetric and skewed
branches (with a trace_disc n = 3 branch for comparison), the total energy difference that
locates phi_e^crit, and the contact-plane angle gamma.

usage: plot_contact.py RUN_DIR [--n3 TRACE_DISC_DIR] [--out PREFIX]
  RUN_DIR   output directory of trace_contact (branch_symmetric.csv, branch_skewed.csv,
            events.json)
  --n3      output directory of `trace_disc --mode 3` on the same scene (its branch.csv)
  --out     prefix of the PNG files (default RUN_DIR/contact); writes PREFIX_eb_hat.png,
            PREFIX_energy.png (total energy relative to the symmetric branch) and
            PREFIX_gamma.png, and prints the events.
"""
import argparse
import csv
import json
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    out = {}
    for key in rows[0].keys() if rows else []:
        values = []
        for r in rows:
            try:
                values.append(float(r[key]))
            except ValueError:
                values.append(math.nan)
        out[key] = values
    return out


def stable_pieces(branch):
    """Consecutive runs of samples with the same stability, for solid/dashed lines."""
    pieces, start = [], 0
    n = len(branch["phi_e"])
    for i in range(1, n + 1):
        if i == n or (branch["n_negative"][i] == 0) != (branch["n_negative"][start] == 0):
            pieces.append((start, min(i + 1, n), branch["n_negative"][start] == 0))
            start = i
    return pieces


def plot_branch(ax, name, branch, values, colour):
    """values (one per sample) against phi_e: solid where stable, dashed where unstable."""
    for i0, i1, stable in stable_pieces(branch):
        ax.plot(branch["phi_e"][i0:i1], values[i0:i1], color=colour,
                linestyle="-" if stable else "--",
                label=f"{name} ({'stable' if stable else 'unstable'})")


def legend(ax):
    """One legend entry per label (the pieces of a branch share theirs)."""
    handles, labels = ax.get_legend_handles_labels()
    unique = dict(zip(labels, handles))
    ax.legend(unique.values(), unique.keys(), fontsize=8)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run")
    parser.add_argument("--n3")
    parser.add_argument("--out")
    parser.add_argument("--from", dest="phi_from", type=float,
                        help="leave out samples below this phi_e (default: 0.3 below the skewed "
                             "branch; a run from flat heads its symmetric branch with the cone)")
    args = parser.parse_args()
    prefix = args.out or os.path.join(args.run, "contact")
    branches = {}
    for name in ("symmetric", "skewed"):
        path = os.path.join(args.run, f"branch_{name}.csv")
        if os.path.exists(path):
            branches[name] = read(path)
    phi_from = args.phi_from
    if phi_from is None and "skewed" in branches:
        phi_from = min(branches["skewed"]["phi_e"]) - 0.3
    if phi_from is not None:
        for name, b in branches.items():
            keep = [i for i, p in enumerate(b["phi_e"]) if p >= phi_from]
            branches[name] = {k: [v[i] for i in keep] for k, v in b.items()}
    colours = {"symmetric": "tab:blue", "skewed": "tab:red", "n = 3": "tab:green"}

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for name, b in branches.items():
        plot_branch(ax, name, b, b["Eb_hat"], colours[name])
    if args.n3:
        n3 = read(os.path.join(args.n3, "branch.csv"))
        lo = min(min(b["phi_e"]) for b in branches.values()) - 0.2
        hi = max(max(b["phi_e"]) for b in branches.values()) + 0.2
        keep = [i for i, p in enumerate(n3["phi_e"]) if lo <= p <= hi]
        ax.plot([n3["phi_e"][i] for i in keep], [n3["Eb_hat"][i] for i in keep],
                color=colours["n = 3"], linestyle="--", label="n = 3 (unstable, no contact)")
    legend(ax)
    ax.set_xlabel("excess angle φe")
    ax.set_ylabel("Ê_b = ∫U_b dΩ / A")
    events = []
    events_path = os.path.join(args.run, "events.json")
    if os.path.exists(events_path):
        with open(events_path) as f:
            events = json.load(f)
    for e in events:
        if e["kind"] in ("stability_loss", "energy_crossing", "contact"):
            ax.axvline(e["phi_e"], color="0.6", linewidth=0.7)
            ax.text(e["phi_e"], ax.get_ylim()[1], e["kind"].replace("_", " "), rotation=90,
                    fontsize=7, va="top", ha="right", color="0.4")
    fig.tight_layout()
    fig.savefig(prefix + "_eb_hat.png", dpi=130)

    if "symmetric" in branches and "skewed" in branches:
        # Total energy relative to the symmetric branch (linear interpolation in phi_e along
        # the symmetric samples, which are monotone there): its zero is phi_e^crit.
        sym = branches["symmetric"]
        order = sorted(range(len(sym["phi_e"])), key=lambda i: sym["phi_e"][i])
        sp = [sym["phi_e"][i] for i in order]
        se = [sym["E_stretch"][i] + sym["E_bend"][i] + sym["E_penalty"][i] for i in order]

        def e_sym(phi):
            for k in range(1, len(sp)):
                if sp[k] >= phi:
                    t = (phi - sp[k - 1]) / (sp[k] - sp[k - 1]) if sp[k] > sp[k - 1] else 0.0
                    return se[k - 1] + t * (se[k] - se[k - 1])
            return math.nan

        fig, ax = plt.subplots(figsize=(6.4, 3.6))
        sk = branches["skewed"]
        difference = [sk["E_stretch"][i] + sk["E_bend"][i] + sk["E_penalty"][i] - e_sym(sk["phi_e"][i])
                      for i in range(len(sk["phi_e"]))]
        plot_branch(ax, "skewed", sk, difference, colours["skewed"])
        ax.axhline(0.0, color=colours["symmetric"], linewidth=1.0, label="symmetric")
        for e in events:
            if e["kind"] in ("stability_loss", "energy_crossing"):
                ax.axvline(e["phi_e"], color="0.6", linewidth=0.7)
        legend(ax)
        ax.set_xlabel("excess angle φe")
        ax.set_ylabel("E − E_symmetric (J)")
        fig.tight_layout()
        fig.savefig(prefix + "_energy.png", dpi=130)

    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    for name, b in branches.items():
        plot_branch(ax, name, b, b["gamma"], colours[name])
    ax.axhline(math.pi / 2, color="0.6", linewidth=0.7)
    legend(ax)
    ax.set_xlabel("excess angle φe")
    ax.set_ylabel("γ (rad): angle between the contact planes")
    fig.tight_layout()
    fig.savefig(prefix + "_gamma.png", dpi=130)
    for e in events:
        print(json.dumps(e))
    print(f"wrote {prefix}_eb_hat.png, {prefix}_energy.png, {prefix}_gamma.png")


if __name__ == "__main__":
    main()
