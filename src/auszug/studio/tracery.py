"""The studio's tracery page: windows built from a style and the page's values, stateless.

The page sends the whole state with every message (a style, or a style file
of the workspace, and its ``KEY=VALUE`` overrides); the server validates it
with the same code as ``auszug tracery`` (:meth:`Style.with_overrides`,
:func:`~auszug.tracery.refine`, :func:`~auszug.tracery.build`) and answers with
the window's exact 2D regions and a preview mesh
(:func:`auszug.tracery.preview.preview_mesh`). A refused value changes
nothing, since the server keeps no tracery state; undo and redo are the
page's (a list of states). The last :data:`CACHE_WINDOWS` built windows are
remembered by their style's value (the complete style table), so undo, redo
and a value typed again come back without a build: a memo of a pure
function, bounded in count and in bytes (:data:`CACHE_BYTES`).

Examples
--------
>>> from auszug.studio.tracery import window_style, build_message
>>> st = window_style(None, "fig20b", "", ["params.excess=1.0", "circle.foils=5"])
>>> st.params.excess, st.circle.foils
(1.0, 5)
>>> msg, payload = build_message(st, "fig20b", "", ["params.excess=1.0"], msg_id=3)
>>> msg.n_lights, len(msg.regions), msg.id
(7, 9, 3)
>>> len(payload) == 4 * msg.binary_floats
True
"""

from __future__ import annotations

import dataclasses
import json
import math
import threading
import time
from collections import OrderedDict
from functools import lru_cache
from pathlib import Path
from typing import TYPE_CHECKING, Any

from auszug.errors import AuszugError
from auszug.studio import protocol as P
from auszug.tracery import ParameterError, build, builtin_style, builtin_styles, load_style, refine, style_data
from auszug.tracery import whole_number as integer
from auszug.tracery.preview import preview_mesh
from auszug.tracery.style import (
    ARCH_DECORATIONS,
    CIRCLE_DECORATIONS,
    FILLET_DECORATIONS,
    MAX_NESTING,
    SUB_ARCH_DECORATIONS,
    Style,
    builtin_profiles,
    parse_overrides,
)

if TYPE_CHECKING:
    from auszug.studio.session import Workspace

__all__ = ["FIELDS", "STYLE_SUFFIXES", "CACHE_WINDOWS", "CACHE_BYTES", "WINDOWS", "WindowCache", "style_key",
           "window_style", "build_message", "style_text", "save_style",
           "export_window", "style_files", "split_values", "svg_path", "tracery_text"]

#: Endings of style files the page opens and saves.
STYLE_SUFFIXES = (".toml", ".json")
#: Profile subdivision steps of exports (window_mesh's subdivide).
MAX_SUBDIVIDE = 4
#: Most override values one message may carry.
MAX_VALUES = 64
#: Built windows the server remembers (by the style's value), the least recently used dropped first.
CACHE_WINDOWS = 24
#: ... and at most this many bytes of them (preview meshes and SVG path texts; Fig. 20h is about 0.3 MB).
CACHE_BYTES = 64 * 2**20

_ORIENT = ("standing", "lying")
#: The page's fields: (key, label, group, kind, choices). Profiles list the built-in ones.
FIELDS: tuple[tuple[str, str, str, str, tuple[str, ...]], ...] = (
    ("params.span", "span", "window", "number", ()),
    ("params.height", "height", "window", "number", ()),
    ("params.excess", "excess", "window", "number", ()),
    ("params.drop", "drop", "window", "number", ()),
    ("params.outer", "outer", "window", "number", ()),
    ("params.inner", "inner", "window", "number", ()),
    ("depth", "depth of recursion", "window", "integer", ()),
    ("arch.decoration", "arch", "decoration", "choice", ARCH_DECORATIONS),
    ("sub-arch.decoration", "sub-arches", "decoration", "choice", SUB_ARCH_DECORATIONS),
    ("circle.decoration", "circle", "decoration", "choice", CIRCLE_DECORATIONS),
    ("fillet.decoration", "fillets", "decoration", "choice", FILLET_DECORATIONS),
    ("circle.foils", "foils", "rosette", "integer", ()),
    ("circle.pointed", "pointed foils", "rosette", "bool", ()),
    ("circle.displacement", "displacement", "rosette", "number", ()),
    ("circle.orientation", "orientation", "rosette", "choice", _ORIENT),
    ("arch.profile", "arch", "profiles", "choice", ()),
    ("sub-arch.profile", "sub-arches", "profiles", "choice", ()),
    ("circle.profile", "circle", "profiles", "choice", ()),
    ("circle.foil-profile", "rosette", "profiles", "choice", ()),
    ("fillet.profile", "fillets", "profiles", "choice", ()),
    ("wall.profile", "wall reveal", "profiles", "choice", ()),
    ("wall.thickness", "thickness", "wall", "number", ()),
    ("wall.slab", "tracery plate", "wall", "number", ()),
    ("wall.margin", "margin", "wall", "number", ()),
    ("subdivide", "profile subdivision (export)", "wall", "integer", ()),
)
_PAGE_KEYS = ("depth", "subdivide")


