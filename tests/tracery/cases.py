"""Canonical fixtures and strong checks shared by the tracery tests.

Fixtures follow the paper: the equilateral arch, a lancet, a four-centred
(depressed) arch, the round arch (degenerate: the two centres coincide), the
trefoil and quatrefoil rosettes, and the prototype window of the worked call.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import strategies as st

from auszug.geometry import Arc, Line
from auszug.tracery import PointedArch, WindowParams

#: The paper's call (-1,0,2) (1,0,2) 4.0 1.25 (0,-1,0) 0.2 0.1 0.05 gothic-window.
PAPER = WindowParams(span=2.0, height=4.0, excess=1.25, drop=0.2, outer=0.1, inner=0.05)

ARCHES = {
    "equilateral": PointedArch(-1.0, 1.0, 4.0, 1.0, bottom=0.0),
    "lancet": PointedArch(-1.0, 1.0, 4.0, 1.25, bottom=0.0),
    "four-centred": PointedArch(-1.0, 1.0, 4.0, 0.75, bottom=0.0),
    "round": PointedArch(-1.0, 1.0, 4.0, 0.5, bottom=0.0),
    "off-centre": PointedArch(2.5, 3.1, 7.0, 1.6, bottom=5.5),
}

SQUARE = (Line((0, 0), (2, 0)), Line((2, 0), (2, 2)), Line((2, 2), (0, 2)), Line((0, 2), (0, 0)))
CIRCLE = (Arc((0.3, -0.2), 1.5, 0.4, 2 * math.pi),)

valid_excess = st.floats(0.5, 3.0)
spans = st.floats(0.1, 10.0)


@st.composite
def window_params(draw: st.DrawFn) -> WindowParams:
    """Window parameters around the paper's, most of them valid."""
    span = draw(st.floats(0.5, 4.0))
    return WindowParams(
        span=span,
        height=span * draw(st.floats(0.8, 4.0)),
        excess=draw(st.floats(0.9, 2.0)),
        drop=span * draw(st.floats(0.0, 0.2)),
        outer=span * draw(st.floats(0.0, 0.08)),
        inner=span * draw(st.floats(0.005, 0.03)),
        x=draw(st.floats(-5, 5)),
        y=draw(st.floats(-5, 5)),
    )


def dist_to_curves(p: np.ndarray, curves) -> float:
    """Distance of point ``p`` to the nearest of ``curves`` (by projection)."""
    return min(float(np.hypot(*(c.point(c.project(p)) - p))) for c in curves)


# -- mesh checks -------------------------------------------------------------------------

def euler_genus(vertices: np.ndarray, faces: np.ndarray) -> float:
    """Genus of a closed connected surface from its Euler characteristic."""
    e = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    n_edges = len(np.unique(e, axis=0))
    return (2 - (len(vertices) - n_edges + len(faces))) / 2


def n_components(faces: np.ndarray, n_vertices: int) -> int:
    """Connected components of the face graph."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    a = np.concatenate([faces[:, 0], faces[:, 1], faces[:, 2]])
    b = np.concatenate([faces[:, 1], faces[:, 2], faces[:, 0]])
    g = coo_matrix((np.ones(len(a)), (a, b)), shape=(n_vertices, n_vertices))
    used = np.unique(faces)
    n, labels = connected_components(g, directed=False)
    return len(np.unique(labels[used]))


def _candidate_pairs(v: np.ndarray, f: np.ndarray) -> np.ndarray:
    """Pairs (i < j) of triangles whose bounding boxes share a cell of a uniform grid."""
    tri = v[f]
    lo, hi = tri.min(1), tri.max(1)
    edge = np.linalg.norm(tri[:, 1] - tri[:, 0], axis=1)
    cell = max(float(np.median(edge)) * 2.0, 1e-9)
    origin = lo.min(0)
    i0 = np.floor((lo - origin) / cell).astype(np.int64)
    i1 = np.floor((hi - origin) / cell).astype(np.int64)
    ext = i1 - i0 + 1
    cnt = ext.prod(1)
    t = np.repeat(np.arange(len(f)), cnt)
    k = np.arange(len(t)) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    ex = ext[t]
    cx = i0[t, 0] + k % ex[:, 0]
    cy = i0[t, 1] + (k // ex[:, 0]) % ex[:, 1]
    cz = i0[t, 2] + k // (ex[:, 0] * ex[:, 1])
    key = (cx * 1_000_003 + cy) * 1_000_033 + cz
    order = np.argsort(key)
    key, t = key[order], t[order]
    starts = np.nonzero(np.r_[True, key[1:] != key[:-1]])[0]
    sizes = np.diff(np.r_[starts, len(key)])
    pairs = []
    for m in np.unique(sizes[sizes > 1]):
        g = starts[sizes == m]
        idx = t[g[:, None] + np.arange(m)[None]]
        a, b = np.triu_indices(m, 1)
        pairs.append(np.stack([idx[:, a].ravel(), idx[:, b].ravel()], 1))
    if not pairs:
        return np.empty((0, 2), np.int64)
    p = np.concatenate(pairs)
    n = np.int64(len(f))
    key = np.unique(np.minimum(p[:, 0], p[:, 1]) * n + np.maximum(p[:, 0], p[:, 1]))
    return np.stack([key // n, key % n], axis=1)


def _segments_hit(p0: np.ndarray, p1: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray,
                  eps: float) -> np.ndarray:
    """Whether each segment p0-p1 crosses the interior of triangle abc (Moller-Trumbore)."""
    d = p1 - p0
    e1, e2 = b - a, c - a
    h = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, h)
    ok = np.abs(det) > 1e-15
    inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    s = p0 - a
    u = inv * np.einsum("ij,ij->i", s, h)
    q = np.cross(s, e1)
    w = inv * np.einsum("ij,ij->i", d, q)
    t = inv * np.einsum("ij,ij->i", e2, q)
    return ok & (u > eps) & (w > eps) & (u + w < 1 - eps) & (t > eps) & (t < 1 - eps)


def self_intersections(vertices: np.ndarray, faces: np.ndarray, eps: float = 1e-7) -> int:
    """Number of pairs of triangles (sharing no vertex) where an edge of one pierces the other."""
    v, f = np.asarray(vertices, float), np.asarray(faces, np.int64)
    pairs = _candidate_pairs(v, f)
    if not len(pairs):
        return 0
    fa, fb = f[pairs[:, 0]], f[pairs[:, 1]]
    share = (fa[:, :, None] == fb[:, None, :]).any(axis=(1, 2))
    pairs = pairs[~share]
    hits = np.zeros(len(pairs), dtype=bool)
    for s0 in range(0, len(pairs), 200_000):
        pr = pairs[s0:s0 + 200_000]
        A, B = v[f[pr[:, 0]]], v[f[pr[:, 1]]]
        h = np.zeros(len(pr), dtype=bool)
        for X, Y in ((A, B), (B, A)):
            for i, j in ((0, 1), (1, 2), (2, 0)):
                h |= _segments_hit(X[:, i], X[:, j], Y[:, 0], Y[:, 1], Y[:, 2], eps)
        hits[s0:s0 + 200_000] = h
    return int(hits.sum())
