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
from auszug.limits import LIMITS, shown

__all__ = [
    "Profile",
    "circle",
    "square",
    "rectangle",
    "ribbon",
    "polygon",
    "from_segments",
    "from_dict",
    "triangulate_polygon",
    "STYLES",
]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]
#: Built-in profile names of :func:`auszug.meshing.profile_for`.
STYLES = ("tube", "bar", "ribbon")


@dataclass(frozen=True, eq=False)
class Profile:
    """A planar cross-section of lines and circular arcs, exact: vertices plus a bulge per segment.

    The profile plane is the member's (width x, depth y) plane. Segment ``i``
    runs from vertex ``i`` to vertex ``i + 1`` (for a closed profile the last
    one back to vertex 0) and is a circular arc of bulge ``tan(sweep / 4)``
    (positive counter-clockwise, DXF-style), a line for bulge 0. The vertices
    themselves are the default polyline (:attr:`points`, what sweeps and caps
    use); :meth:`sample` gives finer polylines on the exact arcs, by a count
    per arc or a chord tolerance, and :meth:`point` evaluates the outline at
    normalised arc length.

    Parameters
    ----------
    points : (m, 2) array_like
        Vertices (drawing units). A closed profile does not repeat its first
        point; it is made counter-clockwise (its exact signed area > 0).
    closed : bool
        Whether the last vertex joins the first.
    name : str
    bulge : (m,) or (m - 1,) array_like, optional
        One per segment (m for closed, m - 1 for open profiles); default all
        0 (a polygon).

    Raises
    ------
    GeometryError
        Non-finite points or bulges, a wrong number of bulges, too few points,
        a zero-length edge, zero size or zero area, or crossing edges (of the
        polyline of :attr:`points`).

    Examples
    --------
    >>> p = square(0.1)
    >>> p.points.tolist()
    [[-0.05, -0.05], [0.05, -0.05], [0.05, 0.05], [-0.05, 0.05]]
    >>> p.closed, p.quarter_symmetric, round(p.radius, 6)
    (True, True, 0.070711)
    >>> half = Profile([[1, 0], [-1, 0]], closed=False, bulge=[1.0])   # a half circle, exact
    >>> np.round(half.point([0.5]), 12).tolist(), round(half.length, 12)
    ([[0.0, 1.0]], 3.14159265359)
    """

    points: Array
    closed: bool = True
    name: str = "profile"
    bulge: Array | None = None

    def __post_init__(self) -> None:
        p = np.asarray(self.points, dtype=float)
        if p.ndim != 2 or p.shape[1] != 2:
            raise GeometryError(f"profile points must have shape (m, 2), got {p.shape}")
        if not np.all(np.isfinite(p)):
            raise GeometryError("profile points must be finite numbers")
        far = np.nonzero((np.abs(p) > LIMITS.coordinate).any(axis=1))[0]
        if len(far):
            i = int(far[0])
            raise GeometryError(f"profile point {i} {shown(p[i].tolist())} is beyond the limit of "
                                f"+-{LIMITS.coordinate:g} (auszug.limits.LIMITS.coordinate)")
        b = None if self.bulge is None else np.asarray(self.bulge, dtype=float).reshape(-1)
        if self.closed and len(p) > 1 and np.array_equal(p[0], p[-1]):
            p = p[:-1]
            if b is not None and len(b) == len(p) + 1:
                b = b[:-1]
        nseg = len(p) if self.closed else max(len(p) - 1, 0)
        if b is None:
            b = np.zeros(nseg)
        elif b.shape != (nseg,) or not np.all(np.isfinite(b)):
            raise GeometryError(f"profile bulge must be {nseg} finite numbers (one per segment), "
                                f"got {b.tolist()}")
        size = float(np.linalg.norm(p.max(0) - p.min(0))) if len(p) else 0.0
        if not size > TOL.zero:
            raise GeometryError("profile has zero size: all its points coincide")
        need = 3 if self.closed else 2
        if len(p) < need and not (self.closed and len(p) == 2 and np.all(b != 0)):
            kind = "closed" if self.closed else "open"
            raise GeometryError(f"a {kind} profile needs at least {need} points, got {len(p)}")
        e = (np.roll(p, -1, axis=0) - p) if self.closed else np.diff(p, axis=0)
        ln = np.linalg.norm(e, axis=1)
        bad = np.nonzero(ln <= 1e-9 * size)[0]
        if len(bad):
            i = int(bad[0])
            raise GeometryError(f"profile edge {i} from point {i} {p[i].tolist()} has zero length")
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            diameter = np.where(b != 0.0, ln * (1.0 + b * b) / (2.0 * np.abs(b)), 0.0)  # of each arc's circle
        big = np.nonzero(~(diameter <= LIMITS.coordinate))[0]
        if len(big):
            i = int(big[0])
            raise GeometryError(f"profile segment {i}: bulge {shown(float(b[i]))} makes a circle of diameter "
                                f"{shown(float(diameter[i]))}, beyond the limit of +-{LIMITS.coordinate:g} "
                                "(auszug.limits.LIMITS.coordinate)")
        if len(p) >= 3:
            hit = _first_crossing(p, self.closed, 1e-9 * size)
            if hit is not None:
                i, j, x = hit
                raise GeometryError(
                    f"profile is self-intersecting: edges {i} and {j} meet at {np.round(x, 12).tolist()}")
        if self.closed:
            area = _signed_area(p) + float(np.sum(_segment_areas(p, b)))
            if abs(area) <= 1e-9 * size * size:
                raise GeometryError("closed profile has zero size: it encloses no area")
            if area < 0:
                p = p[::-1].copy()
                b = -np.concatenate([b[-2::-1], b[-1:]])
        p.setflags(write=False)
        b.setflags(write=False)
        object.__setattr__(self, "points", p)
        object.__setattr__(self, "bulge", b)
        object.__setattr__(self, "closed", bool(self.closed))
        object.__setattr__(self, "name", str(self.name))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Profile):
            return NotImplemented
        b = self.bulges
        return (self.closed == other.closed and self.name == other.name
                and self.points.shape == other.points.shape and bool(np.array_equal(self.points, other.points))
                and bool(np.array_equal(b, other.bulges)))

    def __hash__(self) -> int:
        return hash((self.name, self.closed, self.points.tobytes(), self.bulges.tobytes()))

    @property
    def bulges(self) -> Array:
        """The bulge of each segment, shape (m,) closed or (m - 1,) open (never None)."""
        assert self.bulge is not None  # set by __post_init__
        return self.bulge

    @property
    def n(self) -> int:
        """Number of vertices (points around)."""
        return len(self.points)

    @property
    def has_arcs(self) -> bool:
        """Whether any segment is an arc."""
        return bool(np.any(self.bulges != 0.0))

    @cached_property
    def radius(self) -> float:
        """Largest distance of a vertex from the centre line (the origin)."""
        return float(np.max(np.linalg.norm(self.points, axis=1)))

    @cached_property
    def area(self) -> float:
        """Area enclosed by the polyline :attr:`points` (what a sweep's caps fill; 0 if open)."""
        return _signed_area(self.points) if self.closed else 0.0

    @cached_property
    def exact_area(self) -> float:
        """Area enclosed by the exact outline of lines and arcs (0 if open)."""
        if not self.closed:
            return 0.0
        return _signed_area(self.points) + float(np.sum(_segment_areas(self.points, self.bulges)))

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

    # -- the exact outline ------------------------------------------------------------------

    @cached_property
    def _segments(self) -> tuple[Array, Array, Array, Array, Array]:
        """Per segment: start (k, 2), end (k, 2), centre (k, 2; start for lines), radius (0 for lines), sweep."""
        a = self.points
        b = np.roll(a, -1, axis=0) if self.closed else a[1:]
        a = a[: len(b)]
        sweep = 4.0 * np.arctan(self.bulges)
        chord = b - a
        c_len = np.hypot(chord[:, 0], chord[:, 1])
        arc = sweep != 0.0
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.where(arc, c_len / (2.0 * np.abs(np.sin(sweep / 2.0))), 0.0)
            h = np.where(arc, r * np.cos(sweep / 2.0), 0.0)
            nrm = np.stack([-chord[:, 1], chord[:, 0]], axis=1) / c_len[:, None]
        ctr = 0.5 * (a + b) + (np.sign(sweep) * h)[:, None] * nrm   # h < 0: an arc over 180 deg
        ctr = np.where(arc[:, None], ctr, a)
        return a, b, ctr, r, sweep

    @cached_property
    def segment_lengths(self) -> Array:
        """Exact length of every segment (arcs: r |sweep|), shape (k,)."""
        a, b, _, r, sweep = self._segments
        chord = np.hypot(*(b - a).T)
        return np.where(sweep != 0.0, r * np.abs(sweep), chord)

    @property
    def length(self) -> float:
        """Exact length of the outline."""
        return float(self.segment_lengths.sum())

    def point(self, u: ArrayLike) -> Array:
        """Points of the exact outline at normalised arc length ``u`` in [0, 1], shape (..., 2).

        ``u`` = 0 is vertex 0; for a closed profile 1 is vertex 0 again.
        """
        uu = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
        ln = self.segment_lengths
        acc = np.concatenate([[0.0], np.cumsum(ln)])
        x = uu * acc[-1]
        i = np.clip(np.searchsorted(acc, x, side="right") - 1, 0, len(ln) - 1)
        f = (x - acc[i]) / ln[i]
        return self._at(i, f)

    def _at(self, i: NDArray[np.int64], f: Array) -> Array:
        a, b, ctr, r, sweep = self._segments
        th0 = np.arctan2(a[i, 1] - ctr[i, 1], a[i, 0] - ctr[i, 0])
        th = th0 + sweep[i] * f
        on_arc = ctr[i] + r[i, ..., None] * np.stack([np.cos(th), np.sin(th)], axis=-1)
        on_line = a[i] + f[..., None] * (b[i] - a[i])
        return np.where((sweep[i] != 0.0)[..., None], on_arc, on_line)

    def sample(self, per_arc: int | None = None, tolerance: float | None = None) -> Array:
        """The outline as a polyline on the exact arcs, shape (k, 2).

        Every vertex is kept and lines are not split; each arc gets ``per_arc``
        steps, or as many as its chords need to stay within ``tolerance`` of
        it (at least one). Neither: the vertices, :attr:`points`. A closed
        profile's polyline does not repeat its first point; an open one ends
        at its last vertex.

        Examples
        --------
        >>> q = Profile([[0, 0], [1, 1], [1, 2]], closed=False, bulge=[math.tan(math.pi / 8), 0])
        >>> q.sample(per_arc=2).round(6).tolist()
        [[0.0, 0.0], [0.707107, 0.292893], [1.0, 1.0], [1.0, 2.0]]
        """
        k = self._arc_counts(per_arc, tolerance)
        if k is None:
            return self.points
        seg = np.repeat(np.arange(len(k)), k)
        f = np.concatenate([np.arange(n) * (1.0 / n) for n in k])
        out = self._at(seg, f)
        first = np.concatenate([[0], np.cumsum(k)[:-1]])
        out[first] = self.points[: len(k)]  # the vertices exactly
        if not self.closed:
            out = np.concatenate([out, self.points[-1:]])
        return out

    def _arc_counts(self, per_arc: int | None, tolerance: float | None) -> NDArray[np.int64] | None:
        """Steps per segment of :meth:`sample` (None: the vertices alone)."""
        if per_arc is None and tolerance is None:
            return None
        _, _, _, r, sweep = self._segments
        arc = sweep != 0.0
        if per_arc is not None:
            k = np.where(arc, max(int(per_arc), 1), 1).astype(np.int64)
        else:
            tol = float(tolerance)  # type: ignore[arg-type]
            if not (math.isfinite(tol) and tol > 0.0):
                raise GeometryError(f"profile sampling tolerance must be a positive number, got {tolerance}")
            with np.errstate(divide="ignore", invalid="ignore"):
                step = np.where(r > tol, 2.0 * np.arccos(np.clip(1.0 - tol / r, -1.0, 1.0)), np.pi)
            k = np.where(arc, np.maximum(1, np.ceil(np.abs(sweep) / step - 1e-9)), 1).astype(np.int64)
        return None if np.all(k == 1) else k

    def sharp(self, per_arc: int | None = None) -> NDArray[np.bool_]:
        """Which points of :meth:`sample` (``per_arc``) are creases, shape (k,).

        The ends of an open profile are creases, and every vertex where the
        tangent turns by more than 1 degree; points inside arcs and
        tangent-continuous vertices are smooth.
        """
        a, b, _, _, sweep = self._segments
        chord = b - a
        ang = np.arctan2(chord[:, 1], chord[:, 0])
        t_start = ang - 0.5 * sweep
        t_end = ang + 0.5 * sweep
        n = len(self.points)
        vsharp = np.ones(n, dtype=bool)
        if self.closed:
            turn = np.abs((t_start - np.roll(t_end, 1) + np.pi) % (2 * np.pi) - np.pi)
            vsharp = turn > math.radians(1.0)
        else:
            turn = np.abs((t_start[1:] - t_end[:-1] + np.pi) % (2 * np.pi) - np.pi)
            vsharp[1:-1] = turn > math.radians(1.0)
        k = per_arc if per_arc is not None and per_arc >= 2 else 1
        out = []
        for i in range(len(sweep)):
            m = k if sweep[i] != 0.0 else 1
            seg = np.zeros(m, dtype=bool)
            seg[0] = vsharp[i]
            out.append(seg)
        if not self.closed:
            out.append(vsharp[-1:])
        return np.concatenate(out)

    def refined(self, per_arc: int | None = None, tolerance: float | None = None) -> "Profile":
        """The same exact outline with its arcs split at the points of :meth:`sample`.

        The new vertices are the sample points, each sub-arc keeps the arc's
        circle (bulge ``tan(sweep / 4k)``), so sweeps of the result follow the
        arcs more closely while the geometry stays exact.
        """
        k = self._arc_counts(per_arc, tolerance)
        if k is None:
            return self
        sweep = self._segments[4]
        bul = np.repeat(np.tan(sweep / (4.0 * k)), k)
        return Profile(self.sample(per_arc, tolerance), self.closed, self.name, bul)

    def require_closed(self, what: str = "a solid") -> None:
        """Raise a clear error unless the profile is closed."""
        if not self.closed:
            raise GeometryError(f"profile {self.name!r} is open; {what} needs a closed profile "
                                "(give \"closed\": true, or a ribbon thickness > 0)")

    def scaled(self, factor: float) -> "Profile":
        """The profile scaled about its centre line (arcs stay arcs)."""
        if not (math.isfinite(factor) and factor > 0):
            raise GeometryError(f"profile scale must be a positive number, got {factor}")
        return Profile(self.points * factor, self.closed, self.name, self.bulges)

    def reversed(self) -> "Profile":
        """An open profile run the other way (a closed one stays counter-clockwise)."""
        if self.closed:
            return self
        return Profile(self.points[::-1], False, self.name, -self.bulges[::-1])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``{"name", "closed", "points"}`` plus ``"bulge"`` if it has arcs (see :func:`from_dict`).

        Examples
        --------
        >>> c = circle(1.0, 6)
        >>> from_dict(c.to_dict()) == c
        True
        """
        d: dict[str, Any] = {"name": self.name, "closed": self.closed, "points": self.points.tolist()}
        if self.has_arcs:
            d["bulge"] = self.bulges.tolist()
        return d


# -- kernels ----------------------------------------------------------------------------------


def _signed_area(p: Array) -> float:
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def _segment_areas(p: Array, bulge: Array) -> Array:
    """Signed area between each segment's chord and its arc (positive for counter-clockwise bulges)."""
    q = np.roll(p, -1, axis=0)[: len(bulge)]
    c = np.hypot(*(q - p[: len(bulge)]).T)
    sweep = 4.0 * np.arctan(bulge)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = c / (2.0 * np.abs(np.sin(sweep / 2.0)))
        a = 0.5 * r * r * (np.abs(sweep) - np.sin(np.abs(sweep)))
    return np.where(sweep != 0.0, np.sign(sweep) * a, 0.0)


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
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # den ~ 0: s, t huge, no crossing
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


