"""Short arcs (auszug.sweeps.arcs): rotation candidates from the mesh's crease circles.

The synthetic fixture is a stepped moulding swept exactly about a known axis by 0.9 rad (as a
lancet's head turns) beside a large flat plate, so that the moulding's sweep is short against the
mesh's diameter: its profile's centroid travels less than ``min_sweep_length``. The truth is the
axis it was built with.
"""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from auszug.errors import GeometryError
from auszug.sweeps import DEFAULT, SweepParams, detect, normalise
from auszug.sweeps.arcs import arc_bounds, arc_candidates, crease_circles, fit_circle, ring_circles
from auszug.sweeps.detect import sweep_length
from auszug.sweeps.fixtures import bumps
from auszug.sweeps.kinematic import axis_angle
from auszug.sweeps.patches import face_areas

#: The moulding's profile in (radius, height) about its axis: a step, a chamfer, a fillet-like bend.
PROFILE = np.array([[1.0, 0.0], [1.0, 0.1], [1.05, 0.1], [1.05, 0.2], [1.1, 0.25], [1.2, 0.25], [1.25, 0.22],
                    [1.3, 0.15], [1.3, 0.0]])
TURN = 0.9                                      # radians, as a lancet's head (0.89 on the window fig20a)
ROT = Rotation.from_rotvec([0.4, -0.7, 0.25])   # the axis z, turned: not along a coordinate axis
SHIFT = np.array([0.3, -0.2, 0.5])


def _grid(k: int, n: int, first: int) -> np.ndarray:
    i, j = np.meshgrid(np.arange(k - 1), np.arange(n - 1), indexing="ij")
    a = first + i * n + j
    return np.vstack([np.c_[a.ravel(), (a + n).ravel(), (a + 1).ravel()],
                      np.c_[(a + 1).ravel(), (a + n).ravel(), (a + n + 1).ravel()]])


@cache
def _arc_mesh():
    """The moulding (profile densified to 5 points a segment, 24 steps of turn) and a plate 5 x 5 beside it.

    Returns the vertices, faces, the number of the moulding's faces (first), the true axis'
    direction and a point of it."""
    prof = np.vstack([np.linspace(a, b, 5, endpoint=False) for a, b in zip(PROFILE[:-1], PROFILE[1:], strict=True)]
                     + [PROFILE[-1:]])
    t = np.linspace(0.0, TURN, 25)
    r, h = prof[:, 0], prof[:, 1]
    ring = np.stack([np.c_[r * np.cos(a), r * np.sin(a), h] for a in t])        # (25, n, 3)
    v = ring.reshape(-1, 3)
    f = _grid(len(t), len(prof), 0)
    plate = np.array([[x, y, -1.0] for x in (-2.5, 2.5) for y in (-2.5, 2.5)])
    fp = len(v) + np.array([[0, 1, 2], [1, 3, 2]])
    v = ROT.apply(np.vstack([v, plate])) + SHIFT
    return v, np.vstack([f, fp]), len(f), ROT.apply([0.0, 0.0, 1.0]), SHIFT


def _axis_of(p, k=-1):
    rot, tr = p.motion.rotation[k], p.motion.translation[k]
    w = np.array([rot[2, 1] - rot[1, 2], rot[0, 2] - rot[2, 0], rot[1, 0] - rot[0, 1]])
    return w / np.linalg.norm(w), np.linalg.lstsq(np.eye(3) - rot, tr, rcond=None)[0]


def test_fit_circle_recovers_a_circle_in_space_and_measures_its_error():
    rng = np.random.default_rng(3)
    rot = Rotation.from_rotvec(rng.normal(size=3))
    t = np.linspace(0.2, 0.7, 7)
    pts = rot.apply(np.c_[0.4 * np.cos(t), 0.4 * np.sin(t), np.zeros_like(t)]) + [1.0, 2.0, 3.0]
    c, n, r, err = fit_circle(pts)
    assert np.allclose(c, [1.0, 2.0, 3.0], atol=1e-9) and r == pytest.approx(0.4, abs=1e-9) and err < 1e-9
    assert float(axis_angle(n, rot.apply([0.0, 0.0, 1.0]))) < 1e-6
    bent = pts + 1e-3 * np.array([0.0, 0.0, 1.0]) * np.sin(np.arange(7))[:, None]
    assert fit_circle(bent)[3] > 1e-4            # off the circle: measured, not hidden


