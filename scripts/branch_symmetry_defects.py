#!/usr/bin/env python3
"""How far the saved states of a study's branches are from the half turn about z and from the
two mirrors, each in its best frame.

usage: branch_symmetry_defects.py STUDY_DIR BRANCH [BRANCH ...]

STUDY_DIR holds scene.json (the model is built from it by the Python package, for the mesh's
reference positions) and, per BRANCH (e.g. skewed, turned, wound), BRANCH/states/*.state. For
about seven states of each branch, spread over its record, prints phi_e and, for the half
turn (x, y) -> (-x, -y) and the mirrors y -> -y and x -> -x of the reference vertices, the
largest residual of the best rigid fit (Kabsch: a rotation for the half turn, a reflection
for a mirror) of the state's vertices onto their images, over the state's largest extent.
0 for a state with the symmetry in some frame. docs/continuation.md, "Symmetric subspace".
Needs the Python package (build/python on PYTHONPATH) and numpy.
"""

import glob
import os
import struct
import sys

import numpy as np

import growshell


def vertex_map(reference, sx, sy):
    """The image of each reference vertex under (x, y) -> (sx x, sy y)."""
    index = {(round(p[0], 9), round(p[1], 9)): i for i, p in enumerate(reference)}
    image = [index.get((round(sx * p[0], 9) + 0.0, round(sy * p[1], 9) + 0.0), -1)
             for p in reference]
    if min(image) < 0:
        sys.exit("the mesh lacks the symmetry (x, y) -> (%dx, %dy)" % (sx, sy))
    return np.array(image)


def load_state(path):
    """phi_e and the vertex positions of a saved state (binary format, any version)."""
    data = open(path, "rb").read()
    if not data.startswith(b"growshell-state "):
        sys.exit(f"{path}: not a binary saved state")
    n, _ = struct.unpack_from("<qQ", data, 18)
    version = int(data[16:17])
    phi = struct.unpack_from("<d", data, 34)[0]
    x_at = 34 + (24 if version >= 2 else 16)
    return phi, np.frombuffer(data, "<f8", n, x_at).reshape(-1, 3)


def fit_defect(y, image, proper):
    """Largest residual of the best rigid fit of y onto y[image], over y's largest extent."""
    a, b = y - y.mean(0), y[image] - y[image].mean(0)
    u, _, vt = np.linalg.svd(b.T @ a)
    d = np.sign(np.linalg.det(u @ vt))
    d = d if proper else -d
    rotation = u @ np.diag([1.0, 1.0, d]) @ vt
    return np.abs(b - a @ rotation.T).max() / np.abs(a).max()


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    study = sys.argv[1]
    model = growshell.model_from_scene(os.path.join(study, "scene.json"))
    reference = np.asarray(model.reference_positions()).reshape(-1, 3)
    maps = {"half turn": (vertex_map(reference, -1, -1), True),
            "mirror y": (vertex_map(reference, 1, -1), False),
            "mirror x": (vertex_map(reference, -1, 1), False)}
    for branch in sys.argv[2:]:
        files = sorted(glob.glob(os.path.join(study, branch, "states", "*.state")))
        if not files:
            sys.exit(f"{study}/{branch}/states holds no saved state")
        for path in files[::max(1, len(files) // 6)] + files[-1:]:
            phi, y = load_state(path)
            defects = ", ".join(f"{name} {fit_defect(y, image, proper):.2e}"
                                for name, (image, proper) in maps.items())
            print(f"{branch:10s} phi_e {phi:.4f}: {defects}")


if __name__ == "__main__":
    main()
