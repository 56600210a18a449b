"""The studio's WebSocket protocol, defined once, here.

Every message is a frozen dataclass with a ``type`` tag. The browser's
TypeScript types (``web/src/protocol.ts``) are generated from this module by
:func:`typescript` (``python -m auszug.studio.protocol > web/src/protocol.ts``);
a test fails when the two drift apart.

Client -> server messages are JSON text frames; each may carry an ``id`` that
the reply echoes. Edits are one message per function of
:mod:`auszug.microarch.edit`. The server answers every message that changes
the drawing with a :class:`Geometry` message and its *payload*: little-endian
float32 data that the :class:`ArrayRef` fields of the geometry point into.
A message with a payload (the types in :data:`WITH_PAYLOAD`) travels as one
binary frame, see :func:`pack`; the others are JSON text frames. Replicas are
not re-sent copies: each basic piece comes once, with the 4x4 transforms of
its replicas (column-major, as three.js's ``Matrix4.fromArray`` reads them).

Examples
--------
>>> msg = decode('{"type": "set_apex_height", "curve": 0, "height": 2.5}')
>>> msg
SetApexHeight(curve=0, height=2.5, drag=0, id=0, type='set_apex_height')
>>> decode('{"type": "set_apex_height", "curve": "zero", "height": 2.5}')
Traceback (most recent call last):
...
auszug.studio.protocol.ProtocolError: set_apex_height.curve: expected an integer, got 'zero'
"""

from __future__ import annotations

import dataclasses
import json
import math
import types
from dataclasses import dataclass, field
from typing import Any, Callable, ClassVar, Literal, Union, get_args, get_origin, get_type_hints

from auszug.errors import AuszugError
from auszug.limits import LIMITS, shown
from auszug.microarch import edit
from auszug.microarch.model import Drawing

__all__ = [
    "PROTOCOL_VERSION",
    "MAX_MESSAGE_BYTES",
    "ProtocolError",
    "Open",
    "Save",
    "Undo",
    "Redo",
    "MoveVertex",
    "MoveHandle",
    "SetApexHeight",
    "SetPrc",
    "RecomputePrc",
    "SetLayerBottom",
    "SetDecoration",
    "SetPost",
    "SetSymmetry",
    "RemoveCurve",
    "DrawCurve",
    "SetLayer",
    "SetPrcAt",
    "SetPrcHeight",
    "AddLayer",
    "RemoveLayer",
    "ListFiles",
    "OpenExample",
    "OpenText",
    "NewDrawing",
    "Recover",
    "GetMesh",
    "GetLoops",
    "Export",
    "EditOp",
    "ArrayRef",
    "PieceGeometry",
    "IntersectionMarker",
    "CurveInfo",
    "Geometry",
    "MeshPiece",
    "MeshGeometry",
    "LoopInfo",
    "Loops",
    "Files",
    "Exported",
    "Saved",
    "Error",
    "WITH_PAYLOAD",
    "Resume",
    "GetThumbnail",
    "Thumbnail",
    "TraceryBuild",
    "TracerySave",
    "TraceryExport",
    "ListStyles",
    "TraceryField",
    "TraceryRegion",
    "TraceryGeometry",
    "TraceryRefused",
    "Styles",
    "CLIENT_MESSAGES",
    "SERVER_MESSAGES",
    "decode",
    "encode",
    "pack",
    "unpack",
    "typescript",
]

#: Bumped whenever a message changes shape; the client shows it on mismatch.
PROTOCOL_VERSION = 6
#: Largest client message the server reads (bytes); larger ones get an :class:`Error` reply.
MAX_MESSAGE_BYTES = 256 * 1024


class ProtocolError(AuszugError, ValueError):
    """A client message that is not valid JSON or not a known, well-formed message."""


XY = tuple[float, float]
Mirror = Literal["none", "first point", "last point", "y axis"]
Mark = Literal["ground", "apex", "free"]
#: Cross-sections of the members in the studio's looks and exports ("curves": polylines only).
Style = Literal["curves", "tube", "bar", "ribbon"]
#: Faces: none, every loop the network closes (automatic), or the loops picked by index.
FacesMode = Literal["none", "auto", "picked"]
#: What the tracery page exports: the window's mesh, its 2D drawing (exact arcs) or its 2D structure.
TraceryExportFormat = Literal["glb", "obj", "stl", "svg", "json"]
ExportFormat = Literal["glb", "obj", "stl", "ply", "svg", "json", "uc", "network.json", "dxf", "3dm"]


# ---------------------------------------------------------------- client -> server


@dataclass(frozen=True)
class Open:
    """Open a drawing; ``path`` is relative to the workspace folder."""

    path: str
    id: int = 0
    type: Literal["open"] = "open"


