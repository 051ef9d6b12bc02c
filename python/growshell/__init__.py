"""growshell from Python: the shell model of a scene, its energy, gradient (numpy) and Hessian
(scipy.sparse) at a state x and an excess angle phi_e, and the studies of `growshell run`.

    import growshell
    model = growshell.model_from_scene("examples/scenes/cone_h004.json")
    x = model.reference_positions()          # the flat sheet, 3 numbers per control point
    e = model.energy(x, 0.5)                 # J
    g = model.gradient(x, 0.5)               # numpy array, N
    H = model.hessian(x, 0.5)                # scipy.sparse.csc_matrix, N x N, symmetric
    results = growshell.run_study("examples/scenes/cone_h004.json", "out/cone",
                                  progress=print)   # results.json as a dict

x is the flat vector of the control points' positions (x0, y0, z0, x1, ...), in m; phi_e the
excess angle in radians. Library errors raise ValueError (bad input: a wrong size, a scene
key, a directory in use) or RuntimeError, with the library's message. docs/guide/python.md.
"""

import json
import os

import numpy as np

from . import _growshell

__all__ = ["Model", "model_from_scene", "model_from_arrays", "run_study", "StudyResults"]


def _overrides(overrides):
    """{key: value} as the text `growshell run --set key=value` takes (JSON for non-strings)."""
    if overrides is None:
        return {}
    if not isinstance(overrides, dict):
        raise TypeError("overrides must be a dict of scene keys to values, e.g. {'thickness': 0.04}")
    text = {}
    for key, value in overrides.items():
        if not isinstance(key, str):
            raise TypeError(f"scene key {key!r} is not a string")
        text[key] = value if isinstance(value, str) else json.dumps(value)
    return text


def _state(x):
    return np.ascontiguousarray(x, dtype=np.float64).reshape(-1)


class Model:
    """The shell model of a scene (its mesh, material, thickness and growth law). The excess
    angle phi_e is an argument of every evaluation, never state of the model."""

    def __init__(self, core):
        self._core = core

    @property
    def dimension(self):
        """Number of unknowns N (3 per control point)."""
        return self._core.dimension

    @property
    def num_elements(self):
        return self._core.num_elements

    @property
    def thickness(self):
        """The thickness at the centre, m (of a model from arrays: the largest)."""
        return self._core.thickness

    @property
    def scene(self):
        """The scene, every key, as a dict (the model was built from it); None for a model
        built from arrays."""
        text = self._core.scene_json()
        return json.loads(text) if text else None

    def reference_positions(self):
        """The flat reference sheet's control points as a state x (numpy array, N)."""
        return np.array(self._core.reference_positions())

    def energy(self, x, phi_e):
        """E_s + E_b at state x and excess angle phi_e, J."""
        return self._core.energy(_state(x), float(phi_e))

    def gradient(self, x, phi_e):
        """dE/dx (numpy array, N), N."""
        return np.array(self._core.gradient(_state(x), float(phi_e)))

    def hessian(self, x, phi_e):
        """d2E/dx2 as a symmetric scipy.sparse.csc_matrix, N x N, N/m."""
        import scipy.sparse

        values, rows, starts, n = self._core.hessian_upper(_state(x), float(phi_e))
        upper = scipy.sparse.csc_matrix((values, rows, starts), shape=(n, n))
        diagonal = scipy.sparse.diags(upper.diagonal())
        return (upper + upper.T - diagonal).tocsc()

    def energy_breakdown(self, x, phi_e):
        """{'stretching', 'bending', 'total' (J), 'eb_hat' (the normalised bending energy),
        'current_area', 'grown_area' (m^2)}."""
        return dict(self._core.energy_breakdown(_state(x), float(phi_e)))

    def limit_positions(self, x):
        """The limit surface's points at the sheet's control points of state x (the ghost
        control points outside the sheet left out), (V, 3) numpy array, m."""
        return np.array(self._core.limit_positions(_state(x)))


    def mirror_axis_pins(self, x):
        """Six dofs that remove the rigid motions at state x, on the mesh's mirror axes, so
        that a mirror-symmetric state stays so (the studies' pins)."""
        return list(self._core.mirror_axis_pins(_state(x)))

    def minimize(self, x, phi_e, pins=None, tolerance=1e-7, max_iterations=200):
        """Newton's method (CHOLMOD) from x at phi_e, with the dofs `pins` held (default
        mirror_axis_pins(x)), to a gradient below `tolerance` Y h^3 / L. Returns a dict: 'x'
        (numpy), 'converged', 'energy' (J), 'iterations', 'message', 'pins'."""
        r = dict(self._core.minimize(_state(x), float(phi_e), list(pins or []),
                                     float(tolerance), int(max_iterations)))
        r["x"] = np.array(r["x"])
        return r

    def trace(self, x, phi_e, phi_max, phi_min=0.0, direction=1, pins=None, tolerance=1e-6,
              max_step=0.1, min_step=1e-6, max_steps=10000, corrector="newton", progress=None):
        """Pseudo-arclength continuation from the equilibrium (x, phi_e) towards phi_max
        (direction +1) or phi_min (-1), with stability (the Hessian's negative eigenvalue count,
        from MUMPS' LDL^T) and its special points located. Returns a dict of numpy arrays
        'phi_e', 'arclength', 'negative_eigenvalues', 'states' (one row per sample), and
        'special_points' (dicts: kind 'fold' or 'branch point', phi_e, negative_before/after,
        x), 'reached_bound', 'message', 'steps', 'factorizations'. `progress(phi_e, negative)`
        is called at each sample. No branch switching: the trace follows the branch it starts
        on (the studies switch onto the cones)."""
        r = dict(self._core.trace(_state(x), float(phi_e), int(direction), float(phi_min),
                                  float(phi_max), list(pins or []), float(tolerance),
                                  float(max_step), float(min_step), int(max_steps), corrector,
                                  progress))
        for key in ("phi_e", "arclength", "negative_eigenvalues", "states"):
            r[key] = np.array(r[key])
        r["special_points"] = [dict(p, x=np.array(p["x"])) for p in r["special_points"]]
        return r


