"""The window as one watertight manifold mesh: profiles swept along every border, set into a wall.

Havemann and Fellner cut each region into the stone by sweeping its profile
along the border, "the profile plane orthogonal to the tangent of the curve;
at corner points ... continued onto the bisector plane" (2004, sec. 2.7), and
remove the self-intersections at sharp corners with a straight-skeleton
operator (``extrudestable``). Here every depth of a profile cuts the exact
offset of the region (:func:`auszug.geometry.offset.offset_curves`) at the
profile's inset: the offset keeps the circle centres, meets at the corners on
the bisector (the medial axis, for arcs), and drops the pieces that vanish,
so the sweep is exact and never self-intersects.

The solid is built directly, without Boolean operations:

* the wall's faces, with the reveal of the arch (the wall profile) from the
  wall face to the face of the tracery plate;
* the plate's face, a polygon with holes: the arch minus the regions' faces;
* per region a loft through the offsets at its profile's depths: a light runs
  to the middle of the plate, a recess (frame or blind region) to its floor,
  which is again a polygon with holes (the regions nested in it);
* the back half as the mirror image of the front half, sharing the vertices
  in the middle plane.

Adjacent rings of the loft are zipped by their position along the region's
border (which input curve, how far along it), so corners connect to corners.
Congruent regions (the sub-windows of a recursive style) are meshed once and
translated.

Coordinates of the mesh: x to the right and z up as x and y of the 2D window;
the wall's front face (towards the viewer) is ``y = -thickness / 2``, its
normal ``(0, -1, 0)``, as in the authors' call.

Examples
--------
>>> from auszug.tracery import build, window_mesh
>>> m = window_mesh(build("fig20a"))
>>> m.is_watertight, m.is_manifold
(True, True)
>>> n_edges = 3 * m.n_faces // 2
>>> (2 - (m.n_vertices - n_edges + m.n_faces)) // 2      # genus: one handle per light
7
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from auszug.errors import GeometryError
from auszug.geometry import TOL, Curve
from auszug.geometry.offset import offset_curves
from auszug.meshing import Loft, Mesh, Part, offset_loft, triangulate_polygon
from auszug.tracery._checks import ParameterError, integer, number
from auszug.tracery.model import Region, Tracery
from auszug.tracery.profile import Moulding

__all__ = ["window_mesh", "Resolution", "subdivide_profile"]

#: A recess may reach at most this share of the half slab (the rest stays solid wall).
SLAB_SHARE = 0.98

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]

@dataclass(frozen=True)
class Resolution:
    """How finely arcs and profiles are sampled.

    Attributes
    ----------
    max_angle : float
        Largest angle an arc sample may span (radians).
    chord : float
        Largest distance between an arc and its chords, relative to the
        window's span.
    per_arc : int
        Samples per arc of a profile.
    max_edge : float
        Longest straight edge along a border, relative to the window's span
        (long lines are split so that triangles stay compact).
    """

    max_angle: float = math.pi / 24
    chord: float = 4e-4
    per_arc: int = 4
    max_edge: float = 0.25


# -- profiles ----------------------------------------------------------------------------

def subdivide_profile(points: Array, sharp: NDArray[np.bool_], steps: int) -> tuple[Array, NDArray[np.bool_]]:
    """Catmull-Clark curve subdivision of a profile polyline, creases kept.

    Each step inserts edge midpoints and moves every smooth vertex to
    ``(p[i-1] + 6 p[i] + p[i+1]) / 8``; crease vertices (``sharp``) and the
    ends stay. This is Catmull-Clark on the swept quad strips in the profile
    direction with the sharp profile vertices as crease lines; along the border
    the exact arcs are sampled directly instead.

    Examples
    --------
    >>> p, s = subdivide_profile(np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 1.0]]), np.array([True, False, True]), 1)
    >>> p.tolist()
    [[0.0, 0.0], [0.5, 0.5], [1.0, 0.875], [1.5, 1.0], [2.0, 1.0]]
    """
    p, s = points, sharp
    for _ in range(steps):
        mid = 0.5 * (p[:-1] + p[1:])
        v = p.copy()
        inner = ~s[1:-1]
        v[1:-1][inner] = (p[:-2][inner] + 6.0 * p[1:-1][inner] + p[2:][inner]) / 8.0
        out = np.empty((2 * len(p) - 1, 2))
        out[0::2] = v
        out[1::2] = mid
        ns = np.zeros(len(out), dtype=bool)
        ns[0::2] = s
        p, s = out, ns
    return p, s


def _levels(profile: Moulding, res: Resolution, subdivide: int) -> Array:
    """The profile as (s, t) levels, consecutive duplicates removed, shape (k, 2)."""
    pts = profile.sample(res.per_arc)
    if subdivide:
        pts, _ = subdivide_profile(pts, profile.sharp(res.per_arc), subdivide)
    keep = np.ones(len(pts), dtype=bool)
    keep[1:] = np.any(np.abs(np.diff(pts, axis=0)) > 1e-12, axis=1)
    return pts[keep]


def _clip_levels(lv: Array, t_end: float) -> Array:
    """Levels cut at depth ``t_end`` (interpolated), extended to it at the last inset."""
    if lv[-1, 1] < t_end - 1e-12:
        return np.vstack([lv, [lv[-1, 0], t_end]])
    k = int(np.searchsorted(lv[:, 1], t_end - 1e-12))
    k = max(k, 1)
    a, b = lv[k - 1], lv[k]
    f = 0.0 if b[1] == a[1] else (t_end - a[1]) / (b[1] - a[1])
    s_end = a[0] + f * (b[0] - a[0])
    out = np.vstack([lv[:k], [s_end, t_end]])
    keep = np.ones(len(out), dtype=bool)
    keep[1:] = np.any(np.abs(np.diff(out, axis=0)) > 1e-12, axis=1)
    return out[keep]


# -- the builder -------------------------------------------------------------------------

class _Half:
    """Vertices and triangles of the front half, appended in blocks."""

    def __init__(self) -> None:
        self.verts: list[Array] = []
        self.faces: list[IntArray] = []
        self.n = 0

    def add(self, v: Array) -> int:
        start = self.n
        self.verts.append(v)
        self.n += len(v)
        return start

    def tri(self, f: IntArray) -> None:
        self.faces.append(f)


def _loft(region: Region, levels: Array, res: Resolution, chord: float, base: tuple[Curve, ...],
          max_edge: float) -> Loft:
    """The region's moulding: its profile (in border widths) swept along its border.

    Meshed through the exact offsets by :func:`auszug.meshing.sweepmodel.offset_loft`.
    """
    b = region.border
    try:
        return offset_loft(base, levels * b, res.max_angle, chord, max_edge)
    except GeometryError as e:
        bad = next((float(s) for s in levels[:, 0] if s != 0.0 and not _offsets(base, float(s) * b)), float("nan"))
        raise ParameterError(f"{region.id}: profile {region.profile.name!r}", bad,
                             "an inset that keeps the opening open", str(e)) from None


def _offsets(base: tuple[Curve, ...], d: float) -> bool:
    try:
        offset_curves(base, d, closed=True)
    except GeometryError:
        return False
    return True


def _max_inset(base: tuple[Curve, ...], want: float) -> float:
    """``want`` if the loop can be offset that far, else (nearly) the largest distance it can."""
    def ok(d: float) -> bool:
        try:
            offset_curves(base, d, closed=True)
        except GeometryError:
            return False
        return True

    if want <= 0.0 or ok(want):
        return want
    lo, hi = 0.0, want
    for _ in range(24):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)
    return lo


def window_mesh(tracery: Tracery, resolution: Resolution | None = None, subdivide: int = 0) -> Mesh:
    """One watertight, manifold triangle mesh of the window set into its wall.

    Parameters
    ----------
    tracery : Tracery
        From :func:`auszug.tracery.build`; its style gives the wall.
    resolution : Resolution, optional
    subdivide : int
        Catmull-Clark steps applied to the profiles (creases kept), 0-4.

    Returns
    -------
    Mesh
        One part ``"window"``; genus = number of lights.

    Raises
    ------
    ParameterError
        If the wall or the plate is too thin for the profiles' depths, the
        margin too small for the reveal, or an inset closes an opening.
    """
    res = resolution or Resolution()
    subdivide = integer("subdivide", subdivide, 0, 4)
    st = tracery.style
    wall = st.wall
    regions = tracery.regions
    arch = regions[0]
    if arch.group != "arch":
        raise GeometryError("the first region of a tracery must be its arch")
    span = float(tracery.params.span)
    chord = res.chord * span
    half_t = 0.5 * wall.thickness
    half_s = 0.5 * wall.slab
    f = arch.border
    front = _Half()
    children: dict[str, list[Region]] = {}
    for r in regions[1:]:
        children.setdefault(r.parent or "", []).append(r)

    # -- reveal: the arch widened by the wall profile, from the wall face to the plate face
    wlv = _levels(wall.profile, res, subdivide)
    smin = float(wlv[:, 0].min())
    apex_y = max(float(c.point(np.linspace(0, 1, 9))[:, 1].max()) for c in arch.curves)
    pts_arch = np.concatenate([c.start[None] for c in arch.curves])
    lo = np.array([pts_arch[:, 0].min(), pts_arch[:, 1].min()])
    hi = np.array([pts_arch[:, 0].max(), apex_y])
    number("wall.margin", wall.margin, -smin * f * 1.05 + 1e-9, why="the reveal must stay inside the wall")
    max_edge = res.max_edge * span
    reveal = _loft(arch, np.column_stack([wlv[:, 0], wlv[:, 1]]), res, chord, arch.curves, max_edge)
    depth_r = half_t - half_s
    starts = []
    for ring, t in zip(reveal.rings, wlv[:, 1], strict=True):
        y = -half_t + float(t) * depth_r
        starts.append(front.add(np.column_stack([ring[:, 0], np.full(len(ring), y), ring[:, 1]])))
    front.tri(reveal.tris + starts[0])
    outer_ring_start, outer_ring_len = starts[0], len(reveal.rings[0])
    arch_ring = (starts[-1], len(reveal.rings[-1]), reveal.rings[-1])

    # -- wall face (rectangle minus the reveal's outer ring) and the box sides
    x0, z0 = lo - wall.margin
    x1, z1 = hi + wall.margin
    corners = np.array([[x0, z0], [x1, z0], [x1, z1], [x0, z1]])
    c_front = front.add(np.column_stack([corners[:, 0], np.full(4, -half_t), corners[:, 1]]))
    c_mid = front.add(np.column_stack([corners[:, 0], np.zeros(4), corners[:, 1]]))
    tri = triangulate_polygon(corners, [reveal.rings[0]])
    idx = np.concatenate([np.arange(4) + c_front, np.arange(outer_ring_len) + outer_ring_start])
    front.tri(idx[tri])
    for i in range(4):
        j = (i + 1) % 4
        # outward sides: quad (front i, front j, mid j, mid i) seen from outside
        front.tri(np.array([[c_front + i, c_mid + j, c_front + j], [c_front + i, c_mid + i, c_mid + j]]))

    # -- regions: lofts (cached per template) and the faces/floors holding them
    lofts: dict[Any, Loft] = {}
    placed: dict[str, tuple[int, int, int]] = {}  # id -> (first ring start, its length, last ring start)

    def loft_of(r: Region) -> Loft:
        key = (r.template, r.role) if r.template >= 0 else r.id
        lf = lofts.get(key)
        if lf is None:
            base = tuple(c.transformed(np.eye(2), (-r.origin[0], -r.origin[1])) for c in r.curves) \
                if r.origin != (0.0, 0.0) else r.curves
            lv = _levels(r.profile, res, subdivide)
            y_face = -half_s + r.face
            if r.role == "light":
                t_mid = -y_face / r.border
                if t_mid <= 0:
                    raise ParameterError("wall.slab", wall.slab, "a plate thicker than the recesses it holds",
                                         f"{r.id} lies {r.face:.4g} deep")
                lv = _clip_levels(lv, t_mid)
            elif r.face + r.profile.depth * r.border >= half_s * SLAB_SHARE:
                deep = r.face + r.profile.depth * r.border
                raise ParameterError("wall.slab", wall.slab,
                                     f"a plate over {deep / (0.5 * SLAB_SHARE):.4g} thick (twice the "
                                     f"recesses' depth, {100 * (1 - SLAB_SHARE):g} % spare)",
                                     f"{r.id} reaches {deep:.4g} deep")
            smax = _max_inset(base, float(lv[:, 0].max()) * r.border) / r.border
            if smax < float(lv[:, 0].max()):
                # the moulding would close this small opening: flatten it to 90 % of what fits
                lv = lv.copy()
                lv[:, 0] = np.minimum(lv[:, 0], 0.9 * smax)
            lf = lofts[key] = _loft(r, lv, res, chord, base, max_edge)
        return lf

    for r in regions[1:]:
        lf = loft_of(r)
        y_face = -half_s + r.face
        ox, oz = r.origin
        n_tot = sum(len(g) for g in lf.rings)
        v = np.empty((n_tot, 3))
        k = 0
        for ring, y in zip(lf.rings, lf.heights, strict=True):
            n = len(ring)
            v[k:k + n, 0] = ring[:, 0] + ox
            v[k:k + n, 1] = y_face + y
            v[k:k + n, 2] = ring[:, 1] + oz
            k += n
        if r.role == "light":
            v[n_tot - len(lf.rings[-1]):, 1] = 0.0  # exactly in the middle plane
        s0 = front.add(v)
        front.tri(lf.tris + s0)
        placed[r.id] = (s0, len(lf.rings[0]), s0 + n_tot - len(lf.rings[-1]))

    # plate face: the arch ring minus the depth-0 regions' face rings
    floor_cache: dict[Any, IntArray] = {}

    def face_polygon(outer: tuple[int, int, Array], kids: list[Region], key: Any) -> None:
        idx = [np.arange(outer[1]) + outer[0]]
        for kid in kids:
            s0, n0, _ = placed[kid.id]
            idx.append(np.arange(n0) + s0)
        gidx = np.concatenate(idx)
        tri = floor_cache.get(key)
        if tri is None:
            rings2 = [outer[2]] + [lofts_first(kid) for kid in kids]
            tri = floor_cache[key] = triangulate_polygon(rings2[0], rings2[1:])
        front.tri(gidx[tri])

    def lofts_first(r: Region) -> Array:
        lf = loft_of(r)
        return lf.rings[0] + np.array(r.origin)

    face_polygon(arch_ring, children.get("arch", []), "arch")
    for r in regions[1:]:
        if r.role == "light":
            continue
        lf = loft_of(r)
        s0, n0, last = placed[r.id]
        floor = lf.rings[-1] + np.array(r.origin)
        key = ("floor", r.template) if r.template >= 0 else r.id
        face_polygon((last, len(floor), floor), children.get(r.id, []), key)

    # -- mirror the front half into the back half, sharing the middle plane
    v = np.concatenate(front.verts)
    fcs = np.concatenate(front.faces)
    on_mid = v[:, 1] == 0.0
    n = len(v)
    remap = np.arange(n, 2 * n)
    remap[on_mid] = np.nonzero(on_mid)[0]
    keep_back = ~on_mid
    back_new = np.cumsum(keep_back) - 1 + n
    remap[keep_back] = back_new[keep_back]
    vb = v[keep_back] * np.array([1.0, -1.0, 1.0])
    verts = np.concatenate([v, vb])
    faces = np.concatenate([fcs, remap[fcs][:, [0, 2, 1]]])
    return _finish(verts, faces)


def _finish(verts: Array, faces: IntArray) -> Mesh:
    """Drop degenerate triangles, orient outwards, wrap as a Mesh."""
    keep = (faces[:, 0] != faces[:, 1]) & (faces[:, 1] != faces[:, 2]) & (faces[:, 0] != faces[:, 2])
    faces = faces[keep]
    if Mesh._unchecked(verts, faces, ()).volume < 0:
        faces = faces[:, ::-1].copy()
    m = Mesh._unchecked(verts, faces, (Part("window", "solid", -1, "", (0, len(verts)), (0, len(faces))),))
    if TOL.strict and not m.is_manifold:  # invariant check of the test-suite's strict mode
        raise GeometryError("internal error: the window mesh is not a closed manifold")
    return m
