"""Circular arcs, including the corpus' "start + tangent handle + end" form."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from auszug.errors import GeometryError
from auszug.geometry import _tolerance
from auszug.geometry.curve import Array, Curve, as_point, cross2
from auszug.geometry.line import Line

__all__ = ["Arc", "arc_from_tangent", "arc_through"]

TAU = 2.0 * math.pi
#: arc_from_tangent refuses handles within asin(BACKWARD_SINE) of pointing straight away from the end
BACKWARD_SINE = 1e-3
#: Below this sine of the angle between tangent and chord an arc is made a Line: its centre
#: would lie so far away (radius = chord / (2 sine)) that evaluating the arc around it errs by
#: more (about radius * 1e-16) than the arc departs from its chord (about chord * sine / 4).
ARC_MIN_SINE = 1e-7


@dataclass(frozen=True, eq=False, repr=False, init=False)
class Arc(Curve):
    """Arc of the circle (``center``, ``radius``) from angle ``theta0`` over ``sweep``.

    t is proportional to arc length. ``sweep > 0`` runs counter-clockwise.

    Parameters
    ----------
    center : (2,) array_like
        Circle centre (drawing units).
    radius : float
        Positive radius.
    theta0 : float
        Angle of the start point (radians).
    sweep : float
        Signed angle swept, 0 < |sweep| <= 2 pi.

    Examples
    --------
    >>> import math
    >>> from auszug.geometry import Arc
    >>> a = Arc((0, 0), 2.0, 0.0, math.pi / 2)
    >>> a.point(1.0).round(12).tolist()
    [0.0, 2.0]
    >>> round(a.length(), 12) == round(math.pi, 12)
    True
    """

    center: Array
    radius: float
    theta0: float
    sweep: float
    kind = "arc"

    # the centre field holds an array; the constructor takes any array-like and converts
    def __init__(self, center: ArrayLike, radius: float, theta0: float, sweep: float) -> None:
        object.__setattr__(self, "center", center)
        object.__setattr__(self, "radius", radius)
        object.__setattr__(self, "theta0", theta0)
        object.__setattr__(self, "sweep", sweep)
        self.__post_init__()

    def __post_init__(self) -> None:
        c = as_point(self.center, "arc centre")
        r, th, sw = float(self.radius), float(self.theta0), float(self.sweep)
        if not (math.isfinite(r) and math.isfinite(th) and math.isfinite(sw)):
            raise GeometryError("arc radius and angles must be finite")
        if r <= _tolerance.TOL.zero:
            raise GeometryError(f"arc radius must be positive, got {r}")
        if abs(sw) * r <= _tolerance.TOL.zero or abs(sw) > TAU + 1e-12:
            raise GeometryError(f"arc sweep must satisfy 0 < |sweep| <= 2 pi, got {sw}")
        object.__setattr__(self, "center", c)
        object.__setattr__(self, "radius", r)
        object.__setattr__(self, "theta0", th)
        object.__setattr__(self, "sweep", sw)

    @classmethod
    def from_center(cls, center: ArrayLike, radius: float, angle0: float, angle1: float) -> Arc:
        """Arc from ``angle0`` to ``angle1`` (radians, the sign of the difference is the direction)."""
        return cls(center, radius, angle0, angle1 - angle0)

    # -- protocol ----------------------------------------------------------------------
    def _angle(self, t: ArrayLike) -> Array:
        return self.theta0 + np.asarray(t, dtype=float) * self.sweep

    def point(self, t: ArrayLike) -> Array:
        """Points at parameters ``t``, shape ``t.shape + (2,)``."""
        a = self._angle(t)
        return self.center + self.radius * np.stack([np.cos(a), np.sin(a)], axis=-1)

    def tangent(self, t: ArrayLike) -> Array:
        """Unit tangents at ``t`` in the direction of travel, shape ``t.shape + (2,)``."""
        a = self._angle(t)
        s = 1.0 if self.sweep > 0 else -1.0
        return s * np.stack([-np.sin(a), np.cos(a)], axis=-1)

    def curvature(self, t: ArrayLike) -> Array:
        """Signed curvature at ``t``: 1/radius, positive for a counter-clockwise arc."""
        return np.full(np.shape(t), (1.0 if self.sweep > 0 else -1.0) / self.radius)

    def length(self) -> float:
        """Arc length: radius times the absolute sweep."""
        return self.radius * abs(self.sweep)

    def split(self, t: float) -> tuple[Arc, Arc]:
        """The two arcs before and after parameter ``t``."""
        return (
            Arc(self.center, self.radius, self.theta0, self.sweep * t),
            Arc(self.center, self.radius, self.theta0 + self.sweep * t, self.sweep * (1.0 - t)),
        )

    def reversed(self) -> Arc:
        """The same arc travelled from end to start."""
        return Arc(self.center, self.radius, self.theta0 + self.sweep, -self.sweep)

    def transformed(self, matrix: ArrayLike, offset: ArrayLike = (0.0, 0.0)) -> Arc:
        """The arc mapped by ``x -> matrix @ x + offset`` (a similarity: rotation or reflection)."""
        m = np.asarray(matrix, dtype=float)
        c = m @ self.center + np.asarray(offset, dtype=float)
        d = m @ np.array([math.cos(self.theta0), math.sin(self.theta0)])
        det = m[0, 0] * m[1, 1] - m[0, 1] * m[1, 0]
        return Arc(c, self.radius, math.atan2(d[1], d[0]), self.sweep if det > 0 else -self.sweep)

    def t_of_angle(self, phi: ArrayLike) -> Array:
        """Parameter of the point at polar angle ``phi`` (may fall outside [0, 1])."""
        d = (np.asarray(phi, dtype=float) - self.theta0) * (1.0 if self.sweep > 0 else -1.0)
        d = np.mod(d, TAU)
        t = d / abs(self.sweep)
        # an angle just before the start is better reported as slightly negative
        back = (TAU - d) / abs(self.sweep)
        return np.where((t > 1.0) & (back < t - 1.0), -back, t)

    def project(self, p: ArrayLike) -> float:
        """Parameter of the point of the arc closest to ``p``."""
        q = np.asarray(p, dtype=float)
        v = q - self.center
        if float(np.hypot(*v)) <= _tolerance.TOL.zero:
            return 0.0
        t = float(self.t_of_angle(math.atan2(v[1], v[0])))
        if 0.0 <= t <= 1.0:
            return t
        d0 = np.hypot(*(self.point(0.0) - q))
        d1 = np.hypot(*(self.point(1.0) - q))
        return 0.0 if d0 <= d1 else 1.0

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description: kind, start, end, center, radius and sweep."""
        return {
            "kind": "arc",
            "start": self.start.tolist(),
            "end": self.end.tolist(),
            "center": self.center.tolist(),
            "radius": self.radius,
            "sweep": self.sweep,
        }


