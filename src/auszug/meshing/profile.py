"""Cross-section profiles to sweep along the curves: circles, bars, ribbons, lines and arcs.

A :class:`Profile` is a planar polyline in profile coordinates (x, y): along a
member, x runs across it *within* the vertical surface over its top view (the
width of a ribbon or a tracery moulding) and y out of that surface, along the
horizontal top-view normal (the depth). Closed profiles are counter-clockwise
and may be capped and made solid; open ones (a zero-thickness ribbon, an open
moulding) give sheets.

Any profile made of lines and circular arcs is built with
:func:`from_segments` (or :func:`from_dict` from JSON), so Gothic moulding
profiles (rolls, fillets, hollows) can be swept; arcs are sampled by angle.
Bad profiles (open where closed is needed, self-intersecting, zero size,
zero-length pieces) raise :class:`~auszug.errors.GeometryError` saying which
point or edge is wrong.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any, Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.errors import GeometryError
from auszug.geometry import TOL, Arc, Line, arc_through

__all__ = [
    "Profile",
    "circle",
    "square",
    "rectangle",
    "ribbon",
    "polygon",
    "from_segments",
    "from_dict",
    "STYLES",
]

Array = NDArray[np.float64]
#: Built-in profile names of :func:`auszug.meshing.profile_for`.
STYLES = ("tube", "bar", "ribbon")


@dataclass(frozen=True, eq=False)
class Profile:
    """A cross-section: a polyline in the member's (width x, depth y) plane.

    Parameters
    ----------
    points : (m, 2) array_like
        Vertices (drawing units). A closed profile does not repeat its first
        point; it is made counter-clockwise.
    closed : bool
        Whether the last vertex joins the first.
    name : str

    Raises
    ------
    GeometryError
        Non-finite points, too few points, a zero-length edge, zero size or
        zero area, or crossing edges.

    Examples
    --------
    >>> p = square(0.1)
    >>> p.points.tolist()
    [[-0.05, -0.05], [0.05, -0.05], [0.05, 0.05], [-0.05, 0.05]]
    >>> p.closed, p.quarter_symmetric, round(p.radius, 6)
    (True, True, 0.070711)
    """

    points: Array
    closed: bool = True
    name: str = "profile"

    def __post_init__(self) -> None:
        p = np.asarray(self.points, dtype=float)
        if p.ndim != 2 or p.shape[1] != 2:
            raise GeometryError(f"profile points must have shape (m, 2), got {p.shape}")
        if not np.all(np.isfinite(p)):
            raise GeometryError("profile points must be finite numbers")
        if self.closed and len(p) > 1 and np.array_equal(p[0], p[-1]):
            p = p[:-1]
        size = float(np.linalg.norm(p.max(0) - p.min(0))) if len(p) else 0.0
        if not size > TOL.zero:
            raise GeometryError("profile has zero size: all its points coincide")
        need = 3 if self.closed else 2
        if len(p) < need:
            kind = "closed" if self.closed else "open"
            raise GeometryError(f"a {kind} profile needs at least {need} points, got {len(p)}")
        e = (np.roll(p, -1, axis=0) - p) if self.closed else np.diff(p, axis=0)
        ln = np.linalg.norm(e, axis=1)
        bad = np.nonzero(ln <= 1e-9 * size)[0]
        if len(bad):
            i = int(bad[0])
            raise GeometryError(f"profile edge {i} from point {i} {p[i].tolist()} has zero length")
        hit = _first_crossing(p, self.closed, 1e-9 * size)
        if hit is not None:
            i, j, x = hit
            raise GeometryError(
                f"profile is self-intersecting: edges {i} and {j} meet at {np.round(x, 12).tolist()}")
        if self.closed:
            area = _signed_area(p)
            if abs(area) <= 1e-9 * size * size:
                raise GeometryError("closed profile has zero size: it encloses no area")
            if area < 0:
                p = p[::-1].copy()
        p.setflags(write=False)
        object.__setattr__(self, "points", p)
        object.__setattr__(self, "closed", bool(self.closed))

    @property
    def n(self) -> int:
        """Number of vertices (points around)."""
        return len(self.points)

    @cached_property
    def radius(self) -> float:
        """Largest distance of a vertex from the centre line (the origin)."""
        return float(np.max(np.linalg.norm(self.points, axis=1)))

    @cached_property
    def area(self) -> float:
        """Enclosed area (0 for open profiles)."""
        return _signed_area(self.points) if self.closed else 0.0

    @cached_property
    def quarter_symmetric(self) -> bool:
        """Whether a quarter turn maps the profile onto itself (circles, squares)."""
        q = np.stack([-self.points[:, 1], self.points[:, 0]], axis=1)
        d = np.linalg.norm(q[:, None, :] - self.points[None, :, :], axis=2)
        return bool(np.all(d.min(axis=1) <= 1e-9 * max(self.radius, TOL.zero)))

    @cached_property
    def cap(self) -> NDArray[np.int64]:
        """Triangles filling a closed profile, counter-clockwise, shape (m - 2, 3).

        Raises
        ------
        GeometryError
            For an open profile.
        """
        if not self.closed:
            raise GeometryError("profile is open; caps and solids need a closed profile")
        return triangulate_polygon(self.points)

    def require_closed(self, what: str = "a solid") -> None:
        """Raise a clear error unless the profile is closed."""
        if not self.closed:
            raise GeometryError(f"profile {self.name!r} is open; {what} needs a closed profile "
                                "(give \"closed\": true, or a ribbon thickness > 0)")

    def scaled(self, factor: float) -> "Profile":
        """The profile scaled about its centre line."""
        if not (math.isfinite(factor) and factor > 0):
            raise GeometryError(f"profile scale must be a positive number, got {factor}")
        return Profile(self.points * factor, self.closed, self.name)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``{"name", "closed", "points"}`` (readable by :func:`from_dict`)."""
        return {"name": self.name, "closed": self.closed, "points": self.points.tolist()}


