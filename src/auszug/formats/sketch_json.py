"""Sketch JSON (``.sketch.json``): the native, lossless form of a design sketch.

The same content as a sketch SVG after reading (strokes as cubic Bezier
chains in the sketch's coordinates, y up; markers; the symmetry curve;
layer names)::

    {"format": "auszug.sketch", "version": 1, "name": "vase",
     "layers": ["back", "front"],
     "strokes": [{"id": "m1", "layer": 0, "controls": [[[x, y], [x, y], [x, y], [x, y]], ...]}, ...],
     "markers": [{"kind": "occlusion", "id": "o1", "point": [x, y]}, ...],
     "symmetry": {"id": "axis", "controls": [...]} or null}

Floats are written with Python's shortest round-trip representation, so
reading gives back exactly the numbers written. Reading validates the
sketch as :mod:`auszug.formats.sketch_svg` does.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from auszug.errors import FormatError
from auszug.formats._registry import FileFormat, register
from auszug.formats.sketch_svg import MARKER_CLASSES, check
from auszug.limits import LIMITS, beyond_coordinate

if TYPE_CHECKING:
    from auszug.lifting import Sketch, Stroke

__all__ = ["FORMAT", "VERSION", "to_dict", "from_dict", "dumps", "loads"]

FORMAT = "auszug.sketch"
VERSION = 1


def _stroke(s: Stroke, layer: bool = True) -> dict[str, Any]:
    d: dict[str, Any] = {"id": s.id}
    if layer:
        d["layer"] = int(s.layer)
    d["controls"] = np.asarray(s.controls, dtype=float).tolist()
    return d


def to_dict(sketch: Sketch) -> dict[str, Any]:
    """The JSON-ready document of ``sketch``."""
    return {"format": FORMAT, "version": VERSION, "name": sketch.name, "layers": list(sketch.layers),
            "strokes": [_stroke(s) for s in sketch.strokes],
            "markers": [{"kind": m.kind, "id": m.id, "point": np.asarray(m.point, dtype=float).tolist()}
                        for m in sketch.markers],
            "symmetry": None if sketch.symmetry is None else _stroke(sketch.symmetry)}


def dumps(sketch: Sketch) -> str:
    """Sketch JSON text.

    Examples
    --------
    >>> import numpy as np
    >>> from auszug.lifting import Sketch, Stroke
    >>> h = Stroke(np.array([[[-1, 0], [-0.4, 0.25], [0.4, 0.25], [1, 0]]], float), "h")
    >>> v = Stroke(np.array([[[0.3, -1], [0.1, -0.3], [-0.1, 0.3], [-0.3, 1]]], float), "v")
    >>> back = loads(dumps(Sketch((h, v), name="cross")))
    >>> back.name, [s.id for s in back.strokes], np.array_equal(back.strokes[1].controls, v.controls)
    ('cross', ['h', 'v'], True)
    """
    return json.dumps(to_dict(sketch), indent=1, allow_nan=False) + "\n"


def _controls(v: Any, where: str, name: str) -> np.ndarray:
    try:
        c = np.array(v, dtype=float)
    except (TypeError, ValueError):
        raise FormatError(f"{where}: controls must be a list of [[x, y] x 4] Bezier segments", name) from None
    if c.ndim != 3 or c.shape[1:] != (4, 2) or not len(c):
        raise FormatError(f"{where}: controls must be a non-empty list of [[x, y] x 4] Bezier segments, "
                          f"got shape {list(c.shape)}", name)
    if not np.all(np.isfinite(c)):
        raise FormatError(f"{where}: coordinates are not finite (NaN or infinity)", name)
    if (far := beyond_coordinate(float(np.abs(c).max()))) is not None:
        raise FormatError(f"{where}: {far}", name)
    return c


def from_dict(d: Any, name: str = "<string>") -> Sketch:
    """The sketch of a sketch JSON document (validated)."""
    # lazy: reading a sketch, not registering the format, needs lifting (and scipy.spatial)
    from auszug.lifting import (
        Marker,
        Sketch,
        Stroke,
    )

    if not isinstance(d, dict) or d.get("format") != FORMAT:
        raise FormatError(f"not a sketch JSON file: expected an object with \"format\": \"{FORMAT}\"", name)
    if d.get("version") != VERSION:
        raise FormatError(f"sketch JSON version {d.get('version')!r} is not supported; expected {VERSION}", name)
    strokes_in, markers_in = d.get("strokes"), d.get("markers", [])
    layers = d.get("layers", [])
    if not isinstance(strokes_in, list) or not isinstance(markers_in, list) or not isinstance(layers, list):
        raise FormatError("\"strokes\", \"markers\" and \"layers\" must be lists", name)
    strokes = []
    for i, s in enumerate(strokes_in):
        if not isinstance(s, dict):
            raise FormatError(f"stroke #{i}: expected an object with \"controls\"", name)
        sid = str(s.get("id", "") or f"stroke #{i}")
        layer = s.get("layer", 0)
        if not isinstance(layer, int) or isinstance(layer, bool) or layer < 0:
            raise FormatError(f"{sid}: layer must be a whole number >= 0, got {layer!r}", name)
        strokes.append(Stroke(_controls(s.get("controls"), sid, name), str(s.get("id", "")), layer))
    markers = []
    for i, m in enumerate(markers_in):
        mid = str(m.get("id", "") if isinstance(m, dict) else "") or f"marker #{i}"
        if not isinstance(m, dict) or m.get("kind") not in MARKER_CLASSES:
            raise FormatError(f"{mid}: kind must be one of {', '.join(MARKER_CLASSES)}", name)
        p = m.get("point")
        if not (isinstance(p, list) and len(p) == 2 and all(isinstance(x, (int, float)) and
                                                            not isinstance(x, bool) and math.isfinite(x)
                                                            for x in p)):
            raise FormatError(f"{mid}: point must be [x, y] with finite numbers, got {p!r}", name)
        if max(abs(float(x)) for x in p) > LIMITS.coordinate:
            raise FormatError(f"{mid}: point {p!r} is beyond the limit of +-{LIMITS.coordinate:g} "
                              "(auszug.limits.LIMITS.coordinate)", name)
        markers.append(Marker(str(m["kind"]), np.array(p, dtype=float), str(m.get("id", ""))))
    sym = d.get("symmetry")
    symmetry = None
    if sym is not None:
        if not isinstance(sym, dict):
            raise FormatError("symmetry must be an object with \"controls\", or null", name)
        layer = sym.get("layer", 0)
        if not isinstance(layer, int) or isinstance(layer, bool) or layer < 0:
            raise FormatError(f"symmetry: layer must be a whole number >= 0, got {layer!r}", name)
        symmetry = Stroke(_controls(sym.get("controls"), "symmetry", name), str(sym.get("id", "")), layer)
    sketch = Sketch(tuple(strokes), tuple(markers), symmetry, str(d.get("name", "")),
                    tuple(str(x) for x in layers))
    check(sketch, name)
    return sketch


def loads(text: str, name: str = "<string>") -> Sketch:
    """Read sketch JSON text."""
    if not text.strip():
        raise FormatError("empty file; expected sketch JSON", name)
    try:
        d = json.loads(text)
    except json.JSONDecodeError as e:
        raise FormatError(f"not JSON: {e.msg}", name, e.lineno) from None
    return from_dict(d, name)


def _write(obj: Any, name: str) -> str:
    from auszug.lifting import (
        Sketch,  # lazy: reading a sketch, not registering the format, needs lifting (and scipy.spatial)
    )

    if not isinstance(obj, Sketch):
        raise FormatError(f"sketch JSON holds a Sketch, got {type(obj).__name__}", name)
    return dumps(obj)


def _read(text: str, name: str) -> Sketch:
    from auszug.lifting import (
        Sketch,  # lazy: reading a sketch, not registering the format, needs lifting (and scipy.spatial)
    )

    s = loads(text, name)
    return s if s.name else Sketch(s.strokes, s.markers, s.symmetry, Path(name).name.split(".")[0], s.layers)


register(FileFormat("sketch_json", (".sketch.json",), "sketch", reader=_read, writer=_write))
