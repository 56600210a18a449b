"""General sweeps (paper sec. 2.3): from ordered ribs to a rigid motion, a profile and a fit.

Given a family's ribs in order (:func:`~auszug.sweeps.order_ribs`), each rib a polyline whose
samples correspond one to one (the family's common part):

1. **Positions.** ``M_i``, the rigid map taking rib 0 to rib ``i`` (least squares over the
   corresponding samples, Kabsch), at time ``t_i = i``.
2. **Velocities** (sec. 2.3.2, Eq. 7): ``C_i`` minimises ``F(b_i, b_{i-1}) + F(b_i, b_{i+1})`` with
   ``F = F_tang + mu_1 F_reg + mu_2 F_pivot``. As printed ``F_reg`` and ``F_pivot`` are the same sum
   and ``F_tang`` does not measure tangential motion, so we read them as:

   - ``F_tang = sum_i (n_i . xdot(x_i))^2``: the velocity at the rib's points is tangent to the
     surface (normals ``n_i`` at the closest points on the mesh), the paper's words "small if x_i
     moves tangential to the reference surface" and Eq. 3;
   - ``F_reg = |C - C_0|^2``: a regulariser of a least-squares problem in ``C`` (Tikhonov),
     towards ``C_0``, the twist of the best rigid map between the two ribs (Kabsch, then the
     logarithm of SE(3), over ``dt``; the mean over both neighbours). Towards zero instead, with
     ``mu_1 = 0.002``, it shrank the velocity: two ribs of a known screw motion 2-20 degrees
     apart gave it 0.7-2.6 % off (and 4 % without F_tang); towards ``C_0`` it only fixes what
     the data leave free (a straight rib's turn about itself);
   - ``F_pivot = sum_i |x'_i - x_i - dt xdot(m_i)|^2`` with ``m_i = (x_i + x'_i) / 2``: the velocity
     carries ``x_i`` to its partner. Evaluating the velocity at the *midpoint* of the pair (not at
     ``x_i`` as printed) makes the estimate second-order: by the Cayley transform, the finite
     screw motion ``x' = R x + T`` satisfies ``x' - x = c x m + c_bar`` exactly, with ``c``
     along the screw axis and ``|c| = 2 tan(phi / 2)`` for the turn ``phi``; so two ribs of a
     screw motion give its velocity up to the factor ``tan(phi / 2) / (phi / 2)`` (0.25 % at
     10 degrees), where the printed form is off by ``phi / 2`` (9 % at 10 degrees).
3. **Hermite interpolation** (sec. 2.3.1, [HPR04]): on each interval the affine maps
   ``A(t) = (L(t), a(t))`` are the cubic Hermite interpolants of the positions ``(R_i, T_i)`` and
   derivatives ``([c_i]x R_i, c_bar_i + c_i x T_i)``; then each ``A(t)`` is projected to the
   closest rigid motion in the sense of the profile's points (Kabsch: ``sum_j |R p_j + T -
   A(t) p_j|^2`` least, ``det R = +1``), at ``samples_per_rib`` parameters per interval.
4. **Profile improvement** (sec. 2.3.3): the mesh is cut by the planes of the moved profile at
   those parameters, each cut (the piece near the moved profile) is mapped back by the inverse
   motion, and every profile point moves to the mean of its closest points on them.
5. **Fit check** (sec. 2.3.4): :func:`~auszug.sweeps.patches.fit_patch`; steps 1-4 are repeated
   ``general_iterations`` times with the improved profile.

Beyond the paper: a fitted sweep is **grown** (:func:`grown_patch`) across its profile to the
whole cut curve (:func:`extend_profile`) and along its path rib by rib while the mesh follows
(:func:`grow_ribs`), then refitted; and a sweep on a mesh whose cuts glide under one turn that
sweeps nothing is also tried as pure translations by parallel cuts (:func:`translational_patch`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.sweeps._kernels import (
    apply_maps,
    batched_gram,
    box_part,
    closest_on_plane_curves,
    closest_on_planes,
    curves_near_profiles,
    eq7_blocks,
    grown_states,
    inverse_maps_at,
    kabsch_sums,
    near_runs,
    polyline_closest_chunked,
    rotations_of,
    twist_steps,
)
from auszug.sweeps.cut import Cuts, EdgeGrid, cut, cut_near
from auszug.sweeps.matching import (
    CurvaturePlots,
    Family,
    Ribs,
    curvature_plots,
    families,
    match_cuts,
    order_ribs,
    split_family,
)
from auszug.sweeps.mesh import SweepMesh, face_components
from auszug.sweeps.motion import Motion, se3_log
from auszug.sweeps.movability import Movability
from auszug.sweeps.params import DEFAULT, SweepParams
from auszug.sweeps.patches import (
    MeshTree,
    RingTree,
    SweepPatch,
    SweptError,
    consistent_pieces,
    face_areas,
    fill_corners,
    fit_patch,
    improve_bounded,
    improve_flat,
    swept_coverage,
    swept_error,
)
from auszug.sweeps.planes import plane_recall
from auszug.sweeps.stage import Stage

__all__ = ["kabsch", "kabsch_batch", "rib_velocity", "rib_velocities", "hermite_motion", "rib_parts", "general_patch",
           "general_stages", "split_ribs", "motion_planes", "profile_planes", "reslice", "GeneralSweep",
           "extend_profile",
           "grow_ribs", "GrownRibs", "grown_patch", "trajectory_error", "translational_patch", "refine_motion",
           "path_tangents", "knot_twists", "smooth_twists"]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Parameters per rib interval at which the Hermite motion is projected and the mesh re-cut (paper: "say, 8").
SAMPLES_PER_RIB = 8


def kabsch(p: ArrayLike, q: ArrayLike, weights: ArrayLike | None = None) -> tuple[Array, Array]:
    """The proper rigid map ``(R (3, 3), T (3,))`` minimising ``sum w_j |R p_j + T - q_j|^2``.

    Examples
    --------
    >>> from scipy.spatial.transform import Rotation
    >>> p = np.random.default_rng(0).normal(size=(10, 3))
    >>> r0 = Rotation.from_rotvec([0.3, -0.2, 1.0]).as_matrix()
    >>> r, t = kabsch(p, p @ r0.T + [1.0, 2.0, 3.0])
    >>> bool(np.allclose(r, r0)), np.round(t, 12).tolist()
    (True, [1.0, 2.0, 3.0])
    """
    a = np.asarray(p, float)
    b = np.asarray(q, float)
    w = np.ones(len(a)) if weights is None else np.asarray(weights, float)
    w = w / w.sum()
    ca, cb = w @ a, w @ b
    h = ((a - ca) * w[:, None]).T @ (b - cb)
    u, _, vt = np.linalg.svd(h)
    d = np.sign(np.linalg.det(vt.T @ u.T))
    r = vt.T @ np.diag([1.0, 1.0, d if d != 0 else 1.0]) @ u.T
    return r, cb - r @ ca


def kabsch_batch(p: ArrayLike, q: ArrayLike) -> tuple[Array, Array]:
    """:func:`kabsch` (equal weights) of ``p (n, 3)`` or ``p (k, n, 3)`` onto each ``q[i] (n, 3)`` of ``q (k, n, 3)``.

    Returns ``R (k, 3, 3)`` and ``T (k, 3)``: one batched SVD, no Python loop per map.

    Examples
    --------
    >>> from scipy.spatial.transform import Rotation
    >>> p = np.random.default_rng(0).normal(size=(10, 3))
    >>> r0 = Rotation.from_rotvec([[0.3, -0.2, 1.0], [0.0, 2.0, 0.1]]).as_matrix()
    >>> r, t = kabsch_batch(p, np.einsum("kij,nj->kni", r0, p) + [[[1.0, 2, 3]], [[0.0, 0, 0]]])
    >>> bool(np.allclose(r, r0)), (np.round(t, 12) + 0.0).tolist()   # + 0.0: no -0.0
    (True, [[1.0, 2.0, 3.0], [0.0, 0.0, 0.0]])
    """
    b = np.ascontiguousarray(np.asarray(q, float))
    a = np.asarray(p, float)
    a3 = np.ascontiguousarray(a[None] if a.ndim == 2 else np.broadcast_to(a, b.shape))
    # compiled: the centroids (numpy's mean over axis 1) and einsum("kni,knj->kij", (a - ca) / n, b - cb), bit for bit
    ca, cb, h = kabsch_sums(a3, b)
    u, _, vt = np.linalg.svd(h)
    v = np.swapaxes(vt, 1, 2)
    ut = np.swapaxes(u, 1, 2)
    d = np.sign(np.linalg.det(v @ ut))
    v[:, :, 2] *= np.where(d != 0, d, 1.0)[:, None]
    r = v @ ut
    return r, cb - np.einsum("kij,kj->ki", r, ca)


def _rows(mid: Array, d: Array, mu2: float) -> tuple[Array, Array]:
    """Normal-equation blocks (6 x 6, 6) of F_pivot for one neighbour: midpoints, displacements per unit time."""
    # pivot: d_i = dt (c x m_i + c_bar): rows for each coordinate; c x m = -[m]x c
    k = len(mid)
    a = np.zeros((k, 3, 6))
    a[:, 0, 1], a[:, 0, 2] = mid[:, 2], -mid[:, 1]
    a[:, 1, 0], a[:, 1, 2] = -mid[:, 2], mid[:, 0]
    a[:, 2, 0], a[:, 2, 1] = mid[:, 1], -mid[:, 0]
    a[:, :, 3:] = np.eye(3)
    a = a.reshape(-1, 6)
    return mu2 * a.T @ a, mu2 * a.T @ d.reshape(-1)


def rib_velocity(rib: ArrayLike, neighbours: list[tuple[Array, float]], normals: ArrayLike | None = None,
                 mu: tuple[float, float] = DEFAULT.mu) -> Array:
    """The velocity state ``(6,) = (c, c_bar)`` of a rib by Eq. 7 (our reading, module docstring).

    Parameters
    ----------
    rib : (n, 3) array_like
        The rib's samples.
    neighbours : list of ((n, 3) array, float)
        Each neighbouring rib (samples corresponding to ``rib``'s) with its time step ``dt``.
    normals : (n, 3) array_like, optional
        Surface normals at the rib's samples (F_tang); None leaves F_tang out.
    mu : (float, float)

    Examples
    --------
    Two positions of a profile 10 degrees apart about the z axis through (1, 0, 0):

    >>> from auszug.sweeps.motion import screw_motion
    >>> a = np.linspace(0, np.pi, 20)
    >>> x = np.column_stack([1.3 + 0.1 * np.cos(a), np.zeros(20), 0.1 * np.sin(a)])   # a half circle
    >>> r, t = screw_motion([0, 0, 1.0], [1.0, 0, 0], 0.0, [np.radians(10)])
    >>> c = rib_velocity(x, [(x @ r[0].T + t[0], 1.0)])
    >>> np.round(c / np.radians(10), 4).tolist()   # (0, 0, 1, 0, -1, 0), up to tan(5 deg) / (5 deg)
    [0.0, 0.0, 1.0018, -0.0, -1.0016, 0.0]
    """
    x = np.asarray(rib, float)
    lhs = mu[0] * np.eye(6)
    rhs = np.zeros(6)
    if normals is not None:
        nr = np.asarray(normals, float)
        t = np.hstack([np.cross(x, nr), nr])     # n . (c x x + c_bar) = (x x n) . c + n . c_bar
        lhs += t.T @ t
    prior = np.zeros(6)
    for y, dt in neighbours:
        yy = np.asarray(y, float)
        a, b = _rows((x + yy) / 2, (yy - x) / dt, mu[1])
        lhs += a
        rhs += b
        w, v = se3_log(*kabsch(x, yy))
        prior += np.r_[w, v] / dt / len(neighbours)
    rhs += mu[0] * prior
    out: Array = np.asarray(np.linalg.solve(lhs, rhs), dtype=np.float64)
    return out


def rib_velocities(parts: Array, normals: Array | None, mu: tuple[float, float] = DEFAULT.mu,
                   times: Array | None = None) -> Array:
    """Velocity states ``(k, 6)`` of ribs ``parts (k, n, 3)`` at ``times (k,)`` (default ``0..k-1``).

    Each rib's neighbours on both sides enter Eq. 7 (:func:`rib_velocity`, all ribs at once:
    the normal equations of every rib and neighbour are batched, one solve per rib).
    """
    x = np.asarray(parts, float)
    k, n = x.shape[:2]
    tt = np.arange(k, dtype=float) if times is None else np.asarray(times, float)
    lhs = np.broadcast_to(mu[0] * np.eye(6), (k, 6, 6)).copy()
    rhs = np.zeros((k, 6))
    if normals is not None:
        nr = np.asarray(normals, float)
        tg = np.concatenate([np.cross(x, nr), nr], axis=2)             # (k, n, 6)
        lhs += batched_gram(tg, tg)                                    # compiled: einsum "kni,knj->kij" bit for bit
    if k < 2:
        out1: Array = np.asarray(np.linalg.solve(lhs, rhs[..., None])[..., 0], dtype=np.float64)
        return out1
    # every (rib, neighbour) pair: i to i + 1 and i + 1 to i
    i = np.r_[np.arange(k - 1), np.arange(1, k)]
    j = np.r_[np.arange(1, k), np.arange(k - 1)]
    dt = (tt[j] - tt[i])[:, None, None]
    mid = (x[i] + x[j]) / 2
    d = (x[j] - x[i]) / dt
    # A^T A and A^T d of A (pairs, 3 n, 6), per point the rows [-[mid]x | I], without building A (compiled,
    # numpy's einsum over A bit for bit)
    ata, atd = eq7_blocks(mid, d)
    # np.add.at over i in its order: the pairs i -> i + 1 first (ribs 0 .. k - 2), then i + 1 -> i (ribs 1 .. k - 1)
    b = k - 1
    lhs[:b] += mu[1] * ata[:b]
    lhs[1:] += mu[1] * ata[b:]
    rhs[:b] += mu[1] * atd[:b]
    rhs[1:] += mu[1] * atd[b:]
    # the prior C_0: the twist of the best rigid map to each neighbour over dt, mean over the neighbours
    rot, tr = kabsch_batch(x[i], x[j])
    w, v = se3_log(rot, tr)
    n_nb = np.bincount(i, minlength=k).astype(float)
    prior = np.zeros((k, 6))
    c0 = np.concatenate([w, v], axis=1) / dt[:, 0] / n_nb[i, None]
    prior[:b] += c0[:b]
    prior[1:] += c0[b:]
    rhs += mu[0] * prior
    out: Array = np.asarray(np.linalg.solve(lhs, rhs[..., None])[..., 0], dtype=np.float64)
    return out


def hermite_motion(profile: Array, rotations: Array, translations: Array, velocities: Array,
                   samples_per_rib: int = SAMPLES_PER_RIB, times: Array | None = None) -> Motion:
    """C1 Hermite interpolation of affine maps between ribs at ``times``, projected to rigid motions.

    Parameters
    ----------
    profile : (n, 3) float array
        The points whose motion defines "closest" rigid map (Kabsch).
    rotations : (k, 3, 3), translations : (k, 3)
        The rigid maps at the ribs (``x -> R_i x + T_i``).
    velocities : (k, 6)
        Velocity states ``(c, c_bar)`` at the ribs (spatial: ``xdot = c x x + c_bar``).
    samples_per_rib : int
        Parameters per interval.
    times : (k,) float array, optional
        Increasing rib parameters (default ``0..k-1``).

    Returns
    -------
    Motion
        Knots at ``t_i + j (t_i+1 - t_i) / samples_per_rib``; exactly the given maps at the ribs.
    """
    k = len(rotations)
    c, cb = velocities[:, :3], velocities[:, 3:]
    hat = np.zeros((k, 3, 3))
    hat[:, 0, 1], hat[:, 0, 2] = -c[:, 2], c[:, 1]
    hat[:, 1, 0], hat[:, 1, 2] = c[:, 2], -c[:, 0]
    hat[:, 2, 0], hat[:, 2, 1] = -c[:, 1], c[:, 0]
    dl = hat @ rotations                       # d/dt of the linear part
    da = cb + np.cross(c, translations)        # d/dt of the translation
    tt = np.arange(k, dtype=float) if times is None else np.asarray(times, float)
    f = np.arange(1, samples_per_rib + 1) / samples_per_rib
    h00, h10 = 2 * f**3 - 3 * f**2 + 1, f**3 - 2 * f**2 + f
    h01, h11 = -2 * f**3 + 3 * f**2, f**3 - f**2
    hh = np.diff(tt)[:, None]                                       # (k - 1, 1) interval lengths
    # the affine maps at every inner sample of every interval: (k - 1, s, 3, 3) and (k - 1, s, 3)
    lin = (h00[None, :, None, None] * rotations[:-1, None] + (hh * h10)[:, :, None, None] * dl[:-1, None]
           + h01[None, :, None, None] * rotations[1:, None] + (hh * h11)[:, :, None, None] * dl[1:, None])
    off = (h00[None, :, None] * translations[:-1, None] + (hh * h10)[:, :, None] * da[:-1, None]
           + h01[None, :, None] * translations[1:, None] + (hh * h11)[:, :, None] * da[1:, None])
    # each projected to the closest rigid motion in the sense of the profile's points (one batched Kabsch), but
    # the last of each interval: it is exactly the given map at the next rib (each map's Kabsch is its own)
    s1 = samples_per_rib - 1
    moved = apply_maps(np.ascontiguousarray(lin[:, :s1].reshape(-1, 3, 3)),
                       np.ascontiguousarray(off[:, :s1].reshape(-1, 3)),
                       np.ascontiguousarray(profile, dtype=float))     # compiled, as einsum bit for bit
    r_all = np.empty((k - 1, samples_per_rib, 3, 3))
    t_all = np.empty((k - 1, samples_per_rib, 3))
    if s1 > 0:
        r_in, t_in = kabsch_batch(profile, moved)
        r_all[:, :s1] = r_in.reshape(k - 1, s1, 3, 3)
        t_all[:, :s1] = t_in.reshape(k - 1, s1, 3)
    r_all[:, -1], t_all[:, -1] = rotations[1:], translations[1:]   # exactly the given maps at the ribs
    ts = np.r_[tt[0], (tt[:-1, None] + hh * f[None, :]).reshape(-1)]
    return Motion(ts, np.concatenate([rotations[:1], r_all.reshape(-1, 3, 3)]),
                  np.concatenate([translations[:1], t_all.reshape(-1, 3)]))


def split_ribs(parts: Array, jump: float) -> list[Array]:
    """Ordered ribs ``(k, n, 3)`` split where a step between consecutive centroids is a jump.

    A jump is more than ``jump`` times the median step.

    Examples
    --------
    >>> x = np.array([0.0, 1.0, 2.0, 3.0, 9.0, 10.0, 11.0])
    >>> parts = np.zeros((7, 2, 3)); parts[:, :, 0] = x[:, None]
    >>> [len(q) for q in split_ribs(parts, 3.0)]
    [4, 3]
    """
    if len(parts) < 3:
        return [parts]
    step = np.linalg.norm(np.diff(parts.mean(axis=1), axis=0), axis=1)
    cut_after = np.flatnonzero(step > jump * np.median(step)) + 1
    return [q for q in np.split(parts, cut_after) if len(q)]


def rib_parts(ribs: Ribs, plots: CurvaturePlots) -> Array:
    """The ribs' common parts ``(k, n, 3)`` in rib order, sample ``j`` corresponding across ribs."""
    from auszug.sweeps.matching import ordered_parts  # here: the module's imports stay as they were (merges)

    return ordered_parts(ribs, plots)


