"""Kinematic sweep patches (auszug.sweeps.patches): profile, motion, faces, fit error, coverage."""

from __future__ import annotations

from dataclasses import replace
from functools import cache

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from auszug.sweeps import cut, initial_planes, kinematic_axis, movability, normalise
from auszug.sweeps.fixtures import extruded, helical, revolved, with_hole
from auszug.sweeps.params import DEFAULT
from auszug.sweeps.patches import kinematic_patches, polyline_hausdorff

N_PROFILE = 60


@cache
def _patches(name, sigma, eps=0.005):
    fx = {"revolved": revolved, "extruded": extruded}[name](sigma=sigma)
    m = normalise(fx.vertices, fx.faces)
    c = cut(m, *initial_planes(m.vertices, 4, 0.055))
    k = kinematic_axis(c, movability(c))
    return fx, m, k, kinematic_patches(m, k, DEFAULT.with_(eps_prox=eps))


def _end_rings(name):
    """The clean fixture's first and last ring of vertices: the true profile at either end."""
    fx = {"revolved": revolved, "extruded": extruded}[name]()
    return fx.vertices[:N_PROFILE], fx.vertices[-N_PROFILE:]


def _profile_error(name, patch):
    return min(polyline_hausdorff(patch.profile, ring) for ring in _end_rings(name))


@pytest.mark.parametrize("name", ["revolved", "extruded"])
def test_clean_kinematic_patch_is_the_whole_mesh_and_its_profile(name):
    fx, m, k, patches = _patches(name, 0.0)
    assert len(patches) == 1
    p = patches[0]
    assert p.kind == ("rotation" if name == "revolved" else "translation")
    assert p.coverage >= 0.999 and len(p.faces) == len(fx.faces)
    assert _profile_error(name, p) <= 1e-3
    assert p.fit_error <= 2 * 0.005 and p.fit_error <= 2e-4
    assert len(p.motion) >= 8
    assert np.allclose(p.motion.rotation[0], np.eye(3)) and np.allclose(p.motion.translation[0], 0)


@pytest.mark.parametrize("name", ["revolved", "extruded", "helical"])
@pytest.mark.parametrize("sigma", [0.0, 5e-4])
def test_a_hole_across_the_middle_cut_leaves_one_whole_patch(name, sigma):
    """The hole lies on the middle profile cut (it is cut around the mesh's middle vertex): the profile
    is taken from the cut nearest the middle that is not shortened (was: two patches with 0.45 + 0.36
    of the extrusion, 0.54 of the surface of revolution). Measured: coverage 1.000 each."""
    fx = with_hole({"revolved": revolved, "extruded": extruded, "helical": helical}[name](sigma=sigma))
    m = normalise(fx.vertices, fx.faces)
    c = cut(m, *initial_planes(m.vertices, 4, 0.055))
    patches = kinematic_patches(m, kinematic_axis(c, movability(c)), DEFAULT.with_(eps_prox=0.005))
    assert len(patches) == 1 and patches[0].coverage >= 0.99
    whole = np.linalg.norm(np.diff(patches[0].profile, axis=0), axis=1).sum()
    assert whole >= 0.98 * fx.profile_length
    if name != "helical":
        assert _profile_error(name, patches[0]) <= (1e-3 if sigma == 0 else 2e-3)


def test_revolved_motion_is_the_true_rotation_over_300_degrees():
    fx, m, k, (p,) = _patches("revolved", 0.0)
    assert p.motion.t[-1] == pytest.approx(np.radians(300.0), abs=1e-3)
    sign = np.sign(k.direction @ fx.axis_direction)
    t = np.linspace(*p.motion.domain, 31)
    r, tr = p.motion.at(t)
    truth = Rotation.from_rotvec(sign * t[:, None] * fx.axis_direction).as_matrix()
    rot_err = np.degrees(Rotation.from_matrix(np.einsum("kij,kjl->kil", r, np.swapaxes(truth, 1, 2))).magnitude())
    assert np.median(rot_err) <= 0.5 and rot_err.max() <= 0.05
    # the axis point stays put
    fixed = np.einsum("kij,j->ki", r, fx.axis_point) + tr
    assert np.abs(fixed - fx.axis_point).max() <= 1e-3


