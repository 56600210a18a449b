"""Kinematic parts (auszug.sweeps.parts): a moulding along a window's border, found piece by piece.

The fixture is the one of test_tracery_border.py: ``tracery.build("fig20a")``'s arch region with
the ``fig18`` profile lofted along its border (the sill and two jambs, lines; two arcs meeting at
the apex). Each line's stretch is an extrusion along it, each arc's a surface of revolution about
the axis through its centre normal to the window; the truth comes from the tracery's own curves.
"""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from auszug.sweeps import DEFAULT, cut, detect, initial_planes, normalise, sweep_length
from auszug.sweeps.fixtures import extruded, revolved
from auszug.sweeps.general import motion_planes
from auszug.sweeps.kinematic import axis_angle
from auszug.sweeps.parts import gliding_shares, part_faces, refined, unscrewed
from auszug.sweeps.planes import plane_recall

from .test_tracery_border import _border


@cache
def _report():
    v, f, *_ = _border()
    return detect((v, f))


def _arc_centres():
    """The border arcs' centres ``(2, 2)`` in the fixture's normalised frame.

    ``_border`` gives every border curve's middle point normalised; the tracery gives them in the
    window's units: two of them fix the scale and the shift."""
    from auszug.tracery import build

    _, _, _, _, where, _, _ = _border()
    curves = build("fig20a").regions[0].curves
    raw = np.array([c.point(np.array([0.5]))[0] for c in curves])
    norm = np.array([p for p, _, _, _ in where])
    scale = float(np.linalg.norm(raw[0] - raw[1]) / np.linalg.norm(norm[0] - norm[1]))
    shift = raw[0] - norm[0] * scale
    assert np.allclose(norm * scale + shift, raw, atol=1e-9 * scale)
    return np.array([(np.asarray(c.center, float) - shift) / scale for c in curves if type(c).__name__ == "Arc"])


def _rotation_axis(p):
    """Unit direction and a point of a rotation patch's axis (from its last map)."""
    r, t = p.motion.at(np.array([p.motion.t[-1]]))
    d = Rotation.from_matrix(r[0]).as_rotvec()
    point = np.linalg.lstsq(np.eye(3) - r[0], t[0], rcond=None)[0]
    return d / np.linalg.norm(d), point


def _translation(p):
    _, t = p.motion.at(np.array([p.motion.t[-1]]))
    return t[0] / np.linalg.norm(t[0])


def test_the_border_is_found_as_five_kinematic_parts():
    """Default parameters (before kinematic parts: no patch): jambs and sill as translations along
    the lines, within 0.2 deg; the arcs as rotations about the window's normal through their centres."""
    _, _, _, _, where, _, planes = _border()
    r = _report()
    assert r.coverage >= 0.98                                   # by area: measured 0.989
    assert r.face_coverage is not None and r.face_coverage >= 0.97   # whole faces: measured 0.978
    assert sorted(p.kind for p in r.patches) == ["rotation", "rotation", "translation", "translation", "translation"]
    assert all(p.fit_error <= 2 * DEFAULT.eps_prox for p in r.patches)
    assert r.stage("parts").numbers["fit"] >= 5
    lines = np.array([[tg[0], tg[1], 0.0] for _, tg, _, line in where if line])
    dirs = np.array([_translation(p) for p in r.patches if p.kind == "translation"])
    assert axis_angle(dirs[:, None], lines[None]).min(axis=1).max() <= 0.2
    assert sorted(int(np.argmax(np.abs(d))) for d in dirs) == [0, 1, 1]     # the sill along x, the jambs along y
    centres = _arc_centres()
    axes = [_rotation_axis(p) for p in r.patches if p.kind == "rotation"]
    for d, _ in axes:
        assert float(axis_angle(d, [0, 0, 1])) <= 0.2
    off = sorted(float(np.linalg.norm(point[:2] - c)) for _, point in axes for c in centres)
    assert off[0] <= 2e-3 and off[1] <= 2e-3                              # each axis through a centre
    near = [min(range(2), key=lambda k, q=q: np.linalg.norm(q[:2] - centres[k])) for _, q in axes]
    assert sorted(near) == [0, 1]                                         # one per arc
    # the true profile planes (the border's normal planes over the middle 80 % of each curve) found
    found = [motion_planes(p.profile, p.motion, per_knot=32) for p in r.patches]
    assert plane_recall(planes, np.vstack([q[0] for q in found]), np.concatenate([q[1] for q in found])) >= 0.95


