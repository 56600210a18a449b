"""The pointed arch by its excess, its exact offset, and the pointed trefoil arch.

A pointed arch over the springers ``(left, y)`` and ``(right, y)`` consists of
two arcs of radius ``r = excess * span``: the right arc is centred on the
springing line at ``right - r`` and rises from the right springer, the left
arc is centred at ``left + r``; they meet on the axis in the apex, at height
``(span / 2) * sqrt(4 excess - 1)`` above the springing line (Havemann and
Fellner 2004, sec. 2). Excess 0.5 is the round arch, below 1 a four-centred
(depressed) arch, 1 the equilateral arch, above 1 a lancet.

Examples
--------
>>> from auszug.tracery.arch import PointedArch
>>> a = PointedArch(-1.0, 1.0, 4.0, 1.0, bottom=0.0)
>>> a.kind, round(a.rise, 12) == round(3 ** 0.5, 12)
('equilateral', True)
>>> a.offset(0.1).centers.tolist() == a.centers.tolist()    # an offset keeps the centres
True
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from auszug.geometry import Arc, Curve, Line
from auszug.tracery._checks import ParameterError, number, require

__all__ = ["PointedArch", "apex_height", "arch_kind", "arc_between", "trefoil_arch"]

Array = NDArray[np.float64]


def apex_height(span: float, excess: float) -> float:
    """Height of the apex above the springing line: ``(span / 2) * sqrt(4 excess - 1)``.

    Examples
    --------
    >>> apex_height(2.0, 1.25)
    2.0
    """
    return 0.5 * span * math.sqrt(4.0 * excess - 1.0)


def arch_kind(excess: float) -> str:
    """``"round"`` (0.5), ``"four-centred"`` (< 1), ``"equilateral"`` (1) or ``"lancet"`` (> 1).

    Examples
    --------
    >>> [arch_kind(e) for e in (0.5, 0.75, 1.0, 1.25)]
    ['round', 'four-centred', 'equilateral', 'lancet']
    """
    if abs(excess - 0.5) <= 1e-12:
        return "round"
    if abs(excess - 1.0) <= 1e-12:
        return "equilateral"
    return "four-centred" if excess < 1.0 else "lancet"


def arc_between(center: Array, start: Array, end: Array, ccw: bool, full: bool = False) -> Arc:
    """The arc of the circle about ``center`` from ``start`` to ``end`` in the given sense.

    ``start`` and ``end`` must be (nearly) equidistant from ``center``; the
    radius is the distance to ``start``. With ``full`` and coincident end
    points the arc is the whole circle.
    """
    c = np.asarray(center, float)
    s = np.asarray(start, float) - c
    e = np.asarray(end, float) - c
    r = math.hypot(s[0], s[1])
    th0 = math.atan2(s[1], s[0])
    th1 = math.atan2(e[1], e[0])
    sweep = (th1 - th0) % (2.0 * math.pi) if ccw else -((th0 - th1) % (2.0 * math.pi))
    if full and abs(sweep) < 1e-12:
        sweep = 2.0 * math.pi if ccw else -2.0 * math.pi
    return Arc(c, r, th0, sweep)


@dataclass(frozen=True)
class PointedArch:
    """A pointed arch, optionally closed below by jambs and a sill into a window region.

    Parameters
    ----------
    left, right : float
        x of the springers (``left < right``).
    springing : float
        y of the springing line.
    excess : float
        Radius over span, >= 0.5.
    bottom : float, optional
        y of the sill; then :meth:`curves` is the closed region (sill, right
        jamb, right arc, left arc, left jamb), counter-clockwise.

    Raises
    ------
    ParameterError
        For ``excess < 0.5``, ``right <= left`` or ``bottom >= springing``.
    """

    left: float
    right: float
    springing: float
    excess: float
    bottom: float | None = None

    def __post_init__(self) -> None:
        number("excess", self.excess, 0.5, why="excess 0.5 is the round arch; below it the arcs do not meet")
        require(self.right > self.left, "span", self.right - self.left, "a number > 0")
        if self.bottom is not None:
            require(self.springing > self.bottom, "height", self.springing - self.bottom, "a number > 0",
                    "the springing line must lie above the sill")

    # -- measures ------------------------------------------------------------------------
    @property
    def span(self) -> float:
        """Distance between the springers."""
        return self.right - self.left

    @property
    def radius(self) -> float:
        """Radius of both arcs, ``excess * span``."""
        return self.excess * self.span

    @property
    def mid(self) -> float:
        """The x of the axis of symmetry."""
        return 0.5 * (self.left + self.right)

    @property
    def rise(self) -> float:
        """Height of the apex above the springing line."""
        return apex_height(self.span, self.excess)

    @property
    def apex(self) -> Array:
        """The apex, shape (2,)."""
        return np.array([self.mid, self.springing + self.rise])

    @property
    def centers(self) -> Array:
        """Centres of the left and the right arc, shape (2, 2) (rows: left arc, right arc)."""
        r = self.radius
        return np.array([[self.left + r, self.springing], [self.right - r, self.springing]])

    @property
    def kind(self) -> str:
        """See :func:`arch_kind`."""
        return arch_kind(self.excess)

    @property
    def apex_angle(self) -> float:
        """Polar angle of the apex about the right arc's centre (radians, in (0, pi/2])."""
        return math.atan2(self.rise, self.radius - 0.5 * self.span)

    # -- curves --------------------------------------------------------------------------
    def right_arc(self) -> Arc:
        """Counter-clockwise from the right springer up to the apex."""
        return Arc(self.centers[1], self.radius, 0.0, self.apex_angle)

    def left_arc(self) -> Arc:
        """Counter-clockwise from the apex down to the left springer."""
        a = self.apex_angle
        return Arc(self.centers[0], self.radius, math.pi - a, a)

    def curves(self) -> tuple[Curve, ...]:
        """The arch (right arc, left arc) or, with a sill, the closed counter-clockwise region."""
        arcs = (self.right_arc(), self.left_arc())
        if self.bottom is None:
            return arcs
        lt, rt, y, b = self.left, self.right, self.springing, self.bottom
        return (Line((lt, b), (rt, b)), Line((rt, b), (rt, y)), *arcs, Line((lt, y), (lt, b)))

    def offset(self, d: float) -> PointedArch:
        """The arch offset inwards by ``d`` (outwards if negative): same centres, new excess.

        The springers move in by ``d``, the radius shrinks by ``d`` and the
        sill rises by ``d``; the excess becomes ``(r - d) / (span - 2 d)``.

        Raises
        ------
        ParameterError
            If ``d`` is not less than half the span (or the height).
        """
        lim = 0.5 * self.span
        if self.bottom is not None:
            lim = min(lim, 0.5 * (self.springing - self.bottom) + 0.5 * self.rise)
        number("border", d, hi=lim, hi_open=True, why=f"wider than half the region ({lim:.6g})")
        span = self.span - 2.0 * d
        if span <= 1e-9 * self.span:
            number("border", d, hi=lim * (1.0 - 1e-9), hi_open=True, why=f"wider than half the region ({lim:.6g})")
        return PointedArch(
            self.left + d, self.right - d, self.springing,
            (self.radius - d) / span, None if self.bottom is None else self.bottom + d,
        )  # fmt: skip

    def with_bottom(self, bottom: float | None) -> PointedArch:
        """The same arch closed by a sill at ``bottom`` (or open)."""
        return PointedArch(self.left, self.right, self.springing, self.excess, bottom)


