"""The local and compiled searches of the general-sweep build (sweeps9) against the whole-mesh originals.

Each must give exactly what the search it stands in for gives: the cut curves near a box as the
whole-mesh cutter gives them (point for point, in order), closest points on a swept ring grid as
libigl's tree of its triangles gives them, the sub-mesh of a box as its numpy definition, the
near test of the recut as the distance to the polyline, and a mesh's boundary edges from its
topology as counted from its faces.
"""

from __future__ import annotations

import numpy as np
import pytest

from auszug.sweeps import _kernels
from auszug.sweeps.cut import EdgeGrid, cut, cut_near
from auszug.sweeps.fixtures import moulding_along_cubic, with_hole
from auszug.sweeps.mesh import normalise
from auszug.sweeps.patches import MeshTree, RingTree, closest_distance, ring_faces


def _mesh(hole: bool = False):
    fx = moulding_along_cubic(n_profile=32, n_path=64)
    fx = with_hole(fx, 0.08) if hole else fx
    return normalise(fx.vertices, fx.faces)


def _in_box(q, box):
    return bool(np.all((q >= box[:3]) & (q <= box[3:]), axis=1).any())


@pytest.mark.parametrize("hole", [False, True])
@pytest.mark.parametrize("part", [False, True])
def test_cut_near_gives_the_whole_cuts_curves_in_its_boxes_point_for_point(hole, part):
    from auszug.sweeps.general import _around

    mesh = _mesh(hole)
    grids = []
    if part:          # a part of the mesh: its edges may have their only face in the second slot
        whole = mesh
        mesh, _, edge_index = _around(mesh, mesh.vertices[: len(mesh.vertices) // 2], 0.05)
        # and the whole mesh's grids taken for the part (EdgeGrid.part): the same curves in the boxes
        grids = [EdgeGrid.of(whole).part(edge_index), EdgeGrid.of(whole, 0.013).part(edge_index)]
        assert len(mesh.edges) < len(whole.edges)
    grids += [None, EdgeGrid.of(mesh, 0.013)]
    rng = np.random.default_rng(11)
    n = rng.normal(size=(30, 3))
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    centre = mesh.vertices[np.unique(mesh.faces)][rng.integers(0, len(np.unique(mesh.faces)), 30)]
    d = np.einsum("ij,ij->i", n, centre)
    half = rng.uniform(0.01, 0.3, size=(30, 1))
    boxes = np.hstack([centre - half, centre + half])
    whole = cut(mesh, n, d)
    for grid in grids:
        near = cut_near(mesh, n, d, boxes, grid)
        got = [(int(near.curve_plane[j]), near.curve(j), bool(near.curve_closed[j]),
                near.edges[near.curve_start[j]:near.curve_start[j + 1]]) for j in range(near.n_curves)]
        gi = 0
        for j in range(whole.n_curves):
            p, q = int(whole.curve_plane[j]), whole.curve(j)
            same = (gi < len(got) and got[gi][0] == p and np.array_equal(got[gi][1], q)
                    and got[gi][2] == bool(whole.curve_closed[j])
                    and np.array_equal(got[gi][3], whole.edges[whole.curve_start[j]:whole.curve_start[j + 1]]))
            if same:
                gi += 1
            else:
                assert not _in_box(q, boxes[p]), f"plane {p}: a curve with a point in the box is missing or differs"
        assert gi == len(got)                   # nothing else, and in the cutter's order
        assert gi > 0


def test_cut_near_with_boxes_holding_the_mesh_is_the_whole_cut():
    mesh = _mesh(hole=True)
    n = np.array([[1.0, 0.0, 0.0], [0.3, 0.4, 0.5], [0.0, 0.0, 1.0]])
    d = np.array([0.01, -0.02, 0.0])
    whole = cut(mesh, n, d)
    near = cut_near(mesh, n, d, np.tile([-1.0, -1, -1, 1, 1, 1], (3, 1)))
    for name in ("points", "normals", "edges", "curve_start", "curve_plane", "curve_closed"):
        assert np.array_equal(getattr(near, name), getattr(whole, name)), name


def test_edge_grid_stores_each_edges_end_points_in_the_grids_order():
    # cut_near's scan reads the end points from the grid instead of the vertices: the same values, bit for bit
    mesh = _mesh(hole=True)
    for cell in (0.013, 0.05):
        g = EdgeGrid.of(mesh, cell)
        assert np.array_equal(np.sort(g.edges), np.arange(len(mesh.edges)))
        assert np.array_equal(g.ends[:3].T, mesh.vertices[mesh.edges[g.edges, 0]])
        assert np.array_equal(g.ends[3:].T, mesh.vertices[mesh.edges[g.edges, 1]])
        # each cell's box: its edges' end points' least and greatest coordinates (inf, -inf where empty)
        for c in range(len(g.cell_start) - 1):
            e = g.edges[g.cell_start[c]:g.cell_start[c + 1]]
            x = mesh.vertices[mesh.edges[e].reshape(-1)]
            want = np.r_[x.min(axis=0), x.max(axis=0)] if len(e) else np.r_[[np.inf] * 3, [-np.inf] * 3]
            assert np.array_equal(g.cell_box[c], want)
        assert len(g.local) == 0


def test_a_parts_grid_is_the_whole_grid_with_the_parts_edge_indices():
    from auszug.sweeps.general import _around

    mesh = _mesh(hole=True)
    part, _, edge_index = _around(mesh, mesh.vertices[:700], 0.05)
    g = EdgeGrid.of(mesh).part(edge_index)
    assert np.array_equal(part.edges, mesh.edges[edge_index >= 0])
    assert np.array_equal(edge_index[edge_index >= 0], np.arange(len(part.edges)))
    with pytest.raises(ValueError):
        g.part(edge_index)


@pytest.mark.parametrize("closed", [False, True])
def test_ring_tree_is_libigls_closest_points_on_the_ring_faces(closed):
    rng = np.random.default_rng(12)
    k, n = 23, 17
    t = np.linspace(0.0, 1.0, k)[:, None]
    s = np.linspace(0.0, 2 * np.pi * (1.0 if closed else 0.7), n, endpoint=not closed)[None]
    rings = np.stack(np.broadcast_arrays(np.cos(s) * (0.3 + 0.1 * t), np.sin(s) * 0.3 + 0 * t,
                                         t * 0.5 + 0.02 * np.sin(5 * s)), -1) + rng.normal(size=(k, n, 3)) * 1e-3
    rings[5, 3] = rings[5, 4]                                     # a zero-length edge: degenerate triangles
    v, f = rings.reshape(-1, 3), ring_faces(k, n, closed)
    pts = np.vstack([v[rng.integers(0, len(v), 400)] + rng.normal(size=(400, 3)) * 0.01,
                     rng.uniform(-0.6, 0.8, size=(400, 3)), v[:20]])
    want, want_c = closest_distance(pts, v, f)
    tree = RingTree(rings, closed)
    for bound in (np.inf, 0.02, 0.0):
        d, face, c = tree.query(pts, bound)
        ok = want <= bound
        assert np.allclose(d[ok], want[ok], rtol=0, atol=1e-15) and np.allclose(c[ok], want_c[ok], atol=1e-15)
        assert np.all(np.isinf(d[~ok])) and np.all(face[~ok] == -1)
        # the face found holds the closest point
        fo = face[ok]
        a, b, cc = v[f[fo, 0]], v[f[fo, 1]], v[f[fo, 2]]
        dd, _ = closest_distance(c[ok], np.vstack([a, b, cc]),
                                 np.stack([np.arange(len(fo)), len(fo) + np.arange(len(fo)),
                                           2 * len(fo) + np.arange(len(fo))], 1))
        assert np.all(dd <= 1e-12)
    assert np.sum(want <= 0.02) > 300


def test_box_part_is_its_numpy_definition():
    mesh = _mesh(hole=True)
    lo, hi = np.array([-0.3, -0.2, -0.5]), np.array([0.2, 0.3, 0.1])
    keep, used, ef, fe, faces, edges, index = _kernels.box_part(mesh.vertices, mesh.faces, mesh.edges,
                                                                mesh.edge_faces, mesh.face_edges, lo, hi)
    inside = np.all((mesh.vertices >= lo) & (mesh.vertices <= hi), axis=1)
    want_keep = np.flatnonzero(inside[mesh.faces].all(axis=1))
    flag = np.zeros(len(mesh.edges), bool)
    flag[mesh.face_edges[want_keep]] = True
    want_used = np.flatnonzero(flag)
    edge_index = np.full(len(mesh.edges), -1)
    edge_index[want_used] = np.arange(len(want_used))
    face_index = np.full(len(mesh.faces) + 1, -1)
    face_index[want_keep] = np.arange(len(want_keep))
    assert np.array_equal(keep, want_keep) and np.array_equal(used, want_used)
    assert np.array_equal(ef, face_index[mesh.edge_faces[want_used]])
    assert np.array_equal(fe, edge_index[mesh.face_edges[want_keep]])
    assert np.array_equal(index, edge_index)
    # the part's faces and edges: the kept rows, as numpy's fancy indexing gives them
    for g, w in ((faces, mesh.faces[want_keep]), (edges, mesh.edges[want_used])):
        assert g.dtype == w.dtype and np.array_equal(g, w)
    assert 0 < len(keep) < len(mesh.faces)
    # an empty box: no faces, no edges
    got = _kernels.box_part(mesh.vertices, mesh.faces, mesh.edges, mesh.edge_faces, mesh.face_edges, hi + 1, hi + 2)
    assert [len(g) for g in got[:6]] == [0] * 6 and got[4].shape == (0, 3) and got[5].shape == (0, 2)
    assert np.all(got[6] == -1) and len(got[6]) == len(mesh.edges)


def test_curves_near_profiles_is_the_distance_within_reach():
    rng = np.random.default_rng(13)
    s = np.linspace(0.0, 1.0, 37)
    moved = np.stack([np.stack([s, 0.1 * np.sin(6 * s + k), 0.05 * k + 0 * s], 1) for k in range(3)])
    pts = np.vstack([moved[k][rng.integers(0, 37, 50)] + rng.normal(size=(50, 3)) * 0.01 for k in range(3)])
    starts = np.array([0, 40, 90, 150])
    plane = np.array([0, 1, 2])
    reach = 0.012
    got = _kernels.curves_near_profiles(pts, starts, plane, moved, reach)
    want = np.concatenate([_kernels.polyline_closest(pts[starts[j]:starts[j + 1]], moved[plane[j]])[0] <= reach
                           for j in range(3)])
    assert np.array_equal(got, want) and 0 < want.sum() < len(want)


def test_mesh_tree_of_a_mesh_has_the_boundary_edges_counted_from_its_faces():
    mesh = _mesh(hole=True)
    assert np.array_equal(MeshTree.of(mesh)._boundary_edges(), MeshTree(mesh.vertices, mesh.faces)._boundary_edges())
    assert (MeshTree.of(mesh)._boundary_edges() >= 0).any()


def test_swept_error_with_upper_bounds_is_the_fit_error_without():
    from auszug.sweeps.motion import Motion, screw_motion
    from auszug.sweeps.patches import swept_error

    mesh = _mesh(hole=True)
    tree = MeshTree.of(mesh)
    rng = np.random.default_rng(14)
    # a profile near the mesh, moved by a screw: some swept points near the mesh, some beyond it
    profile = mesh.vertices[np.unique(mesh.faces)][:40] + rng.normal(size=(40, 3)) * 0.002
    r, t = screw_motion([0.2, 1.0, 0.1], [0.0, 0.0, 0.0], 0.01, np.linspace(0.0, 0.3, 9))
    motion = Motion(np.arange(9.0), r, t)
    want = swept_error(profile, False, motion, 0.005, tree)
    x = motion.apply(profile, motion.t)
    d = tree.query(x.reshape(-1, 3))[0].reshape(9, 40)
    for slack in (0.0, 1e-4, 1e-2):
        upper = d + rng.uniform(0.0, slack, size=d.shape)
        upper[rng.random(d.shape) < 0.1] = np.inf
        got = swept_error(profile, False, motion, 0.005, tree, upper)
        assert got.fit_error == want.fit_error
        assert np.array_equal(got.vertices, want.vertices)
    assert want.fit_error > 0


def test_improve_bounded_bounds_the_improved_points_distances_to_each_keys_pieces():
    from auszug.sweeps.patches import improve_bounded, improve_flat

    rng = np.random.default_rng(15)
    s = np.linspace(0, 1, 50)
    profile = np.stack([s, 0.1 * np.sin(6 * s), 0 * s], axis=1)
    pieces, keys = [], []
    for k in range(10):
        a, b = sorted(rng.integers(0, 50, 2))
        q = profile[a:b + 2] + rng.normal(size=(len(profile[a:b + 2]), 3)) * 0.004
        pieces.append(q)
        keys.append(k % 3)
    starts = np.concatenate([[0], np.cumsum([len(q) for q in pieces])])
    pts = np.concatenate(pieces)
    got, bound = improve_bounded(profile, pts, starts, np.array(keys), 3, 0.004)
    assert np.array_equal(got, improve_flat(profile, pts, starts, 0.004))
    for key in range(3):
        d = np.min([_kernels.polyline_closest(got, q)[0] for q, kk in zip(pieces, keys, strict=True)
                    if kk == key], axis=0)
        assert np.all(d <= bound[key] + 1e-15)
        assert np.isfinite(bound[key]).any()


def _closest_on_cut_reference(c, plane, target):
    """The plane's curves one by one (numpy), as the re-slicing took them before sweeps9."""
    dist = np.full(len(target), np.inf)
    cp = np.zeros((len(target), 3))
    at_end = np.zeros(len(target), bool)
    for j in np.flatnonzero(c.curve_plane == plane):
        q = c.curve(int(j))
        if len(q) < 2:
            continue
        closed = bool(c.curve_closed[j])
        if closed:
            q = np.vstack([q, q[:1]])
        d, p = _kernels.polyline_closest(target, q)
        better = d < dist
        dist[better], cp[better] = d[better], p[better]
        if not closed:
            ends = (np.linalg.norm(p - q[0], axis=1) <= 1e-12) | (np.linalg.norm(p - q[-1], axis=1) <= 1e-12)
            at_end[better] = ends[better]
        else:
            at_end[better] = False
    return dist, cp, at_end


def test_closest_on_plane_curves_is_the_curve_by_curve_search():
    mesh = _mesh(hole=True)
    rng = np.random.default_rng(16)
    n = np.array([[1.0, 0.0, 0.0], [0.3, 0.4, 0.5], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]])
    d = np.array([0.01, -0.02, 0.0, 0.3])
    c = cut(mesh, n, d)
    # and a closed loop on plane 0 (a circle in it), a curve of one point on plane 1
    from dataclasses import replace

    a = np.linspace(0, 2 * np.pi, 30, endpoint=False)
    loop = np.stack([np.full(30, 0.01), 0.2 * np.cos(a), 0.2 * np.sin(a)], 1)
    c = replace(c, points=np.vstack([c.points, loop, [[0.0, 0.0, 0.0]]]),
                curve_start=np.r_[c.curve_start, len(c.points) + 30, len(c.points) + 31],
                curve_plane=np.r_[c.curve_plane, 0, 1], curve_closed=np.r_[c.curve_closed, True, False])
    assert c.curve_closed.any() and (~c.curve_closed).any()
    for plane in range(4):
        target = rng.uniform(-0.5, 0.5, size=(200, 3))
        target[:50] = c.points[rng.integers(0, len(c.points), 50)]          # on the cuts: at their points
        target[50:60] = loop[:10] * [1.0, 1.1, 1.1]                            # beside the loop
        got = _kernels.closest_on_plane_curves(target, c.points, c.curve_start, c.curve_plane, c.curve_closed, plane)
        want = _closest_on_cut_reference(c, plane, target)
        for g, w in zip(got, want, strict=True):
            assert np.array_equal(g, w)
    # every plane at once (reslice): each plane's own targets, as one plane at a time; plane 4 has no curve (inf)
    targets = rng.uniform(-0.5, 0.5, size=(5, 80, 3))
    many = _kernels.closest_on_planes(targets, c.points, c.curve_start, c.curve_plane, c.curve_closed)
    for plane in range(5):
        one = _kernels.closest_on_plane_curves(targets[plane], c.points, c.curve_start, c.curve_plane,
                                               c.curve_closed, plane)
        for g, w in zip(many, one, strict=True):
            assert np.array_equal(g[plane], w)
    assert np.isinf(many[0][4]).all() and np.isfinite(many[0][:2]).all()


def test_cut_near_where_the_cutter_starts_a_chain_inside_it_is_the_whole_cut():
    """Every edge's faces swapped: an open chain's end edges have their one face in the second slot.

    The cutter then starts each open chain at its smallest edge (its phase 1), mostly an inner
    edge, and the walk from it covers only one side: the chain comes out as two curves. cut_near
    walks the first chain of a component at once and the rest in the cutter's sorted order; it
    must still give the whole cut bit for bit.
    """
    from dataclasses import replace

    mesh = _mesh(hole=True)
    ef = mesh.edge_faces[:, ::-1].copy()
    swapped = replace(mesh, edge_faces=np.ascontiguousarray(ef))
    rng = np.random.default_rng(5)
    n = rng.normal(size=(40, 3))
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    d = rng.uniform(-0.2, 0.2, 40)
    whole = cut(swapped, n, d)
    near = cut_near(swapped, n, d, np.tile([-1.0, -1, -1, 1, 1, 1], (40, 1)))
    for name in ("points", "normals", "edges", "curve_start", "curve_plane", "curve_closed"):
        assert np.array_equal(getattr(near, name), getattr(whole, name)), name
    # the case in question occurs: open curves that start on an edge with two faces
    first = whole.edges[whole.curve_start[:-1]]
    inner_start = (swapped.edge_faces[first] >= 0).all(axis=1) & ~whole.curve_closed
    assert inner_start.sum() >= 5


def test_face_passes_of_the_fit_are_their_numpy_definitions():
    """Triangle areas (bit for bit), the box's face vertices, the covered faces, the boundary edges."""
    from auszug.sweeps.general import _around
    from auszug.sweeps.patches import face_areas

    rng = np.random.default_rng(8)
    for scale in (1e-3, 1.0, 1e3):
        v = rng.normal(size=(500, 3)) * scale
        f = rng.integers(0, 500, size=(2000, 3))
        want = 0.5 * np.linalg.norm(np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]), axis=1)
        assert np.array_equal(face_areas(v, f), want)
    mesh = _around(_mesh(hole=True), _mesh(hole=True).vertices[:700], 0.05)[0]     # a part: not every vertex used
    lo, hi = np.array([-0.2, -0.3, -0.1]), np.array([0.1, 0.2, 0.3])
    used = np.zeros(len(mesh.vertices), bool)
    used[mesh.faces.reshape(-1)] = True
    want_in = np.all((mesh.vertices >= lo) & (mesh.vertices <= hi), axis=1) & used
    got_in = _kernels.face_vertices_in_box(mesh.vertices, mesh.faces, lo, hi)
    assert np.array_equal(got_in, want_in) and 0 < got_in.sum() < used.sum()
    dist = np.where(rng.uniform(size=len(mesh.vertices)) < 0.7, rng.uniform(0, 0.01, len(mesh.vertices)), np.inf)
    want_f = np.flatnonzero((dist[mesh.faces] <= 0.005).all(axis=1))
    assert np.array_equal(_kernels.faces_within(dist, mesh.faces, 0.005), want_f) and len(want_f) > 0
    # boundary edges from the topology, against counting each edge's faces
    whole = _mesh(hole=True)
    counted = MeshTree(whole.vertices, whole.faces)._boundary_edges()
    assert np.array_equal(MeshTree.of(whole)._bnd, counted) and (counted >= 0).any()