def test_border_profiles_are_the_lofted_profile():
    """Each patch's profile has the profile's length within the loft's chord tolerance."""
    _, _, prof, _, _, chord, _ = _border()
    length = float(np.linalg.norm(np.diff(prof, axis=0), axis=1).sum())
    for p in _report().patches:
        got = float(np.linalg.norm(np.diff(p.profile, axis=0), axis=1).sum())
        assert got == pytest.approx(length, abs=0.1 * length)


def test_no_coverage_samples_gives_the_per_face_figure():
    """``coverage_samples = 0``: the same patches, the coverage counted in whole faces alone (measured: by
    area 0.989, by whole faces 0.978)."""
    v, f, *_ = _border()
    r, r0 = _report(), detect((v, f), DEFAULT.with_(coverage_samples=0))
    assert [p.faces.tolist() for p in r0.patches] == [p.faces.tolist() for p in r.patches]
    assert r0.coverage == r0.face_coverage == r.face_coverage
    assert r.coverage >= r.face_coverage + 0.005


def test_parts_off_gives_no_patch_on_the_border():
    """Without the parts and the stage arcs no patch; with the stage arcs alone (crease chains cut into
    their arcs since sweeps-window7: the border's arcs run tangentially into its jambs) only rotations
    about the window's normal through the border arcs' centres.

    Before sweeps-tree4 the coarse pass fitted a sweep whose profile doubles back on itself (22 points,
    0.071 long over an extent of 0.042): its swept surface overlaps itself, and the reciprocal test counted
    every swept point farther than eps_prox as beyond the mesh (fit error 4.997e-3, 0.021 without that
    test; the trim kept all 22 points, their paths' far points discounted too), so changes of the rib
    normals at ties grew it into 2 patches (sweeps-build8, sweeps-build9, sweeps-tree3). Its sheets cross
    the mesh instead of lying along it, so with ``reciprocal_angle`` (30 deg) the trims keep 2-4 points of
    the cuts (9, 18 and 8 without the normal test): the coarse pass sweeps a profile of 4 points, 0.0034
    long, along a path 3.7 long (coverage 0.006), and the refinement keeps none of its knots, so the motion
    stage drops it. (With libigl's tree and the rib normals of the face it returned, sweeps-tree4's first
    step: a 2-point profile 0.0045 long, coverage 0.0087, left out by the fit stage.)"""
    v, f, *_ = _border()
    r = detect((v, f), DEFAULT.with_(max_parts=0, arc_axes=0))
    assert r.patches == () and r.stage("parts") is None
    motion = [s for s in r.stages if s.name == "motion"]
    assert len(motion) == 2 and motion[1].numbers["dropped"] == 1 and motion[1].numbers["candidates"] == 0
    r = detect((v, f), DEFAULT.with_(max_parts=0))
    assert r.stage("parts") is None
    centres = _arc_centres()
    for p in r.patches:
        assert p.kind == "rotation"
        d, q = _rotation_axis(p)
        assert float(axis_angle(d, [0, 0, 1])) <= 0.2
        assert min(float(np.linalg.norm(q[:2] - c)) for c in centres) <= 2e-3


def test_unscrewed_keeps_rotations_and_translations():
    rot = np.r_[0.0, 0.0, 1.0, np.cross([0.2, 0.1, 0.0], [0.0, 0.0, 1.0])]
    tr = np.r_[0.0, 0.0, 0.0, 0.6, 0.8, 0.0]
    out = unscrewed(np.array([rot, tr]))
    assert np.allclose(out[0], rot / np.linalg.norm(rot), atol=1e-12)
    assert np.allclose(out[1], tr, atol=1e-12)
    # a screw about the same axis loses its pitch, nothing else
    screw = rot + np.r_[0.0, 0.0, 0.0, 0.0, 0.0, 0.05]
    assert np.allclose(unscrewed(screw[None])[0], rot / np.linalg.norm(rot), atol=1e-12)


