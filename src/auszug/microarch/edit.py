"""Editing operations (paper sec. 4.4) as pure functions: drawing in, new drawing out.

Top-view edits (moving points, changing symmetry) leave every side-view
parameter alone: layer bottoms, apex heights, PRC fractions, decorations. Side-
view edits (heights, PRC, layer bottoms) leave the top view alone. With the
parameterisation p(u) = u the side view is then *exactly* unchanged by a top-view
edit, as sec. 4.4 promises; with the arc-length parameterisation the heights of
the bottom, the PRC and the apex are.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Literal

import numpy as np

from auszug.errors import DrawingError
from auszug.microarch.model import BasicCurve, Drawing, Segment, Symmetry

__all__ = [
    "move_vertex",
    "move_handle",
    "set_apex_height",
    "set_prc",
    "set_prc_height",
    "set_prc_at",
    "recompute_prc",
    "set_layer_bottom",
    "add_curve",
    "draw_curve",
    "remove_curve",
    "set_layer",
    "add_layer",
    "remove_layer",
    "set_decoration",
    "set_post",
    "set_symmetry",
]


def _check_curve(d: Drawing, i: int) -> BasicCurve:
    if not 0 <= i < len(d.curves):
        raise DrawingError(f"no curve {i}: the drawing has {len(d.curves)} curves")
    return d.curves[i]


def _check_ogee(d: Drawing, curve: int, segment: int) -> BasicCurve:
    """The curve, if ``segment`` is one of its ogee segments (a DrawingError otherwise)."""
    c = _check_curve(d, curve)
    n = len(c.marks) - 1
    if not 0 <= segment < n:
        raise DrawingError(f"no segment {segment} of curve {curve}: it has {n} segments (0..{n - 1})")
    if c.segment_kind(segment) != "ogee":
        raise DrawingError(f"segment {segment} of curve {curve} is not an ogee")
    return c


def _axis_follow(c: BasicCurve, verts: tuple) -> Symmetry:
    s = c.symmetry
    if not s.mirror:
        return s
    cen = np.asarray(s.center)
    if s.axis_rule == "first point":
        ax = np.asarray(verts[0]) - cen
    elif s.axis_rule == "last point":
        ax = np.asarray(verts[-1]) - cen
    else:
        return s
    if float(np.hypot(*ax)) <= 1e-12:
        return s
    return replace(s, axis=(float(ax[0]), float(ax[1])))


def move_vertex(d: Drawing, curve: int, vertex: int, xy: tuple[float, float]) -> Drawing:
    """Move a top-view vertex of a basic curve; its handles keep their positions.

    A mirror axis that follows the first or last point (``axis_rule``) follows it.

    Examples
    --------
    >>> from auszug.microarch import BasicCurve, Drawing, Segment
    >>> d = Drawing((BasicCurve(((0, 0), (1, 0)), (Segment(),), ("ground", "apex"), height=1.0),))
    >>> move_vertex(d, 0, 1, (2.0, 0.0)).curves[0].vertices
    ((0.0, 0.0), (2.0, 0.0))
    """
    c = _check_curve(d, curve)
    if not 0 <= vertex < len(c.vertices):
        raise DrawingError(f"curve {curve} has no point {vertex}")
    verts = list(c.vertices)
    verts[vertex] = (float(xy[0]), float(xy[1]))
    verts_t = tuple(verts)
    return d.with_curve(curve, c.with_(vertices=verts_t, symmetry=_axis_follow(c, verts_t)))


def move_handle(d: Drawing, curve: int, segment: int, handle: int, xy: tuple[float, float]) -> Drawing:
    """Move a tangent handle (arc) or inner control point (Bezier) of a segment."""
    c = _check_curve(d, curve)
    if not 0 <= segment < len(c.segments):
        raise DrawingError(f"curve {curve} has no segment {segment}")
    seg = c.segments[segment]
    if seg.kind == "line":
        seg = Segment("arc", ((float(xy[0]), float(xy[1])),))
    else:
        hs = list(seg.handles)
        if not 0 <= handle < len(hs):
            raise DrawingError(f"segment {segment} of curve {curve} has no handle {handle}")
        hs[handle] = (float(xy[0]), float(xy[1]))
        seg = Segment(seg.kind, tuple(hs))
    segs = list(c.segments)
    segs[segment] = seg
    return d.with_curve(curve, c.with_(segments=tuple(segs)))


def set_apex_height(d: Drawing, curve: int, height: float) -> Drawing:
    """Set the absolute apex height of a curve (the PRC keeps its top-view place)."""
    c = _check_curve(d, curve)
    return d.with_curve(curve, c.with_(height=float(height)))


def set_prc(d: Drawing, curve: int, fraction: float | None, segment: int = 0) -> Drawing:
    """Set the PRC of an ogee segment by its location (top-view arc-length fraction); ``None`` = automatic."""
    c = _check_ogee(d, curve, segment)
    prc = list(c.prc)
    prc[segment] = None if fraction is None else float(fraction)
    return d.with_curve(curve, c.with_(prc=tuple(prc)))


def set_prc_height(d: Drawing, curve: int, z: float, segment: int = 0) -> Drawing:
    """Set the PRC by its height; the apex height follows (sec. 4.3.2).

    The PRC keeps its top-view location and height ``z``: the apex moves to the
    intersection of the line A^s C^s with the vertical through B (Remark 1).
    """
    from auszug.microarch.network import build

    _check_ogee(d, curve, segment)
    net = build(d)
    piece = next(p for p in net.pieces if p.basic == curve and p.segment == segment and p.kind == "ogee")
    assert piece.top is not None and piece.prc_fraction is not None  # an ogee piece has both
    c = d.curves[curve]
    z0 = net.bottoms[c.layer]
    g_c = float(piece.g_of_t(piece.top.t_at_u(piece.prc_fraction)))
    G = float(piece.g_of_t(1.0))
    if not z > z0:
        raise DrawingError(f"PRC height {z:g} must be above the bottom {z0:g}")
    return set_apex_height(d, curve, z0 + (z - z0) * G / g_c)


def set_prc_at(d: Drawing, curve: int, point: tuple[float, float], segment: int = 0) -> Drawing:
    """Make the top-view point nearest to ``point`` on the ogee (e.g. a clicked intersection) its PRC."""
    from auszug.microarch.prc import oriented_segments

    _check_ogee(d, curve, segment)
    top = next(t for ci, si, t in oriented_segments(d) if ci == curve and si == segment)
    t = top.project(np.asarray(point, dtype=float))
    return set_prc(d, curve, float(top.u_at_t(t)), segment)


def recompute_prc(d: Drawing, curves: list[int] | None = None) -> Drawing:
    """Replace stored PRCs by Algorithm 1's choice (all curves, or the given ones)."""
    from auszug.microarch.prc import algorithm1

    choice = algorithm1(d)
    out = d
    for (ci, si), ch in choice.items():
        if curves is None or ci in curves:
            out = set_prc(out, ci, ch.fraction, si)
    return out


