"""One studio session: the current drawing, its undo/redo stacks and its geometry.

No networking here: :class:`Session` turns protocol messages into new drawings
and :func:`geometry` turns a drawing into a :class:`~auszug.studio.protocol.Geometry`
message plus its float32 payload. The server only moves bytes.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from auszug.errors import AuszugError
from auszug.microarch.model import Drawing
from auszug.microarch.network import build
from auszug.microarch.prc import intersections
from auszug.studio import protocol as P

__all__ = ["WorkspaceError", "Workspace", "Session", "geometry", "curve_infos", "replica_transforms"]

#: How many edits undo remembers.
UNDO_DEPTH = 500


class WorkspaceError(AuszugError, ValueError):
    """A path that leaves the workspace folder, or a file that cannot be used there."""


@dataclass(frozen=True)
class Workspace:
    """The folder the studio may read and write; every path is resolved inside it.

    Examples
    --------
    >>> ws = Workspace(Path("/tmp"))
    >>> ws.resolve("../etc/passwd")
    Traceback (most recent call last):
    ...
    auszug.studio.session.WorkspaceError: '../etc/passwd' is outside the workspace
    """

    root: Path

    def resolve(self, rel: str) -> Path:
        """The absolute path of ``rel``; refuses anything that resolves outside the root."""
        if not rel or "\x00" in rel:
            raise WorkspaceError("expected a file name inside the workspace")
        root = self.root.resolve()
        p = (root / rel).resolve()
        if p != root and root not in p.parents:
            raise WorkspaceError(f"{rel!r} is outside the workspace")
        return p

    def relative(self, p: Path) -> str:
        """``p`` relative to the root, with forward slashes."""
        return p.resolve().relative_to(self.root.resolve()).as_posix()


def replica_transforms(drawing: Drawing, basic: int) -> NDArray[np.float64]:
    """Column-major 4x4 transforms (k, 16) of the replicas of basic curve ``basic``.

    Replica j maps (x, y, z) to (M_j (xy - c) + c, z) with M_j the symmetry
    group's 2x2 matrix and c its centre.

    Examples
    --------
    >>> from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry
    >>> c = BasicCurve(((1, 0), (2, 0)), (Segment(),), ("ground", "apex"), height=1.0, symmetry=Symmetry(fold=4))
    >>> t = replica_transforms(Drawing((c,)), 0)
    >>> t.shape, t[1].reshape(4, 4).T[:2, :2].round(12).tolist()
    ((4, 16), [[0.0, -1.0], [1.0, 0.0]])
    """
    sym = drawing.curves[basic].symmetry
    m = sym.matrices()
    c = np.asarray(sym.center)
    k = len(m)
    t = np.zeros((k, 4, 4))
    t[:, :2, :2] = m
    t[:, 2, 2] = 1.0
    t[:, 3, 3] = 1.0
    t[:, :2, 3] = c - np.einsum("kij,j->ki", m, c)
    return np.ascontiguousarray(t.transpose(0, 2, 1)).reshape(k, 16)


def _handles(seg) -> list[tuple[float, float]]:  # noqa: ANN001
    return [(float(h[0]), float(h[1])) for h in seg.handles]


def curve_infos(drawing: Drawing) -> list[P.CurveInfo]:
    """The editable definition of every basic curve, as the design tools show it."""
    bottoms = drawing.bottoms()
    out = []
    for i, c in enumerate(drawing.curves):
        sym = c.symmetry
        out.append(P.CurveInfo(
            vertices=[(float(x), float(y)) for x, y in c.vertices],
            handles=[_handles(sg) for sg in c.segments],
            marks=list(c.marks),
            fold=sym.fold,
            mirror=sym.axis_rule if sym.mirror else "none",
            axis=[float(sym.axis[0]), float(sym.axis[1])] if sym.mirror else None,
            center=(float(sym.center[0]), float(sym.center[1])),
            layer=c.layer,
            apex=float(drawing.apex_height(i, bottoms)),
            bottom=float(bottoms[c.layer]),
            prc=list(c.prc),
            decoration=c.decoration,
            decoration_at=c.decoration_at,
            post_top=c.post_top,
            name=c.name,
        ))
    return out


def _side(points: NDArray[np.float64]) -> NDArray[np.float64]:
    """(n, 2) side view (s, z) of a piece's samples: s = top-view arc length from the start."""
    d = np.hypot(*np.diff(points[:, :2], axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(d)])
    return np.stack([s, points[:, 2]], axis=1)


def _layer_bottoms(drawing: Drawing) -> list[float]:
    b = list(drawing.bottoms())
    return b + [float(z) for z in drawing.layer_bottoms[len(b):]]


