"""Regularity cues (paper sec. 3.2, 5.2): candidates, their angles on a 3D network, their rows.

Each family holds all candidates of one class as index arrays; ``angles(X)``
measures every candidate on the control points ``X`` (n, 3) in degrees (0 =
perfectly regular), ``add(P, which, weight)`` adds the chosen candidates'
residual rows to a :class:`~auszug.lifting.solver.Poly2` (soft term or hard
constraint). Residuals are normalised by the 2D lengths involved, so that
the weight w_c means the same for every cue.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from auszug.lifting.params import LiftParams
from auszug.lifting.sketch import SketchGraph
from auszug.lifting.solver import Poly2
from auszug.lifting.terms import add_dot, add_lin3

__all__ = ["likelihood", "Parallel", "Orthogonal", "Symmetry", "Planar", "parallel_cues", "orthogonal_cues",
           "symmetry_cues", "planar_cues", "angle_between", "PlanePairs", "plane_cues", "Linear",
           "linear_cues"]

Array = NDArray[np.float64]
Index = NDArray[np.intp]


def likelihood(alpha: Array, params: LiftParams) -> Array:
    """L(alpha) = min(1, a alpha^b) within the outer bound, 0 beyond (Eq. 10), alpha in degrees.

    Examples
    --------
    >>> from auszug.lifting.params import DEFAULT
    >>> likelihood(np.array([0.0, 5.0, 10.0, 15.0, 15.1]), DEFAULT).round(4).tolist()
    [1.0, 1.0, 0.0353, 0.005, 0.0]
    """
    a = np.asarray(alpha, dtype=float)
    with np.errstate(divide="ignore", over="ignore"):
        v = params.coefficient * np.power(np.maximum(a, 1e-300), params.exponent)
    out = np.minimum(1.0, v)
    return np.where(a > params.outer_deg, 0.0, np.where(a <= params.inner_deg, 1.0, out))


def angle_between(u: Array, v: Array) -> Array:
    """Angles between rows of u and v (..., 3), degrees; 0 where either is zero."""
    nu = np.linalg.norm(u, axis=-1)
    nv = np.linalg.norm(v, axis=-1)
    den = nu * nv
    c = np.where(den > 0, np.einsum("...i,...i->...", u, v) / np.where(den > 0, den, 1.0), 1.0)
    return np.degrees(np.arccos(np.clip(c, -1.0, 1.0)))


@dataclass(frozen=True)
class Parallel:
    """Tangent parallelism at adjacent intersections along a curve.

    ``(h1 - p1) / n1`` and ``s (h2 - p2) / n2`` equal (n the 2D handle lengths).
    """

    p1: Index
    h1: Index
    p2: Index
    h2: Index
    sign: Array
    n1: Array
    n2: Array
    angle2d: Array
    where: tuple[str, ...]

    def __len__(self) -> int:
        return len(self.p1)

    def angles(self, X: Array) -> Array:
        """Each candidate's angle on control points X (n, 3), degrees (0 = regular)."""
        return angle_between(X[self.h1] - X[self.p1], self.sign[:, None] * (X[self.h2] - X[self.p2]))

    def add(self, P: Poly2, which: Index, weight: Array | float) -> None:
        """Add the residual rows of candidates ``which`` (soft term or hard constraint)."""
        if not len(which):
            return
        i = which
        slots = np.stack([self.h1[i], self.p1[i], self.h2[i], self.p2[i]], axis=1)
        a, b = 1.0 / self.n1[i], self.sign[i] / self.n2[i]
        w = np.stack([a, -a, -b, b], axis=1)
        add_lin3(P, slots, w, np.zeros(3 * len(i)), np.broadcast_to(np.asarray(weight, float), (len(i),)))