@pytest.mark.parametrize("name", ["revolved", "extruded"])
def test_refined_recovers_the_true_motion_from_a_tilted_start(name):
    """From a start 3 deg off, the robust refit returns the fixture's axis within 0.05 deg."""
    fx = {"revolved": revolved, "extruded": extruded}[name](n_profile=40, n_path=60)
    m = normalise(fx.vertices, fx.faces)
    c = cut(m, *initial_planes(m.vertices, 3, 0.1))
    truth_d = fx.axis_direction
    tilt = Rotation.from_rotvec(np.radians(3.0) * np.array([1.0, 0, 0])).as_matrix()
    if name == "extruded":
        start = np.r_[0.0, 0.0, 0.0, tilt @ truth_d]
    else:
        p = (np.asarray(fx.axis_point, float) - m.centre) / m.scale
        d = tilt @ truth_d
        start = np.r_[d, np.cross(p, d)]
    got = refined(start / np.linalg.norm(start), c.points, c.normals)
    d_got = got[3:] if name == "extruded" else got[:3]
    assert float(axis_angle(d_got, truth_d)) <= 0.05
    share = gliding_shares(c, got[None])[0]
    assert np.mean(share >= DEFAULT.kinematic_share) >= 0.95


def test_part_faces_is_the_box_and_range_of_the_points():
    """A translation part of the extrusion: the faces whose vertices lie within the points' span."""
    fx = extruded(n_profile=40, n_path=60)
    m = normalise(fx.vertices, fx.faces)
    d = fx.axis_direction / np.linalg.norm(fx.axis_direction)
    axis = unscrewed(np.r_[0.0, 0.0, 0.0, d][None])[0]
    from auszug.sweeps.parts import _axis

    ka = _axis(axis, DEFAULT)
    s = m.vertices @ d
    lo, hi = np.quantile(s, [0.25, 0.75])
    pts = m.vertices[(s >= lo) & (s <= hi)]
    faces = part_faces(m, ka, pts, 0.0)
    inside = (s >= lo - 1e-12) & (s <= hi + 1e-12)
    assert np.array_equal(faces, np.flatnonzero(inside[m.faces].all(axis=1)))


def test_fitting_block_is_the_largest_all_true_block():
    """Against a brute force over every block of small random matrices (widths random)."""
    from auszug.sweeps.parts import fitting_block

    rng = np.random.default_rng(5)
    for trial in range(60):
        k, n = int(rng.integers(1, 9)), int(rng.integers(2, 8))
        ok = rng.random((k, n)) < (0.5 + 0.4 * rng.random())
        w = rng.random(n - 1) + 0.05
        min_width = float(rng.choice([0.0, 0.5]))
        pos = np.concatenate([[0.0], np.cumsum(w)])
        best = 0.0
        for r0 in range(k):
            for r1 in range(r0, k):
                for c0 in range(n):
                    for c1 in range(c0 + 1, n):
                        width = pos[c1] - pos[c0]
                        if width >= min_width and ok[r0:r1 + 1, c0:c1 + 1].all():
                            best = max(best, (r1 - r0 + 1) * width)
        got = fitting_block(ok, w, min_width)
        if best == 0.0:
            assert got is None, trial
            continue
        r0, r1, c0, c1 = got
        assert ok[r0:r1 + 1, c0:c1 + 1].all() and c1 > c0
        assert pos[c1] - pos[c0] >= min_width
        assert (r1 - r0 + 1) * (pos[c1] - pos[c0]) == pytest.approx(best, rel=1e-12), trial


def _fitting_block_reference(ok, widths, min_width, max_starts=128):
    """The block search as first written in numpy (per first column, running ANDs and row runs), a
    reference for the compiled one: the same columns tried, the same block of equal areas chosen."""
    k, n = ok.shape
    if n < 2 or k == 0:
        return None
    pos = np.concatenate([[0.0], np.cumsum(widths)])
    rows = np.arange(k)[:, None]
    best = (0.0, None)
    for c0 in np.unique(np.linspace(0, n - 2, min(n - 1, max_starts)).astype(int)):
        acc = np.logical_and.accumulate(ok[:, c0:], axis=1)[:, 1:]
        last_bad = np.maximum.accumulate(np.where(acc, -1, rows), axis=0)
        run = rows - last_bad
        end = np.argmax(run, axis=0)
        length = run[end, np.arange(run.shape[1])]
        width = pos[c0 + 1:] - pos[c0]
        area = np.where(width >= min_width, length * width, 0.0)
        j = int(np.argmax(area))
        if area[j] > best[0]:
            r1 = int(end[j])
            best = (float(area[j]), (r1 - int(length[j]) + 1, r1, int(c0), int(c0) + 1 + j))
    return best[1]


