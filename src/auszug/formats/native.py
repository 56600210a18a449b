"""auszug's own drawing format: versioned JSON, lossless for every :class:`Drawing`.

A file holds one drawing (documented in ``docs/formats.md``)::

    {
      "format": "auszug.drawing",
      "version": 1,
      "name": "tn-3",
      "layer_bottoms": [0.0],
      "default_apex": null,
      "curves": [
        {
          "vertices": [[-0.8, 0.0], [0.0, -0.5]],
          "segments": [{"kind": "arc", "handles": [[-0.6, -0.3]]}],
          "marks": ["ground", "apex"],
          "symmetry": {"fold": 4, "mirror": true, "axis": [-0.8, 0.0], "center": [0.0, 0.0],
                       "axis_rule": "first point"},
          "layer": 0, "height": 1.0, "prc": [null], "decoration": false,
          "decoration_at": null, "post_top": null, "name": ""
        }
      ]
    }

Numbers are written with Python's shortest round-trip repr, so
``read_native(write_native(d)) == d`` exactly. The reader checks everything and
reports problems as :class:`~auszug.errors.FormatError` naming the file, the
line, and the place in the document as a JSON path (``curves[2].vertices[1]``).
Keys the version does not define are rejected: any addition to the format gets
a new version number.
"""

from __future__ import annotations

import bisect
import json
import json.decoder
import json.scanner
import math
import re
from typing import Any, Literal, cast

from auszug.errors import DrawingError, FormatError
from auszug.formats._registry import FileFormat, register
from auszug.limits import LIMITS, check_text_size, shown
from auszug.microarch.model import MARKS, BasicCurve, Drawing, Segment, Source, Symmetry

__all__ = ["FORMAT_ID", "VERSION", "from_dict", "read_native", "to_dict", "write_native"]

#: Value of the ``"format"`` key.
FORMAT_ID = "auszug.drawing"
#: The format version this module reads and writes.
VERSION = 1

_TOP_KEYS = ("format", "version", "name", "layer_bottoms", "default_apex", "curves")
_CURVE_KEYS = ("vertices", "segments", "marks", "symmetry", "layer", "height", "prc", "decoration",
               "decoration_at", "post_top", "name")
_SYM_KEYS = ("fold", "mirror", "axis", "center", "axis_rule")
_SEG_KEYS = ("kind", "handles")
_HANDLES = {"line": 0, "arc": 1, "bezier": 2}
_AXIS_RULES = ("first point", "last point", "y axis", "fixed")


# -- writing ---------------------------------------------------------------------------------
def _xy(p: tuple[float, float]) -> list[float]:
    return [float(p[0]), float(p[1])]


def to_dict(drawing: Drawing) -> dict[str, Any]:
    """The JSON document of ``drawing`` as plain Python data (version :data:`VERSION`).

    Examples
    --------
    >>> from auszug.microarch.model import BasicCurve, Drawing, Segment
    >>> d = Drawing((BasicCurve(((0, 0), (1, 0)), (Segment(),), ("ground", "apex")),))
    >>> doc = to_dict(d)
    >>> doc["format"], doc["version"], doc["curves"][0]["segments"]
    ('auszug.drawing', 1, [{'kind': 'line', 'handles': []}])
    """
    curves = []
    for c in drawing.curves:
        s = c.symmetry
        curves.append({
            "vertices": [_xy(v) for v in c.vertices],
            "segments": [{"kind": g.kind, "handles": [_xy(h) for h in g.handles]} for g in c.segments],
            "marks": list(c.marks),
            "symmetry": {"fold": s.fold, "mirror": s.mirror, "axis": _xy(s.axis),
                         "center": _xy(s.center), "axis_rule": s.axis_rule},
            "layer": c.layer,
            "height": c.height,
            "prc": list(c.prc),
            "decoration": c.decoration,
            "decoration_at": c.decoration_at,
            "post_top": c.post_top,
            "name": c.name,
        })
    return {
        "format": FORMAT_ID,
        "version": VERSION,
        "name": drawing.name,
        "layer_bottoms": list(drawing.layer_bottoms),
        "default_apex": drawing.default_apex,
        "curves": curves,
    }


def _dump(v: Any) -> str:
    return json.dumps(v, allow_nan=False, ensure_ascii=False)


