"""Shared documents, files, examples, uploads, new drawings, save, autosave and crash recovery."""

from __future__ import annotations

import json
import os
import shutil
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from starlette.testclient import TestClient

from auszug import examples
from auszug.formats import format_for, load
from auszug.microarch import edit
from auszug.studio import protocol as P
from auszug.studio.server import create_app

from .conftest import BASE, WS, receive


def _geometry(ws) -> tuple[dict, bytes]:
    msg, data = receive(ws)
    assert msg["type"] == "geometry", msg
    assert len(data) == 4 * msg["binary_floats"]
    return msg, data


def _reply(ws, kind: str) -> dict:
    msg = ws.receive_json()
    assert msg["type"] == kind, msg
    return msg


def _same(a, b) -> bool:
    return replace(a, name="") == replace(b, name="")


def _round_trip(d, name: str):
    """``d`` written and read back in the format of ``name`` (how a saved drawing reads)."""
    fmt = format_for(name, "drawing")
    return fmt.reader(fmt.writer(d, name), name)


def _wait_for(p: Path, timeout: float = 10.0) -> None:
    t0 = time.monotonic()
    while not p.exists():
        if time.monotonic() - t0 > timeout:
            raise AssertionError(f"{p} did not appear within {timeout} s")
        time.sleep(0.01)


def _app(workspace: Path, **kw):
    return TestClient(create_app(workspace, **kw), base_url=BASE)


# ---------------------------------------------------------------- two tabs, one document


def test_edit_in_one_tab_arrives_in_the_other(client, workspace):
    with client.websocket_connect(WS) as a, client.websocket_connect(WS) as b:
        a.send_json({"type": "open", "path": "tn-2.uc", "id": 1})
        ga, _ = _geometry(a)
        b.send_json({"type": "open", "path": "./tn-2.uc", "id": 1})
        gb, _ = _geometry(b)
        assert ga["path"] == gb["path"] == "tn-2.uc" and ga["revision"] == gb["revision"]
        a.send_json({"type": "set_apex_height", "curve": 0, "height": 2.5, "id": 7})
        g_a, data_a = _geometry(a)
        g_b, data_b = _geometry(b)
        assert g_a["id"] == 7 and g_b["id"] == 0
        assert data_a == data_b                                  # identical geometry, byte for byte
        assert {**g_a, "id": 0} == g_b
        assert g_b["can_undo"] and g_b["dirty"] and g_b["curves"][0]["apex"] == 2.5
        # undo in the second tab undoes the first tab's edit, in both
        b.send_json({"type": "undo", "id": 3})
        u_b, data_ub = _geometry(b)
        u_a, data_ua = _geometry(a)
        assert (u_b["id"], u_a["id"]) == (3, 0) and data_ua == data_ub
        assert not u_a["can_undo"] and u_a["can_redo"] and not u_a["dirty"]
        assert u_a["curves"][0]["apex"] == ga["curves"][0]["apex"]
        assert u_a["revision"] > g_a["revision"]


def test_tabs_on_different_files_do_not_see_each_other(client):
    with client.websocket_connect(WS) as a, client.websocket_connect(WS) as b:
        a.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(a)
        b.send_json({"type": "open", "path": "tn-11.uc"})
        _geometry(b)
        a.send_json({"type": "set_apex_height", "curve": 0, "height": 2.5, "id": 1})
        assert _geometry(a)[0]["id"] == 1
        b.send_json({"type": "list_files", "id": 2})
        assert _reply(b, "files")["id"] == 2       # nothing from a's edit came before this reply


def test_opening_another_file_moves_the_tab(client):
    with client.websocket_connect(WS) as a, client.websocket_connect(WS) as b:
        for ws in (a, b):
            ws.send_json({"type": "open", "path": "tn-2.uc"})
            _geometry(ws)
        b.send_json({"type": "open", "path": "tn-11.uc", "id": 4})
        assert _geometry(b)[0]["path"] == "tn-11.uc"
        a.send_json({"type": "set_apex_height", "curve": 0, "height": 2.5, "id": 5})
        assert _geometry(a)[0]["id"] == 5
        b.send_json({"type": "list_files", "id": 6})
        assert _reply(b, "files")["id"] == 6       # b no longer gets tn-2.uc's geometry


