"""A 2D design sketch and its curve graph: strokes split at crossings, shared control points.

A :class:`Sketch` holds strokes as chains of cubic Beziers (x, y in the
sketch's own units, y up) and the user's annotations. :func:`sketch_graph`
finds the crossings between strokes, drops the ones marked as occlusions,
splits the strokes there and numbers the control points, so that the curves
meeting at an intersection share one control point (paper sec. 5.2, Fig. 8).
"""

from __future__ import annotations

import hashlib
import math
import threading
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree
from scipy.spatial.distance import pdist

from auszug.errors import GeometryError
from auszug.geometry import CubicBezier, Line, intersect, intersect_many
from auszug.lifting.params import DEFAULT, LiftParams
from auszug.limits import LIMITS, beyond_coordinate

__all__ = ["Stroke", "Marker", "Sketch", "Crossing", "Gap", "Junction", "SketchGraph", "sketch_graph",
           "nearest_end_gap", "near_junctions"]

Array = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class Stroke:
    """One drawn curve: a chain of cubic Beziers.

    Attributes
    ----------
    controls : (m, 4, 2) ndarray
        The Bezier segments' control points; segment k ends where k + 1 starts.
    id : str
        Its name in messages (the SVG id, or ``"path #i"``).
    layer : int
        Index of its layer (independent part), back to front.
    """

    controls: Array
    id: str = ""
    layer: int = 0


@dataclass(frozen=True)
class Marker:
    """An annotation at a point: ``kind`` is ``"occlusion"`` or ``"flip"``."""

    kind: str
    point: Array
    id: str = ""


@dataclass(frozen=True, eq=False)
class Sketch:
    """A design sketch: strokes and annotations (orthographic view along z).

    Attributes
    ----------
    strokes : tuple of Stroke
    markers : tuple of Marker
        Occlusion and flip markers (each snaps to the nearest crossing).
    symmetry : Stroke or None
        The global symmetry curve (half the object is drawn). Read and
        validated; not used by the solver yet (see docs/lifting.md).
    name : str
    layers : tuple of str
        Layer names, back to front.
    """

    strokes: tuple[Stroke, ...]
    markers: tuple[Marker, ...] = ()
    symmetry: Stroke | None = None
    name: str = ""
    layers: tuple[str, ...] = field(default_factory=tuple)

    def fingerprint(self) -> str:
        """A hash of the sketch's content (hex digest).

        Every stroke's control points (as float64 bytes with their shape), id and layer, the
        markers, the symmetry curve, the name and the layer names. Equal contents give equal
        fingerprints; a stroke array changed in place changes it. :func:`auszug.lifting.layer_graphs`
        keys its memo on it, so that the graphs are built once per sketch (a reader's validation,
        then :func:`auszug.lifting.lift`).
        """
        h = hashlib.sha1()

        def stroke(s: Stroke | None) -> None:
            if s is None:
                h.update(b"none")
                return
            c = np.ascontiguousarray(s.controls, dtype=np.float64)
            h.update(repr((c.shape, s.id, s.layer)).encode())
            h.update(c.tobytes())

        h.update(repr((len(self.strokes), self.name, self.layers)).encode())
        for s in self.strokes:
            stroke(s)
        stroke(self.symmetry)
        for m in self.markers:
            pt = np.ascontiguousarray(m.point, dtype=np.float64)
            h.update(repr((m.kind, m.id, pt.shape)).encode())
            h.update(pt.tobytes())
        return h.hexdigest()

    def diagonal(self) -> float:
        """Diagonal of the bounding box of all control points."""
        pts = np.concatenate([s.controls.reshape(-1, 2) for s in self.strokes]) if self.strokes else np.zeros((1, 2))
        return float(np.linalg.norm(pts.max(0) - pts.min(0)))


@dataclass(frozen=True)
class Crossing:
    """A point where two or more strokes meet in the graph.

    Attributes
    ----------
    point : int
        Index of the shared control point.
    ends : tuple of (int, int)
        The half-edges at the point: (segment index, end) with end 0 (the
        segment starts here) or 3 (it ends here).
    strokes : tuple of int
        The stroke of each half-edge.
    smooth : bool
        Two strokes, each passing G1 through the point, at 2D angle at least
        ``min_crossing_deg``: the paper's smooth crossing (hard orthogonality).
    flipped : bool
        A flip marker snapped here.
    """

    point: int
    ends: tuple[tuple[int, int], ...]
    strokes: tuple[int, ...]
    smooth: bool
    flipped: bool = False


@dataclass(frozen=True)
class Gap:
    """A stroke end joined by ``LiftParams.close_gaps`` (off by default).

    Attributes
    ----------
    stroke : int
        Index of the stroke in the graph's ``strokes``.
    end : int
        0: its start, 1: its end.
    kind : str
        ``"trim"``: the piece beyond its last crossing (with stroke ``to``) cut off; ``"extend"``: moved
        onto the inside of stroke ``to``; ``"end"``: moved to meet the end of stroke ``to`` (and of any
        other stroke ending there); ``"close"``: moved to meet its own other end (the stroke becomes a
        loop).
    to : int
        The stroke it was joined to (itself for ``"close"``).
    distance : float
        The piece cut off (arc length) or the gap bridged, relative to the diagonal.
    """

    stroke: int
    end: int
    kind: str
    to: int
    distance: float


@dataclass(frozen=True)
class Junction:
    """Crossings of three or more strokes drawn near one point, made one by ``LiftParams.close_gaps``.

    A hand drawing of strokes meant to pass through one point (a box's edge and the sections of its two
    faces, the ribs at a vault's boss) draws a small triangle of crossings instead. Left so, every pair
    crossing smoothly is a hard orthogonality at its own point, which the 3D object cannot meet.

    Attributes
    ----------
    strokes : tuple of int
        The strokes (indices into the graph's ``strokes``) now passing through (or ending at) one point.
    point : (2,) ndarray
        That point (normalised, as the graph's ``points``).
    spread : float
        The largest distance between two of the drawn crossings (and stroke ends) joined, relative to the
        diagonal.
    distance : float
        The largest move of a stroke, relative to the diagonal (at most ``close_gaps``).
    """

    strokes: tuple[int, ...]
    point: Array
    spread: float
    distance: float