def set_layer_bottom(d: Drawing, layer: int, z: float) -> Drawing:
    """Set the bottom height of a layer (stores all bottoms explicitly)."""
    b = list(d.all_bottoms())
    if not 0 <= layer < len(b):
        raise DrawingError(f"no layer {layer}: the drawing has {len(b)} layers")
    b[layer] = float(z)
    return replace(d, layer_bottoms=tuple(b))


def add_layer(d: Drawing, bottom: float | None = None) -> Drawing:
    """Add an (empty) layer on top; its bottom defaults to the highest apex of the top layer."""
    b = list(d.all_bottoms())
    if bottom is None:
        top = len(b) - 1
        hs = [d.apex_height(i, b) for i, c in enumerate(d.curves) if c.layer == top]
        bottom = max(hs) if hs else b[-1] + 1.0
    b.append(float(bottom))
    return replace(d, layer_bottoms=tuple(b))


def remove_layer(d: Drawing, layer: int) -> Drawing:
    """Remove a layer and its curves; the layers above move down one index."""
    b = list(d.all_bottoms())
    if not 0 <= layer < len(b):
        raise DrawingError(f"no layer {layer}")
    curves = tuple(c.with_(layer=c.layer - (1 if c.layer > layer else 0)) for c in d.curves if c.layer != layer)
    del b[layer]
    return replace(d, curves=curves, layer_bottoms=tuple(b))


def add_curve(d: Drawing, curve: BasicCurve) -> Drawing:
    """Append a basic curve."""
    return replace(d, curves=d.curves + (curve,))


