"""The legacy (MATLAB-era) and v1 dialects of ``.uc`` drawing files (read only).

Both dialects start a basic curve with ``unitCurve n_points n_rot has_reflection``
(three numbers; the web dialect has two) and mark every point with ``ptLab``
(0 ground, 1 apex, 2 free end). They differ in how a curved segment is given.

Legacy (``corpus/legacy``), tab separated::

    numCurves N
    unitCurve n_points n_rot has_reflection
    reflectionPoint x y        if has_reflection: axis through the origin and (x, y)
    ptPos x y                  n_points times, each optionally followed by
    ptTan dx dy                a tangent handle VECTOR relative to ptPos
    ptLab 0|1|2

v1 (``corpus/web/two_curves.uc``): per curve the points, with the two inner
control points of a cubic segment written between its end points, then the
labels; ``n_points`` counts the ``ptPos`` *and* ``ptTangent`` lines (the only
v1 file declares 4 for 2 ``ptPos``, 2 ``ptTangent`` and 2 ``ptLab``)::

    unitCurve n_controls n_rot has_reflection
    reflectionPoint x y
    ptPos x0 y0
    ptTangent x y              absolute control points (0 or 2 per segment)
    ptTangent x y
    ptPos x1 y1
    ptLab 0
    ptLab 1

Conventions, and the evidence for them
--------------------------------------
**Legacy ptTan: segment i is the cubic P_i, P_i + t_i, P_{i+1} + t_{i+1}, P_{i+1}.**
Each handle vector points from its vertex *into* the segment. In the corpus
only 2-point curves carry ``ptTan`` (U.XI.20, 22, 24, 25, 29, 30, 31, 33, 34,
35), always on both points. The four sign conventions (P_0 +- t_0,
P_1 +- t_1) were compared on all ten files:

- Total turning of the basic curves, summed per file (deg), convention
  (+,+) / (+,-) / (-,+) / (-,-): U.XI.20 235/633/551/835, U.XI.22
  322/714/905/1120, U.XI.24 142/389/419/576, U.XI.25 175/384/349/534, U.XI.29
  197/422/395/519, U.XI.30 135/231/247/224, U.XI.31 188/308/365/432, U.XI.33
  153/421/390/565, U.XI.34 269/683/571/806, U.XI.35 313/765/843/1118. (+,+) is
  the least wiggly in every file; the others make S-bends and loops.
- Crossings between replicas away from shared end points: (+,+) has the
  fewest (or ties) in every file, e.g. U.XI.24 0/6/18/18, U.XI.31 8/16/64/56.
- Smooth joins where the goldsmiths drew them smooth: U.XI.22 curves 0 and 1
  start at (0.4, 0.4) with opposite vectors (-0.1, 0.25) and (0.1, -0.25), so
  under (+,+) they continue each other with a common tangent (one smooth
  S-curve from (0, 1) through (0.4, 0.4) to (1, 0)). Points on a mirror axis
  carry a vector perpendicular to it (U.XI.25 end (0, -0.6), U.XI.30 start
  (-0.7, 0), U.XI.31 start (0, 0.9)): mirror replicas meet with a common
  tangent, and under (+,+) they approach from the curve's own side instead of
  overshooting the axis and crossing each other.
- The authors redrew U.XI.29, 31 and 34 in the web dialect (``corpus/web``,
  circular arcs, rotated, mirrored and rescaled). The angle between an end
  tangent and the chord does not change under such maps; web arc / P + t /
  P - t, at the ground end then the apex: U.XI.29 curve 0 35/65/115 and
  35/44/137, curve 1 35/43/137 and 35/47/133; U.XI.31 curve 0 49/45/135 and
  49/45/135, curve 1 40/33/148 (its apex vector is zero); U.XI.34 curve 0
  (web curve 2) 32/52/128 and 32/38/142. P + t is within 30 deg of the redraw
  everywhere, P - t 80-115 deg off: the handle points into the segment.

At an *interior* vertex (a curve of more than 2 points, which the corpus never
gives a ``ptTan``) we read the vector as the direction of travel: the outgoing
segment's handle is P + t and the incoming one's P - t, so the curve is smooth
there. A point without ``ptTan`` has the zero vector; a segment whose two
handle vectors are both zero is a straight :class:`~auszug.microarch.model.Segment`
(``"line"``), any other a ``"bezier"`` with absolute handles.

**v1 ptTangent values are absolute control points in Bezier order**
(P_0, C_1, C_2, P_1). In ``two_curves.uc`` they lie in the same range as the
``ptPos`` values (|C| up to 0.82; legacy vectors are 0.01-2 long offsets), and
read as absolute points curve 0's handles lie within 0.035 of its chord (a
nearly straight rib) and the drawing has 4 replica crossings and 170 deg of
total turning; read as vectors relative to their points (in either sign) the
same curves turn 306-466 deg and bulge far past the drawing. Two equal
handles on their end points are read as a line, as in the legacy dialect.

Symmetry axis. ``reflectionPoint`` is written with 6 decimals, ``ptPos`` with
12; where it equals the curve's first (or last) point to that precision the
axis is taken through that exact point (so a vertex on the axis is its own
mirror image, exactly) with axis rule ``"first point"`` (``"last point"``);
a point (0, y) gives ``"y axis"``; any other is ``"fixed"``.

Heights are not stored: every curve is on layer 0, which starts at height 0,
with the PRC left to Algorithm 1 and the apex height of the authors' prototype,
``Drawing.default_apex`` = H = max(1, longest chord of any segment).
"""

