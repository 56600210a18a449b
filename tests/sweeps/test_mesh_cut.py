"""Normalisation, plane sampling and the compiled plane cutter (auszug.sweeps.mesh, planes, cut)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial import ConvexHull
from scipy.spatial.transform import Rotation

from auszug.errors import GeometryError
from auszug.sweeps.cut import cut
from auszug.sweeps.fixtures import extruded, revolved
from auszug.sweeps.mesh import normalise
from auszug.sweeps.planes import canonical, geodesic_sphere, hemisphere, initial_planes, plane_recall, refine_box


def _sphere(freq=12):
    pts = geodesic_sphere(freq)
    hull = ConvexHull(pts)
    f = hull.simplices.copy()
    # outward orientation
    flip = np.einsum("ij,ij->i", np.cross(pts[f[:, 1]] - pts[f[:, 0]], pts[f[:, 2]] - pts[f[:, 0]]), pts[f[:, 0]]) < 0
    f[flip] = f[flip][:, ::-1]
    return pts, f


def test_normalise_centres_and_scales():
    fx = extruded(n_profile=20, n_path=20)
    v = fx.vertices * 37.0 + np.array([5.0, -3.0, 100.0])
    m = normalise(v, fx.faces)
    lo, hi = m.vertices.min(0), m.vertices.max(0)
    assert np.allclose((lo + hi) / 2, 0, atol=1e-15)
    assert np.isclose(np.linalg.norm(hi - lo), 1.0, rtol=1e-14)
    assert np.allclose(m.to_input(m.vertices), v, atol=1e-12)
    # every edge has one or two faces, and the faces' edges are the edges
    for k in range(3):
        e = m.edges[m.face_edges[:, k]]
        a, b = fx.faces[:, k], fx.faces[:, (k + 1) % 3]
        assert np.array_equal(e, np.sort(np.stack([a, b], 1), axis=1))


def test_normalise_topology_and_normals_match_a_plain_numpy_reference():
    # the edge topology by np.unique on (low, high) rows and the normals by np.add.at, written out here, against
    # normalise's stable-argsort keys and compiled accumulation: the same arrays bit for bit, on a mesh with its
    # faces shuffled and rotated (no runs of sorted keys) and on a third of it (both open: edges with one face)
    rng = np.random.default_rng(3)
    fx = revolved(n_profile=24, n_path=30)
    shuffled = fx.faces[rng.permutation(len(fx.faces))][:, [1, 2, 0]]
    for v, f in ((fx.vertices, shuffled), (fx.vertices, fx.faces[: len(fx.faces) // 3])):
        m = normalise(v, f)
        rows = np.sort(np.stack([f, f[:, [1, 2, 0]]], axis=2).reshape(-1, 2), axis=1)
        edges, inv, counts = np.unique(rows, axis=0, return_inverse=True, return_counts=True)
        assert np.array_equal(m.edges, edges)
        assert np.array_equal(m.face_edges, inv.reshape(-1, 3))
        faces_of = [np.flatnonzero(inv.reshape(-1) == e) // 3 for e in range(len(edges))]
        want = np.array([[fs[0], fs[1] if len(fs) == 2 else -1] for fs in faces_of])
        assert np.array_equal(m.edge_faces, want)
        assert (counts == 1).any() and np.array_equal(m.edge_faces[:, 1] == -1, counts == 1)     # open: boundaries
        x = m.vertices
        fn = np.cross(x[f[:, 1]] - x[f[:, 0]], x[f[:, 2]] - x[f[:, 0]])
        acc = np.zeros_like(x)
        for k in range(3):
            np.add.at(acc, f[:, k], fn)
        nrm = np.linalg.norm(acc, axis=1, keepdims=True)
        assert np.array_equal(m.normals, np.divide(acc, nrm, out=np.zeros_like(acc), where=nrm > 0))


@pytest.mark.parametrize(
    "v, f, what",
    [
        (np.zeros((0, 3)), np.zeros((0, 3), int), "non-empty"),
        ([[0, 0, 0], [1, 0, 0], [0, np.nan, 0]], [[0, 1, 2]], "non-finite"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 3]], "indices"),
        ([[0, 0, 0], [0, 0, 0], [0, 0, 0]], [[0, 1, 2]], "zero-size"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]], [[0, 1, 2], [1, 0, 3], [0, 1, 4]], "2-manifold"),
        ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0.0, 1.0, 2.0]], "integer"),
    ],
)
def test_normalise_rejects_bad_meshes(v, f, what):
    with pytest.raises(GeometryError, match=what):
        normalise(v, f)


def test_edge_topology_is_a_dictionary_of_the_faces_edges_and_the_mesh_trees_is_the_meshs():
    """``edge_topology`` against a plain dictionary of every face's sides (edges in key order, each
    edge's first and last face, each face's edges in face order, counts), on a mesh with boundaries,
    on one with an edge of three faces (the first and the last kept) and on no faces; and a
    ``MeshTree`` of a mesh's faces, built without the mesh, has its topology and boundary edges."""
    from auszug.sweeps.fixtures import bumps, with_hole
    from auszug.sweeps.mesh import edge_topology
    from auszug.sweeps.patches import MeshTree

    fx = with_hole(extruded(n_profile=20, n_path=15))
    fan = np.array([[0, 1, 2], [1, 0, 3], [0, 1, 4], [2, 1, 5]])        # edge (0, 1) has three faces
    for f, n in ((fx.faces, len(fx.vertices)), (fan, 6), (bumps(n=12).faces, 144), (np.zeros((0, 3), np.int64), 3)):
        seen: dict[tuple[int, int], list[int]] = {}
        for i, tri in enumerate(np.asarray(f).tolist()):
            for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
                seen.setdefault((min(a, b), max(a, b)), []).append(i)
        keys = sorted(seen)
        edges, ef, fe, counts = edge_topology(f, n)
        assert edges.tolist() == [list(k) for k in keys]
        assert ef.tolist() == [[seen[k][0], seen[k][-1] if len(seen[k]) > 1 else -1] for k in keys]
        assert counts.tolist() == [len(seen[k]) for k in keys]
        ids = {k: i for i, k in enumerate(keys)}
        assert fe.tolist() == [[ids[(min(a, b), max(a, b))] for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0]))]
                               for t in np.asarray(f).tolist()]
        assert edges.dtype == ef.dtype == fe.dtype == counts.dtype == np.int64
    assert edge_topology(fan, 6)[3].max() == 3
    m = normalise(fx.vertices, fx.faces)
    tree = MeshTree(m.vertices, m.faces)
    fe, ef = tree._topology()
    assert np.array_equal(fe, m.face_edges) and np.array_equal(ef, m.edge_faces)
    assert np.array_equal(tree._edge_ends(), m.edges)
    assert np.array_equal(tree._boundary_edges(), MeshTree.of(m)._boundary_edges())
    assert (tree._boundary_edges() >= 0).any()