# -- kernels ----------------------------------------------------------------------------------


def _signed_area(p: Array) -> float:
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def _first_crossing(p: Array, closed: bool, tol: float) -> tuple[int, int, Array] | None:
    """The first pair of non-adjacent edges that meet (vectorised over all pairs)."""
    a = p
    b = np.roll(p, -1, axis=0) if closed else p[1:]
    if not closed:
        a = p[:-1]
    m = len(a)
    if m < 3:
        return None
    i, j = np.triu_indices(m, k=2)
    if closed:
        keep = ~((i == 0) & (j == m - 1))
        i, j = i[keep], j[keep]
    if len(i) == 0:
        return None
    p1, d1 = a[i], b[i] - a[i]
    p2, d2 = a[j], b[j] - a[j]
    den = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    w = p2 - p1
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (w[:, 0] * d2[:, 1] - w[:, 1] * d2[:, 0]) / den
        t = (w[:, 0] * d1[:, 1] - w[:, 1] * d1[:, 0]) / den
    l1 = np.linalg.norm(d1, axis=1)
    l2 = np.linalg.norm(d2, axis=1)
    e1, e2 = tol / l1, tol / l2
    cross = (np.abs(den) > 0) & (s >= -e1) & (s <= 1 + e1) & (t >= -e2) & (t <= 1 + e2)
    # parallel edges: overlapping collinear pieces also count
    par = np.abs(den) <= 1e-15 * l1 * l2
    if np.any(par):
        dist = np.abs(w[:, 0] * d1[:, 1] - w[:, 1] * d1[:, 0]) / l1
        u0 = np.einsum("ij,ij->i", w, d1) / (l1 * l1)
        u1 = np.einsum("ij,ij->i", w + d2, d1) / (l1 * l1)
        lo, hi = np.minimum(u0, u1), np.maximum(u0, u1)
        overlap = par & (dist <= tol) & (hi >= -e1) & (lo <= 1 + e1)
        cross = cross | overlap
        s = np.where(par, np.clip(np.maximum(lo, 0.0), 0, 1), s)
    k = np.nonzero(cross)[0]
    if len(k) == 0:
        return None
    k0 = int(k[0])
    return int(i[k0]), int(j[k0]), p1[k0] + s[k0] * d1[k0]


