"""The ``.uc`` drawing files of the corpus: web dialect (read/write), legacy and v1 (read).

The web dialect ("saved state" of the authors' web demo) is documented in
``auszug/examples/FORMATS.md``. :func:`read_uc` recognises the dialect by the
``unitCurve`` line: two numbers (``n_rot has_reflection``) is the web dialect,
three (``n_points n_rot has_reflection``) the legacy or v1 dialect.
"""

from __future__ import annotations

import math
from typing import Any

from auszug.errors import DrawingError, FormatError
from auszug.formats import uc_text
from auszug.formats._registry import FileFormat, register
from auszug.formats.uc_legacy import read_legacy
from auszug.formats.uc_text import MAX_NUMBER
from auszug.limits import LIMITS
from auszug.microarch.model import BasicCurve, Drawing, Segment, Source, Symmetry

__all__ = ["MAX_NUMBER", "read_uc", "read_web", "write_web"]

_WEB_KEYS = {
    "numCurves", "unitCurve", "reflectionPoint", "ref_symmetry_type", "ptPos", "level",
    "height", "prc_t", "decoration_t", "decoration_height", "vertical_line_top", "layer_bottom",
}
#: Keys whose numbers are not coordinates or heights: their own checks bound them.
_COUNTS_AND_FRACTIONS = {"level", "prc_t", "decoration_t"}


def read_uc(text: str, path: str = "<string>") -> Drawing:
    """Read any dialect of ``.uc`` text into a :class:`Drawing`.

    Parameters
    ----------
    text : str
        File contents.
    path : str
        File name used in error messages and as the drawing name.

    Raises
    ------
    FormatError
        Naming the file, the line and the problem.
    """
    empty = True
    for _no, toks in uc_text.iter_lines(text, path):
        empty = False
        if toks[0] == "unitCurve":
            if len(toks) - 1 == 3:
                return read_legacy(text, path)
            break
    if empty:
        raise FormatError("empty file: expected 'numCurves N' then curves", path)
    return read_web(text, path)


# The authors' web demo draws A, T, B as a straight line when the handle T deviates
# from the chord AB by less than 0.01 rad (observed in the reference outputs: every
# curve up to 0.524 deg is drawn straight, every one from 0.594 deg curved), and the
# drawings made with it rely on that: the chancel's straight ribs are stored with
# handles up to 0.52 deg off. We read such segments as the lines their authors saw.
WEB_LINE_ANGLE = 0.01


def _web_segment(a: tuple, t: tuple, b: tuple) -> Segment:
    ux, uy = t[0] - a[0], t[1] - a[1]
    wx, wy = b[0] - a[0], b[1] - a[1]
    ang = abs(math.atan2(ux * wy - uy * wx, ux * wx + uy * wy))
    if ang < WEB_LINE_ANGLE:
        return Segment("line")
    return Segment("arc", (t,))


