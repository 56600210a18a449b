"""Solids: one watertight, manifold mesh with positive volume for every corpus drawing; exact volumes
for simple cases; base plates and thickened faces; open profiles refused."""

from __future__ import annotations

import math

import numpy as np
import pytest

from auszug.errors import GeometryError
from auszug.meshing import Mesh, default_size, profile_for
from auszug.meshing.faces import network_faces
from auszug.meshing.profile import ribbon, square
from auszug.meshing.solid import base_plate, solid, thicken, unite
from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry, build
from tests.meshing.cases import ALL, IDS, network, star


@pytest.mark.parametrize("path", ALL, ids=IDS)
def test_every_corpus_drawing_gives_a_watertight_manifold_solid(path):
    import io

    import trimesh  # in the dev set (mesh extra): a missing trimesh fails, not skips

    from auszug.formats import stl

    net = network(path)
    s = solid(net, profile_for("bar", default_size(net), 4), 24, base=True)
    assert s.watertight and s.mesh.is_manifold
    assert s.volume > 0
    tm = trimesh.Trimesh(s.mesh.vertices, s.mesh.faces, process=False)
    assert tm.is_watertight and tm.is_winding_consistent and tm.is_volume
    assert tm.volume == pytest.approx(s.volume, rel=1e-9)
    # as a printer gets it: binary STL (float32 corners, no topology) read back by position
    data = stl.dumps(s.mesh)
    back = stl.loads(data)
    assert back.n_faces == s.mesh.n_faces and back.is_manifold, "the STL welds into a pinched or open mesh"
    tm = trimesh.load(io.BytesIO(data), file_type="stl")   # trimesh merges vertices by position
    assert tm.is_watertight and tm.is_winding_consistent and tm.is_volume
    assert tm.volume == pytest.approx(s.volume, rel=1e-5)


def test_a_level_ring_of_square_bars_has_the_exact_volume():
    """A level square of side 2 (four level segments, C4) swept with a 0.1 bar: a square frame.

    The bars end at the corners (no mirror there, so no mitre): each corner misses its outer
    0.05 x 0.05 notch, and the union counts the inner overlap once.
    """
    c = BasicCurve(((1.0, -1.0), (1.0, 1.0)), (Segment("line"),), ("apex", "apex"),
                   Symmetry(fold=4), height=1.0)
    net = build(Drawing((c,), layer_bottoms=(0.0,)))
    s = solid(net, square(0.1), 8)
    assert s.watertight and s.components == 1
    assert s.volume == pytest.approx(4 * 2.0 * 0.01 - 4 * 0.05 ** 2 * 0.1, rel=1e-9)


def test_mirror_joints_unite_into_one_shell_without_double_volume():
    net = build(star())
    one = solid(net, square(0.05), 40, cut=True)
    assert one.watertight and one.components == 1 and one.slivers == 0
    # the joined volume is the sum of the four members cut at their mirror planes
    from auszug.meshing.solid import closed_member
    from auszug.meshing.sweep import sweep_members

    (mb,) = sweep_members(net, square(0.05), 40)
    v, f = closed_member(mb)
    assert one.volume == pytest.approx(4 * Mesh(v, f).volume, rel=1e-6)


def test_base_plate_adds_its_volume_less_the_sunken_feet():
    net = network("teaching-sheet/tn-1.uc")
    prof = square(0.02)
    without = solid(net, prof, 24)
    with_base = solid(net, prof, 24, base=True)
    v, f = base_plate(net, 0.04, 0.04, 0.005)
    plate = Mesh(v, f).volume
    assert with_base.components == 1 and without.components == 1
    assert with_base.volume == pytest.approx(without.volume + plate, rel=2e-3)


def test_thickened_faces_are_closed_shells_united_with_the_members():
    net = network("teaching-sheet/tn-1.uc")
    fs = network_faces(net, resolution=48)
    tv, tf = thicken(fs.faces[0].vertices, fs.faces[0].faces, 0.004)
    shell = Mesh(tv, tf)
    assert shell.is_watertight and shell.volume == pytest.approx(0.004 * fs.faces[0].area, rel=0.05)
    s = solid(net, profile_for("tube", default_size(net), 12), 32, faces=fs, base=True)
    assert s.watertight and s.mesh.is_manifold and s.components == 1
    assert s.volume > solid(net, profile_for("tube", default_size(net), 12), 32, base=True).volume


def test_open_profiles_cannot_make_solids():
    with pytest.raises(GeometryError, match="a solid needs a closed profile"):
        solid(build(star()), ribbon(0.1), 8)


def test_unite_refuses_an_open_mesh():
    with pytest.raises(GeometryError, match="not a closed 2-manifold"):
        unite([(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]]), np.array([[0, 1, 2]]))])


def test_thickness_must_be_positive():
    with pytest.raises(GeometryError, match="positive"):
        thicken(np.zeros((3, 3)), np.array([[0, 1, 2]]), -1.0)
    assert math.isfinite(1.0)