def triangulate_polygon(points: ArrayLike, holes: Sequence[ArrayLike] = (), manifold: bool = True
                        ) -> NDArray[np.int64]:
    """Triangles of a simple counter-clockwise polygon, optionally with holes, counter-clockwise.

    The one triangulator of auszug (profile caps, face fills, tracery plates
    and floors): mapbox-earcut (free, no Shewchuk Triangle); a convex polygon
    without holes is fanned.

    Parameters
    ----------
    points : (m, 2) array_like
        The outer ring, counter-clockwise, first point not repeated.
    holes : sequence of (k_i, 2) array_like
        Rings inside it (any orientation), disjoint from it and each other.
    manifold : bool
        Make the fill use every ring vertex and edge (the default: fills that meet lofts
        and members in one closed mesh). ``False`` returns earcut's first fill as it is,
        made counter-clockwise: it may leave out collinear ring vertices and keep zero-area
        slivers, and costs about a tenth (the live previews of ``tracery.preview``).

    Returns
    -------
    (t, 3) ndarray of int64
        Indices into ``points`` followed by the holes' points in order;
        m - 2 triangles without holes, m + sum(k_i) + 2 (#holes - 1) with
        (with ``manifold=False``, fewer if collinear vertices were left out).

    Examples
    --------
    >>> triangulate_polygon([[0, 0], [1, 0], [1, 1], [0, 1]]).tolist()
    [[0, 1, 2], [0, 2, 3]]
    >>> len(triangulate_polygon([[0, 0], [3, 0], [3, 3], [0, 3]], [[[1, 1], [2, 1], [2, 2], [1, 2]]]))
    8
    """
    p = np.asarray(points, dtype=float)
    m = len(p)
    if not len(holes):
        e = np.roll(p, -1, axis=0) - p
        turn = e[:, 0] * np.roll(e[:, 1], -1) - e[:, 1] * np.roll(e[:, 0], -1)
        if np.all(turn >= 0):
            k = np.arange(1, m - 1)
            return np.stack([np.zeros_like(k), k, k + 1], axis=1).astype(np.int64)
    import mapbox_earcut

    rings = [p] + [np.asarray(h, dtype=float).reshape(-1, 2) for h in holes]
    allp = np.ascontiguousarray(np.concatenate(rings), dtype=np.float64)
    ends = np.cumsum([len(r) for r in rings]).astype(np.uint32)
    starts = np.concatenate([[0], ends]).astype(np.int64)
    tri = np.empty((0, 3), np.int64)
    for angle in (0.0, *_TURNS):
        # earcut drops exactly collinear ring vertices and may bridge holes along a line they
        # share (two sills on one line); seen turned by an irrational angle, rounding breaks
        # those exact collinearities, and the triangles index the untouched points
        q = allp if angle == 0.0 else np.ascontiguousarray(allp @ _rotation(angle).T)
        tri = mapbox_earcut.triangulate_float64(q, ends).reshape(-1, 3).astype(np.int64)
        # earcut's triangles all turn one way: make them counter-clockwise together (per triangle,
        # rounding could flip a sliver and break the fill's manifoldness)
        a, b, c = q[tri[:, 0]], q[tri[:, 1]], q[tri[:, 2]]
        cross = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
        if cross.sum() < 0:
            tri = tri[:, ::-1].copy()
        if not manifold:
            return tri
        tri = _restore_dropped(tri, starts)
        if _fills_rings(tri, starts):
            break
    else:
        # no turned view gave earcut a fill that uses every ring edge once: manifold3d's
        # triangulator (exact on collinear ring edges) does
        return _manifold_fill(rings, starts)
    return _flip_slivers(tri, allp)