def split_values(values: list[str]) -> tuple[dict[str, Any], int | None, int]:
    """``KEY=VALUE`` items -> (style overrides, depth or None, subdivide).

    Values are read as ``auszug tracery --set`` reads them (TOML values, else
    plain strings); a later item overrides an earlier one of the same key.

    Raises
    ------
    ParameterError
        For an item without ``=``, too many items, or a bad depth / subdivide.

    Examples
    --------
    >>> split_values(["params.excess=1.2", "depth=2", "circle.orientation=lying"])
    ({'params.excess': 1.2, 'circle.orientation': 'lying'}, 2, 0)
    """
    if len(values) > MAX_VALUES:
        raise ParameterError("values", len(values), f"at most {MAX_VALUES} values")
    over = parse_overrides(list(values))
    depth = over.pop("depth", None)
    sub = over.pop("subdivide", 0)
    if depth is not None:
        depth = integer("depth", depth, 0, MAX_NESTING)
    return over, depth, integer("subdivide", sub, 0, MAX_SUBDIVIDE)


def window_style(workspace: Workspace | None, style: str, path: str, values: list[str]) -> Style:
    """The style the page shows: a built-in (or ``"prototype"``) or a workspace file, with ``values``.

    Raises
    ------
    ParameterError
        For an unknown style or a bad value (the message names the key).
    auszug.errors.FormatError, WorkspaceError
        For a style file that cannot be read, or a path outside the workspace.
    """
    over, depth, _ = split_values(values)
    for key, value in over.items():
        named = [value] if key.split(".")[-1] in ("window", "extends") and isinstance(value, str) else []
        for ref in named + _refs(value):
            if ref not in _builtin_names():
                raise ParameterError(key, ref, "a built-in style name (" + ", ".join(_builtin_names()) + ")",
                                     "the studio reads style files only from the style picker")
    if path:
        if workspace is None:
            raise AuszugError("no workspace to open style files from")
        p = workspace.resolve(path)
        if p.suffix.lower() not in STYLE_SUFFIXES:
            raise AuszugError(f"{path}: a style file ends in .toml or .json")
        _confined(workspace, p, path, set())
        st = load_style(p)
    elif style == "prototype":
        st = builtin_style("fig20a").with_overrides({"name": "prototype"})
    else:
        if style not in _builtin_names():
            raise ParameterError("style", style, "a built-in style (" + ", ".join(_builtin_names()) + ") or prototype")
        st = _builtin(style)
    if over:
        st = st.with_overrides(over)
    if depth is not None and depth != st.depth():
        st = refine(st, depth)
    return st


@lru_cache(maxsize=1)
def _builtin_names() -> tuple[str, ...]:
    """The built-in style names (``builtin_styles()`` builds every style for its descriptions: once)."""
    return tuple(builtin_styles())


@lru_cache(maxsize=32)
def _builtin(name: str) -> Style:
    """A built-in style, resolved once (styles are immutable; ``with_overrides`` copies)."""
    return builtin_style(name)


def _refs(node: Any) -> list[str]:
    """The style references (``extends``, ``window`` strings) anywhere in a style table."""
    out: list[str] = []
    if isinstance(node, dict):
        for k, v in node.items():
            if k in ("extends", "window") and isinstance(v, str):
                out.append(v)
            out += _refs(v)
    return out


def _confined(workspace: Workspace, p: Path, shown: str, seen: set[Path]) -> None:
    """Refuse a style file whose ``extends`` or nested ``window`` names a file outside the workspace.

    References are resolved as :func:`auszug.tracery.load_style` resolves them (relative to
    the file, then as a built-in name), so the studio reads no file outside its workspace.
    """
    from auszug.studio.session import WorkspaceError
    if p in seen:
        return
    seen.add(p)
    from auszug.limits import check_file_size

    check_file_size(p)
    data = style_data(p.read_text(encoding="utf-8"), shown, p.suffix.lower())

    for ref in _refs(data):
        cand = p.parent / ref
        if cand.suffix.lower() in STYLE_SUFFIXES and cand.is_file():
            root = workspace.root.resolve()
            real = cand.resolve()
            if root not in real.parents:
                raise WorkspaceError(f"{shown}: refers to {ref!r}, outside the workspace")
            _confined(workspace, real, workspace.relative(real), seen)
        elif ref not in _builtin_names():
            if Path(ref).suffix.lower() in STYLE_SUFFIXES:
                raise WorkspaceError(f"{shown}: refers to {ref!r}, which is not a style file of the workspace")
            raise ParameterError("extends", ref, "a built-in style (" + ", ".join(_builtin_names()) + ") or a "
                                 ".toml/.json file beside the style")