def write_native(drawing: Drawing, name: str = "") -> str:
    """``drawing`` as a JSON document: one line per field, so errors point at a line.

    Raises
    ------
    FormatError
        If the drawing holds a number JSON cannot store (a non-finite ``default_apex``).

    Examples
    --------
    >>> from auszug.microarch.model import BasicCurve, Drawing, Segment
    >>> d = Drawing((BasicCurve(((0, 0), (1, 0)), (Segment(),), ("ground", "apex")),), name="a")
    >>> read_native(write_native(d)) == d
    True
    """
    doc = to_dict(drawing)
    try:
        out = ["{"]
        for key in _TOP_KEYS[:-1]:
            out.append(f"  {_dump(key)}: {_dump(doc[key])},")
        out.append('  "curves": [')
        for ci, c in enumerate(doc["curves"]):
            out.append("    {")
            items = [f"      {_dump(k)}: {_dump(v)}" for k, v in c.items()]
            out.append(",\n".join(items))
            out.append("    }" + ("," if ci + 1 < len(doc["curves"]) else ""))
        out.append("  ]")
        out.append("}")
    except ValueError as e:  # allow_nan=False
        raise FormatError(f"cannot write a non-finite number as JSON ({e})", name or None) from None
    return "\n".join(out) + "\n"


# -- reading ---------------------------------------------------------------------------------
class _Obj(dict):
    """A JSON object that remembers where it and each of its values start in the text."""

    pos: int | None = None
    child_pos: dict[Any, int]


class _Arr(list):
    """A JSON array that remembers where it and each of its items start in the text."""

    pos: int | None = None
    child_pos: dict[Any, int]


class _Decoder(json.JSONDecoder):
    """Pure-Python JSON decoder whose objects and arrays carry text offsets.

    The standard library's pure-Python scanner calls ``parse_object`` and
    ``parse_array`` for every container; wrapping the ``scan_once`` they are
    given records where each direct child value starts.
    """

    def __init__(self, path: str):
        super().__init__(parse_constant=float)
        self.path = path
        self.parse_object = self._object
        self.parse_array = self._array
        # the pure-Python scanner and its object/array parsers are undocumented, so not in typeshed
        self.scan_once = json.scanner.py_make_scanner(self)  # type: ignore[attr-defined]  # see above

    @staticmethod
    def _recording(scan_once, starts: list[int]):
        def scan(s: str, idx: int):
            starts.append(idx)
            return scan_once(s, idx)

        return scan

    def _object(self, s_and_end, strict, scan_once, object_hook, object_pairs_hook, memo):
        s, end = s_and_end
        starts: list[int] = []
        pairs, e = json.decoder.JSONObject(  # type: ignore[attr-defined]  # undocumented, as above
            s_and_end, strict, self._recording(scan_once, starts), None, list, memo)
        out = _Obj()
        out.pos = end - 1
        out.child_pos = {}
        for (k, v), at in zip(pairs, starts, strict=True):
            if k in out:
                raise FormatError(f"key {k!r} appears twice in one object", self.path,
                                  s.count("\n", 0, at) + 1)
            out[k] = v
            out.child_pos[k] = at
        return out, e

    def _array(self, s_and_end, scan_once):
        end = s_and_end[1]
        starts: list[int] = []
        values, e = json.decoder.JSONArray(  # type: ignore[attr-defined]  # undocumented, as above
            s_and_end, self._recording(scan_once, starts))
        out = _Arr(values)
        out.pos = end - 1
        out.child_pos = dict(enumerate(starts))
        return out, e


