"""The prototype window: outer arch, two sub-arches, the rosette circle and four fillets.

Havemann and Fellner's ``gothic-window`` (2004, sec. 2.2-2.4 and 3.5), here as
an exact construction with lines and arcs:

1. The outer arch ``A`` over the window's span, with jambs down to the sill.
2. The ensemble ``E``: ``A`` offset inwards by ``outer`` (same centres).
3. Two sub-arches of the same excess split ``E``'s width at the axis, their
   springing line ``drop`` below ``A``'s.
4. The rosette circle touches ``E``'s arcs from inside and the inner arcs of
   both sub-arches from outside. Its centre ``m_C`` is equidistant from the
   circle (``m_R``, ``r_E``) and the circle (``m_LR``, ``r_s``), so
   ``|m_C - m_R| + |m_C - m_LR| = r_E + r_s``: ``m_C`` is where the ellipse
   with foci ``m_R``, ``m_LR`` and this radius sum meets the axis (Fig. 6).
5. The sub-arches and the circle cut ``E`` into seven cells: two sub-arches,
   the circle and four fillets (top, bottom, left, right), each fillet bounded
   by three arcs of ``E``, the circle and the sub-arches (plus a piece of
   ``E``'s jamb when the drop is large).
6. Every cell is offset inwards by ``inner``: the regions (openings), seven
   polygons inside the arch region; with the arch, the paper's eight.

Coordinates: x to the right, y up; the sill's midpoint is ``(x, y)``, the
springing line at ``y + height``. The paper's call ``(-1,0,2) (1,0,2) 4.0 1.25
(0,-1,0) 0.2 0.1 0.05 gothic-window`` is ``WindowParams(span=2, height=4,
excess=1.25, drop=0.2, outer=0.1, inner=0.05)`` shifted by 2 in y (their
springers lie at height 2, 4 above the sill).

Examples
--------
>>> from auszug.tracery.window import WindowParams, prototype
>>> w = prototype(WindowParams(span=2, height=4, excess=1.25, drop=0.2, outer=0.1, inner=0.05))
>>> sorted(w.cells)
['circle', 'fillet-bottom', 'fillet-left', 'fillet-right', 'fillet-top', 'sub-arch-left', 'sub-arch-right']
>>> w.tangency_residual() < 1e-9
True
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from functools import cached_property
from typing import Any, Mapping

import numpy as np
from numpy.typing import NDArray

from auszug.errors import GeometryError
from auszug.geometry import Arc, Curve, Line
from auszug.geometry.offset import offset_curves
from auszug.limits import LIMITS
from auszug.tracery._checks import ParameterError, number
from auszug.tracery.arch import PointedArch, arc_between

__all__ = ["WindowParams", "Prototype", "prototype", "ellipse_axis_point", "CELLS"]

Array = NDArray[np.float64]

#: The seven cells of the prototype window in the order of the paper's polygons.
CELLS = ("sub-arch-left", "sub-arch-right", "circle", "fillet-top", "fillet-bottom", "fillet-left", "fillet-right")
GROUP = {"sub-arch-left": "sub-arch", "sub-arch-right": "sub-arch", "circle": "circle",
         "fillet-top": "fillet", "fillet-bottom": "fillet", "fillet-left": "fillet", "fillet-right": "fillet"}


@dataclass(frozen=True)
class WindowParams:
    """The high-level parameters of the prototype window (drawing units).

    Attributes
    ----------
    span : float
        Width of the window between the jambs, > 0.
    height : float
        Height of the jambs: the springing line lies this far above the sill, > 0.
    excess : float
        Excess of the arch and of the sub-arches, >= 0.5.
    drop : float
        How far the sub-arches' springing line lies below the arch's, >= 0.
    outer : float
        Width by which the ensemble is offset from the outer arch, >= 0.
    inner : float
        Border width of every region (half the width of a bar between two
        regions), > 0.
    x, y : float
        Midpoint of the sill.
    """

    span: float = 2.0
    height: float = 4.0
    excess: float = 1.25
    drop: float = 0.2
    outer: float = 0.1
    inner: float = 0.05
    x: float = 0.0
    y: float = 0.0

    def __post_init__(self) -> None:
        big = LIMITS.coordinate
        why = "the coordinate limit, auszug.limits.LIMITS.coordinate"
        for name in ("span", "height", "drop", "outer", "inner", "x", "y"):  # each blamed by its own name
            number(name, getattr(self, name), -big, big, why=why)
        number("excess", self.excess, hi=big, why=why)
        number("span", self.span, 0.0, lo_open=True)
        number("height", self.height, 0.0, lo_open=True)
        number("excess", self.excess, 0.5, why="excess 0.5 is the round arch; below it the arcs do not meet")
        number("outer", self.outer, 0.0, 0.25 * self.span, hi_open=True,
               why="the two sub-arches must keep a positive width")
        number("inner", self.inner, 0.0, 0.125 * (self.span - 2.0 * self.outer), lo_open=True, hi_open=True,
               why="a sub-arch is (span - 2 outer) / 2 wide and needs room inside its borders")
        number("inner", self.inner, 1e-6 * self.span,
               why="a border narrower than a millionth of the span is below the geometry's resolution")
        number("drop", self.drop, 0.0, self.height - self.outer - 2.0 * self.inner, hi_open=True,
               why="the sub-arches must spring above their sills")
        number("x", self.x)
        number("y", self.y)

    @classmethod
    def from_mapping(cls, values: Mapping[str, Any]) -> WindowParams:
        """Parameters from a mapping (unknown names are an error naming the known ones)."""
        known = {f.name for f in fields(cls)}
        unknown = sorted(set(values) - known)
        if unknown:
            raise ParameterError(unknown[0], values[unknown[0]],
                                 "a known window parameter: " + ", ".join(sorted(known)))
        return cls(**{k: number(k, v) for k, v in values.items()})

    def scaled(self, factor: float) -> WindowParams:
        """All lengths multiplied by ``factor`` about the origin (excess unchanged)."""
        return WindowParams(self.span * factor, self.height * factor, self.excess, self.drop * factor,
                            self.outer * factor, self.inner * factor, self.x * factor, self.y * factor)

    def arch(self) -> PointedArch:
        """The outer arch region."""
        h = 0.5 * self.span
        return PointedArch(self.x - h, self.x + h, self.y + self.height, self.excess, bottom=self.y)

    def as_dict(self) -> dict[str, float]:
        """The parameters as a plain dict."""
        return {f.name: getattr(self, f.name) for f in fields(self)}


def ellipse_axis_point(f1: Array, f2: Array, total: float, x: float) -> Array | None:
    """The upper point of the vertical line at ``x`` on the ellipse ``|p - f1| + |p - f2| = total``.

    Computed as in the paper by mapping the ellipse to the unit circle and
    intersecting the mapped line with it.

    Parameters
    ----------
    f1, f2 : (2,) array_like
        The foci.
    total : float
        The sum of the distances (twice the semi-major axis).
    x : float
        The line.

    Returns
    -------
    (2,) ndarray or None
        None if the line misses the ellipse.

    Examples
    --------
    >>> p = ellipse_axis_point(np.array([-1.0, 0.0]), np.array([1.0, 0.0]), 4.0, 0.0)
    >>> p.round(12).tolist() == [0.0, round(3 ** 0.5, 12)]
    True
    """
    f1 = np.asarray(f1, float)
    f2 = np.asarray(f2, float)
    c = 0.5 * (f1 + f2)
    e = f2 - f1
    fc = 0.5 * math.hypot(e[0], e[1])
    a = 0.5 * total
    if a <= fc:
        return None
    b = math.sqrt(a * a - fc * fc)
    u = e / (2.0 * fc) if fc > 0 else np.array([1.0, 0.0])
    v = np.array([-u[1], u[0]])
    # line p(t) = (x, t): in ellipse coordinates (X/a, Y/b)
    p0 = np.array([x, 0.0]) - c
    X0, Y0 = p0 @ u / a, p0 @ v / b
    Xt, Yt = u[1] / a, v[1] / b
    qa = Xt * Xt + Yt * Yt
    qb = 2.0 * (X0 * Xt + Y0 * Yt)
    qc = X0 * X0 + Y0 * Y0 - 1.0
    disc = qb * qb - 4.0 * qa * qc
    if disc < 0.0:
        return None
    t = (-qb + math.sqrt(disc)) / (2.0 * qa)
    return np.array([x, t])


@dataclass(frozen=True, eq=False)
class Prototype:
    """The constructed prototype window: partition and regions, all exact.

    Attributes
    ----------
    params : WindowParams
    arch : PointedArch
        The outer arch region ``A`` (the opening in the wall).
    ensemble : PointedArch
        ``A`` offset by ``outer``.
    sub_arches : tuple of PointedArch
        Left and right sub-arch cells (with sills on the ensemble's sill).
    circle_center : (2,) ndarray
    circle_radius : float
        The rosette circle (the cell, before the inner offset).
    tangency : dict of str to (2,) ndarray
        Where the circle touches ``E`` (``"arch-left"``, ``"arch-right"``) and
        the sub-arches (``"sub-arch-left"``, ``"sub-arch-right"``).
    cells : dict of str to tuple of Curve
        The seven counter-clockwise cells, keys :data:`CELLS`.
    """

    params: WindowParams
    arch: PointedArch
    ensemble: PointedArch
    sub_arches: tuple[PointedArch, PointedArch]
    circle_center: Array
    circle_radius: float
    tangency: dict[str, Array]
    cells: dict[str, tuple[Curve, ...]]

    @cached_property
    def regions(self) -> dict[str, tuple[Curve, ...]]:
        """The seven cells offset inwards by ``inner`` (the openings), keys :data:`CELLS`.

        The window is symmetric: the left fillet's opening is the right one's mirror image in
        the middle line (offset once; the two are exact mirror images).
        """
        b = self.params.inner
        out: dict[str, tuple[Curve, ...]] = {}
        for name in (*CELLS[:-2], "fillet-right", "fillet-left"):
            if name == "fillet-left":
                flip = np.array([[-1.0, 0.0], [0.0, 1.0]])
                at = np.array([2.0 * self.ensemble.mid, 0.0])
                out[name] = tuple(c.transformed(flip, at).reversed() for c in reversed(out["fillet-right"]))
            elif name.startswith("sub-arch"):
                out[name] = self.sub_region(name).curves()
            elif name == "circle":
                out[name] = (Arc(self.circle_center, self.circle_radius - b, -0.5 * math.pi, 2 * math.pi),)
            else:
                try:
                    out[name] = offset_curves(self.cells[name], b, closed=True).curves
                except GeometryError as e:
                    raise GeometryError(f"{name}: {e}") from None
        return {name: out[name] for name in CELLS}

    def sub_region(self, name: str) -> PointedArch:
        """The sub-arch region ``"sub-arch-left"`` or ``"sub-arch-right"`` (cell offset by ``inner``)."""
        return self.sub_arches[0 if name.endswith("left") else 1].offset(self.params.inner)

    def tangency_residual(self) -> float:
        """Largest deviation of the circle from touching ``E`` and the sub-arches' arcs.

        Distances from the circle centre to the four arcs (by projection on the
        arcs themselves) minus the circle radius.
        """
        c, rc = self.circle_center, self.circle_radius
        res = 0.0
        e = self.ensemble
        sl, sr = self.sub_arches
        for arc, outside in ((e.right_arc(), False), (e.left_arc(), False),
                             (sl.right_arc(), True), (sr.left_arc(), True)):
            q = arc.point(arc.project(c))
            d = float(np.hypot(*(q - c)))
            res = max(res, abs(d - rc))
            del outside
        return res


def _solve_circle(e: PointedArch, sr: PointedArch) -> tuple[Array, float] | None:
    """Centre and radius of the circle touching E's right arc (inside) and sr's left arc (outside)."""
    f1 = e.centers[1]  # centre of E's right arc
    f2 = sr.centers[0]  # centre of the right sub-arch's left arc
    mc = ellipse_axis_point(f1, f2, e.radius + sr.radius, e.mid)
    if mc is None:
        return None
    rc = e.radius - float(np.hypot(*(mc - f1)))
    return mc, rc


def prototype(params: WindowParams | None = None, arch: PointedArch | None = None, **kw: float) -> Prototype:
    """Construct the prototype window.

    Parameters
    ----------
    params : WindowParams, optional
        Default :class:`WindowParams()`; keywords override fields.
    arch : PointedArch, optional
        The outer arch region, if not ``params.arch()`` (a nested window fills
        a sub-arch, whose excess differs from the sub-arches' own).

    Returns
    -------
    Prototype

    Raises
    ------
    ParameterError
        If the parameters do not give a valid window (the message names the
        parameter and its valid range).

    Examples
    --------
    >>> w = prototype(excess=1.0, drop=0.0, outer=0.0, inner=0.05)
    >>> w.sub_arches[1].centers.round(12).tolist()   # excess 1: centres on the springers
    [[1.0, 4.0], [0.0, 4.0]]
    """
    p = params if params is not None else WindowParams()
    if kw:
        p = replace(p, **kw)
    try:
        return _construct(p, arch)
    except _Misfit as e:
        # blame the parameter the misfit names if some value of it fits, else the first that can
        for name in (e.name, *(n for n in ("drop", "excess", "inner", "outer") if n != e.name)):
            lo, hi = _valid_interval(p, name, arch)
            if lo is not None:
                break
        else:
            raise ParameterError(e.name, getattr(p, e.name),
                                 "a value for which the window fits (there is none with the other parameters)",
                                 e.why) from None
        assert hi is not None
        if name == "inner":  # its lower limit is WindowParams' own, 1e-6 span
            valid = f"a number in [{max(lo, 1e-6 * p.span):.6g}, {hi:.6g}]"
        else:
            valid = f"a number in [{0.0 if lo < 1e-6 * p.span else lo:.6g}, {hi:.6g}]"
        raise ParameterError(name, getattr(p, name), valid, e.why) from None


class _Misfit(Exception):
    """A geometric misfit blamed on one parameter (turned into a ParameterError with its range)."""

    def __init__(self, name: str, why: str) -> None:
        self.name = name
        self.why = why
        super().__init__(f"{name}: {why}")


#: Static bounds scanned for the valid range of a parameter.
def _bounds(p: WindowParams, name: str) -> tuple[float, float]:
    if name == "excess":
        return 0.5, 4.0
    if name == "drop":
        return 0.0, p.height - p.outer - 2.0 * p.inner
    if name == "outer":
        return 0.0, 0.25 * p.span
    return 1e-6 * p.span, 0.125 * (p.span - 2.0 * p.outer)  # inner (its own lower limit, see WindowParams)


def _fits(p: WindowParams, name: str, value: float, arch: PointedArch | None) -> bool:
    """Whether ``p`` with ``name = value`` gives a window (the parameters' own checks included)."""
    try:
        _construct(replace(p, **{name: value}), arch)
    except (_Misfit, ParameterError, GeometryError):
        return False
    return True


def _valid_interval(p: WindowParams, name: str, arch: PointedArch | None,
                    samples: int = 48) -> tuple[float | None, float | None]:
    """The interval of ``name`` values (others fixed) that give a valid window, nearest the given value."""
    lo, hi = _bounds(p, name)
    vs = np.linspace(lo, hi, samples + 2)[1:-1]
    ok = [_fits(p, name, float(v), arch) for v in vs]
    if not any(ok):
        return None, None
    here = float(getattr(p, name))
    idx = [i for i, o in enumerate(ok) if o]
    k = min(idx, key=lambda i: abs(vs[i] - here))
    i0 = k
    while i0 > 0 and ok[i0 - 1]:
        i0 -= 1
    i1 = k
    while i1 < len(vs) - 1 and ok[i1 + 1]:
        i1 += 1

    def edge(good: float, bad: float) -> float:
        for _ in range(30):
            mid = 0.5 * (good + bad)
            if _fits(p, name, mid, arch):
                good = mid
            else:
                bad = mid
        return good

    a = edge(float(vs[i0]), float(vs[i0 - 1]) if i0 > 0 else lo)
    b = edge(float(vs[i1]), float(vs[i1 + 1]) if i1 < len(vs) - 1 else hi)
    return a, b


def _construct(p: WindowParams, arch: PointedArch | None = None) -> Prototype:
    a = p.arch() if arch is None else arch
    e = a.offset(p.outer) if p.outer > 0 else a
    ys = a.springing - p.drop
    xm = e.mid
    sl = PointedArch(e.left, xm, ys, p.excess, bottom=e.bottom)
    sr = PointedArch(xm, e.right, ys, p.excess, bottom=e.bottom)
    # the sub-arches must stay inside E: their apex below E's arcs
    if sr.apex[1] >= e.springing and not _inside_arc(e, sr.apex):
        raise _Misfit("drop", "the sub-arches pierce the arch")
    sol = _solve_circle(e, sr)
    if sol is None or sol[1] <= 2.0 * p.inner:
        raise _Misfit("drop", "no rosette circle fits between the arch and the sub-arches")
    mc, rc = sol
    f1, f2 = e.centers[1], sr.centers[0]
    t_er = f1 + e.radius * (mc - f1) / np.hypot(*(mc - f1))
    t_sr = f2 + sr.radius * (mc - f2) / np.hypot(*(mc - f2))
    mir = np.array([-1.0, 1.0])
    t_el = (t_er - [xm, 0.0]) * mir + [xm, 0.0]
    t_sl = (t_sr - [xm, 0.0]) * mir + [xm, 0.0]
    # where the circle touches: on E's right arc below the apex, on sr's left arc
    if not (t_er[0] > xm and t_er[1] < e.apex[1]):
        raise _Misfit("drop", "the rosette circle would touch the arch at its apex")
    ang_sr = math.atan2(t_sr[1] - f2[1], t_sr[0] - f2[0])
    if not (math.pi - sr.apex_angle - 1e-12 <= ang_sr <= math.pi):
        raise _Misfit("drop", "the rosette circle would touch the sub-arches beyond their apexes")
    cells = _cells(e, sl, sr, mc, rc, t_er, t_el, t_sr, t_sl, ys)
    tang = {"arch-left": t_el, "arch-right": t_er, "sub-arch-left": t_sl, "sub-arch-right": t_sr}
    w = Prototype(p, a, e, (sl, sr), mc, rc, tang, cells)
    try:
        w.regions  # noqa: B018 - validate the offsets now
    except GeometryError as err:
        raise _Misfit("inner", str(err)) from None
    return w


def _inside_arc(e: PointedArch, q: Array) -> bool:
    cl, cr = e.centers
    return bool(np.hypot(*(q - cr)) < e.radius and np.hypot(*(q - cl)) < e.radius)


def _cells(e: PointedArch, sl: PointedArch, sr: PointedArch, mc: Array, rc: float,
           t_er: Array, t_el: Array, t_sr: Array, t_sl: Array, ys: float) -> dict[str, tuple[Curve, ...]]:
    """The seven counter-clockwise cells of E."""
    ecl, ecr = e.centers
    slc_l, slc_r = sl.centers
    src_l, src_r = sr.centers
    apex = e.apex
    m = np.array([e.mid, ys])
    cells: dict[str, tuple[Curve, ...]] = {
        "sub-arch-left": sl.curves(),
        "sub-arch-right": sr.curves(),
        "circle": (Arc(mc, rc, -0.5 * math.pi, 2.0 * math.pi),),
        "fillet-top": (
            arc_between(ecr, t_er, apex, ccw=True),
            arc_between(ecl, apex, t_el, ccw=True),
            arc_between(mc, t_el, t_er, ccw=False),
        ),
        "fillet-bottom": (
            arc_between(src_l, m, t_sr, ccw=False),
            arc_between(mc, t_sr, t_sl, ccw=False),
            arc_between(slc_r, t_sl, m, ccw=False),
        ),
    }
    jr0, jr1 = np.array([e.right, ys]), np.array([e.right, e.springing])
    jl0, jl1 = np.array([e.left, e.springing]), np.array([e.left, ys])
    right: list[Curve] = []
    left: list[Curve] = []
    if e.springing - ys > 1e-12:
        right.append(Line(jr0, jr1))
    right += [
        arc_between(ecr, jr1, t_er, ccw=True),
        arc_between(mc, t_er, t_sr, ccw=False),
        arc_between(src_l, t_sr, sr.apex, ccw=False),
        arc_between(src_r, sr.apex, jr0, ccw=False),
    ]
    left += [arc_between(ecl, t_el, jl0, ccw=True)]
    if e.springing - ys > 1e-12:
        left.append(Line(jl0, jl1))
    left += [
        arc_between(slc_l, jl1, sl.apex, ccw=False),
        arc_between(slc_r, sl.apex, t_sl, ccw=False),
        arc_between(mc, t_sl, t_el, ccw=False),
    ]
    cells["fillet-right"] = tuple(right)
    cells["fillet-left"] = tuple(left)
    return cells