@pytest.mark.parametrize("closed", [False, True])
def test_ring_tree_within_is_its_distance_within_the_bound(closed):
    """RingTree.within stops at the first triangle within the bound: the same answer as the nearest distance."""
    rng = np.random.default_rng(21)
    k, n = 31, 19
    t = np.linspace(0.0, 1.0, k)[:, None]
    a = np.linspace(0.0, 2 * np.pi if closed else 2.5, n, endpoint=not closed)[None, :]
    rings = np.stack([np.cos(a) * (0.3 + 0.1 * t), np.sin(a) * (0.3 + 0.1 * t), t + 0.05 * np.sin(3 * a)], axis=2)
    tree = RingTree(rings, closed)
    pts = rings.reshape(-1, 3)[rng.integers(0, k * n, 3000)] + rng.normal(size=(3000, 3)) * 0.01
    for bound in (0.002, 0.01, 0.03):
        want = tree.query(pts, bound)[0] <= bound
        got = tree.within(pts, bound)
        assert np.array_equal(got, want) and 0 < got.sum() < len(pts)
    # a point of the surface is within a zero bound
    assert tree.within(rings[3, 4][None], 0.0)[0]


@pytest.mark.parametrize("swap", [False, True])
def test_cut_near_gives_the_closed_loops_of_a_tube_as_the_cutter(swap):
    """Closed cut curves (a tube cut across), walked from their smallest edge in the cutter's direction.

    cut_near emits a component from the order of its first walk (its seed, then each way round);
    the cutter's direction from the start edge depends on which face it enters first, so both
    orders of every edge's faces are tried, with the tube's true planes and some at random.
    """
    from dataclasses import replace

    from auszug.sweeps.fixtures import closed_along_cubic

    fx = closed_along_cubic(n_profile=24, n_path=48, n_planes=12)
    mesh = normalise(fx.vertices, fx.faces)
    if swap:
        mesh = replace(mesh, edge_faces=np.ascontiguousarray(mesh.edge_faces[:, ::-1]))
    planes = np.asarray(fx.planes, float)       # the true profile planes, to normalised coordinates
    n_true = planes[:, :3]
    d_true = (planes[:, 3] - n_true @ mesh.centre) / mesh.scale
    rng = np.random.default_rng(6)
    centre = mesh.vertices[rng.integers(0, len(mesh.vertices), 30)]
    n = rng.normal(size=(30, 3))
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    n = np.vstack([n_true, n])
    d = np.r_[d_true, np.einsum("ij,ij->i", n[len(planes):], centre)]
    whole = cut(mesh, n, d)
    near = cut_near(mesh, n, d, np.tile([-1.0, -1, -1, 1, 1, 1], (len(d), 1)))
    for name in ("points", "normals", "edges", "curve_start", "curve_plane", "curve_closed"):
        assert np.array_equal(getattr(near, name), getattr(whole, name)), name
    assert whole.curve_closed.sum() >= 5 and (~whole.curve_closed).sum() >= 5


