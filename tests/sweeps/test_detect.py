"""The whole analysis (auszug.sweeps.detect): every stage, patches in input coordinates, known answers."""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from auszug.errors import GeometryError
from auszug.sweeps import detect
from auszug.sweeps.fixtures import bumps, extruded, revolved
from auszug.sweeps.params import DEFAULT


@cache
def _report(name, sigma=0.0, eps=0.005):
    fx = {"revolved": revolved, "extruded": extruded, "bumps": bumps}[name](sigma=sigma)
    return fx, detect((fx.vertices, fx.faces), DEFAULT.with_(eps_prox=eps))


@pytest.mark.parametrize("name", ["revolved", "extruded"])
@pytest.mark.parametrize("sigma", [0.0, 5e-4])
def test_kinematic_meshes_are_one_patch(name, sigma):
    fx, r = _report(name, sigma)
    assert [p.kind for p in r.patches] == ["rotation" if name == "revolved" else "translation"]
    assert r.coverage >= (0.95 if sigma == 0 else 0.85)
    assert r.patches[0].fit_error <= 2 * 0.005
    assert [s.name for s in r.stages] == ["normalise", "cut", "kinematic", "fit"]
    assert r.stage("kinematic").numbers["kinematic"] == 1


@pytest.mark.parametrize("eps, most", [(0.001, 0.0), (0.005, 0.01)])
def test_random_bumps_are_no_sweep(eps, most):
    fx, r = _report("bumps", 0.0, eps)
    assert r.coverage <= most
    if most == 0.0:
        assert r.patches == ()
    assert r.stage("kinematic").numbers["kinematic"] == 0
    # nothing covers 0.95 after the first pass, so the coarse pass runs as well, and finds no sweep
    # either; then the kinematic parts are sought, and none fits; then the mirror images of the
    # candidates that fit in the mesh's mirror planes (bumps at random have none, nor any candidate);
    # then the rotations about the axes of exact arcs among the creases (smooth bumps have no crease)
    general = ["match", "families", "motion"]
    assert [s.name for s in r.stages] == ["normalise", "cut", "kinematic", *general, *general, "parts", "mirror",
                                          "arcs", "fit"]
    assert r.stage("mirror").numbers["fit"] == 0
    assert r.stage("arcs").numbers["axes"] == 0 and r.stage("arcs").numbers["fit"] == 0
    assert [s.numbers.get("curvature_window") for s in r.stages[6:9]] == [DEFAULT.coarse_window] * 3
    assert all(s.summary.startswith("coarse pass") for s in r.stages[6:9])
    assert r.stage("parts").numbers["fit"] == 0


def test_patches_are_in_the_input_coordinates():
    """Moving and scaling the input moves and scales the patch; the fit error (relative) stays."""
    fx, ref = _report("revolved")
    rot = Rotation.from_rotvec([0.3, -0.5, 0.2]).as_matrix()
    shift = np.array([10.0, -4.0, 2.5])
    v = 7.0 * fx.vertices @ rot.T + shift
    r = detect((v, fx.faces))
    (p,), (q,) = r.patches, ref.patches
    assert r.bbox_diameter == pytest.approx(float(np.linalg.norm(np.ptp(v, axis=0))), rel=1e-12)
    # every profile point lies on the moved mesh: its distance to the moved reference profile's sweep is tiny
    from auszug.sweeps.patches import closest_distance

    d, _ = closest_distance(p.profile, v, fx.faces)
    assert d.max() <= 1e-3 * r.bbox_diameter
    # the profile swept to its last position is on the mesh as well
    end = p.motion.apply(p.profile, [p.motion.t[-1]])[0]
    d, _ = closest_distance(end, v, fx.faces)
    assert d.max() <= 1e-3 * r.bbox_diameter
    assert p.fit_error == pytest.approx(q.fit_error, abs=2e-4)
    assert len(p.faces) == len(q.faces)


def test_progress_reports_every_stage_in_order():
    fx = extruded(n_profile=30, n_path=30)
    seen = []
    detect((fx.vertices, fx.faces), progress=lambda name, done, total: seen.append((name, done, total)))
    assert [s[0] for s in seen] == ["normalise", "cut", "kinematic", "fit", "fit"]
    assert seen[-1][1] == seen[-1][2]


def test_explain_names_every_stage_and_patch():
    fx, r = _report("extruded")
    text = r.explain()
    for s in r.stages:
        assert text.count(s.name) >= 1
    assert "patch 0: translation" in text and "coverage 1.000" in text


def test_bad_meshes_are_refused():
    with pytest.raises(GeometryError, match="non-finite"):
        detect(([[0, 0, 0], [1, 0, np.nan], [0, 1, 0]], [[0, 1, 2]]))
    with pytest.raises(GeometryError, match="non-empty"):
        detect((np.zeros((0, 3)), np.zeros((0, 3), int)))
