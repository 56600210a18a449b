"""Reverse curves (ogee arcs): two arcs turning opposite ways, joined G1 (paper supp. A).

Given end points A, B and unit travel directions d_A, d_B, a reverse curve is
an arc from A (tangent d_A) to the point of reverse curvature C (PRC), then an
arc turning the other way from C to B (arriving along d_B), with one tangent
at C. The family has one degree of freedom; this module gives

* :func:`prc_locus`: the locus of the PRCs (Remark 2; Remark 1 for parallel tangents),
* :func:`reverse_curve_through`: the curve through a chosen PRC (construction of A.1),
* :func:`reverse_curve_from_radius`: the curve with a chosen first radius (A.2),
* :func:`equal_radius_reverse_curve`: the curve whose two radii are equal.

Signed radii
------------
Internally an arc's radius is signed: positive when it turns left. With
N = :func:`~auszug.geometry.rot90` (the left normal) the centres are
O_A = A + rho_A N(d_A) and O_B = B + rho_B N(d_B). Two circles tangent at C
with the curve passing from one to the other without a cusp means
|O_A - O_B| = |rho_A - rho_B|; for a reverse curve rho_A rho_B < 0, so this
is the paper's |O_A O_B| = r_A + r_B. Squared, with w = A - B and
c = d_A . d_B, the rho_B^2 terms cancel::

    |w|^2 + 2 rho_A w.N(d_A) - 2 rho_B w.N(d_B) + 2 rho_A rho_B (1 - c) = 0,    (*)

linear in each radius given the other. The PRC is
C = O_A + rho_A / (rho_A - rho_B) (O_B - O_A), which for rho_A = r_A,
rho_B = -r_B is the paper's C = (r_B O_A + r_A O_B) / (r_A + r_B).

Two kinds of reverse curve fit the same data: those whose total turning
(the sum of the two sweeps) is the angle from d_A to d_B, and those that wind
a full extra turn (:func:`winds`). Only the former are ogees; their PRCs form
the arc of Remark 2 (:func:`prc_locus`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from auszug.errors import GeometryError
from auszug.geometry import _tolerance
from auszug.geometry.arc import Arc, arc_from_tangent
from auszug.geometry.curve import Array, as_point
from auszug.geometry.line import Line

__all__ = [
    "ReverseCurve",
    "prc_locus",
    "reverse_curve_through",
    "reverse_curve_from_radius",
    "equal_radius_reverse_curve",
    "turning_angle",
    "winds",
]

_TAU = 2.0 * math.pi
Turn = Literal["left", "right"]


@dataclass(frozen=True, eq=False)
class ReverseCurve:
    """A reverse curve (ogee): arc ``first`` from A to the PRC, arc ``second`` on to B.

    Attributes
    ----------
    first, second : Arc
        The two arcs; ``first.end`` and ``second.start`` are the PRC.
    prc : (2,) ndarray
        The point of reverse curvature C.
    center_a, center_b : (2,) ndarray
        Centres O_A and O_B.
    radius_a, radius_b : float
        Radii r_A and r_B (positive).
    """

    first: Arc
    second: Arc
    prc: Array
    center_a: Array
    center_b: Array
    radius_a: float
    radius_b: float

    @property
    def first_turn(self) -> Turn:
        """Which way the first arc turns, ``"left"`` (counter-clockwise) or ``"right"``."""
        return "left" if self.first.sweep > 0 else "right"

    @property
    def arcs(self) -> tuple[Arc, Arc]:
        """(first, second)."""
        return self.first, self.second

    def length(self) -> float:
        """Total arc length (drawing units)."""
        return self.first.length() + self.second.length()

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready description."""
        return {
            "kind": "reverse_curve",
            "first": self.first.to_dict(),
            "second": self.second.to_dict(),
            "prc": self.prc.tolist(),
        }


# -- input handling ---------------------------------------------------------------------


def _direction(d: ArrayLike, name: str) -> Array:
    v = as_point(d, name)
    n = math.hypot(v[0], v[1])
    if n <= _tolerance.TOL.zero:
        raise GeometryError(f"{name} must be a non-zero vector, got {v.tolist()}")
    return v / n


