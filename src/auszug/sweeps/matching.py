"""Partial congruence of planar cuts by their curvature plots (paper sec. 2.1) and families (sec. 2.2).

Two planar curves are congruent iff their signed curvatures as functions of arc length agree up
to the sign (the plane's two sides) and the direction of travel. Every movable run is resampled
at one arc-length spacing ``h`` and its signed curvature taken in its plane; a partial match of
runs ``a`` and ``b`` is a window on a diagonal of the ``n_a x n_b`` correspondence matrix, in one
of the 4 variants (b as is, negated, reversed, both), at least ``l_min / h`` samples long, with

    mean |kappa_a - kappa_b'| <= eps_match * max(E_kappa,0, kappa_floor)        (Eq. 6)

where ``E_kappa,0`` is the mean of ``(|kappa_a| + |kappa_b'|) / 2`` over the window (the energy
against zero curvature, made symmetric). The floor lets straight pieces (``kappa = 0``, every
Gothic fillet and face) match: without it their threshold would be 0 and noise alone would
forbid a match.

The paper solves this "by dynamic programming" with a cost matrix ``C[j, j'] = min E`` over the
matches of the prefixes. A mean is not decomposable that way (a prefix's best mean says nothing
about the best mean of its extension: the printed recursion has no optimal substructure), so we
solve the stated problem directly: on each diagonal, the condition is ``sum (d_t - tau_t) <= 0``
over the window, and the longest such window is the widest ramp of the prefix sums, found in
O(n) with prefix minima and suffix maxima. All diagonals of all 4 variants of all pairs run in
one compiled parallel loop: O(n_a n_b) per pair.

Closed profiles (beyond the paper, whose implementation handles none): a run that is a whole
closed cut curve keeps its plot (the run taken as open, matched as the paper's) and gets a loop
beside it (``period`` samples round to its start again, curvature taken cyclically). A pair of
closed plots is matched again on its loops, each twice over, so the diagonals hold every cyclic
shift, in the same 4 variants (4 x shifts); a window is at most one period long and its starts
are taken modulo the periods. This cyclic match replaces the open one only if it covers at least
``family_keep`` of the shorter loop (letting partial matches wrap changed the tracery border's
open matches and a general patch crowded out its kinematic parts). A seed with cyclic matches
grows its family from those only, on the loops; the family is closed if its common part is at
least ``family_keep`` of the shortest loop, and its parts (:func:`family_parts`) are then the
members' whole loops, each resampled to the seed's period from its sample matching the seed's
first, so that sample ``i`` corresponds across members up to the loops' different lengths
(oblique cuts of one tube differ in length; their common part is shorter than any loop).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.sweeps import _kernels
from auszug.sweeps.cut import Cuts
from auszug.sweeps.movability import Movability
from auszug.sweeps.params import DEFAULT, SweepParams

__all__ = ["CurvaturePlots", "Matches", "Family", "Ribs", "resample", "signed_curvature", "curvature_plots",
           "match_cuts", "families", "family_parts", "align_loops", "order_energy", "order_ribs", "ordered_parts",
           "split_family"]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]


@dataclass(frozen=True)
class CurvaturePlots:
    """Movable runs resampled at one spacing, with their signed curvature.

    Attributes
    ----------
    points : (N, 3) float array
        Every run's samples, run after run, ``spacing`` apart along the run.
    kappa : (N,) float array
        Signed curvature at each sample, in the run's plane (sign by the plane's normal).
    start : (r + 1,) int array
        Run ``k`` is ``points[start[k]:start[k + 1]]``.
    run : (r,) int array
        The movable run (index into :class:`~auszug.sweeps.movability.Movability`) of each plot.
    normal : (r, 3) float array
        The unit normal of each run's plane.
    spacing : float
    period : (r,) int array
        Samples of a closed plot's loop (a whole closed cut curve, resampled round to its start
        again, its last sample joined to its first); 0 for an open plot.
    loop_points : (L, 3) float array
        The closed plots' loops, plot after plot (``period`` samples each; none for open plots):
        the plot's own samples (the run taken as open, as the paper's) and those on the closing
        segment.
    loop_kappa : (L,) float array
        Their curvature, taken cyclically.
    """

    points: Array
    kappa: Array
    start: IntArray
    run: IntArray
    normal: Array
    spacing: float
    period: IntArray | None = None
    loop_points: Array | None = None
    loop_kappa: Array | None = None

    def periods(self) -> IntArray:
        """``period``, zeros when not given."""
        return np.zeros(self.n_runs, np.int64) if self.period is None else self.period

    def loop_start(self) -> IntArray:
        """Loop ``k`` is ``loop_points[loop_start[k]:loop_start[k + 1]]`` (empty for an open plot)."""
        return np.concatenate([[0], np.cumsum(self.periods())]).astype(np.int64)

    def loop(self, k: int) -> tuple[Array, Array]:
        """Samples ``(period, 3)`` and curvature ``(period,)`` of plot ``k``'s loop."""
        ls = self.loop_start()
        assert self.loop_points is not None and self.loop_kappa is not None
        return self.loop_points[ls[k]:ls[k + 1]], self.loop_kappa[ls[k]:ls[k + 1]]

    @property
    def n_runs(self) -> int:
        """Number of curvature plots."""
        return len(self.run)

    def samples(self, k: int) -> Array:
        """Samples ``(n, 3)`` of plot ``k``."""
        return self.points[self.start[k] : self.start[k + 1]]

    def curvature(self, k: int) -> Array:
        """Curvature ``(n,)`` of plot ``k``."""
        return self.kappa[self.start[k] : self.start[k + 1]]


