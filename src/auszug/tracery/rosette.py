"""Rosettes of round and pointed foils in a circle (Havemann and Fellner 2004, sec. 2.5).

``n`` round foils in the unit circle have radius ``sin(a/2) / (1 + sin(a/2))``
with ``a = 2 pi / n``: a foil's centre ``m`` lies at ``1 - r`` from the
centre ``c`` and the foil touches both lines from ``c`` at angles ``+-a/2``
(Fig. 9); the feet ``a``, ``b`` of the perpendiculars from ``m`` on those lines
are where neighbouring foils touch, and the foil's outer arc from ``b`` to
``a`` is copied round ``n`` times. Pointed foils move the two arc centres
from ``m`` along the lines ``(a, m)`` and ``(b, m)`` by the factor
``displacement`` (1.15 in Fig. 10), so each foil becomes a small pointed arch
lying on its side, tangent to its neighbours in ``a`` and ``b``; the rosette
is then scaled down so that the tips touch the circle.

A standing rosette has a foil on top (its axis at 90 degrees); a lying one is
turned by half a foil, so a cusp is on top.

Examples
--------
>>> from auszug.tracery.rosette import foil_radius
>>> round(foil_radius(4), 12)
0.414213562373
"""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np
from numpy.typing import ArrayLike

from auszug.geometry import Arc, Curve
from auszug.tracery._checks import choice, integer, number

__all__ = ["foil_radius", "rosette", "ORIENTATIONS"]

ORIENTATIONS = ("standing", "lying")


def foil_radius(n: int) -> float:
    """Radius of each of ``n`` round foils in the unit circle: ``s / (1 + s)``, ``s = sin(pi / n)``.

    Raises
    ------
    ParameterError
        For ``n < 2``.

    Examples
    --------
    >>> foil_radius(2), round(foil_radius(3), 12)
    (0.5, 0.464101615138)
    """
    n = integer("foils", n, 2)
    s = math.sin(math.pi / n)
    return s / (1.0 + s)


def _unit_foil(
    n: int, pointed: bool, displacement: float
) -> tuple[list[tuple[np.ndarray, float, float, float]], float]:
    """Arcs of the foil on the +x axis in the unit circle, as (centre, radius, theta0, sweep), and the scale."""
    alpha = 2.0 * math.pi / n
    r = foil_radius(n)
    m = np.array([1.0 - r, 0.0])
    half = 0.5 * alpha
    if not pointed:
        # from b (below) counter-clockwise round the outside to a (above)
        return [(m, r, -half - 0.5 * math.pi, alpha + math.pi)], 1.0
    foot = (1.0 - r) * math.cos(half)
    a = foot * np.array([math.cos(half), math.sin(half)])
    b = np.array([a[0], -a[1]])
    k = displacement
    m1 = a + k * (m - a)  # centre of the arc through a (below the axis)
    m2 = b + k * (m - b)  # centre of the arc through b (above the axis)
    rk = k * r
    # tip: on the axis, |tip - m2| = rk, outer solution
    tip_x = m2[0] + math.sqrt(max(rk * rk - m2[1] * m2[1], 0.0))
    th_b = math.atan2(b[1] - m2[1], b[0] - m2[0])
    th_tip2 = math.atan2(-m2[1], tip_x - m2[0])
    sw2 = (th_tip2 - th_b) % (2.0 * math.pi)
    th_tip1 = math.atan2(-m1[1], tip_x - m1[0])
    th_a = math.atan2(a[1] - m1[1], a[0] - m1[0])
    sw1 = (th_a - th_tip1) % (2.0 * math.pi)
    return [(m2, rk, th_b, sw2), (m1, rk, th_tip1, sw1)], 1.0 / tip_x


def rosette(
    center: ArrayLike,
    radius: float,
    foils: int,
    pointed: bool = False,
    displacement: float = 1.15,
    orientation: str = "standing",
) -> tuple[tuple[Curve, ...], ...]:
    """The foiled outline inscribed in the circle (``center``, ``radius``).

    Parameters
    ----------
    center : (2,) array_like
    radius : float
        The circle the foils touch from inside.
    foils : int
        Number of foils, >= 2.
    pointed : bool
        Pointed instead of round foils.
    displacement : float
        Pointed foils: how far the arc centres move, relative to the round
        foil's radius; > 1 (1 gives round foils).
    orientation : {"standing", "lying"}

    Returns
    -------
    tuple of loops
        Each loop a tuple of counter-clockwise arcs. For ``foils >= 3`` one
        loop (the foils touch each other in the inner points ``a``, ``b``);
        for 2 foils, which touch in the centre, one loop per foil (there
        ``a = b`` is the centre, so pointed foils come out round).

    Examples
    --------
    >>> from auszug.tracery.rosette import rosette
    >>> (loop,) = rosette((0, 0), 1.0, 4)
    >>> len(loop), max(float(np.hypot(*c.point(0.5))) for c in loop)
    (4, 1.0)
    """
    n = integer("foils", foils, 2)
    number("radius", radius, 0.0, lo_open=True)
    if pointed:
        number("displacement", displacement, 1.0, 3.0, lo_open=True,
               why="1 gives round foils; large values make needle-thin foils")
    choice("orientation", orientation, ORIENTATIONS)
    c = np.asarray(center, dtype=float)
    arcs, scale = _unit_foil(n, bool(pointed), float(displacement))
    alpha = 2.0 * math.pi / n
    phi0 = 0.5 * math.pi + (0.5 * alpha if orientation == "lying" else 0.0)
    s = radius * scale
    loops: list[list[Curve]] = []
    cur: list[Curve] = []
    for j in range(n):
        phi = phi0 + j * alpha
        cs, sn = math.cos(phi), math.sin(phi)
        foil: list[Curve] = []
        for m, r, th0, sw in arcs:
            mc = c + s * np.array([cs * m[0] - sn * m[1], sn * m[0] + cs * m[1]])
            foil.append(Arc(mc, s * r, th0 + phi, sw))
        if n == 2:
            loops.append(foil)
        else:
            cur.extend(foil)
    if n > 2:
        loops.append(cur)
    return tuple(tuple(lp) for lp in loops)


def foil_tangency_residual(loop: Sequence[Curve]) -> float:
    """Largest gap between consecutive arcs of a closed loop (0 for an exact rosette)."""
    return max(float(np.hypot(*(loop[i].end - loop[(i + 1) % len(loop)].start))) for i in range(len(loop)))
