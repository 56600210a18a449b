"""Mesh OBJ: a group per member replica and face, materials per basic curve, exact re-load, trimesh."""

from __future__ import annotations

import numpy as np
import pytest

from auszug.errors import FormatError
from auszug.formats import load, save
from auszug.formats.mesh_obj import dumps, loads, mtl, part_colour
from auszug.formats.svg import colour
from auszug.meshing import concatenate, network_faces, profile_for, sweep_network
from auszug.microarch import build
from tests.conftest import CORPUS


@pytest.fixture(scope="module")
def mesh():
    net = build(load(CORPUS / "web" / "U.XI.28.uc"))
    return concatenate([sweep_network(net, profile_for("bar", 0.02), 24),
                        network_faces(net, resolution=32).mesh()])


def test_round_trip_keeps_counts_groups_and_coordinates(mesh, tmp_path):
    out = save(mesh, tmp_path / "u.obj", kind="mesh")
    back = load(out, kind="mesh")
    assert (back.n_vertices, back.n_faces) == (mesh.n_vertices, mesh.n_faces)
    assert np.abs(back.vertices - mesh.vertices).max() < 1e-9
    assert np.array_equal(back.faces, mesh.faces)
    assert [p.name for p in back.parts] == [p.name.replace("/", "_") for p in mesh.parts]
    assert [p.faces for p in back.parts] == [p.faces for p in mesh.parts]


def test_trimesh_reads_the_same_counts(mesh, tmp_path):
    import trimesh  # in the dev set (mesh extra): a missing trimesh fails, not skips
    (tmp_path / "u.obj").write_text(dumps(mesh, "u.obj"))
    (tmp_path / "u.mtl").write_text(mtl(mesh))
    tm = trimesh.load(tmp_path / "u.obj", force="mesh", process=False)
    assert (len(tm.vertices), len(tm.faces)) == (mesh.n_vertices, mesh.n_faces)
    scene = trimesh.load(tmp_path / "u.obj", group_material=False, split_object=True, process=False)
    assert len(scene.geometry) == len(mesh.parts)


def test_materials_are_the_curve_colours(mesh):
    text = dumps(mesh, "u.obj")
    assert "mtllib u.mtl" in text and "Z IS UP" in text
    lib = mtl(mesh)
    assert lib.count("newmtl") == 5                      # curve0..curve3, face
    h = colour(2).lstrip("#")
    assert f"newmtl curve2\nKd {int(h[0:2], 16) / 255:.4f}" in lib
    used = [ln.split()[1] for ln in text.splitlines() if ln.startswith("usemtl")]
    assert used[0] == "curve0" and used[-1] == "face"
    assert part_colour(mesh.parts[-1]) != part_colour(mesh.parts[0])


def test_polygons_are_fanned_and_bad_lines_named():
    m = loads("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\ng quad\nf 1 2 3 4\n")
    assert m.faces.tolist() == [[0, 1, 2], [0, 2, 3]]
    with pytest.raises(FormatError, match=r"x.obj:2: 'f' refers to a vertex out of range"):
        loads("v 0 0 0\nf 1 2 3\n", "x.obj")
    with pytest.raises(FormatError, match=r"x.obj:1: 'v' needs 3 numbers"):
        loads("v 0 a 0\n", "x.obj")