def trefoil_arch(arch: PointedArch, split: float = 0.5, lobe: float = 0.5, upper: float = 0.55) -> tuple[Curve, ...]:
    """The pointed trefoil arch inscribed in a pointed arch (Havemann and Fellner, Fig. 12).

    Each arc of the pointed arch is split at ``split`` (fraction of its angle,
    from the springer); the upper parts stay and form the pointed top lobe. The
    lower part of each side is replaced by a pair of smaller arcs, each centred
    on the line through the centre and an end point of the arc it continues,
    so that the joints stay tangent continuous:

    * the upper lobe is closed by an arc of radius ``upper * r`` tangent to the
      arch at the split point;
    * the side lobe is an arc of radius ``lobe * span / 2`` centred on the
      springing line, tangent to the jamb at the springer;
    * the two meet in a sharp cusp pointing into the opening.

    Parameters
    ----------
    arch : PointedArch
        With a sill (the region) or without (only the head).
    split : float
        In (0, 1).
    lobe : float
        Side lobe radius over half the span, in (0, 1).
    upper : float
        Upper lobe closing radius over the arch radius, in (0, 1).

    Returns
    -------
    tuple of Curve
        The closed counter-clockwise region (if ``arch`` has a sill) or the
        open head from the right springer to the left springer.

    Raises
    ------
    ParameterError
        If a parameter is out of range or the lobes do not meet.

    Examples
    --------
    >>> from auszug.tracery.arch import PointedArch, trefoil_arch
    >>> head = trefoil_arch(PointedArch(-1.0, 1.0, 0.0, 1.0))
    >>> [c.kind for c in head]
    ['arc', 'arc', 'arc', 'arc', 'arc', 'arc']
    """
    number("split", split, 0.0, 1.0, lo_open=True, hi_open=True)
    number("lobe", lobe, 0.0, 1.0, lo_open=True, hi_open=True)
    number("upper", upper, 0.0, 1.0, lo_open=True, hi_open=True)
    r = arch.radius
    cl, cr = arch.centers
    a_apex = arch.apex_angle
    th_s = split * a_apex
    s_pt = cr + r * np.array([math.cos(th_s), math.sin(th_s)])
    rho2 = upper * r
    c2 = s_pt + rho2 * (cr - s_pt) / r
    rho1 = lobe * 0.5 * arch.span
    c1 = np.array([arch.right - rho1, arch.springing])
    # cusp: where the side lobe circle meets the upper-lobe closing circle, first along the lobe
    e = c2 - c1
    dd = math.hypot(e[0], e[1])
    if not (abs(rho1 - rho2) < dd < rho1 + rho2):
        raise ParameterError("lobe", lobe, "a side lobe that meets the upper lobe",
                             f"with split={split:g} and upper={upper:g}; try a larger lobe or upper")
    along = (dd * dd + rho1 * rho1 - rho2 * rho2) / (2.0 * dd)
    h = math.sqrt(max(rho1 * rho1 - along * along, 0.0))
    u = e / dd
    m = c1 + along * u
    cands = [m + h * np.array([-u[1], u[0]]), m - h * np.array([-u[1], u[0]])]
    # first along the lobe arc, counter-clockwise from the springer (angle 0 about c1)
    angs = [math.atan2(k[1] - c1[1], k[0] - c1[0]) % (2 * math.pi) for k in cands]
    k_pt = cands[int(np.argmin(angs))]
    ang_k = min(angs)
    if not (0.0 < ang_k < math.pi) or k_pt[0] <= arch.mid:
        raise ParameterError("lobe", lobe, "a side lobe whose cusp lies inside the arch, right of the axis",
                             f"with split={split:g} and upper={upper:g}")
    lobe_r = arc_between(c1, np.array([arch.right, arch.springing]), k_pt, ccw=True)
    upper_close_r = arc_between(c2, k_pt, s_pt, ccw=True)
    if upper_close_r.sweep > math.pi:
        raise ParameterError("upper", upper, "an upper lobe that closes below the split point",
                             f"with split={split:g} and lobe={lobe:g}")
    top_r = Arc(cr, r, th_s, a_apex - th_s)
    # mirror for the left side
    mir = np.array([[-1.0, 0.0], [0.0, 1.0]])
    off = np.array([2.0 * arch.mid, 0.0])
    right_side = [lobe_r, upper_close_r, top_r]
    left_side = [c.transformed(mir, off).reversed() for c in reversed(right_side)]
    head: list[Curve] = [*right_side, *left_side]
    if arch.bottom is None:
        return tuple(head)
    lt, rt, y, b = arch.left, arch.right, arch.springing, arch.bottom
    return (Line((lt, b), (rt, b)), Line((rt, b), (rt, y)), *head, Line((lt, y), (lt, b)))