@dataclass(frozen=True)
class Matches:
    """The partial matches found between pairs of curvature plots.

    Attributes
    ----------
    plots : CurvaturePlots
    pairs : (p, 2) int array
        Plot indices ``(a, b)``, ``a < b``, of the matched pairs.
    length : (p,) int array
        Window length in samples (times ``plots.spacing``: arc length).
    flipped, reversed : (p,) bool arrays
        The variant: b's curvature negated; b traversed backwards.
    start_a : (p,) int array
        First sample of the window on a.
    start_b : (p,) int array
        The sample of b matching ``start_a`` (then b runs forwards, or backwards if reversed).
    energy : (p,) float array
        ``E_kappa,kappa'``, the mean ``|kappa - kappa'|`` over the window.
    reference : (p,) float array
        ``E_kappa,0`` over the window (before the floor).
    tested : int
        Pairs compared (after angle pruning).
    cyclic : (p,) bool array
        A cyclic match of two closed plots' loops (its starts index the loops, its window is at
        least ``family_keep`` of the shorter loop).
    """

    plots: CurvaturePlots
    pairs: IntArray
    length: IntArray
    flipped: BoolArray
    reversed: BoolArray
    start_a: IntArray
    start_b: IntArray
    energy: Array
    reference: Array
    tested: int
    cyclic: BoolArray | None = None

    @property
    def n_matches(self) -> int:
        """Number of matched pairs."""
        return len(self.pairs)

    def correspondence(self, k: int) -> tuple[IntArray, IntArray]:
        """Sample indices ``(i_a, i_b)`` of match ``k``, position by position (modulo a closed plot's period)."""
        t = np.arange(self.length[k])
        ia = self.start_a[k] + t
        ib = self.start_b[k] - t if self.reversed[k] else self.start_b[k] + t
        if self.cyclic is None or not self.cyclic[k]:
            return ia, ib
        per = self.plots.periods()
        return ia % int(per[self.pairs[k, 0]]), ib % int(per[self.pairs[k, 1]])


@dataclass(frozen=True)
class Family:
    """Near-congruent parts of several runs (sec. 2.2), trimmed to one length.

    Attributes
    ----------
    seed : int
        The plot the family was grown from.
    members : (k,) int array
        Plot indices, the seed first.
    start : (k,) int array
        Each member's sample matching the seed's first sample of the common part.
    reversed : (k,) bool array
        The member runs backwards against the seed.
    flipped : (k,) bool array
        The member's curvature is the seed's negated (its plane's normal points the other way).
    length : int
        Samples in the common part.
    period : (k,) int array or None
        A family of cyclic matches: each member's period (its indices are into its loop, modulo
        the period); None for a family of open matches.
    closed : bool
        A family of cyclic matches whose common part is at least ``family_keep`` of the shortest loop.
    """

    seed: int
    members: IntArray
    start: IntArray
    reversed: BoolArray
    flipped: BoolArray
    length: int
    period: IntArray | None = None
    closed: bool = False

    def indices(self, j: int) -> IntArray:
        """Sample indices of member ``j`` (in its plot), in the seed's order."""
        t = np.arange(self.length)
        i = self.start[j] - t if self.reversed[j] else self.start[j] + t
        return i if self.period is None else i % int(self.period[j])