def test_mesh_tree_answers_the_same_points_again_from_its_last_query():
    mesh = _mesh(hole=True)
    tree = MeshTree.of(mesh)
    rng = np.random.default_rng(9)
    a = mesh.vertices[rng.integers(0, len(mesh.vertices), 200)] + rng.normal(size=(200, 3)) * 0.01
    b = a + 0.003
    first = tree.query(a)
    first[0][:] = -1.0                      # the caller's copy: the kept answer is not touched
    again = tree.query(a.copy())
    fresh = MeshTree.of(mesh).query(a)
    other = tree.query(b)
    for x, y in zip(again, fresh, strict=True):
        assert np.array_equal(x, y)
    for x, y in zip(other, MeshTree.of(mesh).query(b), strict=True):
        assert np.array_equal(x, y)
    assert not np.array_equal(other[2], again[2])


def _tied_polyline(rng, n):
    """A polyline with exact ties: dyadic points, every stretch walked there and back, zero-length segments."""
    q = np.round(np.cumsum(rng.normal(size=(n, 3)) * 0.01, axis=0) * 1024) / 1024
    q = np.vstack([q, q[::-1][1:]])                                 # back over the same segments: equal distances
    return np.repeat(q, rng.integers(1, 3, len(q)), axis=0)        # repeated points: zero-length segments