def _normals_at(mesh: SweepMesh, points: Array, tree: MeshTree) -> Array:
    """Unit normals of the mesh at the closest points of ``points (..., 3)`` (:meth:`MeshTree.normals`: ties aside)."""
    return tree.normals(points)


#: :func:`_plane_of`'s last points and answer: one profile's plane is asked for by the recut, both refinement
#: steps, the turn into the normal planes and the twists (one SVD instead of five).
_LAST_PLANE: list[tuple[Array, Array, float]] = []


def _plane_of(points: Array) -> tuple[Array, float]:
    """The least-squares plane of ``points (n, 3)``: unit normal ``(3,)`` and offset (the last answer kept)."""
    if _LAST_PLANE:
        p0, n0, d0 = _LAST_PLANE[0]
        if p0.shape == points.shape and np.array_equal(p0, points):
            return n0.copy(), d0
    o = points.mean(axis=0)
    n = np.linalg.svd(points - o)[2][2]
    _LAST_PLANE[:] = [(np.array(points, dtype=float, copy=True), n.copy(), float(n @ o))]
    return n, float(n @ o)


def _polyline_distance(points: Array, polyline: Array) -> Array:
    """Distances ``(m,)`` of points ``(m, 3)`` to a polyline ``(n, 3)`` (compiled)."""
    return polyline_closest_chunked(np.ascontiguousarray(points, dtype=float),
                                    np.ascontiguousarray(polyline, dtype=float))[0]


def _on_polyline(points: Array, polyline: Array) -> tuple[Array, Array]:
    """Distances ``(m,)`` and closest points ``(m, 3)`` of points ``(m, 3)`` on a polyline ``(n, 3)`` (compiled)."""
    d, c = polyline_closest_chunked(np.ascontiguousarray(points, dtype=float),
                                    np.ascontiguousarray(polyline, dtype=float))
    return d, c


def _recut(mesh: SweepMesh, profile: Array, motion: Motion, reach: float,
           grid: EdgeGrid | None = None) -> tuple[Array, IntArray]:
    """:func:`_recut_knots` without the pieces' knots."""
    back, starts, _ = _recut_knots(mesh, profile, motion, reach, grid)
    return back, starts


