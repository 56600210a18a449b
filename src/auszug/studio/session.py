"""Studio documents: a drawing with its undo/redo history, its network and its geometry message.

No networking here. A :class:`Document` turns protocol messages into new
drawings; :func:`geometry` (and the fast :func:`geometry_frames` the server
sends) turns a drawing into a :class:`~auszug.studio.protocol.Geometry`
message plus its float32 payload. :class:`Workspace` confines every path to
the workspace folder. The server (:mod:`auszug.studio.server`) shares one
document between all tabs that have the same file open (:mod:`auszug.studio.hub`).

Speed: an edit builds the network once (:func:`network_of` keeps the last
networks by drawing object, so undo and redo rebuild nothing), and the
geometry JSON is written from plain dicts without dataclasses (same text as
``protocol.encode`` of the dataclass message; a test checks it).
"""

from __future__ import annotations

import copy
import errno
import itertools
import json
import os
import re
import secrets
import stat
import threading
import time
import weakref
from dataclasses import dataclass, field, replace
from functools import lru_cache
from pathlib import Path, PurePosixPath
from typing import Any, Callable

import numpy as np
from numpy.typing import NDArray

from auszug._cache import LruCache
from auszug.errors import AuszugError, DrawingError, FormatError
from auszug.limits import LIMITS, check_file_size, shown
from auszug.microarch.model import Drawing
from auszug.microarch.network import Network, build
from auszug.microarch.prc import intersections
from auszug.studio import protocol as P

__all__ = [
    "WorkspaceError",
    "EditCancelled",
    "Workspace",
    "AUTOSAVE_DIR",
    "drawing_endings",
    "Document",
    "Session",
    "network_of",
    "geometry",
    "geometry_frames",
    "curve_infos",
    "replica_transforms",
    "check_file_name",
    "read_drawing",
    "example_document",
    "text_document",
    "new_document",
    "open_document",
    "resume_document",
    "check_doc_id",
]

#: How many edits undo remembers.
UNDO_DEPTH = 500
#: How many undo steps back a drag's next edit looks for the drag's own step.
_DRAG_REACH = 16
#: Where autosaves live, relative to the workspace.
AUTOSAVE_DIR = ".auszug/autosave"
#: A set-aside (offered) autosave is ``<autosave name><OFFER_INFIX><mtime in ns>.json``.
OFFER_INFIX = ".offered-"
_OFFER = re.compile(r"^(?P<of>.+)" + re.escape(OFFER_INFIX) + r"(?P<ns>[0-9]{1,20})\.json$")
#: Revisions count up over all documents, so a tab that moves to another document never goes back.
_REVISIONS = itertools.count(1)


class WorkspaceError(AuszugError, ValueError):
    """A path that leaves the workspace folder, or a file that cannot be used there."""


class EditCancelled(AuszugError):
    """A change given up (its time budget ran out); the document is as before it."""


def _is_drawing(name: str) -> bool:
    """Whether ``name`` is a drawing file's: the formats registry decides (``x.network.json`` is not)."""
    from auszug.formats import suffix_of

    return suffix_of(name, "drawing") is not None


def drawing_endings() -> str:
    """The registered drawing endings for messages: ``".uc or .json"``."""
    from auszug.formats import suffixes

    return " or ".join(suffixes("drawing"))


