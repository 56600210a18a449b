"""More general-sweep fixtures (issue 11, section 3): a letter G along the cubic, a remeshed, a holed
and a decimated version of the moulding along the cubic. Targets: coverage >= 0.95 and plane recall
>= 0.95 on clean fixtures, met on all four (docs/sweeps.md, Numbers)."""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest

from auszug.sweeps import DEFAULT, detect
from auszug.sweeps.fixtures import decimated, letter_g_along_cubic, letter_g_profile, moulding_along_cubic, with_hole
from auszug.sweeps.general import motion_planes
from auszug.sweeps.planes import plane_recall


@cache
def _run(name):
    fx = {"letter_g": letter_g_along_cubic, "remeshed": lambda: moulding_along_cubic(jitter=0.4),
          "hole": lambda: with_hole(moulding_along_cubic()),
          "decimated": lambda: decimated(moulding_along_cubic(), 6000)}[name]()
    r = detect((fx.vertices, fx.faces), DEFAULT.with_(eps_prox=0.005))
    planes = [motion_planes(p.profile, p.motion, 8) for p in r.patches]
    recall = plane_recall(fx.planes, np.vstack([n for n, _ in planes]), np.concatenate([d for _, d in planes]))
    return fx, r, recall


def test_letter_g_profile_is_an_open_g():
    g = letter_g_profile(80)
    assert g.shape == (80, 2)
    assert np.allclose(g.min(axis=0), -g.max(axis=0))                  # centred on its box
    assert np.linalg.norm(g[0] - g[-1]) > 0.1                           # open
    step = np.linalg.norm(np.diff(g, axis=0), axis=1)
    assert step.min() > 0


@pytest.mark.parametrize("name, coverage, recall, profile", [
    ("letter_g", 0.95, 0.95, 0.95),     # measured 0.996, 1.00, 0.98 of the profile (targets met)
    ("remeshed", 0.95, 0.95, 0.95),     # measured 1.000, 1.00, 0.96 (targets met)
    ("hole", 0.95, 0.95, 0.95),         # measured 1.000, 1.00, 0.97 (targets met; main had 0.776, 0.37)
    ("decimated", 0.95, 0.95, 0.88),    # measured 0.986, 1.00, 0.91 (targets met; main had 0.728, 0.20)
])
def test_general_sweep_fixture(name, coverage, recall, profile):
    """Coverage and plane recall (issue targets 0.95 / 0.95 on clean fixtures), every kept patch within
    the fit bound, and the patch of most coverage sweeps (nearly) the whole profile."""
    fx, r, rec = _run(name)
    assert r.patches and all(p.kind == "general" for p in r.patches)
    assert all(p.fit_error <= DEFAULT.fit_factor * 0.005 for p in r.patches)
    assert r.coverage >= coverage
    assert rec >= recall
    best = max(r.patches, key=lambda p: p.coverage)
    assert np.linalg.norm(np.diff(best.profile, axis=0), axis=1).sum() >= profile * fx.profile_length


def test_hole_and_decimation_keep_the_truth():
    base = moulding_along_cubic()
    h = with_hole(base)
    assert len(h.faces) < len(base.faces) and np.array_equal(h.planes, base.planes)
    # every vertex of the holed mesh is a vertex of the base mesh, and the hole is one
    from scipy.spatial import cKDTree

    assert cKDTree(base.vertices).query(h.vertices)[0].max() == 0.0
    assert len(base.vertices) - len(h.vertices) >= 100
    d = decimated(base, 6000)
    assert len(d.faces) <= 6000 and np.array_equal(d.planes, base.planes)


@cache
def _closed():
    from auszug.sweeps.fixtures import closed_along_cubic

    fx = closed_along_cubic()
    r = detect((fx.vertices, fx.faces), DEFAULT.with_(eps_prox=0.005))
    planes = [motion_planes(p.profile, p.motion, 8) for p in r.patches]
    recall = plane_recall(fx.planes, np.vstack([n for n, _ in planes]), np.concatenate([d for _, d in planes])) \
        if planes else 0.0
    return fx, r, recall


def test_closed_profile_is_a_closed_rounded_quatrefoil():
    from auszug.sweeps.fixtures import closed_along_cubic, closed_profile

    p = closed_profile(96)
    assert np.linalg.norm(p[0] - p[-1]) < 2 * np.linalg.norm(p[1] - p[0])        # the loop's last step
    fx = closed_along_cubic()
    assert 0.2 <= fx.profile_length <= 0.25                                      # above l_min = 0.2
    # a tube open at its two ends: every edge has two faces but the two end rings'
    e = np.sort(np.vstack([fx.faces[:, [0, 1]], fx.faces[:, [1, 2]], fx.faces[:, [2, 0]]]), axis=1)
    _, count = np.unique(e, axis=0, return_counts=True)
    assert set(count.tolist()) == {1, 2} and int((count == 1).sum()) == 2 * len(p)


def test_closed_general_sweep_is_one_closed_patch():
    """A closed profile swept along the cubic with twist: found as one closed-profile patch (issue 11:
    closed profiles). Measured: 1 patch, closed, coverage 1.000, fit error 3.7e-4 - 4.5e-4, recall 1.00,
    the profile 0.99 of the true loop's length."""
    fx, r, rec = _closed()
    closed = [p for p in r.patches if p.closed]
    assert closed and all(p.kind == "general" for p in r.patches)
    best = max(closed, key=lambda p: p.coverage)
    assert best.coverage >= 0.95 and r.coverage >= 0.95
    assert best.fit_error <= DEFAULT.fit_factor * 0.005
    assert rec >= 0.95
    loop = np.vstack([best.profile, best.profile[:1]])
    assert np.linalg.norm(np.diff(loop, axis=0), axis=1).sum() >= 0.95 * fx.profile_length


def test_closed_profile_cut_open_by_a_hole_is_still_one_closed_patch():
    """The closed tube with a hole (radius 0.06, the tube's about 0.075): the true profile planes
    through the hole cut the mesh in open arcs, yet the sweep is found as one closed-profile patch
    across it (issue 11: closed profiles; the cyclic matching runs on the whole loops elsewhere on
    the tube). Measured: 10 of the 60 true planes cut open arcs; 1 patch, closed, coverage 1.000,
    recall 1.00, fit error 5.1e-4 (6.2e-4 with a hole of radius 0.03)."""
    from auszug.sweeps import cut, normalise
    from auszug.sweeps.fixtures import closed_along_cubic

    fx = with_hole(closed_along_cubic(), 0.06)
    m = normalise(fx.vertices, fx.faces)
    c = cut(m, fx.planes[:, :3], fx.planes[:, 3])
    # the hole opens some of the true profile loops (each plane's cut: closed loops or open arcs)
    opened = {int(p) for p, closed in zip(c.curve_plane, c.curve_closed, strict=True) if not closed}
    assert len(opened) >= 8
    r = detect((fx.vertices, fx.faces), DEFAULT.with_(eps_prox=0.005))
    assert len(r.patches) == 1 and r.patches[0].closed and r.patches[0].kind == "general"
    assert r.coverage >= 0.95
    assert r.patches[0].fit_error <= DEFAULT.fit_factor * 0.005
    planes = motion_planes(r.patches[0].profile, r.patches[0].motion, 8)
    assert plane_recall(fx.planes, planes[0], planes[1]) >= 0.95