@dataclass(frozen=True, eq=False)
class SketchGraph:
    """Strokes split at crossings, with shared control points.

    All coordinates are normalised: ``xy = (sketch_xy - offset) / scale``,
    so the sketch's diagonal is 1.

    Attributes
    ----------
    points : (n, 2) ndarray
        Control points (normalised).
    segments : (s, 4) int ndarray
        Control point indices of each Bezier segment.
    seg_stroke : (s,) int ndarray
        The stroke each segment belongs to.
    chains : tuple of (k,) int ndarray
        Per stroke, its segments in order.
    closed : (strokes,) bool ndarray
        Whether the stroke is a closed loop (last segment ends at the first's start).
    joints : (j, 2) int ndarray
        Consecutive segments (a, b) of one stroke, a ending where b starts.
    joint_g1 : (j,) bool ndarray
        Whether the stroke is G1 at the joint.
    crossings : tuple of Crossing
    occluded : (k, 2) ndarray
        The 2D crossings marked as occlusions (normalised), not intersections.
    offset : (2,) ndarray
    scale : float
    strokes : tuple of Stroke
        The input strokes.
    marked : tuple of int
        Indices of the sketch's markers that snapped to a crossing of this graph.
    gaps : tuple of Gap
        The stroke ends ``LiftParams.close_gaps`` joined (none by default).
    junctions : tuple of Junction
        The crossings drawn near one point that ``LiftParams.close_gaps`` made one (none by default).
    """

    points: Array
    segments: NDArray[np.intp]
    seg_stroke: NDArray[np.intp]
    chains: tuple[NDArray[np.intp], ...]
    closed: NDArray[np.bool_]
    joints: NDArray[np.intp]
    joint_g1: NDArray[np.bool_]
    crossings: tuple[Crossing, ...]
    occluded: Array
    offset: Array
    scale: float
    strokes: tuple[Stroke, ...]
    marked: tuple[int, ...] = ()
    gaps: tuple[Gap, ...] = ()
    junctions: tuple[Junction, ...] = ()

    def stroke_name(self, i: int) -> str:
        """Stroke ``i``'s id, or ``stroke #i`` where it has none (for messages)."""
        return self.strokes[i].id or f"stroke #{i}"

    def tangent(self, seg: int, end: int) -> Array:
        """2D tangent handle of a half-edge: from its end point to the next control point."""
        s = self.segments[seg]
        return self.points[s[1]] - self.points[s[0]] if end == 0 else self.points[s[2]] - self.points[s[3]]


def _validate(sketch: Sketch, params: LiftParams) -> float:
    if not sketch.strokes:
        raise GeometryError("the sketch has no strokes")
    if len(sketch.strokes) > LIMITS.sketch_strokes:
        raise GeometryError(f"the sketch has {len(sketch.strokes)} strokes: more than the limit of "
                            f"{LIMITS.sketch_strokes} (auszug.limits.LIMITS.sketch_strokes)")
    for i, s in enumerate(sketch.strokes):
        c = np.asarray(s.controls, dtype=float)
        name = s.id or f"stroke #{i}"
        if c.ndim != 3 or c.shape[1:] != (4, 2) or len(c) == 0:
            raise GeometryError(f"{name}: expected Bezier controls of shape (m, 4, 2), got {c.shape}")
        if not np.all(np.isfinite(c)):
            raise GeometryError(f"{name}: coordinates are not finite (NaN or infinity)")
        if (far := beyond_coordinate(float(np.abs(c).max()))) is not None:
            raise GeometryError(f"{name}: {far}")
    n_segments = sum(len(s.controls) for s in sketch.strokes)
    if n_segments > LIMITS.sketch_segments:
        raise GeometryError(f"the sketch has {n_segments} Bezier segments: more than the limit of "
                            f"{LIMITS.sketch_segments} (auszug.limits.LIMITS.sketch_segments)")
    diag = sketch.diagonal()
    if not diag > 0:
        raise GeometryError("the sketch has zero extent")
    for i, s in enumerate(sketch.strokes):
        c = np.asarray(s.controls, dtype=float)
        if np.ptp(c.reshape(-1, 2), axis=0).max() <= params.merge * diag:
            raise GeometryError(f"{s.id or f'stroke #{i}'}: zero-length stroke")
    keys: dict[bytes, int] = {}
    for i, s in enumerate(sketch.strokes):
        k = np.round(np.asarray(s.controls) / (params.merge * diag * 100)).astype(np.int64).tobytes()
        kr = np.round(np.asarray(s.controls)[::-1, ::-1] / (params.merge * diag * 100)).astype(np.int64).tobytes()
        for key in (k, kr):
            if key in keys:
                j = keys[key]
                raise GeometryError(f"{s.id or f'stroke #{i}'}: duplicate of "
                                    f"{sketch.strokes[j].id or f'stroke #{j}'}")
        keys[k] = i
    return diag


#: A segment with one handle retracted onto its end point is cut this far (in its parameter) from that end.
RETRACTED_CUT = 0.1


def _fix_handles(c: Array, tiny: float) -> Array:
    """Retracted handles (on their end point) given a length, the drawn curve kept.

    A handle on its end point (a cusp node of Inkscape or Illustrator) leaves the curve's tangent there
    pointing to the next control point, but gives the solver no tangent vector. With both handles of a
    segment retracted, the segment is the straight line between its ends: the handles are moved onto
    that line, the same line. With one retracted, the segment is cut at ``RETRACTED_CUT`` (0.1) from that
    end: the long piece is the drawn curve exactly; in the short piece the retracted handle is moved a
    third of the way to the piece's other handle, which moves that piece by at most 4/27 * 0.1^2
    (0.15 %) of the distance from the end point to the segment's other handle (moving the handle on the
    whole segment, as before 2026-12-05, moved the drawn curve by up to 4/27 of it, 15 %). A segment too
    small for the cut (the short piece within 100 merge distances) has its handle moved without it.

    Point-sized segments (all four control points within ``tiny``: a node drawn twice) are left out.

    Returns
    -------
    (m', 4, 2) ndarray
        The stroke's segments, m' <= 2m.
    """
    c = np.asarray(c, dtype=float)
    out: list[Array] = []
    for seg in c:
        if np.ptp(seg, axis=0).max() <= tiny and len(c) > 1:
            continue        # a point-sized segment (a doubled node): the drawn curve is the same without it
        r0 = np.linalg.norm(seg[1] - seg[0]) <= tiny
        r1 = np.linalg.norm(seg[2] - seg[3]) <= tiny
        if r0 != r1:
            end = 0 if r0 else 3
            reach = float(np.linalg.norm(seg[2 if end == 0 else 1] - seg[end]))
            if reach * RETRACTED_CUT**2 > 100 * tiny:      # the short piece stays well above the merge distance
                b = CubicBezier.from_array(seg)
                t = RETRACTED_CUT if end == 0 else 1.0 - RETRACTED_CUT
                out += [_move_handles(b.segment(0.0, t).controls, tiny),
                        _move_handles(b.segment(t, 1.0).controls, tiny)]
                continue
        out.append(_move_handles(seg, tiny))
    return np.array(out)


def _move_handles(seg: Array, tiny: float) -> Array:
    """One segment's retracted handles moved a third of the way to its other handle (or other end)."""
    seg = seg.copy()
    for a, b, o in ((0, 1, 2), (3, 2, 1)):
        if np.linalg.norm(seg[b] - seg[a]) <= tiny:
            other = seg[o] if np.linalg.norm(seg[o] - seg[a]) > tiny else seg[3 - a]
            seg[b] = seg[a] + (other - seg[a]) / 3.0
    return seg


def _angle(u: Array, v: Array) -> float:
    """Angle between two 2D vectors in degrees."""
    nu, nv = float(np.linalg.norm(u)), float(np.linalg.norm(v))
    if nu == 0 or nv == 0:
        return 0.0
    return math.degrees(math.acos(max(-1.0, min(1.0, float(np.dot(u, v)) / (nu * nv)))))


