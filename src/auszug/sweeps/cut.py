"""Planar cuts of a mesh: many planes at once, cut segments linked into polylines (compiled).

Each plane is one iteration of a compiled parallel loop: signed distances of all vertices, the
crossed edges, then a walk from crossed edge to crossed edge through the faces (a face that a
plane crosses has exactly two crossed edges). Chains start at boundary edges; what remains are
closed loops. Work is ``O(vertices + edges)`` per plane, so linear in vertices x planes.
A vertex exactly on a plane counts as on its positive side (no special cases; a repeated point
is dropped).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numba
import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.sweeps import _kernels
from auszug.sweeps.mesh import SweepMesh

__all__ = ["Cuts", "cut", "EdgeGrid", "cut_near"]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]

#: Cuts by fewer planes than this run on one thread (the per-sweep re-cuts of sec. 2.3).
SERIAL_BELOW = 64

#: Cell size of :class:`EdgeGrid` (bounding-box diameters): a few edges' lengths of the meshes of
#: sweep detection (32k vertices: edges up to 0.0075).
GRID_CELL = 0.02


@dataclass(frozen=True)
class Cuts:
    """Polylines of many planar cuts, in one shared array (trimesh-style offsets).

    Attributes
    ----------
    plane_normals : (p, 3) float array
    plane_offsets : (p,) float array
        Planes ``n . x = d`` in normalised mesh coordinates.
    points : (N, 3) float array
        Every cut curve's points, curve after curve.
    normals : (N, 3) float array
        Unit surface normals there (vertex normals interpolated along the cut edge).
    edges : (N,) int array
        The mesh edge each point lies on.
    curve_start : (c + 1,) int array
        Curve ``k`` is ``points[curve_start[k]:curve_start[k + 1]]``.
    curve_plane : (c,) int array
        The plane of each curve.
    curve_closed : (c,) bool array
        Closed loops (the last point joins the first) versus chains from boundary to boundary.
    """

    plane_normals: Array
    plane_offsets: Array
    points: Array
    normals: Array
    edges: IntArray
    curve_start: IntArray
    curve_plane: IntArray
    curve_closed: BoolArray

    @property
    def n_planes(self) -> int:
        """Number of planes cut (including those that miss the mesh)."""
        return len(self.plane_offsets)

    @property
    def n_curves(self) -> int:
        """Number of cut curves."""
        return len(self.curve_plane)

    def curve(self, k: int) -> Array:
        """Points ``(n, 3)`` of curve ``k``."""
        return self.points[self.curve_start[k] : self.curve_start[k + 1]]

    def curve_lengths(self) -> Array:
        """Arc length of every curve ``(c,)`` (closing segment included for loops)."""
        seg = np.linalg.norm(np.diff(self.points, axis=0), axis=1)
        cum = np.concatenate([[0.0], np.cumsum(seg)])
        s, e = self.curve_start[:-1], self.curve_start[1:] - 1
        length = cum[e] - cum[s]
        close = np.linalg.norm(self.points[e] - self.points[s], axis=1)
        return length + np.where(self.curve_closed, close, 0.0)


def cut(mesh: SweepMesh, normals: ArrayLike, offsets: ArrayLike) -> Cuts:
    """Cut ``mesh`` by the planes ``normals[i] . x = offsets[i]`` (normalised coordinates).

    Examples
    --------
    >>> from auszug.sweeps.fixtures import extruded
    >>> from auszug.sweeps.mesh import normalise
    >>> fx = extruded(n_profile=30, n_path=40)
    >>> c = cut(normalise(fx.vertices, fx.faces), [[1.0, 0, 0], [0, 0, 1.0]], [0.0, 0.0])
    >>> c.n_curves, c.curve_closed.tolist()
    (2, [False, False])
    """
    n = np.ascontiguousarray(np.array(normals, float, ndmin=2))
    d = np.ascontiguousarray(np.array(offsets, float, ndmin=1))
    if n.shape != (len(d), 3):
        raise ValueError(f"plane normals (p, 3) and offsets (p,) must match, got {n.shape} and {d.shape}")
    n = n / np.linalg.norm(n, axis=1, keepdims=True)
    # a few planes run on one thread: waking the thread pool costs more than it gains (measured on
    # 2 loaded cores, 32k vertices: 1 plane 1.0 ms serial against 55 ms in parallel; 40 planes 33 ms
    # against 74 ms)
    threads = numba.get_num_threads()
    if len(d) < SERIAL_BELOW:
        numba.set_num_threads(1)
    try:
        counts = _kernels.cut_count(mesh.vertices, mesh.edges, n, d)
        start = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
        pts, nrm, eid, first, closed, written = _kernels.cut_fill(
            mesh.vertices, mesh.normals, mesh.edges, mesh.edge_faces, mesh.face_edges, n, d, start)
    finally:
        numba.set_num_threads(threads)
    keep = eid >= 0
    slot_plane = np.repeat(np.arange(len(d)), counts)
    pts, nrm, eid, first, closed = pts[keep], nrm[keep], eid[keep], first[keep], closed[keep]
    starts = np.flatnonzero(first)
    curve_plane = slot_plane[keep][starts].astype(np.int64)
    return Cuts(n, d, pts, nrm, eid, np.append(starts, len(pts)).astype(np.int64), curve_plane, closed[starts])


@dataclass(frozen=True)
class EdgeGrid:
    """A mesh's edges binned by their midpoints in a uniform grid (for :func:`cut_near`).

    Attributes
    ----------
    origin : (3,) float array
    dims : (3,) int array
        Cells along x, y, z.
    cell_start : (c + 1,) int array
        Cell ``i``'s edges are ``edges[cell_start[i]:cell_start[i + 1]]`` (cells x-major).
    edges : (e,) int array
        Edge indices, cell after cell (of the larger mesh for a part's grid, :meth:`part`).
    cell : float
        Cell size.
    longest : float
        The longest edge of the mesh (of the larger mesh for a part's grid).
    ends : (6, e) float array
        The edges' end points in the order of ``edges`` (rows: the first end's x, y, z, then the
        second's), read by :func:`cut_near`'s scan in a row.
    cell_box : (c, 6) float array
        Per cell the box of its edges' end points (min, max corners; inf, -inf for an empty
        cell): :func:`cut_near` passes over the cells whose box lies on one side of a plane.
    local : (E,) int array
        Empty for a mesh's own grid; for a part's grid (:meth:`part`) each of the larger mesh's
        edges' index among the part's (-1 for an edge not in the part).
    """

    origin: Array
    dims: IntArray
    cell_start: IntArray
    edges: IntArray
    cell: float
    longest: float
    ends: Array
    cell_box: Array
    local: IntArray = field(default_factory=lambda: np.zeros(0, np.int64))

    @classmethod
    def of(cls, mesh: SweepMesh, cell: float = GRID_CELL) -> "EdgeGrid":
        """The grid of ``mesh``'s edges (one compiled pass)."""
        lo, dims, start, order, longest, ends, cell_box = _kernels.edge_grid(mesh.vertices, mesh.edges, float(cell))
        return cls(lo, dims, start, order, float(cell), float(longest), ends, cell_box)

    def part(self, edge_index: IntArray) -> "EdgeGrid":
        """The grid for a part of its mesh: the part's edges in the same cells, no new binning.

        The part shares the mesh's vertices and keeps some of its edges; ``edge_index (E,)`` is
        each of the mesh's edges' index among the part's (-1 for an edge not in the part, as
        :func:`~auszug.sweeps._kernels.box_part` gives it). :func:`cut_near` on the part with
        this grid gives the same curves in a box as with the part's own grid (:meth:`of`): it
        seeds from the same crossed edges of the part in the cells near the box (the longest
        edge, hence the cells' margin, is the whole mesh's, no shorter) and passes over the
        others; it may find other curves without a point in the box.
        """
        if len(self.local):
            raise ValueError("a part's grid: take the part of its whole mesh's grid")
        return replace(self, local=np.ascontiguousarray(edge_index, dtype=np.int64))


def cut_near(mesh: SweepMesh, normals: ArrayLike, offsets: ArrayLike, boxes: ArrayLike,
             grid: EdgeGrid | None = None) -> Cuts:
    """The cut curves of each plane that have a point in its box, exactly as :func:`cut` gives them.

    ``boxes (p, 6)`` are per plane the box's minimum and maximum corners. Each cut curve with a
    point in its plane's box comes out point for point as :func:`cut` gives it, and a plane's
    curves in the same order; curves without a point there may be missing. The work is the
    grid's cells in the boxes near the planes and the curves found, not the whole mesh
    (:class:`EdgeGrid`, built here if not given).

    Examples
    --------
    >>> from auszug.sweeps.fixtures import extruded
    >>> from auszug.sweeps.mesh import normalise
    >>> m = normalise(*(lambda f: (f.vertices, f.faces))(extruded(n_profile=30, n_path=40)))
    >>> whole = cut(m, [[1.0, 0, 0]], [0.0])
    >>> near = cut_near(m, [[1.0, 0, 0]], [0.0], [[-0.1, -1, -1, 0.1, 1, 1]])
    >>> bool(np.array_equal(near.points, whole.points)), near.n_curves
    (True, 1)
    """
    n = np.ascontiguousarray(np.array(normals, float, ndmin=2))
    d = np.ascontiguousarray(np.array(offsets, float, ndmin=1))
    b = np.ascontiguousarray(np.array(boxes, float, ndmin=2))
    if n.shape != (len(d), 3) or b.shape != (len(d), 6):
        raise ValueError(f"plane normals (p, 3), offsets (p,) and boxes (p, 6) must match, got {n.shape}, {d.shape} "
                         f"and {b.shape}")
    n = n / np.linalg.norm(n, axis=1, keepdims=True)      # as cut(): the same signed distances, bit for bit
    g = EdgeGrid.of(mesh) if grid is None else grid
    pts, nrm, eid, start, plane, closed = _kernels.cut_near(
        mesh.vertices, mesh.normals, mesh.edges, mesh.edge_faces, mesh.face_edges, g.origin, g.dims, g.cell_start,
        g.edges, g.cell, g.longest, n, d, b, g.ends, g.cell_box, g.local)
    return Cuts(n, d, pts, nrm, eid, start, plane, closed)