class _Reader:
    """Validates a decoded document, naming the JSON path and line of every problem.

    Checks take the value, its JSON path, and its container and key there, so a
    problem is reported on the line where the value starts.
    """

    def __init__(self, path: str, text: str | None):
        self.path = path
        self.text = text
        self._newlines: list[int] | None = None  # offsets of the text's line ends, found when needed

    def line(self, node: Any, key: Any = None) -> int | None:
        if self.text is None:
            return None
        pos = getattr(node, "child_pos", {}).get(key) if key is not None else None
        if pos is None:
            pos = getattr(node, "pos", None)
        if pos is None:
            return None
        if self._newlines is None:
            self._newlines = [m.start() for m in re.finditer("\n", self.text)]
        return bisect.bisect_left(self._newlines, pos) + 1

    def fail(self, where: str, problem: str, node: Any, key: Any = None) -> FormatError:
        return FormatError(f"{where}: {problem}" if where else problem, self.path, self.line(node, key))

    # -- leaves: (value, JSON path, container, key in the container) ---------------------
    def obj(self, v: Any, where: str, keys: tuple[str, ...], required: tuple[str, ...],
            parent: Any, key: Any) -> dict:
        if not isinstance(v, dict):
            raise self.fail(where, f"expected an object, got {_what(v)}", parent, key)
        unknown = [k for k in v if k not in keys]
        if unknown:
            raise self.fail(where, f"unknown key {unknown[0]!r}; expected keys: {', '.join(keys)}",
                            v, unknown[0])
        missing = [k for k in required if k not in v]
        if missing:
            raise self.fail(where, f"missing key {missing[0]!r}", v)
        return v

    def arr(self, v: Any, where: str, parent: Any, key: Any) -> list:
        if not isinstance(v, list):
            raise self.fail(where, f"expected an array, got {_what(v)}", parent, key)
        return v

    def num(self, v: Any, where: str, parent: Any, key: Any, bound: float | None = LIMITS.coordinate) -> float:
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise self.fail(where, f"expected a number, got {_what(v)}", parent, key)
        try:
            f = float(v)
        except OverflowError:
            f = math.inf
        if not math.isfinite(f):
            raise self.fail(where, f"expected a finite number, got {_what(f)}", parent, key)
        if bound is not None and abs(f) > bound:
            raise self.fail(where, f"{_what(v)} is beyond the limit of +-{bound:g} for coordinates and "
                            "heights (auszug.limits.LIMITS.coordinate)", parent, key)
        return f

    def count(self, n: int, what: str, limit: str, where: str, parent: Any, key: Any) -> None:
        """Refuse ``n`` items above the limit ``limit`` (a field of :class:`~auszug.limits.Limits`)."""
        top = getattr(LIMITS, limit)
        if n > top:
            raise self.fail(where, f"{n} {what} is above the limit of {top} (auszug.limits.LIMITS.{limit})",
                            parent, key)

    def opt_num(self, v: Any, where: str, parent: Any, key: Any) -> float | None:
        return None if v is None else self.num(v, where, parent, key)

    def integer(self, v: Any, where: str, parent: Any, key: Any, minimum: int, maximum: str = "") -> int:
        """A whole number >= ``minimum`` and, with ``maximum`` (``"fold"``, ``"layers"``), within that limit."""
        f = self.num(v, where, parent, key, None)
        if f != int(f) or f < minimum:
            raise self.fail(where, f"expected a whole number >= {minimum}, got {_what(v)}", parent, key)
        if maximum:
            top = getattr(LIMITS, maximum) - (1 if maximum == "layers" else 0)
            if f > top:
                raise self.fail(where, f"{_what(v)} is above the limit of {top} "
                                f"(auszug.limits.LIMITS.{maximum})", parent, key)
        return int(f)

    def boolean(self, v: Any, where: str, parent: Any, key: Any) -> bool:
        if not isinstance(v, bool):
            raise self.fail(where, f"expected true or false, got {_what(v)}", parent, key)
        return v

    def string(self, v: Any, where: str, parent: Any, key: Any) -> str:
        if not isinstance(v, str):
            raise self.fail(where, f"expected a string, got {_what(v)}", parent, key)
        return v

    def point(self, v: Any, where: str, parent: Any, key: Any) -> tuple[float, float]:
        if not isinstance(v, list) or len(v) != 2:
            raise self.fail(where, f"expected a point [x, y], got {_what(v)}", parent, key)
        return (self.num(v[0], f"{where}[0]", v, 0), self.num(v[1], f"{where}[1]", v, 1))

    def field(self, c: dict, name: str, where: str, check: str, default: Any, *extra: Any) -> Any:
        """Optional member ``name`` of ``c`` through the check method ``check``."""
        if name not in c:
            return default
        return getattr(self, check)(c[name], f"{where}.{name}" if where else name, c, name, *extra)

    # -- structure ---------------------------------------------------------------------
    def drawing(self, doc: Any, stem: str) -> Drawing:
        if not isinstance(doc, dict):
            raise self.fail("", f"expected a JSON object holding a drawing, got {_what(doc)}", doc)
        fmt = doc.get("format")
        if fmt != FORMAT_ID:
            got = "no 'format' key" if "format" not in doc else f"'format' is {_what(fmt)}"
            raise self.fail("format", f"not an auszug drawing: {got}, expected {FORMAT_ID!r}",
                            doc, "format")
        if "version" not in doc:
            raise self.fail("", "missing key 'version'", doc)
        ver = doc["version"]
        if isinstance(ver, bool) or not isinstance(ver, int) or ver != VERSION:
            raise self.fail("version", f"unsupported version {_what(ver)}; this auszug reads "
                            f"version {VERSION}", doc, "version")
        self.obj(doc, "", _TOP_KEYS, ("format", "version", "curves"), doc, None)
        name = self.field(doc, "name", "", "string", stem)
        lb = self.field(doc, "layer_bottoms", "", "arr", [])
        self.count(len(lb), "layer bottoms", "layers", "layer_bottoms", doc, "layer_bottoms")
        bottoms = tuple(self.num(z, f"layer_bottoms[{i}]", lb, i) for i, z in enumerate(lb))
        apex = self.field(doc, "default_apex", "", "opt_num", None)
        cs = self.arr(doc["curves"], "curves", doc, "curves")
        self.count(len(cs), "curves", "curves", "curves", doc, "curves")
        curves = tuple(self.curve(c, f"curves[{i}]", cs, i) for i, c in enumerate(cs))
        try:
            return Drawing(curves=curves, layer_bottoms=bottoms, name=name, default_apex=apex)
        except DrawingError as e:  # the drawing's totals (segments, network curves)
            raise self.fail("curves", str(e), doc, "curves") from None

    def curve(self, c: Any, where: str, parent: Any, key: Any) -> BasicCurve:
        c = self.obj(c, where, _CURVE_KEYS, ("vertices", "segments", "marks"), parent, key)
        w = f"{where}.vertices"
        vs = self.arr(c["vertices"], w, c, "vertices")
        self.count(len(vs) - 1, "segments", "segments", w, c, "vertices")
        verts = tuple(self.point(v, f"{w}[{i}]", vs, i) for i, v in enumerate(vs))
        if len(verts) < 2:
            raise self.fail(w, f"a curve needs at least 2 vertices, got {len(verts)}", c, "vertices")
        for i in range(1, len(verts)):
            (x0, y0), (x1, y1) = verts[i - 1], verts[i]
            if math.hypot(x1 - x0, y1 - y0) <= 1e-12:
                raise self.fail(f"{w}[{i}]", f"coincides with vertex {i - 1} (zero-length segment)", vs, i)
        w = f"{where}.segments"
        ss = self.arr(c["segments"], w, c, "segments")
        if len(ss) != len(verts) - 1:
            raise self.fail(w, f"{len(verts)} vertices need {len(verts) - 1} segments, got {len(ss)}",
                            c, "segments")
        segs = tuple(self.segment(s, f"{w}[{i}]", ss, i) for i, s in enumerate(ss))
        w = f"{where}.marks"
        ms = self.arr(c["marks"], w, c, "marks")
        if len(ms) != len(verts):
            raise self.fail(w, f"{len(verts)} vertices need {len(verts)} marks, got {len(ms)}", c, "marks")
        marks = tuple(self.string(m, f"{w}[{i}]", ms, i) for i, m in enumerate(ms))
        for i, m in enumerate(marks):
            if m not in MARKS:
                raise self.fail(f"{w}[{i}]", f"unknown mark {m!r}; expected one of {', '.join(MARKS)}",
                                ms, i)
        sym = self.symmetry(c["symmetry"], f"{where}.symmetry", c, "symmetry") if "symmetry" in c \
            else Symmetry()
        prc: tuple[float | None, ...] = ()
        if "prc" in c:
            w = f"{where}.prc"
            ps = self.arr(c["prc"], w, c, "prc")
            if len(ps) != len(segs):
                raise self.fail(w, f"need one entry (a number or null) per segment ({len(segs)}), "
                                f"got {len(ps)}", c, "prc")
            prc = tuple(self.opt_num(p, f"{w}[{i}]", ps, i) for i, p in enumerate(ps))
            for i, p in enumerate(prc):
                if p is not None and not 0.0 < p < 1.0:
                    raise self.fail(f"{w}[{i}]", f"a PRC fraction must lie strictly between 0 and 1, "
                                    f"got {p!r}", ps, i)
        deco_at = self.field(c, "decoration_at", where, "opt_num", None)
        if deco_at is not None and not 0.0 < deco_at < 1.0:
            raise self.fail(f"{where}.decoration_at", f"must lie strictly between 0 and 1, got {deco_at!r}",
                            c, "decoration_at")
        try:
            return BasicCurve(
                vertices=verts, segments=segs, marks=marks, symmetry=sym,
                layer=self.field(c, "layer", where, "integer", 0, 0, "layers"),
                height=self.field(c, "height", where, "opt_num", None),
                prc=prc,
                decoration=self.field(c, "decoration", where, "boolean", False),
                decoration_at=deco_at,
                post_top=self.field(c, "post_top", where, "opt_num", None),
                name=self.field(c, "name", where, "string", ""),
                source=Source(self.line(parent, key), self.line(c, "height") if "height" in c else None,
                              tuple(range(len(verts))), tuple(self.line(vs, i) or 0 for i in range(len(verts)))
                              if self.text is not None else ()),
            )
        except DrawingError as e:
            raise self.fail(where, str(e), c) from None

    def segment(self, s: Any, where: str, parent: Any, key: Any) -> Segment:
        s = self.obj(s, where, _SEG_KEYS, ("kind",), parent, key)
        kind = self.string(s["kind"], f"{where}.kind", s, "kind")
        if kind not in _HANDLES:
            raise self.fail(f"{where}.kind", f"unknown segment kind {kind!r}; expected line, arc or "
                            "bezier", s, "kind")
        hs = self.field(s, "handles", where, "arr", [])
        if len(hs) != _HANDLES[kind]:
            raise self.fail(f"{where}.handles", f"a {kind} segment needs {_HANDLES[kind]} handle(s), "
                            f"got {len(hs)}", s, "handles")
        known = cast(Literal["line", "arc", "bezier"], kind)  # one of _HANDLES, checked above
        return Segment(known, tuple(self.point(h, f"{where}.handles[{i}]", hs, i) for i, h in enumerate(hs)))

    def symmetry(self, s: Any, where: str, parent: Any, key: Any) -> Symmetry:
        s = self.obj(s, where, _SYM_KEYS, (), parent, key)
        fold = self.field(s, "fold", where, "integer", 1, 1, "fold")
        mirror = self.field(s, "mirror", where, "boolean", False)
        axis = self.field(s, "axis", where, "point", (0.0, 1.0))
        center = self.field(s, "center", where, "point", (0.0, 0.0))
        rule = self.field(s, "axis_rule", where, "string", "fixed")
        if rule not in _AXIS_RULES:
            raise self.fail(f"{where}.axis_rule", f"unknown axis rule {rule!r}; expected one of "
                            f"{', '.join(_AXIS_RULES)}", s, "axis_rule")
        if mirror and math.hypot(*axis) <= 1e-12:
            raise self.fail(f"{where}.axis", "a mirror axis needs a direction of non-zero length",
                            s, "axis" if "axis" in s else None)
        try:
            return Symmetry(fold, mirror, axis, center, rule)
        except DrawingError as e:  # pragma: no cover - checked above
            raise self.fail(where, str(e), s) from None