@dataclass(frozen=True)
class Save:
    """Save the drawing; ``path`` is relative to the workspace (empty: where it was opened)."""

    path: str = ""
    id: int = 0
    type: Literal["save"] = "save"


@dataclass(frozen=True)
class Undo:
    """Undo the last edit."""

    id: int = 0
    type: Literal["undo"] = "undo"


@dataclass(frozen=True)
class Redo:
    """Redo the last undone edit."""

    id: int = 0
    type: Literal["redo"] = "redo"


class EditOp:
    """Base of the edit messages: each applies one function of :mod:`auszug.microarch.edit`.

    The messages of dragging (points, handles, heights) carry ``drag``: a non-zero
    number the client picks per drag gesture. Consecutive edits with the same
    ``drag`` make one undo step (undo after a drag goes back to before it).
    """

    #: Fields of a message that are not parameters of its edit function.
    NOT_PARAMETERS: ClassVar[tuple[str, ...]] = ("id", "type", "drag")

    #: The edit function; called as ``fn(drawing, **fields)`` without ``id`` and ``type``.
    fn: ClassVar[Callable[..., Drawing]]
    #: The request number the reply echoes (a field of every edit message).
    id: int

    #: Structural edits (a new curve, a curve to another layer, a removed curve) keep the apex of
    #: every curve they leave alone: a curve whose apex follows the next layer's bottom by default
    #: (no height of its own) gets its old apex written down when the edit would move it, so
    #: drawing the first curve of layer 1 never silently raises a layer-0 curve.
    KEEPS_APEXES: ClassVar[bool] = False

    def apply(self, drawing: Drawing) -> Drawing:
        """The edited drawing (the input is not changed)."""
        kw = {f.name: getattr(self, f.name) for f in dataclasses.fields(self)  # type: ignore[arg-type]  # edit messages are dataclasses
              if f.name not in EditOp.NOT_PARAMETERS}
        out = type(self).fn(drawing, **kw)
        return _keep_apexes(drawing, out) if self.KEEPS_APEXES else out


def _keep_apexes(before: Drawing, after: Drawing) -> Drawing:
    """``after`` with the apex of every curve it shares (the same object) with ``before`` kept."""
    old = {id(c): i for i, c in enumerate(before.curves)}
    b0, b1 = before.bottoms(), after.bottoms()
    for j, c in enumerate(after.curves):
        i = old.get(id(c))
        if i is None or c.height is not None:
            continue
        h0 = before.apex_height(i, b0)
        if after.apex_height(j, b1) != h0:
            after = after.with_curve(j, c.with_(height=h0))
            b1 = after.bottoms()   # derived bottoms follow the heights written down
    return after


@dataclass(frozen=True)
class MoveVertex(EditOp):
    """:func:`auszug.microarch.edit.move_vertex`."""

    curve: int
    vertex: int
    xy: XY
    drag: int = 0
    id: int = 0
    type: Literal["move_vertex"] = "move_vertex"
    fn = staticmethod(edit.move_vertex)


@dataclass(frozen=True)
class MoveHandle(EditOp):
    """:func:`auszug.microarch.edit.move_handle`."""

    curve: int
    segment: int
    handle: int
    xy: XY
    drag: int = 0
    id: int = 0
    type: Literal["move_handle"] = "move_handle"
    fn = staticmethod(edit.move_handle)


@dataclass(frozen=True)
class SetApexHeight(EditOp):
    """:func:`auszug.microarch.edit.set_apex_height`."""

    curve: int
    height: float
    drag: int = 0
    id: int = 0
    type: Literal["set_apex_height"] = "set_apex_height"
    fn = staticmethod(edit.set_apex_height)


@dataclass(frozen=True)
class SetPrc(EditOp):
    """:func:`auszug.microarch.edit.set_prc` (``fraction`` null: automatic)."""

    curve: int
    fraction: float | None
    segment: int = 0
    id: int = 0
    type: Literal["set_prc"] = "set_prc"
    fn = staticmethod(edit.set_prc)


@dataclass(frozen=True)
class RecomputePrc(EditOp):
    """:func:`auszug.microarch.edit.recompute_prc` (``curves`` null: all)."""

    curves: list[int] | None = None
    id: int = 0
    type: Literal["recompute_prc"] = "recompute_prc"
    fn = staticmethod(edit.recompute_prc)


@dataclass(frozen=True)
class SetLayerBottom(EditOp):
    """:func:`auszug.microarch.edit.set_layer_bottom`."""

    layer: int
    z: float
    drag: int = 0
    id: int = 0
    type: Literal["set_layer_bottom"] = "set_layer_bottom"
    fn = staticmethod(edit.set_layer_bottom)


