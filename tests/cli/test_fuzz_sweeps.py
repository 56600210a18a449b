"""Fuzzing ``auszug sweeps`` end to end: mutated mesh files through the command line.

The readers alone are fuzzed in tests/formats/test_fuzz_mesh_readers.py; here a
mutated mesh goes on through ``sweeps.detect`` and the writers, so a mesh that
reads but is odd (a degenerate, duplicated or far-away vertex, a flipped or
missing face) must still end in exit 0 with the result written, or exit 2 with
one line naming the file and no output left behind (tests/fuzzing.py).
The analysis runs with ``--planes 10 --refinements 0 --match-angle 2`` (few planes, few matches
for the general fallback that most mutated meshes fall into) so a case costs about 0.1-0.5 s.
"""

from __future__ import annotations

import json
import random
import struct
from functools import cache

import numpy as np
import pytest

from auszug.formats import mesh_obj, ply, stl
from auszug.meshing.mesh import Mesh
from auszug.sweeps.fixtures import revolved
from tests.fuzzing import assert_finite, case, cases, mutate_bytes, mutate_text, run_cli

#: Cases per mesh format in a ``make test`` run (about 0.2 s each).
N = 12
FAST = ["--quiet", "--planes", "10", "--refinements", "0", "--match-angle", "2"]
OBJ_TOKENS = ["v", "f", "g", "vn", "vt", "1/1", "-1", "0"]


@cache
def _mesh() -> Mesh:
    """A coarse surface of revolution: 600 vertices, 1102 triangles."""
    fx = revolved(n_profile=30, n_path=20)
    return Mesh(fx.vertices, fx.faces)


def _valid(fmt: str) -> bytes:
    m = _mesh()
    if fmt == "stl":
        return stl.dumps(m)
    if fmt == "ply":
        return ply.dumps(m)
    return mesh_obj.dumps(m, "m.obj").encode()


def _odd_mesh(rnd: random.Random) -> Mesh:
    """The fixture with 1-3 geometric mutations that a reader accepts and detect must cope with.

    A vertex moved far away or onto another, a face flipped, repeated or dropped, a run of faces
    dropped (a hole), every vertex snapped to a coarse grid, the mesh flattened along an axis.
    """
    m = _mesh()
    v, f = m.vertices.copy(), m.faces.copy()
    for _ in range(rnd.randint(1, 3)):
        op = rnd.randrange(7)
        i = rnd.randrange(len(v))
        if op == 0:
            v[i] = rnd.choice([1e5, -1e5, 1e-30, 1e3]) * np.asarray([rnd.random() for _ in range(3)])
        elif op == 1:
            v[i] = v[rnd.randrange(len(v))]
        elif op == 2:
            j = rnd.randrange(len(f))
            f[j] = f[j, ::-1]
        elif op == 3:
            f = np.concatenate([f, f[rnd.randrange(len(f)):][:rnd.randint(1, 50)]])
        elif op == 4:
            j = rnd.randrange(len(f))
            f = np.delete(f, np.s_[j:j + rnd.randint(1, 400)], axis=0)
        elif op == 5:
            v = np.round(v, rnd.randint(0, 2))
        else:
            v[:, rnd.randrange(3)] *= rnd.choice([0.0, 1e-9, 1e4])
    return Mesh(v, f)


def _in_place(data: bytes, rnd: random.Random) -> bytes:
    """``data`` with 1-4 runs of four bytes overwritten (the length kept, so the binary reader parses it)."""
    b = bytearray(data)
    for _ in range(rnd.randint(1, 4)):
        i = rnd.randrange(len(b) - 4)
        b[i:i + 4] = struct.pack("<f", rnd.choice([0.0, -0.0, 1.0, 1e5, -1e5, 1e-40, float("nan"), float("inf")]))
    return bytes(b)


def _mutated(fmt: str, seed: int) -> bytes:
    """Seed mod 3: 0 byte- or token-level mutations, 1 the same in place, 2 a mesh-level mutation."""
    rnd = random.Random(seed)
    if seed % 3 == 2:
        m = _odd_mesh(rnd)
        return {"stl": stl.dumps, "ply": ply.dumps}[fmt](m) if fmt != "obj" else mesh_obj.dumps(m, "m.obj").encode()
    data = _valid(fmt)
    if fmt == "obj":
        return mutate_text(data.decode(), rnd, tokens=OBJ_TOKENS).encode()
    return mutate_bytes(data, rnd) if seed % 3 == 0 else _in_place(data, rnd)


@pytest.mark.parametrize("fmt", ["stl", "ply", "obj"])
def test_the_unmutated_fixture_gives_one_patch(tmp_path, fmt):
    """The fuzz seed mesh is analysed (so mutations start from a success, not a refusal)."""
    src = tmp_path / f"m.{fmt}"
    src.write_bytes(_valid(fmt))
    out = tmp_path / "m.sweeps.json"
    got = run_cli(["sweeps", str(src), "-o", str(out), *FAST], src.name, [out])
    assert got.kind == "ok" and ": 1 patch(es), coverage 1.000" in got.value
    assert json.loads(out.read_text())["patches"][0]["kind"] == "rotation"


@pytest.mark.parametrize("fmt", ["stl", "ply", "obj"])
def test_sweeps_on_mutated_meshes_keeps_the_contract(tmp_path, fmt):
    kinds = {"ok": 0, "refused": 0}
    for seed in cases(N):
        src = tmp_path / f"fuzzed-{seed}.{fmt}"
        src.write_bytes(_mutated(fmt, seed))
        out = tmp_path / f"fuzzed-{seed}.sweeps.json"
        png = tmp_path / f"fuzzed-{seed}.png"
        argv = ["sweeps", str(src), "-o", str(out), *FAST]
        if seed % 4 == 0:  # the picture too, from the same report
            argv += ["--png", str(png)]
        with case(f"sweeps {fmt} seed {seed}"):
            got = run_cli(argv, src.name, [out, png] if seed % 4 == 0 else [out])
            kinds[got.kind] += 1
            if got.kind == "ok":
                rep = json.loads(out.read_text())
                assert 0.0 <= rep["coverage"] <= 1.0
                assert_finite(rep["bbox_diameter"], *(np.asarray(p["profile"], dtype=float).ravel()
                                                       for p in rep["patches"]))
                out.unlink()
                png.unlink(missing_ok=True)
        src.unlink()
    # the mutations must reach both sides of the contract, or the fuzzer tests nothing
    if len(cases(N)) >= N:
        assert kinds["ok"] > 0 and kinds["refused"] > 0, kinds