def test_a_second_tab_sees_the_edited_state(client):
    with client.websocket_connect(WS) as a:
        a.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(a)
        a.send_json({"type": "set_apex_height", "curve": 0, "height": 2.5})
        _, data = _geometry(a)
        with client.websocket_connect(WS) as b:
            b.send_json({"type": "open", "path": "tn-2.uc", "id": 2})
            g, data_b = _geometry(b)
            assert data_b == data and g["dirty"] and g["can_undo"]


def test_the_last_tab_closing_drops_the_document(client, workspace):
    with client.websocket_connect(WS) as a:
        a.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(a)
        a.send_json({"type": "set_apex_height", "curve": 0, "height": 2.5})
        _geometry(a)
    with client.websocket_connect(WS) as b:
        b.send_json({"type": "open", "path": "tn-2.uc"})
        g, _ = _geometry(b)
        # a fresh document from the file, offering the (flushed) autosave
        assert not g["dirty"] and not g["can_undo"] and g["recoverable"]
    assert client.app.hub.docs == {}


# ---------------------------------------------------------------- files, examples, uploads, new drawings


def test_list_files(client, workspace):
    (workspace / "sub").mkdir()
    shutil.copy(workspace / "tn-2.uc", workspace / "sub" / "b.uc")
    (workspace / "sub" / "c.json").write_text("{}")
    (workspace / "tn-2.network.json").write_text("{}")
    (workspace / "notes.txt").write_text("x")
    (workspace / ".auszug" / "autosave").mkdir(parents=True)
    (workspace / ".auszug" / "autosave" / "tn-2.uc.json").write_text("{}")
    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "list_files", "id": 3})
        files = _reply(ws, "files")
    assert files["id"] == 3
    assert files["workspace"] == ["sub/b.uc", "sub/c.json", "tn-11.uc", "tn-2.uc"]
    assert files["examples"] == examples.names() and "web/U.XI.28.uc" in files["examples"]


def test_list_files_skips_links_out_of_the_workspace(client, workspace, tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    shutil.copy(workspace / "tn-2.uc", outside / "x.uc")
    os.symlink(outside / "x.uc", workspace / "link.uc")
    os.symlink(outside, workspace / "linked")
    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "list_files"})
        assert _reply(ws, "files")["workspace"] == ["tn-11.uc", "tn-2.uc"]


def test_open_example(client):
    want = load(examples.path("web/U.XI.28.uc"))
    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "open_example", "name": "web/U.XI.28.uc", "id": 2})
        g, _ = _geometry(ws)
        assert (g["id"], g["path"], g["name"], g["n_curves"], g["dirty"]) == (2, "", want.name, len(want.curves),
                                                                              False)
        ws.send_json({"type": "open_example", "name": "../../../etc/passwd", "id": 3})
        err = _reply(ws, "error")
        assert err["id"] == 3 and "no bundled example '../../../etc/passwd'" in err["message"]


def test_examples_are_private_per_tab(client):
    with client.websocket_connect(WS) as a, client.websocket_connect(WS) as b:
        for ws in (a, b):
            ws.send_json({"type": "open_example", "name": "teaching-sheet/tn-2.uc"})
            _geometry(ws)
        a.send_json({"type": "set_apex_height", "curve": 0, "height": 2.5, "id": 1})
        _geometry(a)
        b.send_json({"type": "undo", "id": 2})
        assert "nothing to undo" in _reply(b, "error")["message"]


def test_open_text(client, workspace):
    text = (workspace / "tn-2.uc").read_text()
    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "open_text", "name": "C:\\Users\\me\\mine.uc", "text": text, "id": 1})
        g, data = _geometry(ws)
        assert (g["path"], g["name"], g["n_curves"]) == ("", "mine", 1)
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        _, data_file = _geometry(ws)
        assert data == data_file
        ws.send_json({"type": "open_text", "name": "mine.json", "text": "{\"format\": 3", "id": 2})
        err = _reply(ws, "error")
        assert err["id"] == 2 and err["message"].startswith("mine.json:1: not valid JSON")
        ws.send_json({"type": "open_text", "name": "broken.uc", "text": "numCurves x\n"})
        assert _reply(ws, "error")["message"].startswith("broken.uc:1: ")
        ws.send_json({"type": "open_text", "name": "notes.txt", "text": "hello"})
        assert _reply(ws, "error")["message"] == "notes.txt: not a drawing file; expected a .uc or .json drawing"
    assert sorted(p.name for p in workspace.iterdir()) == ["tn-11.uc", "tn-2.uc"]   # no temporary files