def test_fitting_block_is_the_numpy_reference_on_large_matrices():
    """The compiled search (first columns spread over a wide profile, columns stopped where no row is
    left) gives the numpy reference's block on matrices up to 300 x 400, dense and sparse, ties
    included (equal widths), with and without a least width."""
    from auszug.sweeps.parts import fitting_block

    rng = np.random.default_rng(11)
    for trial in range(120):
        k, n = int(rng.integers(1, 300)), int(rng.integers(1, 400))
        ok = rng.random((k, n)) < float(rng.choice([0.3, 0.9, 0.99, 1.0]))
        w = np.ones(max(n - 1, 0)) if trial % 3 == 0 else rng.random(max(n - 1, 0)) * float(rng.choice([1.0, 0.01]))
        min_width = float(rng.choice([0.0, 0.05, 2.0]))
        max_starts = int(rng.choice([4, 128]))
        assert fitting_block(ok, w, min_width, max_starts) == _fitting_block_reference(ok, w, min_width, max_starts), \
            trial


def test_the_border_rounded_to_float32_gives_the_same_parts():
    """An STL or PLY file stores float32: the border read back (coordinates off by up to 1.5e-8)
    is found as the same five parts (before the parts ran on the whole mesh, a 2 % patch of the
    coarse matching pass took part of the arch and the arcs were lost: coverage 0.629)."""
    v, f, *_ = _border()
    r = detect((v.astype(np.float32).astype(float), f))
    assert r.coverage >= 0.95
    assert sorted(p.kind for p in r.patches) == ["rotation", "rotation", "translation", "translation", "translation"]


#: Measured (docs/sweeps.md, "Planar patches about crease arcs" and "Round mouldings' rings"): fig20c
#: 0.978 of the area (0.973 before the rings' axes), its wall's face 0.999 and foils 1.000 (0.715); fig20d
#: 0.968 (0.935), 0.986, 1.000.
WINDOWS = [("fig20c", 0.975, 0.99, 0.99), ("fig20d", 0.96, 0.98, 0.99)]


def _area2(ring):
    """Twice the area of a closed polygon ``(n, 2)``."""
    return abs(float((ring[:, 0] * np.roll(ring[:, 1], -1) - np.roll(ring[:, 0], -1) * ring[:, 1]).sum()))


@cache
def _window(name: str = "fig20a"):
    """The project's own window, ``window_mesh(build(name))`` (fig20a: 1241 vertices, 2506 triangles), its
    report at the defaults and per face what it is, from how ``window_mesh`` builds it: the box's
    sides (slab sides), the wall's face and the plate's face (the planes ``|y| = thickness / 2`` and
    ``|y| = slab / 2``), the reveal between them, and the lofts of the regions (the lancets' mouldings,
    the oculus, the fillets between them, the foils in the oculus) by the smallest region whose
    border holds the face's centre."""
    from matplotlib.path import Path

    from auszug.sweeps.patches import face_areas
    from auszug.tracery import build, window_mesh

    t = build(name)
    m = window_mesh(t)
    v, f = np.asarray(m.vertices, float), np.asarray(m.faces, np.int64)
    tri = v[f]
    ay, c = np.abs(tri[:, :, 1]), tri.mean(axis=1)
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    lo, hi = v.min(axis=0), v.max(axis=0)
    half_t, half_s = 0.5 * t.style.wall.thickness, 0.5 * t.style.wall.slab
    what = np.full(len(f), "", object)
    on_box = np.any(np.isclose(c[:, [0, 2]], lo[[0, 2]], atol=1e-9) | np.isclose(c[:, [0, 2]], hi[[0, 2]], atol=1e-9),
                    axis=1)
    what[on_box & (np.abs(n[:, 1]) <= 1e-9 * np.linalg.norm(n, axis=1))] = "slab sides"
    what[(what == "") & np.all(np.isclose(ay, half_t, atol=1e-9), axis=1)] = "wall face"
    what[(what == "") & np.all(np.isclose(ay, half_s, atol=1e-9), axis=1)] = "plate face"
    what[(what == "") & np.all(ay >= half_s - 1e-9, axis=1)] = "reveal"
    names = {"sub-arch": "lancet mouldings", "circle": "oculus", "fillet": "fillets", "rosette": "foils"}
    borders = [(r.group, np.vstack([cv.point(np.linspace(0, 1, 200)) for cv in r.curves]) + np.array(r.origin))
               for r in t.regions[1:]]
    for group, border in sorted(borders, key=lambda gb: _area2(gb[1])):
        what[(what == "") & Path(border).contains_points(c[:, [0, 2]])] = names[group]
    # a moulding stepping out beyond its border (fig20c's lancets' sills: 148 faces; none on fig20a): the
    # nearest border's
    from scipy.spatial import cKDTree

    pts = np.vstack([b for _, b in borders])
    group_of = np.concatenate([[names[g]] * len(b) for g, b in borders])
    left = np.flatnonzero(what == "")
    what[left] = group_of[cKDTree(pts).query(c[left][:, [0, 2]])[1]]
    assert (what != "").all()
    return v, f, what, face_areas(v, f), detect((v, f))


