"""Fuzzing the mesh readers (STL binary + ASCII, PLY binary + ASCII, GLB, glTF, OBJ).

These are the readers the sweeps issue feeds user meshes through. Each mutated
file must read into a valid mesh (finite coordinates within the coordinate
limit, every face index in range) or be refused with a FormatError naming the
file; never another exception. See tests/fuzzing.py for the contract.
"""

from __future__ import annotations

import json
import random
from collections import Counter

import numpy as np
import pytest

from auszug.errors import FormatError
from auszug.formats import gltf, mesh_obj, ply, stl
from auszug.limits import LIMITS
from auszug.meshing.mesh import Mesh, Part
from tests.fuzzing import (
    ODD_VALUES,
    assert_finite,
    case,
    cases,
    expect_contract,
    mutate_bytes,
    mutate_json,
    mutate_text,
)

NAME = "fuzzed-mesh"

#: A closed mesh of two parts (a tetrahedron and a square pyramid), small enough that a
#: mutation often hits a count, an index or a coordinate.
MESH = Mesh(
    [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1],
     [2, 0, 0], [3, 0, 0], [3, 1, 0], [2, 1, 0], [2.5, 0.5, 1]],
    [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3],
     [4, 6, 5], [4, 7, 6], [4, 5, 8], [5, 6, 8], [6, 7, 8], [7, 4, 8]],
    (Part("0/r0", "member", 0, "r0", (0, 4), (0, 4)), Part("1/r0", "member", 1, "r0", (4, 9), (4, 10))),
)


def _ascii_stl(m: Mesh) -> str:
    out = ["solid fuzz"]
    for f in m.faces:
        out += ["facet normal 0 0 1", "outer loop", *(f"vertex {x:g} {y:g} {z:g}" for x, y, z in m.vertices[f]),
                "endloop", "endfacet"]
    return "\n".join([*out, "endsolid fuzz"]) + "\n"


def _ascii_ply(m: Mesh) -> str:
    head = ["ply", "format ascii 1.0", f"element vertex {m.n_vertices}", "property float x", "property float y",
            "property float z", f"element face {m.n_faces}", "property list uchar int vertex_indices", "end_header"]
    return "\n".join([*head, *(f"{x:g} {y:g} {z:g}" for x, y, z in m.vertices),
                      *(f"3 {a} {b} {c}" for a, b, c in m.faces)]) + "\n"


BINARY = {"stl": (stl.loads, stl.dumps(MESH)), "ply": (ply.loads, ply.dumps(MESH)),
          "glb": (gltf.loads, gltf.dumps_glb(MESH))}
TEXT = {"stl-ascii": (stl.loads, _ascii_stl(MESH)), "ply-ascii": (ply.loads, _ascii_ply(MESH)),
        "obj": (mesh_obj.loads, mesh_obj.dumps(MESH, "m.obj"))}
KEYWORDS = {"stl-ascii": ["vertex", "facet", "endloop", "solid"],
            "ply-ascii": ["element", "vertex", "face", "property", "list", "float", "uchar", "int", "end_header",
                          "format", "binary_little_endian", "double"],
            "obj": ["v", "f", "g", "vn", "vt", "1/1", "-1", "0"]}
#: Cases per reader and mutation kind in a ``make test`` run.
N = 1000


def check_mesh(m: object) -> None:
    """A read mesh is valid: finite coordinates within the limit, faces of three in-range indices."""
    assert isinstance(m, Mesh)
    assert_finite(m.vertices)
    assert m.vertices.shape[1:] == (3,) and m.faces.shape[1:] == (3,)
    if m.n_vertices:
        assert np.abs(m.vertices).max() <= LIMITS.coordinate
    if m.n_faces:
        assert m.faces.min() >= 0 and m.faces.max() < m.n_vertices
    for p in m.parts:
        assert 0 <= p.faces[0] <= p.faces[1] <= m.n_faces


def _run(kind: str, read, make) -> Counter:
    seen: Counter = Counter()
    for seed in cases(N):
        data = make(random.Random(seed))
        with case(f"{kind} seed {seed}"):
            out = expect_contract(read, data, NAME, name=NAME)
            if out.kind == "ok":
                check_mesh(out.value)
        seen[out.kind] += 1
    return seen


@pytest.mark.parametrize("kind", sorted(BINARY))
def test_mutated_binary_files(kind):
    read, data = BINARY[kind]
    seen = _run(kind, read, lambda r: mutate_bytes(data, r))
    assert seen["ok"] and seen["refused"], seen  # the fuzzer reaches both ends of the contract


@pytest.mark.parametrize("kind", sorted(TEXT))
def test_mutated_text_files(kind):
    read, text = TEXT[kind]
    seen = _run(kind, read, lambda r: mutate_text(text, r, tokens=KEYWORDS[kind]))
    assert seen["ok"] and seen["refused"], seen


@pytest.mark.parametrize("kind", sorted(TEXT))
def test_byte_damaged_text_files(kind):
    read, text = TEXT[kind]
    seen = _run(kind, read, lambda r: mutate_bytes(text.encode(), r).decode("utf-8", "replace"))
    assert seen["ok"] and seen["refused"], seen


def test_mutated_gltf_json():
    """The embedded glTF's document: accessors, views, counts and types replaced by odd values."""
    doc = json.loads(gltf.dumps_gltf(MESH))
    keys = ["count", "bufferView", "byteOffset", "componentType", "type", "mesh", "indices", "POSITION", "uri"]

    def make(r: random.Random) -> str:
        return json.dumps(mutate_json(doc, r, keys=keys))

    seen = _run("gltf", gltf.loads, make)
    assert seen["ok"] and seen["refused"], seen


@pytest.mark.parametrize("read, data", [
    (stl.loads, stl.dumps(MESH)[:84] + b"\0" * 50),
    (ply.loads, ply.dumps(MESH).replace(b"element vertex 9", b"element vertex 99999999999")),
    (ply.loads, ply.dumps(MESH).replace(b"element vertex 9", b"element vertex -9")),
    (ply.loads, _ascii_ply(MESH).replace("3 0 2 1", "3 0 2 12")),
    (ply.loads, _ascii_ply(MESH).replace("0 0 1", "0 0 nan")),
    (ply.loads, _ascii_ply(MESH).replace("0 0 1", "0 0 1e300")),
    (stl.loads, _ascii_stl(MESH).replace("vertex 0 0 1", "vertex 0 0 inf")),
    (mesh_obj.loads, mesh_obj.dumps(MESH).replace("v 0 0 1", "v 0 0 1e400")),
    (gltf.loads, gltf.dumps_glb(MESH)[:-8]),
    (gltf.loads, gltf.dumps_gltf(MESH).replace('"count": 4', '"count": 400')),
    (gltf.loads, gltf.dumps_gltf(MESH).replace('"type": "VEC3"', '"type": "VEC2"')),
    (gltf.loads, "[]"),
])
def test_found_cases_refused(read, data):
    """Inputs of the kinds the fuzzer found crashing before the readers shared one check."""
    with pytest.raises(FormatError, match=NAME):
        read(data, NAME)


def test_odd_values_cover_types():
    """The JSON mutator's values include each JSON type and the non-finite numbers."""
    kinds = {type(v).__name__ for v in ODD_VALUES}
    assert {"NoneType", "bool", "int", "float", "str", "list", "dict"} <= kinds