from __future__ import annotations

import math

from auszug.errors import DrawingError, FormatError
from auszug.formats import uc_text
from auszug.limits import LIMITS
from auszug.microarch.model import AxisRule, BasicCurve, Drawing, Segment, Source, Symmetry

__all__ = ["LABEL_MARKS", "read_legacy"]

#: ``ptLab`` value -> vertex mark.
LABEL_MARKS: dict[int, str] = {0: "ground", 1: "apex", 2: "free"}

_KEYS = {"numCurves", "unitCurve", "reflectionPoint", "ptPos", "ptTan", "ptTangent", "ptLab"}

# reflectionPoint is written with 6 decimals: it names a curve point when it
# agrees with it to this distance in each coordinate (half a unit of the 6th
# decimal, with room for the rounding of the 12-decimal point).
_AXIS_POINT_TOL = 1e-6


class _Curve:
    """A curve while it is being read."""

    def __init__(self, line: int, n_points: int, fold: int, mirror: bool):
        self.line = line
        self.n_points = n_points
        self.fold = fold
        self.mirror = mirror
        self.axis: tuple[float, float] | None = None
        self.axis_line = line
        self.points: list[tuple[float, float]] = []
        self.point_lines: list[int] = []
        self.tans: list[tuple[float, float] | None] = []  # legacy: one vector per point
        self.gaps: list[list[tuple[tuple[float, float], int]]] = []  # v1: handles after point i
        self.labels: list[tuple[int, int]] = []
        self.n_controls = 0  # ptPos + ptTangent lines so far (what n_points counts)


def _add_point(cur: _Curve, ci: int, xy: list[float], path: str, no: int) -> None:
    if cur.n_controls == cur.n_points:
        raise FormatError(
            f"curve {ci} declares {cur.n_points} points but this is point number "
            f"{cur.n_points + 1}", path, no)
    p = (xy[0], xy[1])
    if cur.points and math.hypot(p[0] - cur.points[-1][0], p[1] - cur.points[-1][1]) <= 1e-12:
        raise FormatError(
            f"curve {ci}: point {len(cur.points)} coincides with point {len(cur.points) - 1} "
            "(zero-length segment)", path, no)
    if cur.gaps and len(cur.gaps[-1]) not in (0, 2):
        h_no = cur.gaps[-1][0][1]
        raise FormatError(
            f"curve {ci}: a curved segment needs 2 'ptTangent' control points between its "
            f"'ptPos' lines, got {len(cur.gaps[-1])}", path, h_no)
    cur.points.append(p)
    cur.n_controls += 1
    cur.point_lines.append(no)
    cur.tans.append(None)
    cur.gaps.append([])


def _segments(cur: _Curve) -> list[Segment]:
    """Top-view segments between consecutive points (see the module notes)."""
    pts = cur.points
    m = len(pts)
    out = []
    for i in range(m - 1):
        a, b = pts[i], pts[i + 1]
        if cur.gaps[i]:
            h0, h1 = cur.gaps[i][0][0], cur.gaps[i][1][0]
        else:
            ta = cur.tans[i] or (0.0, 0.0)
            tb = cur.tans[i + 1] or (0.0, 0.0)
            sb = 1.0 if i + 1 == m - 1 else -1.0  # last vertex: into the segment; interior: travel
            h0 = (a[0] + ta[0], a[1] + ta[1])
            h1 = (b[0] + sb * tb[0], b[1] + sb * tb[1])
        if h0 == a and h1 == b:
            out.append(Segment("line"))
        else:
            out.append(Segment("bezier", (h0, h1)))
    return out


