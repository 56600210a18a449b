"""Fuzzing the studio protocol: random and malformed messages to a live server (uvicorn, a real WebSocket).

The contract: the connection is never dropped and the server never dies; every
message that fails gets an ``error`` reply, never an "internal error" (an
exception the server did not expect); and a valid message after the garbage
still gets its reply. Messages are valid ones with values mutated
(tests/fuzzing.py), well-typed messages with odd values, and raw garbage.
"""

from __future__ import annotations

import json
import random
from collections import Counter
from typing import Any

import pytest

from auszug.studio import protocol as P
from tests.fuzzing import ODD_VALUES, case, cases, mutate_bytes, mutate_json

from .e2e import Studio

#: Valid messages on a drawing with two curves (tn-2.uc), one per type, as a client sends them.
VALID: list[dict[str, Any]] = [
    {"type": "move_vertex", "curve": 0, "vertex": 1, "xy": [0.3, 0.2], "drag": 1},
    {"type": "move_handle", "curve": 0, "segment": 0, "handle": 0, "xy": [0.1, 0.1]},
    {"type": "set_apex_height", "curve": 0, "height": 2.0},
    {"type": "set_prc", "curve": 0, "fraction": 0.5, "segment": 0},
    {"type": "recompute_prc", "curves": [0]},
    {"type": "set_layer_bottom", "layer": 0, "z": 0.1},
    {"type": "set_decoration", "curve": 0, "on": True, "at": 0.5},
    {"type": "set_post", "curve": 0, "top": 1.0},
    {"type": "set_symmetry", "curve": 0, "fold": 3, "mirror": "none"},
    {"type": "remove_curve", "curve": 1},
    {"type": "draw_curve", "vertices": [[0, 0], [0.5, 0.2], [1, 0]], "handles": [[], []], "marks": [],
     "fold": 2, "mirror": "none", "layer": 0},
    {"type": "set_layer", "curve": 0, "layer": 1},
    {"type": "set_prc_at", "curve": 0, "point": [0.2, 0.1], "segment": 0},
    {"type": "set_prc_height", "curve": 0, "z": 1.5, "segment": 0},
    {"type": "add_layer", "bottom": 0.5},
    {"type": "remove_layer", "layer": 1},
    {"type": "undo"}, {"type": "redo"}, {"type": "recover"},
    {"type": "open", "path": "tn-2.uc"}, {"type": "save", "path": "copy.uc"},
    {"type": "list_files"}, {"type": "open_example", "name": "teaching-sheet/tn-2.uc"},
    {"type": "open_text", "name": "t.uc",
     "text": "numCurves 1\nunitCurve 2 2 0\nptPos 0 0\nptLab 0\nptPos 1 0\nptLab 1\n"},
    {"type": "new_drawing", "name": "fresh"},
    {"type": "get_mesh", "style": "bar", "faces": "none", "loops": [], "size": 0.02, "segments": 16},
    {"type": "get_loops"},
    {"type": "export", "format": "stl", "style": "bar", "faces": "none", "loops": [], "solid": False,
     "colors": []},
]
KEYS = sorted({k for m in VALID for k in m}) + ["id", "zzz"]
TYPES = sorted({m["type"] for m in VALID}) + ["error", "geometry", "", "OPEN"]
#: Fuzz rounds in a ``make test`` run; each sends a burst of messages, then a sentinel.
N = 150
BURST = 6
#: Seconds a reply may take (a mesh job on a loaded machine included).
TIMEOUT = 60


def _garbage(rnd: random.Random) -> str | bytes:
    """One message: a mutated valid one (most), a well-typed one with odd values, or raw garbage."""
    k = rnd.randrange(10)
    base = dict(rnd.choice(VALID), id=rnd.randint(1, 10**6))
    if k < 5:
        return json.dumps(mutate_json(base, rnd, keys=KEYS))
    if k < 7:
        m = {key: (v if rnd.random() < 0.5 else rnd.choice(ODD_VALUES)) for key, v in base.items()}
        m["type"] = rnd.choice(TYPES) if rnd.random() < 0.2 else base["type"]
        return json.dumps(m)
    if k == 7:
        return mutate_bytes(json.dumps(base).encode(), rnd)
    if k == 8:
        return rnd.choice(["", "null", "[]", "{}", '{"type": null}', "[" * 100_000, '{"a":' * 50_000,
                           b"\xed\xa0\x80", '"\\ud800"', "1e999", "{" + '"id": 1,' * 1000 + '"type": "undo"}'])
    return rnd.randbytes(rnd.randint(0, 64))


