"""Figures of growshell's branches with matplotlib (Debian: python3-matplotlib).

    import growshell, growshell.plots
    trace = model.trace(x, 0.1, 3.0)
    eb_hat = [model.energy_breakdown(s, p)["eb_hat"] for s, p in zip(trace["states"], trace["phi_e"])]
    axes = growshell.plots.bifurcation_diagram(trace["phi_e"], eb_hat, trace["negative_eigenvalues"],
                                               trace["special_points"], ylabel=r"$\\hat E_b$")
    growshell.plots.study_diagram(results)   # a cone_branch study's StudyResults
"""

import json
import os

import numpy as np


def _pyplot():
    try:
        import matplotlib.pyplot as plt
    except ImportError as error:
        raise ImportError("growshell.plots needs matplotlib (Debian: apt-get install "
                          "python3-matplotlib)") from error
    return plt


def bifurcation_diagram(phi_e, values, negative_eigenvalues, special_points=(), ax=None,
                        ylabel="value", label=None, color=None):
    """Draws `values` against phi_e (rad): stable parts (no negative eigenvalue) solid,
    unstable ones dashed, and each special point (dicts with 'kind' and 'phi_e', as
    Model.trace gives them, or events.json's entries) marked at its phi_e on the curve and
    labelled with it. Returns the axes."""
    plt = _pyplot()
    phi = np.asarray(phi_e, dtype=float)
    y = np.asarray(values, dtype=float)
    negative = np.asarray(negative_eigenvalues)
    if not (phi.shape == y.shape == negative.shape):
        raise ValueError(f"phi_e, values and negative_eigenvalues differ in length: "
                         f"{phi.shape}, {y.shape}, {negative.shape}")
    if ax is None:
        _, ax = plt.subplots(figsize=(6, 4))
    stable = negative == 0
    line = None
    start = 0
    for k in range(1, phi.size + 1):
        if k == phi.size or stable[k] != stable[start]:
            end = min(k + 1, phi.size)  # join the pieces
            style = "-" if stable[start] else "--"
            kwargs = {"color": line.get_color() if line else color}
            if line is None and label:
                kwargs["label"] = label
            (drawn,) = ax.plot(phi[start:end], y[start:end], style, **kwargs)
            line = line or drawn
            start = k
    markers = {"fold": "s", "branch point": "o", "branch_point": "o"}
    for point in special_points:
        at = float(point["phi_e"])
        value = np.interp(at, phi, y) if np.all(np.diff(phi) > 0) else \
            y[int(np.argmin(np.abs(phi - at)))]
        ax.plot([at], [value], markers.get(point.get("kind"), "^"), color="black")
        ax.annotate(f"{point.get('kind', '')} {at:.4f}", (at, value), textcoords="offset points",
                    xytext=(4, 4), fontsize=8)
    ax.set_xlabel(r"$\varphi_e$ (rad)")
    ax.set_ylabel(ylabel)
    if label:
        ax.legend()
    return ax


def study_diagram(results, ax=None):
    """E_b-hat against phi_e of a cone_branch study (growshell.run_study's StudyResults), stable
    solid and unstable dashed, with its special points and events from events.json."""
    branch = results.branch()
    events = []
    path = os.path.join(results.directory, results.get("events", "events.json"))
    if os.path.isfile(path):
        with open(path) as f:
            data = json.load(f)
        events = data.get("events", data) if isinstance(data, dict) else data
        events = [e for e in events if isinstance(e, dict) and "phi_e" in e]
    ax = bifurcation_diagram(branch["phi_e"], branch["Eb_hat"], branch["n_negative"],
                             [{"kind": e.get("kind", ""), "phi_e": e["phi_e"]} for e in events],
                             ax=ax, ylabel=r"$\hat E_b$ (1/m$^2$)")
    h = results.get("thickness")
    if h is not None:
        ax.set_title(f"{results.get('study', 'study')}, h = {h} m")
    return ax