def geometry(drawing: Drawing, *, path: str = "", revision: int = 0, can_undo: bool = False,
             can_redo: bool = False, msg_id: int = 0, dirty: bool = False,
             recoverable: str = "") -> tuple[P.Geometry, bytes]:
    """The :class:`~auszug.studio.protocol.Geometry` message of ``drawing`` and its binary payload.

    Posts and pillars that lie on a mirror axis are their own mirror image;
    their duplicate replicas are left out, as :meth:`Network.curves` does, so
    ``n_replicas`` equals the number of network curves.
    """
    net = build(drawing)
    chunks: list[NDArray[np.float32]] = []
    offset = 0

    def put(a: NDArray[np.float64]) -> P.ArrayRef:
        nonlocal offset
        a32 = np.ascontiguousarray(a, dtype="<f4")
        chunks.append(a32.ravel())
        ref = P.ArrayRef(offset=offset, shape=list(a32.shape))
        offset += a32.size
        return ref

    pieces = []
    n_rep = 0
    for p in net.pieces:
        tr = replica_transforms(drawing, p.basic)
        labels = drawing.curves[p.basic].symmetry.labels()
        if p.top is None:  # vertical: drop replicas that coincide with an earlier one
            reps = net.replicate(p)
            keep: list[int] = []
            for k in range(len(reps)):
                if not any(np.allclose(reps[k], reps[j], rtol=0, atol=1e-12) for j in keep):
                    keep.append(k)
            tr = tr[keep]
            labels = [labels[k] for k in keep]
        n_rep += len(tr)
        pieces.append(P.PieceGeometry(
            basic=p.basic, segment=p.segment, layer=drawing.curves[p.basic].layer, kind=p.kind,
            points=put(p.points), side=put(_side(p.points)), transforms=put(tr), labels=labels,
            prc=None if p.prc is None else [float(v) for v in p.prc],
            prc_s=None if p.prc_fraction is None or p.top is None
            else float(p.prc_fraction * p.top.length()),
        ))
    markers = [
        P.IntersectionMarker(curve=x.curve, segment=x.segment, other_curve=x.other_curve,
                             other_segment=x.other_segment, replica=x.replica,
                             point=(float(x.point[0]), float(x.point[1])), true=bool(x.true))
        for x in intersections(drawing)
    ]
    bounds = [float(v) for v in net.bounds().ravel()] if net.pieces else [0.0] * 6
    payload = np.concatenate(chunks).astype("<f4").tobytes() if chunks else b""
    msg = P.Geometry(
        revision=revision, path=path, name=drawing.name, n_curves=len(drawing.curves),
        n_replicas=n_rep, pieces=pieces, intersections=markers, curves=curve_infos(drawing),
        layers=[float(z) for z in _layer_bottoms(drawing)], bounds=bounds,
        can_undo=can_undo, can_redo=can_redo, dirty=dirty, recoverable=recoverable,
        binary_floats=offset, id=msg_id,
    )
    return msg, payload


@dataclass
class Session:
    """The drawing being edited, with undo and redo.

    Every edit is a pure function of :mod:`auszug.microarch.edit`; a failed edit
    (an :class:`~auszug.errors.AuszugError`) leaves the session unchanged. An
    edit is only kept when the edited drawing builds.
    """

    workspace: Workspace
    drawing: Drawing | None = None
    path: str = ""
    revision: int = 0
    undo_stack: list[Drawing] = field(default_factory=list)
    redo_stack: list[Drawing] = field(default_factory=list)

    def open(self, rel: str) -> None:
        """Load ``rel`` (inside the workspace) and forget the undo history."""
        from auszug.formats import load

        p = self.workspace.resolve(rel)
        if not p.is_file():
            raise WorkspaceError(f"no such file in the workspace: {rel!r}")
        d = load(p)
        build(d)  # refuse a drawing that does not build before replacing the current one
        self.drawing, self.path = d, self.workspace.relative(p)
        self.undo_stack.clear()
        self.redo_stack.clear()
        self.revision += 1

    def save(self, rel: str = "") -> str:
        """Write the drawing (format by extension) inside the workspace; the relative path written."""
        from auszug.formats import save

        d = self._need()
        p = self.workspace.resolve(rel or self.path)
        save(d, p, kind="drawing")
        return self.workspace.relative(p)

    def apply(self, op: P.EditOp) -> None:
        """Apply one edit message; on error nothing changes."""
        d = self._need()
        new = op.apply(d)
        build(new)
        self.undo_stack.append(d)
        del self.undo_stack[:-UNDO_DEPTH]
        self.redo_stack.clear()
        self.drawing = new
        self.revision += 1

    def undo(self) -> None:
        """Go back one edit."""
        d = self._need()
        if not self.undo_stack:
            raise AuszugError("nothing to undo")
        self.redo_stack.append(d)
        self.drawing = self.undo_stack.pop()
        self.revision += 1

    def redo(self) -> None:
        """Redo the last undone edit."""
        d = self._need()
        if not self.redo_stack:
            raise AuszugError("nothing to redo")
        self.undo_stack.append(d)
        self.drawing = self.redo_stack.pop()
        self.revision += 1

    def geometry(self, msg_id: int = 0) -> tuple[P.Geometry, bytes]:
        """The current geometry message and payload."""
        return geometry(self._need(), path=self.path, revision=self.revision,
                        can_undo=bool(self.undo_stack), can_redo=bool(self.redo_stack), msg_id=msg_id)

    def _need(self) -> Drawing:
        if self.drawing is None:
            raise AuszugError("no drawing is open: send an 'open' message first")
        return self.drawing