@dataclass(frozen=True)
class SetDecoration(EditOp):
    """:func:`auszug.microarch.edit.set_decoration`."""

    curve: int
    on: bool
    at: float | None = None
    drag: int = 0
    id: int = 0
    type: Literal["set_decoration"] = "set_decoration"
    fn = staticmethod(edit.set_decoration)


@dataclass(frozen=True)
class SetPost(EditOp):
    """:func:`auszug.microarch.edit.set_post` (``top`` null: no post)."""

    curve: int
    top: float | None
    drag: int = 0
    id: int = 0
    type: Literal["set_post"] = "set_post"
    fn = staticmethod(edit.set_post)


@dataclass(frozen=True)
class SetSymmetry(EditOp):
    """:func:`auszug.microarch.edit.set_symmetry` (null: unchanged)."""

    curve: int
    fold: int | None = None
    mirror: Mirror | None = None
    id: int = 0
    type: Literal["set_symmetry"] = "set_symmetry"
    fn = staticmethod(edit.set_symmetry)


@dataclass(frozen=True)
class RemoveCurve(EditOp):
    """:func:`auszug.microarch.edit.remove_curve`."""

    curve: int
    id: int = 0
    type: Literal["remove_curve"] = "remove_curve"
    fn = staticmethod(edit.remove_curve)
    KEEPS_APEXES = True


@dataclass(frozen=True)
class DrawCurve(EditOp):
    """:func:`auszug.microarch.edit.draw_curve`: append a curve drawn by clicks.

    ``handles`` has one list per segment: [] line, [h] arc (tangent at the
    segment's first point aims at h), [h1, h2] cubic Bezier.
    """

    vertices: list[XY]
    handles: list[list[XY]]
    marks: list[Mark]
    fold: int = 1
    mirror: Mirror = "none"
    layer: int = 0
    id: int = 0
    type: Literal["draw_curve"] = "draw_curve"
    fn = staticmethod(edit.draw_curve)
    KEEPS_APEXES = True


@dataclass(frozen=True)
class SetLayer(EditOp):
    """:func:`auszug.microarch.edit.set_layer`: move a curve to another layer."""

    curve: int
    layer: int
    id: int = 0
    type: Literal["set_layer"] = "set_layer"
    fn = staticmethod(edit.set_layer)
    KEEPS_APEXES = True


@dataclass(frozen=True)
class SetPrcAt(EditOp):
    """:func:`auszug.microarch.edit.set_prc_at`: the top-view point nearest ``point`` becomes the PRC."""

    curve: int
    point: XY
    segment: int = 0
    id: int = 0
    type: Literal["set_prc_at"] = "set_prc_at"
    fn = staticmethod(edit.set_prc_at)


@dataclass(frozen=True)
class SetPrcHeight(EditOp):
    """:func:`auszug.microarch.edit.set_prc_height`: drag the PRC in the side view (the apex follows)."""

    curve: int
    z: float
    segment: int = 0
    drag: int = 0
    id: int = 0
    type: Literal["set_prc_height"] = "set_prc_height"
    fn = staticmethod(edit.set_prc_height)


@dataclass(frozen=True)
class AddLayer(EditOp):
    """:func:`auszug.microarch.edit.add_layer` (``bottom`` null: the highest apex below)."""

    bottom: float | None = None
    id: int = 0
    type: Literal["add_layer"] = "add_layer"
    fn = staticmethod(edit.add_layer)


@dataclass(frozen=True)
class RemoveLayer(EditOp):
    """:func:`auszug.microarch.edit.remove_layer` (and its curves)."""

    layer: int
    id: int = 0
    type: Literal["remove_layer"] = "remove_layer"
    fn = staticmethod(edit.remove_layer)


@dataclass(frozen=True)
class ListFiles:
    """List the drawings of the workspace and the bundled examples (answered by :class:`Files`)."""

    id: int = 0
    type: Literal["list_files"] = "list_files"


@dataclass(frozen=True)
class GetThumbnail:
    """Ask for a gallery card's picture (answered by :class:`Thumbnail`).

    The top view of workspace file ``path`` or bundled ``example``: exactly one of them.
    """

    path: str = ""
    example: str = ""
    id: int = 0
    type: Literal["get_thumbnail"] = "get_thumbnail"


@dataclass(frozen=True)
class OpenExample:
    """Open a bundled drawing, e.g. ``web/U.XI.28.uc`` (a name from :class:`Files`); saving asks for a name."""

    name: str
    id: int = 0
    type: Literal["open_example"] = "open_example"


@dataclass(frozen=True)
class OpenText:
    """Open the text of a local file the user picked in the browser (``name`` gives the format)."""

    name: str
    text: str
    id: int = 0
    type: Literal["open_text"] = "open_text"