def _manifold_fill(rings: list[Array], starts: NDArray[np.int64]) -> NDArray[np.int64]:
    """Triangles of the rings by manifold3d (outer ring counter-clockwise, holes clockwise).

    Indices refer to the rings' own vertex order, concatenated; triangles are counter-clockwise.
    """
    import manifold3d

    polys, idx = [], []
    for k, r in enumerate(rings):
        x, y = r[:, 0], r[:, 1]
        ccw = float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)) > 0.0
        order = np.arange(len(r))
        if ccw != (k == 0):
            order = order[::-1]
        polys.append(np.ascontiguousarray(r[order], dtype=np.float64))
        idx.append(starts[k] + order)
    tri = np.asarray(manifold3d.triangulate(polys), dtype=np.int64).reshape(-1, 3)
    return np.concatenate(idx)[tri]


def _flip_slivers(tri: NDArray[np.int64], p: Array) -> NDArray[np.int64]:
    """Remove triangles of three collinear points by flipping their longest edge.

    A zero-area triangle (a, b, c) with c inside its edge (a, b) and the
    triangle (b, a, d) across that edge together are the triangle (b, a, d)
    with c on an edge: it becomes (b, c, d) and (c, a, d). Earcut leaves such
    slivers where ring vertices are collinear (a sill line shared by holes).
    """
    a, b, c = p[tri[:, 0]], p[tri[:, 1]], p[tri[:, 2]]
    cr = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    scale = float(np.ptp(p, axis=0).max()) if len(p) else 1.0
    tol = 1e-14 * scale * scale
    queue: list[int] = np.flatnonzero(np.abs(cr) <= tol).tolist()
    if not queue:
        return tri
    pts = p.tolist()

    def area2(t: list[int]) -> float:
        (ax, ay), (bx, by), (cx, cy) = pts[t[0]], pts[t[1]], pts[t[2]]
        return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)

    def sliver(t: list[int]) -> bool:
        return abs(area2(t)) <= tol

    tl: list[list[int]] = tri.tolist()
    edge: dict[tuple[int, int], int] = {}
    for k, (x, y, z) in enumerate(tl):
        edge[(x, y)] = edge[(y, z)] = edge[(z, x)] = k
    budget = 8 * len(queue) + 16
    while queue and budget:
        budget -= 1
        k = queue.pop()
        t = tl[k]
        if not sliver(t):
            continue
        ln = [math.dist(pts[t[i]], pts[t[(i + 1) % 3]]) for i in range(3)]
        i = ln.index(max(ln))
        va, vb, vc = t[i], t[(i + 1) % 3], t[(i + 2) % 3]
        j = edge.get((vb, va))
        if j is None:
            continue
        vd = next(v for v in tl[j] if v != va and v != vb)
        for e in ((va, vb), (vb, vc), (vc, va), (vb, va), (va, vd), (vd, vb)):
            edge.pop(e, None)
        tl[k] = [vb, vc, vd]
        tl[j] = [vc, va, vd]
        for kk in (k, j):
            x, y, z = tl[kk]
            edge[(x, y)] = edge[(y, z)] = edge[(z, x)] = kk
        queue += [k, j]
    return np.asarray(tl, dtype=np.int64).reshape(-1, 3)