@dataclass(frozen=True)
class Orthogonal:
    """Orthogonal tangents at an intersection: ``(h1 - p) . (h2 - p) = 0``."""

    p: Index
    h1: Index
    h2: Index
    n1: Array
    n2: Array
    where: tuple[str, ...]

    def __len__(self) -> int:
        return len(self.p)

    def angles(self, X: Array) -> Array:
        """Each candidate's angle on control points X (n, 3), degrees (0 = regular)."""
        return np.abs(90.0 - angle_between(X[self.h1] - X[self.p], X[self.h2] - X[self.p]))

    def add(self, P: Poly2, which: Index, weight: Array | float) -> None:
        """Add the residual rows of candidates ``which`` (soft term or hard constraint)."""
        if not len(which):
            return
        i = which
        one = np.ones(len(i))
        add_dot(P, np.stack([self.h1[i], self.p[i]], 1), np.stack([one, -one], 1) / self.n1[i, None],
                np.stack([self.h2[i], self.p[i]], 1), np.stack([one, -one], 1) / self.n2[i, None], 0.0,
                np.broadcast_to(np.asarray(weight, float), (len(i),)))


@dataclass(frozen=True)
class Symmetry:
    """Local symmetry (Eq. 8): ``((f_out + f_in) / 2 - p) . (h - p) = 0``.

    The curve through ``p`` with far control points ``f_out`` and ``f_in``
    (the ends of its two segments at ``p``) is a local symmetry plane of the
    curve whose tangent handle at ``p`` is ``h``.
    """

    p: Index
    f_out: Index
    f_in: Index
    h: Index
    nm: Array
    nh: Array
    where: tuple[str, ...]

    def __len__(self) -> int:
        return len(self.p)

    def angles(self, X: Array) -> Array:
        """Each candidate's angle on control points X (n, 3), degrees (0 = regular)."""
        m = 0.5 * (X[self.f_out] + X[self.f_in]) - X[self.p]
        return np.abs(90.0 - angle_between(m, X[self.h] - X[self.p]))

    def add(self, P: Poly2, which: Index, weight: Array | float) -> None:
        """Add the residual rows of candidates ``which`` (soft term or hard constraint)."""
        if not len(which):
            return
        i = which
        one = np.ones(len(i))
        add_dot(P, np.stack([self.f_out[i], self.f_in[i], self.p[i]], 1),
                np.stack([0.5 * one, 0.5 * one, -one], 1) / self.nm[i, None],
                np.stack([self.h[i], self.p[i]], 1), np.stack([one, -one], 1) / self.nh[i, None], 0.0,
                np.broadcast_to(np.asarray(weight, float), (len(i),)))