@dataclass(frozen=True)
class NewDrawing:
    """Start an empty drawing called ``name`` (saved as ``name`` + .json unless told otherwise)."""

    name: str = "untitled"
    id: int = 0
    type: Literal["new_drawing"] = "new_drawing"


@dataclass(frozen=True)
class Recover:
    """Replace the open drawing by its autosaved version (offered by ``Geometry.recoverable``)."""

    id: int = 0
    type: Literal["recover"] = "recover"


@dataclass(frozen=True)
class Resume:
    """Show document ``doc`` (``Geometry.doc``) again: a tab that reconnects or reloads.

    The document itself if the server still has it open; else the workspace
    file ``path`` (its autosave restored if this document wrote it), or the
    autosave of the unsaved document ``doc``.
    """

    doc: str
    path: str = ""
    id: int = 0
    type: Literal["resume"] = "resume"


@dataclass(frozen=True)
class GetMesh:
    """Ask for the members (and faces) of the current drawing (answered by :class:`MeshGeometry`).

    ``loops`` are indices into the last :class:`Loops` reply, used with ``faces="picked"``.
    ``size`` null: the default member size (1.2 % of the bounding-box diagonal).
    """

    style: Style = "bar"
    faces: FacesMode = "none"
    loops: list[int] = field(default_factory=list)
    size: float | None = None
    segments: int = 64
    id: int = 0
    type: Literal["get_mesh"] = "get_mesh"


@dataclass(frozen=True)
class GetLoops:
    """Ask for the closed loops of the network that faces can fill (answered by :class:`Loops`)."""

    id: int = 0
    type: Literal["get_loops"] = "get_loops"


@dataclass(frozen=True)
class Export:
    """Export the current drawing; answered by :class:`Exported` and the file's bytes.

    Mesh formats (glb, obj, stl, ply) use ``style``/``faces``/``loops`` as
    :class:`GetMesh`; ``solid`` unites everything into one watertight solid.
    ``colors`` are ``#rrggbb`` per basic curve (glb, obj). svg: top and side
    views; json / uc: the drawing; network.json: the 3D curve network; dxf / 3dm:
    the curve network for CAD programs. ``segments`` (steps along each member,
    1..1000; null: 200, 64 for a solid) and ``around`` (points around a tube's
    or bar's profile, 3..64; null: 40 for tubes, 4 for bars and ribbons) set a
    mesh export's resolution.
    """

    format: ExportFormat
    style: Style = "bar"
    faces: FacesMode = "none"
    loops: list[int] = field(default_factory=list)
    solid: bool = False
    colors: list[str] = field(default_factory=list)
    segments: int | None = None
    around: int | None = None
    id: int = 0
    type: Literal["export"] = "export"


@dataclass(frozen=True)
class TraceryBuild:
    """Build a window (the tracery page); answered by :class:`TraceryGeometry` or :class:`TraceryRefused`.

    ``style``: a built-in style name or ``"prototype"``; or ``path``: a style
    file (.toml/.json) in the workspace. ``values``: ``KEY=VALUE`` overrides as
    ``auszug tracery --set`` reads them (``params.excess=1.2``,
    ``circle.foils=6``), plus ``depth=N`` (refine the sub-arches N levels) and
    ``subdivide=K`` (profile subdivision of exports). The server keeps no
    tracery state: a refused set changes nothing.
    """

    style: str = "fig20a"
    path: str = ""
    values: list[str] = field(default_factory=list)
    id: int = 0
    type: Literal["tracery_build"] = "tracery_build"


@dataclass(frozen=True)
class TracerySave:
    """Save the window's style (as :class:`TraceryBuild` gives it) to workspace file ``target`` (.toml or .json)."""

    target: str
    style: str = "fig20a"
    path: str = ""
    values: list[str] = field(default_factory=list)
    id: int = 0
    type: Literal["tracery_save"] = "tracery_save"


@dataclass(frozen=True)
class TraceryExport:
    """Export the window: glb/obj/stl (the finished watertight mesh), svg (2D, exact arcs), json (2D structure)."""

    format: TraceryExportFormat
    style: str = "fig20a"
    path: str = ""
    values: list[str] = field(default_factory=list)
    id: int = 0
    type: Literal["tracery_export"] = "tracery_export"


@dataclass(frozen=True)
class ListStyles:
    """List the built-in tracery styles and the workspace's style files (answered by :class:`Styles`)."""

    id: int = 0
    type: Literal["list_styles"] = "list_styles"


# ---------------------------------------------------------------- server -> client


@dataclass(frozen=True)
class ArrayRef:
    """A float32 array in the payload of a :class:`Geometry` message.

    ``offset`` counts float32 values (not bytes) from the payload's start;
    ``shape`` is row-major, e.g. ``[n, 3]`` for points, ``[k, 16]`` for transforms.
    """

    offset: int
    shape: list[int]
    dtype: Literal["f4", "u4"] = "f4"


