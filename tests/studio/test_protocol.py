"""The protocol: decoding is strict, every edit maps to its edit function, the TypeScript does not drift."""

from __future__ import annotations

import dataclasses
import inspect
import json

import pytest

from auszug.microarch import edit
from auszug.studio import protocol as P
from tests.conftest import REPO

TS = REPO / "web" / "src" / "protocol.ts"


def test_typescript_in_sync():
    """web/src/protocol.ts is exactly what protocol.py generates (regenerate: make protocol)."""
    assert TS.read_text(encoding="utf-8") == P.typescript(), (
        "web/src/protocol.ts is out of date: run `make protocol`")


@pytest.mark.parametrize("cls", [c for c in P.CLIENT_MESSAGES if issubclass(c, P.EditOp)])
def test_edit_fields_match_edit_function(cls):
    """Each edit message's fields are exactly its function's parameters after the drawing."""
    params = list(inspect.signature(cls.fn).parameters)[1:]
    fields = [f.name for f in dataclasses.fields(cls) if f.name not in P.EditOp.NOT_PARAMETERS]
    assert set(fields) == set(params)
    assert cls.fn.__name__ in edit.__all__


def test_type_tags_unique():
    tags = [c.__dataclass_fields__["type"].default for c in P.CLIENT_MESSAGES + P.SERVER_MESSAGES]
    assert len(tags) == len(set(tags))


def test_decode_round_trip():
    for msg in (P.Open(path="a.uc", id=3), P.MoveVertex(curve=1, vertex=0, xy=(0.5, -1.0)),
                P.SetPrc(curve=0, fraction=None, segment=1), P.RecomputePrc(curves=[0, 2]),
                P.SetSymmetry(curve=0, fold=5, mirror="y axis"), P.Undo(id=7)):
        assert P.decode(json.dumps(dataclasses.asdict(msg))) == msg


@pytest.mark.parametrize("text, says", [
    ("{", "not valid JSON"),
    ("[1, 2]", "JSON object"),
    ('{"type": "explode"}', "unknown message type 'explode'"),
    ('{"type": "open"}', "missing field 'path'"),
    ('{"type": "open", "path": "a", "extra": 1}', "unknown field(s) extra"),
    ('{"type": "set_apex_height", "curve": true, "height": 1}', "expected an integer"),
    ('{"type": "set_apex_height", "curve": 0, "height": NaN}', "finite number"),
    ('{"type": "move_vertex", "curve": 0, "vertex": 0, "xy": [1]}', "list of 2 values"),
    ('{"type": "set_symmetry", "curve": 0, "mirror": "diagonal"}', "expected one of"),
])
def test_decode_rejects(text, says):
    with pytest.raises(P.ProtocolError, match=None) as e:
        P.decode(text)
    assert says in str(e.value)


def test_pack_layout_written_out():
    """A message with a payload is one frame: JSON length, JSON padded with spaces to 4 bytes, payload."""
    payload = b"\x00\x00\x80\x3f" + b"\x00\x00\x00\x40"   # float32 1.0, 2.0
    frame = P.pack('{"type":"mesh"}', payload)               # 15 bytes of JSON -> padded to 16
    assert frame == b"\x10\x00\x00\x00" + b'{"type":"mesh"} ' + payload
    assert P.unpack(frame) == ({"type": "mesh"}, payload)
    assert P.pack('{"a":1}!', b"") == b"\x08\x00\x00\x00" + b'{"a":1}!'     # already aligned: no padding
    # non-ASCII JSON counts bytes, not characters
    frame = P.pack('{"n":"\u00e9"}', b"xyzw")
    assert int.from_bytes(frame[:4], "little") == 12 and frame[4 + 12:] == b"xyzw"
    assert P.unpack(frame)[0] == {"n": "\u00e9"}


@pytest.mark.parametrize("frame, says", [
    (b"\x01\x00", "has no header"),
    (b"\x08\x00\x00\x00{}", "cannot hold a message of 8 bytes"),
    (b"\x03\x00\x00\x00{} xxxx", "cannot hold a message of 3 bytes"),
])
def test_unpack_rejects(frame, says):
    with pytest.raises(P.ProtocolError, match=says):
        P.unpack(frame)


FIXTURE = REPO / "web" / "src" / "replicas.fixture.json"


def replica_fixture() -> str:
    """The matrices of C_n (+ mirror) that the page's preview of a curve being drawn must reproduce."""
    from auszug.geometry.symmetry import SymmetryGroup

    cases = []
    for fold in (1, 2, 3, 4, 5, 6, 7, 8, 12, 16):
        for axis in (None, (1.0, 0.0), (0.0, 1.0), (0.3, 0.7), (-2.0, 1.0)):
            g = SymmetryGroup(fold, axis is not None, axis=axis or (0.0, 1.0))
            cases.append({"fold": fold, "axis": None if axis is None else list(axis), "labels": g.labels(),
                          "matrices": [[float(v) for v in m.ravel()] for m in g.matrices()]})
    return json.dumps(cases, indent=0) + "\n"


def test_replica_fixture_in_sync():
    """web/src/replicas.fixture.json is what geometry.symmetry computes (regenerate: AUSZUG_WRITE_FIXTURES=1)."""
    import os

    want = replica_fixture()
    if os.environ.get("AUSZUG_WRITE_FIXTURES"):
        FIXTURE.write_text(want)
    assert FIXTURE.read_text() == want, (
        "web/src/replicas.fixture.json is out of date: run this test with AUSZUG_WRITE_FIXTURES=1")