def test_geodesic_sphere_counts_and_spacing():
    for freq in (1, 2, 3, 4, 6):
        s = geodesic_sphere(freq)
        assert len(s) == 10 * freq**2 + 2
        assert np.allclose(np.linalg.norm(s, axis=1), 1)
        h = hemisphere(freq)
        assert len(h) == 5 * freq**2 + 1
        # every sphere point is, up to sign, a hemisphere point
        assert np.allclose(np.max(np.abs(s @ h.T), axis=1), 1)
    # frequency 4: neighbours about 63.4 / 4 degrees apart
    s = geodesic_sphere(4)
    g = np.degrees(np.arccos(np.clip(s @ s.T, -1, 1)))
    np.fill_diagonal(g, 180)
    assert 12 < g.min(1).mean() < 18


def test_initial_planes_meet_the_mesh_and_match_the_papers_count():
    fx = revolved()
    m = normalise(fx.vertices, fx.faces)
    n, d = initial_planes(m.vertices, 4, 0.055)
    proj = m.vertices @ n.T
    assert np.all((proj.min(0) <= d) & (d <= proj.max(0)))
    assert 700 <= len(d) <= 1500  # the paper's Fig. 12 starts with 1452 planes


def test_refine_box_and_canonical_planes():
    n, d = refine_box([[0, 0, 1.0], [0, 0, -1.0]], [0.1, -0.1], 4.0, 0.01)
    assert len(n) == 26  # the second box is the same plane's: de-duplicated
    cn, cd = canonical(-n, -d)
    assert np.allclose(cn, n) and np.allclose(cd, d)
    assert plane_recall([[0, 0, 1, 0.1]], n, d, angle=4.1, offset=0.011) == 1.0
    assert plane_recall([[0, 0, 1, 0.1]], n, d, angle=3.0, offset=0.001) == 0.0