def resample(polyline: ArrayLike, spacing: float, closed: bool = False) -> Array:
    """Points ``spacing`` apart along a polyline (``floor(length / spacing) + 1`` of them, from its start).

    Examples
    --------
    >>> resample([[0, 0, 0], [1, 0, 0], [1, 1, 0]], 0.5).tolist()
    [[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.5, 0.0], [1.0, 1.0, 0.0]]
    """
    p = np.asarray(polyline, float)
    if closed:
        p = np.vstack([p, p[:1]])
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])
    u = np.arange(int(np.floor(s[-1] / spacing + 1e-9)) + 1) * spacing
    return np.column_stack([np.interp(u, s, p[:, k]) for k in range(3)])


def signed_curvature(points: ArrayLike, normal: ArrayLike, window: int, closed: bool = False) -> Array:
    """Signed curvature ``(n,)`` of evenly spaced planar points: turning angle over ``+-window`` samples.

    The angle between the chords to the samples ``window`` before and after, over the mean chord
    length; one-sided (shorter) near the ends, cyclic for ``closed`` points (the last joined to the
    first). Positive where the curve turns counter-clockwise
    seen from the side ``normal`` points to.

    Examples
    --------
    >>> t = np.linspace(0, 1, 101)
    >>> arc = np.column_stack([np.cos(t), np.sin(t), 0 * t]) * 0.2
    >>> k = signed_curvature(arc, [0, 0, 1], 5)
    >>> bool(np.allclose(k[5:-5], 5.0, rtol=1e-3)), bool(np.allclose(signed_curvature(arc, [0, 0, -1], 5), -k))
    (True, True)
    """
    p = np.asarray(points, float)
    n = len(p)
    if n < 3:
        return np.zeros(n)
    idx = np.arange(n)
    cyclic = closed and n > 2 * window
    if cyclic:
        lo, hi = (idx - window) % n, (idx + window) % n
    else:
        lo, hi = np.maximum(idx - window, 0), np.minimum(idx + window, n - 1)
    e1 = p[idx] - p[lo]
    e2 = p[hi] - p[idx]
    cr = np.cross(e1, e2) @ np.asarray(normal, float)
    ang = np.arctan2(cr, np.einsum("ij,ij->i", e1, e2))
    lens = 0.5 * (np.linalg.norm(e1, axis=1) + np.linalg.norm(e2, axis=1))
    both = np.ones(n, bool) if cyclic else (lo < idx) & (idx < hi)
    return np.where(both & (lens > 0), ang / np.where(lens > 0, lens, 1.0), 0.0)


def curvature_plots(cuts: Cuts, mov: Movability, runs: ArrayLike | None = None,
                    params: SweepParams = DEFAULT) -> CurvaturePlots:
    """Resample the movable ``runs`` (default: all) at ``params.match_spacing``, with curvatures.

    A run that is a whole closed cut curve is resampled as a loop: ``spacing`` apart from its
    start round to its start again (the last step, closing the loop, between ``spacing / 2`` and
    ``3 spacing / 2``; the samples before it are those of the run taken as open), its curvature
    taken cyclically (its ``period``).

    Examples
    --------
    >>> from auszug.sweeps import cut, movability, normalise
    >>> from auszug.sweeps.fixtures import extruded
    >>> fx = extruded(n_profile=40, n_path=20)
    >>> c = cut(normalise(fx.vertices, fx.faces), [[1.0, 0, 0]], [0.0])
    >>> p = curvature_plots(c, movability(c))
    >>> p.n_runs, len(p.samples(0)) == int(fx.profile_length / 0.005) + 1
    (1, True)
    """
    h = params.match_spacing
    window = max(1, int(round(params.curvature_window / (2 * h))))
    sel = np.arange(mov.n_runs) if runs is None else np.asarray(runs, np.int64)
    pts, kap, counts, periods, loops, loop_kap = [], [], [], [], [], []
    normals = cuts.plane_normals[cuts.curve_plane[mov.run_curve[sel]]] if len(sel) else np.zeros((0, 3))
    for r, nrm in zip(sel, normals, strict=True):  # one resampling per run (not per pair)
        idx = mov.run_indices(cuts, int(r))
        k = int(mov.run_curve[r])
        loop = bool(cuts.curve_closed[k]) and len(idx) == int(cuts.curve_start[k + 1] - cuts.curve_start[k])
        q = resample(cuts.points[idx], h)
        pts.append(q)
        kap.append(signed_curvature(q, nrm, window))
        counts.append(len(q))
        periods.append(0)
        if loop:   # the open run's samples and those on the closing segment
            lq = resample(cuts.points[idx], h, closed=True)
            if len(lq) > 3 and np.linalg.norm(lq[-1] - lq[0]) < 0.5 * h:
                lq = lq[:-1]
            loops.append(lq)
            loop_kap.append(signed_curvature(lq, nrm, window, True))
            periods[-1] = len(lq)
    start = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    points = np.vstack(pts) if pts else np.zeros((0, 3))
    kappa = np.concatenate(kap) if kap else np.zeros(0)
    return CurvaturePlots(points, kappa, start, sel.astype(np.int64), normals, h, np.array(periods, np.int64),
                          np.vstack(loops) if loops else np.zeros((0, 3)),
                          np.concatenate(loop_kap) if loop_kap else np.zeros(0))


