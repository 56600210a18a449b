"""Profiles fitted with exact lines and arcs (auszug.sweeps.profilefit): the base moulding's known pieces."""

from __future__ import annotations

from dataclasses import replace
from functools import cache

import numpy as np
import pytest

from auszug.errors import GeometryError
from auszug.sweeps import DEFAULT, detect, fit_lines_arcs
from auszug.sweeps.fixtures import extruded, gothic_base_profile, revolved
from auszug.sweeps.patches import closest_distance
from auszug.sweeps.profilefit import polyline_hausdorff_2d

# The base moulding of auszug.sweeps.fixtures, written out independently: its 9 pieces, their joints
# and bulges, and the centres and radii of its three arcs (lower torus, scotia, upper torus).
KINDS = ("line", "line", "arc", "line", "arc", "line", "arc", "line", "line")
JOINTS = np.array([[0.30, 0.00], [0.30, 0.05], [0.24, 0.05], [0.24, 0.13], [0.22, 0.13], [0.20, 0.19],
                   [0.20, 0.22], [0.20, 0.27], [0.17, 0.27], [0.17, 0.34]])
BULGES = np.array([0, 0, 1.0, 0, -0.6, 0, 1.0, 0, 0])


def _arcs() -> list[tuple[np.ndarray, float]]:
    out = []
    for i in np.nonzero(BULGES)[0]:
        a, b, g = JOINTS[i], JOINTS[i + 1], BULGES[i]
        th = 4 * np.arctan(g)
        c = np.linalg.norm(b - a)
        r = c / (2 * abs(np.sin(th / 2)))
        left = np.array([-(b - a)[1], (b - a)[0]]) / c
        out.append(((a + b) / 2 + left * (c / 2) / np.tan(th / 2), r))
    return out


ARCS = _arcs()
RADII = np.array([r for _, r in ARCS])


def _chord_error(p: np.ndarray) -> float:
    """Largest sagitta of the polyline's chords on the three exact arcs: the Hausdorff distance of the
    exact profile to its samples (lines are sampled exactly)."""
    worst = 0.0
    for c, r in ARCS:
        on = np.abs(np.linalg.norm(p - c, axis=1) - r) < 1e-12
        both = on[:-1] & on[1:]
        chords = np.linalg.norm(np.diff(p, axis=0), axis=1)[both]
        if len(chords):
            worst = max(worst, float(np.max(r - np.sqrt(r * r - chords ** 2 / 4))))
    return worst


def test_known_radii_of_the_exact_arcs():
    assert RADII == pytest.approx([0.04, 0.06324555 / (2 * np.sin(2 * np.arctan(0.6))), 0.025], rel=1e-7)


@pytest.mark.parametrize("n", [40, 60, 100, 200])
def test_sampled_base_moulding_gives_back_its_exact_pieces(n):
    p, _ = gothic_base_profile(n)
    f = fit_lines_arcs(p, tolerance=1e-3)
    assert f is not None
    assert f.kinds == KINDS
    assert np.abs(f.radii - RADII).max() <= 1e-8
    assert np.abs(f.profile.points - JOINTS).max() <= 1e-8
    assert np.abs(f.profile.bulges - BULGES).max() <= 1e-7
    assert not f.profile.closed
    # the Hausdorff distance is exactly the polyline's own chord error on the arcs
    assert f.hausdorff == pytest.approx(_chord_error(p), rel=1e-3)   # the fit's sampling: 1e-3 of the tolerance


def test_fit_is_refused_beyond_the_tolerance():
    p, _ = gothic_base_profile(60)
    sag = _chord_error(p)
    assert fit_lines_arcs(p, tolerance=0.99 * sag) is None
    assert fit_lines_arcs(p, tolerance=1.01 * sag) is not None