def _what(v: Any) -> str:
    """Short description of a JSON value for messages."""
    if v is None:
        return "null"
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return shown(v)
    if isinstance(v, list):
        return f"an array of {len(v)}"
    return "an object"


def _stem(path: str) -> str:
    name = path.replace("\\", "/").rsplit("/", 1)[-1]
    return name[:-5] if name.lower().endswith(".json") else name


def from_dict(doc: Any, path: str = "<data>") -> Drawing:
    """The :class:`Drawing` of a decoded JSON document (see :func:`to_dict`).

    Raises
    ------
    FormatError
        Naming the JSON path of the problem (no line: plain data has none).

    Examples
    --------
    >>> from_dict({"format": "auszug.drawing", "version": 1, "curves": []}).curves
    ()
    """
    return _Reader(path, None).drawing(doc, _stem(path))


def read_native(text: str | bytes, path: str = "<string>") -> Drawing:
    """Read a drawing from auszug JSON text.

    Parameters
    ----------
    text : str or bytes
        The document (bytes are decoded as UTF-8).
    path : str
        File name for messages; its stem names the drawing if the file does not.

    Raises
    ------
    FormatError
        Naming the file, the line and the JSON path of the problem.

    Examples
    --------
    >>> read_native('{"format": "auszug.drawing", "version": 2, "curves": []}', "d.json")
    Traceback (most recent call last):
    ...
    auszug.errors.FormatError: d.json:1: version: unsupported version 2; this auszug reads version 1
    """
    check_text_size(text, path)
    if isinstance(text, bytes):
        try:
            text = text.decode("utf-8")
        except UnicodeDecodeError as e:
            raise FormatError(f"not UTF-8 text ({e.reason} at byte {e.start})", path) from None
    dec = _Decoder(path)
    try:
        doc = dec.decode(text)
    except json.JSONDecodeError as e:
        raise FormatError(f"not valid JSON: {e.msg} (column {e.colno})", path, e.lineno) from None
    except RecursionError:
        raise FormatError("not a drawing: JSON nested too deeply", path) from None
    return _Reader(path, text).drawing(doc, _stem(path))


register(FileFormat("json", (".json",), "drawing", reader=read_native, writer=write_native))