def match_cuts(plots: CurvaturePlots, params: SweepParams = DEFAULT) -> Matches:
    """Match every pair of plots whose planes meet at most ``params.match_angle`` (sec. 2.1-2.2).

    Examples
    --------
    Two cuts of an extrusion by planes 10 degrees apart are the same profile (sheared a little):

    >>> from auszug.sweeps import cut, movability, normalise
    >>> from auszug.sweeps.fixtures import extruded
    >>> fx = extruded(n_profile=80, n_path=40)
    >>> c = cut(normalise(fx.vertices, fx.faces), [[1.0, 0, 0], [1.0, 0, 0]], [-0.1, 0.2])
    >>> m = match_cuts(curvature_plots(c, movability(c)))
    >>> m.n_matches, int(m.length[0]) == len(m.plots.samples(0)), float(m.energy[0]) < 1e-9
    (1, True, True)
    """
    r = plots.n_runs
    ia, ib = np.triu_indices(r, 1)
    cosang = np.abs(np.einsum("ij,ij->i", plots.normal[ia], plots.normal[ib])) if r > 1 else np.zeros(0)
    keep = cosang >= np.cos(np.radians(params.match_angle)) - 1e-12
    pairs = np.ascontiguousarray(np.column_stack([ia[keep], ib[keep]]).astype(np.int64))
    min_len = max(2, int(np.ceil(params.l_min / plots.spacing - 1e-9)))
    per = plots.periods()
    ln, var, sa, sb, e, ref = _kernels.match_pairs(plots.kappa, plots.start, pairs, float(params.eps_match),
                                                   float(params.kappa_floor), min_len)
    rev = (var & 2) != 0
    mb = np.diff(plots.start)[pairs[:, 1]] if len(pairs) else np.zeros(0, np.int64)
    start_b = np.where(rev, mb - 1 - sb, sb)  # in b's own indices
    pa, pb = (per[pairs[:, 0]], per[pairs[:, 1]]) if len(pairs) else (np.zeros(0, np.int64),) * 2
    loops = (pa > 0) & (pb > 0)
    cyclic = np.zeros(len(pairs), bool)
    if loops.any():   # pairs of closed plots again, their loops twice over: every cyclic shift is a diagonal
        start = np.concatenate([[0], np.cumsum(2 * per)]).astype(np.int64)
        kappa = np.concatenate([np.tile(plots.loop(k)[1], 2) for k in range(r)])
        sub = np.ascontiguousarray(pairs[loops])
        c_ln, c_var, c_sa, c_sb, c_e, c_ref = _kernels.match_pairs(kappa, start, sub, float(params.eps_match),
                                                                   float(params.kappa_floor), min_len)
        c_ln = np.minimum(c_ln, np.minimum(pa[loops], pb[loops]))    # at most one period
        c_rev = (c_var & 2) != 0
        c_sb = np.where(c_rev, np.diff(start)[sub[:, 1]] - 1 - c_sb, c_sb) % pb[loops]
        # a cyclic match counts only as (nearly) a whole loop; partial matches stay the open ones
        whole = c_ln >= params.family_keep * np.minimum(pa[loops], pb[loops])
        at = np.flatnonzero(loops)[whole]
        ln[at], var[at], sa[at], start_b[at] = c_ln[whole], c_var[whole], c_sa[whole] % pa[at], c_sb[whole]
        e[at], ref[at], rev[at] = c_e[whole], c_ref[whole], c_rev[whole]
        cyclic[at] = True
    ok = ln > 0
    return Matches(plots, pairs[ok], ln[ok], (var & 1)[ok] != 0, rev[ok], sa[ok], start_b[ok], e[ok], ref[ok],
                   len(pairs), cyclic[ok])