@pytest.mark.parametrize("n", [1, 2, 3, 9, 40, 300])
def test_polyline_closest_chunked_is_polyline_closest_bit_for_bit(n):
    """The chunked search (nearest chunk first, the others pruned) keeps the first of equal distances, as the scan."""
    rng = np.random.default_rng(30 + n)
    for _ in range(5):
        q = _tied_polyline(rng, n) if n > 1 else rng.normal(size=(1, 3))
        pts = np.vstack([q[rng.integers(0, len(q), 50)],                              # on its points
                         q[rng.integers(0, len(q), 50)] + rng.normal(size=(50, 3)) * 0.005,
                         rng.uniform(-1, 1, size=(50, 3)),                              # far away
                         np.round(rng.normal(size=(50, 3)) * 0.02 * 1024) / 1024])      # dyadic: exact ties
        pts = np.ascontiguousarray(pts)
        want = _kernels.polyline_closest(pts, q)
        got = _kernels.polyline_closest_chunked(pts, q)
        for g, w in zip(got, want, strict=True):
            assert np.array_equal(g, w)


def _improve_sums_reference(profile, pts, piece_start, reach, end_reach, piece_key, n_keys):
    """improve_sums as the in-order scan of every chunk whose grown box holds the point (numpy, sweeps9)."""
    n = len(profile)
    acc, count, dmin = profile.copy(), np.ones(n), np.full((n_keys, n), np.inf)
    for j in range(len(piece_start) - 1):
        q = pts[piece_start[j]:piece_start[j + 1]]
        if len(q) < 2:
            continue
        n_seg = len(q) - 1
        lo = np.array([q[h:min(h + 16, n_seg) + 1].min(axis=0) for h in range(0, n_seg, 16)]) - reach
        hi = np.array([q[h:min(h + 16, n_seg) + 1].max(axis=0) for h in range(0, n_seg, 16)]) + reach
        a, b = q[:-1], q[1:]
        bb = b - a
        w = bb[:, 0] * bb[:, 0] + bb[:, 1] * bb[:, 1] + bb[:, 2] * bb[:, 2]
        for i in range(n):
            p = profile[i]
            ok = np.repeat(np.all((p >= lo) & (p <= hi), axis=1), 16)[:n_seg]
            f = ((p[0] - a[:, 0]) * bb[:, 0] + (p[1] - a[:, 1]) * bb[:, 1] + (p[2] - a[:, 2]) * bb[:, 2])
            f = np.where(w > 0, np.clip(f / np.where(w > 0, w, 1.0), 0.0, 1.0), 0.0)
            c = a + f[:, None] * bb
            d2 = (p[0] - c[:, 0]) ** 2 + (p[1] - c[:, 1]) ** 2 + (p[2] - c[:, 2]) ** 2
            d2 = np.where(ok, d2, np.inf)
            g = int(np.argmin(d2))                       # the first of equal distances
            d = np.sqrt(d2[g])
            dmin[piece_key[j], i] = min(dmin[piece_key[j], i], d)
            if d > reach:
                continue
            if np.isfinite(end_reach) and d > end_reach:
                if ((c[g] - q[0]) ** 2).sum() <= 1e-24 or ((c[g] - q[-1]) ** 2).sum() <= 1e-24:
                    continue
            acc[i] += c[g]
            count[i] += 1.0
    return acc, count, dmin