def test_a_short_arc_swept_exactly_gives_its_true_axis():
    v, f, n_arc, d, q = _arc_mesh()
    m = normalise(v, f)
    axes = crease_circles(m)
    assert axes, "no crease arc found"
    top = axes[0]
    # every axis found is the true one (the moulding's corners sweep circles about it, and nothing else is round)
    for ax in axes:
        assert float(axis_angle(ax.direction, d)) <= 0.2
        y = m.to_input(ax.point) - q
        assert np.linalg.norm(y - (y @ d) * d) <= 1e-6 * m.scale
    assert top.n_vertices >= 6 * 25 and top.error <= DEFAULT.arc_fit * DEFAULT.eps_prox


def test_the_short_arc_is_swept_by_patches_about_its_axis_shorter_than_min_sweep_length():
    v, f, n_arc, d, q = _arc_mesh()
    m = normalise(v, f)
    found, tried = arc_candidates(m, np.ones(len(f), bool))
    assert tried == 1
    short = arc_bounds(DEFAULT)
    good = [p for p in found if p.fit_error <= DEFAULT.fit_factor * DEFAULT.eps_prox
            and p.coverage >= short.min_patch_area and sweep_length(p) >= short.min_sweep_length]
    assert good
    # the sweep is short: below the general bound (0.2), which would have dropped it
    assert all(sweep_length(p) < DEFAULT.min_sweep_length for p in good)
    on = np.zeros(len(f), bool)
    for p in good:
        on[p.faces] = True
    areas = face_areas(v, f)
    assert float(areas[:n_arc][on[:n_arc]].sum() / areas[:n_arc].sum()) >= 0.95
    assert not on[n_arc:].any()                  # the plate is not a rotation about that axis


def test_detect_keeps_the_short_arc_in_the_stage_arcs():
    v, f, n_arc, d, q = _arc_mesh()
    r = detect((v, f))
    st = r.stage("arcs")
    assert st is not None and st.numbers["axes"] >= 1 and st.numbers["fit"] >= 1
    least = DEFAULT.min_sweep_length * r.bbox_diameter
    rots = [p for p in r.patches if p.kind == "rotation" and sweep_length(p) < least]
    assert rots
    for p in rots:
        w, c = _axis_of(p)
        assert float(axis_angle(w, d)) <= 0.2
        y = c - q
        assert np.linalg.norm(y - (y @ d) * d) <= 1e-3
    on = np.zeros(len(f), bool)
    for p in rots:
        on[p.faces] = True
    areas = face_areas(v, f)
    assert float(areas[:n_arc][on[:n_arc]].sum() / areas[:n_arc].sum()) >= 0.95
    # without the stage no patch sweeps that short
    r0 = detect((v, f), DEFAULT.with_(arc_axes=0))
    assert r0.stage("arcs") is None
    assert all(sweep_length(p) >= DEFAULT.min_sweep_length * r0.bbox_diameter for p in r0.patches)


@pytest.mark.parametrize("sigma", [0.0, 5e-4])
@pytest.mark.parametrize("eps", [0.001, 0.005])
def test_bumps_have_no_crease_arc_even_when_every_edge_is_a_crease(sigma, eps):
    """Random Gaussian bumps: no edge turns by 20 deg (so no crease at all at the defaults); with
    every edge a crease (``arc_crease`` 0.01 deg) the chains are no circles within ``arc_fit``."""
    fx = bumps(sigma=sigma)
    m = normalise(fx.vertices, fx.faces)
    p = DEFAULT.with_(eps_prox=eps)
    assert crease_circles(m, None, p) == []
    assert crease_circles(m, None, p.with_(arc_crease=0.01)) == []


