#!/usr/bin/python3
"""A cone_branch study from Python: the two-fold e-cone traced from the flat sheet, its key
values, its branch as numpy arrays, and its bifurcation diagram (growshell.plots, if
matplotlib is there).

usage: PYTHONPATH=build/python examples/python/run_cone_study.py [OUT_DIR]
"""
import os
import sys

import growshell

out = sys.argv[1] if len(sys.argv) > 1 else "out/python_cone"
results = growshell.run_study("examples/scenes/cone_h004.json", out,
                              overrides={"continuation.phi_max": 4.5,
                                         "output.write_vtk": False},
                              resume=os.path.exists(os.path.join(out, "record.json")),  # go on
                              progress=lambda line: print(line, flush=True))
print(f"completed: {results.completed} ({results.end})")
print(f"first branch point phi_e = {results['phi_branch']:.6f}, "
      f"E_b-hat max {results['eb_hat_max']:.4f} at phi_e = {results['phi_max']:.4f}")
branch = results.branch()
print(f"{branch['phi_e'].size} samples, E_b-hat from {branch['Eb_hat'][0]:.4g} to "
      f"{branch['Eb_hat'][-1]:.4g}")
try:
    import matplotlib
    matplotlib.use("Agg")
    import growshell.plots
except ImportError:
    sys.exit(0)
axes = growshell.plots.study_diagram(results)  # stable solid, unstable dashed, events marked
axes.figure.tight_layout()
axes.figure.savefig(f"{out}/eb_hat_python.png", dpi=120)
print(f"wrote {out}/eb_hat_python.png")