def _field_value(st: Style, key: str, kind: str) -> float | bool | str:
    if key == "depth":
        return st.depth()
    node: Any = st.data
    for part in key.split("."):
        node = node.get(part) if isinstance(node, dict) else None
    if kind == "choice":
        return node if isinstance(node, str) else "(inline)"
    if kind == "bool":
        return bool(node)
    return float(node) if kind == "number" else int(node)


def _fields(st: Style, subdivide: int) -> list[P.TraceryField]:
    lib = builtin_profiles()
    local = sorted(st.data.get("profiles") or {})
    region = sorted(k for k, v in lib.items() if not v.wall) + local
    walls = sorted(k for k, v in lib.items() if v.wall) + local
    out = []
    for key, label, group, kind, options in FIELDS:
        opts = list(options)
        if key.endswith("profile"):
            opts = walls if key == "wall.profile" else region
        value: float | bool | str = subdivide if key == "subdivide" else _field_value(st, key, kind)
        if kind == "choice" and value not in opts:
            opts = [*opts, str(value)]
        out.append(P.TraceryField(key=key, label=label, group=group, kind=kind,  # type: ignore[arg-type]
                                  value=value, options=opts))
    return out


def _canonical(values: list[str]) -> list[str]:
    """The values, one per key (the last wins), in the order keys first appear."""
    last: dict[str, str] = {}
    for v in values:
        k, _, rest = v.partition("=")
        last[k.strip()] = f"{k.strip()}={rest.strip()}"
    return list(last.values())


def _fmt(v: float) -> str:
    return f"{v:.10f}".rstrip("0").rstrip(".") if v != 0 else "0"


def svg_path(curves: tuple[Any, ...]) -> str:
    """:func:`auszug.tracery.draw.path_data` of a closed loop, the same text, without numpy per arc.

    Examples
    --------
    >>> from auszug.tracery import build
    >>> from auszug.tracery.draw import path_data
    >>> all(svg_path(r.curves) == path_data(r.curves) for r in build("fig20d").regions)
    True
    """
    from auszug.geometry import Arc

    c0 = curves[0]
    if isinstance(c0, Arc):     # c0.start's arithmetic: centre + radius * (cos, sin) of theta0 + 0 * sweep
        cx, cy = c0.center.tolist()
        th = float(c0.theta0) + 0.0 * float(c0.sweep)
        x, y = cx + float(c0.radius) * math.cos(th), cy + float(c0.radius) * math.sin(th)
    else:
        x, y = c0.p0.tolist()
    parts = [f"M{_fmt(x)} {_fmt(y)}"]
    for c in curves:
        if isinstance(c, Arc):
            cx, cy = c.center.tolist()
            r, th, sw = float(c.radius), float(c.theta0), float(c.sweep)
            sweeps = [sw] if abs(sw) < 2 * math.pi - 1e-9 else [sw / 2, sw / 2]
            rs = _fmt(r)
            for part in sweeps:
                th += part
                # the same arithmetic as path_data: centre + radius * (cos, sin)
                qx, qy = cx + r * math.cos(th), cy + r * math.sin(th)
                parts.append(f"A{rs} {rs} 0 {1 if abs(part) > math.pi else 0} {1 if part > 0 else 0} "
                             f"{_fmt(qx)} {_fmt(qy)}")
        else:                   # c.end's arithmetic: p0 + 1 * (p1 - p0)
            (x0, y0), (x1, y1) = c.p0.tolist(), c.p1.tolist()
            parts.append(f"L{_fmt(x0 + (x1 - x0))} {_fmt(y0 + (y1 - y0))}")
    parts.append("Z")
    return " ".join(parts)


@dataclasses.dataclass(frozen=True)
class _Built:
    """What a window's message carries that depends on its style's value alone (the cache's entries)."""

    regions: list[P.TraceryRegion]
    n_lights: int
    depth: int
    bounds: list[float]
    mesh_bounds: list[float]
    n_verts: int
    n_faces: int
    payload: bytes
    build_ms: float
    mesh_ms: float

    @property
    def nbytes(self) -> int:
        """About the memory it holds: the payload and the path texts."""
        return len(self.payload) + sum(len(r.d) + len(r.id) + 64 for r in self.regions)


