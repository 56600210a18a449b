"""Members: samples exactly on the curves, frames, exact replicas, joints at mirror planes, caps, counts."""

from __future__ import annotations

import math

import numpy as np
import pytest

from auszug.meshing import Mesh, default_size, profile_for, sweep_network
from auszug.meshing._clip import plane_loops
from auszug.meshing.frames import sweep_frames
from auszug.meshing.profile import circle, ribbon, square
from auszug.meshing.solid import closed_member
from auszug.meshing.sweep import SWEPT_KINDS, sample_piece, sweep_members, sweep_profile
from auszug.microarch import build
from tests.meshing.cases import ALL, IDS, arc_curve, network, star

SOME = ["teaching-sheet/tn-1.uc", "teaching-sheet/tn-5.uc", "teaching-sheet/tn-10.uc", "web/U.XI.28.uc",
        "web/3d-scan-final.uc", "web/weird_ones/flower.uc", "web/ribbons/side5-metal.uc", "legacy/U.XI.20.uc"]


def _size(net) -> float:
    b = net.bounds()
    return float(np.linalg.norm(b[1] - b[0]))


@pytest.mark.parametrize("name", SOME)
def test_samples_lie_exactly_on_the_network_curves(name):
    net = network(name)
    for p in net.pieces:
        if p.kind not in SWEPT_KINDS or p.top is None:
            continue
        for run in sample_piece(p, 150):
            xy, z = run.points[:, :2], run.points[:, 2]
            t = np.array([p.top.project(q) for q in xy])
            # at the vertical ends a parameter off by 1e-16 moves the height by 1e-8: snap
            t = np.where(t > 1 - 1e-12, 1.0, np.where(t < 1e-12, 0.0, t))
            assert np.abs(p.top.point(t) - xy).max() < 1e-12 * _size(net)
            assert np.abs(p.height_at_t(t) - z).max() < 1e-9 * _size(net)
            assert np.abs(np.linalg.norm(run.tangents, axis=1) - 1).max() < 1e-12
            # tangents agree with the chords between samples
            chord = np.diff(run.points, axis=0)
            chord /= np.linalg.norm(chord, axis=1, keepdims=True)
            mid = run.tangents[:-1] + run.tangents[1:]
            mid /= np.linalg.norm(mid, axis=1, keepdims=True)
            assert np.einsum("ij,ij->i", chord, mid).min() > math.cos(math.radians(2))


@pytest.mark.parametrize("name", SOME)
def test_ogee_ends_are_exactly_vertical(name):
    net = network(name)
    for p in net.pieces:
        if p.kind == "ogee" and not p.decoration_point:
            runs = sample_piece(p, 50)
            assert runs[0].tangents[0].tolist() == [0.0, 0.0, 1.0]
            assert runs[-1].tangents[-1].tolist() == [0.0, 0.0, 1.0]


def test_samples_are_even_in_3d_arc_length():
    net = build(arc_curve())
    (run,) = sample_piece(net.pieces[0], 200)
    step = np.linalg.norm(np.diff(run.points, axis=0), axis=1)
    assert step.max() / step.min() < 1.05     # the vertical ends are as fine as the middle


def test_decorated_ogee_is_split_at_its_cusp():
    net = network("teaching-sheet/tn-5.uc")
    deco = [p for p in net.pieces if p.kind == "ogee" and p.decoration_point]
    assert deco
    runs = sample_piece(deco[0], 100)
    assert len(runs) == 2
    assert np.array_equal(runs[0].points[-1], runs[1].points[0])
    assert runs[0].tangents[-1] @ runs[1].tangents[0] < math.cos(1e-3)


@pytest.mark.parametrize("name", SOME)
def test_member_frames_are_orthonormal_and_continuous(name):
    net = network(name)
    for mb in sweep_members(net, square(0.01), 120):
        for f in mb.frames:
            for a, b in ((f.tangent, f.width), (f.tangent, f.depth), (f.width, f.depth)):
                assert np.abs(np.einsum("ij,ij->i", a, b)).max() < 1e-12
            assert np.abs(np.linalg.norm(f.width, axis=1) - 1).max() < 1e-12
            if len(f.width) > 2:
                cosang = np.einsum("ij,ij->i", f.width[1:], f.width[:-1])
                assert cosang.min() > math.cos(math.radians(10))


