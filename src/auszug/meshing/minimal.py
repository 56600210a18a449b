"""Discrete minimal surfaces spanning closed 3D polygons (Pinkall-Polthier), converged.

:func:`disk_mesh` triangulates the unit disk with a given number of boundary
points (concentric rings of interior points, Delaunay by scipy/Qhull; the
boundary points are in convex position, so every boundary edge is a mesh
edge; no Shewchuk Triangle). :func:`minimal_surface` maps its boundary onto
the polygon by arc length, starts from the harmonic map of the disk mesh,
and then repeats the Pinkall-Polthier step: solve the Laplace equation with
the cotangent weights of the *current* surface and the boundary fixed,
until the area stops decreasing and the discrete mean curvature
(the area gradient) at every interior vertex is below tolerance.

The boundary vertices are the given points, unchanged, so a surface spanning
points sampled on curves has its boundary exactly on the curves.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.errors import GeometryError
from auszug.meshing.mesh import Mesh, Part, triangle_areas

__all__ = [
    "MinimalSurface",
    "disk_mesh",
    "cotan_laplacian",
    "area_gradient",
    "delaunay_flips",
    "minimal_surface",
    "flat_area",
]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]
#: Default relative tolerance on the residual mean curvature (|H| times the boundary radius).
RESIDUAL_TOL = 1e-6


@dataclass(frozen=True, eq=False)
class MinimalSurface:
    """A converged (or best-effort) discrete minimal surface.

    Attributes
    ----------
    vertices : (n, 3) ndarray
        The first ``len(boundary)`` vertices are the boundary, in order.
    faces : (m, 3) ndarray
    boundary : (k,) ndarray of int
        Boundary vertex indices in loop order.
    area : float
    start_area : float
        Area of the harmonic start surface.
    areas : tuple of float
        Area after every iteration.
    iterations : int
    converged : bool
        Residual below tolerance and area no longer decreasing.
    residual : float
        Largest discrete mean curvature |H| over interior vertices, times the
        boundary's radius (length / 2 pi): dimensionless.
    mean_curvature : float
        Largest |H| over interior vertices (1 / drawing units).
    """

    vertices: Array
    faces: IntArray
    boundary: IntArray
    area: float
    start_area: float
    areas: tuple[float, ...]
    iterations: int
    converged: bool
    residual: float
    mean_curvature: float

    def mesh(self, name: str = "face", basic: int = -1, replica: str = "") -> Mesh:
        """As a :class:`Mesh` with one part."""
        return Mesh(self.vertices, self.faces,
                    (Part(name, "face", basic, replica, (0, len(self.vertices)), (0, len(self.faces))),))


def disk_mesh(n_boundary: int, angles: ArrayLike | None = None) -> tuple[Array, IntArray]:
    """A triangulated unit disk whose first ``n_boundary`` points lie on the circle.

    Parameters
    ----------
    n_boundary : int
        Boundary points (>= 3).
    angles : (n_boundary,) array_like, optional
        Their polar angles, increasing (default: evenly spaced).

    Returns
    -------
    points : (n, 2) ndarray
    faces : (m, 3) ndarray
        Counter-clockwise.

    Examples
    --------
    >>> p, f = disk_mesh(12)
    >>> len(p) > 12, bool(np.allclose(np.hypot(*p[:12].T), 1.0))
    (True, True)
    """
    n = int(n_boundary)
    if n < 3:
        raise GeometryError(f"a disk mesh needs at least 3 boundary points, got {n}")
    th = 2 * np.pi * np.arange(n) / n if angles is None else np.asarray(angles, dtype=float)
    bnd = np.stack([np.cos(th), np.sin(th)], axis=1)
    h = 2 * np.pi / n
    rings = [bnd]
    k = 1
    while True:
        r = 1.0 - k * h * math.sqrt(3.0) / 2.0
        if r < 0.6 * h:
            break
        m = max(3, int(round(2 * np.pi * r / h)))
        a = 2 * np.pi * (np.arange(m) + 0.5 * (k % 2)) / m
        rings.append(r * np.stack([np.cos(a), np.sin(a)], axis=1))
        k += 1
    rings.append(np.zeros((1, 2)))
    pts = np.concatenate(rings)
    from scipy.spatial import Delaunay

    tri = Delaunay(pts, qhull_options="Qbb Qc Qz Q12").simplices.astype(np.int64)
    a, b, c = pts[tri[:, 0]], pts[tri[:, 1]], pts[tri[:, 2]]
    cr = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    tri[cr < 0] = tri[cr < 0][:, ::-1]
    tri = tri[np.abs(cr) > 1e-14]
    return pts, tri


def _inside(pts: Array, poly: Array) -> NDArray[np.bool_]:
    """Point-in-polygon (crossing number), vectorised over points and edges."""
    a, b = poly, np.roll(poly, -1, axis=0)
    px, py = pts[:, 0, None], pts[:, 1, None]
    cond = (a[None, :, 1] > py) != (b[None, :, 1] > py)
    with np.errstate(divide="ignore", invalid="ignore"):
        xint = a[None, :, 0] + (py - a[None, :, 1]) * (b[None, :, 0] - a[None, :, 0]) / (b[None, :, 1] - a[None, :, 1])
    return (np.count_nonzero(cond & (px < xint), axis=1) % 2) == 1


def _segment_distance(pts: Array, poly: Array) -> Array:
    """Distance from each point to the closed polygon, shape (p,)."""
    a, b = poly, np.roll(poly, -1, axis=0)
    ab = b - a
    t = np.clip(np.einsum("pkj,kj->pk", pts[:, None, :] - a[None], ab) / np.einsum("kj,kj->k", ab, ab), 0.0, 1.0)
    q = a[None] + t[..., None] * ab[None]
    return np.linalg.norm(pts[:, None, :] - q, axis=2).min(axis=1)


def polygon_mesh(poly: ArrayLike) -> tuple[Array, IntArray] | None:
    """Triangulate a simple planar polygon with interior points (hexagonal lattice + Delaunay).

    The polygon's points are the first vertices, unchanged; interior points
    are spaced like the boundary. Returns None when the Delaunay
    triangulation does not contain every boundary edge (very thin or sharply
    pinched polygons), so the caller can fall back to :func:`disk_mesh`.

    Parameters
    ----------
    poly : (k, 2) array_like
        Counter-clockwise, simple, first point not repeated.

    Returns
    -------
    points : (n, 2) ndarray
    faces : (m, 3) ndarray
        Counter-clockwise.
    """
    from scipy.spatial import Delaunay

    p = np.asarray(poly, dtype=float)
    k = len(p)
    h = float(np.mean(np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1)))
    lo, hi = p.min(0) - h, p.max(0) + h
    dy = h * math.sqrt(3.0) / 2.0
    ys = np.arange(lo[1], hi[1] + dy, dy)
    xs = np.arange(lo[0], hi[0] + h, h)
    gx, gy = np.meshgrid(xs, ys)
    gx = gx + (np.arange(len(ys)) % 2)[:, None] * (h / 2.0)
    lat = np.stack([gx.ravel(), gy.ravel()], axis=1)
    lat = lat[_inside(lat, p)]
    if len(lat):
        lat = lat[_segment_distance(lat, p) > 0.55 * h]
    pts = np.concatenate([p, lat])
    tri = Delaunay(pts, qhull_options="Qbb Qc Qz Q12").simplices.astype(np.int64)
    cen = pts[tri].mean(axis=1)
    tri = tri[_inside(cen, p)]
    a, b, c = pts[tri[:, 0]], pts[tri[:, 1]], pts[tri[:, 2]]
    cr = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    tri[cr < 0] = tri[cr < 0][:, ::-1]
    tri = tri[np.abs(cr) > 1e-14 * h * h]
    # every boundary edge must be there, once, in the counter-clockwise direction
    from auszug.meshing.mesh import boundary_edges

    be = boundary_edges(tri)
    want = np.stack([np.arange(k), (np.arange(k) + 1) % k], axis=1)
    if len(be) != k or not np.array_equal(np.unique(be[:, 0] * k + be[:, 1]), np.sort(want[:, 0] * k + want[:, 1])):
        return None
    used = np.unique(tri)
    if len(used) != len(pts):
        return None
    return pts, tri


def _projections(b: Array, centre: Array | None) -> list[Array]:
    c = b - b.mean(0)
    out = []
    if centre is not None:
        th = np.unwrap(np.arctan2(b[:, 1] - centre[1], b[:, 0] - centre[0]))
        r = float(np.mean(np.hypot(b[:, 0] - centre[0], b[:, 1] - centre[1])))
        if abs(th[-1] - th[0]) < np.pi and r > 0:
            out.append(np.stack([th * r, b[:, 2]], axis=1))
    # best-fit plane, with in-plane axes fixed by the first point so that the projection (and
    # the mesh built on it) moves with the polygon under rigid motions
    _, _, vt = np.linalg.svd(c, full_matrices=False)
    nrm = vt[2]
    e1 = c[0] - (c[0] @ nrm) * nrm
    if np.linalg.norm(e1) > 1e-12 * (np.abs(c).max() + 1e-300):
        e1 = e1 / np.linalg.norm(e1)
        out.append(np.stack([c @ e1, c @ np.cross(nrm, e1)], axis=1))
    else:
        out.append(c @ vt[:2].T)
    out.append(b[:, :2].copy())
    return out


def _simple_projection(b: Array, centre: Array | None, mesh: bool = False):
    """The first projection of the closed polygon that is simple (made counter-clockwise)."""
    from auszug.meshing.profile import _first_crossing

    size = float(np.linalg.norm(b.max(0) - b.min(0)))
    for uv in _projections(b, centre):
        x, y = uv[:, 0], uv[:, 1]
        area = 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
        if abs(area) <= 1e-6 * size * size:
            continue
        if area < 0:
            uv = uv * np.array([1.0, -1.0])
        if _first_crossing(uv, True, 1e-9 * size) is not None:
            continue
        if not mesh:
            return uv
        out = polygon_mesh(uv)
        if out is not None:
            return out
    return None


def _planar_start(b: Array, centre: Array | None) -> tuple[Array, IntArray] | None:
    """A fold-free planar triangulation of the boundary in a projection where it is simple."""
    return _simple_projection(b, centre, mesh=True)


def _cotans(v: Array, f: IntArray) -> tuple[Array, Array]:
    """Cotangents at the three corners of every triangle (corner k opposite edge (k+1, k+2)) and areas."""
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    e0, e1, e2 = c - b, a - c, b - a   # edge opposite corner 0, 1, 2
    cr = np.cross(e2, -e1)
    dbl = np.linalg.norm(cr, axis=1)
    dbl = np.maximum(dbl, 1e-300)
    cot0 = np.einsum("ij,ij->i", -e2, e1) / dbl     # at a: between (b - a) and (c - a)
    cot1 = np.einsum("ij,ij->i", -e0, e2) / dbl     # at b: between (c - b) and (a - b)
    cot2 = np.einsum("ij,ij->i", -e1, e0) / dbl     # at c: between (a - c) and (b - c)
    return np.stack([cot0, cot1, cot2], axis=1), 0.5 * dbl


def cotan_laplacian(vertices: ArrayLike, faces: ArrayLike):
    """The cotangent Laplacian L, with (L x)_i = sum_j w_ij (x_i - x_j), w_ij = (cot a + cot b) / 2.

    L x is the gradient of the surface area with respect to the vertex
    positions, so it vanishes at the interior vertices of a discrete minimal
    surface.

    Returns
    -------
    scipy.sparse.csr_matrix, shape (n, n)
    """
    from scipy.sparse import coo_matrix

    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces, dtype=np.int64)
    cot, _ = _cotans(v, f)
    i = np.concatenate([f[:, 1], f[:, 2], f[:, 0]])
    j = np.concatenate([f[:, 2], f[:, 0], f[:, 1]])
    w = 0.5 * np.concatenate([cot[:, 0], cot[:, 1], cot[:, 2]])
    n = len(v)
    rows = np.concatenate([i, j, i, j])
    cols = np.concatenate([j, i, i, j])
    vals = np.concatenate([-w, -w, w, w])
    return coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsr()


def area_gradient(vertices: ArrayLike, faces: ArrayLike) -> tuple[Array, Array]:
    """Gradient of the area at every vertex, (n, 3), and the barycentric vertex areas, (n,).

    The discrete mean curvature is |H_i| = |grad_i| / (2 A_i).
    """
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces, dtype=np.int64)
    L = cotan_laplacian(v, f)
    ar = triangle_areas(v, f)
    va = np.asarray(np.bincount(f.reshape(-1), weights=np.repeat(ar / 3.0, 3), minlength=len(v)), dtype=float)
    return L @ v, va


def flat_area(points: ArrayLike, centre: ArrayLike | None = (0.0, 0.0)) -> float:
    """Area of the earcut triangulation of a closed 3D polygon, or NaN.

    The polygon is projected where it is simple (the cylinder chart about
    ``centre``, its best-fit plane, or the top view, in that order), cut into
    triangles there by earcut, and the triangles are taken between its own 3D
    points (no interior points): the surface a plain "flat" fill gives,
    against which a minimal surface is compared. NaN when no projection is
    simple.
    """
    from auszug.meshing.profile import triangulate_polygon

    p = np.asarray(points, dtype=float)
    uv = _simple_projection(p, None if centre is None else np.asarray(centre, dtype=float))
    if uv is None:
        return math.nan
    tri = triangulate_polygon(uv)
    return float(triangle_areas(p, tri).sum())


class _Pattern:
    """The fixed sparsity of the cotangent Laplacian of one triangulation.

    Vertices ``0..k-1`` are the boundary, ``k..n-1`` the interior. Each
    iteration only recomputes the values (one ``bincount``); the structure,
    and where the interior-interior and interior-boundary blocks and the
    interior diagonal sit in it, is computed once per triangulation.
    """

    def __init__(self, faces: IntArray, n: int, k: int) -> None:
        f = faces
        i = np.concatenate([f[:, 1], f[:, 2], f[:, 0]])    # edge opposite corner 0, 1, 2
        j = np.concatenate([f[:, 2], f[:, 0], f[:, 1]])
        rows = np.concatenate([i, j, i, j])
        cols = np.concatenate([j, i, i, j])
        self.sign = np.concatenate([-np.ones(2 * len(i)), np.ones(2 * len(i))])
        key = rows * n + cols
        ukey, self.pos = np.unique(key, return_inverse=True)
        r, c = ukey // n, ukey % n
        self.n, self.k, self.nnz = n, k, len(ukey)
        self.indices = c
        self.indptr = np.concatenate([[0], np.cumsum(np.bincount(r, minlength=n))])
        m_ii = (r >= k) & (c >= k)
        m_ib = (r >= k) & (c < k)
        self.sel_ii, self.sel_ib = np.flatnonzero(m_ii), np.flatnonzero(m_ib)
        self.ii_indices = c[m_ii] - k
        self.ii_indptr = np.concatenate([[0], np.cumsum(np.bincount(r[m_ii] - k, minlength=n - k))])
        self.ib_indices = c[m_ib]
        self.ib_indptr = np.concatenate([[0], np.cumsum(np.bincount(r[m_ib] - k, minlength=n - k))])
        self.ii_diag = np.flatnonzero(r[m_ii] == c[m_ii])

    def values(self, cot: Array) -> Array:
        """The non-zeros of L in CSR order for corner cotangents (m, 3)."""
        w = 0.5 * np.concatenate([cot[:, 0], cot[:, 1], cot[:, 2]])
        return np.asarray(np.bincount(self.pos, weights=np.tile(w, 4) * self.sign, minlength=self.nnz), dtype=float)

    def full(self, data: Array):
        """L as a CSR matrix."""
        from scipy.sparse import csr_matrix

        return csr_matrix((data, self.indices, self.indptr), shape=(self.n, self.n))

    def blocks(self, data: Array, shift: Array | None = None):
        """Interior-interior (CSC; symmetric) minus ``diag(shift)``, and interior-boundary (CSR)."""
        from scipy.sparse import csc_matrix, csr_matrix

        m = self.n - self.k
        d_ii = data[self.sel_ii]
        if shift is not None:
            d_ii = d_ii.copy()
            d_ii[self.ii_diag] -= shift
        lii = csc_matrix((d_ii, self.ii_indices, self.ii_indptr), shape=(m, m))
        lib = csr_matrix((data[self.sel_ib], self.ib_indices, self.ib_indptr), shape=(m, self.k))
        return lii, lib


def _factor(mat):
    from scipy.sparse.linalg import splu

    return splu(mat, permc_spec="MMD_AT_PLUS_A", options={"SymmetricMode": True})


def _gradient(x: Array, f: IntArray, cot: Array) -> Array:
    """Area gradient L x from corner cotangents, shape (n, 3)."""
    n = len(x)
    g = np.zeros((n, 3))
    for c, (a, b) in enumerate(((1, 2), (2, 0), (0, 1))):
        d = (x[f[:, a]] - x[f[:, b]]) * (0.5 * cot[:, c])[:, None]
        for ax in range(3):
            g[:, ax] += np.bincount(f[:, a], weights=d[:, ax], minlength=n)
            g[:, ax] -= np.bincount(f[:, b], weights=d[:, ax], minlength=n)
    return g


def _vertex_normals_areas(x: Array, f: IntArray) -> tuple[Array, Array, Array]:
    """Area-weighted unit vertex normals (n, 3), barycentric vertex areas (n,), triangle areas (m,)."""
    n = len(x)
    fn = np.cross(x[f[:, 1]] - x[f[:, 0]], x[f[:, 2]] - x[f[:, 0]])
    dbl = np.linalg.norm(fn, axis=1)
    vn = np.zeros((n, 3))
    for ax in range(3):
        w = np.repeat(fn[:, ax], 3)
        vn[:, ax] = np.bincount(f.reshape(-1), weights=w, minlength=n)
    ln = np.linalg.norm(vn, axis=1, keepdims=True)
    vn = np.divide(vn, ln, out=np.zeros_like(vn), where=ln > 0)
    va = np.asarray(np.bincount(f.reshape(-1), weights=np.repeat(dbl / 6.0, 3), minlength=n), dtype=float)
    return vn, va, 0.5 * dbl


def delaunay_flips(x: Array, faces: IntArray, max_rounds: int = 100) -> IntArray:
    """Flip interior edges until every one is Delaunay (opposite angles sum to at most pi).

    Flips are done in rounds of independent edges (no triangle in two flips),
    each the most non-Delaunay among its neighbours; an edge whose flip would
    duplicate an existing edge is left alone. Boundary edges never flip.
    Delaunay edges have non-negative cotangent weights, which keeps the
    Pinkall-Polthier and Newton steps well conditioned.

    Parameters
    ----------
    x : (n, 3) ndarray
    faces : (m, 3) ndarray
        Consistently oriented.

    Returns
    -------
    (m, 3) ndarray
        The flipped faces (same orientation).
    """
    f = np.array(faces, dtype=np.int64, copy=True)
    n = len(x)
    for _ in range(max_rounds):
        cot, _ = _cotans(x, f)
        # half-edge opposite corner c of face t runs from f[t, c+1] to f[t, c+2]
        hv0 = np.concatenate([f[:, 1], f[:, 2], f[:, 0]])
        hv1 = np.concatenate([f[:, 2], f[:, 0], f[:, 1]])
        hf = np.tile(np.arange(len(f)), 3)
        hc = np.repeat(np.arange(3), len(f))
        hcot = cot[hf, hc]
        key = np.minimum(hv0, hv1) * n + np.maximum(hv0, hv1)
        order = np.argsort(key, kind="stable")
        ks = key[order]
        pair = np.flatnonzero(ks[1:] == ks[:-1])
        h1, h2 = order[pair], order[pair + 1]
        csum = hcot[h1] + hcot[h2]
        bad = np.flatnonzero(csum < -1e-9)
        if len(bad) == 0:
            break
        h1, h2, csum = h1[bad], h2[bad], csum[bad]
        f1, f2 = hf[h1], hf[h2]
        c1, c2 = hc[h1], hc[h2]
        opp1, opp2 = f[f1, c1], f[f2, c2]
        newkey = np.minimum(opp1, opp2) * n + np.maximum(opp1, opp2)
        fresh = ~np.isin(newkey, ks) & (opp1 != opp2)
        h1, h2, csum, f1, f2, c1, c2, opp1, opp2 = (a[fresh] for a in (h1, h2, csum, f1, f2, c1, c2, opp1, opp2))
        if len(f1) == 0:
            break
        # independent set: each flip is the worst among those touching its faces
        best = np.full(len(f), np.inf)
        np.minimum.at(best, f1, csum)
        np.minimum.at(best, f2, csum)
        pick = (csum == best[f1]) & (csum == best[f2])
        # ties: keep the first flip per face
        idx = np.flatnonzero(pick)
        used = np.concatenate([f1[idx], f2[idx]])
        _, first, cnt = np.unique(used, return_index=True, return_counts=True)
        dup_faces = np.unique(used)[cnt > 1]
        ok = ~(np.isin(f1[idx], dup_faces) | np.isin(f2[idx], dup_faces))
        # allow the first of each duplicated group
        idx = idx[ok] if ok.any() else idx[:1]
        if len(idx) == 0:
            break
        a = hv0[h1[idx]]   # face f1 runs a -> b along the edge
        b = hv1[h1[idx]]
        c, d = opp1[idx], opp2[idx]
        f[f1[idx]] = np.stack([a, d, c], axis=1)
        f[f2[idx]] = np.stack([d, b, c], axis=1)
    return f


def _tangential_smooth(x: Array, f: IntArray, k: int, rounds: int = 5, lam: float = 0.5) -> Array:
    """Even out the vertices within the surface: uniform Laplacian smoothing, tangential part only.

    The shape changes only to second order; the triangles get rounder, which
    the Newton steps on the mean curvature need near sharp corners.
    """
    from scipy.sparse import coo_matrix

    n = len(x)
    i = np.concatenate([f[:, 0], f[:, 1], f[:, 2]])
    j = np.concatenate([f[:, 1], f[:, 2], f[:, 0]])
    adj = coo_matrix((np.ones(2 * len(i)), (np.concatenate([i, j]), np.concatenate([j, i]))), shape=(n, n)).tocsr()
    adj.data[:] = 1.0
    deg = np.asarray(adj.sum(axis=1)).reshape(-1)
    x = x.copy()
    for _ in range(rounds):
        vn, _, _ = _vertex_normals_areas(x, f)
        d = (adj @ x) / deg[:, None] - x
        d -= np.einsum("ij,ij->i", d, vn)[:, None] * vn
        x[k:] += lam * d[k:]
    return x


def _angle_defect(x: Array, f: IntArray) -> Array:
    """2 pi minus the sum of the corner angles at every vertex, shape (n,)."""
    n = len(x)
    ang = np.empty(f.shape)
    for c in range(3):
        u = x[f[:, (c + 1) % 3]] - x[f[:, c]]
        v = x[f[:, (c + 2) % 3]] - x[f[:, c]]
        ang[:, c] = np.arctan2(np.linalg.norm(np.cross(u, v), axis=1), np.einsum("ij,ij->i", u, v))
    return np.asarray(2 * np.pi - np.bincount(f.reshape(-1), weights=ang.reshape(-1), minlength=n), dtype=float)


def minimal_surface(
    boundary: ArrayLike,
    max_iterations: int = 100,
    tol: float = RESIDUAL_TOL,
    area_rtol: float = 1e-12,
    pp_steps: int = 3,
    centre: ArrayLike | None = (0.0, 0.0),
) -> MinimalSurface:
    """Fill a closed 3D polygon with a converged discrete minimal surface.

    Parameters
    ----------
    boundary : (k, 3) array_like
        The closed polygon, first point not repeated (k >= 3). These become
        the mesh's boundary vertices, unchanged.
    max_iterations : int
        Cap on iterations.
    tol : float
        Converged when the residual mean curvature (see
        :class:`MinimalSurface`) is below this ...
    area_rtol : float
        ... and the area changed by less than this fraction in the last step.
    pp_steps : int
        Pinkall-Polthier steps at least, before the normal Newton steps.
    centre : (2,) array_like or None
        Axis of the cylinder chart tried first for the start triangulation.

    Returns
    -------
    MinimalSurface

    Notes
    -----
    Pinkall-Polthier steps (Laplace equation with the current surface's
    cotangent weights) remove most of the excess area within a few steps,
    but then creep: the vertices slide along the surface while the shape
    hardly changes. The shape is then finished by Newton steps on the mean
    curvature along the vertex normals, ``L phi = -(grad A . n)``, reusing the
    last factorisation, which converges linearly with a rate of about 5 to 10
    per step. The residual is the discrete mean curvature
    ``|H_i| = |grad_i A . n_i| / (2 A_i)`` (cotangent formula, barycentric
    vertex areas) at interior vertices.

    Raises
    ------
    GeometryError
        For fewer than 3 points, non-finite points, or a degenerate polygon.

    Examples
    --------
    >>> import numpy as np
    >>> t = 2 * np.pi * np.arange(48) / 48
    >>> ms = minimal_surface(np.stack([np.cos(t), np.sin(t), 0 * t], 1))   # a flat disk
    >>> ms.converged, bool(np.abs(ms.vertices[:, 2]).max() < 1e-12)
    (True, True)
    """
    b = np.asarray(boundary, dtype=float)
    if b.ndim != 2 or b.shape[1] != 3 or len(b) < 3:
        raise GeometryError(f"a minimal surface needs a closed polygon of at least 3 3D points, got shape {b.shape}")
    if not np.all(np.isfinite(b)):
        raise GeometryError("boundary points must be finite")
    seg = np.linalg.norm(np.roll(b, -1, axis=0) - b, axis=1)
    total = float(seg.sum())
    if not total > 0 or np.any(seg <= 1e-14 * total):
        raise GeometryError("the boundary polygon has zero length or repeated points")
    k = len(b)
    s = np.concatenate([[0.0], np.cumsum(seg[:-1])]) / total
    start_mesh = _planar_start(b, None if centre is None else np.asarray(centre, dtype=float))
    if start_mesh is None:
        uv, faces = disk_mesh(k, 2 * np.pi * s)
    else:
        uv, faces = start_mesh
    n = len(uv)
    bnd = np.arange(k)
    x = np.zeros((n, 3))
    x[:k] = b
    radius = total / (2 * np.pi)
    if n == k:
        ar = float(triangle_areas(x, faces).sum())
        return MinimalSurface(x, faces, bnd, ar, ar, (ar,), 0, True, 0.0, 0.0)
    pat = _Pattern(faces, n, k)
    uv3 = np.concatenate([uv, np.zeros((n, 1))], axis=1)
    lii, lib = pat.blocks(pat.values(_cotans(uv3, faces)[0]))
    x[k:] = _factor(lii).solve(-(lib @ b))
    start = float(triangle_areas(x, faces).sum())
    areas = [start]

    def measure(x: Array, faces: IntArray, pat: _Pattern):
        cot, tri_area = _cotans(x, faces)
        data = pat.values(cot)
        g = pat.full(data) @ x
        vn, va, _ = _vertex_normals_areas(x, faces)
        gn = np.einsum("ij,ij->i", g[k:], vn[k:])
        h = gn / (2.0 * np.maximum(va[k:], 1e-300))
        return data, vn, va, gn, h, float(tri_area.sum())

    # 1. Pinkall-Polthier steps, keeping the triangulation Delaunay
    it = 0
    for it in range(1, max_iterations + 1):
        nf = delaunay_flips(x, faces)
        if not np.array_equal(nf, faces):
            faces = nf
            pat = _Pattern(faces, n, k)
        lii, lib = pat.blocks(pat.values(_cotans(x, faces)[0]))
        xn = x.copy()
        xn[k:] = _factor(lii).solve(-(lib @ b))
        a_new = float(triangle_areas(xn, faces).sum()) if np.all(np.isfinite(xn)) else math.inf
        if not a_new < areas[-1]:
            break
        x = xn
        areas.append(a_new)
        if it >= pp_steps and areas[-2] - a_new <= 1e-3 * a_new:
            break
    x = _tangential_smooth(x, faces, k)
    nf = delaunay_flips(x, faces)
    if not np.array_equal(nf, faces):
        faces = nf
        pat = _Pattern(faces, n, k)
    areas.append(float(triangle_areas(x, faces).sum()))
    # 2. Newton steps along the vertex normals: L - M |A|^2 (the Jacobi operator) is the
    #    Hessian of the area for normal displacements; its factorisation is reused while
    #    the residual keeps falling fast.
    data, vn, va, gn, h, _ = measure(x, faces, pat)
    res = float(np.abs(h).max()) * radius
    converged = False
    lu = None
    stale = 0
    start_it = it
    for it in range(start_it + 1, max_iterations + 1):  # noqa: B007  (the result reports the last it)
        if res <= tol and len(areas) > 1 and abs(areas[-2] - areas[-1]) <= area_rtol * areas[-1]:
            converged = True
            break
        if lu is None:
            a2 = np.maximum(4.0 * h * h + 2.0 * _angle_defect(x, faces)[k:] / np.maximum(va[k:], 1e-300), 0.0)
            try:
                lu = _factor(pat.blocks(data, va[k:] * a2)[0])
                phi = lu.solve(-gn)
                if not np.all(np.isfinite(phi)) or float(phi @ gn) >= 0.0:
                    raise RuntimeError("indefinite")
            except RuntimeError:
                lu = _factor(pat.blocks(data)[0])   # without the curvature term: positive
                phi = lu.solve(-gn)
            stale = 0
        else:
            phi = lu.solve(-gn)
            stale += 1
        step = 1.0
        ok = False
        for _ in range(30):   # backtracking: the area must not grow
            xn = x.copy()
            xn[k:] += (step * phi)[:, None] * vn[k:]
            a_new = float(triangle_areas(xn, faces).sum())
            if a_new <= areas[-1] * (1 + 1e-14):
                ok = True
                break
            step *= 0.5
        if not ok:
            if stale == 0:
                break
            lu = None
            continue
        x = xn
        areas.append(a_new)
        res_old = res
        data, vn, va, gn, h, _ = measure(x, faces, pat)
        res = float(np.abs(h).max()) * radius
        if step < 1.0 or (res > 0.7 * res_old and stale >= 2):
            lu = None       # slow progress: refresh the factorisation
    else:
        converged = res <= tol
    hmax = res / radius
    return MinimalSurface(x, faces, bnd, areas[-1], start, tuple(areas), it, converged, res, hmax)