def triangulate_polygon(points: ArrayLike) -> NDArray[np.int64]:
    """Triangles of a simple counter-clockwise polygon, counter-clockwise, shape (m - 2, 3).

    Uses mapbox-earcut (free, no Shewchuk Triangle); a convex polygon is fanned.

    Examples
    --------
    >>> triangulate_polygon([[0, 0], [1, 0], [1, 1], [0, 1]]).tolist()
    [[0, 1, 2], [0, 2, 3]]
    """
    p = np.asarray(points, dtype=float)
    m = len(p)
    e = np.roll(p, -1, axis=0) - p
    turn = e[:, 0] * np.roll(e[:, 1], -1) - e[:, 1] * np.roll(e[:, 0], -1)
    if np.all(turn >= 0):
        k = np.arange(1, m - 1)
        return np.stack([np.zeros_like(k), k, k + 1], axis=1).astype(np.int64)
    import mapbox_earcut

    tri = mapbox_earcut.triangulate_float64(np.array(p, dtype=np.float64, order="C", copy=True),
                                            np.array([m], dtype=np.uint32)).reshape(-1, 3).astype(np.int64)
    a, b, c = p[tri[:, 0]], p[tri[:, 1]], p[tri[:, 2]]
    cw = ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])) < 0
    tri[cw] = tri[cw][:, ::-1]
    return tri


def _subdivide(p: Array, closed: bool, around: int) -> Array:
    """Insert points on the edges so that the outline has about ``around`` points."""
    e = (np.roll(p, -1, axis=0) - p) if closed else np.diff(p, axis=0)
    ln = np.linalg.norm(e, axis=1)
    extra = max(0, around - len(p))
    if extra == 0:
        return p
    k = np.maximum(1, np.round(ln / ln.sum() * (len(ln) + extra)).astype(int))
    idx = np.repeat(np.arange(len(ln)), k)
    frac = np.concatenate([np.arange(n) / n for n in k])
    return p[idx] + frac[:, None] * e[idx]


# -- constructors -------------------------------------------------------------------------------


def _positive(name: str, v: float) -> float:
    try:
        f = float(v)
    except (TypeError, ValueError):
        raise GeometryError(f"{name} must be a number, got {v!r}") from None
    if not (math.isfinite(f) and f > 0.0):
        raise GeometryError(f"{name} must be a positive number (zero size is not a profile), got {v!r}")
    return f


def circle(radius: float, around: int = 40) -> Profile:
    """A regular ``around``-gon inscribed in the circle (a round tube).

    Examples
    --------
    >>> p = circle(1.0, 8)
    >>> p.n, p.quarter_symmetric
    (8, True)
    """
    r = _positive("tube radius", radius)
    n = int(around)
    if n < 3:
        raise GeometryError(f"a round profile needs at least 3 points around, got {around}")
    a = 2.0 * np.pi * np.arange(n) / n
    return Profile(r * np.stack([np.cos(a), np.sin(a)], axis=1), True, "tube")


def rectangle(width: float, depth: float, around: int = 4, name: str = "rectangle") -> Profile:
    """A ``width`` (x) by ``depth`` (y) rectangle centred on the curve; ``around`` >= 4 subdivides its sides."""
    w = _positive("width", width) / 2.0
    d = _positive("depth", depth) / 2.0
    p = np.array([[-w, -d], [w, -d], [w, d], [-w, d]])
    return Profile(_subdivide(p, True, int(around)), True, name)


