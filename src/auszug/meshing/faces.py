"""Faces: minimal surfaces filling the closed loops of a network, one solve per symmetry orbit.

:func:`network_faces` finds the loops (:func:`~auszug.meshing.loops.find_loops`,
or takes the given ones), groups them into orbits of the symmetry the whole
drawing shares (the elements common to every basic curve's group), fills one
loop per orbit with a converged minimal surface
(:func:`~auszug.meshing.minimal.minimal_surface`) and maps it onto the other
loops of its orbit, mirrored images with their triangles reversed. The
boundary vertices are points of the network's curves, so every face's
boundary lies exactly on them.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Sequence

import numpy as np
from numpy.typing import NDArray

from auszug.errors import DrawingError, GeometryError
from auszug.geometry.network import as_curve_network
from auszug.limits import LIMITS
from auszug.meshing._work import check_triangles, face_triangles
from auszug.meshing.loops import Loop, NetworkGraph, _add_rims, find_loops, network_graph
from auszug.meshing.mesh import Mesh, Part
from auszug.meshing.minimal import RESIDUAL_TOL, MinimalSurface, flat_area, minimal_surface

__all__ = ["Face", "Faces", "common_group", "network_faces"]

Array = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class Face:
    """One filled loop.

    Attributes
    ----------
    loop : Loop
    family : int
        Index of its symmetry orbit (faces of one family are images of each other).
    transform : (2, 2) ndarray
        The top-view map from the family's solved face to this one (identity for it).
    vertices : (n, 3) ndarray
    faces : (m, 3) ndarray
    boundary : (k,) ndarray of int
        Boundary vertex indices in loop order.
    surface : MinimalSurface
        The family's solve (area, residual, iterations, convergence).
    flat_area : float
        Area of the earcut fill of the same boundary (:func:`~auszug.meshing.minimal.flat_area`).
    """

    loop: Loop
    family: int
    transform: Array
    vertices: Array
    faces: NDArray[np.int64]
    boundary: NDArray[np.int64]
    surface: MinimalSurface
    flat_area: float

    @property
    def area(self) -> float:
        """Area of the minimal surface."""
        return self.surface.area


@dataclass(frozen=True, eq=False)
class Faces:
    """All faces of a network.

    Attributes
    ----------
    faces : tuple of Face
    graph : NetworkGraph
    """

    faces: tuple[Face, ...]
    graph: NetworkGraph

    @property
    def converged(self) -> bool:
        """Whether every family's solve converged."""
        return all(f.surface.converged for f in self.faces)

    @property
    def residual(self) -> float:
        """Largest residual mean curvature (dimensionless) over all faces (0 without faces)."""
        return max((f.surface.residual for f in self.faces), default=0.0)

    @property
    def families(self) -> int:
        """Number of distinct solves."""
        return len({f.family for f in self.faces})

    def mesh(self) -> Mesh:
        """All faces as one mesh, a part ``face<family>/<i>`` each."""
        vs, fs, parts = [], [], []
        nv = nf = 0
        count: dict[int, int] = {}
        for fc in self.faces:
            j = count.get(fc.family, 0)
            count[fc.family] = j + 1
            vs.append(fc.vertices)
            fs.append(fc.faces + nv)
            parts.append(Part(f"face{fc.family}/{j}", "face", fc.family, str(j),
                              (nv, nv + len(fc.vertices)), (nf, nf + len(fc.faces))))
            nv += len(fc.vertices)
            nf += len(fc.faces)
        if not vs:
            return Mesh(np.empty((0, 3)), np.empty((0, 3), dtype=np.int64))
        return Mesh(np.concatenate(vs), np.concatenate(fs), tuple(parts))


def common_group(network: Any) -> tuple[Array, Array]:
    """Symmetry elements shared by every basic curve: (k, 2, 2) matrices and the centre (2,).

    Only the identity when the curves have different centres.
    """
    groups = as_curve_network(network).groups
    if not groups:
        return np.eye(2)[None], np.zeros(2)
    c0 = np.asarray(groups[0].center)
    mats = groups[0].matrices()
    for g in groups[1:]:
        if not np.allclose(np.asarray(g.center), c0, atol=1e-12):
            return np.eye(2)[None], c0
        other = g.matrices()
        keep = [m for m in mats if np.any(np.all(np.abs(other - m) <= 1e-9, axis=(1, 2)))]
        mats = np.array(keep)
    return mats, c0


def _orbits(graph: NetworkGraph, loops: Sequence[Loop], mats: Array, centre: Array) -> list[tuple[int, int]]:
    """For every loop: (representative loop index, group element mapping it there)."""
    from scipy.spatial import cKDTree

    mids = np.array([graph.edge_points(e, 3)[1] for e in range(len(graph.edges))])
    tree = cKDTree(mids)
    keys = {lp.key(): i for i, lp in enumerate(loops)}
    rep: list[tuple[int, int]] = [(-1, 0)] * len(loops)
    tol = max(graph.tol, 1e-7 * graph.size)
    for i, lp in enumerate(loops):
        if rep[i][0] >= 0:
            continue
        rep[i] = (i, 0)
        es = np.array([e for e, _ in lp.halfedges])
        for k in range(1, len(mats)):
            p = mids[es].copy()
            p[:, :2] = (p[:, :2] - centre) @ mats[k].T + centre
            d, j = tree.query(p)
            if np.any(d > 10 * tol):
                continue
            other = keys.get(frozenset(j.tolist()))
            if other is not None and rep[other][0] < 0:
                rep[other] = (i, k)
    return rep