@dataclass(frozen=True)
class Planar:
    """Curve planarity (Eq. 9), one candidate per stroke.

    Soft: with the best-fit normal n fixed (the local step of the paper's
    local-global solve), rows ``n . (X_k - mean X)``, weighted by ``2 m``
    since the paper's sum over ordered pairs equals ``2 m sum (a_k - mean a)^2``.
    Hard: the stroke's normal variable ``N`` (slot ``normal_slot``), with
    ``N . (X_k - X_0) = 0`` and ``N . N = 1``.
    """

    points: tuple[Index, ...]
    stroke: Index
    normal_slot: Index
    where: tuple[str, ...]

    def __len__(self) -> int:
        return len(self.points)

    def _groups(self) -> list[tuple[Index, Index]]:
        """The candidates grouped by their number of control points: (candidates (g,), points (g, m)) each."""
        sizes = np.array([len(p) for p in self.points], dtype=np.intp)
        return [(idx, np.stack([self.points[i] for i in idx])) for idx in
                (np.flatnonzero(sizes == m) for m in np.unique(sizes))]

    def normals(self, X: Array) -> Array:
        """Best-fit normal of each candidate (minimiser of Eq. 9), shape (k, 3).

        One batched SVD per group of candidates with the same number of points (LAPACK runs the
        same routine on every matrix of a stack), without the full left factor (m, m): the right
        singular vectors are the same bits either way (checked on 3-1000 points), and a stroke of
        292 control points took most of the time building that factor.
        """
        out = np.zeros((len(self.points), 3))
        for idx, P in self._groups():
            Y = X[P]
            Y = Y - Y.mean(1, keepdims=True)
            out[idx] = np.linalg.svd(Y, full_matrices=False)[2][:, -1]
        return out

    def angles(self, X: Array) -> Array:
        """The paper's weighted mean deviation of control-point chords from the plane.

        As printed, the angle between a chord and the *normal* is averaged with
        weights (90 - angle)^2, which gives ~90 deg for a planar curve; we read
        the deviation from the plane, 90 - angle(chord, n), in both places:
        alpha = sum dev^3 / sum dev^2 (0 for an exactly planar curve).
        """
        n = self.normals(X)
        return np.array([_planarity_angle(X[p], n[i]) for i, p in enumerate(self.points)], dtype=float)

    def add_soft(self, P: Poly2, which: Index, weight: Array, X: Array, offset_slot: Index | None = None) -> None:
        """Soft planarity rows with the best-fit normals on X fixed (the local step).

        With ``offset_slot`` (one unknown per candidate, its column index) the rows are
        ``n . X_k - d`` with d that unknown: minimised over d this is exactly
        ``n . (X_k - mean X)``, without coupling every point of the stroke to every other
        (the mean's rows are dense: the KKT factorisation filled in).
        """
        n = self.normals(X)
        for i, wt in zip(which, np.broadcast_to(weight, (len(which),)), strict=True):
            p = self.points[i]
            m = len(p)
            own = 3 * p[:, None] + np.arange(3)
            if offset_slot is not None:
                rows = np.repeat(np.arange(m), 4)
                cols = np.concatenate([own, np.full((m, 1), int(offset_slot[i]))], axis=1).reshape(-1)
                vals = np.tile(np.concatenate([n[i], [-1.0]]), m)
            else:
                rows = np.repeat(np.arange(m), 3 * (m + 1))
                cols = np.concatenate([np.concatenate([own[k], own.reshape(-1)]) for k in range(m)])
                vals = np.tile(np.concatenate([n[i], np.tile(-n[i] / m, m)]), m)
            P.add(np.zeros(m), float(wt) * 2 * m, lin=(rows, cols, vals))

    def add_hard(self, C: Poly2, which: Index, offset_slot: Index | None = None) -> None:
        """Hard planarity with each stroke's normal variable N (unit length).

        Rows ``N . (X_k - X_0) = 0``, or with ``offset_slot`` (one unknown d per
        candidate, its column index) ``N . X_k - d = 0``: the same plane, without
        every row sharing X_0.
        """
        for i in which:
            p = self.points[i]
            ns = int(self.normal_slot[i])
            if offset_slot is None:
                k = len(p) - 1
                add_dot(C, np.full((k, 1), ns), np.ones((k, 1)), np.stack([p[1:], np.full(k, p[0])], 1),
                        np.tile([1.0, -1.0], (k, 1)), 0.0, 1.0)
            else:
                m = len(p)
                rows = np.repeat(np.arange(m), 3)
                ii = (3 * ns + np.tile(np.arange(3), m))
                jj = (3 * p[:, None] + np.arange(3)).reshape(-1)
                C.add(np.zeros(m), 1.0, lin=(np.arange(m), np.full(m, int(offset_slot[i])), -np.ones(m)),
                      bil=(rows, ii, jj, np.ones(3 * m)))
            add_dot(C, np.array([[ns]]), np.ones((1, 1)), np.array([[ns]]), np.ones((1, 1)), -1.0, 1.0)


def _planarity_angle(Y: Array, n: Array) -> float:
    """:meth:`Planar.angles` of one curve's control points Y (k, 3) about the normal n (3,), degrees."""
    iu, ju = np.triu_indices(len(Y), 1)
    d = Y[ju] - Y[iu]
    keep = np.linalg.norm(d, axis=1) > 1e-12
    dev = np.abs(90.0 - angle_between(d[keep], np.broadcast_to(n, d[keep].shape)))
    w = dev**2
    return float((dev * w).sum() / w.sum()) if w.sum() > 0 else 0.0