def arc_from_tangent(start: ArrayLike, handle: ArrayLike, end: ArrayLike) -> Arc | Line:
    """The arc from ``start`` to ``end`` whose tangent at ``start`` points to ``handle``.

    This is how the corpus stores a top-view curve (points A, T, B). When the
    three points are collinear with the handle pointing towards ``end`` the
    result is the straight :class:`Line`; so it is when the handle is off the
    chord by less than :data:`ARC_MIN_SINE` (an arc that flat cannot be
    evaluated more closely than it departs from its chord).

    Parameters
    ----------
    start, handle, end : (2,) array_like
        A, T and B (drawing units).

    Returns
    -------
    Arc or Line

    Raises
    ------
    GeometryError
        If ``handle`` coincides with ``start``, ``end`` coincides with ``start``,
        or the handle points straight away from ``end`` (no such arc).

    Examples
    --------
    >>> from auszug.geometry import arc_from_tangent
    >>> a = arc_from_tangent((1, 0), (1, 1), (-1, 0))   # upper half circle
    >>> a.center.round(12).tolist(), a.radius
    ([0.0, 0.0], 1.0)
    >>> arc_from_tangent((0, 0), (1, 0), (2, 0)).kind
    'line'
    """
    a = as_point(start, "start point")
    h = as_point(handle, "tangent handle")
    b = as_point(end, "end point")
    tol = _tolerance.TOL
    d = h - a
    dn = math.hypot(d[0], d[1])
    ch = b - a
    cl = math.hypot(ch[0], ch[1])
    if cl <= tol.zero:
        raise GeometryError(f"start and end coincide at {a.tolist()}")
    if dn <= tol.zero:
        raise GeometryError(f"tangent handle coincides with the start point {a.tolist()}")
    d = d / dn
    cr = float(cross2(d, ch))
    dt = float(np.dot(d, ch))
    if abs(cr) <= max(tol.collinear, ARC_MIN_SINE) * cl:
        if dt > 0:
            return Line(a, b)
        raise GeometryError(
            f"tangent handle {h.tolist()} points away from the end point {b.tolist()}: no arc"
        )
    if dt < 0 and abs(cr) < BACKWARD_SINE * cl:
        # the arc would run almost a full circle on a huge radius: ill-conditioned, never meant
        raise GeometryError(
            f"tangent handle {h.tolist()} points almost straight away from the end point "
            f"{b.tolist()}: the arc would be a near-full circle of radius {cl * cl / (2 * abs(cr)):.3g}"
        )
    r_signed = cl * cl / (2.0 * cr)
    c = a + r_signed * np.array([-d[1], d[0]])
    sweep = 2.0 * math.atan2(cr, dt)
    th0 = math.atan2(a[1] - c[1], a[0] - c[0])
    return Arc(c, abs(r_signed), th0, sweep)


