"""The tracery page's server side (auszug.studio.tracery, the tracery_* messages), in process."""

from __future__ import annotations

import dataclasses
import json
import math
import tomllib

import numpy as np
import pytest

from auszug.studio.session import Workspace
from auszug.studio.tracery import split_values, style_text, window_style
from auszug.tracery import build, builtin_style, builtin_styles, load_style, window_mesh
from auszug.tracery.draw import path_data
from auszug.tracery.preview import preview_mesh

from .conftest import WS, receive


def _reply(ws) -> tuple[dict, bytes | None]:
    return receive(ws)


def _build(ws, **msg) -> tuple[dict, bytes | None]:
    ws.send_json({"type": "tracery_build", **msg})
    return _reply(ws)


def test_build_sends_the_exact_regions_and_the_preview_mesh(client):
    with client.websocket_connect(WS) as ws:
        m, payload = _build(ws, style="fig20b", values=["params.span=3", "circle.foils=5"], id=4)
    assert m["type"] == "tracery" and m["id"] == 4 and m["values"] == ["params.span=3", "circle.foils=5"]
    t = build(builtin_style("fig20b").with_overrides({"params.span": 3, "circle.foils": 5}))
    assert [(r["id"], r["d"]) for r in m["regions"]] == [(r.id, path_data(r.curves)) for r in t.regions]
    assert m["bounds"][2] - m["bounds"][0] == 3.0
    # the payload: float32 positions then uint32 indices, exactly as the ArrayRefs say
    n, k = m["positions"]["shape"][0], m["indices"]["shape"][0]
    assert len(payload) == 4 * m["binary_floats"] == 4 * (3 * n + 3 * k)
    pos = np.frombuffer(payload, "<f4", 3 * n).reshape(n, 3)
    idx = np.frombuffer(payload, "<u4", 3 * k, offset=4 * m["indices"]["offset"]).reshape(k, 3)
    assert idx.max() < n
    assert np.allclose(pos.min(0), m["mesh_bounds"][:3]) and np.allclose(pos.max(0), m["mesh_bounds"][3:])
    # front half: from the wall's face (thickness 0.9) to the middle plane; the wall is span + 2 margins wide
    assert pos[:, 1].min() == pytest.approx(-0.45) and pos[:, 1].max() == 0.0
    assert np.ptp(pos[:, 0]) == pytest.approx(3 + 2 * 0.6, abs=1e-6)
    fields = {f["key"]: f for f in m["fields"]}
    assert fields["params.span"]["value"] == 3.0 and fields["circle.foils"]["value"] == 5
    assert fields["circle.pointed"]["kind"] == "bool" and "rosette" in fields["circle.decoration"]["options"]


@pytest.mark.parametrize(("value", "key", "words"), [
    ("params.excess=1e300", "excess", "1e+06"),
    ("params.inner=0.3", "inner", "inner"),
    ("circle.foils=1", "circle.foils", ">= 2"),
    ("circle.foils=100000", "circle.foils", "1024"),
    ("params.span=nan", "span", "span"),
    ("depth=7", "depth", "6"),
    ("subdivide=9", "subdivide", "4"),
    ("circle.bogus=1", "circle.bogus", "circle.foils"),
    ("noequals", "--set", "NAME=VALUE"),
])
def test_a_bad_value_is_refused_naming_it(client, value, key, words):
    with client.websocket_connect(WS) as ws:
        m, payload = _build(ws, style="fig20b", values=[value], id=9)
        assert m["type"] == "tracery_refused" and m["id"] == 9 and payload is None
        assert m["key"].endswith(key) and words in m["message"], m
        assert m["message"].startswith("fig20b: ")
        # the server keeps no tracery state: the next good message builds as if nothing happened
        ok, _ = _build(ws, style="fig20b", values=[], id=10)
        assert ok["type"] == "tracery" and ok["values"] == []


def test_every_style_and_the_prototype_build(client):
    with client.websocket_connect(WS) as ws:
        for name in [*builtin_styles(), "prototype"]:
            m, _ = _build(ws, style=name)
            assert m["type"] == "tracery", m
            assert len(m["regions"]) == len(build(builtin_style("fig20a" if name == "prototype" else name)).regions)
        m, _ = _build(ws, style="fig99")
        assert m["type"] == "tracery_refused" and "fig20a" in m["message"]


def test_depth_refines_the_window(client):
    with client.websocket_connect(WS) as ws:
        m, _ = _build(ws, style="fig20c", values=["depth=2"])
    assert m["depth"] == 2
    assert {f["key"]: f["value"] for f in m["fields"]}["depth"] == 2


