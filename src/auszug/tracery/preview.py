"""A fast preview mesh of a window, for live views (the studio's tracery page).

:func:`auszug.tracery.window_mesh` builds the finished window: exact offsets at
every profile depth, zipped lofts, one watertight manifold solid (about 100 ms
for Fig. 20h). A live view needs a new mesh within a few milliseconds, so the
preview cuts two corners and keeps the look:

* each region's border is sampled once (coarser arcs: ``max_angle``,
  ``chord``), and the profile's insets are *vertex offsets* of that polygon
  (along the corner bisectors, the miter capped), not exact offsets, so
  sharp concave corners may fold over slightly;
* a profile is sampled ``per_arc`` times per arc (:data:`PREVIEW_DETAIL`), and
  a flat face needs no samples along it: profile points on the straight line
  through their neighbours are left out (a light's last face, continued to the
  middle plane, is one strip, not two);
* every region is meshed on its own (its profile swept as quad strips, its
  recess floor triangulated with its children's openings as holes), the
  back half is the mirror image of the front half (or left to the viewer,
  ``back=False``), and nothing is zipped: the preview is neither watertight
  nor manifold (the recess floors are earcut's fills as they are,
  ``triangulate_polygon(..., manifold=False)``). Export uses
  :func:`~auszug.tracery.window_mesh`.

Every triangle faces out of the stone (counter-clockwise seen from outside), so
a viewer may cull back faces; in the front half (``y <= 0``) that means every
face looks to the front (``-y``) or sideways, apart from slivers where a sharp
concave corner folds.

Coordinates as :func:`~auszug.tracery.window_mesh`: x right, z up (the 2D
window's x and y), the wall's front face at ``y = -thickness / 2``.

Examples
--------
>>> from auszug.tracery import build
>>> from auszug.tracery.preview import preview_mesh
>>> v, f = preview_mesh(build("fig20a"))
>>> v.shape[1], f.shape[1], bool(f.max() < len(v))
(3, 3, True)
>>> bool(abs(v[:, 1].min() + 0.45) < 1e-6)   # the wall's front face, thickness 0.9
True
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from auszug.geometry import Arc, Curve
from auszug.meshing import triangulate_polygon
from auszug.tracery.model import Region, Tracery

__all__ = ["preview_mesh", "PREVIEW_MAX_ANGLE", "PREVIEW_CHORD", "PREVIEW_DETAIL"]

#: Largest angle of an arc sample in the preview (radians).
PREVIEW_MAX_ANGLE = math.pi / 12
#: Largest chord deviation of the preview, relative to the window's span.
PREVIEW_CHORD = 2e-3
#: Samples per arc of a region's profile in the preview (the finished mesh subdivides further).
PREVIEW_DETAIL = 1
#: Profile points this close to the line through their neighbours (profile units: the border) are
#: left out: the face there is flat.
_FLAT = 1e-9
#: Largest miter factor of a vertex offset (sharp corners). Exact offsets have none; 3 cut the
#: tips of Fig. 20's fillet lights short by up to 4 % of the span (test_preview's silhouette test).
_MITER = 8.0

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]


def _inward(p: Array) -> tuple[Array, Array]:
    """Per vertex of a counter-clockwise loop (m, 2): the offset directions for a unit inset, (m, 2) each.

    ``p + s * d_in`` for insets ``s >= 0``, ``p + s * d_out`` for outsets ``s < 0``; both along
    the corner's bisector. Where the offset lines meet (a convex corner inset, a reflex corner
    outset) the vertex goes to their meeting point (the miter, as an exact offset's sharp
    corner; capped at :data:`_MITER` times ``|s|``); where they part (the exact offset rounds
    the corner with an arc of radius ``|s|``), it goes ``|s|`` along the bisector, onto that arc.
    """
    return _inward_loops(p, np.array([0, len(p)]))


def _inward_loops(p: Array, starts: IntArray) -> tuple[Array, Array]:
    """:func:`_inward` of many loops at once: loop ``k`` is ``p[starts[k]:starts[k + 1]]``."""
    idx = np.arange(len(p))
    first = np.repeat(starts[:-1], np.diff(starts))
    last = np.repeat(starts[1:] - 1, np.diff(starts))
    nxt = np.where(idx == last, first, idx + 1)
    prv = np.where(idx == first, last, idx - 1)
    e = p[nxt] - p                                              # the edge leaving each vertex
    ln = np.hypot(e[:, 0], e[:, 1])
    ln[ln == 0.0] = 1.0
    n = np.empty_like(e)
    n[:, 0] = -e[:, 1] / ln                                     # left of each edge: inside
    n[:, 1] = e[:, 0] / ln
    b = n + n[prv]
    bl = np.hypot(b[:, 0], b[:, 1])
    bad = bl < 1e-9
    bl[bad] = 1.0
    b = b / bl[:, None]
    b[bad] = n[bad]
    cos = b[:, 0] * n[:, 0] + b[:, 1] * n[:, 1]
    miter = 1.0 / np.maximum(cos, 1.0 / _MITER)
    e_in = e[prv]                                               # the edge arriving at each vertex
    convex = e_in[:, 0] * e[:, 1] - e_in[:, 1] * e[:, 0] > 0.0  # a left turn of a ccw loop
    d_in: Array = b * np.where(convex, miter, 1.0)[:, None]
    d_out: Array = b * np.where(convex, 1.0, miter)[:, None]
    return d_in, d_out


def _strips(start: int, m: int, k: int) -> IntArray:
    """Triangles joining k consecutive closed rings of m vertices each, starting at vertex ``start``."""
    i = np.arange(m)
    j = np.empty(m, np.int64)
    j[:-1] = i[1:]
    j[-1] = 0
    base = start + m * np.arange(k - 1)[:, None]                 # (k-1, 1)
    a, b = base + i, base + j
    out = np.empty((k - 1, m, 2, 3), np.int64)                   # per quad (a, b, d) and (a, d, c)
    out[:, :, 0, 0] = a
    out[:, :, 0, 1] = b
    out[:, :, 0, 2] = b + m
    out[:, :, 1, 0] = a
    out[:, :, 1, 1] = b + m
    out[:, :, 1, 2] = a + m
    res: IntArray = out.reshape(-1, 3)
    return res


class _Builder:
    """Vertex and face blocks; ``starts[k]`` is the first vertex of ``verts[k]``."""

    def __init__(self) -> None:
        self.verts: list[Array] = []
        self.faces: list[IntArray] = []
        self.starts: list[int] = []
        self.n = 0

    def add(self, v: Array, f: IntArray) -> None:
        """A block of vertices (k, 3) and its faces (indices from 0)."""
        self.starts.append(self.n)
        self.faces.append(f + self.n)
        self.verts.append(v)
        self.n += len(v)

    def rings(self, p: Array, d: tuple[Array, Array], levels: Array, unit: float, y0: float, dy: float) -> Array:
        """Rings ``p + d * s * unit`` at depths ``y0 + t * dy`` for the (s, t) levels; the last ring (m, 2).

        ``d`` is (for insets s >= 0, for outsets s < 0), as :func:`_inward` gives them.
        """
        m = len(p)
        s = levels[:, 0] * unit
        dd = np.where((s >= 0.0)[:, None, None], d[0][None, :, :], d[1][None, :, :])
        xy = p[None, :, :] + s[:, None, None] * dd
        y = y0 + levels[:, 1] * dy
        v = np.empty((len(levels), m, 3))
        v[:, :, 0] = xy[:, :, 0]
        v[:, :, 1] = y[:, None]
        v[:, :, 2] = xy[:, :, 1]
        self.add(v.reshape(-1, 3), _strips(0, m, len(levels)))
        last: Array = xy[-1]
        return last

    def cap(self, outer: Array, holes: list[Array], y: float, flip: bool = False) -> None:
        """A flat face at depth y: ``outer`` (ccw) minus ``holes``, facing -y (or +y if ``flip``)."""
        try:
            tri = triangulate_polygon(outer, holes, manifold=False)
        except Exception:   # a preview shows what it can; export reports errors
            return
        pts = np.concatenate([outer, *holes]) if holes else outer
        v = np.column_stack([pts[:, 0], np.full(len(pts), y), pts[:, 1]])
        # ccw in (x, z) is ccw seen from -y (x right, z up): the triangles face -y as they are
        self.add(v, tri[:, ::-1] if flip else tri)


def _flat_out(lv: Array) -> Array:
    """The profile points (k, 2) without repeats and without points inside a straight run."""
    keep = np.ones(len(lv), dtype=bool)
    keep[1:] = np.any(np.abs(np.diff(lv, axis=0)) > 1e-12, axis=1)
    lv = lv[keep]
    if len(lv) < 3:
        return lv
    a, b = lv[1:-1] - lv[:-2], lv[2:] - lv[1:-1]
    la, lb = np.hypot(a[:, 0], a[:, 1]), np.hypot(b[:, 0], b[:, 1])
    cross = a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    straight = (np.abs(cross) <= _FLAT * la * lb) & (a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1] > 0)
    keep = np.ones(len(lv), dtype=bool)
    keep[1:-1] = ~straight
    out: Array = lv[keep]
    return out


def _levels(r: Region, per_arc: int) -> Array:
    return _flat_out(r.profile.sample(per_arc))


def _sample(curves: tuple[Curve, ...], max_angle: float, chord: float) -> Array:
    """:func:`~auszug.tracery.model.polygon` of the loop, the same points, its arcs in one numpy pass."""
    return _sample_loops([curves], max_angle, chord)[0]


def _sample_loops(loops: list[tuple[Curve, ...]], max_angle: float, chord: float) -> tuple[Array, IntArray]:
    """:func:`_sample` of many loops at once: the points (n, 2), loop ``k`` at ``starts[k]:starts[k + 1]``."""
    fixed_at: list[int] = []
    fixed: list[Array] = []
    arcs: list[tuple[int, int, float, float, float, float, float]] = []
    starts = [0]
    at = 0
    for curves in loops:
        for c in curves:
            if isinstance(c, Arc):
                r = c.radius
                step = max_angle
                if chord < r:
                    step = max(step, 2.0 * math.acos(1.0 - chord / r))
                step = min(step, math.pi / 4)
                n = max(1, math.ceil(abs(c.sweep) / step - 1e-9))
                cx, cy = c.center.tolist()
                arcs.append((at, n, cx, cy, r, c.theta0, c.sweep))
                at += n
            else:
                fixed_at.append(at)
                fixed.append(c.start)
                at += 1
        starts.append(at)
    out = np.empty((at, 2))
    if fixed:
        out[fixed_at] = fixed
    if arcs:
        a = np.array(arcs)
        first, n = a[:, 0].astype(np.int64), a[:, 1].astype(np.int64)
        k = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)     # the sample's number in its arc
        idx = np.repeat(first, n) + k
        t = k / np.repeat(a[:, 1], n)
        ang = np.repeat(a[:, 5], n) + t * np.repeat(a[:, 6], n)
        r = np.repeat(a[:, 4], n)
        out[idx, 0] = np.repeat(a[:, 2], n) + r * np.cos(ang)
        out[idx, 1] = np.repeat(a[:, 3], n) + r * np.sin(ang)
    return out, np.array(starts, dtype=np.int64)


def _ring_mesh(p: Array, d: tuple[Array, Array], at: IntArray, m: IntArray, levels: Array, lat: IntArray,
               unit: Array, y0: Array, dy: Array) -> tuple[Array, IntArray, IntArray, IntArray]:
    """:meth:`_Builder.rings` of many regions at once.

    Region ``r`` sweeps the loop ``p[at[r]:at[r] + m[r]]`` (directions ``d``) through its levels
    ``levels[lat[r]:lat[r + 1]]`` (s, t), scaled by ``unit[r]``, at depths ``y0[r] + t * dy[r]``.

    Returns
    -------
    vertices : (n, 3) ndarray
    faces : (f, 3) ndarray
        Indices from 0 into ``vertices``.
    vstart, fstart : (R + 1,) ndarray
        Region ``r``'s vertices and faces are ``[vstart[r], vstart[r + 1])`` and likewise.
    """
    k = np.diff(lat)
    nv = m * k
    vstart = np.concatenate([[0], np.cumsum(nv)])
    reg = np.repeat(np.arange(len(m)), nv)
    j = np.arange(int(vstart[-1])) - vstart[reg]
    mm = m[reg]
    lev, i = j // mm, j % mm
    row = lat[reg] + lev
    sv = levels[row, 0] * unit[reg]
    src = at[reg] + i
    dd = np.where((sv >= 0.0)[:, None], d[0][src], d[1][src])
    v = np.empty((len(j), 3))
    v[:, 0] = p[src, 0] + sv * dd[:, 0]
    v[:, 1] = y0[reg] + levels[row, 1] * dy[reg]
    v[:, 2] = p[src, 1] + sv * dd[:, 1]
    nq = m * np.maximum(k - 1, 0)
    fq = np.concatenate([[0], np.cumsum(nq)])
    qreg = np.repeat(np.arange(len(m)), nq)
    q = np.arange(int(fq[-1])) - fq[qreg]
    qm = m[qreg]
    ql, qi = q // qm, q % qm
    a = vstart[qreg] + ql * qm + qi
    b = vstart[qreg] + ql * qm + (qi + 1) % qm
    f = np.empty((len(q), 2, 3), np.int64)                       # per quad (a, b, b') and (a, b', a')
    f[:, 0, 0] = a
    f[:, 0, 1] = b
    f[:, 0, 2] = b + qm
    f[:, 1, 0] = a
    f[:, 1, 1] = b + qm
    f[:, 1, 2] = a + qm
    return v, f.reshape(-1, 3), vstart, 2 * fq


def preview_mesh(tracery: Tracery, max_angle: float = PREVIEW_MAX_ANGLE, chord: float = PREVIEW_CHORD,
                 per_arc: int = PREVIEW_DETAIL, back: bool = True) -> tuple[NDArray[np.float32], NDArray[np.uint32]]:
    """Triangles that look like the window: profiles swept along the sampled borders, not united.

    Parameters
    ----------
    tracery : Tracery
        From :func:`auszug.tracery.build`.
    max_angle : float
        Largest angle an arc sample spans (radians).
    chord : float
        Largest chord deviation, relative to the window's span.
    per_arc : int
        Samples per arc of a profile.
    back : bool
        Include the back half (the mirror image of the front half in the
        middle plane ``y = 0``); without it only ``y <= 0`` is meshed, and a
        viewer can draw the back half as a mirrored instance of the front.

    Returns
    -------
    vertices : (n, 3) float32 ndarray
    faces : (m, 3) uint32 ndarray
        Counter-clockwise seen from outside.
    """
    st = tracery.style
    wall = st.wall
    regions = tracery.regions
    chord_abs = chord * float(tracery.params.span)
    half_t, half_s = 0.5 * wall.thickness, 0.5 * wall.slab
    children: dict[str, list[int]] = {}
    for i, r in enumerate(regions[1:], 1):
        children.setdefault(r.parent or "", []).append(i)
    # congruent regions (the sub-windows of a recursive style) are meshed once and translated
    first: dict[int, int] = {}
    meshed: list[int] = []
    for i, r in enumerate(regions[1:], 1):
        if r.template < 0 or r.template not in first:
            meshed.append(i)
            if r.template >= 0:
                first[r.template] = i
    floors = [i for i in meshed if regions[i].role == "frame"]
    need = sorted({0, *meshed, *(k for i in [0, *floors] for k in children.get(regions[i].id, []))})
    pts, starts = _sample_loops([regions[i].curves for i in need], max_angle, chord_abs)
    d_all = _inward_loops(pts, starts)
    where = {i: n for n, i in enumerate(need)}

    def poly(i: int) -> Array:
        return pts[starts[where[i]]:starts[where[i] + 1]]

    levels: dict[tuple[int, float, float], Array] = {}

    def lv_of(r: Region) -> Array:
        """The region's (s, t) levels; a light's end at the middle plane."""
        key = (id(r.profile), r.face, r.border) if r.role == "light" else (id(r.profile), 0.0, 0.0)
        lv = levels.get(key)
        if lv is None:
            lv = _levels(r, per_arc)
            if r.role == "light":
                y0 = -half_s + r.face
                if y0 + lv[-1, 1] * r.border > 0.0:
                    lv = lv[y0 + lv[:, 1] * r.border <= 0.0]
                if len(lv):
                    lv = _flat_out(np.vstack([lv, [lv[-1, 0], -y0 / r.border]]))
            levels[key] = lv
        return lv

    out = _Builder()
    # the arch: the reveal in the wall, the wall's face round it, the plate's face
    r0, p = regions[0], poly(0)
    n0 = where[0]
    d = (d_all[0][starts[n0]:starts[n0 + 1]], d_all[1][starts[n0]:starts[n0 + 1]])
    lv = lv_of(r0)
    out.rings(p, d, lv, r0.border, -half_t, half_t - half_s)
    s0 = float(lv[0, 0]) * r0.border
    wide = p + d[0 if s0 >= 0 else 1] * s0
    lo, hi = p.min(0) - wall.margin, p.max(0) + wall.margin     # the wall: margin round the arch
    box = np.array([[lo[0], lo[1]], [hi[0], lo[1]], [hi[0], hi[1]], [lo[0], hi[1]]])
    out.cap(box, [wide[::-1]], -half_t)
    # its sides, facing out of the box (a clockwise loop's strips face away from its inside)
    flat = np.zeros_like(box)
    out.rings(box[::-1], (flat, flat), np.array([[0.0, 0.0], [0.0, 1.0]]), 1.0, -half_t, half_t)
    out.cap(p, [poly(k)[::-1] for k in children.get(r0.id, [])], -half_s)

    # every other region's profile swept along its border, all in one pass
    lvs = [lv_of(regions[i]) for i in meshed]
    rs = [regions[i] for i in meshed]
    at = np.array([starts[where[i]] for i in meshed], dtype=np.int64)
    m = np.array([starts[where[i] + 1] - starts[where[i]] for i in meshed], dtype=np.int64)
    lat = np.concatenate([[0], np.cumsum([len(x) for x in lvs])]).astype(np.int64)
    unit = np.array([r.border for r in rs])
    y0 = np.array([-half_s + r.face for r in rs])
    lv_cat = np.concatenate(lvs) if lvs else np.empty((0, 2))
    rv, rf, vstart, fstart = _ring_mesh(pts, d_all, at, m, lv_cat, lat, unit, y0, unit)
    out.add(rv, rf)
    caps: dict[int, tuple[int, int]] = {}                      # region -> its cap's block
    for n, i in enumerate(meshed):
        r = rs[n]
        if r.role == "light" or not len(lvs[n]):
            continue
        floor = rv[vstart[n + 1] - m[n]:vstart[n + 1]][:, [0, 2]]
        k = len(out.verts)
        out.cap(floor, [poly(c)[::-1] for c in children.get(r.id, [])] if r.role == "frame" else [],
                y0[n] + lvs[n][-1, 1] * r.border)
        if len(out.verts) > k:
            caps[i] = (k, out.starts[k])
    # the translated copies: the first region's strips and floor, moved by the difference of origins
    own = {i: n for n, i in enumerate(meshed)}
    for i, r in enumerate(regions[1:], 1):
        if r.template < 0 or first[r.template] == i:
            continue
        j = first[r.template]
        n = own[j]
        o = regions[j].origin
        shift = np.array([r.origin[0] - o[0], 0.0, r.origin[1] - o[1]])
        out.add(rv[vstart[n]:vstart[n + 1]] + shift, rf[fstart[n]:fstart[n + 1]] - vstart[n])
        if j in caps:
            k, s_k = caps[j]
            out.add(out.verts[k] + shift, out.faces[k] - s_k)
    v = np.concatenate(out.verts)
    f = np.concatenate(out.faces)
    if not back:
        return v.astype(np.float32), f.astype(np.uint32)
    mirror = v * np.array([1.0, -1.0, 1.0])
    verts = np.concatenate([v, mirror]).astype(np.float32)
    faces = np.concatenate([f, f[:, ::-1] + len(v)]).astype(np.uint32)
    return verts, faces