def _inputs(A: ArrayLike, dA: ArrayLike, B: ArrayLike, dB: ArrayLike):
    a = as_point(A, "start point A")
    b = as_point(B, "end point B")
    da = _direction(dA, "tangent direction at A")
    db = _direction(dB, "tangent direction at B")
    if math.hypot(*(a - b)) <= _tolerance.TOL.zero:
        raise GeometryError(f"A and B coincide at {a.tolist()}: expected two distinct end points")
    return a, da, b, db


def _left(v: Array) -> Array:
    return np.array([-v[1], v[0]])


def _parallel(da: Array, db: Array) -> bool:
    return abs(da[0] * db[1] - da[1] * db[0]) <= _tolerance.TOL.collinear


def _straight_ahead(a: Array, da: Array, b: Array) -> bool:
    """B lies on the tangent line at A (then parallel tangents admit no reverse curve)."""
    w = b - a
    return abs(float(w @ _left(da))) <= _tolerance.TOL.collinear * math.hypot(*w)


# -- building the curve -----------------------------------------------------------------


def _arc(center: Array, rho: float, p: Array, q: Array, what: str) -> Arc:
    """The arc of the circle (center, |rho|) from p to q turning like sign(rho)."""
    th0 = math.atan2(p[1] - center[1], p[0] - center[0])
    th1 = math.atan2(q[1] - center[1], q[0] - center[0])
    s = 1.0 if rho > 0 else -1.0
    sweep = ((th1 - th0) * s) % _TAU
    if sweep * abs(rho) <= _tolerance.TOL.zero or (_TAU - sweep) * abs(rho) <= _tolerance.TOL.zero:
        raise GeometryError(f"the {what} arc has zero length: the PRC coincides with its end point")
    return Arc(center, abs(rho), th0, s * sweep)


def _build(a: Array, da: Array, b: Array, db: Array, rho_a: float, rho_b: float) -> ReverseCurve:
    """The reverse curve with signed radii ``rho_a``, ``rho_b`` (opposite signs)."""
    if not (math.isfinite(rho_a) and math.isfinite(rho_b)) or rho_a * rho_b >= 0.0:
        raise GeometryError(
            f"no reverse curve with signed radii ({rho_a:.6g}, {rho_b:.6g}): expected finite "
            "radii of opposite signs (the arcs must turn opposite ways)"
        )
    oa = a + rho_a * _left(da)
    ob = b + rho_b * _left(db)
    c = oa + (rho_a / (rho_a - rho_b)) * (ob - oa)
    first = _arc(oa, rho_a, a, c, "first")
    second = _arc(ob, rho_b, c, b, "second")
    if _tolerance.TOL.strict:
        _check(first, second, a, da, b, db)
    return ReverseCurve(first, second, c, oa, ob, abs(rho_a), abs(rho_b))


def _check(first: Arc, second: Arc, a: Array, da: Array, b: Array, db: Array) -> None:
    """Strict-mode invariants: end points, end tangents, G1 at the PRC, opposite turns."""
    scale = 1.0 + first.radius + second.radius
    tol = 1e-9 * scale
    problems = []
    if np.hypot(*(first.start - a)) > tol or np.hypot(*(second.end - b)) > tol:
        problems.append("end points moved")
    if np.hypot(*(first.end - second.start)) > tol:
        problems.append("arcs do not meet at the PRC")
    if np.hypot(*(first.tangent(0.0) - da)) > 1e-9 or np.hypot(*(second.tangent(1.0) - db)) > 1e-9:
        problems.append("end tangents changed")
    if np.hypot(*(first.tangent(1.0) - second.tangent(0.0))) > 1e-9:
        problems.append("not G1 at the PRC")
    if first.sweep * second.sweep >= 0:
        problems.append("arcs turn the same way")
    if problems:  # pragma: no cover - an internal error, not bad input
        raise AssertionError("reverse curve invariants violated: " + ", ".join(problems))


# -- public -----------------------------------------------------------------------------