@pytest.mark.parametrize("name, value", [
    ("arc_axes", -1), ("arc_axes", 257), ("arc_axes", 1.5), ("arc_axes", True),
    ("arc_crease", 0.0), ("arc_crease", 180.0), ("arc_crease", float("nan")),
    ("arc_fit", 0.0), ("arc_fit", 1.5), ("arc_fit", "0.05"),
    ("arc_sweep_length", -0.1), ("arc_sweep_length", float("nan")),
    ("arc_min_area", -0.01), ("arc_min_area", 1.5), ("arc_min_area", None),
    ("arc_rings", -1), ("arc_rings", 65), ("arc_rings", 2.5), ("arc_ring_fit", 0.0), ("arc_ring_fit", 1.5),
    ("arc_ring_fit", float("nan")),
])
def test_bad_arc_settings_are_refused(name, value):
    with pytest.raises(GeometryError, match=rf"sweep parameter {name} = .*: expected "):
        SweepParams(**{name: value})


def test_the_arcs_bounds_are_the_smaller_ones():
    p = DEFAULT.with_(min_sweep_length=0.05, arc_sweep_length=0.1, min_patch_area=0.02, arc_min_area=0.005)
    b = arc_bounds(p)
    assert (b.min_sweep_length, b.min_patch_area) == (0.05, 0.005)


@cache
def _plate_mesh():
    """A square plate 4 x 4 with a round opening of radius 1 (64 sides) whose reveal, a cylinder 0.3 deep,
    meets the plate at a right angle: the rim is a crease circle, and the plate's face around it is
    swept by a radial line about the opening's axis. Turned and shifted as the arc mesh. Returns the
    vertices, faces, the number of the plate's faces (first), the true axis' direction and a point."""
    from auszug.meshing import triangulate_polygon

    centre = np.array([0.3, -0.2])
    a = np.linspace(0.0, 2 * np.pi, 64, endpoint=False)
    rim = centre + np.c_[np.cos(a), np.sin(a)]
    square = np.array([[-2.0, -2.0], [2.0, -2.0], [2.0, 2.0], [-2.0, 2.0]])
    f_plate = triangulate_polygon(square, [rim])
    v = np.vstack([np.c_[square, np.zeros(4)], np.c_[rim, np.zeros(64)], np.c_[rim, np.full(64, -0.3)]])
    i = np.arange(64)
    j = (i + 1) % 64
    f_wall = np.vstack([np.c_[4 + i, 4 + j, 68 + i], np.c_[4 + j, 68 + j, 68 + i]])
    v = ROT.apply(v) + SHIFT
    return v, np.vstack([f_plate, f_wall]), len(f_plate), ROT.apply([0.0, 0.0, 1.0]), ROT.apply([*centre, 0.0]) + SHIFT