def test_extruded_motion_is_the_true_translation():
    fx, m, k, (p,) = _patches("extruded", 0.0)
    t = np.linspace(*p.motion.domain, 11)
    r, tr = p.motion.at(t)
    assert np.abs(r - np.eye(3)).max() <= 1e-12
    sign = np.sign(k.direction @ fx.axis_direction)
    assert np.abs(tr - sign * t[:, None] * fx.axis_direction).max() <= 1e-3
    assert p.motion.t[-1] == pytest.approx(np.ptp(fx.vertices[:, 0]), abs=1e-9)


@pytest.mark.parametrize("name", ["revolved", "extruded"])
@pytest.mark.parametrize("sigma", [5e-4, 1e-3])
def test_noisy_kinematic_patch(name, sigma):
    fx, m, k, patches = _patches(name, sigma)
    assert len(patches) == 1
    p = patches[0]
    assert p.coverage >= 0.85
    assert p.fit_error <= 2 * 0.005
    assert _profile_error(name, p) <= 4 * sigma


@pytest.mark.parametrize("sigma", [0.0, 5e-4, 1e-3])
def test_revolved_motion_keeps_the_true_axis_point_within_1e_3(sigma):
    """Issue target: translation error of the motion, median <= 1e-3. The true axis point, in the
    coordinates the motion is in (the noisy mesh normalises to a slightly shifted centre and scale:
    3.8e-4 and 1.0018 at sigma 5e-4, which alone moved the point by 1.2e-3 in an earlier measurement),
    stays put: measured median / max 7.6e-5 / 9.9e-5, 3.2e-4 / 4.2e-4, 1.8e-4 / 2.3e-4."""
    fx, m, k, (p,) = _patches("revolved", sigma)
    point = (fx.axis_point - m.centre) / m.scale
    r, tr = p.motion.at(np.linspace(*p.motion.domain, 31))
    move = np.linalg.norm(np.einsum("kij,j->ki", r, point) + tr - point, axis=1)
    assert np.median(move) <= 1e-3 and move.max() <= 1e-3


def test_profile_improvement_reduces_noise():
    """Sec. 2.3.3: averaging intermediate cuts mapped back by the motion beats the single cut."""
    fx = revolved(sigma=1e-3)
    m = normalise(fx.vertices, fx.faces)
    c = cut(m, *initial_planes(m.vertices, 4, 0.055))
    k = kinematic_axis(c, movability(c))
    one = kinematic_patches(m, k, DEFAULT.with_(profile_cuts=0))[0]
    many = kinematic_patches(m, k, DEFAULT.with_(profile_cuts=16))[0]
    assert _profile_error("revolved", many) < 0.75 * _profile_error("revolved", one)


def test_tight_eps_prox_covers_less_of_a_noisy_mesh():
    *_, (loose,) = _patches("revolved", 1e-3, 0.005)
    *_, (tight,) = _patches("revolved", 1e-3, 0.001)
    assert tight.coverage < 0.5 < 0.99 < loose.coverage
    assert set(tight.faces.tolist()) <= set(loose.faces.tolist())


def test_sweep_value_remeshes_onto_the_mesh():
    """A found patch is a value of meshing's sweep model; its mesh lies on the input."""
    from auszug.sweeps.patches import closest_distance

    fx, m, k, (p,) = _patches("revolved", 0.0)
    sw = p.sweep()
    mesh = sw.mesh()
    d, _ = closest_distance(mesh.vertices, m.vertices, m.faces)
    assert d.max() <= 2e-4
    r, t = sw.frames_at(sw.rigid.s)
    assert np.allclose(np.linalg.det(r), 1.0)


def test_hausdorff_of_polylines_known_answer():
    a = np.array([[0, 0, 0], [1, 0, 0.0]])
    b = np.array([[0, 0.2, 0], [0.5, 0.3, 0], [1, 0.2, 0.0]])
    assert polyline_hausdorff(a, b) == pytest.approx(0.3)
    assert polyline_hausdorff(a, a) == 0.0