def test_save_writes_a_style_that_reopens_to_the_same_window(client, workspace):
    values = ["circle.foils=6", "params.excess=1.1", "circle.orientation=\"lying\"", "depth=1"]
    with client.websocket_connect(WS) as ws:
        for target in ("a/b.toml", "c.style.json"):
            ws.send_json({"type": "tracery_save", "target": target, "style": "fig20c", "values": values, "id": 3})
            m, _ = _reply(ws)
            assert m == {"type": "saved", "path": target, "id": 3}
            st = load_style(workspace / target)
            want = window_style(None, "fig20c", "", values)
            assert st.data == want.data
            got = [path_data(r.curves) for r in build(st).regions]
            assert got == [path_data(r.curves) for r in build(want).regions]
            # and the page reopens it by path
            m, _ = _build(ws, path=target)
            assert m["type"] == "tracery" and m["name"] == "fig20c" and m["depth"] == 1
        ws.send_json({"type": "list_styles", "id": 5})
        m, _ = _reply(ws)
        assert m["workspace"] == ["a/b.toml", "c.style.json"] and m["builtin"] == list(builtin_styles())
        # refused: another ending, outside the workspace, a style that does not build; nothing written
        for target, words in (("x.txt", ".toml or .json"), ("../out.toml", "outside the workspace")):
            ws.send_json({"type": "tracery_save", "target": target, "style": "fig20a", "id": 6})
            m, _ = _reply(ws)
            assert m["type"] == "error" and words in m["message"]
        ws.send_json({"type": "tracery_save", "target": "bad.toml", "style": "fig20a", "values": ["params.inner=0.3"]})
        m, _ = _reply(ws)
        assert m["type"] == "tracery_refused"
    assert not (workspace / "x.txt").exists() and not (workspace / "bad.toml").exists()
    assert not (workspace.parent / "out.toml").exists()


def test_style_text_round_trips_every_builtin_style():
    for name in builtin_styles():
        st = builtin_style(name)
        for suffix in (".toml", ".json"):
            text = style_text(st, suffix)
            data = tomllib.loads(text) if suffix == ".toml" else json.loads(text)
            assert "window" not in data["sub-arch"] or isinstance(data["sub-arch"]["window"], dict)
            from auszug.tracery import parse_style

            assert parse_style(text, suffix).data == st.data


@pytest.mark.parametrize("fmt", ["glb", "obj", "stl", "svg", "json"])
def test_export_is_the_finished_window(client, fmt):
    import trimesh

    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "tracery_export", "format": fmt, "style": "fig20a", "values": ["params.span=2.5"],
                      "id": 8})
        m, data = _reply(ws)
    assert m["type"] == "exported" and m["id"] == 8 and m["size"] == len(data) and m["name"] == (
        "fig20a.tracery.json" if fmt == "json" else f"fig20a.{fmt}")
    if fmt in ("glb", "obj", "stl"):
        import io

        mesh = trimesh.load(io.BytesIO(data), file_type=fmt, force="mesh")
        assert mesh.is_watertight and mesh.volume > 0
        ref = window_mesh(build(builtin_style("fig20a").with_overrides({"params.span": 2.5})))
        assert len(mesh.faces) == ref.n_faces
        assert np.ptp(mesh.bounds[:, 0]) == pytest.approx(2.5 + 2 * 0.6, abs=1e-5)
    elif fmt == "svg":
        assert data.startswith(b"<?xml") and data.count(b"<path") == 8
    else:
        doc = json.loads(data)
        assert doc["format"] == "auszug.tracery" and doc["params"]["span"] == 2.5 and len(doc["regions"]) == 8


def test_a_slow_build_is_given_up_after_the_budget(client, monkeypatch):
    import auszug.studio.server as S

    monkeypatch.setattr(S, "LIMITS", dataclasses.replace(S.LIMITS, edit_seconds=0.001))
    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "tracery_build", "style": "fig20c", "values": ["depth=6"], "id": 2})
        m, _ = _reply(ws)
        assert m["type"] == "error" and m["id"] == 2 and "took longer than 0.001 s" in m["message"]
        monkeypatch.setattr(S, "LIMITS", dataclasses.replace(S.LIMITS, edit_seconds=20.0))
        ws.send_json({"type": "list_styles", "id": 3})   # the server still answers
        assert _reply(ws)[0]["id"] == 3


def test_split_values_and_a_workspace_file_outside(workspace):
    assert split_values(["a.b=1", "a.b=2", "depth=0", "subdivide=2"]) == ({"a.b": 2}, 0, 2)
    with pytest.raises(Exception, match="outside the workspace"):
        window_style(Workspace(workspace), "", "../x.toml", [])
    with pytest.raises(Exception, match="at most 64 values"):
        split_values(["a=1"] * 65)


def test_the_preview_mesh_matches_the_window():
    """The preview's front half and its mirror span the finished mesh's box (x and z exactly, y the wall)."""
    for name in ("fig20a", "fig20d", "fig20h"):
        t = build(name)
        v, f = preview_mesh(t)
        ref = window_mesh(t)
        lo, hi = ref.bounds()
        assert np.allclose(v.min(0), lo, atol=1e-5) and np.allclose(v.max(0), hi, atol=1e-5)
        half, hf = preview_mesh(t, back=False)
        assert len(v) == 2 * len(half) and len(f) == 2 * len(hf)
        assert np.array_equal(v[len(half):], half * np.array([1, -1, 1], np.float32))
        assert math.isclose(float(half[:, 1].max()), 0.0, abs_tol=1e-9)