def _recut_knots(mesh: SweepMesh, profile: Array, motion: Motion, reach: float,
                 grid: EdgeGrid | None = None) -> tuple[Array, IntArray, IntArray]:
    """Cuts of the mesh by the moved profile's planes at the motion's knots, mapped back (sec. 2.3.3).

    Per knot, each stretch of a cut curve within ``reach`` of the moved profile, mapped back by the
    inverse of the knot's map. Returns the pieces' points ``(m, 3)`` and their starts ``(q + 1,)``
    (piece ``j`` is ``points[starts[j]:starts[j + 1]]``); one compiled pass finds the stretches of
    all curves. Only the curves with a point in the moved profile's box grown by ``reach`` are
    cut (:func:`~auszug.sweeps.cut.cut_near`, on ``grid``): the others have no point within
    ``reach``, so the pieces are those of the whole cut. Also returns each piece's knot ``(q,)``.
    """
    n0, _ = _plane_of(profile)
    moved = motion.apply(profile, motion.t)
    normals = np.einsum("kij,j->ki", motion.rotation, n0)
    offsets = np.einsum("ki,ki->k", normals, moved.mean(axis=1))
    c = cut_near(mesh, normals, offsets, np.hstack([moved.min(axis=1) - reach, moved.max(axis=1) + reach]), grid)
    if c.n_curves == 0:
        return np.zeros((0, 3)), np.zeros(1, np.int64), np.zeros(0, np.int64)
    near = curves_near_profiles(c.points, c.curve_start, c.curve_plane, np.ascontiguousarray(moved), reach)
    # each stretch of a curve near the moved profile (of 2 points or more) is a piece of its own: joined, a curve
    # broken by a hole in the mesh would bridge the hole by a chord (one compiled pass)
    starts, idx, k, knot = near_runs(near, c.curve_start, np.ascontiguousarray(c.curve_plane, dtype=np.int64))
    if not len(knot):
        return np.zeros((0, 3)), np.zeros(1, np.int64), np.zeros(0, np.int64)
    # compiled, as np.einsum("nji,nj->ni", R[k], points[idx] - T[k]) bit for bit
    back = inverse_maps_at(motion.rotation, motion.translation, k, c.points, idx)
    return back, starts, knot


@dataclass(frozen=True)
class GeneralSweep:
    """A general sweep fitted to ordered ribs (normalised coordinates).

    Attributes
    ----------
    profile : (n, 3) float array
        The profile at the first rib (improved).
    motion : Motion
    velocities : (k, 6) float array
        Eq. 7 velocity states at the ribs (last iteration).
    fit_error : float
    coverage : float
    faces : (m,) int array
    closed : bool
        The profile is a closed loop (its last point joined to its first).
    """

    profile: Array
    motion: Motion
    velocities: Array
    fit_error: float
    coverage: float
    faces: IntArray
    closed: bool = False


def profile_planes(profile: Array, motion: Motion, t: ArrayLike) -> tuple[Array, Array]:
    """The profile planes of a sweep at parameters ``t (q,)``: normals ``(q, 3)``, offsets ``(q,)``.

    Our convention (the paper leaves the plane to the ribs found): the plane through the moved
    profile's centroid normal to the centroid's velocity, i.e. the profile lies in the normal
    planes of its centroid's path. For a moulding swept with its profile in the normal planes of
    a path this is that plane, up to the twist times the centroid's distance from the path: with
    the true motion of the general-sweep fixture 1.2 deg (the top eigenvector of ``sum v_j v_j^T``
    over all profile points, our earlier convention, gave 2.3 deg, median).
    """
    tt = np.atleast_1d(np.asarray(t, float))
    lo, hi = motion.domain
    h = 1e-3 * max(hi - lo, 1e-12)
    tc = np.clip(tt, lo + h, hi - h)
    centroid = profile.mean(axis=0)[None]
    q = len(tt)
    y = motion.apply(centroid, np.concatenate([tt, tc + h, tc - h]))[:, 0]    # one evaluation of the motion
    x = y[:q]
    v = (y[q:2 * q] - y[2 * q:]) / (2 * h)
    n = v / np.maximum(np.linalg.norm(v, axis=1, keepdims=True), 1e-300)
    return n, np.einsum("qi,qi->q", n, x)


#: :func:`reslice` cuts the mesh only within this distance of the moved profile (bounding-box
#: diameters, 10 eps_prox at the default) and the whole plane where a point's closest cut point is
#: farther: the same ribs, less work.
RESLICE_REACH = 0.05


def reslice(mesh: SweepMesh, profile: Array, motion: Motion, tol: float = np.inf,
            t: ArrayLike | None = None, far: float = np.inf, grid: EdgeGrid | None = None) -> Array | None:
    """New ribs ``(k, n, 3)`` at the motion's integer parameters (or at ``t (k,)``); None if a plane misses the mesh.

    The mesh is cut by the profile planes (:func:`profile_planes`) there; sample ``j`` of a rib is
    the closest point to the moved profile's point ``j`` on the plane's cut curves, or the moved
    point itself where that closest point is an end of a cut curve farther than ``tol`` (beyond
    the mesh: over a hole or past its end). In the inner ribs (all but two at each end), the
    samples farther than ``far`` from the cut are the moved profile's points too: over a hole they
    found closest points on another part of the profile (the letter G's arc end beside its bar,
    0.06 away, not at a curve's end). The two end ribs at each end lie where the mesh ends, and
    their far samples stay on the cut (taken as the moved profile's points there too, the clean
    cubic's fit error rose from 8.5e-4 to 2.4e-3). The curves are cut near the moved profile
    first (:func:`~auszug.sweeps.cut.cut_near` within :data:`RESLICE_REACH`, on ``grid``); a plane
    where a point's closest cut point is farther is cut whole: every curve within that reach of a
    point is among those cut, so the ribs are those of the whole cuts.
    """
    if t is None:
        ts = motion.domain[0] + np.arange(int(round(motion.domain[1] - motion.domain[0])) + 1, dtype=float)
    else:
        ts = np.asarray(t, float)
    k = len(ts)
    n, d = profile_planes(profile, motion, ts)
    x = motion.apply(profile, ts)
    r = RESLICE_REACH
    c = cut_near(mesh, n, d, np.hstack([x.min(axis=1) - r, x.max(axis=1) + r]), grid)
    # every plane's closest points at once (compiled, each plane as _closest_on_cut gives it); a plane without a
    # curve there, or with a point farther than the reach, is cut whole
    x = np.ascontiguousarray(x)
    dist, cp, at_end = closest_on_planes(x, c.points, c.curve_start, c.curve_plane, c.curve_closed)
    for i in np.flatnonzero(~np.isfinite(dist).any(axis=1) | (dist.max(axis=1) > r)):
        got = _closest_on_cut(cut(mesh, n[i:i + 1], d[i:i + 1]), 0, x[i])
        if got is None:
            return None
        dist[i], cp[i], at_end[i] = got
    # beyond the mesh (closest cut point an end of a cut curve, and far): the moved profile's point
    beyond = at_end & (dist > tol)
    if far < np.inf and k > 4:
        beyond[2:k - 2] |= dist[2:k - 2] > far
    out: Array = np.where(beyond[:, :, None], x, cp)
    return out


def _far(params: SweepParams) -> float:
    """Re-slicing: a moved profile point farther than this from the cut has no partner there.

    ``4 grow_tolerance eps_prox``, the first round's reach of a grown rib (:func:`grow_ribs`).
    """
    return 4 * params.grow_tolerance * params.eps_prox


def general_patch(mesh: SweepMesh, parts: Array, params: SweepParams = DEFAULT,
                  areas: Array | None = None, tree: MeshTree | None = None,
                  times: Array | None = None, closed: bool = False) -> GeneralSweep:
    """Fit a sweep to ordered rib parts ``(k, n, 3)`` (k >= 2), iterating sec. 2.3.2-2.3.4.

    The ribs lie at parameters ``times (k,)`` (default ``0..k-1``); ``closed``: they are closed
    loops (the profile's last point joined to its first).

    The first round fits a motion to the ribs as found (cuts by the initial planes, up to 8
    degrees off the profile planes) and re-slices the mesh by its profile planes
    (:func:`reslice`); each further round (``general_iterations`` in all) fits the re-sliced
    ribs, improves the profile, checks the fit and re-slices again. The round of least fit
    error is returned (the first round is fitted only if re-slicing fails).
    """
    got = _general_fit(mesh, parts, params, areas, tree, times, closed)
    assert isinstance(got, GeneralSweep)
    return got


