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
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.spatial import cKDTree

from auszug.errors import GeometryError
from auszug.geometry import CubicBezier, intersect_many
from auszug.lifting.params import DEFAULT, LiftParams
from auszug.limits import LIMITS, beyond_coordinate

__all__ = ["Stroke", "Marker", "Sketch", "Crossing", "SketchGraph", "sketch_graph"]

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

    # every segment as a Bezier; crossings between segments of different strokes
    flat: list[tuple[int, int]] = []
    curves: list[CubicBezier] = []
    for si, c in enumerate(strokes_c):
        for k in range(len(c)):
            flat.append((si, k))
            curves.append(CubicBezier.from_array(c[k]))
    hits = intersect_many(curves)
    raw: list[tuple[int, int, float, int, int, float, Array]] = []
    for (a, b), hs in hits.items():
        sa, ka = flat[a]
        sb, kb = flat[b]
        if sa == sb:
            continue
        for h in hs:
            raw.append((sa, ka, h.t1, sb, kb, h.t2, h.point))
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
    tree = cKDTree(ends)
    parent = np.arange(2 * S)

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return int(i)

    for i, j in tree.query_pairs(params.merge * 10):
        ri, rj = find(i), find(j)
        if ri != rj:
            parent[max(ri, rj)] = min(ri, rj)
    roots = np.array([find(i) for i in range(2 * S)])
    # an occluded crossing must not join strokes that happen to end there: keep ends of
    # different strokes apart when they sit on an occlusion
    uroots, end_pt = np.unique(roots, return_inverse=True)
    npts = len(uroots)
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
                       offset, float(scale), tuple(sketch.strokes), tuple(marked))


def _tangent(points: Array, segments: NDArray[np.intp], half: tuple[int, int]) -> Array:
    s, e = half
    if e == 0:
        return points[segments[s, 1]] - points[segments[s, 0]]
    return points[segments[s, 2]] - points[segments[s, 3]]
