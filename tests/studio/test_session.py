"""Sessions: geometry equals the network's curves; undo/redo restore drawings exactly."""

from __future__ import annotations

import json

import numpy as np
import pytest

from auszug.errors import AuszugError
from auszug.formats import load
from auszug.microarch import build
from auszug.studio import protocol as P
from auszug.studio.session import Session, Workspace, WorkspaceError, geometry, geometry_frames


def _replicas(msg: P.Geometry, payload: bytes) -> list[np.ndarray]:
    """All replica point arrays of a geometry message, in network-curve order."""
    data = np.frombuffer(payload, dtype="<f4")
    assert data.size == msg.binary_floats
    out = []
    for p in msg.pieces:
        n = p.points.shape[0]
        pts = data[p.points.offset : p.points.offset + n * 3].reshape(n, 3).astype(float)
        k = p.transforms.shape[0]
        tr = data[p.transforms.offset : p.transforms.offset + k * 16].reshape(k, 4, 4).transpose(0, 2, 1)
        homo = np.concatenate([pts, np.ones((n, 1))], axis=1)
        out += [(homo @ t.T)[:, :3] for t in tr.astype(float)]
    return out


@pytest.mark.parametrize("name", ["tn-2.uc", "tn-11.uc"])
def test_geometry_reproduces_network(workspace, name):
    """Instancing the basic pieces with the sent transforms gives every network curve (float32)."""
    d = load(workspace / name)
    msg, payload = geometry(d)
    curves = sorted(build(d).curves(), key=lambda c: c.piece)
    reps = _replicas(msg, payload)
    assert msg.n_replicas == len(curves) == len(reps)
    for c, r in zip(curves, reps, strict=True):
        np.testing.assert_allclose(r, c.points, atol=1e-4 * max(1.0, float(np.abs(c.points).max())))


def test_edit_undo_redo(workspace):
    s = Session(Workspace(workspace))
    s.open("tn-2.uc")
    d0 = s.drawing
    s.apply(P.SetApexHeight(curve=0, height=2.5))
    d1 = s.drawing
    assert d1.curves[0].height == 2.5 and d0.curves[0].height != 2.5
    s.undo()
    assert s.drawing == d0
    s.redo()
    assert s.drawing == d1
    with pytest.raises(AuszugError, match="nothing to redo"):
        s.redo()


def test_failed_edit_changes_nothing(workspace):
    s = Session(Workspace(workspace))
    s.open("tn-2.uc")
    d0, rev = s.drawing, s.revision
    with pytest.raises(AuszugError):
        s.apply(P.SetApexHeight(curve=99, height=1.0))
    assert s.drawing is d0 and s.revision == rev and not s.undo_stack


@pytest.mark.parametrize("rel", ["../outside.uc", "/etc/passwd", "sub/../../x.uc", ""])
def test_workspace_confines(workspace, rel):
    with pytest.raises(WorkspaceError):
        Workspace(workspace).resolve(rel)


def test_save_round_trip(workspace):
    s = Session(Workspace(workspace))
    s.open("tn-2.uc")
    s.apply(P.SetApexHeight(curve=0, height=2.5))
    assert s.save("edited.json") == "edited.json"
    assert load(workspace / "edited.json") == s.drawing


# ---------------------------------------------------------------- the fast geometry path


FAST_CASES = ["web/U.XI.28.uc", "web/3d-scan-final.uc", "legacy/U.XI.22.uc", "teaching-sheet/tn-9.uc",
              "teaching-sheet/tn-12.uc", "web/two_curves.uc"]


@pytest.mark.parametrize("name", FAST_CASES)
def test_fast_geometry_text_equals_dataclass_encoding(name):
    """geometry_frames' hand-written JSON is exactly json.dumps(dataclasses.asdict(msg)), for any id."""
    import dataclasses
    import json

    from auszug import examples
    from auszug.studio.session import geometry_frames

    d = load(examples.path(name))
    kw = dict(path="sub/x.uc", revision=17, can_undo=True, can_redo=False, dirty=True,
              recoverable="2026-01-02T03:04:05+00:00", doc="0123456789abcdef")
    text, payload = geometry_frames(d, **kw)
    for msg_id in (0, 5, 123456):
        msg, payload2 = geometry(d, msg_id=msg_id, **kw)
        assert payload == payload2
        assert text.text(msg_id) == P.encode(msg)
        assert text.text(msg_id) == json.dumps(dataclasses.asdict(msg), separators=(",", ":"), allow_nan=False)
    assert json.loads(text.text(1))["pieces"][0]["points"]["dtype"] == "f4"