def test_closed_profile_of_an_extruded_pipe():
    """A pipe (closed cross-section, no caps) is one translation patch with a closed profile; its
    sweep value re-meshes exactly onto the input."""
    from auszug.sweeps import detect
    from auszug.sweeps.patches import closest_distance

    n, k = 48, 30
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    prof = np.column_stack([0.3 * np.cos(a) + 0.05 * np.cos(3 * a), 0.2 * np.sin(a)])
    z = np.linspace(0, 0.8, k)
    v = np.column_stack([np.tile(prof[:, 0], k), np.tile(prof[:, 1], k), np.repeat(z, n)])
    i, j = np.meshgrid(np.arange(k - 1), np.arange(n), indexing="ij")
    a0, b0 = i * n + j, i * n + (j + 1) % n
    f = np.vstack([np.stack([a0, b0, b0 + n], -1).reshape(-1, 3), np.stack([a0, b0 + n, a0 + n], -1).reshape(-1, 3)])
    (p,) = detect((v, f)).patches
    assert p.kind == "translation" and p.closed and p.coverage == pytest.approx(1.0)
    assert p.motion.t[-1] == pytest.approx(0.8 / np.linalg.norm(np.ptp(v, axis=0)))
    d, _ = closest_distance(replace(p, profile_fit=None).sweep().mesh(caps=False).vertices, v, f)
    assert d.max() <= 1e-12
    # the profile is no line-and-arc curve: its fit (the default sweep) stays within its Hausdorff distance
    fit = p.profile_fit
    assert fit is not None and fit.profile.closed and 0 < fit.hausdorff <= DEFAULT.profile_fit_tolerance
    d, _ = closest_distance(p.sweep().mesh(caps=False).vertices, v, f)
    assert d.max() <= fit.hausdorff * np.linalg.norm(np.ptp(v, axis=0)) * (1 + 1e-9)


@pytest.mark.parametrize("sigma", [0.0, 5e-4])
def test_helical_surface_is_one_screw_patch(sigma):
    """The base moulding screwed by 540 deg: the screw's pitch and angle come out, the profile at both
    ends lies on the mesh."""
    from auszug.sweeps import detect
    from auszug.sweeps.fixtures import helical
    from auszug.sweeps.patches import closest_distance

    fx = helical(sigma=sigma)
    r = detect((fx.vertices, fx.faces))
    (p,) = r.patches
    assert p.kind == "screw" and r.coverage >= (0.95 if sigma == 0 else 0.85)
    assert np.degrees(p.motion.t[-1]) == pytest.approx(540.0, abs=0.1 if sigma == 0 else 1.0)
    diam = float(np.linalg.norm(np.ptp(fx.vertices * 1.0, axis=0)))
    lift = p.motion.apply(fx.axis_point[None], [2 * np.pi])[0, 0] - fx.axis_point      # one turn along the axis
    assert abs(abs(lift @ fx.axis_direction) - 2 * np.pi * 0.1 / helical_diameter()) <= 2e-3 * diam
    for pts in (p.profile, p.motion.apply(p.profile, [p.motion.t[-1]])[0]):
        d, _ = closest_distance(pts, fx.vertices, fx.faces)
        assert d.max() <= (5e-4 if sigma == 0 else 3e-3)
    assert p.fit_error <= 2 * 0.005


def helical_diameter():
    """Bounding-box diameter of the helical fixture before normalisation."""
    from auszug.sweeps.fixtures import gothic_base_profile

    p, _ = gothic_base_profile(60)
    th = np.radians(np.linspace(0.0, 540.0, 240))
    r, z = np.tile(p[:, 0], 240), np.tile(p[:, 1], 240)
    t = np.repeat(th, 60)
    v = np.column_stack([r * np.cos(t), r * np.sin(t), z + 0.1 * t])
    return float(np.linalg.norm(np.ptp(v, axis=0)))


def _sheets(hole: bool, shift: float = 0.0):
    """Two parallel unit squares 0.01 apart (the two sides of a fold), the lower one shifted down by
    ``shift`` and, with ``hole``, without its faces within 0.2 of its centre: ``(V, F)``."""
    from auszug.sweeps.fixtures import grid_faces

    n = 41
    x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n), indexing="ij")
    lower = np.column_stack([x.ravel(), y.ravel(), np.full(n * n, -shift)])
    upper = lower + [0, 0, 0.01 + shift]
    f = grid_faces(n, n)
    if hole:
        centre = lower[f].mean(axis=1)[:, :2]
        f = f[np.linalg.norm(centre - 0.5, axis=1) > 0.2]
    return np.vstack([lower, upper]), np.vstack([f, grid_faces(n, n) + n * n])