def _read_until(ws: Any, sentinel: int, seen: Counter) -> None:
    """Read replies until the reply to ``sentinel``; every reply is well formed and no internal error."""
    while True:
        frame = ws.recv(timeout=TIMEOUT)
        if isinstance(frame, bytes):
            n = int.from_bytes(frame[:4], "little")
            assert n % 4 == 0 and 4 + n <= len(frame), "bad binary frame"
            msg = json.loads(frame[4:4 + n].decode("utf-8"))
        else:
            msg = json.loads(frame)
        seen[msg["type"]] += 1
        if msg["type"] == "error":
            assert msg["message"] and "internal error" not in msg["message"], msg["message"]
        if msg.get("id") == sentinel and msg["type"] == "files":
            return


@pytest.fixture
def studio(workspace):
    s = Studio(workspace)
    yield s
    s.stop()


def test_random_messages_to_a_live_server(studio):
    from websockets.sync.client import connect  # the studio's own dependency (pyproject.toml)

    url = f"ws://127.0.0.1:{studio.port}/ws"
    seen: Counter = Counter()
    with connect(url, origin=f"http://127.0.0.1:{studio.port}", max_size=None) as ws:
        for seed in cases(N):
            rnd = random.Random(seed)
            ws.send(json.dumps({"type": "open", "path": rnd.choice(["tn-2.uc", "tn-11.uc"]), "id": 1}))
            burst = [_garbage(rnd) for _ in range(BURST)]
            with case(f"studio seed {seed}: {[str(b)[:200] for b in burst]}"):
                for b in burst:
                    ws.send(b)
                # the connection lives: a valid message after the garbage gets its reply
                ws.send(json.dumps({"type": "list_files", "id": 10**9 + seed}))
                _read_until(ws, 10**9 + seed, seen)
    assert seen["error"] and seen["geometry"], seen  # both ends of the contract were reached
    # the server lives too: a new connection opens a drawing
    with connect(url, origin=f"http://127.0.0.1:{studio.port}") as ws:
        ws.send(json.dumps({"type": "list_files", "id": 7}))
        _read_until(ws, 7, Counter())


@pytest.mark.parametrize("text", ["[" * 100_000, '{"a":' * 50_000])
def test_deeply_nested_json_is_a_protocol_error(text):
    """Found by the fuzzer: json's RecursionError was an internal error, not a ProtocolError."""
    with pytest.raises(P.ProtocolError, match="not valid JSON"):
        P.decode(text)


def test_deeply_nested_json_keeps_the_connection(client):
    """Found by the fuzzer: the error reply's id lookup parsed the message again, and its
    RecursionError closed the connection."""
    from .conftest import WS

    with client.websocket_connect(WS) as ws:
        ws.send_text('{"a":' * 50_000)
        assert "not valid JSON" in ws.receive_json()["message"]
        ws.send_json({"type": "list_files", "id": 3})
        assert ws.receive_json()["id"] == 3


@pytest.mark.parametrize("msg, message", [
    ({"type": "set_prc_at", "curve": 3, "point": [0.2, 0.1]}, "no curve 3"),  # StopIteration: internal error
    ({"type": "set_prc_height", "curve": 5, "z": 1.0}, "no curve 5"),
    ({"type": "set_prc", "curve": 0, "fraction": 0.5, "segment": -1}, "no segment -1"),  # set the last one
    ({"type": "set_prc_at", "curve": 0, "point": [0.2, 0.1], "segment": 99}, "no segment 99"),
])
def test_found_edit_cases(client, msg, message):
    from .conftest import WS

    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc", "id": 1})
        ws.receive()
        ws.send_json({**msg, "id": 2})
        err = ws.receive_json()
        assert err["type"] == "error" and err["id"] == 2 and message in err["message"], err