def square(size: float, around: int = 4) -> Profile:
    """A square bar of side ``size`` (the authors' default look)."""
    return rectangle(size, size, around, "bar")


def ribbon(width: float, thickness: float = 0.0, around: int = 2) -> Profile:
    """A flat band of ``width`` lying in the member's vertical surface.

    ``thickness`` 0 gives an open sheet (for rendering); > 0 a thin closed
    rectangle (printable).

    Examples
    --------
    >>> ribbon(0.2).closed, ribbon(0.2, 0.02).closed
    (False, True)
    """
    w = _positive("ribbon width", width)
    if float(thickness) == 0.0:
        p = np.array([[-w / 2.0, 0.0], [w / 2.0, 0.0]])
        return Profile(_subdivide(p, False, max(2, int(around))), False, "ribbon")
    return rectangle(w, _positive("ribbon thickness", thickness), max(4, int(around)), "ribbon")


def polygon(points: ArrayLike, closed: bool = True, name: str = "profile") -> Profile:
    """A profile of straight edges through ``points``."""
    return Profile(np.asarray(points, dtype=float), closed, name)


def _arc_curve(p0: Array, seg: Mapping[str, Any], i: int) -> Arc | Line:
    p1 = _xy(seg["arc"], f"segment {i} end")
    if "through" in seg:
        return arc_through(p0, _xy(seg["through"], f"segment {i} 'through'"), p1)
    if "bulge" in seg:
        b = float(seg["bulge"])
        if not math.isfinite(b):
            raise GeometryError(f"segment {i}: bulge must be finite")
        if b == 0.0:
            return Line(p0, p1)
        c = p1 - p0
        ln = float(np.hypot(*c))
        mid = (p0 + p1) / 2.0 + np.array([c[1], -c[0]]) / max(ln, 1e-300) * (b * ln / 2.0)
        return arc_through(p0, mid, p1)
    if "center" in seg:
        c = _xy(seg["center"], f"segment {i} centre")
        r0, r1 = float(np.hypot(*(p0 - c))), float(np.hypot(*(p1 - c)))
        if abs(r0 - r1) > 1e-6 * max(r0, r1):
            raise GeometryError(f"segment {i}: start and end are not equally far from the centre "
                                f"({r0:g} and {r1:g})")
        a0 = math.atan2(p0[1] - c[1], p0[0] - c[0])
        a1 = math.atan2(p1[1] - c[1], p1[0] - c[0])
        ccw = bool(seg.get("ccw", True))
        sweep = (a1 - a0) % (2 * math.pi) if ccw else -((a0 - a1) % (2 * math.pi))
        if sweep == 0.0:
            sweep = 2 * math.pi if ccw else -2 * math.pi
        return Arc(c, r0, a0, sweep)
    raise GeometryError(f"segment {i}: an arc needs 'through', 'bulge' or 'center'")


def _xy(v: Any, what: str) -> Array:
    try:
        a = np.asarray(v, dtype=float)
    except (TypeError, ValueError):
        raise GeometryError(f"{what} must be a pair of numbers, got {v!r}") from None
    if a.shape != (2,) or not np.all(np.isfinite(a)):
        raise GeometryError(f"{what} must be a pair of finite numbers, got {v!r}")
    return a