def test_interior_distance_over_a_hole_beside_a_fold_is_not_counted():
    """Over a hole, the closest mesh point of a swept point may lie on the fold's other side, not on
    the hole's rim: with the swept surface given, that point counts as beyond the mesh; a swept
    surface off the mesh by more than eps still counts everywhere (reciprocal closest points)."""
    from auszug.sweeps.patches import MeshTree

    v, f = _sheets(hole=True)
    tree = MeshTree(v, f)
    over_hole = np.array([[0.5, 0.5, 0.0], [0.45, 0.55, 0.0]])
    on_mesh = np.array([[0.1, 0.1, 0.0], [0.9, 0.3, 0.01]])
    plain = tree.interior_distance(over_hole)
    assert np.allclose(plain, 0.01)                                    # the upper sheet, not the rim
    swept = _sheets(hole=False)                                        # the whole fold, as swept
    assert np.allclose(tree.interior_distance(over_hole, swept, 0.005), 0.0)
    assert np.allclose(tree.interior_distance(on_mesh, swept, 0.005), 0.0, atol=1e-12)
    # a sweep 0.008 below the lower sheet: its points beside the hole are 0.008 off (closest mesh
    # point on the lower sheet, which that sweep does not pass through)
    low = _sheets(hole=False, shift=0.008)
    off = np.array([[0.1, 0.1, -0.008], [0.8, 0.75, -0.008]])
    assert np.allclose(tree.interior_distance(off, low, 0.005), 0.008)


def _pleated_sweep(amplitude: float = 0.015):
    """A flat mesh (the unit square at z = 0, 41 x 41 vertices) and a profile that zigzags across it and
    doubles back on itself (x: 0, 0.018, 0.012, 0.030, 0.024, ...; z: +-``amplitude`` in turn, 0 at the two
    ends; 12 points),
    translated 0.4 along y over the square's middle: ``(V, F, profile (12, 3), motion)``.

    Every inner profile point lies ``amplitude`` off the mesh; each of the swept surface's sheets crosses
    the mesh at 40-79 deg, halfway between two profile points, 0.003 along x from each inner point (so within
    0.003 of the closest mesh point of a far profile point: the swept surface overlaps itself over the mesh,
    as the tracery border's coarse-pass sweeps did)."""
    from auszug.sweeps.fixtures import grid_faces
    from auszug.sweeps.motion import Motion

    n = 41
    x, y = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n), indexing="ij")
    v = np.column_stack([x.ravel(), y.ravel(), np.zeros(n * n)])
    k = np.arange(12)
    z = amplitude * (-1.0) ** k
    z[[0, -1]] = 0.0                    # the ends on the mesh: every far point has a sheet on each side
    profile = np.column_stack([0.4 + 0.006 * k + 0.012 * (k % 2), np.full(12, 0.3), z])
    t = np.linspace(0.0, 1.0, 9)
    motion = Motion(t, np.repeat(np.eye(3)[None], len(t), axis=0), np.outer(t, [0.0, 0.4, 0.0]))
    return v, grid_faces(n, n), profile, motion


def test_a_pleated_sweep_is_not_accepted_by_the_reciprocal_test():
    """A swept surface that doubles back across the mesh may not discount its own far points by its other
    sheets: the reciprocal test counts only a sheet lying along the mesh (``reciprocal_angle``, 30 deg; these
    sheets cross it at 40-79 deg), so the fit error is the profile's true distance to the mesh, 0.015 (above
    the fit bound 0.01). Without the normal test (180, the rule before sweeps-tree4) every far swept point is
    discounted and the pleat's fit error is 0 (sweeps-tree3: the tracery border's 4.997e-3 against 0.021)."""
    from auszug.sweeps.patches import MeshTree, swept_error

    v, f, profile, motion = _pleated_sweep()
    tree = MeshTree(v, f)
    eps = DEFAULT.eps_prox
    old = swept_error(profile, False, motion, eps, tree, angle=180.0).fit_error
    assert old == 0.0
    err = swept_error(profile, False, motion, eps, tree, angle=DEFAULT.reciprocal_angle).fit_error
    assert err == pytest.approx(0.015, abs=1e-9)
    assert err > DEFAULT.fit_factor * eps
    # the parallel fold of the hole test still discounts with the default angle (its sheets lie along the mesh)
    hv, hf = _sheets(hole=True)
    assert np.allclose(MeshTree(hv, hf).interior_distance([[0.5, 0.5, 0.0]], _sheets(hole=False), eps), 0.0)


