"""The Python package growshell (python/), run by ctest `python_module` with PYTHONPATH at the
build tree's python/ and GROWSHELL_MODEL_VALUES naming tests/python/model_values.cpp's
program, GROWSHELL_TEST_OUT a scratch directory.

- energy, gradient and Hessian through Python equal the library's (model_values) to the last
  bits (1e-13 relative: the same code, only copied);
- the gradient and the Hessian agree with central differences of the energy and the gradient
  (relative 1e-6 at step 1e-6 m on a state of the coarse cone mesh);
- a model from numpy arrays (a Delaunay disc) with thickness as one value, per vertex and per
  face;
- Newton's method and continuation from Python find the study's cone (E_b-hat to 1e-6);
- a small cone_branch study run from Python: the flat sheet's first branch point at
  c2 h^2 / R^2 (physics.md: c2 = 10.59) within this coarse mesh's 3 %, its branch's columns as
  numpy arrays, every progress line delivered, a used directory refused, and a resume of the
  finished study returns the same results;
- the bifurcation diagram (growshell.plots) draws stable parts solid, unstable ones dashed,
  and labels the special points;
- bad input raises ValueError (or FileNotFoundError-like RuntimeError) with the library's
  message naming what is wrong.
"""

import json
import math
import os
import pathlib
import subprocess

import numpy as np
import pytest

import growshell

SCENE = {"thickness": 0.04, "mesh": {"size_slope": 0.25},
         "continuation": {"phi_max": 0.3}, "output": {"write_vtk": False},
         "study": {"eigenmodes": 0}}
PHI = 0.4


@pytest.fixture(scope="module")
def scratch():
    out = pathlib.Path(os.environ.get("GROWSHELL_TEST_OUT", "python_module_out"))
    out.mkdir(parents=True, exist_ok=True)
    return out


@pytest.fixture(scope="module")
def scene(scratch):
    path = scratch / "coarse.json"
    path.write_text(json.dumps(SCENE))
    return path


@pytest.fixture(scope="module")
def model(scene):
    return growshell.model_from_scene(scene)


def perturbed(model):
    x = model.reference_positions()
    i = np.arange(x.size, dtype=float)
    return x + 1e-3 * np.sin(0.7 * i + 0.3)


def test_values_equal_the_librarys(model, scene):
    program = os.environ.get("GROWSHELL_MODEL_VALUES")
    if not program:
        pytest.skip("GROWSHELL_MODEL_VALUES not set (run through ctest)")
    reference = json.loads(subprocess.run([program, str(scene), repr(PHI)], check=True,
                                          capture_output=True, text=True).stdout)
    x = perturbed(model)
    assert model.energy(x, PHI) == pytest.approx(reference["energy"], rel=1e-13)
    g = model.gradient(x, PHI)
    g_ref = np.array(reference["gradient"])
    assert g.shape == g_ref.shape
    assert np.max(np.abs(g - g_ref)) <= 1e-13 * np.max(np.abs(g_ref))
    H = model.hessian(x, PHI)
    upper = np.array(reference["hessian_upper"])
    rows, cols = upper[:, 0].astype(int), upper[:, 1].astype(int)
    values = np.asarray(H[rows, cols]).ravel()
    assert np.max(np.abs(values - upper[:, 2])) <= 1e-13 * np.max(np.abs(upper[:, 2]))
    # Symmetric, and nothing beyond the library's pattern.
    assert abs(H - H.T).max() == 0.0
    assert H.nnz == 2 * len(upper) - np.count_nonzero(rows == cols)


def test_gradient_and_hessian_against_central_differences(model):
    x = perturbed(model)
    rng = np.random.default_rng(7)
    g = model.gradient(x, PHI)
    H = model.hessian(x, PHI)
    step = 1e-6
    for _ in range(3):
        v = rng.standard_normal(x.size)
        v /= np.linalg.norm(v)
        slope = (model.energy(x + step * v, PHI) - model.energy(x - step * v, PHI)) / (2 * step)
        assert slope == pytest.approx(g @ v, rel=1e-6)
        dg = (model.gradient(x + step * v, PHI) - model.gradient(x - step * v, PHI)) / (2 * step)
        Hv = H @ v
        assert np.linalg.norm(dg - Hv) <= 1e-6 * np.linalg.norm(Hv)


def test_flat_sheet_has_no_bending_and_phi_e_is_an_argument(model):
    x = model.reference_positions()
    parts = model.energy_breakdown(x, 0.0)
    assert parts["bending"] == 0.0
    assert parts["stretching"] == pytest.approx(0.0, abs=1e-20)
    # Growth stretches the flat sheet; the model keeps no excess angle between calls.
    assert model.energy(x, PHI) > 0.0
    assert model.energy(x, 0.0) == pytest.approx(0.0, abs=1e-20)
    points = model.limit_positions(x)
    assert points.shape[1] == 3 and 0 < points.shape[0] <= model.dimension // 3
    # The flat sheet's limit surface lies in the plane z = 0, inside the disc of radius 1 and
    # close to its rim (the limit of the rim polygon; 0.9936 on this mesh).
    assert np.max(np.abs(points[:, 2])) < 1e-12
    assert 0.98 < np.max(np.hypot(points[:, 0], points[:, 1])) <= 1.0 + 1e-12
    assert model.scene["thickness"] == 0.04


