"""A patch's profile polyline fitted with exact lines and circular arcs (beyond the paper).

Gothic profiles are lines and arcs (fillets, rolls, hollows), so a profile found on a mesh is
given back as meshing's exact :class:`~auszug.meshing.profile.Profile` (vertices and a bulge per
segment) that can be swept again and exported:

1. **segment by curvature**: the discrete curvature of the polyline (turning angle over the mean
   of the two edges) splits it at corners (turning more than ``corner_angle`` and more than its
   neighbours); each stretch
   between corners is fitted as a line (curvature near zero) or an arc (curvature near
   constant), and split again at its point of largest curvature change while neither fits
   within the tolerance;
2. **least squares**: lines by total least squares (the principal axis of the points), arcs by
   the algebraic (Kasa) circle fit refined geometrically (``scipy.optimize.least_squares`` on the
   distances to the circle);
3. neighbouring pieces of one kind whose union still fits are **merged**;
4. pieces are **joined G0**: each joint is snapped to the meeting point of the two fitted
   primitives nearest to the polyline's vertex there (their mean projection when they barely
   meet, as at a tangent joint);
5. the fit is **kept** only when its Hausdorff distance to the polyline (both ways) is at most the
   tolerance.

All lengths in the units of the points given.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.errors import GeometryError
from auszug.meshing.profile import Profile

__all__ = ["Piece", "ProfileFit", "FittedProfile", "fit_circle_2d", "fit_lines_arcs", "fit_profile",
           "profile_frame", "polyline_hausdorff_2d"]

Array = NDArray[np.float64]
#: A piece's vertices must lie within this share of the tolerance of its line or circle (tighter than
#: the Hausdorff bound of the whole fit, so that a short fillet is not swallowed by a neighbouring arc).
PIECE_SHARE = 0.25
#: An arc spans at least this many polyline vertices (three fit any circle: no evidence of one).
MIN_ARC_POINTS = 4


@dataclass(frozen=True)
class Piece:
    """One fitted piece of a profile: a line or a circular arc over polyline vertices ``i0..i1``.

    Attributes
    ----------
    kind : {"line", "arc"}
    i0, i1 : int
        First and last polyline vertex of the piece (shared with the neighbours).
    centre : (2,) float array
        A point of the line (its centroid) or the circle's centre.
    direction : (2,) float array
        The line's unit direction (zero for an arc).
    radius : float
        The circle's radius (0 for a line).
    error : float
        Largest distance of the piece's polyline vertices to the fitted line or circle.
    """

    kind: str
    i0: int
    i1: int
    centre: Array
    direction: Array
    radius: float
    error: float


@dataclass(frozen=True)
class ProfileFit:
    """An exact line-and-arc profile fitted to a polyline.

    Attributes
    ----------
    profile : Profile
        The fit: its vertices are the snapped joints, one bulge per piece.
    pieces : tuple of Piece
        The pieces, in order along the polyline.
    hausdorff : float
        Hausdorff distance between the fit (sampled on its exact arcs) and the polyline.
    """

    profile: Profile
    pieces: tuple[Piece, ...]
    hausdorff: float

    @property
    def radii(self) -> Array:
        """Radii ``(k,)`` of the arcs, in order."""
        return np.array([p.radius for p in self.pieces if p.kind == "arc"])

    @property
    def kinds(self) -> tuple[str, ...]:
        """``"line"`` or ``"arc"`` for every piece."""
        return tuple(p.kind for p in self.pieces)


def _fit_line(p: Array) -> tuple[Array, Array, float]:
    c = p.mean(axis=0)
    _, _, vt = np.linalg.svd(p - c)
    d = vt[0]
    err = float(np.max(np.abs((p - c) @ np.array([-d[1], d[0]])))) if len(p) else 0.0
    return c, d, err


def fit_circle_2d(p: Array) -> tuple[Array, float, float]:
    """The circle nearest to the points ``p (k, 2)``: centre ``(2,)``, radius and max |distance - radius|.

    Kasa's algebraic fit, refined by geometric least squares on the points' distances to the
    circle (``scipy.optimize.least_squares``, Levenberg-Marquardt); lengths in the points' units.
    Fewer than three points, coincident points or a radius beyond 1e6 times their extent give
    radius and error ``inf``.

    Examples
    --------
    >>> t = np.linspace(0.0, 1.0, 6)
    >>> c, r, e = fit_circle_2d(np.c_[2 * np.cos(t) + 1, 2 * np.sin(t)])
    >>> (np.round(c, 9) + 0.0).tolist(), round(r, 9), e < 1e-12
    ([1.0, 0.0], 2.0, True)
    """
    from scipy.optimize import least_squares

    if len(p) < 3:
        return np.zeros(2), np.inf, np.inf
    s = float(np.max(np.ptp(p, axis=0)))
    if s <= 0:
        return np.zeros(2), np.inf, np.inf
    m = p.mean(axis=0)
    q = (p - m) / s
    a = np.column_stack([q, np.ones(len(q))])
    b = (q * q).sum(axis=1)
    sol, *_ = np.linalg.lstsq(a, b, rcond=None)
    c0 = sol[:2] / 2
    r0 = float(np.sqrt(max(sol[2] + c0 @ c0, 0.0)))
    if not (np.isfinite(r0) and r0 > 0 and r0 < 1e6):
        return np.zeros(2), np.inf, np.inf

    def res(x: Array) -> Array:
        return np.linalg.norm(q - x[:2], axis=1) - x[2]

    out = least_squares(res, np.array([c0[0], c0[1], r0]), method="lm", xtol=1e-15, ftol=1e-15, gtol=1e-15)
    c, r = out.x[:2] * s + m, abs(float(out.x[2])) * s
    err = float(np.max(np.abs(np.linalg.norm(p - c, axis=1) - r)))
    return c, r, err


def _turning(p: Array) -> Array:
    """Signed turning angle ``(n,)`` at every vertex (0 at the two ends) and the curvature there."""
    e = np.diff(p, axis=0)
    ang = np.arctan2(e[:, 1], e[:, 0])
    t = np.zeros(len(p))
    t[1:-1] = (np.diff(ang) + np.pi) % (2 * np.pi) - np.pi
    return t


def _piece(p: Array, i0: int, i1: int, tol: float) -> Piece | None:
    q = p[i0:i1 + 1]
    c, d, err = _fit_line(q)
    if err <= tol:
        return Piece("line", i0, i1, c, d, 0.0, err)
    if len(q) >= MIN_ARC_POINTS:
        cc, r, cerr = fit_circle_2d(q)
        if cerr <= tol:
            return Piece("arc", i0, i1, cc, np.zeros(2), r, cerr)
    return None


def _segment(p: Array, i0: int, i1: int, kappa: Array, tol: float, out: list[Piece]) -> None:
    pc = _piece(p, i0, i1, tol)
    if pc is not None:
        out.append(pc)
        return
    if i1 - i0 < 2:
        raise GeometryError(f"profile vertices {i0}..{i1} fit no line within {tol:.3g}")
    # split at the largest change of curvature inside (a joint of line and arc, or two arcs)
    inner = np.arange(i0 + 1, i1)
    score = np.abs(kappa[inner + 1] - kappa[inner - 1])
    k = int(inner[int(np.argmax(score))])
    _segment(p, i0, k, kappa, tol, out)
    _segment(p, k, i1, kappa, tol, out)


def _merge(p: Array, pieces: list[Piece], tol: float) -> list[Piece]:
    changed = True
    while changed and len(pieces) > 1:
        changed = False
        best, at = None, -1
        for j in range(len(pieces) - 1):
            a, b = pieces[j], pieces[j + 1]
            m = _piece(p, a.i0, b.i1, tol)
            if m is not None and (best is None or m.error < best.error):
                best, at = m, j
        if best is not None:
            pieces = pieces[:at] + [best] + pieces[at + 2:]
            changed = True
    return pieces


def _shift_joints(p: Array, pieces: list[Piece], tol: float, reach: int = 3) -> list[Piece]:
    """Move each joint inside a run by up to ``reach`` vertices where both pieces then fit better (summed error)."""
    for j in range(len(pieces) - 1):
        a, b = pieces[j], pieces[j + 1]
        best = (a.error + b.error, a, b)
        for k in range(max(a.i0 + 1, a.i1 - reach), min(b.i1 - 1, a.i1 + reach) + 1):
            if k == a.i1:
                continue
            na, nb = _piece(p, a.i0, k, tol), _piece(p, k, b.i1, tol)
            if na is not None and nb is not None and na.error + nb.error < best[0]:
                best = (na.error + nb.error, na, nb)
        pieces[j], pieces[j + 1] = best[1], best[2]
    return pieces


def _project(pc: Piece, x: Array) -> Array:
    if pc.kind == "line":
        return pc.centre + ((x - pc.centre) @ pc.direction) * pc.direction
    v = x - pc.centre
    n = float(np.linalg.norm(v))
    return pc.centre + pc.radius * (v / n if n > 0 else np.array([1.0, 0.0]))


def _meet(a: Piece, b: Piece) -> list[Array]:
    """Intersection points of two fitted primitives (possibly none)."""
    if a.kind == "line" and b.kind == "line":
        m = np.column_stack([a.direction, -b.direction])
        if abs(np.linalg.det(m)) < 1e-12:
            return []
        s = np.linalg.solve(m, b.centre - a.centre)
        return [a.centre + s[0] * a.direction]
    if a.kind == "arc" and b.kind == "line":
        a, b = b, a
    if a.kind == "line":   # line a, circle b
        f = a.centre - b.centre
        bb = float(f @ a.direction)
        cc = float(f @ f) - b.radius ** 2
        disc = bb * bb - cc
        if disc < 0:
            return []
        r = np.sqrt(disc)
        return [a.centre + (-bb - r) * a.direction, a.centre + (-bb + r) * a.direction]
    d = b.centre - a.centre
    dist = float(np.linalg.norm(d))
    if dist < 1e-15 or dist > a.radius + b.radius or dist < abs(a.radius - b.radius):
        return []
    x = (dist ** 2 + a.radius ** 2 - b.radius ** 2) / (2 * dist)
    h = np.sqrt(max(a.radius ** 2 - x * x, 0.0))
    u = d / dist
    base = a.centre + x * u
    w = np.array([-u[1], u[0]])
    return [base + h * w, base - h * w]


def _joint(a: Piece, b: Piece, x: Array, tol: float) -> Array:
    hits = [h for h in _meet(a, b) if np.linalg.norm(h - x) <= tol]
    if hits:
        return min(hits, key=lambda h: float(np.linalg.norm(h - x)))
    return 0.5 * (_project(a, x) + _project(b, x))


def _bulge(pc: Piece, a: Array, b: Array, mid: Array) -> float:
    """Bulge of the arc from ``a`` to ``b`` through ``mid`` (on ``pc``'s circle).

    The joints ``a``, ``b`` may lie a little off the fitted circle (snapped to a neighbour); the arc
    through them and ``mid`` keeps its middle on the fitted circle.
    """
    m = np.array([b - a, mid - a])
    rhs = 0.5 * np.array([(b - a) @ (b + a), (mid - a) @ (mid + a)])
    centre = np.linalg.solve(m, rhs) if abs(np.linalg.det(m)) > 1e-18 else pc.centre
    ua, ub, um = (np.arctan2(*(v - centre)[::-1]) for v in (a, b, mid))
    d1 = (um - ua + np.pi) % (2 * np.pi) - np.pi
    d2 = (ub - um + np.pi) % (2 * np.pi) - np.pi
    return float(np.tan((d1 + d2) / 4))


def _to_segments(p: Array, closed: bool) -> Array:
    a = p
    b = np.roll(p, -1, axis=0) if closed else p[1:]
    return np.stack([a if closed else p[:-1], b], axis=1)


def _point_segment_distance(x: Array, seg: Array) -> Array:
    """Distance ``(n,)`` of points ``(n, 2)`` to the nearest of segments ``(m, 2, 2)``."""
    a, b = seg[:, 0], seg[:, 1]
    ab = b - a
    ll = np.maximum((ab * ab).sum(axis=1), 1e-300)
    best = np.full(len(x), np.inf)
    for lo in range(0, len(x), 512):
        xs = x[lo:lo + 512]
        t = np.clip(((xs[:, None, :] - a[None]) * ab[None]).sum(-1) / ll[None], 0.0, 1.0)
        d = np.linalg.norm(xs[:, None, :] - (a[None] + t[..., None] * ab[None]), axis=-1)
        best[lo:lo + 512] = d.min(axis=1)
    return best


def polyline_hausdorff_2d(a: ArrayLike, b: ArrayLike, closed_a: bool = False, closed_b: bool = False) -> float:
    """Hausdorff distance of two planar polylines ``(n, 2)`` and ``(m, 2)`` (vertices to segments, both ways).

    Exact for polylines: the farthest point of one polyline from the other is one of its vertices
    or lies where that distance is largest along an edge, which for distances to a polyline is at
    a vertex or an equidistant point; sampling ``a`` and ``b`` densely makes the gap negligible.

    Examples
    --------
    >>> polyline_hausdorff_2d([[0, 0], [1, 0]], [[0, 0.5], [1, 0.5]])
    0.5
    """
    pa, pb = np.asarray(a, float), np.asarray(b, float)
    return float(max(_point_segment_distance(pa, _to_segments(pb, closed_b)).max(),
                     _point_segment_distance(pb, _to_segments(pa, closed_a)).max()))


def fit_lines_arcs(points: ArrayLike, closed: bool = False, tolerance: float = 1e-3,
                   corner_angle: float = 30.0, name: str = "profile", _start: int | None = None) -> ProfileFit | None:
    """Fit a planar polyline with lines and circular arcs joined end to end.

    Parameters
    ----------
    points : (n, 2) array_like
        The polyline (a closed one does not repeat its first point).
    closed : bool
    tolerance : float
        The largest Hausdorff distance of the whole fit to the polyline (units of ``points``); a
        piece's vertices lie within ``PIECE_SHARE`` (1/4) of it of their line or circle.
    corner_angle : float
        Vertices turning by more than this (degrees) and by at least 1.5 times as much as either
        neighbour are corners: pieces always end there (an evenly turning coarse arc has none).
    name : str
        Name of the :class:`Profile`.

    Returns
    -------
    ProfileFit or None
        None when the fit's Hausdorff distance to the polyline exceeds ``tolerance`` (or the
        fitted pieces do not make a valid profile).

    Raises
    ------
    GeometryError
        Fewer than 2 points (3 closed), non-finite points or a tolerance <= 0.

    Examples
    --------
    >>> u = np.linspace(0, np.pi, 20)
    >>> half = np.column_stack([np.cos(u), np.sin(u)])
    >>> f = fit_lines_arcs(np.vstack([[[2.0, 0.0]], half, [[-2.0, 0.0]]]), tolerance=0.01)
    >>> f.kinds, np.round(f.radii, 9).tolist(), np.round(f.profile.bulges, 9).tolist()
    (('line', 'arc', 'line'), [1.0], [0.0, 1.0, 0.0])

    The Hausdorff distance is the polyline's own chord error on the arc, ``1 - cos(pi / 38)``:

    >>> bool(round(f.hausdorff, 9) == round(1 - np.cos(np.pi / 38), 9))
    True
    """
    p = np.asarray(points, float)
    if p.ndim != 2 or p.shape[1] != 2 or len(p) < (3 if closed else 2) or not np.isfinite(p).all():
        raise GeometryError(f"profile fit needs finite points of shape (n, 2), n >= {3 if closed else 2}, "
                            f"got shape {p.shape}")
    if not tolerance > 0:
        raise GeometryError(f"profile fit tolerance must be > 0, got {tolerance!r}")
    keep = np.concatenate([[True], np.linalg.norm(np.diff(p, axis=0), axis=1) > 1e-12 * max(np.ptp(p), 1e-300)])
    p = p[keep]
    n_open = len(p)
    if closed:
        t = _turning(np.vstack([p[-1:], p, p[:1]]))[1:-1]
        start = int(np.argmax(np.abs(t))) if _start is None else _start
        p = np.vstack([np.roll(p, -start, axis=0), np.roll(p, -start, axis=0)[:1]])
    n = len(p)
    e = np.linalg.norm(np.diff(p, axis=0), axis=1)
    turn = _turning(p)
    kappa = np.zeros(n)
    kappa[1:-1] = turn[1:-1] / (0.5 * (e[:-1] + e[1:]))
    if n > 2:
        kappa[0], kappa[-1] = kappa[1], kappa[-2]
    piece_tolerance = PIECE_SHARE * tolerance
    a = np.abs(turn)
    corners = [0] + [i for i in range(1, n - 1)
                     if a[i] > np.radians(corner_angle) and a[i] >= 1.5 * max(a[i - 1], a[i + 1])] + [n - 1]
    pieces: list[Piece] = []
    try:
        for i0, i1 in zip(corners[:-1], corners[1:], strict=True):
            run: list[Piece] = []
            _segment(p, i0, i1, kappa, piece_tolerance, run)
            pieces.extend(_shift_joints(p, _merge(p, run, piece_tolerance), piece_tolerance))
    except GeometryError:
        return None
    if closed and _start is None and len(pieces) > 1:
        # the start may lie inside a piece (cut in two by the wrap): start again at a found joint
        return fit_lines_arcs(points, True, tolerance, corner_angle, name, (start + pieces[0].i1) % n_open)
    joints = [p[0]] + [_joint(a, b, p[a.i1], tolerance) for a, b in zip(pieces[:-1], pieces[1:], strict=True)]
    joints.append(_joint(pieces[-1], pieces[0], p[-1], tolerance) if closed else p[-1])
    if closed:
        joints[0] = joints[-1]
    else:
        joints[0] = _project(pieces[0], p[0])
        joints[-1] = _project(pieces[-1], p[-1])
    bulge = []
    for k, pc in enumerate(pieces):
        if pc.kind == "line":
            bulge.append(0.0)
        else:
            mid = p[(pc.i0 + pc.i1) // 2] if pc.i1 - pc.i0 >= 2 else 0.5 * (p[pc.i0] + p[pc.i1])
            bulge.append(_bulge(pc, joints[k], joints[k + 1], _project(pc, mid)))
    v = np.asarray(joints[:-1] if closed else joints)
    b = np.asarray(bulge)
    try:
        prof = Profile(v, closed=closed, name=name, bulge=b)
    except GeometryError:
        return None
    dense = prof.sample(tolerance=tolerance / 1000)
    poly = p[:-1] if closed else p
    h = polyline_hausdorff_2d(dense, poly, closed, closed)
    if not h <= tolerance:
        return None
    return ProfileFit(prof, tuple(pieces), h)


@dataclass(frozen=True, eq=False)
class FittedProfile:
    """A patch's profile as exact lines and arcs in its plane: meshing's :class:`Profile` and a frame.

    A point ``(x, y)`` of :attr:`profile` is at ``origin + x * axes[:, 0] + y * axes[:, 1]``;
    ``axes[:, 2]`` is the plane's normal (the same frame as :meth:`SweepPatch.sweep`).

    Attributes
    ----------
    origin : (3,) float array
        The frame's origin (the profile polyline's centroid).
    axes : (3, 3) float array
        Orthonormal, right-handed columns (W, D, N): in-plane principal direction, in-plane
        normal, plane normal.
    profile : Profile
        Vertices (the snapped joints) and one bulge per piece.
    hausdorff : float
        Hausdorff distance of the fit to the polyline, over the bounding-box diameter.
    """

    origin: Array
    axes: Array
    profile: Profile
    hausdorff: float

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, FittedProfile):
            return NotImplemented
        return (bool(np.array_equal(self.origin, other.origin)) and bool(np.array_equal(self.axes, other.axes))
                and self.profile == other.profile and self.hausdorff == other.hausdorff)

    __hash__ = None  # type: ignore[assignment]

    def vertices(self) -> Array:
        """The profile's vertices in space, shape ``(m, 3)``."""
        return self.origin + self.profile.points @ self.axes[:, :2].T

    def scaled(self, scale: float, centre: ArrayLike) -> "FittedProfile":
        """The same fit after ``x -> scale * x + centre`` (lengths scale, :attr:`hausdorff` is relative)."""
        p = self.profile
        return FittedProfile(scale * self.origin + np.asarray(centre, float), self.axes,
                             Profile(scale * p.points, closed=p.closed, name=p.name, bulge=p.bulges), self.hausdorff)