def prc_locus(A: ArrayLike, dA: ArrayLike, B: ArrayLike, dB: ArrayLike) -> Arc | Line:
    """The locus of the points of reverse curvature of the reverse curves from A to B.

    Remark 2: with D the intersection of the tangent lines and l the
    perpendicular bisector of AB, the circumcircle of A, B, D (which also holds
    F, the intersection of the normals) meets l in two points O. The locus is
    an arc from A to B of the circle centred at the right O through A and B.

    Which O, and which arc: every G1 pair of arcs from A to B (reverse or not)
    with joint C satisfies dir(CB) - dir(AC) = (phi_1 + phi_2) where 2 phi_i are
    the sweeps, and the sweeps add up to the turning theta from d_A to d_B
    (:func:`turning_angle`; or theta +- 2 pi for curves that wind a full extra
    turn). So the joints see AB under a constant angle (the circle), and those
    of non-winding curves lie on the arc from A to B whose sweep is theta: the
    arc leaving A in the direction dir(AB) - theta / 2. Its centre is the O
    with angle AOB = |theta| = alpha, the angle between the tangents (as the
    paper's proof has it). The circle's other arc holds the joints of curves
    that wind (:func:`winds`).

    Every interior point of that arc is the PRC of a reverse curve when the
    tangents lie on the same side of the chord AB (cross(AB, d_A) and
    cross(AB, d_B) of one sign: an S-shaped, ogee configuration). Otherwise
    part of the arc holds the joints of same-turn (C-shaped) biarcs and no arc
    from A to B is a locus of PRCs: a GeometryError says so.

    Remark 1: for parallel tangents pointing the same way theta = 0 and the
    arc is the segment AB.

    Parameters
    ----------
    A, B : (2,) array_like
        End points.
    dA, dB : (2,) array_like
        Travel directions at A and B (any non-zero length).

    Returns
    -------
    Arc or Line
        From A to B, with sweep theta; every interior point is the PRC of
        exactly one reverse curve, which does not wind.

    Raises
    ------
    GeometryError
        For coincident end points, zero directions, tangents on opposite sides
        of the chord AB (or B straight ahead of A along parallel tangents): no
        reverse curves with PRCs filling an arc from A to B.

    Examples
    --------
    >>> from auszug.geometry import prc_locus
    >>> prc_locus((0, 0), (0, 1), (2, 2), (0, 1)).kind    # parallel: the segment AB
    'line'
    >>> loc = prc_locus((0, 0), (0, 1), (3, 2), (1, 1))   # D = (0, -1)
    >>> loc.center.round(6).tolist(), round(loc.radius, 6), round(loc.sweep, 12)
    ([3.914214, -2.62132], 4.71088, -0.785398163397)
    """
    a, da, b, db = _inputs(A, dA, B, dB)
    ab = b - a
    chord = math.hypot(*ab)
    sa = float(ab[0] * da[1] - ab[1] * da[0]) / chord
    sb = float(ab[0] * db[1] - ab[1] * db[0]) / chord
    eps = _tolerance.TOL.collinear
    if (sa > eps and sb < -eps) or (sa < -eps and sb > eps):
        raise GeometryError(
            "the tangents at A and B lie on opposite sides of the chord AB (a C-shaped, not an "
            "S-shaped configuration): the PRCs of reverse curves do not fill an arc from A to B; "
            "expected tangents on the same side of AB"
        )
    if max(abs(sa), abs(sb)) <= eps:
        raise GeometryError(
            "B lies straight ahead of A on parallel tangents: no reverse curve exists"
        )
    theta = turning_angle(da, db)
    if abs(theta) <= _tolerance.TOL.collinear:
        return Line(a, b)  # Remark 1
    tau = math.atan2(ab[1], ab[0]) - 0.5 * theta
    return arc_from_tangent(a, a + np.array([math.cos(tau), math.sin(tau)]), b)


def turning_angle(d_a: ArrayLike, d_b: ArrayLike) -> float:
    """The signed angle from ``d_a`` to ``d_b`` in (-pi, pi] (radians).

    A reverse curve whose total turning (the sum of its arcs' sweeps) equals
    this angle does not wind; the others turn a full extra turn (+-2 pi).

    Examples
    --------
    >>> round(turning_angle((1, 0), (0, 1)), 12)
    1.570796326795
    """
    a = _direction(d_a, "first direction")
    b = _direction(d_b, "second direction")
    return math.atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1])