def arc_through(p0: ArrayLike, p1: ArrayLike, p2: ArrayLike) -> Arc | Line:
    """The arc from ``p0`` through ``p1`` to ``p2`` (a Line if collinear and ordered).

    Examples
    --------
    >>> from auszug.geometry import arc_through
    >>> a = arc_through((1, 0), (0, 1), (-1, 0))
    >>> a.radius, a.center.round(12).tolist()
    (1.0, [0.0, 0.0])
    """
    a = as_point(p0, "first point")
    m = as_point(p1, "middle point")
    b = as_point(p2, "last point")
    tol = _tolerance.TOL
    cr = float(cross2(m - a, b - a))
    scale = float(np.hypot(*(m - a)) * np.hypot(*(b - a)))
    if scale <= tol.zero:
        raise GeometryError("arc_through needs three distinct points")
    if abs(cr) <= max(tol.collinear, ARC_MIN_SINE) * scale:
        if np.dot(m - a, b - m) > 0:
            return Line(a, b)
        raise GeometryError("three collinear points out of order: no arc through them")
    # tangent at p0 of the circle through the three points: reflect chord direction
    # about the perpendicular of (p0, p1) chord ... via circumcentre.
    bx, by = m - a
    cx, cy = b - a
    dd = 2.0 * (bx * cy - by * cx)
    ux = (cy * (bx * bx + by * by) - by * (cx * cx + cy * cy)) / dd
    uy = (bx * (cx * cx + cy * cy) - cx * (bx * bx + by * by)) / dd
    c = a + np.array([ux, uy])
    r = math.hypot(ux, uy)
    th0 = math.atan2(a[1] - c[1], a[0] - c[0])
    th1 = math.atan2(m[1] - c[1], m[0] - c[0])
    th2 = math.atan2(b[1] - c[1], b[0] - c[0])
    ccw = cr > 0
    sweep = (th2 - th0) % TAU if ccw else -((th0 - th2) % TAU)
    del th1
    return Arc(c, r, th0, sweep)