@dataclass(frozen=True)
class PieceGeometry:
    """One basic piece of the network with the transforms of its replicas.

    ``points`` is (n, 3), the piece of the basic curve itself; ``transforms`` is
    (k, 16), one column-major 4x4 matrix per replica (the identity first), so
    that replica j is ``transforms[j] @ points``. ``labels`` name the replicas
    (``r0``, ``r0m``, ...). ``prc`` is the basic piece's point of reverse
    curvature (x, y, z), if it has one; its replicas use the same transforms.
    ``side`` is (n, 2): the side view of ``points``, (s, z) with s the top-view
    arc length from the piece's start. ``prc_s`` is the PRC's s.
    """

    basic: int
    segment: int
    layer: int
    kind: str
    points: ArrayRef
    side: ArrayRef
    transforms: ArrayRef
    labels: list[str]
    prc: list[float] | None
    prc_s: float | None


@dataclass(frozen=True)
class IntersectionMarker:
    """A top-view intersection of basic segment (curve, segment) with a replica of another.

    ``true``: the 3D curves meet there. Markers are given for the basic curve;
    the client replicates them with that curve's transforms if it wants all.
    """

    curve: int
    segment: int
    other_curve: int
    other_segment: int
    replica: str
    point: XY
    true: bool


@dataclass(frozen=True)
class CurveInfo:
    """The editable definition of one basic curve (what the design tools show).

    ``handles`` per segment as in :class:`DrawCurve`; ``mirror`` is the axis rule
    (``"fixed"``: a mirror whose axis follows no point); ``axis`` the mirror axis
    direction (null: no mirror); ``apex`` the absolute apex height, ``bottom``
    its layer's bottom; ``prc`` the stored fraction per segment (null: automatic).
    ``replicas`` are the linear parts of the curve's symmetry group about
    ``center`` (row-major 2x2 ``[a, b, c, d]``: (x, y) -> (a x + b y, c x + d y)),
    one per element in the order of ``labels`` (``r0`` = identity, ``r0m``,
    ``r1``, ...), exactly the network's ``groups[i].matrices()``: replica k of a
    top-view point p is ``center + M_k (p - center)``. ``color`` is the curve's
    colour from :data:`auszug.formats.palette.PALETTE` (``#RRGGBB``).
    """

    vertices: list[XY]
    handles: list[list[XY]]
    marks: list[str]
    fold: int
    mirror: str
    axis: list[float] | None
    center: XY
    layer: int
    apex: float
    bottom: float
    prc: list[float | None]
    decoration: bool
    decoration_at: float | None
    post_top: float | None
    name: str
    replicas: list[list[float]]
    labels: list[str]
    color: str


@dataclass(frozen=True)
class Geometry:
    """The drawing's network after an open, edit, undo or redo; it has a payload.

    Sent to every tab that has the document open (``id`` is the requester's,
    0 for the others). ``dirty``: edited since the last save. ``recoverable``:
    an autosave newer than the file exists (send :class:`Recover`), else "";
    it stays offered (and its file untouched) until recovered, whatever is
    edited meanwhile. ``doc``: the document's id (for :class:`Resume`).
    ``layers`` are the bottoms of all layers.
    """

    revision: int
    path: str
    name: str
    n_curves: int
    n_replicas: int
    pieces: list[PieceGeometry]
    intersections: list[IntersectionMarker]
    curves: list[CurveInfo]
    layers: list[float]
    bounds: list[float]
    can_undo: bool
    can_redo: bool
    dirty: bool
    recoverable: str
    doc: str
    binary_floats: int
    id: int = 0
    protocol: int = PROTOCOL_VERSION
    type: Literal["geometry"] = "geometry"


@dataclass(frozen=True)
class MeshPiece:
    """A triangle mesh and where it goes: ``transforms`` (k, 16) place its k copies.

    ``positions`` (n, 3) f4, ``indices`` (m, 3) u4; ``basic`` the basic curve
    (-1 for faces, whose mesh is sent with all copies and the identity).
    """

    basic: int
    name: str
    positions: ArrayRef
    indices: ArrayRef
    transforms: ArrayRef


@dataclass(frozen=True)
class MeshGeometry:
    """Members and faces of the drawing at ``revision``; it has a payload."""

    revision: int
    style: str
    pieces: list[MeshPiece]
    faces: int
    converged: bool
    residual: float
    binary_floats: int
    id: int = 0
    type: Literal["mesh"] = "mesh"


@dataclass(frozen=True)
class LoopInfo:
    """One closed loop of the network: ``boundary`` (n, 3) f4 polyline, ``centre`` (x, y, z)."""

    index: int
    boundary: ArrayRef
    centre: list[float]
    rim: bool