def model_from_scene(path, overrides=None):
    """The model of the scene file `path`, with `overrides` ({scene key: value}, as
    `growshell run --set`) applied. Raises ValueError naming a bad key or value."""
    return Model(_growshell.model_from_scene(os.fspath(path), _overrides(overrides)))


def model_from_arrays(vertices, faces, thickness, youngs_modulus=1e4, poisson_ratio=0.3,
                      stretching_law="saint_venant_kirchhoff", center=(0.0, 0.0),
                      smoothing_radius=0.0, quadrature_degree=2):
    """The model of a planar sheet given as arrays: `vertices` (V, 3) with z = 0 or (V, 2), m;
    `faces` (F, 3) vertex indices, counter-clockwise seen from +z. Its ghost layer is added
    (the control points beyond the boundary that make every face an element), so the state
    has more than 3 V entries; the sheet's vertices keep their indices and come first.
    `thickness` (m): one number, or one per vertex (linear on each face), or one per face
    (constant on each). Material: Young's modulus (Pa), Poisson ratio, stretching law
    ('saint_venant_kirchhoff' or 'neo_hookean'). Growth: circumferential about `center`
    (x, y), with the excess angle spread over `smoothing_radius` (m; 0: a point defect).
    Raises ValueError naming what is wrong with the arrays."""
    v = np.asarray(vertices, dtype=np.float64)
    if v.ndim != 2 or v.shape[1] not in (2, 3):
        raise ValueError(f"vertices must be an array of shape (V, 2) or (V, 3), not {v.shape}")
    if v.shape[1] == 2:
        v = np.column_stack([v, np.zeros(len(v))])
    f = np.asarray(faces)
    if f.ndim != 2 or f.shape[1] != 3 or not np.issubdtype(f.dtype, np.integer):
        raise ValueError(f"faces must be an integer array of shape (F, 3), not {f.shape} {f.dtype}")
    t = np.atleast_1d(np.asarray(thickness, dtype=np.float64))
    if t.size == 1:
        on = "constant"
    elif t.size == len(v):
        on = "vertex"
    elif t.size == len(f):
        on = "face"
    else:
        raise ValueError(f"thickness has {t.size} values: give one, one per vertex ({len(v)}) "
                         f"or one per face ({len(f)})")
    return Model(_growshell.model_from_arrays(
        np.ascontiguousarray(v), np.ascontiguousarray(f, dtype=np.int32), t, on,
        float(youngs_modulus), float(poisson_ratio), stretching_law,
        np.asarray(center, dtype=np.float64).reshape(2), float(smoothing_radius),
        int(quadrature_degree)))


class StudyResults(dict):
    """results.json of a study as a dict, with `directory`, `completed` and `end`, and
    `branch(name)` reading one of its branch CSV files into numpy columns."""

    def __init__(self, directory, data):
        super().__init__(data)
        self.directory = directory

    @property
    def completed(self):
        return bool(self.get("completed"))

    @property
    def end(self):
        return self.get("end")

    def branch(self, key="branch_csv"):
        """The CSV the results key `key` names ('branch_csv' of a cone_branch study;
        'symmetric_csv', 'skewed_csv', 'turned_csv' of an econe_contact study), as a dict of
        column name to numpy array."""
        if key not in self:
            raise KeyError(f"results.json of {self.directory} has no key {key!r}")
        path = os.path.join(self.directory, self[key])
        data = np.genfromtxt(path, delimiter=",", names=True)
        return {name: np.atleast_1d(data[name]) for name in data.dtype.names}


def run_study(scene, out=None, overrides=None, resume=False, overwrite=False, progress=None):
    """Runs the study the scene file names (study.kind) into `out` (default: the scene's
    output.directory), as `growshell run` does (without its figure), and returns its
    results.json as StudyResults. `resume` goes on with a recorded run, `overwrite` replaces
    one; without either a used directory raises ValueError. `progress(line)` receives each
    line of the study's log. The interpreter's other threads run meanwhile (the GIL is
    released). A study that ended early (e.g. at a step below min_step) returns its results
    with completed False and the reason in `end`."""
    if resume and overwrite:
        raise ValueError("resume and overwrite exclude each other")
    existing = "resume" if resume else "overwrite" if overwrite else "refuse"
    overrides = _overrides(overrides)
    if out is not None:
        out = os.fspath(out)
    _growshell.run_study(os.fspath(scene), overrides, out or "", existing, progress)
    directory = out or json.loads(_scene_json(scene, overrides))["output"]["directory"]
    with open(os.path.join(directory, "results.json")) as f:
        return StudyResults(directory, json.load(f))


def _scene_json(scene, overrides):
    """The scene file with its overrides, every key, as JSON text (without building a model)."""
    return _growshell.scene_json(os.fspath(scene), overrides)