def test_the_window_is_mostly_found_in_kinematic_parts():
    """The whole window at the defaults. Per whole face (a face counted only when one patch holds its
    three corners): 0.213 before several blocks per part profile, the trimming over the whole mesh, the
    one profile cut as is and 3 slices; 0.646 before the translations across planar faces; measured now
    0.811 (slab sides 1.000, wall face 0.688, reveal 0.763, plate face 0.765, lancet mouldings 0.799,
    oculus 1.000, fillets 0.292). By area (the report's coverage: the long faces above the arch, whose
    corners lie on different patches, count by the part of them on a patch): measured 0.911 (slab
    sides 1.000, wall face 0.905, reveal 0.879, plate face 0.915, lancet mouldings 0.831, oculus 1.000,
    fillets 0.396). With the mirror images of the candidates in the window's two mirror planes (the
    right arc's rotation, the left arc's mirrored): 0.947 by area (wall face 0.966, reveal 0.976, plate
    face 0.948, lancet mouldings 0.831, fillets 0.410), 0.836 in whole faces (plate face 0.833, reveal
    0.865, fillets 0.332). With the rotations about the crease arcs' axes (stage ``arcs``: the lancets'
    heads, whose arcs sweep less than ``min_sweep_length``): 0.967 by area (lancet mouldings 0.945,
    plate face 0.991, fillets 0.471), 0.859 in whole faces (lancet mouldings 0.924, plate face 0.892,
    fillets 0.387), in 19 patches. With the crease chains cut into their arcs and the planar patches about
    the arcs' axes (sweeps-window7): 0.976 by area (wall face 0.999), 0.859 in whole faces, 23 patches."""
    v, f, what, areas, r = _window()
    assert r.coverage >= 0.97
    assert r.face_coverage is not None and r.face_coverage >= 0.85
    assert all(p.fit_error <= DEFAULT.fit_factor * DEFAULT.eps_prox for p in r.patches)
    on = np.zeros(len(f), bool)
    for p in r.patches:
        on[p.faces] = True
    assert float(areas[on].sum() / areas.sum()) == pytest.approx(r.face_coverage, abs=1e-12)
    share = {k: float(areas[on & (what == k)].sum() / areas[what == k].sum()) for k in set(what)}
    want = {"slab sides": 0.99, "wall face": 0.67, "reveal": 0.84, "plate face": 0.87, "lancet mouldings": 0.90,
            "oculus": 0.99, "fillets": 0.37}
    assert sorted(share) == sorted(want)
    for k, at_least in want.items():
        assert share[k] >= at_least, (k, share[k])
    sh = r.face_shares
    assert sh is not None and np.all(sh[on] == 1.0)
    assert float((sh * areas).sum() / areas.sum()) == pytest.approx(r.coverage, abs=1e-12)
    by_area = {k: float((sh * areas)[what == k].sum() / areas[what == k].sum()) for k in set(what)}
    want = {"slab sides": 0.99, "wall face": 0.99, "reveal": 0.96, "plate face": 0.98, "lancet mouldings": 0.93,
            "oculus": 0.99, "fillets": 0.45}
    for k, at_least in want.items():
        assert by_area[k] >= at_least, (k, by_area[k])
    assert _sampled_apart(v, f, areas, on, r) == pytest.approx(r.coverage, abs=0.01)
    # the lancets' jambs and the box's sides are translations along the window's height
    up = [p for p in r.patches if p.kind == "translation" and float(axis_angle(_translation(p), [0, 0, 1])) <= 0.2]
    assert len(up) >= 4
    # the wall's top and bottom and its face above the arch and below the sill: along its width
    across = [p for p in r.patches if p.kind == "translation" and float(axis_angle(_translation(p), [1, 0, 0])) <= 0.2]
    assert len(across) >= 2
    # the window is mirror symmetric in the planes x = 0 and y = 0 (its centre's): both found, every
    # face's mirror image on the mesh; and the arch's two arcs are rotations about the window's normal,
    # one about an axis right of the middle (the left arc), one left of it (the right arc, whose
    # rotation no candidate of the parts stage is: it comes from the left arc's mirrored)
    st = r.stage("mirror")
    assert st is not None and st.numbers["planes"] == 2 and st.numbers["fit"] >= 1
    centres = []
    for p in r.patches:
        if p.kind == "rotation":
            w, c = _turn_axis(p)
            if abs(w[1]) >= 0.999:
                centres.append(c[0])
    assert min(centres) <= -1.0 and max(centres) >= 1.0
    # the lancets' heads: rotations sweeping less than min_sweep_length (stage arcs), each about an
    # axis normal to the wall through the centre of one of the lancets' arcs (the tracery's own)
    from auszug.tracery import build

    heads = [np.r_[c.center[0], 0.0, c.center[1]] for g in build("fig20a").regions[1:] if g.group == "sub-arch"
             for c in g.curves if type(c).__name__ == "Arc"]
    assert len(heads) == 4
    _short_patches_turn_about_the_tracery_s_arcs("fig20a", r, heads)