def test_a_plate_around_a_round_opening_is_swept_about_the_opening_s_axis():
    """The planar patches of the stage arcs (``flat_candidates``): rotations of a radial line about the
    axis of the crease circle where the plate meets the opening's reveal. Each fits (a plane swept in
    itself: every swept point on the plate), and together they cover the plate's ring around the
    opening that no translation's block reaches."""
    from auszug.sweeps.arcs import flat_candidates
    from auszug.sweeps.patches import MeshTree, add_by_area, area_coverage

    v, f, n_plate, d, q = _plate_mesh()
    m = normalise(v, f)
    axes = crease_circles(m)
    assert len(axes) == 1
    assert float(axis_angle(axes[0].direction, d)) <= 0.01
    y = m.to_input(axes[0].point) - q
    assert np.linalg.norm(y - (y @ d) * d) <= 1e-9 * m.scale
    free = np.ones(len(f), bool)
    found = flat_candidates(m, free, axes, DEFAULT, MeshTree.of(m))
    assert found and all(p.kind == "rotation" for p in found)
    bound = DEFAULT.fit_factor * DEFAULT.eps_prox
    for p in found:
        assert p.fit_error <= bound
        w, c = _axis_of(p, len(p.motion.t) // 4)       # not the last map: a whole turn is the identity
        assert float(axis_angle(w, axes[0].direction)) <= 1e-6
        y = c - axes[0].point
        assert np.linalg.norm(y - (y @ w) * w) <= 1e-9
    areas = face_areas(m.vertices, m.faces)
    taken = add_by_area(m, [], found, DEFAULT.eps_prox, DEFAULT.coverage_samples, DEFAULT.arc_min_area, areas)
    assert taken
    share = area_coverage(m, taken, DEFAULT.eps_prox, DEFAULT.coverage_samples, areas)
    plate = float((share * areas)[:n_plate].sum() / areas[:n_plate].sum())
    # the ring out to the nearest side (radius 1.7 about the centre (0.3, -0.2)): 0.461 of the plate
    opening = 32 * np.sin(np.pi / 32)
    ring = (np.pi * 1.7**2 - opening) / (16.0 - opening)
    assert plate >= ring
    assert plate >= 0.76            # measured 0.767 in 4 patches: blocks beyond the ring, towards the corners
    # of the reveal only its strip within eps_prox of the plate's plane (the plate's samples' tolerance)
    reveal = float((share * areas)[n_plate:].sum() / areas[n_plate:].sum())
    assert reveal <= 1.05 * DEFAULT.eps_prox * m.scale / 0.3
    # no circle on the random bumps: no axis, so no planar patch either
    b = bumps()
    mb = normalise(b.vertices, b.faces)
    assert flat_candidates(mb, np.ones(len(b.faces), bool), crease_circles(mb)) == []


def _round_moulding():
    """A round moulding about a known axis (``ROT``'s z through ``SHIFT``), turning by ``TURN``: a flat
    strip (radius 1.5 to 1.2, height 0) running tangentially into a quarter circle of radius 0.2
    (centre (1.2, -0.2)) and on into a vertical line down to height -0.5: no crease anywhere. 25 steps
    of turn, the profile 4 + 8 + 4 segments. Returns the vertices, faces, true direction and point."""
    a = np.linspace(np.pi / 2, np.pi, 9)
    prof = np.vstack([np.c_[np.linspace(1.5, 1.2, 4, endpoint=False), np.zeros(4)],
                      np.c_[1.2 + 0.2 * np.cos(a), -0.2 + 0.2 * np.sin(a)],
                      np.c_[np.ones(4), np.linspace(-0.275, -0.5, 4)]])
    t = np.linspace(0.0, TURN, 25)
    r, h = prof[:, 0], prof[:, 1]
    v = np.stack([np.c_[r * np.cos(x), r * np.sin(x), h] for x in t]).reshape(-1, 3)
    return ROT.apply(v) + SHIFT, _grid(len(t), len(prof), 0), ROT.apply([0.0, 0.0, 1.0]), SHIFT


def test_a_round_moulding_has_no_crease_but_its_rings_give_its_axis():
    """The rings of a moulding whose profile has no corner (``ring_circles``): exact coaxial circles
    along the edge lines; one axis, the true one; the crease circles find nothing; the rotation
    patches about it (``arc_candidates``) cover the moulding and fit."""
    v, f, d, q = _round_moulding()
    m = normalise(v, f)
    assert crease_circles(m) == []
    axes = ring_circles(m)
    assert len(axes) == 1
    assert float(axis_angle(axes[0].direction, d)) <= 1e-6
    y = m.to_input(axes[0].point) - q
    assert np.linalg.norm(y - (y @ d) * d) <= 1e-9 * m.scale
    assert len(axes[0].chains) >= DEFAULT.arc_rings
    # every profile point sweeps an exact ring: 17 of them, none missed
    assert len(ring_circles(m, None, DEFAULT.with_(arc_rings=17))) == 1
    assert ring_circles(m, None, DEFAULT.with_(arc_rings=18)) == []
    found, tried = arc_candidates(m, np.ones(len(f), bool), DEFAULT, axes=axes)
    bound = DEFAULT.fit_factor * DEFAULT.eps_prox
    assert tried == 1 and found and all(p.kind == "rotation" and p.fit_error <= bound for p in found)
    on = np.zeros(len(f), bool)
    for p in found:
        on[p.faces] = True
    areas = face_areas(v, f)
    assert float(areas[on].sum() / areas.sum()) >= 0.95


@pytest.mark.parametrize("sigma", [0.0, 5e-4])
@pytest.mark.parametrize("eps", [0.001, 0.005])
def test_bumps_have_no_exact_ring(sigma, eps):
    """Random Gaussian bumps: no run of an edge line is an exact circle (``arc_ring_fit``), not even one."""
    fx = bumps(sigma=sigma)
    m = normalise(fx.vertices, fx.faces)
    assert ring_circles(m, None, DEFAULT.with_(eps_prox=eps, arc_rings=1)) == []


def _edge_lines_reference(mesh, free, turn):
    """The edge lines as first written in numpy (every pair of edges meeting end to start listed, the
    straightest per edge by a sort, the lines walked in Python): a reference for the compiled one."""
    faces = mesh.faces if free is None else mesh.faces[free]
    e = np.unique(np.sort(np.vstack([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1), axis=0)
    k = len(e)
    src, dst = np.r_[e[:, 0], e[:, 1]], np.r_[e[:, 1], e[:, 0]]
    u = mesh.vertices[dst] - mesh.vertices[src]
    u /= np.maximum(np.linalg.norm(u, axis=1, keepdims=True), 1e-300)
    rev = (np.arange(2 * k) + k) % (2 * k)
    order = np.argsort(src, kind="stable")
    first = np.searchsorted(src[order], np.arange(len(mesh.vertices) + 1))
    n_out = first[dst + 1] - first[dst]
    i = np.repeat(np.arange(2 * k), n_out)
    j = order[np.repeat(first[dst] - np.r_[0, np.cumsum(n_out)[:-1]], n_out) + np.arange(len(i))]
    ok = j != rev[i]
    i, j = i[ok], j[ok]
    c = np.einsum("ij,ij->i", u[i], u[j])
    best = np.lexsort((-c, i))
    i, j, c = i[best], j[best], c[best]
    head = np.r_[True, i[1:] != i[:-1]]
    nxt = np.full(2 * k, -1, np.int64)
    take = head & (c >= np.cos(np.radians(turn)))
    nxt[i[take]] = j[take]
    # kept where mutual: the continuation of x's reverse is the reverse of x's (a plain loop)
    keep = [x >= 0 and nxt[rev[x]] == rev[i] for i, x in enumerate(nxt.tolist())]
    nxt = np.where(keep, nxt, -1)
    prev = np.full(2 * k, -1, np.int64)
    for i, x in enumerate(nxt.tolist()):
        if x >= 0:
            prev[x] = i
    seen = np.zeros(2 * k, bool)
    out = []
    for s0 in [*np.flatnonzero(prev < 0).tolist(), *range(2 * k)]:
        if seen[s0]:
            continue
        path = [int(src[s0])]
        x = s0
        while x >= 0 and not seen[x]:
            seen[x] = seen[rev[x]] = True
            path.append(int(dst[x]))
            x = int(nxt[x])
        out.append(path)
    return out


@pytest.mark.parametrize("case", ["window", "revolved", "bumps", "holed"])
def test_edge_lines_are_the_numpy_reference(case):
    """The compiled edge lines (the straightest mutual continuation per edge, lines walked open ones
    first) are the numpy version's, line by line and in order, on a window, a surface of revolution
    (a regular grid: continuations tied up to round-off), random bumps and a holed extrusion, over
    all faces and over a random 70 % of them, at turns of 5 and 30 degrees."""
    from auszug.sweeps import fixtures
    from auszug.sweeps.arcs import edge_lines

    if case == "window":
        from auszug.tracery import build, window_mesh

        w = window_mesh(build("fig20a"))
        v, f = np.asarray(w.vertices, float), np.asarray(w.faces, np.int64)
    else:
        fx = {"revolved": lambda: fixtures.revolved(n_profile=40, n_path=60), "bumps": lambda: bumps(n=60),
              "holed": lambda: fixtures.with_hole(fixtures.extruded(n_profile=30, n_path=30))}[case]()
        v, f = fx.vertices, fx.faces
    m = normalise(v, f)
    rng = np.random.default_rng(3)
    for free in (None, rng.random(len(m.faces)) < 0.7):
        for turn in (5.0, 30.0):
            got = [line.tolist() for line in edge_lines(m, free, turn)]
            assert got == _edge_lines_reference(m, free, turn), (case, turn)
            assert all(len(line) >= 2 for line in got)
    assert edge_lines(m, np.zeros(len(m.faces), bool)) == []
