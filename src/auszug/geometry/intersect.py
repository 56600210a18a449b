"""Intersections of planar curves: analytic for lines and arcs, subdivision for Beziers.

:func:`intersect` returns every point where two curves meet, as
:class:`Intersection` values carrying both curves' own parameters. Lines and
arcs are intersected in closed form with plain Python floats (for scalars this
is several times faster than numpy); :func:`intersect_many` adds a vectorised
bounding-box prefilter so that all pairs of a drawing's 30-60 curves take a
few milliseconds. Pairs involving a :class:`~auszug.geometry.CubicBezier` are
intersected by bounding-box subdivision down to flat pieces, then Newton's
method on both curves to ``TOL.intersect`` (slower: a fraction of a
millisecond per pair).

Conventions
-----------
* Points closer than ``TOL.intersect`` are one point: curves that come within
  that distance of each other meet there, and a parameter that overshoots
  [0, 1] by less than that distance is clamped. Hits of one meeting point
  (within ``2 TOL.intersect`` of each other, as each is known to ``TOL.intersect``)
  are merged into one, unless they lie on different branches of a curve through
  a double point (a Bezier loop): those are different parameters, and both kept.
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
from auszug.geometry.bezier import CubicBezier
from auszug.geometry.curve import Array, Curve
from auszug.geometry.line import Line

__all__ = ["Intersection", "intersect", "intersect_many", "Prepared", "prepare", "intersect_prepared"]

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
    __slots__ = ("x0", "y0", "x1", "y1", "dx", "dy", "len", "box", "root")

    def __init__(self, c: Line) -> None:
        self.x0, self.y0 = c.p0.tolist()
        self.x1, self.y1 = c.p1.tolist()
        self.dx = self.x1 - self.x0
        self.dy = self.y1 - self.y0
        self.len = c.length()
        self.root: _Piece | None = None
        self.box = (
            min(self.x0, self.x1),
            min(self.y0, self.y1),
            max(self.x0, self.x1),
            max(self.y0, self.y1),
        )

    def ev(self, t: float) -> tuple[float, float, float, float]:
        """(x, y, dx/dt, dy/dt) at ``t``."""
        return self.x0 + t * self.dx, self.y0 + t * self.dy, self.dx, self.dy

    def piece(self, t0: float, t1: float) -> _Piece:
        xa, ya = self.x0 + t0 * self.dx, self.y0 + t0 * self.dy
        xb, yb = self.x0 + t1 * self.dx, self.y0 + t1 * self.dy
        box = (min(xa, xb), min(ya, yb), max(xa, xb), max(ya, yb))
        return _Piece(t0, t1, box, 0.0, (xa, ya, xb, yb), None)

    def project(self, x: float, y: float) -> tuple[float, float]:
        """(distance, parameter) of the closest point of the segment."""
        t = ((x - self.x0) * self.dx + (y - self.y0) * self.dy) / (self.len * self.len)
        t = 0.0 if t < 0.0 else (1.0 if t > 1.0 else t)
        return math.hypot(self.x0 + t * self.dx - x, self.y0 + t * self.dy - y), t


class _ArcPrim:
    __slots__ = ("cx", "cy", "r", "th0", "sw", "sgn", "x0", "y0", "x1", "y1", "len", "box", "root")

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
        self.root: _Piece | None = None
        self.box = _arc_box(self.cx, self.cy, r, th0, self.sw, self.x0, self.y0, self.x1, self.y1)

    def ev(self, t: float) -> tuple[float, float, float, float]:
        """(x, y, dx/dt, dy/dt) at ``t``."""
        a = self.th0 + t * self.sw
        c, s = math.cos(a), math.sin(a)
        rs = self.r * self.sw
        return self.cx + self.r * c, self.cy + self.r * s, -rs * s, rs * c

    def piece(self, t0: float, t1: float) -> _Piece:
        a0, sw = self.th0 + t0 * self.sw, (t1 - t0) * self.sw
        r = self.r
        xa, ya = self.cx + r * math.cos(a0), self.cy + r * math.sin(a0)
        xb, yb = self.cx + r * math.cos(a0 + sw), self.cy + r * math.sin(a0 + sw)
        box = _arc_box(self.cx, self.cy, r, a0, sw, xa, ya, xb, yb)
        dev = r * (1.0 - math.cos(0.5 * sw))  # farthest distance from the chord line
        return _Piece(t0, t1, box, dev, (xa, ya, xb, yb), None)

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


class _Piece:
    """A parameter interval [t0, t1] of a curve, for subdivision.

    ``box`` bounds the piece, ``dev`` bounds its distance from the ``chord``
    (x0, y0, x1, y1); ``ctrl`` holds a Bezier piece's 8 control coordinates.
    """

    __slots__ = ("t0", "t1", "box", "dev", "chord", "ctrl", "kids", "ln", "nx", "ny")

    def __init__(self, t0: float, t1: float, box: _Box, dev: float,
                 chord: tuple[float, float, float, float], ctrl: tuple[float, ...] | None):
        self.t0, self.t1, self.box, self.dev, self.chord, self.ctrl = t0, t1, box, dev, chord, ctrl
        self.kids: tuple[_Piece, _Piece] | None = None  # the halves, once computed
        # the chord's length and unit left normal (0, 0 for a point), used by every test
        # of the piece against another: computed once per piece
        x0, y0, x1, y1 = chord
        self.ln = ln = math.hypot(x1 - x0, y1 - y0)
        if ln > 0.0:
            self.nx, self.ny = (y0 - y1) / ln, (x1 - x0) / ln
        else:
            self.nx = self.ny = 0.0


_Box = tuple[float, float, float, float]


def _bez_piece(t0: float, t1: float, c: tuple[float, ...]) -> _Piece:
    x0, y0, x1, y1, x2, y2, x3, y3 = c
    box = (min(x0, x1, x2, x3), min(y0, y1, y2, y3), max(x0, x1, x2, x3), max(y0, y1, y2, y3))
    ex, ey = x3 - x0, y3 - y0
    el = math.hypot(ex, ey)
    if el > 0.0:
        dev = max(abs((x1 - x0) * ey - (y1 - y0) * ex), abs((x2 - x0) * ey - (y2 - y0) * ex)) / el
        # handles beyond the chord's ends fold the piece back: not flat either
        along1 = ((x1 - x0) * ex + (y1 - y0) * ey) / el
        along2 = ((x2 - x0) * ex + (y2 - y0) * ey) / el
        dev = max(dev, -along1, along1 - el, -along2, along2 - el)
    else:
        dev = max(math.hypot(x1 - x0, y1 - y0), math.hypot(x2 - x0, y2 - y0))
    return _Piece(t0, t1, box, dev, (x0, y0, x3, y3), c)


def _bez_halves(p: _Piece) -> tuple[_Piece, _Piece]:
    assert p.ctrl is not None  # a Bezier piece
    x0, y0, x1, y1, x2, y2, x3, y3 = p.ctrl
    ax, ay = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
    bx, by = 0.5 * (x1 + x2), 0.5 * (y1 + y2)
    cx, cy = 0.5 * (x2 + x3), 0.5 * (y2 + y3)
    dx, dy = 0.5 * (ax + bx), 0.5 * (ay + by)
    ex, ey = 0.5 * (bx + cx), 0.5 * (by + cy)
    mx, my = 0.5 * (dx + ex), 0.5 * (dy + ey)
    tm = 0.5 * (p.t0 + p.t1)
    return (_bez_piece(p.t0, tm, (x0, y0, ax, ay, dx, dy, mx, my)),
            _bez_piece(tm, p.t1, (mx, my, ex, ey, cx, cy, x3, y3)))


class _BezPrim:
    __slots__ = ("curve", "c", "x0", "y0", "x1", "y1", "box", "root", "__weakref__")

    def __init__(self, c: CubicBezier) -> None:
        self.curve = c
        self.c = tuple(c.controls.ravel().tolist())
        self.x0, self.y0 = self.c[0], self.c[1]
        self.x1, self.y1 = self.c[6], self.c[7]
        xs, ys = self.c[0::2], self.c[1::2]
        self.box = (min(xs), min(ys), max(xs), max(ys))
        self.root: _Piece | None = None

    def _maybe_near(self, x: float, y: float, tol: float) -> bool:
        """False when the point is certainly farther than ``tol`` from the curve.

        Every flat piece of the (memoised) subdivision tree is excluded by its box or strip.
        """
        stack = [_root(self)]
        while stack:
            p = stack.pop()
            b = p.box
            if x < b[0] - tol or x > b[2] + tol or y < b[1] - tol or y > b[3] + tol:
                continue
            x0, y0, x1, y1 = p.chord
            ln = p.ln
            if ln > 0.0 and abs((x - x0) * (y0 - y1) + (y - y0) * (x1 - x0)) / ln > p.dev + tol:
                continue
            if _is_flat(p, tol) or p.t1 - p.t0 < 1e-6:
                return True
            stack.extend(_split(self, p))
        return False

    def ev(self, t: float) -> tuple[float, float, float, float]:
        """(x, y, dx/dt, dy/dt) at ``t``."""
        x0, y0, x1, y1, x2, y2, x3, y3 = self.c
        m = 1.0 - t
        b0, b1, b2, b3 = m * m * m, 3.0 * m * m * t, 3.0 * m * t * t, t * t * t
        d0, d1, d2 = 3.0 * m * m, 6.0 * m * t, 3.0 * t * t
        return (
            b0 * x0 + b1 * x1 + b2 * x2 + b3 * x3,
            b0 * y0 + b1 * y1 + b2 * y2 + b3 * y3,
            d0 * (x1 - x0) + d1 * (x2 - x1) + d2 * (x3 - x2),
            d0 * (y1 - y0) + d1 * (y2 - y1) + d2 * (y3 - y2),
        )

    def piece(self, t0: float, t1: float) -> _Piece:
        if t0 == 0.0 and t1 == 1.0:
            return _bez_piece(0.0, 1.0, self.c)
        c = self.curve.segment(t0, t1).controls.ravel().tolist()
        return _bez_piece(t0, t1, tuple(c))

    def project(self, x: float, y: float) -> tuple[float, float]:
        """(distance, parameter) of the closest point of the curve.

        When the point is farther than ``TOL.intersect`` from the curve, as the
        subdivision tree shows cheaply, only a distance above that (inf) and
        parameter 0: callers only ask whether a point lies on the curve.
        """
        # an end point itself (curves of a network share end points): its exact parameter
        if x == self.x0 and y == self.y0:
            return 0.0, 0.0
        if x == self.x1 and y == self.y1:
            return 0.0, 1.0
        if not self._maybe_near(x, y, _tolerance.TOL.intersect):
            return math.inf, 0.0
        t = self.curve.project((x, y))
        px, py, _, _ = self.ev(t)
        return math.hypot(px - x, py - y), t


# Curves are immutable, so their float form is memoised per object (weakly: the cache
# never keeps a curve alive). This halves the cost of intersecting a pair.
Prepared = _LinePrim | _ArcPrim | _BezPrim
_PRIMS: weakref.WeakKeyDictionary[Curve, Prepared] = weakref.WeakKeyDictionary()


def prepare(c: Curve) -> Prepared:
    """The float form of a curve that :func:`intersect_prepared` works on, memoised per curve.

    Its ``x0, y0, x1, y1`` are the end points; callers that intersect one curve with
    many (offsets, PRC search) prepare it once.
    """
    try:
        return _PRIMS[c]
    except (KeyError, TypeError):
        pass
    if isinstance(c, Line):
        p: Prepared = _LinePrim(c)
    elif isinstance(c, Arc):
        p = _ArcPrim(c)
    elif isinstance(c, CubicBezier):
        p = _BezPrim(c)
    else:
        raise TypeError(
            f"intersect supports Line, Arc and CubicBezier curves, got {type(c).__name__}"
        )
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


def _endpoint_hits(a, b, tol: float, out: list[_Hit], swap: bool) -> None:
    """End points of ``a`` lying on ``b`` (this also finds the ends of overlaps)."""
    bx0, by0, bx1, by1 = b.box
    for ta, x, y in ((0.0, a.x0, a.y0), (1.0, a.x1, a.y1)):
        if x < bx0 - tol or x > bx1 + tol or y < by0 - tol or y > by1 + tol:
            continue
        dist, tb = b.project(x, y)
        if dist <= tol:
            out.append((tb, ta, x, y) if swap else (ta, tb, x, y))


def _same_place(p, s: float, t: float, tol: float) -> bool:
    """Whether parameters ``s`` and ``t`` of one point are one place of the curve ``p``.

    Not two branches through a double point (a Bezier loop): the curve between them
    stays put. The ends of a closed curve are one place.
    """
    if s == t:
        return True
    if s + t == 1.0 and s * t == 0.0:
        return math.hypot(p.x0 - p.x1, p.y0 - p.y1) <= tol
    xm, ym, _, _ = p.ev(0.5 * (s + t))
    xs, ys, _, _ = p.ev(s)
    return math.hypot(xm - xs, ym - ys) <= 2.0 * tol


def _finish(hits: list[_Hit], a, b, tol: float) -> list[Intersection]:
    """Snap to end points, merge duplicates, sort by t1."""
    snapped: list[_Hit] = []
    closed_a = math.hypot(a.x0 - a.x1, a.y0 - a.y1) <= tol
    closed_b = math.hypot(b.x0 - b.x1, b.y0 - b.y1) <= tol
    for t1, t2, x, y in hits:
        if closed_a and t1 == 1.0:  # the ends of a closed curve: report its start
            t1, x, y = 0.0, a.x0, a.y0
        if closed_b and t2 == 1.0:
            t2 = 0.0
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
            if (
                math.hypot(h[2] - k[2], h[3] - k[3]) <= 2.0 * tol
                and _same_place(a, h[0], k[0], tol)
                and _same_place(b, h[1], k[1], tol)
            ):
                break
        else:
            kept.append(h)
    kept.sort()
    return [Intersection(t1, t2, np.array((x, y))) for t1, t2, x, y in kept]


def _boxes_apart(a, b, tol: float) -> bool:
    ba, bb = a.box, b.box
    return ba[0] > bb[2] + tol or bb[0] > ba[2] + tol or ba[1] > bb[3] + tol or bb[1] > ba[3] + tol


def intersect_prepared(a: Prepared, b: Prepared) -> list[Intersection]:
    """Intersections of two prepared curves: :func:`intersect` without the preparation."""
    tol = _tolerance.TOL.intersect
    if _boxes_apart(a, b, tol):
        return []
    if isinstance(a, _BezPrim) or isinstance(b, _BezPrim):
        return _finish(_subdivision_hits(a, b, tol), a, b, tol)
    hits: list[_Hit] = []
    if isinstance(a, _LinePrim):
        if isinstance(b, _LinePrim):
            _line_line(a, b, tol, hits)
        else:
            _line_arc(a, b, tol, hits, swap=False)
    elif isinstance(b, _LinePrim):
        _line_arc(b, a, tol, hits, swap=True)
    else:
        _arc_arc(a, b, tol, hits)
    _endpoint_hits(a, b, tol, hits, swap=False)
    _endpoint_hits(b, a, tol, hits, swap=True)
    if not hits:
        return []
    return _finish(hits, a, b, tol)


# -- subdivision + Newton (any pair involving a Bezier) ----------------------------------

_FLAT = 0.02  # a piece is flat when it deviates from its chord by < 2 % of the chord
_MAX_DEPTH = 48
_NEWTON_STEPS = 60
_NEWTON_DONE = 1e-15  # residual (drawing units) at which Newton stops early


def _newton(a, b, s: float, t: float) -> tuple[float, float, float, float, float]:
    """Refine a meeting point of ``a`` at ``s`` and ``b`` at ``t``.

    Levenberg-Marquardt on A(s) - B(t) = 0 with a tiny damping, i.e. Newton's
    method where the 2x2 Jacobian is regular and a least-squares descent to the
    closest approach at a tangency (where it is singular). Parameters stay in
    [0, 1]. Returns (s, t, x, y, residual).
    """
    res = math.inf
    for _ in range(_NEWTON_STEPS):
        xa, ya, ax, ay = a.ev(s)
        xb, yb, bx, by = b.ev(t)
        fx, fy = xa - xb, ya - yb
        res = math.hypot(fx, fy)
        if res <= _NEWTON_DONE:
            break
        # normal equations of J = [A' | -B']: (J^T J + mu I) delta = J^T f
        paa, pbb, pab = ax * ax + ay * ay, bx * bx + by * by, -(ax * bx + ay * by)
        mu = 1e-14 * (paa + pbb) + 1e-300
        ga, gb = ax * fx + ay * fy, -(bx * fx + by * fy)
        det = (paa + mu) * (pbb + mu) - pab * pab
        if not det > 0.0:  # both derivatives vanish (handles on end points): step inwards
            s = s + 1e-6 if s < 0.5 else s - 1e-6
            t = t + 1e-6 if t < 0.5 else t - 1e-6
            continue
        ds = ((pbb + mu) * ga - pab * gb) / det
        dt = ((paa + mu) * gb - pab * ga) / det
        sn = min(max(s - ds, 0.0), 1.0)
        tn = min(max(t - dt, 0.0), 1.0)
        if abs(sn - s) + abs(tn - t) <= 1e-16:
            break
        s, t = sn, tn
    xa, ya, _, _ = a.ev(s)
    xb, yb, _, _ = b.ev(t)
    return s, t, xa, ya, math.hypot(xa - xb, ya - yb)


def _chord_guess(pa: _Piece, pb: _Piece) -> tuple[float, float]:
    """Parameters where the two pieces' chords cross (clamped), else the midpoints."""
    ax0, ay0, ax1, ay1 = pa.chord
    bx0, by0, bx1, by1 = pb.chord
    dx, dy, ex, ey = ax1 - ax0, ay1 - ay0, bx1 - bx0, by1 - by0
    den = dx * ey - dy * ex
    u = v = 0.5
    if den != 0.0:
        qx, qy = bx0 - ax0, by0 - ay0
        u = min(max((qx * ey - qy * ex) / den, 0.0), 1.0)
        v = min(max((qx * dy - qy * dx) / den, 0.0), 1.0)
    return pa.t0 + u * (pa.t1 - pa.t0), pb.t0 + v * (pb.t1 - pb.t0)