def sketch_graph(sketch: Sketch, params: LiftParams = DEFAULT, require_markers: bool = True) -> SketchGraph:
    """The curve graph of a sketch (see the module docstring).

    Raises
    ------
    GeometryError
        For no strokes, non-finite or zero-length strokes, duplicate strokes,
        a marker farther than ``params.snap`` of the diagonal from every
        crossing (naming its id), or a sketch without any intersection.

    Examples
    --------
    >>> import numpy as np
    >>> h = Stroke(np.array([[[-1, 0], [-0.3, 0.1], [0.3, 0.1], [1, 0]]], float), "h")
    >>> v = Stroke(np.array([[[0, -1], [0.1, -0.3], [0.1, 0.3], [0, 1]]], float), "v")
    >>> g = sketch_graph(Sketch((h, v)))
    >>> len(g.segments), len(g.crossings), g.crossings[0].smooth
    (4, 1, True)
    """
    diag = _validate(sketch, params)
    allc = np.concatenate([np.asarray(s.controls, float).reshape(-1, 2) for s in sketch.strokes])
    offset = 0.5 * (allc.min(0) + allc.max(0))
    scale = diag
    tiny = params.merge
    strokes_c = [_fix_handles((np.asarray(s.controls, float) - offset) / scale, tiny) for s in sketch.strokes]

    # crossings between segments of different strokes
    raw = _raw_crossings(strokes_c)
    gaps: tuple[Gap, ...] = ()
    junctions: tuple[Junction, ...] = ()
    if params.close_gaps > 0:
        occl_pts = [(np.asarray(m.point, float) - offset) / scale for m in sketch.markers if m.kind == "occlusion"]
        strokes_c, gaps, junctions = _close_gaps(strokes_c, raw, params, np.array(occl_pts).reshape(-1, 2))
        if gaps or junctions:
            raw = _raw_crossings(strokes_c)
    # cluster crossing points (one crossing can be found on two segments at a joint)
    if raw:
        cpts = np.array([r[6] for r in raw])
        tree = cKDTree(cpts)
        label = np.arange(len(raw))
        for i, j in sorted(tree.query_pairs(params.merge * 10)):
            li, lj = label[i], label[j]
            label[label == max(li, lj)] = min(li, lj)
        uniq = np.unique(label)
        centres = np.array([cpts[label == u].mean(0) for u in uniq])
    else:
        label = np.zeros(0, dtype=np.intp)
        uniq = np.zeros(0, dtype=np.intp)
        centres = np.zeros((0, 2))

    # markers snap to the nearest crossing
    occluded_c: set[int] = set()
    flipped_c: set[int] = set()
    marked: list[int] = []
    for mi, m in enumerate(sketch.markers):
        p = (np.asarray(m.point, float) - offset) / scale
        d = np.linalg.norm(centres - p, axis=1) if len(centres) else np.array([np.inf])
        j = int(np.argmin(d))
        if d[j] > params.snap and not require_markers:
            continue
        if len(centres) == 0:
            raise GeometryError(f"{m.kind} marker {m.id or '(no id)'}: the sketch has no crossing to mark")
        if d[j] > params.snap:
            raise GeometryError(f"{m.kind} marker {m.id or '(no id)'} at {np.asarray(m.point).tolist()}: no "
                                f"crossing within {params.snap:.0%} of the sketch's diagonal "
                                f"(nearest {d[j]:.3g} of it)")
        (occluded_c if m.kind == "occlusion" else flipped_c).add(j)
        marked.append(mi)
    if occluded_c & flipped_c:
        raise GeometryError("a crossing is marked both as an occlusion and as flipped")

    # split parameters per (stroke, segment), for the crossings that are intersections
    splits: dict[tuple[int, int], list[float]] = {}
    for r, lab in zip(raw, label, strict=True):
        ci = int(np.searchsorted(uniq, lab))
        if ci in occluded_c:
            continue
        for s, k, t in ((r[0], r[1], r[2]), (r[3], r[4], r[5])):
            splits.setdefault((s, k), []).append(t)
    flipped_pts = centres[sorted(flipped_c)] if flipped_c else np.zeros((0, 2))

    seg_ctrl: list[Array] = []
    seg_stroke: list[int] = []
    chains: list[NDArray[np.intp]] = []
    for si, c in enumerate(strokes_c):
        ids = []
        for k in range(len(c)):
            b = CubicBezier.from_array(c[k])
            # a crossing within the merge distance of the segment's end (or of the split before it) is
            # there, not a split: its tiny piece would shrink to a point when the ends merge below
            ts, last = [], c[k][0]
            for t in sorted(t for t in splits.get((si, k), []) if 1e-9 < t < 1 - 1e-9):
                q = b.point(t)
                if min(np.linalg.norm(q - last), np.linalg.norm(q - c[k][3])) > params.merge * 10:
                    ts.append(t)
                    last = q
            bounds = [0.0, *ts, 1.0]
            for t0, t1 in zip(bounds[:-1], bounds[1:], strict=True):
                if t1 - t0 < 1e-9:
                    continue
                ids.append(len(seg_ctrl))
                seg_ctrl.append(b.segment(t0, t1).controls if (t0, t1) != (0.0, 1.0) else c[k])
                seg_stroke.append(si)
        chains.append(np.array(ids, dtype=np.intp))
    ctrl = np.array(seg_ctrl)                 # (s, 4, 2)
    S = len(ctrl)
    # number the control points: segment ends shared when they coincide, handles own
    ends = np.concatenate([ctrl[:, 0], ctrl[:, 3]])
    groups = _link_groups(ends, params.merge * 10)        # numbered in the order of their first end
    npts = len(groups)
    end_pt = np.empty(2 * S, dtype=np.intp)
    end_pt[np.concatenate(groups)] = np.repeat(np.arange(npts), [len(m) for m in groups])
    points = np.zeros((npts + 2 * S, 2))
    cnt = np.zeros(npts)
    np.add.at(points[:npts], end_pt, ends)
    np.add.at(cnt, end_pt, 1.0)
    points[:npts] /= cnt[:, None]
    segments = np.zeros((S, 4), dtype=np.intp)
    segments[:, 0] = end_pt[:S]
    segments[:, 3] = end_pt[S:]
    segments[:, 1] = npts + 2 * np.arange(S)
    segments[:, 2] = npts + 2 * np.arange(S) + 1
    points[segments[:, 1]] = ctrl[:, 1]
    points[segments[:, 2]] = ctrl[:, 2]

    joints = []
    closed = np.zeros(len(chains), dtype=bool)
    for si, ch in enumerate(chains):
        for a, b in zip(ch[:-1], ch[1:], strict=True):
            joints.append((a, b))
        if len(ch) > 1 and segments[ch[-1], 3] == segments[ch[0], 0]:
            joints.append((ch[-1], ch[0]))
            closed[si] = True
        elif len(ch) == 1 and segments[ch[0], 3] == segments[ch[0], 0]:
            closed[si] = True
    J = np.array(joints, dtype=np.intp).reshape(-1, 2)
    g1 = np.zeros(len(J), dtype=bool)
    for n, (a, b) in enumerate(J):
        tin = points[segments[a, 3]] - points[segments[a, 2]]
        tout = points[segments[b, 1]] - points[segments[b, 0]]
        g1[n] = _angle(tin, tout) < params.smooth_joint_deg

    # crossings: points where half-edges of two or more strokes meet
    halfs: dict[int, list[tuple[int, int]]] = {}
    for s in range(S):
        halfs.setdefault(int(segments[s, 0]), []).append((s, 0))
        halfs.setdefault(int(segments[s, 3]), []).append((s, 3))
    g1_at = {(int(a), int(b)): bool(g) for (a, b), g in zip(J, g1, strict=True)}
    joint_of = {}
    for a, b in J:
        joint_of[(int(a), 3)] = (int(a), int(b))
        joint_of[(int(b), 0)] = (int(a), int(b))
    seg_stroke_a = np.array(seg_stroke, dtype=np.intp)
    crossings = []
    for p, hs in sorted(halfs.items()):
        st = [int(seg_stroke_a[s]) for s, _ in hs]
        if len(set(st)) < 2:
            continue
        smooth = False
        if len(set(st)) == 2 and len(hs) == 4:
            joints_here = {joint_of.get(h) for h in hs}
            if None not in joints_here and len(joints_here) == 2 and all(g1_at[j] for j in joints_here if j):
                sa = [h for h in hs if seg_stroke_a[h[0]] == st[0]]
                sb = [h for h in hs if seg_stroke_a[h[0]] != st[0]]
                ta = _tangent(points, segments, sa[0])
                tb = _tangent(points, segments, sb[0])
                ang = _angle(ta, tb)
                smooth = min(ang, 180 - ang) >= params.min_crossing_deg
        flipped = bool(len(flipped_pts) and np.linalg.norm(flipped_pts - points[p], axis=1).min() <= params.snap)
        crossings.append(Crossing(p, tuple(hs), tuple(st), smooth, flipped))
    if len(crossings) > LIMITS.sketch_crossings:
        raise GeometryError(f"the sketch has {len(crossings)} crossings: more than the limit of "
                            f"{LIMITS.sketch_crossings} (auszug.limits.LIMITS.sketch_crossings)")
    if not crossings:
        raise GeometryError("the sketch has no intersection between strokes: nothing to lift "
                            "(strokes must cross or touch; occlusion markers remove crossings)")
    occl = centres[sorted(occluded_c)] if occluded_c else np.zeros((0, 2))
    return SketchGraph(points, segments, seg_stroke_a, tuple(chains), closed, J, g1, tuple(crossings), occl,
                       offset, float(scale), tuple(sketch.strokes), tuple(marked), gaps, junctions)


