#!/usr/bin/python3
"""The model of a scene from Python: energy, gradient and Hessian of a state, and a
finite-difference check of the gradient along a random direction.

usage: PYTHONPATH=build/python examples/python/energy_gradient_hessian.py [SCENE.json] [PHI_E]
"""
import sys

import numpy as np

import growshell

scene = sys.argv[1] if len(sys.argv) > 1 else "examples/scenes/cone_h004.json"
phi_e = float(sys.argv[2]) if len(sys.argv) > 2 else 0.5

model = growshell.model_from_scene(scene)
x = model.reference_positions()
x = x + 1e-3 * np.sin(np.arange(x.size))  # a state off the flat sheet
energy = model.energy(x, phi_e)
gradient = model.gradient(x, phi_e)
hessian = model.hessian(x, phi_e)
print(f"{model.dimension} unknowns, {model.num_elements} elements, h = {model.thickness} m")
print(f"E = {energy:.10g} J at phi_e = {phi_e}; |g|_inf = {np.abs(gradient).max():.3e} N; "
      f"Hessian {hessian.shape[0]} x {hessian.shape[1]}, {hessian.nnz} entries")

direction = np.random.default_rng(0).standard_normal(x.size)
direction /= np.linalg.norm(direction)
step = 1e-6
difference = (model.energy(x + step * direction, phi_e) -
              model.energy(x - step * direction, phi_e)) / (2 * step)
print(f"dE along a random direction: gradient {gradient @ direction:.10g}, "
      f"central difference {difference:.10g}")