def winds(rc: ReverseCurve, d_a: ArrayLike, d_b: ArrayLike) -> bool:
    """Whether the reverse curve turns a full extra turn (total turning != angle d_a -> d_b).

    Examples
    --------
    >>> rc = equal_radius_reverse_curve((0, 0), (0, 1), (2, 2), (0, 1), "right")
    >>> winds(rc, (0, 1), (0, 1))
    False
    """
    total = rc.first.sweep + rc.second.sweep
    return abs(total - turning_angle(d_a, d_b)) > math.pi


def reverse_curve_through(
    A: ArrayLike, dA: ArrayLike, B: ArrayLike, dB: ArrayLike, C: ArrayLike
) -> ReverseCurve:
    """The reverse curve from A to B whose point of reverse curvature is C.

    Construction of A.1: O_A is where the perpendicular bisector of AC meets
    the normal at A (signed radius rho_A = |C - A|^2 / (2 (C - A).N(d_A))),
    likewise O_B. C must be a point of reverse curvature (within
    ``TOL.intersect``): a point of :func:`prc_locus`, or of the other arc of
    its circle for a reverse curve that winds. Only there are the two circles
    tangent at C.

    Parameters
    ----------
    A, B : (2,) array_like
        End points.
    dA, dB : (2,) array_like
        Travel directions at A and B.
    C : (2,) array_like
        The point of reverse curvature, on the locus.

    Returns
    -------
    ReverseCurve

    Raises
    ------
    GeometryError
        If C is not on the locus, lies on the tangent line at A or B (an arc
        would be straight), or coincides with A or B.

    Examples
    --------
    >>> from auszug.geometry import reverse_curve_through
    >>> rc = reverse_curve_through((0, 0), (0, 1), (2, 2), (0, 1), (1, 1))
    >>> rc.radius_a, rc.radius_b, rc.first_turn
    (1.0, 1.0, 'right')
    """
    a, da, b, db = _inputs(A, dA, B, dB)
    c = as_point(C, "point of reverse curvature C")
    tol = _tolerance.TOL
    rhos = []
    for p, dp, name in ((a, da, "A"), (b, db, "B")):
        v = c - p
        dist = math.hypot(*v)
        if dist <= tol.zero:
            raise GeometryError(f"C coincides with {name}: expected a PRC strictly between A and B")
        den = 2.0 * float(v @ _left(dp))
        if abs(den) <= tol.collinear * dist:
            raise GeometryError(
                f"C lies on the tangent line at {name}: that arc would be straight, "
                "expected C on the locus of PRCs (prc_locus)"
            )
        rhos.append(float(v @ v) / den)
    rho_a, rho_b = rhos
    oa, ob = a + rho_a * _left(da), b + rho_b * _left(db)
    gap = abs(math.hypot(*(oa - ob)) - abs(rho_a - rho_b))
    if rho_a * rho_b >= 0 or gap > tol.intersect * max(1.0, abs(rho_a) + abs(rho_b)):
        raise GeometryError(
            f"C = {c.tolist()} is not a point of reverse curvature for these end points and "
            "tangents: expected a point on prc_locus(A, dA, B, dB)"
        )
    rc = _build(a, da, b, db, rho_a, rho_b)
    # report the given C exactly (the arcs meet it to rounding)
    return ReverseCurve(rc.first, rc.second, c, rc.center_a, rc.center_b, rc.radius_a,
                        rc.radius_b)