_Raw = tuple[int, int, float, int, int, float, Array]


def _raw_crossings(strokes_c: list[Array], only: set[int] | None = None) -> list[_Raw]:
    """Every crossing of two strokes: (stroke a, segment of a, t on it, stroke b, segment of b, t, point).

    With ``only``, the crossings of those strokes with the others (each once).
    """
    flat: list[tuple[int, int]] = []
    curves: list[CubicBezier] = []
    for si, c in enumerate(strokes_c):
        for k in range(len(c)):
            flat.append((si, k))
            curves.append(CubicBezier.from_array(c[k]))
    if only is None:
        pairs = list(intersect_many(curves).items())
    else:
        mine = [i for i, (si, _) in enumerate(flat) if si in only]
        rest = [i for i, (si, _) in enumerate(flat) if si not in only]
        mc = [curves[m] for m in mine]
        pairs = [((mine[i], mine[j]), hs) for (i, j), hs in intersect_many(mc).items()]
        pairs += [((mine[i], rest[j]), hs) for (i, j), hs in intersect_many(mc, [curves[r] for r in rest]).items()]
    raw: list[_Raw] = []
    for (a, b), hs in pairs:
        sa, ka = flat[a]
        sb, kb = flat[b]
        if sa == sb:
            continue
        for h in hs:
            raw.append((sa, ka, h.t1, sb, kb, h.t2, h.point))
    return raw


def _close_gaps(strokes_c: list[Array], raw: list[_Raw], params: LiftParams,
                occlusions: Array) -> tuple[list[Array], tuple[Gap, ...], tuple[Junction, ...]]:
    """Free stroke ends within ``params.close_gaps`` of the diagonal joined (see :class:`Gap`).

    Coordinates are normalised (diagonal 1). In order (docs/lifting.md, "Closing gaps"):

    0. :func:`_join_crossings`: crossings of three or more strokes within that distance of one point
       are made one (:class:`Junction`), before any end moves (a trim would cut a stroke's overshoot
       at one of the crossings instead).
    1. :func:`_trim`: a piece of at most that length beyond a stroke's first or last crossing is cut off
       at the crossing ("trim").
    2. :func:`_meet`: free ends within that distance of each other meet at one point ("end", "close";
       "extend" where the point is on another stroke's inside).
    3. :func:`_extend`: an end still free is moved onto the stroke it points at, or the nearest stroke
       or its own other end ("extend", "end", "close"); then the trim once more, for the stubs the
       moves left (a stroke reached just inside its end).
    4. Ends joined to a stroke's inside that a later move of that stroke bent away are put back; a
       stroke with an end still not joined is left as drawn (its records dropped).
    5. Where an end lies on another stroke's inside, that stroke is cut there (:func:`_split_at`), so
       that the graph's merge of near points joins them without a second intersection test (which may
       miss a curve that only touches another with its end).

    Moves translate an end with its handle (:func:`_move_end`), by at most ``close_gaps``. Ends whose
    joint would lie within ``params.snap`` of an occlusion marker are left as drawn.
    """
    try:
        out = [c.copy() for c in strokes_c]
        junctions = _join_crossings(out, raw, params, occlusions)
        out, gaps = _close_gaps_in(out, _raw_crossings(out) if junctions else raw, params, occlusions)
        return out, gaps, junctions
    finally:
        _BOXES.index = None


def _close_gaps_in(strokes_c: list[Array], raw: list[_Raw], params: LiftParams,
                   occlusions: Array) -> tuple[list[Array], tuple[Gap, ...]]:
    out = [c.copy() for c in strokes_c]
    gaps = _trim(out, raw, params, occlusions, set())
    # every end as drawn (or cut): no end moves farther than close_gaps from it
    ref = {(si, e): (c[0, 0] if e == 0 else c[-1, 3]).copy() for si, c in enumerate(out) for e in (0, 1)}
    gaps += _meet(out, params, occlusions, {(g.stroke, g.end) for g in gaps})
    moved = _extend(out, raw, params, occlusions, {(g.stroke, g.end) for g in gaps})
    gaps += moved
    if moved:
        gaps += _trim(out, _raw_crossings(out, {g.stroke for g in moved}), params, occlusions,
                      {(g.stroke, g.end) for g in gaps})
    # an end joined to a stroke's inside leaves it when a later move of that stroke's end bends the
    # segment it lies on (by at most that move): put back onto the stroke, a few times over (a put-back
    # bends its own stroke's end segment in turn)
    last = {(g.stroke, g.end): g for g in gaps}
    for _ in range(4):
        again = False
        for (si, end), g in last.items():
            if g.kind not in ("trim", "extend"):
                continue
            q = out[si][0, 0] if end == 0 else out[si][-1, 3]
            if _reaches(out, g, params):
                continue
            x = _closest_on(out[g.to], q)[0]
            for e2 in (0, 1):           # two ends joined to each other's inside chase each other: one point
                h = last.get((g.to, e2))
                xe = out[g.to][0, 0] if e2 == 0 else out[g.to][-1, 3]
                if h is not None and h.to == si and float(np.linalg.norm(xe - q)) <= params.close_gaps:
                    x = xe
            if float(np.linalg.norm(x - ref[(si, end)])) <= params.close_gaps:
                _move_end(out, si, end, x)
                again = True
        if not again:
            break
    # what is still not joined (ends chasing each other in a tangle): its strokes as drawn, repeated
    # for the ends joined to those
    while bad := {si for (si, end) in last if not _joined(out, si, end, params)}:
        for si in bad:
            out[si] = strokes_c[si].copy()
        gaps = [g for g in gaps if g.stroke not in bad]
        last = {(g.stroke, g.end): g for g in gaps}
    # the strokes an end now lies on (inside): cut there, once every end is where it stays
    for si, end in last:
        q = out[si][0, 0] if end == 0 else out[si][-1, 3]
        sj = _on_stroke(q, out, si, params)
        if sj >= 0:
            _split_at(out, sj, q, params)
    return out, tuple(gaps)