def _split(prim, p: _Piece) -> tuple[_Piece, _Piece]:
    """The two halves of a piece, memoised.

    A curve's subdivision tree is shared by all the pairs it takes part in.
    """
    if p.kids is None:
        if p.ctrl is not None:
            p.kids = _bez_halves(p)
        else:
            tm = 0.5 * (p.t0 + p.t1)
            p.kids = (prim.piece(p.t0, tm), prim.piece(tm, p.t1))
    return p.kids


def _root(prim) -> _Piece:
    """The whole curve as a piece, memoised on the primitive."""
    if prim.root is None:
        prim.root = prim.piece(0.0, 1.0)
    return prim.root


def _fat_apart(pa: _Piece, pb: _Piece, tol: float) -> bool:
    """Whether ``pb`` lies wholly on one side of the strip around the chord line of ``pa``.

    The strip has half-width ``pa.dev`` and contains ``pa``: then the pieces cannot meet.
    """
    if pa.ln == 0.0:
        return False
    x0, y0, _, _ = pa.chord
    nx, ny = pa.nx, pa.ny
    if pb.ctrl is not None:
        c0, c1, c2, c3, c4, c5, c6, c7 = pb.ctrl
        d0, d1 = (c0 - x0) * nx + (c1 - y0) * ny, (c2 - x0) * nx + (c3 - y0) * ny
        d2, d3 = (c4 - x0) * nx + (c5 - y0) * ny, (c6 - x0) * nx + (c7 - y0) * ny
        margin = pa.dev + tol
        return min(d0, d1, d2, d3) > margin or max(d0, d1, d2, d3) < -margin
    bx0, by0, bx1, by1 = pb.chord
    e0, e1 = (bx0 - x0) * nx + (by0 - y0) * ny, (bx1 - x0) * nx + (by1 - y0) * ny
    margin = pa.dev + pb.dev + tol
    return min(e0, e1) > margin or max(e0, e1) < -margin