def _linearity_angle(Y: Array) -> float:
    """:meth:`Linear.angles` of one curve's control points Y (k, 3), degrees."""
    u = np.linalg.svd(Y - Y.mean(0), full_matrices=False)[2][0]
    iu, ju = np.triu_indices(len(Y), 1)
    d = Y[ju] - Y[iu]
    keep = np.linalg.norm(d, axis=1) > 1e-12
    a = angle_between(d[keep], np.broadcast_to(u, d[keep].shape))
    dev = np.minimum(a, 180.0 - a)
    w = dev**2
    return float((dev * w).sum() / w.sum()) if w.sum() > 0 else 0.0


@dataclass(frozen=True)
class Linear:
    """Curve linearity (paper sec. 5.2, ``C_linear``), one candidate per stroke.

    Rows ``t B_0 + (1 - t) B_3 - B_k`` for the handles ``B_k`` (k = 1, 2) of
    each segment of the stroke, with ``t`` the least-squares fraction on the
    2D sketch, as the paper states (three rows, x y z, per handle). With the
    G1 joints' fixed ratios (:func:`~auszug.lifting.terms.structure`) straight
    segments make a straight curve. Segments the structure already keeps
    straight have no rows (they would be redundant hard constraints).
    """

    points: tuple[Index, ...]       # per candidate: its control points (for the angle)
    stroke: Index
    rows: Index                     # (r, 3) point slots per row: handle, B_0, B_3
    t: Array                        # (r,) the 2D fraction of each row
    cand: Index                     # (r,) candidate of each row
    where: tuple[str, ...]

    def __len__(self) -> int:
        return len(self.points)

    def angles(self, X: Array) -> Array:
        """The paper's "angles between pairs of lines connecting control points", as one figure per curve.

        Each chord between two control points makes an angle dev (0-90 deg) with
        the curve's principal direction; alpha = sum dev^3 / sum dev^2, the
        weighting :meth:`Planar.angles` uses (0 for a straight curve).
        """
        return np.array([_linearity_angle(X[p]) for p in self.points], dtype=float)

    def add(self, P: Poly2, which: Index, weight: Array | float) -> None:
        """Add the rows of candidates ``which`` (soft term or hard constraint)."""
        if not len(which):
            return
        wt = np.broadcast_to(np.asarray(weight, float), (len(which),))
        pos = np.full(len(self.points), -1)
        pos[np.asarray(which)] = np.arange(len(which))
        r = np.nonzero(pos[self.cand] >= 0)[0]
        if not len(r):
            return
        t = self.t[r]
        w = np.stack([-np.ones_like(t), t, 1.0 - t], axis=1)
        add_lin3(P, self.rows[r], w, np.zeros(3 * len(r)), wt[pos[self.cand[r]]])


@dataclass(frozen=True)
class PlanePairs:
    """Plane parallelism and plane orthogonality between planar strokes (paper sec. 5.2, curve level).

    Candidates pair two planarity candidates ``ia``, ``ib`` (indices into
    ``planar``) whose strokes' planes are parallel (``orthogonal`` False) or
    orthogonal. The residuals are on the strokes' unit normal variables
    (which hard planarity ties to the strokes): parallel ``N_a - s N_b``
    (three rows, s = +-1 fixed when the candidates are made, since a normal's
    sign is free), orthogonal ``N_a . N_b`` (one row). The angles are taken
    between the best-fit normals of the control points (:meth:`Planar.normals`).
    """

    planar: Planar
    ia: Index
    ib: Index
    sign: Array
    orthogonal: NDArray[np.bool_]
    where: tuple[str, ...]

    def __len__(self) -> int:
        return len(self.ia)

    def angles(self, X: Array) -> Array:
        """Each candidate's angle on control points X (n, 3), degrees (0 = regular)."""
        if not len(self):
            return np.zeros(0)
        n = self.planar.normals(X)
        a = angle_between(n[self.ia], n[self.ib])
        line = np.minimum(a, 180.0 - a)          # the angle between the planes, 0-90 deg
        return np.where(self.orthogonal, 90.0 - line, line)

    def add(self, P: Poly2, which: Index, weight: Array | float) -> None:
        """Add the residual rows of candidates ``which`` (soft term or hard constraint)."""
        which = np.asarray(which, dtype=np.intp)
        if not len(which):
            return
        w = np.broadcast_to(np.asarray(weight, float), (len(which),))
        na = self.planar.normal_slot[self.ia[which]]
        nb = self.planar.normal_slot[self.ib[which]]
        par = ~self.orthogonal[which]
        if par.any():
            k = np.nonzero(par)[0]
            slots = np.stack([na[k], nb[k]], axis=1)
            coef = np.stack([np.ones(len(k)), -self.sign[which[k]]], axis=1)
            add_lin3(P, slots, coef, np.zeros(3 * len(k)), w[k])
        if (~par).any():
            k = np.nonzero(~par)[0]
            one = np.ones((len(k), 1))
            add_dot(P, na[k, None], one, nb[k, None], one, 0.0, w[k])