def _general_fit(mesh: SweepMesh, parts: Array, params: SweepParams = DEFAULT,
                 areas: Array | None = None, tree: MeshTree | None = None,
                 times: Array | None = None, closed: bool = False,
                 faces: bool = True, grid: EdgeGrid | None = None) -> GeneralSweep | tuple[GeneralSweep, SweptError]:
    """:func:`general_patch`, or without the covered faces and with the fit error.

    With ``faces`` False the covered faces are not found (coverage nan, no faces) and the fit
    error is returned with the sweep (:func:`_covered` finds them later). ``grid``: the edge grid
    of the local cuts (:func:`~auszug.sweeps.cut.cut_near`), built from ``mesh`` if not given.
    """
    a = face_areas(mesh.vertices, mesh.faces) if areas is None else areas
    tr_ = MeshTree(mesh.vertices, mesh.faces) if tree is None else tree
    grid = EdgeGrid.of(mesh) if grid is None else grid      # the local cuts of every round
    best: tuple[Array, Motion, Array, SweptError] | None = None
    ribs: Array | None = parts
    n_rounds = params.general_iterations
    for i in range(n_rounds):
        if ribs is None:
            break
        # the profile: the middle rib (the end ribs of a grown sweep lie where the mesh ends) taken to the first
        mid = kabsch(ribs[len(ribs) // 2], ribs[0])
        profile = ribs[len(ribs) // 2] @ mid[0].T + mid[1]
        normals = _normals_at(mesh, ribs, tr_)
        rot, tr = kabsch_batch(profile, ribs)
        vel = rib_velocities(ribs, normals, params.mu, times)
        motion = hermite_motion(profile, rot, tr, vel, SAMPLES_PER_RIB, times)
        if i == 0 and n_rounds > 1:
            # the ribs as found are cuts by planes up to 8 deg off the profile planes: their motion
            # only serves to re-slice (fitted, they missed the mesh by 2-6e-3, re-sliced by 0.6-1.9e-3)
            again = reslice(mesh, profile, motion, params.end_gap * params.eps_prox, times, _far(params),
                            grid)
            if again is not None:
                ribs = again
                continue
        back, starts, knot = _recut_knots(mesh, profile, motion, 4 * params.eps_prox, grid)
        back, starts, knot = consistent_pieces(profile, closed, back, starts, knot, params.piece_trim)
        # the improved profile, and bounds of its points' distances to the mesh at the knots (the recut's
        # pieces lie on the mesh): the fit error queries only the swept points that may be the farthest
        profile, upper = improve_bounded(profile, back, starts, knot, len(motion), params.eps_prox)
        # the fit error in every round, the covered faces only of the round kept
        err = swept_error(profile, closed, motion, params.eps_prox, tr_, upper, params.reciprocal_angle)
        if best is None or err.fit_error < best[3].fit_error:
            best = (profile, motion, vel, err)
        if i + 1 < n_rounds:
            ribs = reslice(mesh, profile, motion, params.end_gap * params.eps_prox, times, _far(params),
                           grid)
    assert best is not None
    if not faces:
        return GeneralSweep(best[0], best[1], best[2], best[3].fit_error, float("nan"), np.zeros(0, np.int64),
                            closed), best[3]
    return _covered(mesh, best[0], best[1], best[2], best[3], params, a, closed)


def _covered(mesh: SweepMesh, profile: Array, motion: Motion, vel: Array, err: SweptError, params: SweepParams,
             areas: Array, closed: bool) -> GeneralSweep:
    """The general sweep of a profile and motion fitted with fit error ``err``: the faces it covers found."""
    fit = swept_coverage(mesh, err, params.eps_prox, areas, distances=False)    # the faces, not the distances
    return GeneralSweep(profile, motion, vel, fit.fit_error, fit.coverage, fit.faces, closed)


#: :func:`refine_motion` leaves a knot's map as it was where the refined one turns farther than this (degrees).
MAX_REFINE_TURN = 5.0


def _twist_steps(profile: Array, rot: Array, tr: Array, tree: MeshTree, bound: float, steps: int, tol: float = 0.0,
                 warm: IntArray | None = None) -> tuple[Array, Array, Array, IntArray]:
    """``steps`` point-to-plane steps of every knot's map ``(rot (k, 3, 3), tr (k, 3))`` about its profile plane.

    Per knot and step: the moved profile's points within ``bound`` of the mesh (not beyond it),
    their closest mesh points ``q_j`` and face normals ``m_j``; the turn ``a`` about the profile
    plane's normal ``n`` through the moved centroid ``c`` and the shift ``(u, v)`` in the plane
    minimising ``sum (m_j . (x_j - q_j + a n x (x_j - c) + u e_1 + v e_2))^2`` (damped by 1e-3 of
    the mean eigenvalue: what the profile leaves free, a circle's turn, stays). One compiled pass
    (:func:`~auszug.sweeps._kernels.twist_steps`): the closest points exact, on the tree's face
    grid (:meth:`~auszug.sweeps.patches.MeshTree.face_grid`), each from the point's face of the
    step before (at the first, ``warm (k, n)``: faces near each point, -1 for none). A knot whose
    step moves its points by at most about ``tol`` takes no more. Also returns upper bounds
    ``(k, n)`` of the moved points' distances to the mesh at the returned maps (inf where unknown)
    and the points' last closest faces ``(k, n)``.
    """
    n0, _ = _plane_of(profile)
    c0 = profile.mean(axis=0)
    rho = max(float(np.sqrt(np.mean(np.sum((profile - c0) ** 2, axis=1)))), 1e-300)
    lo, dims, h, start, entries, fbox = tree.face_grid()
    w = np.full((len(rot), len(profile)), -1, np.int64) if warm is None else np.ascontiguousarray(warm, dtype=np.int64)
    out: tuple[Array, Array, Array, IntArray] = twist_steps(
        np.ascontiguousarray(profile, dtype=float), np.ascontiguousarray(rot, dtype=float),
        np.ascontiguousarray(tr, dtype=float), n0, c0, rho, int(steps), float(bound), float(tol), w,
        tree.vertices, tree.faces, tree._boundary_edges(), lo, dims, h, start, entries, fbox)
    return out


def path_tangents(points: Array, window: float, switch: float = 0.0) -> Array:
    """Unit tangents ``(k, 3)`` of a path through ``points (k, 3)``: local cubic fits over ``window`` of arc length.

    At each point, the cubic in arc length (chords) fitted by least squares to the points within
    ``window`` of it along the path, its derivative there (a quadratic or a line where fewer
    points lie within; central differences where none but the neighbours, and with ``window`` 0).

    With ``switch`` > 0, a point whose centred cubic fits worse (residual variance) than ``switch``
    times the better of the one-sided cubics over ``window`` behind and ahead of it (each over at
    least half as many points, and 6) takes that one's tangent: a path of arcs meeting with a jump
    of curvature (a member's ogee, G1 at its inflection) turned the centred fits' tangents there by
    1 deg; with noise the centred fit stays (its residual is the noise's, as the sides').

    Examples
    --------
    >>> a = np.linspace(0, 1, 50)
    >>> pts = np.column_stack([np.cos(a), np.sin(a), 0 * a])
    >>> tan = path_tangents(pts + np.random.default_rng(0).normal(0, 1e-4, (50, 3)), 0.2)
    >>> float(np.degrees(np.arccos(np.abs(np.einsum("ki,ki->k", tan, np.column_stack([-np.sin(a), np.cos(a),
    ...     0 * a]))).min()))) < 0.5
    True
    """
    x = np.asarray(points, float)
    k = len(x)
    s = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(x, axis=0), axis=1))]
    out = np.gradient(x, s if np.all(np.diff(s) > 0) else np.arange(k, dtype=float), axis=0)
    if window > 0:
        lo = np.searchsorted(s, s - window, side="left")
        hi = np.searchsorted(s, s + window, side="right")
        count = hi - lo

        def fits(at: IntArray, b0: IntArray, b1: IntArray, deg: int) -> tuple[Array, Array]:
            # polynomials of degree deg fitted to the points b0[j]:b1[j] about at[j] (arc length in window
            # units), all at once: their derivatives at ``at`` and their residual variances
            n = b1 - b0
            rows = b0[:, None] + np.arange(int(n.max()))[None, :]                  # (q, width)
            inside = rows < b1[:, None]
            rows = np.minimum(rows, k - 1)
            u = np.where(inside, (s[rows] - s[at, None]) / window, 0.0)
            a = (u[:, :, None] ** np.arange(deg + 1)[None, None, :]) * inside[:, :, None]
            y = x[rows] * inside[:, :, None]
            at_ = np.swapaxes(a, 1, 2)
            coef = np.linalg.solve(at_ @ a, at_ @ y)                               # (q, deg + 1, 3)
            res = y - a @ coef                                                     # 0 on the padding
            return coef[:, 1], np.einsum("qwi,qwi->q", res, res) / np.maximum(n - deg - 1, 1)

        # a cubic needs 5 points, a quadratic 4: the fits of each degree at once (least squares by the
        # normal equations, batched; in window units the powers are within 1, the equations well
        # conditioned; rows of zeros pad the windows to the longest, and change no fit)
        for deg, pick in ((3, count >= 5), (2, count == 4)):
            at = np.flatnonzero(pick)
            if not len(at):
                continue
            out[at], var = fits(at, lo[at], hi[at], deg)
            if switch <= 0 or deg != 3:
                continue
            # the one-sided cubics behind and ahead (each over at least half the window's points, and
            # 6): a side whose fit is ``switch`` times better takes over, the better side last
            half = np.maximum(6, (count[at] + 1) // 2)
            for b0, b1 in ((lo[at], at + 1), (at, hi[at])):
                ok = (count[at] >= 6) & (b1 - b0 >= half)
                if not ok.any():
                    continue
                tan, vs = fits(at[ok], b0[ok], b1[ok], 3)
                take = var[ok] > switch * vs
                sel = np.flatnonzero(ok)[take]
                out[at[sel]] = tan[take]
                var[sel] = switch * vs[take]
    out /= np.maximum(np.linalg.norm(out, axis=1, keepdims=True), 1e-300)
    result: Array = out
    return result


def _into_normal_planes(profile: Array, rot: Array, tr: Array, window: float,
                        switch: float = 0.0) -> tuple[Array, Array]:
    """Every knot's map turned about the moved centroid so that the profile's plane is normal to the centroid's path.

    The path's tangent is :func:`path_tangents` of the moved centroids over ``window``; the turn
    is the least one taking the plane's normal to it (``switch``: :func:`path_tangents`).
    """
    n0, _ = _plane_of(profile)
    c = rot @ profile.mean(axis=0) + tr
    vel = path_tangents(c, window, switch)
    nn = rot @ n0
    vel = np.where((np.einsum("ki,ki->k", vel, nn) < 0)[:, None], -vel, vel)
    ax = np.cross(nn, vel)
    sn = np.linalg.norm(ax, axis=1)
    ang = np.arctan2(sn, np.einsum("ki,ki->k", nn, vel))
    turn = rotations_of(np.ascontiguousarray(ax / np.maximum(sn, 1e-300)[:, None] * ang[:, None]))
    return turn @ rot, np.einsum("kij,kj->ki", turn, tr - c) + c


def knot_twists(profile: Array, rot: Array, tr: Array) -> tuple[Array, Array]:
    """Each knot's turn about its profile plane's normal against a frame carried along the normals, and arc lengths.

    The profile plane's normal at knot ``k`` is ``n_k = R_k n0``; a direction ``e`` in the profile's
    plane is carried from knot to knot by the least turn taking ``n_k`` to ``n_{k+1}`` (no turn
    about the normals: a rotation-minimising frame of the knots). Returns the angles ``(k,)``
    (radians, 0 at the first knot) by which each knot's map turns ``e`` about ``n_k`` beyond the
    carried direction, and the arc lengths ``(k,)`` of the moved centroids' polyline.
    """
    n0, _ = _plane_of(profile)
    e0 = np.cross(n0, np.eye(3)[int(np.argmin(np.abs(n0)))])
    e0 /= np.linalg.norm(e0)
    n, a = rot @ n0, rot @ e0
    c = rot @ profile.mean(axis=0) + tr
    s = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(c, axis=0), axis=1))]
    # a_k carried by the least turn n_k -> n_{k+1} (Rodrigues), then the signed angle to a_{k+1} about n_{k+1}
    n1, n2, a1 = n[:-1], n[1:], a[:-1]
    ax = np.cross(n1, n2)
    cos = np.einsum("ki,ki->k", n1, n2)
    carried = (a1 * cos[:, None] + np.cross(ax, a1)
               + ax * (np.einsum("ki,ki->k", ax, a1) / np.maximum(1.0 + cos, 1e-12))[:, None])
    step = np.arctan2(np.einsum("ki,ki->k", n2, np.cross(carried, a[1:])), np.einsum("ki,ki->k", carried, a[1:]))
    return np.r_[0.0, np.cumsum(step)], s


def smooth_twists(theta: Array, s: Array, window: float, rounds: int = 2) -> Array:
    """Robust local lines through the knots' twists ``theta (k,)`` at arc lengths ``s (k,)`` (LOWESS).

    At each knot, the line fitted by weighted least squares to the knots within ``window`` of arc
    length (tricube weights of the distance), its value there; then ``rounds`` times again with
    each knot's weight also times the biweight of its residual over 6 median absolute residuals
    (at least 1e-6 rad; a knot far off its neighbours, a grown end's, pulls no line). A line has no bias where the
    twist grows linearly along the path (a member's frames: 45 deg along tn-2's ogee); a knot with
    fewer than 3 knots of weight in its window keeps its twist.

    Examples
    --------
    >>> s = np.linspace(0, 1, 101)
    >>> noisy = 0.3 * s + np.random.default_rng(0).normal(0, 0.01, 101)
    >>> bool(np.abs(smooth_twists(noisy, s, 0.1) - 0.3 * s).std() < 0.5 * np.abs(noisy - 0.3 * s).std())
    True
    >>> bool(np.allclose(smooth_twists(0.3 * s, s, 0.1), 0.3 * s))
    True
    """
    k = len(theta)
    lo = np.searchsorted(s, s - window, side="left")
    hi = np.searchsorted(s, s + window, side="right")
    rows = lo[:, None] + np.arange(int((hi - lo).max(initial=1)))[None, :]
    inside = rows < hi[:, None]
    rows = np.minimum(rows, k - 1)
    u = np.where(inside, (s[rows] - s[:, None]) / window, 0.0)
    kern = np.where(inside, np.clip(1.0 - np.abs(u) ** 3, 0.0, None) ** 3, 0.0)
    y = theta[rows]
    robust = np.ones(k)
    out = theta.copy()
    for _ in range(rounds + 1):
        w = kern * robust[rows]
        s0, s1, s2 = w.sum(axis=1), (w * u).sum(axis=1), (w * u * u).sum(axis=1)
        t0, t1 = (w * y).sum(axis=1), (w * u * y).sum(axis=1)
        det = s0 * s2 - s1 * s1
        ok = ((w > 0).sum(axis=1) >= 3) & (det > 1e-12 * np.maximum(s0 * s2, 1e-300))
        out = np.where(ok, (s2 * t0 - s1 * t1) / np.where(ok, det, 1.0), theta)
        if not ok.any():
            break
        # a knot without a line keeps its weight; the scale never under 1e-6 rad (a point 0.01 from the
        # centroid moved by 1e-8): where the lines fit the knots exactly but for a few, rounding would cut the others
        res = np.abs(theta - out)[ok]
        scale = max(6.0 * float(np.median(res)), 1e-6)
        robust[ok] = np.clip(1.0 - (res / scale) ** 2, 0.0, None) ** 2
    result: Array = out
    return result


