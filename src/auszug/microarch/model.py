"""The drawing model: basic curves with symmetry, marks, heights, layers.

A :class:`Drawing` is what a user gives (paper sec. 4.2): a set of basic curves,
each with its own symmetry group, plus heights. It is an immutable value; the
editing operations of :mod:`auszug.microarch.edit` return new drawings.

A basic curve is a polyline of top-view *segments* (lines, arcs given by a
tangent handle, or cubic Beziers) between *vertices*; each vertex carries a mark
that fixes its height:

``"ground"``
    on its layer's bottom (the paper's circle and diamond marks);
``"apex"``
    at the curve's apex height;
``"free"``
    a free end: the segment from an apex to it descends (suppl. C).

A segment from a ground vertex to an apex vertex (either direction) is an
**ogee**; from an apex to a free vertex a **free end**; between two vertices of
equal mark a **level** segment (horizontal, found in legacy drawings).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import lru_cache
from typing import Any, Literal, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.errors import DrawingError, GeometryError
from auszug.geometry import TOL, Curve, Line, arc_from_tangent
from auszug.geometry.symmetry import SymmetryGroup
from auszug.limits import LIMITS, check_count, check_number, shown

__all__ = [
    "Mark",
    "AxisRule",
    "Segment",
    "Symmetry",
    "BasicCurve",
    "Drawing",
    "Source",
]

Mark = Literal["ground", "apex", "free"]
AxisRule = Literal["first point", "last point", "y axis", "fixed"]
MARKS: tuple[str, ...] = ("ground", "apex", "free")

Array = NDArray[np.float64]


@dataclass(frozen=True)
class Segment:
    """How one top-view segment between two vertices is drawn.

    Attributes
    ----------
    kind : {"line", "arc", "bezier"}
        ``"arc"``: one circular arc whose tangent at the segment's first vertex
        points to ``handles[0]`` (the corpus' A, T, B form; a line if collinear).
        ``"bezier"``: cubic with absolute inner control points ``handles[0:2]``.
    handles : tuple of (2,) tuples
        Absolute positions (drawing units).
    """

    kind: Literal["line", "arc", "bezier"] = "line"
    handles: tuple[tuple[float, float], ...] = ()

    def __post_init__(self) -> None:
        need = {"line": 0, "arc": 1, "bezier": 2}.get(self.kind)
        if need is None:
            raise DrawingError(f"segment kind must be line, arc or bezier, got {self.kind!r}")
        if len(self.handles) != need:
            raise DrawingError(f"a {self.kind} segment needs {need} handle(s), got {len(self.handles)}")
        hs = tuple((float(h[0]), float(h[1])) for h in self.handles)
        if not all(math.isfinite(c) and abs(c) <= LIMITS.coordinate for h in hs for c in h):
            for h in hs:
                for c in h:
                    check_number("segment handle coordinate", c)
        object.__setattr__(self, "handles", hs)

    def curve(self, p0: ArrayLike, p1: ArrayLike) -> Curve:
        """The top-view curve from ``p0`` to ``p1``."""
        a, b = np.asarray(p0, dtype=float), np.asarray(p1, dtype=float)
        return _segment_curve(self, (float(a[0]), float(a[1])), (float(b[0]), float(b[1])), False)

    def _make(self, p0: ArrayLike, p1: ArrayLike) -> Curve:
        if self.kind == "line":
            return Line(p0, p1)
        if self.kind == "arc":
            return arc_from_tangent(p0, self.handles[0], p1)
        from auszug.geometry.bezier import CubicBezier

        return CubicBezier(p0, self.handles[0], self.handles[1], p1)


def _segment_curve(seg: Segment, p0: tuple, p1: tuple, flip: bool) -> Curve:
    """The curve of a segment between two points, built once.

    Curves are immutable values: the same segment between the same points is built
    once (interactive rebuilds reuse the curves an edit did not touch).
    """
    return _cached_curve(seg, p0, p1, flip, (TOL.zero, TOL.collinear))


@lru_cache(maxsize=1024)
def _group(fold: int, mirror: bool, center: tuple, axis: tuple) -> SymmetryGroup:
    return SymmetryGroup(fold, mirror, center, axis)


@lru_cache(maxsize=1024)
def _group_matrices(group: SymmetryGroup) -> Array:
    m = group.matrices()
    m.setflags(write=False)
    return m


@lru_cache(maxsize=8192)
def _cached_curve(seg: Segment, p0: tuple, p1: tuple, flip: bool, tol: tuple) -> Curve:
    c = seg._make(p0, p1)
    return c.reversed() if flip else c


@dataclass(frozen=True)
class Symmetry:
    """A basic curve's symmetry: C_n(center), optionally with the mirror sigma_d.

    Attributes
    ----------
    fold : int
        n >= 1, rotations by 2 pi k / n about ``center``.
    mirror : bool
        Whether the mirror through ``center`` along ``axis`` belongs to the group.
    axis : (2,) tuple
        Direction of the mirror axis (any non-zero length; the axis passes
        through ``center``).
    center : (2,) tuple
        Centre of rotation (the corpus always uses the origin).
    axis_rule : {"first point", "last point", "y axis", "fixed"}
        Editing hint: what the axis follows when the curve's points move.
    """

    fold: int = 1
    mirror: bool = False
    axis: tuple[float, float] = (0.0, 1.0)
    center: tuple[float, float] = (0.0, 0.0)
    axis_rule: AxisRule = "fixed"

    def __post_init__(self) -> None:
        try:
            whole = not isinstance(self.fold, bool) and int(self.fold) == self.fold
        except (TypeError, ValueError, OverflowError):
            whole = False
        if not whole or self.fold < 1:
            raise DrawingError(f"rotation fold must be an integer >= 1, got {shown(self.fold)}")
        check_count("rotation fold", int(self.fold), "fold")
        object.__setattr__(self, "fold", int(self.fold))
        ax = (float(self.axis[0]), float(self.axis[1]))
        ce = (float(self.center[0]), float(self.center[1]))
        if not all(math.isfinite(v) for v in ax + ce):
            raise DrawingError("symmetry axis and centre must be finite")
        for v in ax + ce:
            check_number("symmetry axis or centre coordinate", v)
        if self.mirror and math.hypot(*ax) <= 1e-12:
            raise DrawingError("mirror axis has zero length (reflection point at the centre)")
        if self.axis_rule not in ("first point", "last point", "y axis", "fixed"):
            raise DrawingError(f"unknown mirror axis rule {self.axis_rule!r}")
        object.__setattr__(self, "axis", ax)
        object.__setattr__(self, "center", ce)

    @property
    def group(self) -> SymmetryGroup:
        """The kernel's symmetry group C_n(center) (+ sigma_axis) of this curve."""
        return _group(self.fold, self.mirror, self.center, self.axis if self.mirror else (0.0, 1.0))

    @property
    def order(self) -> int:
        """Number of group elements (replicas of a basic curve, itself included)."""
        return self.group.order

    def matrices(self) -> Array:
        """Linear parts about :attr:`center`, shape (order, 2, 2), read-only.

        Ordered r0, r0m, r1, r1m, ... (``m`` = mirror applied before the rotation)
        when mirrored, else r0, r1, ...
        """
        return _group_matrices(self.group)

    def labels(self) -> list[str]:
        """Replica labels in the order of :meth:`matrices`: ``r0``, ``r0m``, ``r1``, ..."""
        return self.group.labels()

    def apply(self, points: ArrayLike) -> Array:
        """All images of ``points`` (..., 2) -> (order, ..., 2)."""
        return self.group.apply(points)


@dataclass(frozen=True)
class Source:
    """Where a basic curve was read from, so that messages name what the user wrote.

    Not part of the drawing's value: curves compare and hash without it.

    Attributes
    ----------
    line : int or None
        The line where the curve starts in its file.
    height_line : int or None
        The line of its apex height, if the file stores one.
    points : tuple of int
        The file's own number of each vertex (a web ``.uc`` curve A, T, B, T2,
        C has its vertices at points 0, 2, 4).
    point_lines : tuple of int
        The line of each vertex.
    """

    line: int | None = None
    height_line: int | None = None
    points: tuple[int, ...] = ()
    point_lines: tuple[int, ...] = ()

    def segment(self, i: int) -> str:
        """``"points 2 to 4, line 7"``: segment ``i`` in the file's terms ("" if unknown)."""
        if i + 1 >= len(self.points):
            return ""
        text = f"points {self.points[i]} to {self.points[i + 1]}"
        if i < len(self.point_lines):
            text += f", line {self.point_lines[i]}"
        return text


@dataclass(frozen=True)
class BasicCurve:
    """One basic curve of a drawing (paper sec. 4.2) with its heights.

    Attributes
    ----------
    vertices : tuple of (x, y)
        m >= 2 top-view vertices (drawing units).
    segments : tuple of Segment
        m - 1 segments joining consecutive vertices.
    marks : tuple of Mark
        One per vertex.
    symmetry : Symmetry
    layer : int
        Layer index (>= 0).
    height : float or None
        Absolute height of the apex vertices; ``None``: the drawing's default.
    prc : tuple of (float or None)
        Per segment: the point of reverse curvature of an ogee segment as a
        fraction in (0, 1) of its top-view arc length, measured from its ground
        end; ``None`` means automatic (Algorithm 1). Ignored for other kinds.
    decoration : bool
        Split the lower side-view arc of the ogee into two arcs of equal radius.
    decoration_at : float or None
        Where the two decoration arcs meet, as a fraction of the ogee's top-view
        arc length from its bottom (below the PRC); ``None``: half way to the PRC.
    post_top : float or None
        Absolute height of a vertical post rising from the apex.
    name : str
        Optional label.
    source : Source or None
        Where a reader found the curve (not part of its value).
    """

    vertices: tuple[tuple[float, float], ...]
    segments: tuple[Segment, ...]
    marks: tuple[str, ...]
    symmetry: Symmetry = field(default_factory=Symmetry)
    layer: int = 0
    height: float | None = None
    prc: tuple[float | None, ...] = ()
    decoration: bool = False
    decoration_at: float | None = None
    post_top: float | None = None
    name: str = ""
    source: Source | None = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        vs = tuple((float(v[0]), float(v[1])) for v in self.vertices)
        if len(vs) < 2:
            raise DrawingError(f"a basic curve needs at least 2 points, got {len(vs)}")
        if not all(math.isfinite(c) and abs(c) <= LIMITS.coordinate for v in vs for c in v):
            for i, v in enumerate(vs):
                for c in v:
                    check_number(f"point {i}: coordinate", c)
        check_count("segments in one curve:", len(vs) - 1, "segments")
        object.__setattr__(self, "vertices", vs)
        segs = tuple(self.segments)
        if len(segs) != len(vs) - 1:
            raise DrawingError(f"{len(vs)} points need {len(vs) - 1} segments, got {len(segs)}")
        object.__setattr__(self, "segments", segs)
        if len(self.marks) != len(vs):
            raise DrawingError(f"{len(vs)} points need {len(vs)} marks, got {len(self.marks)}")
        for mk in self.marks:
            if mk not in MARKS:
                raise DrawingError(f"unknown point mark {mk!r}; expected one of {MARKS}")
        object.__setattr__(self, "marks", tuple(self.marks))
        prc = tuple(self.prc) if self.prc else (None,) * len(segs)
        if len(prc) != len(segs):
            raise DrawingError(f"need one PRC entry per segment ({len(segs)}), got {len(prc)}")
        for f in prc:
            if f is not None and not (0.0 < float(f) < 1.0):
                raise DrawingError(f"PRC fraction must lie strictly between 0 and 1, got {f}")
        object.__setattr__(self, "prc", tuple(None if f is None else float(f) for f in prc))
        if self.decoration_at is not None and not 0.0 < float(self.decoration_at) < 1.0:
            raise DrawingError(f"decoration point must lie strictly inside the curve, got {self.decoration_at}")
        try:
            whole = not isinstance(self.layer, bool) and int(self.layer) == self.layer
        except (TypeError, ValueError, OverflowError):
            whole = False
        if not whole or self.layer < 0:
            raise DrawingError(f"layer must be an integer >= 0, got {shown(self.layer)}")
        if self.layer >= LIMITS.layers:
            raise DrawingError(f"layer {shown(self.layer)} is above the limit of {LIMITS.layers - 1} "
                               f"({LIMITS.layers} layers, auszug.limits.LIMITS.layers)")
        object.__setattr__(self, "layer", int(self.layer))
        for nm in ("height", "post_top"):
            v = getattr(self, nm)
            if v is not None:
                object.__setattr__(self, nm, check_number("apex height" if nm == "height" else "post top", v))
        for i in range(len(vs) - 1):
            if math.hypot(vs[i + 1][0] - vs[i][0], vs[i + 1][1] - vs[i][1]) <= 1e-12:
                raise DrawingError(f"points {i} and {i + 1} coincide: zero-length segment")
        for i, (a, b) in enumerate(zip(self.marks[:-1], self.marks[1:], strict=True)):
            if {a, b} == {"ground", "free"}:
                raise DrawingError(f"segment {i} joins a ground point to a free end; "
                                   "a free end must follow an apex")

    # -- derived -----------------------------------------------------------------------
    def segment_kind(self, i: int) -> Literal["ogee", "free_end", "level"]:
        """What segment ``i`` is, from the marks of its end vertices."""
        a, b = self.marks[i], self.marks[i + 1]
        if {a, b} == {"ground", "apex"}:
            return "ogee"
        if {a, b} == {"apex", "free"}:
            return "free_end"
        return "level"

    def top_curve(self, i: int, oriented: bool = False) -> Curve:
        """Top-view curve of segment ``i`` from vertex i to vertex i + 1.

        With ``oriented``, ogees run from their ground end and free ends from
        their apex (the direction of the side view).
        """
        flip = False
        if oriented:
            kind = self.segment_kind(i)
            flip = (kind == "ogee" and self.marks[i] == "apex") or (kind == "free_end" and self.marks[i] == "free")
        try:
            return _segment_curve(self.segments[i], self.vertices[i], self.vertices[i + 1], flip)
        except GeometryError as e:
            raise DrawingError(f"segment {i}: {e}") from None

    def with_(self, **changes: Any) -> "BasicCurve":
        """A copy with some fields replaced (validated again)."""
        return replace(self, **changes)


@dataclass(frozen=True)
class Drawing:
    """A top-view drawing: basic curves, layers and heights (paper sec. 4.2-4.3).

    Attributes
    ----------
    curves : tuple of BasicCurve
    layer_bottoms : tuple of float
        Absolute bottom height of every layer 0..L-1 (L = max layer + 1). Empty:
        derived (bottom(0) = 0, bottom(l) = highest apex of layer l - 1).
    name : str
        Drawing name (file stem).
    default_apex : float or None
        Apex height of curves that store none; ``None``: the bottom of the next
        layer, or bottom + 1 for the top layer.
    """

    curves: tuple[BasicCurve, ...]
    layer_bottoms: tuple[float, ...] = ()
    name: str = ""
    default_apex: float | None = None

    def __post_init__(self) -> None:
        cs = tuple(self.curves)
        object.__setattr__(self, "curves", cs)
        check_count("basic curves:", len(cs), "curves")
        check_count("segments in the drawing:", sum(len(c.segments) for c in cs), "segments")
        check_count("network curves (segments times symmetry order):",
                    sum(len(c.segments) * c.symmetry.order for c in cs), "network_curves")
        lb = tuple(float(z) for z in self.layer_bottoms)
        if not all(math.isfinite(z) and abs(z) <= LIMITS.coordinate for z in lb):
            for i, z in enumerate(lb):
                check_number(f"bottom of layer {i}", z)
        check_count("layer bottoms:", len(lb), "layers")
        object.__setattr__(self, "layer_bottoms", lb)
        if self.default_apex is not None:
            object.__setattr__(self, "default_apex", check_number("default apex height", self.default_apex))

    @property
    def n_layers(self) -> int:
        """Number of layers: max layer index + 1."""
        return max((c.layer for c in self.curves), default=0) + 1

    def bottoms(self) -> tuple[float, ...]:
        """Bottom height of every layer, derived where not stored."""
        n = max((c.layer for c in self.curves), default=0) + 1
        if len(self.layer_bottoms) >= n:
            return self.layer_bottoms[:n]
        out = list(self.layer_bottoms)
        while len(out) < n:
            lower = len(out) - 1
            if lower < 0:
                out.append(0.0)
                continue
            hs = [c.height for c in self.curves if c.layer == lower and c.height is not None]
            out.append(max(hs) if hs else out[-1] + 1.0)
        return tuple(out)

    def all_bottoms(self) -> tuple[float, ...]:
        """:meth:`bottoms`, followed by the stored bottoms of empty layers above the highest used one.

        Examples
        --------
        >>> c = BasicCurve(((0, 0), (1, 0)), (Segment(),), ("ground", "apex"), height=1.0)
        >>> d = Drawing((c,), (0.0, 1.0, 2.5))
        >>> d.bottoms(), d.all_bottoms()
        ((0.0,), (0.0, 1.0, 2.5))
        """
        b = self.bottoms()
        return b + tuple(float(z) for z in self.layer_bottoms[len(b):])

    def apex_height(self, i: int, bottoms: Sequence[float] | None = None) -> float:
        """Absolute apex height of curve ``i`` (stored or default)."""
        c = self.curves[i]
        if c.height is not None:
            return c.height
        if self.default_apex is not None:
            return self.default_apex
        b = self.bottoms() if bottoms is None else bottoms
        if c.layer + 1 < len(b):
            return b[c.layer + 1]
        return b[c.layer] + 1.0

    def with_curve(self, i: int, curve: BasicCurve) -> "Drawing":
        """A copy with curve ``i`` replaced."""
        cs = list(self.curves)
        cs[i] = curve
        return replace(self, curves=tuple(cs))