@pytest.mark.parametrize("end_reach", [np.inf, 0.004])
def test_improve_sums_is_the_in_order_scan_of_its_chunks_bit_for_bit(end_reach):
    rng = np.random.default_rng(31)
    s = np.linspace(0, 1, 70)
    profile = np.round(np.stack([s, 0.1 * np.sin(6 * s), 0 * s], axis=1) * 1024) / 1024
    pieces = []
    for k in range(14):
        a, b = sorted(rng.integers(0, 70, 2))
        q = profile[a:b + 2] + (np.round(rng.normal(size=(len(profile[a:b + 2]), 3)) * 4) / 1024 if k % 3 else 0.0)
        if k % 4 == 0:
            q = np.vstack([q, q[::-1][1:]])              # there and back: equal distances on two segments
        pieces.append(np.repeat(q, 1 + k % 2, axis=0) if k % 5 == 0 else q)
    pieces.append(profile[:1].copy())
    starts = np.concatenate([[0], np.cumsum([len(q) for q in pieces])]).astype(np.int64)
    pts = np.ascontiguousarray(np.concatenate(pieces))
    keys = np.arange(len(pieces), dtype=np.int64) % 4
    got = _kernels.improve_sums(profile, pts, starts, 0.02, end_reach, keys, 4)
    want = _improve_sums_reference(profile, pts, starts, 0.02, end_reach, keys, 4)
    for g, w in zip(got, want, strict=True):
        assert np.array_equal(g, w)
    assert np.isfinite(want[2]).any() and np.isinf(want[2]).any() and (want[1] > 1).any()


def test_curves_near_profiles_at_exactly_the_reach():
    """Points exactly ``reach`` from a segment (dyadic, no round-off) are near; the next float beyond is not."""
    reach = 2.0 ** -7
    line = np.array([[0.0, 0, 0], [0.25, 0, 0], [0.5, 0, 0], [0.5, 0.25, 0]] + [[0.5, 0.25, 0.0]] * 30)
    x = np.linspace(0.0, 0.5, 17)
    on = np.stack([x, np.full(17, reach), np.zeros(17)], 1)
    beyond = np.stack([x, np.full(17, np.nextafter(reach, 1.0)), np.zeros(17)], 1)
    pts = np.ascontiguousarray(np.vstack([on, beyond, [[0.5 + reach, 0.125, 0.0]]]))
    got = _kernels.curves_near_profiles(pts, np.array([0, len(pts)]), np.array([0]), line[None].copy(), reach)
    want = _kernels.polyline_closest(pts, line)[0] <= reach
    assert np.array_equal(got, want)
    assert got[:17].all() and not got[17:33].any() and got[33] and got[34]     # 33: on the last segment


@pytest.mark.parametrize("closed", [False, True])
def test_ring_tree_within_of_points_in_surface_order_is_its_distance_within_the_bound(closed):
    """Points in order along the surface (as a mesh's vertices): the search starts near the last triangle found."""
    rng = np.random.default_rng(32)
    k, n = 57, 41
    t = np.linspace(0.0, 1.0, k)[:, None]
    a = np.linspace(0.0, 2 * np.pi if closed else 2.5, n, endpoint=not closed)[None, :]
    rings = np.stack([np.cos(a) * (0.3 + 0.1 * t), np.sin(a) * (0.3 + 0.1 * t), t + 0.05 * np.sin(3 * a)], axis=2)
    tree = RingTree(rings, closed)
    tt = np.linspace(-0.05, 1.05, 90)[:, None]
    aa = np.linspace(0.0, 2.7, 70)[None, :]                      # past the open rings' end
    pts = np.stack([np.cos(aa) * (0.3 + 0.1 * tt), np.sin(aa) * (0.3 + 0.1 * tt),
                    tt + 0.05 * np.sin(3 * aa) + 0 * aa], axis=2).reshape(-1, 3)
    pts = pts + rng.normal(size=pts.shape) * 0.006
    for bound in (0.002, 0.006, 0.02):
        want = tree.query(pts, bound)[0] <= bound
        got = tree.within(pts, bound)
        assert np.array_equal(got, want) and 0 < got.sum() < len(pts)



def _query_points(mesh, seed):
    """Points near the mesh, far inside its box and far outside it (the coarse grid's case)."""
    rng = np.random.default_rng(seed)
    near = mesh.vertices[rng.integers(0, len(mesh.vertices), 400)] + rng.normal(0, 0.004, (400, 3))
    far = rng.uniform(-0.9, 0.9, (200, 3))
    off = rng.normal(size=(60, 3))
    off *= rng.uniform(0.8, 3.0, (60, 1)) / np.linalg.norm(off, axis=1, keepdims=True)
    return np.ascontiguousarray(np.vstack([near, far, off, mesh.vertices[:50]]))


