"""Triangle meshes: the :class:`Mesh` value, its named parts, and vectorised kernels.

A mesh is ``vertices`` (n, 3) and ``faces`` (m, 3) (indices, counter-clockwise
seen from outside), the potpourri3d/trimesh V/F convention, plus
:class:`Part` records that name contiguous runs of vertices and faces: one
per member replica (``"0/r1m"``), face replica (``"face2/r0"``) or base plate.
Exporters turn parts into OBJ groups and glTF nodes.

The functions (:func:`triangle_areas`, :func:`signed_volume`,
:func:`edge_counts`, :func:`is_closed`, :func:`weld`, ...) are pure and
vectorised; :class:`Mesh` is a thin facade over them.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Iterable, Literal, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.errors import GeometryError

__all__ = [
    "PartKind",
    "Part",
    "Mesh",
    "triangle_areas",
    "triangle_normals",
    "signed_volume",
    "edge_counts",
    "is_closed",
    "boundary_edges",
    "weld",
    "concatenate",
]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]
PartKind = Literal["member", "face", "base", "solid"]


def triangle_areas(vertices: ArrayLike, faces: ArrayLike) -> Array:
    """Area of every triangle.

    Parameters
    ----------
    vertices : (n, 3) array_like
    faces : (m, 3) array_like of int

    Returns
    -------
    (m,) ndarray

    Examples
    --------
    >>> triangle_areas([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]).tolist()
    [0.5]
    """
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    return 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)


def triangle_normals(vertices: ArrayLike, faces: ArrayLike) -> Array:
    """Unit normal of every triangle (right-hand rule), zero for degenerate ones, shape (m, 3)."""
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    ln = np.linalg.norm(n, axis=1, keepdims=True)
    return np.divide(n, ln, out=np.zeros_like(n), where=ln > 0)


def signed_volume(vertices: ArrayLike, faces: ArrayLike) -> float:
    """Enclosed volume of a closed, outward-oriented mesh (divergence theorem).

    Examples
    --------
    >>> v = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
    >>> f = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]
    >>> round(signed_volume(v, f), 12)
    0.166666666667
    """
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    if len(f) == 0:
        return 0.0
    # translate to the centroid for accuracy far from the origin
    v = v - v.mean(axis=0)
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    return float(np.einsum("ij,ij->", a, np.cross(b, c)) / 6.0)


def _directed_edges(faces: IntArray) -> IntArray:
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    return np.stack([f, np.roll(f, -1, axis=1)], axis=-1).reshape(-1, 2)


def edge_counts(faces: ArrayLike) -> tuple[IntArray, IntArray, IntArray]:
    """Undirected edges with how often each is used forwards and backwards.

    Returns
    -------
    edges : (k, 2) ndarray of int
        Unique undirected edges, smaller index first.
    forward : (k,) ndarray of int
        How many faces use the edge from ``edges[:, 0]`` to ``edges[:, 1]``.
    backward : (k,) ndarray of int
        How many use it the other way.
    """
    d = _directed_edges(np.asarray(faces))
    fwd = d[:, 0] < d[:, 1]
    lo, hi = np.minimum(d[:, 0], d[:, 1]), np.maximum(d[:, 0], d[:, 1])
    n = np.int64(hi.max() + 1) if len(hi) else np.int64(1)
    # one int64 key per undirected edge: a 1-D unique is many times faster than unique(axis=0)
    keys, inv = np.unique(lo * n + hi, return_inverse=True)
    inv = inv.reshape(-1)
    edges = np.stack([keys // n, keys % n], axis=1)
    forward = np.bincount(inv[fwd], minlength=len(edges))
    backward = np.bincount(inv[~fwd], minlength=len(edges))
    return edges, forward, backward


def is_closed(faces: ArrayLike) -> bool:
    """Whether every edge is shared by exactly two faces with opposite directions.

    That is a closed, consistently oriented (watertight) 2-manifold away from
    its vertices; :meth:`Mesh.is_manifold` also checks the vertices.

    Examples
    --------
    >>> is_closed([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    True
    >>> is_closed([[0, 1, 2]])
    False
    """
    f = np.asarray(faces)
    if f.size == 0:
        return False
    _, fw, bw = edge_counts(f)
    return bool(np.all((fw == 1) & (bw == 1)))


def boundary_edges(faces: ArrayLike) -> IntArray:
    """Directed edges used by exactly one face, in that face's direction, shape (k, 2)."""
    d = _directed_edges(np.asarray(faces))
    key = np.sort(d, axis=1)
    _, inv, cnt = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    return d[cnt[inv.reshape(-1)] == 1]


def _vertex_manifold(faces: IntArray, n_vertices: int) -> bool:
    """Whether the faces around every vertex form one fan (no pinched vertices)."""
    f = np.asarray(faces, dtype=np.int64)
    if len(f) == 0:
        return True
    # around vertex v each face contributes the wedge (next, prev); a single fan means the
    # wedges link into exactly one cycle (closed) or one path (boundary)
    v = f.reshape(-1)
    nxt = np.roll(f, -1, axis=1).reshape(-1)
    prv = np.roll(f, 1, axis=1).reshape(-1)
    # link the wedge whose outgoing edge is (v, a) to the wedge whose incoming edge is (a, v)
    m = len(v)
    key_a = v * np.int64(n_vertices) + nxt
    key_b = v * np.int64(n_vertices) + prv
    order_b = np.argsort(key_b, kind="stable")
    pos = np.minimum(np.searchsorted(key_b[order_b], key_a), m - 1)
    hit = key_b[order_b[pos]] == key_a
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    a_idx = np.nonzero(hit)[0]
    g = coo_matrix((np.ones(len(a_idx)), (a_idx, order_b[pos[hit]])), shape=(m, m))
    _, roots = connected_components(g, directed=False)
    fans = np.unique(v * np.int64(m) + roots)   # (vertex, fan) pairs as one int64 key each
    return bool(len(fans) == len(np.unique(v)))


def weld(vertices: ArrayLike, faces: ArrayLike, tol: float = 0.0) -> tuple[Array, IntArray]:
    """Merge vertices closer than ``tol`` (exact duplicates for 0); drop faces that collapse.

    Vertices within ``tol`` of each other end up as one, and so do chains of
    such neighbours (a k-d tree finds every pair, wherever it lies). Each
    merged vertex keeps the position of its group's first vertex; the
    vertices keep their first-occurrence order.

    Returns
    -------
    vertices : (k, 3) ndarray
    faces : (l, 3) ndarray

    Examples
    --------
    >>> v, f = weld([[0, 0, 0], [1, 0, 0], [1, 1e-9, 0], [0, 1, 0]], [[0, 1, 3], [0, 2, 3], [0, 1, 2]], 1e-6)
    >>> len(v), f.tolist()
    (3, [[0, 1, 2], [0, 1, 2]])
    """
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    if tol > 0.0 and len(v):
        from scipy.sparse import coo_matrix
        from scipy.sparse.csgraph import connected_components
        from scipy.spatial import cKDTree

        pairs = cKDTree(v).query_pairs(tol, output_type="ndarray")
        n = len(v)
        g = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
        _, key = connected_components(g, directed=False)
    else:
        key = v
    _, first, inv = np.unique(key, axis=0, return_index=True, return_inverse=True)
    inv = inv.reshape(-1)
    order = np.argsort(first)           # keep the first occurrence order
    remap = np.empty_like(order)
    remap[order] = np.arange(len(order))
    new_f = remap[inv[f]]
    keep = (new_f[:, 0] != new_f[:, 1]) & (new_f[:, 1] != new_f[:, 2]) & (new_f[:, 0] != new_f[:, 2])
    return v[first[order]], new_f[keep]


@dataclass(frozen=True)
class Part:
    """A named run of vertices and faces of a :class:`Mesh`.

    Attributes
    ----------
    name : str
        ``"<basic>/<replica>"`` for members (like network curve ids, e.g.
        ``"0/r1m"``, ``"2/r0.free_end1"``), ``"face<i>/<replica>"`` for faces,
        ``"base"`` for the base plate, ``"solid"`` for a united solid.
    kind : {"member", "face", "base", "solid"}
    basic : int
        Basic curve index (members), face family index (faces), -1 otherwise.
    replica : str
        Replica label ``r<k>`` / ``r<k>m`` (``""`` if none).
    vertices : (int, int)
        ``[start, stop)`` into :attr:`Mesh.vertices`.
    faces : (int, int)
        ``[start, stop)`` into :attr:`Mesh.faces`.
    """

    name: str
    kind: str
    basic: int
    replica: str
    vertices: tuple[int, int]
    faces: tuple[int, int]


@dataclass(frozen=True, eq=False)
class Mesh:
    """A triangle mesh with named parts.

    Attributes
    ----------
    vertices : (n, 3) ndarray of float64
        z is up, drawing units.
    faces : (m, 3) ndarray of int64
        Counter-clockwise seen from outside.
    parts : tuple of Part
        Contiguous, non-overlapping runs (may be empty: one anonymous part).

    Examples
    --------
    >>> m = Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
    ...          [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    >>> m.n_vertices, m.n_faces, m.is_watertight, round(m.volume, 6)
    (4, 4, True, 0.166667)
    """

    vertices: Array
    faces: IntArray
    parts: tuple[Part, ...] = field(default=())

    def __post_init__(self) -> None:
        v = np.asarray(self.vertices, dtype=np.float64).reshape(-1, 3)
        f = np.asarray(self.faces, dtype=np.int64).reshape(-1, 3)
        if len(f) and (f.min() < 0 or f.max() >= len(v)):
            raise GeometryError(f"face indices must lie in 0..{len(v) - 1}")
        object.__setattr__(self, "vertices", v)
        object.__setattr__(self, "faces", f)
        object.__setattr__(self, "parts", tuple(self.parts))

    @classmethod
    def _unchecked(cls, vertices: Array, faces: IntArray, parts: tuple[Part, ...] = ()) -> "Mesh":
        """A mesh from arrays already known to be valid (float64 (n, 3), int64 (m, 3))."""
        m = object.__new__(cls)
        object.__setattr__(m, "vertices", vertices)
        object.__setattr__(m, "faces", faces)
        object.__setattr__(m, "parts", tuple(parts))
        return m

    # -- counts and measures -------------------------------------------------------------
    @property
    def n_vertices(self) -> int:
        """Number of vertices."""
        return len(self.vertices)

    @property
    def n_faces(self) -> int:
        """Number of triangles."""
        return len(self.faces)

    @cached_property
    def area(self) -> float:
        """Total surface area."""
        return float(triangle_areas(self.vertices, self.faces).sum())

    @cached_property
    def volume(self) -> float:
        """Signed enclosed volume (meaningful for closed meshes)."""
        return signed_volume(self.vertices, self.faces)

    @cached_property
    def is_watertight(self) -> bool:
        """Every edge shared by exactly two consistently oriented faces."""
        return is_closed(self.faces)

    @cached_property
    def is_manifold(self) -> bool:
        """Watertight, and the faces around every vertex form a single fan."""
        return self.is_watertight and _vertex_manifold(self.faces, self.n_vertices)

    def bounds(self) -> Array:
        """Axis-aligned bounds, shape (2, 3)."""
        return np.stack([self.vertices.min(0), self.vertices.max(0)])

    # -- parts ---------------------------------------------------------------------------
    def part(self, name: str) -> "Mesh":
        """The part called ``name`` as a mesh of its own."""
        for p in self.parts:
            if p.name == name:
                return self._sub(p)
        raise KeyError(f"no part {name!r}; parts: {[p.name for p in self.parts][:8]}...")

    def _sub(self, p: Part) -> "Mesh":
        v0, v1 = p.vertices
        f0, f1 = p.faces
        part = replace(p, vertices=(0, v1 - v0), faces=(0, f1 - f0))
        return Mesh(self.vertices[v0:v1], self.faces[f0:f1] - v0, (part,))

    def split_parts(self) -> list["Mesh"]:
        """Every part as a mesh of its own."""
        return [self._sub(p) for p in self.parts]

    def select(self, kinds: Iterable[str]) -> "Mesh":
        """Only the parts of the given kinds."""
        ks = set(kinds)
        return concatenate([m for m in self.split_parts() if m.parts[0].kind in ks])

    def welded(self, tol: float = 0.0) -> "Mesh":
        """One part, vertices within ``tol`` merged (see :func:`weld`)."""
        v, f = weld(self.vertices, self.faces, tol)
        return Mesh(v, f, (Part("mesh", "solid", -1, "", (0, len(v)), (0, len(f))),))


def concatenate(meshes: Sequence[Mesh]) -> Mesh:
    """Meshes side by side (parts kept, indices shifted); an empty list gives an empty mesh."""
    meshes = [m for m in meshes if m.n_faces or m.n_vertices]
    if not meshes:
        return Mesh(np.empty((0, 3)), np.empty((0, 3), dtype=np.int64))
    nv = np.cumsum([0] + [m.n_vertices for m in meshes])
    nf = np.cumsum([0] + [m.n_faces for m in meshes])
    v = np.concatenate([m.vertices for m in meshes])
    f = np.concatenate([m.faces + nv[i] for i, m in enumerate(meshes)])
    parts: list[Part] = []
    for i, m in enumerate(meshes):
        ps = m.parts or (Part(f"part{i}", "member", -1, "", (0, m.n_vertices), (0, m.n_faces)),)
        for p in ps:
            parts.append(replace(p, vertices=(p.vertices[0] + int(nv[i]), p.vertices[1] + int(nv[i])),
                                 faces=(p.faces[0] + int(nf[i]), p.faces[1] + int(nf[i]))))
    return Mesh(v, f, tuple(parts))