def test_svg_path_is_path_data_for_every_region():
    from auszug.studio.tracery import svg_path

    for name in builtin_styles():
        for st in (builtin_style(name), builtin_style(name).with_overrides({"params.excess": 0.9, "params.span": 3.7})):
            for r in build(st).regions:
                assert svg_path(r.curves) == path_data(r.curves)


def test_style_references_stay_inside_the_workspace(client, workspace, tmp_path):
    outside = tmp_path / "outside.toml"
    outside.write_text('extends = "fig20b"\n')
    (workspace / "sub").mkdir()
    (workspace / "sub" / "base.toml").write_text('extends = "fig20c"\n[circle]\nfoils = 5\n')
    (workspace / "ok.toml").write_text('extends = "sub/base.toml"\n')
    (workspace / "abs.toml").write_text(f'extends = "{outside}"\n')
    (workspace / "up.toml").write_text('extends = "../outside.toml"\n')
    (workspace / "nested.toml").write_text(f'extends = "fig20f"\n[sub-arch]\nwindow = {{ extends = "{outside}" }}\n')
    (workspace / "link.toml").symlink_to(outside)
    (workspace / "via-link.toml").write_text('extends = "link.toml"\n')
    with client.websocket_connect(WS) as ws:
        m, _ = _build(ws, path="ok.toml")
        assert m["type"] == "tracery" and {f["key"]: f["value"] for f in m["fields"]}["circle.foils"] == 5
        for name in ("abs.toml", "up.toml", "nested.toml", "via-link.toml", "link.toml"):
            m, _ = _build(ws, path=name, id=7)
            assert m["type"] == "error" and m["id"] == 7 and "outside the workspace" in m["message"], (name, m)
        # values may name built-in styles only, also inside an inline table
        for value in (f'sub-arch.window="{outside}"', f'sub-arch.window={{extends="{outside}"}}',
                      'sub-arch.window="ok.toml"'):
            m, _ = _build(ws, style="fig20f", values=[value])
            assert m["type"] == "tracery_refused" and "built-in style name" in m["message"], (value, m)
        m, _ = _build(ws, style="fig20f", values=['sub-arch.window="fig20b"'])
        assert m["type"] == "tracery"


def test_the_fast_reply_text_is_the_protocols_encoding():
    from auszug.studio import protocol as P
    from auszug.studio.tracery import build_message, tracery_text

    for name in builtin_styles():
        values = ["params.excess=1.1", "circle.orientation=\"lying\""]
        msg, _ = build_message(window_style(None, name, "", values), name, "", values, msg_id=12)
        assert tracery_text(msg) == P.encode(msg)


def test_a_window_built_before_comes_from_the_cache_the_same(client):
    """Undo, redo and a value typed again: the same window, from the cache; the cache stays bounded."""
    from auszug.studio.tracery import CACHE_WINDOWS, WINDOWS

    WINDOWS.clear()
    with client.websocket_connect(WS) as ws:
        first, p1 = _build(ws, style="fig20d", values=["params.excess=1.3"])
        other, _ = _build(ws, style="fig20d", values=["params.excess=1.1"])
        again, p2 = _build(ws, style="fig20d", values=["params.excess=1.3"], id=9)
        # the same style value written another way (a default spelled out) is the same window
        same, p3 = _build(ws, style="fig20d", values=["params.excess=1.30", "circle.foils=4"])
    assert not first["cached"] and not other["cached"] and again["cached"] and same["cached"]
    assert p1 == p2 == p3 and again["regions"] == first["regions"] and again["id"] == 9
    drop = {"cached", "id", "values"}
    assert {k: v for k, v in again.items() if k not in drop} == {k: v for k, v in first.items() if k not in drop}
    assert again["values"] == ["params.excess=1.3"] and same["values"] == ["params.excess=1.30", "circle.foils=4"]
    # least recently used first out: after CACHE_WINDOWS other windows, 1.3 is built again
    with client.websocket_connect(WS) as ws:
        for k in range(CACHE_WINDOWS):
            m, _ = _build(ws, style="fig20a", values=[f"params.span={2 + 0.01 * (k + 1)}"])
            assert not m["cached"]
        assert len(WINDOWS) == CACHE_WINDOWS
        m, p4 = _build(ws, style="fig20d", values=["params.excess=1.3"])
    assert not m["cached"] and p4 == p1


def test_the_window_cache_is_bounded_in_bytes():
    from auszug.studio.tracery import WindowCache

    c = WindowCache(entries=10, max_bytes=100)
    for k in range(5):
        c.put(str(k), k, 30)
    assert len(c) == 3 and c.nbytes == 90 and [c.get(str(k)) for k in range(5)] == [None, None, 2, 3, 4]
    c.put("big", "x", 101)                      # larger than the whole cache: not kept, nothing dropped
    assert c.get("big") is None and len(c) == 3
    c.put("3", "again", 60)                     # replacing an entry counts its new size
    assert c.nbytes <= 100 and c.get("3") == "again"