#: Turns (radians) of the retries of :func:`triangulate_polygon`.
_TURNS = (math.sqrt(2.0) - 1.0, math.pi / 7.0 - 0.1, math.e / 5.0)


def _rotation(a: float) -> Array:
    return np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])


def _fills_rings(tri: NDArray[np.int64], starts: NDArray[np.int64]) -> bool:
    """Whether the triangles cover the rings exactly: every ring edge once, every other edge twice."""
    n = int(starts[-1])
    holes = len(starts) - 2
    if len(tri) != n - 2 + 2 * holes:
        return False
    e = np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1)
    code, cnt = np.unique(e[:, 0] * n + e[:, 1], return_counts=True)
    idx = np.arange(n)
    nxt = idx + 1
    nxt[starts[1:] - 1] = starts[:-1]
    ring = np.sort(np.stack([idx, nxt], axis=1), axis=1)
    ring_code = ring[:, 0] * n + ring[:, 1]
    once = code[cnt == 1]
    return bool(np.all(cnt <= 2) and len(once) == n and np.array_equal(np.sort(ring_code), once))


def _restore_dropped(tri: NDArray[np.int64], starts: NDArray[np.int64]) -> NDArray[np.int64]:
    """Put back the ring vertices earcut leaves out (it drops collinear ones).

    A run of dropped vertices between kept ring neighbours ``a`` and ``b``
    lies on the output edge (a, b); its triangle (a, b, c) is replaced by the
    fan from ``c`` through the run, so every ring edge is a mesh edge again
    (no T-junctions where the fill meets a loft or a member).
    """
    n = int(starts[-1])
    used = np.zeros(n, dtype=bool)
    used[tri.ravel()] = True
    if used.all() or not len(tri):
        return tri
    # runs of dropped vertices, per ring: kept ring position i, its next kept one, the gap between
    ra: list[IntArray] = []
    rg: list[IntArray] = []
    rs: list[IntArray] = []
    rl: list[IntArray] = []
    for r in range(len(starts) - 1):
        s0, ln = int(starts[r]), int(starts[r + 1] - starts[r])
        kpos = np.flatnonzero(used[s0:s0 + ln])
        if len(kpos) == ln or not len(kpos):
            continue
        gap = (np.roll(kpos, -1) - kpos) % ln
        gap[gap == 0] = ln
        sel = gap > 1
        ra.append(kpos[sel])
        rg.append(gap[sel])
        rs.append(np.full(int(sel.sum()), s0))
        rl.append(np.full(int(sel.sum()), ln))
    if not ra:
        return tri
    pos, gap, s0s, lns = (np.concatenate(x) for x in (ra, rg, rs, rl))
    a = s0s + pos
    b = s0s + (pos + gap) % lns
    code = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    code = code[:, 0] * n + code[:, 1]
    order = np.argsort(code)
    code_s = code[order]
    owner = np.tile(np.arange(len(tri)), 3)[order]
    slot = np.repeat(np.arange(3), len(tri))[order]

    def find(u: IntArray, v: IntArray) -> IntArray:
        k = np.minimum(np.searchsorted(code_s, u * n + v), len(code_s) - 1)
        return np.where(code_s[k] == u * n + v, k, -1)

    kf, kb = find(a, b), find(b, a)
    fwd = kf >= 0
    k = np.where(fwd, kf, kb)
    ok = k >= 0
    if not ok.any():
        return tri
    pos, gap, s0s, lns, k, fwd = pos[ok], gap[ok], s0s[ok], lns[ok], k[ok], fwd[ok]
    t = owner[k]
    apex = tri[t, (slot[k] + 2) % 3]
    # the fan from the apex through the chain a, dropped..., b (reversed where the triangle runs b -> a)
    run = np.repeat(np.arange(len(gap)), gap)
    j = np.arange(len(run)) - np.repeat(np.cumsum(gap) - gap, gap)
    p0 = s0s[run] + (pos[run] + j) % lns[run]
    p1 = s0s[run] + (pos[run] + j + 1) % lns[run]
    f = fwd[run]
    extra = np.stack([np.where(f, p0, p1), np.where(f, p1, p0), apex[run]], axis=1)
    drop = np.zeros(len(tri), dtype=bool)
    drop[t] = True
    return np.concatenate([tri[~drop], extra]).astype(np.int64)


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
    """The circle, exact, as ``around`` arcs: its vertices are the inscribed regular ``around``-gon (a round tube).

    Examples
    --------
    >>> p = circle(1.0, 8)
    >>> p.n, p.quarter_symmetric, round(p.exact_area, 12) == round(math.pi, 12)
    (8, True, True)
    """
    r = _positive("tube radius", radius)
    n = int(around)
    if n < 3:
        raise GeometryError(f"a round profile needs at least 3 points around, got {around}")
    a = 2.0 * np.pi * np.arange(n) / n
    return Profile(r * np.stack([np.cos(a), np.sin(a)], axis=1), True, "tube", np.full(n, math.tan(math.pi / (2 * n))))


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
        b = seg["bulge"]
        if isinstance(b, bool) or not isinstance(b, (int, float)) or not math.isfinite(b):
            raise GeometryError(f"segment {i}: bulge must be a finite number, got {shown(b)}")
        b = float(b)
        if b == 0.0:
            return Line(p0, p1)
        c = p1 - p0
        ln = float(np.hypot(*c))
        with np.errstate(over="ignore", invalid="ignore"):
            mid = (p0 + p1) / 2.0 + np.array([c[1], -c[0]]) / max(ln, 1e-300) * (b * ln / 2.0)
        if not (np.isfinite(mid).all() and np.abs(mid).max() <= LIMITS.coordinate):
            raise GeometryError(f"segment {i}: bulge {shown(b)} puts the arc's middle beyond the limit of "
                                f"+-{LIMITS.coordinate:g} (auszug.limits.LIMITS.coordinate)")
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
        raise GeometryError(f"{what} must be a pair of numbers, got {shown(v)}") from None
    if a.shape != (2,) or not np.all(np.isfinite(a)):
        raise GeometryError(f"{what} must be a pair of finite numbers, got {shown(v)}")
    if np.abs(a).max() > LIMITS.coordinate:
        raise GeometryError(f"{what} {shown(a.tolist())} is beyond the limit of +-{LIMITS.coordinate:g} "
                            "(auszug.limits.LIMITS.coordinate)")
    return a


