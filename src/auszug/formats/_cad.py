"""What the CAD writers (DXF, Rhino .3dm) share: the network's curves with their exact parts.

Every network curve is its piece under one symmetry element: the top view is
mapped by ``xy -> M (xy - c) + c`` (``M`` the element's 2x2 transform, ``c``
the group's centre), the height is kept. A piece's exact parts map the same
way: a :class:`~auszug.geometry.network.CircularRun`'s centre, start and end
as points, its plane normal as an axial vector, ``n' = det(M3) M3 n`` with
``M3 = [[M, 0], [0, 1]]``. A reflection reverses the sense of rotation about
the plainly mapped normal, and the factor ``det(M3) = -1`` turns the normal
round again, so every mapped arc still turns counter-clockwise about its
normal from its start to its end: exactly what DXF ARC entities (about their
extrusion) and Rhino arcs (about their plane's z axis) need.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Iterator

import numpy as np
from numpy.typing import NDArray

from auszug.errors import FormatError
from auszug.geometry.network import CircularRun, CurveNetwork, NetworkCurve, as_curve_network

__all__ = ["Arc3", "CadCurve", "network_and_source", "cad_curves", "map_run"]

Array = NDArray[np.float64]


@dataclass(frozen=True)
class Arc3:
    """A planar circular arc in 3D, counter-clockwise about ``normal`` from ``start`` to ``end``."""

    center: Array
    normal: Array
    radius: float
    start: Array
    end: Array
    angle: float


@dataclass(frozen=True)
class CadCurve:
    """A network curve and its exact description, if it has one.

    Attributes
    ----------
    curve : NetworkCurve
    arcs : tuple of Arc3
        The piece's circular runs mapped to this replica (covering the whole
        curve, in order), or empty.
    line : (2, 3) ndarray or None
        Start and end of a straight curve (post, pillar, level line), else None.
    """

    curve: NetworkCurve
    arcs: tuple[Arc3, ...] = ()
    line: Array | None = None

    @property
    def exact(self) -> bool:
        """Whether the whole curve has an exact description (arcs or a line)."""
        return bool(self.arcs) or self.line is not None


def network_and_source(obj: Any) -> tuple[CurveNetwork, str]:
    """The curve network and the source file name of a NetworkFile, a Network or a CurveNetwork."""
    from auszug.formats.network_json import NetworkFile, unpack

    if isinstance(obj, NetworkFile) and isinstance(obj.network, CurveNetwork):
        return obj.network, obj.source or obj.network.name
    if isinstance(obj, CurveNetwork):
        return obj, obj.name
    net, source = unpack(obj)
    return as_curve_network(net), source


def map_run(run: CircularRun, m: Array, c: Array) -> Arc3:
    """A circular run (in the piece's coordinates) under ``xy -> m (xy - c) + c``, z kept."""
    m3 = np.eye(3)
    m3[:2, :2] = m
    det = float(np.linalg.det(m3))
    sign = 1.0 if det > 0.0 else -1.0     # the elements are orthogonal: det is +-1

    def point(p: Array) -> Array:
        p = np.asarray(p, dtype=float)
        return np.array([*(m @ (p[:2] - c) + c), p[2]])

    n = sign * (m3 @ np.asarray(run.normal, dtype=float))
    return Arc3(point(run.center), n / np.linalg.norm(n), float(run.radius), point(run.start),
                point(run.end), float(run.angle))


def _angle(center: Array, normal: Array, start: Array, end: Array) -> float:
    a, b = start - center, end - center
    ang = float(np.arctan2(np.dot(np.cross(a, b), normal), np.dot(a, b)))
    return ang if ang > 0.0 else ang + 2.0 * np.pi


def _joined(arcs: tuple[Arc3, ...]) -> tuple[Arc3, ...]:
    """The arcs with each joint where two circles cross moved onto both circles.

    A run's end point is the piece evaluated at the run's end, which at a
    vertical tangent of the side view (a decoration's cusp) lies up to about
    ``sqrt(2 r eps g)`` (~1e-8 of the size) along the *next* arc: one ulp of g
    moves the height that much. Where the two circles cross, their
    intersection next to that point is the joint, exact to float precision,
    so the arcs then meet without a gap; where they touch (a smooth join) the
    point already lies on both, up to rounding.
    """
    if len(arcs) < 2:
        return arcs
    joints = [a.end for a in arcs[:-1]]
    for i, (a, b) in enumerate(zip(arcs[:-1], arcs[1:], strict=False)):
        e = b.center - a.center
        d = float(np.linalg.norm(e))
        if d == 0.0 or abs(float(np.dot(a.normal, b.normal))) < 1.0 - 1e-12:
            continue
        e = e / d
        x = (a.radius ** 2 - b.radius ** 2 + d * d) / (2.0 * d)
        h2 = a.radius ** 2 - x * x
        if not h2 > (1e-6 * min(a.radius, b.radius)) ** 2:   # touching (or apart): keep the point
            continue
        f = np.cross(a.normal, e)
        base = a.center + x * e
        p = joints[i]
        cand = [base + math.sqrt(h2) * f, base - math.sqrt(h2) * f]
        q = min(cand, key=lambda v: float(np.linalg.norm(v - p)))
        if np.linalg.norm(q - p) <= 1e-6 * max(a.radius, b.radius):
            joints[i] = q
    out = []
    for i, a in enumerate(arcs):
        s = a.start if i == 0 else joints[i - 1]
        t = a.end if i == len(arcs) - 1 else joints[i]
        out.append(Arc3(a.center, a.normal, a.radius, s, t, _angle(a.center, a.normal, s, t)))
    return tuple(out)


def cad_curves(net: CurveNetwork, source: str = "") -> Iterator[CadCurve]:
    """Every curve of ``net`` with its exact parts, after checking all numbers are finite.

    Raises
    ------
    FormatError
        If a coordinate of a curve or of an exact part is not finite (checked for
        all curves before the first is yielded, so a writer makes nothing).
    """
    runs = [p.circular_runs() for p in net.pieces]
    straight = [p.is_straight() for p in net.pieces]
    out: list[CadCurve] = []
    for c in net.curves():
        pts = np.asarray(c.points, dtype=float)
        if not np.all(np.isfinite(pts)):
            raise FormatError(f"curve {c.id} has non-finite coordinates; cannot write it", source)
        if len(pts) < 2:
            raise FormatError(f"curve {c.id} has fewer than 2 points; cannot write it", source)
        centre = np.asarray(net.groups[c.basic].center, dtype=float)
        m = np.asarray(c.transform, dtype=float)
        arcs = _joined(tuple(map_run(r, m, centre) for r in runs[c.piece]))
        for a in arcs:
            if not all(np.all(np.isfinite(v)) for v in (a.center, a.normal, a.start, a.end, a.radius)):
                raise FormatError(f"an arc of curve {c.id} has non-finite numbers; cannot write it", source)
        line = pts[[0, -1]].copy() if straight[c.piece] and not arcs else None
        out.append(CadCurve(c, arcs, line))
    return iter(out)