def _is_flat(p: _Piece, tol: float) -> bool:
    return p.dev <= max(_FLAT * p.ln, tol)


def _near(a, b, sa: float, tol: float) -> bool:
    """Whether the point of ``a`` at ``sa`` is within ``tol`` of curve ``b``."""
    x, y, _, _ = a.ev(sa)
    return b.project(x, y)[0] <= tol


def _subdivision_hits(a, b, tol: float) -> list[_Hit]:
    """Raw hits of two curves by bounding-box subdivision, Newton refinement, and the end-point checks.

    Overlaps are reduced to their end points, tangential clusters merged.
    """
    newton: list[tuple[float, float, float, float, float]] = []
    stack = [(_root(a), _root(b), 0)]
    while stack:
        pa, pb, depth = stack.pop()
        ba, bb = pa.box, pb.box
        if ba[0] > bb[2] + tol or bb[0] > ba[2] + tol or ba[1] > bb[3] + tol or bb[1] > ba[3] + tol:
            continue
        if _fat_apart(pa, pb, tol) or _fat_apart(pb, pa, tol):
            continue
        fa, fb = _is_flat(pa, tol), _is_flat(pb, tol)
        if (fa and fb) or depth >= _MAX_DEPTH:
            if any(
                pa.t0 <= h[0] <= pa.t1 and pb.t0 <= h[1] <= pb.t1 for h in newton
            ):  # a neighbouring pair of pieces already found the meeting point here
                continue
            s, t = _chord_guess(pa, pb)
            s, t, x, y, res = _newton(a, b, s, t)
            if res <= tol and not any(
                math.hypot(x - h[2], y - h[3]) <= tol
                and _same_place(a, s, h[0], tol)
                and _same_place(b, t, h[1], tol)
                for h in newton
            ):
                newton.append((s, t, x, y, res))
            continue
        size_a = (ba[2] - ba[0]) + (ba[3] - ba[1])
        size_b = (bb[2] - bb[0]) + (bb[3] - bb[1])
        if fb or (not fa and size_a >= size_b):
            for q in _split(a, pa):
                stack.append((q, pb, depth + 1))
        else:
            for q in _split(b, pb):
                stack.append((pa, q, depth + 1))

    ends: list[_Hit] = []
    _endpoint_hits(a, b, tol, ends, swap=False)
    _endpoint_hits(b, a, tol, ends, swap=True)

    # overlaps: two end hits between which the curves coincide (checked at 9 points)
    spans: list[tuple[float, float]] = []
    protected: set[int] = set()
    for i in range(len(ends)):
        for j in range(i + 1, len(ends)):
            s0, s1 = sorted((ends[i][0], ends[j][0]))
            if math.hypot(ends[i][2] - ends[j][2], ends[i][3] - ends[j][3]) <= 2.0 * tol and (
                _same_place(a, s0, s1, tol)
            ):
                continue
            if all(_near(a, b, s0 + k * (s1 - s0) / 10.0, tol) for k in range(1, 10)):
                spans.append((s0, s1))
                protected.update((i, j))
    raw: list[tuple[_Hit, float, bool]] = [(h, 0.0, k in protected) for k, h in enumerate(ends)]
    for s, t, x, y, res in newton:
        if not any(s0 - 1e-9 <= s <= s1 + 1e-9 for s0, s1 in spans):
            raw.append(((s, t, x, y), res, False))

    # one meeting point may have been reached from several starts: merge hits between
    # which the curves stay within tol (a tangency is known only to ~sqrt(tol))
    raw.sort(key=lambda r: r[0][0])
    kept: list[tuple[_Hit, float, bool]] = []
    for h, res, prot in raw:
        if kept:
            k, kres, kprot = kept[-1]
            dist = math.hypot(h[2] - k[2], h[3] - k[3])
            same = (
                dist <= 2.0 * tol
                and _same_place(a, h[0], k[0], tol)
                and _same_place(b, h[1], k[1], tol)
            ) or (
                not (prot and kprot)
                and dist <= 1e-3
                and _near(a, b, 0.5 * (h[0] + k[0]), tol)
                and _near(b, a, 0.5 * (h[1] + k[1]), tol)
            )
            if same:
                exact_h = (h[0] in (0.0, 1.0)) + (h[1] in (0.0, 1.0))  # how many parameters are end points
                exact_k = (k[0] in (0.0, 1.0)) + (k[1] in (0.0, 1.0))
                if (exact_h, -res) > (exact_k, -kres):
                    kept[-1] = (h, res, prot or kprot)
                continue
        kept.append((h, res, prot))
    return [h for h, _, _ in kept]


# -- public -----------------------------------------------------------------------------


def intersect(c1: Curve, c2: Curve) -> list[Intersection]:
    """All points where two curves meet.

    Parameters
    ----------
    c1, c2 : Line, Arc or CubicBezier
        The curves.

    Returns
    -------
    list of Intersection
        Sorted by ``t1``; duplicates merged (see the module notes). A tangency is
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
    return intersect_prepared(prepare(c1), prepare(c2))


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
    pa = [prepare(c) for c in curves_a]
    pb = pa if curves_b is None else [prepare(c) for c in curves_b]
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
    for i, j in zip(*(ix.tolist() for ix in np.nonzero(near)), strict=True):
        hits = intersect_prepared(pa[i], pb[j])
        if hits:
            out[(i, j)] = hits
    return out