@pytest.mark.parametrize("hole", [False, True])
def test_face_grid_nearest_is_libigls_closest_points_within_the_bound(hole):
    """The face grid's exact search within a bound (``MeshTree.query_within``'s kernel): libigl's
    distances (its brute ``point_mesh_squared_distance``, not the code under test), a closest point on
    the face returned, and nothing farther than the bound; the same from points far off the grid."""
    mesh = _mesh(hole)
    tree = MeshTree.of(mesh)
    pts = _query_points(mesh, 5)
    d0 = closest_distance(pts, mesh.vertices, mesh.faces)[0]
    bound = 0.02
    d, face, cp = _kernels.mesh_closest_within(tree.vertices, tree.faces, *tree.face_grid(), pts, bound)
    inside = d0 <= bound
    assert inside[:400].mean() > 0.9 and (~inside).sum() > 50          # both kinds tested
    assert np.all(np.isinf(d[~inside]) & (face[~inside] == -1))
    assert np.abs(d[inside] - d0[inside]).max() <= 1e-14
    # the closest point lies on the face returned, at the distance returned
    for i in np.flatnonzero(inside)[::10]:
        assert closest_distance(cp[i][None], mesh.vertices, mesh.faces[face[i]][None])[0][0] <= 1e-14
    assert np.abs(np.linalg.norm(cp[inside] - pts[inside], axis=1) - d[inside]).max() <= 1e-14


@pytest.mark.parametrize("hole", [False, True])
def test_mesh_tree_query_is_exact_near_and_far(hole):
    """``MeshTree.query`` (the fine grid near, the coarse grid where no face is near): libigl's
    distances and closest points everywhere, up to points three diameters away, and each closest
    point on the face returned; a tree of a few faces the same, and a tree of none gives inf."""
    mesh = _mesh(hole)
    pts = _query_points(mesh, 6)
    for faces in (mesh.faces, mesh.faces[::97]):
        tree = MeshTree(mesh.vertices, faces)
        d0, c0 = closest_distance(pts, mesh.vertices, faces)
        d, face, cp = tree.query(pts)
        far = d0 > 3 * tree.face_grid()[2]
        assert far.sum() > 100 and (~far).sum() > 100                     # both searches tested
        assert np.abs(d - d0).max() <= 1e-14
        assert np.abs(cp - c0).max() <= 1e-9                                # unique closest points here
        for i in range(0, len(pts), 7):         # the closest point on the face returned
            assert closest_distance(cp[i][None], mesh.vertices, faces[face[i]][None])[0][0] <= 1e-14
    d, face, _ = MeshTree(mesh.vertices, np.zeros((0, 3), np.int64)).query(pts[:5])
    assert np.all(np.isinf(d)) and np.all(face == -1)


@pytest.mark.parametrize("hole", [False, True])
def test_mesh_tree_query_within_is_its_query_within_the_bound(hole):
    """``MeshTree.query_within`` (only the cells within the bound searched): where ``query``'s distance
    is at most the bound, the same bits and a face at that distance; elsewhere inf and -1; for
    bounds below, about and above the grid's cell, and on a tree of a few faces."""
    mesh = _mesh(hole)
    pts = _query_points(mesh, 6)
    for faces in (mesh.faces, mesh.faces[::97]):
        tree = MeshTree(mesh.vertices, faces)
        d0 = tree.query(pts)[0]
        h = tree.face_grid()[2]
        for bound in (0.0, 1e-3, 0.5 * h, h, 3 * h, 0.3):
            d, face, cp = tree.query_within(pts, bound)
            near = d0 <= bound
            assert np.array_equal(np.isfinite(d), near), bound
            assert np.array_equal(d[near], d0[near]), bound
            assert np.all(face[~near] == -1) and np.all(face[near] >= 0)
            i = np.flatnonzero(near)
            assert np.abs(np.linalg.norm(cp[i] - pts[i], axis=1) - d[i]).max(initial=0.0) <= 1e-14
            for j in i[::7]:        # the closest point on the face returned
                assert closest_distance(cp[j][None], mesh.vertices, faces[face[j]][None])[0][0] <= 1e-14
        assert (d0 <= 3 * h).sum() > 100 and (d0 > 0.3).sum() > 100       # both kinds of points
    d, face, _ = MeshTree(mesh.vertices, np.zeros((0, 3), np.int64)).query_within(pts[:5], 1.0)
    assert np.all(np.isinf(d)) and np.all(face == -1)


@pytest.mark.parametrize("hole", [False, True])
def test_interior_max_is_the_largest_interior_distance(hole):
    """``MeshTree.interior_max`` (points certified by a face within the largest distance so far are
    not searched) is ``interior_distance(...).max()`` exactly, on rings of points around the mesh
    reaching past its ends and over its hole (the boundary rule), for tolerances that leave some,
    many and no points to the reciprocal test with the rings' own surface."""
    mesh = _mesh(hole)
    tree = MeshTree.of(mesh)
    rng = np.random.default_rng(8)
    checked = 0
    for _ in range(12):
        start = mesh.vertices[rng.integers(0, len(mesh.vertices))]
        step = rng.normal(size=3) * rng.uniform(0.005, 0.05)
        ring = start + np.cumsum(rng.normal(0, 0.01, (40, 3)), axis=0)
        rings = np.ascontiguousarray(ring[None, :, :] + np.arange(12)[:, None, None] * step
                                     + rng.normal(0, rng.uniform(1e-4, 0.02), (12, 40, 3)))
        surface = RingTree(rings, False)
        pts = rings.reshape(-1, 3)
        for tol in (0.0, 0.002, 0.01, 1.0):
            want = float(tree.interior_distance(pts, surface, tol).max())
            got = tree.interior_max(pts, surface, tol)
            assert got == want
            checked += want > 0
    assert checked > 20
    assert tree.interior_max(np.zeros((0, 3)), RingTree(np.zeros((2, 2, 3)), False), 0.01) == 0.0


