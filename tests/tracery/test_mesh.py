"""3D: one watertight manifold mesh without self-intersections, of the genus its openings imply."""

from __future__ import annotations

import manifold3d
import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from auszug.meshing.sweepmodel import zip_rings
from auszug.tracery import ParameterError, build, builtin_style, builtin_styles, refine
from auszug.tracery.mesh import Resolution, subdivide_profile, window_mesh
from tests.tracery.cases import euler_genus, n_components, self_intersections

CASES = [(name, None) for name in builtin_styles()] + [
    (name, depth) for name in ("fig20a", "fig20b", "fig20c", "fig20d", "fig20e") for depth in range(4)
]


def _tracery(name, depth):
    st = builtin_style(name)
    return build(st if depth is None else refine(st, depth))


@pytest.mark.parametrize("name, depth", CASES)
def test_watertight_manifold_of_the_right_genus(name, depth):
    t = _tracery(name, depth)
    m = window_mesh(t)
    assert m.is_watertight and m.is_manifold
    assert n_components(m.faces, m.n_vertices) == 1
    assert euler_genus(m.vertices, m.faces) == len(t.lights)  # one handle per light through the plate
    assert m.volume > 0
    # manifold3d agrees: a valid manifold of the same genus
    mm = manifold3d.Manifold(manifold3d.Mesh64(m.vertices, m.faces.astype(np.uint64)))
    assert mm.status() == manifold3d.Error.NoError
    assert mm.genus() == len(t.lights)
    assert mm.volume() == pytest.approx(m.volume, rel=1e-7)


SELF = [(name, None) for name in builtin_styles()] + [("fig20b", d) for d in range(4)] + [("fig20d", 3)]


@pytest.mark.parametrize("name, depth", SELF)
def test_no_self_intersections(name, depth):
    m = window_mesh(_tracery(name, depth))
    # the mesh is the mirror image of its front half (y <= 0), the halves meeting only in
    # the middle plane along shared edges: checking the front half checks the whole
    front = m.faces[(m.vertices[m.faces][:, :, 1] <= 0.0).all(axis=1)]
    assert len(front) > 0.45 * m.n_faces
    assert self_intersections(m.vertices, front) == 0


def test_the_check_finds_intersections():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0.2, 0.2, -1], [0.3, 0.3, 1], [0.9, 0.9, 1.0]], float)
    assert self_intersections(v, np.array([[0, 1, 2], [3, 4, 5]])) == 1
    assert self_intersections(v, np.array([[0, 1, 2], [3, 5, 2]])) == 0  # sharing a vertex


def test_the_mesh_is_symmetric_about_the_middle_plane_and_the_axis():
    m = window_mesh(build("fig20c"))
    v = m.vertices
    key = lambda a: np.unique(np.round(a, 9), axis=0)  # noqa: E731  (a one-line helper)
    assert np.array_equal(key(v), key(v * [1, -1, 1]))
    assert np.array_equal(key(v), key(v * [-1, 1, 1]))
    # the front face of the wall is y = -thickness / 2 with normal (0, -1, 0) as in the paper's call
    assert v[:, 1].min() == pytest.approx(-0.45) and v[:, 1].max() == pytest.approx(0.45)


def test_finer_resolution_and_subdivision_keep_the_topology():
    t = build("fig20d")
    coarse = window_mesh(t, Resolution(max_angle=np.pi / 8, chord=2e-3, per_arc=2))
    fine = window_mesh(t, Resolution(max_angle=np.pi / 48, chord=1e-4, per_arc=8))
    smooth = window_mesh(t, subdivide=2)
    assert coarse.n_faces < window_mesh(t).n_faces < fine.n_faces
    for m in (coarse, fine, smooth):
        assert m.is_manifold and euler_genus(m.vertices, m.faces) == 7
    assert smooth.n_faces > window_mesh(t).n_faces
    assert fine.volume == pytest.approx(window_mesh(t).volume, rel=2e-3)


def test_profiles_cut_the_stone():
    flat = window_mesh(build(builtin_style("fig20a").with_overrides(
        {"sub-arch.profile": "flat", "circle.profile": "flat", "fillet.profile": "flat"})))
    chamfer = window_mesh(build("fig20a"))
    assert chamfer.volume > flat.volume  # insets narrow the openings inside the plate


