"""Fixtures of the studio tests: a workspace with corpus drawings and an in-process client."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from tests.conftest import CORPUS

#: Host and origin a browser on the studio's own page sends.
BASE = "http://127.0.0.1:8765"


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    """A workspace folder holding tn-2.uc and tn-11.uc from the teaching sheet."""
    ws = tmp_path / "ws"
    ws.mkdir()
    for name in ("tn-2.uc", "tn-11.uc"):
        shutil.copy(CORPUS / "teaching-sheet" / name, ws / name)
    return ws


@pytest.fixture
def client(workspace: Path):
    """A Starlette TestClient of the studio app on ``workspace``, as seen from 127.0.0.1:8765."""
    from starlette.testclient import TestClient

    from auszug.studio.server import create_app

    with TestClient(create_app(workspace), base_url=BASE) as c:
        yield c

#: The WebSocket endpoint at that address (TestClient needs the full URL for the Host header).
WS = "ws://127.0.0.1:8765/ws"


def receive(ws) -> tuple[dict, bytes | None]:
    """The next server message and its payload: a JSON text frame (payload None), or one
    binary frame read by the header layout written out here, not by the code under test:
    uint32 little-endian JSON length n (a multiple of 4), n bytes of JSON, the payload."""
    import json

    frame = ws.receive()
    if frame.get("text") is not None:
        return json.loads(frame["text"]), None
    data = frame["bytes"]
    n = int.from_bytes(data[:4], "little")
    assert n % 4 == 0 and 4 + n <= len(data), f"bad frame header {n} for {len(data)} bytes"
    return json.loads(data[4:4 + n].decode("utf-8")), data[4 + n:]


def pytest_sessionfinish(session, exitstatus):
    """Close the end-to-end tests' chromium, if they started one."""
    from tests.studio import e2e

    e2e.close_chromium()
