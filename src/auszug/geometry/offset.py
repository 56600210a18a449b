"""Exact offsets of line/arc sequences, with corners re-intersected.

The offset of a line is a parallel line and the offset of an arc is an arc of
the same centre with the radius changed by the distance; only the corners need
work. Following Havemann and Fellner (2004, sec. 2.4), the offset pieces of
two curves meeting in a corner are re-intersected ("the intersection of the
offset circles must be computed"); an offset pointed arch therefore keeps its
centres and changes its excess. Pieces that the offset trims away entirely (a
short segment between two corners, a small arc whose radius collapses) are
removed and their neighbours re-intersected, which is what a straight (here:
circular) skeleton does, so that offsets never self-intersect at sharp corners.

Conventions
-----------
* ``distance > 0`` offsets to the left of the direction of travel: for a
  counter-clockwise closed loop that is inwards (the region shrinks), for a
  clockwise loop outwards.
* Corners where the offsets on the chosen side overlap are trimmed at the
  intersection of the offset carriers. Corners where they separate are
  extended to the intersection of the carriers (a mitre) when it lies within
  ``miter_limit * |distance|`` of the corner, and otherwise joined by an arc
  of radius ``|distance|`` around the corner (a round join).
* A tangent-continuous joint stays a tangent-continuous joint. A cusp (the
  direction reverses, as where two circles touch) is classified by the
  curvatures on both sides: a tapering tip is trimmed, a spike of the outside
  gets a round join.

Examples
--------
>>> from auszug.geometry import Line
>>> from auszug.geometry.offset import offset_curves
>>> square = [Line((0, 0), (2, 0)), Line((2, 0), (2, 2)), Line((2, 2), (0, 2)), Line((0, 2), (0, 0))]
>>> inset = offset_curves(square, 0.5)
>>> [c.start.tolist() for c in inset.curves]
[[0.5, 0.5], [1.5, 0.5], [1.5, 1.5], [0.5, 1.5]]
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np
from numpy.typing import NDArray

from auszug.errors import GeometryError
from auszug.geometry import _tolerance
from auszug.geometry.arc import Arc
from auszug.geometry.curve import Curve
from auszug.geometry.intersect import prepare
from auszug.geometry.line import Line

__all__ = ["OffsetCurves", "offset_curves", "is_closed", "signed_area"]

_TAU = 2.0 * math.pi


@dataclass(frozen=True, eq=False)
class OffsetCurves:
    """The offset of a curve sequence.

    Attributes
    ----------
    curves : tuple of Line or Arc
        The offset pieces in order (a closed loop if the input was closed).
    source : (m,) ndarray of int
        For each piece the index of the input curve it offsets; for a round
        join the index of the input curve that follows the corner.
    is_join : (m,) ndarray of bool
        Whether the piece is a round join around an input corner.
    distance : float
        The signed offset distance (positive = to the left).
    closed : bool
        Whether the sequence is a closed loop.
    """

    curves: tuple[Curve, ...]
    source: NDArray[np.int64]
    is_join: NDArray[np.bool_]
    distance: float
    closed: bool


def _line(x0: float, y0: float, x1: float, y1: float) -> Line:
    """A Line from trusted finite floats, skipping the public validation (hot path)."""
    ln = object.__new__(Line)
    object.__setattr__(ln, "p0", np.array((x0, y0)))
    object.__setattr__(ln, "p1", np.array((x1, y1)))
    object.__setattr__(ln, "_len", math.hypot(x1 - x0, y1 - y0))
    return ln


def _arc(cx: float, cy: float, r: float, th0: float, sweep: float) -> Arc:
    """An Arc from trusted finite floats, skipping the public validation (hot path)."""
    a = object.__new__(Arc)
    object.__setattr__(a, "center", np.array((cx, cy)))
    object.__setattr__(a, "radius", r)
    object.__setattr__(a, "theta0", th0)
    object.__setattr__(a, "sweep", sweep)
    return a


def _wrap(a: float) -> float:
    """Angle wrapped into (-pi, pi]."""
    a = math.fmod(a, _TAU)
    if a <= -math.pi:
        a += _TAU
    elif a > math.pi:
        a -= _TAU
    return a


class _Carrier:
    """The offset of one input curve as plain floats, with its nominal range [0, length].

    ``s`` is signed length along the offset piece from its nominal start.
    """

    __slots__ = ("index", "line", "x0", "y0", "ux", "uy", "cx", "cy", "r", "th0", "sg",
                 "length", "a", "b", "dead", "kappa", "t0", "t1", "end")

    def __init__(self, index: int, c: Curve, d: float) -> None:
        self.index = index
        self.dead = False
        if isinstance(c, Line):
            self.line = True
            (x0, y0), (x1, y1) = c.p0.tolist(), c.p1.tolist()
            L = c.length()
            self.ux, self.uy = (x1 - x0) / L, (y1 - y0) / L
            self.x0, self.y0 = x0 - d * self.uy, y0 + d * self.ux
            self.length = L
            self.kappa = 0.0
            self.t0 = self.t1 = (self.ux, self.uy)
            self.end = (x1, y1)
        elif isinstance(c, Arc):
            self.line = False
            self.cx, self.cy = c.center.tolist()
            self.sg = 1.0 if c.sweep > 0 else -1.0
            self.r = c.radius - d * self.sg
            self.th0 = c.theta0
            self.kappa = self.sg / c.radius
            th1 = c.theta0 + c.sweep
            self.t0 = (-self.sg * math.sin(c.theta0), self.sg * math.cos(c.theta0))
            self.t1 = (-self.sg * math.sin(th1), self.sg * math.cos(th1))
            self.end = (self.cx + c.radius * math.cos(th1), self.cy + c.radius * math.sin(th1))
            if self.r <= _tolerance.TOL.zero * 1e3:
                self.dead = True
                self.r = 0.0
            self.length = self.r * abs(c.sweep)
        else:
            raise TypeError(f"offsets support Line and Arc curves, got {type(c).__name__}")
        self.a = 0.0
        self.b = self.length

    def point(self, s: float) -> tuple[float, float]:
        if self.line:
            return self.x0 + s * self.ux, self.y0 + s * self.uy
        th = self.th0 + self.sg * s / self.r
        return self.cx + self.r * math.cos(th), self.cy + self.r * math.sin(th)

    def s_near(self, x: float, y: float, s_ref: float) -> float:
        """Parameter of the carrier point (x, y), the branch nearest to ``s_ref``."""
        if self.line:
            return (x - self.x0) * self.ux + (y - self.y0) * self.uy
        th_ref = self.th0 + self.sg * s_ref / self.r
        dth = _wrap(math.atan2(y - self.cy, x - self.cx) - th_ref)
        return s_ref + self.sg * dth * self.r


def _carrier_hits(p: _Carrier, q: _Carrier) -> list[tuple[float, float]]:
    """Intersection points of two full carriers (lines extended, whole circles)."""
    tol = _tolerance.TOL.intersect
    if p.line and q.line:
        den = p.ux * q.uy - p.uy * q.ux
        if abs(den) <= _tolerance.TOL.collinear:
            return []
        wx, wy = q.x0 - p.x0, q.y0 - p.y0
        t = (wx * q.uy - wy * q.ux) / den
        return [(p.x0 + t * p.ux, p.y0 + t * p.uy)]
    if p.line or q.line:
        ln, ci = (p, q) if p.line else (q, p)
        wx, wy = ci.cx - ln.x0, ci.cy - ln.y0
        foot = wx * ln.ux + wy * ln.uy
        h = wx * ln.uy - wy * ln.ux
        gap = abs(h) - ci.r
        if gap > tol:
            return []
        w = math.sqrt(max(ci.r * ci.r - h * h, 0.0))
        return [(ln.x0 + s * ln.ux, ln.y0 + s * ln.uy) for s in ((foot - w, foot + w) if w > 0 else (foot,))]
    ex, ey = q.cx - p.cx, q.cy - p.cy
    dd = math.hypot(ex, ey)
    if dd <= tol:
        return []
    if dd > p.r + q.r + tol or dd < abs(p.r - q.r) - tol:
        return []
    along = (dd * dd + p.r * p.r - q.r * q.r) / (2.0 * dd)
    h = math.sqrt(max(p.r * p.r - along * along, 0.0))
    ux, uy = ex / dd, ey / dd
    mx, my = p.cx + along * ux, p.cy + along * uy
    if h <= tol:
        return [(mx, my)]
    return [(mx - h * uy, my + h * ux), (mx + h * uy, my - h * ux)]


def _turn(cin: _Carrier, cout: _Carrier) -> float:
    """Signed turning angle at the joint of ``cin`` into ``cout`` (cusps: +-pi by curvature)."""
    ax, ay = cin.t1
    bx, by = cout.t0
    cr = ax * by - ay * bx
    dt = ax * bx + ay * by
    if abs(cr) <= _tolerance.TOL.collinear and dt < 0.0:
        # cusp: a tapering tip (region between the two curves) is a left turn by pi
        return math.pi if cin.kappa + cout.kappa < 0.0 else -math.pi
    return math.atan2(cr, dt)


def is_closed(curves: Sequence[Curve], tol: float | None = None) -> bool:
    """Whether each curve ends where the next begins, the last where the first begins."""
    tol = _tolerance.TOL.intersect * 10 if tol is None else tol
    n = len(curves)
    return n > 0 and all(
        float(np.hypot(*(curves[i].end - curves[(i + 1) % n].start))) <= tol for i in range(n)
    )


def signed_area(curves: Sequence[Curve]) -> float:
    """Signed area enclosed by a closed loop of lines and arcs (positive = counter-clockwise).

    Exact for lines and arcs: the polygon of the end points plus each arc's
    circular segment.

    Examples
    --------
    >>> import math
    >>> from auszug.geometry import Arc
    >>> round(signed_area([Arc((0, 0), 1.0, 0.0, 2 * math.pi)]), 12) == round(math.pi, 12)
    True
    """
    area = 0.0
    for c in curves:
        p0, p1 = c.start, c.end
        area += 0.5 * float(p0[0] * p1[1] - p0[1] * p1[0])
        if isinstance(c, Arc):
            s = c.sweep
            area += 0.5 * c.radius * c.radius * (s - math.sin(s))
    return area


def _at_offset(x: float, y: float, prims: list, lo: float, hi: float) -> bool:
    """Whether the distance from (x, y) to the nearest input curve lies in [lo, hi].

    A point of a true offset lies at the offset distance from the input, or a
    little further on a mitre (at most the mitre limit); a point nearer lies
    where the region has vanished, one much further where two pieces were
    joined across the region (a spurious re-join).
    """
    best = math.inf
    for pr in prims:
        bx = pr.box
        if x < bx[0] - best or x > bx[2] + best or y < bx[1] - best or y > bx[3] + best:
            continue
        dist = pr.project(x, y)[0]
        if dist < lo:
            return False
        best = min(best, dist)
    return best <= hi


def _join(p: _Carrier, q: _Carrier, turn: float | None, d: float, corner: tuple[float, float],
          miter_limit: float, prims: list) -> tuple[float, float] | None | str:
    """Where carrier ``p`` ends and ``q`` begins: ``(b_p, a_q)``, ``"round"`` or None (no join).

    ``turn`` is the input turning angle at the common corner, or None for a
    re-join after a piece between them was removed (any trimming that leaves
    both neighbours positive length is accepted). A join point must keep the
    offset distance from every input curve (``prims``): a point nearer to one
    lies where the offset region has vanished.
    """
    tolc = _tolerance.TOL.collinear
    ex, ey = p.point(p.length)
    sx, sy = q.point(0.0)
    if turn is not None and abs(turn) <= tolc:
        return p.length, 0.0  # tangent-continuous: the offset points coincide
    cands = _carrier_hits(p, q)
    best = None
    tol = _tolerance.TOL.intersect
    for x, y in cands:
        b = p.s_near(x, y, p.length)
        a = q.s_near(x, y, 0.0)
        din, dout = b - p.length, a
        if turn is not None:
            trim = turn * d > 0.0
            if trim and not (din <= tol and dout >= -tol):
                continue
            if not trim and not (din >= -tol and dout <= tol):
                continue
            if not trim and math.hypot(x - corner[0], y - corner[1]) > miter_limit * abs(d) + tol:
                continue
        if b - p.a <= tol or q.b - a <= tol:
            if turn is None:
                continue
        score = abs(din) + abs(dout)
        if best is not None and score >= best[0]:
            continue
        if not _at_offset(x, y, prims, abs(d) * (1.0 - 1e-7) - tol, miter_limit * abs(d) * 1.01 + tol):
            continue
        if best is None or score < best[0]:
            best = (score, b, a)
    if best is not None:
        return best[1], best[2]
    if turn is not None and turn * d < 0.0:
        return "round"
    return None


def offset_curves(
    curves: Sequence[Curve],
    distance: float,
    closed: bool | None = None,
    miter_limit: float = 4.0,
    check: bool | None = None,
) -> OffsetCurves:
    """Offset a sequence of lines and arcs by ``distance``, re-intersecting the corners.

    Parameters
    ----------
    curves : sequence of Line or Arc, length n >= 1
        Consecutive curves (each ends where the next begins).
    distance : float
        Signed distance; positive offsets to the left of the direction of
        travel (inwards for a counter-clockwise loop).
    closed : bool, optional
        Whether the last curve joins the first (default: detected).
    miter_limit : float
        At separating corners the carriers' intersection is used when it lies
        within ``miter_limit * |distance|`` of the corner, else a round join.
    check : bool, optional
        Verify that the offset of a closed loop does not cross itself (default:
        ``TOL.strict``).

    Returns
    -------
    OffsetCurves

    Raises
    ------
    GeometryError
        If the offset removes the whole sequence (the distance is larger than
        the region is wide), or, with ``check``, if the offset loop crosses
        itself (the region splits).

    Examples
    --------
    The offset of a pointed arch keeps its centres and changes its excess:

    >>> from auszug.geometry import Arc, Line
    >>> right = Arc.from_center((-1.0, 0.0), 2.0, 0.0, math.pi / 3)   # excess 1, span 2
    >>> left = Arc.from_center((1.0, 0.0), 2.0, 2 * math.pi / 3, math.pi)
    >>> arch = offset_curves([right, left], 0.25)
    >>> [(c.center.tolist(), c.radius) for c in arch.curves]
    [([-1.0, 0.0], 1.75), ([1.0, 0.0], 1.75)]
    >>> arch.curves[0].end.round(12).tolist() == arch.curves[1].start.round(12).tolist()
    True
    """
    curves = list(curves)
    n = len(curves)
    if n == 0:
        raise GeometryError("offset of an empty curve sequence")
    d = float(distance)
    if not math.isfinite(d):
        raise GeometryError(f"offset distance must be finite, got {distance}")
    if closed is None:
        closed = is_closed(curves)
    if d == 0.0:
        return OffsetCurves(tuple(curves), np.arange(n), np.zeros(n, bool), 0.0, closed)
    car = [_Carrier(i, c, d) for i, c in enumerate(curves)]
    prims = [prepare(c) for c in curves]
    m = n if closed else n - 1  # number of corners
    turns = [_turn(car[k], car[(k + 1) % n]) for k in range(m)]
    corners = [car[k].end for k in range(m)]
    tol = _tolerance.TOL.intersect
    # Each alive carrier knows whether its predecessor is its original neighbour
    # (then the original corner's turn applies) or a re-join.
    alive = [i for i in range(n) if not car[i].dead]
    round_after: dict[int, int] = {}  # carrier index -> corner index of a round join after it
    def too_few() -> bool:
        if not closed or len(alive) != 1:
            return len(alive) < 1
        c = car[alive[0]]
        return c.line or c.length < (_TAU - 1e-9) * c.r  # one piece closes only as a whole circle

    for _ in range(2 * n + 2):
        if too_few():
            raise GeometryError(
                f"offset by {d:g} removes the whole curve sequence (it is narrower than {2 * abs(d):g})"
            )
        round_after.clear()
        for c in car:
            c.a, c.b = 0.0, c.length
        k = len(alive)
        broken = None
        for j in range(k if closed else k - 1):
            p, q = car[alive[j]], car[alive[(j + 1) % k]]
            adjacent = (p.index + 1) % n == q.index and (closed or p.index + 1 == q.index)
            corner = p.index if adjacent else None
            turn = turns[corner] if corner is not None else None
            where = corners[corner] if corner is not None else p.point(p.length)
            res = _join(p, q, turn, d, where, miter_limit, prims)
            if res is None:
                broken = p if p.b - p.a < q.b - q.a else q
                break
            if isinstance(res, str):  # "round", which _join answers only at a corner (turn known)
                assert corner is not None
                round_after[p.index] = corner
                continue
            p.b, q.a = res
        if broken is None:
            shortest = min(alive, key=lambda i: car[i].b - car[i].a)
            if car[shortest].b - car[shortest].a > tol:
                break
            broken = car[shortest]
        alive.remove(broken.index)
    else:  # pragma: no cover - each pass removes a piece, so this cannot run out
        raise GeometryError("offset did not converge")
    out: list[Curve] = []
    src: list[int] = []
    join: list[bool] = []
    k = len(alive)
    for j, i in enumerate(alive):
        c = car[i]
        if c.line:
            out.append(_line(*c.point(c.a), *c.point(c.b)))
        else:
            th = c.th0 + c.sg * c.a / c.r
            out.append(_arc(c.cx, c.cy, c.r, th, c.sg * (c.b - c.a) / c.r))
        src.append(i)
        join.append(False)
        if i in round_after:
            corner = round_after[i]
            nxt = car[alive[(j + 1) % k]]
            x0, y0 = c.point(c.b)
            x1, y1 = nxt.point(nxt.a)
            cx, cy = corners[corner]
            th0 = math.atan2(y0 - cy, x0 - cx)
            out.append(_arc(cx, cy, abs(d), th0, turns[corner]))
            src.append(nxt.index)
            join.append(True)
    result = OffsetCurves(tuple(out), np.array(src, dtype=np.int64), np.array(join, dtype=bool), d, closed)
    lo, hi = abs(d) * (1.0 - 1e-7) - 10 * tol, miter_limit * abs(d) * 1.01 + 10 * tol
    for i in alive:
        x, y = car[i].point(0.5 * (car[i].a + car[i].b))
        if not _at_offset(x, y, prims, lo, hi):
            raise GeometryError(
                f"offset by {d:g} does not keep the distance {abs(d):g} from the curves near "
                f"({x:.6g}, {y:.6g}): the region splits or vanishes there (the border is too wide for it)"
            )
    if closed and (_tolerance.TOL.strict if check is None else check):
        _check_simple(result)
    return result


def _check_simple(off: OffsetCurves) -> None:
    """Raise if two non-adjacent pieces of a closed offset loop cross."""
    from auszug.geometry.intersect import intersect_many

    cs = off.curves
    m = len(cs)
    if m < 3:
        return
    for (i, j), hits in intersect_many(list(cs)).items():
        if j == i + 1 or (i == 0 and j == m - 1):
            hits = [h for h in hits if not _is_shared_end(cs, i, j, h)]
        if hits:
            p = hits[0].point
            raise GeometryError(
                f"offset by {off.distance:g} crosses itself near ({p[0]:.6g}, {p[1]:.6g}): "
                "the region splits (the border is too wide for it)"
            )


def _is_shared_end(cs: Sequence[Curve], i: int, j: int, h) -> bool:
    tol = 10 * _tolerance.TOL.intersect
    a, b = (cs[i], cs[j]) if j == i + 1 else (cs[j], cs[i])
    return bool(np.hypot(*(h.point - a.end)) <= tol and np.hypot(*(h.point - b.start)) <= tol)