def test_open_text_larger_than_the_limit_is_refused(client):
    with client.websocket_connect(WS) as ws:
        ws.send_text(json.dumps({"type": "open_text", "name": "big.uc", "text": "x" * P.MAX_MESSAGE_BYTES}))
        err = _reply(ws, "error")
        assert "larger than the limit of 262144 bytes" in err["message"]
        ws.send_text(json.dumps({"type": "open_text", "name": "big.uc", "text": "\u00e9" * (P.MAX_MESSAGE_BYTES // 2)}))
        assert "larger than the limit" in _reply(ws, "error")["message"]    # counted in UTF-8 bytes
        ws.send_json({"type": "open", "path": "tn-2.uc", "id": 5})
        assert _geometry(ws)[0]["id"] == 5                                    # the server lives


def test_new_drawing_draw_and_save(client, workspace):
    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "new_drawing", "name": "sketch", "id": 1})
        g, data = _geometry(ws)
        assert (g["n_curves"], g["pieces"], g["path"], g["name"], data) == (0, [], "", "sketch", b"")
        ws.send_json({"type": "draw_curve", "vertices": [[1, 0], [0.2, 0.8]], "handles": [[]],
                      "marks": ["ground", "apex"], "fold": 4, "mirror": "first point", "id": 2})
        g, _ = _geometry(ws)
        assert g["n_curves"] == 1 and g["dirty"]
        ws.send_json({"type": "save", "id": 3})
        assert _reply(ws, "saved") == {"type": "saved", "path": "sketch.json", "id": 3}
        g, _ = _geometry(ws)
        assert (g["path"], g["dirty"], g["id"]) == ("sketch.json", False, 0)
        for bad in ("a/b", "", "..", " x"):
            ws.send_json({"type": "new_drawing", "name": bad, "id": 9})
            assert "not" in _reply(ws, "error")["message"]
    d = load(workspace / "sketch.json")
    assert len(d.curves) == 1 and d.curves[0].symmetry.fold == 4


def test_saving_an_example_makes_it_the_files_document(client, workspace):
    with client.websocket_connect(WS) as a, client.websocket_connect(WS) as b:
        a.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(a)
        b.send_json({"type": "open_example", "name": "web/U.XI.28.uc"})
        _, data_example = _geometry(b)
        b.send_json({"type": "save", "path": "tn-2.uc", "id": 4})
        assert _reply(b, "saved")["path"] == "tn-2.uc"
        g_b, data_b = _geometry(b)
        g_a, data_a = _geometry(a)   # the other tab had tn-2.uc open: it now shows what was saved there
        assert data_a == data_b == data_example and g_a["path"] == "tn-2.uc" and not g_a["dirty"]
        a.send_json({"type": "set_apex_height", "curve": 0, "height": 9.0, "id": 5})
        _geometry(a)
        assert _geometry(b)[0]["curves"][0]["apex"] == 9.0          # one document now
    assert _same(load(workspace / "tn-2.uc"), _round_trip(load(examples.path("web/U.XI.28.uc")), "x.uc"))


@pytest.mark.parametrize("path,problem", [
    ("x.txt", "'x.txt': can only save drawings as .uc or .json"),
    ("x.network.json", "can only save drawings as .uc or .json"),
    (".auszug/autosave/x.json", "the .auszug folder is reserved for autosaves"),
])
def test_save_refuses(client, workspace, path, problem):
    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(ws)
        ws.send_json({"type": "save", "path": path, "id": 2})
        err = _reply(ws, "error")
        assert err["id"] == 2 and problem in err["message"]
    assert not (workspace / path).exists()


def test_save_over_a_folder_or_fifo_refused(client, workspace):
    (workspace / "dir.json").mkdir()
    os.mkfifo(workspace / "pipe.json")
    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(ws)
        ws.send_json({"type": "save", "path": "dir.json"})
        assert "'dir.json': cannot save over it, it is a folder" in _reply(ws, "error")["message"]
        ws.send_json({"type": "save", "path": "pipe.json"})
        assert "'pipe.json': cannot save over it, it is not a regular file" in _reply(ws, "error")["message"]
    assert (workspace / "dir.json").is_dir()


def test_save_formats_round_trip(client, workspace):
    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(ws)
        ws.send_json({"type": "set_apex_height", "curve": 0, "height": 2.5})
        _geometry(ws)
        for path in ("out/copy.json", "copy.uc"):
            ws.send_json({"type": "save", "path": path})
            assert _reply(ws, "saved")["path"] == path
            g, _ = _geometry(ws)
            assert g["path"] == path and not g["dirty"]
    want = edit.set_apex_height(load(workspace / "tn-2.uc"), 0, 2.5)
    assert _same(load(workspace / "out" / "copy.json"), want)
    assert _same(load(workspace / "copy.uc"), _round_trip(want, "copy.uc"))
    # formats.save wrote exactly the writer's bytes
    assert (workspace / "copy.uc").read_text() == format_for("copy.uc", "drawing").writer(load(workspace / "copy.uc"),
                                                                                          "copy.uc")


# ---------------------------------------------------------------- symlinks


def test_symlinks_out_of_the_workspace_refused(client, workspace, tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    shutil.copy(workspace / "tn-2.uc", outside / "secret.uc")
    os.symlink(outside / "secret.uc", workspace / "link.uc")
    os.symlink(outside, workspace / "linked")
    os.symlink(outside / "new.json", workspace / "dangling.json")
    os.symlink(workspace / "tn-11.uc", workspace / "inside.uc")
    with client.websocket_connect(WS) as ws:
        for path in ("link.uc", "linked/secret.uc"):
            ws.send_json({"type": "open", "path": path})
            assert _reply(ws, "error")["message"] == f"'{path}' is outside the workspace"
        ws.send_json({"type": "open", "path": "inside.uc", "id": 2})   # a link within the workspace is fine
        assert _geometry(ws)[0]["path"] == "tn-11.uc"
        for path in ("link.uc", "linked/new.json", "dangling.json"):
            ws.send_json({"type": "save", "path": path})
            assert "is outside the workspace" in _reply(ws, "error")["message"]
    assert sorted(p.name for p in outside.iterdir()) == ["secret.uc"]
    assert (outside / "secret.uc").read_bytes() == (workspace / "tn-2.uc").read_bytes()


# ---------------------------------------------------------------- autosave and recovery


def test_autosave_is_written_while_editing(workspace):
    with _app(workspace, autosave_delay=0) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(ws)
        ws.send_json({"type": "set_apex_height", "curve": 0, "height": 2.5})
        _geometry(ws)
        auto = workspace / ".auszug" / "autosave" / "tn-2.uc.json"
        _wait_for(auto)      # during the session, not only at shutdown: a crash keeps it
        want = edit.set_apex_height(load(workspace / "tn-2.uc"), 0, 2.5)
        t0 = time.monotonic()
        while not _same(load(auto), want):
            assert time.monotonic() - t0 < 10
            time.sleep(0.01)


def test_crash_recovery_after_restart(workspace):
    original = (workspace / "tn-2.uc").read_bytes()
    with _app(workspace) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        g0, _ = _geometry(ws)
        assert g0["recoverable"] == ""
        ws.send_json({"type": "set_apex_height", "curve": 0, "height": 2.5})
        ws.send_json({"type": "move_vertex", "curve": 0, "vertex": 1, "xy": [0.1, 0.9]})
        _geometry(ws)
        _, edited = _geometry(ws)
    # the server is gone (a new app on the same workspace is a restart); the file is untouched
    assert (workspace / "tn-2.uc").read_bytes() == original
    want = edit.move_vertex(edit.set_apex_height(load(workspace / "tn-2.uc"), 0, 2.5), 0, 1, (0.1, 0.9))
    with _app(workspace) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        g, data = _geometry(ws)
        assert g["recoverable"] and g["recoverable"][:4].isdigit() and "T" in g["recoverable"]
        assert not g["dirty"] and data != edited
        ws.send_json({"type": "recover", "id": 8})
        g, data = _geometry(ws)
        assert (g["id"], g["dirty"], g["can_undo"], g["recoverable"]) == (8, True, True, "")
        assert data == edited                                  # the edited geometry, exactly
        assert _same(c.app.hub.get("tn-2.uc").drawing, want)   # and the edited drawing
        ws.send_json({"type": "undo"})
        _, data = _geometry(ws)                                # recovery is an undoable edit
        assert data != edited


def test_saved_work_survives_restart_byte_for_byte(workspace):
    with _app(workspace, autosave_delay=0) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(ws)
        ws.send_json({"type": "set_apex_height", "curve": 0, "height": 2.5})
        _, edited = _geometry(ws)
        _wait_for(workspace / ".auszug" / "autosave" / "tn-2.uc.json")
        ws.send_json({"type": "save", "id": 2})
        assert _reply(ws, "saved")["path"] == "tn-2.uc"
        g, _ = _geometry(ws)
        assert not g["dirty"]
        saved = (workspace / "tn-2.uc").read_bytes()
    assert not (workspace / ".auszug" / "autosave" / "tn-2.uc.json").exists()   # saving deletes the autosave
    with _app(workspace) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        g, data = _geometry(ws)
        assert g["recoverable"] == "" and not g["dirty"] and data == edited
    assert (workspace / "tn-2.uc").read_bytes() == saved


def test_recover_without_autosave_is_an_error(client):
    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(ws)
        ws.send_json({"type": "recover", "id": 3})
        err = _reply(ws, "error")
        assert err == {"type": "error", "id": 3, "message": "tn-2.uc: no autosave to recover"}


def test_unsaved_documents_autosave_per_document(workspace):
    """Two tabs on one example (same name) are two documents with two autosaves; after a restart
    each tab resumes its own drawing by its document id."""
    auto = workspace / ".auszug" / "autosave" / "unsaved"
    with _app(workspace, autosave_delay=0) as c, c.websocket_connect(WS) as a, c.websocket_connect(WS) as b:
        ids = []
        for ws, h in ((a, 2.5), (b, 3.5)):
            ws.send_json({"type": "open_example", "name": "teaching-sheet/tn-2.uc"})
            ids.append(_geometry(ws)[0]["doc"])
            ws.send_json({"type": "set_apex_height", "curve": 0, "height": h})
            _geometry(ws)
        assert ids[0] != ids[1]
        for i in ids:
            _wait_for(auto / i / "tn-2.uc.json")
    for i, h in zip(ids, (2.5, 3.5), strict=True):
        assert load(auto / i / "tn-2.uc.json").curves[0].height == h
    with _app(workspace) as c, c.websocket_connect(WS) as ws:
        for i, h in zip(ids, (2.5, 3.5), strict=True):
            ws.send_json({"type": "resume", "doc": i, "id": 4})
            g, _ = _geometry(ws)
            assert (g["id"], g["doc"], g["path"], g["dirty"], g["curves"][0]["apex"]) == (4, i, "", True, h)
        ws.send_json({"type": "resume", "doc": "0123456789abcdef", "id": 5})
        assert "gone" in _reply(ws, "error")["message"]
        ws.send_json({"type": "resume", "doc": "../../etc", "id": 6})
        assert "not a document id" in _reply(ws, "error")["message"]


def test_offered_autosave_is_never_overwritten(workspace):
    """A restart offers the autosave; edits made before restoring it do not overwrite it."""
    with _app(workspace, autosave_delay=0) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(ws)
        ws.send_json({"type": "set_apex_height", "curve": 0, "height": 2.5})
        _geometry(ws)
    with _app(workspace, autosave_delay=0) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        g, _ = _geometry(ws)
        assert g["recoverable"]
        for h in (3.0, 3.25):
            ws.send_json({"type": "set_apex_height", "curve": 0, "height": h})
            g, _ = _geometry(ws)
            assert g["recoverable"]            # still offered after edits
        _wait_for(workspace / ".auszug" / "autosave" / "tn-2.uc.json")
        time.sleep(0.2)
        assert load(workspace / ".auszug" / "autosave" / "tn-2.uc.json").curves[0].height == 3.25
        ws.send_json({"type": "recover", "id": 8})
        g, _ = _geometry(ws)
        assert g["id"] == 8 and g["curves"][0]["apex"] == 2.5 and not g["recoverable"]
        ws.send_json({"type": "undo", "id": 9})
        assert _geometry(ws)[0]["curves"][0]["apex"] == 3.25   # the recovery is one undoable edit


def _offers(workspace: Path) -> list[str]:
    """The set-aside autosaves of tn-2.uc, oldest first (their names end in the time written, ns)."""
    auto = workspace / ".auszug" / "autosave"
    return sorted((p.name for p in auto.glob("tn-2.uc.json.offered-*.json")),
                  key=lambda n: int(n.rsplit("-", 1)[1].removesuffix(".json")))


def _edit_and_leave(workspace: Path, height: float) -> None:
    """Open tn-2.uc (setting any differing autosave aside), edit it, leave (the autosave is written)."""
    with _app(workspace, autosave_delay=0) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(ws)
        ws.send_json({"type": "set_apex_height", "curve": 0, "height": height})
        _geometry(ws)


def test_set_aside_autosaves_are_kept_three_per_file_and_thirty_days():
    """prune_offers: the newest LIMITS.autosave_offers per autosave, none older than
    LIMITS.autosave_offer_days, the one on offer always; links and other files untouched."""
    import tempfile

    from auszug.limits import LIMITS
    from auszug.studio.session import Workspace, prune_offers

    assert (LIMITS.autosave_offers, LIMITS.autosave_offer_days) == (3, 30.0)
    day = 86400 * 10**9
    now = 1000 * day
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp)
        auto = root / ".auszug" / "autosave"
        (auto / "sub").mkdir(parents=True)
        names = [f"a.uc.json.offered-{now - k * day}.json" for k in (1, 2, 3, 4, 5)]
        names += [f"b.uc.json.offered-{now - 31 * day}.json", f"b.uc.json.offered-{now - 29 * day}.json"]
        for n in names:
            (auto / n).write_text("{}")
        (auto / "sub" / f"c.json.json.offered-{now - 40 * day}.json").write_text("{}")
        (auto / "a.uc.json").write_text("{}")                  # the live autosave: not an offer
        (auto / "note.offered-12.txt").write_text("x")          # not an offer's name
        target = root / "elsewhere.json"
        target.write_text("{}")
        (auto / f"z.uc.json.offered-{now - 99 * day}.json").symlink_to(target)   # a link: left alone
        gone = prune_offers(Workspace(root), now_ns=now)
        assert sorted(p.name for p in gone) == sorted([names[3], names[4], names[5],
                                                       f"c.json.json.offered-{now - 40 * day}.json"])
        left = sorted(p.name for p in auto.iterdir() if p.is_file() or p.is_symlink())
        assert left == sorted([*names[:3], names[6], "a.uc.json", "note.offered-12.txt",
                               f"z.uc.json.offered-{now - 99 * day}.json"])
        assert target.read_text() == "{}"
        # only one autosave's offers, and the one on offer kept however old
        old = auto / f"b.uc.json.offered-{now - 50 * day}.json"
        old.write_text("{}")
        assert prune_offers(Workspace(root), auto / "b.uc.json", keep=old, now_ns=now) == []
        assert prune_offers(Workspace(root), auto / "b.uc.json", now_ns=now) == [old]


def test_set_aside_autosaves_do_not_pile_up(workspace):
    """Each restart with unrestored work sets one autosave aside; at most three stay, newest first,
    and the studio's start removes those past thirty days."""
    for k in range(5):
        _edit_and_leave(workspace, 2.0 + 0.25 * k)
        time.sleep(0.01)   # distinct modification times
    with _app(workspace) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        assert _geometry(ws)[0]["recoverable"]
    offers = _offers(workspace)
    assert len(offers) == 3
    # the newest is on offer: the last edit's drawing
    auto = workspace / ".auszug" / "autosave"
    assert load(auto / offers[-1]).curves[0].height == 3.0
    stale = auto / f"tn-2.uc.json.offered-{time.time_ns() - 31 * 86400 * 10**9}.json"
    shutil.copy(auto / offers[0], stale)
    create_app(workspace)
    assert _offers(workspace) == offers


def test_restored_autosave_is_deleted_once_autosaved(workspace):
    """Restoring the offer makes it the drawing; when that drawing is autosaved (or saved), the
    set-aside copy goes; undoing the restoration before that keeps it."""
    _edit_and_leave(workspace, 2.5)
    with _app(workspace, autosave_delay=0) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        assert _geometry(ws)[0]["recoverable"]
        [offer] = _offers(workspace)
        ws.send_json({"type": "recover"})
        assert _geometry(ws)[0]["curves"][0]["apex"] == 2.5
        t0 = time.monotonic()
        while _offers(workspace) and time.monotonic() - t0 < 10:
            time.sleep(0.01)
        assert _offers(workspace) == []
        assert load(workspace / ".auszug" / "autosave" / "tn-2.uc.json").curves[0].height == 2.5
    # saving the restored drawing (no autosave in between) deletes the offer too
    with _app(workspace, autosave_delay=30) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        assert _geometry(ws)[0]["recoverable"]
        assert len(_offers(workspace)) == 1
        ws.send_json({"type": "recover"})
        _geometry(ws)
        assert len(_offers(workspace)) == 1
        ws.send_json({"type": "save", "id": 4})
        _reply(ws, "saved")
        assert _offers(workspace) == []
        assert load(workspace / "tn-2.uc").curves[0].height == 2.5


def test_reconnecting_tab_gets_back_its_own_state(workspace):
    """After a crash (here: a restart after the autosave), the tab that wrote the autosave resumes
    with it applied; any other tab that opens the file gets the offer instead."""
    with _app(workspace, autosave_delay=0) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        doc = _geometry(ws)[0]["doc"]
        ws.send_json({"type": "set_apex_height", "curve": 0, "height": 2.5})
        _geometry(ws)
    with _app(workspace) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "resume", "doc": doc, "path": "tn-2.uc", "id": 3})
        g, _ = _geometry(ws)
        assert (g["doc"], g["path"], g["dirty"], g["can_undo"], g["recoverable"]) == (doc, "tn-2.uc", True, True, "")
        assert g["curves"][0]["apex"] == 2.5
        with c.websocket_connect(WS) as other:   # a reload of the same tab while the document is open
            other.send_json({"type": "resume", "doc": doc, "path": "tn-2.uc"})
            assert _geometry(other)[0]["revision"] == g["revision"]
        ws.send_json({"type": "undo"})
        assert _geometry(ws)[0]["curves"][0]["apex"] == load(workspace / "tn-2.uc").curves[0].height
        ws.send_json({"type": "redo"})
        _geometry(ws)
    with _app(workspace) as c, c.websocket_connect(WS) as ws:   # a stranger: offered, not applied
        ws.send_json({"type": "resume", "doc": "0123456789abcdef", "path": "tn-2.uc"})
        g, _ = _geometry(ws)
        assert g["recoverable"] and g["curves"][0]["apex"] == load(workspace / "tn-2.uc").curves[0].height


