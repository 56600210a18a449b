"""The rows of the fixture matrix (issue 11, section 3) met by the coarse matching pass, the
re-slicing that leaves points over a hole alone, and the translational sweep across holes: the
letter G along the cubic at sigma 5e-4 and 1e-3 and with the hole (clean and at 5e-4), and the
double translational arch at sigma 1e-3, with the hole (clean and at 5e-4) and decimated to 6000
triangles. Targets: coverage >= 0.95 clean, >= 0.85 noisy; plane recall (true profile planes within
2 deg and 0.005 found) >= 0.95 clean, >= 0.85 at sigma 5e-4 (none is set at 1e-3: asserted at 0.85)."""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest

from auszug.sweeps import DEFAULT, detect
from auszug.sweeps.fixtures import decimated, double_translational, letter_g_along_cubic, with_hole
from auszug.sweeps.general import motion_planes
from auszug.sweeps.planes import plane_recall

PARAMS = DEFAULT.with_(eps_prox=0.005)


@cache
def _fixture(name):
    return {"letter_g 5e-4": lambda: letter_g_along_cubic(sigma=5e-4),
            "letter_g 1e-3": lambda: letter_g_along_cubic(sigma=1e-3),
            "letter_g hole": lambda: with_hole(letter_g_along_cubic()),
            "letter_g hole 5e-4": lambda: with_hole(letter_g_along_cubic(sigma=5e-4)),
            "arch 1e-3": lambda: double_translational(sigma=1e-3),
            "arch hole": lambda: with_hole(double_translational()),
            "arch hole 5e-4": lambda: with_hole(double_translational(sigma=5e-4)),
            "arch decimated": lambda: decimated(double_translational(), 6000)}[name]()


@cache
def _run(name, params=PARAMS):
    fx = _fixture(name)
    return fx, detect((fx.vertices, fx.faces), params)


def _length(p):
    return float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())


def _recall(fx, r):
    planes = [motion_planes(p.profile, p.motion, 8) for p in r.patches]
    return plane_recall(fx.planes, np.vstack([n for n, _ in planes]), np.concatenate([d for _, d in planes]))


@pytest.mark.parametrize("name, coverage, recall, coarse", [
    ("letter_g 5e-4", 0.85, 0.85, False),   # measured 1.000, 1.00 (0.997, 1.00 by the coarse pass before
                                            # sweeps-members4; main then: 0.748, 0.52)
    ("letter_g 1e-3", 0.85, 0.85, True),    # measured 0.995, 0.93 (main: no patch)
])
def test_noisy_letter_g_is_found_by_the_coarse_pass(name, coverage, recall, coarse):
    """Over the short window (0.05) the noisy cuts' curvature is mostly noise (at 1e-3: 16 of 16 245
    pairs matched, no patch kept); the coarse pass (0.08) matches the G again and one sweep grows
    over the whole mesh, its profile (nearly) the whole G, in the true profile planes. At 5e-4 the
    first pass covers it since the profile improvement leaves out the pieces of the knots off the
    profile (sweeps-members4: coverage 1.000 in one patch, fit error 4.7e-3): no coarse pass runs."""
    fx, r = _run(name)
    ran = any(s.name == "match" and s.numbers.get("curvature_window") == DEFAULT.coarse_window for s in r.stages)
    assert ran == coarse
    assert r.patches and all(p.kind == "general" for p in r.patches)
    assert all(p.fit_error <= PARAMS.fit_factor * PARAMS.eps_prox for p in r.patches)
    assert r.coverage >= coverage
    assert _recall(fx, r) >= recall
    best = max(r.patches, key=lambda p: p.coverage)
    assert _length(best.profile) >= 0.9 * fx.profile_length


@pytest.mark.parametrize("name, coverage, recall", [
    ("letter_g hole", 0.95, 0.95),        # measured 0.999, 1.00 (main: 0.915, 0.93)
    ("letter_g hole 5e-4", 0.85, 0.85),   # measured 0.997, 0.98 (main: 0.893, 0.90)
])
def test_holed_letter_g_is_one_sweep_across_the_hole(name, coverage, recall):
    """Re-slicing across the hole, the points over it found their closest cut points on another part
    of the G (its arc's end beside the bar, 0.06 away, not at a cut curve's end) and the profile
    carried that piece along the whole sweep (main: a jump of 0.061 between two profile samples, the
    arc's first 9 of 80 columns uncovered). Now such points keep the moved profile's place: one
    patch, its profile the whole G in one piece."""
    fx, r = _run(name)
    assert r.patches and all(p.fit_error <= PARAMS.fit_factor * PARAMS.eps_prox for p in r.patches)
    assert r.coverage >= coverage
    assert _recall(fx, r) >= recall
    best = max(r.patches, key=lambda p: p.coverage)
    assert best.coverage >= coverage
    steps = np.linalg.norm(np.diff(best.profile, axis=0), axis=1)
    assert steps.max() <= 3 * np.median(steps)                          # one piece: no jump
    assert _length(best.profile) >= 0.9 * fx.profile_length


def test_without_the_coarse_pass_the_noisiest_g_is_not_found():
    """The coarse pass is what finds it: with ``coarse_window = 0`` the same mesh gives no patch that
    covers the targets (main's result: none at all)."""
    _, r = _run("letter_g 1e-3", PARAMS.with_(coarse_window=0.0))
    assert not any(s.numbers.get("curvature_window") for s in r.stages)
    assert r.coverage < 0.85


@pytest.mark.parametrize("name, coverage, recall, angle", [
    ("arch 1e-3", 0.85, 0.85, 1.0),         # measured 0.974, 0.97 (main: 0.749, 0.00)
    ("arch hole", 0.95, 0.95, 1.0),         # measured 0.973, 0.97 (main: 0.941, 0.05 in 4 patches)
    ("arch hole 5e-4", 0.85, 0.85, 1.0),    # measured 0.973, 0.97 (main: 0.878, 0.03 in 3 patches)
    ("arch decimated", 0.95, 0.95, 1.0),    # measured 0.960-0.961, 0.97 (main: 0.796, 0.00)
])
def test_double_translational_variants_are_one_translation(name, coverage, recall, angle):
    """One patch of translations only, its profile (nearly) the whole moulding in a plane x = const:
    across the hole the parallel cuts' points over it count neither way, and the planes normal to
    the path's chord replace the general sweep's tilted one."""
    fx, r = _run(name)
    assert r.patches and all(p.fit_error <= PARAMS.fit_factor * PARAMS.eps_prox for p in r.patches)
    assert r.coverage >= coverage
    best = max(r.patches, key=lambda p: p.coverage)
    assert best.coverage >= coverage
    assert np.abs(best.motion.rotation - np.eye(3)).max() <= 1e-12          # translations only
    assert _length(best.profile) >= 0.9 * fx.profile_length
    # the truth: every profile plane is x = const
    assert np.allclose(fx.planes[:, :3], [1.0, 0.0, 0.0])
    o = best.profile.mean(axis=0)
    n = np.linalg.svd(best.profile - o)[2][2]
    assert np.degrees(np.arccos(min(1.0, abs(n[0])))) <= angle
    moved = o + best.motion.at(np.linspace(*best.motion.domain, 8 * len(best.motion)))[1]
    assert plane_recall(fx.planes, np.tile(n, (len(moved), 1)), moved @ n, 2.0, 0.005) >= recall