def test_empty_drawing_geometry():
    from auszug.microarch.model import Drawing

    msg, payload = geometry(Drawing((), name="blank"))
    assert (msg.n_curves, msg.pieces, msg.bounds, payload, msg.binary_floats) == (0, [], [0.0] * 6, b"", 0)


def test_bounds_equal_the_networks():
    from auszug import examples

    for name in FAST_CASES:
        d = load(examples.path(name))
        want = build(d).bounds().ravel()
        sent = json.loads(geometry_frames(d)[0].text())["bounds"]
        np.testing.assert_allclose(sent, want, rtol=0, atol=1e-14 * np.abs(want).max())   # to rounding
        np.testing.assert_allclose(geometry(d)[0].bounds, want, rtol=0, atol=1e-14 * np.abs(want).max())


def test_network_of_reuses_one_build_per_drawing(workspace):
    from auszug.studio.session import network_of

    d = load(workspace / "tn-2.uc")
    assert network_of(d) is network_of(d)
    assert network_of(d) is not network_of(load(workspace / "tn-2.uc"))   # keyed by the object, not its value


def test_undo_redo_reuse_networks(workspace, monkeypatch):
    import auszug.studio.session as S

    s = Session(Workspace(workspace))
    s.open("tn-2.uc")
    s.apply(P.SetApexHeight(curve=0, height=2.5))
    built = []
    monkeypatch.setattr(S, "build", lambda d: built.append(d) or build(d))
    s.undo()
    s.redo()
    assert built == []   # the networks of both drawings were kept


def test_revisions_increase_across_documents(workspace):
    from auszug.studio.session import new_document, open_document

    ws = Workspace(workspace)
    a = open_document(ws, "tn-2.uc")
    b = new_document(ws, "x")
    r = b.revision
    a.apply(P.SetApexHeight(curve=0, height=2.5))
    assert b.revision < a.revision and r > 0


def test_dirty_follows_the_file_state(workspace):
    from auszug.studio.session import open_document

    doc = open_document(Workspace(workspace), "tn-2.uc")
    assert not doc.dirty
    doc.apply(P.SetApexHeight(curve=0, height=2.5))
    assert doc.dirty
    doc.undo()
    assert not doc.dirty
    doc.redo()
    doc.save()
    assert not doc.dirty and load(workspace / "tn-2.uc").curves[0].height == 2.5


# ---------------------------------------------------------------- workspace


def test_workspace_refuses_symlink_escapes(workspace, tmp_path):
    import os

    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "x.uc").write_text("secret")
    os.symlink(outside / "x.uc", workspace / "link.uc")
    os.symlink(outside, workspace / "dir")
    os.symlink(workspace / "tn-2.uc", workspace / "ok.uc")
    ws = Workspace(workspace)
    for rel in ("link.uc", "dir/x.uc", "dir/new.json", "dir/../../outside/x.uc"):
        with pytest.raises(WorkspaceError, match="is outside the workspace"):
            ws.resolve(rel)
        with pytest.raises(WorkspaceError, match="is outside the workspace"):
            ws.resolve_for_writing(rel)
    assert ws.resolve("ok.uc") == (workspace / "tn-2.uc").resolve()


def test_workspace_symlink_loop(workspace):
    import os

    os.symlink(workspace / "a.uc", workspace / "b.uc")
    os.symlink(workspace / "b.uc", workspace / "a.uc")
    with pytest.raises(WorkspaceError):
        Workspace(workspace).resolve("a.uc")


def test_workspace_writing_needs_a_regular_file(workspace):
    import os

    (workspace / "d.json").mkdir()
    os.mkfifo(workspace / "p.json")
    ws = Workspace(workspace)
    with pytest.raises(WorkspaceError, match="it is a folder"):
        ws.resolve_for_writing("d.json")
    with pytest.raises(WorkspaceError, match="not a regular file"):
        ws.resolve_for_writing("p.json")
    with pytest.raises(WorkspaceError, match="the workspace folder itself"):
        ws.resolve_for_writing(".")
    assert ws.resolve_for_writing("new/fresh.json") == workspace.resolve() / "new" / "fresh.json"