@dataclass(frozen=True)
class Loops:
    """The loops faces can fill at ``revision``; it has a payload."""

    revision: int
    loops: list[LoopInfo]
    binary_floats: int
    id: int = 0
    type: Literal["loops"] = "loops"


@dataclass(frozen=True)
class Files:
    """Drawings in the workspace (relative paths) and the bundled examples (names for :class:`OpenExample`)."""

    workspace: list[str]
    examples: list[str]
    #: One line per workspace entry left out because it could not be read (a link loop...).
    notes: list[str] = field(default_factory=list)
    id: int = 0
    type: Literal["files"] = "files"


@dataclass(frozen=True)
class Thumbnail:
    """A drawing's top view as a small SVG document (``svg``), for :class:`GetThumbnail`'s ``path`` or ``example``."""

    svg: str
    path: str = ""
    example: str = ""
    id: int = 0
    type: Literal["thumbnail"] = "thumbnail"


@dataclass(frozen=True)
class Exported:
    """An exported file: ``name`` (suggested file name), ``mime``; the payload is the file (``size`` bytes)."""

    name: str
    mime: str
    size: int
    id: int = 0
    type: Literal["exported"] = "exported"


@dataclass(frozen=True)
class Saved:
    """The drawing was written to ``path`` (relative to the workspace)."""

    path: str
    id: int = 0
    type: Literal["saved"] = "saved"


@dataclass(frozen=True)
class Error:
    """A message could not be carried out; the session is unchanged."""

    message: str
    id: int = 0
    type: Literal["error"] = "error"


@dataclass(frozen=True)
class TraceryField:
    """One editable value of the tracery page: ``key`` (as :class:`TraceryBuild` ``values`` take it).

    ``kind``: number, integer, bool or choice (``options``); ``value`` the
    style's current value (a profile given inline shows as ``"(inline)"``).
    """

    key: str
    label: str
    group: str
    kind: Literal["number", "integer", "bool", "choice"]
    value: float | bool | str
    options: list[str]


@dataclass(frozen=True)
class TraceryRegion:
    """One region of the window: ``d`` its exact border as SVG path data (y up: the page flips it)."""

    id: str
    group: str
    depth: int
    role: str
    d: str


@dataclass(frozen=True)
class TraceryGeometry:
    """A built window; it has a payload: the preview mesh (``positions`` (n, 3) f4, ``indices`` (m, 3) u4).

    The preview mesh is the window's front half (``y <= 0``); its back half is
    the mirror image in ``y = 0`` (:func:`auszug.tracery.preview.preview_mesh`).
    ``bounds`` [xmin, ymin, xmax, ymax] of the 2D structure; ``mesh_bounds``
    [xmin, ymin, zmin, xmax, ymax, zmax] of the preview mesh (its front half). ``values``: the
    overrides as the server understood them (canonical ``KEY=VALUE``).
    ``build_ms``, ``mesh_ms``: the server's time for the structure and the mesh; ``cached``: they
    came from the server's cache of recently built windows (the times are then the original build's).
    """

    style: str
    path: str
    name: str
    values: list[str]
    fields: list[TraceryField]
    regions: list[TraceryRegion]
    n_lights: int
    depth: int
    bounds: list[float]
    mesh_bounds: list[float]
    positions: ArrayRef
    indices: ArrayRef
    build_ms: float
    mesh_ms: float
    binary_floats: int
    cached: bool = False
    id: int = 0
    type: Literal["tracery"] = "tracery"


@dataclass(frozen=True)
class TraceryRefused:
    """A tracery value was refused (nothing changed): ``key`` the value the message blames, if known."""

    key: str
    message: str
    id: int = 0
    type: Literal["tracery_refused"] = "tracery_refused"


@dataclass(frozen=True)
class Styles:
    """Built-in tracery styles (``builtin`` with one-line ``descriptions``) and the workspace's style files."""

    builtin: list[str]
    descriptions: list[str]
    workspace: list[str]
    notes: list[str] = field(default_factory=list)
    id: int = 0
    type: Literal["styles"] = "styles"


CLIENT_MESSAGES: tuple[type, ...] = (
    Open, Resume, Save, Undo, Redo, MoveVertex, MoveHandle, SetApexHeight, SetPrc, RecomputePrc,
    SetLayerBottom, SetDecoration, SetPost, SetSymmetry, RemoveCurve,
    DrawCurve, SetLayer, SetPrcAt, SetPrcHeight, AddLayer, RemoveLayer,
    ListFiles, OpenExample, OpenText, NewDrawing, Recover, GetMesh, GetLoops, Export, GetThumbnail,
    TraceryBuild, TracerySave, TraceryExport, ListStyles,
)
SERVER_MESSAGES: tuple[type, ...] = (Geometry, MeshGeometry, Loops, Files, Exported, Saved, Error, Thumbnail,
                                     TraceryGeometry, TraceryRefused, Styles)
