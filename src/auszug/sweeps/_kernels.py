"""Compiled kernels of sweep detection (numba, cached on disk).

Private: the public functions in :mod:`auszug.sweeps.cut`, :mod:`auszug.sweeps.movability` and
:mod:`auszug.sweeps.matching` validate their input and call these. Every kernel is one pass over
all planes (or curves, or curve pairs); no Python loop runs per plane, curve or pair.

The cutter runs in parallel over planes (``prange``). The curve and pair kernels are serial:
numba's parallel lowering doubled their first-call compilation (45 s against 21 s for all
kernels on the 2-core development machine, a cost every fresh checkout pays once) for at most a
2x gain on two shared cores, and they are the cheaper part of the run.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

# --------------------------------------------------------------------------------------- the mesh


@njit(cache=True)
def vertex_normal_sums(v, faces):  # pragma: no cover - compiled
    """``(n, 3)``: the sum of the (unnormalised) cross products of the faces around each vertex.

    Bit for bit ``fn = np.cross(v[f1] - v[f0], v[f2] - v[f0])`` and then ``for k in 0..2:
    np.add.at(out, faces[:, k], fn)``: the same products and differences (no fused multiply-add:
    numba compiles without fastmath), the same additions in the same order (corner k of every
    face in face order, then corner k + 1).
    """
    m = len(faces)
    fn = np.empty((m, 3))
    for i in range(m):
        a, b, c = faces[i, 0], faces[i, 1], faces[i, 2]
        ux, uy, uz = v[b, 0] - v[a, 0], v[b, 1] - v[a, 1], v[b, 2] - v[a, 2]
        wx, wy, wz = v[c, 0] - v[a, 0], v[c, 1] - v[a, 1], v[c, 2] - v[a, 2]
        fn[i, 0] = uy * wz - uz * wy
        fn[i, 1] = uz * wx - ux * wz
        fn[i, 2] = ux * wy - uy * wx
    out = np.zeros((len(v), 3))
    for k in range(3):
        for i in range(m):
            j = faces[i, k]
            out[j, 0] += fn[i, 0]
            out[j, 1] += fn[i, 1]
            out[j, 2] += fn[i, 2]
    return out


# --------------------------------------------------------------------------------------- cutting


@njit(cache=True, parallel=True)
def cut_count(v, edges, pn, pd):  # pragma: no cover - compiled
    """Crossed edges per plane (an upper bound of its cut points)."""
    n_planes = len(pd)
    out = np.zeros(n_planes, np.int64)
    for p in prange(n_planes):
        nx, ny, nz, d = pn[p, 0], pn[p, 1], pn[p, 2], pd[p]
        side = np.empty(len(v), np.bool_)
        for i in range(len(v)):
            side[i] = v[i, 0] * nx + v[i, 1] * ny + v[i, 2] * nz - d >= 0.0
        c = 0
        for e in range(len(edges)):
            if side[edges[e, 0]] != side[edges[e, 1]]:
                c += 1
        out[p] = c
    return out


@njit(cache=True)
def _other_edge(face_edges, f, e, crossed):  # pragma: no cover - compiled
    for k in range(3):
        g = face_edges[f, k]
        if g != e and crossed[g]:
            return g
    return -1


@njit(cache=True)
def _emit(v, vn, edges, dist, e, pts, nrm, eid, pos, begin):  # pragma: no cover - compiled
    a, b = edges[e, 0], edges[e, 1]
    return _put(v, vn, a, b, dist[a] / (dist[a] - dist[b]), e, pts, nrm, eid, pos, begin)


@njit(cache=True)
def _put(v, vn, a, b, t, e, pts, nrm, eid, pos, begin):  # pragma: no cover - compiled
    """Append the point at ``t`` along edge ``e = (a, b)`` and its normal; a repeat of the last is skipped."""
    x0 = v[a, 0] + t * (v[b, 0] - v[a, 0])
    x1 = v[a, 1] + t * (v[b, 1] - v[a, 1])
    x2 = v[a, 2] + t * (v[b, 2] - v[a, 2])
    if pos > begin:
        dx, dy, dz = x0 - pts[pos - 1, 0], x1 - pts[pos - 1, 1], x2 - pts[pos - 1, 2]
        if dx * dx + dy * dy + dz * dz < 1e-28:  # a vertex on the plane: same point again
            return pos
    pts[pos, 0], pts[pos, 1], pts[pos, 2] = x0, x1, x2
    m0 = vn[a, 0] + t * (vn[b, 0] - vn[a, 0])
    m1 = vn[a, 1] + t * (vn[b, 1] - vn[a, 1])
    m2 = vn[a, 2] + t * (vn[b, 2] - vn[a, 2])
    s = np.sqrt(m0 * m0 + m1 * m1 + m2 * m2)
    if s > 0:
        m0, m1, m2 = m0 / s, m1 / s, m2 / s
    nrm[pos, 0], nrm[pos, 1], nrm[pos, 2] = m0, m1, m2
    eid[pos] = e
    return pos + 1


@njit(cache=True, parallel=True)
def cut_fill(v, vn, edges, edge_faces, face_edges, pn, pd, start):  # pragma: no cover - compiled
    """Cut every plane and link its crossing points into polylines, written at ``start[p]``.

    Returns points, normals, edge ids (-1 in unused slots), a curve-start flag and a closed flag
    per written point (set at a curve's first point), and the number written per plane.
    """
    n_planes = len(pd)
    total = start[n_planes]
    pts = np.zeros((total, 3))
    nrm = np.zeros((total, 3))
    eid = np.full(total, -1, np.int64)
    first = np.zeros(total, np.bool_)
    closed = np.zeros(total, np.bool_)
    written = np.zeros(n_planes, np.int64)
    for p in prange(n_planes):
        nx, ny, nz, d = pn[p, 0], pn[p, 1], pn[p, 2], pd[p]
        dist = np.empty(len(v))
        for i in range(len(v)):
            dist[i] = v[i, 0] * nx + v[i, 1] * ny + v[i, 2] * nz - d
        crossed = np.zeros(len(edges), np.bool_)
        # the crossed edges in increasing order (at most start[p + 1] - start[p] of them): the
        # two phases below visit only these, not every edge again
        hit = np.empty(start[p + 1] - start[p], np.int64)
        n_hit = 0
        for e in range(len(edges)):
            if (dist[edges[e, 0]] >= 0.0) != (dist[edges[e, 1]] >= 0.0):
                crossed[e] = True
                hit[n_hit] = e
                n_hit += 1
        seen = np.zeros(len(edges), np.bool_)
        pos = start[p]
        # open chains start at crossed boundary edges, then what is left are closed loops
        for phase in range(2):
            for h in range(n_hit):
                e0 = hit[h]
                if seen[e0]:
                    continue
                if phase == 0 and edge_faces[e0, 1] >= 0:
                    continue
                begin = pos
                e, prev = e0, -1
                is_closed = False
                while True:
                    seen[e] = True
                    pos = _emit(v, vn, edges, dist, e, pts, nrm, eid, pos, begin)
                    f = edge_faces[e, 0]
                    if f == prev or f < 0:
                        f = edge_faces[e, 1]
                    if f < 0 or f == prev:
                        break
                    g = _other_edge(face_edges, f, e, crossed)
                    if g < 0:
                        break
                    if seen[g]:
                        is_closed = g == e0
                        break
                    prev, e = f, g
                if pos - begin >= 2:
                    first[begin] = True
                    closed[begin] = is_closed
                else:
                    pos = begin  # a single point: no curve
                    eid[begin] = -1
        written[p] = pos - start[p]
        for k in range(pos, start[p + 1]):
            eid[k] = -1
    return pts, nrm, eid, first, closed, written


# ------------------------------------------------------------------------------------ movability


@njit(cache=True)
def _velocity_fit(x, nrm, w):  # pragma: no cover - compiled
    a = np.zeros((6, 6))
    row = np.empty(6)
    for i in range(len(x)):
        n0, n1, n2 = nrm[i, 0], nrm[i, 1], nrm[i, 2]
        row[0] = x[i, 1] * n2 - x[i, 2] * n1
        row[1] = x[i, 2] * n0 - x[i, 0] * n2
        row[2] = x[i, 0] * n1 - x[i, 1] * n0
        row[3], row[4], row[5] = n0, n1, n2
        for r in range(6):
            wr = w[i] * row[r]
            for c in range(r, 6):
                a[r, c] += wr * row[c]
    for r in range(6):
        for c in range(r):
            a[r, c] = a[c, r]
    vals, vecs = np.linalg.eigh(a)
    return vals, vecs[:, 0].copy(), a


@njit(cache=True)
def _movability_values(x, nrm, c, f, v0):  # pragma: no cover - compiled
    v02 = v0 * v0
    for i in range(len(x)):
        vx = c[3] + c[1] * x[i, 2] - c[2] * x[i, 1]
        vy = c[4] + c[2] * x[i, 0] - c[0] * x[i, 2]
        vz = c[5] + c[0] * x[i, 1] - c[1] * x[i, 0]
        s = vx * vx + vy * vy + vz * vz + v02
        if s < 1e-24:
            f[i] = 0.0  # the point does not move (it is on the rotation axis)
        else:
            dot = nrm[i, 0] * vx + nrm[i, 1] * vy + nrm[i, 2] * vz
            f[i] = dot * dot / s


@njit(cache=True)
def weight_iteration(x, nrm, curve_start, beta, gamma, iterations, v0):  # pragma: no cover - compiled
    """Alg. 1 steps 1-3 on every curve: velocity states (C, 6), eigenvalues (C, 6), weights, f, A (C, 6, 6)."""
    n_curves = len(curve_start) - 1
    mats = np.zeros((n_curves, 6, 6))
    cs = np.zeros((n_curves, 6))
    ev = np.zeros((n_curves, 6))
    w = np.ones(len(x))
    f = np.zeros(len(x))
    for k in range(n_curves):
        a, b = curve_start[k], curve_start[k + 1]
        xs, ns = x[a:b], nrm[a:b]
        ws, fs = w[a:b], f[a:b]
        vals, c = np.zeros(6), np.zeros(6)
        for _ in range(iterations):
            vals, c, am = _velocity_fit(xs, ns, ws)
            mats[k] = am
            _movability_values(xs, ns, c, fs, v0)
            for i in range(b - a):
                ws[i] = 1.0 / (1.0 + beta * fs[i] ** gamma)
        # the final state: the eigenvector of the last fit, weights and f from it
        cs[k] = c
        ev[k] = vals
    return cs, ev, w, f, mats


@njit(cache=True)
def _dist(x, i, j):  # pragma: no cover - compiled
    return np.sqrt((x[j, 0] - x[i, 0]) ** 2 + (x[j, 1] - x[i, 1]) ** 2 + (x[j, 2] - x[i, 2]) ** 2)


@njit(cache=True)
def _bridge(x, good, closed, gap):  # pragma: no cover - compiled
    """Absorb stretches of bad vertices spanning at most ``gap`` of arc length between good ones."""
    n = len(good)
    out = good.copy()
    any_good = False
    for i in range(n):
        if good[i]:
            any_good = True
            break
    if not any_good or gap <= 0.0:
        return out
    i = 0
    while i < n:
        if good[i]:
            i += 1
            continue
        j = i
        while j < n and not good[j]:
            j += 1
        # bad stretch [i, j): bridge if it has good neighbours on both sides and is short
        if closed or (i > 0 and j < n):
            a = (i - 1) % n
            span = 0.0
            k = a
            while k != j % n:
                k2 = (k + 1) % n
                span += _dist(x, k, k2)
                k = k2
            if span <= gap:
                for m in range(i, j):
                    out[m] = True
        i = j
    if closed and not good[0] and not good[n - 1]:
        # the stretch wrapping over the start was seen as two pieces: redo it as one
        i0 = n - 1
        while i0 > 0 and not good[i0 - 1]:
            i0 -= 1
        j0 = 0
        while j0 < n and not good[j0]:
            j0 += 1
        span = 0.0
        k = (i0 - 1) % n
        while k != j0 % n:
            k2 = (k + 1) % n
            span += _dist(x, k, k2)
            k = k2
        ok = span <= gap
        for m in range(i0, n):
            out[m] = ok
        for m in range(0, j0):
            out[m] = ok
    return out


@njit(cache=True)
def _sliding(x, w, c, j, closed):  # pragma: no cover - compiled
    """Weighted squared velocity along the curve's tangent at vertex ``j``, and weighted squared speed."""
    n = len(x)
    a = (j - 1) % n if closed else max(j - 1, 0)
    b = (j + 1) % n if closed else min(j + 1, n - 1)
    tx, ty, tz = x[b, 0] - x[a, 0], x[b, 1] - x[a, 1], x[b, 2] - x[a, 2]
    tl = np.sqrt(tx * tx + ty * ty + tz * tz)
    vx = c[3] + c[1] * x[j, 2] - c[2] * x[j, 1]
    vy = c[4] + c[2] * x[j, 0] - c[0] * x[j, 2]
    vz = c[5] + c[0] * x[j, 1] - c[1] * x[j, 0]
    vv = vx * vx + vy * vy + vz * vz
    if tl == 0.0 or vv < 1e-24:
        return 0.0, 0.0
    d = (tx * vx + ty * vy + tz * vz) / tl
    return w[j] * d * d, w[j] * vv


@njit(cache=True, inline="always")
def _add_row(m, wt, x, j, dx, dy, dz):  # pragma: no cover - compiled
    """``m += wt r r^T`` with ``r = (x_j x d, d)``: ``r . C`` is the speed of point ``j`` along ``d``."""
    r0 = x[j, 1] * dz - x[j, 2] * dy
    r1 = x[j, 2] * dx - x[j, 0] * dz
    r2 = x[j, 0] * dy - x[j, 1] * dx
    row = (r0, r1, r2, dx, dy, dz)
    for a in range(6):
        ra = wt * row[a]
        for b in range(6):
            m[a, b] += ra * row[b]


@njit(cache=True)
def _least_sliding(x, nrm, w, idx, closed, glide_f):  # pragma: no cover - compiled
    """Least ``sliding share + mean f / glide_f`` over all velocity states, on the points ``idx``.

    The share of the weighted squared speed along the curve's tangent plus the weighted mean
    squared normal speed (over the squared speed) in units of ``glide_f``: the smallest
    eigenvalue of ``T + N / glide_f`` against ``S`` (``T``, ``N``, ``S`` the weighted quadratic
    forms of tangential, normal and whole squared speed), by a Cholesky factor of ``S``.
    """
    n = len(x)
    t_m = np.zeros((6, 6))
    n_m = np.zeros((6, 6))
    s_m = np.zeros((6, 6))
    for j in idx:
        a = (j - 1) % n if closed else max(j - 1, 0)
        b = (j + 1) % n if closed else min(j + 1, n - 1)
        tx, ty, tz = x[b, 0] - x[a, 0], x[b, 1] - x[a, 1], x[b, 2] - x[a, 2]
        tl = np.sqrt(tx * tx + ty * ty + tz * tz)
        if tl == 0.0:
            continue
        _add_row(t_m, w[j], x, j, tx / tl, ty / tl, tz / tl)
        _add_row(n_m, w[j], x, j, nrm[j, 0], nrm[j, 1], nrm[j, 2])
        _add_row(s_m, w[j], x, j, 1.0, 0.0, 0.0)
        _add_row(s_m, w[j], x, j, 0.0, 1.0, 0.0)
        _add_row(s_m, w[j], x, j, 0.0, 0.0, 1.0)
    tr = 0.0
    for a in range(6):
        tr += s_m[a, a]
    if tr <= 0.0:
        return np.inf
    for a in range(6):
        s_m[a, a] += 1e-12 * tr
    low = np.linalg.cholesky(s_m)
    inv = np.linalg.inv(low)
    m = inv @ (t_m + n_m / glide_f) @ inv.T
    return np.linalg.eigvalsh(0.5 * (m + m.T))[0]


@njit(cache=True)
def _runs_of_curve(x, nrm, w, f, c, closed, thresh, l_min, gap, max_slide, min_spread, glide_f, loop_slide,
                   out_i0, out_i1, out_len, out_e, out_s, k0, write):  # pragma: no cover - compiled
    n = len(w)
    if n == 0:
        return 0
    good = _bridge(x, w > thresh, closed, gap)
    count = 0
    all_good = True
    for i in range(n):
        if not good[i]:
            all_good = False
            break
    s0 = 0
    if closed and not all_good:
        for i in range(n):
            if not good[i]:
                s0 = (i + 1) % n
                break
    i = 0
    while i < n:
        idx = (s0 + i) % n if closed else i
        if not good[idx]:
            i += 1
            continue
        j = i
        length = 0.0
        e = 0.0
        sl_num = 0.0
        sl_den = 0.0
        cov = np.zeros((3, 3))
        while j < n:
            jj = (s0 + j) % n if closed else j
            if not good[jj]:
                break
            e += (1.0 - w[jj]) ** 2 * f[jj]
            sn, sd = _sliding(x, w, c, jj, closed)
            sl_num += sn
            sl_den += sd
            for r in range(3):
                for q in range(3):
                    cov[r, q] += nrm[jj, r] * nrm[jj, q]
            if j > i:
                pj = (s0 + j - 1) % n if closed else j - 1
                length += _dist(x, pj, jj)
            j += 1
        if closed and all_good:
            length += _dist(x, n - 1, 0)
        slide = sl_num / sl_den if sl_den > 0 else 0.0
        spread = np.linalg.eigvalsh(cov / (j - i))[1] if length >= l_min else 0.0
        if slide > max_slide and loop_slide > 0.0 and closed and all_good and length >= l_min \
                and spread >= min_spread:
            # a whole closed cut whose Eq. 4 velocity slides: does another velocity state glide it
            # without sliding? (a loop slides along itself only by turning in its plane)
            idx = np.empty(j - i, np.int64)
            for q in range(i, j):
                idx[q - i] = (s0 + q) % n
            q = _least_sliding(x, nrm, w, idx, closed, glide_f)
            if q <= loop_slide:
                slide = q
        if length >= l_min and slide <= max_slide and spread >= min_spread:
            if write:
                out_i0[k0 + count] = (s0 + i) % n if closed else i
                out_i1[k0 + count] = (s0 + j - 1) % n if closed else j - 1
                out_len[k0 + count] = length
                out_e[k0 + count] = e / (j - i)
                out_s[k0 + count] = slide
            count += 1
        i = j
    return count


@njit(cache=True)
def movable_runs(x, nrm, w, f, cs, curve_start, closed, thresh, l_min, gap, max_slide,
                 min_spread, glide_f, loop_slide):  # pragma: no cover - compiled
    """Alg. 1 step 4: runs of weight above ``thresh`` at least ``l_min`` long, with gliding energy.

    Gaps of at most ``gap`` arc length are bridged; runs whose velocity is more than
    ``max_slide`` (share of squared speed) along the curve itself are dropped, unless (``loop_slide``
    > 0) the run is a whole closed curve and some velocity state's sliding share plus its mean
    normal speed in units of ``glide_f`` (:func:`_least_sliding`) is at most ``loop_slide``; and so
    are runs whose normals hardly turn
    (second eigenvalue of their mean ``n n^T`` below ``min_spread``).
    """
    n_curves = len(curve_start) - 1
    dummy_i = np.zeros(1, np.int64)
    dummy_f = np.zeros(1)
    counts = np.zeros(n_curves, np.int64)
    for k in range(n_curves):
        a, b = curve_start[k], curve_start[k + 1]
        counts[k] = _runs_of_curve(x[a:b], nrm[a:b], w[a:b], f[a:b], cs[k], closed[k], thresh, l_min, gap,
                                   max_slide, min_spread, glide_f, loop_slide,
                                   dummy_i, dummy_i, dummy_f, dummy_f, dummy_f, 0, False)
    offs = np.zeros(n_curves + 1, np.int64)
    offs[1:] = np.cumsum(counts)
    total = offs[n_curves]
    i0 = np.zeros(total, np.int64)
    i1 = np.zeros(total, np.int64)
    length = np.zeros(total)
    energy = np.zeros(total)
    slide = np.zeros(total)
    curve = np.zeros(total, np.int64)
    for k in range(n_curves):
        a, b = curve_start[k], curve_start[k + 1]
        _runs_of_curve(x[a:b], nrm[a:b], w[a:b], f[a:b], cs[k], closed[k], thresh, l_min, gap, max_slide,
                       min_spread, glide_f, loop_slide, i0, i1, length, energy, slide, offs[k], True)
        for r in range(offs[k], offs[k + 1]):
            curve[r] = k
    return curve, i0, i1, length, energy, slide


# -------------------------------------------------------------------------------------- matching


@njit(cache=True)
def _longest_nonpositive(d, n, q, lmin, rmax):  # pragma: no cover - compiled
    """Longest window ``[i, j)`` of ``d[:n]`` with ``sum <= 0``: (start, length), O(n).

    With prefix sums ``P``, a window ``[i, j)`` qualifies iff ``P[j] <= P[i]``; this is the widest
    ramp of ``Q = -P`` (``Q[i] <= Q[j]``), found with prefix minima and suffix maxima of ``Q``.
    """
    q[0] = 0.0
    for k in range(n):
        q[k + 1] = q[k] - d[k]
    lmin[0] = q[0]
    for k in range(1, n + 1):
        lmin[k] = min(lmin[k - 1], q[k])
    rmax[n] = q[n]
    for k in range(n - 1, -1, -1):
        rmax[k] = max(rmax[k + 1], q[k])
    i = 0
    j = 0
    best, start = 0, 0
    while i <= n and j <= n:
        if lmin[i] <= rmax[j] + 1e-12 * (1.0 + abs(rmax[j])):
            if j - i > best:
                best, start = j - i, i
            j += 1
        else:
            i += 1
    return start, best


@njit(cache=True)
def match_pairs(kappa, offs, pairs, eps, kfloor, min_len):  # pragma: no cover - compiled
    """Sec. 2.1 on every pair: the longest diagonal window below the threshold, over 4 variants.

    Variant bits: 1 = the second curve's curvature negated (flip), 2 = its direction reversed.
    Returns per pair: length (samples; 0 if none reaches ``min_len``), variant, start in the first
    curve, start in the second curve's variant, mean |kappa - kappa'| and the reference energy.
    """
    n_pairs = len(pairs)
    out_len = np.zeros(n_pairs, np.int64)
    out_var = np.zeros(n_pairs, np.int64)
    out_sa = np.zeros(n_pairs, np.int64)
    out_sb = np.zeros(n_pairs, np.int64)
    out_e = np.zeros(n_pairs)
    out_ref = np.zeros(n_pairs)
    m_max = 0
    for r in range(len(offs) - 1):
        m_max = max(m_max, offs[r + 1] - offs[r])
    for p in range(n_pairs):
        a, b = pairs[p, 0], pairs[p, 1]
        ka = kappa[offs[a]:offs[a + 1]]
        kb = kappa[offs[b]:offs[b + 1]]
        ma, mb = len(ka), len(kb)
        d1 = np.empty(m_max)
        d2 = np.empty(m_max)
        q = np.empty(m_max + 1)
        lo = np.empty(m_max + 1)
        hi = np.empty(m_max + 1)
        best_len, best_e = 0, np.inf
        for var in range(4):
            sgn = -1.0 if var & 1 else 1.0
            rev = (var & 2) != 0
            for o in range(-(ma - min_len), mb - min_len + 1):
                i0 = max(0, -o)
                i1 = min(ma, mb - o)
                n = i1 - i0
                if n < min_len or n < best_len:
                    continue
                for t in range(n):
                    i = i0 + t
                    j = i + o
                    kbj = sgn * (kb[mb - 1 - j] if rev else kb[j])
                    diff = abs(ka[i] - kbj)
                    d1[t] = diff - eps * 0.5 * (abs(ka[i]) + abs(kbj))
                    d2[t] = diff - eps * kfloor
                for cond in range(2):
                    s, length = _longest_nonpositive(d1 if cond == 0 else d2, n, q, lo, hi)
                    if length < min_len or length < best_len:
                        continue
                    e = 0.0
                    ref = 0.0
                    for t in range(s, s + length):
                        i = i0 + t
                        j = i + o
                        kbj = sgn * (kb[mb - 1 - j] if rev else kb[j])
                        e += abs(ka[i] - kbj)
                        ref += 0.5 * (abs(ka[i]) + abs(kbj))
                    e /= length
                    ref /= length
                    if length > best_len or e < best_e:
                        best_len, best_e = length, e
                        out_len[p], out_var[p] = length, var
                        out_sa[p], out_sb[p] = i0 + s, i0 + s + o
                        out_e[p], out_ref[p] = e, ref
    return out_len, out_var, out_sa, out_sb, out_e, out_ref


# ------------------------------------------------------------------------------ closest points on polylines


@njit(cache=True, inline="always")
def _point_segment(px, py, pz, ax, ay, az, cx, cy, cz):  # pragma: no cover - compiled
    """Squared distance from (px, py, pz) to the segment from a to c and the closest point."""
    bx, by, bz = cx - ax, cy - ay, cz - az
    w = bx * bx + by * by + bz * bz
    f = 0.0
    if w > 0:
        f = ((px - ax) * bx + (py - ay) * by + (pz - az) * bz) / w
        f = min(max(f, 0.0), 1.0)
    qx, qy, qz = ax + f * bx, ay + f * by, az + f * bz
    return (px - qx) ** 2 + (py - qy) ** 2 + (pz - qz) ** 2, qx, qy, qz


@njit(cache=True, inline="always")
def _segment_closest(px, py, pz, polyline, j):  # pragma: no cover - compiled
    """Squared distance from (px, py, pz) to segment j of ``polyline (n, 3)`` and the closest point."""
    return _point_segment(px, py, pz, polyline[j, 0], polyline[j, 1], polyline[j, 2],
                          polyline[j + 1, 0], polyline[j + 1, 1], polyline[j + 1, 2])


@njit(cache=True)
def polyline_closest(points, polyline):  # pragma: no cover - compiled
    """Distances (m,) and closest points (m, 3) of points (m, 3) on the segments of a polyline (n, 3)."""
    m = len(points)
    dist = np.full(m, np.inf)
    cp = np.zeros((m, 3))
    for i in range(m):
        px, py, pz = points[i, 0], points[i, 1], points[i, 2]
        best = np.inf
        for j in range(len(polyline) - 1):
            d, qx, qy, qz = _segment_closest(px, py, pz, polyline, j)
            if d < best:
                best = d
                cp[i, 0], cp[i, 1], cp[i, 2] = qx, qy, qz
        if len(polyline) == 1:
            best = (px - polyline[0, 0]) ** 2 + (py - polyline[0, 1]) ** 2 + (pz - polyline[0, 2]) ** 2
            cp[i, 0], cp[i, 1], cp[i, 2] = polyline[0, 0], polyline[0, 1], polyline[0, 2]
        dist[i] = np.sqrt(best)
    return dist, cp


@njit(cache=True, inline="always")
def _prune_limit(px, py, pz, best):  # pragma: no cover - compiled
    """Squared distance beyond which a box holds no segment as near as ``best`` (squared), with a margin.

    The margin (1e-9 times the coordinates' and the distance's size) exceeds the round-off of a
    segment's computed distance and of a box's, so a box farther than this holds no segment whose
    computed squared distance is at most ``best``.
    """
    r = np.sqrt(best)
    r += 1e-9 * (1.0 + abs(px) + abs(py) + abs(pz) + r)
    return r * r


@njit(cache=True)
def _chunk_boxes(q, n_seg, chunk):  # pragma: no cover - compiled
    """Bounding boxes ``(c, 6)`` (min, max) of a polyline's chunks of ``chunk`` segments (points ``s0 .. s1``)."""
    n_chunk = (n_seg + chunk - 1) // chunk
    box = np.empty((n_chunk, 6))
    for h in range(n_chunk):
        s0, s1 = h * chunk, min((h + 1) * chunk, n_seg)
        for ax in range(3):
            lo, hi = q[s0, ax], q[s0, ax]
            for r in range(s0 + 1, s1 + 1):
                lo = min(lo, q[r, ax])
                hi = max(hi, q[r, ax])
            box[h, ax], box[h, 3 + ax] = lo, hi
    return box


@njit(cache=True)
def _chunks_closest(px, py, pz, q, n_seg, chunk, raw, allowed, lb):  # pragma: no cover - compiled
    """The nearest segment of a polyline ``q`` to a point among the chunks with ``allowed[h]``.

    Returns the squared distance, the segment (-1 if none) and the closest point: the least
    ``(squared distance, segment)`` pair, i.e. what a search of those chunks' segments in order
    gives when it keeps the first of equal distances (:func:`polyline_closest`). The chunk whose
    box ``raw[h]`` is nearest is searched first; then every other allowed chunk whose box is not
    farther than the best distance so far (with :func:`_prune_limit`'s margin): a chunk passed
    over holds no segment as near. ``lb (c,)`` is scratch.
    """
    n_chunk = len(raw)
    h0 = -1
    m = np.inf
    for h in range(n_chunk):
        if not allowed[h]:
            continue
        lb[h] = _box_sq(px, py, pz, raw, h)
        if lb[h] < m or h0 < 0:
            m = lb[h]
            h0 = h
    best = np.inf
    bg = -1
    cx, cy, cz = 0.0, 0.0, 0.0
    if h0 < 0:
        return best, bg, cx, cy, cz
    for g in range(h0 * chunk, min((h0 + 1) * chunk, n_seg)):
        d2, qx, qy, qz = _segment_closest(px, py, pz, q, g)
        if d2 < best or (d2 == best and g < bg):
            best, bg, cx, cy, cz = d2, g, qx, qy, qz
    limit = _prune_limit(px, py, pz, best)
    for h in range(n_chunk):
        if h == h0 or not allowed[h] or lb[h] > limit:
            continue
        for g in range(h * chunk, min((h + 1) * chunk, n_seg)):
            d2, qx, qy, qz = _segment_closest(px, py, pz, q, g)
            if d2 < best or (d2 == best and g < bg):
                best, bg, cx, cy, cz = d2, g, qx, qy, qz
                limit = _prune_limit(px, py, pz, best)
    return best, bg, cx, cy, cz


@njit(cache=True)
def polyline_closest_chunked(points, polyline):  # pragma: no cover - compiled
    """:func:`polyline_closest` bit for bit; the segments in chunks of 8, nearest first (:func:`_chunks_closest`).

    Points far from most of a long polyline visit few of its segments; the first of equal
    distances is kept, as the scan keeps it.
    """
    m = len(points)
    dist = np.full(m, np.inf)
    cp = np.zeros((m, 3))
    n_seg = len(polyline) - 1
    if n_seg < 1:
        return polyline_closest(points, polyline)
    chunk = 8
    raw = _chunk_boxes(polyline, n_seg, chunk)
    allowed = np.ones(len(raw), np.bool_)
    lb = np.empty(len(raw))
    for i in range(m):
        px, py, pz = points[i, 0], points[i, 1], points[i, 2]
        best, g, qx, qy, qz = _chunks_closest(px, py, pz, polyline, n_seg, chunk, raw, allowed, lb)
        if g >= 0:
            cp[i, 0], cp[i, 1], cp[i, 2] = qx, qy, qz
        dist[i] = np.sqrt(best)
    return dist, cp


@njit(cache=True)
def key_distance_medians(points, polyline, piece_start, piece_key, n_keys):  # pragma: no cover - compiled
    """Per key the median distance of its pieces' points to a polyline: ``(n_keys,)`` medians and point counts.

    Piece ``j`` is ``points[piece_start[j]:piece_start[j + 1]]``, of key ``piece_key[j]`` in
    ``0 .. n_keys - 1``. A point's distance is that of :func:`polyline_closest` bit for bit (the
    square root of the least squared distance of the same formula over all segments): the search
    starts at the segment nearest the piece's previous point, then visits only the chunks of 8
    segments, and in them the segments, whose box is not farther than the best so far (with
    :func:`_prune_limit`'s margin: a box passed over holds no segment as near). A key's median is
    ``(s[(c - 1) // 2] + s[c // 2]) / 2`` of its ``c`` sorted distances ``s`` (both found by a
    partition; nan where ``c`` is 0). One pass over all pieces.
    """
    m = len(points)
    n_seg = len(polyline) - 1
    d = np.empty(m)
    if n_seg < 1:
        d = polyline_closest(points, polyline)[0]
    else:
        chunk = 8
        raw = _chunk_boxes(polyline, n_seg, chunk)
        seg_box = _chunk_boxes(polyline, n_seg, 1)
        n_chunk = len(raw)
        for j in range(len(piece_start) - 1):
            g0 = -1
            for i in range(piece_start[j], piece_start[j + 1]):
                px, py, pz = points[i, 0], points[i, 1], points[i, 2]
                best = np.inf
                bg = -1
                if g0 >= 0:
                    # the previous point's segment and its neighbours first: their least bounds the search
                    for g in range(max(g0 - 1, 0), min(g0 + 2, n_seg)):
                        d2, _, _, _ = _segment_closest(px, py, pz, polyline, g)
                        if d2 < best:
                            best, bg = d2, g
                limit = _prune_limit(px, py, pz, best)
                for h in range(n_chunk):
                    if _box_sq(px, py, pz, raw, h) > limit:
                        continue
                    for g in range(h * chunk, min((h + 1) * chunk, n_seg)):
                        if g0 >= 0 and g0 - 1 <= g <= g0 + 1:
                            continue
                        if _box_sq(px, py, pz, seg_box, g) > limit:
                            continue
                        d2, _, _, _ = _segment_closest(px, py, pz, polyline, g)
                        if d2 < best:
                            best, bg = d2, g
                            limit = _prune_limit(px, py, pz, best)
                d[i] = np.sqrt(best)
                g0 = bg
    # per key its points' distances, sorted; the median of each
    count = np.zeros(n_keys, np.int64)
    for j in range(len(piece_start) - 1):
        count[piece_key[j]] += piece_start[j + 1] - piece_start[j]
    off = np.zeros(n_keys + 1, np.int64)
    for k in range(n_keys):
        off[k + 1] = off[k] + count[k]
    fill = off[:-1].copy()
    buf = np.empty(off[n_keys])
    for j in range(len(piece_start) - 1):
        k = piece_key[j]
        for i in range(piece_start[j], piece_start[j + 1]):
            buf[fill[k]] = d[i]
            fill[k] += 1
    med = np.full(n_keys, np.nan)
    for k in range(n_keys):
        c = count[k]
        if c > 0:
            # s[c // 2] by a partition; for even c, s[c // 2 - 1] is the largest of the part before it
            half = c // 2
            s = np.partition(buf[off[k]:off[k + 1]], half)
            lo = s[half]
            if c % 2 == 0:
                lo = s[0]
                for r in range(1, half):
                    lo = max(lo, s[r])
            med[k] = (lo + s[half]) / 2
    return med, count


@njit(cache=True)
def closest_on_plane_curves(target, pts, curve_start, curve_plane, curve_closed, plane):  # pragma: no cover - compiled
    """Closest points of ``target (n, 3)`` on the cut curves of one plane together (each as :func:`polyline_closest`).

    Curves of fewer than 2 points are skipped, a closed curve gets its closing segment. Returns
    the distances ``(n,)`` (inf where the plane has no curve), the closest points ``(n, 3)`` and
    whether each is an end of an open curve ``(n,)`` (within 1e-12); a later curve replaces an
    earlier one only where strictly nearer.
    """
    n = len(target)
    dist = np.full(n, np.inf)
    cp = np.zeros((n, 3))
    at_end = np.zeros(n, np.bool_)
    for j in range(len(curve_plane)):
        if curve_plane[j] != plane:
            continue
        a, b = curve_start[j], curve_start[j + 1]
        if b - a < 2:
            continue
        closed = curve_closed[j]
        m = b - a + 1 if closed else b - a
        if closed:
            q = np.empty((m, 3))
            q[:b - a] = pts[a:b]
            q[b - a] = pts[a]
        else:
            q = pts[a:b]
        d, p = polyline_closest_chunked(target, q)
        for i in range(n):
            if d[i] < dist[i]:
                dist[i] = d[i]
                cp[i, 0], cp[i, 1], cp[i, 2] = p[i, 0], p[i, 1], p[i, 2]
                if closed:
                    at_end[i] = False
                else:
                    e0 = np.sqrt((p[i, 0] - q[0, 0]) ** 2 + (p[i, 1] - q[0, 1]) ** 2 + (p[i, 2] - q[0, 2]) ** 2)
                    e1 = np.sqrt((p[i, 0] - q[m - 1, 0]) ** 2 + (p[i, 1] - q[m - 1, 1]) ** 2
                                 + (p[i, 2] - q[m - 1, 2]) ** 2)
                    at_end[i] = e0 <= 1e-12 or e1 <= 1e-12
    return dist, cp, at_end


@njit(cache=True)
def curves_near_profiles(pts, curve_start, curve_plane, moved, reach):  # pragma: no cover - compiled
    """Whether every cut point (m,) is within ``reach`` of the polyline ``moved[plane] (n, 3)`` of its curve's plane.

    ``pts (m, 3)`` are the points of all curves, curve ``j`` being ``pts[curve_start[j]:curve_start[j + 1]]``;
    ``moved (k, n, 3)`` one polyline per plane. The same as the distance to the polyline
    (:func:`polyline_closest`) being at most ``reach``: each polyline is searched in chunks of 8
    segments, a chunk only when its box grown by ``reach`` holds the point, and the search stops
    at the first segment within ``reach`` (the square root is monotone, so a segment's distance
    is at most ``reach`` exactly when the least one is). A chunk whose own box is farther than
    ``reach`` (with :func:`_prune_limit`'s margin) is passed over, and the nearest chunk is
    searched first: the answer does not depend on the order. One pass over all curves.
    """
    out = np.zeros(len(pts), np.bool_)
    k, n = moved.shape[0], moved.shape[1]
    chunk = 8
    n_seg = n - 1
    n_chunk = max(1, (n_seg + chunk - 1) // chunk)
    box = np.empty((k, n_chunk, 6))
    raw = np.empty((k, n_chunk, 6))
    for p in range(k):
        for h in range(n_chunk):
            s0, s1 = h * chunk, min((h + 1) * chunk, n_seg)       # segments s0 .. s1 - 1: points s0 .. s1
            s1 = max(s1, s0)
            for ax in range(3):
                lo, hi = np.inf, -np.inf
                for r in range(s0, min(s1 + 1, n)):
                    lo = min(lo, moved[p, r, ax])
                    hi = max(hi, moved[p, r, ax])
                box[p, h, ax] = lo - reach
                box[p, h, 3 + ax] = hi + reach
                raw[p, h, ax], raw[p, h, 3 + ax] = lo, hi
    lb = np.empty(n_chunk)
    for j in range(len(curve_start) - 1):
        p = curve_plane[j]
        line = moved[p]
        for i in range(curve_start[j], curve_start[j + 1]):
            x0, x1, x2 = pts[i, 0], pts[i, 1], pts[i, 2]
            if n == 1:
                out[i] = np.sqrt((x0 - line[0, 0]) ** 2 + (x1 - line[0, 1]) ** 2 + (x2 - line[0, 2]) ** 2) <= reach
                continue
            # the chunks whose grown box holds the point and whose box is within reach (with
            # _prune_limit's margin: the others hold no segment within reach), the nearest first
            limit = _prune_limit(x0, x1, x2, reach * reach)
            h0 = -1
            m = np.inf
            for h in range(n_chunk):
                lb[h] = np.inf
                if (x0 < box[p, h, 0] or x0 > box[p, h, 3] or x1 < box[p, h, 1] or x1 > box[p, h, 4]
                        or x2 < box[p, h, 2] or x2 > box[p, h, 5]):
                    continue
                b2 = _box_sq(x0, x1, x2, raw[p], h)
                if b2 > limit:
                    continue
                lb[h] = b2
                if b2 < m or h0 < 0:
                    m, h0 = b2, h
            found = False
            if h0 >= 0:
                for g in range(h0 * chunk, min((h0 + 1) * chunk, n_seg)):
                    d2, _, _, _ = _segment_closest(x0, x1, x2, line, g)
                    if np.sqrt(d2) <= reach:
                        found = True
                        break
                for h in range(n_chunk):
                    if found:
                        break
                    if h == h0 or lb[h] > limit:
                        continue
                    for g in range(h * chunk, min((h + 1) * chunk, n_seg)):
                        d2, _, _, _ = _segment_closest(x0, x1, x2, line, g)
                        if np.sqrt(d2) <= reach:
                            found = True
                            break
            out[i] = found
    return out


@njit(cache=True)
def improve_sums(profile, pts, piece_start, reach, end_reach, piece_key, n_keys):  # pragma: no cover - compiled
    """Sums (n, 3) and counts (n,) of the closest points of ``profile (n, 3)`` on each piece of ``pts``.

    Also the least distance ``(n_keys, n)`` of each profile point to the pieces of each key
    ``piece_key (q,)`` (inf where no chunk of them is within ``reach``): an upper bound of the
    point's distance to the pieces (the distance itself where within ``reach``).

    Piece ``j`` is the polyline ``pts[piece_start[j]:piece_start[j + 1]]`` (pieces of fewer than
    2 points are skipped). A closest point counts when within ``reach``, and, when it is an end of
    its piece, only within ``end_reach``. The sums start at the profile itself (count 1).

    Each piece is searched in chunks of 16 segments, a chunk only when its box grown by ``reach``
    holds the point: a closest point within ``reach`` lies in such a chunk. Of those chunks the
    nearest is searched first and the others only where their box is not farther than the best
    so far (:func:`_chunks_closest`), keeping the first of equal distances in segment order (as
    :func:`polyline_closest`): the same result as a search of those chunks' segments in order.
    """
    n = len(profile)
    acc = profile.copy()
    count = np.ones(n)
    dmin = np.full((n_keys, n), np.inf)
    check_ends = np.isfinite(end_reach)
    chunk = 16
    for j in range(len(piece_start) - 1):
        a, b = piece_start[j], piece_start[j + 1]
        if b - a < 2:
            continue
        q = pts[a:b]
        n_seg = len(q) - 1
        n_chunk = (n_seg + chunk - 1) // chunk
        raw = _chunk_boxes(q, n_seg, chunk)
        box = np.empty((n_chunk, 6))
        for h in range(n_chunk):
            for ax in range(3):
                box[h, ax] = raw[h, ax] - reach
                box[h, 3 + ax] = raw[h, 3 + ax] + reach
        allowed = np.empty(n_chunk, np.bool_)
        lb = np.empty(n_chunk)
        for i in range(n):
            px, py, pz = profile[i, 0], profile[i, 1], profile[i, 2]
            for h in range(n_chunk):
                allowed[h] = not (px < box[h, 0] or px > box[h, 3] or py < box[h, 1] or py > box[h, 4]
                                  or pz < box[h, 2] or pz > box[h, 5])
            # the nearest segment of the chunks whose grown box holds the point, nearest chunk first
            best, _, cx, cy, cz = _chunks_closest(px, py, pz, q, n_seg, chunk, raw, allowed, lb)
            d = np.sqrt(best)
            key = piece_key[j]
            if d < dmin[key, i]:
                dmin[key, i] = d
            if d > reach:
                continue
            if check_ends and d > end_reach:
                e0 = (cx - q[0, 0]) ** 2 + (cy - q[0, 1]) ** 2 + (cz - q[0, 2]) ** 2
                e1 = (cx - q[-1, 0]) ** 2 + (cy - q[-1, 1]) ** 2 + (cz - q[-1, 2]) ** 2
                if e0 <= 1e-24 or e1 <= 1e-24:
                    continue
            acc[i, 0] += cx
            acc[i, 1] += cy
            acc[i, 2] += cz
            count[i] += 1.0
    return acc, count, dmin


# ------------------------------------------------------------------------------ kinematic parts


@njit(cache=True)
def glide_shares(x, nrm, starts, states, beta, gamma, floor, thresh):  # pragma: no cover - compiled
    """Per state ``(k, 6)`` and curve, the share of its points whose Alg. 1 weight exceeds ``thresh``.

    ``starts (c + 1,)`` delimits the curves in ``x``, ``nrm`` ``(N, 3)``.
    """
    k, n_c = len(states), len(starts) - 1
    out = np.zeros((k, n_c))
    f2 = floor * floor
    # 1 / (1 + beta f^gamma) > thresh  <=>  f < fmax (f >= 0, gamma > 0)
    fmax = ((1.0 / thresh - 1.0) / beta) ** (1.0 / gamma)
    for s in range(k):
        c0, c1, c2 = states[s, 0], states[s, 1], states[s, 2]
        b0, b1, b2 = states[s, 3], states[s, 4], states[s, 5]
        for j in range(n_c):
            a, b = starts[j], starts[j + 1]
            good = 0
            for i in range(a, b):
                px, py, pz = x[i, 0], x[i, 1], x[i, 2]
                vx = b0 + c1 * pz - c2 * py
                vy = b1 + c2 * px - c0 * pz
                vz = b2 + c0 * py - c1 * px
                nv = nrm[i, 0] * vx + nrm[i, 1] * vy + nrm[i, 2] * vz
                if nv * nv < fmax * (vx * vx + vy * vy + vz * vz + f2):
                    good += 1
            out[s, j] = good / max(b - a, 1)
    return out


# ------------------------------------------------------------------- closest points on a swept ring grid


@njit(cache=True, inline="always")
def _triangle_closest(px, py, pz, ax, ay, az, bx, by, bz, cx, cy, cz):  # pragma: no cover - compiled
    """Squared distance from p to triangle abc and the closest point.

    By the Voronoi regions of the vertices, edges and face in barycentric terms; a triangle with
    a zero-length edge (every denominator below is an edge's squared length or the area) or no
    area falls to its edges.
    """
    abx, aby, abz = bx - ax, by - ay, bz - az
    acx, acy, acz = cx - ax, cy - ay, cz - az
    bcx, bcy, bcz = cx - bx, cy - by, cz - bz
    flat = (abx * abx + aby * aby + abz * abz == 0.0 or acx * acx + acy * acy + acz * acz == 0.0
            or bcx * bcx + bcy * bcy + bcz * bcz == 0.0)
    qx, qy, qz = ax, ay, az
    if not flat:
        apx, apy, apz = px - ax, py - ay, pz - az
        d1 = abx * apx + aby * apy + abz * apz
        d2 = acx * apx + acy * apy + acz * apz
        bpx, bpy, bpz = px - bx, py - by, pz - bz
        d3 = abx * bpx + aby * bpy + abz * bpz
        d4 = acx * bpx + acy * bpy + acz * bpz
        cpx, cpy, cpz = px - cx, py - cy, pz - cz
        d5 = abx * cpx + aby * cpy + abz * cpz
        d6 = acx * cpx + acy * cpy + acz * cpz
        vc = d1 * d4 - d3 * d2
        vb = d5 * d2 - d1 * d6
        va = d3 * d6 - d5 * d4
        if d1 <= 0.0 and d2 <= 0.0:
            qx, qy, qz = ax, ay, az
        elif d3 >= 0.0 and d4 <= d3:
            qx, qy, qz = bx, by, bz
        elif vc <= 0.0 and d1 >= 0.0 and d3 <= 0.0 and d1 - d3 > 0.0:
            v = d1 / (d1 - d3)
            qx, qy, qz = ax + v * abx, ay + v * aby, az + v * abz
        elif d6 >= 0.0 and d5 <= d6:
            qx, qy, qz = cx, cy, cz
        elif vb <= 0.0 and d2 >= 0.0 and d6 <= 0.0 and d2 - d6 > 0.0:
            w = d2 / (d2 - d6)
            qx, qy, qz = ax + w * acx, ay + w * acy, az + w * acz
        elif va <= 0.0 and (d4 - d3) >= 0.0 and (d5 - d6) >= 0.0 and (d4 - d3) + (d5 - d6) > 0.0:
            w = (d4 - d3) / ((d4 - d3) + (d5 - d6))
            qx, qy, qz = bx + w * bcx, by + w * bcy, bz + w * bcz
        elif va + vb + vc > 0.0:
            s = va + vb + vc
            v = vb / s
            w = vc / s
            qx, qy, qz = ax + abx * v + acx * w, ay + aby * v + acy * w, az + abz * v + acz * w
        else:
            flat = True
    if flat:       # the nearest point of the three edges
        best = np.inf
        for e in range(3):
            if e == 0:
                ux, uy, uz, wx, wy, wz = ax, ay, az, bx, by, bz
            elif e == 1:
                ux, uy, uz, wx, wy, wz = bx, by, bz, cx, cy, cz
            else:
                ux, uy, uz, wx, wy, wz = cx, cy, cz, ax, ay, az
            dd, rx, ry, rz = _point_segment(px, py, pz, ux, uy, uz, wx, wy, wz)
            if dd < best:
                best = dd
                qx, qy, qz = rx, ry, rz
    return (px - qx) ** 2 + (py - qy) ** 2 + (pz - qz) ** 2, qx, qy, qz


@njit(cache=True, inline="always")
def _grid_dims(lo, hi, n, h):  # pragma: no cover - compiled
    """Cells per axis ``(3,)`` of a grid of cell size ``h`` from ``lo`` to ``hi`` over ``n`` elements.

    With no element ``lo`` is set to 0 (one cell).
    """
    dims = np.ones(3, np.int64)
    if n == 0:
        lo[:] = 0.0
    else:
        for ax in range(3):
            dims[ax] = max(1, int((hi[ax] - lo[ax]) / h) + 1)
    return dims


@njit(cache=True)
def ring_grid_boxes(rings, closed):  # pragma: no cover - compiled
    """Bounding boxes of the quads of a ring grid ``rings (k, n, 3)`` and of 2 x 2 blocks of them, level by level.

    Level 0 is the ``(k - 1) x m`` quads (``m = n`` for closed rings, else ``n - 1``), each level
    above halves both counts (rounding up) down to one box. Returns the boxes ``(total, 6)`` (min
    then max), each level's first row ``(L + 1,)`` and its shape ``(L, 2)``.
    """
    k, n = rings.shape[0], rings.shape[1]
    m = n if closed else n - 1
    shapes = []
    a, b = k - 1, m
    shapes.append((a, b))
    while a > 1 or b > 1:
        a, b = (a + 1) // 2, (b + 1) // 2
        shapes.append((a, b))
    n_lev = len(shapes)
    shape = np.zeros((n_lev, 2), np.int64)
    off = np.zeros(n_lev + 1, np.int64)
    for lv in range(n_lev):
        shape[lv, 0], shape[lv, 1] = shapes[lv]
        off[lv + 1] = off[lv] + shapes[lv][0] * shapes[lv][1]
    box = np.empty((off[n_lev], 6))
    for i in range(k - 1):
        for j in range(m):
            j1 = (j + 1) % n
            r = off[0] + i * m + j
            for ax in range(3):
                lo = min(min(rings[i, j, ax], rings[i, j1, ax]), min(rings[i + 1, j, ax], rings[i + 1, j1, ax]))
                hi = max(max(rings[i, j, ax], rings[i, j1, ax]), max(rings[i + 1, j, ax], rings[i + 1, j1, ax]))
                box[r, ax], box[r, 3 + ax] = lo, hi
    for lv in range(1, n_lev):
        pa, pb = shape[lv - 1, 0], shape[lv - 1, 1]
        for i in range(shape[lv, 0]):
            for j in range(shape[lv, 1]):
                r = off[lv] + i * shape[lv, 1] + j
                for ax in range(3):
                    box[r, ax], box[r, 3 + ax] = np.inf, -np.inf
                for ci in range(2 * i, min(2 * i + 2, pa)):
                    for cj in range(2 * j, min(2 * j + 2, pb)):
                        c = off[lv - 1] + ci * pb + cj
                        for ax in range(3):
                            box[r, ax] = min(box[r, ax], box[c, ax])
                            box[r, 3 + ax] = max(box[r, 3 + ax], box[c, 3 + ax])
    return box, off, shape


@njit(cache=True, inline="always")
def _box_sq(px, py, pz, box, r):  # pragma: no cover - compiled
    dx = max(box[r, 0] - px, 0.0, px - box[r, 3])
    dy = max(box[r, 1] - py, 0.0, py - box[r, 4])
    dz = max(box[r, 2] - pz, 0.0, pz - box[r, 5])
    return dx * dx + dy * dy + dz * dz


@njit(cache=True)
def _ring_triangle_closest(rings, n, i, j, t, px, py, pz):  # pragma: no cover - compiled
    """:func:`_triangle_closest` of a point to triangle ``t`` (0 or 1) of quad ``(i, j)`` of the ring grid.

    Triangles as :func:`~auszug.sweeps.patches.ring_faces` numbers them (``n`` points a ring).
    """
    j1 = (j + 1) % n
    a0 = rings[i, j]
    if t == 0:
        b0, c0 = rings[i, j1], rings[i + 1, j1]
    else:
        b0, c0 = rings[i + 1, j1], rings[i + 1, j]
    return _triangle_closest(px, py, pz, a0[0], a0[1], a0[2], b0[0], b0[1], b0[2], c0[0], c0[1], c0[2])


@njit(cache=True)
def _search_scratch(n_lev):  # pragma: no cover - compiled
    """The box search's stack (levels, rows, columns; ``4 n_lev + 4`` each) and child scratch (4 each)."""
    return (np.empty(4 * n_lev + 4, np.int64), np.empty(4 * n_lev + 4, np.int64), np.empty(4 * n_lev + 4, np.int64),
            np.empty(4), np.empty(4, np.int64), np.empty(4, np.int64))


@njit(cache=True)
def _push_near_children(px, py, pz, box, off, shape, lv, i, j, limit, cd, ci_, cj_,
                        stack_l, stack_i, stack_j, sp):  # pragma: no cover - compiled
    """Push box ``(i, j)`` of level ``lv``'s children within squared distance ``limit``, nearest last.

    The stack (``stack_l/i/j``, ``sp`` entries) is popped from the end, so the nearest child is
    searched first; ``cd, ci_, cj_`` (4 each) are scratch. Returns the new ``sp``.
    """
    nc = 0
    pa, pb = shape[lv - 1, 0], shape[lv - 1, 1]
    for ci in range(2 * i, min(2 * i + 2, pa)):
        for cj in range(2 * j, min(2 * j + 2, pb)):
            d = _box_sq(px, py, pz, box, off[lv - 1] + ci * pb + cj)
            if d > limit:
                continue
            h = nc
            while h > 0 and cd[h - 1] < d:     # sorted far to near
                cd[h], ci_[h], cj_[h] = cd[h - 1], ci_[h - 1], cj_[h - 1]
                h -= 1
            cd[h], ci_[h], cj_[h] = d, ci, cj
            nc += 1
    for h in range(nc):
        stack_l[sp], stack_i[sp], stack_j[sp] = lv - 1, ci_[h], cj_[h]
        sp += 1
    return sp


@njit(cache=True)
def ring_grid_nearest(rings, closed, box, off, shape, points, bound):  # pragma: no cover - compiled
    """Closest points on the triangulated ring grid (:func:`~auszug.sweeps.patches.ring_faces`) within ``bound``.

    Returns distances ``(q,)`` (inf where the surface is farther than ``bound``), face indices
    ``(q,)`` (-1 there; numbered as ``ring_faces``) and closest points ``(q, 3)``. A depth-first
    search of the box levels of :func:`ring_grid_boxes`, nearer children first, pruning boxes
    farther than the best distance so far (``bound`` at the start): exact. Each point starts from
    the triangle of the previous point found (points given in order along a surface, such as a
    mesh's vertices, need few boxes then).
    """
    n = rings.shape[1]
    m = n if closed else n - 1
    n_lev = len(shape)
    q = len(points)
    dist = np.full(q, np.inf)
    face = np.full(q, -1, np.int64)
    cp = np.zeros((q, 3))
    stack_l, stack_i, stack_j, cd, ci_, cj_ = _search_scratch(n_lev)
    b2 = bound * bound
    last = -1
    for p in range(q):
        px, py, pz = points[p, 0], points[p, 1], points[p, 2]
        best = b2
        found = False
        bx, by, bz = 0.0, 0.0, 0.0
        bf = -1
        top = n_lev - 1
        if _box_sq(px, py, pz, box, off[top]) > best:
            continue
        if last >= 0:      # the previous point's triangle first: its distance bounds the search
            qd = last // 2
            d2, qx, qy, qz = _ring_triangle_closest(rings, n, qd // m, qd % m, last % 2, px, py, pz)
            if d2 <= best:
                best, found, bx, by, bz, bf = d2, True, qx, qy, qz, last
        sp = 0
        stack_l[0], stack_i[0], stack_j[0] = top, 0, 0
        sp = 1
        while sp > 0:
            sp -= 1
            lv, i, j = stack_l[sp], stack_i[sp], stack_j[sp]
            if _box_sq(px, py, pz, box, off[lv] + i * shape[lv, 1] + j) > best:
                continue
            if lv == 0:
                for t in range(2):
                    fi = 2 * (i * m + j) + t
                    if fi == bf:
                        continue
                    d2, qx, qy, qz = _ring_triangle_closest(rings, n, i, j, t, px, py, pz)
                    if d2 < best or (not found and d2 <= best):
                        best = d2
                        found = True
                        bx, by, bz = qx, qy, qz
                        bf = fi
                continue
            # children, nearest pushed last (popped first)
            sp = _push_near_children(px, py, pz, box, off, shape, lv, i, j, best, cd, ci_, cj_,
                                     stack_l, stack_i, stack_j, sp)
        if found:
            dist[p] = np.sqrt(best)
            face[p] = bf
            cp[p, 0], cp[p, 1], cp[p, 2] = bx, by, bz
            last = bf
    return dist, face, cp


@njit(cache=True)
def ring_grid_within(rings, closed, box, off, shape, points, bound):  # pragma: no cover - compiled
    """Whether each point's distance to the triangulated ring grid is at most ``bound`` ``(q,)``.

    The same as ``ring_grid_nearest(..., bound)[0] <= bound``: a point is within when a triangle's
    squared distance (:func:`_triangle_closest`, as there) is at most ``bound ** 2`` and its square
    root at most ``bound`` (the nearest triangle's is the smallest). The search stops at the first
    such triangle: the previous point's first (points in order along a surface), then the other
    triangles of the 3 x 3 quads around it, then the box of 8 x 8 quads around it (level 3), then
    the whole grid from the top without that box, each depth first, nearer children first, pruning
    boxes farther than ``bound``. Any triangle within decides, so the order of the search changes
    no answer.
    """
    n = rings.shape[1]
    m = n if closed else n - 1
    n_quads = rings.shape[0] - 1
    n_lev = len(shape)
    q = len(points)
    out = np.zeros(q, np.bool_)
    stack_l, stack_i, stack_j, cd, ci_, cj_ = _search_scratch(n_lev)
    b2 = bound * bound
    last = -1
    top = n_lev - 1
    near = min(3, top)      # the previous triangle's box of 8 x 8 quads is searched first
    for p in range(q):
        px, py, pz = points[p, 0], points[p, 1], points[p, 2]
        if _box_sq(px, py, pz, box, off[top]) > b2:
            continue
        hit = -1
        skip_i, skip_j = -1, -1         # the level-``near`` box searched already (none)
        if last >= 0:
            qd = last // 2
            li, lj = qd // m, qd % m
            d2 = _ring_triangle_closest(rings, n, li, lj, last % 2, px, py, pz)[0]
            if d2 <= b2 and np.sqrt(d2) <= bound:
                hit = last
            # the triangles of the quads around the previous point's
            for di in range(-1, 2):
                if hit >= 0:
                    break
                i = li + di
                if i < 0 or i >= n_quads:
                    continue
                for dj in range(-1, 2):
                    if hit >= 0:
                        break
                    j = lj + dj
                    if closed:
                        j = j % m
                    elif j < 0 or j >= m:
                        continue
                    if _box_sq(px, py, pz, box, off[0] + i * m + j) > b2:
                        continue
                    for t in range(2):
                        fi = 2 * (i * m + j) + t
                        if fi == last:
                            continue
                        d2 = _ring_triangle_closest(rings, n, i, j, t, px, py, pz)[0]
                        if d2 <= b2 and np.sqrt(d2) <= bound:
                            hit = fi
                            break
        # any triangle within decides: first the box of ``near`` levels around the previous
        # point's triangle, then (if none there) the whole grid from the top but that box
        for start in range(2):
            if hit >= 0:
                break
            sp = 0
            if start == 0:
                if last < 0 or near == 0:
                    continue
                qd = last // 2
                skip_i, skip_j = (qd // m) >> near, (qd % m) >> near
                stack_l[0], stack_i[0], stack_j[0] = near, skip_i, skip_j
            else:
                stack_l[0], stack_i[0], stack_j[0] = top, 0, 0
            sp = 1
            while sp > 0 and hit < 0:
                sp -= 1
                lv, i, j = stack_l[sp], stack_i[sp], stack_j[sp]
                if start == 1 and lv == near and i == skip_i and j == skip_j:
                    continue
                if _box_sq(px, py, pz, box, off[lv] + i * shape[lv, 1] + j) > b2:
                    continue
                if lv == 0:
                    for t in range(2):
                        d2 = _ring_triangle_closest(rings, n, i, j, t, px, py, pz)[0]
                        if d2 <= b2 and np.sqrt(d2) <= bound:
                            hit = 2 * (i * m + j) + t
                            break
                    continue
                sp = _push_near_children(px, py, pz, box, off, shape, lv, i, j, b2, cd, ci_, cj_,
                                         stack_l, stack_i, stack_j, sp)
        if hit >= 0:
            out[p] = True
            last = hit
    return out


#: :func:`cut_near` passes over a cell whose end points' box lies farther than this from the plane: far above the
#: round-off of a signed distance (1e-16 at the unit scale of the normalised mesh), far below an edge.
CELL_SIDE_MARGIN = 1e-9


@njit(cache=True)
def edge_grid(v, edges, h):  # pragma: no cover - compiled
    """The edges binned by their midpoints in a uniform grid of cell size ``h``.

    Returns the grid's origin ``(3,)``, its cell counts ``(3,)``, the first entry of each cell
    ``(c + 1,)`` and the edges cell after cell ``(e,)``, the longest edge, the edges' end points
    in the grid's order ``(6, e)`` (rows: the first end's x, y, z, the second's; the scan of
    :func:`cut_near` reads them in a row instead of two vertices a scattered edge), and per cell
    the box of its edges' end points ``(c, 6)`` (min, max; inf, -inf for an empty cell).
    """
    n_e = len(edges)
    lo = np.full(3, np.inf)
    hi = np.full(3, -np.inf)
    mid = np.empty((n_e, 3))
    longest = 0.0
    for e in range(n_e):
        a, b = edges[e, 0], edges[e, 1]
        ll = 0.0
        for ax in range(3):
            mid[e, ax] = 0.5 * (v[a, ax] + v[b, ax])
            lo[ax] = min(lo[ax], mid[e, ax])
            hi[ax] = max(hi[ax], mid[e, ax])
            ll += (v[b, ax] - v[a, ax]) ** 2
        longest = max(longest, np.sqrt(ll))
    dims = _grid_dims(lo, hi, n_e, h)
    cell = np.empty(n_e, np.int64)
    count = np.zeros(dims[0] * dims[1] * dims[2] + 1, np.int64)
    for e in range(n_e):
        i = min(int((mid[e, 0] - lo[0]) / h), dims[0] - 1)
        j = min(int((mid[e, 1] - lo[1]) / h), dims[1] - 1)
        k = min(int((mid[e, 2] - lo[2]) / h), dims[2] - 1)
        cell[e] = (i * dims[1] + j) * dims[2] + k
        count[cell[e] + 1] += 1
    for c in range(1, len(count)):
        count[c] += count[c - 1]
    fill = count[:-1].copy()
    out = np.empty(n_e, np.int64)
    for e in range(n_e):
        out[fill[cell[e]]] = e
        fill[cell[e]] += 1
    # the end points and the cells' boxes in the grid's order: written in a row, cell after cell
    ends = np.empty((6, n_e))
    n_c = len(count) - 1
    cell_box = np.empty((n_c, 6))
    cell_box[:, :3] = np.inf
    cell_box[:, 3:] = -np.inf
    for c in range(n_c):
        for q in range(count[c], count[c + 1]):
            e = out[q]
            a, b = edges[e, 0], edges[e, 1]
            for ax in range(3):
                xa, xb = v[a, ax], v[b, ax]
                ends[ax, q] = xa
                ends[3 + ax, q] = xb
                cell_box[c, ax] = min(cell_box[c, ax], min(xa, xb))
                cell_box[c, 3 + ax] = max(cell_box[c, 3 + ax], max(xa, xb))
    return lo, dims, count, out, longest, ends, cell_box


@njit(cache=True, inline="always")
def _side(v, i, nx, ny, nz, d):  # pragma: no cover - compiled
    """The signed distance of vertex ``i`` to the plane, as the cutter computes it."""
    return v[i, 0] * nx + v[i, 1] * ny + v[i, 2] * nz - d


@njit(cache=True, inline="always")
def _crossed(v, edges, e, nx, ny, nz, d):  # pragma: no cover - compiled
    return (_side(v, edges[e, 0], nx, ny, nz, d) >= 0.0) != (_side(v, edges[e, 1], nx, ny, nz, d) >= 0.0)


@njit(cache=True)
def _other_crossed(v, edges, face_edges, f, e, nx, ny, nz, d):  # pragma: no cover - compiled
    for k in range(3):
        g = face_edges[f, k]
        if g != e and _crossed(v, edges, g, nx, ny, nz, d):
            return g
    return -1


@njit(cache=True)
def _step_face(v, edges, edge_faces, face_edges, e, prev, nx, ny, nz, d):  # pragma: no cover - compiled
    """The face across edge ``e`` away from face ``prev`` and its other crossed edge (-1: the walk ends)."""
    f = edge_faces[e, 0]
    if f == prev or f < 0:
        f = edge_faces[e, 1]
    if f < 0 or f == prev:
        return f, -1
    return f, _other_crossed(v, edges, face_edges, f, e, nx, ny, nz, d)


@njit(cache=True)
def _emit_local(v, vn, edges, e, nx, ny, nz, d, pts, nrm, eid, pos, begin):  # pragma: no cover - compiled
    """:func:`_emit` with the two signed distances computed on the spot (the same arithmetic)."""
    a, b = edges[e, 0], edges[e, 1]
    da = _side(v, a, nx, ny, nz, d)
    db = _side(v, b, nx, ny, nz, d)
    return _put(v, vn, a, b, da / (da - db), e, pts, nrm, eid, pos, begin)


@njit(cache=True)
def _chain_from(comp, comp_face, a, b, na, loop, edge_faces, s):  # pragma: no cover - compiled
    """The cutter's walk from edge ``s`` over a component found by :func:`cut_near`'s first walk, or an empty array.

    The component is ``comp[a:b]``: its seed, then the ``na`` edges walked through the seed's
    first face, then those through its second (``comp_face``: the face between each edge and the
    one before it). The cutter's walk from ``s`` enters the first face of ``s`` that it has
    (:func:`_step_face`) and follows the chain; where it takes in the whole component (``s`` an
    end of an open chain, or any edge of a loop), its edges in walk order; else (``s`` inside an
    open chain) an empty array, and the caller walks the mesh.
    """
    size = b - a
    out = np.empty(size, np.int64)
    if loop:           # comp[a:b] is the loop in order; comp_face[a + j] between comp[a + j - 1] and comp[a + j]
        j = 0
        while comp[a + j] != s:
            j += 1
        f0 = edge_faces[s, 0] if edge_faces[s, 0] >= 0 else edge_faces[s, 1]
        ahead = comp_face[a + j + 1] if j + 1 < size else edge_faces[comp[a], 1]
        for k in range(size):
            out[k] = comp[a + (j + k) % size] if f0 == ahead else comp[a + (j - k) % size]
        return out
    nb = size - 1 - na
    end_a = comp[a + na]            # the seed itself when na == 0
    end_b = comp[b - 1] if nb > 0 else comp[a]
    k = 0
    if s == end_b:                  # the second walk's edges back to the seed, then the first walk's
        for q in range(b - 1, a, -1):
            if q > a + na:
                out[k] = comp[q]
                k += 1
        for q in range(a, a + na + 1):
            out[k] = comp[q]
            k += 1
        return out
    if s == end_a:
        for q in range(a + na, a - 1, -1):
            out[k] = comp[q]
            k += 1
        for q in range(a + na + 1, b):
            out[k] = comp[q]
            k += 1
        return out
    return np.empty(0, np.int64)


@njit(cache=True)
def _room(pts, nrm, eid, used, need):  # pragma: no cover - compiled
    """Point buffers ``pts, nrm (cap, 3)``, ``eid (cap,)`` with room for ``need`` rows.

    The same arrays when ``need <= cap``, else new ones ``2 need`` long holding the first ``used``
    rows (the rest zero, ``eid`` -1).
    """
    if need <= len(pts):
        return pts, nrm, eid
    cap = 2 * need
    pts2 = np.zeros((cap, 3))
    nrm2 = np.zeros((cap, 3))
    eid2 = np.full(cap, -1, np.int64)
    pts2[:used] = pts[:used]
    nrm2[:used] = nrm[:used]
    eid2[:used] = eid[:used]
    return pts2, nrm2, eid2


@njit(cache=True)
def cut_near(v, vn, edges, edge_faces, face_edges, grid_lo, grid_dims, grid_start, grid_edges, h, longest, pn, pd,
             boxes, grid_ends, cell_box, grid_local):  # pragma: no cover - compiled
    """The cut curves of each plane that cross its box ``boxes[p] (6,)`` (min, max), as :func:`cut_fill` gives them.

    Every crossed edge whose cut point may lie in the box (its midpoint's cell within the box
    grown by half the longest edge) seeds its curve; the curve's crossed edges are found by
    walking from the seed through the faces, and the cutter's own walk (:func:`cut_fill`: open
    chains from the crossed edges without a second face in increasing order, then the rest in
    increasing order) is run on them. So each curve comes out point for point as the whole-mesh
    cut gives it, and the curves of a plane in the same order; curves without a point in the box
    may be missing. Work: the cells of the box near the plane and the curves found, not the mesh.

    Returns points, normals, edge ids, curve starts ``(c + 1,)``, curve planes ``(c,)`` and
    closed flags ``(c,)``. ``grid_ends (6, e)``: the grid's edges' end points (:func:`edge_grid`),
    whose signed distances are the cutter's bit for bit (the same products and sums). With
    ``grid_local (E,)`` not empty the grid is of a larger mesh sharing this mesh's vertices, this
    mesh a part of it: the grid's edge ``e`` is this mesh's edge ``grid_local[e]``, passed over
    where -1 (not of the part). ``cell_box (c, 6)``: per cell the box of its
    edges' end points (:func:`edge_grid`); a cell whose box lies farther than :data:`CELL_SIDE_MARGIN`
    on one side of the plane is passed over (every end point's signed distance has that sign
    whatever the round-off, so no edge of it is crossed).
    """
    n_planes = len(pd)
    local = len(grid_local) > 0
    x0, y0, z0 = grid_ends[0], grid_ends[1], grid_ends[2]
    x1, y1, z1 = grid_ends[3], grid_ends[4], grid_ends[5]
    cap = 1024
    pts = np.zeros((cap, 3))
    nrm = np.zeros((cap, 3))
    eid = np.full(cap, -1, np.int64)
    starts = np.zeros(64, np.int64)
    planes = np.zeros(64, np.int64)
    closed_out = np.zeros(64, np.bool_)
    n_curves = 0
    pos = 0
    stamp = np.zeros(len(edges), np.int64)      # plane + 1 where an edge's curve is found
    seen = np.zeros(len(edges), np.int64)       # plane + 1 where the cutter's walk passed
    comp = np.empty(len(edges), np.int64)
    comp_face = np.empty(len(edges), np.int64)
    tpts = np.zeros((1024, 3))                  # the plane's chains as walked
    tnrm = np.zeros((1024, 3))
    teid = np.full(1024, -1, np.int64)
    ch_key = np.zeros(64, np.int64)
    ch_begin = np.zeros(64, np.int64)
    ch_end = np.zeros(64, np.int64)
    ch_closed = np.zeros(64, np.bool_)
    for p in range(n_planes):
        nx, ny, nz, d = pn[p, 0], pn[p, 1], pn[p, 2], pd[p]
        mark = p + 1
        g = 0.5 * longest
        i0 = np.empty(3, np.int64)
        i1 = np.empty(3, np.int64)
        for ax in range(3):
            i0[ax] = max(0, int(np.floor((boxes[p, ax] - g - grid_lo[ax]) / h)))
            i1[ax] = min(grid_dims[ax] - 1, int(np.floor((boxes[p, 3 + ax] + g - grid_lo[ax]) / h)))
        # the components (curves) met, as lists of their crossed edges
        comp_start = [0]
        comp_na = [0]           # per component: the edges of its walk through the seed's first face
        comp_loop = [False]     # per component: a closed loop
        comp_na.pop()
        comp_loop.pop()
        n_comp_edges = 0
        ax_, ay_, az_ = abs(nx), abs(ny), abs(nz)
        for ci in range(i0[0], i1[0] + 1):
            for cj in range(i0[1], i1[1] + 1):
                for ck in range(i0[2], i1[2] + 1):
                    c = (ci * grid_dims[1] + cj) * grid_dims[2] + ck
                    if grid_start[c] == grid_start[c + 1]:
                        continue
                    # the signed distances of the cell's end points lie within centre +- half-extent
                    cx = 0.5 * (cell_box[c, 0] + cell_box[c, 3])
                    cy = 0.5 * (cell_box[c, 1] + cell_box[c, 4])
                    cz = 0.5 * (cell_box[c, 2] + cell_box[c, 5])
                    ext = (0.5 * (cell_box[c, 3] - cell_box[c, 0]) * ax_ + 0.5 * (cell_box[c, 4] - cell_box[c, 1]) * ay_
                           + 0.5 * (cell_box[c, 5] - cell_box[c, 2]) * az_)
                    if abs(cx * nx + cy * ny + cz * nz - d) > ext + CELL_SIDE_MARGIN:
                        continue           # every end point of this cell on one side of the plane
                    for q in range(grid_start[c], grid_start[c + 1]):
                        # _crossed of the edge from its end points stored in the grid's order
                        if (x0[q] * nx + y0[q] * ny + z0[q] * nz - d >= 0.0) == \
                                (x1[q] * nx + y1[q] * ny + z1[q] * nz - d >= 0.0):
                            continue
                        e0 = grid_edges[q]
                        if local:
                            e0 = grid_local[e0]
                            if e0 < 0:
                                continue       # not an edge of this mesh (the grid of the mesh it is a part of)
                        if stamp[e0] == mark:
                            continue
                        # walk both ways from e0 to collect its curve's crossed edges
                        stamp[e0] = mark
                        comp[n_comp_edges] = e0
                        comp_face[n_comp_edges] = -1
                        n_comp_edges += 1
                        loop = False
                        for side in range(2):
                            e, f = e0, edge_faces[e0, side]
                            while f >= 0:
                                nxt = _other_crossed(v, edges, face_edges, f, e, nx, ny, nz, d)
                                if nxt < 0 or stamp[nxt] == mark:
                                    loop = loop or (side == 0 and nxt >= 0)
                                    break
                                stamp[nxt] = mark
                                comp[n_comp_edges] = nxt
                                comp_face[n_comp_edges] = f          # the face between it and the edge before
                                n_comp_edges += 1
                                f = edge_faces[nxt, 1] if edge_faces[nxt, 0] == f else edge_faces[nxt, 0]
                                e = nxt
                            if side == 0:
                                comp_na.append(n_comp_edges - comp_start[-1] - 1)
                        comp_loop.append(loop)
                        comp_start.append(n_comp_edges)
        # the cutter's walk on each component's edges, each chain emitted as it is walked (into the plane's
        # buffer); chains keyed by (phase, start edge). A component is one chain of crossed edges: the
        # cutter starts it at its smallest edge without a second face (phase 0), else at its smallest edge
        # (phase 1); where that walk does not take in the whole component (a start with a face on either
        # side), the rest follows the cutter's order: the component's edges sorted, phase 0, then phase 1
        n_comp = len(comp_start) - 1
        n_e = len(edges)
        tpos = 0
        n_ch = 0
        for r in range(n_comp):
            s0 = -1
            s1 = -1
            for q in range(comp_start[r], comp_start[r + 1]):
                e = comp[q]
                if edge_faces[e, 1] < 0 and (s0 < 0 or e < s0):
                    s0 = e
                if s1 < 0 or e < s1:
                    s1 = e
            first = np.array([s0 if s0 >= 0 else s1], np.int64)
            walked = 0
            for stage in range(3):
                # stage 0: the first chain; 1 and 2: the cutter's phases 0 and 1 over the sorted edges
                if stage > 0 and walked == comp_start[r + 1] - comp_start[r]:
                    break
                phase = (0 if s0 >= 0 else 1) if stage == 0 else stage - 1
                order = first if stage == 0 else np.sort(comp[comp_start[r]:comp_start[r + 1]])
                for qi in range(len(order)):
                    e0 = order[qi]
                    if seen[e0] == mark:
                        continue
                    if phase == 0 and edge_faces[e0, 1] >= 0:
                        continue
                    tpts, tnrm, teid = _room(tpts, tnrm, teid, tpos, tpos + comp_start[r + 1] - comp_start[r] + 2)
                    if n_ch + 1 > len(ch_key):
                        ch_key2 = np.zeros(2 * len(ch_key), np.int64)
                        ch_begin2 = np.zeros(2 * len(ch_key), np.int64)
                        ch_end2 = np.zeros(2 * len(ch_key), np.int64)
                        ch_closed2 = np.zeros(2 * len(ch_key), np.bool_)
                        ch_key2[:n_ch] = ch_key[:n_ch]
                        ch_begin2[:n_ch] = ch_begin[:n_ch]
                        ch_end2[:n_ch] = ch_end[:n_ch]
                        ch_closed2[:n_ch] = ch_closed[:n_ch]
                        ch_key, ch_begin, ch_end, ch_closed = ch_key2, ch_begin2, ch_end2, ch_closed2
                    begin = tpos
                    is_closed = False
                    seq = _chain_from(comp, comp_face, comp_start[r], comp_start[r + 1], comp_na[r], comp_loop[r],
                                      edge_faces, e0) if stage == 0 else np.empty(0, np.int64)
                    if len(seq):
                        # the walk from e0 takes in the whole component: its edges in walk order, as walked
                        for qq in range(len(seq)):
                            e = seq[qq]
                            seen[e] = mark
                            walked += 1
                            tpos = _emit_local(v, vn, edges, e, nx, ny, nz, d, tpts, tnrm, teid, tpos, begin)
                        is_closed = comp_loop[r]
                    else:
                        e, prev = e0, -1
                        while True:
                            seen[e] = mark
                            walked += 1
                            tpos = _emit_local(v, vn, edges, e, nx, ny, nz, d, tpts, tnrm, teid, tpos, begin)
                            f, g2 = _step_face(v, edges, edge_faces, face_edges, e, prev, nx, ny, nz, d)
                            if g2 < 0:
                                break
                            if seen[g2] == mark:
                                is_closed = g2 == e0
                                break
                            prev, e = f, g2
                    ch_key[n_ch] = phase * n_e + e0
                    ch_begin[n_ch] = begin
                    ch_end[n_ch] = tpos
                    ch_closed[n_ch] = is_closed
                    n_ch += 1
        # the chains in the cutter's order: phase, then start edge
        for ci in np.argsort(ch_key[:n_ch]):
            begin, end = ch_begin[ci], ch_end[ci]
            if end - begin < 2:
                continue
            pts, nrm, eid = _room(pts, nrm, eid, pos, pos + end - begin)
            if n_curves + 2 > len(starts):
                starts2 = np.zeros(2 * len(starts), np.int64)
                planes2 = np.zeros(2 * len(starts), np.int64)
                closed2 = np.zeros(2 * len(starts), np.bool_)
                starts2[:n_curves] = starts[:n_curves]
                planes2[:n_curves] = planes[:n_curves]
                closed2[:n_curves] = closed_out[:n_curves]
                starts, planes, closed_out = starts2, planes2, closed2
            starts[n_curves] = pos
            planes[n_curves] = p
            closed_out[n_curves] = ch_closed[ci]
            n_curves += 1
            pts[pos:pos + end - begin] = tpts[begin:end]
            nrm[pos:pos + end - begin] = tnrm[begin:end]
            eid[pos:pos + end - begin] = teid[begin:end]
            pos += end - begin
    curve_start = np.empty(n_curves + 1, np.int64)
    curve_start[:n_curves] = starts[:n_curves]
    curve_start[n_curves] = pos
    return pts[:pos].copy(), nrm[:pos].copy(), eid[:pos].copy(), curve_start, planes[:n_curves].copy(), \
        closed_out[:n_curves].copy()


# ------------------------------------------------------------------------------------ sub-meshes


@njit(cache=True)
def box_part(v, faces, edges, edge_faces, face_edges, lo, hi):  # pragma: no cover - compiled
    """The faces whose three vertices lie in the box ``[lo, hi]``, their edges, the part's index maps and rows.

    Returns the kept faces ``(f,)`` and edges ``(e,)`` (increasing), the part's ``edge_faces (e, 2)``
    (-1 for a face not kept) and ``face_edges (f, 3)`` (indices into the kept edges), the kept
    rows of ``faces`` and ``edges`` (as numpy's ``faces[keep]``, ``edges[used]``), and each edge's
    index among the kept edges ``(E,)`` (-1 for an edge not kept): one pass over the vertices, the
    faces and the edges each.
    """
    n_v = len(v)
    inside = np.empty(n_v, np.bool_)
    for i in range(n_v):
        inside[i] = (lo[0] <= v[i, 0] <= hi[0]) and (lo[1] <= v[i, 1] <= hi[1]) and (lo[2] <= v[i, 2] <= hi[2])
    n_f = len(faces)
    n_e = len(edge_faces)
    face_index = np.empty(n_f, np.int64)
    edge_index = np.full(n_e, -1, np.int64)
    keep_all = np.empty(n_f, np.int64)
    n_keep = 0
    for f in range(n_f):
        if inside[faces[f, 0]] and inside[faces[f, 1]] and inside[faces[f, 2]]:
            face_index[f] = n_keep
            keep_all[n_keep] = f
            n_keep += 1
            for k in range(3):
                edge_index[face_edges[f, k]] = 0
        else:
            face_index[f] = -1
    keep = keep_all[:n_keep].copy()
    sub_faces = np.empty((n_keep, 3), faces.dtype)
    for r in range(n_keep):
        f = keep[r]
        sub_faces[r, 0], sub_faces[r, 1], sub_faces[r, 2] = faces[f, 0], faces[f, 1], faces[f, 2]
    used_all = np.empty(n_e, np.int64)
    n_used = 0
    for e in range(n_e):
        if edge_index[e] == 0:
            edge_index[e] = n_used
            used_all[n_used] = e
            n_used += 1
    used = used_all[:n_used].copy()
    ef = np.empty((n_used, 2), np.int64)
    sub_edges = np.empty((n_used, edges.shape[1]), edges.dtype)
    for r in range(n_used):
        e = used[r]
        for k in range(2):
            g = edge_faces[e, k]
            ef[r, k] = face_index[g] if g >= 0 else -1
        for c in range(edges.shape[1]):
            sub_edges[r, c] = edges[e, c]
    fe = np.empty((n_keep, 3), np.int64)
    for r in range(n_keep):
        f = keep[r]
        for k in range(3):
            fe[r, k] = edge_index[face_edges[f, k]]
    return keep, used, ef, fe, sub_faces, sub_edges, edge_index


# ------------------------------------------------------------------------------ per-face passes of the fit


@njit(cache=True)
def closest_features(v, faces, face_edges, face, c, gap):  # pragma: no cover - compiled
    """The vertex, or else the edge, closest points ``c (n, 3)`` on faces ``face (n,)`` lie on (-1 for none).

    As ``MeshTree._features``: within ``gap`` of a corner of the face, that vertex (the nearest
    corner); else within ``gap`` of a side, that edge (``face_edges``' id; the nearest side);
    else inside the face. Returns vertex ids ``(n,)`` and edge ids ``(n,)``.
    """
    n = len(face)
    vid = np.full(n, -1, np.int64)
    eid = np.full(n, -1, np.int64)
    for p in range(n):
        f = face[p]
        cx, cy, cz = c[p, 0], c[p, 1], c[p, 2]
        best, kb = np.inf, -1
        for k in range(3):
            i = faces[f, k]
            d = np.sqrt((cx - v[i, 0]) ** 2 + (cy - v[i, 1]) ** 2 + (cz - v[i, 2]) ** 2)
            if d < best:
                best, kb = d, k
        if best <= gap:
            vid[p] = faces[f, kb]
            continue
        best, kb = np.inf, -1
        for k in range(3):
            a, b = faces[f, k], faces[f, (k + 1) % 3]
            abx, aby, abz = v[b, 0] - v[a, 0], v[b, 1] - v[a, 1], v[b, 2] - v[a, 2]
            w = abx * abx + aby * aby + abz * abz
            t = ((cx - v[a, 0]) * abx + (cy - v[a, 1]) * aby + (cz - v[a, 2]) * abz) / (w if w > 0 else 1.0)
            t = min(max(t, 0.0), 1.0)
            d = np.sqrt((cx - v[a, 0] - t * abx) ** 2 + (cy - v[a, 1] - t * aby) ** 2 + (cz - v[a, 2] - t * abz) ** 2)
            if d < best:
                best, kb = d, k
        if best <= gap:
            eid[p] = face_edges[f, kb]
    return vid, eid


@njit(cache=True)
def triangle_areas(v, faces):  # pragma: no cover - compiled
    """Areas ``(m,)`` of triangles: ``|(b - a) x (c - a)| / 2`` in numpy's order of operations (the same bits)."""
    out = np.empty(len(faces))
    for i in range(len(faces)):
        a, b, c = faces[i, 0], faces[i, 1], faces[i, 2]
        ux, uy, uz = v[b, 0] - v[a, 0], v[b, 1] - v[a, 1], v[b, 2] - v[a, 2]
        wx, wy, wz = v[c, 0] - v[a, 0], v[c, 1] - v[a, 1], v[c, 2] - v[a, 2]
        cx = uy * wz - uz * wy
        cy = uz * wx - ux * wz
        cz = ux * wy - uy * wx
        out[i] = 0.5 * np.sqrt(cx * cx + cy * cy + cz * cz)
    return out


@njit(cache=True)
def face_vertices_in_box(v, faces, lo, hi):  # pragma: no cover - compiled
    """Per vertex: it is a vertex of one of ``faces`` and lies in the box ``[lo, hi]`` ``(n,)``."""
    used = np.zeros(len(v), np.bool_)
    for i in range(len(faces)):
        for k in range(3):
            used[faces[i, k]] = True
    for i in range(len(v)):
        if used[i]:
            used[i] = (lo[0] <= v[i, 0] <= hi[0]) and (lo[1] <= v[i, 1] <= hi[1]) and (lo[2] <= v[i, 2] <= hi[2])
    return used


@njit(cache=True)
def faces_within(dist, faces, eps):  # pragma: no cover - compiled
    """The faces ``(f,)`` (increasing) whose three vertices have ``dist <= eps``."""
    keep = np.empty(len(faces), np.int64)
    n = 0
    for i in range(len(faces)):
        if dist[faces[i, 0]] <= eps and dist[faces[i, 1]] <= eps and dist[faces[i, 2]] <= eps:
            keep[n] = i
            n += 1
    return keep[:n].copy()


@njit(cache=True)
def boundary_edges_of(faces, edge_faces, face_edges):  # pragma: no cover - compiled
    """Per face its boundary edges as vertex pairs ``(m, 3, 2)`` (-1 where the edge has two faces).

    The edges in face order ``(0, 1), (1, 2), (2, 0)``, as :attr:`SweepMesh.face_edges`.
    """
    out = np.full((len(faces), 3, 2), -1, np.int64)
    for i in range(len(faces)):
        for k in range(3):
            e = face_edges[i, k]
            if edge_faces[e, 0] < 0 or edge_faces[e, 1] < 0:
                out[i, k, 0] = faces[i, k]
                out[i, k, 1] = faces[i, (k + 1) % 3]
    return out


# ------------------------------------------------------------------------- rigid maps applied to points


@njit(cache=True)
def apply_maps(r, tr, x):  # pragma: no cover - compiled
    """Points ``x (n, 3)`` moved by each map ``(r (q, 3, 3), tr (q, 3))``: ``(q, n, 3)``.

    Equal bit for bit to ``np.einsum("qij,nj->qni", r, x) + tr[:, None, :]``: numpy's einsum sums
    the three products of a row as ``(p0 + p2) + p1`` (from 0.0), then the translation is added.
    """
    q = r.shape[0]
    n = x.shape[0]
    out = np.empty((q, n, 3))
    for k in range(q):
        for p in range(n):
            x0, x1, x2 = x[p, 0], x[p, 1], x[p, 2]
            for i in range(3):
                s = 0.0 + ((r[k, i, 0] * x0 + r[k, i, 2] * x2) + r[k, i, 1] * x1)
                out[k, p, i] = s + tr[k, i]
    return out


@njit(cache=True)
def near_runs(near, curve_start, curve_plane):  # pragma: no cover - compiled
    """The runs of near points ``near (m,)`` of each curve, of 2 points or more, as pieces.

    Curve ``j`` is points ``curve_start[j]:curve_start[j + 1]``, of plane ``curve_plane[j]``; a run
    is a maximal stretch of consecutive near points of one curve. Returns the pieces' starts
    ``(q + 1,)`` into the runs' points, the runs' point indices ``(r,)`` (curve after curve, in
    order), each such point's plane ``(r,)`` and each piece's plane ``(q,)``.
    """
    m = len(near)
    idx = np.empty(m, np.int64)
    plane_of = np.empty(m, np.int64)
    starts = np.zeros(m + 1, np.int64)
    piece_plane = np.empty(m, np.int64)
    n_p = 0
    pos = 0
    for j in range(len(curve_start) - 1):
        pl = curve_plane[j]
        i = curve_start[j]
        end = curve_start[j + 1]
        while i < end:
            if not near[i]:
                i += 1
                continue
            a = i
            while i < end and near[i]:
                i += 1
            if i - a >= 2:
                for t in range(a, i):
                    idx[pos] = t
                    plane_of[pos] = pl
                    pos += 1
                piece_plane[n_p] = pl
                n_p += 1
                starts[n_p] = pos
    return starts[:n_p + 1].copy(), idx[:pos].copy(), plane_of[:pos].copy(), piece_plane[:n_p].copy()


@njit(cache=True)
def inverse_maps_at(r, tr, knot, pts, idx):  # pragma: no cover - compiled
    """Each point ``pts[idx[p]]`` mapped back by the inverse of the map ``knot[p]`` of ``(r (q, 3, 3), tr (q, 3))``.

    Returns ``(m, 3)``, equal bit for bit to ``np.einsum("nji,nj->ni", r[knot], pts[idx] - tr[knot])``
    (numpy's einsum sums these three products in order, from 0.0), without the gathered copies.
    """
    m = len(idx)
    out = np.empty((m, 3))
    for p in range(m):
        k = knot[p]
        d0 = pts[idx[p], 0] - tr[k, 0]
        d1 = pts[idx[p], 1] - tr[k, 1]
        d2 = pts[idx[p], 2] - tr[k, 2]
        for i in range(3):
            s = 0.0
            s += r[k, 0, i] * d0
            s += r[k, 1, i] * d1
            s += r[k, 2, i] * d2
            out[p, i] = s
    return out


# ------------------------------------------------------------------------- Eq. 7 and Kabsch sums


@njit(cache=True)
def eq7_blocks(mid, d):  # pragma: no cover - compiled
    """The normal-equation blocks of F_pivot per rib pair: ``A^T A (p, 6, 6)`` and ``A^T d (p, 6)``.

    ``mid (p, n, 3)`` are the pairs' midpoints and ``d (p, n, 3)`` their displacements per unit
    time; ``A (p, 3 n, 6)`` has per point the rows ``[-[m]x | I]`` (``c x m + c_bar``), point after
    point. Equal bit for bit to ``np.einsum("pri,prj->pij", A, A)`` and ``np.einsum("pri,pr->pi", A,
    d.reshape(p, 3 n))``: numpy's einsum sums these products over ``r`` in order, from 0.0, and so
    does this pass, without building ``A``.
    """
    n_p, n = mid.shape[0], mid.shape[1]
    lhs = np.zeros((n_p, 6, 6))
    rhs = np.zeros((n_p, 6))
    row = np.zeros(6)
    for p in range(n_p):
        for q in range(n):
            mx, my, mz = mid[p, q, 0], mid[p, q, 1], mid[p, q, 2]
            for c in range(3):
                if c == 0:
                    row[0], row[1], row[2], row[3], row[4], row[5] = 0.0, mz, -my, 1.0, 0.0, 0.0
                elif c == 1:
                    row[0], row[1], row[2], row[3], row[4], row[5] = -mz, 0.0, mx, 0.0, 1.0, 0.0
                else:
                    row[0], row[1], row[2], row[3], row[4], row[5] = my, -mx, 0.0, 0.0, 0.0, 1.0
                dc = d[p, q, c]
                for i in range(6):
                    ri = row[i]
                    for j in range(6):
                        lhs[p, i, j] += ri * row[j]
                    rhs[p, i] += ri * dc
    return lhs, rhs


@njit(cache=True)
def batched_gram(a, b):  # pragma: no cover - compiled
    """``a (k, n, i)`` and ``b (k, n, j)``: ``(k, i, j)`` sums over ``n`` of ``a[:, n, :, None] b[:, n, None, :]``.

    Equal bit for bit to ``np.einsum("kni,knj->kij", a, b)`` (numpy sums over ``n`` in order, from 0.0).
    """
    k, n, ni, nj = a.shape[0], a.shape[1], a.shape[2], b.shape[2]
    out = np.zeros((k, ni, nj))
    for h in range(k):
        for q in range(n):
            for i in range(ni):
                ai = a[h, q, i]
                for j in range(nj):
                    out[h, i, j] += ai * b[h, q, j]
    return out


@njit(cache=True)
def kabsch_sums(a, b):  # pragma: no cover - compiled
    """The centroids and cross-covariances of Kabsch for point sets ``a`` onto ``b (k, n, 3)``.

    ``a`` is ``(k, n, 3)``, or ``(1, n, 3)`` for the same points for every ``b[h]``. Returns ``ca``,
    ``cb (k, 3)`` and ``h (k, 3, 3) = sum_q (a_q - ca) / n (b_q - cb)^T``; bit for bit numpy's
    ``mean(axis=1)`` (the rows summed in order, then divided by ``n``) and
    ``np.einsum("kni,knj->kij", (a - ca[:, None]) / n, b - cb[:, None])`` (summed over ``q`` in order).
    """
    k, n = b.shape[0], b.shape[1]
    ca = np.zeros((k, 3))
    cb = np.zeros((k, 3))
    h = np.zeros((k, 3, 3))
    for g in range(k):
        ga = 0 if a.shape[0] == 1 else g
        for q in range(n):
            for i in range(3):
                ca[g, i] += a[ga, q, i]
                cb[g, i] += b[g, q, i]
        for i in range(3):
            ca[g, i] /= n
            cb[g, i] /= n
        for q in range(n):
            for i in range(3):
                ai = (a[ga, q, i] - ca[g, i]) / n
                for j in range(3):
                    h[g, i, j] += ai * (b[g, q, j] - cb[g, j])
    return ca, cb, h


# ------------------------------------------------------------------------- rotation vectors <-> matrices


@njit(cache=True)
def rotations_of(w):  # pragma: no cover - compiled
    """Rotation matrices ``(n, 3, 3)`` of rotation vectors ``w (n, 3)``.

    Bit for bit scipy's ``Rotation.from_rotvec(w).as_matrix()``: the unit quaternion with
    ``sin(t/2)/t`` (its series up to ``t = 1e-3``), then the quaternion's matrix in scipy's order.
    """
    n = w.shape[0]
    r = np.empty((n, 3, 3))
    for p in range(n):
        w0, w1, w2 = w[p, 0], w[p, 1], w[p, 2]
        th = np.sqrt(w0 * w0 + w1 * w1 + w2 * w2)
        if th <= 1e-3:
            t2 = th * th
            s = 0.5 - t2 / 48.0 + t2 * t2 / 3840.0
        else:
            s = np.sin(th / 2.0) / th
        x, y, z, q = w0 * s, w1 * s, w2 * s, np.cos(th / 2.0)
        x2, y2, z2, q2 = x * x, y * y, z * z, q * q
        xy, zq, xz, yq, yz, xq = x * y, z * q, x * z, y * q, y * z, x * q
        r[p, 0, 0], r[p, 0, 1], r[p, 0, 2] = x2 - y2 - z2 + q2, 2.0 * (xy - zq), 2.0 * (xz + yq)
        r[p, 1, 0], r[p, 1, 1], r[p, 1, 2] = 2.0 * (xy + zq), -x2 + y2 - z2 + q2, 2.0 * (yz - xq)
        r[p, 2, 0], r[p, 2, 1], r[p, 2, 2] = 2.0 * (xz - yq), 2.0 * (yz + xq), -x2 - y2 + z2 + q2
    return r


@njit(cache=True)
def rotvecs_of(r):  # pragma: no cover - compiled
    """Rotation vectors ``(n, 3)`` of rotations ``r (n, 3, 3)`` (angle in [0, pi]).

    As scipy's ``Rotation.from_matrix(r).as_rotvec()`` for orthogonal ``r``: the quaternion from the
    largest of the diagonal and the trace (Markley), normalised, made canonical (``w >= 0``), then
    ``2 atan2(|xyz|, w)`` with the series of ``angle / sin(angle / 2)`` up to 1e-3. A matrix whose
    determinant is not positive (no rotation) gets NaN (scipy raises there; the caller does).
    """
    n = r.shape[0]
    out = np.empty((n, 3))
    qv = np.empty(4)
    for p in range(n):
        m = r[p]
        det = (m[0, 0] * (m[1, 1] * m[2, 2] - m[1, 2] * m[2, 1]) - m[0, 1] * (m[1, 0] * m[2, 2] - m[1, 2] * m[2, 0])
               + m[0, 2] * (m[1, 0] * m[2, 1] - m[1, 1] * m[2, 0]))
        if not det > 0.0:
            out[p, 0], out[p, 1], out[p, 2] = np.nan, np.nan, np.nan
            continue
        tr = m[0, 0] + m[1, 1] + m[2, 2]
        c = 0
        best = m[0, 0]
        if m[1, 1] > best:
            c, best = 1, m[1, 1]
        if m[2, 2] > best:
            c, best = 2, m[2, 2]
        if tr > best:
            c = 3
        if c == 3:
            qv[0], qv[1], qv[2], qv[3] = m[2, 1] - m[1, 2], m[0, 2] - m[2, 0], m[1, 0] - m[0, 1], 1.0 + tr
        else:
            i = c
            j = (i + 1) % 3
            k = (j + 1) % 3
            qv[i] = 1.0 - tr + 2.0 * m[i, i]
            qv[j] = m[j, i] + m[i, j]
            qv[k] = m[k, i] + m[i, k]
            qv[3] = m[k, j] - m[j, k]
        nq = np.sqrt(qv[0] * qv[0] + qv[1] * qv[1] + qv[2] * qv[2] + qv[3] * qv[3])
        x, y, z, q = qv[0] / nq, qv[1] / nq, qv[2] / nq, qv[3] / nq
        if q < 0.0 or (q == 0.0 and (x < 0.0 or (x == 0.0 and (y < 0.0 or (y == 0.0 and z < 0.0))))):
            x, y, z, q = -x, -y, -z, -q
        ang = 2.0 * np.arctan2(np.sqrt(x * x + y * y + z * z), q)
        if ang <= 1e-3:
            a2 = ang * ang
            s = 2.0 + a2 / 12.0 + 7.0 * a2 * a2 / 2880.0
        else:
            s = ang / np.sin(ang / 2.0)
        out[p, 0], out[p, 1], out[p, 2] = s * x, s * y, s * z
    return out


# ------------------------------------------------------------------- the motion's refinement against the mesh


@njit(cache=True)
def face_grid_cell(v, faces, per_edge, per_face):  # pragma: no cover - compiled
    """The cell size of :func:`face_grid`: ``per_edge`` mean edge lengths, larger for at most ``per_face`` cells a face.

    The cells are counted in the box of the faces' vertices.
    """
    m = len(faces)
    if m == 0:
        return 1.0
    lo = np.full(3, np.inf)
    hi = np.full(3, -np.inf)
    total = 0.0
    for f in range(m):
        for k in range(3):
            a, b = faces[f, k], faces[f, (k + 1) % 3]
            total += np.sqrt((v[a, 0] - v[b, 0]) ** 2 + (v[a, 1] - v[b, 1]) ** 2 + (v[a, 2] - v[b, 2]) ** 2)
            for ax in range(3):
                lo[ax] = min(lo[ax], v[a, ax])
                hi[ax] = max(hi[ax], v[a, ax])
    vol = 1.0
    for ax in range(3):
        vol *= max(hi[ax] - lo[ax], 1e-12)
    return max(per_edge * total / (3 * m), (vol / (per_face * m)) ** (1.0 / 3.0), 1e-12)


@njit(cache=True)
def face_grid(v, faces, h):  # pragma: no cover - compiled
    """The faces binned in a uniform grid of cell size ``h``: each face in every cell its bounding box meets.

    Returns the grid's origin ``(3,)``, its cell counts ``(3,)``, the first entry of each cell
    ``(c + 1,)``, the faces cell after cell ``(e,)`` and their bounding boxes ``(e, 6)`` (min then
    max; stored with the entries, so a cell's search reads them in a row).
    """
    m = len(faces)
    lo = np.full(3, np.inf)
    hi = np.full(3, -np.inf)
    fbox = np.empty((m, 6))
    for f in range(m):
        for ax in range(3):
            a, b, c = v[faces[f, 0], ax], v[faces[f, 1], ax], v[faces[f, 2], ax]
            fbox[f, ax] = min(a, min(b, c))
            fbox[f, 3 + ax] = max(a, max(b, c))
            lo[ax] = min(lo[ax], fbox[f, ax])
            hi[ax] = max(hi[ax], fbox[f, 3 + ax])
    dims = _grid_dims(lo, hi, m, h)
    count = np.zeros(dims[0] * dims[1] * dims[2] + 1, np.int64)
    cells = np.empty((m, 6), np.int64)          # each face's cell range
    for f in range(m):
        for ax in range(3):
            cells[f, ax] = min(int((fbox[f, ax] - lo[ax]) / h), dims[ax] - 1)
            cells[f, 3 + ax] = min(int((fbox[f, 3 + ax] - lo[ax]) / h), dims[ax] - 1)
        for i in range(cells[f, 0], cells[f, 3] + 1):
            for j in range(cells[f, 1], cells[f, 4] + 1):
                for k in range(cells[f, 2], cells[f, 5] + 1):
                    count[(i * dims[1] + j) * dims[2] + k + 1] += 1
    for c in range(1, len(count)):
        count[c] += count[c - 1]
    fill = count[:-1].copy()
    out = np.empty(count[-1], np.int64)
    ebox = np.empty((count[-1], 6))
    for f in range(m):
        for i in range(cells[f, 0], cells[f, 3] + 1):
            for j in range(cells[f, 1], cells[f, 4] + 1):
                for k in range(cells[f, 2], cells[f, 5] + 1):
                    c = (i * dims[1] + j) * dims[2] + k
                    out[fill[c]] = f
                    ebox[fill[c]] = fbox[f]
                    fill[c] += 1
    return lo, dims, count, out, ebox


@njit(cache=True, inline="always")
def _cell_faces_nearest(px, py, pz, v, faces, start, entries, fbox, c, best, bf, bx, by, bz,
                        sec):  # pragma: no cover - compiled
    """:func:`_grid_nearest`'s search of cell ``c``'s faces: the best so far and the bound of the others updated."""
    for e in range(start[c], start[c + 1]):
        f = entries[e]
        if f == bf:
            continue
        db = _box_sq(px, py, pz, fbox, e)
        if db > best:
            sec = min(sec, db)
            continue
        a, b, cc = faces[f, 0], faces[f, 1], faces[f, 2]
        d2, qx, qy, qz = _triangle_closest(px, py, pz, v[a, 0], v[a, 1], v[a, 2], v[b, 0], v[b, 1],
                                           v[b, 2], v[cc, 0], v[cc, 1], v[cc, 2])
        if d2 < best or (bf < 0 and d2 <= best):
            if bf >= 0:
                sec = min(sec, best)
            best, bf, bx, by, bz = d2, f, qx, qy, qz
        else:
            sec = min(sec, d2)
    return best, bf, bx, by, bz, sec


@njit(cache=True, inline="always")
def _grid_nearest(px, py, pz, v, faces, lo, dims, h, start, entries, fbox, best, warm0, warm1):  # pragma: no cover
    """The face closest to p within squared distance ``best`` (exact), trying faces ``warm0, warm1`` first (-1: none).

    The cells are searched in shells about p's cell (clamped to the grid), each cell and face
    skipped when its box is farther than the best so far, until a shell's cells all lie farther
    (those ``s`` cells out are at least ``(s - 1) h`` away). Returns the squared distance, the face
    (-1 if none within), the closest point and a lower bound of the squared distance of every
    other face (the faces tested, the boxes of those skipped, the shells not searched).
    """
    bf = -1
    bx, by, bz = 0.0, 0.0, 0.0
    sec = np.inf
    for w in (warm0, warm1):
        if w >= 0 and w != bf:
            a, b, c = faces[w, 0], faces[w, 1], faces[w, 2]
            d2, qx, qy, qz = _triangle_closest(px, py, pz, v[a, 0], v[a, 1], v[a, 2], v[b, 0], v[b, 1], v[b, 2],
                                               v[c, 0], v[c, 1], v[c, 2])
            if d2 < best or (bf < 0 and d2 <= best):
                if bf >= 0:
                    sec = min(sec, best)
                best, bf, bx, by, bz = d2, w, qx, qy, qz
            else:
                sec = min(sec, d2)
    ci = min(max(int(np.floor(max(min((px - lo[0]) / h, 1e9), -1e9))), 0), dims[0] - 1)
    cj = min(max(int(np.floor(max(min((py - lo[1]) / h, 1e9), -1e9))), 0), dims[1] - 1)
    ck = min(max(int(np.floor(max(min((pz - lo[2]) / h, 1e9), -1e9))), 0), dims[2] - 1)
    if bf < 0:
        # no start: first the face of p's cell whose box centre is nearest (the best then bounds the rest)
        oc = (ci * dims[1] + cj) * dims[2] + ck
        near, dn = -1, np.inf
        for e in range(start[oc], start[oc + 1]):
            ex = 0.5 * (fbox[e, 0] + fbox[e, 3]) - px
            ey = 0.5 * (fbox[e, 1] + fbox[e, 4]) - py
            ez = 0.5 * (fbox[e, 2] + fbox[e, 5]) - pz
            if ex * ex + ey * ey + ez * ez < dn:
                near, dn = entries[e], ex * ex + ey * ey + ez * ez
        if near >= 0:
            a, b, c = faces[near, 0], faces[near, 1], faces[near, 2]
            d2, qx, qy, qz = _triangle_closest(px, py, pz, v[a, 0], v[a, 1], v[a, 2], v[b, 0], v[b, 1], v[b, 2],
                                               v[c, 0], v[c, 1], v[c, 2])
            if d2 <= best:
                best, bf, bx, by, bz = d2, near, qx, qy, qz
            else:
                sec = min(sec, d2)
    top = max(dims[0], max(dims[1], dims[2]))
    for sh in range(top):
        gap = (sh - 1) * h
        if sh > 1 and gap * gap > best:
            sec = min(sec, gap * gap)
            break
        for i in range(max(ci - sh, 0), min(ci + sh, dims[0] - 1) + 1):
            dx = max(lo[0] + i * h - px, 0.0, px - (lo[0] + (i + 1) * h))
            if dx * dx > best:
                sec = min(sec, dx * dx)
                continue
            for j in range(max(cj - sh, 0), min(cj + sh, dims[1] - 1) + 1):
                dy = max(lo[1] + j * h - py, 0.0, py - (lo[1] + (j + 1) * h))
                if dx * dx + dy * dy > best:
                    sec = min(sec, dx * dx + dy * dy)
                    continue
                edge_ij = abs(i - ci) == sh or abs(j - cj) == sh
                k = max(ck - sh, 0)
                while k <= min(ck + sh, dims[2] - 1):
                    dz = max(lo[2] + k * h - pz, 0.0, pz - (lo[2] + (k + 1) * h))
                    dc = dx * dx + dy * dy + dz * dz
                    if dc <= best:
                        best, bf, bx, by, bz, sec = _cell_faces_nearest(px, py, pz, v, faces, start, entries, fbox,
                                                                        (i * dims[1] + j) * dims[2] + k, best, bf,
                                                                        bx, by, bz, sec)
                    else:
                        sec = min(sec, dc)
                    # inside the shell only its two faces in k
                    k = k + 1 if edge_ij or k == ck + sh else ck + sh
    return best, bf, bx, by, bz, sec


@njit(cache=True)
def mesh_closest(v, faces, lo, dims, h, start, entries, fbox, clo, cdims, ch, cstart, centries, cfbox, points,
                 reach):  # pragma: no cover - compiled
    """Closest points on the mesh (exact): distances, faces and points, ``MeshTree.query``'s search.

    Each point is searched first on the fine grid of :func:`face_grid` within ``reach`` (from the
    previous point's face), and only where no face lies that near on the coarse grid (the same
    faces binned in larger cells), so a point far from the mesh visits few cells. Every face
    within the distance found is tested (its box first), so the distance is exact; of faces at
    the same distance the first found is kept. With no face at all: inf, -1 and zeros.
    """
    q = len(points)
    dist = np.full(q, np.inf)
    face = np.full(q, -1, np.int64)
    cp = np.zeros((q, 3))
    last = -1
    r2 = reach * reach
    for p in range(q):
        px, py, pz = points[p, 0], points[p, 1], points[p, 2]
        d2, f, x, y, z, _ = _grid_nearest(px, py, pz, v, faces, lo, dims, h, start, entries, fbox, r2, last, -1)
        if f < 0:
            d2, f, x, y, z, _ = _grid_nearest(px, py, pz, v, faces, clo, cdims, ch, cstart, centries, cfbox, np.inf,
                                              last, -1)
        if f >= 0:
            dist[p], face[p] = np.sqrt(d2), f
            cp[p, 0], cp[p, 1], cp[p, 2] = x, y, z
            last = f
    return dist, face, cp


@njit(cache=True)
def mesh_closest_within(v, faces, lo, dims, h, start, entries, fbox, points, bound):  # pragma: no cover - compiled
    """Closest points on the mesh within ``bound`` (exact there): :func:`mesh_closest` pruned from the start.

    Only the fine grid's cells within ``bound`` of a point are searched (the previous point's face
    first), so a point far from the mesh costs a few cells. A point whose distance, computed as
    :func:`mesh_closest` computes it, is at most ``bound`` gets the same distance and a face at
    it; any other point gets inf, -1 and zeros.
    """
    q = len(points)
    dist = np.full(q, np.inf)
    face = np.full(q, -1, np.int64)
    cp = np.zeros((q, 3))
    last = -1
    r2 = bound * bound * (1.0 + 1e-12)      # a margin over the squared bound's round-off; cut below
    for p in range(q):
        px, py, pz = points[p, 0], points[p, 1], points[p, 2]
        d2, f, x, y, z, _ = _grid_nearest(px, py, pz, v, faces, lo, dims, h, start, entries, fbox, r2, last, -1)
        if f >= 0:
            last = f
            d = np.sqrt(d2)
            if d <= bound:
                dist[p], face[p] = d, f
                cp[p, 0], cp[p, 1], cp[p, 2] = x, y, z
    return dist, face, cp


@njit(cache=True, inline="always")
def _on_boundary(v, bnd, f, cx, cy, cz):  # pragma: no cover - compiled
    """Whether the closest point ``c`` on face ``f`` lies on one of its boundary edges (``bnd (m, 3, 2)``, -1 inner).

    As :meth:`~auszug.sweeps.patches.MeshTree.interior_distance`: within 1e-9 of the edge.
    """
    for e in range(3):
        i0, i1 = bnd[f, e, 0], bnd[f, e, 1]
        if i0 < 0:
            continue
        abx, aby, abz = v[i1, 0] - v[i0, 0], v[i1, 1] - v[i0, 1], v[i1, 2] - v[i0, 2]
        w = abx * abx + aby * aby + abz * abz
        t = ((cx - v[i0, 0]) * abx + (cy - v[i0, 1]) * aby + (cz - v[i0, 2]) * abz) / (w if w > 0 else 1.0)
        t = min(max(t, 0.0), 1.0)
        gx, gy, gz = cx - (v[i0, 0] + t * abx), cy - (v[i0, 1] + t * aby), cz - (v[i0, 2] + t * abz)
        if np.sqrt(gx * gx + gy * gy + gz * gz) <= 1e-9:
            return True
    return False


@njit(cache=True, inline="always")
def _at_boundary_vertex(v, faces, bvert, f, cx, cy, cz):  # pragma: no cover - compiled
    """Whether the closest point ``c`` on face ``f`` lies within 1e-9 of a corner that is a boundary vertex."""
    for k in range(3):
        i = faces[f, k]
        if bvert[i]:
            gx, gy, gz = cx - v[i, 0], cy - v[i, 1], cz - v[i, 2]
            if np.sqrt(gx * gx + gy * gy + gz * gz) <= 1e-9:
                return True
    return False


@njit(cache=True, inline="always")
def _cells_near(px, py, pz, r, lo, dims, h):  # pragma: no cover - compiled
    """The cells of a uniform grid (origin ``lo``, cell ``h``, ``dims`` cells) the box ``p +- r`` meets, clamped.

    Returns ``i0, i1, j0, j1, k0, k1`` (inclusive). A coordinate more than 1e9 cells off the grid is
    taken as 1e9 cells off before it is turned into an index.
    """
    i0 = min(max(int(np.floor(max(min((px - r - lo[0]) / h, 1e9), -1e9))), 0), dims[0] - 1)
    i1 = min(max(int(np.floor(max(min((px + r - lo[0]) / h, 1e9), -1e9))), 0), dims[0] - 1)
    j0 = min(max(int(np.floor(max(min((py - r - lo[1]) / h, 1e9), -1e9))), 0), dims[1] - 1)
    j1 = min(max(int(np.floor(max(min((py + r - lo[1]) / h, 1e9), -1e9))), 0), dims[1] - 1)
    k0 = min(max(int(np.floor(max(min((pz - r - lo[2]) / h, 1e9), -1e9))), 0), dims[2] - 1)
    k1 = min(max(int(np.floor(max(min((pz + r - lo[2]) / h, 1e9), -1e9))), 0), dims[2] - 1)
    return i0, i1, j0, j1, k0, k1


@njit(cache=True, inline="always")
def _grid_within(px, py, pz, v, faces, lo, dims, h, start, entries, fbox, r2, warm):  # pragma: no cover - compiled
    """Whether some face of the grid of :func:`face_grid` lies within squared distance ``r2`` of p (``warm`` first).

    Returns the face found (-1 for none): the first within, not the closest.
    """
    if warm >= 0:
        a, b, c = faces[warm, 0], faces[warm, 1], faces[warm, 2]
        d2, _, _, _ = _triangle_closest(px, py, pz, v[a, 0], v[a, 1], v[a, 2], v[b, 0], v[b, 1], v[b, 2],
                                        v[c, 0], v[c, 1], v[c, 2])
        if d2 <= r2:
            return warm
    i0, i1, j0, j1, k0, k1 = _cells_near(px, py, pz, np.sqrt(r2), lo, dims, h)
    for i in range(i0, i1 + 1):
        for j in range(j0, j1 + 1):
            for k in range(k0, k1 + 1):
                cell = (i * dims[1] + j) * dims[2] + k
                for e in range(start[cell], start[cell + 1]):
                    if _box_sq(px, py, pz, fbox, e) > r2:
                        continue
                    f = entries[e]
                    a, b, c = faces[f, 0], faces[f, 1], faces[f, 2]
                    d2, _, _, _ = _triangle_closest(px, py, pz, v[a, 0], v[a, 1], v[a, 2], v[b, 0], v[b, 1],
                                                    v[b, 2], v[c, 0], v[c, 1], v[c, 2])
                    if d2 <= r2:
                        return f
    return -1


@njit(cache=True)
def interior_max(v, faces, bnd, bvert, lo, dims, h, start, entries, fbox, clo, cdims, ch, cstart, centries, cfbox,
                 points, tol, reach):  # pragma: no cover - compiled
    """The largest distance of ``points`` to the mesh as ``MeshTree.interior_distance`` counts it, with fewer searches.

    A point whose closest point lies on a boundary edge of the mesh (``bnd``) or within 1e-9 of a
    boundary vertex (``bvert (n,)``: whichever face of the vertex the search found) counts 0; one within ``tol``
    its distance; one farther is left to the caller (its reciprocal test needs the swept
    surface): returned with its distance and closest point. Once the largest distance counted so
    far is ``e``, a point with some face within ``e`` (the previous point's face tried first)
    cannot raise it and is not searched further; every other point is searched exactly
    (:func:`mesh_closest`'s search). So the largest distance is the one of searching every point.

    Returns the largest distance counted, and the indices ``(k,)``, distances ``(k,)``, closest
    points ``(k, 3)`` and the faces found ``(k,)`` of the points left to the caller.
    """
    q = len(points)
    err = 0.0
    idx = np.empty(q, np.int64)
    dd = np.empty(q)
    cp = np.empty((q, 3))
    ff = np.empty(q, np.int64)
    nd = 0
    last = -1
    r2 = reach * reach
    for p in range(q):
        px, py, pz = points[p, 0], points[p, 1], points[p, 2]
        if err > 0.0:
            f = _grid_within(px, py, pz, v, faces, lo, dims, h, start, entries, fbox, err * err, last)
            if f >= 0:
                last = f
                continue
        d2, f, x, y, z, _ = _grid_nearest(px, py, pz, v, faces, lo, dims, h, start, entries, fbox, r2, last, -1)
        if f < 0:
            d2, f, x, y, z, _ = _grid_nearest(px, py, pz, v, faces, clo, cdims, ch, cstart, centries, cfbox, np.inf,
                                              last, -1)
        if f < 0:
            continue
        last = f
        d = np.sqrt(d2)
        if _on_boundary(v, bnd, f, x, y, z) or _at_boundary_vertex(v, faces, bvert, f, x, y, z):
            continue
        if d <= tol:
            err = max(err, d)
        else:
            idx[nd], dd[nd] = p, d
            cp[nd, 0], cp[nd, 1], cp[nd, 2] = x, y, z
            ff[nd] = f
            nd += 1
    return err, idx[:nd], dd[:nd], cp[:nd], ff[:nd]


@njit(cache=True)
def _solve3(a, b, out):  # pragma: no cover - compiled
    """``out = a^-1 b`` for a symmetric positive definite ``a (3, 3)`` (Cholesky)."""
    l00 = np.sqrt(a[0, 0])
    l10 = a[1, 0] / l00
    l20 = a[2, 0] / l00
    l11 = np.sqrt(a[1, 1] - l10 * l10)
    l21 = (a[2, 1] - l20 * l10) / l11
    l22 = np.sqrt(a[2, 2] - l20 * l20 - l21 * l21)
    y0 = b[0] / l00
    y1 = (b[1] - l10 * y0) / l11
    y2 = (b[2] - l20 * y0 - l21 * y1) / l22
    out[2] = y2 / l22
    out[1] = (y1 - l21 * out[2]) / l11
    out[0] = (y0 - l10 * out[1] - l20 * out[2]) / l00


@njit(cache=True)
def twist_steps(profile, r, t, n0, c0, rho, steps, bound, tol, warm_in, v, faces, bnd, lo, dims, h, start, entries,
                fbox):  # pragma: no cover - compiled
    """``steps`` point-to-plane steps of every knot's map about its profile plane (``general._twist_steps``).

    Per knot and step: the moved profile's points ``x_j`` within ``bound`` of the mesh whose closest
    point is not on its boundary (or on the mesh), their closest points ``q_j`` and unit face
    normals ``m_j``; the turn ``a`` about the plane's normal ``n = R n0`` through ``c = R c0 + T`` and
    the shift ``(u, v)`` in the plane minimising ``sum (m_j . (x_j - q_j + a n x (x_j - c) + u e_1 +
    v e_2))^2``, damped by 1e-3 of the mean eigenvalue; no step with fewer than 6 points. A knot
    whose step moves its points by at most about ``tol`` (``|a| rho``, ``|u|``, ``|v|`` all within)
    takes no more steps. Closest points on the grid of :func:`face_grid` (exact), each from the
    point's face of the step before (at the first, ``warm_in (k, n)``, -1 for none, and the
    previous point's face); where a point has moved since its last search by less than half the
    gap between its distance then and the bound of every other face's, that face is still the
    closest and the only one tested.

    Returns the maps ``r (k, 3, 3)``, ``t (k, 3)``, upper bounds ``(k, n)`` of the moved points'
    distances to the mesh at the returned maps (the last step's distance plus how far the step
    moved the point; inf where no face was within ``bound``) and the points' last closest faces
    ``(k, n)`` (-1 for none).
    """
    k, n = r.shape[0], profile.shape[0]
    r = r.copy()
    t = t.copy()
    upper = np.full((k, n), np.inf)
    last = warm_in.copy()
    x = np.empty((n, 3))
    dq = np.empty(n)
    b2 = bound * bound
    xr = np.empty((n, 3))
    dr = np.empty(n)
    lr = np.empty(n)
    ref_ok = np.zeros(n, np.bool_)
    for kn in range(k):
        warm = last[kn]
        ref_ok[:] = False
        for s in range(steps):
            nn = np.empty(3)
            cc = np.empty(3)
            for i in range(3):
                nn[i] = r[kn, i, 0] * n0[0] + r[kn, i, 1] * n0[1] + r[kn, i, 2] * n0[2]
                cc[i] = r[kn, i, 0] * c0[0] + r[kn, i, 1] * c0[1] + r[kn, i, 2] * c0[2] + t[kn, i]
            # a unit vector in the plane: n x the axis least along n
            ax = 0
            for i in range(1, 3):
                if abs(nn[i]) < abs(nn[ax]):
                    ax = i
            ex = np.zeros(3)
            ex[ax] = 1.0
            e1 = np.array([nn[1] * ex[2] - nn[2] * ex[1], nn[2] * ex[0] - nn[0] * ex[2], nn[0] * ex[1] - nn[1] * ex[0]])
            e1 /= np.sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2])
            e2 = np.array([nn[1] * e1[2] - nn[2] * e1[1], nn[2] * e1[0] - nn[0] * e1[2], nn[0] * e1[1] - nn[1] * e1[0]])
            ata = np.zeros((3, 3))
            atb = np.zeros(3)
            used = 0
            for p in range(n):
                for i in range(3):
                    x[p, i] = r[kn, i, 0] * profile[p, 0] + r[kn, i, 1] * profile[p, 1] + r[kn, i, 2] * profile[p, 2] \
                        + t[kn, i]
                f = -1
                if ref_ok[p]:
                    # the face found last is still the closest while the point has moved by less than half the
                    # gap between its distance and the bound of every other face's then (one face tested)
                    mv = np.sqrt((x[p, 0] - xr[p, 0]) ** 2 + (x[p, 1] - xr[p, 1]) ** 2 + (x[p, 2] - xr[p, 2]) ** 2)
                    if dr[p] + 2.0 * mv + 1e-12 < lr[p]:
                        wf = warm[p]
                        a, b, c = faces[wf, 0], faces[wf, 1], faces[wf, 2]
                        d2, qx, qy, qz = _triangle_closest(x[p, 0], x[p, 1], x[p, 2], v[a, 0], v[a, 1], v[a, 2],
                                                           v[b, 0], v[b, 1], v[b, 2], v[c, 0], v[c, 1], v[c, 2])
                        f = wf if d2 <= b2 else -2
                if f == -1:
                    d2, f, qx, qy, qz, sec = _grid_nearest(x[p, 0], x[p, 1], x[p, 2], v, faces, lo, dims, h, start,
                                                           entries, fbox, b2, warm[p], warm[p - 1] if p > 0 else -1)
                    ref_ok[p] = f >= 0
                    if f >= 0:
                        xr[p, 0], xr[p, 1], xr[p, 2] = x[p, 0], x[p, 1], x[p, 2]
                        dr[p], lr[p] = np.sqrt(d2), np.sqrt(sec)
                elif f == -2:
                    f = -1
                dq[p] = np.sqrt(d2) if f >= 0 else np.inf
                if f < 0:
                    continue
                warm[p] = f
                if d2 > 0.0 and _on_boundary(v, bnd, f, qx, qy, qz):
                    continue
                a, b, c = faces[f, 0], faces[f, 1], faces[f, 2]
                ux, uy, uz = v[b, 0] - v[a, 0], v[b, 1] - v[a, 1], v[b, 2] - v[a, 2]
                wx, wy, wz = v[c, 0] - v[a, 0], v[c, 1] - v[a, 1], v[c, 2] - v[a, 2]
                mx, my, mz = uy * wz - uz * wy, uz * wx - ux * wz, ux * wy - uy * wx
                ml = max(np.sqrt(mx * mx + my * my + mz * mz), 1e-300)
                mx, my, mz = mx / ml, my / ml, mz / ml
                rx, ry, rz = x[p, 0] - cc[0], x[p, 1] - cc[1], x[p, 2] - cc[2]
                # m . (n x (x - c)) / rho, m . e1, m . e2
                row0 = (mx * (nn[1] * rz - nn[2] * ry) + my * (nn[2] * rx - nn[0] * rz)
                        + mz * (nn[0] * ry - nn[1] * rx)) / rho
                row1 = mx * e1[0] + my * e1[1] + mz * e1[2]
                row2 = mx * e2[0] + my * e2[1] + mz * e2[2]
                rhs = -(mx * (x[p, 0] - qx) + my * (x[p, 1] - qy) + mz * (x[p, 2] - qz))
                row = (row0, row1, row2)
                for i in range(3):
                    for j in range(3):
                        ata[i, j] += row[i] * row[j]
                    atb[i] += row[i] * rhs
                used += 1
            u = np.zeros(3)
            if used >= 6:
                lam = 1e-3 * (ata[0, 0] + ata[1, 1] + ata[2, 2]) / 3 + 1e-300
                for i in range(3):
                    ata[i, i] += lam
                _solve3(ata, atb, u)
            w = np.empty((1, 3))
            for i in range(3):
                w[0, i] = nn[i] * (u[0] / rho)
            turn = rotations_of(w)[0]
            nr = turn @ r[kn]
            tc = t[kn] - cc
            for i in range(3):
                t[kn, i] = turn[i, 0] * tc[0] + turn[i, 1] * tc[1] + turn[i, 2] * tc[2] + cc[i] + u[1] * e1[i] \
                    + u[2] * e2[i]
            r[kn] = nr
            done = abs(u[0]) <= tol and abs(u[1]) <= tol and abs(u[2]) <= tol
            if done or s == steps - 1:
                for p in range(n):
                    if np.isfinite(dq[p]):
                        mv = 0.0
                        for i in range(3):
                            y = r[kn, i, 0] * profile[p, 0] + r[kn, i, 1] * profile[p, 1] \
                                + r[kn, i, 2] * profile[p, 2] + t[kn, i]
                            mv += (y - x[p, i]) ** 2
                        upper[kn, p] = dq[p] + np.sqrt(mv)
            if done:
                break
    return r, t, upper, last


@njit(cache=True, inline="always")
def _flags_within(px, py, pz, r, v, faces, lo, dims, h, start, entries, fbox, flag):  # pragma: no cover - compiled
    """The least squared distance of the faces near p, and whether a flagged and an unflagged face lie within ``r``.

    Every face of the cells the box ``p +- r`` meets (a margin wider) is tested; the least squared
    distance is over those whose box is within that (inf if none).
    """
    rc = r * (1 + 1e-9) + 1e-12         # the cells: a margin more (a face's cells are found by the same floors)
    i0, i1, j0, j1, k0, k1 = _cells_near(px, py, pz, rc, lo, dims, h)
    r2 = rc * rc
    best = np.inf
    seen_on, seen_off = False, False
    for i in range(i0, i1 + 1):
        for j in range(j0, j1 + 1):
            for k in range(k0, k1 + 1):
                c = (i * dims[1] + j) * dims[2] + k
                for e in range(start[c], start[c + 1]):
                    if _box_sq(px, py, pz, fbox, e) > r2:
                        continue
                    f = entries[e]
                    a, b, cc = faces[f, 0], faces[f, 1], faces[f, 2]
                    df = _triangle_closest(px, py, pz, v[a, 0], v[a, 1], v[a, 2], v[b, 0], v[b, 1], v[b, 2],
                                           v[cc, 0], v[cc, 1], v[cc, 2])[0]
                    best = min(best, df)
                    if np.sqrt(df) <= r:
                        if flag[f]:
                            seen_on = True
                        else:
                            seen_off = True
    return best, seen_on, seen_off


@njit(cache=True)
def grown_states(points, flag, v, faces, lo, dims, h, start, entries, fbox, margin):  # pragma: no cover - compiled
    """Whether every face nearest each point is flagged, none is, or both kinds are: ``(q,)`` of 1, 0, -1.

    The faces nearest a point are those within ``margin`` of its least distance to the mesh of
    :func:`face_grid` (exact): any closest-point search that breaks ties its own way (libigl's tree)
    answers one of them, so where they agree (1 or 0) its face's flag is known without it. A point
    on the mesh (a face within ``margin``: the ribs' points lie on cut curves) needs only the faces
    within ``2 margin`` (the nearest among them, and every face within the margin of it); else the
    exact search (:func:`_grid_nearest`, from the previous point's face) gives the least distance,
    and where the nearest face is nearer than every other by more than the margin (the search's
    bound of the rest) it alone decides; else the faces within the distance plus the margin are tested.
    """
    q = len(points)
    out = np.full(q, -1, np.int64)
    last = -1
    for p in range(q):
        px, py, pz = points[p, 0], points[p, 1], points[p, 2]
        # on the mesh: a face within the margin is among those within 2 margins, and then every face within the
        # margin of the nearest is too
        d0, on, off = _flags_within(px, py, pz, 2 * margin, v, faces, lo, dims, h, start, entries, fbox, flag)
        if np.sqrt(d0) > margin:
            d2, bf, _, _, _, sec = _grid_nearest(px, py, pz, v, faces, lo, dims, h, start, entries, fbox, np.inf,
                                                 last, -1)
            if bf < 0:
                continue
            last = bf
            r = np.sqrt(d2) + margin
            if sec > r * r:
                out[p] = 1 if flag[bf] else 0
                continue
            _, on, off = _flags_within(px, py, pz, r, v, faces, lo, dims, h, start, entries, fbox, flag)
        else:
            _, on, off = _flags_within(px, py, pz, np.sqrt(d0) + margin, v, faces, lo, dims, h, start, entries,
                                       fbox, flag)
        if on and not off:
            out[p] = 1
        elif off and not on:
            out[p] = 0
    return out


@njit(cache=True)
def knot_maps(knots, rotation, translation, t):  # pragma: no cover - compiled
    """:meth:`~auszug.sweeps.motion.Motion.at`'s maps at the knots and its intervals, without the screws between.

    Each parameter of ``t (q,)`` clamped to the knots' range, its interval ``i`` (the last knot at or
    before it, at most the last but one) and its fraction ``f = (t - t_i) / (t_{i+1} - t_i)``, as numpy
    computes them (``searchsorted(side="right") - 1``, clipped). Returns the maps ``R (q, 3, 3)``,
    ``T (q, 3)`` of the knot ``i`` (``i + 1`` where ``f >= 1``), and the parameters strictly inside an
    interval ``(p,)`` with their intervals ``(p,)`` and fractions ``(p,)``: those still need the screw.
    """
    q = len(t)
    k = len(knots)
    r = np.empty((q, 3, 3))
    tr = np.empty((q, 3))
    inner = np.empty(q, np.int64)
    ii = np.empty(q, np.int64)
    ff = np.empty(q)
    n_in = 0
    lo, hi = knots[0], knots[k - 1]
    for p in range(q):
        x = t[p]
        a, b = 0, k
        if x != x:          # nan: clip keeps it, searchsorted puts it last
            a = b = k
        else:
            x = min(max(x, lo), hi)
        # searchsorted(side="right"): the first knot greater than x
        while a < b:
            mid = (a + b) // 2
            if knots[mid] <= x:
                a = mid + 1
            else:
                b = mid
        i = min(max(a - 1, 0), k - 2)
        f = (x - knots[i]) / (knots[i + 1] - knots[i])
        j = i + 1 if f >= 1.0 else i
        r[p] = rotation[j]
        tr[p] = translation[j]
        if f > 0.0 and not f >= 1.0:
            inner[n_in], ii[n_in], ff[n_in] = p, i, f
            n_in += 1
    return r, tr, inner[:n_in], ii[:n_in], ff[:n_in]


@njit(cache=True)
def unit_face_normals(v, faces, face):  # pragma: no cover - compiled
    """Unit normals ``(k, 3)`` of the faces ``face (k,)``: numpy's ``cross(v1 - v0, v2 - v0)`` over its norm.

    The cross product as ``np.cross`` forms it (each component a product less a product, rounded in
    turn), the norm as ``np.linalg.norm(axis=1)`` (the squares summed in order), divided by it (at
    least 1e-300).
    """
    k = len(face)
    out = np.empty((k, 3))
    for i in range(k):
        f = face[i]
        a, b, c = faces[f, 0], faces[f, 1], faces[f, 2]
        a0, a1, a2 = v[b, 0] - v[a, 0], v[b, 1] - v[a, 1], v[b, 2] - v[a, 2]
        b0, b1, b2 = v[c, 0] - v[a, 0], v[c, 1] - v[a, 1], v[c, 2] - v[a, 2]
        p = a1 * b2
        q = a2 * b1
        n0 = p - q
        p = a2 * b0
        q = a0 * b2
        n1 = p - q
        p = a0 * b1
        q = a1 * b0
        n2 = p - q
        s = n0 * n0
        s = s + n1 * n1
        s = s + n2 * n2
        nn = np.sqrt(s)
        if nn < 1e-300:         # as np.maximum: nan stays nan
            nn = 1e-300
        out[i, 0], out[i, 1], out[i, 2] = n0 / nn, n1 / nn, n2 / nn
    return out


@njit(cache=True)
def rotation_defects(r):  # pragma: no cover - compiled
    """Per matrix of ``r (k, 3, 3)`` the largest entry of ``|R^T R - I|`` and the determinant ``(k,)`` each.

    The products summed in order, the determinant by cofactors along the first row (both within
    round-off of numpy's einsum and LU determinant: they are compared with tolerances of 1e-9).
    """
    k = len(r)
    err = np.empty(k)
    det = np.empty(k)
    for m in range(k):
        e = 0.0
        for i in range(3):
            for j in range(3):
                s = r[m, 0, i] * r[m, 0, j] + r[m, 1, i] * r[m, 1, j] + r[m, 2, i] * r[m, 2, j]
                e = max(e, abs(s - (1.0 if i == j else 0.0)))
        err[m] = e
        det[m] = (r[m, 0, 0] * (r[m, 1, 1] * r[m, 2, 2] - r[m, 1, 2] * r[m, 2, 1])
                  - r[m, 0, 1] * (r[m, 1, 0] * r[m, 2, 2] - r[m, 1, 2] * r[m, 2, 0])
                  + r[m, 0, 2] * (r[m, 1, 0] * r[m, 2, 1] - r[m, 1, 1] * r[m, 2, 0]))
    return err, det


@njit(cache=True)
def closest_on_planes(targets, pts, curve_start, curve_plane, curve_closed):  # pragma: no cover - compiled
    """:func:`closest_on_plane_curves` of each plane ``i`` with its own targets ``targets[i] (n, 3)``, all at once.

    Returns the distances ``(k, n)``, closest points ``(k, n, 3)`` and ends ``(k, n)`` of the ``k``
    planes, each as that function gives it.
    """
    k, n = targets.shape[0], targets.shape[1]
    dist = np.empty((k, n))
    cp = np.empty((k, n, 3))
    at_end = np.empty((k, n), np.bool_)
    for i in range(k):
        d, c, e = closest_on_plane_curves(targets[i], pts, curve_start, curve_plane, curve_closed, i)
        dist[i] = d
        cp[i] = c
        at_end[i] = e
    return dist, cp, at_end


# ------------------------------------------------------------------------------ kinematic parts


@njit(cache=True)
def fitting_block(ok, pos, min_width, starts):  # pragma: no cover - compiled
    """The largest all-True block of ``ok (k, n)`` by rows x summed column widths, first columns ``starts``.

    ``pos (n,)`` are the columns' places (the cumulated widths); a block of columns ``c0..c1`` is
    ``pos[c1] - pos[c0]`` wide and counts 0 below ``min_width``. Per first column, the columns
    after it are added one by one (the rows all True so far kept), the longest run of such rows
    (its first end) times the width is the block's area, and the columns stop where no row is
    left. The block of the largest area (the first of equal ones, columns then rows) is returned
    as ``r0, r1, c0, c1`` (inclusive), or -1s when every area is 0:
    :func:`~auszug.sweeps.parts.fitting_block`'s answer.
    """
    k, n = ok.shape
    acc = np.empty(k, np.bool_)
    best = 0.0
    out = (-1, -1, -1, -1)
    for s in range(len(starts)):
        c0 = starts[s]
        any_row = False
        for r in range(k):
            acc[r] = ok[r, c0]
            any_row = any_row or acc[r]
        if not any_row:
            continue
        for c1 in range(c0 + 1, n):
            run, top, end = 0, 0, -1
            for r in range(k):
                acc[r] = acc[r] and ok[r, c1]
                run = run + 1 if acc[r] else 0
                if run > top:
                    top, end = run, r
            if top == 0:
                break
            width = pos[c1] - pos[c0]
            area = top * width if width >= min_width else 0.0
            if area > best:
                best = area
                out = (end - top + 1, end, c0, c1)
    return out


# ------------------------------------------------------------------------------ edge lines


@njit(cache=True)
def straightest_next(dst, u, order, first, rev, cos_turn):  # pragma: no cover - compiled
    """Per directed edge ``i`` the edge out of its end that turns least from it (-1: none within the turn).

    ``dst (2k,)`` are the edges' ends, ``u (2k, 3)`` their unit directions, ``order`` the edges
    grouped by their start (``first (n + 1,)`` delimits each vertex's), ``rev`` each edge's reverse
    (never its own continuation). The largest cosine wins, the first in ``order`` of equal ones;
    it counts when at least ``cos_turn``. :func:`~auszug.sweeps.arcs.edge_lines`' first step.
    """
    n2 = len(dst)
    nxt = np.full(n2, -1, np.int64)
    for i in range(n2):
        b = dst[i]
        best_c = -np.inf
        best_j = -1
        for t in range(first[b], first[b + 1]):
            j = order[t]
            if j == rev[i]:
                continue
            # summed as numpy's einsum sums three products here, (x + z) + y: the numpy version's ties
            c = (u[i, 0] * u[j, 0] + u[i, 2] * u[j, 2]) + u[i, 1] * u[j, 1]
            if c > best_c:
                best_c, best_j = c, j
        if best_j >= 0 and best_c >= cos_turn:
            nxt[i] = best_j
    return nxt


@njit(cache=True)
def walk_lines(src, dst, nxt, rev, prev):  # pragma: no cover - compiled
    """The lines of the mutual continuations ``nxt``: vertices ``(v,)`` and each line's first entry ``(l + 1,)``.

    Lines start at the edges with no predecessor (``prev < 0``) in index order, then at every edge
    not yet on a line (the cycles); a line follows ``nxt`` until it ends or meets an edge seen, and
    an edge and its reverse are seen together. :func:`~auszug.sweeps.arcs.edge_lines`' second step.
    """
    n2 = len(src)
    seen = np.zeros(n2, np.bool_)
    verts = np.empty(n2 + 1, np.int64)
    offs = np.empty(n2 + 1, np.int64)
    nv, nl = 0, 0
    offs[0] = 0
    for stage in range(2):
        for s0 in range(n2):
            if seen[s0] or (stage == 0 and prev[s0] >= 0):
                continue
            verts[nv] = src[s0]
            nv += 1
            x = s0
            while x >= 0 and not seen[x]:
                seen[x] = True
                seen[rev[x]] = True
                verts[nv] = dst[x]
                nv += 1
                x = nxt[x]
            nl += 1
            offs[nl] = nv
    return verts[:nv], offs[:nl + 1]
