"""Tracery JSON (``.tracery.json``, and ``.json`` for ``auszug tracery``): a window's 2D structure.

The document holds every region of the window as a polygon and as its exact
line and arc segments; its required keys are fixed (more may be added, never
removed)::

    {"format": "auszug.tracery", "version": 1, "style": "fig20a",
     "params": {"span": 2.0, "height": 4.0, "excess": 1.25, "drop": 0.2,
                "outer": 0.1, "inner": 0.05, "x": 0.0, "y": 0.0},
     "regions": [{"id": "arch/circle", "group": "circle", "depth": 0,
                  "role": "light", "border": 0.05, "face": 0.0,
                  "profile": {"name": "chamfer", "points": [[0, 0], ...]},
                  "boundary": [[x, y], ...],
                  "segments": [{"kind": "arc", "start": [x, y], "end": [x, y],
                                "center": [x, y], "radius": r, "sweep": s}, ...]}]}

``group`` is ``"arch"``, ``"sub-arch"``, ``"circle"``, ``"fillet"``,
``"rosette"`` or ``"light"``; ``depth`` the nesting level of the window the
region belongs to; ``role`` ``"frame"`` (holds further tracery), ``"light"``
(an opening) or ``"blind"`` (a recess). ``boundary`` is the closed polygon
(first point not repeated, counter-clockwise, x right, y up); ``segments``
the exact boundary, each segment ending where the next starts; a line has
``"center": null`` (and ``radius``, ``sweep`` null), an arc runs from
``start`` to ``end`` about ``center`` by the signed angle ``sweep`` (radians,
positive counter-clockwise).

Floats are written with Python's shortest round-trip representation, so a
read gives back exactly the numbers that were written.
"""

from __future__ import annotations

import json
import math
from typing import Any

import numpy as np

from auszug.errors import FormatError
from auszug.formats._registry import FileFormat, register
from auszug.limits import check_text_size

__all__ = ["FORMAT", "VERSION", "to_dict", "dumps", "loads", "segment_dict"]

FORMAT = "auszug.tracery"
VERSION = 1


def segment_dict(c: Any) -> dict[str, Any]:
    """The JSON form of one line or arc.

    Examples
    --------
    >>> from auszug.geometry import Line
    >>> segment_dict(Line((0, 0), (1, 0)))
    {'kind': 'line', 'start': [0.0, 0.0], 'end': [1.0, 0.0], 'center': None, 'radius': None, 'sweep': None}
    """
    from auszug.geometry import Arc

    if isinstance(c, Arc):
        return {"kind": "arc", "start": c.start.tolist(), "end": c.end.tolist(), "center": c.center.tolist(),
                "radius": c.radius, "sweep": c.sweep}
    return {"kind": "line", "start": c.start.tolist(), "end": c.end.tolist(), "center": None,
            "radius": None, "sweep": None}


def to_dict(tracery: Any, max_angle: float = math.pi / 64) -> dict[str, Any]:
    """The document of a :class:`auszug.tracery.Tracery` as plain Python data.

    Parameters
    ----------
    tracery : Tracery
    max_angle : float
        Angular step of the arcs in the ``boundary`` polygons (radians).
    """
    style = getattr(tracery.style, "name", tracery.style)
    params = tracery.params.as_dict() if hasattr(tracery.params, "as_dict") else dict(tracery.params)
    regions = []
    for r in tracery.regions:
        poly = r.polygon(max_angle)
        if not np.all(np.isfinite(poly)):
            raise FormatError(f"region {r.id} has non-finite coordinates; cannot write JSON")
        regions.append({
            "id": r.id, "group": r.group, "depth": r.depth, "role": r.role,
            "border": r.border, "face": r.face,
            "profile": {"name": r.profile.name, **r.profile.to_data()},
            "boundary": poly.tolist(),
            "segments": [segment_dict(c) for c in r.curves],
        })  # fmt: skip
    return {"format": FORMAT, "version": VERSION, "style": style, "params": params, "regions": regions}


def dumps(tracery: Any, indent: int | None = None) -> str:
    """JSON text of the document (compact unless ``indent``)."""
    return json.dumps(to_dict(tracery), indent=indent, allow_nan=False)


