"""Sketch SVG (``.svg`` of kind ``"sketch"``): a design sketch as Inkscape and Illustrator write it.

Read with svgelements (MIT). Every shape (``path``, ``line``, ``polyline``,
``polygon``, ``rect``, ``circle``, ``ellipse``) is a stroke, one per subpath;
its segments of any kind become cubic Beziers (lines with handles at thirds,
quadratics degree-elevated, elliptical arcs by svgelements' cubic
approximation, six cubics for half a circle). A sampled curve, a run of at
least :data:`FIT_MIN_LINES` straight segments each turning from the last by
less than :data:`FIT_TURN_DEG` (a tablet's or a tracing tool's polyline), is
refitted by least squares as a G1 cubic chain within :data:`FIT_TOL` of the
sketch's diagonal of its vertices (:func:`auszug.lifting.fit.fit_polyline`;
its end points kept, corners between runs kept). Every ``transform`` and the root's
``viewBox`` are applied (coordinates are CSS px of the page, which are the
user units when there is no viewBox), and y is flipped to point up:
``y = -y_svg``.

A clone (``<use>``, Inkscape's Alt+D) is read as the element it shows, transformed, its
strokes named ``"<use id>: <element id>"``; hidden shapes (``display:none``, also of a
hidden layer, and ``visibility:hidden``) are not read, nor ``<defs>``.

Layers (``<g inkscape:groupmode="layer">``, the innermost one counts) are
independent parts, back to front in document order (shapes outside every
layer form one more part, placed by where its first shape comes). Annotations,
in any layer:

- ``<circle class="occlusion">``: the 2D crossing under its centre is not a
  3D intersection;
- ``<circle class="flip">``: flip the convexity of the intersection under it;
- ``<path class="symmetry">``: the global symmetry curve (at most one): half the object is
  drawn, the lift is mirrored across the curve's plane. It belongs to the layer it is drawn in if
  that layer has strokes, else (an annotation layer, outside the layers) to the layer whose
  strokes' bounding box it overlaps most.

Each marker snaps to the nearest crossing within 1 % of the sketch's diagonal.
The reader validates the sketch as :func:`auszug.lifting.lift` will, so a
sketch that cannot be lifted is refused here: empty or non-SVG text, NaN or
infinity in a shape's coordinates, zero-length or duplicate strokes, no
crossing, parts of a layer not joined by any crossing, a marker off every
crossing all give a :class:`~auszug.errors.FormatError` naming the element
(its ``id``, else ``<tag> #index`` in document order) and the problem.
See docs/formats.md.
"""

from __future__ import annotations

import io
import re
import xml.etree.ElementTree as ET
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from auszug.errors import FormatError, GeometryError
from auszug.formats._registry import FileFormat, register
from auszug.limits import LIMITS, beyond_coordinate

if TYPE_CHECKING:
    from auszug.lifting import Sketch, Stroke

__all__ = ["read_sketch_svg", "MARKER_CLASSES", "SYMMETRY_CLASS", "FIT_MIN_LINES", "FIT_TURN_DEG", "FIT_TOL",
           "FIT_MAX_SPANS"]

Array = NDArray[np.float64]

#: ``class`` names of the marker circles and the kind of marker each makes.
MARKER_CLASSES = ("occlusion", "flip")
#: ``class`` name of the global symmetry path.
SYMMETRY_CLASS = "symmetry"
#: A run of at least this many straight segments of one stroke is a sampled curve (fewer: a polygon's sides).
FIT_MIN_LINES = 4
#: ... each turning from the one before by less than this (degrees): larger turns are corners.
FIT_TURN_DEG = 30.0
#: A sampled curve's fit keeps its vertices within this share of the sketch's diagonal.
FIT_TOL = 2e-3
#: The most cubics of one sampled curve's fit (a run it cannot fit with these stays straight segments).
FIT_MAX_SPANS = 256

_SVG_NS = "http://www.w3.org/2000/svg"
_INKSCAPE = "{http://www.inkscape.org/namespaces/inkscape}"
_GEOMETRY_ATTRS = ("d", "points", "x", "y", "x1", "y1", "x2", "y2", "cx", "cy", "r", "rx", "ry", "width", "height",
                   "transform")
_NONFINITE = re.compile(r"(?i)(?<![a-z])(nan|inf)")


def _fail(problem: str, name: str, line: int | None = None) -> FormatError:
    return FormatError(problem, name, line)


