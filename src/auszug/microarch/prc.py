"""Top-view intersections and the point of reverse curvature (paper sec. 4.3.1, Algorithm 1).

An intersection between a basic curve and one of its own replicas is *true*
(the two 3D curves meet) exactly when both curves pass it at the same
parameter, t = t', because replicas share the height function; intersections
between different basic curves can always be made true (independent heights).

:func:`algorithm1` follows the paper's Algorithm 1 for every ogee segment:
the true intersection with the segment's own replicas closest to its midpoint;
else the intersection with the other basic curves (and their replicas) closest
to the midpoint; else the midpoint. "Closest" is measured in normalised arc
length. Intersections at the segment's own end points are not candidates (a
PRC must lie strictly inside the curve). The paper states the algorithm for a
single layer; we look for other curves on the segment's own layer only, since
curves of other layers do not meet it in 3D.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from auszug._cache import LruCache
from auszug.geometry import TOL, Curve
from auszug.geometry.intersect import intersect_prepared, prepare
from auszug.microarch.model import Drawing

__all__ = ["TopIntersection", "PrcChoice", "intersections", "algorithm1", "oriented_segments"]

Array = NDArray[np.float64]
Branch = Literal["own replicas", "other curves", "midpoint"]


@dataclass(frozen=True)
class TopIntersection:
    """A top-view intersection of a basic segment with a replica of a segment.

    Attributes
    ----------
    curve, segment : int
        The basic curve and its segment.
    other_curve, other_segment : int
        The curve and segment whose replica is met.
    replica : str
        Label of that replica (``r<k>`` or ``r<k>m``).
    u, u_other : float
        Normalised arc length on the segment and on the replica, each measured
        from the segment's start (its ground end for an ogee).
    point : (2,) ndarray
        Where they meet (drawing units).
    same_family : bool
        Whether the replica is one of the segment's own replicas.
    true : bool
        Whether the 3D curves meet there: ``u == u_other`` (within
        ``TOL.param_equal``) for the own family, always for other curves.
    """

    curve: int
    segment: int
    other_curve: int
    other_segment: int
    replica: str
    u: float
    u_other: float
    point: Array
    same_family: bool
    true: bool


@dataclass(frozen=True)
class PrcChoice:
    """What Algorithm 1 chose for one ogee segment.

    Attributes
    ----------
    curve, segment : int
    fraction : float
        The PRC as a fraction of the segment's top-view arc length from its ground end.
    branch : {"own replicas", "other curves", "midpoint"}
        Which branch of Algorithm 1 chose it.
    point : (2,) ndarray
        The PRC in the top view.
    intersection : TopIntersection or None
        The chosen intersection (``None`` for the midpoint).
    """

    curve: int
    segment: int
    fraction: float
    branch: Branch
    point: Array
    intersection: TopIntersection | None


def oriented_segments(drawing: Drawing) -> list[tuple[int, int, Curve]]:
    """Every segment's top curve, oriented from its ground end for ogees.

    Returns
    -------
    list of (curve index, segment index, Curve)
    """
    return [(ci, si, c.top_curve(si, oriented=True)) for ci, c in enumerate(drawing.curves)
            for si in range(len(c.segments))]


@lru_cache(maxsize=4096)
def _replicas(top: Curve, sym) -> tuple[Curve, ...]:
    """Images of an (immutable, cached) top curve under a symmetry group."""
    cen = np.asarray(sym.center)
    return tuple(top.transformed(m, cen - m @ cen) for m in sym.matrices())


def _same_curve(a: Curve, b: Curve, tol: float) -> bool:
    """Whether two curves are the same point set (either orientation)."""
    # quick refusal from the end points' floats (memoised by the intersection kernel): curves
    # whose ends differ by clearly more than tol are not the same; the margin covers the
    # rounding between an end point and the curve evaluated at t = 0 or 1
    pa_, pb_ = prepare(a), prepare(b)
    m = tol + 1e-12 * max(1.0, abs(pa_.x0), abs(pa_.y0), abs(pa_.x1), abs(pa_.y1))
    fwd = (abs(pa_.x0 - pb_.x0) <= m and abs(pa_.y0 - pb_.y0) <= m and abs(pa_.x1 - pb_.x1) <= m
           and abs(pa_.y1 - pb_.y1) <= m)
    bwd = (abs(pa_.x0 - pb_.x1) <= m and abs(pa_.y0 - pb_.y1) <= m and abs(pa_.x1 - pb_.x0) <= m
           and abs(pa_.y1 - pb_.y0) <= m)
    if not (fwd or bwd):
        return False
    pa = a.point(np.array([0.0, 0.5, 1.0]))
    pb = b.point(np.array([0.0, 0.5, 1.0]))
    return bool(np.all(np.abs(pa - pb) <= tol) or np.all(np.abs(pa - pb[::-1]) <= tol))


def intersections(drawing: Drawing, layer_only: bool = False) -> list[TopIntersection]:
    """All top-view intersections of every basic segment with every replica of every segment.

    Intersections of a segment with a replica identical to itself, and with its
    own untransformed copy, are left out. (Every other intersection of the
    drawing is an image of one of these under a symmetry.)

    Parameters
    ----------
    drawing : Drawing
    layer_only : bool
        Only replicas of curves on the same layer as the basic segment.

    Returns
    -------
    list of TopIntersection
    """
    tol = TOL
    segs = oriented_segments(drawing)
    if not segs:
        return []
    ids = {(ci, si): _key_id(_segment_key(drawing, ci, si)) for ci, si, _ in segs}
    layers = tuple(c.layer for c in drawing.curves) if layer_only else ()
    if layer_only and len(set(layers)) <= 1:
        layer_only, layers = False, ()   # one layer: the same result, and the same cache entry
    whole = (tuple(ids.items()), layers, tol.param_equal)
    hit = _RESULTS.get(whole)
    if hit is not None:
        return list(hit)
    # the work comes in blocks: one basic segment i against every replica of one segment j,
    # cached as finished records; an edit of one curve recomputes only the blocks it touches
    scale = [None]   # the drawing's size, for the identical-replica test (computed when needed)
    out: list[TopIntersection] = []
    blocks = _BLOCKS.data   # the OrderedDict itself: this loop runs for every rebuild
    param_equal = tol.param_equal
    for ci, si, top in segs:
        kid_i = ids[(ci, si)]
        layer_i = drawing.curves[ci].layer
        for cj, sj, top_j in segs:
            if layer_only and layer_i != layers[cj]:
                continue
            bk = (kid_i, ids[(cj, sj)], ci, si, cj, sj, param_equal)
            block = blocks.get(bk)
            if block is None:
                block = _block(drawing, segs, scale, ci, si, top, kid_i, cj, sj, top_j, ids[(cj, sj)])
                _BLOCKS.put(bk, block)
            else:
                try:
                    blocks.move_to_end(bk)
                except KeyError:   # evicted meanwhile by another thread; the block is still right
                    pass
            out.extend(block)
    _RESULTS.put(whole, tuple(out))
    return out


def _block(drawing: Drawing, segs: list, scale: list, ci: int, si: int, top: Curve, kid_i: int,
           cj: int, sj: int, top_j: Curve, kid_j: int) -> tuple[TopIntersection, ...]:
    """The intersection records of basic segment (ci, si) with every replica of (cj, sj).

    Pairs come from :data:`_PAIRS` where cached (keyed by both segments' geometry and the
    replica), else from the intersection kernel pair by pair (for a few pairs numpy would cost
    more than it saves). The segment's own untransformed copy is left out, and so is a replica
    identical to it (it overlaps the segment everywhere).
    """
    sym = drawing.curves[cj].symmetry
    param_equal = TOL.param_equal
    same_family = ci == cj and si == sj
    out: list[TopIntersection] = []
    ptop = None
    pairs = _PAIRS.data   # (its values may be None: a miss is _MISS)
    # segment i meets replica k of segment j where replica k of (segment j against replica m
    # of segment i, m the inverse of k in i's group) does: a pair computed already the other
    # way round (an earlier block, or an earlier k) gives this one
    inverse = _inverses(sym, drawing.curves[ci].symmetry)
    labels = sym.labels()
    reps = _replicas(top_j, sym)
    got: dict[int, Any] = {}          # k -> hits (a tuple, or None for an identical replica)
    found: dict[int, list] = {}       # k -> the kernel's raw hits, for pairs computed here
    later: list[int] = []             # k derived from a pair computed here (same family)
    for k in range(len(reps)):
        if k == 0 and same_family:
            continue
        pk = (kid_i, kid_j, k)
        hits = pairs.get(pk, _MISS)
        if hits is not _MISS:
            try:
                pairs.move_to_end(pk)
            except KeyError:   # evicted meanwhile by another thread; the value is still right
                pass
            got[k] = hits
        elif inverse[k] >= 0 and (back := pairs.get((kid_j, kid_i, inverse[k]), _MISS)) is not _MISS:
            got[k] = None if back is None else _mapped(back, sym, k)
            _PAIRS.put(pk, got[k])
        elif same_family and inverse[k] in found:
            later.append(k)
        else:
            if ptop is None:
                ptop = prepare(top)
            found[k] = intersect_prepared(ptop, prepare(reps[k]))
    # arc length once per curve for all the pairs computed here (a replica has its curve's)
    t1 = [h.t1 for k in found for h in found[k]]
    if t1:
        u1 = top.u_at_t(np.array(t1)).tolist()
        u2 = top_j.u_at_t(np.array([h.t2 for k in found for h in found[k]])).tolist()
    n = 0
    for k, fk in found.items():
        hits = tuple((u1[n + q], u2[n + q], h.point) for q, h in enumerate(fk))
        n += len(fk)
        if hits and same_family:
            if scale[0] is None:
                ends = [t.start for _, _, t in segs] + [t.end for _, _, t in segs]
                scale[0] = max(1.0, float(np.max(np.abs(ends))))
            if _same_curve(top, reps[k], 1e-9 * scale[0]):
                hits = None
        got[k] = hits
        _PAIRS.put((kid_i, kid_j, k), hits)
    for k in later:
        back = got[inverse[k]]
        got[k] = None if back is None else _mapped(back, sym, k)
        _PAIRS.put((kid_i, kid_j, k), got[k])
    for k in sorted(got):
        hits = got[k]
        if hits:
            lab = labels[k]
            out.extend(TopIntersection(ci, si, cj, sj, lab, u, u2, pt, same_family,
                                       (abs(u - u2) <= param_equal) if same_family else True)
                       for u, u2, pt in hits)
    return tuple(out)


def _inverses(sym_j, sym_i) -> tuple[int, ...]:
    """For each replica k of group ``sym_j``, the replica m of ``sym_i`` whose map is k's inverse, else -1.

    Both groups must turn about one centre (else every entry is -1); two groups of the same
    elements in another order (a D2 whose axis is x, another's y) find each other's inverses.
    """
    mats_j, mats_i = sym_j.matrices(), sym_i.matrices()
    if tuple(sym_j.center) != tuple(sym_i.center):
        return (-1,) * len(mats_j)
    return _inverse_indices(mats_j.tobytes(), mats_i.tobytes())


@lru_cache(maxsize=1024)
def _inverse_indices(mats_j: bytes, mats_i: bytes) -> tuple[int, ...]:
    mj = np.frombuffer(mats_j).reshape(-1, 2, 2)
    mi = np.frombuffer(mats_i).reshape(-1, 2, 2)
    eye = np.eye(2)
    out: list[int] = []
    if len(mj) * len(mi) <= 4096:
        # small groups (the usual case, and a group whose mirror axis follows a dragged point is
        # new at every drag step, so this runs per edit): every product mj[k] @ mi[i] at once
        err = np.abs(mj[:, None] @ mi[None] - eye).max(axis=(2, 3))
        for row in (err <= 1e-12):
            m = np.flatnonzero(row)
            out.append(int(m[0]) if len(m) == 1 else -1)
        return tuple(out)
    # Large groups (fold 1024 with a mirror has 2048 maps: every pair would be 4 M products):
    # candidates by a rounded key of k's inverse (the maps are orthogonal: the inverse is the
    # transpose), each checked by the product itself; a key that rounds the other way at a digit
    # boundary falls back to checking every map of i. Linear in the group sizes.
    index: dict[tuple[float, ...], list[int]] = {}
    for n, key in enumerate(map(tuple, np.round(mi.reshape(-1, 4), 9))):
        index.setdefault(key, []).append(n)
    for mk, key in zip(mj, map(tuple, np.round(mj.transpose(0, 2, 1).reshape(-1, 4), 9)), strict=True):
        hit = [n for n in index.get(key, ()) if np.abs(mk @ mi[n] - eye).max() <= 1e-12]
        if not hit:
            hit = np.flatnonzero(np.abs(mk @ mi - eye).max(axis=(1, 2)) <= 1e-12).tolist()
        out.append(hit[0] if len(hit) == 1 else -1)
    return tuple(out)


def _mapped(back: tuple, sym, k: int) -> tuple:
    """The hits of (segment i, replica k of j) from those of (segment j, replica k^-1 of i).

    The parameters swap (a rigid replica has its curve's parametrisation) and the points
    map by replica k; sorted along segment i, as the kernel returns them.
    """
    m = sym.matrices()[k]
    c = np.asarray(sym.center, dtype=float)
    return tuple(sorted(((u2, u, m @ (np.asarray(pt) - c) + c) for u, u2, pt in back), key=lambda h: h[0]))


#: Intersections of one basic segment with one replica, keyed by the geometry of both (their
#: vertices, handles, marks and the replica's symmetry element): an edit recomputes only the
#: pairs it touches. Values are immutable tuples.
_PAIRS = LruCache(20000)
_MISS = object()
#: The TopIntersection records of one basic segment with all replicas of one segment, at given
#: curve/segment indices (keyed by both segments' key ids and the indices).
_BLOCKS = LruCache(20000)
#: Whole results of :func:`intersections`, keyed by the segments' key ids (an apex drag hits).
_RESULTS = LruCache(64)
#: Segment keys -> small integers, so pair keys hash cheaply. Ids are never reused: when the
#: table is cleared, keys get fresh ids and the cached pairs of the old ids simply go unused.
_KEY_IDS: dict = {}
_NEXT_ID = [0]


def _key_id(key: tuple) -> int:
    """A small integer standing for a segment key (same key, same id while the table lasts)."""
    kid = _KEY_IDS.get(key)
    if kid is None:
        if len(_KEY_IDS) >= 50000:
            _KEY_IDS.clear()
        kid = _KEY_IDS[key] = _NEXT_ID[0]
        _NEXT_ID[0] += 1
    return kid


def _segment_key(drawing: Drawing, ci: int, si: int) -> tuple:
    c = drawing.curves[ci]
    return (c.vertices[si], c.vertices[si + 1], c.segments[si], c.marks[si], c.marks[si + 1], c.symmetry,
            TOL.intersect, TOL.zero, TOL.collinear)


def algorithm1(drawing: Drawing) -> dict[tuple[int, int], PrcChoice]:
    """Algorithm 1 of the paper for every ogee segment of ``drawing``.

    Returns
    -------
    dict of (curve, segment) to PrcChoice
        One entry per ogee segment (also for those whose PRC is stored: the
        drawing's stored choice is the user's and is honoured by
        :func:`~auszug.microarch.network.build`; this is what Algorithm 1 would
        pick).

    Examples
    --------
    >>> from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry
    >>> from auszug.microarch.prc import algorithm1
    >>> c = BasicCurve(((1.0, 0.0), (-0.5, 0.5)), (Segment("line"),), ("ground", "apex"),
    ...                Symmetry(fold=1, mirror=True, axis=(0.0, 1.0)))
    >>> ch = algorithm1(Drawing((c,)))[(0, 0)]
    >>> ch.branch, round(ch.fraction, 12)   # meets its mirror image at x = 0
    ('own replicas', 0.666666666667)
    """
    curves = tuple((c.vertices, c.segments, c.marks, c.symmetry, c.layer) for c in drawing.curves)
    key = (TOL.param_equal, TOL.intersect, TOL.zero, TOL.collinear, curves)
    hit = _CHOICES.get(key)
    if hit is not None:
        return dict(hit)
    out = _algorithm1(drawing)
    _CHOICES.put(key, out)
    return dict(out)


_CHOICES = LruCache(256)


def _algorithm1(drawing: Drawing) -> dict[tuple[int, int], PrcChoice]:
    eps = TOL.param_equal
    allx = intersections(drawing, layer_only=True)
    out: dict[tuple[int, int], PrcChoice] = {}
    segs = oriented_segments(drawing)
    for ci, si, top in segs:
        if drawing.curves[ci].segment_kind(si) != "ogee":
            continue
        mine = [x for x in allx if x.curve == ci and x.segment == si and eps < x.u < 1.0 - eps]
        own = [x for x in mine if x.same_family and x.true]
        other = [x for x in mine if not x.same_family]
        ranked: tuple[tuple[Branch, list[TopIntersection]], ...] = (("own replicas", own), ("other curves", other))
        for branch, cands in ranked:
            if cands:
                best = min(cands, key=lambda x: (abs(x.u - 0.5), x.u))
                out[(ci, si)] = PrcChoice(ci, si, best.u, branch, np.asarray(best.point), best)
                break
        else:
            out[(ci, si)] = PrcChoice(ci, si, 0.5, "midpoint", top.point_at(0.5), None)
    return out
