"""Mirror candidates: the mesh's mirror planes, and each patch's mirror image fitted again.

Beyond the paper. Gothic work is full of mirror symmetry (a window's two halves, its inner and
outer faces), and where the search finds a sweep on one side it may miss its twin on the other:
the window fig20a's left arc has a rotation part, its right arc none, since no candidate of the
``parts`` stage is a rotation about that arc's axis. Here:

1. :func:`mirror_planes`: candidate planes through the mesh's area centroid, normal to the
   principal axes of its area-weighted second moment and to the geodesic sphere's normals
   (``sphere_frequency``); a plane is accepted when the mirror images of the faces' centroids
   lie within ``eps_prox`` of the mesh for at least ``mirror_share`` of the area (``MeshTree``;
   a plane is given up as soon as more than the rest of the area is off the mesh),
   the best ``mirror_planes`` of them, no two within 5 degrees;
2. :func:`mirrored`: a patch's mirror image in a plane: the profile reflected, the motion
   conjugated by the reflection (``R' = S R S``, ``T' = S R s + S T + s`` for the reflection
   ``x -> S x + s``), so that its maps stay proper (det +1) and the mirrored profile swept by
   the mirrored motion is the mirror image of the swept surface; for a rotation, the axis is
   mirrored;
3. :func:`mirror_candidates`: the mirror images of the candidates that fit, in each accepted plane
   (and in the planes after it, of those images: two perpendicular planes give the half turn
   about their line), each through the same fit check against the mesh as every other candidate
   (:func:`~auszug.sweeps.patches.fit_patch`); never accepted without it. A mirror image whose
   faces are mostly its original's (a patch symmetric in the plane) is not fitted again, and an
   image that lies mostly (``patch_overlap``) on the faces of the candidates given is dropped.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
from numpy.typing import NDArray

from auszug.sweeps.mesh import SweepMesh
from auszug.sweeps.motion import Motion
from auszug.sweeps.params import DEFAULT, SweepParams
from auszug.sweeps.patches import MeshTree, SweepPatch, face_areas, fit_patch
from auszug.sweeps.planes import geodesic_sphere

__all__ = ["mirror_planes", "mirrored", "mirror_candidates"]

Array = NDArray[np.float64]

#: Faces whose mirror images :func:`mirror_planes` tests at a time (at least this many, fewer than twice
#: as many: the faces split evenly) before it checks whether the plane can still reach ``mirror_share``
#: (a plane is given up after the first chunk that shows it cannot).
MIRROR_CHUNK = 2048


def mirror_planes(mesh: SweepMesh, params: SweepParams = DEFAULT,
                  tree: MeshTree | None = None) -> list[tuple[Array, float, float]]:
    """The mesh's mirror planes (normalised coordinates), best first.

    Parameters
    ----------
    mesh : SweepMesh
    params : SweepParams
        ``mirror_share``, ``mirror_planes``, ``eps_prox`` and ``sphere_frequency``.
    tree : MeshTree, optional
        The mesh's tree (built here if not given).

    Returns
    -------
    list of (normal (3,), offset, share)
        Planes ``normal . x = offset`` (unit normals) whose mirror image of the mesh lies within
        ``eps_prox`` of it for ``share >= mirror_share`` of the area; at most ``mirror_planes``.

    Examples
    --------
    >>> from auszug.sweeps.fixtures import extruded
    >>> from auszug.sweeps.mesh import normalise
    >>> fx = extruded(n_profile=40, n_path=40)
    >>> len(mirror_planes(normalise(fx.vertices, fx.faces))) >= 1
    True
    """
    if params.mirror_planes == 0 or len(mesh.faces) == 0:
        return []
    tree = tree if tree is not None else MeshTree(mesh.vertices, mesh.faces)
    areas = face_areas(mesh.vertices, mesh.faces)
    total = float(areas.sum())
    if total <= 0:
        return []
    c = mesh.vertices[mesh.faces].mean(axis=1)
    w = areas / total
    centroid = w @ c
    y = c - centroid
    _, axes = np.linalg.eigh((y * w[:, None]).T @ y)
    sphere = geodesic_sphere(params.sphere_frequency)
    normals = np.vstack([axes.T, sphere[sphere @ np.array([0.3, 0.5, 0.8]) > 0]])
    # the faces in a fixed shuffled order, in chunks: a plane is given up once the area of its faces
    # whose images lie off the mesh exceeds 1 - mirror_share (most planes, after a chunk or two);
    # the share of a plane kept is summed over every face
    order = np.random.default_rng(0).permutation(len(c))
    chunks = np.array_split(order, max(1, len(order) // MIRROR_CHUNK))
    found: list[tuple[Array, float, float]] = []
    for n in normals:
        n = n / np.linalg.norm(n)
        if any(abs(float(n @ m)) > np.cos(np.radians(5.0)) for m, _, _ in found):
            continue
        h = float(n @ centroid)
        share, missed = 0.0, 0.0
        for idx in chunks:
            image = c[idx] - 2.0 * ((c[idx] @ n) - h)[:, None] * n
            on = tree.query_within(image, params.eps_prox)[0] <= params.eps_prox
            share += float(w[idx[on]].sum())
            missed += float(w[idx[~on]].sum())
            if missed > 1.0 - params.mirror_share:
                break
        if missed <= 1.0 - params.mirror_share and share >= params.mirror_share:
            found.append((n, h, share))
    found.sort(key=lambda x: -x[2])
    return found[:params.mirror_planes]


def mirrored(p: SweepPatch, normal: Array, offset: float) -> tuple[Array, Motion]:
    """The mirror image of a patch in the plane ``normal . x = offset``: its profile and its motion.

    The motion's maps ``x -> R x + T`` become ``x -> S R S x + S R s + S T + s`` for the
    reflection ``x -> S x + s`` (``S = I - 2 n n^T``, ``s = 2 offset n``): proper rotations again,
    the identity at the first parameter again, and the mirrored profile moved by them is the mirror
    image of the moved profile.

    Examples
    --------
    A quarter turn about the z axis through (1, 0, 0), mirrored in the plane x = 0, is a turn the
    other way about the z axis through (-1, 0, 0):

    >>> from auszug.sweeps.motion import screw_motion
    >>> r, t = screw_motion([0, 0, 1.0], [1.0, 0, 0], 0.0, [0.0, np.pi / 2])
    >>> p = SweepPatch(0, "rotation", np.array([[2.0, 0, 0], [2, 0, 1]]), False, Motion(np.array([0.0, 1.0]), r, t),
    ...                np.zeros(0, np.int64), 0.0, 0.0)
    >>> prof, m = mirrored(p, np.array([1.0, 0, 0]), 0.0)
    >>> np.round(m.apply(prof, [1.0])[0], 6).tolist()
    [[-1.0, 1.0, 0.0], [-1.0, 1.0, 1.0]]
    """
    n = np.asarray(normal, float) / np.linalg.norm(normal)
    s_mat = np.eye(3) - 2.0 * np.outer(n, n)
    s_vec = 2.0 * float(offset) * n
    profile = p.profile @ s_mat.T + s_vec
    r = np.einsum("ij,kjl,lm->kim", s_mat, p.motion.rotation, s_mat)
    t = np.einsum("ij,kjl,l->ki", s_mat, p.motion.rotation, s_vec) + p.motion.translation @ s_mat.T + s_vec
    return profile, Motion(p.motion.t.copy(), r, t)


def mirror_candidates(mesh: SweepMesh, patches: list[SweepPatch], planes: list[tuple[Array, float, float]],
                      params: SweepParams = DEFAULT, tree: MeshTree | None = None,
                      first_id: int = 0) -> list[SweepPatch]:
    """The mirror images of ``patches`` in the ``planes``, each fitted against the mesh, not filtered.

    Parameters
    ----------
    mesh : SweepMesh
    patches : list of SweepPatch
        The candidates to mirror (those that fit).
    planes : list of (normal, offset, share)
        From :func:`mirror_planes`.
    params : SweepParams
    tree : MeshTree, optional
    first_id : int
        Id of the first patch.

    Returns
    -------
    list of SweepPatch
        Same kind as their originals; faces, fit error and coverage from
        :func:`~auszug.sweeps.patches.fit_patch`. In each plane the images of the patches and of
        the images that fit in the planes before it; an image is returned only when less than
        ``patch_overlap`` of its faces' area lies in the faces of ``patches`` (one that covers
        again what they cover adds nothing).
    """
    tree = tree if tree is not None else MeshTree(mesh.vertices, mesh.faces)
    areas = face_areas(mesh.vertices, mesh.faces)
    out: list[SweepPatch] = []
    pool = list(patches)
    taken = np.zeros(len(mesh.faces), bool)
    for p in patches:
        taken[p.faces] = True
    for n, h, _ in planes:
        # the mirror image of a face set: the faces whose mirrored centroids lie nearest
        c = mesh.vertices[mesh.faces].mean(axis=1)
        image = c - 2.0 * ((c @ n) - h)[:, None] * n
        new: list[SweepPatch] = []
        for p in pool:
            if len(p.faces):
                a = areas[p.faces]
                mask = np.zeros(len(mesh.faces), bool)
                mask[p.faces] = True
                same = tree.on_faces(image[p.faces], mask)     # on an edge or a vertex of one of them too
                if a.sum() > 0 and float(a[same].sum() / a.sum()) >= params.patch_overlap:
                    continue            # the patch is its own mirror image (near enough)
            profile, motion = mirrored(p, n, h)
            fit = fit_patch(mesh, profile, p.closed, motion, params, areas, tree)
            new.append(replace(p, profile=profile, motion=motion,
                               faces=fit.faces, fit_error=fit.fit_error, coverage=fit.coverage, profile_fit=None))
        # an image adds a candidate only where the patches given leave some of its faces: one that
        # covers again what they cover (at least patch_overlap of its area) would only compete
        # with them in the fit stage's ranking (on the window fig20c such an image displaced an
        # original and lost 0.012 of the area)
        for q in new:
            a = areas[q.faces]
            if a.sum() > 0 and float(a[taken[q.faces]].sum() / a.sum()) < params.patch_overlap:
                out.append(replace(q, id=first_id + len(out)))
        # images that fit are mirrored again in the later planes
        pool.extend(q for q in new if q.fit_error <= params.fit_factor * params.eps_prox
                    and q.coverage >= params.min_patch_area)
    return out
