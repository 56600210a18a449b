"""Plane parallelism and orthogonality (class "plane"): clustering, angles, rows, and a lift of the vase."""

from __future__ import annotations

import numpy as np

from auszug.lifting import layer_graphs, lift
from auszug.lifting.cues import Planar, PlanePairs, angle_between, plane_cues
from auszug.lifting.params import DEFAULT
from auszug.lifting.solver import Poly2, solve
from auszug.lifting.terms import add_lin3
from tests.lifting.truth import depth_rmse, revolve


def _rot_z(deg: float) -> np.ndarray:
    a = np.radians(deg)
    return np.array([[np.cos(a), -np.sin(a), 0.0], [np.sin(a), np.cos(a), 0.0], [0.0, 0.0, 1.0]])


def _planar(k: int) -> Planar:
    """A planarity family of k strokes whose normal variables are slots 0..k-1 (no points)."""
    pts = tuple(np.arange(4 * i, 4 * i + 4, dtype=np.intp) for i in range(k))
    st = np.arange(k, dtype=np.intp)
    return Planar(pts, st, st.copy(), tuple(f"s{i} planar" for i in range(k)))


def test_single_linkage_clusters_chain_and_orthogonal_clusters_pair():
    """Known normals: 0, 10, 20 deg about z chain into one cluster (0 and 20 are 20 deg apart, beyond
    15 deg, but single linkage joins them through 10); its spanning tree has 2 links. A normal 3 deg
    off z is its own cluster, orthogonal to the first within 15 deg: one orthogonality candidate
    between the clusters' first members. A normal 50 deg off both pairs with nothing, and an unapplied
    normal parallel to the first is left out. The sign of a flipped normal is recorded."""
    x = np.array([1.0, 0.0, 0.0])
    n = np.array([x, _rot_z(10) @ x, -(_rot_z(20) @ x),
                  [0.0, np.sin(np.radians(3)), np.cos(np.radians(3))],
                  _rot_z(10) @ np.array([np.cos(np.radians(50)), 0.0, np.sin(np.radians(50))]),
                  x])
    applied = np.array([True, True, True, True, True, False])
    pp = plane_cues(_planar(6), applied, n, tuple(f"s{i}" for i in range(6)), 15.0)
    got = {(int(a), int(b), bool(o), float(s)) for a, b, o, s in zip(pp.ia, pp.ib, pp.orthogonal, pp.sign,
                                                                      strict=True)}
    assert got == {(0, 1, False, 1.0), (1, 2, False, -1.0), (0, 3, True, 1.0)}
    assert len(pp.where) == 3 and "s0 | s3 orthogonal planes" in pp.where


def test_nearly_straight_strokes_take_no_part():
    """A stroke whose points' second singular value is below min_spread of the first has no plane to
    compare: with min_spread = tan(5 deg) a curve bulging 5 % of its length is left out, one bulging
    20 % is kept."""
    t = np.linspace(0.0, 1.0, 4)
    flat = np.c_[t, 0.05 * np.sin(np.pi * t), np.zeros(4)]         # sv2/sv1 0.058
    round_ = np.c_[t, 0.4 * np.sin(np.pi * t), np.zeros(4)]         # sv2/sv1 0.46
    X = np.concatenate([flat, round_, round_ + [0.0, 0.0, 1.0]])
    pla = Planar((np.arange(4), np.arange(4, 8), np.arange(8, 12)), np.arange(3), np.arange(3),
                 ("a planar", "b planar", "c planar"))
    n = np.tile([0.0, 0.0, 1.0], (3, 1))
    spread = float(np.tan(np.radians(5.0)))
    pp = plane_cues(pla, np.ones(3, bool), n, ("a", "b", "c"), 15.0, X, spread)
    assert [(int(a), int(b)) for a, b in zip(pp.ia, pp.ib, strict=True)] == [(1, 2)]
    assert len(plane_cues(pla, np.ones(3, bool), n, ("a", "b", "c"), 15.0)) == 2


