"""Sweep patches: a profile, its motion, the mesh faces it covers, its fit error (paper sec. 2.3.4).

A patch is a planar profile (a polyline at motion parameter ``t0``) and a :class:`Motion` taking it
to every later position. Kinematic surfaces (revolution, extrusion, helical) give their patches
directly from :func:`~auszug.sweeps.kinematic_axis`:

- the **parameter** of a point: its angle about the axis (rotation; screw, unwound by the pitch)
  or its distance along the direction (translation); the patch runs over the parameters of the
  mesh's vertices (for a rotation, the full turn minus the largest empty angular gap);
- the **profile**: the cut by the plane containing the axis (orthogonal to the direction) at the
  middle parameter, its pieces at least ``l_min`` long each a patch, mapped back to ``t0``;
  improved (sec. 2.3.3) by ``profile_cuts`` further cuts at parameters spread over the range, also
  mapped back: each profile point moves to the mean of its closest points on them;
- the **motion**: the exact kinematic motion at ``motion_samples`` (>= 8) parameters.

The fit check (:func:`fit_patch`) meshes the swept surface (rings of the profile at parameters
dense enough that chords stay within ``eps_prox / 10``), takes closest points both ways (the
swept points on the mesh with the compiled face grids of :class:`MeshTree`; the mesh's vertices on the swept
surface with the compiled :class:`RingTree` of its rings, within ``eps_prox``): the faces covered
are the mesh faces whose three vertices lie within ``eps_prox`` of the swept surface, the fit
error the largest distance of the swept surface's points to the mesh, and coverage the covered
faces' share of the mesh's area.

All in normalised coordinates (bounding-box diameter 1); :func:`auszug.sweeps.detect` converts
the accepted patches to the input's coordinates.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Literal, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.errors import GeometryError
from auszug.sweeps._kernels import (
    boundary_edges_of,
    closest_features,
    face_grid,
    face_grid_cell,
    face_vertices_in_box,
    faces_within,
    improve_sums,
    interior_max,
    mesh_closest,
    mesh_closest_within,
    ring_grid_boxes,
    ring_grid_nearest,
    ring_grid_within,
    triangle_areas,
    unit_face_normals,
)
from auszug.sweeps.cut import cut
from auszug.sweeps.kinematic import KinematicAxis
from auszug.sweeps.mesh import SweepMesh, edge_topology, vertex_normals
from auszug.sweeps.motion import Motion, screw_motion
from auszug.sweeps.params import DEFAULT, SweepParams

if TYPE_CHECKING:
    from auszug.meshing.sweepmodel import Sweep
    from auszug.sweeps.profilefit import FittedProfile

__all__ = ["SweepPatch", "Fit", "MeshTree", "RingTree", "kinematic_patches", "fit_patch", "face_areas", "sweep_surface",
           "closest_distance", "polyline_hausdorff", "SweptError", "swept_error", "swept_coverage", "improve_flat",
           "improve_bounded", "consistent_pieces", "fill_corners", "area_coverage", "area_samples", "sample_hits",
           "add_by_area"]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]
Kind = Literal["rotation", "translation", "screw", "general"]


@dataclass(frozen=True)
class SweepPatch:
    """A profile swept by a rigid motion, and what of the mesh it explains.

    Attributes
    ----------
    id : int
    kind : {"rotation", "translation", "screw", "general"}
    profile : (n, 3) float array
        The profile polyline at the motion's first parameter (the first rib).
    closed : bool
        Whether the profile is a closed loop.
    motion : Motion
        Rigid maps taking the profile to its position at ``t``; identity at ``t[0]``. ``t`` is
        the angle (radians) for rotations and screws, the distance for translations, the rib
        number for general sweeps.
    faces : (m,) int array
        Indices of the mesh faces the patch covers (their vertices within ``eps_prox``).
    fit_error : float
        Largest distance of the swept profile to the mesh, over the bounding-box diameter.
    coverage : float
        The covered faces' share of the mesh's area, 0..1.
    profile_fit : FittedProfile or None
        The profile as exact lines and arcs (beyond the paper; :func:`auszug.sweeps.fit_profile`),
        None where no fit is within ``profile_fit_tolerance``.
    """

    id: int
    kind: Kind
    profile: Array
    closed: bool
    motion: Motion
    faces: IntArray
    fit_error: float
    coverage: float
    profile_fit: FittedProfile | None = None

    def swept(self, t: ArrayLike) -> Array:
        """The profile at parameters ``t (q,)``: shape ``(q, n, 3)``."""
        return self.motion.apply(self.profile, t)

    def sweep(self) -> Sweep:
        """The patch as a value of meshing's sweep model (:class:`auszug.meshing.sweepmodel.Sweep`).

        The profile plane gets the frame (W, D, N) with origin the profile's centroid, W along its
        principal direction, N its normal; frame ``k`` is the motion's ``R_k`` applied to it.
        Re-meshing it (``.mesh()``) gives the swept surface with a ring per motion knot. The
        profile is :attr:`profile_fit` (exact lines and arcs) where there is one, else the
        polyline.
        """
        from auszug.meshing.profile import Profile
        from auszug.meshing.sweepmodel import Path, RigidFrames, Sweep
        from auszug.sweeps.profilefit import profile_frame

        if self.profile_fit is not None:
            o, basis, prof = self.profile_fit.origin, self.profile_fit.axes, self.profile_fit.profile
        else:
            o, basis, xy = profile_frame(self.profile, self.closed)
            prof = Profile(xy, closed=self.closed, name=f"patch {self.id}")
        rot = self.motion.rotation @ basis
        origins = np.einsum("kij,j->ki", self.motion.rotation, o) + self.motion.translation
        moved = np.linalg.norm(np.diff(origins, axis=0), axis=1)
        if np.all(moved > 1e-12):
            path = Path.polyline(origins)
        else:   # the centroid stays put (a pure turn about it): tangents from the frames' normal
            path = Path(origins + 1e-12 * np.arange(len(origins))[:, None] * rot[:, :, 2], rot[:, :, 2],
                        s=self.motion.t)
        return Sweep(prof, path, RigidFrames(self.motion.t, rot, origins))


@dataclass(frozen=True)
class Fit:
    """The fit check of one swept surface against the mesh (normalised coordinates).

    Attributes
    ----------
    vertex_distance : (n_vertices,) float array
        Distance of every mesh vertex to the swept surface where at most ``eps_prox`` (inf where
        farther, and at vertices of no face of the mesh, which may be a part).
    faces : (m,) int array
        Faces whose three vertices are within ``eps_prox``.
    fit_error : float
        Largest distance of the swept surface's sample points to the mesh.
    coverage : float
        Area share of ``faces``.
    """

    vertex_distance: Array
    faces: IntArray
    fit_error: float
    coverage: float


def face_areas(vertices: ArrayLike, faces: ArrayLike) -> Array:
    """Areas ``(m,)`` of triangles.

    Examples
    --------
    >>> face_areas([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]).tolist()
    [0.5]
    """
    v = np.ascontiguousarray(vertices, dtype=float)
    f = np.ascontiguousarray(faces, dtype=np.int64)
    out: Array = triangle_areas(v.reshape(-1, 3), f.reshape(-1, 3))    # one compiled pass, numpy's arithmetic
    return out


def closest_distance(points: ArrayLike, vertices: ArrayLike, elements: ArrayLike) -> tuple[Array, Array]:
    """Distances ``(n,)`` and closest points ``(n, 3)`` of points to triangles or segments (libigl).

    ``elements`` is ``(m, 3)`` triangles or ``(m, 2)`` segments into ``vertices (k, 3)``.

    Examples
    --------
    >>> d, c = closest_distance([[0.2, 0.2, 1.0]], [[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])
    >>> d.tolist(), np.round(c, 12).tolist()
    ([1.0], [[0.2, 0.2, 0.0]])
    """
    import igl

    p = np.ascontiguousarray(np.asarray(points, float).reshape(-1, 3))
    if len(p) == 0:
        return np.zeros(0), np.zeros((0, 3))
    sq, _, c = igl.point_mesh_squared_distance(p, np.ascontiguousarray(np.asarray(vertices, float)),
                                               np.ascontiguousarray(np.asarray(elements, np.int64)))
    return np.sqrt(np.maximum(sq, 0.0)), np.asarray(c)


#: :meth:`MeshTree.face_grid`'s cell size in mean edge lengths of the mesh.
FACE_GRID_CELL = 1.5

#: :meth:`MeshTree.face_grid` has at most this many cells per face (the cell grows on a sparse mesh).
FACE_GRID_CELLS = 8

#: A closest point this near a face's corner (side) lies on that vertex (edge): :meth:`MeshTree.normals`,
#: :meth:`MeshTree.interior_distance` (normalised coordinates).
FEATURE_GAP = 1e-9

#: :meth:`MeshTree.query` searches the fine face grid within this many of its cells; a point with no face that near
#: is searched on the coarse grid, whose cells are :data:`COARSE_GRID_CELL` fine cells wide.
FINE_REACH = 1.0

#: The coarse grid's cell size in the fine grid's cells (:data:`FINE_REACH`).
COARSE_GRID_CELL = 4.0

#: Where :meth:`MeshTree.of` keeps a mesh's tree (an attribute of the mesh object, not a dataclass field).
_TREE_KEY = "_mesh_tree"


class MeshTree:
    """Exact closest points on one triangle mesh, its faces binned once in two uniform grids (compiled).

    The fine grid (:meth:`face_grid`) is searched near each point, a coarse one where no face is
    near (:func:`~auszug.sweeps._kernels.mesh_closest`): true point-triangle distances, every face
    within the distance found tested. Of faces at the same distance (a closest point on an edge
    or a vertex) the first found is kept; the answers built on the face (:meth:`normals`,
    :meth:`on_faces`, :meth:`interior_distance`, :meth:`interior_max`) take the edge or the
    vertex instead (:meth:`_features`), so they do not depend on that choice.

    Examples
    --------
    >>> t = MeshTree(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]]), np.array([[0, 1, 2]]))
    >>> d, f, c = t.query([[0.2, 0.2, 2.0]])
    >>> d.tolist(), f.tolist()
    ([2.0], [0])
    """

    def __init__(self, vertices: ArrayLike, faces: ArrayLike) -> None:
        self.vertices = np.ascontiguousarray(np.asarray(vertices, float))
        self.faces = np.ascontiguousarray(np.asarray(faces, np.int64).reshape(-1, 3))

    @classmethod
    def of(cls, mesh: SweepMesh) -> "MeshTree":
        """The tree of a whole :class:`~auszug.sweeps.mesh.SweepMesh`, built once per mesh (:meth:`built`).

        The first call builds it and keeps it with the mesh; every later call for the same mesh
        object (the kinematic stage, both passes of the general stages, the kinematic parts of
        one ``detect``) gets the same tree. A tree answers a query from the mesh and the query
        alone, so sharing it changes no result.

        Examples
        --------
        >>> from auszug.sweeps.fixtures import extruded
        >>> from auszug.sweeps.mesh import normalise
        >>> m = normalise(*(lambda f: (f.vertices, f.faces))(extruded(n_profile=30, n_path=10)))
        >>> MeshTree.of(m) is MeshTree.of(m)
        True
        """
        got: MeshTree | None = mesh.__dict__.get(_TREE_KEY)
        if got is None:
            got = cls.built(mesh)
            object.__setattr__(mesh, _TREE_KEY, got)      # frozen: a cache of the mesh, not a field
        return got

    @classmethod
    def built(cls, mesh: SweepMesh) -> "MeshTree":
        """A new tree of a whole :class:`~auszug.sweeps.mesh.SweepMesh`, its grids built, boundary edges from topology.

        The same as ``MeshTree(mesh.vertices, mesh.faces)`` with its grids built (:meth:`grids`),
        without counting the edges' faces again (an edge with one face is a boundary edge).
        :meth:`of` keeps it with the mesh.
        """
        tree = cls(mesh.vertices, mesh.faces)
        tree._bnd = boundary_edges_of(tree.faces, mesh.edge_faces, mesh.face_edges)     # one compiled pass
        tree._topo = (mesh.face_edges, mesh.edge_faces)
        tree._ends = mesh.edges
        tree._vn = mesh.normals
        tree.grids()
        return tree

    def query(self, points: ArrayLike) -> tuple[Array, IntArray, Array]:
        """Distances ``(n,)``, closest faces ``(n,)`` and closest points ``(n, 3)`` (exact).

        The last query is kept: the same points again (a family's ribs, asked first whether a grown
        patch holds them, then for their normals) get copies of its answer. A tree of no faces
        gives inf, -1 and zeros.
        """
        p = np.ascontiguousarray(np.asarray(points, float).reshape(-1, 3))
        if len(p) == 0:
            return np.zeros(0), np.zeros(0, np.int64), np.zeros((0, 3))
        last = self.__dict__.get("_last")
        if last is not None and last[0].shape == p.shape and np.array_equal(last[0], p):
            return last[1].copy(), last[2].copy(), last[3].copy()
        (lo, dims, h, start, entries, fbox), coarse = self.grids()
        out = mesh_closest(self.vertices, self.faces, lo, dims, h, start, entries, fbox, *coarse, p,
                           float(FINE_REACH * h))
        self._last = (p.copy(), out[0].copy(), out[1].copy(), out[2].copy())
        return out

    def query_within(self, points: ArrayLike, bound: float) -> tuple[Array, IntArray, Array]:
        """:meth:`query` for the points within ``bound`` of the mesh; inf, -1 and zeros for the others.

        Where the distance is at most ``bound`` the answer is :meth:`query`'s distance (the same
        bits) and a face at it; the search visits only the cells within ``bound``, so points far
        from the mesh (a swept profile beyond a part, a mirror image off a mesh that has no such
        symmetry) cost little (:func:`~auszug.sweeps._kernels.mesh_closest_within`).

        Examples
        --------
        >>> t = MeshTree(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]]), np.array([[0, 1, 2]]))
        >>> d, f, c = t.query_within([[0.2, 0.2, 0.5], [0.2, 0.2, 2.0]], 1.0)
        >>> d.tolist(), f.tolist()
        ([0.5, inf], [0, -1])
        """
        p = np.ascontiguousarray(np.asarray(points, float).reshape(-1, 3))
        if len(p) == 0:
            return np.zeros(0), np.zeros(0, np.int64), np.zeros((0, 3))
        lo, dims, h, start, entries, fbox = self.face_grid()
        out: tuple[Array, IntArray, Array] = mesh_closest_within(self.vertices, self.faces, lo, dims, h, start,
                                                                 entries, fbox, p, float(bound))
        return out

    def face_grid(self) -> tuple[Array, IntArray, float, IntArray, IntArray, Array]:
        """The tree's faces binned in a uniform grid (compiled :func:`~auszug.sweeps._kernels.face_grid`), built once.

        For compiled exact closest-point searches that start near the answer (:meth:`query`, the
        motion's refinement, :func:`~auszug.sweeps.general.refine_motion`). The cell is
        :data:`FACE_GRID_CELL` mean edge lengths, larger where the grid would have more than
        :data:`FACE_GRID_CELLS` cells per face. Returns the origin, the cell counts, the cell
        size, each cell's first entry, the faces cell after cell and the faces' bounding boxes.
        """
        got = self.__dict__.get("_grid")
        if got is None:
            v, f = self.vertices, self.faces
            h = float(face_grid_cell(v, f, float(FACE_GRID_CELL), float(FACE_GRID_CELLS)))
            lo, dims, start, entries, fbox = face_grid(v, f, h)
            got = (lo, dims, h, start, entries, fbox)
            self._grid = got
        return got

    def grids(self) -> tuple[tuple[Array, IntArray, float, IntArray, IntArray, Array],
                             tuple[Array, IntArray, float, IntArray, IntArray, Array]]:
        """The fine grid (:meth:`face_grid`) and the coarse one (:data:`COARSE_GRID_CELL` times its cell), once."""
        fine = self.face_grid()
        got = self.__dict__.get("_coarse")
        if got is None:
            h = fine[2] * COARSE_GRID_CELL
            lo, dims, start, entries, fbox = face_grid(self.vertices, self.faces, h)
            got = (lo, dims, h, start, entries, fbox)
            self._coarse = got
        return fine, got

    def _boundary_edges(self) -> IntArray:
        """Per face its boundary edges as vertex pairs ``(m, 3, 2)`` (-1 where the edge is inner)."""
        if not hasattr(self, "_bnd"):
            f = self.faces
            e = np.stack([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]], axis=1)       # (m, 3, 2)
            single = self._edge_topology()[3][self._topology()[0]] == 1                # (m, 3)
            self._bnd = np.where(single[:, :, None], e, -1)
        out: IntArray = self._bnd
        return out

    def _edge_topology(self) -> tuple[IntArray, IntArray, IntArray, IntArray]:
        """:func:`~auszug.sweeps.mesh.edge_topology` of the tree's faces, once (the edge counts too)."""
        got: tuple[IntArray, IntArray, IntArray, IntArray] | None = self.__dict__.get("_etopo")
        if got is None:
            got = edge_topology(self.faces, len(self.vertices))
            self._etopo = got
        return got

    def _topology(self) -> tuple[IntArray, IntArray]:
        """Each face's edges ``(m, 3)`` (in face order ``(0, 1), (1, 2), (2, 0)``) and each edge's faces ``(k, 2)``.

        As :attr:`SweepMesh.face_edges` and :attr:`SweepMesh.edge_faces` (-1 where a boundary
        edge has one face; an edge of more than two faces keeps its first and last).
        """
        got: tuple[IntArray, IntArray] | None = self.__dict__.get("_topo")
        if got is None:
            _, ef, fe, _ = self._edge_topology()
            got = (fe, ef)
            self._topo = got
        return got

    def _boundary_vertices(self) -> NDArray[np.bool_]:
        """Whether each vertex ``(n,)`` is an end of a boundary edge (an edge with one face)."""
        got: NDArray[np.bool_] | None = self.__dict__.get("_bvert")
        if got is None:
            bnd = self._boundary_edges()
            got = np.zeros(len(self.vertices), bool)
            got[bnd[bnd >= 0]] = True
            self._bvert = got
        return got

    def _features(self, face: IntArray, c: Array) -> tuple[IntArray, IntArray]:
        """The vertex ``(n,)`` or else the edge ``(n,)`` (ids of :meth:`_topology`; -1 for none) closest points lie on.

        A closest point ``c (n, 3)`` on face ``face (n,)`` within ``FEATURE_GAP`` of a corner of the
        face lies on that vertex; else within it of a side, on that edge; else inside the face.
        The faces equally near a point whose closest point lies on an edge or a vertex (a tie, the
        face returned depending on the search) all give the same vertex or edge. One compiled
        pass (:func:`~auszug.sweeps._kernels.closest_features`).
        """
        out: tuple[IntArray, IntArray] = closest_features(
            self.vertices, self.faces, self._topology()[0], np.ascontiguousarray(face, dtype=np.int64),
            np.ascontiguousarray(np.asarray(c, float).reshape(-1, 3)), float(FEATURE_GAP))
        return out

    def _edge_ends(self) -> IntArray:
        """Each edge's end vertices ``(k, 2)`` (ids of :meth:`_topology`), the lower first (:attr:`SweepMesh.edges`)."""
        got: IntArray | None = self.__dict__.get("_ends")
        if got is None:
            got = self._edge_topology()[0]
            self._ends = got
        return got

    def _vertex_normals(self) -> Array:
        """Unit area-weighted vertex normals ``(n, 3)`` (:attr:`SweepMesh.normals` for a tree of a whole mesh)."""
        got: Array | None = self.__dict__.get("_vn")
        if got is None:
            got = vertex_normals(self.vertices, self.faces)
            self._vn = got
        return got

    def normals(self, points: ArrayLike) -> Array:
        """Unit normals ``(..., 3)`` of the mesh at the closest points of ``points (..., 3)``, independent of ties.

        Inside a face, its normal; on an edge (:meth:`_features`), the vertex normals of its two
        ends (area-weighted, :meth:`_vertex_normals`) interpolated linearly at the closest point and
        normalised, the lower-numbered end first (the normals :func:`~auszug.sweeps.cut.cut` gives
        its cut points, which lie on edges; the place along the edge is the point's projection on
        it, the same bits whichever face the search returned); at a vertex, its vertex normal. So on an edge or a
        vertex the same whichever face of it the search returns (a tie). (The normal of the
        lowest-numbered face, and the mean of an edge's faces' normals, were tried in
        sweeps-build9: the latter turned the re-sliced ribs' velocities on the tracery border into
        a spurious sweep.)

        Examples
        --------
        >>> t = MeshTree(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 1.0]]), np.array([[1, 3, 2], [0, 1, 2]]))
        >>> n = t.normals([[0.1, 0.1, 1.0], [0.5, 0.5, -0.5]])    # inside face 1; on the edge of faces 0 and 1
        >>> np.round(n, 4).tolist()
        [[0.0, 0.0, 1.0], [-0.4082, -0.4082, 0.8165]]
        """
        p = np.asarray(points, float)
        _, face, c = self.query(p)
        v = self.vertices
        # compiled: np.cross(v1 - v0, v2 - v0) over np.maximum(its norm, 1e-300), bit for bit
        n: Array = unit_face_normals(v, self.faces, np.ascontiguousarray(face, dtype=np.int64))
        vid, eid = self._features(face, c)
        vn = self._vertex_normals()
        on_e = np.flatnonzero(eid >= 0)
        if len(on_e):
            ab = self._edge_ends()[eid[on_e]]
            a, b = v[ab[:, 0]], v[ab[:, 1]]
            d = b - a
            w = np.einsum("ki,ki->k", d, d)
            # from the point, not its closest point: the same bits whichever tied face the search returned
            q = p.reshape(-1, 3)[on_e]
            t = np.clip(np.einsum("ki,ki->k", q - a, d) / np.where(w > 0, w, 1.0), 0.0, 1.0)
            m = vn[ab[:, 0]] + t[:, None] * (vn[ab[:, 1]] - vn[ab[:, 0]])
            s = np.linalg.norm(m, axis=1, keepdims=True)
            n[on_e] = np.where(s > 0, m / np.where(s > 0, s, 1.0), n[on_e])
        at_v = np.flatnonzero(vid >= 0)
        if len(at_v):
            m = vn[vid[at_v]]
            n[at_v] = np.where(np.linalg.norm(m, axis=1, keepdims=True) > 0, m, n[at_v])
        return n.reshape(p.shape)

    def on_faces(self, points: ArrayLike, mask: NDArray[np.bool_]) -> NDArray[np.bool_]:
        """Whether the closest point of each of ``points (n, 3)`` lies on a face of ``mask (m,)`` (its edges too).

        A closest point on an edge or a vertex (:meth:`_features`) lies on all the faces around
        it: the answer does not depend on which of them the search returns.
        """
        _, face, c = self.query(points)
        out = np.asarray(mask, bool)[face]
        vid, eid = self._features(face, c)
        if (eid >= 0).any():
            ef = self._topology()[1][eid[eid >= 0]]
            out[eid >= 0] = (mask[np.maximum(ef, 0)] & (ef >= 0)).any(axis=1)
        if (vid >= 0).any():
            around = np.bincount(self.faces.ravel(), np.repeat(np.asarray(mask, float), 3), len(self.vertices)) > 0
            out[vid >= 0] = around[vid[vid >= 0]]
        return out

    def interior_max(self, points: ArrayLike, surface: RingTree, tol: float,
                     angle: float = DEFAULT.reciprocal_angle) -> float:
        """``interior_distance(points, surface, tol, angle).max()`` (0 for no points), with fewer searches.

        One compiled pass (:func:`~auszug.sweeps._kernels.interior_max`): a point with a face
        within the largest distance counted so far is not searched further, as it cannot raise
        it; the points farther than ``tol`` get the reciprocal test as in
        :meth:`interior_distance`. The same number.
        """
        p = np.ascontiguousarray(np.asarray(points, float).reshape(-1, 3))
        if len(p) == 0:
            return 0.0
        (lo, dims, h, start, entries, fbox), coarse = self.grids()
        err, idx, d, c, face = interior_max(self.vertices, self.faces, self._boundary_edges(),
                                            self._boundary_vertices(), lo, dims, h, start, entries, fbox, *coarse, p,
                                            float(tol), float(FINE_REACH * h))
        if len(idx):
            ds, sf, back = surface.query(c, tol)      # only the distances within tol count
            other = (ds <= tol) & (np.linalg.norm(back - p[idx], axis=1) >= 0.5 * d)
            if angle < 180.0 and other.any():
                at = np.flatnonzero(other)
                ns = unit_face_normals(np.ascontiguousarray(surface.vertices), surface.faces,
                                       np.ascontiguousarray(sf[at]))
                other[at[~self._along(face[at], c[at], ns, angle)]] = False
            err = max(float(err), float(np.where(other, 0.0, d).max()))
        return float(err)

    def _along(self, face: IntArray, c: Array, normals: Array, angle: float) -> NDArray[np.bool_]:
        """Whether the unit ``normals (k, 3)`` lie within ``angle`` degrees (either orientation) of the mesh at ``c``.

        ``c (k, 3)`` are closest points found on the faces ``face (k,)``: the normal of the face it lies
        on; on an edge or at a vertex (:meth:`_features`, a tie) of any face around it, so the answer does not
        depend on which of them the search returned (:meth:`interior_distance`'s reciprocal test).
        """
        v, f = self.vertices, self.faces
        cos = np.cos(np.radians(angle))
        face = np.ascontiguousarray(face, dtype=np.int64)
        ok: NDArray[np.bool_] = np.abs(np.einsum("ki,ki->k", unit_face_normals(v, f, face), normals)) >= cos
        vid, eid = self._features(face, c)
        on_e = np.flatnonzero((eid >= 0) & ~ok)
        if len(on_e):
            ef = self._topology()[1][eid[on_e]]                                # (e, 2), -1 past a boundary edge
            for j in range(2):
                has = ef[:, j] >= 0
                nj = unit_face_normals(v, f, np.ascontiguousarray(np.maximum(ef[:, j], 0)))
                ok[on_e] |= has & (np.abs(np.einsum("ki,ki->k", nj, normals[on_e])) >= cos)
        at_v = np.flatnonzero((vid >= 0) & ~ok)
        if len(at_v):
            start, around = self._vertex_faces()
            lo, hi = start[vid[at_v]], start[vid[at_v] + 1]
            row = np.repeat(np.arange(len(at_v)), hi - lo)                  # each point's faces around its vertex
            pos = np.arange(len(row)) - np.repeat(np.cumsum(hi - lo) - (hi - lo), hi - lo) + np.repeat(lo, hi - lo)
            nf = unit_face_normals(v, f, np.ascontiguousarray(around[pos]))
            hit = np.abs(np.einsum("ki,ki->k", nf, normals[at_v][row])) >= cos
            ok[at_v] = np.bincount(row, hit, len(at_v)) > 0
        return ok

    def _vertex_faces(self) -> tuple[IntArray, IntArray]:
        """Each vertex's faces ``faces[start[i]:start[i + 1]]``: ``start (n + 1,)`` and ``faces (3 m,)``."""
        got: tuple[IntArray, IntArray] | None = self.__dict__.get("_vfaces")
        if got is None:
            flat = self.faces.ravel()
            order = np.argsort(flat, kind="stable")
            start = np.zeros(len(self.vertices) + 1, np.int64)
            np.cumsum(np.bincount(flat, minlength=len(self.vertices)), out=start[1:])
            got = (start, (order // 3).astype(np.int64))
            self._vfaces = got
        return got

    def interior_distance(self, points: ArrayLike,
                          surface: MeshTree | RingTree | tuple[Array, IntArray] | None = None,
                          tol: float = 0.0, angle: float = DEFAULT.reciprocal_angle) -> Array:
        """Distances ``(n,)`` to the mesh, 0 where a point lies beyond the mesh.

        A point whose closest point is on the mesh's boundary lies beyond the mesh (past its end or
        over a hole), where the mesh says nothing; the fit check does not count it against a sweep.

        With ``surface``, the swept surface ``(V (k, 3), F (m, 3))`` (or its tree, or its
        :class:`RingTree`) the points lie on, a point
        farther than ``tol`` from the mesh also counts as beyond it when its closest mesh point lies
        on *another part* of that surface: within ``tol`` of it, and there at least half the
        point's distance away from the point (the reciprocal closest-point test of registration
        with partial overlap). Over a hole in a mesh whose profile folds (a torus) the closest mesh
        point is often on the fold's other side, not on the hole's rim; where the sweep misses
        the mesh, the closest mesh point lies off the sweep and the distance counts.

        That other part must lie *along* the mesh there: the swept surface's normal at the point
        nearest the closest mesh point (its triangle's) within ``angle`` degrees of the mesh's normal
        at the closest point (the normal of the face found; either orientation;
        :attr:`~auszug.sweeps.params.SweepParams.reciprocal_angle`). A swept surface that folds
        over itself crosses the mesh where its other sheet meets it and discounts nothing there
        (180: no normal test).
        """
        p = np.asarray(points, float).reshape(-1, 3)
        d, face, c = self.query(p)
        out: Array = d
        bv = self._boundary_vertices()
        if bv[self.faces[face]].any():
            # on a boundary edge or at a boundary vertex (the mesh's topology: whichever face of the
            # vertex the search returned)
            vid, eid = self._features(face, c)
            _, ef = self._topology()
            on = np.zeros(len(p), bool)
            on[vid >= 0] = bv[vid[vid >= 0]]
            on[eid >= 0] = (ef[eid[eid >= 0]] < 0).any(axis=1)
            out = np.where(on, 0.0, d)
        if surface is not None and (not isinstance(surface, tuple) or len(surface[1])):
            far = np.flatnonzero(out > tol)
            if len(far):
                if isinstance(surface, tuple):
                    surface = MeshTree(surface[0], surface[1])
                if isinstance(surface, RingTree):
                    ds, sf, back = surface.query(c[far], tol)     # only the distances within tol count
                else:
                    ds, sf, back = surface.query(c[far])
                other = (ds <= tol) & (np.linalg.norm(back - p[far], axis=1) >= 0.5 * d[far])
                if angle < 180.0 and other.any():
                    at = np.flatnonzero(other)
                    sv = np.ascontiguousarray(surface.vertices)
                    ns = unit_face_normals(sv, surface.faces, np.ascontiguousarray(sf[at]))
                    other[at[~self._along(face[far[at]], c[far[at]], ns, angle)]] = False
                out = out.copy()
                out[far[other]] = 0.0
        return out


class RingTree:
    """Closest points on a swept surface stored as rings of a profile (:func:`ring_faces`), compiled.

    The quads between consecutive rings and their 2 x 2 blocks, level by level, carry bounding
    boxes (built in one pass, no tree to balance); a query descends them nearer box first and
    prunes boxes farther than the best distance so far: exact, like :class:`MeshTree` on
    ``(rings.reshape(-1, 3), ring_faces(k, n, closed))``, and a query within a ``bound`` prunes
    from the start.

    Parameters
    ----------
    rings : (k, n, 3) float array
        ``k >= 2`` rings of ``n >= 2`` points.
    closed : bool
        Closed rings (the last point joins the first).

    Examples
    --------
    >>> rings = np.array([[[0, 0, 0], [1, 0, 0]], [[0, 1, 0], [1, 1, 0.0]]])
    >>> d, f, c = RingTree(rings, False).query([[0.25, 0.5, 2.0], [4.0, 0.5, 0.0]], bound=2.5)
    >>> d.tolist(), f.tolist(), c[0].tolist()
    ([2.0, inf], [1, -1], [0.25, 0.5, 0.0])
    """

    def __init__(self, rings: ArrayLike, closed: bool = False) -> None:
        self.rings = np.ascontiguousarray(np.asarray(rings, float))
        if self.rings.ndim != 3 or self.rings.shape[0] < 2 or self.rings.shape[1] < 2 or self.rings.shape[2] != 3:
            raise ValueError(f"rings: expected a (k, n, 3) array with k, n >= 2, got shape {self.rings.shape}")
        self.closed = bool(closed)
        self._box, self._off, self._shape = ring_grid_boxes(self.rings, self.closed)

    @property
    def vertices(self) -> Array:
        """The rings' points ``(k n, 3)``, ring after ring."""
        return self.rings.reshape(-1, 3)

    @property
    def faces(self) -> IntArray:
        """The triangles ``(f, 3)`` (:func:`ring_faces`)."""
        return ring_faces(self.rings.shape[0], self.rings.shape[1], self.closed)

    def query(self, points: ArrayLike, bound: float = np.inf) -> tuple[Array, IntArray, Array]:
        """Distances ``(q,)``, closest faces ``(q,)`` and points ``(q, 3)``; inf, -1 and 0 beyond ``bound``."""
        p = np.ascontiguousarray(np.asarray(points, float).reshape(-1, 3))
        if len(p) == 0:
            return np.zeros(0), np.zeros(0, np.int64), np.zeros((0, 3))
        d, f, c = ring_grid_nearest(self.rings, self.closed, self._box, self._off, self._shape, p, float(bound))
        return d, f, c

    def within(self, points: ArrayLike, bound: float) -> NDArray[np.bool_]:
        """Whether each point ``(q, 3)`` is within ``bound`` of the surface: ``query(points, bound)[0] <= bound``.

        The search for a point stops at the first triangle within ``bound``.
        """
        p = np.ascontiguousarray(np.asarray(points, float).reshape(-1, 3))
        if len(p) == 0:
            return np.zeros(0, bool)
        out: NDArray[np.bool_] = ring_grid_within(self.rings, self.closed, self._box, self._off, self._shape, p,
                                                  float(bound))
        return out


def polyline_hausdorff(a: ArrayLike, b: ArrayLike, closed_a: bool = False, closed_b: bool = False) -> float:
    """Two-sided Hausdorff distance of two polylines ``(n, 3)``, ``(m, 3)`` (vertices to segments).

    Exact up to the vertices: the largest distance from a polyline to another is attained at one
    of its vertices or where the closest segment changes; the vertices are refined 8 times to
    catch the latter.

    Examples
    --------
    >>> polyline_hausdorff([[0, 0, 0], [1, 0, 0]], [[0, 0.1, 0], [1, 0.1, 0], [1.5, 0.1, 0]])
    0.5099019513592785
    """
    pa = np.asarray(a, float)
    pb = np.asarray(b, float)

    def dense(p: Array, closed: bool) -> tuple[Array, IntArray]:
        q = np.vstack([p, p[:1]]) if closed else p
        f = np.linspace(0.0, 1.0, 8, endpoint=False)
        pts = (q[:-1, None, :] + f[None, :, None] * np.diff(q, axis=0)[:, None, :]).reshape(-1, 3)
        pts = np.vstack([pts, q[-1:]])
        n = len(q)
        seg = np.stack([np.arange(n - 1), np.arange(1, n)], axis=1)
        return pts, seg

    da, sa = dense(pa, closed_a)
    db, sb = dense(pb, closed_b)
    qa = np.vstack([pa, pa[:1]]) if closed_a else pa
    qb = np.vstack([pb, pb[:1]]) if closed_b else pb
    d1, _ = closest_distance(da, qb, sb)
    d2, _ = closest_distance(db, qa, sa)
    return float(max(d1.max(), d2.max()))


# -- the parameter of a point under a kinematic motion ------------------------------------------


#: A kinematic patch's profile cut is "whole" when at least this share of the longest of its
#: candidate cuts: noise of sigma 1e-3 spreads the cut lengths of the revolved moulding by 1.9 %,
#: the fixtures' hole (radius 0.06) shortens the cut through it by 20 %.
WHOLE_CUT = 0.95


def _axis_frame(direction: Array) -> tuple[Array, Array]:
    """Two unit vectors completing ``direction`` to a right-handed frame."""
    d = direction / np.linalg.norm(direction)
    a = np.array([1.0, 0, 0]) if abs(d[0]) < 0.9 else np.array([0, 1.0, 0])
    e1 = np.cross(d, a)
    e1 /= np.linalg.norm(e1)
    return e1, np.cross(d, e1)


@dataclass(frozen=True)
class _Kinematic:
    """A kinematic motion with the angular origin of its parameter."""

    kind: str
    direction: Array
    point: Array | None
    pitch: float
    e1: Array
    e2: Array
    phi0: float      # angle of the range's start (rotation, screw)
    shift: float     # parameter offset: the range starts at 0

    def raw_angle(self, x: Array) -> Array:
        assert self.point is not None
        y = x - self.point
        return np.arctan2(y @ self.e2, y @ self.e1)

    def param(self, x: Array) -> Array:
        """Parameter of points ``(n, 3)`` (0 at the range's start)."""
        if self.kind == "translation":
            return x @ self.direction - self.shift
        assert self.point is not None
        phi = np.mod(self.raw_angle(x) - self.phi0, 2 * np.pi)
        if self.kind == "rotation":
            return phi
        # screw: phi + 2 pi k with k chosen so that the height matches the pitch's advance
        h = (x - self.point) @ self.direction
        k = np.round((h / self.pitch - self.shift - phi) / (2 * np.pi))
        return phi + 2 * np.pi * k

    def motion(self, t: Array) -> tuple[Array, Array]:
        """Maps at parameters ``t`` taking the profile at 0 to ``t``."""
        return screw_motion(self.direction, self.point, self.pitch if self.kind == "screw" else 0.0, t)

    def plane(self, t: float) -> tuple[Array, float]:
        """The profile plane at parameter ``t``: normal and offset."""
        if self.kind == "translation":
            return self.direction, float(t + self.shift)
        assert self.point is not None
        ang = self.phi0 + t
        radial = np.cos(ang) * self.e1 + np.sin(ang) * self.e2
        n = np.cross(self.direction, radial)
        return n, float(n @ self.point)


def _kinematic(mesh: SweepMesh, axis: KinematicAxis, used: Array) -> tuple[_Kinematic, float]:
    """The kinematic motion of ``axis`` with the parameter range of the ``used`` vertices."""
    d = axis.direction / np.linalg.norm(axis.direction)
    e1, e2 = _axis_frame(d)
    x = mesh.vertices[used]
    if axis.kind == "translation":
        s = x @ d
        return _Kinematic("translation", d, None, 0.0, e1, e2, 0.0, float(s.min())), float(np.ptp(s))
    assert axis.point is not None
    k0 = _Kinematic(axis.kind, d, axis.point, axis.pitch, e1, e2, 0.0, 0.0)
    phi = np.sort(np.mod(k0.raw_angle(x), 2 * np.pi))
    gaps = np.diff(np.concatenate([phi, phi[:1] + 2 * np.pi]))
    g = int(np.argmax(gaps))
    start = float(phi[(g + 1) % len(phi)])
    if axis.kind == "rotation":
        typical = float(np.median(gaps[gaps > 0])) if np.any(gaps > 0) else 0.0
        # no real gap (the largest is within a few rings' spacing): a full turn
        full = gaps[g] <= max(20 * typical, np.radians(5.0))
        span = 2 * np.pi if full else float(2 * np.pi - gaps[g])
        return _Kinematic("rotation", d, axis.point, 0.0, e1, e2, start, 0.0), span
    # screw: unwind by the pitch; the parameter's origin at the lowest unwound vertex
    k1 = replace(k0, phi0=start)
    h = (x - axis.point) @ d
    shift = float(np.median(h / axis.pitch - np.mod(k1.raw_angle(x) - start, 2 * np.pi)))
    k2 = replace(k1, shift=shift)
    t = k2.param(x)
    lo = float(t.min())
    return replace(k2, phi0=start + lo, shift=shift + lo), float(np.ptp(t))


def _pieces(points: Array, keep: NDArray[np.bool_], closed: bool) -> list[tuple[Array, bool]]:
    """Maximal runs of consecutive kept points of a polyline (wrapping for closed ones)."""
    if keep.all():
        return [(points, closed)]
    idx = np.flatnonzero(keep)
    if len(idx) == 0:
        return []
    breaks = np.flatnonzero(np.diff(idx) > 1)
    runs = np.split(idx, breaks + 1)
    if closed and keep[0] and keep[-1] and len(runs) > 1:
        runs[0] = np.concatenate([runs[-1], runs[0]])
        runs.pop()
    return [(points[r], False) for r in runs if len(r) >= 2]


def _length(p: Array, closed: bool) -> float:
    q = np.vstack([p, p[:1]]) if closed else p
    return float(np.linalg.norm(np.diff(q, axis=0), axis=1).sum())


def _improve(profile: Array, closed: bool, others: list[Array], end_reach: float = np.inf) -> Array:
    """Each profile point moved to the mean of itself and its closest points on the other curves.

    A closest point at an end of another curve counts only within ``end_reach`` (a curve that ends
    on the mesh's boundary, at a hole, says nothing about the profile points beyond it).
    """
    if not others:
        return profile
    starts = np.concatenate([[0], np.cumsum([len(q) for q in others])]).astype(np.int64)
    return improve_flat(profile, np.concatenate(others, axis=0).reshape(-1, 3), starts, end_reach)


def improve_flat(profile: Array, pts: Array, piece_start: IntArray, end_reach: float = np.inf) -> Array:
    """:func:`_improve` with the other curves as pieces of one array ``pts (m, 3)`` (``piece_start (q + 1,)``).

    One compiled pass over all pieces (no Python loop per curve).
    """
    return improve_bounded(profile, pts, piece_start, np.zeros(max(len(piece_start) - 1, 0), np.int64), 1,
                           end_reach)[0]


def improve_bounded(profile: Array, pts: Array, piece_start: IntArray, piece_key: IntArray, n_keys: int,
                    end_reach: float = np.inf) -> tuple[Array, Array]:
    """:func:`improve_flat`, and upper bounds ``(n_keys, n)`` of the improved points' distances to each key's pieces.

    ``piece_key (q,)`` in ``0..n_keys - 1`` groups the pieces (the recut's knots). The bound of a
    point is its distance before the improvement plus how far the improvement moved it (inf where
    no piece of the key was searched, farther than 0.02).
    """
    if len(piece_start) < 2:
        return profile, np.full((n_keys, len(profile)), np.inf)
    acc, count, dmin = improve_sums(np.ascontiguousarray(profile, dtype=float), np.ascontiguousarray(pts, dtype=float),
                                    np.asarray(piece_start, np.int64), 0.02, float(end_reach),
                                    np.asarray(piece_key, np.int64), int(n_keys))
    out: Array = acc / count[:, None]
    bound: Array = dmin + np.linalg.norm(out - profile, axis=1)[None, :]
    return out, bound


#: :func:`fill_corners` inserts a point only where this share of the pieces' farthest points lie on one side.
CORNER_AGREEMENT = 0.75


def consistent_pieces(profile: Array, closed: bool, pts: Array, piece_start: IntArray, piece_key: IntArray,
                      trim: float) -> tuple[Array, IntArray, IntArray]:
    """The pieces of the keys (knots) that lie near the profile: those of far keys dropped (beyond the paper).

    Per key, the median distance of its pieces' points to the profile polyline; the keys whose
    median exceeds ``trim`` times the median over the keys are dropped (their pieces' points,
    starts and keys). A grown sweep's end knots lie where the mesh ends or on another part of it,
    and their pieces pulled the mean of :func:`improve_bounded` off the profile (a member's square
    bar: its corners cut by up to 1.5e-3). ``trim`` 0 keeps every piece.

    Examples
    --------
    >>> sq = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
    >>> pts = np.vstack([sq + 0.01, sq - 0.01, sq + [0, 0, 0.5]])
    >>> p, s, k = consistent_pieces(sq, True, pts, np.array([0, 4, 8, 12]), np.array([0, 1, 2]), 2.0)
    >>> s.tolist(), k.tolist()
    ([0, 4, 8], [0, 1])
    """
    n_pieces = len(piece_start) - 1
    if trim <= 0 or n_pieces < 1 or len(profile) < 2:
        return pts, piece_start, piece_key
    from auszug.sweeps._kernels import key_distance_medians

    ring = np.vstack([profile, profile[:1]]) if closed else profile
    key = np.asarray(piece_key, np.int64)
    # per key the median of its points' distances to the profile polyline (one compiled pass)
    med, count = key_distance_medians(np.ascontiguousarray(pts, dtype=float), np.ascontiguousarray(ring, dtype=float),
                                      np.asarray(piece_start, np.int64), key, int(key.max()) + 1)
    keys = np.flatnonzero(count > 0)
    med = med[keys]
    far = keys[med > trim * np.median(med)]
    if not len(far):
        return pts, piece_start, piece_key
    keep = ~np.isin(piece_key, far)
    sizes = np.diff(piece_start)[keep]
    return (pts[np.repeat(keep, np.diff(piece_start))], np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64),
            np.asarray(piece_key)[keep])


def fill_corners(profile: Array, closed: bool, pts: Array, piece_start: IntArray, tol: float,
                 reach: float, min_pieces: int = 3) -> tuple[Array, IntArray]:
    """The profile with a point inserted on each segment that cuts off a corner of the pieces (beyond the paper).

    Every piece point (mapped back near the profile) belongs to the profile segment nearest it
    (within ``reach``, its foot inside the segment); per segment and piece, its point farthest
    from the segment; per segment with such points from at least ``min_pieces`` pieces, of which
    :data:`CORNER_AGREEMENT` lie on one side of it (a corner; noise scatters them to both), their
    median (per coordinate) is inserted when it lies farther than ``tol`` from the segment. The
    mean of closest points (:func:`improve_bounded`) moves a point only across the pieces, never
    along them, so a corner between two profile points stays cut by their chord (a member's
    square bar: 1.7e-3 where its points lay within 4e-4 of the truth); the cuts' own corners
    are points of the pieces. Returns the new profile and the indices of the inserted points in it.

    Examples
    --------
    >>> prof = np.array([[0.0, 0, 0], [1, 0, 0], [2, 1, 0]])      # the corner at (2, 0) cut
    >>> piece = np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0], [2, 1, 0]])
    >>> out, new = fill_corners(prof, False, np.vstack([piece] * 3), np.array([0, 4, 8, 12]), 0.01, 1.0)
    >>> out.tolist(), new.tolist()
    ([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0]], [2])
    """
    n = len(profile)
    if n < 2 or len(piece_start) < 2 or tol <= 0:
        return profile, np.zeros(0, np.int64)
    a = profile if closed else profile[:-1]
    ab = (np.roll(profile, -1, axis=0) if closed else profile[1:]) - a
    l2 = np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300)
    normal = np.linalg.svd(profile - profile.mean(axis=0))[2][2]        # the profile's plane
    m = len(pts)
    seg = np.zeros(m, np.int64)
    dist = np.full(m, np.inf)
    u = np.zeros(m)
    for c0 in range(0, m, 2048):          # chunks of points: (chunk, segments) arrays
        x = pts[c0:c0 + 2048]
        uu = np.einsum("mij,ij->mi", x[:, None, :] - a[None], ab) / l2
        dd = np.linalg.norm(x[:, None, :] - a[None] - np.clip(uu, 0, 1)[..., None] * ab[None], axis=2)
        j = dd.argmin(axis=1)
        r = np.arange(len(x))
        seg[c0:c0 + 2048], dist[c0:c0 + 2048], u[c0:c0 + 2048] = j, dd[r, j], uu[r, j]
    piece = np.repeat(np.arange(len(piece_start) - 1), np.diff(piece_start))
    sel = np.flatnonzero((u > 0) & (u < 1) & (dist <= reach))
    if not len(sel):
        return profile, np.zeros(0, np.int64)
    # per (segment, piece) the farthest point
    sel = sel[np.lexsort((-dist[sel], piece[sel], seg[sel]))]
    first = np.r_[True, (seg[sel][1:] != seg[sel][:-1]) | (piece[sel][1:] != piece[sel][:-1])]
    far = sel[first]
    s_far = seg[far]
    bounds = np.flatnonzero(np.r_[True, s_far[1:] != s_far[:-1], True])
    inserts: dict[int, Array] = {}
    for g0, g1 in zip(bounds[:-1], bounds[1:], strict=True):
        if g1 - g0 < min_pieces:
            continue
        s = int(s_far[g0])
        # the pieces' farthest points on one side of the segment (a corner), not on both (noise)
        side = np.sign((pts[far[g0:g1]] - a[s]) @ np.cross(normal, ab[s]))
        if abs(float(side.mean())) < 2 * CORNER_AGREEMENT - 1:
            continue
        x = np.median(pts[far[g0:g1]], axis=0)
        w = x - a[s]
        if np.linalg.norm(w - np.clip(w @ ab[s] / l2[s], 0.0, 1.0) * ab[s]) > tol:
            inserts[s] = x
    if not inserts:
        return profile, np.zeros(0, np.int64)
    at = np.array(sorted(inserts)) + 1
    out: Array = np.insert(profile, at, np.array([inserts[s] for s in sorted(inserts)]), axis=0)
    return out, at + np.arange(len(at))


def sweep_surface(profile: Array, closed: bool, motion: Motion, tol: float,
                  max_rings: int = 4096) -> tuple[Array, IntArray]:
    """The swept surface as a triangle mesh ``(V, F)``.

    Rings of the profile at parameters refined until every profile point's path deviates from its
    chords by at most ``tol``.
    """
    t, rings = _sweep_rings(profile, motion, tol, max_rings)
    return rings.reshape(-1, 3), ring_faces(len(t), len(profile), closed)


def _sweep_rings(profile: Array, motion: Motion, tol: float, max_rings: int = 4096) -> tuple[Array, Array]:
    """The parameters ``(k,)`` and rings ``(k, n, 3)`` of :func:`sweep_surface` (the motion's knots among them)."""
    t = np.array(motion.t, float)
    # each ring is the motion at its own parameter (row by row, bit for bit as in one call for all
    # parameters): the rings found are kept, only the new parameters' are computed
    a = motion.apply(profile, t)
    while len(t) < max_rings:
        mid = (t[:-1] + t[1:]) / 2
        m = motion.apply(profile, mid)
        dev = np.linalg.norm(m - (a[:-1] + a[1:]) / 2, axis=2).max(axis=1)
        bad = dev > tol
        if not bad.any():
            break
        order = np.argsort(np.concatenate([t, mid[bad]]), kind="stable")
        t = np.concatenate([t, mid[bad]])[order]
        a = np.concatenate([a, m[bad]])[order]
    return t, a


def ring_faces(k: int, n: int, closed: bool = False) -> IntArray:
    """Triangles ``(2 (k - 1) m, 3)`` between ``k`` rings of ``n`` points stored ring after ring.

    ``m`` is ``n`` for closed rings, else ``n - 1``.

    Examples
    --------
    >>> ring_faces(2, 3).tolist()
    [[0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4]]
    """
    j = np.arange(n if closed else n - 1)
    j1 = (j + 1) % n
    i = np.arange(k - 1)[:, None]
    a_, b_, c_, d_ = i * n + j, i * n + j1, (i + 1) * n + j1, (i + 1) * n + j
    f = np.stack([np.stack([a_, b_, c_], -1), np.stack([a_, c_, d_], -1)], axis=2).reshape(-1, 3)
    return f.astype(np.int64)


def fit_patch(mesh: SweepMesh, profile: Array, closed: bool, motion: Motion,
              params: SweepParams = DEFAULT, areas: Array | None = None, tree: MeshTree | None = None) -> Fit:
    """The fit check (sec. 2.3.4) of a profile and motion against the mesh (normalised coordinates).

    ``tree`` is the mesh's :class:`MeshTree` (built here if not given). The same as
    :func:`swept_error` followed by :func:`swept_coverage`.
    """
    err = swept_error(profile, closed, motion, params.eps_prox,
                      tree if tree is not None else MeshTree(mesh.vertices, mesh.faces), angle=params.reciprocal_angle)
    return swept_coverage(mesh, err, params.eps_prox, areas)


@dataclass(frozen=True)
class SweptError:
    """The swept surface of a profile and motion and its fit error (the first half of the fit check).

    Attributes
    ----------
    vertices : (k, 3) float array
        The swept surface's vertices (rings of the profile, :func:`sweep_surface`).
    tree : RingTree
        Closest points on the swept surface.
    fit_error : float
        Largest distance of the vertices to the mesh (:meth:`MeshTree.interior_distance`).
    """

    vertices: Array
    tree: RingTree
    fit_error: float


#: :func:`swept_error` with upper bounds queries first the swept points of the largest bounds, this many.
FIRST_QUERIED = 64


def swept_error(profile: Array, closed: bool, motion: Motion, eps: float, tree: MeshTree,
                upper: Array | None = None, angle: float = DEFAULT.reciprocal_angle) -> SweptError:
    """The swept surface (chords within ``eps / 10``) and its largest distance to the mesh of ``tree``.

    Swept points beyond the mesh do not count (:meth:`MeshTree.interior_distance` with the
    swept surface's own tree for the reciprocal test and ``angle``, its
    :attr:`~auszug.sweeps.params.SweepParams.reciprocal_angle`).

    ``upper (len(motion), n)``, optional, bounds each profile point's distance to the mesh at each
    of the motion's knots from above (inf where unknown). Only the largest distance is kept, so
    the swept points whose bound is at most the largest distance found are not queried: first
    the :data:`FIRST_QUERIED` points of the largest bounds (and every point of no bound), then
    those whose bound exceeds the largest of them. The same fit error, fewer closest points.
    """
    t, rings = _sweep_rings(profile, motion, eps / 10)
    sv = rings.reshape(-1, 3)
    swept = RingTree(rings, closed)     # one tree of the swept surface for both directions
    if len(sv) == 0:
        return SweptError(sv, swept, float("inf"))
    if upper is None:
        return SweptError(sv, swept, tree.interior_max(sv, swept, eps, angle))
    ub = np.full(rings.shape[:2], np.inf)
    k = np.searchsorted(motion.t, t)
    at = (k < len(motion.t)) & (motion.t[np.minimum(k, len(motion.t) - 1)] == t)
    # a margin for the round-off of the bound (the pieces mapped back by the knots' maps)
    ub[at] = np.asarray(upper, float)[k[at]] * (1 + 1e-9) + 1e-12
    ub = ub.reshape(-1)
    unknown = ub == np.inf
    n_unknown = int(np.sum(unknown))
    if n_unknown >= FIRST_QUERIED and not np.isnan(ub).any():
        # the order below without sorting every point: the points of no bound first, in index order (a stable
        # sort of -ub puts them first), then the others of a bound above the error found, by decreasing bound
        # (ties in index order); filtering before the stable sort keeps the same order
        first = np.flatnonzero(unknown)
        err = tree.interior_max(sv[first], swept, eps, angle)
        rest = np.flatnonzero(~unknown & (ub > err))
        rest = rest[np.argsort(-ub[rest], kind="stable")]
    else:
        order = np.argsort(-ub, kind="stable")
        first = order[:max(FIRST_QUERIED, int(np.sum(~np.isfinite(ub))))]
        err = tree.interior_max(sv[first], swept, eps, angle)
        rest = order[len(first):]
        rest = rest[ub[rest] > err]
    if len(rest):
        err = max(err, tree.interior_max(sv[rest], swept, eps, angle))
    return SweptError(sv, swept, err)


def swept_coverage(mesh: SweepMesh, err: SweptError, eps: float, areas: Array | None = None,
                   distances: bool = True) -> Fit:
    """The mesh faces within ``eps`` of a swept surface and their share of the area (the second half).

    Only the vertices in the swept surface's box grown by ``eps`` are queried (the others are
    farther than ``eps``), each within ``eps`` (:meth:`RingTree.query` with that bound). With
    ``distances`` False only whether each vertex is within ``eps`` is found (:meth:`RingTree.within`,
    the same faces): the fit's ``vertex_distance`` is then 0 there instead of the distance.
    """
    sv = err.vertices
    lo, hi = sv.min(axis=0) - eps, sv.max(axis=0) + eps
    # only the vertices of the mesh's faces (it may be a part) in the box: one compiled pass
    inside = face_vertices_in_box(mesh.vertices, mesh.faces, lo, hi)
    dv = np.full(mesh.n_vertices, np.inf)
    if distances:
        dv[inside] = err.tree.query(mesh.vertices[inside], eps)[0]
    else:
        dv[inside] = np.where(err.tree.within(mesh.vertices[inside], eps), 0.0, np.inf)
    faces = faces_within(dv, mesh.faces, float(eps))
    a = face_areas(mesh.vertices, mesh.faces) if areas is None else areas
    total = float(a.sum())
    cov = float(a[faces].sum() / total) if total > 0 else 0.0
    return Fit(dv, faces, err.fit_error, cov)


#: The additive recurrence (R2 sequence) that spreads the samples inside a face: its two
#: increments are ``1 / g, 1 / g^2`` for the plastic number ``g`` (the root of ``x^3 = x + 1``).
_R2 = (0.7548776662466927, 0.5698402909980532)


def area_samples(vertices: ArrayLike, faces: ArrayLike, n: int,
                 areas: Array | None = None) -> tuple[IntArray, Array]:
    """``n`` points spread evenly over a mesh's area: their faces ``(n,)`` and positions ``(n, 3)``.

    Systematic sampling: the ``i``-th point falls at area ``(i + 1/2) A / n`` along the faces in
    order (so a face of area ``a`` gets ``floor`` or ``ceil`` of ``n a / A`` points), and inside its
    face at the ``i``-th point of the R2 sequence folded into the triangle. Deterministic.

    Examples
    --------
    >>> f, x = area_samples([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], [[0, 1, 2], [1, 3, 2]], 4)
    >>> f.tolist(), bool(np.all((x >= 0) & (x <= 1)))
    ([0, 0, 1, 1], True)
    """
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    a = face_areas(v, f) if areas is None else np.asarray(areas, float)
    total = float(a.sum())
    if n <= 0 or len(f) == 0 or not total > 0:
        return np.zeros(0, np.int64), np.zeros((0, 3))
    i = np.arange(n, dtype=float)
    fid = np.searchsorted(np.cumsum(a), (i + 0.5) * (total / n), side="right")
    fid = np.minimum(fid, len(f) - 1).astype(np.int64)
    u = np.mod(0.5 + i * _R2[0], 1.0)
    w = np.mod(0.5 + i * _R2[1], 1.0)
    fold = u + w > 1
    u[fold], w[fold] = 1 - u[fold], 1 - w[fold]
    tri = v[f[fid]]
    x = tri[:, 0] + u[:, None] * (tri[:, 1] - tri[:, 0]) + w[:, None] * (tri[:, 2] - tri[:, 0])
    return fid, x


def area_coverage(mesh: SweepMesh, patches: Sequence[SweepPatch], eps: float, samples: int,
                  areas: Array | None = None) -> Array:
    """Per face the share of its area that the patches cover ``(m,)`` in [0, 1].

    A face one patch covers whole (in its ``faces``: its three corners within ``eps`` of the
    patch's swept surface) counts 1. The other faces are sampled (:func:`area_samples`, ``samples``
    points over the whole mesh, so a face gets about ``samples`` times its share of the area; a
    face too small for one counts 0): a sample is covered when it lies within ``eps`` of the
    swept surface (rings as in the fit check, chords within ``eps / 10``) of a patch that holds at
    least one of the face's corners within ``eps``. So a long face whose corners lie on different
    patches, or on one patch and beyond it, counts by the part of it that lies on them. The mesh's
    covered area is ``(share * areas).sum()``; it is at least the per-face figure.

    Parameters
    ----------
    mesh : SweepMesh
    patches : sequence of SweepPatch
        In the mesh's (normalised) coordinates.
    eps : float
    samples : int
        At most this many samples (0: the per-face figure alone).
    areas : (m,) float array, optional

    Returns
    -------
    (m,) float array
    """
    m = len(mesh.faces)
    share = np.zeros(m)
    for p in patches:
        share[p.faces] = 1.0
    if not patches or samples <= 0:
        return share
    fid, x = area_samples(mesh.vertices, mesh.faces, samples, areas)
    open_ = share[fid] < 1
    fid, x = fid[open_], x[open_]
    if len(fid) == 0:
        return share
    hit = np.zeros(len(fid), bool)
    for p in patches:
        ask = ~hit
        hit[ask] = sample_hits(mesh, p, eps, fid[ask], x[ask])
    count = np.bincount(fid, minlength=m)
    got = np.bincount(fid, weights=hit.astype(float), minlength=m)
    sampled = count > 0
    share[sampled] = got[sampled] / count[sampled]
    return share


def sample_hits(mesh: SweepMesh, patch: SweepPatch, eps: float, fid: IntArray, x: Array) -> NDArray[np.bool_]:
    """Which of the points ``x (n, 3)`` on the faces ``fid (n,)`` a patch covers (:func:`area_coverage`'s test).

    A point is covered when it lies within ``eps`` of the patch's swept surface (rings as in the
    fit check, chords within ``eps / 10``) and the patch holds at least one corner of its face
    within ``eps``. The faces of ``patch.faces`` are not special here (their points lie on it).
    """
    hit = np.zeros(len(fid), bool)
    if len(patch.profile) < 2 or len(fid) == 0:
        return hit
    rings = _sweep_rings(patch.profile, patch.motion, eps / 10)[1]
    tree = RingTree(rings, patch.closed)
    sv = rings.reshape(-1, 3)
    lo, hi = sv.min(axis=0) - eps, sv.max(axis=0) + eps
    inside = face_vertices_in_box(mesh.vertices, mesh.faces, lo, hi)
    near = np.zeros(mesh.n_vertices, bool)
    near[inside] = tree.within(mesh.vertices[inside], eps)
    held: NDArray[np.bool_] = np.asarray(near[mesh.faces].any(axis=1))
    ask = held[fid] & np.all((x >= lo) & (x <= hi), axis=1)
    if ask.any():
        hit[ask] = tree.within(x[ask], eps)
    return hit


def kinematic_patches(mesh: SweepMesh, axis: KinematicAxis, params: SweepParams = DEFAULT,
                      first_id: int = 0) -> list[SweepPatch]:
    """The patches of a kinematic surface (normalised coordinates), fitted but not yet filtered.

    One patch per piece of the profile cut at least ``l_min`` long; each piece's profile is
    improved by ``profile_cuts`` further cuts and fitted by :func:`fit_patch`. The profile cut is the
    middle one (in the motion's parameter), or, where a hole or a torn part shortens that cut by more
    than 1 %, the cut nearest the middle within 1 % of the longest of them.

    Examples
    --------
    >>> from auszug.sweeps import cut, initial_planes, kinematic_axis, movability, normalise
    >>> from auszug.sweeps.fixtures import extruded
    >>> fx = extruded(n_profile=40, n_path=40)
    >>> m = normalise(fx.vertices, fx.faces)
    >>> c = cut(m, *initial_planes(m.vertices, 3, 0.1))
    >>> p = kinematic_patches(m, kinematic_axis(c, movability(c)))
    >>> len(p), p[0].kind, p[0].coverage > 0.99, p[0].fit_error < 1e-6
    (1, 'translation', True, True)
    """
    used = np.zeros(mesh.n_vertices, bool)
    used[mesh.faces.ravel()] = True
    kin, span = _kinematic(mesh, axis, used)
    if not span > 0:
        raise GeometryError("the kinematic motion has an empty parameter range over the mesh")
    t_mid = span / 2
    m = max(8, params.motion_samples)
    t_knots = np.linspace(0.0, span, m)
    rot, tr = kin.motion(t_knots)
    motion = Motion(t_knots, rot, tr)
    areas = face_areas(mesh.vertices, mesh.faces)
    tree = MeshTree.of(mesh)
    # the middle cut and the further cuts for the profile improvement, inside the range, nearest the
    # middle first; each cut's pieces (within a quarter turn of its parameter for rotations)
    t_more = np.linspace(0.0, span, params.profile_cuts + 2)[1:-1]
    t_more = t_more[np.abs(t_more - t_mid) > 1e-9 * max(span, 1.0)]
    t_all = [t_mid, *sorted((float(t) for t in t_more), key=lambda t: abs(t - t_mid))]
    cuts: list[list[tuple[Array, bool]]] = []
    for tk in t_all:
        nk, ok = kin.plane(tk)
        ck = cut(mesh, nk[None], np.array([ok]))
        pieces: list[tuple[Array, bool]] = []
        for j in range(ck.n_curves):
            q = ck.curve(j)
            keep = np.abs(kin.param(q) - tk) < np.pi / 2 if kin.kind != "translation" else np.ones(len(q), bool)
            pieces += _pieces(q, keep, bool(ck.curve_closed[j]))
        cuts.append(pieces)
    # the profile comes from the middle cut unless a hole or a torn part makes it shorter: then from the
    # cut nearest the middle that is whole (within WHOLE_CUT of the longest)
    total = [sum(_length(p, c) for p, c in pieces) for pieces in cuts]
    best = next(i for i, v in enumerate(total) if v >= WHOLE_CUT * max(total))
    t_prof = t_all[best]

    def mapped(piece: Array, tk: float) -> Array:
        tq = np.full(len(piece), tk) if kin.kind == "translation" else np.clip(kin.param(piece), 0.0, span)
        return motion.inverse_apply(piece, tq)

    # the improvement uses the other whole cuts only: a cut's ends at a hole's rim would pull the
    # profile points across the hole toward them
    whole = [i for i, v in enumerate(total) if i != best and v >= WHOLE_CUT * max(total)]
    more = [mapped(piece, t_all[i]) for i in whole for piece, _ in cuts[i]]
    out: list[SweepPatch] = []
    for piece, closed in cuts[best]:
        if _length(piece, closed) < params.l_min:
            continue
        prof = _improve(mapped(piece, t_prof), closed, more)
        fit = fit_patch(mesh, prof, closed, motion, params, areas, tree)
        kind: Kind = kin.kind  # type: ignore[assignment]
        out.append(SweepPatch(first_id + len(out), kind, prof, closed, motion, fit.faces, fit.fit_error,
                              fit.coverage))
    return out


def add_by_area(mesh: SweepMesh, kept: Sequence[SweepPatch], candidates: Sequence[SweepPatch], eps: float,
                samples: int, least: float, areas: Array | None = None) -> list[SweepPatch]:
    """The candidates that each add at least ``least`` of the mesh's area to what ``kept`` covers, greedily.

    The area is :func:`area_coverage`'s (the same samples): per face, the share of its samples
    that lie within ``eps`` of a patch's swept surface and on a face of which the patch holds a
    corner (faces a patch holds whole count whole). Repeatedly the candidate that adds the most is
    taken while it adds at least ``least``. For patches whose faces are mostly partly covered (a
    plane's long faces reaching beyond the swept block), whose whole faces say little of what they
    cover.

    Parameters
    ----------
    mesh : SweepMesh
    kept : sequence of SweepPatch
        The patches kept so far.
    candidates : sequence of SweepPatch
        Fitted candidates (filtered by fit error and sweep length before).
    eps : float
    samples : int
        As :func:`area_coverage` (0: nothing is added).
    least : float
        Least share of the mesh's area a candidate must add.
    areas : (m,) float array, optional

    Returns
    -------
    list of SweepPatch
        The candidates taken, in the order taken.
    """
    a = face_areas(mesh.vertices, mesh.faces) if areas is None else np.asarray(areas, float)
    total = float(a.sum())
    if not candidates or samples <= 0 or not total > 0:
        return []
    fid, x = area_samples(mesh.vertices, mesh.faces, samples, a)
    count = np.bincount(fid, minlength=len(mesh.faces))
    weight = a[fid] / np.maximum(count[fid], 1) / total        # each sample's share of the area
    whole = np.zeros(len(mesh.faces), bool)
    for p in kept:
        whole[p.faces] = True
    hit = whole[fid].copy()
    for p in kept:
        ask = ~hit
        hit[ask] = sample_hits(mesh, p, eps, fid[ask], x[ask])
    own = []
    for p in candidates:
        on = np.zeros(len(mesh.faces), bool)
        on[p.faces] = True
        own.append(sample_hits(mesh, p, eps, fid, x) | on[fid])
    left = list(range(len(candidates)))
    out: list[SweepPatch] = []
    while left:
        gains = [float(weight[own[i] & ~hit].sum()) for i in left]
        j = int(np.argmax(gains))
        if gains[j] < least:
            break
        i = left.pop(j)
        out.append(candidates[i])
        hit |= own[i]
    return out