def _half_swept_square(lift: float = 0.0):
    """A square of two triangles (normalised: half-side ``a``) and a translation sweeping a segment over
    its left half, ``lift`` above it: no triangle has its three corners on the swept strip."""
    from auszug.sweeps import Motion
    from auszug.sweeps.patches import SweepPatch

    m = normalise(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0.0]]), np.array([[0, 1, 2], [1, 3, 2]]))
    a = float(m.vertices[:, 0].max())
    prof = np.stack([np.linspace(-a, 0.0, 11), np.full(11, -a), np.full(11, lift)], axis=1)
    t = np.linspace(0.0, 2 * a, 8)
    motion = Motion(t, np.repeat(np.eye(3)[None], 8, axis=0), np.stack([0 * t, t, 0 * t], axis=1))
    return m, a, SweepPatch(0, "translation", prof, False, motion, np.zeros(0, np.int64), 0.0, 0.0)


def test_area_coverage_counts_the_part_of_a_long_face_on_a_patch():
    """Per face no triangle is covered (each has a corner beyond the strip); by area the strip and its
    ``eps`` band are: ``(a + eps) / 2a`` of the square (0.507 at eps 0.005), to the samples' precision."""
    from auszug.sweeps.patches import area_coverage, face_areas

    m, a, p = _half_swept_square()
    areas = face_areas(m.vertices, m.faces)
    share = area_coverage(m, [p], 0.005, 100_000, areas)
    assert float((share * areas).sum() / areas.sum()) == pytest.approx((a + 0.005) / (2 * a), abs=2e-3)
    # the left half holds 3/4 of the first triangle (corners (0, 0), (1, 0), (0, 1)) and 1/4 of the second
    assert share[0] == pytest.approx(0.75, abs=0.02) and share[1] == pytest.approx(0.25, abs=0.02)
    # no samples: the per-face figure (nothing); the strip 2 eps above the square: nothing either
    assert area_coverage(m, [p], 0.005, 0, areas).tolist() == [0.0, 0.0]
    _, _, off = _half_swept_square(lift=0.01)
    assert area_coverage(m, [off], 0.005, 100_000, areas).tolist() == [0.0, 0.0]
    # a face the patch holds whole counts whole
    assert area_coverage(m, [replace(p, faces=np.array([1]))], 0.005, 100_000, areas)[1] == 1.0


def test_area_samples_are_spread_by_area():
    from auszug.sweeps.patches import area_samples, face_areas

    fx = revolved(n_profile=20, n_path=30)
    areas = face_areas(fx.vertices, fx.faces)
    fid, x = area_samples(fx.vertices, fx.faces, 5000, areas)
    assert len(fid) == len(x) == 5000
    per = np.bincount(fid, minlength=len(fx.faces))
    want = 5000 * areas / areas.sum()
    assert np.all((per >= np.floor(want) - 1e-9) & (per <= np.ceil(want) + 1e-9))
    # each sample inside its face: barycentric coordinates in [0, 1]
    tri = fx.vertices[fx.faces[fid]]
    e1, e2, d = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0], x - tri[:, 0]
    g = np.stack([np.einsum("ij,ij->i", e1, e1), np.einsum("ij,ij->i", e1, e2), np.einsum("ij,ij->i", e2, e2)], 1)
    r = np.stack([np.einsum("ij,ij->i", d, e1), np.einsum("ij,ij->i", d, e2)], 1)
    det = g[:, 0] * g[:, 2] - g[:, 1] ** 2
    u = (g[:, 2] * r[:, 0] - g[:, 1] * r[:, 1]) / det
    w = (g[:, 0] * r[:, 1] - g[:, 1] * r[:, 0]) / det
    assert np.all((u >= -1e-9) & (w >= -1e-9) & (u + w <= 1 + 1e-9))
    assert len(area_samples(fx.vertices, fx.faces, 0)[0]) == 0


def _square(n_side: int, half: float = 0.01, phase: float = 0.0) -> np.ndarray:
    """A closed square loop in the plane z = 0, ``n_side`` points a side, shifted ``phase`` of a step along it."""
    u = (np.arange(n_side) + phase) / n_side * 2 * half - half
    one = np.full(n_side, half)
    return np.column_stack([np.r_[u, one, -u, -one], np.r_[-one, u, one, -u], np.zeros(4 * n_side)])