def from_segments(start: ArrayLike, segments: Sequence[Mapping[str, Any]], closed: bool = True,
                  around: int = 40, name: str = "profile") -> Profile:
    """A profile of lines and circular arcs, sampled with about ``around`` points.

    Parameters
    ----------
    start : (2,) array_like
        First point.
    segments : sequence of dict
        Each runs from the current point to its end: ``{"line": [x, y]}``, or
        ``{"arc": [x, y], "through": [x, y]}`` (three-point arc),
        ``{"arc": [x, y], "bulge": b}`` (DXF bulge: tan of a quarter of the
        swept angle, positive counter-clockwise) or
        ``{"arc": [x, y], "center": [x, y], "ccw": true}``.
    closed : bool
        Join the last point to ``start`` (with a line unless they coincide).
    around : int
        Points for the whole outline (arcs get at least one per 22.5 degrees).

    Examples
    --------
    >>> roll = from_segments([-1, 0], [{"line": [1, 0]}, {"arc": [-1, 0], "center": [0, 0]}], around=16)
    >>> roll.closed, roll.n, round(roll.area, 2)
    (True, 16, 1.55)
    """
    p0 = _xy(start, "profile start")
    curves: list[Arc | Line] = []
    cur = p0
    for i, seg in enumerate(segments):
        if not isinstance(seg, Mapping):
            raise GeometryError(f"segment {i} must be an object like {{\"line\": [x, y]}}, got {seg!r}")
        try:
            if "line" in seg:
                end = _xy(seg["line"], f"segment {i} end")
                c: Arc | Line = Line(cur, end)
            elif "arc" in seg:
                c = _arc_curve(cur, seg, i)
            else:
                raise GeometryError(f"segment {i} must have a 'line' or 'arc' key, got {sorted(seg)}")
        except GeometryError as e:
            if str(e).startswith("segment"):
                raise
            raise GeometryError(f"segment {i}: {e} (zero size or degenerate)") from None
        curves.append(c)
        cur = c.end
    if not curves:
        raise GeometryError("a profile needs at least one segment")
    size = max(float(np.max(np.abs(np.array([c.start for c in curves] + [cur])))), TOL.zero)
    if closed and float(np.hypot(*(cur - p0))) > 1e-9 * size:
        curves.append(Line(cur, p0))
    lengths = np.array([c.length() for c in curves])
    around = max(int(around), 3)
    pts = []
    for c, ln in zip(curves, lengths, strict=True):
        k = max(1, int(round(around * ln / lengths.sum())))
        if isinstance(c, Arc):
            k = max(k, int(math.ceil(abs(c.sweep) / (math.pi / 8))))
        pts.append(c.point(np.arange(k) / k))
    if not closed:
        pts.append(cur[None, :])
    return Profile(np.concatenate(pts), closed, name)


def from_dict(d: Mapping[str, Any], around: int = 40) -> Profile:
    """A profile from its JSON description.

    Either ``{"points": [[x, y], ...], "closed": true}`` (straight edges) or
    ``{"start": [x, y], "segments": [...], "closed": true}`` (see
    :func:`from_segments`); optional ``"name"`` and ``"scale"`` (multiplies
    all coordinates).

    Examples
    --------
    >>> from_dict({"points": [[0, 0], [1, 0], [0, 1]]}).n
    3
    >>> from_dict({"points": [[0, 0], [1, 0]], "closed": True})
    Traceback (most recent call last):
    ...
    auszug.errors.GeometryError: a closed profile needs at least 3 points, got 2
    """
    if not isinstance(d, Mapping):
        raise GeometryError(f"a profile must be a JSON object, got {type(d).__name__}")
    closed = d.get("closed", True)
    if not isinstance(closed, bool):
        raise GeometryError(f"'closed' must be true or false, got {closed!r}")
    name = str(d.get("name", "profile"))
    if "points" in d:
        try:
            pts = np.asarray(d["points"], dtype=float)
        except (TypeError, ValueError):
            raise GeometryError("'points' must be a list of [x, y] pairs") from None
        prof = Profile(pts.reshape(-1, 2) if pts.size % 2 == 0 else pts, closed, name)
    elif "segments" in d:
        if "start" not in d:
            raise GeometryError("a profile with 'segments' needs a 'start' point")
        segs = d["segments"]
        if not isinstance(segs, Sequence) or isinstance(segs, (str, bytes)):
            raise GeometryError("'segments' must be a list")
        prof = from_segments(d["start"], segs, closed, around, name)
    else:
        raise GeometryError("a profile needs 'points' or 'start' and 'segments'")
    if "scale" in d:
        prof = prof.scaled(_positive("scale", d["scale"]))
    return prof
