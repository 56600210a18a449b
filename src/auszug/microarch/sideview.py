"""Side views (paper sec. 4.3.2): ogee biarcs over the horizontal side-view coordinate.

A side view lives in the (g, z) plane, g the horizontal side-view coordinate
p(u) of Eq. (1) measured from the segment's lower end (arc length by default)
and z the absolute height. It is a chain of circular arcs, each the graph of a
function z(g) over its g-interval, so every top-view point gets one height.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from auszug.errors import DrawingError
from auszug.geometry.heights import SideView

__all__ = ["SideView", "ogee", "decorated", "free_end"]

Array = NDArray[np.float64]


def _arc_radius(dg: float, dz: float) -> float:
    """Radius of the circle through (0, 0) with vertical tangent there and through (dg, dz)."""
    return (dg * dg + dz * dz) / (2.0 * dg)


def ogee(extent: float, z0: float, z1: float, g_prc: float) -> SideView:
    """The ogee side view with vertical end tangents (Remark 1).

    Parameters
    ----------
    extent : float
        Horizontal extent G > 0 of the side view (top-view arc length by default).
    z0, z1 : float
        Heights of the lower end A and the apex B, z1 > z0.
    g_prc : float
        Side-view coordinate of the PRC, 0 < g_prc < G; its height lies on the
        chord A^s B^s (Remark 1).

    Returns
    -------
    SideView
        Two arcs: the lower centred on the horizontal through A, the upper on
        the horizontal through B; G1 at the PRC.

    Examples
    --------
    >>> from auszug.microarch.sideview import ogee
    >>> sv = ogee(2.0, 0.0, 2.0, 1.0)    # symmetric: two quarter circles of radius 1
    >>> sv.radii.tolist(), float(sv.height(1.0))
    ([1.0, 1.0], 1.0)
    """
    if not (extent > 0.0 and math.isfinite(extent)):
        raise DrawingError(f"side view needs a positive horizontal extent, got {extent}")
    if not z1 > z0:
        raise DrawingError(f"apex height {z1:g} is not above the bottom {z0:g}")
    if not 0.0 < g_prc < extent:
        raise DrawingError(f"PRC must lie strictly inside the curve (0 < {g_prc:g} < {extent:g})")
    zc = z0 + (z1 - z0) * g_prc / extent
    ra = _arc_radius(g_prc, zc - z0)
    rb = _arc_radius(extent - g_prc, z1 - zc)
    return SideView(
        breaks=np.array([0.0, g_prc, extent]),
        centers=np.array([[ra, z0], [extent - rb, z1]]),
        radii=np.array([ra, rb]),
        upper=np.array([1.0, -1.0]),
        vertical=np.array([0.0, extent]),
    )


def decorated(base: SideView, g_split: float) -> tuple[SideView, tuple[float, float]]:
    """Split the lower arc of an ogee into two decorative arcs of equal radius (suppl. C).

    The lower arc A..C (vertical tangent at the bottom A, the ogee's tangent at
    the PRC C) is replaced by two arcs of one radius r that keep its end points
    and end tangents, so the curve stays G1 at A and at C and its top view is
    unchanged. Two arcs of equal radius joined G1 would either be the original
    arc (same turning) or fold back over the top view (reverse turning: the only
    solution with r > 0 starts by moving backwards), so the two arcs meet in a
    cusp D pointing upwards: the decoration of the teaching sheet (U.XI.11 (2,3),
    paper Fig. C.8). The free parameter r is fixed by where the cusp lies:
    ``g_split``.

    Parameters
    ----------
    base : SideView
        An ogee from :func:`ogee`.
    g_split : float
        Side-view coordinate of the cusp, 0 < g_split < g_prc. Where the cusp
        would lie so high that the second arc folds back, the highest admissible
        cusp is used (the second arc then starts vertically).

    Returns
    -------
    SideView
        Three arcs: the two decoration arcs and the ogee's upper arc.
    (g_d, z_d) : tuple of float
        The cusp.

    Raises
    ------
    DrawingError
        If no split at ``g_split`` exists.
    """
    from auszug.geometry.roots import find_root

    gc = float(base.breaks[1])
    G = float(base.breaks[2])
    ra = float(base.radii[0])
    z0 = float(base.centers[0, 1])
    zc = float(base.height(gc))
    if not 0.0 < g_split < gc:
        raise DrawingError(f"decoration point must lie between the bottom and the PRC (0 < {g_split:g} < {gc:g})")
    c = np.array([gc, zc])
    tc = np.array([zc - z0, ra - gc]) / ra        # unit tangent at C of the clockwise lower arc
    right = np.array([tc[1], -tc[0]])             # towards the centre of a clockwise arc

    def cusp(r: float) -> tuple[Array, Array, Array]:
        """Centres of both arcs of radius r and their upper-left intersection D."""
        o1 = np.array([r, z0])
        o2 = c + r * right
        v = o2 - o1
        d = math.hypot(v[0], v[1])
        h = math.sqrt(max(r * r - d * d / 4.0, 0.0))
        return o1, o2, (o1 + o2) / 2.0 + h * np.array([-v[1], v[0]]) / d

    def gap(r: float) -> float:                   # > 0 while the circles are apart
        o1, o2, _ = cusp(r)
        return math.hypot(*(o2 - o1)) - 2.0 * r

    # circles of radius r meet for r in (r_touch, ra); at ra they coincide (the plain arc)
    r_hi = ra * (1.0 - 1e-9)
    lo = 1e-9 * ra
    if gap(lo) <= 0.0:
        raise DrawingError("cannot decorate this ogee: its lower arc is degenerate")
    r_touch = find_root(gap, lo, r_hi, xtol=1e-15)
    # the second arc must start on the upper half of its circle (else it folds back):
    # the largest admissible cusp is where D is the leftmost point of circle 2
    def level(r: float) -> float:
        _, o2, d = cusp(r)
        return d[1] - o2[1]

    r_lo = r_touch if level(r_touch * (1 + 1e-12)) >= 0.0 else find_root(level, r_touch * (1 + 1e-12), r_hi, xtol=1e-15)
    g_max = float(cusp(r_lo)[2][0])
    g_min = float(cusp(r_hi)[2][0])
    if g_split < g_min:
        raise DrawingError(f"decoration point g = {g_split:g} is too low: it must lie in [{g_min:g}, {g_max:g}]")
    if g_split >= g_max:
        # the nearest admissible decoration: the second arc starts vertically at the cusp
        r = r_lo
    else:
        r = find_root(lambda rr: float(cusp(rr)[2][0]) - g_split, r_lo, r_hi, xtol=1e-15)
    o1, o2, d = cusp(float(r))
    sv = SideView(
        breaks=np.array([0.0, d[0], gc, G]),
        centers=np.array([o1, o2, base.centers[1]]),
        radii=np.array([r, r, base.radii[1]]),
        upper=np.array([1.0, 1.0, -1.0]),
        vertical=np.array([0.0, o2[0] - r, base.vertical[1]]),
    )
    return sv, (float(d[0]), float(d[1]))


def free_end(base: SideView) -> SideView:
    """The side view of a free end after the ogee ``base`` (suppl. C).

    One arc leaves the apex with a vertical tangent and descends: the mirror
    image of the ogee's upper arc, continued on its circle (radius r_B, centre
    on the horizontal through the apex). This is also what the authors' demo
    draws. It is a graph over g up to g = 2 r_B.
    """
    rb = float(base.radii[-1])
    z1 = float(base.centers[-1, 1])
    return SideView(
        breaks=np.array([0.0, 2.0 * rb]),
        centers=np.array([[rb, z1]]),
        radii=np.array([rb]),
        upper=np.array([-1.0]),
        vertical=np.array([0.0]),
    )
