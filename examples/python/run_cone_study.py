#!/usr/bin/python3
"""A cone_branch study from Python: the two-fold e-cone traced from the flat sheet, its key
values, and E_b-hat against phi_e from its branch as numpy arrays (drawn if matplotlib is
there).

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
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit(0)
figure, axes = plt.subplots(figsize=(5, 3.5))
axes.plot(branch["phi_e"], branch["Eb_hat"], "-")
axes.set_xlabel(r"$\varphi_e$ (rad)")
axes.set_ylabel(r"$\hat E_b$")
axes.set_title("two-fold e-cone, h = 0.04")
figure.tight_layout()
figure.savefig(f"{out}/eb_hat_python.png", dpi=120)
print(f"wrote {out}/eb_hat_python.png")