def _smoothed_twists(profile: Array, rot: Array, tr: Array, window: float) -> tuple[Array, Array, Array]:
    """Every knot's map turned about its profile plane's normal through the moved centroid to the smoothed twist.

    :func:`knot_twists`, :func:`smooth_twists` over ``window``; also returns the turns ``(k,)`` (radians).
    """
    theta, s = knot_twists(profile, rot, tr)
    turn = smooth_twists(theta, s, window) - theta
    n0, _ = _plane_of(profile)
    c = rot @ profile.mean(axis=0) + tr
    e = rotations_of(np.ascontiguousarray((rot @ n0) * turn[:, None]))
    return e @ rot, np.einsum("kij,kj->ki", e, tr - c) + c, turn


def refine_motion(profile: Array, motion: Motion, tree: MeshTree, params: SweepParams = DEFAULT) -> Motion:
    """Each knot's rigid map refined against the mesh about its profile plane (beyond the paper).

    The fit check bounds the largest distance by ``fit_factor * eps_prox``; a profile small
    against that (a member's square bar, 1.5-2 % of the diameter, against 1 % at eps_prox 0.005)
    fits turned the wrong way about the path, and the motion's turn about the profile plane's
    normal follows the ribs' errors (docs/sweeps.md, "Microarch members"). Here every knot's map
    is refined by ``twist_steps`` point-to-plane steps (ICP) of the moved profile's points to
    their closest mesh points, in the three freedoms the surface fixes: the turn about the
    plane's normal through the moved centroid and the shift within the plane (the plane itself,
    the profile's tilt and its place along the path, a prism's surface does not fix); then each
    map is turned so that the profile lies in the normal plane of its centroid's path (the
    convention of :func:`profile_planes`, the centroids now on the surface's path; its tangents
    by local cubic fits over ``tangent_window`` of arc length, :func:`path_tangents`) and refined
    by as many steps again. Small steps from the fitted maps: a symmetric profile does not jump
    to another of its alignments. Last, each knot's turn about its plane's normal (against a frame
    carried along the normals, :func:`knot_twists`) is set to a robust local line's through the
    knots' turns within ``twist_window`` of arc length (:func:`smooth_twists`): with noise each
    knot's turn follows the noisy faces about it (tn-2's member at sigma 5e-4: +-0.4 deg per knot).

    Parameters
    ----------
    profile : (n, 3) float array
        The profile at the motion's parameter 0 (its points are moved by the knots' maps).
    motion : Motion
    tree : MeshTree
        The mesh's closest points.
    params : SweepParams
        ``twist_steps`` (0: the motion unchanged), ``twist_tolerance`` (a knot whose step moves
        its points by less takes no more), ``fit_factor * eps_prox`` (points farther from the
        mesh do not count), ``tangent_window``, ``tangent_switch``, ``twist_window`` (0: no lines).

    Returns
    -------
    Motion
        The same knots with the refined maps.

    Examples
    --------
    A square tube along the x axis, its sweep turned 3 degrees about the path at every knot: turned back.

    >>> from auszug.sweeps.motion import rotation_about
    >>> side = np.linspace(-0.05, 0.05, 6)[:-1]
    >>> sq = np.column_stack([np.r_[side, 0.05 + 0 * side, -side, -0.05 + 0 * side],
    ...                       np.r_[-0.05 + 0 * side, side, 0.05 + 0 * side, -side]])
    >>> xs = np.linspace(-0.5, 0.5, 41)
    >>> v = np.column_stack([np.repeat(xs, 20), np.tile(sq[:, 0], 41), np.tile(sq[:, 1], 41)])
    >>> from auszug.sweeps.fixtures import grid_faces
    >>> g = grid_faces(41, 21)
    >>> f = (g // 21) * 20 + (g % 21) % 20
    >>> prof = np.column_stack([np.full(20, -0.4), sq])
    >>> t = np.arange(9.0)
    >>> rot = np.broadcast_to(rotation_about([1.0, 0, 0], np.radians(3.0)), (9, 3, 3))
    >>> wrong = Motion(t, rot, np.column_stack([0.1 * t, 0 * t, 0 * t]))
    >>> fixed = refine_motion(prof, wrong, MeshTree(v, f))
    >>> float(np.degrees(np.arccos((np.trace(fixed.rotation[4]) - 1) / 2))) < 1e-3
    True
    """
    if params.twist_steps <= 0 or len(profile) < 3:
        return motion
    return _refine_bounded(profile, motion, tree, params)[0]


def _refine_bounded(profile: Array, motion: Motion, tree: MeshTree,
                    params: SweepParams) -> tuple[Motion, Array, NDArray[np.bool_]]:
    """:func:`refine_motion` (``twist_steps`` > 0), its distance bounds, its unrefined knots.

    The bounds ``(k, n)`` are upper bounds of the moved profile's distances to the mesh at the
    refined knots (inf where unknown), for :func:`~auszug.sweeps.patches.swept_error`. The mask
    ``(k,)`` marks the knots the refinement left alone: each keeps its unrefined map, because the
    refined one turned farther than :data:`MAX_REFINE_TURN`.
    """
    bound = params.fit_factor * params.eps_prox
    tol = params.twist_tolerance
    r, t, _, faces = _twist_steps(profile, motion.rotation, motion.translation, tree, bound, params.twist_steps, tol)
    r, t = _into_normal_planes(profile, r, t, params.tangent_window, params.tangent_switch)
    r, t, upper, _ = _twist_steps(profile, r, t, tree, bound, params.twist_steps, tol, faces)
    if params.twist_window > 0 and len(r) >= 3:
        # each knot's twist follows the noisy faces about it: robust local lines along the path; a point moves
        # by at most the turn times its distance from the centroid, which bounds its distance to the mesh
        r, t, turn = _smoothed_twists(profile, r, t, params.twist_window)
        upper = upper + np.abs(turn)[:, None] * np.linalg.norm(profile - profile.mean(axis=0), axis=1)[None, :]
    # a knot turned farther than MAX_REFINE_TURN keeps its map (an end past the mesh, its centroid's path
    # bent by the end's few points; a symmetric profile sliding towards another alignment)
    cos = (np.einsum("kij,kij->k", r, motion.rotation) - 1) / 2
    far = cos < np.cos(np.radians(MAX_REFINE_TURN))
    r[far], t[far] = motion.rotation[far], motion.translation[far]
    upper[far] = np.inf
    return Motion(motion.t.copy(), r, t), upper, far


def motion_planes(profile: Array, motion: Motion, per_knot: int = 1) -> tuple[Array, Array]:
    """The profile planes (:func:`profile_planes`) at the motion's knots, ``per_knot`` per knot interval."""
    t = np.interp(np.arange((len(motion) - 1) * per_knot + 1) / per_knot, np.arange(len(motion)), motion.t)
    return profile_planes(profile, motion, t)


def _around(mesh: SweepMesh, points: Array, margin: float) -> tuple[SweepMesh, IntArray, IntArray]:
    """The part of the mesh whose faces lie in the box of ``points`` grown by ``margin``, its faces' indices.

    The part keeps the mesh's vertex array (its faces index it as before); only its faces and
    the edges of those faces are selected, so cutting it walks just the part, and nothing is
    recomputed but the index maps (no new topology, no new vertex normals). Also returns each of
    the mesh's edges' index among the part's ``(E,)`` (-1 for one not kept; for
    :meth:`~auszug.sweeps.cut.EdgeGrid.part`).
    """
    from dataclasses import replace

    lo, hi = points.reshape(-1, 3).min(axis=0) - margin, points.reshape(-1, 3).max(axis=0) + margin
    # one compiled pass: the kept faces and edges, their index maps and rows (numpy's fancy indexing took 0.5 ms
    # of a part of 20k faces)
    keep, _, edge_faces, face_edges, faces, edges, edge_index = box_part(mesh.vertices, mesh.faces, mesh.edges,
                                                                        mesh.edge_faces, mesh.face_edges, lo, hi)
    return replace(mesh, faces=faces, edges=edges, edge_faces=edge_faces, face_edges=face_edges), keep, edge_index


def _per_component(fams: tuple[Family, ...], mesh: SweepMesh, cuts: Cuts, mov: Movability,
                   plots: CurvaturePlots) -> list[Family]:
    """Every family split by the mesh component its members' cuts lie on (:func:`split_family`).

    A mesh of several pieces (the unwelded members of a curve network) has congruent cuts on each
    piece; one family of them orders ribs that jump between pieces, and no sweep fits them all
    (four members of U.XI.91: coverage 0.227 before, docs/sweeps.md).
    """
    comp = face_components(mesh)
    if len(fams) == 0 or comp.max(initial=0) == 0:
        return list(fams)
    edge = cuts.edges[cuts.curve_start[mov.run_curve[plots.run]]]      # per plot: its first point's edge
    of_plot = comp[mesh.edge_faces[edge, 0]]
    return [part for f in fams for part in split_family(f, of_plot[f.members])]