def reverse_curve_from_radius(
    A: ArrayLike,
    dA: ArrayLike,
    B: ArrayLike,
    dB: ArrayLike,
    r_A: float,
    first_turn: Turn | None = None,
) -> ReverseCurve:
    """The reverse curve from A to B whose first arc has radius ``r_A`` (paper A.2).

    The second radius follows from the law of cosines in the triangle F O_A O_B
    (F the intersection of the normals at A and B, t = |AF|, s = |BF|,
    alpha = angle AFB)::

        (r_A + r_B)^2 = (s - r_B)^2 + (t + r_A)^2 - 2 (s - r_B)(t + r_A) cos(alpha).

    The paper prints ``(t + r_B)`` in the last factor; that is a misprint: the
    law of cosines multiplies the two sides adjacent to the angle, |FO_B| = s - r_B
    and |FO_A| = t + r_A, and only this version makes the circles tangent at C
    (shown in ``tests/geometry/test_reverse.py::test_law_of_cosines_misprint``).
    With signed radii and distances measured along the normals the relation
    becomes (*) of the module notes, which needs no F and so also covers
    parallel tangents; it is linear in r_B.

    Parameters
    ----------
    A, B : (2,) array_like
        End points.
    dA, dB : (2,) array_like
        Travel directions at A and B.
    r_A : float
        Radius of the first arc, > 0.
    first_turn : {"left", "right"}, optional
        Which way the first arc turns. By default the one that gives a reverse
        curve; when both do, the one that does not wind (:func:`winds`); when
        neither winds, the paper's choice (O_A on the side of A away from F,
        i.e. O_A = A + r_A (A - F) / |AF|).

    Returns
    -------
    ReverseCurve

    Raises
    ------
    GeometryError
        If no reverse curve with this first radius (and turn) exists, or the
        choice is ambiguous (parallel normals, both turns possible).

    Examples
    --------
    >>> from auszug.geometry import reverse_curve_from_radius
    >>> rc = reverse_curve_from_radius((0, 0), (0, 1), (3, 3), (0, 1), 1.0)
    >>> rc.radius_b, rc.prc.round(12).tolist()
    (2.0, [1.0, 1.0])
    """
    a, da, b, db = _inputs(A, dA, B, dB)
    r = float(r_A)
    if not (math.isfinite(r) and r > _tolerance.TOL.zero):
        raise GeometryError(f"first radius r_A must be a positive number, got {r_A!r}")
    turns: tuple[Turn, ...] = (first_turn,) if first_turn is not None else ("left", "right")
    for t in turns:
        _check_turn(t)
    found: dict[str, ReverseCurve] = {}
    errors = []
    for t in turns:
        rho_a = r if t == "left" else -r
        rho_b = _second_radius(a, da, b, db, rho_a)
        try:
            found[t] = _build(a, da, b, db, rho_a, rho_b)
        except GeometryError as e:
            errors.append(f"turning {t} first: {e}")
    if not found:
        raise GeometryError(f"no reverse curve with first radius {r:g}: " + "; ".join(errors))
    if len(found) == 2:  # prefer the curve that does not wind a full extra turn
        plain = {t: rc for t, rc in found.items() if not winds(rc, da, db)}
        found = plain or found
    if len(found) == 1:
        return next(iter(found.values()))
    # both turns work: the paper's convention, O_A on the far side of A from F
    na = _left(da)
    f_dist = _normal_intersection(a, na, b, _left(db))
    if f_dist is None:
        raise GeometryError(
            "both turning directions give a reverse curve with this radius and the normals are "
            "parallel: pass first_turn='left' or 'right'"
        )
    # F = A + f_dist N(d_A); O_A = A + rho_A N(d_A) is away from F when rho_A f_dist < 0
    return found["right"] if f_dist > 0 else found["left"]


def _check_turn(t: object) -> None:
    if t not in ("left", "right"):
        raise GeometryError(f"first_turn must be 'left' or 'right', got {t!r}")


def _normal_intersection(a: Array, na: Array, b: Array, nb: Array) -> float | None:
    """The s with F = A + s n_A on the normal line at B, or None for parallel normals."""
    den = na[0] * nb[1] - na[1] * nb[0]
    if abs(den) <= _tolerance.TOL.collinear:
        return None
    w = b - a
    return float((w[0] * nb[1] - w[1] * nb[0]) / den)