def plane_cues(planar: Planar, applied: NDArray[np.bool_], normals: Array, names: tuple[str, ...],
               cluster_deg: float, X: Array | None = None, min_spread: float = 0.0) -> PlanePairs:
    """Plane parallelism and orthogonality candidates by single-linkage clustering of the normals.

    The applied planarity candidates' normals are clustered by single
    linkage: two normals closer than ``cluster_deg`` as lines (a normal's sign
    is free) are linked. Every link of the clusters' minimum spanning trees
    (Kruskal, shortest first) is a parallelism candidate, so a cluster of k
    strokes gets k - 1 and the hard constraints are not redundant. Two
    clusters whose mean normals are within ``cluster_deg`` of orthogonal give
    one orthogonality candidate between their first members.

    Parameters
    ----------
    planar : Planar
    applied : (k,) bool ndarray
        Which planarity candidates are applied (only their normals are tied to the strokes).
    normals : (k, 3) ndarray
        The current unit normal of every planarity candidate.
    names : (k,) tuple of str
        The strokes' names, for ``where``.
    cluster_deg : float
        The single-linkage threshold and the orthogonality tolerance, degrees (paper: 15).
    X : (n, 3) ndarray, optional
        The current control points; with ``min_spread``, a stroke takes part
        only when its points' second singular value is at least ``min_spread``
        times the first (its plane is well defined; a nearly straight curve's
        plane turns freely about its chord).
    min_spread : float
    """
    ok = np.asarray(applied, dtype=bool).copy()
    if X is not None and min_spread > 0:
        for i, p in enumerate(planar.points):
            sv = np.linalg.svd(X[p] - X[p].mean(0), compute_uv=False)
            ok[i] &= bool(sv[1] >= min_spread * max(sv[0], 1e-300))
    idx = np.nonzero(ok)[0]
    n = normals / np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-300)
    cos_t = np.cos(np.radians(cluster_deg))
    edges = []
    for u in range(len(idx)):
        for v in range(u + 1, len(idx)):
            c = abs(float(n[idx[u]] @ n[idx[v]]))
            if c >= cos_t:
                edges.append((-c, u, v))
    edges.sort()
    parent = list(range(len(idx)))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    ia: list[int] = []
    ib: list[int] = []
    orth: list[bool] = []
    where: list[str] = []
    for _, u, v in edges:
        a, b = find(u), find(v)
        if a == b:
            continue
        parent[max(a, b)] = min(a, b)
        ia.append(int(idx[u]))
        ib.append(int(idx[v]))
        orth.append(False)
        where.append(f"{names[idx[u]]} | {names[idx[v]]} parallel planes")
    clusters: dict[int, list[int]] = {}
    for u in range(len(idx)):
        clusters.setdefault(find(u), []).append(u)
    reps, means = [], []
    for members in clusters.values():
        first = n[idx[members[0]]]
        m = sum(n[idx[u]] * (1.0 if float(n[idx[u]] @ first) >= 0 else -1.0) for u in members)
        reps.append(members[0])
        means.append(m / max(float(np.linalg.norm(m)), 1e-300))
    sin_t = np.sin(np.radians(cluster_deg))
    for x in range(len(reps)):
        for y in range(x + 1, len(reps)):
            if abs(float(means[x] @ means[y])) <= sin_t:
                ia.append(int(idx[reps[x]]))
                ib.append(int(idx[reps[y]]))
                orth.append(True)
                where.append(f"{names[idx[reps[x]]]} | {names[idx[reps[y]]]} orthogonal planes")
    A, B = np.array(ia, dtype=np.intp), np.array(ib, dtype=np.intp)
    sign = np.sign(np.einsum("ij,ij->i", n[A], n[B])) if len(A) else np.zeros(0)
    sign = np.where(sign == 0, 1.0, sign)
    return PlanePairs(planar, A, B, sign, np.array(orth, dtype=bool), tuple(where))