def general_stages(mesh: SweepMesh, cuts: Cuts, mov: Movability, params: SweepParams, step: Callable[[str], float],
                   true_planes: ArrayLike | None = None,
                   translations: bool = False) -> tuple[list[SweepPatch], list[Stage]]:
    """The stages match, families and motion on a non-kinematic mesh; patches and summaries.

    ``cuts`` and ``mov`` are the initial planes' cuts and their movability. Every movable run of
    them is matched (the longest ``max_match_runs``): ranking planes by gliding energy and
    refining around the best (:func:`~auszug.sweeps.search_planes`) misses the profile planes
    (docs/sweeps.md), while the families of the initial cuts with most support (members times
    the length of their common part) lie near them. With ``true_planes`` the motion stage also
    reports the plane recall of the fitted motions' profile planes. With ``translations`` (the
    cuts glide under one turn whose sweep does not fit: a translation along a curved path), each
    fitted sweep is also tried as a pure translation (:func:`translational_patch`), kept when it
    covers more within the fit bound.
    """
    stages: list[Stage] = []
    t = step("match")
    runs = np.arange(mov.n_runs, dtype=np.int64)
    if len(runs) > params.max_match_runs:
        runs = np.sort(np.argsort(-mov.run_length, kind="stable")[:params.max_match_runs])
    plots = curvature_plots(cuts, mov, runs, params)
    matches = match_cuts(plots, params)
    stages.append(Stage("match", time.perf_counter() - t,
                        f"{len(runs)} runs, {matches.tested} pairs within {params.match_angle:g} deg, "
                        f"{matches.n_matches} matched",
                        {"runs": len(runs), "pairs": matches.tested, "matches": matches.n_matches}))
    t = step("families")
    # support of a family: its members times the length of their common part
    fams = sorted(_per_component(families(matches, params), mesh, cuts, mov, plots),
                  key=lambda f: (-len(f.members) * f.length, -f.length))
    # most support first, but a family half of whose runs an earlier pick already holds is
    # skipped: the most supported families crowd the same stretch of a path
    big: list[Family] = []
    held: set[int] = set()
    for f in fams:
        if len(big) >= params.max_families:
            break
        runs_f = {int(x) for x in f.members}
        if len(runs_f) < 3 or len(runs_f & held) >= 0.5 * len(runs_f):
            continue
        big.append(f)
        held |= runs_f
    ribs = [order_ribs(f, plots, params) for f in big]
    ribs = [r for r in ribs if len(r.order) >= 3]
    stages.append(Stage("families", time.perf_counter() - t,
                        f"{len(fams)} families; the {len(ribs)} of most support with >= 3 ordered ribs tried "
                        f"(ribs: {', '.join(str(len(r.order)) for r in ribs) or 'none'})",
                        {"families": len(fams), "tried": len(ribs)}))
    t = step("motion")
    areas = face_areas(mesh.vertices, mesh.faces)
    total = float(areas.sum())
    out: list[SweepPatch] = []
    tree = MeshTree.of(mesh)
    grown = np.zeros(len(mesh.faces), bool)
    skipped = n_refined = dropped = 0
    whole_grid: EdgeGrid | None = None
    # a family's ordered ribs may jump across a gap (parallel cuts of two parallel stretches of a
    # border): each stretch between such jumps is fitted on its own
    stretches = [(q, r.family.closed) for r in ribs for q in split_ribs(rib_parts(r, plots), params.rib_jump)
                 if len(q) >= 3]
    for parts, closed in stretches:
        # a family whose ribs lie on what an earlier grown patch covers adds nothing
        if grown.any() and _held(tree, parts, grown, params.patch_overlap, params.twist_steps > 0):
            skipped += 1
            continue
        # the sweep between the first and the last rib stays near them: fit it to that part of the
        # mesh (distances to a part are never smaller than to the whole: the fit error is safe)
        sub, faces, edge_index = _around(mesh, parts, params.l_min / 4 + 4 * params.eps_prox)
        # the part's local cuts on the mesh's edge grid (binned once per stage): the same curves as on its own grid
        if whole_grid is None:
            whole_grid = EdgeGrid.of(mesh)
        fitted = _general_fit(sub, parts, params, areas[faces], tree, closed=closed, faces=False,
                              grid=whole_grid.part(edge_index))
        assert isinstance(fitted, tuple)
        g0, err0 = fitted
        bound = params.fit_factor * params.eps_prox
        refined = tried = False
        no_sweep = False            # the refinement kept no knot (_refined): not a sweep of this mesh
        if not params.grow and params.twist_steps > 0 and g0.fit_error <= bound:
            # the refined motion's fit replaces the fitted one's: the latter's covered faces are found only if
            # the refinement fails (the same sweeps, one search of the covered faces less)
            got, refined = _refined(mesh, g0, params, tree, areas)
            no_sweep = got is None
            g = g0 if got is None else got
            tried = True
        if not refined:
            g = _covered(sub, g0.profile, g0.motion, g0.velocities, err0, params, areas[faces], closed)
            g = GeneralSweep(g.profile, g.motion, g.velocities, g.fit_error,
                             float(areas[faces[g.faces]].sum() / total) if total > 0 else 0.0, faces[g.faces], closed)
        if params.grow and g.fit_error <= bound:
            g = grown_patch(mesh, g, params, tree, areas)
        if params.twist_steps > 0 and g.fit_error <= bound and not tried:
            got, refined = _refined(mesh, g, params, tree, areas)
            no_sweep = got is None
            g = g if got is None else got
        if translations and not closed:
            tp = translational_patch(mesh, g.profile, g.motion, params, tree, areas)
            if tp is not None and tp.fit_error <= params.fit_factor * params.eps_prox and (
                    no_sweep or tp.coverage > g.coverage):
                g, refined, no_sweep = tp, False, False
        if no_sweep:
            dropped += 1
            continue
        n_refined += refined
        if g.fit_error <= params.fit_factor * params.eps_prox:
            grown[g.faces] = True
            if params.corner_tolerance > 0 and g.closed:     # after: the families skipped stay the same
                g = _filled(mesh, g, params, tree, areas)
        out.append(SweepPatch(len(out), "general", g.profile, g.closed, g.motion, g.faces, g.fit_error, g.coverage))
    numbers: dict[str, float | int] = {"candidates": len(out), "refined": n_refined, "dropped": dropped}
    summary = (f"{len(out)} general sweep(s) fitted ({skipped} families on grown patches skipped, {n_refined} "
               f"motion(s) refined against the mesh, {dropped} dropped: every knot's profile plane off its path's "
               f"normal plane by more than {MAX_REFINE_TURN:g} deg)") + (
        ": fit errors " + ", ".join(f"{p.fit_error:.2e}" for p in out) if out else "")
    if true_planes is not None and len(np.asarray(true_planes)):
        found = [motion_planes(p.profile, p.motion) for p in out]
        n = np.vstack([f[0] for f in found]) if found else np.zeros((0, 3))
        d = np.concatenate([f[1] for f in found]) if found else np.zeros(0)
        numbers["recall"] = plane_recall(true_planes, n, d)
    stages.append(Stage("motion", time.perf_counter() - t, summary, numbers))
    return out, stages


#: :func:`_held` takes the faces within this distance of a point's nearest (normalised coordinates) for the
#: faces a closest-point search may answer at ties: far above the searches' round-off (1e-16), far below an edge.
TIE_MARGIN = 1e-9


def _held(tree: MeshTree, parts: Array, grown: NDArray[np.bool_], overlap: float, grid: bool) -> bool:
    """Whether the closest points of at least ``overlap`` of ``parts (..., 3)`` lie on grown faces (``grown (m,)``).

    A closest point on an edge or at a vertex lies on every face around it
    (:meth:`~auszug.sweeps.patches.MeshTree.on_faces`): the answer does not depend on which of them
    a search returns at a tie. With ``grid`` (the tree's face grid is built) the points' nearest
    faces are found on the grid first (:func:`~auszug.sweeps._kernels.grown_states`): a point whose
    faces within :data:`TIE_MARGIN` of its nearest are all grown (none) is on (off) the grown faces;
    the tree is asked only where the points of a mixed answer could decide (fewer queries: most
    families held by a grown patch are held wholly).
    """
    if grid:
        lo, dims, h, start, entries, fbox = tree.face_grid()
        st = grown_states(np.ascontiguousarray(parts.reshape(-1, 3), dtype=float), grown, tree.vertices,
                          tree.faces, lo, dims, h, start, entries, fbox, TIE_MARGIN)
        n, on, unknown = len(st), int(np.sum(st == 1)), int(np.sum(st < 0))
        # the share as np.mean gives it: an integer count over n, rounded once
        if on / n >= overlap:
            return True
        if (on + unknown) / n < overlap:
            return False
    return float(np.mean(tree.on_faces(parts.reshape(-1, 3), grown))) >= overlap


def _refined(mesh: SweepMesh, g: GeneralSweep, params: SweepParams, tree: MeshTree,
             areas: Array) -> tuple[GeneralSweep | None, bool]:
    """``g`` with its motion refined (:func:`refine_motion`) and checked again, if it still fits; else ``g``.

    None when the refinement kept no knot: the mesh turns every knot's profile plane farther than
    :data:`MAX_REFINE_TURN` (into the normal plane of its path and about it), so its profile
    planes lie nowhere near the path's normal planes. Such a "sweep" moves its profile mostly
    within its own plane, and its swept surface overlaps itself: the fit check's reciprocal test
    (:meth:`~auszug.sweeps.patches.MeshTree.interior_distance`) then counts every swept point
    farther than ``eps_prox`` from the mesh as beyond it (the closest mesh point lies on another
    part of the swept surface), so its fit error is ``eps_prox`` or less whatever the sweep
    (the tracery border's coarse pass: a profile doubling back on itself, 4.997e-3 against 0.021
    without the reciprocal test, its planes 11-90 deg off its path's normal planes).
    """
    if len(g.profile) >= 3:
        motion, upper, far = _refine_bounded(g.profile, g.motion, tree, params)
        if far.all():
            return None, False
    else:
        motion, upper = g.motion, None
    # the same fit error as without the bounds, fewer closest points (swept_error)
    err = swept_error(g.profile, g.closed, motion, params.eps_prox, tree, upper, params.reciprocal_angle)
    if err.fit_error > params.fit_factor * params.eps_prox:
        return g, False
    fit = swept_coverage(mesh, err, params.eps_prox, areas, distances=False)
    return GeneralSweep(g.profile, motion, g.velocities, fit.fit_error, fit.coverage, fit.faces, g.closed), True


def _filled(mesh: SweepMesh, g: GeneralSweep, params: SweepParams, tree: MeshTree, areas: Array) -> GeneralSweep:
    """``g`` with the corners its profile's chords cut off put back (:func:`~auszug.sweeps.patches.fill_corners`).

    Once, on the finished sweep: the mesh recut at its knots (:func:`_recut_knots`), the pieces of
    the knots off the profile left out (:func:`~auszug.sweeps.patches.consistent_pieces`), the
    corners inserted; kept if the sweep still fits and covers no less (else ``g``). Only closed
    profiles are filled (a member's bar): on the tracery window a filled open profile covered more
    and the fit stage dropped another patch under it (19 -> 18 patches, the lancet mouldings'
    whole faces 0.924 -> 0.897). Inserted in every round of
    :func:`general_patch` instead, the profile's new points changed the rounds that follow: the
    tracery border's general stage then kept a sweep wandering 4 diameters along (0.028 of the
    area), and tn-2's member at sigma 5e-4 kept a patch half as long (coverage 1.000 -> 0.941).
    """
    back, starts, knot = _recut_knots(mesh, g.profile, g.motion, 4 * params.eps_prox)
    back, starts, knot = consistent_pieces(g.profile, g.closed, back, starts, knot, params.piece_trim)
    profile, added = fill_corners(g.profile, g.closed, back, starts, params.corner_tolerance, params.eps_prox / 2)
    if not len(added):
        return g
    err = swept_error(profile, g.closed, g.motion, params.eps_prox, tree, angle=params.reciprocal_angle)
    if err.fit_error > params.fit_factor * params.eps_prox:
        return g
    fit = swept_coverage(mesh, err, params.eps_prox, areas, distances=False)
    if fit.coverage < g.coverage:
        return g
    return GeneralSweep(profile, g.motion, g.velocities, fit.fit_error, fit.coverage, fit.faces, g.closed)


# --- growing a patch along its motion and across its profile ---------------------------------------------------


def _compose(step: tuple[Array, Array], m: tuple[Array, Array]) -> tuple[Array, Array]:
    """The map ``step o m`` of two rigid maps ``(R, T)``."""
    return step[0] @ m[0], step[0] @ m[1] + step[1]