def _joined(out: list[Array], si: int, end: int, params: LiftParams) -> bool:
    """Whether stroke ``si``'s start (``end`` 0) or end (1) lies on another stroke or on its own other end."""
    c = out[si]
    q = c[0, 0] if end == 0 else c[-1, 3]
    return float(np.linalg.norm(q - (c[-1, 3] if end == 0 else c[0, 0]))) <= 10.0 * params.merge or not _free(
        out, si, end, params)


def _free(out: list[Array], si: int, end: int, params: LiftParams) -> bool:
    """Whether stroke ``si``'s start (``end`` 0) or end (1) meets no other stroke (its inside or an end)."""
    near = 10.0 * params.merge
    c = out[si]
    q = c[0, 0] if end == 0 else c[-1, 3]
    for sj, _ in _near(out, q, near):
        cj = out[sj]
        if sj != si and min(float(np.linalg.norm(q - cj[0, 0])), float(np.linalg.norm(q - cj[-1, 3]))) <= near:
            return False
    return _on_stroke(q, out, si, params) < 0


def _move_end(out: list[Array], si: int, end: int, target: Array) -> None:
    """Move, in place, stroke ``si``'s start (``end`` 0) or end (1) to ``target`` with its handle."""
    c = out[si].copy()
    if end == 0:
        c[0, :2] += target - c[0, 0]
    else:
        c[-1, 2:] += target - c[-1, 3]
    out[si] = c


def _along(raw: list[_Raw], n: int) -> list[list[tuple[int, float, Array, int]]]:
    """Per stroke, its crossings as (segment, t, point, other stroke), in order along it."""
    along: list[list[tuple[int, float, Array, int]]] = [[] for _ in range(n)]
    for sa, ka, ta, sb, kb, tb, pt in raw:
        along[sa].append((ka, ta, pt, sb))
        along[sb].append((kb, tb, pt, sa))
    return [sorted(x, key=lambda h: (h[0], h[1])) for x in along]


def _is_loop(c: Array, params: LiftParams) -> bool:
    return bool(np.linalg.norm(c[0, 0] - c[-1, 3]) <= 10.0 * params.merge)


def _near_occlusion(q: Array, occlusions: Array, params: LiftParams) -> bool:
    return bool(len(occlusions)) and float(np.linalg.norm(occlusions - q, axis=1).min()) <= params.snap


def _trim(out: list[Array], raw: list[_Raw], params: LiftParams, occlusions: Array,
          skip: set[tuple[int, int]]) -> list[Gap]:
    """Cut, in place, the pieces of at most ``close_gaps`` beyond a stroke's first or last crossing.

    A cut whose crossing's other stroke is cut before reaching it (two overshoots past each other) is
    not made, nor one that would leave no more of the stroke than it cuts off.
    """
    tol, near = params.close_gaps, 10.0 * params.merge
    plan: dict[tuple[int, int], tuple[int, float, Gap]] = {}     # (stroke, end) -> segment, t, record
    for si, xs in enumerate(_along(raw, len(out))):
        c = out[si]
        if _is_loop(c, params) or not xs:
            continue
        (k0, t0, p0, o0), (k1, t1, p1, o1) = xs[0], xs[-1]
        # the arc is at least the chord: only a crossing within tol of the end is measured along the stroke
        d0 = _arc_to(c, k0, t0, from_start=True) if float(np.linalg.norm(p0 - c[0, 0])) <= tol else math.inf
        d1 = _arc_to(c, k1, t1, from_start=False) if float(np.linalg.norm(p1 - c[-1, 3])) <= tol else math.inf
        cut0 = (si, 0) not in skip and near < d0 <= tol and not _near_occlusion(p0, occlusions, params)
        cut1 = (si, 1) not in skip and near < d1 <= tol and not _near_occlusion(p1, occlusions, params)
        cut = (d0 if cut0 else 0.0) + (d1 if cut1 else 0.0)
        if (cut0 or cut1) and _arc_to(c, 0, 0.0, from_start=False) - cut <= max(d0 if cut0 else 0.0,
                                                                               d1 if cut1 else 0.0):
            continue            # what would remain is no longer than a cut piece: the stroke is the stub
        if cut0:
            plan[(si, 0)] = (k0, t0, Gap(si, 0, "trim", o0, d0))
        if cut1:
            plan[(si, 1)] = (k1, t1, Gap(si, 1, "trim", o1, d1))
    orig = list(out)
    while True:
        for si in {si for si, _ in plan}:
            c = orig[si]
            if (si, 1) in plan:
                k1, t1, _ = plan[(si, 1)]
                keep = [CubicBezier.from_array(c[k1]).segment(0.0, t1).controls[None]] if t1 > 1e-9 else []
                c = np.concatenate([c[:k1], *keep])
            if (si, 0) in plan:
                k0, t0, _ = plan[(si, 0)]
                keep = [CubicBezier.from_array(c[k0]).segment(t0, 1.0).controls[None]] if t0 < 1 - 1e-9 else []
                c = np.concatenate([*keep, c[k0 + 1:]])
            out[si] = c
        lost = [key for key, (_, _, gp) in plan.items() if not _reaches(out, gp, params)]
        if not lost:
            break
        for key in lost:
            del plan[key]
        for si in {si for si, _ in lost}:
            out[si] = orig[si]
    return [gp for _, _, gp in plan.values()]


def _reaches(out: list[Array], gp: Gap, params: LiftParams) -> bool:
    """Whether the end ``gp`` records lies on stroke ``gp.to`` (its inside or an end, within 10 merge distances)."""
    near = 10.0 * params.merge
    c, cj = out[gp.stroke], out[gp.to]
    q = c[0, 0] if gp.end == 0 else c[-1, 3]
    if min(float(np.linalg.norm(q - cj[0, 0])), float(np.linalg.norm(q - cj[-1, 3]))) <= near:
        return True
    return float(np.linalg.norm(_closest_on(cj, q)[0] - q)) <= near