def test_refined_motions_bounds_bound_the_distances_and_the_early_stop_changes_little():
    """A square tube's sweep with every knot turned and shifted a little, refined: the bounds of the
    moved profile's distances at the knots (for the fit check) are upper bounds, and the early stop
    (``twist_tolerance``) leaves every map within a small multiple of it of all the steps' map."""
    from scipy.spatial.transform import Rotation

    from auszug.sweeps.fixtures import grid_faces
    from auszug.sweeps.general import _refine_bounded
    from auszug.sweeps.motion import Motion
    from auszug.sweeps.params import DEFAULT

    side = np.linspace(-0.02, 0.02, 9)[:-1]
    one = np.full(8, 0.02)
    sq = np.column_stack([np.r_[side, one, -side, -one], np.r_[-one, side, one, -side]])
    n, n_path = len(sq), 61
    xs = np.linspace(-0.5, 0.5, n_path)
    rng = np.random.default_rng(7)
    v = np.column_stack([np.repeat(xs, n), np.tile(sq[:, 0], n_path), np.tile(sq[:, 1], n_path)])
    v[:, 1:] += rng.normal(0, 3e-4, (len(v), 2))                   # a noisy tube: the steps do not end at once
    g = grid_faces(n_path, n + 1)
    tree = MeshTree(v, (g // (n + 1)) * n + (g % (n + 1)) % n)
    prof = np.column_stack([np.zeros(n), sq])
    k = 41
    t = np.arange(k, dtype=float)
    rot = Rotation.from_rotvec(np.column_stack([np.radians(rng.uniform(-1, 1, (k, 2))), 0 * t])).as_matrix()
    wrong = Motion(t, rot, np.column_stack([-0.4 + 0.02 * t, rng.uniform(-5e-4, 5e-4, (k, 2))]))
    got, upper, far = _refine_bounded(prof, wrong, tree, DEFAULT)
    assert not far.any()                                           # every map refined (turns of about 1 deg)
    d = tree.query(got.apply(prof, got.t).reshape(-1, 3))[0].reshape(k, n)
    assert np.isfinite(upper).mean() > 0.95
    assert np.all(d[np.isfinite(upper)] <= upper[np.isfinite(upper)] + 1e-15)
    every, _, _ = _refine_bounded(prof, wrong, tree, DEFAULT.with_(twist_tolerance=0.0))
    more, _, _ = _refine_bounded(prof, wrong, tree, DEFAULT.with_(twist_tolerance=0.0, twist_steps=5))
    fine, _, _ = _refine_bounded(prof, wrong, tree, DEFAULT.with_(twist_tolerance=1e-9))
    assert DEFAULT.twist_tolerance == 1e-7

    def apart(a, b):
        return float(np.abs(a.apply(prof, t) - b.apply(prof, t)).max())

    # on the noisy tube the steps have not settled: a 5th moves points by 9.4e-5 (measured); the early stop
    # at 1e-7 by 2.8e-5 (a knot whose step fell below it takes a larger one later), at 1e-9 by 4.8e-9
    assert 0 < apart(got, every) <= apart(more, every) <= 2e-4
    assert apart(fine, every) <= 1e-7


@pytest.mark.parametrize("hole", [False, True])
def test_grown_states_agree_with_libigls_face_wherever_known(hole):
    """The grid's answer whether a point's nearest faces are flagged (the grown check of the general stages):
    where it is known (1 or 0) it is the flag of libigl's closest face, at ties too (points on edges and at
    vertices, where the tree picks one of the faces); at the ties between flagged and unflagged faces it is
    unknown, and there the closest point lies on a flagged face (`MeshTree.on_faces`: an edge or a vertex
    lies on every face around it); `_held` decides as the share of `on_faces` does, for shares around the
    threshold (sweeps-tree4: not the share of the faces the search returned, which depends on ties)."""
    from auszug.sweeps.general import TIE_MARGIN, _held

    mesh = _mesh(hole)
    tree = MeshTree.of(mesh)
    v, f = tree.vertices, tree.faces
    rng = np.random.default_rng(11)
    e = mesh.edges[rng.integers(0, len(mesh.edges), 300)]
    on_edges = v[e[:, 0]] + rng.uniform(0, 1, (300, 1)) * (v[e[:, 1]] - v[e[:, 0]])
    at_vertices = v[rng.integers(0, len(v), 200)]
    fc = f[rng.integers(0, len(f), 300)]
    w = rng.dirichlet([1.0, 1.0, 1.0], 300)
    in_faces = np.einsum("nk,nki->ni", w, v[fc])
    off = in_faces + rng.normal(0, 0.01, (300, 3))
    pts = np.ascontiguousarray(np.vstack([on_edges, at_vertices, in_faces, off]))
    # a flagged region: the faces with a vertex in a half space, so flagged and unflagged faces meet along a border
    flag = (v[f][:, :, 0] > np.median(v[:, 0])).any(axis=1)
    st = _kernels.grown_states(pts, flag, v, f, *tree.face_grid(), TIE_MARGIN)
    face = tree.query(pts)[1]
    known = st >= 0
    assert np.array_equal(st[known] == 1, flag[face[known]])
    # ties between flagged and unflagged faces exist (the border's edges and vertices) and are left unknown
    assert 0 < (~known).sum() < 0.2 * len(pts)
    assert known[600:].mean() > 0.95           # inside faces and off the mesh nearly always known
    on = tree.on_faces(pts, flag)
    assert np.array_equal(on[known], st[known] == 1) and on[~known].all()
    for part in (pts[:300].reshape(10, 30, 3), pts[:500].reshape(20, 25, 3), pts[600:1100].reshape(5, 100, 3)):
        share = float(np.mean(tree.on_faces(part.reshape(-1, 3), flag)))
        for overlap in (0.05, max(share - 1e-3, 1e-3), share, min(share + 1e-3, 1.0), 0.8, 1.0):
            assert _held(tree, part, flag, overlap, True) == (share >= overlap)
            assert _held(tree, part, flag, overlap, False) == (share >= overlap)


def _near_runs_numpy(near, curve_start, curve_plane):
    # the recut's pieces as numpy found them before near_runs (sweeps-build12's _recut_knots)
    n_curves = len(curve_start) - 1
    curve_of = np.repeat(np.arange(n_curves), np.diff(curve_start))
    first = np.zeros(len(near), bool)
    first[curve_start[:-1][curve_start[:-1] < len(near)]] = True
    begins = near & (first | ~np.r_[False, near[:-1]])
    ends = near & (np.r_[first[1:], True] | ~np.r_[near[1:], False])
    a = np.flatnonzero(begins)
    b = np.flatnonzero(ends) + 1
    keep = b - a >= 2
    a, b = a[keep], b[keep]
    starts = np.concatenate([[0], np.cumsum(b - a)]).astype(np.int64)
    idx = np.arange(starts[-1]) + np.repeat(a - starts[:-1], b - a)
    return starts, idx, curve_plane[curve_of[idx]], curve_plane[curve_of[a]].astype(np.int64)


def test_near_runs_are_the_numpy_pieces():
    rng = np.random.default_rng(13)
    for trial in range(300):
        sizes = rng.integers(0, 12, size=rng.integers(1, 9))         # curves of 0 to 11 points
        sizes[0] = max(sizes[0], 1)
        curve_start = np.r_[0, np.cumsum(sizes)].astype(np.int64)
        curve_plane = np.sort(rng.integers(0, 5, size=len(sizes))).astype(np.int64)
        near = rng.random(int(curve_start[-1])) < rng.uniform(0.2, 0.9)
        got = _kernels.near_runs(near, curve_start, curve_plane)
        want = _near_runs_numpy(near, curve_start, curve_plane)
        for g, w in zip(got, want, strict=True):
            assert g.dtype == np.int64 and np.array_equal(g, w), trial
    # every point near: one piece per curve of 2 points or more
    got = _kernels.near_runs(np.ones(5, bool), np.array([0, 1, 3, 5]), np.array([0, 0, 2]))
    assert got[0].tolist() == [0, 2, 4] and got[1].tolist() == [1, 2, 3, 4] and got[3].tolist() == [0, 2]


def _tie_cases(mesh, n: int = 40, seed: int = 5):
    """Points whose closest points lie on mesh edges and vertices (ties), with every face equally near.

    Points on (and just off, along the surface's normal) random edges' midpoints and random
    vertices, boundary ones among them; for each, the faces within 1e-12 of the least distance
    by a brute-force search of every face (libigl's distance to one face at a time) and their
    closest points."""
    rng = np.random.default_rng(seed)
    v, f = mesh.vertices, mesh.faces
    e = mesh.edges[rng.choice(len(mesh.edges), n, replace=False)]
    bnd = mesh.edges[(mesh.edge_faces < 0).any(axis=1)]
    e = np.vstack([e, bnd[rng.choice(len(bnd), 8, replace=False)]])
    at = np.vstack([0.5 * (v[e[:, 0]] + v[e[:, 1]]), v[rng.choice(len(v), n, replace=False)], v[bnd[:8, 0]]])
    nrm = mesh.normals[np.r_[e[:, 0], rng.choice(len(v), n, replace=False), bnd[:8, 0]]]
    pts = np.vstack([at, at + 0.01 * nrm, at - 0.01 * nrm])
    dist = np.column_stack([closest_distance(pts, v, f[[j]])[0] for j in range(len(f))])     # (q, m)
    cps = [closest_distance(pts, v, f[[j]])[1] for j in range(len(f))]
    cases = []
    for i in range(len(pts)):
        tied = np.flatnonzero(dist[i] <= dist[i].min() + 1e-12)
        cases.append((pts[i], dist[i].min(), tied, [cps[j][i] for j in tied]))
    return cases


def _smooth_normal(mesh, face, c):
    """The mesh's normal at ``c`` on ``face``, found afresh: a corner within 1e-9 gives its vertex normal, a side
    within 1e-9 its ends' vertex normals interpolated at ``c`` (the lower end first) and normalised, else the face's."""
    from auszug.sweeps.mesh import vertex_normals

    v, vn = mesh.vertices, vertex_normals(mesh.vertices, mesh.faces)
    tri = mesh.faces[face]
    for k in tri:
        if np.linalg.norm(c - v[k]) <= 1e-9:
            return vn[k]
    for i in range(3):
        a, b = sorted((int(tri[i]), int(tri[(i + 1) % 3])))
        t = float(np.clip((c - v[a]) @ (v[b] - v[a]) / ((v[b] - v[a]) @ (v[b] - v[a])), 0.0, 1.0))
        if np.linalg.norm(c - (v[a] + t * (v[b] - v[a]))) <= 1e-9:
            m = vn[a] + t * (vn[b] - vn[a])
            return m / np.linalg.norm(m)
    n = np.cross(v[tri[1]] - v[tri[0]], v[tri[2]] - v[tri[0]])
    return n / np.linalg.norm(n)


class _Forced(MeshTree):
    """A MeshTree whose query returns given faces and closest points (one tie's answer)."""

    def answer(self, d, face, c):
        self._forced = (np.asarray(d, float), np.asarray(face, np.int64), np.asarray(c, float))

    def query(self, points):
        d, face, c = self._forced
        return d.copy(), face.copy(), c.copy()


@pytest.mark.parametrize("hole", [False, True])
def test_mesh_tree_answers_do_not_depend_on_which_tied_face_the_search_returns(hole):
    """The rib normals, the fit error's beyond-the-mesh test and the grown-patch test take the closest
    point's feature (face, edge or vertex), not the face the search returned: at a tie every face
    equally near gives the same answer (sweeps-build9: a different search's choices moved fit errors
    and added patches on the tracery border)."""
    from auszug.sweeps.general import _around

    mesh = _mesh(hole)      # a part of it near one end: the brute-force search is of every face
    near = np.linalg.norm(mesh.vertices[mesh.faces].mean(axis=1) - mesh.vertices[0], axis=1) < 0.25
    mesh = _around(mesh, mesh.vertices[mesh.faces[near]].reshape(-1, 3), 0.0)[0]
    cases = _tie_cases(mesh)
    assert sum(len(t) >= 2 for _, _, t, _ in cases) >= 40         # real ties, on edges and at vertices
    assert sum(len(t) >= 3 for _, _, t, _ in cases) >= 10
    tree = _Forced(mesh.vertices, mesh.faces)
    mask = np.random.default_rng(3).random(len(mesh.faces)) < 0.5
    bv = np.zeros(len(mesh.vertices), bool)
    bv[mesh.edges[(mesh.edge_faces < 0).any(axis=1)].ravel()] = True
    n_beyond = 0
    for p, d, tied, cps in cases:
        got = []
        for j, c in zip(tied, cps, strict=True):
            tree.answer([d], [j], [c])
            got.append((tree.normals(p[None])[0], tree.interior_distance(p[None])[0],
                        bool(tree.on_faces(p[None], mask)[0])))
        for g in got[1:]:
            assert np.array_equal(g[0], got[0][0]) and g[1] == got[0][1] and g[2] == got[0][2]
        # the normal: at a vertex its vertex normal, on an edge its ends' interpolated (as the cutter's), else the
        # face's; the grown test true iff one of the tied faces is in the mask
        assert np.abs(_smooth_normal(mesh, tied[0], cps[0]) - got[0][0]).max() <= 1e-12
        assert got[0][2] == bool(mask[tied].any())
        # the reciprocal test's "along the mesh" (sweeps-tree4): a normal within the angle of any tied face's, the
        # same for every tied face; probes: the tied faces' own normals and two fixed directions
        tn = _kernels.unit_face_normals(mesh.vertices, mesh.faces, np.asarray(tied, np.int64))
        probes = np.vstack([tn, [[0.0, 0.0, 1.0], [0.6, 0.8, 0.0]]])
        want = (np.abs(probes @ tn.T) >= np.cos(np.radians(30.0))).any(axis=1)
        for j, c in zip(tied, cps, strict=True):
            k = len(probes)
            assert np.array_equal(tree._along(np.full(k, j), np.repeat(c[None], k, axis=0), probes, 30.0), want)
        # beyond the mesh (0) exactly where the closest point is at a boundary vertex or on a boundary edge
        on_bv = any(np.linalg.norm(cps[0] - mesh.vertices[k]) <= 1e-9 and bv[k] for k in mesh.faces[tied].ravel())
        if on_bv:
            n_beyond += 1
            assert got[0][1] == 0.0
    assert n_beyond >= 8
