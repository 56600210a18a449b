"""The sweep model: exact profiles, paths, rigid frames, evaluation and meshes, against closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest

from auszug.errors import GeometryError
from auszug.geometry import Arc
from auszug.meshing import Path, Profile, RigidFrames, Sweep, circle, from_dict, offset_loft
from auszug.meshing.sweep import sweep_members
from auszug.meshing.sweepmodel import _expm, _rotvec

from .test_profile import MOULDING

RNG = np.random.default_rng(20251)


def _random_rotations(k: int) -> np.ndarray:
    q = RNG.normal(size=(k, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
    ], axis=1)


def _helix(n: int = 80, turns: float = 1.5, radius: float = 1.0, pitch: float = 0.7) -> Path:
    th = np.linspace(0.0, 2 * math.pi * turns, n)
    p = np.stack([radius * np.cos(th), radius * np.sin(th), pitch * th / (2 * math.pi)], axis=1)
    t = np.stack([-radius * np.sin(th), radius * np.cos(th), np.full(n, pitch / (2 * math.pi))], axis=1)
    return Path(p, t / np.linalg.norm(t, axis=1, keepdims=True))


# -- profiles: the exact outline and its samples ----------------------------------------------


@pytest.mark.parametrize("tol", [1e-2, 1e-4, 1e-6])
def test_samples_lie_on_the_exact_arcs_and_their_chords_stay_within_the_tolerance(tol):
    p = from_dict(MOULDING, around=12).scaled(100.0)  # the roll: radius 0.5, a half circle in 4 arcs
    s = p.sample(tolerance=tol)
    roll = s[s[:, 1] > 0.41]
    assert np.allclose(np.hypot(roll[:, 0], roll[:, 1] - 0.4), 0.5, rtol=0, atol=1e-14)
    # every chord of the arc within tol of it: the sagitta r (1 - cos(step / 2)) <= tol
    arc = s[(s[:, 1] >= 0.4 - 1e-12) & (np.abs(s[:, 0]) <= 0.5 + 1e-12)]
    mids = 0.5 * (arc[1:] + arc[:-1])
    sag = 0.5 - np.hypot(mids[:, 0], mids[:, 1] - 0.4)
    assert sag.max() <= tol * (1 + 1e-9) and sag.max() > tol / 4
    assert p.exact_area == pytest.approx(0.8 + 0.5 * math.pi * 0.25, rel=1e-13)
    assert p.length == pytest.approx(2 + 0.4 + 0.5 + math.pi * 0.5 + 0.5 + 0.4, rel=1e-13)


def test_point_is_exact_arc_length_and_refined_keeps_the_geometry():
    c = circle(2.0, 6)
    u = np.linspace(0.0, 1.0, 25)
    q = c.point(u)
    assert np.allclose(q, 2.0 * np.stack([np.cos(2 * math.pi * u), np.sin(2 * math.pi * u)], 1), rtol=0, atol=1e-14)
    assert c.length == pytest.approx(4 * math.pi, rel=1e-14)
    fine = c.refined(per_arc=5)
    assert fine.n == 30 and fine.exact_area == pytest.approx(c.exact_area, rel=1e-14)
    assert np.allclose(fine.point(u), q, atol=1e-12)
    assert c.sample(per_arc=5).shape == (30, 2) and np.array_equal(c.sample(), c.points)


@pytest.mark.parametrize("prof", [
    circle(0.3, 7),
    from_dict(MOULDING, around=20),
    Profile([[0, 0], [0.6, 0.6], [0.6, 1.2]], closed=False, name="round", bulge=[math.tan(math.pi / 8), 0]),
    Profile([[1, 0], [-1, 0]], closed=True, name="lens", bulge=[0.3, 0.3]),
])
def test_profile_round_trip_through_its_dict(prof):
    before = prof.points.copy()
    d = prof.to_dict()
    again = from_dict(d)
    assert again == prof and hash(again) == hash(prof)
    assert again.exact_area == prof.exact_area and again.length == prof.length
    assert np.array_equal(prof.points, before)


def test_clockwise_arcs_are_reversed_with_their_bulges():
    ccw = Profile([[1, 0], [0, 1], [-1, 0]], bulge=[0.2, 0.0, -0.1])
    cw = Profile(ccw.points[::-1], bulge=-np.array([0.0, 0.2, -0.1])[[0, 1, 2]])
    assert cw.exact_area == pytest.approx(ccw.exact_area, rel=1e-14) and cw.exact_area > 0
    with pytest.raises(GeometryError, match="bulge must be 3 finite numbers"):
        Profile([[1, 0], [0, 1], [-1, 0]], bulge=[0.1, 0.2])


# -- sweeps with closed forms ------------------------------------------------------------------


def test_a_straight_extrusion_is_the_exact_cylinder():
    r = 0.4
    z = np.linspace(0.0, 3.0, 7)
    sw = Sweep(circle(r, 12), Path.polyline(np.stack([0 * z, 0 * z, z], 1)))
    s, v = np.meshgrid(np.linspace(0, 3, 11), np.linspace(0, 1, 37), indexing="ij")
    x = sw.point(s, v)
    # the frame starts with W = x, D = y (the reference basis of +z) and does not turn along a line
    want = np.stack([r * np.cos(2 * math.pi * v), r * np.sin(2 * math.pi * v), s], -1)
    assert np.allclose(x, want, rtol=0, atol=1e-14)
    m = sw.mesh()
    assert m.is_watertight and m.volume == pytest.approx(3.0 * circle(r, 12).area, rel=1e-13)


def test_a_revolution_is_the_exact_torus_at_the_knots_and_close_between():
    big, r, n = 2.0, 0.5, 64
    th = np.linspace(0.0, 2 * math.pi, n)
    path = Path(big * np.stack([np.cos(th), np.sin(th), 0 * th], 1), np.stack([-np.sin(th), np.cos(th), 0 * th], 1),
                big * th)
    fr = RigidFrames.rotation_minimising(path, width0=[1.0, 0.0, 0.0])
    sw = Sweep(circle(r, 16), path, fr)
    v = np.linspace(0.0, 1.0, 33)
    x = sw.point(path.knots[:, None], v[None, :])
    phi = 2 * math.pi * v[None, :]
    # W radial outwards, D = T x W = -z
    want = np.stack([(big + r * np.cos(phi)) * np.cos(th[:, None]), (big + r * np.cos(phi)) * np.sin(th[:, None]),
                     -r * np.sin(phi) + 0 * th[:, None]], -1)
    assert np.allclose(x, want, rtol=0, atol=1e-12)
    # between knots the origin moves on the chord: off the torus by at most the chord's sagitta
    mid = sw.point(0.5 * (path.knots[1:] + path.knots[:-1])[:, None], v[None, :])
    dev = np.abs(np.hypot(np.hypot(mid[..., 0], mid[..., 1]) - big, mid[..., 2]) - r)
    assert dev.max() <= big * (1 - math.cos(math.pi / (n - 1))) * 1.01
    m = sw.mesh()
    assert m.is_watertight  # capped ends meet


def test_rotation_minimising_frames_are_proper_rotations():
    fr = Sweep(from_dict(MOULDING), _helix()).rigid
    r = fr.rotation
    assert np.abs(np.einsum("kji,kjl->kil", r, r) - np.eye(3)).max() < 1e-13
    assert np.allclose(np.linalg.det(r), 1.0, atol=1e-13)
    assert np.allclose(fr.tangent, _helix().tangents, atol=1e-13)
    ri, _ = fr.at(RNG.uniform(fr.s[0], fr.s[-1], 200))
    assert np.abs(np.einsum("kji,kjl->kil", ri, ri) - np.eye(3)).max() < 1e-12
    assert np.allclose(np.linalg.det(ri), 1.0, atol=1e-12)


def test_evaluation_between_given_frames_interpolates_rigidly():
    k = 6
    rot = _random_rotations(k)
    org = RNG.normal(size=(k, 3))
    s = np.cumsum(RNG.uniform(0.2, 1.0, k))
    fr = RigidFrames(s, rot, org)
    prof = from_dict(MOULDING)
    sw = Sweep(prof, Path.polyline(org), fr)
    # at the knots: exactly the given motions
    r_at, t_at = sw.frames_at(s)
    assert np.array_equal(r_at, rot) and np.array_equal(t_at, org)
    # half way: the half rotation (squared it is the whole relative rotation), the chord's midpoint
    half = 0.5 * (s[1:] + s[:-1])
    r_h, t_h = sw.frames_at(half)
    rel_h = np.einsum("kji,kjl->kil", rot[:-1], r_h)
    rel = np.einsum("kji,kjl->kil", rot[:-1], rot[1:])
    assert np.allclose(rel_h @ rel_h, rel, atol=1e-12)
    assert np.allclose(t_h, 0.5 * (org[1:] + org[:-1]), atol=1e-15)
    # rigid: distances between profile points are kept at any s
    ss = RNG.uniform(s[0], s[-1], 50)
    v1, v2 = RNG.uniform(0, 1, 50), RNG.uniform(0, 1, 50)
    d3 = np.linalg.norm(sw.point(ss, v1) - sw.point(ss, v2), axis=1)
    d2 = np.linalg.norm(prof.point(v1) - prof.point(v2), axis=1)
    assert np.allclose(d3, d2, rtol=0, atol=1e-13)


def test_rotation_log_and_exp_are_inverse_including_half_turns():
    rot = _random_rotations(50)
    assert np.allclose(_expm(_rotvec(rot)), rot, atol=1e-12)
    half = _expm(np.array([[0.0, 0.0, math.pi], [math.pi / math.sqrt(2), math.pi / math.sqrt(2), 0.0]]))
    assert np.allclose(_expm(_rotvec(half)), half, atol=1e-12)


def test_explicit_frames_must_be_rotations():
    bad = np.stack([np.eye(3), np.diag([1.0, 1.0, -1.0])])
    with pytest.raises(GeometryError, match="frame 1 is not a rotation"):
        RigidFrames(np.array([0.0, 1.0]), bad, np.zeros((2, 3)))
    with pytest.raises(GeometryError, match="only 2 vertices; sample its arcs"):
        Sweep(Profile([[1, 0], [-1, 0]], bulge=[0.4, 0.4]), _helix()).mesh()


def test_closed_profiles_along_a_helix_mesh_watertight_with_caps():
    for prof in (from_dict(MOULDING), circle(0.1, 9), Profile([[1, 0], [-1, 0]], bulge=[0.4, 0.4]).scaled(0.1)):
        sw = Sweep(prof, _helix())
        m = sw.mesh(per_arc=2) if prof.n < 3 else sw.mesh()
        assert m.is_watertight and m.is_manifold and m.volume > 0
        fine = sw.mesh(tolerance=1e-6)
        assert fine.is_watertight and fine.n_vertices > m.n_vertices
        # centroid (nearly) on the path: the volume is the exact area times the path's length (Pappus)
        assert fine.volume == pytest.approx(prof.exact_area * sw.path.length, rel=1e-2)


def test_members_are_sweeps_whose_surface_passes_through_their_vertices():
    from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry, build

    c = BasicCurve(((1.0, 0.0), (0.0, 1.0)), (Segment("line"),), ("ground", "apex"), Symmetry(fold=2), height=1.0)
    prof = circle(0.02, 8)
    (mb,) = sweep_members(build(Drawing((c,))), prof, segments=16, cut=False, caps=False)
    sw = mb.sweeps[0]
    u = np.arange(prof.n) / prof.n  # the vertices' arc length: a regular polygon's
    x = sw.point(sw.rigid.s[:, None], u[None, :]).reshape(-1, 3)
    assert np.allclose(x, mb.vertices[: len(x)], rtol=0, atol=1e-15)


# -- sweeps along planar loops: the offset loft -----------------------------------------------


def test_the_offset_loft_of_a_circle_is_the_sweep_with_planar_frames():
    big = 1.0
    loop = (Arc(np.array([0.0, 0.0]), big, 0.0, math.pi), Arc(np.array([0.0, 0.0]), big, math.pi, math.pi))
    levels = np.array([[0.0, 0.0], [0.1, 0.1], [0.1, 0.3], [0.25, 0.4]])
    lf = offset_loft(loop, levels, math.pi / 24, 1e-4)
    assert [len(r) for r in lf.rings] == [48] * 4 and lf.heights == [0.0, 0.1, 0.3, 0.4]
    th = np.arctan2(lf.rings[0][:, 1], lf.rings[0][:, 0])
    path = Path(big * np.stack([np.cos(th), np.sin(th), 0 * th], 1), np.stack([-np.sin(th), np.cos(th), 0 * th], 1),
                np.unwrap(th) - th[0])
    w = -path.points / big  # profile x: the inward normal
    d = np.tile([0.0, 0.0, 1.0], (len(th), 1))  # profile y: the plane's normal
    frames = RigidFrames(path.knots, np.stack([w, d, np.cross(w, d)], axis=2), path.points)
    prof = Profile(levels, closed=False)
    sw = Sweep(prof, path, frames)
    acc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(levels, axis=0), axis=1))])
    x = sw.point(path.knots[None, :], (acc / acc[-1])[:, None])
    for k, ring in enumerate(lf.rings):
        assert np.allclose(x[k, :, :2], ring, rtol=0, atol=1e-14)
        assert np.allclose(x[k, :, 2], lf.heights[k], rtol=0, atol=1e-15)