def _check_xml(text: str, name: str) -> None:
    """Refuse empty, non-XML and non-SVG text with the XML parser's line."""
    if not text.strip():
        raise _fail("empty file; expected an SVG document", name)
    try:
        root = ET.fromstring(text)
    except ET.ParseError as e:
        raise _fail(f"not an SVG file: {e}", name, e.position[0] if e.position else None) from None
    tag = root.tag.rsplit("}", 1)[-1]
    if tag != "svg":
        raise _fail(f"not an SVG file: the root element is <{tag}>, expected <svg>", name)
    space = root.tag[1:].split("}", 1)[0] if root.tag.startswith("{") else ""
    if space not in ("", _SVG_NS):
        raise _fail(f"not an SVG file: its <svg> is in the namespace {space!r}, expected {_SVG_NS!r}", name)


def _cubic(seg: Any) -> list[Array]:
    """A path segment as cubic Bezier control arrays (4, 2), in SVG coordinates."""
    import svgelements as se

    def xy(p: Any) -> Array:
        return np.array([float(p.x), float(p.y)])

    if isinstance(seg, (se.Line, se.Close)):
        a, b = xy(seg.start), xy(seg.end)
        return [np.array([a, a + (b - a) / 3, a + 2 * (b - a) / 3, b])]
    if isinstance(seg, se.QuadraticBezier):
        a, c, b = xy(seg.start), xy(seg.control), xy(seg.end)
        return [np.array([a, a + 2 * (c - a) / 3, b + 2 * (c - b) / 3, b])]
    if isinstance(seg, se.CubicBezier):
        return [np.array([xy(seg.start), xy(seg.control1), xy(seg.control2), xy(seg.end)])]
    if isinstance(seg, se.Arc):
        return [_cubic(c)[0] for c in seg.as_cubic_curves()]
    return []


def _subpaths(path: Any) -> list[tuple[Array, NDArray[np.bool_]]]:
    """The subpaths of an svgelements Path as (m, 4, 2) cubic chains and (m,) masks of straight segments.

    A segment is straight when drawn by a ``Line`` or ``Close`` command. Zero-length pieces are
    dropped; a subpath of nothing but zero-length pieces gives an empty (0, 4, 2) chain, a bare
    move none.
    """
    import svgelements as se

    out: list[list[Array]] = []
    lines: list[list[bool]] = []
    drawn: list[bool] = []
    for seg in path:
        if isinstance(seg, se.Move):
            out.append([])
            lines.append([])
            drawn.append(False)
            continue
        if not out:
            out.append([])
            lines.append([])
            drawn.append(False)
        for c in _cubic(seg):
            drawn[-1] = True
            if np.ptp(c, axis=0).max() > 0 or not np.all(np.isfinite(c)):
                out[-1].append(c)
                lines[-1].append(isinstance(seg, (se.Line, se.Close)))
    return [(np.array(s).reshape(-1, 4, 2), np.array(k, dtype=bool))
            for s, k, d in zip(out, lines, drawn, strict=True) if d]