def profile_frame(profile: ArrayLike, closed: bool) -> tuple[Array, Array, Array]:
    """The plane frame of a profile polyline ``(n, 3)``: origin ``(3,)``, axes ``(3, 3)`` and 2D points ``(n, 2)``.

    The origin is the centroid, the first axis the principal direction, the third the plane's
    normal (right-handed); a closed profile gets the frame in which it runs counter-clockwise.
    """
    p = np.asarray(profile, float)
    o = p.mean(axis=0)
    _, _, vt = np.linalg.svd(p - o)
    e1, e3 = vt[0], vt[2]
    e2 = np.cross(e3, e1)
    xy = (p - o) @ np.stack([e1, e2], axis=1)
    if closed:
        x, y = xy[:, 0], xy[:, 1]
        if float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)) < 0:
            e2, e3 = -e2, -e3
            xy = (p - o) @ np.stack([e1, e2], axis=1)
    return o, np.stack([e1, e2, e3], axis=1), xy


def fit_profile(profile: ArrayLike, closed: bool, tolerance: float, name: str = "profile") -> FittedProfile | None:
    """Fit a profile polyline ``(n, 3)`` in its plane with lines and arcs (:func:`fit_lines_arcs`).

    ``tolerance`` is in the units of ``profile`` (bounding-box diameters on a normalised mesh, so
    :attr:`FittedProfile.hausdorff` is relative to the diameter). None when no fit is within it.
    """
    o, axes, xy = profile_frame(profile, closed)
    fit = fit_lines_arcs(xy, closed=closed, tolerance=tolerance, name=name)
    if fit is None:
        return None
    return FittedProfile(o, axes, fit.profile, fit.hausdorff)