def test_save_as_in_one_tab_does_not_move_the_others(workspace):
    with _app(workspace) as c, c.websocket_connect(WS) as a, c.websocket_connect(WS) as b:
        a.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(a)
        b.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(b)
        a.send_json({"type": "set_apex_height", "curve": 0, "height": 2.5})
        _geometry(a)
        _geometry(b)
        a.send_json({"type": "save", "path": "copy.json", "id": 5})
        assert _reply(a, "saved")["path"] == "copy.json"
        ga, _ = _geometry(a)
        assert ga["path"] == "copy.json" and not ga["dirty"]
        a.send_json({"type": "set_apex_height", "curve": 0, "height": 3.0})
        assert _geometry(a)[0]["curves"][0]["apex"] == 3.0
        b.send_json({"type": "set_apex_height", "curve": 0, "height": 2.75, "id": 6})
        gb, _ = _geometry(b)      # b heard nothing of a's save or of a's edit after it
        assert (gb["id"], gb["path"], gb["dirty"], gb["doc"]) == (6, "tn-2.uc", True, gb["doc"])
        assert gb["doc"] != ga["doc"]
        b.send_json({"type": "undo"})
        b.send_json({"type": "undo"})
        _geometry(b)
        gb, _ = _geometry(b)     # the history before the fork is b's too
        assert gb["curves"][0]["apex"] == load(workspace / "tn-2.uc").curves[0].height and not gb["dirty"]
    assert load(workspace / "copy.json").curves[0].height == 2.5


