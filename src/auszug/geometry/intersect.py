"""Intersections of planar curves: analytic for lines and arcs.

:func:`intersect` returns every point where two curves meet, as
:class:`Intersection` values carrying both curves' own parameters. Lines and
arcs are intersected in closed form with plain Python floats (for scalars this
is several times faster than numpy); :func:`intersect_many` adds a vectorised
bounding-box prefilter so that all pairs of a drawing's 30-60 curves take a
few milliseconds.

Conventions
-----------
* Points closer than ``TOL.intersect`` are one point: curves that come within
  that distance of each other meet there, and a parameter that overshoots
  [0, 1] by less than that distance is clamped. Hits of one meeting point
  (within ``2 TOL.intersect`` of each other, as each is known to ``TOL.intersect``)
  are merged into one.
* A tangency is one point. Where two curves overlap (collinear lines, arcs of
  one circle) the end points of the overlap are reported.
* A hit within ``TOL.intersect`` of a curve's end point gets that curve's
  parameter exactly 0.0 or 1.0, so curves meeting at end points report exact
  end parameters.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from auszug.geometry import _tolerance
from auszug.geometry.arc import Arc
from auszug.geometry.curve import Array, Curve
from auszug.geometry.line import Line

__all__ = ["Intersection", "intersect", "intersect_many"]

_TAU = 2.0 * math.pi


@dataclass(frozen=True, eq=False, slots=True)
class Intersection:
    """A point where two curves meet.

    Attributes
    ----------
    t1 : float
        Parameter of the point on the first curve, in [0, 1].
    t2 : float
        Parameter of the point on the second curve, in [0, 1].
    point : (2,) ndarray
        The point (drawing units); within ``TOL.intersect`` of both curves.
    """

    t1: float
    t2: float
    point: Array

    def swapped(self) -> Intersection:
        """The same intersection seen from the other curve (t1 and t2 exchanged).

        Examples
        --------
        >>> import numpy as np
        >>> Intersection(0.25, 0.5, np.zeros(2)).swapped().t1
        0.5
        """
        return Intersection(self.t2, self.t1, self.point)

    def __repr__(self) -> str:
        return f"Intersection(t1={self.t1!r}, t2={self.t2!r}, point={self.point.tolist()!r})"


# -- primitives: the curves as plain floats ----------------------------------------------
# Each primitive carries its end points and an axis-aligned bounding box, and knows how to
# (a) turn a point known to lie on its carrier into a parameter, with the range check, and
# (b) project an arbitrary point.


class _LinePrim:
    __slots__ = ("x0", "y0", "x1", "y1", "dx", "dy", "len", "box")

    def __init__(self, c: Line) -> None:
        self.x0, self.y0 = c.p0.tolist()
        self.x1, self.y1 = c.p1.tolist()
        self.dx = self.x1 - self.x0
        self.dy = self.y1 - self.y0
        self.len = c.length()
        self.box = (
            min(self.x0, self.x1),
            min(self.y0, self.y1),
            max(self.x0, self.x1),
            max(self.y0, self.y1),
        )

    def project(self, x: float, y: float) -> tuple[float, float]:
        """(distance, parameter) of the closest point of the segment."""
        t = ((x - self.x0) * self.dx + (y - self.y0) * self.dy) / (self.len * self.len)
        t = 0.0 if t < 0.0 else (1.0 if t > 1.0 else t)
        return math.hypot(self.x0 + t * self.dx - x, self.y0 + t * self.dy - y), t


class _ArcPrim:
    __slots__ = ("cx", "cy", "r", "th0", "sw", "sgn", "x0", "y0", "x1", "y1", "len", "box")

    def __init__(self, c: Arc) -> None:
        self.cx, self.cy = c.center.tolist()
        self.r = c.radius
        self.th0 = c.theta0
        self.sw = c.sweep
        self.sgn = 1.0 if c.sweep > 0 else -1.0
        r, th0, th1 = self.r, self.th0, self.th0 + self.sw
        self.x0 = self.cx + r * math.cos(th0)
        self.y0 = self.cy + r * math.sin(th0)
        self.x1 = self.cx + r * math.cos(th1)
        self.y1 = self.cy + r * math.sin(th1)
        self.len = r * abs(self.sw)
        self.box = _arc_box(self.cx, self.cy, r, th0, self.sw, self.x0, self.y0, self.x1, self.y1)

    def t_raw(self, x: float, y: float) -> float:
        """Parameter of the polar angle of (x, y); may fall outside [0, 1]."""
        d = ((math.atan2(y - self.cy, x - self.cx) - self.th0) * self.sgn) % _TAU
        a = abs(self.sw)
        t = d / a
        if t > 1.0:
            back = (_TAU - d) / a
            if back < t - 1.0:
                return -back
        return t

    def project(self, x: float, y: float) -> tuple[float, float]:
        """(distance, parameter) of the closest point of the arc."""
        rho = math.hypot(x - self.cx, y - self.cy)
        if rho > 0.0:
            t = self.t_raw(x, y)
            if 0.0 <= t <= 1.0:
                return abs(rho - self.r), t
        d0 = math.hypot(x - self.x0, y - self.y0)
        d1 = math.hypot(x - self.x1, y - self.y1)
        return (d0, 0.0) if d0 <= d1 else (d1, 1.0)


def _arc_box(
    cx: float, cy: float, r: float, th0: float, sw: float,
    x0: float, y0: float, x1: float, y1: float,
) -> tuple[float, float, float, float]:  # fmt: skip
    """Exact bounding box of an arc: its end points plus the axis extremes it sweeps over."""
    xmin, xmax = min(x0, x1), max(x0, x1)
    ymin, ymax = min(y0, y1), max(y0, y1)
    lo = min(th0, th0 + sw)
    span = abs(sw)
    # quarter angles k * pi/2 within [lo, lo + span]
    k = math.ceil(lo / (0.5 * math.pi))
    while k * 0.5 * math.pi <= lo + span:
        q = k % 4
        if q == 0:
            xmax = cx + r
        elif q == 1:
            ymax = cy + r
        elif q == 2:
            xmin = cx - r
        else:
            ymin = cy - r
        k += 1
    return xmin, ymin, xmax, ymax


# Curves are immutable, so their float form is memoised per object (weakly: the cache
# never keeps a curve alive). This halves the cost of intersecting a pair.
_PRIMS: weakref.WeakKeyDictionary[Curve, _LinePrim | _ArcPrim] = weakref.WeakKeyDictionary()


def _prim(c: Curve) -> _LinePrim | _ArcPrim:
    try:
        return _PRIMS[c]
    except (KeyError, TypeError):
        pass
    if isinstance(c, Line):
        p: _LinePrim | _ArcPrim = _LinePrim(c)
    elif isinstance(c, Arc):
        p = _ArcPrim(c)
    else:
        raise TypeError(f"intersect supports Line and Arc curves, got {type(c).__name__}")
    _PRIMS[c] = p
    return p


# -- analytic kernels -------------------------------------------------------------------
# Each appends raw hits (t1, t2, x, y) with parameters already range-checked and clamped.

_Hit = tuple[float, float, float, float]


def _clamp_t(t: float, tol_t: float) -> float | None:
    if t < 0.0:
        return 0.0 if t >= -tol_t else None
    if t > 1.0:
        return 1.0 if t <= 1.0 + tol_t else None
    return t


def _line_line(a: _LinePrim, b: _LinePrim, tol: float, out: list[_Hit]) -> None:
    den = a.dx * b.dy - a.dy * b.dx
    qx, qy = b.x0 - a.x0, b.y0 - a.y0
    if abs(den) <= _tolerance.TOL.collinear * a.len * b.len:
        # parallel: if the carriers coincide the lines overlap, and the overlap's end
        # points are found by the end-point checks; otherwise the lines are disjoint
        # unless they cross far away, which the general formula below still handles.
        d0 = abs(qx * a.dy - qy * a.dx) / a.len
        ex, ey = b.x1 - a.x0, b.y1 - a.y0
        d1 = abs(ex * a.dy - ey * a.dx) / a.len
        if (d0 <= tol and d1 <= tol) or den == 0.0:
            return
    t = (qx * b.dy - qy * b.dx) / den
    s = (qx * a.dy - qy * a.dx) / den
    t = _clamp_t(t, tol / a.len)
    if t is None:
        return
    s = _clamp_t(s, tol / b.len)
    if s is None:
        return
    out.append((t, s, a.x0 + t * a.dx, a.y0 + t * a.dy))


def _line_arc(a: _LinePrim, b: _ArcPrim, tol: float, out: list[_Hit], swap: bool) -> None:
    L = a.len
    ux, uy = a.dx / L, a.dy / L
    wx, wy = b.cx - a.x0, b.cy - a.y0
    foot = wx * ux + wy * uy  # arc length along the line to the foot of the centre
    h = wx * uy - wy * ux  # signed distance of the centre from the line
    gap = abs(h) - b.r
    if gap > tol:
        return
    if gap >= -tol:  # tangent: one point, the foot
        cands = (foot,)
    else:
        w = math.sqrt((b.r - h) * (b.r + h))
        cands = (foot - w, foot + w)
    tol_a = tol / L
    tol_b = tol / b.len
    for s in cands:
        t = _clamp_t(s / L, tol_a)
        if t is None:
            continue
        x, y = a.x0 + t * a.dx, a.y0 + t * a.dy
        tb = _clamp_t(b.t_raw(x, y), tol_b)
        if tb is None:
            continue
        out.append((tb, t, x, y) if swap else (t, tb, x, y))


def _arc_arc(a: _ArcPrim, b: _ArcPrim, tol: float, out: list[_Hit]) -> None:
    ex, ey = b.cx - a.cx, b.cy - a.cy
    d = math.hypot(ex, ey)
    if d <= tol and abs(a.r - b.r) <= tol:
        return  # one circle: the overlap's end points come from the end-point checks
    ext = d - (a.r + b.r)
    inn = d - abs(a.r - b.r)
    if ext > tol or inn < -tol:
        return
    ux, uy = ex / d, ey / d
    if abs(ext) <= tol or abs(inn) <= tol:  # tangent: one point on the line of centres
        along = (d * d + a.r * a.r - b.r * b.r) / (2.0 * d)
        s = a.r if along >= 0.0 else -a.r
        pts = ((a.cx + s * ux, a.cy + s * uy),)
    else:
        along = (d * d + a.r * a.r - b.r * b.r) / (2.0 * d)
        h = math.sqrt(max(a.r * a.r - along * along, 0.0))
        mx, my = a.cx + along * ux, a.cy + along * uy
        pts = ((mx - h * uy, my + h * ux), (mx + h * uy, my - h * ux))
    tol_a = tol / a.len
    tol_b = tol / b.len
    for x, y in pts:
        ta = _clamp_t(a.t_raw(x, y), tol_a)
        if ta is None:
            continue
        tb = _clamp_t(b.t_raw(x, y), tol_b)
        if tb is None:
            continue
        out.append((ta, tb, x, y))


def _endpoint_hits(a, b, tol: float, out: list[_Hit], swap: bool) -> None:  # noqa: ANN001
    """End points of ``a`` lying on ``b`` (this also finds the ends of overlaps)."""
    for ta, x, y in ((0.0, a.x0, a.y0), (1.0, a.x1, a.y1)):
        dist, tb = b.project(x, y)
        if dist <= tol:
            out.append((tb, ta, x, y) if swap else (ta, tb, x, y))


def _finish(hits: list[_Hit], a, b, tol: float) -> list[Intersection]:  # noqa: ANN001
    """Snap to end points, merge duplicates, sort by t1."""
    snapped: list[_Hit] = []
    for t1, t2, x, y in hits:
        if t1 != 0.0 and t1 != 1.0:
            if math.hypot(x - a.x0, y - a.y0) <= tol:
                t1, x, y = 0.0, a.x0, a.y0
            elif math.hypot(x - a.x1, y - a.y1) <= tol:
                t1, x, y = 1.0, a.x1, a.y1
        if t2 != 0.0 and t2 != 1.0:
            if math.hypot(x - b.x0, y - b.y0) <= tol:
                t2 = 0.0
            elif math.hypot(x - b.x1, y - b.y1) <= tol:
                t2 = 1.0
        snapped.append((t1 + 0.0, t2 + 0.0, x, y))  # + 0.0 turns -0.0 into 0.0
    # Each hit is known to within tol, so two hits of one meeting point can be up to
    # 2 tol apart (e.g. an end point within tol of the other curve, and the exact
    # crossing next to it). Of such duplicates keep the one with the most exact end
    # parameters, then the smallest t1.
    snapped.sort(key=lambda h: (-((h[0] in (0.0, 1.0)) + (h[1] in (0.0, 1.0))), h[0], h[1]))
    kept: list[_Hit] = []
    for h in snapped:
        for k in kept:
            if math.hypot(h[2] - k[2], h[3] - k[3]) <= 2.0 * tol:
                break
        else:
            kept.append(h)
    kept.sort()
    return [Intersection(t1, t2, np.array((x, y))) for t1, t2, x, y in kept]


def _boxes_apart(a, b, tol: float) -> bool:  # noqa: ANN001
    ba, bb = a.box, b.box
    return ba[0] > bb[2] + tol or bb[0] > ba[2] + tol or ba[1] > bb[3] + tol or bb[1] > ba[3] + tol


def _intersect_prims(a, b) -> list[Intersection]:  # noqa: ANN001
    tol = _tolerance.TOL.intersect
    if _boxes_apart(a, b, tol):
        return []
    hits: list[_Hit] = []
    la, lb = type(a) is _LinePrim, type(b) is _LinePrim
    if la and lb:
        _line_line(a, b, tol, hits)
    elif la:
        _line_arc(a, b, tol, hits, swap=False)
    elif lb:
        _line_arc(b, a, tol, hits, swap=True)
    else:
        _arc_arc(a, b, tol, hits)
    _endpoint_hits(a, b, tol, hits, swap=False)
    _endpoint_hits(b, a, tol, hits, swap=True)
    if not hits:
        return []
    return _finish(hits, a, b, tol)


# -- public -----------------------------------------------------------------------------


def intersect(c1: Curve, c2: Curve) -> list[Intersection]:
    """All points where two curves meet.

    Parameters
    ----------
    c1, c2 : Line or Arc
        The curves.

    Returns
    -------
    list of Intersection
        Sorted by ``t1``; points within ``TOL.intersect`` merged. A tangency is
        one point; an overlap (collinear lines, arcs of one circle) is reported
        by its end points. Empty when the curves do not meet.

    Raises
    ------
    TypeError
        For curve types without an intersection routine.

    Examples
    --------
    >>> import math
    >>> from auszug.geometry import Arc, Line, intersect
    >>> [(h.t1, h.t2) for h in intersect(Line((0, 0), (2, 2)), Line((0, 2), (2, 0)))]
    [(0.5, 0.5)]
    >>> hits = intersect(Line((-2, 0), (2, 0)), Arc((0, 0), 1.0, 0.0, math.pi))
    >>> [(h.t1, h.t2) for h in hits]
    [(0.25, 1.0), (0.75, 0.0)]
    >>> [h.t2 for h in intersect(Line((0, 1), (1, 1)), Arc((0, 0), 1.0, 0.0, 3.0))]
    [0.5235987755982988]
    """
    return _intersect_prims(_prim(c1), _prim(c2))


def intersect_many(
    curves_a: Sequence[Curve], curves_b: Sequence[Curve] | None = None
) -> dict[tuple[int, int], list[Intersection]]:
    """Intersections of many curve pairs, with a vectorised bounding-box prefilter.

    Parameters
    ----------
    curves_a : sequence of Curve, length n
    curves_b : sequence of Curve, length m, optional
        If given, every pair ``(curves_a[i], curves_b[j])`` is intersected;
        otherwise every pair ``(curves_a[i], curves_a[j])`` with ``i < j``.

    Returns
    -------
    dict of (int, int) to list of Intersection
        ``{(i, j): intersect(curves_a[i], curves_b[j])}`` for the pairs that
        meet; pairs that do not meet are absent.

    Examples
    --------
    >>> from auszug.geometry import Line, intersect_many
    >>> star = [Line((-1, 0), (1, 0)), Line((0, -1), (0, 1)), Line((-1, -1), (1, 1))]
    >>> sorted(intersect_many(star))
    [(0, 1), (0, 2), (1, 2)]
    >>> intersect_many(star, [Line((5, 5), (6, 6))])
    {}
    """
    pa = [_prim(c) for c in curves_a]
    pb = pa if curves_b is None else [_prim(c) for c in curves_b]
    if not pa or not pb:
        return {}
    tol = _tolerance.TOL.intersect
    ba = np.array([p.box for p in pa])
    bb = ba if curves_b is None else np.array([p.box for p in pb])
    near = (
        (ba[:, None, 0] <= bb[None, :, 2] + tol)
        & (bb[None, :, 0] <= ba[:, None, 2] + tol)
        & (ba[:, None, 1] <= bb[None, :, 3] + tol)
        & (bb[None, :, 1] <= ba[:, None, 3] + tol)
    )
    if curves_b is None:
        near = np.triu(near, k=1)
    out: dict[tuple[int, int], list[Intersection]] = {}
    for i, j in zip(*(ix.tolist() for ix in np.nonzero(near))):
        hits = _intersect_prims(pa[i], pb[j])
        if hits:
            out[(i, j)] = hits
    return out
