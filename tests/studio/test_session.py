"""Sessions: geometry equals the network's curves; undo/redo restore drawings exactly."""

from __future__ import annotations

import numpy as np
import pytest

from auszug.errors import AuszugError
from auszug.formats import load
from auszug.microarch import build
from auszug.studio import protocol as P
from auszug.studio.session import Session, Workspace, WorkspaceError, geometry


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
    for c, r in zip(curves, reps):
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
