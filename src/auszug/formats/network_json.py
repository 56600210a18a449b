"""Network JSON (``.network.json``): the 3D curve network as sampled polylines.

The document is the exchange format of ``auszug build``; its required keys are
fixed (more may be added, never removed)::

    {"format": "auszug.network", "version": 1, "source": "<drawing file name>", "up": "z",
     "layers": [{"index": 0, "bottom": 0.0}, ...],
     "curves": [{"id": "0/r1m", "basic": 0, "layer": 0, "kind": "ogee", "rotation": 1,
                 "mirrored": true, "transform": [[a, b], [c, d]],
                 "points": [[x, y, z], ...], "prc": [x, y, z] or null}, ...]}

``points`` run from the curve's start (the ground end of an ogee) to its end
(the apex); z is the height. ``transform`` is the 2x2 linear part of the
symmetry element about the basic curve's symmetry centre (``center``, the
origin in every corpus drawing) that maps the basic curve's top view
(``r0``) onto this replica: ``xy = transform @ (xy0 - center) + center``.

Extra keys: top level ``parameterization``, ``samples``, ``basic_curves``
(symmetry, heights per basic curve) and ``prc_choices`` (which branch of
Algorithm 1 chose an automatic PRC); per curve ``segment``, ``piece`` and
``center``.

Floats are written with Python's shortest round-trip representation, so a
read gives back exactly the numbers that were written.
"""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import orjson

from auszug.errors import AuszugError, FormatError
from auszug.formats._registry import FileFormat, register
from auszug.geometry.network import KINDS, CurveNetwork, Piece, as_curve_network
from auszug.limits import check_count, check_number, check_text_size

__all__ = ["NetworkFile", "FORMAT", "VERSION", "VERSIONS", "KINDS", "to_dict", "dumps", "loads", "unpack",
           "exact_piece", "network_from_dict"]

FORMAT = "auszug.network"
#: The version written.
VERSION = 2
#: The versions read (version 2 adds ``tolerance``, per curve ``features`` and ``exact``).
VERSIONS = (1, 2)


@dataclass(frozen=True)
class NetworkFile:
    """What a network file holds: a network and the name of the drawing it was built from.

    The network writers (JSON, OBJ, SVG, DXF, 3dm, figures) accept either this
    or a bare network (whose name then stands in for the source).

    Attributes
    ----------
    network : CurveNetwork or a producer of one (``auszug.microarch.Network``)
    source : str
        File name of the drawing (``"tn-1.uc"``).
    """

    network: Any
    source: str = ""


def unpack(obj: Any) -> tuple[CurveNetwork, str]:
    """``(curve network, source)`` of a :class:`NetworkFile` or a bare network.

    Raises
    ------
    TypeError
        If ``obj`` holds no curve network.
    """
    if isinstance(obj, NetworkFile):
        net, source = obj.network, obj.source
    else:
        net, source = obj, ""
    cn = as_curve_network(net)
    return cn, source or cn.name