class WindowCache:
    """The last built windows by key, least recently used dropped first; thread-safe.

    At most ``entries`` windows and ``max_bytes`` bytes (:attr:`_Built.nbytes`); a window larger
    than ``max_bytes`` is not kept.

    Examples
    --------
    >>> c = WindowCache(entries=2, max_bytes=10**6)
    >>> c.put("a", 1, 10); c.put("b", 2, 10); c.get("a"); c.put("c", 3, 10)
    1
    >>> c.get("b") is None, c.get("a"), c.get("c"), len(c)
    (True, 1, 3, 2)
    """

    def __init__(self, entries: int = CACHE_WINDOWS, max_bytes: int = CACHE_BYTES) -> None:
        self.entries, self.max_bytes = entries, max_bytes
        self._items: OrderedDict[str, tuple[Any, int]] = OrderedDict()
        self._bytes = 0
        self._lock = threading.Lock()

    def __len__(self) -> int:
        return len(self._items)

    @property
    def nbytes(self) -> int:
        """The bytes of the windows held (as given to :meth:`put`)."""
        return self._bytes

    def get(self, key: str) -> Any:
        """The value kept under ``key`` (now the most recently used), or None."""
        with self._lock:
            item = self._items.get(key)
            if item is None:
                return None
            self._items.move_to_end(key)
            return item[0]

    def put(self, key: str, value: Any, nbytes: int) -> None:
        """Keep ``value`` (about ``nbytes`` bytes) under ``key``, dropping the least recently used to fit."""
        with self._lock:
            old = self._items.pop(key, None)
            if old is not None:
                self._bytes -= old[1]
            if nbytes > self.max_bytes:
                return
            self._items[key] = (value, nbytes)
            self._bytes += nbytes
            while len(self._items) > self.entries or self._bytes > self.max_bytes:
                _, (_, n) = self._items.popitem(last=False)
                self._bytes -= n

    def clear(self) -> None:
        """Forget every window."""
        with self._lock:
            self._items.clear()
            self._bytes = 0


#: The server's cache of built windows (:func:`build_message`).
WINDOWS = WindowCache()


def style_key(st: Style) -> str:
    """The style's value as text: equal for styles that build the same window (the cache's key)."""
    return json.dumps(st.data, sort_keys=True, separators=(",", ":"), default=repr)


def _built(st: Style) -> _Built:
    """Build the window of ``st``: structure, preview mesh, SVG paths."""
    t0 = time.perf_counter()
    t = build(st)
    t1 = time.perf_counter()
    verts, faces = preview_mesh(t, back=False)   # the page draws the back half as the front's mirror
    t2 = time.perf_counter()
    # every region lies inside the outer arch (the first region): its polygon's box is the window's
    # (Tracery.bounds samples all 121 regions of Fig. 20h finely, as long as the build itself)
    arch = t.regions[0].polygon()
    lo, hi = arch.min(0), arch.max(0)
    regions = [P.TraceryRegion(id=r.id, group=r.group, depth=r.depth, role=r.role, d=svg_path(r.curves))
               for r in t.regions]
    vlo, vhi = verts.min(0), verts.max(0)
    return _Built(regions=regions, n_lights=len(t.lights), depth=t.depth,
                  bounds=[float(lo[0]), float(lo[1]), float(hi[0]), float(hi[1])],
                  mesh_bounds=[float(x) for x in (*vlo, *vhi)], n_verts=len(verts), n_faces=len(faces),
                  payload=verts.tobytes() + faces.tobytes(),
                  build_ms=round((t1 - t0) * 1e3, 3), mesh_ms=round((t2 - t1) * 1e3, 3))