@dataclass(frozen=True)
class Workspace:
    """The folder the studio may read and write; every path is resolved inside it.

    Symbolic links are followed before the check, so a link (or a linked
    folder) inside the workspace that points outside it is refused too.

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
        """The absolute, link-free path of ``rel``; refuses anything that resolves outside the root.

        Raises
        ------
        WorkspaceError
            For an empty path, a NUL byte, or a path (or link target) outside the workspace.
        """
        if not rel or "\x00" in rel:
            raise WorkspaceError("expected a file name inside the workspace")
        root = self.root.resolve()
        try:
            p = (root / rel).resolve()
        except (OSError, RuntimeError) as e:  # a symlink loop
            raise WorkspaceError(f"{rel!r}: cannot resolve ({e})") from None
        if p != root and root not in p.parents:
            raise WorkspaceError(f"{rel!r} is outside the workspace")
        return p

    def resolve_for_writing(self, rel: str) -> Path:
        """:meth:`resolve`, and refuse targets that are not regular files or lie in the autosave folder."""
        p = self.resolve(rel)
        if p == self.root.resolve():
            raise WorkspaceError(f"{rel!r} is the workspace folder itself, not a file")
        try:
            st = p.lstat()
        except FileNotFoundError:
            st = None
        if st is not None and not stat.S_ISREG(st.st_mode):
            what = "a folder" if stat.S_ISDIR(st.st_mode) else "not a regular file"
            raise WorkspaceError(f"{rel!r}: cannot save over it, it is {what}")
        reserved = self.root.resolve() / ".auszug"
        if reserved == p or reserved in p.parents:
            raise WorkspaceError(f"{rel!r}: the .auszug folder is reserved for autosaves")
        return p

    def relative(self, p: Path) -> str:
        """``p`` relative to the root, with forward slashes."""
        return p.resolve().relative_to(self.root.resolve()).as_posix()

    def autosave_path(self, key: str) -> Path:
        """Where the autosave of ``key`` goes: a workspace path, or ``unsaved/<doc id>/<name>``."""
        return self.root.resolve() / AUTOSAVE_DIR / (key + ".json")

    def drawings(self, limit: int = 10000) -> list[str]:
        """Drawing files below the root (every registered drawing format), relative and sorted.

        :meth:`listing` without its notes.
        """
        return self.listing(limit)[0]

    def listing(self, limit: int = 10000, accept: Callable[[str], bool] | None = None) -> tuple[list[str], list[str]]:
        """(drawings, notes): :meth:`drawings`, and a note per entry skipped as unreadable.

        ``accept`` picks other files by name instead of the drawings (the tracery
        page's style files).

        A note is one line: a symbolic link loop, a folder without permission, a
        link to nothing or a link that points outside the workspace.

        Hidden folders (``.auszug`` with the autosaves, ``.git``...) and
        ``node_modules`` are skipped silently, as are other files the registry
        knows (network files ``*.network.json``, tracery styles ``*.tracery.json``).
        Links to folders are not followed (a loop cannot make the walk endless).
        """
        root = self.root.resolve()
        out: list[str] = []
        notes: list[str] = []

        def rel(p: Path | str) -> str:
            try:
                return Path(p).relative_to(root).as_posix()
            except ValueError:
                return str(p)

        def unreadable(e: OSError) -> None:
            notes.append(f"{rel(e.filename) if e.filename else 'a folder'}: skipped, cannot read it "
                         f"({e.strerror or e})")

        for dirpath, dirnames, filenames in os.walk(root, onerror=unreadable):
            dirnames[:] = sorted(d for d in dirnames if not d.startswith(".") and d != "node_modules")
            for fn in sorted(filenames):
                if fn.startswith(".") or not (accept or _is_drawing)(fn):
                    continue
                p = Path(dirpath) / fn
                try:
                    real = p.resolve(strict=True)
                except RuntimeError:   # Python < 3.13 reports a link loop so
                    notes.append(f"{rel(p)}: skipped, a symbolic link loop")
                    continue
                except OSError as e:
                    what = ("a symbolic link loop" if e.errno == errno.ELOOP else "a link to nothing"
                            if isinstance(e, FileNotFoundError) else f"cannot read it ({e.strerror or e})")
                    notes.append(f"{rel(p)}: skipped, {what}")
                    continue
                if root not in real.parents:
                    notes.append(f"{rel(p)}: skipped, it links outside the workspace")
                elif real.is_file():
                    out.append(p.relative_to(root).as_posix())
                    if len(out) >= limit:
                        notes.append(f"only the first {limit} drawings are listed")
                        return sorted(out), notes
        return sorted(out), notes


# ---------------------------------------------------------------- networks and geometry

#: The last networks built, keyed by drawing object (entries hold the drawing, so its id stays unique).
_NETS = LruCache(64)


def network_of(drawing: Drawing) -> Network:
    """The network of ``drawing``, built once per drawing object (the last few are kept).

    The cache holds the drawing itself, so its ``id`` is not reused while the
    entry lives; undo and redo find their networks here.
    """
    hit = _NETS.get(id(drawing))
    if hit is not None and hit[0] is drawing:
        return hit[1]
    net = build(drawing)
    _NETS.put(id(drawing), (drawing, net))
    return net


@lru_cache(maxsize=1024)
def _transforms(sym: Any) -> NDArray[np.float64]:  # a Symmetry
    m = sym.matrices()
    c = np.asarray(sym.center)
    k = len(m)
    t = np.zeros((k, 4, 4))
    t[:, :2, :2] = m
    t[:, 2, 2] = 1.0
    t[:, 3, 3] = 1.0
    t[:, :2, 3] = c - np.einsum("kij,j->ki", m, c)
    out = np.ascontiguousarray(t.transpose(0, 2, 1)).reshape(k, 16)
    out.setflags(write=False)
    return out


def replica_transforms(drawing: Drawing, basic: int) -> NDArray[np.float64]:
    """Column-major 4x4 transforms (k, 16) of the replicas of basic curve ``basic``.

    Replica j maps (x, y, z) to (M_j (xy - c) + c, z) with M_j the symmetry
    group's 2x2 matrix and c its centre. The array is read-only (cached).

    Examples
    --------
    >>> from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry
    >>> c = BasicCurve(((1, 0), (2, 0)), (Segment(),), ("ground", "apex"), height=1.0, symmetry=Symmetry(fold=4))
    >>> t = replica_transforms(Drawing((c,)), 0)
    >>> t.shape, t[1].reshape(4, 4).T[:2, :2].round(12).tolist()
    ((4, 16), [[0.0, -1.0], [1.0, 0.0]])
    """
    return _transforms(drawing.curves[basic].symmetry)


def _xy(p: Any) -> list[float]:
    return [float(p[0]), float(p[1])]


@lru_cache(maxsize=1024)
def _replicas(group: Any) -> tuple[list[list[float]], list[str]]:  # a geometry.symmetry.SymmetryGroup
    """The group's 2x2 matrices (row-major, as lists) and labels: what the page maps points with."""
    return [[float(v) for v in m.ravel()] for m in group.matrices()], list(group.labels())


@lru_cache(maxsize=4096)
def _curve_info(c: Any, apex: float, bottom: float, index: int) -> dict:  # a BasicCurve
    from auszug.formats.palette import colour

    sym = c.symmetry
    replicas, labels = _replicas(sym.group)
    return {
        "vertices": [_xy(v) for v in c.vertices],
        "handles": [[_xy(h) for h in sg.handles] for sg in c.segments],
        "marks": list(c.marks),
        "fold": sym.fold,
        "mirror": sym.axis_rule if sym.mirror else "none",
        "axis": _xy(sym.axis) if sym.mirror else None,
        "center": _xy(sym.center),
        "layer": c.layer,
        "apex": float(apex),
        "bottom": float(bottom),
        "prc": list(c.prc),
        "decoration": c.decoration,
        "decoration_at": c.decoration_at,
        "post_top": c.post_top,
        "name": c.name,
        "replicas": replicas,
        "labels": labels,
        "color": colour(index),
    }


def _curve_dicts(drawing: Drawing) -> list[dict]:
    bottoms = drawing.bottoms()
    return [_curve_info(c, drawing.apex_height(i, bottoms), bottoms[c.layer], i) for i, c in enumerate(drawing.curves)]


def _curve_info_message(d: dict) -> P.CurveInfo:
    """A CurveInfo from its dict (points as tuples; the cached dict is not shared)."""
    kw = copy.deepcopy(d)
    kw["vertices"] = [tuple(v) for v in d["vertices"]]
    kw["handles"] = [[tuple(h) for h in hs] for hs in d["handles"]]
    kw["center"] = tuple(d["center"])
    return P.CurveInfo(**kw)


def curve_infos(drawing: Drawing) -> list[P.CurveInfo]:
    """The editable definition of every basic curve, as the design tools show it."""
    return [_curve_info_message(d) for d in _curve_dicts(drawing)]


def _side(points: NDArray[np.float64]) -> NDArray[np.float64]:
    """(n, 2) side view (s, z) of a piece's samples: s = top-view arc length from the start."""
    d = np.hypot(*np.diff(points[:, :2], axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(d)])
    return np.stack([s, points[:, 2]], axis=1)


def _distinct_replicas(sym: Any, points: NDArray[np.float64]) -> list[int]:
    """Replicas of a vertical piece that do not coincide (to 1e-12) with an earlier one.

    The rule of :meth:`Network.curves`; all pairs at once instead of ``allclose`` per pair.
    """
    c = np.asarray(sym.center)
    xy = np.matmul(sym.matrices(), (points[:, :2] - c).T).transpose(0, 2, 1) + c    # (k, n, 2)
    flat = np.concatenate([xy, np.broadcast_to(points[:, 2:], xy.shape[:2] + (1,))], axis=2).reshape(len(xy), -1)
    close = np.abs(flat[:, None, :] - flat[None, :, :]).max(axis=2) <= 1e-12
    keep: list[int] = []
    for k in range(len(flat)):
        if not close[k, keep].any():
            keep.append(k)
    return keep


def _ref(offset: int, shape: tuple[int, ...]) -> dict:
    return {"offset": offset, "shape": list(shape), "dtype": "f4"}


def _dumps(v: Any) -> str:
    return json.dumps(v, separators=(",", ":"), allow_nan=False)


class _PieceData:
    """What a geometry message says about one network piece, computed once per piece object.

    The engine reuses the pieces of the curves an edit leaves alone, so an
    edit recomputes only its own curve's: side view, replica transforms (without
    duplicates for vertical pieces), the float32 bytes, bounds, the JSON tail.
    """

    __slots__ = ("sym", "layer", "head", "n", "k", "data", "lo", "hi", "tail", "tail_json", "n_rep")

    def __init__(self, p: Any, sym: Any, layer: int):  # a Piece and a Symmetry
        self.sym, self.layer = sym, layer
        tr = _transforms(sym)
        labels = sym.labels()
        if p.top is None:  # vertical: drop replicas that coincide with an earlier one
            keep = _distinct_replicas(sym, p.points)
            tr = tr[keep]
            labels = [labels[k] for k in keep]
        pts = p.points
        self.n, self.k, self.n_rep = len(pts), len(tr), len(tr)
        buf = np.empty(len(pts) * 5 + tr.size, dtype="<f4")
        buf[:3 * len(pts)] = pts.ravel()
        buf[3 * len(pts):5 * len(pts)] = _side(pts).ravel()
        buf[5 * len(pts):] = tr.ravel()
        self.data = buf.tobytes()
        c = np.asarray(sym.center)
        xy = np.matmul(sym.matrices(), (pts[:, :2] - c).T)    # (k, 2, n): every replica's top view
        self.lo = (*(xy.min(axis=(0, 2)) + c), float(pts[:, 2].min()))
        self.hi = (*(xy.max(axis=(0, 2)) + c), float(pts[:, 2].max()))
        self.head = (p.basic, p.segment, layer, p.kind)
        self.tail = {"labels": labels, "prc": None if p.prc is None else [float(v) for v in p.prc],
                     "prc_s": None if p.prc_fraction is None or p.top is None
                     else float(p.prc_fraction * p.top.length())}
        self.tail_json = _dumps(self.tail)[1:-1]

    def refs(self, offset: int) -> tuple[dict, dict, dict]:
        """ArrayRefs of points, side and transforms when the piece's data start at ``offset``."""
        n = self.n
        return (_ref(offset, (n, 3)), _ref(offset + 3 * n, (n, 2)), _ref(offset + 5 * n, (self.k, 16)))

    def as_dict(self, offset: int) -> dict:
        """The PieceGeometry fields as a dict."""
        b, sg, ly, kind = self.head
        pts, side, tr = self.refs(offset)
        return {"basic": b, "segment": sg, "layer": ly, "kind": kind, "points": pts, "side": side,
                "transforms": tr, **copy.deepcopy(self.tail)}   # the cache's lists stay private

    def as_json(self, offset: int) -> str:
        """The PieceGeometry as JSON text (the same text as encoding :meth:`as_dict`)."""
        b, sg, ly, kind = self.head
        n, o = self.n, offset
        return (f'{{"basic":{b},"segment":{sg},"layer":{ly},"kind":{_dumps(kind)},'
                f'"points":{{"offset":{o},"shape":[{n},3],"dtype":"f4"}},'
                f'"side":{{"offset":{o + 3 * n},"shape":[{n},2],"dtype":"f4"}},'
                f'"transforms":{{"offset":{o + 5 * n},"shape":[{self.k},16],"dtype":"f4"}},{self.tail_json}}}')

    @property
    def size(self) -> int:
        """Its float32 values in the payload."""
        return 5 * self.n + 16 * self.k


_PIECES: "weakref.WeakKeyDictionary[Any, _PieceData]" = weakref.WeakKeyDictionary()


def _piece_data(p: Any, curves: tuple) -> _PieceData:
    c = curves[p.basic]
    d = _PIECES.get(p)
    if d is None or d.layer != c.layer or not (d.sym is c.symmetry or d.sym == c.symmetry):
        d = _PieceData(p, c.symmetry, c.layer)
        try:
            _PIECES[p] = d
        except TypeError:  # pragma: no cover - pieces are weak-referenceable dataclasses
            pass
    return d


@lru_cache(maxsize=4096)
def _curve_json(c: Any, apex: float, bottom: float, index: int) -> str:
    return _dumps(_curve_info(c, apex, bottom, index))


class _Body:
    """The drawing-dependent part of a geometry message, as data for both the dict and the text form."""

    def __init__(self, drawing: Drawing, net: Network):
        curves = drawing.curves
        self.drawing = drawing
        self.pieces = [_piece_data(p, curves) for p in net.pieces]
        self.offsets = []
        o = 0
        for d in self.pieces:
            self.offsets.append(o)
            o += d.size
        self.binary_floats = o
        self.payload = b"".join(d.data for d in self.pieces)
        self.n_rep = sum(d.n_rep for d in self.pieces)
        self.markers = [
            {"curve": x.curve, "segment": x.segment, "other_curve": x.other_curve,
             "other_segment": x.other_segment, "replica": x.replica,
             "point": [float(x.point[0]), float(x.point[1])], "true": bool(x.true)}
            for x in intersections(drawing)
        ]
        if self.pieces:
            lo = [min(d.lo[i] for d in self.pieces) for i in range(3)]
            hi = [max(d.hi[i] for d in self.pieces) for i in range(3)]
            self.bounds = [float(v) for v in lo + hi]
        else:
            self.bounds = [0.0] * 6
        self.layers = [float(z) for z in drawing.all_bottoms()]
        bottoms = drawing.bottoms()
        self.curve_keys = [(c, drawing.apex_height(i, bottoms), bottoms[c.layer], i) for i, c in enumerate(curves)]

    def as_dict(self, *, path: str, revision: int, can_undo: bool, can_redo: bool, dirty: bool,
                recoverable: str, doc: str) -> dict:
        """The Geometry message as a dict in field order, without the trailing id/protocol/type."""
        d = self.drawing
        return {
            "revision": revision, "path": path, "name": d.name, "n_curves": len(d.curves),
            "n_replicas": self.n_rep, "pieces": [p.as_dict(o) for p, o in zip(self.pieces, self.offsets, strict=True)],
            "intersections": self.markers, "curves": [copy.deepcopy(_curve_info(*k)) for k in self.curve_keys],
            "layers": self.layers, "bounds": self.bounds, "can_undo": can_undo, "can_redo": can_redo,
            "dirty": dirty, "recoverable": recoverable, "doc": doc, "binary_floats": self.binary_floats,
        }

    def head(self, *, path: str, revision: int, can_undo: bool, can_redo: bool, dirty: bool,
             recoverable: str, doc: str) -> str:
        """The JSON text of :meth:`as_dict` without its closing brace (fragments cached per piece and curve)."""
        d = self.drawing
        pieces = ",".join(p.as_json(o) for p, o in zip(self.pieces, self.offsets, strict=True))
        curves = ",".join(_curve_json(*k) for k in self.curve_keys)
        return (f'{{"revision":{int(revision)},"path":{_dumps(path)},"name":{_dumps(d.name)},'
                f'"n_curves":{len(d.curves)},"n_replicas":{self.n_rep},"pieces":[{pieces}],'
                f'"intersections":{_dumps(self.markers)},"curves":[{curves}],"layers":{_dumps(self.layers)},'
                f'"bounds":{_dumps(self.bounds)},"can_undo":{_dumps(bool(can_undo))},'
                f'"can_redo":{_dumps(bool(can_redo))},"dirty":{_dumps(bool(dirty))},'
                f'"recoverable":{_dumps(recoverable)},"doc":{_dumps(doc)},"binary_floats":{self.binary_floats}')


class GeometryText:
    """The JSON text of a Geometry message for any ``id``: the body is encoded once.

    ``text(msg_id)`` equals ``protocol.encode`` of the dataclass message with that id.
    """

    __slots__ = ("_head",)

    def __init__(self, head: str):
        self._head = head

    def text(self, msg_id: int = 0) -> str:
        """The message text with ``id`` = ``msg_id``."""
        return f'{self._head},"id":{int(msg_id)},"protocol":{P.PROTOCOL_VERSION},"type":"geometry"}}'


def geometry_frames(drawing: Drawing, *, net: Network | None = None, path: str = "", revision: int = 0,
                    can_undo: bool = False, can_redo: bool = False, dirty: bool = False,
                    recoverable: str = "", doc: str = "") -> tuple[GeometryText, bytes]:
    """The geometry message of ``drawing`` as ready-to-send text (for any id) and its binary payload.

    The fast path of :func:`geometry`: no dataclasses, the network built once
    (``net``, or :func:`network_of`), JSON fragments of unchanged pieces and
    curves reused.
    """
    body = _Body(drawing, network_of(drawing) if net is None else net)
    head = body.head(path=path, revision=revision, can_undo=can_undo, can_redo=can_redo, dirty=dirty,
                     recoverable=recoverable, doc=doc)
    return GeometryText(head), body.payload


def _message(d: dict, msg_id: int) -> P.Geometry:
    """The dataclass of a geometry dict (for the Python API and the tests)."""
    pieces = [P.PieceGeometry(**{**p, "points": P.ArrayRef(**p["points"]), "side": P.ArrayRef(**p["side"]),
                                 "transforms": P.ArrayRef(**p["transforms"])}) for p in d["pieces"]]
    markers = [P.IntersectionMarker(**{**m, "point": tuple(m["point"])}) for m in d["intersections"]]
    curves = [_curve_info_message(c) for c in d["curves"]]
    return P.Geometry(**{**d, "pieces": pieces, "intersections": markers, "curves": curves, "id": msg_id})


def geometry(drawing: Drawing, *, path: str = "", revision: int = 0, can_undo: bool = False,
             can_redo: bool = False, msg_id: int = 0, dirty: bool = False,
             recoverable: str = "", net: Network | None = None, doc: str = "") -> tuple[P.Geometry, bytes]:
    """The :class:`~auszug.studio.protocol.Geometry` message of ``drawing`` and its binary payload.

    Posts and pillars that lie on a mirror axis are their own mirror image;
    their duplicate replicas are left out, as :meth:`Network.curves` does, so
    ``n_replicas`` equals the number of network curves.
    """
    body = _Body(drawing, network_of(drawing) if net is None else net)
    d = body.as_dict(path=path, revision=revision, can_undo=can_undo, can_redo=can_redo, dirty=dirty,
                     recoverable=recoverable, doc=doc)
    return _message(d, msg_id), body.payload


# ---------------------------------------------------------------- documents


def check_file_name(name: str) -> str:
    """``name`` if it is a plain file name (no folder, not empty, no NUL); else :class:`WorkspaceError`."""
    if not name or name in (".", "..") or "/" in name or "\\" in name or "\x00" in name or len(name) > 255:
        raise WorkspaceError(f"{name!r} is not a plain file name (no folders, not empty)")
    if name != name.strip():
        raise WorkspaceError(f"{name!r}: a file name must not start or end with blanks")
    return name


def _drawing_format(name: str) -> Any:  # a FileFormat
    from auszug.formats import format_for

    if not _is_drawing(name):
        raise FormatError(f"not a drawing file; expected a {drawing_endings()} drawing", name)
    return format_for(PurePosixPath(name), "drawing")


def read_drawing(name: str, text: str) -> Drawing:
    """Parse drawing text in the format of ``name``'s extension (no file is touched).

    Raises
    ------
    FormatError
        Naming ``name``, the line and the problem.
    """
    fmt = _drawing_format(name)
    d = fmt.reader(text, name)
    if not isinstance(d, Drawing):  # pragma: no cover - drawing readers return drawings
        raise FormatError("not a drawing", name)
    return d


def _same_drawing(a: Drawing, b: Drawing) -> bool:
    """Equal up to the name (a file's stem names its drawing; the autosave's stem differs)."""
    return a is b or replace(a, name="") == replace(b, name="")


def _autosave_time(p: Path) -> str:
    from datetime import datetime

    return datetime.fromtimestamp(p.stat().st_mtime).astimezone().isoformat(timespec="seconds")


def prune_offers(workspace: Workspace, of: Path | None = None, *, keep: Path | None = None,
                 now_ns: int | None = None) -> list[Path]:
    """Delete set-aside autosaves past their lifetime; the paths deleted.

    An autosave offered for recovery is moved aside (:meth:`Document.check_recoverable`).
    Of the offers of one autosave, the newest :attr:`~auszug.limits.Limits.autosave_offers`
    are kept, and none older than :attr:`~auszug.limits.Limits.autosave_offer_days`
    (by the time in its name: when the autosave was written). ``of``: only the
    offers of that autosave file, else every one below the workspace's autosave
    folder. ``keep``: an offer never deleted (the one a document offers now).
    Symbolic links and other files are left alone.
    """
    folder = workspace.root.resolve() / AUTOSAVE_DIR
    now = time.time_ns() if now_ns is None else now_ns
    cutoff = now - int(LIMITS.autosave_offer_days * 86400e9)
    groups: dict[Path, list[tuple[int, Path]]] = {}
    dirs = [of.parent] if of is not None else [Path(d) for d, _, _ in os.walk(folder, followlinks=False)]
    for d in dirs:
        try:
            names = os.listdir(d)
        except OSError:
            continue
        for n in names:
            m = _OFFER.match(n)
            if not m or (of is not None and m["of"] != of.name):
                continue
            p = d / n
            try:
                if not stat.S_ISREG(p.lstat().st_mode):
                    continue
            except OSError:
                continue
            groups.setdefault(d / m["of"], []).append((int(m["ns"]), p))
    gone = []
    for offers in groups.values():
        offers.sort(reverse=True)
        for i, (ns, p) in enumerate(offers):
            if p == keep or (i < LIMITS.autosave_offers and ns >= cutoff):
                continue
            try:
                p.unlink()
                gone.append(p)
            except OSError:
                pass
    return gone


class Document:
    """One open drawing: the drawing, its undo/redo stacks, revision, dirty flag and autosave state.

    Every edit is a pure function of :mod:`auszug.microarch.edit`; a failed edit
    (an :class:`~auszug.errors.AuszugError`) leaves the document unchanged, and
    an edit is only kept when the edited drawing builds. All changes hold the
    document's lock, so worker threads and the event loop may both use it.

    Parameters
    ----------
    workspace : Workspace
    drawing : Drawing
    path : str
        Workspace-relative path ("" for a document not saved yet).
    name : str
        File name for an unsaved document (its default save name and autosave name).
    """

    def __init__(self, workspace: Workspace, drawing: Drawing, path: str = "", name: str = "", doc_id: str = ""):
        self.workspace = workspace
        self.doc_id = doc_id or secrets.token_hex(8)   # names the document in Resume and its autosave
        self.offered: Path | None = None     # the autosave offered by ``recoverable``, kept aside
        self._restored: Drawing | None = None  # the drawing ``recover`` made of :attr:`offered`
        self.lock = threading.RLock()
        self.drawing = drawing
        self.net = network_of(drawing)
        self.path = path
        self.name = name or (PurePosixPath(path).name if path else (drawing.name or "untitled"))
        self.revision = next(_REVISIONS)
        self.undo_stack: list[Drawing] = []
        self.redo_stack: list[Drawing] = []
        self.clean: Drawing = drawing        # the drawing as last opened or saved
        self.recoverable = ""
        self.changes = 0                     # counts every change (the autosaver compares)
        self.autosaved_changes = 0           # ``changes`` when the autosave was last written
        self.autosave_lock = threading.Lock()  # one autosave or save at a time touches the files
        self.slow_edits = False              # the last edit was slow: the server runs the next in a thread
        self._frames: tuple[int, GeometryText, bytes] | None = None
        self._steps: list[frozenset[int]] = []  # the drag gestures in each undo step (parallel to undo_stack)

    # -- state ------------------------------------------------------------------------
    @property
    def dirty(self) -> bool:
        """Whether the drawing differs from the one last opened or saved (undo back clears it)."""
        return self.drawing is not self.clean

    @property
    def label(self) -> str:
        """How error messages name the document: its path, else its name."""
        return self.path or self.name

    @property
    def autosave_key(self) -> str:
        """The autosave's name below the autosave folder: the path, or ``unsaved/<doc id>/<name>``.

        Per document, not per name: two unsaved "untitled" drawings (or two tabs on
        one example) never share an autosave.
        """
        return self.path if self.path else f"unsaved/{self.doc_id}/{self.name}"

    def autosave_file(self) -> Path:
        """The autosave file of this document."""
        return self.workspace.autosave_path(self.autosave_key)

    def snapshot(self) -> tuple[Drawing, Network, int]:
        """(drawing, network, revision), consistent, for work outside the lock (meshes, autosave)."""
        with self.lock:
            return self.drawing, self.net, self.revision

    def check_recoverable(self) -> str:
        """Set and return :attr:`recoverable`: the autosave's ISO time if it differs from the drawing.

        The autosave then moves aside (``<autosave>.offered-<time>.json``, :attr:`offered`):
        the autosaves of the edits that follow cannot overwrite it, and it stays
        offered until :meth:`recover`. Older offers of the same file are pruned
        (:func:`prune_offers`); a restored offer is deleted once the restored
        drawing is autosaved or saved.
        """
        p = self.autosave_file()
        rec = ""
        try:
            if p.is_file():
                check_file_size(p)
                saved = read_drawing(p.name, p.read_text(encoding="utf-8"))
                if not _same_drawing(saved, self.drawing):
                    rec = _autosave_time(p)
                    aside = p.with_name(f"{p.name}.offered-{p.stat().st_mtime_ns}.json")
                    os.replace(p, aside)
                    self.offered = aside
                    prune_offers(self.workspace, p, keep=aside)
        except (OSError, AuszugError, UnicodeDecodeError):
            rec = ""   # an unreadable autosave is no recovery; it is overwritten on the next change
        self.recoverable = rec
        return rec

    def autosave_owner(self) -> str:
        """The document id that wrote the current autosave ("" if none or unknown)."""
        try:
            a = self.autosave_file()
            return a.with_name(a.name + ".doc").read_text(encoding="utf-8").strip()
        except OSError:
            return ""

    # -- changes ----------------------------------------------------------------------
    def _set(self, new: Drawing, net: Network) -> None:
        self.drawing = new
        self.net = net
        self.revision = next(_REVISIONS)
        self.changes += 1
        self._frames = None

    def _push(self, new: Drawing, net: Network, drag: int = 0) -> None:
        self.undo_stack.append(self.drawing)
        self._steps.append(frozenset((drag,)) if drag else frozenset())
        del self.undo_stack[:-UNDO_DEPTH]
        del self._steps[:-UNDO_DEPTH]
        self.redo_stack.clear()
        self._set(new, net)

    def _drag_step(self, drag: int) -> int:
        """The index of the undo step that holds drag gesture ``drag`` (-1: none).

        Only the last few steps are searched: a drag's step is near the top
        (other tabs' edits may have come in between).
        """
        for i in range(len(self._steps) - 1, max(-1, len(self._steps) - 1 - _DRAG_REACH), -1):
            if drag in self._steps[i]:
                return i
        return -1

    def change(self, fn: Any, *args: Any, cancel: threading.Event | None = None) -> None:
        """Run one change ``fn(*args)`` and compute its geometry: all or nothing.

        ``fn`` is :meth:`apply`, :meth:`undo`, :meth:`redo` or :meth:`recover`.
        If the change or its geometry message fails, or ``cancel`` is set by
        the time both are done (the server's time budget ran out), the
        document is put back exactly as it was (drawing, undo and redo
        stacks, revision, change count) and the error is raised; there is
        no undo step for a change the page never saw.

        Raises
        ------
        EditCancelled
            ``cancel`` was set.
        """
        with self.lock:
            before = (self.drawing, self.net, list(self.undo_stack), list(self.redo_stack), self.revision,
                      self.recoverable, self.changes, self._frames, list(self._steps))
        try:
            fn(*args)
            if cancel is not None and cancel.is_set():
                raise EditCancelled("cancelled")
            self.frames()
            if cancel is not None and cancel.is_set():
                raise EditCancelled("cancelled")
        except BaseException:
            with self.lock:
                (self.drawing, self.net, self.undo_stack[:], self.redo_stack[:], self.revision,
                 self.recoverable, self.changes, self._frames, self._steps[:]) = before
            raise

    def apply(self, op: P.EditOp) -> None:
        """Apply one edit message; on error nothing changes.

        The edit and its build run outside the lock (readers such as a mesh
        snapshot never wait for them); the commit checks that no other change
        came in between, and else starts over from the newer drawing. A
        change whose reply must be built too goes through :meth:`change`.
        """
        drag = getattr(op, "drag", 0)
        while True:
            base = self.drawing
            new = op.apply(base)
            if new == base:
                return   # a no-op (a click that sets what is already set): no change, no undo step
            net = network_of(new)   # refuses a drawing that does not build
            with self.lock:
                if self.drawing is base:
                    i = self._drag_step(drag) if drag else -1
                    if i >= 0:
                        # the same drag goes on: still one undo step. If other edits (another tab's
                        # drag) came in since it began, they join that step: an undo never lands in
                        # the middle of a drag
                        merged = frozenset().union(*self._steps[i:])
                        del self.undo_stack[i + 1:]
                        del self._steps[i + 1:]
                        self._steps[i] = merged
                        self.redo_stack.clear()
                        self._set(new, net)
                    else:
                        self._push(new, net, drag)
                    return

    def replace_drawing(self, new: Drawing) -> None:
        """Replace the whole drawing as one undoable edit (recovery, save over another tab's file)."""
        net = network_of(new)
        with self.lock:
            self._push(new, net)

    def undo(self) -> None:
        """Go back one edit."""
        with self.lock:
            if not self.undo_stack:
                raise AuszugError("nothing to undo")
            prev = self.undo_stack[-1]
            net = network_of(prev)
            self.undo_stack.pop()
            self._steps.pop()
            self.redo_stack.append(self.drawing)
            self._set(prev, net)

    def redo(self) -> None:
        """Redo the last undone edit."""
        with self.lock:
            if not self.redo_stack:
                raise AuszugError("nothing to redo")
            nxt = self.redo_stack[-1]
            net = network_of(nxt)
            self.redo_stack.pop()
            self.undo_stack.append(self.drawing)
            self._steps.append(frozenset())   # a redone drag is over: it takes no more edits
            self._set(nxt, net)

    def recover(self) -> None:
        """Replace the drawing by the offered autosave (an undoable edit; the document becomes dirty)."""
        p = self.offered if self.offered is not None else self.autosave_file()
        if not p.is_file():
            raise WorkspaceError(f"{self.label}: no autosave to recover")
        check_file_size(p)
        saved = read_drawing("autosave.json", p.read_text(encoding="utf-8"))
        with self.lock:
            self.replace_drawing(replace(saved, name=self.drawing.name))
            self.recoverable = ""
            self._restored = self.drawing

    def _drop_restored_offer(self, written: Drawing) -> None:
        """Delete the restored offer once ``written`` (just autosaved or saved) is the restored drawing."""
        if self._restored is None or written is not self._restored or self.offered is None:
            return
        try:
            self.offered.unlink()
        except FileNotFoundError:
            pass
        self.offered, self._restored = None, None

    def fork(self) -> "Document":
        """A new document with this one's drawing, file, dirty state and undo/redo history.

        "Save as" in one tab of a shared document forks it: that tab moves to the
        new file, the other tabs stay on the old one.
        """
        with self.lock:
            d = Document(self.workspace, self.drawing, path=self.path, name=self.name)
            d.undo_stack, d.redo_stack = list(self.undo_stack), list(self.redo_stack)
            d._steps = list(self._steps)
            d.clean, d.changes = self.clean, self.changes
            d.slow_edits = self.slow_edits
            return d

    def default_save_path(self) -> str:
        """Where an unsaved document goes by default: ``<name>.json`` (a drawing ending replaced)."""
        from auszug.formats import suffix_of

        stem, suf = self.name, suffix_of(self.name, "drawing")
        if suf and len(stem) > len(suf):
            stem = stem[: -len(suf)]
        return stem + ".json"

    def save(self, rel: str = "") -> str:
        """Write the drawing inside the workspace (format by its drawing ending); the relative path written.

        ``rel`` empty: the document's own path, or :meth:`default_save_path` if
        it has none. Afterwards the document is clean, its path is the one
        written and the old autosave is gone.

        Raises
        ------
        WorkspaceError
            Outside the workspace, not a regular file, or not a drawing file name.
        FormatError
            If the format cannot hold the drawing.
        """
        from auszug.formats import save

        target = rel or self.path or self.default_save_path()
        if not _is_drawing(target):
            raise WorkspaceError(f"{target!r}: can only save drawings as {drawing_endings()}")
        p = self.workspace.resolve_for_writing(target)
        with self.autosave_lock:
            with self.lock:
                d = self.drawing
                old_autosave = self.autosave_file()
            try:
                save(d, p, kind="drawing")
            except OSError as e:
                raise WorkspaceError(f"{target}: cannot write ({e.strerror or e})") from None
            new_rel = self.workspace.relative(p)
            with self.lock:
                self.path = new_rel
                self.name = PurePosixPath(new_rel).name
                self.clean = d
                self.recoverable = ""
                self.revision = next(_REVISIONS)
                self.autosaved_changes = self.changes
                self._frames = None
            for a in {old_autosave, self.autosave_file()}:
                for f in (a, a.with_name(a.name + ".doc")):
                    try:
                        f.unlink()
                    except FileNotFoundError:
                        pass
            self._drop_restored_offer(d)
        return new_rel

    def write_autosave(self) -> int:
        """Write the autosave now (blocking; a worker thread calls it); the change count written.

        A dirty drawing goes to :meth:`autosave_file` as native JSON, atomically;
        a clean one (saved, or undone back to the file) removes the autosave.
        """
        from auszug.formats import save

        with self.autosave_lock:
            with self.lock:
                d, changes, dirty, target = self.drawing, self.changes, self.dirty, self.autosave_file()
            owner = target.with_name(target.name + ".doc")
            if dirty:
                save(d, target, kind="drawing")
                if not owner.is_file() or owner.read_text(encoding="utf-8") != self.doc_id:
                    owner.write_text(self.doc_id, encoding="utf-8")
                self._drop_restored_offer(d)
            else:
                for f in (target, owner):
                    try:
                        f.unlink()
                    except FileNotFoundError:
                        pass
            with self.lock:
                self.autosaved_changes = max(self.autosaved_changes, changes)
        return changes

    # -- geometry ---------------------------------------------------------------------
    def frames(self) -> tuple[GeometryText, bytes]:
        """The current geometry message (text for any id) and payload, computed once per revision.

        Computed outside the lock from a consistent snapshot of the state.
        """
        with self.lock:
            f = self._frames
            if f is not None and f[0] == self.revision:
                return f[1], f[2]
            state: dict[str, Any] = dict(drawing=self.drawing, net=self.net, path=self.path, revision=self.revision,
                         can_undo=bool(self.undo_stack), can_redo=bool(self.redo_stack), dirty=self.dirty,
                         recoverable=self.recoverable, doc=self.doc_id)
        text, payload = geometry_frames(**state)
        with self.lock:
            if self.revision == state["revision"]:
                self._frames = (state["revision"], text, payload)
        return text, payload

    def geometry(self, msg_id: int = 0) -> tuple[P.Geometry, bytes]:
        """The current geometry as a dataclass message and payload (Python API, tests)."""
        with self.lock:
            return geometry(self.drawing, net=self.net, path=self.path, revision=self.revision,
                            can_undo=bool(self.undo_stack), can_redo=bool(self.redo_stack),
                            msg_id=msg_id, dirty=self.dirty, recoverable=self.recoverable, doc=self.doc_id)


def load_drawing(workspace: Workspace, rel: str) -> tuple[Drawing, str]:
    """Read the drawing ``rel`` inside the workspace: (the drawing, its clean relative path); errors name ``rel``."""
    p = workspace.resolve(rel)
    rel_clean = workspace.relative(p)
    if p.is_dir():
        raise WorkspaceError(f"{rel_clean}: is a folder, not a drawing")
    if not p.is_file():
        raise WorkspaceError(f"no such file in the workspace: {rel!r}")
    fmt = _drawing_format(rel_clean)
    check_file_size(p, rel_clean)
    try:
        text = p.read_text(encoding="utf-8")
    except UnicodeDecodeError as e:
        raise FormatError(f"not a text file ({e.reason} at byte {e.start})", rel_clean) from None
    except OSError as e:
        raise WorkspaceError(f"{rel_clean}: cannot read ({e.strerror or e})") from None
    return fmt.reader(text, rel_clean), rel_clean


def example_drawing(name: str) -> Drawing:
    """The bundled drawing ``name`` (one of ``examples.names()``)."""
    from auszug import examples

    if name not in examples.names():
        raise WorkspaceError(f"no bundled example {name!r}; list_files names them")
    return read_drawing(name, examples.path(name).read_text(encoding="utf-8"))


def open_document(workspace: Workspace, rel: str, resume: str = "") -> Document:
    """Load ``rel`` (inside the workspace) as a new document; errors name ``rel``.

    Checks for an autosave that differs from the file (:attr:`Document.recoverable`).
    ``resume``: the id of the document a reconnecting tab showed; if that
    document wrote the autosave, the autosave is restored at once (an undoable
    edit) and the new document takes the id.
    """
    d, rel_clean = load_drawing(workspace, rel)
    doc = _built(workspace, d, rel_clean, "", rel_clean)
    if resume and check_doc_id(resume) and doc.autosave_owner() == resume and doc.autosave_file().is_file():
        a = doc.autosave_file()
        check_file_size(a)
        saved = read_drawing("autosave.json", a.read_text(encoding="utf-8"))
        doc.doc_id = resume
        if not _same_drawing(saved, doc.drawing):
            doc.replace_drawing(replace(saved, name=doc.drawing.name))
        return doc
    doc.check_recoverable()
    return doc


_DOC_ID = re.compile(r"[0-9a-f]{16}")


def check_doc_id(doc_id: str) -> str:
    """``doc_id`` if it is a document id (16 hex digits), else a :class:`WorkspaceError`."""
    if not _DOC_ID.fullmatch(doc_id):
        raise WorkspaceError(f"not a document id: {shown(doc_id)}")
    return doc_id


def resume_document(workspace: Workspace, doc_id: str, path: str = "") -> Document:
    """The document a reconnecting (or reloaded) tab showed, from the workspace and the autosaves.

    ``path``: the workspace file (:func:`open_document` with ``resume``).
    Else the unsaved document ``doc_id``'s autosave, as a dirty document with
    that id.

    Raises
    ------
    WorkspaceError
        Not a document id, or an unsaved document without an autosave.
    """
    check_doc_id(doc_id)
    if path:
        return open_document(workspace, path, resume=doc_id)
    folder = workspace.autosave_path(f"unsaved/{doc_id}").with_suffix("")
    found = sorted(p for p in folder.glob("*.json") if ".offered-" not in p.name) if folder.is_dir() else []
    if not found:
        raise WorkspaceError("the unsaved drawing of this tab is gone (no autosave of it); open it again")
    p = found[-1]
    check_file_size(p)
    name = p.name[: -len(".json")]
    saved = read_drawing("autosave.json", p.read_text(encoding="utf-8"))
    doc = _built(workspace, saved, "", name, name)
    doc.doc_id = doc_id
    doc.clean = Drawing((), name=name)   # unsaved: dirty until saved
    return doc


def _built(workspace: Workspace, d: Drawing, path: str, name: str, label: str) -> Document:
    try:
        return Document(workspace, d, path=path, name=name)
    except DrawingError as e:
        raise DrawingError(e.problem, f"{label}: {e.where}" if e.where else label) from None


def example_document(workspace: Workspace, name: str) -> Document:
    """A private (unsaved) document of the bundled drawing ``name`` (one of ``examples.names()``)."""
    d = example_drawing(name)
    doc = _built(workspace, d, "", PurePosixPath(name).name, name)
    doc.check_recoverable()
    return doc


def text_document(workspace: Workspace, name: str, text: str) -> Document:
    """A private document from the text of a file the user picked (``name`` gives the format)."""
    base = PurePosixPath(name.replace("\\", "/")).name
    check_file_name(base)
    d = read_drawing(base, text)
    doc = _built(workspace, d, "", base, base)
    doc.check_recoverable()
    return doc


def new_document(workspace: Workspace, name: str = "untitled") -> Document:
    """A private, empty drawing called ``name`` (a plain file name)."""
    check_file_name(name)
    doc = Document(workspace, Drawing((), name=name), name=name)
    doc.check_recoverable()
    return doc


@dataclass
class Session:
    """One document at a time for one user: the Python API without a server.

    The server shares documents between tabs (:class:`~auszug.studio.hub.Hub`);
    this is the same logic for a single caller (scripts, tests, benchmarks).
    """

    workspace: Workspace
    document: Document | None = field(default=None)

    @property
    def drawing(self) -> Drawing | None:
        """The open drawing (None before :meth:`open`)."""
        return None if self.document is None else self.document.drawing

    @property
    def path(self) -> str:
        """Workspace-relative path of the open drawing."""
        return "" if self.document is None else self.document.path

    @property
    def revision(self) -> int:
        """Revision of the open document (0: none)."""
        return 0 if self.document is None else self.document.revision

    @property
    def undo_stack(self) -> list[Drawing]:
        """The open document's undo stack."""
        return [] if self.document is None else self.document.undo_stack

    @property
    def redo_stack(self) -> list[Drawing]:
        """The open document's redo stack."""
        return [] if self.document is None else self.document.redo_stack

    def open(self, rel: str) -> None:
        """Load ``rel`` (inside the workspace) and forget the undo history."""
        self.document = open_document(self.workspace, rel)

    def save(self, rel: str = "") -> str:
        """Write the drawing (format by extension) inside the workspace; the relative path written."""
        return self._need().save(rel)

    def apply(self, op: P.EditOp) -> None:
        """Apply one edit message; on error nothing changes."""
        self._need().apply(op)

    def undo(self) -> None:
        """Go back one edit."""
        self._need().undo()

    def redo(self) -> None:
        """Redo the last undone edit."""
        self._need().redo()

    def geometry(self, msg_id: int = 0) -> tuple[P.Geometry, bytes]:
        """The current geometry message and payload."""
        return self._need().geometry(msg_id)

    def _need(self) -> Document:
        if self.document is None:
            raise AuszugError("no drawing is open: send an 'open' message first")
        return self.document