def _split_at(out: list[Array], sj: int, q: Array, params: LiftParams) -> None:
    """Cut, in place, stroke ``sj``'s segment that passes within 10 merge distances of ``q`` at ``q``'s projection.

    Nothing happens where that point is within 10 merge distances of a knot or end of the stroke (the
    graph's merge of near points joins ``q`` there) or no segment passes that near.
    """
    near = 10.0 * params.merge
    cj = out[sj]
    for k, seg in enumerate(cj):
        if float(np.linalg.norm(np.clip(q, seg.min(0), seg.max(0)) - q)) > near:
            continue
        b = CubicBezier.from_array(seg)
        t = b.project(q)
        x = b.point(t)
        if float(np.linalg.norm(x - q)) > near:
            continue
        if min(float(np.linalg.norm(x - seg[0])), float(np.linalg.norm(x - seg[3]))) > near:
            out[sj] = np.concatenate([cj[:k], b.segment(0.0, t).controls[None], b.segment(t, 1.0).controls[None],
                                      cj[k + 1:]])
        return


def _link_groups(pts: Array, r: float) -> list[NDArray[np.intp]]:
    """Single-linkage groups of ``pts`` (n, 2) at distance ``r``: per group its indices, ascending.

    Groups (singletons too) come in the order of their first index.
    """
    pairs = cKDTree(pts).query_pairs(r, output_type="ndarray")
    link = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(pts), len(pts)))
    n, label = connected_components(link, directed=False)
    order = np.argsort(label, kind="stable")
    return np.split(order, np.cumsum(np.bincount(label, minlength=n))[:-1])


def _join_crossings(out: list[Array], raw: list[_Raw], params: LiftParams,
                    occlusions: Array) -> tuple[Junction, ...]:
    """Join, in place, crossings of three or more strokes drawn within ``close_gaps`` of one point into one.

    ``raw`` are the crossings of ``out`` as given (:func:`_raw_crossings`). Crossings are grouped by single
    linkage at ``close_gaps``. A group of three or more strokes, every two of them crossing once in it
    (:func:`_every_pair_once`), gets a point: the one nearest (least squares, :func:`_meeting_point`) to the
    strokes' tangent lines at their points closest to the group's centre. Strokes with an end within
    ``close_gaps`` of that point (drawn to end there) join the group. When every crossing and every stroke is
    within ``close_gaps`` of the point, each stroke is moved through it (:func:`_through`). A group within
    ``params.snap`` of an occlusion marker stays as drawn, and so does one whose strokes afterwards do not all
    pass through the point or cross each other again within twice ``close_gaps`` of it.
    """
    tol, near = params.close_gaps, 10.0 * params.merge
    if len(raw) < 2:
        return ()
    pts = np.array([r[6] for r in raw])
    found: list[Junction] = []
    for members in _link_groups(pts, tol):
        strokes = {raw[i][0] for i in members} | {raw[i][3] for i in members}
        if len(members) < 2 or not _every_pair_once([(raw[i][0], raw[i][3]) for i in members]):
            continue
        centre = pts[members].mean(0)
        lines = [_closest_on(out[si], centre) for si in sorted(strokes)]
        q = _meeting_point(np.array([x for x, _ in lines]), np.array([u for _, u in lines]), params)
        ends = [(si, e) for si, c in enumerate(out) if si not in strokes and not _is_loop(c, params)
                for e in (0, 1) if float(np.linalg.norm((c[0, 0] if e == 0 else c[-1, 3]) - q)) <= tol]
        group = sorted(strokes | {si for si, _ in ends})
        spots = np.concatenate([pts[members], np.reshape([out[si][0, 0] if e == 0 else out[si][-1, 3]
                                                          for si, e in ends], (-1, 2))])
        spread = float(pdist(spots).max())
        if spread <= near or float(np.linalg.norm(spots - q, axis=1).max()) > tol \
                or _near_occlusion(q, occlusions, params):
            continue
        if max(float(np.linalg.norm(_closest_on(out[si], q)[0] - q)) for si in group) > tol:
            continue
        before = {si: out[si] for si in group}
        moves = [_through(out, si, q, params) for si in group]
        # every stroke through the point, and no two of them crossing once more near it (bent ends can)
        again = [r for r in _raw_crossings(out, set(group)) if r[0] in before and r[3] in before
                 and near < float(np.linalg.norm(r[6] - q)) <= 2.0 * tol]
        if again or max(float(np.linalg.norm(_closest_on(out[si], q)[0] - q)) for si in group) > near:
            for si, c in before.items():
                out[si] = c
            continue
        found.append(Junction(tuple(group), q.copy(), spread, max(moves)))
    return tuple(found)


def _every_pair_once(crossings: list[tuple[int, ...]]) -> bool:
    """Whether crossings (each the strokes meeting there) are of three or more strokes, every two crossing once.

    What strokes meant to meet at one point draw: a triangle of three, six crossings of four. Crossings of
    strokes that do not all cross each other there (two near-parallel pairs crossing in a small
    quadrilateral) or of one pair twice (a near touch) are not such a point.
    """
    pairs = [(a, b) for st in crossings for a in sorted(set(st)) for b in sorted(set(st)) if a < b]
    strokes = {s for st in crossings for s in st}
    return len(strokes) >= 3 and len(set(pairs)) == len(pairs) == len(strokes) * (len(strokes) - 1) // 2


def _through(out: list[Array], si: int, q: Array, params: LiftParams) -> float:
    """Move, in place, stroke ``si`` through ``q``; the distance it moved there (relative to the diagonal).

    The stroke's point closest to ``q`` is made a knot (cut there) and moved to ``q`` with its two handles,
    so the stroke's tangent direction there is kept; only the two segments at the knot change, each cut
    first at its crossing with another stroke nearest the knot and farther than ``close_gaps`` from
    ``q``, so that no other crossing moves. Where the closest point is an end, the end moves with its
    handle (:func:`_move_end`).
    """
    near = 10.0 * params.merge
    c = out[si]
    dist, k, t = _nearest_on(c, q)
    x = CubicBezier.from_array(c[k]).point(t)
    loop = _is_loop(c, params)
    if dist <= 1e-12:
        _split_at(out, si, q, params)
        return dist
    if float(np.linalg.norm(x - c[k][0])) <= near:
        j = k
    elif float(np.linalg.norm(x - c[k][3])) <= near:
        j = k + 1
    else:
        b = CubicBezier.from_array(c[k])
        c = np.concatenate([c[:k], b.segment(0.0, t).controls[None], b.segment(t, 1.0).controls[None], c[k + 1:]])
        j = k + 1
    if not loop and j in (0, len(c)):
        _move_end(out, si, 0 if j == 0 else 1, q)
        return dist
    j %= len(c)
    out[si] = c
    tol = params.close_gaps
    cut: dict[int, float] = {}               # segment -> where it is cut: its crossing nearest the knot
    for sa, ka, ta, _, kb, tb, pt in _raw_crossings(out, {si}):
        kk, tt = (ka, ta) if sa == si else (kb, tb)
        if float(np.linalg.norm(pt - q)) <= tol or not 1e-9 < tt < 1 - 1e-9:
            continue
        if kk == j and tt < cut.get(kk, 1.0):
            cut[kk] = tt
        elif kk == (j - 1) % len(c) and tt > cut.get(kk, 0.0):
            cut[kk] = tt
    for kk in sorted(cut, reverse=True):
        b = CubicBezier.from_array(c[kk])
        c = np.concatenate([c[:kk], b.segment(0.0, cut[kk]).controls[None], b.segment(cut[kk], 1.0).controls[None],
                            c[kk + 1:]])
        if kk < j:
            j += 1
    c = c.copy()
    delta = q - c[j][0]
    c[j][:2] += delta                           # the handles move along: the tangent direction is kept
    c[j - 1][2:] += delta
    out[si] = c
    return dist