def families(matches: Matches, params: SweepParams = DEFAULT) -> tuple[Family, ...]:
    """Families of near-congruent parts (sec. 2.2): one grown from every plot that has matches.

    The seed's longest match fixes a window on the seed; every other plot matching the seed on a
    window overlapping it joins, longest overlap first, while the common part stays at least
    ``l_min`` long and at least ``family_keep`` of that first window (so that one partial match
    does not cut everybody's part short); the part is trimmed to what all members share. Families with the same member
    set are kept once. Members are paired with the seed only (within ``match_angle`` of it; the
    angle pruning of sec. 2.2), not with each other.

    Examples
    --------
    >>> from auszug.sweeps import cut, movability, normalise
    >>> from auszug.sweeps.fixtures import extruded
    >>> fx = extruded(n_profile=80, n_path=40)
    >>> c = cut(normalise(fx.vertices, fx.faces), [[1.0, 0, 0]] * 3, [-0.1, 0.0, 0.2])
    >>> fam = families(match_cuts(curvature_plots(c, movability(c))))
    >>> len(fam), fam[0].members.tolist()
    (1, [0, 1, 2])
    """
    min_len = max(2, int(np.ceil(params.l_min / matches.plots.spacing - 1e-9)))
    per = matches.plots.periods()
    out: list[Family] = []
    seen: set[tuple[int, ...]] = set()
    pa, pb = matches.pairs[:, 0], matches.pairs[:, 1]
    cyc = np.zeros(len(pa), bool) if matches.cyclic is None else matches.cyclic
    for seed in np.unique(matches.pairs):  # one family per seed (not per pair)
        mine = np.flatnonzero((pa == seed) | (pb == seed))
        # a seed with cyclic matches (whole loops) grows a family of those only, on the loops
        is_cyclic = bool(cyc[mine].any())
        mine = mine[cyc[mine] == is_cyclic]
        # express every match of the seed as (other, window on seed, other's start, reversed, flipped)
        as_a = pa[mine] == seed
        other = np.where(as_a, pb[mine], pa[mine])
        ln = matches.length[mine]
        rev = matches.reversed[mine]
        flip = matches.flipped[mine]
        s_seed = np.where(as_a, matches.start_a[mine], np.where(rev, matches.start_b[mine] - ln + 1,
                                                                 matches.start_b[mine]))
        s_other = np.where(as_a, matches.start_b[mine], np.where(rev, matches.start_a[mine] + ln - 1,
                                                                  matches.start_a[mine]))
        first = int(np.argmax(ln))
        p_seed = int(per[seed]) if is_cyclic else 0
        if p_seed:
            s_seed = s_seed % p_seed
        lo, hi = int(s_seed[first]), int(s_seed[first] + ln[first])
        shortest = max(min_len, int(np.ceil(params.family_keep * ln[first])))
        overlap = np.array([_meet(lo, hi, int(s), int(n), p_seed)[2] for s, n in zip(s_seed, ln, strict=True)])
        order = np.argsort(-overlap, kind="stable")
        members = []
        for k in order:
            nlo, nhi, _ = _meet(lo, hi, int(s_seed[k]), int(ln[k]), p_seed)
            if nhi - nlo < shortest:
                continue
            lo, hi = nlo, nhi
            members.append(k)
        key = tuple(sorted([int(seed)] + [int(other[k]) for k in members]))
        if key in seen:
            continue
        seen.add(key)
        ks = np.array(members, np.int64)
        # each member's sample matching the seed's sample `lo`
        off = (lo - s_seed[ks]) % p_seed if p_seed else lo - s_seed[ks]
        st = np.where(rev[ks], s_other[ks] - off, s_other[ks] + off)
        mem = np.r_[seed, other[ks]].astype(np.int64)
        pm = per[mem] if is_cyclic else None
        if pm is not None:
            st = st % pm[1:]
        closed = pm is not None and hi - lo >= params.family_keep * int(pm.min())
        out.append(Family(int(seed), mem, np.r_[lo % p_seed if p_seed else lo, st].astype(np.int64),
                          np.r_[False, rev[ks]], np.r_[False, flip[ks]], hi - lo, pm, closed))
    return tuple(out)


def _meet(lo: int, hi: int, s: int, n: int, period: int) -> tuple[int, int, int]:
    """The common part ``(lo', hi', length)`` of the windows ``[lo, hi)`` and ``[s, s + n)`` on a plot.

    On a closed plot (``period`` > 0) both are arcs of the loop: ``s`` is taken to the shift
    (by a multiple of the period) meeting ``[lo, hi)`` most, and a whole loop meets every arc
    in all of it. ``hi' - lo'`` may be negative (no common part).

    Examples
    --------
    >>> _meet(0, 10, 5, 10, 0), _meet(2, 10, 38, 8, 40), _meet(0, 40, 30, 39, 40)
    ((5, 10, 5), (2, 6, 4), (30, 69, 39))
    """
    if period <= 0:
        a, b = max(lo, s), min(hi, s + n)
        return a, b, b - a
    if hi - lo >= period:
        return s, s + min(n, period), min(n, period)
    best = (0, 0, -(1 << 40))
    s0 = lo + (s - lo) % period
    for c in (s0, s0 - period):
        a, b = max(lo, c), min(hi, c + n)
        if b - a > best[2]:
            best = (a, b, b - a)
    return best


