"""The energy terms and constraints of True2Form (paper sec. 5.2) as :class:`~auszug.lifting.solver.Poly2` rows.

Unknowns: the 3D positions of the graph's control points, ``v[3 p + c]``,
then one plane normal per stroke, ``v[3 (n_points + s) + c]``. All sketch
coordinates are normalised (diagonal 1).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from auszug.lifting.params import LiftParams
from auszug.lifting.sketch import SketchGraph
from auszug.lifting.solver import Poly2

__all__ = ["omega", "add_lin3", "add_dot", "fidelity", "structure", "COLLINEAR_SIN"]

Array = NDArray[np.float64]
Index = NDArray[np.intp]

#: Three control points count as collinear (the triplet form of Eq. 4) when twice their
#: triangle's area is below this share of the squared longest side (about 1 deg).
COLLINEAR_SIN = 0.02


def omega(d: Array, params: LiftParams) -> Array:
    """omega_d of Eq. 2: exp(-d^2 / 2 sigma^2) + eps (d relative to the diagonal)."""
    return np.exp(-np.asarray(d) ** 2 / (2.0 * params.sigma**2)) + params.eps


def add_lin3(P: Poly2, slots: Index, w: Array, const: Array, weight: Array | float) -> slice:
    """Rows ``sum_k w[r, k] X[slots[r, k]] + const[r]`` for the three coordinates (3 m rows, xyz per r)."""
    slots = np.atleast_2d(slots)
    w = np.atleast_2d(w)
    m, K = slots.shape
    rows = np.broadcast_to(3 * np.arange(m)[:, None, None] + np.arange(3)[None, None, :], (m, K, 3))
    cols = 3 * slots[:, :, None] + np.arange(3)[None, None, :]
    vals = np.broadcast_to(w[:, :, None], (m, K, 3))
    wt = np.repeat(np.broadcast_to(np.asarray(weight, float), (m,)), 3)
    return P.add(np.asarray(const, float).reshape(-1), wt, lin=(rows, cols, vals))


def add_dot(P: Poly2, sa: Index, wa: Array, sb: Index, wb: Array, const: Array | float = 0.0,
            weight: Array | float = 1.0) -> slice:
    """Rows ``(sum_k wa X[sa]) . (sum_l wb X[sb]) + const`` (one row per r)."""
    sa, wa, sb, wb = (np.atleast_2d(x) for x in (sa, wa, sb, wb))
    m, K = sa.shape
    L = sb.shape[1]
    r = np.broadcast_to(np.arange(m)[:, None, None, None], (m, K, L, 3))
    i = np.broadcast_to(3 * sa[:, :, None, None] + np.arange(3), (m, K, L, 3))
    j = np.broadcast_to(3 * sb[:, None, :, None] + np.arange(3), (m, K, L, 3))
    val = np.broadcast_to((wa[:, :, None] * wb[:, None, :])[..., None], (m, K, L, 3))
    return P.add(np.broadcast_to(np.asarray(const, float), (m,)), weight, bil=(r, i, j, val))


def fidelity(g: SketchGraph, n: int, params: LiftParams, w_a: float) -> Poly2:
    """E_fidelity (Eq. 7): accuracy (Eq. 1-2), variation (Eq. 3-5), foreshortening (Eq. 6)."""
    P = Poly2(n)
    bar = g.points
    seg = g.segments
    S = len(seg)
    # accuracy, absolute: every control point of every segment, x and y
    p = seg.reshape(-1)
    rows = np.arange(2 * len(p))
    cols = (3 * p[:, None] + np.arange(2)).reshape(-1)
    P.add(-bar[p].reshape(-1), w_a, lin=(rows, cols, np.ones(len(rows))))
    # accuracy, slopes of the control polygon's edges
    a, b = seg[:, :3].reshape(-1), seg[:, 1:].reshape(-1)
    d = np.linalg.norm(bar[b] - bar[a], axis=1)
    wd = omega(d, params)
    m = len(a)
    rows = np.repeat(np.arange(2 * m), 2)
    cols = np.stack([3 * b[:, None] + np.arange(2), 3 * a[:, None] + np.arange(2)], axis=-1).reshape(-1)
    vals = np.tile([1.0, -1.0], 2 * m)
    P.add(-(bar[b] - bar[a]).reshape(-1), w_a * np.repeat(wd, 2), lin=(rows, cols, vals))
    # foreshortening: z differences along the control polygon
    rows = np.repeat(np.arange(m), 2)
    cols = np.stack([3 * b + 2, 3 * a + 2], axis=-1).reshape(-1)
    P.add(np.zeros(m), params.w_f * wd, lin=(rows, cols, np.tile([1.0, -1.0], m)))
    # minimal variation: quadruplets within segments and across consecutive segments
    quads = [seg]
    if len(g.joints):
        quads.append(np.stack([seg[g.joints[:, 0], 1], seg[g.joints[:, 0], 2],
                               seg[g.joints[:, 1], 1], seg[g.joints[:, 1], 2]], axis=1))
    Q = np.concatenate(quads)
    _variation(P, bar, Q, params)
    del S
    return P


def _variation(P: Poly2, bar: Array, Q: Index, params: LiftParams) -> None:
    """Eq. 3-5: minimal variation rows.

    The fourth point as the affine combination of the three others (the
    largest triangle), or, for collinear quadruplets, the inner points of
    collinear triplets by linear interpolation.
    """
    X = bar[Q]                                        # (q, 4, 2)
    diff = X[:, :, None] - X[:, None, :]
    dmax = np.linalg.norm(diff, axis=-1).max(axis=(1, 2))
    tri = np.array([[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]])   # base triangle leaving out point k
    e1, e2 = X[:, tri[:, 1]] - X[:, tri[:, 0]], X[:, tri[:, 2]] - X[:, tri[:, 0]]
    area2 = np.abs(e1[..., 0] * e2[..., 1] - e1[..., 1] * e2[..., 0])  # (q, 4)
    best = np.argmax(area2, axis=1)
    ok = (area2[np.arange(len(Q)), best] > COLLINEAR_SIN * dmax**2) & (dmax > 0)
    wq = params.w_v * omega(dmax, params)
    if ok.any():
        qi = np.nonzero(ok)[0]
        k = best[qi]
        base = tri[k]                                  # (q', 3)
        B = X[qi[:, None], base]                       # (q', 3, 2)
        T = X[qi, k]                                   # (q', 2)
        # barycentric weights of T in triangle B
        M = np.stack([B[:, 1] - B[:, 0], B[:, 2] - B[:, 0]], axis=-1)   # (q', 2, 2)
        lam = np.linalg.solve(M, (T - B[:, 0])[..., None])[..., 0]
        w3 = np.stack([1 - lam.sum(1), lam[:, 0], lam[:, 1]], axis=1)
        slots = np.concatenate([Q[qi[:, None], base], Q[qi, k][:, None]], axis=1)
        w = np.concatenate([w3, -np.ones((len(qi), 1))], axis=1)
        add_lin3(P, slots, w, np.zeros(3 * len(qi)), wq[qi])
    col = np.nonzero(~ok & (dmax > 0))[0]
    if len(col):
        trip = np.concatenate([Q[col][:, [0, 1, 2]], Q[col][:, [1, 2, 3]]])
        wt = np.concatenate([wq[col], wq[col]])
        T0, T1, T2 = bar[trip[:, 0]], bar[trip[:, 1]], bar[trip[:, 2]]
        dd = np.einsum("ij,ij->i", T0 - T2, T0 - T2)
        good = dd > 1e-24
        t0 = np.where(good, np.einsum("ij,ij->i", T1 - T2, T0 - T2) / np.where(good, dd, 1.0), 0.0)
        w = np.stack([t0, -np.ones_like(t0), 1 - t0], axis=1)
        add_lin3(P, trip[good], w[good], np.zeros(3 * int(good.sum())), wt[good])


def structure(g: SketchGraph, n: int, params: LiftParams, pin: int) -> Poly2:
    """The hard linear constraints: z of ``pin`` is 0, G1 joints, straight segments.

    G1 (paper: B2, B3 = B0', B1' collinear) is enforced as the linear
    ``B1' - B0' = lambda (B0' - B2)`` with lambda the 2D ratio of the handle
    lengths: collinear with the sketch's own proportions (docs/lifting.md).
    A straight segment keeps its handles at their 2D chord fractions.
    """
    C = Poly2(n)
    C.add([0.0], lin=([0], [3 * pin + 2], [1.0]))
    bar = g.points
    seg = g.segments
    J = g.joints[g.joint_g1]
    if len(J):
        a2, j, b1 = seg[J[:, 0], 2], seg[J[:, 1], 0], seg[J[:, 1], 1]
        lam = np.linalg.norm(bar[b1] - bar[j], axis=1) / np.maximum(np.linalg.norm(bar[j] - bar[a2], axis=1), 1e-300)
        slots = np.stack([b1, j, a2], axis=1)
        w = np.stack([np.ones_like(lam), -1 - lam, lam], axis=1)
        add_lin3(C, slots, w, np.zeros(3 * len(J)), 1.0)
    P0, P3 = bar[seg[:, 0]], bar[seg[:, 3]]
    ch = P3 - P0
    L2 = np.einsum("ij,ij->i", ch, ch)
    for k in (1, 2):
        Pk = bar[seg[:, k]]
        s = np.einsum("ij,ij->i", Pk - P0, ch) / np.maximum(L2, 1e-300)
        off = np.linalg.norm(Pk - (P0 + s[:, None] * ch), axis=1)
        if k == 1:
            straight = off <= params.straight_tol
        else:
            straight &= off <= params.straight_tol
    straight &= L2 > 0
    if straight.any():
        si = np.nonzero(straight)[0]
        for k in (1, 2):
            Pk = bar[seg[si, k]]
            s = np.einsum("ij,ij->i", Pk - P0[si], ch[si]) / L2[si]
            slots = np.stack([seg[si, k], seg[si, 0], seg[si, 3]], axis=1)
            w = np.stack([np.ones_like(s), -(1 - s), -s], axis=1)
            add_lin3(C, slots, w, np.zeros(3 * len(si)), 1.0)
    return C