def _halves_by_stroke(g: SketchGraph, c) -> dict[int, list[tuple[int, int]]]:
    out: dict[int, list[tuple[int, int]]] = {}
    for h, s in zip(c.ends, c.strokes, strict=True):
        out.setdefault(s, []).append(h)
    return out


def _handle(g: SketchGraph, half: tuple[int, int]) -> int:
    s, e = half
    return int(g.segments[s, 1] if e == 0 else g.segments[s, 2])


def _name(g: SketchGraph, s: int) -> str:
    return g.strokes[s].id or f"stroke #{s}"


def smooth_orthogonal(g: SketchGraph) -> Orthogonal:
    """The always-applied orthogonality at smooth crossings (one pair per crossing)."""
    p, h1, h2, where = [], [], [], []
    for c in g.crossings:
        if not c.smooth:
            continue
        hs = _halves_by_stroke(g, c)
        (sa, ha), (sb, hb) = sorted(hs.items())
        p.append(c.point)
        h1.append(_handle(g, ha[0]))
        h2.append(_handle(g, hb[0]))
        where.append(f"{_name(g, sa)} x {_name(g, sb)}")
    return _ortho(g, p, h1, h2, where)


def _ortho(g: SketchGraph, p, h1, h2, where) -> Orthogonal:
    p, h1, h2 = (np.array(x, dtype=np.intp) for x in (p, h1, h2))
    bar = g.points
    n1 = np.linalg.norm(bar[h1] - bar[p], axis=1) if len(p) else np.zeros(0)
    n2 = np.linalg.norm(bar[h2] - bar[p], axis=1) if len(p) else np.zeros(0)
    return Orthogonal(p, h1, h2, n1, n2, tuple(where))


def orthogonal_cues(g: SketchGraph) -> Orthogonal:
    """Orthogonality candidates at the intersections that are not smooth crossings.

    One tangent per stroke where the stroke is G1 through the point (its two
    halves are collinear), else each half; every pair of different strokes.
    """
    p, h1, h2, where = [], [], [], []
    g1 = {(int(a), int(b)) for (a, b), ok in zip(g.joints, g.joint_g1, strict=True) if ok}
    for c in g.crossings:
        if c.smooth:
            continue
        hs = _halves_by_stroke(g, c)
        reps: list[tuple[int, tuple[int, int]]] = []
        for s, halves in sorted(hs.items()):
            segs = {h[0]: h[1] for h in halves}
            through = len(halves) == 2 and any((a, b) in g1 or (b, a) in g1 for a in segs for b in segs if a != b)
            for h in (halves[:1] if through else halves):
                reps.append((s, h))
        for i in range(len(reps)):
            for j in range(i + 1, len(reps)):
                if reps[i][0] == reps[j][0]:
                    continue
                p.append(c.point)
                h1.append(_handle(g, reps[i][1]))
                h2.append(_handle(g, reps[j][1]))
                where.append(f"{_name(g, reps[i][0])} x {_name(g, reps[j][0])} (corner)")
    return _ortho(g, p, h1, h2, where)