def test_straight_bar_volume_is_side_squared_times_length():
    p = np.array([[0.2, -0.1, 0.0], [0.2, -0.1, 1.5]])
    t = np.tile([0.0, 0.0, 1.0], (2, 1))
    v, f = sweep_profile(p, sweep_frames(p, t, [1.0, 0, 0]), square(0.1))
    m = Mesh(v, f)
    assert m.is_watertight and m.is_manifold
    assert m.volume == pytest.approx(0.01 * 1.5, rel=1e-12)


def test_resolution_control_gives_the_counts():
    net = build(arc_curve())
    m = sweep_network(net, circle(0.01, 12), 30, cut=False)
    assert len(m.parts) == 8
    assert all(p.vertices[1] - p.vertices[0] == 31 * 12 for p in m.parts)
    assert all(p.faces[1] - p.faces[0] == 2 * 30 * 12 + 2 * 10 for p in m.parts)


def test_open_profiles_sweep_sheets_without_caps():
    net = build(arc_curve())
    m = sweep_network(net, ribbon(0.05), 20, cut=False)
    assert m.parts[0].faces[1] - m.parts[0].faces[0] == 2 * 20 * 1
    assert not m.is_watertight


@pytest.mark.parametrize("name", ["teaching-sheet/tn-1.uc", "web/U.XI.28.uc", "web/ribbons/side5-metal.uc"])
def test_part_names_are_the_network_curve_ids(name):
    net = network(name)
    m = sweep_network(net, square(0.01), 16)
    ids = {c.id for c in net.curves() if c.kind in SWEPT_KINDS}
    assert {p.name for p in m.parts} == ids


@pytest.mark.parametrize("name", SOME)
def test_replicas_are_exact_images_of_the_basic_member(name):
    net = network(name)
    m = sweep_network(net, square(0.01), 40)
    by_name = {p.name: p for p in m.parts}
    for p in m.parts:
        if p.replica == "r0":
            continue
        base = by_name[p.name.replace(f"/{p.replica}", "/r0", 1)]
        sym = net.drawing.curves[p.basic].symmetry
        M = sym.matrices()[sym.labels().index(p.replica)]
        c = np.asarray(sym.center)
        v0 = m.vertices[base.vertices[0]:base.vertices[1]]
        v1 = m.vertices[p.vertices[0]:p.vertices[1]]
        assert np.abs(v1[:, :2] - ((v0[:, :2] - c) @ M.T + c)).max() < 1e-14 * _size(net)
        assert np.array_equal(v1[:, 2], v0[:, 2])


@pytest.mark.parametrize("path", ALL, ids=IDS)
def test_joints_of_neighbouring_replicas_coincide_at_the_mirror_plane(path):
    net = network(path)
    size = _size(net)
    prof = profile_for("bar", default_size(net), 8)
    for mb in sweep_members(net, prof, 48):
        sym = net.drawing.curves[mb.basic].symmetry
        c = np.asarray(sym.center)
        for cut in mb.cuts:
            (loop,) = plane_loops(mb.vertices, mb.faces, cut.origin, cut.normal, 1e-9 * size)
            M = sym.matrices()[cut.element]
            img = mb.vertices.copy()
            img[:, :2] = (img[:, :2] - c) @ M.T + c
            a, b = mb.vertices[loop], img[loop]
            # the neighbour's cut outline is the same polygon ...
            assert np.linalg.norm(a[:, None] - b[None], axis=2).min(axis=1).max() < 1e-9 * size
            # ... and neither member reaches across the plane: no overlap
            assert ((mb.vertices - cut.origin) @ cut.normal).min() > -1e-9 * size
            assert ((img - cut.origin) @ cut.normal).max() < 1e-9 * size


def test_ends_on_mirror_axes_are_cut_and_their_frames_meet_the_plane():
    net = build(star())
    (mb,) = sweep_members(net, square(0.05), 40)
    assert sorted(c.end for c in mb.cuts) == [0, 1]
    f = mb.frames[0]
    for cut in mb.cuts:
        w = f.width[0] if cut.end == 0 else f.width[-1]
        d = f.depth[0] if cut.end == 0 else f.depth[-1]
        # a square's side faces the plane: W or D is its normal
        assert max(abs(w @ cut.normal), abs(d @ cut.normal)) == pytest.approx(1.0, abs=1e-12)