@pytest.mark.parametrize("name, least, wall, foils", WINDOWS)
def test_the_windows_with_foils_are_found_by_area(name, least, wall, foils):
    """The windows fig20c (pointed trefoil in the oculus) and fig20d (quatrefoil, trefoil lancet heads) at
    the defaults. Before the crease chains were cut into their arcs and the planar patches about the arcs'
    axes (stage arcs): 0.923 and 0.898 of the area; the wall's face beside the arch was 0.813 and 0.892
    covered (its long faces from the box's corners reach the reveal's arcs, where no translation's block
    does), the foils 0.152 and 0.094 (their lobes' arcs ran into each other in one crease chain, no
    circle). Every patch fits; the area figure agrees with random points apart from its samples; the
    short patches turn about the tracery's own arcs, two of them about the arch's. fig20d's round
    mouldings (no crease) before the axes of their exact rings (``ring_circles``): 0.935."""
    from auszug.tracery import build

    v, f, what, areas, r = _window(name)
    assert r.coverage >= least
    assert all(p.fit_error <= DEFAULT.fit_factor * DEFAULT.eps_prox for p in r.patches)
    sh = r.face_shares
    assert sh is not None
    by_area = {k: float((sh * areas)[what == k].sum() / areas[what == k].sum()) for k in set(what)}
    assert by_area["wall face"] >= wall and by_area["foils"] >= foils, by_area
    on = np.zeros(len(f), bool)
    for p in r.patches:
        on[p.faces] = True
    assert _sampled_apart(v, f, areas, on, r) == pytest.approx(r.coverage, abs=0.01)
    st, fit = r.stage("arcs"), r.stage("fit")
    assert st is not None and fit is not None and st.numbers["flat_fit"] >= 2 and fit.numbers["flat"] >= 2
    if name == "fig20d":
        # its round mouldings have no crease: their axes come from their exact rings (measured: 14 axes,
        # 61 patches fitted; the lancets' mouldings 0.913 of their area, 0.79 before, when their trefoil
        # heads left 0.020 of the mesh's area)
        assert st.numbers["ring_axes"] >= 4 and st.numbers["ring_fit"] >= 4
        assert by_area["lancet mouldings"] >= 0.9, by_area
    arch = [np.r_[c.center[0], 0.0, c.center[1]] for c in build(name).regions[0].curves if type(c).__name__ == "Arc"]
    assert len(arch) == 2
    _short_patches_turn_about_the_tracery_s_arcs(name, r, arch)