def test_open_errors_name_the_file(workspace):
    from auszug.errors import FormatError
    from auszug.studio.session import open_document

    (workspace / "bad.uc").write_text("numCurves 1\nunitCurve zero\n")
    (workspace / "bin.uc").write_bytes(b"\xff\xfe\x00")
    ws = Workspace(workspace)
    with pytest.raises(FormatError, match=r"^bad\.uc:2: "):
        open_document(ws, "bad.uc")
    with pytest.raises(FormatError, match=r"^bin\.uc: not a text file"):
        open_document(ws, "bin.uc")
    with pytest.raises(WorkspaceError, match="no such file in the workspace: 'nope.uc'"):
        open_document(ws, "nope.uc")


def test_messages_do_not_share_the_caches(workspace):
    d = load(workspace / "tn-2.uc")
    msg, _ = geometry(d)
    msg.pieces[0].labels.append("junk")
    msg.curves[0].marks.append("junk")
    again, _ = geometry(d)
    assert "junk" not in again.pieces[0].labels and "junk" not in again.curves[0].marks


def test_concurrent_edits_from_threads_are_all_kept(workspace):
    """Document is safe without the server's lock: edits from several threads all land, in some order."""
    import threading

    from auszug.studio.session import open_document

    doc = open_document(Workspace(workspace), "tn-2.uc")

    def nudge(t):
        for i in range(10):   # every edit sets a height of its own (setting the same one is a no-op)
            doc.apply(P.SetApexHeight(curve=0, height=1.0 + 0.01 * (10 * t + i)))

    threads = [threading.Thread(target=nudge, args=(t,)) for t in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(doc.undo_stack) == 40 and doc.changes == 40


def test_a_drag_is_one_undo_step(workspace):
    """Edits sharing a non-zero drag make one undo step; another drag, or drag 0, starts a new one."""
    s = Session(Workspace(workspace))
    s.open("tn-2.uc")
    d0 = s.drawing
    x, y = d0.curves[0].vertices[1]
    for k in range(1, 6):
        s.apply(P.MoveVertex(curve=0, vertex=1, xy=(x + 0.01 * k, y), drag=7))
    d1 = s.drawing
    assert d1.curves[0].vertices[1] == (x + 0.05, y) and len(s.undo_stack) == 1
    s.apply(P.SetApexHeight(curve=0, height=2.0, drag=8))
    s.apply(P.SetApexHeight(curve=0, height=2.2, drag=8))
    s.apply(P.MoveVertex(curve=0, vertex=1, xy=(x, y + 0.1)))       # drag 0: a step of its own
    s.apply(P.MoveVertex(curve=0, vertex=1, xy=(x, y + 0.2)))
    assert len(s.undo_stack) == 4
    s.undo()
    s.undo()
    assert s.drawing.curves[0].height == 2.2
    s.undo()
    assert s.drawing == d1
    s.undo()
    assert s.drawing == d0 and not s.undo_stack
    s.redo()
    assert s.drawing == d1
    # after an undo the same drag number does not merge into the undone step
    s.apply(P.MoveVertex(curve=0, vertex=1, xy=(x, y), drag=7))
    assert len(s.undo_stack) == 2 and not s.redo_stack


@pytest.mark.parametrize("name", ["teaching-sheet/tn-2.uc", "teaching-sheet/tn-11.uc", "web/U.XI.28.uc",
                                  "web/3d-scan-final.uc"])
def test_curves_carry_the_networks_replica_transforms_and_the_palette(name):
    """Each curve's replicas, labels and centre are the curve network's group; its colour the palette's."""
    from auszug import examples
    from auszug.formats.palette import colour

    d = load(examples.path(name))
    net = build(d)
    groups = net.to_curve_network().groups
    msg, payload = geometry(d, net=net)
    text, _ = geometry_frames(d, net=net)
    sent = json.loads(text.text())["curves"]
    assert len(msg.curves) == len(groups) == len(sent)
    for i, (c, g, s) in enumerate(zip(msg.curves, groups, sent, strict=True)):
        mats = np.asarray(c.replicas).reshape(-1, 2, 2)
        np.testing.assert_array_equal(mats, g.matrices())            # exactly: float64 through JSON
        np.testing.assert_array_equal(np.asarray(s["replicas"]).reshape(-1, 2, 2), g.matrices())
        assert c.labels == s["labels"] == g.labels() and c.labels[0] == "r0"
        assert tuple(c.center) == tuple(float(v) for v in g.center)
        assert c.color == s["color"] == colour(i)
    # the replicas map each piece's points as its 4x4 transforms do
    data = np.frombuffer(payload, dtype="<f4")
    for p in msg.pieces:
        c = msg.curves[p.basic]
        n, k = p.points.shape[0], p.transforms.shape[0]
        pts = data[p.points.offset:p.points.offset + 3 * n].reshape(n, 3).astype(float)
        tr = data[p.transforms.offset:p.transforms.offset + 16 * k].reshape(k, 4, 4).transpose(0, 2, 1)
        mats = np.asarray(c.replicas).reshape(-1, 2, 2)
        ctr = np.asarray(c.center)
        by_label = {lb: m for lb, m in zip(c.labels, mats, strict=True)}
        for lb, t in zip(p.labels, tr, strict=True):
            want = (pts[:, :2] - ctr) @ by_label[lb].T + ctr
            np.testing.assert_allclose(pts[:, :2] @ t[:2, :2].T + t[:2, 3], want, atol=1e-5)


def _state(doc) -> tuple:
    return (doc.drawing, doc.net, list(doc.undo_stack), list(doc.redo_stack), doc.revision, doc.changes,
            doc.frames()[1])


@pytest.mark.parametrize("op", ["apply", "undo", "redo"])
def test_a_change_whose_reply_fails_is_rolled_back(workspace, monkeypatch, op):
    """All or nothing: if the geometry of a change cannot be built, the change is undone too."""
    import auszug.studio.session as S

    doc = S.open_document(Workspace(workspace), "tn-2.uc")
    doc.change(doc.apply, P.SetApexHeight(curve=0, height=2.0))
    doc.change(doc.apply, P.SetApexHeight(curve=0, height=2.2))
    doc.change(doc.undo)
    before = _state(doc)
    real = S.geometry_frames

    def failing(**kw):
        raise RuntimeError("no reply")

    monkeypatch.setattr(S, "geometry_frames", failing)
    fn, args = {"apply": (doc.apply, (P.SetApexHeight(curve=0, height=2.5, drag=3),)),
                "undo": (doc.undo, ()), "redo": (doc.redo, ())}[op]
    with pytest.raises(RuntimeError, match="no reply"):
        doc.change(fn, *args)
    monkeypatch.setattr(S, "geometry_frames", real)
    after = _state(doc)
    assert after[:6] == before[:6] and after[0] is before[0] and after[6] == before[6]
    # the next drag edit starts a new undo step (the failed one left no drag behind)
    doc.change(doc.apply, P.SetApexHeight(curve=0, height=2.6, drag=3))
    assert len(doc.undo_stack) == len(before[2]) + 1


def test_a_cancelled_change_is_rolled_back(workspace):
    import threading

    import auszug.studio.session as S

    doc = S.open_document(Workspace(workspace), "tn-2.uc")
    before = _state(doc)
    cancel = threading.Event()
    cancel.set()
    with pytest.raises(S.EditCancelled):
        doc.change(doc.apply, P.SetSymmetry(curve=0, fold=12), cancel=cancel)
    assert _state(doc)[:6] == before[:6] and not doc.dirty


@pytest.mark.parametrize("ending", [".json", ".uc"])
def test_every_value_an_edit_accepts_saves_and_reopens(workspace, ending):
    """The studio's edits check the limits the readers check: a drawing at the limits reopens equal."""
    from auszug.limits import LIMITS

    s = Session(Workspace(workspace))
    s.open("tn-2.uc")
    c = LIMITS.coordinate
    s.apply(P.SetApexHeight(curve=0, height=c))
    s.apply(P.SetSymmetry(curve=0, fold=LIMITS.fold))
    s.apply(P.MoveVertex(curve=0, vertex=0, xy=(-c, c)))
    for bad in (1e300, 1e120, c * (1 + 1e-12), float("inf")):
        with pytest.raises(AuszugError, match="apex height"):
            s.apply(P.SetApexHeight(curve=0, height=bad))
    with pytest.raises(AuszugError, match="fold"):
        s.apply(P.SetSymmetry(curve=0, fold=LIMITS.fold + 1))
    s.save("limits" + ending)
    back = load(workspace / ("limits" + ending))
    assert back.curves[0].height == c and back.curves[0].symmetry.fold == LIMITS.fold
    assert tuple(back.curves[0].vertices[0]) == (-c, c)


def test_a_no_op_edit_leaves_no_undo_step(workspace):
    """Setting what is already set (a PRC click on the PRC, the same apex) changes nothing."""
    s = Session(Workspace(workspace))
    s.open("tn-2.uc")
    d0, rev = s.drawing, s.revision
    s.apply(P.SetApexHeight(curve=0, height=d0.curves[0].height))
    s.apply(P.SetPrc(curve=0, segment=0, fraction=d0.curves[0].prc[0]))
    assert s.drawing is d0 and s.revision == rev and not s.undo_stack and not s.document.dirty
    s.apply(P.SetApexHeight(curve=0, height=2.0))
    s.apply(P.SetApexHeight(curve=0, height=2.0))
    assert len(s.undo_stack) == 1 and s.drawing.curves[0].height == 2.0


def test_interleaved_drags_of_two_tabs_make_no_partial_undo_steps(workspace):
    """Two tabs drag at once (their edits interleave): no undo lands in the middle of either drag."""
    s = Session(Workspace(workspace))
    s.open("tn-2.uc")
    d0 = s.drawing
    x, y = d0.curves[0].vertices[1]
    for k in range(1, 5):
        s.apply(P.MoveVertex(curve=0, vertex=1, xy=(x + 0.01 * k, y), drag=11))   # tab A
        s.apply(P.SetApexHeight(curve=0, height=2.0 + 0.05 * k, drag=22))         # tab B
    assert len(s.undo_stack) == 1
    s.undo()
    assert s.drawing == d0
    s.redo()
    assert s.drawing.curves[0].vertices[1] == (x + 0.04, y) and s.drawing.curves[0].height == 2.2
    # drags one after the other stay one step each
    for k in range(1, 4):
        s.apply(P.MoveVertex(curve=0, vertex=1, xy=(x, y + 0.01 * k), drag=33))
    for k in range(1, 4):
        s.apply(P.SetApexHeight(curve=0, height=2.5 + 0.01 * k, drag=44))
    assert len(s.undo_stack) == 3
    s.undo()
    assert s.drawing.curves[0].height == 2.2 and s.drawing.curves[0].vertices[1] == (x, y + 0.03)


def test_listing_notes_a_folder_it_cannot_read(workspace, monkeypatch):
    """A folder that cannot be listed (permissions; the tests run as root, so the refusal is staged)
    is skipped with a note; the rest is listed."""
    import os

    (workspace / "locked").mkdir()
    (workspace / "locked" / "x.uc").write_text((workspace / "tn-2.uc").read_text())
    real = os.scandir

    def scandir(path="."):
        if os.fspath(path).endswith("locked"):
            raise PermissionError(13, "Permission denied", os.fspath(path))
        return real(path)

    monkeypatch.setattr(os, "scandir", scandir)
    files, notes = Workspace(workspace).listing()
    assert files == ["tn-11.uc", "tn-2.uc"]
    assert notes == ["locked: skipped, cannot read it (Permission denied)"]


def test_structural_edits_keep_the_other_curves_apexes(workspace):
    """Issue 13: drawing the first curve of layer 1 raised a layer-0 curve whose apex follows the next
    layer's bottom. Now a new curve, a curve moved to another layer or a removed curve leaves every
    other curve's apex where it was (a default apex is written down); moving a bottom still moves it."""
    from auszug.microarch import BasicCurve, Drawing, Segment
    from auszug.microarch import edit as E

    c = BasicCurve(((1.0, 0.0), (0.0, 0.0)), (Segment(),), ("ground", "apex"))   # no height of its own
    d = Drawing((c,), (0.0, 2.5))
    assert d.apex_height(0) == 1.0
    raw = E.draw_curve(d, [(0.0, 1.0), (0.0, 0.0)], [[]], ["ground", "apex"], layer=1)
    assert raw.apex_height(0) == 2.5          # the edit function alone raises it
    new = P.DrawCurve(vertices=[(0.0, 1.0), (0.0, 0.0)], handles=[[]], marks=["ground", "apex"], layer=1).apply(d)
    assert new.apex_height(0) == 1.0 and new.curves[0].height == 1.0 and new.curves[1].layer == 1
    back = P.RemoveCurve(curve=1).apply(new)
    assert back.apex_height(0) == 1.0
    moved = P.SetLayer(curve=1, layer=0).apply(new)
    assert moved.apex_height(0) == 1.0
    # a layer bottom is what a default apex follows: that edit still moves it
    two = Drawing((c, c.with_(layer=1, height=4.0)), (0.0, 2.5))
    assert two.apex_height(0) == 2.5
    assert P.SetLayerBottom(layer=1, z=3.0).apply(two).apex_height(0) == 3.0