def test_a_joint_is_one_bar_at_the_bottom():
    """At the common bottom point the two cut halves make one square bar of the full section."""
    net = build(star())
    m = sweep_network(net, square(0.05), 60)
    z0 = m.vertices[:, 2].min()
    bottom = m.vertices[(np.abs(m.vertices[:, 2] - z0) < 1e-12) & (m.vertices[:, 0] > 0)]   # at (1, 0)
    ext = bottom.max(0) - bottom.min(0)
    assert ext[:2].max() == pytest.approx(0.05, rel=1e-9)


@pytest.mark.parametrize("name", SOME)
def test_every_member_closed_at_its_cuts_is_watertight_with_positive_volume(name):
    net = network(name)
    for mb in sweep_members(net, profile_for("tube", default_size(net), 10), 40):
        v, f = closed_member(mb)
        m = Mesh(v, f)
        assert m.is_watertight and m.is_manifold, mb.piece
        assert m.volume > 0


# -- lifted sketch pieces (3D cubic Beziers) ---------------------------------------------------------


def _bezier3(c, t):
    m = 1.0 - t[:, None]
    tt = t[:, None]
    return m**3 * c[0] + 3 * m * m * tt * c[1] + 3 * m * tt * tt * c[2] + tt**3 * c[3]


def _sketch_network(controls):
    """A network of lifted sketch pieces, one basic curve each, as the lifting package builds it."""
    from auszug.geometry import CubicBezier
    from auszug.geometry.network import CurveNetwork, Piece, SideCoordinate, SymmetryGroup

    pieces = tuple(Piece(k, 0, "sketch", CubicBezier.from_array(c[:, :2]), None, SideCoordinate("u"),
                         c[[0, 3]].copy(), depth=c[:, 2].copy()) for k, c in enumerate(controls))
    return CurveNetwork(pieces, tuple(SymmetryGroup(1) for _ in controls), tuple(0 for _ in controls), (0.0,),
                        float(np.abs(np.concatenate(controls)).max()))


SKETCH_BEZIERS = [np.array([[0.0, 0, 0], [1, 0.5, 0.8], [2, -0.3, 1.2], [3, 0.2, 0.1]]),
                  # a handle on its end point (zero derivative there) and a stretch along the view (z)
                  np.array([[0.0, 0, 0], [0, 0, 0], [0.1, 0.2, 1.5], [0.2, 0.1, 2.5]])]


@pytest.mark.parametrize("c", SKETCH_BEZIERS, ids=["generic", "end-handle-along-view"])
def test_sketch_pieces_sweep_rings_of_the_radius_around_the_exact_3d_bezier(c):
    net = _sketch_network([c])
    piece = net.pieces[0]
    assert "sketch" in SWEPT_KINDS
    (run,) = sample_piece(piece, 60)
    # samples on the exact 3D curve: Bernstein in x, y (the top view) and in z (the depths)
    t = np.array([piece.top.project(q) for q in run.points[:, :2]])
    assert np.abs(_bezier3(c, t) - run.points).max() < 1e-9
    assert run.points[0].tolist() == c[0].tolist() and run.points[-1].tolist() == c[3].tolist()
    # even in 3D arc length (within 1 %), unit tangents along the chords
    step = np.linalg.norm(np.diff(run.points, axis=0), axis=1)
    assert step.max() / step.min() < 1.01
    chord = np.diff(run.points, axis=0) / step[:, None]
    mid = run.tangents[:-1] + run.tangents[1:]
    mid /= np.linalg.norm(mid, axis=1, keepdims=True)
    assert np.einsum("ij,ij->i", chord, mid).min() > math.cos(math.radians(2))
    # the member: every ring at distance r from its sample, in the sample's normal plane
    r, m = 0.05, 12
    (member,) = sweep_members(net, circle(r, m), segments=60, kinds=("sketch",))
    rings = member.vertices[: 61 * m].reshape(61, m, 3) - run.points[:, None, :]
    assert np.abs(np.linalg.norm(rings, axis=2) - r).max() < 1e-12
    assert np.abs(np.einsum("kij,kj->ki", rings, run.tangents)).max() < 1e-12
    mesh = Mesh(member.vertices, member.faces)
    assert mesh.is_watertight and mesh.volume > 0


def test_a_lifted_network_meshes_with_every_piece_a_member():
    from auszug.meshing import Look, mesh_network

    net = _sketch_network(SKETCH_BEZIERS)
    m = mesh_network(net, Look(style="tube", size=0.1, around=8, segments=20)).mesh
    assert [p.name for p in m.parts] == [c.id for c in net.curves()]
    assert len(m.vertices) == 2 * 21 * 8 and m.is_watertight   # rings only: the caps triangulate the end rings