def _need(d: Any, key: str, kind: type | tuple[type, ...], where: str, name: str) -> Any:
    if not isinstance(d, dict) or key not in d:
        raise FormatError(f"{where}: missing {key!r}", name)
    v = d[key]
    if not isinstance(v, kind) or isinstance(v, bool) and kind is not bool:
        raise FormatError(f"{where}: {key!r} has the wrong type ({type(v).__name__})", name)
    return v


def _point(v: Any, where: str, name: str) -> np.ndarray:
    a = np.asarray(v, dtype=float) if isinstance(v, list) else None
    if a is None or a.shape != (2,) or not np.all(np.isfinite(a)):
        raise FormatError(f"{where}: expected a point [x, y], got {v!r}", name)
    return a


def loads(text: str, name: str = "<string>") -> Any:
    """Read a tracery JSON document back into a :class:`auszug.tracery.Tracery`.

    Regions get their exact segments back (their polygons are recomputed);
    ``style`` is the style's name.

    Raises
    ------
    FormatError
        Naming the file, and the line for JSON syntax errors.
    """
    from auszug.geometry import Arc, Curve, Line
    from auszug.geometry.offset import is_closed
    from auszug.tracery.model import GROUPS, ROLES, Region, Tracery
    from auszug.tracery.profile import Moulding
    from auszug.tracery.window import WindowParams

    check_text_size(text, name)
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as e:
        raise FormatError(f"not valid JSON: {e.msg}", name, e.lineno) from None
    if not isinstance(doc, dict) or doc.get("format") != FORMAT:
        raise FormatError(f'not a tracery document (expected "format": "{FORMAT}")', name)
    if doc.get("version") != VERSION:
        raise FormatError(f"unsupported version {doc.get('version')!r}; expected {VERSION}", name)
    try:
        params = WindowParams.from_mapping(_need(doc, "params", dict, "document", name))
    except ValueError as e:
        raise FormatError(f"params: {e}", name) from None
    regions = []
    for i, rd in enumerate(_need(doc, "regions", list, "document", name)):
        where = f"regions[{i}]"
        group = _need(rd, "group", str, where, name)
        role = _need(rd, "role", str, where, name)
        if group not in GROUPS or role not in ROLES:
            raise FormatError(f"{where}: unknown group {group!r} or role {role!r}", name)
        curves: list[Curve] = []
        for j, sd in enumerate(_need(rd, "segments", list, where, name)):
            w2 = f"{where}.segments[{j}]"
            kind = _need(sd, "kind", str, w2, name)
            p0 = _point(_need(sd, "start", list, w2, name), w2, name)
            p1 = _point(_need(sd, "end", list, w2, name), w2, name)
            try:
                if kind == "line":
                    curves.append(Line(p0, p1))
                elif kind == "arc":
                    c = _point(_need(sd, "center", list, w2, name), w2, name)
                    sweep = float(_need(sd, "sweep", (int, float), w2, name))
                    r = float(np.hypot(*(p0 - c)))
                    curves.append(Arc(c, r, math.atan2(p0[1] - c[1], p0[0] - c[0]), sweep))
                else:
                    raise FormatError(f"{w2}: kind must be 'line' or 'arc', got {kind!r}", name)
            except ValueError as e:
                raise FormatError(f"{w2}: {e}", name) from None
        if not curves or not is_closed(curves, 1e-7):
            raise FormatError(f"{where}: the segments do not form a closed loop", name)
        prof = _need(rd, "profile", dict, where, name)
        try:
            profile = Moulding(str(prof.get("name", "")), prof["points"], prof.get("bulge"), bool(prof.get("wall")))
        except (KeyError, ValueError) as e:
            raise FormatError(f"{where}.profile: {e}", name) from None
        regions.append(Region(
            _need(rd, "id", str, where, name), group, int(_need(rd, "depth", int, where, name)),
            tuple(curves), role, float(_need(rd, "border", (int, float), where, name)), profile,
            float(_need(rd, "face", (int, float), where, name)),
        ))  # fmt: skip
    return Tracery(tuple(regions), params, doc.get("style", ""))


def _write(obj: Any, name: str) -> str:
    return dumps(obj, indent=None) + "\n"


register(FileFormat("tracery_json", (".tracery.json", ".json"), "tracery", reader=loads, writer=_write))
