"""Meshes with known sweep structure, generated in code (seeded), for tests and benchmarks.

Every fixture is normalised (centred on its bounding-box centre, bounding-box diameter 1) and
carries its truth in those coordinates: the axis of a surface of revolution, the direction of an
extrusion, the profile planes of a moulding swept along a curved path. Noise is a displacement of
every vertex along its normal, Gaussian with deviation ``sigma`` (bounding-box diameter 1).

Examples
--------
>>> fx = revolved(n_profile=40, n_path=60)
>>> fx.vertices.shape, round(float(np.ptp(fx.vertices, axis=0) @ np.ptp(fx.vertices, axis=0)), 12)
((2400, 3), 1.0)
>>> fx.kind, np.round(fx.axis_direction, 6).tolist()
('rotation', [0.0, 0.0, 1.0])
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Sequence

import numpy as np
from numpy.typing import NDArray

from auszug.sweeps.mesh import vertex_normals

__all__ = [
    "Fixture",
    "gothic_base_profile",
    "extruded",
    "revolved",
    "helical",
    "moulding_along_ellipse",
    "moulding_along_cubic",
    "letter_g_profile",
    "closed_profile",
    "closed_along_cubic",
    "letter_g_along_cubic",
    "with_hole",
    "decimated",
    "double_translational",
    "bumps",
    "grid_faces",
    "SweptMembers",
    "swept_members",
    "SweepErrors",
    "sweep_errors",
]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]

# A Gothic base moulding, bottom to top, in (r, z): plinth face, plinth top, lower torus, fillet,
# scotia (hollow), fillet, upper torus, shaft. Each segment is ("line", end) or ("arc", end, bulge)
# with bulge = tan(swept angle / 4), positive counter-clockwise (turning left, so bulging to the right).
_BASE: tuple[tuple[float, float], tuple[tuple[Any, ...], ...]] = (
    (0.30, 0.00),
    (("line", (0.30, 0.05)),
     ("line", (0.24, 0.05)),
     ("arc", (0.24, 0.13), 1.0),        # lower torus: a half circle bulging outwards
     ("line", (0.22, 0.13)),
     ("arc", (0.20, 0.19), -0.6),       # scotia: a hollow bulging inwards
     ("line", (0.20, 0.22)),
     ("arc", (0.20, 0.27), 1.0),        # upper torus
     ("line", (0.17, 0.27)),
     ("line", (0.17, 0.34))),
)


@dataclass(frozen=True)
class Fixture:
    """A normalised test mesh and what is known about it.

    Attributes
    ----------
    name : str
    kind : str
        ``"translation"`` (extrusion), ``"rotation"`` (surface of revolution), ``"screw"``
        (helical surface), ``"moulding"``
        (a profile swept along a curved planar path, not kinematic) or ``"none"`` (no sweep).
    vertices : (n, 3) float array
        Bounding-box diameter 1, centred.
    faces : (m, 3) int array
    axis_direction : (3,) float array or None
        Rotation axis or translation direction (unit); None where there is none.
    axis_point : (3,) float array or None
        A point of the rotation axis.
    planes : (k, 4) float array
        True profile planes ``(n, d)`` with ``n . x = d`` (moulding fixtures), else empty.
    profile_length : float
        Arc length of the profile (normalised units).
    """

    name: str
    kind: str
    vertices: Array
    faces: IntArray
    axis_direction: Array | None
    axis_point: Array | None
    planes: Array
    profile_length: float


def gothic_base_profile(n: int = 100) -> tuple[Array, Array]:
    """Points ``(n, 2)`` in (r, z) of the base moulding, evenly spaced by arc length per segment.

    Corners are vertices. Also returns the arc-length parameter of each point.

    Examples
    --------
    >>> p, s = gothic_base_profile(60)
    >>> p.shape, bool(np.all(np.diff(s) > 0))
    ((60, 2), True)
    """
    start, segs = _BASE
    pieces: list[tuple[str, Array, Array, float]] = []
    cur = np.asarray(start, float)
    for seg in segs:
        end = np.asarray(seg[1], float)
        bulge = float(seg[2]) if seg[0] == "arc" else 0.0
        pieces.append((seg[0], cur, end, bulge))
        cur = end
    lengths = np.array([_seg_length(a, b, g) for _, a, b, g in pieces])
    total = lengths.sum()
    counts = np.maximum(2, np.round(lengths / total * (n - 1)).astype(int))
    counts[np.argmax(counts)] += (n - 1) - counts.sum()
    pts = [pieces[0][1][None]]
    for (_, a, b, g), k in zip(pieces, counts, strict=True):
        u = np.linspace(0.0, 1.0, k + 1)[1:]
        pts.append(_seg_points(a, b, g, u))
    p = np.vstack(pts)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
    return p, s


def _seg_length(a: Array, b: Array, bulge: float) -> float:
    chord = float(np.linalg.norm(b - a))
    if bulge == 0.0:
        return chord
    theta = 4 * np.arctan(abs(bulge))
    return chord / (2 * np.sin(theta / 2)) * theta


def _seg_points(a: Array, b: Array, bulge: float, u: Array) -> Array:
    if bulge == 0.0:
        return a + u[:, None] * (b - a)
    theta = 4 * np.arctan(bulge)  # signed swept angle, positive counter-clockwise
    chord = b - a
    c = np.linalg.norm(chord)
    r = c / (2 * np.sin(abs(theta) / 2))
    left = np.array([-chord[1], chord[0]]) / c
    centre = (a + b) / 2 + left * (c / 2) / np.tan(theta / 2)
    a0 = np.arctan2(a[1] - centre[1], a[0] - centre[0])
    ang = a0 + theta * u
    return centre + r * np.stack([np.cos(ang), np.sin(ang)], axis=1)


def grid_faces(n_rows: int, n_cols: int) -> IntArray:
    """Triangles of an ``n_rows x n_cols`` vertex grid (row-major), two per quad, alternating diagonals."""
    i, j = np.meshgrid(np.arange(n_rows - 1), np.arange(n_cols - 1), indexing="ij")
    a = (i * n_cols + j).ravel()
    b, c, d = a + 1, a + n_cols, a + n_cols + 1
    alt = ((i + j) % 2 == 0).ravel()
    t1 = np.where(alt[:, None], np.stack([a, b, d], 1), np.stack([a, b, c], 1))
    t2 = np.where(alt[:, None], np.stack([a, d, c], 1), np.stack([b, d, c], 1))
    return np.vstack([t1, t2]).astype(np.int64)


def _finish(name: str, kind: str, v: Array, f: IntArray, sigma: float, seed: int,
            axis: Array | None, point: Array | None, planes: Array, plen: float) -> Fixture:
    lo, hi = v.min(0), v.max(0)
    centre, diam = (lo + hi) / 2, float(np.linalg.norm(hi - lo))
    v = (v - centre) / diam
    if point is not None:
        point = (point - centre) / diam
    if len(planes):
        n = planes[:, :3]
        planes = np.column_stack([n, (planes[:, 3] - n @ centre) / diam])
    if sigma > 0:
        rng = np.random.default_rng(seed)
        v = v + rng.normal(0.0, sigma, len(v))[:, None] * vertex_normals(v, f)
    return Fixture(name, kind, v, f, axis, point, planes, plen / diam)


def extruded(n_profile: int = 60, n_path: int = 120, length: float = 0.8, sigma: float = 0.0,
             seed: int = 0) -> Fixture:
    """The base moulding extruded along the x axis (a translational sweep)."""
    p, s = gothic_base_profile(n_profile)
    x = np.linspace(0.0, length, n_path)
    v = np.column_stack([np.repeat(x, n_profile), np.tile(p[:, 0], n_path), np.tile(p[:, 1], n_path)])
    f = grid_faces(n_path, n_profile)
    return _finish("extruded", "translation", v, f, sigma, seed, np.array([1.0, 0, 0]), None,
                   np.empty((0, 4)), float(s[-1]))


def revolved(n_profile: int = 60, n_path: int = 120, degrees: float = 300.0, sigma: float = 0.0,
             seed: int = 0) -> Fixture:
    """The base moulding revolved about the z axis by ``degrees`` (a surface of revolution)."""
    p, s = gothic_base_profile(n_profile)
    th = np.radians(np.linspace(0.0, degrees, n_path))
    r, z = np.tile(p[:, 0], n_path), np.tile(p[:, 1], n_path)
    t = np.repeat(th, n_profile)
    v = np.column_stack([r * np.cos(t), r * np.sin(t), z])
    f = grid_faces(n_path, n_profile)
    return _finish("revolved", "rotation", v, f, sigma, seed, np.array([0, 0, 1.0]), np.zeros(3),
                   np.empty((0, 4)), float(s[-1]))


def helical(n_profile: int = 60, n_path: int = 240, degrees: float = 540.0, pitch: float = 0.1,
            sigma: float = 0.0, seed: int = 0) -> Fixture:
    """The base moulding screwed about the z axis by ``degrees``, rising ``pitch`` per radian (a helical surface).

    ``axis_point`` is the origin (before normalisation); the pitch in normalised units is
    ``pitch / diameter`` (the fixture's ``profile_length`` is normalised the same way).
    """
    p, s = gothic_base_profile(n_profile)
    th = np.radians(np.linspace(0.0, degrees, n_path))
    r, z = np.tile(p[:, 0], n_path), np.tile(p[:, 1], n_path)
    t = np.repeat(th, n_profile)
    v = np.column_stack([r * np.cos(t), r * np.sin(t), z + pitch * t])
    f = grid_faces(n_path, n_profile)
    return _finish("helical", "screw", v, f, sigma, seed, np.array([0, 0, 1.0]), np.zeros(3),
                   np.empty((0, 4)), float(s[-1]))


def moulding_along_ellipse(n_profile: int = 60, n_path: int = 160, a: float = 0.6, b: float = 0.4,
                           n_planes: int = 60, sigma: float = 0.0, seed: int = 0) -> Fixture:
    """The base moulding swept along a half ellipse (an elliptical arch), profile in the normal planes.

    The profile's r runs along the ellipse's outward normal from the path (r - 0.15 >= 0), z
    vertically, so the profile's plane at parameter t is the normal plane of the path there: a
    moulding (profile) surface, not kinematic. ``planes`` samples those true profile planes over
    the middle 90 % of the path (the ends' planes meet only the mesh's boundary).
    """
    p, s = gothic_base_profile(n_profile)
    t = np.linspace(0.0, np.pi, n_path)
    path = np.column_stack([a * np.cos(t), b * np.sin(t), np.zeros_like(t)])
    tan = np.column_stack([-a * np.sin(t), b * np.cos(t), np.zeros_like(t)])
    tan /= np.linalg.norm(tan, axis=1, keepdims=True)
    out = np.column_stack([tan[:, 1], -tan[:, 0], np.zeros_like(t)])  # outward normal (ccw path)
    off = p[:, 0] - 0.15
    v = (path[:, None, :] + off[None, :, None] * out[:, None, :]
         + p[None, :, 1, None] * np.array([0, 0, 1.0])[None, None, :]).reshape(-1, 3)
    f = grid_faces(n_path, n_profile)
    tq = np.linspace(0.05 * np.pi, 0.95 * np.pi, n_planes)
    pq = np.column_stack([a * np.cos(tq), b * np.sin(tq), np.zeros_like(tq)])
    nq = np.column_stack([-a * np.sin(tq), b * np.cos(tq), np.zeros_like(tq)])
    nq /= np.linalg.norm(nq, axis=1, keepdims=True)
    planes = np.column_stack([nq, np.einsum("ij,ij->i", nq, pq)])
    return _finish("moulding", "moulding", v, f, sigma, seed, None, None, planes, float(s[-1]))


def _cubic() -> Any:
    """The fixtures' non-planar cubic Bezier: ``bez(t) -> (points (k, 3), unit tangents (k, 3))``."""
    ctrl = np.array([[0.0, 0.0, 0.0], [0.7, 0.9, 0.5], [1.4, -0.6, 0.9], [2.1, 0.3, 0.2]])

    def bez(t: Array) -> tuple[Array, Array]:
        b = np.stack([(1 - t) ** 3, 3 * t * (1 - t) ** 2, 3 * t**2 * (1 - t), t**3], 1)
        db = np.stack([-3 * (1 - t) ** 2, 3 * (1 - t) ** 2 - 6 * t * (1 - t), 6 * t * (1 - t) - 3 * t**2, 3 * t**2], 1)
        tan = db @ ctrl
        return b @ ctrl, tan / np.linalg.norm(tan, axis=1, keepdims=True)

    return bez


def _along_cubic(name: str, prof: Array, n_path: int, twist: float, n_planes: int, sigma: float, seed: int,
                 jitter: float = 0.0, closed: bool = False) -> Fixture:
    """The 2-d profile ``prof (n, 2)`` (centred on the path) swept along the cubic with ``twist`` degrees.

    ``jitter`` > 0 remeshes: every vertex moves along the surface by up to ``jitter`` of the grid's
    spacing in both directions (path parameter and profile arc length), seeded, so the triangles
    are irregular while every vertex stays exactly on the swept surface. ``closed``: the profile is
    a closed curve (its last point joined to its first; not with ``jitter``), the tube open at its
    two ends.
    """
    from auszug.meshing.frames import sweep_frames

    bez = _cubic()
    fine = 8 if jitter > 0 else 1     # the remeshed version picks its vertices from a finer path
    t = np.linspace(0.0, 1.0, (n_path - 1) * fine + 1)
    path, tan = bez(t)
    fr = sweep_frames(path, tan, [0.0, 0.0, 1.0])
    ang = np.radians(twist) * fr.arclength / fr.arclength[-1]
    wdt = np.cos(ang)[:, None] * fr.width + np.sin(ang)[:, None] * fr.depth
    dep = -np.sin(ang)[:, None] * fr.width + np.cos(ang)[:, None] * fr.depth
    n = len(prof)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(prof, axis=0), axis=1))])
    length = float(s[-1] + np.linalg.norm(prof[0] - prof[-1])) if closed else float(s[-1])
    rows = np.repeat(np.arange(n_path) * fine, n)
    arc = np.tile(s, n_path)
    if jitter > 0:
        rng = np.random.default_rng(seed + 2000)
        inner_rows = (rows > 0) & (rows < (n_path - 1) * fine)
        step = np.round(rng.uniform(-jitter, jitter, len(rows)) * fine).astype(int)
        rows = np.where(inner_rows, rows + step, rows)
        ds = np.diff(s)
        j = np.tile(np.arange(n), n_path)
        inner_cols = (j > 0) & (j < n - 1)
        shift = rng.uniform(-jitter, jitter, len(arc)) * np.where(inner_cols, np.minimum(ds[np.minimum(j, n - 2)],
                                                                                          ds[np.maximum(j - 1, 0)]), 0)
        arc = arc + shift
    px, py = np.interp(arc, s, prof[:, 0]), np.interp(arc, s, prof[:, 1])
    v = path[rows] + px[:, None] * wdt[rows] + py[:, None] * dep[rows]
    if closed:   # one more column, the first again, merged into the first
        g = grid_faces(n_path, n + 1)
        f = (g // (n + 1)) * n + (g % (n + 1)) % n
    else:
        f = grid_faces(n_path, n)
    pq, nq = bez(np.linspace(0.05, 0.95, n_planes))
    planes = np.column_stack([nq, np.einsum("ij,ij->i", nq, pq)])
    return _finish(name, "moulding", v, f, sigma, seed, None, None, planes, length)


def moulding_along_cubic(n_profile: int = 60, n_path: int = 160, twist: float = 120.0, n_planes: int = 60,
                         scale: float = 2.0, sigma: float = 0.0, seed: int = 0, jitter: float = 0.0) -> Fixture:
    """The base moulding swept along a non-planar cubic Bezier with ``twist`` degrees of twist.

    The profile (centred on the path, scaled by ``scale``) lies in the path's normal planes, carried by
    rotation-minimising frames turned linearly by up to ``twist`` degrees: a general sweep whose
    straight segments sweep twisted ruled surfaces, not cylinders or planes, so no part of it is
    kinematic. ``planes`` samples the true profile planes over the middle 90 % of the path.
    ``jitter`` > 0 gives a remeshed version (irregular triangles, vertices still on the surface).
    """
    p, _ = gothic_base_profile(n_profile)
    return _along_cubic("cubic", scale * (p - np.array([0.235, 0.17])), n_path, twist, n_planes, sigma, seed, jitter)


def letter_g_profile(n: int = 80, radius: float = 0.16) -> Array:
    """Points ``(n, 2)`` of a letter G centred on its bounding box.

    An arc of 280 degrees from the upper right round the left to the lower right, up the right
    side to the middle, then a bar inwards.
    """
    arc_n = int(0.75 * n)
    a = np.radians(np.linspace(40.0, 320.0, arc_n))
    arc = radius * np.column_stack([np.cos(a), np.sin(a)])
    end = arc[-1]
    up = np.column_stack([np.full(n // 8, end[0]), np.linspace(end[1], 0.0, n // 8 + 1)[1:]])
    bar = np.column_stack([np.linspace(end[0], 0.2 * radius, n - arc_n - n // 8 + 1)[1:],
                           np.zeros(n - arc_n - n // 8)])
    g = np.vstack([arc, up, bar])
    return g - (g.min(axis=0) + g.max(axis=0)) / 2


def letter_g_along_cubic(n_path: int = 160, twist: float = 120.0, n_planes: int = 60, sigma: float = 0.0,
                         seed: int = 0) -> Fixture:
    """A letter-G profile swept along the cubic with twist, like :func:`moulding_along_cubic`.

    The profile is :func:`letter_g_profile` (an arc and lines).
    """
    return _along_cubic("letter_g", letter_g_profile(), n_path, twist, n_planes, sigma, seed)


def closed_profile(n: int = 96, radius: float = 0.075) -> Array:
    """Points ``(n, 2)`` of a closed, non-symmetric rounded quatrefoil centred on the origin.

    The polar curve ``r = radius (1 + 0.22 cos 4a + 0.12 cos a + 0.08 sin 2a)``: four rounded
    lobes of different sizes, so no rotation about the origin but the identity maps it to itself
    (``cos a``) and no reflection does (``cos a`` allows only ``a -> -a``, which ``sin 2a`` breaks):
    no rigid motion but the identity maps the curve onto itself, reversed or not. Its last point
    is not its first (the curve closes from the last to the first).
    """
    a = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    r = radius * (1 + 0.22 * np.cos(4 * a) + 0.12 * np.cos(a) + 0.08 * np.sin(2 * a))
    return np.column_stack([r * np.cos(a), r * np.sin(a)])


def closed_along_cubic(n_profile: int = 96, n_path: int = 160, twist: float = 120.0, n_planes: int = 60,
                       radius: float = 0.075, sigma: float = 0.0, seed: int = 0) -> Fixture:
    """A closed profile (:func:`closed_profile`) swept along the cubic with twist, like :func:`moulding_along_cubic`.

    A tube open at its two ends; the profile lies in the path's normal planes (``planes``, over
    the middle 90 % of the path), ``profile_length`` is the whole closed curve's length.
    """
    return _along_cubic("closed", closed_profile(n_profile, radius), n_path, twist, n_planes, sigma, seed,
                        closed=True)


def with_hole(fx: Fixture, radius: float = 0.06, seed: int = 0) -> Fixture:
    """The fixture with a hole; the truth is unchanged.

    Faces whose centroid lies within ``radius`` of the vertex nearest the mesh's mean are removed
    (unused vertices dropped).
    """
    c = fx.vertices[fx.faces].mean(axis=1)
    middle = fx.vertices[np.argmin(np.linalg.norm(fx.vertices - fx.vertices.mean(axis=0), axis=1))]
    keep = np.linalg.norm(c - middle, axis=1) > radius
    used, inv = np.unique(fx.faces[keep], return_inverse=True)
    return Fixture(fx.name + "_hole", fx.kind, fx.vertices[used], inv.reshape(-1, 3).astype(np.int64),
                   fx.axis_direction, fx.axis_point, fx.planes, fx.profile_length)


def decimated(fx: Fixture, faces: int) -> Fixture:
    """The fixture decimated to about ``faces`` triangles by edge collapses; the truth is unchanged.

    libigl ``decimate``: shortest edge first, merged at its midpoint, so the vertices leave the
    true surface by the chords' sag (the bounding box is as before up to the collapses).
    """
    import igl

    out = igl.decimate(np.asfortranarray(fx.vertices), np.asfortranarray(fx.faces.astype(np.int32)), int(faces))
    u, g = np.asarray(out[0], float), np.asarray(out[1], np.int64)
    return Fixture(fx.name + "_decimated", fx.kind, np.ascontiguousarray(u), np.ascontiguousarray(g),
                   fx.axis_direction, fx.axis_point, fx.planes, fx.profile_length)


def double_translational(n_profile: int = 60, n_path: int = 120, length: float = 0.8, rise: float = 0.15,
                         sigma: float = 0.0, seed: int = 0) -> Fixture:
    """The base moulding translated (never turned) along the arch ``z = rise sin(pi x / length)``.

    A double translational surface: every profile plane is ``x = const`` (``planes``), the motion a
    pure translation along a curved path, so it is no kinematic surface (no single direction).
    """
    p, s = gothic_base_profile(n_profile)
    x = np.linspace(0.0, length, n_path)
    h = rise * np.sin(np.pi * x / length)
    v = np.column_stack([np.repeat(x, n_profile), np.tile(p[:, 0], n_path),
                         np.repeat(h, n_profile) + np.tile(p[:, 1], n_path)])
    planes = np.column_stack([np.tile([1.0, 0.0, 0.0], (n_path, 1)), x])
    return _finish("double_translational", "moulding", v, grid_faces(n_path, n_profile), sigma, seed, None, None,
                   planes, float(s[-1]))


def bumps(n: int = 90, n_bumps: int = 40, sigma: float = 0.0, seed: int = 0) -> Fixture:
    """A height field of random Gaussian bumps over the unit square: no sweep."""
    rng = np.random.default_rng(seed + 1000)
    u = np.linspace(0.0, 1.0, n)
    x, y = np.meshgrid(u, u, indexing="ij")
    z = np.zeros_like(x)
    for cx, cy, h, w in zip(rng.uniform(0, 1, n_bumps), rng.uniform(0, 1, n_bumps),
                            rng.uniform(-0.08, 0.08, n_bumps), rng.uniform(0.06, 0.14, n_bumps), strict=True):
        z += h * np.exp(-((x - cx) ** 2 + (y - cy) ** 2) / (2 * w * w))
    v = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    return _finish("bumps", "none", v, grid_faces(n, n), sigma, seed, None, None, np.empty((0, 4)), 0.0)


# -- members of curve networks (microarch), swept by meshing's sweep model --------------------------


@dataclass(frozen=True)
class SweptMembers:
    """Members of a curve network swept with a look, normalised, with their true profile and motion.

    Attributes
    ----------
    name : str
    vertices : (n, 3) float array
        Bounding-box diameter 1, centred (noise, if any, added after normalising).
    faces : (m, 3) int array
        The members' triangles (caps and mirror-plane cuts included), unwelded between members.
    profile : (k, 2) float array
        The true profile, densely sampled on its exact outline, in the members' frame (normalised units).
    closed : bool
        Whether the profile is closed.
    runs : tuple of RigidFrames
        One per smooth run of every member (meshing's sweep model, normalised): the profile point
        ``(x, y)`` at path parameter ``s`` is ``origin(s) + R(s) (x, y, 0)``.
    planes : (q, 4) float array
        True profile planes ``(n, d)``, ``n . x = d``: the runs' normal planes over the middle 90 %
        of each run.
    profile_length : float
        Length of the profile (normalised units).
    sigma : float
        Deviation of the normal noise (normalised units).
    """

    name: str
    vertices: Array
    faces: IntArray
    profile: Array
    closed: bool
    runs: tuple[Any, ...]
    planes: Array
    profile_length: float
    sigma: float = 0.0


def swept_members(network: Any, members: Sequence[int] | None = None, look: Any = None, n_planes: int = 20,
                  sigma: float = 0.0, seed: int = 0, name: str = "members") -> SweptMembers:
    """Members of ``network`` swept by meshing's public pipeline, normalised, with their truth.

    The members are :func:`auszug.meshing.members_of` (every basic piece swept once, not
    replicated, with the look's profile, frames, caps and mirror-plane cuts); each member's
    :attr:`~auszug.meshing.Member.sweeps` is its exact sweep (profile, path, rigid frames), so the
    truth is known exactly. No microarch internals are read: ``network`` is any value meshing
    accepts (a ``CurveNetwork`` or a producer of one, e.g. ``microarch.Network``).

    Parameters
    ----------
    network : CurveNetwork or a producer of one
    members : sequence of int, optional
        Indices into the swept members (default all).
    look : meshing.Look, optional
        Default ``Look("bar")`` (a square bar, the default member look).
    n_planes : int
        True profile planes per run, over the middle 90 % of its path.
    sigma : float
        Deviation of a displacement of every vertex along its normal (after normalising).
    seed : int
    name : str

    Returns
    -------
    SweptMembers

    Raises
    ------
    GeometryError
        No member selected, or an index out of range.
    """
    from auszug.errors import GeometryError
    from auszug.meshing import Look, RigidFrames, members_of

    lk = Look("bar") if look is None else look
    allm = members_of(network, lk)
    idx = list(range(len(allm))) if members is None else [int(i) for i in members]
    if not idx or any(not 0 <= i < len(allm) for i in idx):
        raise GeometryError(f"members {idx} not in the network's {len(allm)} swept member(s)")
    chosen = [allm[i] for i in idx]
    verts, faces, off = [], [], 0
    for mb in chosen:
        verts.append(np.asarray(mb.vertices, float))
        faces.append(np.asarray(mb.faces, np.int64) + off)
        off += len(mb.vertices)
    v, f = np.vstack(verts), np.vstack(faces)
    lo, hi = v.min(axis=0), v.max(axis=0)
    centre, diam = (lo + hi) / 2, float(np.linalg.norm(hi - lo))
    v = (v - centre) / diam
    prof = chosen[0].sweeps[0].profile
    closed = bool(prof.closed)
    dense = prof.point(np.linspace(0.0, 1.0, 64 * prof.n + (0 if closed else 1), endpoint=not closed)) / diam
    runs, planes = [], []
    for mb in chosen:
        for sw in mb.sweeps:
            fr = sw.rigid
            r = RigidFrames(fr.s / diam, fr.rotation, (fr.origin - centre) / diam)
            runs.append(r)
            u = np.linspace(0.0, 1.0, 2 * n_planes + 1)[1:-1:2]     # the middles of n_planes equal slices
            s = r.s[0] + (0.05 + 0.9 * u) * (r.s[-1] - r.s[0])         # of the middle 90 % of the run
            rot, o = r.at(s)
            n = rot[:, :, 2]
            planes.append(np.column_stack([n, np.einsum("ij,ij->i", n, o)]))
    if sigma > 0:
        rng = np.random.default_rng(seed)
        v = v + rng.normal(0.0, sigma, len(v))[:, None] * vertex_normals(v, f)
    return SweptMembers(name, v, f, dense, closed, tuple(runs), np.vstack(planes), float(prof.length) / diam,
                        float(sigma))


@dataclass(frozen=True)
class SweepErrors:
    """How far a detection's patches are from a :class:`SweptMembers` truth (normalised units).

    Attributes
    ----------
    recall : float
        Share of the true profile planes with a found profile plane within 2 degrees and 0.005
        (:func:`~auszug.sweeps.planes.plane_recall`; 8 planes per knot interval of every patch).
    hausdorff : (p,) float array
        Per patch: Hausdorff distance of its profile at the middle knot of its motion (the
        reference rib: the ends may be grown over a member's cut or capped end) to the true
        profile placed in the true profile plane through that profile's centroid.
    rotation : (p,) float array
        Per patch: median over its motion's other knots of the angle (degrees) between the found
        map from the reference rib to the knot and the true map from the reference rib's true
        profile plane to the plane through the moved centroid.
    translation : (p,) float array
        Per patch: median over the same knots of the distance between where the found map and
        the true one take the reference profile's centroid.
    run : (p,) int array
        Per patch: the true run it was compared with (the one whose path passes nearest the
        reference profile's centroid).
    """

    recall: float
    hausdorff: Array
    rotation: Array
    translation: Array
    run: IntArray

    @property
    def median_rotation(self) -> float:
        """Median of the patches' rotation errors (degrees; nan without patches)."""
        return float(np.median(self.rotation)) if len(self.rotation) else float("nan")

    @property
    def median_translation(self) -> float:
        """Median of the patches' translation errors (nan without patches)."""
        return float(np.median(self.translation)) if len(self.translation) else float("nan")


def _true_param(run: Any, points: Array) -> Array:
    """Per point, the path parameter of the true run's profile plane through it (nearest sample, one Newton step)."""
    s = np.linspace(run.s[0], run.s[-1], 16 * len(run.s))
    rot, o = run.at(s)
    near = np.argmin(np.linalg.norm(points[:, None, :] - o[None], axis=2), axis=1)
    t = rot[near, :, 2]
    return np.clip(s[near] + np.einsum("ij,ij->i", points - o[near], t), run.s[0], run.s[-1])


def sweep_errors(report: Any, truth: SweptMembers) -> SweepErrors:
    """Compare a :class:`~auszug.sweeps.detect.SweepReport` of ``truth``'s mesh with the truth.

    The report must be of ``(truth.vertices, truth.faces)`` (its patches in those coordinates).

    Parameters
    ----------
    report : SweepReport
    truth : SweptMembers

    Returns
    -------
    SweepErrors
    """
    from auszug.sweeps.general import motion_planes
    from auszug.sweeps.patches import polyline_hausdorff
    from auszug.sweeps.planes import plane_recall

    normals, offsets, haus, rots, trans, which = [], [], [], [], [], []
    for p in report.patches:
        nn, dd = motion_planes(p.profile, p.motion, 8)
        normals.append(nn)
        offsets.append(dd)
        m = len(p.motion) // 2                               # the middle rib: the reference
        prof = p.swept(p.motion.t[m:m + 1])[0]
        c = prof.mean(axis=0)
        dist = [float(np.min(np.linalg.norm(r.origin - c, axis=1))) for r in truth.runs]
        k = int(np.argmin(dist))
        run = truth.runs[k]
        r0, o0 = run.at(_true_param(run, c[None]))
        placed = o0[0] + truth.profile @ r0[0][:, :2].T
        haus.append(polyline_hausdorff(prof, placed, p.closed, truth.closed))
        others = np.delete(np.arange(len(p.motion)), m)
        rm, tm = p.motion.rotation[m], p.motion.translation[m]
        found_r = p.motion.rotation[others] @ rm.T             # found maps from the middle rib to the others
        found_t = p.motion.translation[others] - np.einsum("kij,j->ki", found_r, tm)
        ck = np.einsum("kij,j->ki", found_r, c) + found_t
        rk, ok = run.at(_true_param(run, ck))
        rel = rk @ r0[0].T                                    # true maps from the middle rib's plane
        img = np.einsum("kij,j->ki", rel, c - o0[0]) + ok
        cosang = (np.einsum("kij,kij->k", found_r, rel) - 1) / 2
        rots.append(float(np.median(np.degrees(np.arccos(np.clip(cosang, -1.0, 1.0))))))
        trans.append(float(np.median(np.linalg.norm(img - ck, axis=1))))
        which.append(k)
    recall = (plane_recall(truth.planes, np.vstack(normals), np.concatenate(offsets)) if normals else 0.0)
    return SweepErrors(recall, np.array(haus), np.array(rots), np.array(trans), np.array(which, np.int64))