def family_parts(family: Family, plots: CurvaturePlots, tolerance: float | None = None) -> Array:
    """The members' parts ``(k, n, 3)``, sample ``i`` corresponding across members.

    An open family's parts are the common part (``n = length``); a closed family's are the
    members' whole loops, each resampled (linearly between its samples) to ``n`` = the seed's
    period, starting at its sample matching the seed's first and running in the seed's direction.
    With ``tolerance``, each closed family's loop is then aligned to the seed's by the least turn
    among the alignments as good as the match's (:func:`align_loops`).
    """
    k = len(family.members)
    if family.period is None:
        return np.stack([plots.samples(int(family.members[j]))[family.indices(j)] for j in range(k)])
    if not family.closed:
        return np.stack([plots.loop(int(family.members[j]))[0][family.indices(j)] for j in range(k)])
    n = int(family.period[0])
    out = np.empty((k, n, 3))
    t = np.arange(n, dtype=float)
    for j in range(k):   # one resampling per member (k <= the family's size)
        loop = plots.loop(int(family.members[j]))[0]
        p = len(loop)
        u = family.start[j] + (-1.0 if family.reversed[j] else 1.0) * t * p / n
        i0 = np.floor(u).astype(np.int64)
        w = (u - i0)[:, None]
        out[j] = (1 - w) * loop[i0 % p] + w * loop[(i0 + 1) % p]
    return out if tolerance is None else align_loops(out, tolerance)


def _kabsch_fits(x: Array, ys: Array) -> tuple[Array, Array]:
    """Residuals and turns of the best proper rigid maps of ``x (n, 3)`` onto each ``ys[c] (n, 3)``.

    Kabsch with equal weights: the root-mean-square residual ``(c,)`` and the turn (degrees, ``(c,)``).
    """
    xc = x - x.mean(axis=0)
    yc = ys - ys.mean(axis=1, keepdims=True)
    h = np.einsum("ni,cnj->cij", xc, yc)
    u, sv, vt = np.linalg.svd(h)
    d = np.sign(np.linalg.det(np.swapaxes(vt, 1, 2) @ np.swapaxes(u, 1, 2)))
    d = np.where(d != 0, d, 1.0)
    sv[:, 2] *= d
    vt[:, 2, :] *= d[:, None]
    r = np.swapaxes(vt, 1, 2) @ np.swapaxes(u, 1, 2)
    sq = float((xc**2).sum()) + (yc**2).sum(axis=(1, 2)) - 2 * sv.sum(axis=1)
    rms = np.sqrt(np.maximum(sq, 0.0) / len(x))
    turn = np.degrees(np.arccos(np.clip((np.trace(r, axis1=1, axis2=2) - 1) / 2, -1.0, 1.0)))
    return rms, turn