def from_segments(start: ArrayLike, segments: Sequence[Mapping[str, Any]], closed: bool = True,
                  around: int = 40, name: str = "profile") -> Profile:
    """A profile of lines and circular arcs, its arcs split into about ``around`` vertices in all.

    The result is exact (each piece of an arc keeps its circle as a bulge);
    its vertices, the polyline that sweeps use, are spread by length.

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
    bulge = []
    for c, ln in zip(curves, lengths, strict=True):
        k = max(1, int(round(around * ln / lengths.sum())))
        if isinstance(c, Arc):
            k = max(k, int(math.ceil(abs(c.sweep) / (math.pi / 8))))
        pts.append(c.point(np.arange(k) / k))
        bulge.append(np.full(k, math.tan(c.sweep / (4 * k)) if isinstance(c, Arc) else 0.0))
    if not closed:
        pts.append(cur[None, :])
    return Profile(np.concatenate(pts), closed, name, np.concatenate(bulge))


def from_dict(d: Mapping[str, Any], around: int = 40) -> Profile:
    """A profile from its JSON description.

    Either ``{"points": [[x, y], ...], "closed": true}`` (straight edges, or
    arcs with ``"bulge": [b, ...]``, one per segment, as :meth:`Profile.to_dict` writes) or
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
        bulge = d.get("bulge")
        if bulge is not None:
            try:
                bulge = np.asarray(bulge, dtype=float)
            except (TypeError, ValueError):
                raise GeometryError("'bulge' must be a list of numbers, one per segment") from None
        prof = Profile(pts.reshape(-1, 2) if pts.size % 2 == 0 else pts, closed, name, bulge)
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