def test_fill_corners_puts_back_the_corners_the_profiles_chords_cut(monkeypatch):
    """A square profile sampled past its corners (every chord across a corner cuts it by 1.8e-3) and cuts
    of the square (its corners among their points): each corner is inserted, the profile is then the
    square (Hausdorff 0 up to round-off). Cuts that scatter to both sides of a segment (noise 5e-4) add
    nothing; nor does a tolerance above the chord's cut."""
    import auszug.sweeps.patches as patches_module
    from auszug.sweeps.patches import fill_corners

    truth = _square(8, phase=0.0)
    profile = _square(4, phase=0.5)                 # no point at a corner
    assert polyline_hausdorff(profile, truth, True, True) > 1.7e-3
    pieces = [np.vstack([truth, truth[:1]])] * 5
    pts, starts = np.vstack(pieces), np.cumsum([0] + [len(q) for q in pieces])
    out, new = fill_corners(profile, True, pts, starts, 5e-4, 0.005)
    assert len(new) == 4 and len(out) == len(profile) + 4
    assert polyline_hausdorff(out, truth, True, True) < 1e-12
    assert np.array_equal(np.delete(out, new, axis=0), profile)           # the old points kept, in order
    same, none = fill_corners(profile, True, pts, starts, 3e-3, 0.005)   # above the cut: nothing
    assert same is profile and len(none) == 0
    # a profile on the square with a point at each corner, cuts of the square with noise across it
    # (5e-4, a tolerance of 5e-5: 12 of the 16 segments would get a point were one side not asked for)
    rng = np.random.default_rng(0)
    noisy = [truth + rng.normal(0, 5e-4, truth.shape) * [1, 1, 0] for _ in range(40)]
    pts, starts = np.vstack(noisy), np.cumsum([0] + [len(q) for q in noisy])
    out, new = fill_corners(truth[::2], True, pts, starts, 5e-5, 0.005)
    assert len(new) == 0
    monkeypatch.setattr(patches_module, "CORNER_AGREEMENT", 0.5)
    assert len(fill_corners(truth[::2], True, pts, starts, 5e-5, 0.005)[1]) >= 8


def test_consistent_pieces_leave_out_the_knots_off_the_profile():
    """Pieces of 10 knots on the profile (within 1e-4) and of 2 knots 3e-3 off it (a grown sweep's ends): the
    2 knots' pieces are left out, the others kept as they were; trim 0 keeps all."""
    from auszug.sweeps.patches import consistent_pieces

    sq = _square(8)
    rng = np.random.default_rng(2)
    pieces = [sq + rng.normal(0, 5e-5, sq.shape) for _ in range(10)] + [sq * 1.3, sq * 1.3]
    pts, starts = np.vstack(pieces), np.cumsum([0] + [len(q) for q in pieces])
    key = np.arange(12)
    p, s, k = consistent_pieces(sq, True, pts, starts, key, 2.0)
    assert k.tolist() == list(range(10)) and np.array_equal(p, pts[:starts[10]]) and np.array_equal(s, starts[:11])
    p, s, k = consistent_pieces(sq, True, pts, starts, key, 0.0)
    assert p is pts and k is key


def test_key_distance_medians_are_those_of_every_point_distance():
    """The compiled per-knot medians (warm-started, pruned) equal the medians of the plain scan's distances bit
    for bit: open and closed profiles, pieces on vertices (ties), far off, empty pieces and knots without points."""
    from auszug.sweeps._kernels import key_distance_medians, polyline_closest

    rng = np.random.default_rng(5)
    for case in range(200):
        closed = case % 2 == 0
        n = int(rng.integers(3, 70))
        a = np.sort(rng.uniform(0, 2 * np.pi, n))
        prof = np.column_stack([np.cos(a), rng.uniform(0.2, 1.0) * np.sin(a), rng.normal(0, 0.01, n)])
        if case % 5 == 0:
            prof = np.round(prof * 4) / 4                  # repeated points, equal distances
        sizes = rng.integers(0, 40, int(rng.integers(1, 20)))
        starts = np.r_[0, np.cumsum(sizes)].astype(np.int64)
        key = rng.integers(0, 15, len(sizes)).astype(np.int64)
        pts = prof[rng.integers(0, n, starts[-1])] + rng.normal(0, rng.choice([0.0, 1e-3, 0.3]), (starts[-1], 3))
        ring = np.ascontiguousarray(np.vstack([prof, prof[:1]]) if closed else prof)
        med, count = key_distance_medians(np.ascontiguousarray(pts), ring, starts, key, 15)
        d = polyline_closest(np.ascontiguousarray(pts), ring)[0]
        of = np.repeat(key, sizes)
        for k in range(15):
            assert count[k] == np.sum(of == k)
            if count[k]:
                assert med[k] == np.median(d[of == k])
            else:
                assert np.isnan(med[k])