def _map_face(ms: MinimalSurface, m: Array, centre: Array, loop: Loop, rep_loop: Loop,
              k_bnd: int) -> tuple[Array, NDArray[np.int64]]:
    v = ms.vertices.copy()
    v[:, :2] = (v[:, :2] - centre) @ m.T + centre
    f = ms.faces[:, ::-1] if np.linalg.det(m) < 0 else ms.faces
    return v, f


def _loop_bound(graph: Any) -> int:
    """An estimate, from above, of the loops :func:`find_loops` finds in ``graph`` (rims added).

    The graph's cycle rank, edges - nodes + components (for a planar graph
    its bounded faces, by Euler), plus one per pair of loose ends. It bounded
    the loops found on every drawing of the bundled examples and on tn-2 up
    to fold 128 (12 673 for 12 160), which tests/test_limits.py checks.
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    n = len(graph.nodes)
    if n == 0:
        return 0
    a = np.array([e.a for e in graph.edges], dtype=np.int64)
    b = np.array([e.b for e in graph.edges], dtype=np.int64)
    adj = coo_matrix((np.ones(len(a)), (a, b)), shape=(n, n))
    comps = connected_components(adj, directed=False)[0]
    degree = np.bincount(np.concatenate([a, b]), minlength=n)
    return max(0, len(a) - n + comps) + int((degree == 1).sum()) // 2


def network_faces(
    network: Any,
    loops: Sequence[Loop] | None = None,
    resolution: int = 96,
    tol: float = RESIDUAL_TOL,
    meet_tol: float = 1e-2,
    rims: bool = True,
    max_iterations: int = 100,
) -> Faces:
    """Minimal-surface faces for the loops of a network (automatic or given).

    Parameters
    ----------
    network : CurveNetwork (or a producer of one, e.g. ``microarch.Network``)
    loops : sequence of Loop, optional
        Default: every loop :func:`~auszug.meshing.loops.find_loops` finds.
    resolution : int
        Boundary points per loop (>= 12); the interior gets triangles of about
        the boundary spacing.
    tol : float
        Residual mean curvature to reach (see :class:`MinimalSurface`).
    meet_tol : float
        Relative height difference within which crossing curves meet
        (the authors' demo uses 1e-2, which traced drawings need).
    rims : bool
        Close open chains whose loose ends share a height.
    max_iterations : int

    Returns
    -------
    Faces
        Empty when the network has no loops.

    Examples
    --------
    >>> from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry, build
    >>> arch = BasicCurve(((-1.0, 2.0), (0.0, 3.0)), (Segment("line"),), ("ground", "apex"),
    ...                   Symmetry(fold=1, mirror=True), height=1.0)
    >>> fs = network_faces(build(Drawing((arch,))), resolution=48)
    >>> len(fs.faces), fs.converged, fs.faces[0].area < fs.faces[0].flat_area
    (1, True, True)
    """
    if int(resolution) < 12:
        raise GeometryError(f"need at least 12 boundary points per face, got {resolution}")
    lower = "a lower face resolution, a lower fold or fewer curves"
    if loops is None:
        graph = network_graph(network, meet_tol)   # checks the curves against LIMITS.face_solid_curves
        if rims:
            graph = _add_rims(graph)   # here, not in find_loops: the bound counts them
            rims = False
        n = _loop_bound(graph)
        if n > LIMITS.faces:
            raise DrawingError(f"the faces (up to {n:,} loops) are above the limit of {LIMITS.faces:,} loops "
                               f"(auszug.limits.LIMITS.faces); {lower.replace('a lower face resolution, ', 'use ')}")
        check_triangles(face_triangles(n, int(resolution)), f"the faces (up to {n:,} loops)", lower)
        loops = find_loops(graph, rims=rims)
    else:
        loops = list(loops)
        if len(loops) > LIMITS.faces:
            raise DrawingError(f"{len(loops):,} faces are above the limit of {LIMITS.faces:,} "
                               "(auszug.limits.LIMITS.faces)")
        check_triangles(face_triangles(len(loops), int(resolution)), f"{len(loops):,} faces", lower)
        if not loops:
            return Faces((), network_graph(network, meet_tol))
        graph = loops[0].graph
    if not loops:
        return Faces((), graph)
    graph = loops[0].graph   # with its rims
    mats, centre = common_group(network)
    rep = _orbits(graph, loops, mats, centre)
    solved: dict[int, tuple[MinimalSurface, float, int]] = {}
    out: list[Face] = []
    fam_of: dict[int, int] = {}
    for i, lp in enumerate(loops):
        r, k = rep[i]
        if r not in solved:
            b, _ = loops[r].boundary(int(resolution))
            ms = minimal_surface(b, max_iterations=max_iterations, tol=tol, centre=centre)
            solved[r] = (ms, flat_area(b, centre), len(b))
            fam_of[r] = len(fam_of)
        ms, fa, kb = solved[r]
        v, f = _map_face(ms, mats[k], centre, lp, loops[r], kb)
        out.append(Face(lp, fam_of[r], mats[k], v, f, ms.boundary, ms, fa))
    return Faces(tuple(out), graph)