def _one_minus_cos(da: Array, db: Array) -> float:
    """The 1 - d_A . d_B, exactly 0 for parallel tangents.

    Not a rounding residue, which would turn an impossible turn into a reverse curve of
    radius ~1e15.
    """
    c = float(da @ db)
    if c > 0 and _parallel(da, db):
        return 0.0
    return 1.0 - c


def _second_radius(a: Array, da: Array, b: Array, db: Array, rho_a: float) -> float:
    """Signed rho_B from (*) given rho_A (inf when the second arc would be straight)."""
    w = a - b
    den = 2.0 * float(w @ _left(db)) - 2.0 * rho_a * _one_minus_cos(da, db)
    num = float(w @ w) + 2.0 * rho_a * float(w @ _left(da))
    if den == 0.0:
        return math.inf
    return num / den


def _equal_radius(a: Array, da: Array, b: Array, db: Array, turn: Turn) -> float | None:
    """Signed rho with rho_A = rho, rho_B = -rho turning ``turn`` first, or None.

    (*) with rho_B = -rho_A: 2 (1 - c) rho^2 - 2 p rho - |w|^2 = 0 with
    p = w.(N(d_A) + N(d_B)). The roots have product -|w|^2 / (2 (1 - c)) < 0:
    one per turn, except for d_A = d_B (c = 1) where only the finite root
    rho = -|w|^2 / (2 p) remains.
    """
    w = a - b
    ww = float(w @ w)
    p = float(w @ (_left(da) + _left(db)))
    q = _one_minus_cos(da, db)
    disc = math.sqrt(p * p + 2.0 * q * ww)
    big_num = p + disc if p >= 0 else p - disc  # no cancellation
    if big_num == 0.0:
        return None
    small = -ww / big_num  # the root that stays finite as q -> 0
    big = big_num / (2.0 * q) if q > 0 else math.inf
    for rho in (small, big):
        if math.isfinite(rho) and rho != 0.0 and (rho > 0) == (turn == "left"):
            return rho
    return None


def equal_radius_reverse_curve(
    A: ArrayLike, dA: ArrayLike, B: ArrayLike, dB: ArrayLike, first_turn: Turn
) -> ReverseCurve:
    """The reverse curve from A to B whose two arcs have the same radius.

    Used for decorations: a side-view arc replaced by two equal arcs with its
    end points and end tangents. With signed radii rho and -rho the centres
    are O_A = A + rho N(d_A), O_B = B - rho N(d_B), and tangency of the circles
    is |A - B + rho (N(d_A) + N(d_B))| = 2 |rho|, i.e.
    2 (1 - d_A.d_B) rho^2 - 2 rho (A - B).(N(d_A) + N(d_B)) - |A - B|^2 = 0,
    a quadratic with one root of each sign (the product of the roots is
    negative); ``first_turn`` picks it. For d_A = d_B it is linear: one turn only.

    Parameters
    ----------
    A, B : (2,) array_like
        End points.
    dA, dB : (2,) array_like
        Travel directions at A and B.
    first_turn : {"left", "right"}
        Which way the first arc turns.

    Returns
    -------
    ReverseCurve
        With ``radius_a == radius_b``.

    Raises
    ------
    GeometryError
        If no such curve exists: with d_A = d_B only one turn is possible (none
        when B lies straight ahead of A); or a degenerate arc.

    Examples
    --------
    >>> from auszug.geometry import equal_radius_reverse_curve
    >>> rc = equal_radius_reverse_curve((0, 0), (0, 1), (2, 2), (0, 1), "right")
    >>> rc.radius_a, rc.radius_b, rc.prc.tolist()
    (1.0, 1.0, [1.0, 1.0])
    """
    a, da, b, db = _inputs(A, dA, B, dB)
    _check_turn(first_turn)
    rho = _equal_radius(a, da, b, db, first_turn)
    if rho is None:
        other = "right" if first_turn == "left" else "left"
        why = (
            "B lies straight ahead of A on parallel tangents"
            if _parallel(da, db) and _straight_ahead(a, da, b)
            else f"with equal tangents at A and B it must turn {other} first"
        )
        raise GeometryError(f"no equal-radius reverse curve turning {first_turn} first: {why}")
    return _build(a, da, b, db, rho, -rho)