def test_undo_back_to_the_file_removes_the_autosave(workspace):
    auto = workspace / ".auszug" / "autosave" / "tn-2.uc.json"
    with _app(workspace, autosave_delay=0) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(ws)
        ws.send_json({"type": "set_apex_height", "curve": 0, "height": 2.5})
        _geometry(ws)
        _wait_for(auto)
        ws.send_json({"type": "undo"})
        assert not _geometry(ws)[0]["dirty"]
    assert not auto.exists()


def test_autosaves_are_coalesced(workspace, monkeypatch):
    from auszug.studio.session import Document

    writes = []
    real = Document.write_autosave

    def counted(self):
        writes.append(self.changes)
        return real(self)

    monkeypatch.setattr(Document, "write_autosave", counted)
    with _app(workspace, autosave_delay=0.3) as c, c.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(ws)
        for k in range(20):
            ws.send_json({"type": "set_apex_height", "curve": 0, "height": 2.0 + 0.01 * k})
            _geometry(ws)
    assert 1 <= len(writes) <= 3 and writes[-1] == 20      # 20 edits, one or two writes and the flush
    assert load(workspace / ".auszug" / "autosave" / "tn-2.uc.json").curves[0].height == pytest.approx(2.19)


def test_geometry_payload_is_float32_of_the_shapes(client):
    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "open", "path": "tn-11.uc"})
        g, data = _geometry(ws)
    f = np.frombuffer(data, "<f4")
    for p in g["pieces"]:
        for ref in (p["points"], p["side"], p["transforms"]):
            assert ref["dtype"] == "f4" and ref["offset"] + int(np.prod(ref["shape"])) <= f.size