def draw_curve(
    d: Drawing,
    vertices: list[tuple[float, float]],
    handles: list[list[tuple[float, float]]],
    marks: list[str],
    fold: int = 1,
    mirror: Literal["none", "first point", "last point", "y axis"] = "none",
    layer: int = 0,
) -> Drawing:
    """Append a basic curve drawn by clicks (the studio's drawing tool).

    Parameters
    ----------
    vertices : list of (x, y)
        m >= 2 top-view points, drawing units.
    handles : list of list of (x, y)
        One entry per segment (m - 1): ``[]`` a line, ``[h]`` an arc whose
        tangent at the segment's first point aims at ``h``, ``[h1, h2]`` a cubic
        Bezier with inner control points h1, h2.
    marks : list of {"ground", "apex", "free"}
        One per vertex.
    fold, mirror
        The symmetry, as :func:`set_symmetry` takes it.
    layer : int
        An existing layer, or the next one above the top (created).

    Examples
    --------
    >>> d = draw_curve(Drawing(()), [(1, 0), (0, 0)], [[(1, 1)]], ["ground", "apex"], fold=4, mirror="first point")
    >>> c = d.curves[0]
    >>> c.segments[0].kind, c.symmetry.order, c.symmetry.axis_rule
    ('arc', 8, 'first point')
    """
    if len(handles) != len(vertices) - 1:
        raise DrawingError(f"{len(vertices)} points need {len(vertices) - 1} handle lists, got {len(handles)}")
    kinds: dict[int, Literal["line", "arc", "bezier"]] = {0: "line", 1: "arc", 2: "bezier"}
    segs = []
    for i, h in enumerate(handles):
        if len(h) not in kinds:
            raise DrawingError(f"segment {i}: expected 0 (line), 1 (arc) or 2 (Bezier) handles, got {len(h)}")
        segs.append(Segment(kinds[len(h)], tuple((float(p[0]), float(p[1])) for p in h)))
    n_layers = len(list(d.all_bottoms()))
    if isinstance(layer, bool) or not 0 <= layer <= n_layers:
        raise DrawingError(f"layer {layer} does not exist: the drawing has layers 0..{n_layers - 1} "
                           f"(or {n_layers} to add one on top)")
    if layer == n_layers:
        d = add_layer(d)
    c = BasicCurve(tuple((float(v[0]), float(v[1])) for v in vertices), tuple(segs), tuple(marks), layer=layer)
    out = add_curve(d, c)
    return set_symmetry(out, len(out.curves) - 1, fold=fold, mirror=mirror)


def set_layer(d: Drawing, curve: int, layer: int) -> Drawing:
    """Move a basic curve to another existing layer (its top view and heights are kept).

    Examples
    --------
    >>> d = Drawing((BasicCurve(((0, 0), (1, 0)), (Segment(),), ("ground", "apex"), height=1.0),), (0.0, 1.0))
    >>> set_layer(d, 0, 1).curves[0].layer
    1
    """
    c = _check_curve(d, curve)
    b = list(d.all_bottoms())
    if isinstance(layer, bool) or not 0 <= layer < len(b):
        raise DrawingError(f"no layer {layer}: the drawing has layers 0..{len(b) - 1}")
    return replace(d.with_curve(curve, c.with_(layer=layer)), layer_bottoms=tuple(b))


def remove_curve(d: Drawing, curve: int) -> Drawing:
    """Remove a basic curve."""
    _check_curve(d, curve)
    return replace(d, curves=d.curves[:curve] + d.curves[curve + 1 :])


def set_decoration(d: Drawing, curve: int, on: bool, at: float | None = None) -> Drawing:
    """Switch the decoration of a curve's ogee on or off; ``at``: where its arcs meet."""
    c = _check_curve(d, curve)
    return d.with_curve(curve, c.with_(decoration=bool(on), decoration_at=at if on else None))


def set_post(d: Drawing, curve: int, top: float | None) -> Drawing:
    """Add (absolute top height) or remove (``None``) a vertical post above the apex."""
    c = _check_curve(d, curve)
    return d.with_curve(curve, c.with_(post_top=None if top is None else float(top)))


def set_symmetry(
    d: Drawing,
    curve: int,
    fold: int | None = None,
    mirror: Literal["none", "first point", "last point", "y axis"] | None = None,
) -> Drawing:
    """Change a curve's rotation fold and/or its mirror (through its first or last point, the y axis, or none)."""
    c = _check_curve(d, curve)
    s = c.symmetry
    if fold is not None:
        s = replace(s, fold=fold)
    if mirror is not None:
        if mirror == "none":
            s = replace(s, mirror=False, axis_rule="fixed")
        else:
            cen = np.asarray(s.center)
            p = {"first point": c.vertices[0], "last point": c.vertices[-1], "y axis": None}[mirror]
            ax = (0.0, 1.0) if p is None else tuple((np.asarray(p) - cen).tolist())
            s = replace(s, mirror=True, axis=ax, axis_rule=mirror)
    return d.with_curve(curve, c.with_(symmetry=s))