def _symmetry(cur: _Curve) -> Symmetry:
    axis = cur.axis if cur.axis is not None else (0.0, 1.0)
    rule: AxisRule = "fixed"
    ends: tuple[tuple[tuple[float, float], AxisRule], ...] = ((cur.points[0], "first point"),
                                                             (cur.points[-1], "last point"))
    if cur.mirror:
        for cand, name in ends:
            if all(abs(u - v) <= _AXIS_POINT_TOL for u, v in zip(axis, cand, strict=True)) and math.hypot(*cand) > 0:
                axis, rule = cand, name
                break
        else:
            if axis[0] == 0.0 and axis[1] != 0.0:
                rule = "y axis"
    return Symmetry(cur.fold, cur.mirror, axis, (0.0, 0.0), rule)


def read_legacy(text: str, path: str = "<string>") -> Drawing:
    """Read the legacy or v1 dialect of ``.uc`` text into a :class:`Drawing`.

    Parameters
    ----------
    text : str
        File contents.
    path : str
        File name used in error messages and (its stem) as the drawing name.

    Returns
    -------
    Drawing
        One basic curve per ``unitCurve``, all on layer 0 with automatic PRCs and
        ``default_apex`` = max(1, longest segment chord).

    Raises
    ------
    FormatError
        Naming the file, the line and the problem.

    Examples
    --------
    >>> d = read_legacy('''numCurves 1
    ... unitCurve 2 4 1
    ... reflectionPoint -0.8 0
    ... ptPos -0.8 0
    ... ptLab 0
    ... ptPos 0 -0.5
    ... ptTan -0.2 0
    ... ptLab 1''', "tn.uc")
    >>> c = d.curves[0]
    >>> c.marks, c.symmetry.fold, c.symmetry.mirror, c.symmetry.axis_rule
    (('ground', 'apex'), 4, True, 'first point')
    >>> c.segments[0].kind, c.segments[0].handles
    ('bezier', ((-0.8, 0.0), (-0.2, -0.5)))
    >>> d.default_apex
    1.0
    """
    empty = True
    declared: tuple[int, int] | None = None
    curves: list[_Curve] = []
    dialect: tuple[str, int] | None = None  # ("ptTan" | "ptTangent", first line)
    n_points = 0  # ptPos lines of the whole drawing
    for no, toks in uc_text.iter_lines(text, path):
        empty = False
        key, args = toks[0], toks[1:]
        if key not in _KEYS:
            raise FormatError(
                f"unknown keyword {key!r} in a legacy/v1 .uc file; expected one of "
                f"{', '.join(sorted(_KEYS))}", path, no)
        if key == "numCurves":
            if declared is not None or curves:
                raise FormatError("'numCurves' must come once, before the first 'unitCurve'", path, no)
            declared = (uc_text.integer(uc_text.numbers(args, 1, key, path, no, None)[0], key, path, no, 0,
                                        "curves"), no)
            continue
        if key == "unitCurve":
            if len(args) != 3:
                raise FormatError(
                    f"'unitCurve' needs 3 numbers (points, rotation fold, has reflection) in the "
                    f"legacy dialect, got {len(args)}", path, no)
            n, fold, refl = uc_text.numbers(args, 3, key, path, no, None)
            declared_points = uc_text.integer(n, "unitCurve points", path, no, 0, "segments", -1)
            if declared_points < 2:
                raise FormatError(f"'unitCurve' declares {declared_points} point(s); a curve needs at least 2",
                                  path, no)
            if len(curves) == LIMITS.curves:
                raise FormatError(f"more than {LIMITS.curves} curves (auszug.limits.LIMITS.curves)", path, no)
            fold_i = uc_text.integer(fold, "unitCurve rotation fold", path, no, 1, "fold")
            if refl not in (0.0, 1.0):
                raise FormatError(f"'unitCurve' reflection flag must be 0 or 1, got {refl:g}", path, no)
            curves.append(_Curve(no, declared_points, fold_i, refl == 1.0))
            continue
        if not curves:
            raise FormatError(f"{key!r} before the first 'unitCurve'", path, no)
        cur, ci = curves[-1], len(curves) - 1
        if key == "reflectionPoint":
            if cur.axis is not None:
                raise FormatError(f"'reflectionPoint' given twice for curve {ci}", path, no)
            x, y = uc_text.numbers(args, 2, key, path, no)
            cur.axis, cur.axis_line = (x, y), no
        elif key == "ptPos":
            n_points += 1
            if n_points > LIMITS.segments + len(curves):
                raise FormatError(f"more than {LIMITS.segments} segments in the drawing "
                                  "(auszug.limits.LIMITS.segments)", path, no)
            _add_point(cur, ci, uc_text.numbers(args, 2, key, path, no), path, no)
        elif key in ("ptTan", "ptTangent"):
            if dialect is None:
                dialect = (key, no)
            elif dialect[0] != key:
                raise FormatError(
                    f"{key!r} mixed with {dialect[0]!r} (line {dialect[1]}): a file is either legacy "
                    "('ptTan' vectors) or v1 ('ptTangent' control points)", path, no)
            if not cur.points:
                raise FormatError(f"{key!r} before the first 'ptPos' of curve {ci}", path, no)
            xy = uc_text.numbers(args, 2, key, path, no)
            if key == "ptTan":
                if cur.tans[-1] is not None:
                    raise FormatError(f"a second 'ptTan' for point {len(cur.points) - 1} of curve {ci}",
                                      path, no)
                cur.tans[-1] = (xy[0], xy[1])
            else:
                if cur.n_controls == cur.n_points:
                    raise FormatError(
                        f"'ptTangent' after the last point of curve {ci}: control points go between "
                        "the 'ptPos' lines of their segment", path, no)
                if len(cur.gaps[-1]) == 2:
                    raise FormatError(
                        f"a third 'ptTangent' between points {len(cur.points) - 1} and "
                        f"{len(cur.points)} of curve {ci}; a cubic segment has 2", path, no)
                cur.gaps[-1].append(((xy[0], xy[1]), no))
                cur.n_controls += 1
        else:  # ptLab
            v = uc_text.numbers(args, 1, key, path, no, None)[0]
            lab = uc_text.integer(v, key, path, no, 0)
            if lab not in LABEL_MARKS:
                raise FormatError(f"'ptLab' must be 0 (ground), 1 (apex) or 2 (free end), got {lab}",
                                  path, no)
            if len(cur.labels) == cur.n_points:
                raise FormatError(f"curve {ci} declares {cur.n_points} points but this is 'ptLab' "
                                  f"number {cur.n_points + 1}", path, no)
            cur.labels.append((lab, no))
    if empty:
        raise FormatError("empty file: expected 'numCurves N' then curves", path)
    if not curves:
        raise FormatError("no 'unitCurve' found: not a drawing", path)
    if declared is not None and declared[0] != len(curves):
        raise FormatError(f"'numCurves {declared[0]}' but {len(curves)} curves follow", path, declared[1])

    basics = []
    longest = 0.0
    for ci, cur in enumerate(curves):
        if cur.n_controls < cur.n_points:
            raise FormatError(
                f"curve {ci} declares {cur.n_points} points but only {cur.n_controls} follow "
                "(truncated file?)", path, cur.line)
        if len(cur.labels) != len(cur.points):
            raise FormatError(
                f"curve {ci} has {len(cur.labels)} 'ptLab' labels for {len(cur.points)} 'ptPos' "
                "points" + (" (truncated file?)" if len(cur.labels) < len(cur.points) else ""),
                path, cur.labels[-1][1] if len(cur.labels) > len(cur.points) else cur.line)
        if cur.gaps[-1]:
            raise FormatError(
                f"'ptTangent' after the last point of curve {ci}: control points go between the "
                "'ptPos' lines of their segment", path, cur.gaps[-1][0][1])
        if cur.mirror and cur.axis is None:
            raise FormatError(f"curve {ci} has a reflection but no 'reflectionPoint' line",
                              path, cur.line)
        if cur.mirror and cur.axis is not None and math.hypot(*cur.axis) <= 1e-12:
            raise FormatError("mirror axis of zero length: 'reflectionPoint' is the origin",
                              path, cur.axis_line)
        try:
            basics.append(BasicCurve(
                vertices=tuple(cur.points),
                segments=tuple(_segments(cur)),
                marks=tuple(LABEL_MARKS[lab] for lab, _ in cur.labels),
                symmetry=_symmetry(cur),
                source=Source(cur.line, None, tuple(range(len(cur.points))), tuple(cur.point_lines)),
            ))
        except DrawingError as e:
            raise FormatError(f"curve {ci}: {e}", path, cur.line) from None
        for a, b in zip(cur.points[:-1], cur.points[1:], strict=True):
            longest = max(longest, math.hypot(b[0] - a[0], b[1] - a[1]))
    if longest > LIMITS.coordinate:
        raise FormatError(f"the longest segment is {longest:g} long, and so would be the apex height of the "
                          f"curves (legacy files store none): beyond the limit of {LIMITS.coordinate:g} for "
                          "heights (auszug.limits.LIMITS.coordinate)", path)
    try:
        return Drawing(curves=tuple(basics), name=uc_text.stem(path), default_apex=max(1.0, longest))
    except DrawingError as e:
        raise FormatError(str(e), path) from None