def _step(a: tuple[Array, Array], b: tuple[Array, Array], h: float = 1.0) -> tuple[Array, Array]:
    """``(b a^-1)^h``: the rigid step taking map ``a`` to map ``b``, scaled along its screw by ``h``."""
    from auszug.sweeps.motion import se3_exp

    r = b[0] @ a[0].T
    t = b[1] - r @ a[1]
    if h == 1.0:
        return r, t
    w, v = se3_log(r, t)
    return se3_exp(h * w, h * v)


def _nearest_curve(c: Cuts, plane: int, target: Array) -> tuple[Array, Array] | None:
    """The cut curve of ``plane`` closest to ``target (n, 3)`` (median distance), or None.

    Returns its points and an ``(n, 4)`` array: the distance of each target point to it and its
    closest point there.
    """
    best: tuple[float, Array, Array, Array] | None = None
    for j in np.flatnonzero(c.curve_plane == plane):
        q = c.curve(int(j))
        if len(q) < 2:
            continue
        if bool(c.curve_closed[j]):
            q = np.vstack([q, q[:1]])
        dist, cp = _on_polyline(target, q)
        if best is None or float(np.median(dist)) < best[0]:
            best = (float(np.median(dist)), q, dist, cp)
    return None if best is None else (best[1], np.stack([best[2], *best[3].T], axis=1))


def _closest_on_cut(c: Cuts, plane: int, target: Array) -> tuple[Array, Array, NDArray[np.bool_]] | None:
    """Closest points of ``target (n, 3)`` on all cut curves of ``plane`` together, or None if it has none.

    Returns the distances ``(n,)``, the closest points ``(n, 3)`` and whether each closest point
    is an end of an open curve ``(n,)``: a cut curve ends only on the mesh's boundary, so a point
    farther than the tolerance from its cut there lies beyond the mesh (past its end, over a hole).
    Where a hole splits the cut into pieces, every target point finds its own piece. One compiled
    pass over the plane's curves (:func:`~auszug.sweeps._kernels.closest_on_plane_curves`).
    """
    dist, cp, at_end = closest_on_plane_curves(np.ascontiguousarray(target, dtype=float), c.points, c.curve_start,
                                               c.curve_plane, c.curve_closed, plane)
    return None if not np.isfinite(dist).any() else (dist, cp, at_end)


def trajectory_error(profile: Array, motion: Motion, tree: MeshTree, tol: float = 0.0,
                     angle: float = DEFAULT.reciprocal_angle) -> Array:
    """Largest distance ``(n,)`` to the mesh of each profile point's path (at the knots and between them).

    Positions beyond the mesh do not count: closest point on its boundary (past its end, over a
    hole), or, when farther than ``tol``, on another part of the swept surface that lies along the
    mesh there (within ``angle`` degrees, :meth:`~auszug.sweeps.patches.MeshTree.interior_distance`).
    """
    t = np.sort(np.concatenate([motion.t, (motion.t[:-1] + motion.t[1:]) / 2]))
    x = motion.apply(profile, t)
    d = tree.interior_distance(x.reshape(-1, 3), RingTree(x), tol, angle).reshape(len(t), len(profile))
    out: Array = d.max(axis=0)
    return out


def _longest_run(ok: NDArray[np.bool_]) -> tuple[int, int]:
    """Start and end (exclusive) of the longest run of True (0, 0 if none)."""
    best, start, cur = (0, 0), 0, False
    for i, v in enumerate(list(ok) + [False]):
        if v and not cur:
            start = i
        if not v and cur and i - start > best[1] - best[0]:
            best = (start, i)
        cur = bool(v)
    return best