def read_web(text: str, path: str = "<string>") -> Drawing:
    """Read the web dialect (see FORMATS.md)."""
    declared: int | None = None
    curves: list[dict[str, Any]] = []  # one record of the lines of each curve
    bottoms: list[float] = []
    for no, toks in uc_text.iter_lines(text, path):
        key, args = toks[0], toks[1:]
        if key not in _WEB_KEYS:
            raise FormatError(f"unknown keyword {key!r}", path, no)
        if key == "numCurves":
            declared = uc_text.integer(uc_text.numbers(args, 1, key, path, no, None)[0], key, path, no, 0,
                                       "curves")
            continue
        if key == "unitCurve":
            if len(args) != 2:
                raise FormatError(
                    f"'unitCurve' needs 2 numbers (rotation fold, has reflection), got {len(args)}",
                    path, no)
            fold, refl = uc_text.numbers(args, 2, key, path, no, None)
            if len(curves) == LIMITS.curves:
                raise FormatError(f"more than {LIMITS.curves} curves (auszug.limits.LIMITS.curves)", path, no)
            cur: dict[str, Any] = {
                "line": no,
                "fold": uc_text.integer(fold, "unitCurve fold", path, no, 1, "fold"),
                "mirror": bool(uc_text.integer(refl, "unitCurve has_reflection", path, no, 0)),
                "points": [],
            }
            if refl not in (0.0, 1.0):
                raise FormatError(f"'unitCurve' reflection flag must be 0 or 1, got {refl:g}", path, no)
            curves.append(cur)
            continue
        if key == "layer_bottom":
            z = uc_text.numbers(args, 1, key, path, no)[0]
            if len(bottoms) < LIMITS.layers:  # the web demo writes hundreds; those of used layers count
                bottoms.append(z)
            continue
        if not curves:
            raise FormatError(f"{key!r} before the first 'unitCurve'", path, no)
        if bottoms:
            raise FormatError(f"{key!r} after the 'layer_bottom' lines", path, no)
        cur = curves[-1]
        if key == "ptPos":
            if len(cur["points"]) == 5:
                raise FormatError(f"curve {len(curves) - 1} has a 6th 'ptPos' point; expected 3 (A, T, B) "
                                  "or 5 (A, T, B, T2, C)", path, no)
            cur["points"].append((tuple(uc_text.numbers(args, 2, key, path, no)), no))
        elif key == "reflectionPoint":
            cur["axis"] = tuple(uc_text.numbers(args, 2, key, path, no))
            cur["axis_line"] = no
        elif key == "ref_symmetry_type":
            rule = {"first": "first point", "last": "last point", "y": "y axis"}.get(
                " ".join(args), " ".join(args))
            if rule not in ("first point", "last point", "y axis"):
                raise FormatError(
                    f"'ref_symmetry_type' must be 'first point', 'last point' or 'y axis', got {rule!r}",
                    path, no)
            cur["rule"] = rule
        else:
            if key in cur:
                raise FormatError(f"{key!r} given twice for one curve", path, no)
            bound = None if key in _COUNTS_AND_FRACTIONS else LIMITS.coordinate
            cur[key] = (uc_text.numbers(args, 1, key, path, no, bound)[0], no)
    if not curves:
        raise FormatError("no 'unitCurve' found: not a drawing", path)
    if declared is not None and declared != len(curves):
        raise FormatError(f"'numCurves {declared}' but {len(curves)} curves follow", path)

    basics = []
    for ci, cur in enumerate(curves):
        where = f"curve {ci} (line {cur['line']})"
        pts = cur["points"]
        if len(pts) not in (3, 5):
            raise FormatError(
                f"curve {ci} has {len(pts)} 'ptPos' points; expected 3 (A, T, B) or 5 (A, T, B, T2, C)",
                path, cur["line"])
        level = 0
        if "level" in cur:
            v, no = cur["level"]
            level = uc_text.integer(v, "level", path, no, 0, "layers", 1)
        prc = None
        if "prc_t" in cur:
            v, no = cur["prc_t"]
            if not 0.0 < v < 1.0:
                raise FormatError(f"'prc_t' must lie strictly between 0 and 1, got {v:g}", path, no)
            prc = v
        deco = False
        deco_at = None
        if "decoration_t" in cur:
            v, no = cur["decoration_t"]
            if not 0.0 <= v < 1.0:
                raise FormatError(f"'decoration_t' must lie in [0, 1), got {v:g}", path, no)
            deco = v > 0.0
            deco_at = v if deco else None
            if deco and prc is not None and v >= prc:
                raise FormatError(f"'decoration_t' {v:g} must lie below 'prc_t' {prc:g}", path, no)
        post = None
        if "vertical_line_top" in cur and cur["vertical_line_top"][0] != 0.0:
            post = cur["vertical_line_top"][0]
        axis = cur.get("axis", (0.0, 1.0))
        if cur["mirror"] and math.hypot(*axis) <= 1e-12:
            raise FormatError("mirror axis of zero length: 'reflectionPoint' is the origin",
                              path, cur.get("axis_line", cur["line"]))
        p = [xy for xy, _ in pts]
        for a, b in ((0, 1), (0, 2)) + (((2, 3), (2, 4)) if len(p) == 5 else ()):
            if math.hypot(p[b][0] - p[a][0], p[b][1] - p[a][1]) <= 1e-12:
                what = "tangent handle" if b in (1, 3) else "end point"
                raise FormatError(f"{where}: {what} (point {b}) coincides with point {a}", path, pts[b][1])
        verts = [p[0], p[2]] + ([p[4]] if len(p) == 5 else [])
        segs = [_web_segment(p[0], p[1], p[2])] + ([_web_segment(p[2], p[3], p[4])] if len(p) == 5 else [])
        marks = ["ground", "apex"] + (["free"] if len(p) == 5 else [])
        try:
            sym = Symmetry(cur["fold"], cur["mirror"], axis, (0.0, 0.0),
                           cur.get("rule", "fixed") if cur["mirror"] else "fixed")
            basics.append(BasicCurve(
                vertices=tuple(verts), segments=tuple(segs), marks=tuple(marks), symmetry=sym,
                layer=level, height=cur["height"][0] if "height" in cur else None,
                prc=(prc,) + ((None,) if len(p) == 5 else ()), decoration=deco,
                decoration_at=deco_at, post_top=post,
                source=Source(cur["line"], cur["height"][1] if "height" in cur else None,
                              tuple(range(0, len(p), 2)), tuple(pts[k][1] for k in range(0, len(p), 2))),
            ))
        except DrawingError as e:
            raise FormatError(f"{where}: {e}", path, cur["line"]) from None
    n_layers = max(c.layer for c in basics) + 1
    try:
        return Drawing(curves=tuple(basics), layer_bottoms=tuple(bottoms[:n_layers]), name=uc_text.stem(path))
    except DrawingError as e:
        raise FormatError(str(e), path) from None