def _sampled_apart(v, f, areas, on, r):
    """The area figure checked apart from its own samples: random points (area-uniform) in the input's
    coordinates, covered when on a face a patch holds whole (``on``) or within eps_prox of the swept
    surface of a patch holding a corner of their face; the share covered."""
    from auszug.sweeps.patches import RingTree, _sweep_rings

    eps = DEFAULT.eps_prox * r.bbox_diameter
    rng = np.random.default_rng(7)
    fid = rng.choice(len(f), 20000, p=areas / areas.sum())
    uw = rng.random((len(fid), 2))
    uw[uw.sum(axis=1) > 1] = 1 - uw[uw.sum(axis=1) > 1]
    tri = v[f[fid]]
    x = tri[:, 0] + uw[:, :1] * (tri[:, 1] - tri[:, 0]) + uw[:, 1:] * (tri[:, 2] - tri[:, 0])
    hit = on[fid].copy()
    for p in r.patches:
        tree = RingTree(_sweep_rings(p.profile, p.motion, eps / 10)[1], p.closed)
        held = tree.within(v, eps)[f].any(axis=1)
        ask = ~hit & held[fid]
        hit[ask] = tree.within(x[ask], eps)
    return float(hit.mean())

def _turn_axis(p):
    """A rotation patch's unit axis and a point of it, from the knot turned furthest from a half turn's
    multiple (a whole turn's last map is the identity, a half turn's has no skew part)."""
    rot, tr = p.motion.rotation, p.motion.translation
    w = np.stack([rot[:, 2, 1] - rot[:, 1, 2], rot[:, 0, 2] - rot[:, 2, 0], rot[:, 1, 0] - rot[:, 0, 1]], axis=1)
    k = int(np.argmax(np.linalg.norm(w, axis=1)))
    return w[k] / np.linalg.norm(w[k]), np.linalg.lstsq(np.eye(3) - rot[k], tr[k], rcond=None)[0]


def _short_patches_turn_about_the_tracery_s_arcs(name, r, must):
    """Every patch sweeping less than min_sweep_length (stage arcs) is a rotation about an axis normal to
    the wall through the centre of one of the tracery's arcs (its own), and one turns about each centre
    of ``must``; each covers arc_min_area in whole faces or is a planar patch (a straight profile in a
    plane y = const, counted by the area it adds)."""
    from auszug.tracery import build

    t = build(name)
    centres = [np.r_[c.center[0], 0.0, c.center[1]] for g in t.regions
               for c in g.curves if type(c).__name__ == "Arc"]
    st = r.stage("arcs")
    assert st is not None and st.numbers["fit"] >= len(must)
    short = [p for p in r.patches if sweep_length(p) < DEFAULT.min_sweep_length * r.bbox_diameter]
    assert len(short) >= len(must)
    hit = set()
    for p in short:
        w, c = _turn_axis(p)
        assert p.kind == "rotation" and float(axis_angle(w, [0, 1, 0])) <= 0.2
        assert min(np.hypot(*(c - h)[[0, 2]]) for h in centres) <= 1e-3, c
        hit |= {i for i, h in enumerate(must) if np.hypot(*(c - h)[[0, 2]]) <= 1e-3}
        assert sweep_length(p) >= DEFAULT.arc_sweep_length * r.bbox_diameter
        flat = np.ptp(p.profile[:, 1]) <= 1e-9 * r.bbox_diameter and np.linalg.matrix_rank(
            p.profile - p.profile[0], tol=1e-9 * r.bbox_diameter) == 1
        assert flat or p.coverage >= DEFAULT.arc_min_area
    assert hit == set(range(len(must)))


@pytest.mark.parametrize("name, value", [
    ("part_blocks", 0), ("part_blocks", 17), ("part_blocks", 2.0), ("part_grow", 1), ("part_grow", None),
    ("part_trim_spacing", 0.4), ("part_trim_spacing", 9.0), ("part_trim_spacing", float("nan")),
    ("part_mean_error", 0.0), ("part_mean_error", 1.5), ("part_mean_error", "0.25"),
    ("part_profile_cuts", -1), ("part_profile_cuts", 257), ("part_profile_cuts", 1.0),
    ("part_across", -0.01), ("part_across", 0.5), ("part_across", float("nan")),
])
def test_bad_part_settings_are_refused(name, value):
    from auszug.errors import GeometryError
    from auszug.sweeps import SweepParams

    with pytest.raises(GeometryError, match=rf"sweep parameter {name} = .*: expected "):
        SweepParams(**{name: value})