def parallel_cues(g: SketchGraph, params: LiftParams) -> Parallel:
    """Tangents of the curves crossing one curve at adjacent intersections along it.

    Candidates: 2D angle (tangent directions aligned by sign) below
    ``params.parallel_2d_deg``.
    """
    at_point: dict[int, object] = {c.point: c for c in g.crossings}
    rows: list[tuple[int, int, int, int, str]] = []
    for s, chain in enumerate(g.chains):
        pts = [int(g.segments[k, 0]) for k in chain] + [int(g.segments[chain[-1], 3])]
        crossings = [q for q in dict.fromkeys(pts) if q in at_point]
        for a, b in zip(crossings[:-1], crossings[1:], strict=True):
            ca, cb = at_point[a], at_point[b]
            oa = _halves_by_stroke(g, ca)
            ob = _halves_by_stroke(g, cb)
            for sa, ha in oa.items():
                if sa == s:
                    continue
                for sb, hb in ob.items():
                    if sb == s:
                        continue
                    rows.append((a, _handle(g, ha[0]), b, _handle(g, hb[0]),
                                 f"{_name(g, sa)} || {_name(g, sb)} along {_name(g, s)}"))
    bar = g.points
    if not rows:
        z = np.zeros(0, np.intp)
        return Parallel(z, z, z, z, np.zeros(0), np.zeros(0), np.zeros(0), np.zeros(0), ())
    p1, h1, p2, h2 = (np.array([r[k] for r in rows], dtype=np.intp) for k in range(4))
    t1, t2 = bar[h1] - bar[p1], bar[h2] - bar[p2]
    sign = np.where(np.einsum("ij,ij->i", t1, t2) >= 0, 1.0, -1.0)
    n1, n2 = np.linalg.norm(t1, axis=1), np.linalg.norm(t2, axis=1)
    cosang = np.einsum("ij,ij->i", t1, sign[:, None] * t2) / np.maximum(n1 * n2, 1e-300)
    ang = np.degrees(np.arccos(np.clip(cosang, -1, 1)))
    keep = (ang < params.parallel_2d_deg) & (n1 > 0) & (n2 > 0)
    where = tuple(r[4] for r, k in zip(rows, keep, strict=True) if k)
    return Parallel(p1[keep], h1[keep], p2[keep], h2[keep], sign[keep], n1[keep], n2[keep], ang[keep], where)


def symmetry_cues(g: SketchGraph, ortho_pairs: list[tuple[int, int, int]]) -> Symmetry:
    """Local symmetry candidates at intersections known to be orthogonal.

    ``ortho_pairs``: (point, handle a, handle b) of the orthogonal pairs; each
    curve through the point that passes (two segments) is tried as the
    symmetry plane of the other.
    """
    seg = g.segments
    ends_at: dict[int, list[tuple[int, int]]] = {}
    for c in g.crossings:
        ends_at[c.point] = list(c.ends)
    rows = []
    for p, ha, hb in ortho_pairs:
        halves = ends_at.get(p, [])
        for mine, other in ((ha, hb), (hb, ha)):
            me = [h for h in halves if _handle(g, h) == mine]
            if not me:
                continue
            s_me = int(g.seg_stroke[me[0][0]])
            mine_all = [h for h in halves if int(g.seg_stroke[h[0]]) == s_me]
            outs = [h for h in mine_all if h[1] == 0]
            ins = [h for h in mine_all if h[1] == 3]
            if len(outs) != 1 or len(ins) != 1:
                continue
            f_out = int(seg[outs[0][0], 3])
            f_in = int(seg[ins[0][0], 0])
            rows.append((p, f_out, f_in, other, f"{_name(g, s_me)} symmetry plane at crossing {p}"))
    if not rows:
        z = np.zeros(0, np.intp)
        return Symmetry(z, z, z, z, np.zeros(0), np.zeros(0), ())
    p, fo, fi, h = (np.array([r[k] for r in rows], dtype=np.intp) for k in range(4))
    bar = g.points
    m = 0.5 * (bar[fo] + bar[fi]) - bar[p]
    nm = np.linalg.norm(m, axis=1)
    nh = np.linalg.norm(bar[h] - bar[p], axis=1)
    span = np.linalg.norm(bar[fo] - bar[fi], axis=1)
    keep = (nm > 1e-3 * np.maximum(span, 1e-300)) & (nh > 0)   # a straight curve defines no plane
    where = tuple(r[4] for r, k in zip(rows, keep, strict=True) if k)
    return Symmetry(p[keep], fo[keep], fi[keep], h[keep], nm[keep], nh[keep], where)