@pytest.fixture(scope="module")
def study(scene, scratch):
    out = scratch / "cone"
    lines = []
    results = growshell.run_study(scene, out, overwrite=out.exists(), progress=lines.append)
    return out, results, lines


def test_a_small_study_end_to_end(scene, study):
    out, results, lines = study
    assert results.completed, results.end
    c2 = 10.59
    assert results["phi_branch"] == pytest.approx(c2 * 0.04 ** 2, rel=0.03)
    branch = results.branch()
    assert branch["phi_e"].size >= 5
    assert np.all(np.diff(branch["phi_e"][1:]) > 0)
    assert branch["phi_e"].max() == pytest.approx(0.3, abs=0.11)
    assert any(line.startswith("# ") for line in lines)
    assert (out / "results.json").is_file()
    # A used directory is refused by name; resumed, the finished study gives the same results.
    with pytest.raises(ValueError, match=str(out.name)):
        growshell.run_study(scene, out)
    again = growshell.run_study(scene, out, resume=True)
    assert again["phi_branch"] == results["phi_branch"]


def test_newton_and_continuation_find_the_studys_cone(model, study):
    """Newton from a saddle-shaped start at 0.1, the cone traced to 0.3 from there, and Newton
    at the study's own samples from the nearest traced state: the study's cone (its E_b-hat
    to 1e-6; measured 2e-9 inside the trace, 4e-7 past it), stable throughout."""
    _, results, _ = study
    x = model.reference_positions()
    points = x.reshape(-1, 3)
    x[2::3] = 1e-2 * (points[:, 0] ** 2 - points[:, 1] ** 2)
    start = model.minimize(x, 0.1)
    assert start["converged"], start["message"]
    samples = []
    trace = model.trace(start["x"], 0.1, 0.3, progress=lambda phi, n: samples.append((phi, n)))
    assert trace["reached_bound"], trace["message"]
    assert trace["phi_e"][0] == pytest.approx(0.1, abs=1e-12)
    assert trace["phi_e"][-1] >= 0.3
    assert np.all(trace["negative_eigenvalues"] == 0)
    assert trace["special_points"] == []
    assert len(samples) == trace["phi_e"].size
    assert trace["states"].shape == (trace["phi_e"].size, model.dimension)
    branch = results.branch()
    checked = 0
    for phi, eb_hat in zip(branch["phi_e"], branch["Eb_hat"]):
        if not 0.12 < phi < 0.4:
            continue
        nearest = trace["states"][np.argmin(np.abs(trace["phi_e"] - phi))]
        at = model.minimize(nearest, phi)
        assert at["converged"], at["message"]
        assert model.energy_breakdown(at["x"], phi)["eb_hat"] == pytest.approx(eb_hat, rel=1e-6)
        checked += 1
    assert checked >= 2


def polar_disc():
    """A disc of radius 1 triangulated from 6 rings of points (scipy's Delaunay), counter-
    clockwise."""
    from scipy.spatial import Delaunay
    points = [(0.0, 0.0)]
    for k in range(1, 7):
        n = 6 * k
        points += [(k / 6 * math.cos(2 * math.pi * j / n), k / 6 * math.sin(2 * math.pi * j / n))
                   for j in range(n)]
    points = np.array(points)
    faces = Delaunay(points).simplices
    a, b, c = points[faces[:, 0]], points[faces[:, 1]], points[faces[:, 2]]
    clockwise = (b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0] < 0
    faces[clockwise] = faces[clockwise][:, [0, 2, 1]]
    return points, faces