def extend_profile(mesh: SweepMesh, profile: Array, motion: Motion, tree: MeshTree, params: SweepParams) -> Array:
    """The profile extended to the whole cut curve it is part of, then trimmed to what the motion sweeps.

    The mesh is cut by the profile plane (:func:`profile_planes`) at the knots a quarter, half
    and three quarters along the motion; at each, the cut curve nearest the moved profile is mapped
    back (the whole curve, resampled at ``match_spacing``) and cut down to the longest stretch of
    points whose paths stay within ``eps_prox`` of the mesh (:func:`trajectory_error`). The
    longest of the three is returned, or ``profile`` itself when none is longer (one cut may
    cross a hole in the mesh).
    """
    from auszug.sweeps.matching import resample

    def length(p: Array) -> float:
        return float(np.linalg.norm(np.diff(p, axis=0), axis=1).sum())

    best = profile
    k = len(motion.t)
    for tm in sorted({float(motion.t[min(k - 1, (q * (k - 1)) // 4)]) for q in (2, 1, 3)}):
        r, tr = motion.at([tm])
        moved = profile @ r[0].T + tr[0]
        c = cut(mesh, *profile_planes(profile, motion, [tm]))
        got = _nearest_curve(c, 0, moved)
        if got is None:
            continue
        curve = resample(got[0], params.match_spacing)
        if len(curve) < 2:
            continue
        back = (curve - tr[0]) @ r[0]
        # keep the orientation of the old profile
        if np.linalg.norm(back[0] - profile[0]) + np.linalg.norm(back[-1] - profile[-1]) > \
                np.linalg.norm(back[-1] - profile[0]) + np.linalg.norm(back[0] - profile[-1]):
            back = back[::-1]
        traj = trajectory_error(back, motion, tree, params.eps_prox, params.reciprocal_angle)
        a, b = _longest_run(traj <= params.eps_prox)
        if b - a >= 2 and length(back[a:b]) > length(best):
            best = back[a:b]
    return best


@dataclass(frozen=True)
class GrownRibs:
    """Ribs of a sweep grown along its path (:func:`grow_ribs`).

    Attributes
    ----------
    ribs : (k, n, 3) float array
        Sample ``j`` of every rib corresponds to profile point ``j``.
    t : (k,) float array
        Their parameters, increasing from 0: one per step, a fraction for a last step that ends at
        the mesh's end.
    """

    ribs: Array
    t: Array

    def __len__(self) -> int:
        return len(self.ribs)


def grow_ribs(mesh: SweepMesh, profile: Array, motion: Motion, params: SweepParams = DEFAULT) -> GrownRibs:
    """Ribs of the sweep continued past both ends of its motion while the mesh follows.

    Starting from the maps at the motion's integer parameters, each end is extrapolated by the
    last rib step (the same screw again), the mesh cut there by the plane through the moved
    profile's centroid normal to the centroid's path (as :func:`profile_planes`; the path's
    tangent from a parabola through the last two centroids and this one), and
    the moved profile's closest points on the nearest cut curve taken as the next rib when at
    least ``grow_share`` of the points on the mesh lie within ``grow_tolerance * eps_prox`` and at
    least ``grow_on_mesh`` of all are on it (the others lie beyond the mesh, over a hole or past
    its end: their closest cut point is an end of a cut curve; the rib's map is corrected to the
    near points, Kabsch, and the cut repeated with it: 4 rounds, as in ICP). The seeds are the
    motion's maps evenly spaced along the centroid's path, one median rib step apart. A failed
    full step is retried as 2 .. ``grow_skip + 1`` steps at once (over a gap in the mesh; the ribs
    in between are the moved profile), then bisected for the farthest fraction of a step that
    fits (to ``eps_prox / 2``), the last rib (the mesh's end); at most ``grow_steps`` ribs are
    added at each end. Sample ``j`` of every rib corresponds to profile point ``j``.
    """
    lo, hi = motion.domain
    ts = lo + np.arange(int(round(hi - lo)) + 1, dtype=float)
    r, tr = motion.at(ts)
    centre = profile.mean(axis=0)
    # seeds: the maps at the ribs, less end steps unlike the others (a rib out of place in its family
    # gives a step of twice the length or turn; extrapolated, it leaves the surface at once)
    cs = np.einsum("kij,j->ki", r, centre) + tr
    length = np.linalg.norm(np.diff(cs, axis=0), axis=1)
    turn = np.arccos(np.clip((np.einsum("kij,kij->k", r[1:], r[:-1]) - 1) / 2, -1.0, 1.0))
    odd = (np.abs(length - np.median(length)) > 0.4 * np.median(length)) | (turn > 2 * np.median(turn) + 1e-3)
    a, b = 0, len(ts)
    while b - a > 3 and odd[a]:
        a += 1
    while b - a > 3 and odd[b - 2]:
        b -= 1
    # the seeds evenly spaced along the centroid's path, one median step apart: a family's ribs
    # (cuts by initial planes) lie unevenly, and the refit puts its ribs at t = 0, 1, 2, ...
    fine = np.linspace(ts[a], ts[b - 1], 32 * (b - a) + 1)
    arc = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(motion.apply(centre[None], fine)[:, 0], axis=0), axis=1))]
    n_steps = max(2, int(round(arc[-1] / max(float(np.median(length[a:b - 1])), 1e-12))))
    tu = np.interp(np.linspace(0.0, arc[-1], n_steps + 1), arc, fine)
    r, tr = motion.at(tu)
    maps = [(r[i], tr[i]) for i in range(len(tu))]
    tol = params.grow_tolerance * params.eps_prox

    def tangent(c0: Array, c1: Array, c2: Array) -> Array:
        """Unit tangent at ``c2`` of the parabola through three centroids (chord-length parameters)."""
        s1 = float(np.linalg.norm(c1 - c0))
        s2 = s1 + float(np.linalg.norm(c2 - c1))
        if s1 <= 0 or s2 <= s1:
            d = c2 - c1
        else:
            d = (c0 * (s2 - s1) / (s1 * s2) - c1 * s2 / (s1 * (s2 - s1)) + c2 * (2 * s2 - s1) / (s2 * (s2 - s1)))
        out: Array = d / max(float(np.linalg.norm(d)), 1e-300)
        return out

    def try_at(m: tuple[Array, Array], c0: Array, c1: Array) -> tuple[Array, tuple[Array, Array]] | None:
        for k in range(4):
            # the profile plane there (our convention, profile_planes): through the moved centroid, normal
            # to the centroid's path, continued by a parabola through the last two centroids (the
            # rotations of extrapolated steps drift; the centroids' path does not); then the map is
            # corrected to the closest points (Kabsch) and the cut repeated, as in ICP
            moved = profile @ m[0].T + m[1]
            c2 = centre @ m[0].T + m[1]
            nm = tangent(c0, c1, c2)
            c = cut(mesh, nm[None], np.array([nm @ c2]))
            got = _closest_on_cut(c, 0, moved)
            if got is None:
                return None
            dist, cp, at_end = got
            # points whose closest cut point is an end of a cut curve, farther than end_gap eps_prox (a profile's
            # own end point lies at one), lie beyond the mesh (over a hole, past its end): they count
            # neither for nor against the step, and are no correspondences for the map
            on = ~(at_end & (dist > params.end_gap * params.eps_prox))
            near = (dist <= (4 * tol if k == 0 else tol)) & on
            if on.mean() < params.grow_on_mesh or near.sum() < max(3.0, 0.5 * on.sum()):
                return None
            # where the mesh ends before the profile does, the closest points pile up at the cut's end:
            # the map is fitted to the others, and those samples take the moved profile's points
            m = kabsch(profile[near], cp[near])
        if near.sum() < params.grow_share * on.sum():
            return None
        return np.where(near[:, None], cp, profile @ m[0].T + m[1]), m

    def grow(seq: list[tuple[Array, Array]]) -> list[tuple[Array, float]]:
        out: list[tuple[Array, float]] = []     # ribs and their steps (1, or the fraction of the last)
        for _ in range(params.grow_steps):
            if len(seq) < 2:
                break
            got = None
            c0, c1 = (centre @ seq[-2][0].T + seq[-2][1]), (centre @ seq[-1][0].T + seq[-1][1])
            # a full step; then 2 .. grow_skip + 1 at once (over a gap in the mesh)
            for h in range(1, params.grow_skip + 2):
                got = try_at(_compose(_step(seq[-2], seq[-1], float(h)), seq[-1]), c0, c1)
                if got is not None:
                    break
            if got is None:
                # the mesh ends within the step: bisect for the farthest fraction of it that still fits
                # (to eps_prox / 2 along the path), the last rib
                lo_f, hi_f, last = 0.0, 1.0, None
                span = float(np.linalg.norm(c1 - c0))
                while (hi_f - lo_f) * span > params.eps_prox / 2 and hi_f - lo_f > 1e-3:
                    f = (lo_f + hi_f) / 2
                    tried = try_at(_compose(_step(seq[-2], seq[-1], f), seq[-1]), c0, c1)
                    if tried is None:
                        hi_f = f
                    else:
                        lo_f, last = f, tried
                if last is not None:
                    out.append((last[0], lo_f))
                break
            # over a gap of h steps, the ribs in between are the profile moved along the step's screw (the
            # mesh says nothing there): the ribs stay one step apart, as the refit's parameters assume
            for j in range(1, h):
                m = _compose(_step(seq[-1], got[1], j / h), seq[-1])
                out.append((profile @ m[0].T + m[1], 1.0))
            out.append((got[0], 1.0))
            seq.append(got[1])
            if h > 1:
                # the next step extrapolates the last one: make it one step long again
                seq[-2] = _compose(_step(seq[-2], seq[-1], 1.0 - 1.0 / h), seq[-2])
        return out

    ahead = grow(list(maps))
    behind = grow(list(maps[::-1]))
    # the motion's own ribs re-cut as well: the profile may have grown beyond what it was fitted to
    again = reslice(mesh, profile, motion, params.end_gap * params.eps_prox, tu, _far(params))
    middle = list(again) if again is not None else [profile @ m[0].T + m[1] for m in maps]
    t_mid = np.arange(len(middle), dtype=float)
    t_ahead = t_mid[-1] + np.cumsum([h for _, h in ahead])
    t_behind = -np.cumsum([h for _, h in behind])[::-1]
    t = np.concatenate([t_behind, t_mid, t_ahead])
    ribs = np.stack([r for r, _ in behind[::-1]] + middle + [r for r, _ in ahead])
    return GrownRibs(ribs, t - t[0])


def grown_patch(mesh: SweepMesh, g: GeneralSweep, params: SweepParams, tree: MeshTree,
                areas: Array | None = None) -> GeneralSweep:
    """A fitted general sweep grown across its profile and along its path, or ``g`` itself.

    Grown across its profile by :func:`extend_profile`, along its path by :func:`grow_ribs`,
    refitted (:func:`general_patch`, 2 rounds: one re-slicing) and its profile trimmed again to
    the points whose paths stay within ``eps_prox``. Returns ``g`` when the grown sweep covers no
    more or fits worse than ``fit_factor * eps_prox``. A closed profile is neither grown across
    nor trimmed (either would open it).
    """
    profile = g.profile if g.closed else extend_profile(mesh, g.profile, g.motion, tree, params)
    grown = grow_ribs(mesh, profile, g.motion, params)
    if len(grown) < 2:
        return g
    h = general_patch(mesh, grown.ribs, params.with_(general_iterations=2), areas, tree, grown.t, g.closed)
    traj = trajectory_error(h.profile, h.motion, tree, params.eps_prox, params.reciprocal_angle)
    a, b = _longest_run(traj <= params.eps_prox)
    if b - a >= 2 and b - a < len(h.profile) and not h.closed:    # a closed profile is kept whole
        fit = fit_patch(mesh, h.profile[a:b], False, h.motion, params, areas, tree)
        h = GeneralSweep(h.profile[a:b], h.motion, h.velocities, fit.fit_error, fit.coverage, fit.faces)
    if h.coverage <= g.coverage or h.fit_error > params.fit_factor * params.eps_prox:
        return g
    return h


def _translate(mesh: SweepMesh, p0: Array, m: Array, d0: float, params: SweepParams, tree: MeshTree,
               areas: Array | None) -> GeneralSweep | None:
    """The translational sweep of ``p0 (n, 3)`` (in the plane ``m . x = d0``) over the mesh's parallel cuts, or None.

    See :func:`translational_patch`.
    """
    tol = params.grow_tolerance * params.eps_prox
    step = params.translation_step

    def place(offset: Array, d_plane: float) -> Array | None:
        cc = cut(mesh, m[None], np.array([d_plane]))
        ok = np.zeros(len(p0), bool)
        on = np.ones(len(p0), bool)
        for _ in range(3):
            got = _closest_on_cut(cc, 0, p0 + offset)
            if got is None:
                return None
            dist, cp, at_end = got
            # points whose closest cut point is an end of a cut curve, and far, lie beyond the mesh (over a
            # hole, past its end): neither for nor against the cut, and no correspondences (as grow_ribs)
            on = ~(at_end & (dist > params.end_gap * params.eps_prox))
            near = (dist <= 4 * tol) & on
            if on.mean() < params.grow_on_mesh or near.sum() < max(3.0, 0.5 * on.sum()):
                return None
            offset = (cp[near] - p0[near]).mean(axis=0)
            ok = (dist <= tol) & on
        return offset if ok.sum() >= params.grow_share * on.sum() else None

    offsets = {0: np.zeros(3)}
    for sign in (1, -1):
        prev, before = np.zeros(3), np.zeros(3)
        for k in range(1, params.translation_steps + 1):
            guess = prev + (prev - before) if k > 1 else prev + sign * step * m
            got_k = place(guess, float(d0 + sign * k * step))
            if got_k is None:
                break
            before, prev = prev, got_k
            offsets[sign * k] = got_k
    keys = sorted(offsets)
    if len(keys) < 3:
        return None
    shifts = np.array([offsets[k] for k in keys])
    start = p0 + shifts[0]
    rot = np.repeat(np.eye(3)[None], len(keys), axis=0)
    mot = Motion(np.arange(len(keys), dtype=float), rot, shifts - shifts[0])
    start = improve_flat(start, *_recut(mesh, start, mot, 4 * params.eps_prox), params.eps_prox)
    a, b = _longest_run(trajectory_error(start, mot, tree, params.eps_prox, params.reciprocal_angle) <= params.eps_prox)
    if b - a < 2:
        return None
    start = start[a:b]
    fit = fit_patch(mesh, start, False, mot, params, areas, tree)
    return GeneralSweep(start, mot, np.zeros((len(keys), 6)), fit.fit_error, fit.coverage, fit.faces)


def _longest_cut(mesh: SweepMesh, normal: Array, offsets: Array, near: Array, spacing: float) -> Array | None:
    """The longest of the cut curves nearest ``near (k, n, 3)[i]`` in the planes ``normal . x = offsets[i]``.

    Resampled at ``spacing``; None if no plane meets the mesh there.
    """
    from auszug.sweeps.matching import resample

    c = cut(mesh, np.repeat(normal[None], len(offsets), axis=0), offsets)
    best: Array | None = None
    for i in range(len(offsets)):
        got = _nearest_curve(c, i, near[i])
        if got is None:
            continue
        p = resample(got[0], spacing)
        if len(p) >= 2 and (best is None or len(p) > len(best)):
            best = p
    return best


def translational_patch(mesh: SweepMesh, profile: Array, motion: Motion, params: SweepParams, tree: MeshTree,
                        areas: Array | None = None) -> GeneralSweep | None:
    """A sweep by pure translations along a curved path (a double translational surface), or None.

    A translation along an arch glides like a turn, and a general sweep fitted to it turns. Here
    the profile is the longest of the cuts by a general sweep's profile planes at the knots a
    quarter, half and three quarters along (the nearest cut curve; one may cross a hole), and the
    mesh is cut by planes *parallel* to it, ``translation_step`` apart on both sides while the mesh
    follows (at most ``translation_steps`` on each); on each the profile is moved by
    translations only (3 rounds of closest points, the mean offset), and a cut counts when
    ``grow_share`` of the moved profile's points on the mesh lie within ``grow_tolerance *
    eps_prox`` of it (points whose closest cut point is a far end of a cut curve lie beyond the
    mesh, over a hole or past its end, and count neither way; at least ``grow_on_mesh`` must be
    on it). The motion is the translations at the cuts (rotation the identity), the profile
    improved and fitted as in :func:`general_patch`.

    A general sweep's profile plane (normal to its centroid's path there) is tilted against the
    profile's own plane by the path's slope, and the cuts by tilted planes are no translates of
    each other. So the sweep is found again with planes normal to the chord of the translations
    found (from end to end of the path; the profile's plane of a sweep along a symmetric arch), at
    most twice; the new planes are kept while their sweep fits within ``fit_factor * eps_prox``
    and covers at least the old one's coverage less ``chord_slack`` (on noisy meshes the tilted
    planes' sweep covers a little more by chance: 0.987 against 0.974 at sigma 5e-4, 2.1 and 0.06
    deg off x = const).
    """
    k = len(motion.t)
    tms = [float(motion.t[min(k - 1, (q * (k - 1)) // 4)]) for q in (2, 1, 3)]
    r, tr = motion.at(tms)
    n, d = profile_planes(profile, motion, tms)
    m = n[0]
    # the planes at the three knots, made parallel to the middle one
    p0 = _longest_cut(mesh, m, np.einsum("j,kj->k", m, np.einsum("kij,j->ki", r, profile.mean(axis=0)) + tr),
                      np.einsum("kij,nj->kni", r, profile) + tr[:, None], params.match_spacing)
    if p0 is None:
        return None
    best = _translate(mesh, p0, m, float(m @ p0.mean(axis=0)), params, tree, areas)
    for _ in range(2):
        if best is None:
            break
        chord = best.motion.translation[-1] - best.motion.translation[0]
        if np.linalg.norm(chord) <= 0:
            break
        m_new = chord / np.linalg.norm(chord)
        if abs(float(m_new @ m)) >= np.cos(np.radians(0.05)):
            break
        # the profile again, in planes normal to the chord through the path a quarter, half and three
        # quarters along
        moved = best.profile[None] + best.motion.translation[[len(best.motion) // 4, len(best.motion) // 2,
                                                              (3 * len(best.motion)) // 4]][:, None]
        p1 = _longest_cut(mesh, m_new, moved.mean(axis=1) @ m_new, moved, params.match_spacing)
        if p1 is None:
            break
        again = _translate(mesh, p1, m_new, float(m_new @ p1.mean(axis=0)), params, tree, areas)
        if again is None or again.coverage < best.coverage - params.chord_slack or \
                again.fit_error > params.fit_factor * params.eps_prox:
            break
        best, m = again, m_new
    return best
