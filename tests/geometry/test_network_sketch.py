"""The lifted-sketch piece: an exact 3D cubic Bezier (top view + Bernstein depths)."""

from __future__ import annotations

import numpy as np

from auszug.formats.network_json import dumps, exact_piece, loads
from auszug.geometry import CubicBezier, SymmetryGroup
from auszug.geometry.heights import SideCoordinate
from auszug.geometry.network import CurveNetwork, Piece

CTRL = np.array([[0.0, 0.0, 0.0], [1.0, 2.0, 0.5], [3.0, 2.0, -1.0], [4.0, 0.0, 0.25]])


def _piece(ctrl=CTRL):
    top = CubicBezier.from_array(ctrl[:, :2])
    p = Piece(0, 0, "sketch", top, None, SideCoordinate("u"), np.zeros((2, 3)), depth=ctrl[:, 2].copy())
    return p


def _bezier3(ctrl, t):
    t = np.asarray(t)[:, None]
    m = 1 - t
    return m**3 * ctrl[0] + 3 * m * m * t * ctrl[1] + 3 * m * t * t * ctrl[2] + t**3 * ctrl[3]


def test_point_t_is_the_3d_bezier():
    t = np.linspace(0, 1, 17)
    assert np.allclose(_piece().point_t(t), _bezier3(CTRL, t), rtol=0, atol=1e-14)


def test_tolerance_sampling_is_within_tolerance_of_the_3d_curve():
    net = CurveNetwork((_piece(),), (SymmetryGroup(1),), (0,), (0.0,))
    tol = 1e-5
    fine = net.resampled(tolerance=tol)
    pts = fine.pieces[0].points
    assert [n for n, _ in fine.features[0]] == ["start", "end"]
    dense = _bezier3(CTRL, np.linspace(0, 1, 20001))
    # every dense curve point lies within tol of the polyline
    a, b = pts[:-1], pts[1:]
    d = b - a
    s = np.clip(np.einsum("qsi,si->qs", dense[:, None] - a, d) / np.einsum("si,si->s", d, d), 0, 1)
    dist = np.linalg.norm(dense[:, None] - (a + s[..., None] * d), axis=-1).min(axis=1)
    assert dist.max() < tol
    assert not fine.pieces[0].is_straight()
    assert fine.pieces[0].circular_runs() == []


def test_network_json_round_trip_is_exact():
    net = CurveNetwork((_piece(),), (SymmetryGroup(1),), (0,), (0.0,)).resampled(samples=9)
    doc = loads(dumps(net, "s.svg"))
    rec = doc["curves"][0]
    assert rec["kind"] == "sketch" and rec["exact"]["depth"] == CTRL[:, 2].tolist()
    p = exact_piece(rec)
    t = np.linspace(0, 1, 33)
    assert np.array_equal(p.point_t(t), _piece().point_t(t))
    assert np.allclose(rec["points"], _piece().sample_uniform(9), rtol=0, atol=1e-12)
