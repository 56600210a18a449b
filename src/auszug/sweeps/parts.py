"""Kinematic parts: the pieces of a mesh that are each a surface of revolution or an extrusion.

Beyond the paper. :func:`~auszug.sweeps.kinematic.kinematic_axis` asks whether *all* cuts glide
under one motion; a Gothic moulding run along a window's border is no such surface as a whole
(its jambs are extrusions, its arches surfaces of revolution about the arcs' centres, each with a
motion of its own), and the general sweeps of sec. 2.3 need profiles of ``l_min`` (20 % of the
diameter), which such a moulding's profile is not. Here the consensus is sought among subsets of
the cuts, one motion after another (a sequential consensus, in the manner of RANSAC):

1. candidates: the own velocity states of cuts not yet explained, whose normals turn
   (``min_spread``) and whose state is well determined (second eigenvalue at least
   ``kinematic_gap`` times the first), at most ``part_candidates`` of them spread evenly over the
   planes, each made a pure rotation or translation (:func:`unscrewed`);
2. each candidate is scored by the cut points of the unexplained curves that glide under it as
   whole curves (at least ``kinematic_share`` of a curve's points with weight above 2/3, as for the
   whole mesh); the best one is refitted to the points of the curves that glide by robust least
   squares, staying a rotation or translation (:func:`refined`), and its gliding curves found again;
3. the part is the mesh near what those curves span: the faces whose vertices lie, in the
   motion's invariant coordinates (for a translation the plane normal to it, for a rotation
   the radius and the height along the axis), within the gliding points' box, and in the
   motion's parameter within the gliding points' range, each grown by ``part_margin``;
4. :func:`~auszug.sweeps.patches.kinematic_patches` on that part (and on ``part_slices`` slices
   of its range), with profiles down to ``part_l_min`` long taken as cut (``part_profile_cuts``),
   each trimmed to up to ``part_blocks`` blocks of profile points times motion on the mesh
   (:func:`fitting_block`), with ``part_grow`` over the whole mesh's range of the motion and on
   the whole mesh, a block kept when its points lie on average within ``part_mean_error`` times
   ``eps_prox`` of the mesh; for a rotation the translation along its axis is tried too; the fit
   check and the area and sweep-length filters of :func:`~auszug.sweeps.detect` decide what is kept;
5. the gliding curves count as explained (kept or not) and the search goes on, at most
   ``max_parts`` times, while some candidate moves at least ``part_min_points`` cut points;
6. each translation that found patches is tried across the planar faces along it (``part_across``):
   the translation along ``n x d`` for the largest planar faces' normal ``n`` along the direction
   ``d``, on the whole mesh (a wall's top and bottom and its face above an opening slide along its
   width, but every cut across the wall runs through the opening's moulding, so none glides whole).

Screw motions are not sought as parts (only rotations and translations): a helical part's
parameter range would need the winding of every face, and no fixture has one.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from auszug.sweeps._kernels import fitting_block as block_of
from auszug.sweeps._kernels import glide_shares
from auszug.sweeps.cut import Cuts
from auszug.sweeps.kinematic import KinematicAxis, motion_of
from auszug.sweeps.mesh import SweepMesh
from auszug.sweeps.motion import Motion, screw_motion
from auszug.sweeps.movability import Movability
from auszug.sweeps.params import DEFAULT, SweepParams
from auszug.sweeps.patches import MeshTree, SweepPatch, _axis_frame, face_areas, fit_patch, kinematic_patches

__all__ = ["fitting_block", "gliding_shares", "kinematic_parts", "part_faces", "refined", "unscrewed"]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]


def gliding_shares(cuts: Cuts, states: Array, params: SweepParams = DEFAULT,
                   curves: NDArray[np.bool_] | None = None) -> Array:
    """Per velocity state and curve, the share of the curve's points that glide under it.

    Parameters
    ----------
    cuts : Cuts
    states : (k, 6) float array
        Velocity states ``(c, c_bar)`` (normalised mesh coordinates).
    params : SweepParams
        ``beta``, ``gamma``, ``speed_floor`` and ``weight_threshold`` (Alg. 1's weight).
    curves : (c,) bool array, optional
        Only these curves are evaluated (the others get share 0).

    Returns
    -------
    (k, c) float array
        Shares in [0, 1].
    """
    s = np.atleast_2d(np.asarray(states, float))
    pick = np.ones(cuts.n_curves, bool) if curves is None else np.asarray(curves, bool)
    out = np.zeros((len(s), cuts.n_curves))
    if not pick.any():
        return out
    sizes = np.diff(cuts.curve_start)
    at = np.repeat(pick, sizes)
    starts = np.concatenate([[0], np.cumsum(sizes[pick])]).astype(np.int64)
    sub = glide_shares(np.ascontiguousarray(cuts.points[at]), np.ascontiguousarray(cuts.normals[at]), starts,
                       np.ascontiguousarray(s), float(params.beta), float(params.gamma), float(params.speed_floor),
                       float(params.weight_threshold))
    out[:, pick] = sub
    return out


def _axis(c: Array, params: SweepParams) -> KinematicAxis:
    kind, direction, point, pitch = motion_of(c, params)
    return KinematicAxis(kind, c, direction, point, pitch, 0, 0.0, float("nan"))


def unscrewed(states: Array, params: SweepParams = DEFAULT) -> Array:
    """Velocity states ``(k, 6)`` made pure rotations or translations (unit norm).

    A translation (by :func:`~auszug.sweeps.kinematic.motion_of`'s test) keeps only ``c_bar``;
    anything else becomes the rotation about its screw axis: ``(d, p x d)`` for the axis through
    ``p`` along ``d``, normalised.

    Examples
    --------
    >>> np.round(unscrewed(np.array([[0, 0, 1.0, 0, 0, 0.3]])), 6).tolist()
    [[0.0, 0.0, 1.0, 0.0, 0.0, 0.0]]
    """
    out = np.empty((len(states), 6))
    for i, c in enumerate(np.asarray(states, float)):
        kind, d, p, _ = motion_of(c, params)
        out[i] = np.r_[0.0, 0.0, 0.0, d] if p is None else np.r_[d, np.cross(p, d)]
    return out / np.linalg.norm(out, axis=1, keepdims=True)


def refined(state: Array, points: Array, normals: Array, params: SweepParams = DEFAULT) -> Array:
    """A rotation or translation state ``(6,)`` refitted to cut points ``(n, 3)`` with normals ``(n, 3)``.

    Robust least squares (scipy's ``least_squares``, Cauchy loss at scale 0.02) of the cosines
    between the velocity and the surface normal over the axis' direction and point (4 unknowns)
    or the translation's direction (2): the motion stays a pure rotation or translation, which the
    summed movability matrices' eigenvector, a screw in general, does not.
    """
    from scipy.optimize import least_squares

    axis = _axis(state, params)
    d0 = axis.direction
    e1, e2 = _axis_frame(d0)
    if axis.kind == "translation":
        def res_t(z: Array) -> Array:
            d = d0 + z[0] * e1 + z[1] * e2
            return np.asarray(normals @ (d / np.linalg.norm(d)))

        z = least_squares(res_t, np.zeros(2), loss="cauchy", f_scale=0.02, x_scale=0.1).x
        d = d0 + z[0] * e1 + z[1] * e2
        return np.r_[0.0, 0.0, 0.0, d / np.linalg.norm(d)]
    p0 = axis.point
    assert p0 is not None

    def geometry(z: Array) -> tuple[Array, Array]:
        d = d0 + z[0] * e1 + z[1] * e2
        return d / np.linalg.norm(d), p0 + z[2] * e1 + z[3] * e2

    def res_r(z: Array) -> Array:
        d, p = geometry(z)
        v = np.cross(d, points - p)
        return np.asarray(np.einsum("ij,ij->i", normals, v) / np.sqrt(np.einsum("ij,ij->i", v, v)
                                                                    + params.speed_floor**2))

    z = least_squares(res_r, np.zeros(4), loss="cauchy", f_scale=0.02, x_scale=0.1).x
    d, p = geometry(z)
    c = np.r_[d, np.cross(p, d)]
    return c / np.linalg.norm(c)


def _coordinates(axis: KinematicAxis, x: Array) -> tuple[Array, Array, float]:
    """Invariant coordinates ``(n, 2)``, the parameter ``(n,)`` (length or angle) and a length per unit of it."""
    d = axis.direction
    e1, e2 = _axis_frame(d)
    if axis.kind == "translation":
        return np.column_stack([x @ e1, x @ e2]), x @ d, 1.0
    assert axis.point is not None
    y = x - axis.point
    h = y @ d
    a, b = y @ e1, y @ e2
    r = np.hypot(a, b)
    return np.column_stack([r, h]), np.arctan2(b, a), max(float(np.median(r)), 1e-9)


def _range(t: Array, angular: bool) -> tuple[float, float]:
    """The smallest interval (for angles: arc, as ``(start, length)``) holding the values ``t``."""
    if not angular:
        return float(t.min()), float(np.ptp(t))
    phi = np.sort(np.mod(t, 2 * np.pi))
    gaps = np.diff(np.concatenate([phi, phi[:1] + 2 * np.pi]))
    g = int(np.argmax(gaps))
    return float(phi[(g + 1) % len(phi)]), float(2 * np.pi - gaps[g])


def part_faces(mesh: SweepMesh, axis: KinematicAxis, points: Array, margin: float,
               faces: IntArray | None = None) -> IntArray:
    """The faces near what ``points`` span under a rotation or translation (step 3 of the module's text).

    Parameters
    ----------
    mesh : SweepMesh
    axis : KinematicAxis
        A rotation or a translation.
    points : (n, 3) float array
        The gliding cut points (normalised coordinates).
    margin : float
        Growth of the box and the range (bounding-box diameters).
    faces : (m,) int array, optional
        The candidate faces (default all).

    Returns
    -------
    (k,) int array
        Indices into ``mesh.faces``, ascending.
    """
    return _part(mesh, axis, points, margin, faces)[0]


def _part(mesh: SweepMesh, axis: KinematicAxis, points: Array, margin: float,
          faces: IntArray | None = None, overlap: bool = False) -> tuple[IntArray, float, float, Array]:
    """:func:`part_faces`, and the part's parameter range and every vertex's parameter in it.

    Returns the faces, the range's start and length (grown by the margin) and every vertex's
    parameter relative to that start ``(n,)``.
    """
    cand = np.arange(len(mesh.faces), dtype=np.int64) if faces is None else np.asarray(faces, np.int64)
    q, t, unit = _coordinates(axis, points)
    lo, hi = q.min(axis=0) - margin, q.max(axis=0) + margin
    angular = axis.kind != "translation"
    start, length = _range(t, angular)
    grow = margin / unit
    vq, vt, _ = _coordinates(axis, mesh.vertices)
    inside = np.all((vq >= lo) & (vq <= hi), axis=1)
    rel = np.mod(vt - start + grow, 2 * np.pi) if angular else vt - start + grow
    in_range = (rel >= 0) & (rel <= length + 2 * grow)
    if not overlap:
        keep = (inside & in_range)[mesh.faces[cand]].all(axis=1)
    elif angular:
        keep = inside[mesh.faces[cand]].all(axis=1) & in_range[mesh.faces[cand]].any(axis=1)
    else:
        r = rel[mesh.faces[cand]]
        keep = inside[mesh.faces[cand]].all(axis=1) & (r.max(axis=1) >= 0) & (r.min(axis=1) <= length + 2 * grow)
    return cand[keep], start - grow, length + 2 * grow, rel


def _submesh(mesh: SweepMesh, keep: IntArray) -> SweepMesh:
    """The mesh restricted to the faces ``keep`` (same vertex array; edges and index maps selected)."""
    used = np.zeros(len(mesh.edges), bool)
    used[mesh.face_edges[keep]] = True
    used_edges = np.flatnonzero(used)
    edge_index = np.full(len(mesh.edges), -1, np.int64)
    edge_index[used_edges] = np.arange(len(used_edges))
    face_index = np.full(len(mesh.faces) + 1, -1, np.int64)    # [-1] stays -1: a missing face
    face_index[keep] = np.arange(len(keep))
    return replace(mesh, faces=mesh.faces[keep], edges=mesh.edges[used_edges],
                   edge_faces=face_index[mesh.edge_faces[used_edges]],
                   face_edges=edge_index[mesh.face_edges[keep]])


def fitting_block(ok: NDArray[np.bool_], widths: Array, min_width: float = 0.0,
                  max_starts: int = 128) -> tuple[int, int, int, int] | None:
    """The largest block of a boolean matrix that is all True, by rows x summed column widths.

    Parameters
    ----------
    ok : (k, n) bool array
        ``ok[r, c]``: profile point ``c`` moved to ring ``r`` lies on the mesh.
    widths : (n - 1,) float array
        Lengths of the profile's segments (between columns ``c`` and ``c + 1``).
    min_width : float
        Blocks narrower than this (summed widths) do not count.
    max_starts : int
        At most this many first columns are tried, spread evenly (``n`` may be large).

    Returns
    -------
    (r0, r1, c0, c1) or None
        Rows ``r0..r1`` and columns ``c0..c1`` (inclusive, ``c1 > c0``), or None when no block of
        two or more columns and ``min_width`` is all True.

    Examples
    --------
    >>> ok = np.array([[1, 1, 1, 0], [1, 1, 1, 1], [0, 1, 1, 1], [0, 1, 1, 1]], bool)
    >>> fitting_block(ok, np.ones(3))
    (1, 3, 1, 3)
    """
    k, n = ok.shape
    if n < 2 or k == 0:
        return None
    pos = np.concatenate([[0.0], np.cumsum(widths)])
    starts = np.unique(np.linspace(0, n - 2, min(n - 1, max_starts)).astype(np.int64))
    r0, r1, c0, c1 = block_of(np.ascontiguousarray(ok, dtype=np.bool_), pos, float(min_width), starts)
    return None if r0 < 0 else (int(r0), int(r1), int(c0), int(c1))


def _trimmed(mesh: SweepMesh, tree: MeshTree, axis: KinematicAxis, p: SweepPatch, params: SweepParams,
             t_range: tuple[float, float] | None = None) -> list[SweepPatch]:
    """The patches over the largest stretches of profile and motion where the moved profile stays on the mesh.

    A part's range is what its box spans, which may hold a corner where the moulding turns, and its
    profile cut may run on beyond the moulding (over a wall's face, into tracery beside it): the
    profile's points are moved by the part's motion to rings ``part_trim_spacing * eps_prox`` apart
    (at most 1024) over ``t_range`` (parameters relative to the profile's own, default the patch's
    motion range), each point on each ring kept when within ``eps_prox`` of the mesh, and the
    largest block of kept points (:func:`fitting_block`: a run of rings times a run of profile
    points at least ``l_min`` long) is a patch, fitted again over it; then the block's points are
    set aside and the next largest is sought, up to ``part_blocks`` patches (a straight profile cut
    may lie on the mesh over several stretches of the motion, a jamb on both sides of an opening).
    A block is no patch when the profile's centroid travels less than ``min_sweep_length`` over it
    (:func:`~auszug.sweeps.detect` would drop it) or when its points' mean distance to the mesh is
    above ``part_mean_error * eps_prox`` (a motion that only approximates a smooth bump stays within
    ``eps_prox`` at its best, but not near 0 on average as a true part's points are).
    """
    lo, hi = (float(p.motion.t[0]), float(p.motion.t[-1])) if t_range is None else t_range
    pitch = axis.pitch if axis.kind == "screw" else 0.0
    scale = (hi - lo) * (1.0 if axis.kind == "translation" else max(float(np.max(np.linalg.norm(
        p.profile - (axis.point if axis.point is not None else 0.0), axis=1))), 1e-9))
    k = int(min(max(8, np.ceil(scale / (params.part_trim_spacing * params.eps_prox))), 1024))
    ts = np.linspace(lo, hi, k)
    rot, tr = screw_motion(axis.direction, axis.point, pitch, ts)
    rings = np.einsum("kij,nj->kni", rot, p.profile) + tr[:, None, :]
    d = tree.query_within(rings.reshape(-1, 3), params.eps_prox)[0].reshape(k, -1)     # inf beyond eps_prox
    ok = d <= params.eps_prox
    closed = p.closed and bool(ok.all())
    n = len(p.profile)
    if closed:
        order = np.r_[np.arange(n), 0]
    elif p.closed:
        # a loop not all on the mesh is opened at its point that is on it least often: a block may
        # then run over the loop's first point
        s = int(np.argmin(ok.sum(axis=0)))
        order = np.r_[np.arange(s, n), np.arange(s), s]
    else:
        order = np.arange(n)
    prof, ok, d, rings = p.profile[order], ok[:, order], d[:, order], rings[:, order]
    widths = np.linalg.norm(np.diff(prof, axis=0), axis=1)
    free = ok.copy()
    seen: list[tuple[int, int, int, int]] = []
    out: list[SweepPatch] = []
    for _ in range(2 * params.part_blocks):
        if len(out) >= params.part_blocks:
            break
        block = fitting_block(free, widths, params.l_min)
        if block is None:
            break
        r0, r1, c0, c1 = block
        free[r0:r1 + 1, c0:c1 + 1] = False
        # the next blocks are sought among the points not yet in one, then grown over all points on
        # the mesh (a face spanning two blocks' rows needs one patch over both)
        while r0 > 0 and ok[r0 - 1, c0:c1 + 1].all():
            r0 -= 1
        while r1 < k - 1 and ok[r1 + 1, c0:c1 + 1].all():
            r1 += 1
        while c0 > 0 and ok[r0:r1 + 1, c0 - 1].all():
            c0 -= 1
        while c1 < len(prof) - 1 and ok[r0:r1 + 1, c1 + 1].all():
            c1 += 1
        if p.closed and not closed and c0 == 0 and c1 == len(prof) - 1:
            c1 -= 1         # an opened loop's block ends short of its first point: no profile meets itself
        if any(a0 <= r0 and r1 <= a1 and b0 <= c0 and c1 <= b1 for a0, a1, b0, b1 in seen):
            continue
        seen.append((r0, r1, c0, c1))
        sub = p.profile if closed else prof[c0:c1 + 1]
        centre = rings[r0:r1 + 1, c0:c1 + 1].mean(axis=1)
        swept = float(np.linalg.norm(np.diff(centre, axis=0), axis=1).sum())
        a, b = float(ts[r0]), float(ts[r1])
        if not b > a or swept < params.min_sweep_length:
            continue        # detect drops a patch sweeping less
        if float(d[r0:r1 + 1, c0:c1 + 1].mean()) > params.part_mean_error * params.eps_prox:
            continue
        tk = np.linspace(0.0, b - a, max(8, params.motion_samples))
        motion = Motion(tk, *screw_motion(axis.direction, axis.point, pitch, tk))
        profile = sub @ rot[r0].T + tr[r0]
        fit = fit_patch(mesh, profile, closed, motion, params, tree=tree)
        out.append(SweepPatch(p.id, p.kind, profile, closed, motion, fit.faces, fit.fit_error, fit.coverage))
        if closed:
            break
    return out


def _good_cover(patches: list[SweepPatch], params: SweepParams, areas: Array) -> float:
    """Area of the union of the faces of the patches that fit."""
    on = np.zeros(len(areas), bool)
    for p in patches:
        if p.fit_error <= params.fit_factor * params.eps_prox:
            on[p.faces] = True
    return float(areas[on].sum())


def _part_patches(mesh: SweepMesh, axis: KinematicAxis, pts: Array, free: NDArray[np.bool_], areas: Array,
                  part_params: SweepParams, params: SweepParams, grow: MeshTree | None = None) -> list[SweepPatch]:
    """The trimmed kinematic patches of the part that ``pts`` span under ``axis`` (faces of ``mesh``).

    :func:`kinematic_patches` takes its profile cut in the middle of the part and, when
    ``part_slices`` is above 1, in the middle of each of that many equal slices of its range (a
    part may hold stretches that are no sweep under its motion, where the one middle cut would
    fall); each profile is trimmed over the whole part's range. Patches of different slices may
    be the same sweep: the fit stage of :func:`~auszug.sweeps.detect` keeps one
    (``patch_overlap``).
    """
    keep, start, length, rel = _part(mesh, axis, pts, params.part_margin, np.flatnonzero(free), grow is not None)
    total = float(areas.sum())
    if len(keep) == 0 or float(areas[keep].sum()) < params.min_patch_area * total:
        return []           # too small to be kept whatever fits
    sub = _submesh(mesh, keep)
    sub_tree = MeshTree(sub.vertices, sub.faces)
    d = axis.direction / np.linalg.norm(axis.direction)
    e1, e2 = _axis_frame(d)
    out = []
    n = params.part_slices
    for i in range(n + 1 if n > 1 else 1):
        # the whole part first, then its slices
        inside = (rel >= (i - 1) * length / n) & (rel <= i * length / n)
        piece = keep[inside[mesh.faces[keep]].all(axis=1)] if i > 0 else keep
        if len(piece) == 0:
            continue
        for p in kinematic_patches(_submesh(mesh, piece) if i > 0 else sub, axis, part_params):
            # the profile's own parameter, relative to the part's start
            c = p.profile.mean(axis=0)
            if axis.kind == "translation":
                t0 = float(c @ d) - start
            else:
                assert axis.point is not None
                y = c - axis.point
                t0 = float(np.mod(np.arctan2(y @ e2, y @ e1) - start, 2 * np.pi))
            if grow is not None:
                # over the whole mesh and its whole range: the profile may sweep on beyond the part
                if axis.kind == "translation":
                    t_lo = float(np.min(mesh.vertices @ d)) - (t0 + start)
                    t_hi = float(np.max(mesh.vertices @ d)) - (t0 + start)
                else:
                    t_lo, t_hi = -np.pi, np.pi
                out.extend(_trimmed(mesh, grow, axis, p, part_params, (t_lo, t_hi)))
                continue
            for q in _trimmed(sub, sub_tree, axis, p, part_params, (-t0, length - t0)):
                faces = keep[q.faces]
                cov = float(areas[faces].sum() / total) if total > 0 else 0.0
                out.append(replace(q, faces=faces, coverage=cov))
    return out


def _across(mesh: SweepMesh, slid: list[Array], free: NDArray[np.bool_], areas: Array, part_params: SweepParams,
            params: SweepParams, grow: MeshTree | None) -> list[SweepPatch]:
    """Patches of the translations across the planar faces along the translations ``slid`` (unit directions).

    Per direction ``d`` (those found first, then each one found here), the faces whose unit normals
    are within ``part_across`` of normal to ``d``, grouped by normal rounded to 0.01 (up to sign),
    give the largest group's normal ``n`` by area; the translation along ``n x d``, unless parallel
    to one tried, is tried on the whole mesh (:func:`_part_patches`), at most ``max_parts`` of them.
    A wall's top and bottom and its face above an opening slide along the wall's width, but every
    cut across the wall runs through the opening's moulding too, so none glides as a whole and no
    candidate suggests that motion.
    """
    out: list[SweepPatch] = []
    if params.part_across <= 0 or not slid:
        return out
    tri = mesh.vertices[mesh.faces]
    nrm = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    unit = nrm / np.maximum(np.linalg.norm(nrm, axis=1, keepdims=True), 1e-300)
    done, queue = list(slid), list(slid)
    while queue and len(done) - len(slid) < params.max_parts:      # at most max_parts directions tried
        d = queue.pop(0)
        along = np.abs(unit @ d) <= params.part_across
        if not along.any():
            continue
        u = unit[along]
        key = np.round(np.where((u @ np.array([1.0, 2.0, 3.0]))[:, None] < 0, -u, u), 2)
        groups, inv = np.unique(key, axis=0, return_inverse=True)
        w = np.bincount(inv.ravel(), weights=areas[along])
        g = int(np.argmax(w))
        if w[g] < params.min_patch_area * float(areas.sum()):
            continue
        e = np.cross(groups[g] / np.linalg.norm(groups[g]), d)
        if np.linalg.norm(e) < 0.5:
            continue
        e /= np.linalg.norm(e)
        if any(abs(float(e @ q)) > 0.999 for q in done):
            continue
        done.append(e)
        found = _part_patches(mesh, _axis(np.r_[0.0, 0.0, 0.0, e], params), mesh.vertices, free, areas,
                              part_params, params, grow)
        if found:
            queue.append(e)
        out.extend(found)
    return out


def kinematic_parts(mesh: SweepMesh, cuts: Cuts, mov: Movability, params: SweepParams = DEFAULT,
                    free: NDArray[np.bool_] | None = None, first_id: int = 0) -> tuple[list[SweepPatch], int]:
    """Rotation and translation patches of the parts of a mesh (normalised coordinates), fitted, not filtered.

    Parameters
    ----------
    mesh : SweepMesh
    cuts, mov : Cuts, Movability
        The initial planes' cuts and their movability.
    params : SweepParams
        ``max_parts``, ``part_candidates``, ``part_min_points``, ``part_margin``, ``part_l_min``
        and the kinematic and fit parameters.
    free : (m,) bool array, optional
        Faces not yet covered (default all): cut points on covered faces are explained already, and
        parts hold free faces only.
    first_id : int
        Id of the first patch.

    Returns
    -------
    patches : list of SweepPatch
        Faces index ``mesh.faces``; coverage is the share of the whole mesh's area.
    tried : int
        Motions tried (parts found, kept or not).
    """
    free_f = np.ones(len(mesh.faces), bool) if free is None else np.array(free, bool)
    out: list[SweepPatch] = []
    if cuts.n_curves == 0 or params.max_parts == 0:
        return out, 0
    areas = face_areas(mesh.vertices, mesh.faces)
    curve_of = np.repeat(np.arange(cuts.n_curves), np.diff(cuts.curve_start))
    # a cut point is explained when both faces of its edge are covered
    ef = mesh.edge_faces[cuts.edges]
    covered_pt = np.where(ef >= 0, ~free_f[np.maximum(ef, 0)], True).all(axis=1)
    counts = np.diff(cuts.curve_start)
    open_curve = np.add.reduceat((~covered_pt).astype(np.int64), cuts.curve_start[:-1]) > counts // 2
    # a curve whose normals hardly turn lies in a nearly flat strip, where every motion in its plane
    # glides: it neither votes nor counts (movability's min_spread, for whole curves)
    nn = np.einsum("ni,nj->nij", cuts.normals, cuts.normals)
    mean_nn = np.add.reduceat(nn, cuts.curve_start[:-1], axis=0) / np.maximum(counts, 1)[:, None, None]
    spread = np.linalg.eigvalsh(mean_nn)
    open_curve &= spread[:, 1] >= params.min_spread
    ev = mov.eigenvalues
    voter = ev[:, 1] >= params.kinematic_gap * np.maximum(ev[:, 0], 1e-300)
    part_params = params.with_(l_min=params.part_l_min, profile_cuts=params.part_profile_cuts)
    grow = MeshTree.of(mesh) if params.part_grow else None
    tried = 0
    slid: list[Array] = []
    while tried < params.max_parts:
        # candidates spread evenly over the open voters, drawn afresh as the open curves shrink
        cand = np.flatnonzero(voter & open_curve)
        if len(cand) == 0:
            break
        cand = cand[np.unique(np.linspace(0, len(cand) - 1, min(len(cand), params.part_candidates)).astype(int))]
        states = unscrewed(mov.velocity[cand], params)
        share = gliding_shares(cuts, states, params, open_curve)
        score = (share >= params.kinematic_share) @ counts
        best = int(np.argmax(score))
        if score[best] < params.part_min_points:
            break
        glide = (share[best] >= params.kinematic_share) & open_curve
        # refitted as a pure rotation or translation to the curves that glide, while that keeps at
        # least 80 % of them gliding (a candidate from one short cut may be tilted by degrees and
        # still glide more curves, within Alg. 1's tolerance)
        c = states[best]
        for _ in range(3):
            sel = glide[curve_of]
            c2 = refined(c, cuts.points[sel], cuts.normals[sel], params)
            g2 = (gliding_shares(cuts, c2[None], params)[0] >= params.kinematic_share) & open_curve
            if g2 @ counts < 0.8 * (glide @ counts):
                break
            c, glide = c2, g2 | glide
        tried += 1
        open_curve &= ~glide
        axis = _axis(c, params)
        if axis.kind == "screw":
            continue
        pts = cuts.points[glide[curve_of] & ~covered_pt]
        if len(pts) < params.part_min_points:
            continue
        found = _part_patches(mesh, axis, pts, free_f, areas, part_params, params, grow)
        if axis.kind == "rotation":
            # cuts of a piece of an extrusion whose profile is partly round glide under the rotation
            # about a line along it too: the translation along the axis is tried, the larger cover wins
            slide = _axis(np.r_[0.0, 0.0, 0.0, axis.direction], params)
            other = _part_patches(mesh, slide, pts, free_f, areas, part_params, params, grow)
            if _good_cover(other, params, areas) > _good_cover(found, params, areas):
                found = other
        # the faces of a fitted patch stay open to later motions: a motion that only approximates
        # a stretch (a rotation of large radius over a straight sill) may fit it first, and the
        # fit stage of detect keeps the patch that covers more (patch_overlap)
        for p in found:
            out.append(replace(p, id=first_id + len(out)))
        if found and axis.kind == "translation":
            slid.append(axis.direction / np.linalg.norm(axis.direction))
    for p in _across(mesh, slid, free_f, areas, part_params, params, grow):
        out.append(replace(p, id=first_id + len(out)))
    return out, tried
