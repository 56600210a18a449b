"""Cutting triangle meshes by planes (vectorised Sutherland-Hodgman), and the cut outlines.

Crossing points are computed once per undirected edge, from its smaller
vertex index to its larger, so neighbouring triangles share them exactly and
the cut mesh stays connected.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

__all__ = ["clip_halfspace", "plane_loops", "compact"]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]


def compact(vertices: Array, faces: IntArray, *extra: NDArray) -> tuple:
    """Drop vertices no face uses; returns (vertices, faces, *extra per-vertex arrays)."""
    used = np.zeros(len(vertices), dtype=bool)
    used[faces.reshape(-1)] = True
    if used.all():
        return (vertices, faces) + tuple(extra)
    remap = np.cumsum(used) - 1
    idx = np.flatnonzero(used)
    return (vertices.take(idx, axis=0), remap[faces]) + tuple(e.take(idx, axis=0) for e in extra)


def clip_halfspace(
    vertices: Array,
    faces: IntArray,
    origin: Array,
    normal: Array,
    eps: float,
    protect: NDArray[np.bool_] | None = None,
) -> tuple[Array, IntArray, NDArray[np.int64], NDArray[np.int64]]:
    """Keep the part of a mesh on the side ``(x - origin) . normal >= 0``.

    Parameters
    ----------
    vertices : (n, 3) ndarray
    faces : (m, 3) ndarray of int
    origin, normal : (3,) ndarray
        A point of the plane and its normal (towards the kept side).
    eps : float
        Vertices closer than this to the plane are taken to lie on it.
    protect : (n,) bool ndarray, optional
        Vertices that are kept whatever their side (faces using only kept or
        protected vertices are kept whole).

    Returns
    -------
    vertices : (k, 3) ndarray
        The old vertices followed by the new ones on the plane (unused old
        vertices are not removed; see :func:`compact`).
    faces : (l, 3) ndarray
    source : (k,) ndarray of int
        For every vertex the old vertex it comes from (for a new vertex, the
        smaller index of its edge).
    face_source : (l,) ndarray of int
        For every face the old face it is (part of).
    """
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces, dtype=np.int64)
    n = len(v)
    d = (v - origin) @ normal
    d[np.abs(d) <= eps] = 0.0
    if protect is not None:
        d[protect] = np.maximum(d[protect], 1.0)
    # column-wise masks: much faster than reductions along the short axis
    pv, nv = d > 0, d < 0
    f0, f1, f2 = f[:, 0], f[:, 1], f[:, 2]
    pos = pv[f0] | pv[f1] | pv[f2]
    neg = nv[f0] | nv[f1] | nv[f2]
    src = np.arange(n)
    if not neg.any():
        kept = np.flatnonzero(pos)
        return v, f.take(kept, axis=0), src, kept
    keep = np.flatnonzero(pos & ~neg)
    mixed = np.flatnonzero(pos & neg)
    df = d[f.take(mixed, axis=0)]
    fm = f.take(mixed, axis=0)
    dm = df
    i = fm
    j = np.roll(fm, -1, axis=1)
    di, dj = dm, np.roll(dm, -1, axis=1)
    cross = di * dj < 0
    lo = np.minimum(i, j)
    hi = np.maximum(i, j)
    key = lo * np.int64(n) + hi
    ukey, inv = np.unique(key[cross], return_inverse=True)
    ulo, uhi = ukey // n, ukey % n
    dlo, dhi = d[ulo], d[uhi]
    w = dlo / (dlo - dhi)
    newv = v[ulo] + (v[uhi] - v[ulo]) * w[:, None]
    new_idx = np.full(key.shape, -1, dtype=np.int64)
    new_idx[cross] = n + inv.reshape(-1)
    # slots per triangle: vertex k (if kept), then the crossing on edge k (if any)
    slots = np.empty((len(fm), 6), dtype=np.int64)
    slots[:, 0::2] = i
    slots[:, 1::2] = new_idx
    valid = np.empty((len(fm), 6), dtype=bool)
    valid[:, 0::2] = di >= 0
    valid[:, 1::2] = cross
    order = np.argsort(~valid, axis=1, kind="stable")
    poly = np.take_along_axis(slots, order, axis=1)
    cnt = valid.sum(axis=1)
    tri1 = poly[:, [0, 1, 2]]
    quad = cnt == 4
    tri2 = poly[quad][:, [0, 2, 3]]
    out_f = np.concatenate([f.take(keep, axis=0), tri1, tri2])
    out_v = np.concatenate([v, newv])
    fsrc = np.concatenate([keep, mixed, mixed[quad]])
    return out_v, out_f, np.concatenate([src, ulo]), fsrc


def plane_loops(vertices: Array, faces: IntArray, origin: Array, normal: Array, eps: float) -> list[IntArray]:
    """Closed chains of boundary edges lying on a plane, each as vertex indices in boundary order.

    Boundary edges are those used by one face only; a loop is returned in the
    direction of its faces' edges.
    """
    from auszug.meshing.mesh import boundary_edges

    be = boundary_edges(faces)
    if len(be) == 0:
        return []
    d = np.abs((vertices - origin) @ normal)
    on = (d[be[:, 0]] <= eps) & (d[be[:, 1]] <= eps)
    be = be[on]
    nxt = {int(a): int(b) for a, b in be}
    loops: list[IntArray] = []
    seen: set[int] = set()
    for start in nxt:
        if start in seen:
            continue
        loop = [start]
        seen.add(start)
        cur = nxt[start]
        while cur != start and cur in nxt and cur not in seen:
            loop.append(cur)
            seen.add(cur)
            cur = nxt[cur]
        if cur == start and len(loop) >= 3:
            loops.append(np.asarray(loop, dtype=np.int64))
    return loops