def align_loops(parts: ArrayLike, tolerance: float) -> Array:
    """Closed parts ``(k, n, 3)`` each re-aligned to the first by the least turn (beyond the paper).

    A profile with symmetries (the square of a bar: four turns and four flips) matches itself
    under several alignments of its loop, all equally congruent, and the curvature match picks
    any of them: one member's samples may correspond to the seed's turned by a quarter turn or
    flipped, and a sweep fitted to such ribs turns the profile where the surface does not (the
    fit bound cannot tell when the profile is small). Every cyclic shift of part ``j``, in both
    directions, is an alignment; those that are local minima of the Kabsch residual (rms) over
    the shifts and within ``tolerance`` of the given alignment's residual are as good a match,
    and the one whose best rigid map from the first part turns least is taken (neighbouring
    cuts of a sweep differ by a small turn). A profile without symmetry has no other alignment
    within the tolerance: its parts are returned as given.

    Parameters
    ----------
    parts : (k, n, 3) array_like
        Closed loops, sample ``i`` corresponding across parts.
    tolerance : float
        Residual (rms, the parts' units) by which another alignment may exceed the given one.

    Returns
    -------
    (k, n, 3) float array

    Examples
    --------
    A square's loop, its copy moved a little and its samples shifted by a quarter turn: aligned back.

    >>> t = np.arange(16)
    >>> side = np.r_[np.linspace(-1, 1, 5)[:-1]]
    >>> sq = np.column_stack([np.r_[side, np.ones(4), -side, -np.ones(4)],
    ...                       np.r_[-np.ones(4), side, np.ones(4), -side], np.zeros(16)])
    >>> moved = np.roll(sq + [0.1, 0.0, 0.3], 4, axis=0)
    >>> out = align_loops(np.stack([sq, moved]), 0.01)
    >>> bool(np.allclose(out[1], sq + [0.1, 0.0, 0.3]))
    True
    """
    x = np.array(parts, dtype=float)
    k, n = x.shape[:2]
    if k < 2 or n < 3:
        return x
    t = np.arange(n)
    idx = np.concatenate([(t[None, :] + t[:, None]) % n, (t[:, None] - t[None, :]) % n])   # shifts, both ways
    for j in range(1, k):
        rms, turn = _kabsch_fits(x[0], x[j][idx])
        r2 = rms.reshape(2, n)
        local = ((r2 <= np.roll(r2, 1, axis=1)) & (r2 <= np.roll(r2, -1, axis=1))).reshape(-1)
        ok = local & (rms <= rms[0] + tolerance)
        ok[0] = True
        best = int(np.flatnonzero(ok)[np.argmin(turn[ok])])
        if turn[best] < turn[0]:
            x[j] = x[j][idx[best]]
    return x


@dataclass(frozen=True)
class Ribs:
    """A family's members ordered like successive positions of a moving profile (sec. 2.2).

    Attributes
    ----------
    family : Family
    order : (k,) int array
        Positions in ``family.members``, in rib order (the seed somewhere inside).
    energy : (k - 1,) float array
        ``E_order`` of each successive pair.
    tolerance : float or None
        The alignment tolerance of a closed family's parts (:func:`family_parts`), or None.
    """

    family: Family
    order: IntArray
    energy: Array
    tolerance: float | None = None

    @property
    def plots(self) -> IntArray:
        """Plot indices of the ribs, in order."""
        return self.family.members[self.order]


def order_energy(parts: Array, omega: tuple[float, float]) -> Array:
    """``E_order`` ``(k, k)`` between equal-length parts ``(k, n, 3)`` (sample ``i`` matching sample ``i``).

    ``-d_min / delta + omega_1 mean(t_i . t'_i) + omega_2 d_min / d_haus``, with ``d_min`` the
    smallest and ``d_haus`` the (two-sided) Hausdorff distance between the parts' samples and
    ``delta`` the diameter of the family (the diagonal of its samples' bounding box). The diagonal
    is -inf.

    Examples
    --------
    >>> x = np.linspace(0, 1, 11)
    >>> parts = np.stack([np.column_stack([x, 0 * x, 0 * x + z]) for z in (0.0, 0.1, 0.5)])
    >>> e = order_energy(parts, (0.6, 1.0))
    >>> int(np.argmax(e[0])), round(float(e[0, 1]), 6)
    (1, 1.510557)
    """
    k, n, _ = parts.shape
    delta = float(np.linalg.norm(np.ptp(parts.reshape(-1, 3), axis=0)))
    tan = np.diff(parts, axis=1)
    tan /= np.maximum(np.linalg.norm(tan, axis=2, keepdims=True), 1e-300)
    out = np.full((k, k), -np.inf)
    for a in range(k):  # one row per part (not per pair): (k, n, n) distances at a time
        d = np.linalg.norm(parts[a][None, :, None, :] - parts[:, None, :, :], axis=3)
        d_min = d.min(axis=(1, 2))
        d_haus = np.maximum(d.min(axis=2).max(axis=1), d.min(axis=1).max(axis=1))
        par = np.einsum("ij,kij->k", tan[a], tan) / (n - 1)
        row = -d_min / delta + omega[0] * par + omega[1] * d_min / np.maximum(d_haus, 1e-300)
        row[a] = -np.inf
        out[a] = row
    return out


