"""Sampling the space of planes (paper sec. 1.3): geodesic-sphere normals, offsets, refinement boxes.

A plane is ``n . x = d`` with a unit normal ``n``. ``n`` and ``-n`` (with ``-d``) are the same
plane; :func:`canonical` picks one so that planes can be compared and de-duplicated.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["geodesic_sphere", "hemisphere", "initial_planes", "spacing_for", "refine_box", "canonical", "plane_recall"]

Array = NDArray[np.float64]

_PHI = (1 + 5**0.5) / 2
_ICO_V = np.array([[-1, _PHI, 0], [1, _PHI, 0], [-1, -_PHI, 0], [1, -_PHI, 0], [0, -1, _PHI], [0, 1, _PHI],
                   [0, -1, -_PHI], [0, 1, -_PHI], [_PHI, 0, -1], [_PHI, 0, 1], [-_PHI, 0, -1], [-_PHI, 0, 1]], float)
_ICO_F = np.array([[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
                   [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5],
                   [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]])


def geodesic_sphere(frequency: int) -> Array:
    """Vertices ``(10 f^2 + 2, 3)`` of the class-I icosahedral geodesic sphere of frequency ``f``.

    Each icosahedron face is divided into ``f^2`` triangles, the grid points projected to the
    unit sphere.

    Examples
    --------
    >>> [len(geodesic_sphere(f)) for f in (1, 2, 4)]
    [12, 42, 162]
    """
    k = int(frequency)
    i, j = np.meshgrid(np.arange(k + 1), np.arange(k + 1), indexing="ij")
    keep = i + j <= k
    a, b = i[keep] / k, j[keep] / k
    bary = np.stack([1 - a - b, a, b], axis=1)  # (g, 3)
    corners = _ICO_V[_ICO_F]  # (20, 3, 3)
    pts = np.einsum("gk,fkd->fgd", bary, corners).reshape(-1, 3)
    pts /= np.linalg.norm(pts, axis=1, keepdims=True)
    _, idx = np.unique(np.round(pts, 9), axis=0, return_index=True)
    return pts[np.sort(idx)]


def canonical(normals: ArrayLike, offsets: ArrayLike) -> tuple[Array, Array]:
    """The same planes with normals in the upper half (first non-zero of z, y, x positive).

    Examples
    --------
    >>> n, d = canonical([[0, 0, -1.0]], [0.3])
    >>> n.tolist(), d.tolist()
    ([[0.0, 0.0, 1.0]], [-0.3])
    """
    n = np.array(normals, float, ndmin=2)
    d = np.array(offsets, float, ndmin=1)
    eps = 1e-12
    z0, y0 = np.abs(n[:, 2]) <= eps, np.abs(n[:, 1]) <= eps
    flip = (n[:, 2] < -eps) | (z0 & ((n[:, 1] < -eps) | (y0 & (n[:, 0] < 0))))
    s = np.where(flip, -1.0, 1.0)
    return n * s[:, None] + 0.0, d * s + 0.0  # + 0.0: no negative zeros


def hemisphere(frequency: int) -> Array:
    """One normal of each antipodal pair of :func:`geodesic_sphere` (``5 f^2 + 1`` of them).

    Examples
    --------
    >>> len(hemisphere(4))
    81
    """
    n, _ = canonical(geodesic_sphere(frequency), np.zeros(10 * frequency**2 + 2))
    _, idx = np.unique(np.round(n, 9), axis=0, return_index=True)
    return n[np.sort(idx)]


def initial_planes(vertices: ArrayLike, frequency: int, spacing: float) -> tuple[Array, Array]:
    """The coarse sampling: for each hemisphere normal, offsets ``spacing`` apart over the mesh.

    Along each normal the vertices project to ``[lo, hi]``; the ``ceil((hi - lo) / spacing)``
    offsets are centred in that interval, ``spacing`` apart (at least one).

    Examples
    --------
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float) - 0.25
    >>> n, d = initial_planes(v, 1, 0.25)
    >>> len(n), bool(np.all(np.abs(np.linalg.norm(n, axis=1) - 1) < 1e-12))
    (30, True)
    """
    v = np.asarray(vertices, float)
    normals = hemisphere(frequency)
    proj = v @ normals.T
    lo, hi = proj.min(0), proj.max(0)
    count = np.maximum(1, np.ceil((hi - lo) / spacing - 1e-9)).astype(np.int64)
    which = np.repeat(np.arange(len(normals)), count)
    k = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    d = (lo + hi)[which] / 2 + (k - (count[which] - 1) / 2) * spacing
    return normals[which], d


def spacing_for(vertices: ArrayLike, frequency: int, target: int) -> float:
    """The offset spacing at which :func:`initial_planes` gives about ``target`` planes (bisection).

    Examples
    --------
    >>> v = np.random.default_rng(0).uniform(-0.3, 0.3, (500, 3))
    >>> 280 <= len(initial_planes(v, 4, spacing_for(v, 4, 300))[1]) <= 320
    True
    """
    lo, hi = 1e-4, 1.0
    for _ in range(40):
        mid = (lo * hi) ** 0.5
        n = len(initial_planes(vertices, frequency, mid)[1])
        lo, hi = (mid, hi) if n > target else (lo, mid)
    return hi


def _tangent_basis(n: Array) -> tuple[Array, Array]:
    helper = np.where(np.abs(n[:, [0]]) < 0.9, np.array([[1.0, 0, 0]]), np.array([[0, 1.0, 0]]))
    u = np.cross(n, helper)
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    return u, np.cross(n, u)


def refine_box(normals: ArrayLike, offsets: ArrayLike, angle: float, offset: float,
               steps: int = 3) -> tuple[Array, Array]:
    """Planes of a ``steps^3`` box around each plane in (normal, offset) coordinates, centres left out.

    The normal is tilted by angles in ``linspace(-angle, angle, steps)`` (degrees) about two
    axes orthogonal to it, the offset shifted by ``linspace(-offset, offset, steps)``.
    Returns canonical planes, duplicates (to a quarter of the box's step) removed.

    Examples
    --------
    >>> n, d = refine_box([[0, 0, 1.0]], [0.1], 4.0, 0.01)
    >>> len(n), round(float(np.degrees(np.arccos(n[:, 2].min()))), 3)
    (26, 5.648)
    """
    n = np.array(normals, float, ndmin=2)
    d = np.array(offsets, float, ndmin=1)
    u, v = _tangent_basis(n)
    t = np.tan(np.radians(np.linspace(-angle, angle, steps)))
    s = np.linspace(-offset, offset, steps)
    a, b, c = (g.ravel() for g in np.meshgrid(t, t, s, indexing="ij"))
    centre = (a == 0) & (b == 0) & (c == 0)
    a, b, c = a[~centre], b[~centre], c[~centre]
    nn = n[:, None, :] + a[None, :, None] * u[:, None, :] + b[None, :, None] * v[:, None, :]
    nn /= np.linalg.norm(nn, axis=2, keepdims=True)
    dd = d[:, None] + c[None, :]
    nn, dd = canonical(nn.reshape(-1, 3), dd.ravel())
    q_ang = max(np.radians(2 * angle / (steps - 1)) / 4, 1e-9)
    q_off = max(2 * offset / (steps - 1) / 4, 1e-12)
    key = np.column_stack([np.round(nn / q_ang), np.round(dd / q_off)])
    _, idx = np.unique(key, axis=0, return_index=True)
    idx = np.sort(idx)
    return nn[idx], dd[idx]


def plane_recall(true_planes: ArrayLike, normals: ArrayLike, offsets: ArrayLike, angle: float = 2.0,
                 offset: float = 0.005) -> float:
    """Share of the true planes ``(k, 4)`` with a found plane within ``angle`` degrees and ``offset``.

    Planes are unoriented: a found plane with normal ``-n`` and offset ``-d`` is the same.

    Examples
    --------
    >>> plane_recall([[0, 0, 1, 0.1], [1, 0, 0, 0]], [[0, 0, -1.0]], [-0.102])
    0.5
    """
    tp = np.array(true_planes, float, ndmin=2)
    if len(tp) == 0:
        return float("nan")
    n = np.array(normals, float, ndmin=2)
    d = np.array(offsets, float, ndmin=1)
    if len(n) == 0:
        return 0.0
    dot = tp[:, :3] @ n.T  # (k, m)
    sign = np.where(dot < 0, -1.0, 1.0)
    ang = np.degrees(np.arccos(np.clip(np.abs(dot), 0.0, 1.0)))
    doff = np.abs(tp[:, [3]] - sign * d[None, :])
    return float(np.mean(np.any((ang <= angle) & (doff <= offset), axis=1)))