def _box_curves(turn_x_face: float = 0.0) -> tuple[Planar, np.ndarray]:
    """Arcs on the faces x = 1, x = -1, y = 1, z = 1 of a cube (4 control points each); the first arc's
    points turned by ``turn_x_face`` deg about the y axis through (1, 0, 0)."""
    t = np.linspace(-0.6, 0.6, 4)
    arc = np.c_[t, 0.5 * (1 - t**2)]                # a planar arc in (u, v)
    faces = []
    for axis, val in ((0, 1.0), (0, -1.0), (1, 1.0), (2, 1.0)):
        u, w = [a for a in range(3) if a != axis]
        P = np.zeros((4, 3))
        P[:, axis] = val
        P[:, u], P[:, w] = arc[:, 0], arc[:, 1]
        faces.append(P)
    a = np.radians(turn_x_face)
    Ry = np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])
    faces[0] = (faces[0] - [1.0, 0, 0]) @ Ry.T + [1.0, 0, 0]
    X = np.concatenate(faces)
    pla = Planar(tuple(np.arange(4 * i, 4 * i + 4) for i in range(4)), np.arange(4), np.arange(4),
                 tuple(f"f{i} planar" for i in range(4)))
    return pla, X


def test_angles_of_a_box_faces_are_exact():
    """Faces of a cube: x = 1 parallel to x = -1, x = 1 orthogonal to y = 1, y = 1 orthogonal to z = 1.
    Exactly 0 deg on the cube; turning the x = 1 arc by 3 deg about y makes its parallel and its
    orthogonality to z = 1 3 deg off, its orthogonality to y = 1 stays exact."""
    pairs = PlanePairs(_box_curves()[0], np.array([0, 0, 2, 0]), np.array([1, 2, 3, 3]), np.ones(4),
                       np.array([False, True, True, True]), ("x|x", "x-y", "y-z", "x-z"))
    assert np.allclose(pairs.angles(_box_curves()[1]), 0.0, atol=1e-9)
    pla, X = _box_curves(3.0)
    turned = PlanePairs(pla, pairs.ia, pairs.ib, pairs.sign, pairs.orthogonal, pairs.where)
    assert np.allclose(turned.angles(X), [3.0, 0.0, 0.0, 3.0], atol=1e-9)


def test_hard_plane_rows_make_two_normals_orthogonal_and_parallel():
    """Unit normals pulled toward targets 87 deg apart (in the xy plane), subject to |N| = 1 and the
    orthogonality row: the least-squares answer opens both symmetrically by 1.5 deg to exactly 90.
    The parallel row with sign -1 between targets 4 deg apart (one flipped) meets in the middle."""
    pla = _planar(2)
    a0 = _rot_z(-43.5) @ np.array([1.0, 0.0, 0.0])
    b0 = _rot_z(43.5) @ np.array([1.0, 0.0, 0.0])
    for orth, target_b, expect_a in ((True, b0, _rot_z(-45.0) @ [1.0, 0.0, 0.0]),
                                     (False, -(_rot_z(4.0) @ [1.0, 0.0, 0.0]), _rot_z(2.0) @ [1.0, 0.0, 0.0])):
        ta = a0 if orth else np.array([1.0, 0.0, 0.0])
        pp = PlanePairs(pla, np.array([0]), np.array([1]), np.array([1.0 if orth else -1.0]),
                        np.array([orth]), ("pair",))
        E = Poly2(6)
        add_lin3(E, np.array([[0], [1]]), np.ones((2, 1)), -np.concatenate([ta, target_b]), 1.0)
        C = Poly2(6)
        for s in (0, 1):   # unit normals
            C.add([-1.0], 1.0, bil=(np.zeros(3), 3 * s + np.arange(3), 3 * s + np.arange(3), np.ones(3)))
        pp.add(C, np.array([0]), 1.0)
        r = solve(E, C, np.concatenate([ta, target_b]))
        assert r.converged
        na, nb = r.v[:3], r.v[3:]
        ang = float(angle_between(na, nb))
        assert (abs(ang - 90.0) if orth else 180.0 - ang) < 1e-7
        assert np.allclose(na, expect_a, atol=1e-7)


