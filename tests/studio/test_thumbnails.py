"""Gallery thumbnails: the top view as a small SVG, exact to the network's curves; over the socket."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from auszug import examples
from auszug.formats import load
from auszug.formats.palette import colour
from auszug.microarch import build
from auszug.studio.thumbnails import MAX_POINTS, THUMB_PX, thumbnail_svg

from .conftest import WS, receive

SVG = "{http://www.w3.org/2000/svg}"


def _polylines(svg: str) -> list[tuple[str, np.ndarray]]:
    root = ET.fromstring(svg)
    assert (root.get("width"), root.get("height")) == (str(THUMB_PX), str(THUMB_PX))
    return [(p.get("stroke"), np.array([[float(v) for v in xy.split(",")] for xy in p.get("points").split()]))
            for p in root.iter(f"{SVG}polyline")]


@pytest.mark.parametrize("name", ["teaching-sheet/tn-2.uc", "web/U.XI.28.uc", "legacy/U.XI.15.uc"])
def test_thumbnail_is_the_top_view_of_every_curve(name):
    net = build(load(examples.path(name)))
    curves = list(net.curves())
    lines = _polylines(thumbnail_svg(net))
    assert len(lines) == len(curves)
    xy = np.concatenate([c.points[:, :2] for c in curves])
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    k = (THUMB_PX - 12) / max(hi - lo)
    for (stroke, pts), c in zip(lines, curves, strict=True):
        assert stroke == colour(c.basic)
        assert 2 <= len(pts) <= MAX_POINTS
        # the ends are the curve's ends, mapped with y flipped and the extent centred in the square
        for got, p in ((pts[0], c.points[0]), (pts[-1], c.points[-1])):
            want = [THUMB_PX / 2 + (p[0] - (lo[0] + hi[0]) / 2) * k, THUMB_PX / 2 - (p[1] - (lo[1] + hi[1]) / 2) * k]
            np.testing.assert_allclose(got, want, atol=0.051)
    allpts = np.concatenate([p for _, p in lines])
    # the binding extent spans the square less the 6 px margins (rounded to 0.1 px)
    span = allpts.max(axis=0) - allpts.min(axis=0)
    assert abs(span.max() - (THUMB_PX - 12)) <= 0.11
    assert allpts.min() >= 6 - 0.051 and allpts.max() <= THUMB_PX - 6 + 0.051


def test_thumbnail_of_an_empty_drawing_is_blank():
    from auszug.microarch import Drawing

    assert _polylines(thumbnail_svg(build(Drawing(())))) == []


def test_thumbnails_over_the_socket(client, workspace):
    (workspace / "bad.uc").write_text("unitCurve x\n")
    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "get_thumbnail", "path": "tn-2.uc", "id": 1})
        msg, payload = receive(ws)
        assert (msg["type"], msg["id"], msg["path"], payload) == ("thumbnail", 1, "tn-2.uc", None)
        assert msg["svg"] == thumbnail_svg(build(load(workspace / "tn-2.uc")))
        ws.send_json({"type": "get_thumbnail", "example": "web/U.XI.28.uc", "id": 2})
        msg, _ = receive(ws)
        assert msg["example"] == "web/U.XI.28.uc" and len(re.findall("<polyline", msg["svg"])) == 32
        for bad, words in (({"path": "../etc/passwd"}, "workspace"), ({"example": "nope.uc"}, "no bundled example"),
                           ({"path": "bad.uc"}, "bad.uc"), ({}, "exactly one")):
            ws.send_json({"type": "get_thumbnail", "id": 3, **bad})
            err = ws.receive_json()
            assert err["type"] == "error" and err["id"] == 3 and words in err["message"], (bad, err)
        ws.send_json({"type": "list_files", "id": 4})
        assert receive(ws)[0]["type"] == "files"   # the connection lives