#: Per thread, the segment boxes of the strokes :func:`_near` last indexed, with those strokes (compared by
#: identity: every change to a stroke during gap closing puts a new array in its place); emptied when
#: :func:`_close_gaps` returns.
_BOXES = threading.local()


def _near(out: list[Array], p: Array, r: float) -> list[tuple[int, int]]:
    """(stroke, segment) of every segment of ``out`` whose control-point box is within ``r`` of ``p``.

    The box holds the segment, so a segment farther than ``r`` from ``p`` may be listed but none nearer
    is left out. One vectorised test instead of a Python loop over all segments.
    """
    cached = getattr(_BOXES, "index", None)
    if not (cached and len(cached[0]) == len(out) and all(a is b for a, b in zip(cached[0], out, strict=True))):
        allc = np.concatenate(out)
        stroke = np.repeat(np.arange(len(out)), [len(c) for c in out])
        k = np.concatenate([np.arange(len(c)) for c in out])
        cached = _BOXES.index = (tuple(out), allc.min(1), allc.max(1), stroke, k)
    _, lo, hi, stroke, k = cached
    d = np.linalg.norm(np.clip(p, lo, hi) - p, axis=1)
    hit = np.nonzero(d <= r)[0]
    return list(zip(stroke[hit].tolist(), k[hit].tolist(), strict=True))


def _on_stroke(p: Array, out: list[Array], si: int, params: LiftParams) -> int:
    """The stroke other than ``si`` on whose inside ``p`` lies (within 10 merge distances), or -1."""
    near = 10.0 * params.merge
    for sj, k in _near(out, p, near):
        if sj == si:
            continue
        cj = out[sj]
        b = CubicBezier.from_array(cj[k])
        if float(np.linalg.norm(b.point(b.project(p)) - p)) <= near and (
                _is_loop(cj, params)
                or min(float(np.linalg.norm(p - cj[0, 0])), float(np.linalg.norm(p - cj[-1, 3]))) > near):
            return sj
    return -1


def _end_dir(c: Array, end: int) -> Array:
    """Unit tangent at a stroke's start (``end`` 0) or end (1), pointing out of the stroke."""
    v = c[0, 0] - c[0, 1] if end == 0 else c[-1, 3] - c[-1, 2]
    n = float(np.linalg.norm(v))
    return v / n if n > 0 else v


def _nearest_on(c: Array, q: Array) -> tuple[float, int, float]:
    """Where the stroke ``c`` (m, 4, 2) comes closest to ``q``: (distance, segment, t)."""
    best = (math.inf, 0, 0.0)
    for k, seg in enumerate(c):
        b = CubicBezier.from_array(seg)
        t = b.project(q)
        d = float(np.linalg.norm(b.point(t) - q))
        if d < best[0]:
            best = (d, k, t)
    return best


def _closest_on(c: Array, q: Array) -> tuple[Array, Array]:
    """The point of the stroke ``c`` (m, 4, 2) closest to ``q``, and its unit tangent there."""
    _, k, t = _nearest_on(c, q)
    b = CubicBezier.from_array(c[k])
    return b.point(t), b.tangent(t)


def _meeting_point(p: Array, u: Array, params: LiftParams) -> Array:
    """The point nearest (least squares) to the lines through ``p`` (k, 2) along ``u`` (k, 2, unit).

    Where the lines cross at less than ``params.smooth_joint_deg`` (the ends continue each other, or
    a stroke closes smoothly), the mean of ``p`` instead. Ends drawn short of a corner along straight
    strokes meet at the corner exactly.
    """
    A = np.zeros((2, 2))
    r = np.zeros(2)
    for pi, ui in zip(p, u, strict=True):
        m = np.eye(2) - np.outer(ui, ui)
        A += m
        r += m @ pi
    if float(np.linalg.eigvalsh(A / len(p))[0]) < 0.5 * (1.0 - math.cos(math.radians(params.smooth_joint_deg))):
        return np.asarray(p.mean(0))
    return np.asarray(np.linalg.solve(A, r))


def _meet(out: list[Array], params: LiftParams, occlusions: Array, trimmed: set[tuple[int, int]]) -> list[Gap]:
    """Move, in place, stroke ends within ``close_gaps`` of each other onto one point.

    Ends are grouped by single linkage at ``close_gaps``; a group of ends of two or more strokes (or of
    one stroke's two ends) meets where the ends' tangent lines meet (:func:`_meeting_point`); where an
    end lies on another stroke's inside (a crossing the others reach), that stroke's tangent line there
    is one of the lines, and the point is moved onto that stroke (its closest point). Ends
    already at that point stay, and so do ends farther than ``close_gaps`` from it (single linkage can
    chain ends much farther apart). A joint the drawing already has (ends of two strokes at one point, or
    an end on another stroke's inside that ``trimmed`` does not list) is the point, as drawn.
    """
    tol, near = params.close_gaps, 10.0 * params.merge
    ends = [(si, e) for si, c in enumerate(out) if not _is_loop(c, params) for e in (0, 1)]
    if len(ends) < 2:
        return []
    pts = np.array([out[si][0, 0] if e == 0 else out[si][-1, 3] for si, e in ends])
    gaps: list[Gap] = []
    for group in _link_groups(pts, tol):
        members = group.tolist()
        if len(members) < 2:
            continue
        on = {i: _on_stroke(pts[i], out, ends[i][0], params) for i in members}
        # an end on a stroke that itself ends in the group is no anchor: that stroke's end moves too
        anchored = [i for i in members if on[i] >= 0 and all(ends[j][0] != on[i] for j in members)]
        lp = [pts[i] for i in members]
        lu = [_end_dir(out[ends[i][0]], ends[i][1]) for i in members]
        for i in anchored:                          # the stroke an end lies on is one of the lines
            lp.append(pts[i])
            lu.append(_closest_on(out[on[i]], pts[i])[1])
        target = _meeting_point(np.array(lp), np.array(lu), params)
        if anchored:                                # and the ends stay on it
            target = _closest_on(out[on[anchored[0]]], target)[0]
        # a joint the drawing already has stays where it is drawn: ends of two strokes at one point, or an
        # end drawn onto another stroke (not cut there by the trim)
        fixed = [i for i in anchored if ends[i] not in trimmed]
        fixed += [i for i in members for j in members
                  if ends[i][0] != ends[j][0] and float(np.linalg.norm(pts[i] - pts[j])) <= near]
        if fixed:
            target = pts[fixed[0]]
        if _near_occlusion(target, occlusions, params):
            continue
        # a long chain of the single linkage: its ends farther than tol from the target stay
        reach = [i for i in members if float(np.linalg.norm(pts[i] - target)) <= tol]
        if len(reach) < 2:
            continue
        for i in reach:
            d = float(np.linalg.norm(pts[i] - target))
            if d <= near:
                continue
            si, e = ends[i]
            _move_end(out, si, e, target)
            others = [ends[j][0] for j in reach if j != i]
            if anchored:
                gaps.append(Gap(si, e, "extend", on[anchored[0]], d))
            else:
                gaps.append(Gap(si, e, "close" if others == [si] else "end", others[0], d))
    return gaps


