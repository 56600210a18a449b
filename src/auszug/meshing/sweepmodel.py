"""The sweep model: a planar profile moved rigidly along a 3D path.

One value describes every swept shape of auszug, the members of a curve
network and the mouldings of window tracery alike, and is what the
sweep-analysis package fits to scanned meshes (a found sweep is a
:class:`Sweep`):

* a :class:`~auszug.meshing.profile.Profile`: lines and arcs in the profile
  plane (x, y), exact, open or closed, sampled on demand;
* a :class:`Path`: points and unit tangents at increasing parameters ``s``
  (arc length by default), e.g. a network piece's samples or a polyline;
* :class:`RigidFrames`: rigid motions ``(R_i, t_i)`` at parameters ``s_i``,
  the columns of ``R`` being (W, D, T): profile x goes along W, profile y
  along D, and T is the direction of travel; rotation-minimising along the
  path by default, or given explicitly. Between knots a frame turns at
  constant speed about one axis (the geodesic of SO(3)) and its origin moves
  along the chord, so every evaluated frame is a rigid motion.

The swept surface is ``X(s, v) = t(s) + R(s) @ (x(v), y(v), 0)`` with
``(x(v), y(v))`` the profile at normalised arc length ``v``
(:meth:`Sweep.point`); :meth:`Sweep.mesh` gives the triangle mesh, a ring of
the profile's vertices at every frame knot, capped for closed profiles.

Mouldings along a *closed planar loop with corners* (a tracery region's
border) are the sweep of the profile with the planar frames (W the inward
normal in the plane, D the plane's normal): :func:`offset_loft` meshes that
sweep exactly through the offsets of the loop at the profile's insets, which
on smooth stretches are the sweep's profile curves and at corners meet on the
bisector (for arcs the medial axis), dropping pieces that vanish, so the
surface never self-intersects.

Examples
--------
>>> import numpy as np
>>> from auszug.meshing.profile import circle
>>> z = np.linspace(0.0, 2.0, 5)
>>> path = Path.polyline(np.stack([0 * z, 0 * z, z], axis=1))
>>> sw = Sweep(circle(0.5, 16), path)                   # a cylinder of radius 0.5
>>> p = sw.point([1.0], [0.25])
>>> bool(np.isclose(np.hypot(p[0, 0], p[0, 1]), 0.5)), float(p[0, 2])
(True, 1.0)
>>> m = sw.mesh()
>>> m.is_watertight, m.n_vertices
(True, 80)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.errors import GeometryError
from auszug.geometry import Arc, Curve
from auszug.meshing.frames import Frames, reference_basis, sweep_frames
from auszug.meshing.mesh import Mesh, Part
from auszug.meshing.profile import Profile

__all__ = [
    "Path",
    "RigidFrames",
    "Sweep",
    "Loft",
    "sweep_grid",
    "loop_ring",
    "zip_rings",
    "offset_loft",
]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Largest deviation of an explicit frame from a rotation (R^T R - I, det R - 1).
FRAME_TOL = 1e-9


def _interval(knots: Array, s: Array) -> tuple[IntArray, Array]:
    """Index i of the knot interval [k_i, k_i+1] holding each s (clamped) and the fraction in it."""
    i = np.clip(np.searchsorted(knots, s, side="right") - 1, 0, max(len(knots) - 2, 0))
    h = knots[i + 1] - knots[i] if len(knots) > 1 else np.ones_like(s)
    f = np.clip(np.divide(s - knots[i], h, out=np.zeros_like(s), where=h > 0), 0.0, 1.0)
    return i.astype(np.int64), f


# -- the path -----------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Path:
    """A 3D path: points with unit tangents at increasing parameters.

    Attributes
    ----------
    points : (n, 3) ndarray
        n >= 2.
    tangents : (n, 3) ndarray
        Unit tangents, in the direction of increasing ``s``.
    s : (n,) ndarray
        Non-decreasing parameters, not all equal; default the cumulative chord length.

    Between samples :meth:`point` is the cubic Hermite curve of the points and
    tangents (exact at the samples, C1).
    """

    points: Array
    tangents: Array
    s: Array | None = None

    def __post_init__(self) -> None:
        p = np.asarray(self.points, dtype=float)
        t = np.asarray(self.tangents, dtype=float)
        if p.ndim != 2 or p.shape[1] != 3 or len(p) < 2 or t.shape != p.shape:
            raise GeometryError(f"a path needs (n, 3) points and tangents, n >= 2; got {p.shape} and {t.shape}")
        if not (np.all(np.isfinite(p)) and np.all(np.isfinite(t))):
            raise GeometryError("path points and tangents must be finite")
        ln = np.linalg.norm(t, axis=1)
        if np.any(ln <= 0.0):
            raise GeometryError(f"path tangent {int(np.argmin(ln))} is zero")
        if np.any(np.abs(ln - 1.0) > 1e-9):
            t = t / ln[:, None]
        if self.s is None:
            s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
        else:
            s = np.asarray(self.s, dtype=float)
            if s.shape != (len(p),):
                raise GeometryError(f"path parameters must have shape ({len(p)},), got {s.shape}")
        if not (np.all(np.diff(s) >= 0.0) and s[-1] > s[0]):
            raise GeometryError("path parameters must not decrease, and must not all be equal")
        object.__setattr__(self, "points", p)
        object.__setattr__(self, "tangents", t)
        object.__setattr__(self, "s", s)

    @classmethod
    def _unchecked(cls, points: Array, tangents: Array, s: Array) -> Path:
        """A path from arrays already known to be valid (no copies, no checks)."""
        out = object.__new__(cls)
        object.__setattr__(out, "points", points)
        object.__setattr__(out, "tangents", tangents)
        object.__setattr__(out, "s", s)
        return out

    @property
    def knots(self) -> Array:
        """The parameters ``s`` (never None)."""
        assert self.s is not None  # set by __post_init__
        return self.s

    @classmethod
    def polyline(cls, points: ArrayLike) -> Path:
        """A path through points: tangents from the neighbouring chords, ``s`` the chord length.

        Examples
        --------
        >>> Path.polyline([[0, 0, 0], [1, 0, 0], [1, 1, 0]]).tangents.round(6).tolist()
        [[1.0, 0.0, 0.0], [0.707107, 0.707107, 0.0], [0.0, 1.0, 0.0]]
        """
        p = np.asarray(points, dtype=float)
        if p.ndim != 2 or p.shape[1] != 3 or len(p) < 2:
            raise GeometryError(f"a polyline path needs (n, 3) points, n >= 2; got {p.shape}")
        d = np.diff(p, axis=0)
        ln = np.linalg.norm(d, axis=1)
        if np.any(ln <= 0.0):
            raise GeometryError(f"polyline path: points {int(np.argmin(ln))} and {int(np.argmin(ln)) + 1} coincide")
        u = d / ln[:, None]
        t = np.concatenate([u[:1], u[:-1] + u[1:], u[-1:]])
        return cls(p, t / np.linalg.norm(t, axis=1, keepdims=True))

    @property
    def length(self) -> float:
        """Length of the polyline of the points."""
        return float(np.linalg.norm(np.diff(self.points, axis=0), axis=1).sum())

    def point(self, s: ArrayLike) -> Array:
        """Points at parameters ``s`` (clamped to the path), shape (..., 3)."""
        ss = np.asarray(s, dtype=float)
        i, f = _interval(self.knots, ss)
        f = f[..., None]
        h00, h10 = 2 * f**3 - 3 * f**2 + 1, f**3 - 2 * f**2 + f
        h01, h11 = -2 * f**3 + 3 * f**2, f**3 - f**2
        p0, p1, t0, t1 = self.points[i], self.points[i + 1], self.tangents[i], self.tangents[i + 1]
        chord = np.linalg.norm(p1 - p0, axis=-1)[..., None]
        return h00 * p0 + h10 * chord * t0 + h01 * p1 + h11 * chord * t1

    def tangent(self, s: ArrayLike) -> Array:
        """Unit tangents at parameters ``s``, shape (..., 3) (the Hermite curve's, exact at the samples)."""
        ss = np.asarray(s, dtype=float)
        i, f = _interval(self.knots, ss)
        f = f[..., None]
        d00, d10 = 6 * f**2 - 6 * f, 3 * f**2 - 4 * f + 1
        d01, d11 = -6 * f**2 + 6 * f, 3 * f**2 - 2 * f
        p0, p1, t0, t1 = self.points[i], self.points[i + 1], self.tangents[i], self.tangents[i + 1]
        chord = np.linalg.norm(p1 - p0, axis=-1)[..., None]
        d = d00 * p0 + d10 * chord * t0 + d01 * p1 + d11 * chord * t1
        return d / np.linalg.norm(d, axis=-1, keepdims=True)


# -- frames ---------------------------------------------------------------------------------


def _rotvec(r: Array) -> Array:
    """Rotation vectors (axis * angle) of rotation matrices, shape (..., 3)."""
    tr = np.clip((np.trace(r, axis1=-2, axis2=-1) - 1.0) / 2.0, -1.0, 1.0)
    ang = np.arccos(tr)
    w = np.stack([r[..., 2, 1] - r[..., 1, 2], r[..., 0, 2] - r[..., 2, 0], r[..., 1, 0] - r[..., 0, 1]], axis=-1)
    s = np.sin(ang)
    small = s < 1e-8
    k = np.where(small, 0.5, ang / (2.0 * np.where(small, 1.0, s)))
    out = k[..., None] * w
    # near a half turn: the axis from the symmetric part
    big = ang > math.pi - 1e-6
    if np.any(big):
        rb = r[big]
        cos = (np.trace(rb, axis1=-2, axis2=-1) - 1.0) / 2.0
        m = (rb + np.swapaxes(rb, -1, -2)) / 2.0 - np.eye(3) * cos[:, None, None]  # (1 - cos) a a^T
        j = np.argmax(np.linalg.norm(m, axis=-1), axis=-1)
        ax = m[np.arange(len(rb)), j]
        ax /= np.linalg.norm(ax, axis=-1, keepdims=True)
        sgn = np.sign(np.einsum("ki,ki->k", ax, w[big]))
        ax *= np.where(sgn == 0, 1.0, sgn)[:, None]
        out[big] = ax * ang[big][:, None]
    return out


def _expm(v: Array) -> Array:
    """Rotation matrices of rotation vectors (Rodrigues), shape (..., 3, 3)."""
    ang = np.linalg.norm(v, axis=-1)
    safe = np.where(ang > 0, ang, 1.0)
    k = v / safe[..., None]
    kx = np.zeros(v.shape[:-1] + (3, 3))
    kx[..., 0, 1], kx[..., 0, 2] = -k[..., 2], k[..., 1]
    kx[..., 1, 0], kx[..., 1, 2] = k[..., 2], -k[..., 0]
    kx[..., 2, 0], kx[..., 2, 1] = -k[..., 1], k[..., 0]
    s, c = np.sin(ang)[..., None, None], np.cos(ang)[..., None, None]
    return np.eye(3) + s * kx + (1.0 - c) * (kx @ kx)


@dataclass(frozen=True, eq=False)
class RigidFrames:
    """Rigid motions along a path: rotation ``R_i`` and origin ``t_i`` at parameter ``s_i``.

    Attributes
    ----------
    s : (k,) ndarray
        Non-decreasing knots (not all equal), k >= 1.
    rotation : (k, 3, 3) ndarray
        Proper rotations (orthonormal, det +1); columns (W, D, T): the images
        of profile x, profile y and the direction of travel.
    origin : (k, 3) ndarray
        Where the profile's origin goes.

    Raises
    ------
    GeometryError
        Shapes that do not match, knots that do not increase, or a rotation
        that is not one (``R^T R = I`` and ``det R = 1`` within 1e-9).

    Examples
    --------
    >>> import numpy as np
    >>> quarter = np.array([[0.0, -1, 0], [1, 0, 0], [0, 0, 1]])          # a quarter turn about z
    >>> fr = RigidFrames(np.array([0.0, 1.0]), np.stack([np.eye(3), quarter]), np.array([[0.0, 0, 0], [0, 0, 2]]))
    >>> r, t = fr.at([0.5])
    >>> np.round(r[0] @ [1.0, 0, 0], 6).tolist(), t[0].tolist()    # half way: an eighth turn, half way up
    ([0.707107, 0.707107, 0.0], [0.0, 0.0, 1.0])
    """

    s: Array
    rotation: Array
    origin: Array

    def __post_init__(self) -> None:
        s = np.atleast_1d(np.asarray(self.s, dtype=float))
        r = np.asarray(self.rotation, dtype=float)
        t = np.asarray(self.origin, dtype=float)
        k = len(s)
        if s.ndim != 1 or k < 1 or r.shape != (k, 3, 3) or t.shape != (k, 3):
            raise GeometryError(f"frames need s (k,), rotation (k, 3, 3), origin (k, 3); got {s.shape}, "
                                f"{r.shape}, {t.shape}")
        if not (np.all(np.isfinite(s)) and np.all(np.isfinite(r)) and np.all(np.isfinite(t))):
            raise GeometryError("frames must be finite")
        if k > 1 and not (np.all(np.diff(s) >= 0.0) and s[-1] > s[0]):
            raise GeometryError("frame knots must not decrease, and must not all be equal")
        err = np.abs(np.einsum("kji,kjl->kil", r, r) - np.eye(3)).max(axis=(1, 2))
        det = np.linalg.det(r)
        bad = np.flatnonzero((err > FRAME_TOL) | (np.abs(det - 1.0) > FRAME_TOL))
        if len(bad):
            i = int(bad[0])
            raise GeometryError(f"frame {i} is not a rotation: |R^T R - I| = {err[i]:.3g}, det R = {det[i]:.6g}")
        object.__setattr__(self, "s", s)
        object.__setattr__(self, "rotation", r)
        object.__setattr__(self, "origin", t)

    def __len__(self) -> int:
        return len(self.s)

    @classmethod
    def _unchecked(cls, s: Array, rotation: Array, origin: Array) -> RigidFrames:
        """Frames from arrays already known to be valid (no checks)."""
        out = object.__new__(cls)
        object.__setattr__(out, "s", s)
        object.__setattr__(out, "rotation", rotation)
        object.__setattr__(out, "origin", origin)
        return out

    @property
    def width(self) -> Array:
        """W at the knots (profile x), shape (k, 3)."""
        return self.rotation[:, :, 0]

    @property
    def depth(self) -> Array:
        """D at the knots (profile y), shape (k, 3)."""
        return self.rotation[:, :, 1]

    @property
    def tangent(self) -> Array:
        """T at the knots, shape (k, 3)."""
        return self.rotation[:, :, 2]

    @classmethod
    def from_frames(cls, origins: ArrayLike, frames: Frames, s: ArrayLike | None = None,
                    trusted: bool = False) -> RigidFrames:
        """The rigid motions of :class:`~auszug.meshing.frames.Frames` at the given origins.

        ``s`` defaults to the frames' arc length; ``trusted`` skips the checks
        (frames from :func:`sweep_frames` are orthonormal by construction).
        """
        r = np.stack([frames.width, frames.depth, frames.tangent], axis=2)
        knots = frames.arclength if s is None else np.asarray(s, dtype=float)
        if trusted:
            return cls._unchecked(knots, r, np.asarray(origins, dtype=float))
        return cls(knots, r, np.asarray(origins, dtype=float))

    @classmethod
    def rotation_minimising(cls, path: Path, width0: ArrayLike | None = None,
                            start_target: ArrayLike | None = None, end_target: ArrayLike | None = None,
                            period: float = math.pi) -> RigidFrames:
        """Rotation-minimising frames at the path's samples (double reflection, :func:`sweep_frames`).

        ``width0`` is the preferred W at the start (default: the first
        tangent's reference direction); the targets turn the frames to meet
        given directions at the ends, up to turns by ``period``.
        """
        w0 = reference_basis(path.tangents[:1])[0][0] if width0 is None else width0
        fr = sweep_frames(path.points, path.tangents, w0, start_target, end_target, period)
        return cls.from_frames(path.points, fr, path.knots)

    def at(self, s: ArrayLike) -> tuple[Array, Array]:
        """The motions at parameters ``s`` (clamped to the knots): rotations (..., 3, 3), origins (..., 3).

        Between knots i and i + 1 at fraction f: ``R = R_i expm(f log(R_i^T R_{i+1}))``
        and ``t = (1 - f) t_i + f t_{i+1}``; at the knots exactly ``(R_i, t_i)``.
        """
        ss = np.asarray(s, dtype=float)
        if len(self.s) == 1:
            shape = ss.shape
            return (np.broadcast_to(self.rotation[0], shape + (3, 3)).copy(),
                    np.broadcast_to(self.origin[0], shape + (3,)).copy())
        i, f = _interval(self.s, ss)
        r0, r1 = self.rotation[i], self.rotation[i + 1]
        rel = np.swapaxes(r0, -1, -2) @ r1
        r = r0 @ _expm(_rotvec(rel) * f[..., None])
        exact1 = f == 1.0
        r = np.where(exact1[..., None, None], r1, np.where((f == 0.0)[..., None, None], r0, r))
        t = (1.0 - f)[..., None] * self.origin[i] + f[..., None] * self.origin[i + 1]
        t = np.where(exact1[..., None], self.origin[i + 1], t)
        return r, t


# -- the sweep ----------------------------------------------------------------------------------


@lru_cache(maxsize=64)
def _grid_faces(n: int, m: int, closed: bool) -> IntArray:
    """Side triangles of an n-ring by m-point sweep (read-only, cached)."""
    j = np.arange(m if closed else m - 1)
    j1 = (j + 1) % m
    i = np.arange(n - 1)[:, None]
    a = i * m + j
    b = i * m + j1
    c = (i + 1) * m + j1
    d = (i + 1) * m + j
    f = np.stack([np.stack([a, b, c], -1), np.stack([a, c, d], -1)], axis=2).reshape(-1, 3).astype(np.int64)
    f.setflags(write=False)
    return f


def sweep_grid(origins: Array, width: Array, depth: Array, points: Array, closed: bool,
               cap: IntArray | None = None, cap_start: bool = True, cap_end: bool = True) -> tuple[Array, IntArray]:
    """The mesh kernel of every sweep: a ring of profile points per frame, quads split in two, caps.

    Parameters
    ----------
    origins, width, depth : (n, 3) ndarray
        Frame origins and the images of profile x and y.
    points : (m, 2) ndarray
        The profile polyline.
    closed : bool
    cap : (m - 2, 3) ndarray, optional
        The profile's triangulation (closed profiles): end caps.
    cap_start, cap_end : bool

    Returns
    -------
    vertices : (n m, 3) ndarray
        Ring after ring, vertex ``i m + j`` = ``origins[i] + x_j width[i] + y_j depth[i]``.
    faces : (k, 3) ndarray
        Outward-oriented for a counter-clockwise profile and right-handed frames.
    """
    n, m = len(origins), len(points)
    v = (origins[:, None, :] + points[None, :, 0, None] * width[:, None, :]
         + points[None, :, 1, None] * depth[:, None, :]).reshape(-1, 3)
    faces = [_grid_faces(n, m, closed)]
    if closed and cap is not None:
        if cap_start:
            faces.append(cap[:, ::-1])
        if cap_end:
            faces.append(cap + (n - 1) * m)
    return v, np.concatenate(faces) if len(faces) > 1 else faces[0].copy()


@dataclass(frozen=True, eq=False)
class Sweep:
    """A profile swept along a path by rigid frames: ``X(s, v) = t(s) + R(s) (x(v), y(v), 0)``.

    Parameters
    ----------
    profile : Profile
    path : Path
    frames : RigidFrames, optional
        Default :meth:`RigidFrames.rotation_minimising` along the path.

    Examples
    --------
    >>> import numpy as np
    >>> from auszug.meshing.profile import square
    >>> sw = Sweep(square(1.0), Path.polyline([[0, 0, 0], [0, 0, 1.0]]))
    >>> m = sw.mesh(); m.is_watertight, round(m.volume, 12)
    (True, 1.0)
    """

    profile: Profile
    path: Path
    frames: RigidFrames | None = None

    def __post_init__(self) -> None:
        if self.frames is None:
            object.__setattr__(self, "frames", RigidFrames.rotation_minimising(self.path))

    @property
    def rigid(self) -> RigidFrames:
        """The frames (never None)."""
        assert self.frames is not None  # set by __post_init__
        return self.frames

    @property
    def domain(self) -> tuple[float, float]:
        """The range of the path parameter covered by the frames."""
        return float(self.rigid.s[0]), float(self.rigid.s[-1])

    def frames_at(self, s: ArrayLike) -> tuple[Array, Array]:
        """Rotations (..., 3, 3) and origins (..., 3) at path parameters ``s`` (see :meth:`RigidFrames.at`)."""
        return self.rigid.at(s)

    def point(self, s: ArrayLike, v: ArrayLike) -> Array:
        """Points of the swept surface, shape (..., 3): path parameter ``s``, profile arc length ``v`` in [0, 1].

        ``s`` and ``v`` broadcast against each other; the profile is exact
        (:meth:`Profile.point`).
        """
        ss, vv = np.broadcast_arrays(np.asarray(s, dtype=float), np.asarray(v, dtype=float))
        r, t = self.frames_at(ss)
        xy = self.profile.point(vv)
        return t + xy[..., 0, None] * r[..., :, 0] + xy[..., 1, None] * r[..., :, 1]

    evaluate = point

    def grid(self, points: Array | None = None, cap_start: bool = True,
             cap_end: bool = True) -> tuple[Array, IntArray]:
        """Vertices and faces of the sweep (see :func:`sweep_grid`); ``points`` default the profile's vertices."""
        fr = self.rigid
        pts = self.profile.points if points is None else points
        if self.profile.closed and len(pts) < 3:
            raise GeometryError(f"profile {self.profile.name!r} has only {len(pts)} vertices; "
                                "sample its arcs to mesh it (mesh(per_arc=...) or mesh(tolerance=...))")
        cap = self.profile.cap if self.profile.closed and points is None else None
        if self.profile.closed and points is not None:
            from auszug.meshing.profile import triangulate_polygon

            cap = triangulate_polygon(pts)
        return sweep_grid(fr.origin, fr.width, fr.depth, pts, self.profile.closed, cap, cap_start, cap_end)

    def mesh(self, caps: bool = True, per_arc: int | None = None, tolerance: float | None = None) -> Mesh:
        """The triangle mesh: a ring at every frame knot, caps for closed profiles.

        ``per_arc`` or ``tolerance`` sample the profile's arcs more finely
        (:meth:`Profile.sample`); default its vertices.
        """
        pts = None if per_arc is None and tolerance is None else self.profile.sample(per_arc, tolerance)
        v, f = self.grid(pts, caps, caps)
        return Mesh(v, f, (Part("sweep", "member", -1, "", (0, len(v)), (0, len(f))),))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: the profile, the path's samples and the frames."""
        fr = self.rigid
        return {"profile": self.profile.to_dict(),
                "path": {"points": self.path.points.tolist(), "tangents": self.path.tangents.tolist(),
                         "s": self.path.knots.tolist()},
                "frames": {"s": fr.s.tolist(), "rotation": fr.rotation.tolist(), "origin": fr.origin.tolist()}}


# -- sweeps along planar loops with corners: lofts through offsets --------------------------------

#: Share of the key interval reserved for round joins at each corner.
_DELTA = 0.05


def loop_ring(curves: tuple[Curve, ...] | list[Curve], source: Any, is_join: Any, n_base: int,
              max_angle: float, chord: float, max_edge: float = 0.0) -> tuple[Array, Array]:
    """Sample an offset loop into a polygon whose points carry zip keys.

    Parameters
    ----------
    curves : sequence of Line or Arc
        The closed loop (an offset of a base loop of ``n_base`` curves).
    source, is_join : (m,) array_like
        As in :class:`auszug.geometry.offset.OffsetCurves`.
    n_base : int
        Number of curves of the base loop.
    max_angle, chord : float
        Arc sampling: angular step, or the angle of a chord deviating
        ``chord``, whichever is larger.
    max_edge : float
        Lines are split into pieces at most this long (0: not split).

    Returns
    -------
    points : (n, 2) ndarray
        The polygon, counter-clockwise, first point not repeated.
    keys : (n,) ndarray
        Increasing position along the base loop in ``[-d, n_base - d)``: a
        point on the offset of base curve ``i`` at fraction ``f`` of the piece
        has key ``i + d + (1 - 2 d) f``; points of a round join before curve
        ``i`` have keys in ``[i - d, i + d)``.
    """
    pts = []
    keys = []
    for c, src, join in zip(curves, source, is_join, strict=True):
        if isinstance(c, Arc):
            step = max_angle
            if chord < c.radius:
                step = max(step, 2.0 * math.acos(1.0 - chord / c.radius))
            n = max(1, math.ceil(abs(c.sweep) / min(step, math.pi / 3) - 1e-9))
            f = np.arange(n) / n
            th = c.theta0 + c.sweep * f
            pts.append(c.center + c.radius * np.stack([np.cos(th), np.sin(th)], axis=-1))
        else:
            n = max(1, math.ceil(c.length() / max_edge - 1e-9)) if max_edge > 0 else 1
            f = np.arange(n) / n
            pts.append(c.start + f[:, None] * (c.end - c.start))
        keys.append(src - _DELTA + 2.0 * _DELTA * f if join else src + _DELTA + (1.0 - 2.0 * _DELTA) * f)
    p = np.concatenate(pts)
    k = np.concatenate(keys)
    k = np.mod(k + _DELTA, n_base) - _DELTA
    start = int(np.argmin(k))
    return np.roll(p, -start, axis=0), np.roll(k, -start)


def zip_rings(ka: Array, kb: Array, period: float) -> IntArray:
    """Triangles joining ring A to ring B by their keys (a zipper), shape (na + nb, 3).

    Vertices ``0 .. na-1`` are ring A, ``na .. na+nb-1`` ring B; both rings
    are closed and their keys increase (modulo ``period``).

    Examples
    --------
    >>> zip_rings(np.array([0.0, 1.0]), np.array([0.0, 1.0]), 2.0).tolist()
    [[0, 1, 2], [1, 3, 2], [1, 0, 3], [0, 2, 3]]
    """
    na, nb = len(ka), len(kb)
    nxt_a = np.append(ka[1:], ka[0] + period)
    nxt_b = np.append(kb[1:], kb[0] + period)
    # advance the ring whose next key is smaller (A first on ties)
    allk = np.concatenate([nxt_a, nxt_b])
    order = np.argsort(allk, kind="stable")
    is_a = order < na
    ia = np.concatenate([[0], np.cumsum(is_a)])[:-1]
    ib = np.concatenate([[0], np.cumsum(~is_a)])[:-1]
    a0 = ia % na
    a1 = (ia + 1) % na
    b0 = ib % nb + na
    b1 = (ib + 1) % nb + na
    tri = np.where(is_a[:, None], np.stack([a0, a1, b0], 1), np.stack([a0, b1, b0], 1))
    return tri.astype(np.int64)


@dataclass(frozen=True)
class Loft:
    """The sweep of a profile along a closed planar loop, as rings in the loop's plane.

    Attributes
    ----------
    rings : list of (n_k, 2) ndarray
        One polygon per profile point: the loop offset by its inset (x),
        counter-clockwise.
    heights : list of float
        The profile point's y: how far the ring lies along the plane's normal.
    tris : (t, 3) ndarray
        Triangles between consecutive rings, indices into the concatenated rings.
    """

    rings: list[Array]
    heights: list[float]
    tris: IntArray


def offset_loft(loop: tuple[Curve, ...], levels: ArrayLike, max_angle: float, chord: float,
                max_edge: float = 0.0) -> Loft:
    """Mesh the sweep of a polyline profile along a closed planar loop of lines and arcs.

    The frames are planar: profile x along the loop's inward normal (its
    inset), profile y along the plane's normal. Every profile point
    ``(x, y)`` becomes the exact offset of the loop by ``x``
    (:func:`auszug.geometry.offset.offset_curves`), which on smooth stretches
    is the sweep's curve and at corners meets on the bisector (a round join
    where the offset moves outwards); consecutive rings are zipped by their
    position along the loop (:func:`zip_rings`), so corners connect to corners.

    Parameters
    ----------
    loop : tuple of Line or Arc
        Closed, counter-clockwise.
    levels : (k, 2) array_like
        The profile's points ``(inset, height)`` in drawing units.
    max_angle, chord, max_edge : float
        Sampling of the rings (see :func:`loop_ring`).

    Raises
    ------
    GeometryError
        If an inset closes the loop (its offset vanishes).
    """
    from auszug.geometry.offset import offset_curves

    lv = np.asarray(levels, dtype=float)
    n_base = len(loop)
    rings: list[Array] = []
    keys: list[Array] = []
    heights: list[float] = []
    cache: dict[float, tuple[Array, Array]] = {}
    for x, y in lv:
        d = float(x)
        if d not in cache:
            if d == 0.0:
                src = np.arange(n_base)
                cache[d] = loop_ring(loop, src, np.zeros(n_base, bool), n_base, max_angle, chord, max_edge)
            else:
                off = offset_curves(loop, d, closed=True)
                cache[d] = loop_ring(off.curves, off.source, off.is_join, n_base, max_angle, chord, max_edge)
        pts, k = cache[d]
        rings.append(pts)
        keys.append(k)
        heights.append(float(y))
    tris = []
    start = 0
    for i in range(len(rings) - 1):
        tris.append(zip_rings(keys[i], keys[i + 1], float(n_base)) + start)
        start += len(rings[i])
    return Loft(rings, heights, np.concatenate(tris) if tris else np.empty((0, 3), np.int64))
