"""Binary STL: exact size, normals, watertight re-load with the same counts (ours and trimesh)."""

from __future__ import annotations

import struct

import numpy as np
import pytest

from auszug.errors import FormatError
from auszug.formats import load, save
from auszug.formats.stl import dumps, loads
from auszug.meshing import profile_for
from auszug.meshing.solid import solid
from auszug.microarch import build
from tests.conftest import CORPUS


@pytest.fixture(scope="module")
def printable():
    net = build(load(CORPUS / "teaching-sheet" / "tn-1.uc"))
    return solid(net, profile_for("tube", 0.03, 10), 32, base=True)


def test_binary_layout(printable):
    data = dumps(printable)
    n = printable.mesh.n_faces
    assert len(data) == 84 + 50 * n and struct.unpack("<I", data[80:84])[0] == n
    normal = np.frombuffer(data, dtype="<f4", count=3, offset=84)
    assert abs(np.linalg.norm(normal) - 1) < 1e-6


def test_solid_reloads_watertight_with_the_same_counts_and_volume(printable, tmp_path):
    out = save(printable, tmp_path / "s.stl", kind="mesh")
    back = load(out, kind="mesh")
    m = printable.mesh
    assert (back.n_vertices, back.n_faces) == (m.n_vertices, m.n_faces)
    assert back.is_watertight
    assert back.volume == pytest.approx(printable.volume, rel=1e-5)       # float32 coordinates


def test_trimesh_reads_a_watertight_volume(printable, tmp_path):
    import trimesh  # in the dev set (mesh extra): a missing trimesh fails, not skips
    (tmp_path / "s.stl").write_bytes(dumps(printable))
    tm = trimesh.load(tmp_path / "s.stl")
    assert len(tm.faces) == printable.mesh.n_faces and len(tm.vertices) == printable.mesh.n_vertices
    assert tm.is_watertight and tm.is_volume
    assert tm.volume == pytest.approx(printable.volume, rel=1e-5)


def test_ascii_stl_and_errors():
    text = ("solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
            "endloop\nendfacet\nendsolid\n")
    assert loads(text).n_faces == 1
    with pytest.raises(FormatError, match="too short"):
        loads(b"abc")
    bad = b"\0" * 80 + struct.pack("<I", 5) + b"\0" * 50
    with pytest.raises(FormatError, match="says 5 triangles but has 1"):
        loads(bad)