def test_model_from_arrays():
    """A model from numpy arrays: its ghost layer added, the flat sheet stress-free at
    phi_e = 0 and stretched by growth, its gradient the energy's slope; thickness as one
    value, per vertex or per face gives the same model when the values agree, and the
    energies scale as h (stretching) and h^3 (bending); a varying thickness gives energies
    between those of its smallest and largest value."""
    points, faces = polar_disc()
    h = 0.04
    model = growshell.model_from_arrays(points, faces, h)
    assert model.dimension > 3 * len(points)  # the ghost layer
    assert model.num_elements == len(faces)
    assert model.scene is None
    x = model.reference_positions()
    assert np.allclose(x[:3 * len(points)].reshape(-1, 3)[:, :2], points, atol=1e-14)
    assert model.energy(x, 0.0) == pytest.approx(0.0, abs=1e-20)
    assert model.energy(x, PHI) > 0.0
    y = x + 1e-3 * np.sin(np.arange(x.size))
    v = np.random.default_rng(3).standard_normal(x.size)
    v /= np.linalg.norm(v)
    slope = (model.energy(y + 1e-6 * v, PHI) - model.energy(y - 1e-6 * v, PHI)) / 2e-6
    assert slope == pytest.approx(model.gradient(y, PHI) @ v, rel=1e-6)
    reference = model.energy(y, PHI)
    per_vertex = growshell.model_from_arrays(points, faces, np.full(len(points), h))
    per_face = growshell.model_from_arrays(points, faces, np.full(len(faces), h))
    assert per_vertex.energy(y, PHI) == pytest.approx(reference, rel=1e-13)
    assert per_face.energy(y, PHI) == pytest.approx(reference, rel=1e-13)
    thick = growshell.model_from_arrays(points, faces, np.full(len(points), 2 * h))
    a, b = model.energy_breakdown(y, PHI), thick.energy_breakdown(y, PHI)
    assert b["stretching"] / a["stretching"] == pytest.approx(2.0, rel=1e-12)
    assert b["bending"] / a["bending"] == pytest.approx(8.0, rel=1e-12)
    # Thickness from h at x = -1 to 2 h at x = +1 (linear: exact per vertex), and per face a
    # checkerboard of h and 2 h.
    for values in (h * (1.5 + 0.5 * points[:, 0]), np.where(np.arange(len(faces)) % 2, h, 2 * h)):
        varying = growshell.model_from_arrays(points, faces, values).energy_breakdown(y, PHI)
        for part in ("stretching", "bending"):
            assert a[part] < varying[part] < b[part]
    with pytest.raises(ValueError, match="faces name vertices"):
        growshell.model_from_arrays(points, faces + len(points), h)
    with pytest.raises(ValueError, match="one per vertex"):
        growshell.model_from_arrays(points, faces, [h, h])
    with pytest.raises(ValueError, match="thickness"):
        growshell.model_from_arrays(points, faces, np.full(len(points), -h))
    with pytest.raises(ValueError, match="stretching_law"):
        growshell.model_from_arrays(points, faces, h, stretching_law="hooke")
    with pytest.raises(ValueError, match="shape"):
        growshell.model_from_arrays(points[:, :1], faces, h)


def test_bifurcation_diagram_draws_stable_solid_and_unstable_dashed(study, scratch):
    plt = pytest.importorskip("matplotlib.pyplot")
    import growshell.plots
    ax = growshell.plots.bifurcation_diagram([0, 1, 2, 3], [0, 1, 0.5, 2], [0, 0, 1, 1],
                                             [{"kind": "fold", "phi_e": 1.5}])
    styles = [line.get_linestyle() for line in ax.lines]
    assert "-" in styles and "--" in styles
    assert any("fold 1.5000" in text.get_text() for text in ax.texts)
    assert ax.get_xlabel() == r"$\varphi_e$ (rad)"
    with pytest.raises(ValueError, match="differ in length"):
        growshell.plots.bifurcation_diagram([0, 1], [0], [0, 0])
    _, results, _ = study
    ax = growshell.plots.study_diagram(results)
    assert any("branch_point" in text.get_text() for text in ax.texts)
    ax.figure.savefig(scratch / "study_diagram.png")
    assert (scratch / "study_diagram.png").stat().st_size > 1000
    plt.close("all")


def test_bad_input_raises_named_errors(model, scene, scratch):
    x = model.reference_positions()
    with pytest.raises(ValueError, match="entries; the model has"):
        model.energy(x[:-3], PHI)
    with pytest.raises(ValueError, match="not finite"):
        model.gradient(np.full(x.size, np.nan), PHI)
    with pytest.raises(ValueError, match="excess angle"):
        model.hessian(x, math.inf)
    with pytest.raises(ValueError, match="mesh.no_such_key"):
        growshell.model_from_scene(scene, {"mesh.no_such_key": 3})
    with pytest.raises(ValueError, match="thickness"):
        growshell.model_from_scene(scene, {"thickness": -0.1})
    with pytest.raises((ValueError, RuntimeError), match="missing.json"):
        growshell.model_from_scene(scratch / "missing.json")
    with pytest.raises(TypeError):
        growshell.model_from_scene(scene, ["thickness", 0.1])
    with pytest.raises(ValueError, match="direction"):
        model.trace(x, 0.0, 0.1, direction=0)
    with pytest.raises(ValueError, match="corrector"):
        model.trace(x, 0.0, 0.1, corrector="broyden")
    with pytest.raises(ValueError, match="tolerance"):
        model.minimize(x, 0.0, tolerance=-1.0)
    with pytest.raises(ValueError, match="resume and overwrite"):
        growshell.run_study(scene, scratch / "x", resume=True, overwrite=True)