def _fit_sampled(c: Array, straight: NDArray[np.bool_], tol: float) -> Array:
    """The chain ``c`` (m, 4, 2) with each run of straight segments that samples a curve refitted.

    A run: at least :data:`FIT_MIN_LINES` consecutive straight segments, each turning from the one
    before by less than :data:`FIT_TURN_DEG`; refitted within ``tol`` of its vertices by
    :func:`~auszug.lifting.fit.fit_polyline` (at most :data:`FIT_MAX_SPANS` cubics, else left as it is).
    """
    from auszug.lifting.fit import fit_polyline

    d = c[:, 3] - c[:, 0]                       # chords (a closed curved segment's is zero: never joined)
    n = np.linalg.norm(d, axis=1)
    cos_turn = np.einsum("ij,ij->i", d[:-1], d[1:]) / np.maximum(n[:-1] * n[1:], 1e-300)
    joined = straight[:-1] & straight[1:] & (cos_turn > np.cos(np.radians(FIT_TURN_DEG)))
    pieces: list[Array] = []
    i = 0
    while i < len(c):
        j = i
        while j + 1 < len(c) and joined[j]:
            j += 1
        fit = None
        if straight[i] and j - i + 1 >= FIT_MIN_LINES:
            fit = fit_polyline(np.r_[c[i:j + 1, 0], c[j:j + 1, 3]], tol, min(FIT_MAX_SPANS, (j - i + 1) // 2))
        pieces.append(c[i:j + 1] if fit is None else fit)
        i = j + 1
    return np.concatenate(pieces)


def _own(e: Any) -> dict[str, str]:
    attrs = e.values.get("attributes", {})
    return attrs if isinstance(attrs, dict) else {}


def read_sketch_svg(text: str | bytes, name: str = "<string>") -> Sketch:
    """Read a sketch from SVG text (see the module docstring).

    Raises
    ------
    FormatError
        Naming the element and the problem (see the module docstring).

    Examples
    --------
    >>> svg = '''<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">
    ...   <path id="h" d="M 0 50 C 30 40 70 40 100 50"/>
    ...   <path id="v" d="M 45 0 Q 50 50 55 100"/>
    ... </svg>'''
    >>> s = read_sketch_svg(svg)
    >>> [(st.id, st.controls.shape) for st in s.strokes], s.strokes[0].controls[0, 0].tolist()
    ([('h', (1, 4, 2)), ('v', (1, 4, 2))], [0.0, -50.0])
    """
    import svgelements as se

    # lazy: reading a sketch, not registering the format, needs lifting (and scipy.spatial)
    from auszug.lifting import (
        Marker,
        Sketch,
        Stroke,
    )

    if isinstance(text, bytes):
        try:
            text = text.decode("utf-8")
        except UnicodeDecodeError as e:
            raise _fail(f"not a text file ({e.reason} at byte {e.start})", name) from None
    _check_xml(text, name)
    try:
        doc = se.SVG.parse(io.StringIO(text), reify=True)
    except Exception as e:  # svgelements raises plain exceptions on odd input
        raise _fail(f"not a readable SVG file: {e}", name) from None
    if not isinstance(doc, se.SVG):    # svgelements's own reading of the root: no SVG document
        raise _fail("not a readable SVG file: no <svg> document element", name)

    strokes: list[tuple[Any, Stroke]] = []     # (layer key, stroke)
    straights: list[NDArray[np.bool_]] = []    # per stroke: which of its segments are straight (as drawn)
    markers: list[Marker] = []
    symmetry: list[tuple[Any, Stroke]] = []   # (layer key, stroke)
    layer_names: dict[Any, str] = {}
    counter = [0]

    def label(e: Any, tag: str, index: int) -> str:
        return str(_own(e).get("id") or f"<{tag}> #{index}")

    def visit(group: Any, layer: Any, clone: str = "") -> None:
        for e in group:
            own = _own(e)
            tag = str(own.get("tag") or type(e).__name__.lower())
            if isinstance(e, se.Use):         # a clone (Inkscape's Alt+D): its element, transformed, named by it
                visit(e, layer, f"{clone}{label(e, tag, counter[0] + 1)}: ")
                continue
            if isinstance(e, se.Group):
                here = layer
                if own.get(f"{_INKSCAPE}groupmode") == "layer":
                    here = id(e)
                    layer_names[here] = str(own.get(f"{_INKSCAPE}label") or own.get("id") or
                                            f"layer {len(layer_names) + 1}")
                visit(e, here, clone)
                continue
            if not isinstance(e, se.Shape):
                continue
            if str(e.values.get("visibility", "")).strip() in ("hidden", "collapse"):
                continue                      # not drawn (``display:none`` svgelements leaves out itself)
            counter[0] += 1
            where = clone + label(e, tag, counter[0])
            for attr in _GEOMETRY_ATTRS:
                if _NONFINITE.search(str(own.get(attr, ""))):
                    raise _fail(f"{where}: NaN or infinity in its {attr!r} attribute", name)
            classes = str(own.get("class", "")).split()
            kinds = [k for k in MARKER_CLASSES if k in classes]
            if kinds:
                if len(kinds) > 1:
                    raise _fail(f"{where}: a marker is one of {', '.join(MARKER_CLASSES)}, not both", name)
                if not isinstance(e, (se.Circle, se.Ellipse)):
                    raise _fail(f"{where}: a {kinds[0]} marker must be a <circle>", name)
                box = e.bbox()
                if box is None:
                    raise _fail(f"{where}: a marker circle without extent", name)
                c = np.array([(box[0] + box[2]) / 2, -(box[1] + box[3]) / 2], dtype=float)
                if not np.all(np.isfinite(c)) or np.abs(c).max() > LIMITS.coordinate:
                    raise _fail(f"{where}: the marker's centre {c.tolist()} is not finite or beyond the limit of "
                                f"+-{LIMITS.coordinate:g} (auszug.limits.LIMITS.coordinate)", name)
                markers.append(Marker(kinds[0], c, where))
                continue
            path = e if isinstance(e, se.Path) else se.Path(e)
            subs = _subpaths(path)
            if not subs:
                raise _fail(f"{where}: an empty shape (no segments); expected a drawn stroke", name)
            for k, (c, straight) in enumerate(subs):
                sid = where if len(subs) == 1 else f"{where} subpath {k + 1}"
                if not len(c) or not np.all(np.isfinite(c)):
                    raise _fail(f"{sid}: {'zero-length stroke' if not len(c) else 'coordinates are not finite'}",
                                name)
                if (far := beyond_coordinate(float(np.abs(c).max()))) is not None:
                    raise _fail(f"{sid}: {far}", name)
                c = c.copy()
                c[..., 1] *= -1.0
                if SYMMETRY_CLASS in classes:
                    symmetry.append((layer, Stroke(c, sid)))
                else:
                    strokes.append((layer, Stroke(c, sid)))
                    straights.append(straight)

    visit(doc, None)
    if not strokes:
        raise _fail("no strokes: the SVG has no path or shape to lift (besides markers)", name)
    n_drawn = sum(len(s.controls) for _, s in strokes)
    if n_drawn > LIMITS.sketch_segments:      # as drawn, before the sampled curves' fit: bounds its cost
        raise _fail(f"the sketch has {n_drawn} Bezier segments: more than the limit of {LIMITS.sketch_segments} "
                    "(auszug.limits.LIMITS.sketch_segments)", name)
    tol = FIT_TOL * Sketch(tuple(s for _, s in strokes)).diagonal()
    strokes = [(k, Stroke(_fit_sampled(s.controls, b, tol), s.id) if b.sum() >= FIT_MIN_LINES else s)
               for (k, s), b in zip(strokes, straights, strict=True)]
    if len(symmetry) > 1:
        raise _fail(f"{symmetry[1][1].id}: a second symmetry path; a sketch has at most one", name)
    order = list(dict.fromkeys(k for k, _ in strokes))   # layers back to front, in document order
    index = {k: i for i, k in enumerate(order)}
    names = tuple(layer_names.get(k, "(no layer)") for k in order)
    out = tuple(Stroke(s.controls, s.id, index[k]) for k, s in strokes)
    sym = None
    if symmetry:
        key, st = symmetry[0]
        # in a layer of strokes: that layer; elsewhere (an annotation layer, outside the layers): the
        # layer whose strokes' bounding box it overlaps most
        lay = index[key] if key in index else _overlapping_layer(st, out)
        if lay is None:
            raise _fail(f"{st.id}: the symmetry path overlaps no layer's strokes; draw it in the layer of the "
                        "half it mirrors", name)
        sym = Stroke(st.controls, st.id, lay)
    sketch = Sketch(out, tuple(markers), sym, Path(name).stem, names)
    check(sketch, name)
    return sketch


def _overlapping_layer(sym: Stroke, strokes: tuple[Stroke, ...]) -> int | None:
    """The layer whose strokes' bounding box overlaps the symmetry path's the most (its first if tied).

    Overlap is the area of the boxes' intersection, or its length where one box is flat (a straight
    axis); None when it overlaps no layer's box.
    """
    c = sym.controls.reshape(-1, 2)
    lo, hi = c.min(0), c.max(0)
    best, best_v = None, 0.0
    for lay in sorted({s.layer for s in strokes}):
        pts = np.concatenate([s.controls.reshape(-1, 2) for s in strokes if s.layer == lay])
        ext = np.minimum(hi, pts.max(0)) - np.maximum(lo, pts.min(0))
        if np.any(ext < 0):
            continue
        v = float(np.prod(ext)) or float(ext.max())
        if best is None or v > best_v:
            best, best_v = lay, v
    return best


def check(sketch: Sketch, name: str) -> None:
    """Refuse a sketch :func:`auszug.lifting.lift` cannot lift, as a FormatError naming the file.

    A sketch refused with the default parameters but accepted with gaps closed up to the limit
    (``LiftParams.close_gaps``, a lifting parameter the reader does not know) is read: the lift
    refuses it, with the same message, unless it is asked to close those gaps.
    """
    from auszug.lifting import (  # lazy: reading a sketch, not registering the format, needs lifting
        CLOSE_GAPS_MAX,
        DEFAULT,
        layer_graphs,
    )

    try:
        layer_graphs(sketch)
    except GeometryError as e:
        try:
            layer_graphs(sketch, replace(DEFAULT, close_gaps=CLOSE_GAPS_MAX))
        except GeometryError:
            raise FormatError(str(e), name) from None


register(FileFormat("sketch_svg", (".svg",), "sketch", reader=read_sketch_svg))
