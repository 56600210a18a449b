"""Printable solids: members (and thickened faces, and a base plate) united into one closed mesh.

Every member is made a closed solid on its own: the swept tube with its end
caps, and where it was cut at a mirror plane, the cut closed by the planar
outline there (earcut), which its mirror image shares exactly. Faces get a
thickness by offsetting the minimal surface both ways along its normals and
stitching the rims. Everything is then united by manifold3d (an optional
dependency, imported when a solid is made) into one watertight, oriented
2-manifold; its volume is reported.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Sequence

import numpy as np
from numpy.typing import NDArray

from auszug.errors import GeometryError
from auszug.geometry import TOL
from auszug.geometry.network import as_curve_network
from auszug.meshing._clip import plane_loops
from auszug.meshing._work import check_curves, check_triangles, member_triangles
from auszug.meshing.faces import Faces
from auszug.meshing.mesh import Mesh, Part, is_closed, weld
from auszug.meshing.profile import Profile, triangulate_polygon
from auszug.meshing.sweep import Member, sweep_members

__all__ = ["Solid", "closed_member", "thicken", "base_plate", "unite", "drop_slivers", "solid"]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True, eq=False)
class Solid:
    """A united solid.

    Attributes
    ----------
    mesh : Mesh
        One part ``"solid"``.
    volume : float
        Enclosed volume (drawing units cubed).
    watertight : bool
        Every edge shared by exactly two consistently oriented triangles.
    components : int
        Separate shells (1 when everything touches; networks whose layers
        stand apart without pillars or a base plate give more).
    inputs : int
        How many closed meshes were united.
    slivers : int
        Tiny shells (below 1e-4 of the volume) the union left and that were
        removed (thickened faces meeting at sharp tips can leave some).
    """

    mesh: Mesh
    volume: float
    watertight: bool
    components: int
    inputs: int
    slivers: int = 0


def _cap_cuts(mb: Member) -> tuple[Array, IntArray]:
    """The member with every mirror-plane cut closed by its planar outline."""
    v, f = mb.vertices, mb.faces
    caps = [f]
    scale = float(np.linalg.norm(v.max(0) - v.min(0)))
    for cut in mb.cuts:
        for loop in plane_loops(v, f, cut.origin, cut.normal, 1e-9 * max(scale, 1.0)):
            # plane coordinates: (horizontal along the plane, up)
            e1 = np.cross([0.0, 0.0, 1.0], cut.normal)
            pts = v[loop] - cut.origin
            uv = np.stack([pts @ e1, pts[:, 2]], axis=1)
            x, y = uv[:, 0], uv[:, 1]
            area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
            order = loop if area > 0 else loop[::-1]
            tri = triangulate_polygon(uv if area > 0 else uv[::-1])
            t = order[tri]
            # the cap faces away from the kept side: its normal is -cut.normal
            a, b, c = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
            nrm = np.cross(b - a, c - a).sum(axis=0)
            if float(nrm @ cut.normal) > 0:
                t = t[:, ::-1]
            caps.append(t)
    return v, np.concatenate(caps)


def closed_member(mb: Member) -> tuple[Array, IntArray]:
    """A member (basic, not replicated) as a closed mesh: vertices (n, 3), faces (m, 3).

    Raises
    ------
    GeometryError
        If the member's profile is open.
    """
    if not mb.closed:
        raise GeometryError("a solid needs a closed profile; this member was swept with an open one")
    return _cap_cuts(mb)


def thicken(vertices: Array, faces: IntArray, thickness: float) -> tuple[Array, IntArray]:
    """A surface with a boundary made a closed shell of the given thickness.

    The surface is offset by +-thickness/2 along its (area-weighted) vertex
    normals, and the two copies are joined along the boundary.

    Examples
    --------
    >>> import numpy as np
    >>> v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0.0]]); f = np.array([[0, 1, 2], [0, 2, 3]])
    >>> tv, tf = thicken(v, f, 0.1)
    >>> m = Mesh(tv, tf); m.is_watertight, round(m.volume, 12)
    (True, 0.1)
    """
    from auszug.meshing.mesh import boundary_edges

    if not (math.isfinite(thickness) and thickness > 0):
        raise GeometryError(f"face thickness must be a positive number, got {thickness}")
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces, dtype=np.int64)
    n = len(v)
    fn = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    vn = np.zeros((n, 3))
    for ax in range(3):
        vn[:, ax] = np.bincount(f.reshape(-1), weights=np.repeat(fn[:, ax], 3), minlength=n)
    ln = np.linalg.norm(vn, axis=1, keepdims=True)
    vn = np.divide(vn, ln, out=np.zeros_like(vn), where=ln > 0)
    h = thickness / 2.0
    top, bot = v + h * vn, v - h * vn
    be = boundary_edges(f)               # directed as the faces run along the rim
    a, b = be[:, 0], be[:, 1]
    # the rim wall: top a -> b belongs to the top surface; the wall runs b -> a on top
    side = np.concatenate([np.stack([b, a, a + n], axis=1), np.stack([b, a + n, b + n], axis=1)])
    out_f = np.concatenate([f, f[:, ::-1] + n, side])
    return np.concatenate([top, bot]), out_f


def base_plate(network: Any, thickness: float, margin: float, sink: float,
               segments: int = 96) -> tuple[Array, IntArray]:
    """A round plate under the network: top ``sink`` above the ground, ``thickness`` thick.

    Its radius reaches ``margin`` beyond the farthest point of the network
    from the symmetry centre.
    """
    network = as_curve_network(network)
    b = network.bounds()
    groups = network.groups
    c = np.asarray(groups[0].center if groups else (0.0, 0.0), dtype=float)
    pts = np.concatenate([network.replicate(p).reshape(-1, 3) for p in network.pieces])
    r = float(np.max(np.hypot(pts[:, 0] - c[0], pts[:, 1] - c[1]))) + margin
    z0 = float(b[0, 2])
    a = 2 * np.pi * np.arange(segments) / segments
    ring = np.stack([c[0] + r * np.cos(a), c[1] + r * np.sin(a)], axis=1)
    lo = np.concatenate([ring, np.full((segments, 1), z0 + sink - thickness)], axis=1)
    hi = np.concatenate([ring, np.full((segments, 1), z0 + sink)], axis=1)
    v = np.concatenate([lo, hi])
    j = np.arange(segments)
    j1 = (j + 1) % segments
    side = np.concatenate([np.stack([j, j1, j1 + segments], 1), np.stack([j, j1 + segments, j + segments], 1)])
    k = np.arange(1, segments - 1)
    top = np.stack([np.full_like(k, segments), k + segments, k + 1 + segments], 1)
    bottom = np.stack([np.zeros_like(k), k + 1, k], 1)
    return v, np.concatenate([side, top, bottom]).astype(np.int64)


def unite(meshes: Sequence[tuple[Array, IntArray]]) -> Mesh:
    """The union of closed meshes (manifold3d), as one :class:`Mesh`.

    Members that only touch (at a point, or along a face) leave features far
    below float32's resolution: vertices 1e-11 apart, or two at one spot
    where shells meet in a point. They are merged (``TOL.solid_merge`` of the
    solid's size): manifold3d simplifies to that tolerance, then vertices
    still that close are welded if the result stays a closed 2-manifold. So
    an STL of the solid, read back by position as printers and slicers read
    it, is watertight too.

    Raises
    ------
    GeometryError
        If an input is not a closed, oriented 2-manifold (manifold3d refuses it).
    """
    import manifold3d as m3

    parts = []
    for i, (v, f) in enumerate(meshes):
        mf = m3.Manifold(m3.Mesh64(np.ascontiguousarray(v, dtype=np.float64),
                                   np.ascontiguousarray(f, dtype=np.uint64)))
        if mf.status() != m3.Error.NoError:
            raise GeometryError(f"solid input {i} is not a closed 2-manifold ({mf.status().name})")
        parts.append(mf)
    if not parts:
        return Mesh(np.empty((0, 3)), np.empty((0, 3), dtype=np.int64))
    u = m3.Manifold.batch_boolean(parts, m3.OpType.Add)
    size = 0.0 if u.is_empty() else float(np.abs(np.asarray(u.bounding_box(), dtype=float)).max())
    merge = TOL.solid_merge * size
    if merge > u.get_tolerance():
        u = u.set_tolerance(merge)
    out = u.to_mesh64()
    v = np.asarray(out.vert_properties, dtype=float)[:, :3]
    f = np.asarray(out.tri_verts, dtype=np.int64)
    wv, wf = weld(v, f, 2.0 * merge)
    if len(wv) < len(v) and len(wf) and Mesh(wv, wf).is_manifold:
        v, f = wv, wf
    return Mesh(v, f, (Part("solid", "solid", -1, "", (0, len(v)), (0, len(f))),))


def _component_labels(faces: IntArray, n: int) -> NDArray[np.int64]:
    """Connected component of every face."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    i = np.concatenate([faces[:, 0], faces[:, 1]])
    j = np.concatenate([faces[:, 1], faces[:, 2]])
    g = coo_matrix((np.ones(len(i)), (i, j)), shape=(n, n))
    _, lab = connected_components(g, directed=False)
    return lab[faces[:, 0]]


def drop_slivers(mesh: Mesh, rel: float = 1e-4) -> tuple[Mesh, int, int]:
    """Remove shells whose volume is below ``rel`` of the total (slivers a union can leave).

    Returns
    -------
    mesh : Mesh
    components : int
        Shells kept.
    dropped : int
        Shells removed.
    """
    from auszug.meshing._clip import compact
    from auszug.meshing.mesh import signed_volume

    if mesh.n_faces == 0:
        return mesh, 0, 0
    lab = _component_labels(mesh.faces, mesh.n_vertices)
    ids = np.unique(lab)
    vols = np.array([signed_volume(mesh.vertices, mesh.faces[lab == c]) for c in ids])
    total = float(np.abs(vols).sum())
    keep_ids = ids[np.abs(vols) >= rel * total]
    if len(keep_ids) == len(ids):
        return mesh, len(ids), 0
    f = mesh.faces[np.isin(lab, keep_ids)]
    v, f = compact(mesh.vertices, f)
    part = Part("solid", "solid", -1, "", (0, len(v)), (0, len(f)))
    return Mesh(v, f, (part,)), len(keep_ids), len(ids) - len(keep_ids)


def solid(
    network: Any,
    profile: Profile,
    segments: int = 64,
    faces: Faces | None = None,
    thickness: float | None = None,
    base: bool = False,
    base_thickness: float | None = None,
    cut: bool = False,
) -> Solid:
    """Members, thickened faces and an optional base plate united into one printable solid.

    Parameters
    ----------
    network : CurveNetwork (or a producer of one, e.g. ``microarch.Network``)
    profile : Profile
        Closed.
    segments : int
        Steps along each member.
    faces : Faces, optional
        Faces to include (from :func:`~auszug.meshing.faces.network_faces`).
    thickness : float, optional
        Face thickness (default: half the profile's smaller extent, so the
        faces' rims stay inside the members).
    base : bool
        Add a round base plate the members' feet sink into.
    base_thickness : float, optional
        Default: twice the profile's extent.
    cut : bool
        Cut members at mirror planes as in the rendered mesh. Off by default:
        the cut halves of a joint touch their neighbours in a single point
        where they part, which a printer (and a position-welding STL reader)
        sees as a pinch; the overlapping members unite into a clean fork.

    Returns
    -------
    Solid

    Raises
    ------
    GeometryError
        For an open profile, or a non-manifold input.

    Examples
    --------
    >>> from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry, build
    >>> from auszug.meshing.profile import square
    >>> c = BasicCurve(((1.0, 0.0), (0.0, 1.0)), (Segment("line"),), ("ground", "apex"),
    ...                Symmetry(fold=2, mirror=True, axis=(1.0, 0.0)), height=1.0)
    >>> s = solid(build(Drawing((c,))), square(0.05), segments=24)
    >>> s.watertight, s.components, s.volume > 0
    (True, 1, True)
    """
    profile.require_closed("a solid")
    n = check_curves(network, "a solid")
    check_triangles(member_triangles(n, int(segments), profile.n), "the solid's members",
                    "fewer segments, fewer points around, a lower fold or fewer curves")
    ext = profile.points.max(0) - profile.points.min(0)
    # uncut: at a mirror joint the cut halves would touch the neighbour along a lens that ends in a
    # point (a zero-thickness contact); overlapping members unite into a clean fork instead
    network = as_curve_network(network)
    members = sweep_members(network, profile, int(segments), cut=cut)
    inputs: list[tuple[Array, IntArray]] = []
    for mb in members:
        v, f = closed_member(mb)
        sym = network.groups[mb.basic]
        mats = sym.matrices()
        c = np.asarray(sym.center)
        for k in mb.replicas:
            vv = v.copy()
            vv[:, :2] = (v[:, :2] - c) @ mats[k].T + c
            inputs.append((vv, f[:, ::-1] if np.linalg.det(mats[k]) < 0 else f))
    if faces is not None and faces.faces:
        t = float(thickness) if thickness is not None else 0.5 * float(ext.min())
        for fc in faces.faces:
            inputs.append(thicken(fc.vertices, fc.faces, t))
    if base:
        bt = float(base_thickness) if base_thickness is not None else 2.0 * float(ext.max())
        inputs.append(base_plate(network, bt, margin=2.0 * float(ext.max()), sink=0.25 * float(ext.min())))
    mesh, comps, dropped = drop_slivers(unite(inputs))
    return Solid(mesh, float(mesh.volume), is_closed(mesh.faces), comps, len(inputs), dropped)