def _plain(v: Any) -> Any:
    """JSON-ready copy of dataclasses, numpy values, tuples and dicts."""
    if dataclasses.is_dataclass(v) and not isinstance(v, type):
        return {f.name: _plain(getattr(v, f.name)) for f in dataclasses.fields(v)}
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, dict):
        return {str(k): _plain(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    return v


def to_dict(network: Any, source: str = "") -> dict[str, Any]:
    """The network JSON document of ``network`` as plain Python data.

    Parameters
    ----------
    network : CurveNetwork or NetworkFile (or a producer of a curve network)
    source : str
        File name of the drawing it was built from (default: the network's name).

    Returns
    -------
    dict
        See the module docstring for the keys.

    Raises
    ------
    FormatError
        If a coordinate is not finite (JSON has no NaN).
    """
    doc = _document(network, source)
    for c in doc["curves"]:
        c["points"] = c["points"].tolist()
    return doc


def _document(network: Any, source: str = "") -> dict[str, Any]:
    """:func:`to_dict`, with each curve's points left an (n, 3) float64 array."""
    net, src = unpack(network)
    source = source or src
    curves = []
    for c in net.curves():
        if not np.all(np.isfinite(c.points)):
            raise FormatError(f"curve {c.id} has non-finite coordinates; cannot write JSON", source)
        curves.append({
            "id": c.id,
            "basic": int(c.basic),
            "layer": int(c.layer),
            "kind": c.kind,
            "rotation": int(c.rotation),
            "mirrored": bool(c.mirrored),
            "transform": np.asarray(c.transform, dtype=float).tolist(),
            "points": np.ascontiguousarray(c.points, dtype=np.float64),
            "prc": None if c.prc is None else np.asarray(c.prc, dtype=float).tolist(),
            "segment": int(c.segment),
            "piece": int(c.piece),
            "center": [float(v) for v in net.groups[c.basic].center],
            "features": [[name, int(i)] for name, i in c.features],
            "exact": net.exact(c),   # already JSON-ready (lists and floats)
        })
    meta = dict(net.meta)
    choices = [
        {"curve": int(k[0]), "segment": int(k[1]), **_plain(_choice_fields(v))}
        for k, v in sorted(meta.pop("prc_choices", {}).items())
    ]
    doc: dict[str, Any] = {
        "format": FORMAT,
        "version": VERSION,
        "source": source,
        "up": "z",
        "parameterization": meta.pop("parameterization", "arclength"),
        "samples": max((len(p.points) for p in net.pieces if p.top is not None), default=0),
        "tolerance": net.tolerance,
        "layers": [{"index": i, "bottom": float(z)} for i, z in enumerate(net.bottoms)],
        "basic_curves": _plain(meta.pop("basic_curves", [])),
        "prc_choices": choices,
        **{k: _plain(v) for k, v in meta.items()},
        "curves": curves,
    }
    return doc


def _choice_fields(ch: Any) -> dict[str, Any]:
    """An Algorithm 1 choice as a flat record (its intersection reduced to the essentials)."""
    if dataclasses.is_dataclass(ch):
        rec = {f.name: getattr(ch, f.name) for f in dataclasses.fields(ch)}
    elif isinstance(ch, dict):
        rec = dict(ch)
    else:
        rec = {"value": ch}
    rec.pop("curve", None)
    rec.pop("segment", None)
    return rec


def dumps(network: Any, source: str = "") -> str:
    """Network JSON text: one top-level key per line, one list entry (layer, curve, ...) per line.

    Examples
    --------
    >>> from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry, build
    >>> c = BasicCurve(((1.0, 0.0), (0.0, 0.0)), (Segment(),), ("ground", "apex"),
    ...                Symmetry(2), height=1.0, prc=(0.5,))
    >>> doc = loads(dumps(build(Drawing((c,)), samples=65), "demo.uc"))
    >>> doc["source"], [c["id"] for c in doc["curves"]], len(doc["curves"][0]["points"])
    ('demo.uc', ['0/r0', '0/r1'], 65)
    """
    doc = _document(network, source)
    out = []
    for key, v in doc.items():
        if isinstance(v, list) and v:
            rows = ",\n".join("  " + _compact(x) for x in v)
            out.append(f" {json.dumps(key)}: [\n{rows}\n ]")
        else:
            out.append(f" {json.dumps(key)}: {_compact(v)}")
    return "{\n" + ",\n".join(out) + "\n}\n"


def _compact(v: Any) -> str:
    """One value as compact JSON; floats in their shortest round-trip form (orjson), arrays too."""
    return orjson.dumps(v, option=orjson.OPT_SERIALIZE_NUMPY).decode()


def _write(obj: Any, name: str) -> str:
    net, source = unpack(obj)
    return dumps(net, source)


# -- reading ---------------------------------------------------------------------------------
def _number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _integer(v: Any) -> bool:
    return isinstance(v, int) and not isinstance(v, bool)


def _vector(v: Any, n: int) -> bool:
    return isinstance(v, list) and len(v) == n and all(_number(x) for x in v)


def loads(text: str, name: str = "<string>") -> dict[str, Any]:
    """Parse and validate network JSON text; return the document as a dict.

    Parameters
    ----------
    text : str
    name : str
        File name for messages.

    Raises
    ------
    FormatError
        Naming the file, the line (for JSON syntax errors) and the first key
        that does not hold what the format expects.
    """
    check_text_size(text, name)
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as e:
        raise FormatError(f"not JSON: {e.msg} (column {e.colno})", name, e.lineno) from None

    def bad(where: str, expected: str) -> FormatError:
        return FormatError(f"{where}: expected {expected}", name)

    if not isinstance(doc, dict):
        raise bad("document", "a JSON object")
    if doc.get("format") != FORMAT:
        raise bad("format", f'"{FORMAT}", got {doc.get("format")!r}')
    if doc.get("version") not in VERSIONS or not _integer(doc.get("version")):
        raise bad("version", f"one of {', '.join(map(str, VERSIONS))}, got {doc.get('version')!r}")
    if not isinstance(doc.get("source"), str):
        raise bad("source", "the drawing's file name (a string)")
    if doc.get("up") != "z":
        raise bad("up", f'"z", got {doc.get("up")!r}')
    layers = doc.get("layers")
    if not isinstance(layers, list):
        raise bad("layers", "a list")
    for i, lay in enumerate(layers):
        if not (isinstance(lay, dict) and lay.get("index") == i and _integer(lay.get("index"))
                and _number(lay.get("bottom"))):
            raise bad(f"layers[{i}]", f'{{"index": {i}, "bottom": <number>}}')
    curves = doc.get("curves")
    if not isinstance(curves, list):
        raise bad("curves", "a list")
    seen: set[str] = set()
    for i, c in enumerate(curves):
        w = f"curves[{i}]"
        if not isinstance(c, dict):
            raise bad(w, "an object")
        if not isinstance(c.get("id"), str) or not c["id"]:
            raise bad(f"{w}.id", "a non-empty string")
        if c["id"] in seen:
            raise bad(f"{w}.id", f"a unique id; {c['id']!r} appears twice")
        seen.add(c["id"])
        for key in ("basic", "rotation"):
            if not _integer(c.get(key)) or c[key] < 0:
                raise bad(f"{w}.{key}", "an integer >= 0")
        if not _integer(c.get("layer")) or not 0 <= c["layer"] < len(layers):
            raise bad(f"{w}.layer", f"a layer index in 0..{len(layers) - 1}")
        if c.get("kind") not in KINDS:
            raise bad(f"{w}.kind", f"one of {', '.join(KINDS)}, got {c.get('kind')!r}")
        if not isinstance(c.get("mirrored"), bool):
            raise bad(f"{w}.mirrored", "true or false")
        t = c.get("transform")
        if not (isinstance(t, list) and len(t) == 2 and all(_vector(r, 2) for r in t)):
            raise bad(f"{w}.transform", "a 2x2 matrix [[a, b], [c, d]]")
        pts = c.get("points")
        if not (isinstance(pts, list) and len(pts) >= 2 and all(_vector(p, 3) for p in pts)):
            raise bad(f"{w}.points", "a list of at least 2 [x, y, z] points")
        if c.get("prc", None) is not None and not _vector(c["prc"], 3):
            raise bad(f"{w}.prc", "null or an [x, y, z] point")
        if "prc" not in c:
            raise bad(f"{w}.prc", "null or an [x, y, z] point (the key is required)")
        feats = c.get("features", [])
        if not (isinstance(feats, list) and all(
                isinstance(f, list) and len(f) == 2 and isinstance(f[0], str) and _integer(f[1])
                and 0 <= f[1] < len(pts) for f in feats)):
            raise bad(f"{w}.features", f'a list of ["name", vertex index in 0..{len(pts) - 1}]')
        ex = c.get("exact")
        if ex is not None:
            try:
                exact_piece(c)
            except (KeyError, TypeError, ValueError, AuszugError) as e:
                raise bad(f"{w}.exact", f"an exact curve description ({type(e).__name__}: {e})") from None
    return doc


def exact_piece(curve: dict[str, Any]) -> Piece:
    """The exact curve of one curve record of a version-2 document, to evaluate.

    Examples
    --------
    >>> from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry, build
    >>> c = BasicCurve(((1.0, 0.0), (0.0, 0.0)), (Segment(),), ("ground", "apex"),
    ...                Symmetry(2), height=1.0, prc=(0.5,))
    >>> rec = loads(dumps(build(Drawing((c,)), samples=9)))["curves"][1]
    >>> p = exact_piece(rec)
    >>> bool(np.allclose(p.point_t(np.linspace(0, 1, 9)), rec["points"], rtol=0, atol=1e-12))
    True
    """
    return Piece.from_dict(curve["exact"], int(curve.get("basic", 0)), int(curve.get("segment", 0)))


def network_from_dict(doc: dict[str, Any], name: str = "<document>") -> CurveNetwork:
    """The exact curve network of a version-2 document (as :func:`loads` returns it).

    The basic pieces are the exact curves of the records of rotation 0, not
    mirrored (``r0``), in their ``piece`` order (the index into the network's
    pieces); each basic curve's symmetry
    group comes from ``basic_curves`` (fold, mirror, centre, axis), the
    identity where the document has none (a lifted sketch, a tracery window).
    Meshing the result gives what meshing the network it was written from
    gives.

    Parameters
    ----------
    doc : dict
        A validated network JSON document.
    name : str
        File name for messages.

    Raises
    ------
    FormatError
        For a version-1 document or a curve without its exact description
        (polylines only), naming the curve.

    Examples
    --------
    >>> from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry, build
    >>> c = BasicCurve(((1.0, 0.0), (0.0, 1.0)), (Segment(),), ("ground", "apex"), Symmetry(4, True), height=1.0)
    >>> net = build(Drawing((c,)))
    >>> back = network_from_dict(loads(dumps(net)))
    >>> [x.id for x in back.curves()] == [x.id for x in net.curves()], back.groups[0].order
    (True, 8)
    """
    from auszug.geometry.symmetry import SymmetryGroup

    basics = {int(b["index"]): b for b in doc.get("basic_curves", []) if isinstance(b, dict) and "index" in b}
    found: list[tuple[int, Piece]] = []
    layer_of: dict[int, int] = {}
    for i, c in enumerate(doc["curves"]):
        if c.get("exact") is None:
            raise FormatError(f"curves[{i}] ({c['id']}): no exact curve (a version-1 file holds polylines only); "
                              "write it again with this version", name)
        if c["rotation"] != 0 or c["mirrored"]:
            continue
        # the record's own samples (bounds, default member sizes and features are taken from them)
        found.append((int(c.get("piece", i)),
                      dataclasses.replace(exact_piece(c), points=np.asarray(c["points"], dtype=float))))
        layer_of[int(c["basic"])] = int(c["layer"])
    n_basic = len(layer_of)
    if sorted(layer_of) != list(range(n_basic)):
        raise FormatError("curves: every basic curve needs its r0 curves, numbered from 0", name)
    pieces = [p for _, p in sorted(found, key=lambda t: t[0])]
    groups: list[SymmetryGroup] = []
    for b in range(n_basic):
        info = basics.get(b)
        if info is None:
            groups.append(SymmetryGroup(1))
            continue
        try:   # basic_curves is an extra key: checked here, with the drawings' limits
            fold = info["fold"]
            if not _integer(fold):
                raise ValueError(f"fold must be a whole number, got {fold!r}")
            check_count("fold", int(fold), "fold")
            axis = (0.0, 1.0) if info.get("axis") is None else info["axis"]
            cx, cy = (check_number("centre", float(v)) for v in info["center"])
            ax, ay = (float(v) for v in axis)
            groups.append(SymmetryGroup(int(fold), bool(info["mirror"]), (cx, cy), (ax, ay)))
        except (KeyError, TypeError, ValueError, AuszugError) as e:
            raise FormatError(f"basic_curves (curve {b}): not a symmetry ({type(e).__name__}: {e})", name) from None
    verts = [v for b in basics.values() for v in b.get("vertices", [])]
    try:
        pts = np.asarray(verts, dtype=float) if verts else np.concatenate(
            [np.asarray(c["points"], dtype=float)[:, :2] for c in doc["curves"]])
    except (TypeError, ValueError) as e:
        raise FormatError(f"basic_curves: vertices must be [x, y] points ({e})", name) from None
    size = max(1e-9, float(np.abs(pts).max()))
    bottoms = tuple(float(lay["bottom"]) for lay in doc["layers"]) or (0.0,)
    return CurveNetwork(tuple(pieces), tuple(groups), tuple(layer_of[b] for b in range(n_basic)), bottoms,
                        size, str(doc.get("source", "")).rsplit(".", 1)[0], {}, (), doc.get("tolerance"))


register(FileFormat("network_json", (".network.json",), "network", reader=loads, writer=_write))