def _ray_hit(out: list[Array], si: int, end: int, skip: int, tol: float) -> tuple[float, int, Array, bool] | None:
    """Where stroke ``si``'s end, continued straight along its tangent for ``tol``, first meets another stroke.

    Returns (distance, stroke, point, False), or None; stroke ``skip`` is not met. A stroke drawn short of
    another along its own direction is extended exactly so (a straight stroke stays on its line).
    """
    c = out[si]
    p = c[0, 0] if end == 0 else c[-1, 3]
    u = _end_dir(c, end)
    if not float(np.linalg.norm(u)) > 0:
        return None
    line = Line(p, p + tol * u)
    lo, hi = np.minimum(p, p + tol * u), np.maximum(p, p + tol * u)
    best: tuple[float, int, Array, bool] | None = None
    for sj, k in _near(out, p, tol):
        seg = out[sj][k]
        if sj in (si, skip) or np.any(seg.min(0) > hi) or np.any(seg.max(0) < lo):
            continue
        for h in intersect(line, CubicBezier.from_array(seg)):
            d = h.t1 * tol
            if d > 0 and (best is None or d < best[0]):
                best = (d, sj, np.asarray(h.point, float), False)
    return best


def _extend(out: list[Array], raw: list[_Raw], params: LiftParams, occlusions: Array,
            skip: set[tuple[int, int]]) -> list[Gap]:
    """Move, in place, the free ends within ``close_gaps`` of another stroke (or their own other end) onto it."""
    tol, near = params.close_gaps, 10.0 * params.merge
    # the stroke an end's piece crosses first: an end is not moved back onto it (a dangling piece
    # longer than the tolerance that curls back is a drawn free end, not a gap)
    first: dict[tuple[int, int], int] = {}
    for si, xs in enumerate(_along(raw, len(out))):
        if xs:
            first[(si, 0)], first[(si, 1)] = xs[0][3], xs[-1][3]
    gaps: list[Gap] = []
    for si in range(len(out)):
        for end in (0, 1):
            c = out[si]
            if (si, end) in skip or _is_loop(c, params):
                continue
            p = c[0, 0] if end == 0 else c[-1, 3]
            if not _free(out, si, end, params):
                continue                                # it meets another stroke already
            best: tuple[float, int, Array, bool] = (np.inf, -1, p, False)   # distance, stroke, point, at its end
            ray = _ray_hit(out, si, end, first.get((si, end), -1), tol)
            if ray is None and len(c) > 1:
                q = c[-1, 3] if end == 0 else c[0, 0]            # its own other end: the loop closes
                best = (float(np.linalg.norm(q - p)), si, q, True)
            for sj, k in _near(out, p, tol) if ray is None else ():
                cj = out[sj]
                if first.get((si, end)) == sj or sj == si:
                    continue
                b = CubicBezier.from_array(cj[k])
                q = b.point(b.project(p))
                d = float(np.linalg.norm(q - p))
                if d < best[0]:
                    at_end = False
                    if not _is_loop(cj, params):
                        for e in (cj[0, 0], cj[-1, 3]):
                            if np.linalg.norm(q - e) <= near:
                                q, at_end = e, True
                    best = (d, sj, q, at_end)
            d, sj, q, at_end = best if ray is None else ray
            if not near < d <= tol or _near_occlusion(q, occlusions, params):
                continue
            _move_end(out, si, end, q)
            gaps.append(Gap(si, end, "close" if sj == si else ("end" if at_end else "extend"), sj, d))
    return gaps


def nearest_end_gap(g: SketchGraph, ends_of: set[int], to: set[int]) -> tuple[float, int, int]:
    """The smallest distance from an end of a stroke in ``ends_of`` to a stroke in ``to``.

    For error messages: how far a stroke not joined to the rest misses it.

    Parameters
    ----------
    g : SketchGraph
    ends_of, to : set of int
        Stroke indices (into ``g.chains``); open strokes of ``ends_of`` are measured.

    Returns
    -------
    distance : float
        Relative to the sketch's diagonal (inf if no stroke of ``ends_of`` has an end).
    stroke, other : int
        The stroke whose end it is, and the stroke it misses (-1, -1 for inf).
    """
    best = (math.inf, -1, -1)
    for si in sorted(ends_of):
        ch = g.chains[si]
        if g.closed[si] or not len(ch):
            continue
        for p in (g.points[g.segments[ch[0], 0]], g.points[g.segments[ch[-1], 3]]):
            for sj in sorted(to):
                for seg in g.points[g.segments[g.chains[sj]]]:
                    if float(np.linalg.norm(np.clip(p, seg.min(0), seg.max(0)) - p)) >= best[0]:
                        continue
                    b = CubicBezier.from_array(seg)
                    d = float(np.linalg.norm(b.point(b.project(p)) - p))
                    if d < best[0]:
                        best = (d, si, sj)
    return best


def near_junctions(g: SketchGraph, within: float) -> list[tuple[float, tuple[int, ...]]]:
    """Crossings of three or more strokes drawn near one point but not at it: where ``close_gaps`` would help.

    For hints: a hand drawing of strokes meant to meet at one point draws a small triangle (or polygon)
    of crossings instead, which the lift reads as separate intersections (see :class:`Junction`).

    Parameters
    ----------
    g : SketchGraph
    within : float
        Crossings closer than this (relative to the diagonal) are grouped (single linkage).

    Returns
    -------
    list of (spread, strokes)
        Per group of two or more crossings of three or more strokes, every two crossing once in it (a
        crossing of several strokes counts for each pair), the largest distance between two of
        its crossings (relative to the diagonal; ``close_gaps`` of about this joins a group of straight
        strokes) and the strokes, sorted by spread.
    """
    if len(g.crossings) < 2:
        return []
    pts = np.array([g.points[c.point] for c in g.crossings])
    found = []
    for members in _link_groups(pts, within):
        strokes = sorted({s for i in members for s in g.crossings[i].strokes})
        if len(members) < 2 or not _every_pair_once([g.crossings[i].strokes for i in members]):
            continue
        found.append((float(pdist(pts[members]).max()), tuple(strokes)))
    return sorted(found)


def _arc_to(c: Array, k: int, t: float, from_start: bool) -> float:
    """Arc length along a stroke's segments ``c`` from its start (or end) to parameter ``t`` of segment ``k``."""
    b = CubicBezier.from_array(c[k])
    if from_start:
        return sum(CubicBezier.from_array(c[i]).length() for i in range(k)) \
            + (b.segment(0.0, t).length() if t > 1e-9 else 0.0)
    return sum(CubicBezier.from_array(c[i]).length() for i in range(k + 1, len(c))) \
        + (b.segment(t, 1.0).length() if t < 1 - 1e-9 else 0.0)


def _tangent(points: Array, segments: NDArray[np.intp], half: tuple[int, int]) -> Array:
    s, e = half
    if e == 0:
        return points[segments[s, 1]] - points[segments[s, 0]]
    return points[segments[s, 2]] - points[segments[s, 3]]
