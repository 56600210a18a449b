"""Networks and exact-curve checks shared by the DXF and Rhino .3dm tests."""

from __future__ import annotations

import math
from dataclasses import replace
from functools import lru_cache

import numpy as np

from auszug import examples
from auszug.formats import load
from auszug.geometry import Arc, Line, SymmetryGroup
from auszug.geometry.heights import SideCoordinate
from auszug.geometry.network import CurveNetwork, NetworkCurve, Piece
from auszug.microarch import build

#: How far a run's end, evaluated on the piece, may lie from where its arc ends: at a
#: vertical tangent of the side view (a decoration's cusp) one ulp of the side-view
#: coordinate g moves the height by sqrt(2 r ulp(g)), up to ~1.5e-8 of the size.
RESOLUTION = 2e-8

#: Drawings with circular runs: mirrored groups (tn-5, u.xi.112, U.XI.34), groups without a
#: mirror (legacy tn-5, U.XI.27), straight posts and pillars (u.xi.112, U.XI.27), decorations
#: (tn-5), and ogees over arc top views, which have no exact form (U.XI.34).
CASES = ["teaching-sheet/tn-5.uc", "legacy/tn-5.uc", "web/u.xi.112.uc", "legacy/U.XI.27.uc", "web/U.XI.34.uc"]


@lru_cache(maxsize=None)
def network(name: str) -> CurveNetwork:
    """The drawing's curve network with its intersections, sampled to 1e-6 of its diagonal."""
    b = build(load(examples.path(name)))
    diag = b.to_curve_network().diagonal()
    return b.with_intersections().resampled(tolerance=1e-6 * diag)


def level_arcs() -> CurveNetwork:
    """A network of horizontal arcs (normal +z and -z), a level line and a post.

    Group 0 is C3 with a skew mirror about an off-origin centre, so mirrored
    replicas turn the other way round; group 1 is C2 without a mirror.
    """
    ccw = Arc((1.0, 0.5), 0.75, 0.3, 2.0)
    cw = Arc((-0.5, 1.0), 0.4, 1.0, -4.0)
    rule = SideCoordinate("arclength")

    def level(basic: int, seg: int, top, z: float) -> Piece:
        t = np.linspace(0.0, 1.0, 17)
        pts = np.concatenate([top.point(t), np.full((17, 1), z)], axis=1)
        return Piece(basic, seg, "level", top, None, rule, pts, z_const=z)

    post = Piece(1, -1, "post", None, None, rule, np.array([[2.0, 0.5, 0.0], [2.0, 0.5, 1.5]]))
    pieces = (level(0, 0, ccw, 0.8), level(0, 1, cw, 1.2), level(1, 0, Line((0.0, 0.0), (1.0, 2.0)), 0.5), post)
    groups = (SymmetryGroup(3, True, center=(0.5, -0.25), axis=(1.0, 2.0)), SymmetryGroup(2))
    net = CurveNetwork(pieces, groups, (0, 0), (0.0,), size=2.0, name="level-arcs")
    return net.resampled(samples=33)


def with_nan(net: CurveNetwork) -> CurveNetwork:
    """``net`` with one coordinate of its last piece not a number."""
    p = net.pieces[-1]
    pts = np.array(p.points)
    pts[len(pts) // 2, 2] = math.nan
    return replace(net, pieces=net.pieces[:-1] + (replace(p, points=pts),))


def mapped(net: CurveNetwork, c: NetworkCurve, pts: np.ndarray) -> np.ndarray:
    """Points of ``c``'s piece (piece coordinates) on the replica ``c``."""
    centre = np.asarray(net.groups[c.basic].center, dtype=float)
    xy = (pts[..., :2] - centre) @ np.asarray(c.transform).T + centre
    return np.concatenate([xy, pts[..., 2:]], axis=-1)


def distance_to_exact(net: CurveNetwork, c: NetworkCurve, t0: float, t1: float, q: np.ndarray) -> np.ndarray:
    """Distance of points ``q`` (k, 3) to the exact curve of ``c`` over top-view parameters [t0, t1].

    The range reaches a millionth of its length past either end: a run's end at
    a decoration's cusp, evaluated on the piece, is already on the next arc.

    The nearest of 4097 samples brackets each point's foot; golden-section
    search on the exact curve (``Piece.point_t``, mapped) refines it to float precision.
    """
    piece = net.pieces[c.piece]

    def at(t: np.ndarray) -> np.ndarray:
        return mapped(net, c, piece.point_t(t))

    lo_span, hi_span = piece.t_span()
    pad = 1e-6 * (t1 - t0)  # a joint where two circles cross may lie just outside [t0, t1] in float
    ts = np.unique(np.concatenate([[max(lo_span, t0 - pad)], np.linspace(t0, t1, 4097), [min(hi_span, t1 + pad)]]))
    grid = at(ts)
    i = np.argmin(np.linalg.norm(grid[None] - q[:, None], axis=2), axis=1)
    lo, hi = ts[np.clip(i - 1, 0, len(ts) - 1)], ts[np.clip(i + 1, 0, len(ts) - 1)]
    g = (math.sqrt(5.0) - 1.0) / 2.0
    for _ in range(80):
        a, b = hi - g * (hi - lo), lo + g * (hi - lo)
        fa = np.linalg.norm(at(a) - q, axis=1)
        fb = np.linalg.norm(at(b) - q, axis=1)
        left = fa < fb
        hi = np.where(left, b, hi)
        lo = np.where(left, lo, a)
    best = np.linalg.norm(at(0.5 * (lo + hi)) - q, axis=1)
    # near a vertical tangent of the side view one ulp of t moves the point ~1e-8: the
    # samples themselves (the ends t0, t1 exactly) may be nearer than any interior t
    return np.minimum(best, np.linalg.norm(grid[i] - q, axis=1))


def mapped_runs(net: CurveNetwork, c: NetworkCurve) -> list[dict[str, object]]:
    """The piece's circular runs on replica ``c``: centre, start, end mapped; the normal as an axial vector."""
    m3 = np.eye(3)
    m3[:2, :2] = c.transform
    det = np.linalg.det(m3)
    out = []
    for r in net.pieces[c.piece].circular_runs():
        out.append({"t0": r.t0, "t1": r.t1, "center": mapped(net, c, r.center), "start": mapped(net, c, r.start),
                    "end": mapped(net, c, r.end), "normal": det * (m3 @ r.normal), "radius": r.radius,
                    "angle": r.angle})
    return out