def test_subdivide_profile_keeps_creases_and_ends():
    p = np.array([[0, 0], [0, 1], [1, 2], [2, 2], [2, 3]], float)
    sharp = np.array([True, True, False, True, True])
    q, s = subdivide_profile(p, sharp, 2)
    assert len(q) == 4 * (len(p) - 1) + 1
    for k in np.nonzero(sharp)[0]:
        assert q[4 * k].tolist() == p[k].tolist() and s[4 * k]
    assert (np.diff(q, axis=0) >= -1e-12).all()  # still monotone


def test_zip_rings_is_a_closed_band():
    ka, kb = np.array([0.0, 0.5, 1.0, 2.5]), np.array([0.1, 1.2, 2.0])
    tri = zip_rings(ka, kb, 3.0)
    assert len(tri) == 7
    e = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    inner = {(a, b) for a, b in e.tolist()}
    # interior edges appear in both directions, the ring edges once each
    ring_a = {(i, (i + 1) % 4) for i in range(4)}
    ring_b = {(4 + (i + 1) % 3, 4 + i) for i in range(3)}
    assert ring_a <= inner and ring_b <= inner
    for a, b in inner - ring_a - ring_b:
        assert (b, a) in inner


@pytest.mark.parametrize("over, name", [({"wall.slab": 0.05}, "wall.slab"), ({"wall.margin": 0.01}, "wall.margin")])
def test_walls_too_thin_for_the_profiles_are_rejected(over, name):
    with pytest.raises(ParameterError) as e:
        window_mesh(build(builtin_style("fig20c").with_overrides(over)))
    assert e.value.name == name


PROFILES = ["flat", "chamfer", "round", "hollow", "step", "fig18"]


@settings(max_examples=25, deadline=None)
@given(st.fixed_dictionaries({
    "excess": st.floats(0.9, 2.0), "drop": st.floats(0.0, 0.5), "inner": st.floats(0.02, 0.08),
    "outer": st.floats(0.0, 0.15), "circle.foils": st.integers(2, 8), "circle.pointed": st.booleans(),
    "circle.orientation": st.sampled_from(["standing", "lying"]),
    "circle.decoration": st.sampled_from(["plain", "rosette"]),
    "sub-arch.decoration": st.sampled_from(["plain", "trefoil"]),
    "fillet.decoration": st.sampled_from(["plain", "blind"]),
    "sub-arch.profile": st.sampled_from(PROFILES), "fillet.profile": st.sampled_from(PROFILES),
    "circle.foil-profile": st.sampled_from(PROFILES), "wall.profile": st.sampled_from(["square", "splay", "orders"]),
}), st.integers(0, 2))
# found by hypothesis: recesses 0.197 deep in a plate 0.4 thick (refused: over the 98 % share)
@example(over={"excess": 2.0, "drop": 0.0, "inner": 0.08, "outer": 0.0, "circle.foils": 2,
               "circle.pointed": False, "circle.orientation": "standing", "circle.decoration": "plain",
               "sub-arch.decoration": "plain", "fillet.decoration": "blind", "sub-arch.profile": "fig18",
               "fillet.profile": "hollow", "circle.foil-profile": "flat", "wall.profile": "square"}, depth=2)
# found by hypothesis (CI's derandomised run): earcut could fill no turned view of a floor with
# collinear ring edges; the triangulator falls back to manifold3d there
@example(over={"excess": 1.0, "drop": 0.039292844692364035, "inner": 0.039292844692364035,
               "outer": 0.039292844692364035, "circle.foils": 2, "circle.pointed": False,
               "circle.orientation": "standing", "circle.decoration": "plain", "sub-arch.decoration": "plain",
               "fillet.decoration": "plain", "sub-arch.profile": "hollow", "fillet.profile": "flat",
               "circle.foil-profile": "flat", "wall.profile": "square"}, depth=2)
def test_any_valid_style_gives_a_manifold_of_the_right_genus(over, depth):
    try:
        t = build(refine(builtin_style("fig20a").with_overrides(over), depth))
    except ParameterError:
        assume(False)
    try:
        m = window_mesh(t)
    except ParameterError as e:
        # a profile too deep for a small region of a random style is refused with a message
        # naming the region, the profile and the inset; never a broken mesh
        msg = str(e)
        # (or the slab is too thin for the recesses: named with the region that reaches deepest)
        assert ("profile" in msg and "inset" in msg) or (msg.startswith("wall.slab") and "deep" in msg), msg
        return
    assert m.is_manifold and euler_genus(m.vertices, m.faces) == len(t.lights)