# ---------------------------------------------------------------- outboxes


def test_outbox_sends_in_order_and_replaces_pending_broadcasts():
    import asyncio

    from auszug.studio.hub import Outbox

    async def run() -> list:
        box = Outbox()
        sent: list = []

        async def send(text, payload):
            sent.append((text, payload))
            await asyncio.sleep(0)

        box.put("reply 1", b"a")
        box.put("broadcast r1", b"b", coalesce=("geometry", 1))
        box.put("files")
        box.put("broadcast r2", b"c", coalesce=("geometry", 1))   # replaces r1, which was not sent
        box.put("broadcast other doc", b"d", coalesce=("geometry", 2))
        task = asyncio.create_task(box.run(send))
        await asyncio.sleep(0.01)
        box.put("later", None)
        box.close()
        await asyncio.wait_for(task, 1)
        box.put("after close")
        return sent

    assert asyncio.run(run()) == [("reply 1", b"a"), ("files", None), ("broadcast r2", b"c"),
                                  ("broadcast other doc", b"d"), ("later", None)]


def test_outbox_stops_when_the_peer_is_gone():
    import asyncio

    from auszug.studio.hub import Outbox

    async def run() -> int:
        box = Outbox()
        calls = []

        async def send(text, payload):
            calls.append(text)
            raise RuntimeError("socket closed")

        box.put("a")
        box.put("b")
        await asyncio.wait_for(box.run(send), 1)
        return len(calls), box.pending()

    assert asyncio.run(run()) == (1, 0)


def test_two_tabs_dragging_at_once_undo_whole_drags(workspace):
    """Two tabs drag on one document, their edits interleaved: an undo in either tab takes back
    whole drags, never a single edit of the other's drag."""
    with _app(workspace) as c, c.websocket_connect(WS) as a, c.websocket_connect(WS) as b:
        a.send_json({"type": "open", "path": "tn-2.uc"})
        g0, data0 = _geometry(a)
        b.send_json({"type": "open", "path": "tn-2.uc"})
        _geometry(b)
        x, y = g0["curves"][0]["vertices"][1]
        for k in range(1, 5):
            a.send_json({"type": "move_vertex", "curve": 0, "vertex": 1, "xy": [x + 0.01 * k, y], "drag": 101})
            _geometry(a)
            _geometry(b)
            b.send_json({"type": "set_apex_height", "curve": 0, "height": 2.0 + 0.05 * k, "drag": 202})
            _geometry(b)
            _geometry(a)
        b.send_json({"type": "undo", "id": 9})
        g, data = _geometry(b)
        assert g["id"] == 9 and not g["can_undo"] and np.array_equal(np.frombuffer(data, "<f4"),
                                                                     np.frombuffer(data0, "<f4"))
