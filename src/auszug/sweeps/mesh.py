"""The input of sweep detection: a triangle mesh, normalised, with its edges and vertex normals.

Normalisation (paper sec. 1.1): centre on the bounding-box centre and scale to bounding-box
diameter 1, so that the side condition ``||C|| = 1`` of a velocity state weighs rotation against
translation the same way on every mesh, and every length threshold is a fraction of the diameter.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.errors import GeometryError
from auszug.sweeps import _kernels

__all__ = ["SweepMesh", "normalise", "edge_topology", "vertex_normals", "face_components"]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True)
class SweepMesh:
    """A normalised triangle mesh with the topology the plane cutter walks.

    Attributes
    ----------
    vertices : (n, 3) float array
        ``(input - centre) / scale``: bounding box centred at 0, diameter 1.
    faces : (m, 3) int array
    normals : (n, 3) float array
        Unit vertex normals (area-weighted face normals; zero where a vertex has only zero-area faces).
    edges : (k, 2) int array
        Unique undirected edges, ``edges[:, 0] < edges[:, 1]``.
    edge_faces : (k, 2) int array
        The one or two faces of each edge (-1 where a boundary edge has one).
    face_edges : (m, 3) int array
        Each face's edges (opposite vertex 2, 0, 1: the edges (0,1), (1,2), (2,0)).
    centre : (3,) float array
        Bounding-box centre of the input.
    scale : float
        Bounding-box diameter of the input.
    """

    vertices: Array
    faces: IntArray
    normals: Array
    edges: IntArray
    edge_faces: IntArray
    face_edges: IntArray
    centre: Array
    scale: float

    def __getstate__(self) -> dict[str, object]:
        """The fields only: what is kept with the mesh (its closest-point tree) is neither pickled nor copied."""
        return {k: v for k, v in self.__dict__.items() if not k.startswith("_")}

    @property
    def n_vertices(self) -> int:
        """Number of vertices."""
        return len(self.vertices)

    def to_input(self, points: ArrayLike) -> Array:
        """Points ``(..., 3)`` from normalised back to input coordinates."""
        return np.asarray(points, float) * self.scale + self.centre

    def plane_to_input(self, normal: ArrayLike, offset: ArrayLike) -> tuple[Array, Array]:
        """Planes ``n . x = d`` from normalised to input coordinates (same unit normals)."""
        n = np.asarray(normal, float)
        return n, np.asarray(offset, float) * self.scale + n @ self.centre


def vertex_normals(vertices: ArrayLike, faces: ArrayLike) -> Array:
    """Unit area-weighted vertex normals ``(n, 3)``; zero rows where the faces around have no area.

    Examples
    --------
    >>> vertex_normals([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]).tolist()
    [[0.0, 0.0, 1.0], [0.0, 0.0, 1.0], [0.0, 0.0, 1.0]]
    """
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    vn = _kernels.vertex_normal_sums(np.ascontiguousarray(v), np.ascontiguousarray(f))
    norm = np.linalg.norm(vn, axis=1, keepdims=True)
    return np.divide(vn, norm, out=np.zeros_like(vn), where=norm > 0)


def edge_topology(faces: IntArray, n_vertices: int) -> tuple[IntArray, IntArray, IntArray, IntArray]:
    """The undirected edges of triangles, each edge's faces and each face's edges.

    Parameters
    ----------
    faces : (m, 3) int array
        Vertex indices in ``0 .. n_vertices - 1``.
    n_vertices : int

    Returns
    -------
    edges : (k, 2) int array
        Each edge's end vertices, the lower first, edges in the order of ``low * n_vertices + high``.
    edge_faces : (k, 2) int array
        Each edge's first and last face in face order (-1 in the second column for an edge of one
        face, a boundary edge).
    face_edges : (m, 3) int array
        Each face's edges in face order: ``(0, 1), (1, 2), (2, 0)``.
    counts : (k,) int array
        Each edge's number of faces (above 2 where the mesh is not a 2-manifold).

    Examples
    --------
    >>> e, ef, fe, n = edge_topology(np.array([[0, 1, 2], [2, 1, 3]]), 4)
    >>> e.tolist(), ef.tolist()
    ([[0, 1], [0, 2], [1, 2], [1, 3], [2, 3]], [[0, -1], [0, -1], [0, 1], [1, -1], [1, -1]])
    >>> fe.tolist(), n.tolist()
    ([[0, 2, 1], [2, 3, 4]], [1, 1, 2, 1, 1])
    """
    f = np.asarray(faces, np.int64).reshape(-1, 3)
    if len(f) == 0:
        none = np.zeros((0, 2), np.int64)
        return none, none.copy(), np.zeros((0, 3), np.int64), np.zeros(0, np.int64)
    a, b = f.ravel(), f[:, [1, 2, 0]].ravel()              # face i's edges (0 1), (1 2), (2 0) at 3i .. 3i + 2
    # one integer key per undirected edge (low * n + high), its edges in key order by one stable argsort: the
    # faces' edges come in runs of nearly sorted keys, which the stable sort takes in one pass (np.unique's
    # quicksort does not); the same keys, inverse and counts as np.unique's
    key = np.minimum(a, b) * np.int64(n_vertices) + np.maximum(a, b)
    order = np.argsort(key, kind="stable")
    ks = key[order]
    first = np.flatnonzero(np.concatenate([[True], ks[1:] != ks[:-1]]))
    keys = ks[first]
    counts = np.diff(np.append(first, len(ks)))
    inv = np.empty(len(ks), np.int64)
    inv[order] = np.repeat(np.arange(len(keys), dtype=np.int64), counts)
    edges = np.stack([keys // n_vertices, keys % n_vertices], axis=1).astype(np.int64)
    face_of = np.repeat(np.arange(len(f), dtype=np.int64), 3)
    ef = np.full((len(edges), 2), -1, np.int64)
    ef[:, 0] = face_of[order[first]]
    more = counts >= 2
    ef[more, 1] = face_of[order[first[more] + counts[more] - 1]]
    return edges, ef, inv.reshape(-1, 3), counts.astype(np.int64)


def normalise(vertices: ArrayLike, faces: ArrayLike) -> SweepMesh:
    """Normalise a mesh ``(V, F)`` and build its edge topology.

    Raises :class:`~auszug.errors.GeometryError` on an empty mesh, non-finite coordinates, face
    indices out of range, a face repeating a vertex, a zero-size bounding box, or an edge shared by more than two faces
    (the cutter links cut segments through faces and needs a 2-manifold, boundaries allowed).

    Examples
    --------
    >>> m = normalise([[0, 0, 0], [2, 0, 0], [0, 2, 0]], [[0, 1, 2]])
    >>> np.round(m.vertices, 4).tolist(), round(m.scale, 12)
    ([[-0.3536, -0.3536, 0.0], [0.3536, -0.3536, 0.0], [-0.3536, 0.3536, 0.0]], 2.828427124746)
    >>> m.edges.tolist(), m.edge_faces.tolist()
    ([[0, 1], [0, 2], [1, 2]], [[0, -1], [0, -1], [0, -1]])
    """
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces)
    if v.ndim != 2 or v.shape[1] != 3 or len(v) == 0:
        raise GeometryError(f"mesh vertices: expected a non-empty (n, 3) array, got shape {v.shape}")
    if f.ndim != 2 or f.shape[1] != 3 or len(f) == 0:
        raise GeometryError(f"mesh faces: expected a non-empty (m, 3) array of triangles, got shape {f.shape}")
    if not np.issubdtype(f.dtype, np.integer):
        raise GeometryError(f"mesh faces: expected integer vertex indices, got {f.dtype}")
    f = f.astype(np.int64)
    if f.min() < 0 or f.max() >= len(v):
        raise GeometryError(f"mesh faces: vertex indices must be in 0..{len(v) - 1}, got {f.min()}..{f.max()}")
    rep = (f[:, 0] == f[:, 1]) | (f[:, 1] == f[:, 2]) | (f[:, 2] == f[:, 0])
    if rep.any():
        bad_face = int(np.flatnonzero(rep)[0])
        raise GeometryError(f"mesh face {bad_face} {f[bad_face].tolist()} repeats a vertex: expected triangles of "
                            "three distinct vertices (remove degenerate faces)")
    if not np.isfinite(v).all():
        bad = int(np.flatnonzero(~np.isfinite(v).all(axis=1))[0])
        raise GeometryError(f"mesh vertex {bad} has a non-finite coordinate: expected finite numbers")
    used = np.zeros(len(v), bool)
    used[f.ravel()] = True
    lo, hi = v[used].min(0), v[used].max(0)
    scale = float(np.linalg.norm(hi - lo))
    if not scale > 0:
        raise GeometryError("mesh has a zero-size bounding box: expected faces that span some space")
    centre = (lo + hi) / 2
    vn = (v - centre) / scale
    edges, ef, fe, counts = edge_topology(f, len(v))
    if counts.max() > 2:
        e = int(np.argmax(counts))
        raise GeometryError(
            f"mesh edge {edges[e].tolist()} is shared by {counts[e]} faces: expected a 2-manifold "
            "(at most two faces per edge)")
    return SweepMesh(vn, f, vertex_normals(vn, f), edges, ef, fe, centre, scale)


def face_components(mesh: SweepMesh) -> IntArray:
    """The connected component of every face: faces sharing an edge are connected.

    Parameters
    ----------
    mesh : SweepMesh

    Returns
    -------
    (m,) int array
        Labels 0, 1, ... in the order of each component's first face.

    Examples
    --------
    >>> m = normalise([[0, 0, 0], [1, 0, 0], [0, 1, 0], [5, 0, 0], [6, 0, 0], [5, 1, 0.0]], [[0, 1, 2], [3, 4, 5]])
    >>> face_components(m).tolist()
    [0, 1]
    """
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    m = len(mesh.faces)
    two = mesh.edge_faces[:, 1] >= 0
    a, b = mesh.edge_faces[two, 0], mesh.edge_faces[two, 1]
    graph = coo_matrix((np.ones(len(a)), (a, b)), shape=(m, m))
    _, raw = connected_components(graph, directed=False)
    # relabel in the order of first appearance
    _, first, inv = np.unique(raw, return_index=True, return_inverse=True)
    rank = np.argsort(np.argsort(first))
    return rank[inv.reshape(-1)].astype(np.int64)
