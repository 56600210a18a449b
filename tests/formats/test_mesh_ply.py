"""PLY: binary little-endian with vertex colours; re-loads with the same counts (ours and trimesh)."""

from __future__ import annotations

import numpy as np
import pytest

from auszug.errors import FormatError
from auszug.formats import load, save
from auszug.formats.mesh_obj import part_colour
from auszug.formats.ply import dumps, loads
from auszug.meshing import profile_for, sweep_network
from auszug.microarch import build
from tests.conftest import CORPUS


@pytest.fixture(scope="module")
def mesh():
    return sweep_network(build(load(CORPUS / "web" / "u.xi.112.uc")), profile_for("bar", 0.02), 24)


def test_round_trip(mesh, tmp_path):
    back = load(save(mesh, tmp_path / "m.ply", kind="mesh"), kind="mesh")
    assert (back.n_vertices, back.n_faces) == (mesh.n_vertices, mesh.n_faces)
    assert np.array_equal(back.faces, mesh.faces)
    assert np.abs(back.vertices - mesh.vertices).max() < 1e-6


def test_trimesh_reads_counts_and_colours(mesh, tmp_path):
    import trimesh  # in the dev set (mesh extra): a missing trimesh fails, not skips
    (tmp_path / "m.ply").write_bytes(dumps(mesh))
    tm = trimesh.load(tmp_path / "m.ply", process=False)
    assert (len(tm.vertices), len(tm.faces)) == (mesh.n_vertices, mesh.n_faces)
    p = mesh.parts[-1]
    want = np.round(np.asarray(part_colour(p)) * 255)
    assert np.array_equal(tm.visual.vertex_colors[p.vertices[0], :3], want)


def test_ascii_ply_with_polygons():
    text = ("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n")
    m = loads(text)
    assert m.faces.tolist() == [[0, 1, 2], [0, 2, 3]]


def test_errors():
    with pytest.raises(FormatError, match="not a PLY file"):
        loads(b"hello")
    with pytest.raises(FormatError, match="binary_big_endian"):
        loads(b"ply\nformat binary_big_endian 1.0\nend_header\n")