def test_cut_of_an_extrusion_across_is_the_profile():
    fx = extruded(n_profile=50, n_path=30)
    m = normalise(fx.vertices, fx.faces)
    xs = np.linspace(-0.3, 0.3, 7) + 1e-3
    c = cut(m, np.tile([1.0, 0, 0], (7, 1)), xs)
    assert c.n_curves == 7 and not c.curve_closed.any()
    assert np.allclose(c.curve_lengths(), fx.profile_length, rtol=1e-12)
    prof = fx.vertices[:50, 1:]  # the first row of the grid: the profile at the start, (y, z)
    for k in range(7):
        p = c.curve(k)
        assert np.allclose(p[:, 0], xs[k], atol=1e-15)
        # every point on the profile polyline
        q = m.to_input(p)[:, 1:]
        seg_a, seg_b = prof[:-1], prof[1:]
        t = np.clip(np.einsum("psd,sd->ps", q[:, None] - seg_a[None], seg_b - seg_a) /
                    np.einsum("sd,sd->s", seg_b - seg_a, seg_b - seg_a), 0, 1)
        dist = np.linalg.norm(q[:, None] - (seg_a + t[..., None] * (seg_b - seg_a)), axis=2).min(1)
        assert dist.max() < 1e-12
    # the normals there are the profile's: orthogonal to the extrusion
    assert np.abs(c.normals[:, 0]).max() < 1e-12


def test_cut_links_through_faces_and_closes_loops():
    v, f = _sphere()
    m = normalise(v, f)
    c = cut(m, [[0, 0, 1.0], [0.6, 0.8, 0]], [0.1, -0.05])
    assert c.n_curves == 2 and c.curve_closed.all()
    r = 1 / (2 * np.sqrt(3))  # the sphere's radius after normalisation
    expect = 2 * np.pi * np.sqrt(r**2 - np.array([0.1, 0.05]) ** 2)
    assert np.allclose(c.curve_lengths(), expect, rtol=3e-3)
    # consecutive points lie on edges of one face
    face_sets = [set(m.edge_faces[e]) - {-1} for e in c.edges]
    for k in range(c.n_curves):
        idx = np.arange(c.curve_start[k], c.curve_start[k + 1])
        for a, b in zip(idx, np.roll(idx, -1), strict=True):
            assert face_sets[a] & face_sets[b]


def test_cut_is_invariant_under_rigid_motion():
    fx = revolved(n_profile=30, n_path=40)
    rot = Rotation.from_rotvec([0.3, -1.1, 0.7])
    m0 = normalise(fx.vertices, fx.faces)
    m1 = normalise(rot.apply(fx.vertices) + [3, 4, 5], fx.faces)
    n, d = initial_planes(m0.vertices, 2, 0.1)
    c0 = cut(m0, n, d)
    # the same planes in the moved mesh's normalised frame: the bounding box is not rotation
    # invariant, so its centre and diameter change: m1 = k R m0 + shift
    k = m0.scale / m1.scale
    shift = m1.vertices[0] - k * rot.apply(m0.vertices[0])
    n1 = rot.apply(n)
    c1 = cut(m1, n1, k * d + n1 @ shift)
    assert c0.n_curves == c1.n_curves
    assert np.allclose(np.sort(c0.curve_lengths()), np.sort(c1.curve_lengths()) / k, atol=1e-9)


def test_cut_missing_planes_and_vertices_on_the_plane():
    fx = extruded(n_profile=20, n_path=21)
    m = normalise(fx.vertices, fx.faces)
    # a plane through a column of vertices (x = 0 exactly) and one that misses the mesh
    c = cut(m, [[1.0, 0, 0], [1.0, 0, 0]], [m.vertices[10 * 20, 0], 2.0])
    assert c.n_planes == 2 and c.n_curves == 1
    p = c.curve(0)
    assert np.linalg.norm(np.diff(p, axis=0), axis=1).min() > 0  # no repeated points
    assert np.isclose(c.curve_lengths()[0], fx.profile_length, rtol=1e-12)