def linear_cues(g: SketchGraph, params: LiftParams) -> Linear:
    """One linearity candidate per stroke that is nearly but not exactly straight in 2D.

    Nearly: its linearity angle (:meth:`Linear.angles`) on the 2D control
    points is below ``params.outer_deg`` (a projection of a straight curve is
    straight, so a curve farther from straight in 2D has L = 0 anyway). Not
    exactly: at least one of its segments is not kept straight by the structure
    (handles within ``params.straight_tol`` of the chord), or one of its joints
    is not G1; a stroke the structure keeps straight needs no cue.
    """
    seg = g.segments
    bar = g.points
    P0, P3 = bar[seg[:, 0]], bar[seg[:, 3]]
    ch = P3 - P0
    L2 = np.maximum(np.einsum("ij,ij->i", ch, ch), 1e-300)
    t: dict[int, Array] = {}
    straight = np.ones(len(seg), dtype=bool)
    for k in (1, 2):
        s = np.einsum("ij,ij->i", bar[seg[:, k]] - P0, ch) / L2
        off = np.linalg.norm(bar[seg[:, k]] - (P0 + s[:, None] * ch), axis=1)
        straight &= off <= params.straight_tol
        t[k] = 1.0 - s            # B_k = t B_0 + (1 - t) B_3
    g1 = {(int(a), int(b)): bool(ok) for (a, b), ok in zip(g.joints, g.joint_g1, strict=True)}
    pts: list[NDArray[np.intp]] = []
    strokes: list[int] = []
    where: list[str] = []
    rows: list[list[int]] = []
    ts: list[float] = []
    cand: list[int] = []
    for si, chain in enumerate(g.chains):
        joints_ok = all(g1.get((int(a), int(b)), True) for a, b in zip(chain[:-1], chain[1:], strict=True))
        if straight[chain].all() and joints_ok:
            continue
        p = np.unique(seg[chain].reshape(-1))
        if _linearity_angle(np.c_[bar[p], np.zeros(len(p))]) >= params.outer_deg:
            continue
        c = len(pts)
        own = [(int(k_seg), k) for k_seg in chain if not straight[k_seg] for k in (1, 2)]
        if not own:   # straight segments at corners: a polyline, no curve to straighten
            continue
        for k_seg, k in own:
            rows.append([int(seg[k_seg, k]), int(seg[k_seg, 0]), int(seg[k_seg, 3])])
            ts.append(float(t[k][k_seg]))
            cand.append(c)
        pts.append(p.astype(np.intp))
        strokes.append(si)
        where.append(f"{_name(g, si)} straight")
    return Linear(tuple(pts), np.array(strokes, dtype=np.intp), np.array(rows, dtype=np.intp).reshape(-1, 3),
                  np.array(ts), np.array(cand, dtype=np.intp), tuple(where))


def planar_cues(g: SketchGraph, n_points: int) -> Planar:
    """One planarity candidate per stroke that is not straight in 2D."""
    pts, strokes, where = [], [], []
    for s, chain in enumerate(g.chains):
        p = np.unique(g.segments[chain].reshape(-1))
        Y = g.points[p] - g.points[p].mean(0)
        sv = np.linalg.svd(Y, compute_uv=False)
        if len(p) < 4 or sv[-1] <= 1e-6 * max(sv[0], 1e-300):
            continue
        pts.append(p.astype(np.intp))
        strokes.append(s)
        where.append(f"{_name(g, s)} planar")
    st = np.array(strokes, dtype=np.intp)
    return Planar(tuple(pts), st, n_points + st, tuple(where))

