"""The batched and compiled pieces of the general-sweep build (sweeps8) against plain references.

Each batched function must give what its one-at-a-time definition gives: velocities rib by rib
(Eq. 7), Kabsch map by map (including mirror data), the profile improvement as the mean of
closest points found by brute force over every segment, and the motion exactly at its knots.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from auszug.sweeps.general import kabsch, kabsch_batch, rib_velocities, rib_velocity
from auszug.sweeps.motion import Motion, screw_motion
from auszug.sweeps.patches import _improve, improve_flat


@pytest.mark.parametrize("with_normals", [False, True])
@pytest.mark.parametrize("times", [None, [0.0, 0.5, 2.0, 2.25, 4.0]])
def test_rib_velocities_are_the_velocity_of_each_rib(with_normals, times):
    rng = np.random.default_rng(3)
    parts = rng.normal(size=(5, 20, 3)) * 0.1 + np.arange(5)[:, None, None] * [0.05, 0.0, 0.02]
    nr = rng.normal(size=(5, 20, 3))
    nr /= np.linalg.norm(nr, axis=2, keepdims=True)
    tt = np.arange(5.0) if times is None else np.asarray(times)
    want = np.array([rib_velocity(parts[i], [(parts[j], tt[j] - tt[i]) for j in (i - 1, i + 1) if 0 <= j < 5],
                                  nr[i] if with_normals else None) for i in range(5)])
    got = rib_velocities(parts, nr if with_normals else None, times=None if times is None else tt)
    assert np.allclose(got, want, rtol=1e-12, atol=1e-12)


def test_kabsch_batch_is_kabsch_map_by_map_and_proper():
    rng = np.random.default_rng(4)
    p = rng.normal(size=(12, 3))
    r0 = Rotation.random(6, random_state=5).as_matrix()
    q = np.einsum("kij,nj->kni", r0, p) + rng.normal(size=(6, 1, 3)) + rng.normal(size=(6, 12, 3)) * 0.01
    q[5] = p * [1.0, 1.0, -1.0]                                  # mirror data: still a proper rotation
    r, t = kabsch_batch(p, q)
    for k in range(6):
        rk, tk = kabsch(p, q[k])
        assert np.allclose(r[k], rk, atol=1e-12) and np.allclose(t[k], tk, atol=1e-12)
    assert np.allclose(np.linalg.det(r), 1.0)
    # per-pair form: p (k, n, 3)
    r2, t2 = kabsch_batch(np.broadcast_to(p, q.shape), q)
    assert np.allclose(r2, r, atol=1e-14) and np.allclose(t2, t, atol=1e-14)


def _improve_reference(profile, pieces, reach, end_reach):
    """Every profile point against every segment of every piece (numpy, no pruning)."""
    acc = profile.copy()
    count = np.ones(len(profile))
    for q in pieces:
        if len(q) < 2:
            continue
        a, b = q[:-1], q[1:]
        ab = b - a
        w = np.einsum("si,si->s", ab, ab)
        f = np.clip(np.einsum("nsi,si->ns", profile[:, None] - a, ab) / np.where(w > 0, w, 1.0), 0.0, 1.0)
        c = a + f[..., None] * ab                                 # (n, s, 3)
        d = np.linalg.norm(profile[:, None] - c, axis=2)
        j = np.argmin(d, axis=1)                                  # the first of equal distances
        dj = d[np.arange(len(profile)), j]
        cj = c[np.arange(len(profile)), j]
        at_end = (np.linalg.norm(cj - q[0], axis=1) <= 1e-12) | (np.linalg.norm(cj - q[-1], axis=1) <= 1e-12)
        ok = (dj <= reach) & (~at_end | (dj <= end_reach))
        acc[ok] += cj[ok]
        count[ok] += 1
    return acc / count[:, None]


@pytest.mark.parametrize("end_reach", [np.inf, 0.004, 0.0])
def test_improve_is_the_mean_of_brute_force_closest_points(end_reach):
    rng = np.random.default_rng(6)
    s = np.linspace(0, 1, 60)
    profile = np.stack([s, 0.1 * np.sin(6 * s), 0 * s], axis=1)
    pieces = []
    for k in range(12):                   # noisy copies, some long (many chunks), some short, some far
        a, b = rng.integers(0, 60, 2)
        a, b = min(a, b), max(a, b) + 1
        q = profile[a:b] + rng.normal(size=(b - a, 3)) * 0.004 + (0.0 if k % 4 else [0, 0, 0.05])
        q = np.repeat(q, 1 + k % 3, axis=0) if k % 5 == 0 else q        # repeated points: zero-length segments
        pieces.append(q)
    pieces.append(profile[:1].copy())                                   # a single point: ignored
    want = _improve_reference(profile, pieces, 0.02, end_reach)
    assert np.allclose(_improve(profile, False, pieces, end_reach), want, rtol=0, atol=1e-15)
    starts = np.concatenate([[0], np.cumsum([len(q) for q in pieces])])
    assert np.allclose(improve_flat(profile, np.concatenate(pieces), starts, end_reach), want, rtol=0, atol=1e-15)
    assert not np.allclose(want, profile)                               # the pieces moved it


def test_motion_at_its_knots_is_its_maps_exactly():
    r, t = screw_motion([1.0, 0.2, 0.3], [0.0, 0.1, 0.0], 0.05, np.linspace(0.0, 2.0, 9))
    m = Motion(np.linspace(0.0, 3.0, 9), r, t)
    rr, tt = m.at(m.t)
    assert np.array_equal(rr, m.rotation) and np.array_equal(tt, m.translation)
    # between knots the screw motion: the middle of a screw's interval is the screw at the middle
    r_mid, t_mid = screw_motion([1.0, 0.2, 0.3], [0.0, 0.1, 0.0], 0.05, [0.125])
    rm, tm = m.at([0.1875])
    assert np.allclose(rm[0], r_mid[0], atol=1e-12) and np.allclose(tm[0], t_mid[0], atol=1e-12)


def test_motion_between_knots_is_the_screw_of_its_interval_bit_for_bit():
    """Motion.at takes each interval's twist from a cache of all intervals: the maps of the plain formula.

    The reference is the definition, ``M(t) = M_k exp(f log(M_k^{-1} M_{k+1}))`` with the log taken
    for the one interval at hand, evaluated one parameter at a time; every parameter alone, in any
    batch and after the cache is filled gives the same bits.
    """
    from auszug.sweeps.motion import se3_exp, se3_log

    rng = np.random.default_rng(4)
    k = 9
    r = Rotation.from_rotvec(np.cumsum(rng.normal(size=(k, 3)) * 0.2, axis=0)).as_matrix()
    m = Motion(np.cumsum(rng.uniform(0.5, 1.5, k)), r, rng.normal(size=(k, 3)))
    ts = np.sort(rng.uniform(m.t[0], m.t[-1], 50))
    want_r, want_t = [], []
    for t in ts:
        i = min(int(np.searchsorted(m.t, t, side="right")) - 1, k - 2)
        f = (t - m.t[i]) / (m.t[i + 1] - m.t[i])
        r0t = m.rotation[i].T
        w, v = se3_log((r0t @ m.rotation[i + 1])[None], (r0t @ (m.translation[i + 1] - m.translation[i]))[None])
        dr, dt = se3_exp(w * f, v * f)
        want_r.append(m.rotation[i] @ dr[0])
        want_t.append(m.translation[i] + m.rotation[i] @ dt[0])
    fresh = Motion(m.t, m.rotation, m.translation)
    got_r, got_t = fresh.at(ts)
    assert np.allclose(got_r, want_r, atol=1e-14) and np.allclose(got_t, want_t, atol=1e-14)
    for t in ts[::7]:       # one at a time after the cache is filled, and on a fresh motion: the same bits
        one = Motion(m.t, m.rotation, m.translation).at([t])
        again = fresh.at([t])
        j = int(np.flatnonzero(ts == t)[0])
        assert np.array_equal(one[0][0], got_r[j]) and np.array_equal(again[1][0], got_t[j])


@pytest.mark.parametrize("q,n", [(1, 1), (1, 7), (9, 128), (300, 3)])
def test_apply_maps_is_numpys_einsum_bit_for_bit(q, n):
    # the compiled map application replaces np.einsum in Motion.apply and the Hermite projection:
    # the fitted sweeps stay the same only if every bit does (signed zeros included)
    from auszug.sweeps._kernels import apply_maps

    rng = np.random.default_rng(q + n)
    r = rng.normal(size=(q, 3, 3))
    tr = rng.normal(size=(q, 3))
    x = rng.normal(size=(n, 3)) * 1e3
    r[0, 0], tr[0, 0], x[0] = -0.0, -0.0, 0.0                    # products and sums of signed zeros
    want = np.einsum("qij,nj->qni", r, x) + tr[:, None, :]
    got = apply_maps(r, tr, x)
    assert got.shape == want.shape
    assert np.array_equal(got, want) and np.array_equal(np.signbit(got), np.signbit(want))


@pytest.mark.parametrize("m", [1, 6, 5000])
def test_inverse_maps_at_is_numpys_einsum_bit_for_bit(m):
    from auszug.sweeps._kernels import inverse_maps_at

    rng = np.random.default_rng(m)
    r = rng.normal(size=(40, 3, 3))
    tr = rng.normal(size=(40, 3))
    pts = rng.normal(size=(m + 9, 3))
    idx = rng.permutation(m + 9)[:m].astype(np.int64)
    knot = rng.integers(0, 40, m)
    r[knot[0], 0, 0], tr[knot[0]] = -0.0, pts[idx[0]]             # a zero difference
    want = np.einsum("nji,nj->ni", r[knot], pts[idx] - tr[knot])
    got = inverse_maps_at(r, tr, knot, pts, idx)
    assert np.array_equal(got, want) and np.array_equal(np.signbit(got), np.signbit(want))


def test_motion_apply_is_the_maps_at_its_parameters():
    r, t = screw_motion([0.3, 0.0, 1.0], [1.0, 0.5, 0.0], 0.2, [0.0, 0.7, 1.9, 2.5])
    m = Motion(np.array([0.0, 1.0, 2.0, 4.0]), r, t)
    x = np.random.default_rng(2).normal(size=(11, 3))
    tt = np.array([0.0, 0.3, 1.0, 3.1, 4.0])
    rr, trr = m.at(tt)
    got = m.apply(x, tt)
    assert got.shape == (5, 11, 3)
    assert np.array_equal(got, np.einsum("qij,nj->qni", rr, x) + trr[:, None, :])


def test_mesh_tree_of_is_built_once_per_mesh_and_answers_as_a_new_tree():
    import copy
    import pickle

    from auszug.sweeps.fixtures import extruded
    from auszug.sweeps.mesh import normalise
    from auszug.sweeps.patches import MeshTree

    fx = extruded(n_profile=30, n_path=12)
    m = normalise(fx.vertices, fx.faces)
    t = MeshTree.of(m)
    assert MeshTree.of(m) is t                                   # shared by every stage on the mesh
    other = normalise(fx.vertices, fx.faces)
    assert MeshTree.of(other) is not t                           # another mesh object: its own tree
    p = np.random.default_rng(0).normal(size=(50, 3)) * 0.3
    d0, f0, c0 = MeshTree.built(m).query(p)
    d, f, c = t.query(p)
    assert np.array_equal(d, d0) and np.array_equal(f, f0) and np.array_equal(c, c0)
    assert np.array_equal(t._boundary_edges(), MeshTree(m.vertices, m.faces)._boundary_edges())
    # the tree is not part of the mesh's state: a pickled or copied mesh builds its own
    for m2 in (pickle.loads(pickle.dumps(m)), copy.deepcopy(m)):
        assert "_mesh_tree" not in m2.__dict__
        assert np.array_equal(m2.vertices, m.vertices) and np.array_equal(m2.faces, m.faces)
        assert MeshTree.of(m2) is not t


def test_sweep_rings_kept_across_refinements_are_the_motion_at_their_parameters():
    # _sweep_rings computes only the new parameters' rings in each refinement: every ring must be
    # what the motion gives at its parameter in one call for all of them, bit for bit
    from auszug.sweeps.general import hermite_motion
    from auszug.sweeps.patches import _sweep_rings

    rng = np.random.default_rng(5)
    profile = np.column_stack([np.linspace(0, 0.2, 30), 0.05 * np.sin(np.linspace(0, 3, 30)), np.zeros(30)])
    r, t = screw_motion([0.2, 0.1, 1.0], [0.3, 0.0, 0.1], 0.05, np.linspace(0.0, 2.0, 6))
    motion = hermite_motion(profile, r, t, rng.normal(size=(6, 6)) * 0.3, 4)
    for tol in (1e-4, 1e-6):
        tt, rings = _sweep_rings(profile, motion, tol)
        assert len(tt) > len(motion.t) and np.all(np.diff(tt) > 0)       # refined at least once
        assert np.array_equal(rings, motion.apply(profile, tt))


def test_ordered_parts_are_the_family_parts_in_rib_order():
    from auszug.sweeps import curvature_plots, cut, families, match_cuts, movability, normalise
    from auszug.sweeps.fixtures import extruded
    from auszug.sweeps.matching import family_parts, order_ribs, ordered_parts

    fx = extruded(n_profile=60, n_path=60)
    xs = np.array([0.05, -0.2, 0.3, -0.05, 0.15, -0.3])
    c = cut(normalise(fx.vertices, fx.faces), np.tile([1.0, 0, 0], (6, 1)), xs)
    pl = curvature_plots(c, movability(c))
    ribs = order_ribs(families(match_cuts(pl))[0], pl)
    want = family_parts(ribs.family, pl)[ribs.order]
    got = ordered_parts(ribs, pl)
    assert np.array_equal(got, want)
    got[0] += 1.0                                             # a copy: the kept parts stay as they were
    assert np.array_equal(ordered_parts(ribs, pl), want)
    other = curvature_plots(c, movability(c))                 # other plots: taken anew
    assert np.array_equal(ordered_parts(ribs, other), family_parts(ribs.family, other)[ribs.order])


@pytest.mark.parametrize("p,n", [(1, 1), (2, 3), (30, 128)])
def test_eq7_blocks_are_numpys_einsum_over_the_built_matrix_bit_for_bit(p, n):
    from auszug.sweeps._kernels import eq7_blocks

    rng = np.random.default_rng(p * n)
    mid = rng.normal(size=(p, n, 3))
    d = rng.normal(size=(p, n, 3))
    mid[0, 0] = [0.0, -0.0, 0.0]
    a = np.zeros((p, n, 3, 6))                  # per point the rows [-[mid]x | I], as rib_velocities built them
    a[:, :, 0, 1], a[:, :, 0, 2] = mid[..., 2], -mid[..., 1]
    a[:, :, 1, 0], a[:, :, 1, 2] = -mid[..., 2], mid[..., 0]
    a[:, :, 2, 0], a[:, :, 2, 1] = mid[..., 1], -mid[..., 0]
    a[:, :, :, 3:] = np.eye(3)
    a = a.reshape(p, 3 * n, 6)
    want_l, want_r = np.einsum("pri,prj->pij", a, a), np.einsum("pri,pr->pi", a, d.reshape(p, 3 * n))
    got_l, got_r = eq7_blocks(mid, d)
    assert np.array_equal(got_l, want_l) and np.array_equal(np.signbit(got_l), np.signbit(want_l))
    assert np.array_equal(got_r, want_r) and np.array_equal(np.signbit(got_r), np.signbit(want_r))


@pytest.mark.parametrize("k,n,m", [(1, 1, 3), (16, 128, 6), (40, 64, 3)])
def test_batched_gram_is_numpys_einsum_bit_for_bit(k, n, m):
    from auszug.sweeps._kernels import batched_gram

    rng = np.random.default_rng(k + n)
    a = rng.normal(size=(k, n, m))
    b = rng.normal(size=(k, n, m))
    assert np.array_equal(batched_gram(a, b), np.einsum("kni,knj->kij", a, b))
    assert np.array_equal(batched_gram(a, a), np.einsum("kni,knj->kij", a, a))


@pytest.mark.parametrize("shared", [True, False])
@pytest.mark.parametrize("k,n", [(1, 3), (7, 128), (120, 64)])
def test_kabsch_sums_are_numpys_centroids_and_einsum_bit_for_bit(shared, k, n):
    from auszug.sweeps._kernels import kabsch_sums

    rng = np.random.default_rng(k * n + shared)
    b = rng.normal(size=(k, n, 3)) * [1.0, 10.0, 0.1] + 3.0
    p = rng.normal(size=(n, 3)) if shared else rng.normal(size=(k, n, 3))
    a = np.broadcast_to(p, b.shape)
    ca, cb = a.mean(axis=1), b.mean(axis=1)                 # kabsch_batch's sums as numpy gave them
    want = np.einsum("kni,knj->kij", (a - ca[:, None]) / n, b - cb[:, None])
    gca, gcb, got = kabsch_sums(np.ascontiguousarray(p[None] if shared else p), b)
    assert np.array_equal(gca, ca) and np.array_equal(gcb, cb) and np.array_equal(got, want)


def _rotvecs(rng, n):
    """Random rotation vectors: general, near the identity (down to 1e-12 rad, and the series'
    bounds 1e-4 and 1e-3 on both sides), near a half turn (down to 1e-12 below pi), and exact 0 and pi."""
    axes = rng.normal(size=(n, 3))
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    small = 10.0 ** rng.uniform(-12, -2, n)
    near_pi = np.pi - 10.0 ** rng.uniform(-12, -2, n)
    edges = np.array([0.0, 1e-4 * (1 - 1e-12), 1e-4, 1e-3 * (1 - 1e-12), 1e-3, 1e-3 * (1 + 1e-12), np.pi])
    ang = np.concatenate([rng.uniform(0, np.pi, n), small, near_pi, edges])
    ax = np.concatenate([axes, axes, axes, axes[: len(edges)]])
    ax[-len(edges):] = [[0.0, 0.0, 1.0], [1.0, 0, 0], [0, -1.0, 0], [0.6, 0.8, 0], [0, 0, -1.0], [1.0, 0, 0],
                        [-0.6, 0, 0.8]]
    return ang[:, None] * ax


def test_rotations_of_is_scipys_from_rotvec_as_matrix_bit_for_bit():
    from auszug.sweeps._kernels import rotations_of

    w = _rotvecs(np.random.default_rng(11), 400)
    assert np.array_equal(rotations_of(w), Rotation.from_rotvec(w).as_matrix())


def test_rotvecs_of_is_scipys_from_matrix_as_rotvec_bit_for_bit():
    from auszug.sweeps._kernels import rotvecs_of

    w = _rotvecs(np.random.default_rng(12), 400)
    r = Rotation.from_rotvec(w).as_matrix()
    # orthogonalised products too, as the motion's interval rotations M_k^T M_{k+1}
    r = np.concatenate([r, np.einsum("kji,kjl->kil", r[:-1], r[1:]), np.eye(3)[None], np.diag([1.0, -1.0, -1.0])[None]])
    got = rotvecs_of(np.ascontiguousarray(r))
    assert np.array_equal(got, Rotation.from_matrix(r).as_rotvec())
    # and the angle comes back: |w| in [0, pi], rotations of it equal to r
    assert np.all(np.linalg.norm(got, axis=1) <= np.pi + 1e-15)
    assert np.allclose(Rotation.from_rotvec(got).as_matrix(), r, rtol=0, atol=1e-12)


def test_se3_log_and_exp_are_their_scipy_definitions_bit_for_bit():
    from auszug.sweeps.motion import rotation_about, se3_exp, se3_log

    rng = np.random.default_rng(13)
    w = _rotvecs(rng, 100)
    v = rng.normal(size=w.shape)
    r, t = se3_exp(w, v)
    assert np.array_equal(r, Rotation.from_rotvec(w).as_matrix())
    w2, v2 = se3_log(r, t)
    assert np.array_equal(w2, Rotation.from_matrix(r).as_rotvec())
    keep = np.linalg.norm(w, axis=1) < np.pi - 1e-6       # the log is unique below a half turn
    assert np.allclose(w2[keep], w[keep], rtol=0, atol=1e-9) and np.allclose(v2[keep], v[keep], rtol=0, atol=1e-7)
    ang = rng.uniform(-4, 4, 7)
    assert np.array_equal(rotation_about([0, 3.0, 4.0], ang),
                          Rotation.from_rotvec(ang[:, None] * np.array([0, 0.6, 0.8])).as_matrix())


def test_unit_face_normals_are_numpys_cross_over_its_norm_bit_for_bit():
    """The rib normals' faces (general._face_normals): numpy's cross product over its norm, bit for bit, also for
    degenerate faces (a repeated vertex: the normal 0 / 1e-300 = 0) and coordinates over 4 orders of magnitude."""
    from auszug.sweeps._kernels import unit_face_normals

    rng = np.random.default_rng(3)
    v = rng.normal(size=(3000, 3)) * rng.uniform(1e-3, 10, (3000, 1))
    f = rng.integers(0, 3000, (9000, 3))
    f[:5, 1] = f[:5, 0]
    face = np.r_[np.arange(5), rng.integers(0, 9000, 20000)].astype(np.int64)
    ff = f[face]
    want = np.cross(v[ff[:, 1]] - v[ff[:, 0]], v[ff[:, 2]] - v[ff[:, 0]])
    want /= np.maximum(np.linalg.norm(want, axis=1, keepdims=True), 1e-300)
    got = unit_face_normals(v, f, face)
    assert np.array_equal(got, want)
    distinct = (ff[:, 0] != ff[:, 1]) & (ff[:, 1] != ff[:, 2]) & (ff[:, 0] != ff[:, 2])
    assert np.all(got[:5] == 0.0) and np.allclose(np.linalg.norm(got[distinct], axis=1), 1.0) and distinct.sum() > 19000