#: Server message types that carry a payload: each is sent as one binary frame (:func:`pack`).
WITH_PAYLOAD: tuple[str, ...] = ("geometry", "mesh", "loops", "exported", "tracery")
#: Nested types that appear inside server messages, in the order the TypeScript lists them.
_NESTED: tuple[type, ...] = (ArrayRef, PieceGeometry, IntersectionMarker, CurveInfo, MeshPiece, LoopInfo,
                              TraceryField, TraceryRegion)

_BY_TYPE: dict[str, type] = {
    f.default: c
    for c in CLIENT_MESSAGES
    for f in dataclasses.fields(c)
    if f.name == "type" and isinstance(f.default, str)
}


# ---------------------------------------------------------------- decoding


def _is_union(tp: Any) -> bool:
    return get_origin(tp) in (Union, types.UnionType)


def _convert(value: Any, tp: Any, where: str) -> Any:
    """Check ``value`` (parsed JSON) against annotation ``tp`` and return it typed."""
    if _is_union(tp):
        args = get_args(tp)
        if value is None and type(None) in args:
            return None
        rest = [a for a in args if a is not type(None)]
        if len(rest) == 1:
            return _convert(value, rest[0], where)
        raise ProtocolError(f"{where}: unsupported union")  # pragma: no cover - not used
    origin = get_origin(tp)
    if tp is bool:
        if not isinstance(value, bool):
            raise ProtocolError(f"{where}: expected true or false, got {shown(value)}")
        return value
    if tp is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise ProtocolError(f"{where}: expected an integer, got {shown(value)}")
        return value
    if tp is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise ProtocolError(f"{where}: expected a finite number, got {shown(value)}")
        return float(value)
    if tp is str:
        if not isinstance(value, str):
            raise ProtocolError(f"{where}: expected a string, got {shown(value)}")
        return value
    if origin is Literal:
        if value not in get_args(tp):
            opts = ", ".join(repr(a) for a in get_args(tp))
            raise ProtocolError(f"{where}: expected one of {opts}, got {shown(value)}")
        return value
    if origin is tuple:
        args = get_args(tp)
        if not isinstance(value, list) or len(value) != len(args):
            raise ProtocolError(f"{where}: expected a list of {len(args)} values, got {shown(value)}")
        return tuple(_convert(v, a, f"{where}[{i}]") for i, (v, a) in enumerate(zip(value, args, strict=True)))
    if origin is list:
        (arg,) = get_args(tp)
        if not isinstance(value, list):
            raise ProtocolError(f"{where}: expected a list, got {shown(value)}")
        return [_convert(v, arg, f"{where}[{i}]") for i, v in enumerate(value)]
    raise ProtocolError(f"{where}: unsupported field type {tp!r}")  # pragma: no cover


def decode(text: str | bytes) -> Any:
    """Parse one client message (JSON text) into its dataclass.

    Raises
    ------
    ProtocolError
        Not JSON, not an object, an unknown ``type``, a missing or unknown field,
        or a field of the wrong type; the message says which.
    """
    try:
        obj = json.loads(text)
    except (ValueError, UnicodeDecodeError) as e:
        raise ProtocolError(f"not valid JSON ({str(e)[:LIMITS.quoted]})") from None
    except RecursionError:   # "[[[[...": Python's parser recurses once per level
        raise ProtocolError("not valid JSON (nested too deeply for a message)") from None
    if not isinstance(obj, dict):
        raise ProtocolError("a message must be a JSON object with a 'type'")
    kind = obj.get("type")
    cls = _BY_TYPE.get(kind) if isinstance(kind, str) else None
    if cls is None:
        raise ProtocolError(f"unknown message type {shown(kind)}; expected one of {', '.join(sorted(_BY_TYPE))}")
    hints, fields = _schema(cls)
    unknown = sorted(set(obj) - fields.keys())
    if unknown:
        raise ProtocolError(f"{kind}: unknown field(s) {', '.join(unknown)}")
    kw = {}
    for name, required in fields.items():
        if name in obj:
            kw[name] = _convert(obj[name], hints[name], f"{kind}.{name}")
        elif required:
            raise ProtocolError(f"{kind}: missing field {name!r}")
    return cls(**kw)


_SCHEMAS: dict[type, tuple[dict[str, Any], dict[str, bool]]] = {}


def _schema(cls: type) -> tuple[dict[str, Any], dict[str, bool]]:
    """Field types and "required" flags of a message class (``get_type_hints`` is slow: cached)."""
    s = _SCHEMAS.get(cls)
    if s is None:
        req = {f.name: f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING
               for f in dataclasses.fields(cls)}
        s = _SCHEMAS[cls] = (get_type_hints(cls), req)
    return s