def test_vase_parallels_come_out_parallel():
    """The vase (revolve truth) with the plane class: the parallels are horizontal circles, so their
    planes are parallel. Of the 10 planar strokes 9 are applied (the lowest parallel, c6, is not);
    the meridians' planes (through the axis) are not clustered, since a meridian bulges 7 % of its
    length (sv2/sv1 0.072 in the truth, 0.005-0.061 in the lift: below tan 5 deg, its plane turns
    freely about its chord; measured 38-83 deg off the truth, and clustered with each other when let
    in). The applied parallels' planes come out parallel within 0.5 deg (measured 0.01 deg).
    Depth RMSE 2.76 % (3.11 % without the class; the same 2.76 % with a final solve of the applied
    cues and no plane cue: the gain is that final solve, docs/lifting.md)."""
    tr = revolve()
    r = lift(tr.sketch, classes=("parallel", "orthogonal", "planar", "plane"))
    assert r.converged
    plane = [c for c in r.cues if c.kind == "plane"]
    assert sorted(c.where for c in plane) == ["c7 | c8 parallel planes", "c8 | c9 parallel planes"]
    assert all(c.applied and c.angle < 0.5 for c in plane)
    planar = {c.where.split()[0] for c in r.cues if c.kind == "planar" and c.applied}
    assert planar == {f"c{i}" for i in range(10)} - {"c6"}
    (_, g), = layer_graphs(tr.sketch)
    X = r.points[0]
    pla_points = {f"c{s}": np.unique(g.segments[g.chains[s]].reshape(-1)) for s in (7, 8, 9)}
    normals = [np.linalg.svd(X[p] - X[p].mean(0))[2][-1] for p in pla_points.values()]
    for i in range(3):
        for j in range(i + 1, 3):
            a = float(angle_between(normals[i], normals[j]))
            assert min(a, 180.0 - a) < 0.5
    err, sign = depth_rmse(tr, r)
    assert sign == 1 and err <= 0.028          # measured 2.76 %
    assert DEFAULT.plane_cluster_deg == 15.0


def test_planar_normals_batched_are_each_candidates_own_svd():
    """The batched normals (one SVD per group of equal-length candidates, no full left factor) are, bit
    for bit, the smallest right singular vectors of each candidate's centred points; each is a unit
    vector orthogonal to an exactly planar candidate's chords."""
    rng = np.random.default_rng(7)
    X = rng.normal(size=(400, 3))
    sizes = [4, 16, 16, 7, 292, 4, 16, 3]
    pts = tuple(rng.choice(400, size=m, replace=False) for m in sizes)
    pla = Planar(pts, np.arange(len(pts)), np.arange(len(pts)), tuple(f"c{i}" for i in range(len(pts))))
    got = pla.normals(X)
    for p, nrm in zip(pts, got, strict=True):
        Y = X[p] - X[p].mean(0)
        assert np.array_equal(nrm, np.linalg.svd(Y, full_matrices=True)[2][-1])
    flat = X.copy()
    flat[pts[4], 2] = 0.5 * flat[pts[4], 0] - 0.25       # candidate 4 exactly in a plane
    n4 = pla.normals(flat)[4]
    assert abs(np.linalg.norm(n4) - 1.0) < 1e-15
    assert np.abs((flat[pts[4]] - flat[pts[4]].mean(0)) @ n4).max() < 1e-14
    assert pla.angles(flat)[4] < 1e-6
    empty = Planar((), np.zeros(0, np.intp), np.zeros(0, np.intp), ())
    assert empty.normals(X).shape == (0, 3) and empty.angles(X).shape == (0,)