def test_closed_rounded_rectangle():
    """Four lines and four quarter circles of radius 0.1, closed: 8 pieces, exact radii, G0 joints."""
    pts = []
    for (cx, cy), a0 in zip([(0.5, 0.2), (-0.5, 0.2), (-0.5, -0.2), (0.5, -0.2)], [0, 90, 180, 270], strict=True):
        u = np.radians(np.linspace(a0, a0 + 90, 9))
        pts.append(np.column_stack([cx + 0.1 * np.cos(u), cy + 0.1 * np.sin(u)]))
    # the straight sides sampled too (as a cut across a mesh is): 5 edges on each
    sides = []
    for k, arc in enumerate(pts):
        nxt = pts[(k + 1) % 4][0]
        sides.append(arc)
        sides.append(arc[-1] + np.linspace(0, 1, 6)[1:-1, None] * (nxt - arc[-1]))
    p = np.vstack(sides)
    f = fit_lines_arcs(p, closed=True, tolerance=1e-3)
    assert f is not None and f.profile.closed
    assert sorted(f.kinds) == ["arc"] * 4 + ["line"] * 4 and f.kinds.count("arc") == 4
    assert np.abs(f.radii - 0.1).max() <= 1e-9
    assert np.abs(np.abs(f.profile.bulges[f.profile.bulges != 0]) - np.tan(np.pi / 8)).max() <= 1e-7  # tangent joints
    assert f.profile.length == pytest.approx(2 * 1.0 + 2 * 0.4 + 2 * np.pi * 0.1, rel=1e-9)
    assert f.hausdorff == pytest.approx(0.1 * (1 - np.cos(np.radians(90 / 8 / 2))), rel=1e-3)


@pytest.mark.parametrize("bad", [np.zeros((1, 2)), np.zeros((5, 3)), np.array([[0, 0], [np.nan, 1.0]])])
def test_bad_polylines_are_refused(bad):
    with pytest.raises(GeometryError, match="profile fit needs"):
        fit_lines_arcs(bad)


def test_polyline_hausdorff_known_answer():
    assert polyline_hausdorff_2d([[0, 0], [1, 0]], [[0, 0.2], [0.5, 0.3], [1, 0.2]]) == pytest.approx(0.3)


@cache
def _detected(name: str, sigma: float):
    fx = {"extruded": extruded, "revolved": revolved}[name](sigma=sigma)
    return fx, detect((fx.vertices, fx.faces))


@pytest.mark.parametrize("name, sigma", [("extruded", 0.0), ("revolved", 0.0), ("extruded", 2e-4),
                                         ("revolved", 2e-4)])
def test_detected_moulding_profile_is_its_lines_and_arcs(name, sigma):
    """The patch found on the base moulding (normalised: lengths in bounding-box diameters) carries the
    fit: 6 lines and 3 arcs in the moulding's order, radii within 1e-3 of the truth."""
    fx, r = _detected(name, sigma)
    (p,) = r.patches
    fit = p.profile_fit
    assert fit is not None and fit.hausdorff <= DEFAULT.profile_fit_tolerance
    kinds = tuple("arc" if b else "line" for b in fit.profile.bulges)
    assert kinds in (KINDS, KINDS[::-1])
    scale = fx.profile_length / gothic_base_profile(60)[1][-1]   # the fixture's normalisation
    radii = [abs(np.linalg.norm(fit.profile.points[i + 1] - fit.profile.points[i])
                 * (1 + b * b) / (4 * abs(b))) for i, b in enumerate(fit.profile.bulges) if b]
    radii = radii if kinds == KINDS else radii[::-1]
    assert np.abs(np.array(radii) - scale * RADII).max() <= 1e-3
    # the vertices lie on the profile polyline's plane, the fit within its Hausdorff distance of it
    v = fit.vertices()
    assert np.abs((v - fit.origin) @ fit.axes[:, 2]).max() <= 1e-12
    assert np.allclose(fit.axes.T @ fit.axes, np.eye(3), atol=1e-12) and np.linalg.det(fit.axes) > 0


@pytest.mark.parametrize("name", ["extruded", "revolved"])
def test_fitted_moulding_sweeps_again_onto_the_mesh(name):
    """patch.sweep() with the exact profile re-meshes within (fit's Hausdorff + the patch's own fit
    error) of the input mesh; the polyline sweep stays as close as before."""
    fx, r = _detected(name, 0.0)
    (p,) = r.patches
    assert p.profile_fit is not None
    swept = p.sweep()
    assert swept.profile.has_arcs
    d, _ = closest_distance(swept.mesh(caps=False, tolerance=1e-6).vertices, fx.vertices, fx.faces)
    d0, _ = closest_distance(replace(p, profile_fit=None).sweep().mesh(caps=False).vertices, fx.vertices, fx.faces)
    assert d.max() <= p.profile_fit.hausdorff + d0.max() + 1e-6
    assert d.max() <= DEFAULT.profile_fit_tolerance + p.fit_error


def test_zero_tolerance_turns_the_fit_off():
    fx = extruded(n_profile=30, n_path=20)
    (p,) = detect((fx.vertices, fx.faces), params=DEFAULT.with_(profile_fit_tolerance=0.0)).patches
    assert p.profile_fit is None