def encode(msg: Any) -> str:
    """A server message as JSON text."""
    return json.dumps(dataclasses.asdict(msg), separators=(",", ":"), allow_nan=False)


def pack(text: str, payload: bytes) -> bytes:
    """One binary frame for a message with a payload.

    Layout: the JSON's length ``n`` in bytes (uint32, little-endian), the
    JSON as UTF-8 padded with spaces to a multiple of 4 bytes (``n`` counts
    the padding), then the payload. The payload thus starts 4-byte aligned
    at byte ``4 + n``, where float32 and uint32 views of it can be made.
    One frame instead of a JSON frame and a binary frame: the browser wakes
    once per reply, not twice.

    Parameters
    ----------
    text : str
        The message's JSON (:func:`encode`).
    payload : bytes
        Its binary data (float32/uint32 arrays, or an exported file).

    Returns
    -------
    bytes
        ``4 + n + len(payload)`` bytes.
    """
    head = text.encode("utf-8")
    pad = b" " * (-len(head) % 4)
    return b"".join(((len(head) + len(pad)).to_bytes(4, "little"), head, pad, payload))


def unpack(frame: bytes) -> tuple[dict[str, Any], bytes]:
    """The JSON message and the payload of a frame made by :func:`pack`.

    Raises
    ------
    ProtocolError
        If the frame is shorter than its header says.
    """
    if len(frame) < 4:
        raise ProtocolError(f"binary frame of {len(frame)} bytes has no header")
    n = int.from_bytes(frame[:4], "little")
    if n % 4 or 4 + n > len(frame):
        raise ProtocolError(f"binary frame of {len(frame)} bytes cannot hold a message of {n} bytes")
    return json.loads(bytes(frame[4:4 + n])), bytes(frame[4 + n:])


# ---------------------------------------------------------------- TypeScript


def _ts_type(tp: Any) -> str:
    if _is_union(tp):
        return " | ".join(_ts_type(a) for a in get_args(tp))
    if tp is type(None):
        return "null"
    if tp in (int, float):
        return "number"
    if tp is str:
        return "string"
    if tp is bool:
        return "boolean"
    origin = get_origin(tp)
    if origin is Literal:
        return " | ".join(json.dumps(a) for a in get_args(tp))
    if origin is tuple:
        return "[" + ", ".join(_ts_type(a) for a in get_args(tp)) + "]"
    if origin is list:
        inner = _ts_type(get_args(tp)[0])
        return f"({inner})[]" if "|" in inner else f"{inner}[]"
    if isinstance(tp, type) and dataclasses.is_dataclass(tp):
        return tp.__name__
    raise TypeError(f"no TypeScript for {tp!r}")  # pragma: no cover


def _ts_interface(cls: type, optional_defaults: bool) -> str:
    doc = " ".join((cls.__doc__ or "").split())
    lines = [f"/** {doc} */", f"export interface {cls.__name__} {{"]
    hints = get_type_hints(cls)
    for f in dataclasses.fields(cls):
        has_default = f.default is not dataclasses.MISSING or f.default_factory is not dataclasses.MISSING
        opt = "?" if optional_defaults and has_default and f.name != "type" else ""
        lines.append(f"  {f.name}{opt}: {_ts_type(hints[f.name])};")
    lines.append("}")
    return "\n".join(lines)


def typescript() -> str:
    """The TypeScript mirror of this module (the contents of ``web/src/protocol.ts``)."""
    out = [
        "// GENERATED by `python -m auszug.studio.protocol` from src/auszug/studio/protocol.py.",
        "// Do not edit: change the Python and regenerate (`make protocol`); a test fails on drift.",
        "",
        f"export const PROTOCOL_VERSION = {PROTOCOL_VERSION};",
        f"export const MAX_MESSAGE_BYTES = {MAX_MESSAGE_BYTES};",
        "export const WITH_PAYLOAD: readonly string[] = "
        + json.dumps(list(WITH_PAYLOAD)) + ";",
        "",
    ]
    for cls in CLIENT_MESSAGES:
        out += [_ts_interface(cls, optional_defaults=True), ""]
    for cls in _NESTED + SERVER_MESSAGES:
        out += [_ts_interface(cls, optional_defaults=False), ""]
    out.append("export type ClientMessage =\n  | " + "\n  | ".join(c.__name__ for c in CLIENT_MESSAGES) + ";")
    out.append("")
    out.append("export type ServerMessage = " + " | ".join(c.__name__ for c in SERVER_MESSAGES) + ";")
    out.append("")
    return "\n".join(out)


if __name__ == "__main__":  # pragma: no cover
    import sys

    sys.stdout.write(typescript())
