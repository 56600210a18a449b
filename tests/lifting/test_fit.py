"""fit_polyline: least-squares G1 cubic chains through sampled curves, against known curves."""

from __future__ import annotations

import numpy as np
import pytest

from auszug.geometry import CubicBezier
from auszug.lifting.fit import fit_polyline


def _distances(chain: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Each point's true distance to the chain (closest point on any of its cubics)."""
    curves = [CubicBezier.from_array(c) for c in chain]
    return np.array([min(float(np.linalg.norm(b.point(b.project(p)) - p)) for b in curves) for p in points])


def _turns_deg(chain: np.ndarray) -> np.ndarray:
    """The tangent's turn (degrees) at each inner knot of a 2D chain."""
    a, b = chain[:-1, 3] - chain[:-1, 2], chain[1:, 1] - chain[1:, 0]
    cos = np.einsum("ij,ij->i", a, b) / (np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1))
    return np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))


@pytest.mark.parametrize("n, tol", [(41, 1e-2), (200, 1e-3), (200, 1e-4), (1000, 1e-5)])
def test_a_sampled_circle_arc_within_the_tolerance_g1_and_no_more_spans_than_needed(n, tol):
    t = np.linspace(0.2, 2.9, n)
    P = np.c_[3.0 + np.cos(t), -1.0 + np.sin(t)]
    c = fit_polyline(P, tol)
    assert c is not None and c.shape[1:] == (4, 2)
    spans = len(c)
    assert spans & (spans - 1) == 0                        # a power of two (spans doubled from 1)
    # the ends exactly, every vertex within tol (its true distance, not only at its own parameter)
    assert np.array_equal(c[0, 0], P[0]) and np.array_equal(c[-1, 3], P[-1])
    assert np.array_equal(c[1:, 0], c[:-1, 3])
    assert _distances(c, P).max() <= tol
    # G1 at every inner knot (C2 spline), so no corners where the drawing had none
    if spans > 1:
        assert _turns_deg(c).max() < 1e-6
    # the chain is the circle's to the tolerance plus the polyline's own chord error
    sag = 1.0 - np.cos((t[1] - t[0]) / 2)
    s = np.concatenate([CubicBezier.from_array(k).point(np.linspace(0, 1, 33)) for k in c])
    assert np.abs(np.linalg.norm(s - [3.0, -1.0], axis=1) - 1.0).max() <= tol + sag + 1e-12
    # half the spans do not reach the tolerance: the fit is no finer than it needs
    if spans > 1:
        assert fit_polyline(P, tol, max_spans=spans // 2) is None


def test_collinear_points_give_a_straight_chain():
    P = np.c_[np.linspace(0, 10, 30) ** 1.3, 0.5 * np.linspace(0, 10, 30) ** 1.3 + 2]
    c = fit_polyline(P, 1e-9)
    assert c is not None and len(c) == 1
    d = P[-1] - P[0]
    off = (c[0] - P[0]) @ np.array([-d[1], d[0]]) / np.linalg.norm(d)
    assert np.abs(off).max() < 1e-12


def test_a_space_curve_and_the_span_limit():
    t = np.linspace(0, 4 * np.pi, 400)
    P = np.c_[np.cos(t), np.sin(t), 0.1 * t]                  # two turns of a helix
    c = fit_polyline(P, 1e-3)
    assert c is not None and c.shape[1:] == (4, 3)
    # each vertex within 1e-3 of a dense sample of the chain (an upper bound of its distance to the chain)
    u = np.linspace(0, 1, 2001)[:, None]
    bern = np.hstack([(1 - u) ** 3, 3 * (1 - u) ** 2 * u, 3 * (1 - u) * u * u, u**3])
    dense = np.concatenate([bern @ k for k in c])
    assert max(float(np.linalg.norm(dense - q, axis=1).min()) for q in P) <= 1e-3
    assert fit_polyline(P, 1e-3, max_spans=2) is None         # two cubics cannot follow two turns


@pytest.mark.parametrize("points, words", [
    ([[0.0, 0.0]], "at least 2 points"),
    ([0.0, 1.0, 2.0], "at least 2 points"),
    ([[0.0, 0.0], [1.0, 1.0], [1.0, 1.0], [2.0, 0.0]], "coincide"),
])
def test_bad_polylines(points, words):
    with pytest.raises(ValueError, match=words):
        fit_polyline(points, 1e-3)