def order_ribs(family: Family, plots: CurvaturePlots, params: SweepParams = DEFAULT) -> Ribs:
    """Greedy rib ordering by ``E_order`` (sec. 2.2), from the seed both ways.

    From ``b_0`` (the seed) take the unused part of largest ``E_order(b_i, .)`` as ``b_{i+1}``,
    provided ``b_{i-1}`` and ``b_{i+1}`` lie on opposite sides of ``b_i``'s plane (their centroids);
    then the same from ``b_0`` backwards (``b_{-1}`` opposite ``b_1``). Parts that never qualify are
    left out.

    Examples
    --------
    Cuts of an extrusion by parallel planes, given shuffled, come out in order:

    >>> from auszug.sweeps import cut, movability, normalise
    >>> from auszug.sweeps.fixtures import extruded
    >>> fx = extruded(n_profile=60, n_path=60)
    >>> xs = np.array([0.05, -0.2, 0.3, -0.05, 0.15, -0.3])
    >>> c = cut(normalise(fx.vertices, fx.faces), np.tile([1.0, 0, 0], (6, 1)), xs)
    >>> pl = curvature_plots(c, movability(c))
    >>> ribs = order_ribs(families(match_cuts(pl))[0], pl)
    >>> xs[pl.run[ribs.plots]].tolist() in ([-0.3, -0.2, -0.05, 0.05, 0.15, 0.3], [0.3, 0.15, 0.05, -0.05, -0.2, -0.3])
    True
    """
    k = len(family.members)
    # a closed family's loops aligned by the least turn within eps_prox (a symmetric profile's alignments)
    parts = family_parts(family, plots, params.eps_prox)
    e = order_energy(parts, params.omega)
    centre = parts.mean(axis=1)
    normal = plots.normal[family.members]

    def side(i: int, j: int) -> float:
        return float(normal[i] @ (centre[j] - centre[i]))

    used = np.zeros(k, bool)
    used[0] = True
    chains: list[list[int]] = [[0], [0]]
    for direction in (0, 1):
        chain = chains[direction]
        while True:
            cur = chain[-1]
            prev = chain[-2] if len(chain) > 1 else (chains[0][1] if direction == 1 and len(chains[0]) > 1 else -1)
            cand = np.flatnonzero(~used)
            if prev >= 0:
                cand = cand[np.array([side(cur, prev) * side(cur, int(j)) < 0 for j in cand], bool)]
            if len(cand) == 0:
                break
            nxt = int(cand[np.argmax(e[cur, cand])])
            chain.append(nxt)
            used[nxt] = True
    order = np.array(chains[1][::-1] + chains[0][1:], np.int64)
    energy = e[order[:-1], order[1:]]
    ribs = Ribs(family, order, energy, params.eps_prox)
    # the parts in rib order, kept with the ribs for these plots (:func:`ordered_parts`: not taken again)
    object.__setattr__(ribs, "_parts", (plots, parts[order]))
    return ribs


def ordered_parts(ribs: Ribs, plots: CurvaturePlots) -> Array:
    """The ribs' common parts ``(k, n, 3)`` in rib order: ``family_parts(family, plots, tolerance)[order]``.

    The parts :func:`order_ribs` took for the same ``plots`` are kept with the ribs and given
    (a copy); other plots' are taken anew.
    """
    kept = ribs.__dict__.get("_parts")
    if kept is not None and kept[0] is plots:
        out: Array = kept[1].copy()
        return out
    return family_parts(ribs.family, plots, ribs.tolerance)[ribs.order]


def split_family(family: Family, component: ArrayLike) -> tuple[Family, ...]:
    """The family split by the mesh component its members lie on (beyond the paper).

    Cuts of separate pieces of a mesh (the members of a curve network, unwelded) are congruent
    where the pieces share a profile, so one family collects runs of several pieces and its
    ordered ribs jump between them; a sweep lies on one piece. Each part keeps its members in
    the family's order, aligned to the same common part (``start``, ``reversed``, ``flipped``
    as before); its seed is its first member.

    Parameters
    ----------
    family : Family
    component : (k,) int array
        The component of each member (in the order of ``family.members``).

    Returns
    -------
    tuple of Family
        One per component, in the order of their first member; the family itself when all
        members lie on one component.

    Examples
    --------
    >>> f = Family(0, np.array([0, 1, 2]), np.array([0, 0, 0]), np.zeros(3, bool), np.zeros(3, bool), 5)
    >>> [p.members.tolist() for p in split_family(f, [7, 3, 7])]
    [[0, 2], [1]]
    """
    comp = np.asarray(component)
    if len(comp) != len(family.members):
        raise ValueError(f"split_family: {len(comp)} components for {len(family.members)} members")
    labels, first = np.unique(comp, return_index=True)
    if len(labels) <= 1:
        return (family,)
    out = []
    for lab in labels[np.argsort(first)]:
        j = np.flatnonzero(comp == lab)
        out.append(Family(int(family.members[j[0]]), family.members[j], family.start[j], family.reversed[j],
                          family.flipped[j], family.length, None if family.period is None else family.period[j],
                          family.closed))
    return tuple(out)