def build_message(st: Style, style: str, path: str, values: list[str], msg_id: int = 0,
                  cache: WindowCache | None = WINDOWS) -> tuple[P.TraceryGeometry, bytes]:
    """The :class:`~auszug.studio.protocol.TraceryGeometry` of ``st`` and its payload (the preview mesh).

    A window built before from an equal style (:func:`style_key`) comes from ``cache`` (None: none).

    Raises
    ------
    ParameterError
        If the style's window cannot be built (a misfit between values).
    """
    _, _, sub = split_values(values)
    key = style_key(st) if cache is not None else ""
    b = cache.get(key) if cache is not None else None
    cached = b is not None
    if b is None:
        b = _built(st)
        if cache is not None:
            cache.put(key, b, b.nbytes)
    msg = P.TraceryGeometry(
        style=style, path=path, name=st.name, values=_canonical(values), fields=_fields(st, sub),
        regions=b.regions, n_lights=b.n_lights, depth=b.depth, bounds=b.bounds, mesh_bounds=b.mesh_bounds,
        positions=P.ArrayRef(offset=0, shape=[b.n_verts, 3]),
        indices=P.ArrayRef(offset=3 * b.n_verts, shape=[b.n_faces, 3], dtype="u4"),
        build_ms=b.build_ms, mesh_ms=b.mesh_ms, binary_floats=3 * (b.n_verts + b.n_faces), cached=cached,
        id=msg_id)
    return msg, b.payload


def _flat(obj: Any) -> dict[str, Any]:
    """A flat dataclass (no nested dataclasses) as a dict in field order."""
    return {f.name: getattr(obj, f.name) for f in dataclasses.fields(obj)}


def tracery_text(msg: P.TraceryGeometry) -> str:
    """``protocol.encode(msg)``, the same text, without ``dataclasses.asdict``'s deep copy.

    Examples
    --------
    >>> m, _ = build_message(window_style(None, "fig20c", "", []), "fig20c", "", [])
    >>> tracery_text(m) == P.encode(m)
    True
    """
    d = _flat(msg)
    d["fields"] = [_flat(f) for f in msg.fields]
    d["regions"] = [_flat(r) for r in msg.regions]
    d["positions"] = _flat(msg.positions)
    d["indices"] = _flat(msg.indices)
    return json.dumps(d, separators=(",", ":"), allow_nan=False)


def _plain(data: Any) -> Any:
    """The style table without None values (TOML has no null; a missing key takes the default)."""
    if isinstance(data, dict):
        return {k: _plain(v) for k, v in data.items() if v is not None}
    if isinstance(data, list):
        return [_plain(v) for v in data]
    return data


def style_text(st: Style, suffix: str) -> str:
    """The complete style (defaults and nested windows inline) as TOML or JSON text.

    :func:`auszug.tracery.load_style` of the text gives the same window.

    Examples
    --------
    >>> from auszug.tracery import builtin_style, parse_style
    >>> st = builtin_style("fig20d")
    >>> parse_style(style_text(st, ".toml")).data == st.data
    True
    """
    data = _plain(st.data)
    if suffix == ".json":
        return json.dumps(data, indent=2) + "\n"
    import tomli_w

    return tomli_w.dumps(data)


def save_style(workspace: Workspace, st: Style, target: str) -> str:
    """Write ``st`` to workspace file ``target`` (.toml or .json) atomically; its relative path.

    Raises
    ------
    AuszugError
        For another ending; WorkspaceError for a path outside the workspace.
    """
    from auszug.formats import atomic_write

    p = workspace.resolve_for_writing(target)
    suffix = p.suffix.lower()
    if suffix not in STYLE_SUFFIXES:
        raise AuszugError(f"{target}: a style file ends in .toml or .json")
    text = style_text(st, suffix)
    atomic_write(p, text)
    return workspace.relative(p)


def export_window(st: Style, format: str, subdivide: int = 0) -> tuple[str, str, bytes]:
    """(file name, MIME type, bytes) of the window: glb/obj/stl the finished mesh, svg, json (2D)."""
    from auszug.formats import format_for
    from auszug.studio.meshes import MIMES
    from auszug.tracery.draw import svg
    from auszug.tracery.mesh import window_mesh

    stem = "".join(c if c.isalnum() or c in "-_" else "-" for c in (st.name or "window")) or "window"
    t = build(st)
    if format in ("glb", "obj", "stl"):
        fname = f"{stem}.{format}"
        data: str | bytes = format_for(Path(fname), "mesh", want="write").write(window_mesh(t, subdivide=subdivide),
                                                                                fname)
    elif format == "svg":
        fname, data = f"{stem}.svg", svg(t)
    elif format == "json":
        fname = f"{stem}.tracery.json"
        data = format_for(Path(fname), "tracery", want="write").write(t, fname)
    else:
        raise AuszugError(f"format must be one of glb, obj, stl, svg, json, got {format!r}")
    raw = data.encode("utf-8") if isinstance(data, str) else bytes(data)
    return fname, MIMES[format], raw


def style_files(workspace: Workspace) -> tuple[list[str], list[str]]:
    """(style files of the workspace, notes): every ``.toml`` and ``*.style.json``, relative, sorted."""
    return workspace.listing(accept=lambda n: n.lower().endswith((".toml", ".style.json")))