def _fmt(v: float) -> str:
    return repr(float(v))


def write_web(drawing: Drawing, name: str = "") -> str:
    """Write ``drawing`` in the web dialect.

    Automatic PRCs are written as Algorithm 1 chooses them; decorations as the
    point where the two equal-radius arcs meet.

    Raises
    ------
    FormatError
        If a curve cannot be expressed in the web dialect (not A, T, B[, T2, C]
        arcs with ground, apex[, free] marks, or a symmetry centre off the origin).
    """
    from auszug.microarch.network import build

    for ci, c in enumerate(drawing.curves):
        ok_marks = c.marks in (("ground", "apex"), ("ground", "apex", "free"))
        ok_segs = all(s.kind in ("arc", "line") for s in c.segments)
        if not ok_marks or not ok_segs:
            raise FormatError(
                f"curve {ci} cannot be written in the web .uc dialect (it needs a ground point, "
                f"an apex and an optional free end joined by arcs); save as .json instead", name)
        if c.symmetry.center != (0.0, 0.0):
            raise FormatError(f"curve {ci}: the web .uc dialect needs the symmetry centre at the "
                              "origin; save as .json instead", name)
    net = build(drawing)
    out = [f"numCurves {len(drawing.curves)}"]
    for ci, c in enumerate(drawing.curves):
        sym = c.symmetry
        out.append(f"unitCurve {sym.fold} {1 if sym.mirror else 0}")
        if sym.mirror:
            out.append(f"reflectionPoint {_fmt(sym.axis[0])} {_fmt(sym.axis[1])}")
            if sym.axis_rule != "fixed":  # absent means fixed (as in u.xi.19-design1.uc)
                out.append(f"ref_symmetry_type {sym.axis_rule}")
        pts = []
        for si, seg in enumerate(c.segments):
            a, b = c.vertices[si], c.vertices[si + 1]
            if seg.kind == "line":
                h = (a[0] + (b[0] - a[0]) / 3.0, a[1] + (b[1] - a[1]) / 3.0)
            else:
                h = seg.handles[0]
            if si == 0:
                pts.append(a)
            pts += [h, b]
        for x, y in pts:
            out.append(f"ptPos {_fmt(x)} {_fmt(y)}")
        piece = net.ogee_of(ci)
        assert piece.prc_fraction is not None  # every ogee piece has its PRC
        out.append(f"level {c.layer}")
        out.append(f"height {_fmt(net.apex_heights[ci])}")
        out.append(f"prc_t {_fmt(piece.prc_fraction)}")
        if piece.decoration_point is not None:
            u_d, z_d = piece.decoration_point
            out.append(f"decoration_t {_fmt(u_d)}")
            out.append(f"decoration_height {_fmt(z_d)}")
        else:
            out.append("decoration_t 0")
            out.append("decoration_height 0")
        if c.post_top is not None:
            out.append(f"vertical_line_top {_fmt(c.post_top)}")
    for z in net.bottoms:
        out.append(f"layer_bottom {_fmt(z)}")
    return "\n".join(out) + "\n"


register(FileFormat("uc", (".uc",), "drawing", reader=read_uc, writer=write_web))
