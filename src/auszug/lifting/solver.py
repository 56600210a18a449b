"""Least squares with equality constraints, all polynomials of degree <= 2, by Newton on the KKT system.

Every term of sketch lifting is a polynomial of degree at most two in the
unknowns (control points and plane normals): the fidelity terms are linear,
orthogonality and symmetry are dot products of two linear vectors, planarity
with a free normal is bilinear. :class:`Poly2` holds many such polynomials at
once in sparse coordinate form; :func:`solve` minimises
``sum_r w_r p_r(v)^2`` subject to ``q_k(v) = 0`` by Newton's method on the
Karush-Kuhn-Tucker system (exact Hessians of the energy and of the
constraints' Lagrangian term), globalised by a backtracking line
search on the l1 exact penalty merit function ``f + mu |q|_1`` with a
second-order correction, an inertia-free curvature test that regularises the
Hessian where it is not positive on the step, the paper's bound on the
multiplier increments (sec. 5.3), and a convergence test on the KKT residual.
The sparse system's pattern is built once per solve and only its values are
filled per step; it is solved by GMRES preconditioned with a sparse LDL^T
(QDLDL) of the system made quasi-definite, with SuperLU as the fallback
(:class:`_KKT`); patterns whose LDL^T in QDLDL's AMD ordering is costly are
factorised from their third Newton step on by our LDL^T
(:mod:`auszug.lifting._ldl`) in a METIS nested-dissection ordering where that
costs fewer multiply-adds (:class:`Orderings`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Callable

import numpy as np
import pymetis
import qdldl
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray
from scipy.sparse.linalg import splu

from auszug.lifting import _ldl

if TYPE_CHECKING:
    from auszug.lifting._ldl import LDL

__all__ = ["Orderings", "Poly2", "SolveResult", "solve"]

#: Factor by which the Hessian regularisation delta grows (negative curvature, short steps) or shrinks.
GROW = 10.0

Array = NDArray[np.float64]
Index = NDArray[np.intp]


@dataclass
class Poly2:
    """Many polynomials of degree <= 2 in ``n`` unknowns, in coordinate form.

    ``p_r(v) = const_r + sum(lin_val * v[lin_col]) + sum(bil_val * v[bil_i] * v[bil_j])``
    over the entries of row r.
    """

    n: int
    const: list[Array] = field(default_factory=list)
    weight: list[Array] = field(default_factory=list)
    lin: list[tuple[Index, Index, Array]] = field(default_factory=list)
    bil: list[tuple[Index, Index, Index, Array]] = field(default_factory=list)
    rows: int = 0
    _frozen: tuple | None = None

    def add(self, const: ArrayLike, weight: ArrayLike = 1.0, lin: tuple | None = None,
            bil: tuple | None = None) -> slice:
        """Add rows; ``lin = (row, col, val)`` and ``bil = (row, i, j, val)`` with rows local (0..m-1).

        Returns the slice of the new rows.
        """
        c = np.atleast_1d(np.asarray(const, dtype=float))
        m = len(c)
        self.const.append(c)
        self.weight.append(np.broadcast_to(np.asarray(weight, dtype=float), (m,)).copy())
        if lin is not None:
            r, col, val = (np.asarray(x).ravel() for x in lin)
            self.lin.append((r.astype(np.intp) + self.rows, col.astype(np.intp), val.astype(float)))
        if bil is not None:
            r, i, j, val = (np.asarray(x).ravel() for x in bil)
            self.bil.append((r.astype(np.intp) + self.rows, i.astype(np.intp), j.astype(np.intp),
                             val.astype(float)))
        out = slice(self.rows, self.rows + m)
        self.rows += m
        self._frozen = None
        return out

    def _arrays(self) -> tuple:
        if self._frozen is None:
            cat = np.concatenate
            c = cat(self.const) if self.const else np.zeros(0)
            w = cat(self.weight) if self.weight else np.zeros(0)
            if self.lin:
                lr, lc, lv = (cat([x[k] for x in self.lin]) for k in range(3))
            else:
                lr = lc = np.zeros(0, np.intp)
                lv = np.zeros(0)
            if self.bil:
                br, bi, bj, bv = (cat([x[k] for x in self.bil]) for k in range(4))
            else:
                br = bi = bj = np.zeros(0, np.intp)
                bv = np.zeros(0)
            A = sp.csr_matrix((lv, (lr, lc)), shape=(self.rows, self.n))
            self._frozen = (c, w, A, br, bi, bj, bv)
        return self._frozen

    @property
    def weights(self) -> Array:
        """The weight of every row, shape (rows,)."""
        return self._arrays()[1]

    def value(self, v: Array) -> Array:
        """p(v), shape (rows,)."""
        c, _, A, br, bi, bj, bv = self._arrays()
        out = c + A @ v
        if len(br):
            out += np.bincount(br, bv * v[bi] * v[bj], minlength=self.rows)
        return out

    def jacobian(self, v: Array) -> sp.csr_matrix:
        """dp/dv, shape (rows, n)."""
        _, _, A, br, bi, bj, bv = self._arrays()
        if not len(br):
            return A
        rr = np.concatenate([br, br])
        cc = np.concatenate([bi, bj])
        vv = np.concatenate([bv * v[bj], bv * v[bi]])
        return (A + sp.csr_matrix((vv, (rr, cc)), shape=(self.rows, self.n))).tocsr()

    def hessian(self, lam: Array) -> sp.csr_matrix:
        """sum_r lam_r d^2 p_r / dv^2, shape (n, n)."""
        _, _, _, br, bi, bj, bv = self._arrays()
        if not len(br):
            return sp.csr_matrix((self.n, self.n))
        val = lam[br] * bv
        return sp.csr_matrix((np.concatenate([val, val]), (np.concatenate([bi, bj]), np.concatenate([bj, bi]))),
                             shape=(self.n, self.n))


@dataclass(frozen=True)
class SolveResult:
    """The outcome of :func:`solve`.

    Attributes
    ----------
    v : (n,) ndarray
        The unknowns.
    lam : (k,) ndarray
        The constraints' Lagrange multipliers.
    energy : float
        sum w p^2 at ``v``.
    violation : float
        Largest absolute constraint residual at ``v``.
    iterations : int
        Newton steps taken (KKT factorisations, including regularised retries, are in ``factorisations``).
    converged : bool
        The KKT residual met the tolerances (or the iteration stalled at float resolution on a
        feasible point).
    stationarity : float
        Largest absolute entry of the Lagrangian's gradient ``g + Jq^T lam`` at ``v``.
    factorisations : int
        KKT factorisations done (LDL^T, or LU where the LDL^T failed).
    gave_up : bool
        The solve ended at its first step, which shortened to ``first_step_min`` did not
        decrease the merit (``v`` is ``v0``, not converged).
    """

    v: Array
    lam: Array
    energy: float
    violation: float
    iterations: int
    converged: bool
    stationarity: float = 0.0
    factorisations: int = 0
    gave_up: bool = False


def _pairs_in_rows(rows: Index) -> tuple[Index, Index]:
    """All ordered pairs (a, b) of entries sharing a row; ``rows`` (m,) sorted. Returns (p,) index arrays."""
    if not len(rows):
        z = np.zeros(0, np.intp)
        return z, z
    starts = np.flatnonzero(np.r_[True, rows[1:] != rows[:-1]])
    counts = np.diff(np.r_[starts, len(rows)])
    owner = np.repeat(np.arange(len(starts)), counts)           # the row block of every entry
    reps = counts[owner]                                         # each entry pairs with its block
    a = np.repeat(np.arange(len(rows)), reps)
    first = np.repeat(starts[owner], reps)
    offset = np.arange(len(a)) - np.repeat(np.cumsum(reps) - reps, reps)
    return a.astype(np.intp), (first + offset).astype(np.intp)


class _Jacobian:
    """The Jacobian of a :class:`Poly2` on a fixed pattern: unique (row, col) entries, values per ``v``."""

    def __init__(self, P: Poly2, rows: NDArray[np.bool_] | None = None) -> None:
        _, _, A, br, bi, bj, bv = P._arrays()
        Ac = A.tocoo()
        keep = np.ones(len(Ac.row), bool) if rows is None else rows[Ac.row]
        keepb = np.ones(len(br), bool) if rows is None else rows[br]
        self.br, self.bi, self.bj, self.bv = br[keepb], bi[keepb], bj[keepb], bv[keepb]
        self.lin_val = Ac.data[keep].astype(float)
        rr = np.concatenate([Ac.row[keep], self.br, self.br]).astype(np.intp)
        cc = np.concatenate([Ac.col[keep], self.bi, self.bj]).astype(np.intp)
        key = rr * max(P.n, 1) + cc
        uniq, self.inv = np.unique(key, return_inverse=True)
        self.row = (uniq // max(P.n, 1)).astype(np.intp)          # sorted by row, then column
        self.col = (uniq % max(P.n, 1)).astype(np.intp)
        self.n, self.size = P.n, len(uniq)

    def values(self, v: Array) -> Array:
        """The entries' values at ``v``, shape (size,)."""
        raw = np.concatenate([self.lin_val, self.bv * v[self.bj], self.bv * v[self.bi]])
        return np.asarray(np.bincount(self.inv, raw, minlength=self.size), dtype=float)

    def rmatvec(self, vals: Array, y: Array) -> Array:
        """J^T y with the entry values ``vals``, shape (n,)."""
        return np.asarray(np.bincount(self.col, vals * y[self.row], minlength=self.n), dtype=float)


class _Assembly:
    """The KKT matrix of one solve on a fixed sparsity pattern (built once, filled per Newton step).

    ``[[2 Jp^T W Jp + hessian_reg I + sum lam_k d2q_k + delta I, Jq^T], [Jq, -kkt_reg I]]`` in CSC
    form: the energy's rows without bilinear entries give a constant Gauss-Newton part; the others
    (soft cues with products) give the pairs of their Jacobian entries, refilled each step.
    """

    def __init__(self, energy: Poly2, constraints: Poly2, hessian_reg: float, kkt_reg: float) -> None:
        n, k = energy.n, constraints.rows
        self.n, self.k = n, k
        _, w, A, br, _, _, _ = energy._arrays()
        self.w = w
        curved = np.zeros(energy.rows, bool)
        curved[br] = True
        self.je = _Jacobian(energy)                                 # the whole energy Jacobian (gradient)
        lin_rows = sp.diags((~curved).astype(float) * w) if energy.rows else sp.csr_matrix((0, 0))
        G0 = (2.0 * (A.T @ lin_rows @ A)).tocoo() if energy.rows else sp.coo_matrix((n, n))
        self.g0 = G0.data
        self.jc = _Jacobian(energy, curved)                         # the rows with products
        self.pa, self.pb = _pairs_in_rows(self.jc.row)
        self.jq = _Jacobian(constraints)
        _, _, _, qr, qi, qj, qv = constraints._arrays()
        self.qr, self.qv = qr, qv
        diag = np.arange(n, dtype=np.intp)
        cdiag = np.arange(n, n + k, dtype=np.intp)
        _, _, _, er, ei, ej, ev = energy._arrays()
        self.er, self.ev = er, ev
        rows = np.concatenate([G0.row, self.jc.col[self.pa], n + self.jq.row, self.jq.col, qi, qj, ei, ej, diag,
                               cdiag])
        cols = np.concatenate([G0.col, self.jc.col[self.pb], self.jq.col, n + self.jq.row, qj, qi, ej, ei, diag,
                               cdiag])
        N = n + k
        key = cols.astype(np.int64) * N + rows
        uniq, self.inv = np.unique(key, return_inverse=True)
        self.indices = (uniq % N).astype(np.int32)
        self.indptr = np.r_[0, np.cumsum(np.bincount((uniq // N).astype(np.intp), minlength=N))].astype(np.int32)
        self.nnz, self.N = len(uniq), N
        self.reg = np.full(n, hessian_reg)
        self.creg = np.full(k, -kkt_reg)
        self.pair_w = 2.0 * w[self.jc.row[self.pa]] if len(self.pa) else np.zeros(0)
        self.diag = diag

    def matrix(self, jc: Array, jq: Array, lam: Array | None, delta: float, wp: Array) -> sp.csc_matrix:
        """The KKT matrix at one Newton step.

        ``jc``: the curved energy rows' Jacobian entries, ``jq``: the constraint Jacobian's, ``lam``:
        the multipliers weighting the constraints' Hessian (None: left out, Gauss-Newton), ``delta``:
        added to the energy block's diagonal.
        """
        hq = self.qv * lam[self.qr] if lam is not None else np.zeros(len(self.qv))
        he = 2.0 * self.ev * wp[self.er] if lam is not None else np.zeros(len(self.ev))
        vals = np.concatenate([self.g0, self.pair_w * jc[self.pa] * jc[self.pb], jq, jq, hq, hq, he, he,
                               self.reg + delta, self.creg])
        data = np.bincount(self.inv, vals, minlength=self.nnz)
        return sp.csc_matrix((data, self.indices, self.indptr), shape=(self.N, self.N))


#: Nested dissection is tried for patterns whose LDL^T in QDLDL's AMD ordering costs at least this many
#: multiply-adds (``sum(c_j^2)``; the 100-curve benchmark: 2.1M for the seed propagation, 74M for
#: the baseline, 53-68M for the parallel and orthogonal rounds, 28M and 84M for the planar rounds;
#: the first planar round's METIS ordering costs 36M, so it would only cost its 70-90 ms there).
ND_MIN_FLOPS = 4e7
#: The compiled LDL^T's time per multiply-add over QDLDL's: both 0.44 ns in the same (AMD) ordering
#: on the 100-curve benchmark's matrices; 0.50-0.53 ns in the nested-dissection orderings (9 ms for
#: 17.6M, 18 ms for 37M); the margin above 1 pays for the ordering (METIS 60-100 ms per pattern).
ND_SPEED = 1.2
#: A kept ordering serves a new pattern of the same size from its first factorisation while its
#: multiply-adds stay within this factor of those it had where it was chosen (the benchmark's
#: baseline ordering on its parallel and orthogonal rounds: 17.9-18.4M against 17.6-18.8M for
#: their own METIS orderings).
ND_REUSE = 1.1


class Orderings:
    """The nested-dissection orderings chosen during one lift, by matrix size, for the later solves.

    A METIS ordering of a KKT pattern costs 50-90 ms (10 000 unknowns); the solves of one lift
    share their unknowns, and so the baseline's ordering serves the rounds after it.
    ``min_flops`` and ``speed``: when nested dissection is tried and used (defaults
    ``ND_MIN_FLOPS``, ``ND_SPEED``; tests force it with 0 and 0).
    """

    def __init__(self, min_flops: float | None = None, speed: float | None = None) -> None:
        self._kept: dict[int, tuple[Index, float]] = {}
        self.min_flops = ND_MIN_FLOPS if min_flops is None else min_flops
        self.speed = ND_SPEED if speed is None else speed

    def get(self, size: int) -> tuple[Index, float] | None:
        """The ordering kept for matrices of ``size`` rows and its multiply-adds where chosen."""
        return self._kept.get(size)

    def put(self, size: int, perm: Index, flops: float) -> None:
        """Keep ``perm`` for matrices of ``size`` rows."""
        self._kept[size] = (perm, flops)

    @staticmethod
    def available() -> bool:
        """Whether the compiled LDL^T kernels (:mod:`auszug.lifting._ldl`, ``make install``) are built."""
        return _ldl.available


def _permuted_upper(indptr: NDArray[np.int32], indices: NDArray[np.int32],
                    perm: Index) -> tuple[Index, Index, Index]:
    """The upper triangle of ``A[perm][:, perm]`` from ``A``'s upper triangle (CSC ``indptr``, ``indices``).

    Returns its ``indptr``, ``indices`` (sorted in each column) and, per entry, the index of the
    same entry in ``A``'s upper triangle's data.
    """
    N = len(indptr) - 1
    iperm = np.empty(N, np.int64)
    iperm[perm] = np.arange(N)
    col = iperm[np.repeat(np.arange(N), np.diff(indptr))]
    row = iperm[indices]
    lo, hi = np.minimum(row, col), np.maximum(row, col)
    order = np.lexsort((lo, hi))
    Ap = np.zeros(N + 1, np.int64)
    np.cumsum(np.bincount(hi, minlength=N), out=Ap[1:])
    return Ap, np.ascontiguousarray(lo[order]), order


def _nested_dissection(indptr: NDArray[np.int32], indices: NDArray[np.int32]) -> Index:
    """METIS's nested-dissection ordering of the symmetric matrix with this upper triangle (CSC)."""
    N = len(indptr) - 1
    U = sp.csc_matrix((np.ones(len(indices)), indices, indptr), shape=(N, N))
    G = (U + U.T).tocsr()
    G.setdiag(0.0)
    G.eliminate_zeros()
    perm, _ = pymetis.nested_dissection(pymetis.CSRAdjacency(G.indptr, G.indices))
    return np.asarray(perm, dtype=np.int64)


class _KKT:
    """Factorises the KKT matrices ``K`` (N, N) of one solve (one sparsity pattern) and solves with them.

    The first choice is a sparse LDL^T without pivoting (QDLDL, AMD ordering; its symbolic
    factorisation is done once per pattern and reused by ``update``) of ``K`` made quasi-definite,
    ``K + diag(ldl_reg I_n, -ldl_reg I_k)`` (the energy block positive definite, the constraint
    block negative definite: such a matrix has an LDL^T for every symmetric ordering). That
    factorisation is the preconditioner of GMRES on ``K`` itself, so the solves are those of
    ``K`` (to a relative residual ``gmres_tol``, or at least ``1e-10``), not of the regularised
    matrix. Measured on the KKT matrices of the 96 x 4 vase grid (benchmarks/bench_lifting.py):
    0.35-0.57M non-zeros in L against 1.2M (baseline) and 8.9M (planar rounds) in SuperLU's L + U,
    a solve of 1 ms against 3-14 ms, 5-12 GMRES iterations per solve. Where the LDL^T fails (a
    zero pivot) or GMRES does not reach ``1e-10``, SuperLU factorises ``K`` (COLAMD, its column
    ordering reused for the later factorisations, scipy having no separate symbolic
    factorisation); ``ldl_reg <= 0`` uses SuperLU alone. With ``orderings`` (a lift's
    :class:`Orderings`), a pattern's third and later factorisations are our LDL^T
    (:mod:`auszug.lifting._ldl`, the same algorithm as QDLDL's) in a nested-dissection ordering
    where :meth:`_nd_try` finds it cheaper (lift-speed5: on the 100-curve benchmark L 0.41-0.48M
    -> 0.25M non-zeros, a factorisation 24-34 ms -> 9 ms, a solve 0.8 -> 0.55 ms).
    """

    def __init__(self, n: int, ldl_reg: float = 1e-7, gmres_tol: float = 1e-13, gmres_its: int = 30,
                 orderings: Orderings | None = None) -> None:
        self.n = n
        self.orderings = orderings
        self.nd: LDL | None = None        # the LDL^T in a nested-dissection ordering, once chosen
        self.nd_map: Index | None = None       # its permuted upper triangle's entries in ``U``'s data
        self.nd_tried = False
        self.ldl_count = 0                     # QDLDL factorisations of this pattern
        self.perm: NDArray[np.intp] | None = None
        self.count = 0
        self.lu_count = 0
        self.ldl: qdldl.Solver | None = None
        self.ldl_reg = ldl_reg
        self.gmres_tol = gmres_tol
        self.gmres_its = max(1, gmres_its)
        self.upper: NDArray[np.bool_] | None = None
        self.prec_solves = 0                   # preconditioner (LDL^T) solves, for the benchmarks

    def _ldl(self, K: sp.csc_matrix) -> Callable[..., Array] | None:
        """The preconditioned solver of ``K``, None where the LDL^T of the regularised ``K`` fails.

        The solver's optional second argument is GMRES's relative tolerance (default ``gmres_tol``).
        """
        N = K.shape[0]
        if self.upper is None:
            col = np.repeat(np.arange(N), np.diff(K.indptr))
            self.upper = K.indices <= col
            self.up_indptr = np.r_[0, np.cumsum(np.bincount(col[self.upper], minlength=N))].astype(np.int32)
            self.up_indices = K.indices[self.upper]
            self.up_diag = np.flatnonzero(self.up_indices == col[self.upper])
            self.sign = np.where(self.up_indices[self.up_diag] < self.n, 1.0, -1.0)
        data = K.data[self.upper]
        data[self.up_diag] += self.ldl_reg * self.sign
        prec: Callable[[Array], Array]
        if self.orderings is not None and not self.nd_tried and self.ldl_count == 0:
            self._nd_cached()
        if self.nd is not None and self.nd_map is not None:
            if not self.nd.factor(data[self.nd_map]):      # a zero pivot
                return None
            prec = self.nd.solve
        else:
            U = sp.csc_matrix((data, self.up_indices, self.up_indptr), shape=K.shape)
            try:
                if self.ldl is None:
                    self.ldl = qdldl.Solver(U, upper=True)
                else:
                    self.ldl.update(U, upper=True)
            except (ValueError, RuntimeError):   # QDLDL: "not quasi-definite" (a zero pivot)
                self.ldl = None
                return None
            self.ldl_count += 1
            prec = self.ldl.solve
            if self.orderings is not None and not self.nd_tried and self.ldl_count >= 2:
                self._nd_try()

        def solve_(b: Array, tol: float | None = None) -> Array:
            t = self.gmres_tol if tol is None else tol
            x, its = _gmres(K, prec, b, t, self.gmres_its, max(1e-10, t))
            self.prec_solves += its
            if x is None:
                raise _NotSolved
            return x

        return solve_

    def _nd_use(self, perm: Index) -> LDL:
        """The LDL^T of this pattern in the ordering ``perm`` (symbolic factorisation only)."""
        Ap, Ai, self.nd_map = _permuted_upper(self.up_indptr, self.up_indices, perm)
        return _ldl.LDL(perm, Ap, Ai)

    def _nd_cached(self) -> None:
        """At a pattern's first factorisation: the ordering kept for this size, if it fills as it did."""
        assert self.orderings is not None
        N = len(self.up_indptr) - 1
        kept = self.orderings.get(N)
        if kept is None:
            return
        perm, flops = kept
        nd = self._nd_use(perm)
        if nd.flops <= ND_REUSE * flops:
            self.nd, self.nd_tried = nd, True
        else:
            self.nd_map = None

    def _nd_try(self) -> None:
        """After a pattern's second QDLDL factorisation: switch to nested dissection where it pays.

        QDLDL's AMD ordering costs ``sum(c_j^2)`` multiply-adds (``c_j``: non-zeros of L's column
        j); the compiled LDL^T in the nested-dissection ordering (the kept one of this size, or a new
        METIS ordering) is used when its count times ``Orderings.speed`` is below that; nothing is
        tried below ``Orderings.min_flops``.
        """
        assert self.orderings is not None and self.ldl is not None
        self.nd_tried = True
        counts = np.diff(self.ldl.factors()[0].indptr).astype(float)
        amd = float(np.sum(counts * counts))
        if amd < self.orderings.min_flops:
            return
        N = len(self.up_indptr) - 1
        kept = self.orderings.get(N)
        if kept is not None:
            nd = self._nd_use(kept[0])
            if self.orderings.speed * nd.flops < amd:
                self.nd = nd
                return
        perm = _nested_dissection(self.up_indptr, self.up_indices)
        nd = self._nd_use(perm)
        if self.orderings.speed * nd.flops < amd:
            self.nd = nd
            self.orderings.put(N, perm, nd.flops)
        else:
            self.nd_map = None

    def _lu(self, K: sp.csc_matrix) -> Callable[[Array], Array]:
        """SuperLU's solver of ``K``."""
        self.lu_count += 1
        if self.perm is None or len(self.perm) != K.shape[0]:
            lu = splu(K, permc_spec="COLAMD")
            self.perm = np.asarray(lu.perm_c, dtype=np.intp)
            return lu.solve
        inv = np.empty_like(self.perm)
        inv[self.perm] = np.arange(len(self.perm))
        lu = splu(K[:, inv].tocsc(), permc_spec="NATURAL")
        perm = self.perm

        def solve_(b: Array) -> Array:
            return lu.solve(b)[perm]

        return solve_

    def factor(self, K: sp.csc_matrix) -> Callable[..., Array]:
        """A function solving ``K x = b`` for ``b`` (N,), returning ``x`` (N,).

        Its optional second argument is GMRES's relative tolerance for that solve (default
        ``gmres_tol``).
        """
        self.count += 1
        if self.ldl_reg > 0.0:
            fast = self._ldl(K)
            if fast is not None:
                state: dict[str, Callable[[Array], Array]] = {}

                def solve_(b: Array, tol: float | None = None) -> Array:
                    if "lu" not in state:
                        try:
                            return fast(b, tol)
                        except _NotSolved:
                            state["lu"] = self._lu(K)
                    return state["lu"](b)

                return solve_
        lu = self._lu(K)
        return lambda b, tol=None: lu(b)


class _NotSolved(Exception):
    """GMRES preconditioned by the LDL^T did not reach its tolerance."""


def _dot(a: Array, b: Array) -> float:
    """``a . b`` for (m,) arrays without BLAS.

    numpy's threaded OpenBLAS took 0.11 ms for one dot product of 10^4 entries on the 2 shared
    cores (load 2.6; 15 ms for 2.5 * 10^4 at load 5), against 0.007 ms on one thread: the merit
    evaluations of the line search spent more time in it than in the polynomials.
    """
    return float(np.sum(a * b))


def _norm(a: Array) -> float:
    """``|a|_2`` for an (m,) array without BLAS (see :func:`_dot`)."""
    return float(np.sqrt(np.sum(a * a)))


def _gmres(K: sp.csc_matrix, prec: Callable[[Array], Array], b: Array, tol: float, its: int,
           accept: float = 1e-10) -> tuple[Array | None, int]:
    """Right-preconditioned GMRES for ``K x = b`` from ``x0 = prec(b)``.

    Stops when the residual is below ``tol |b|_2`` or after ``its`` iterations (one restart-free
    cycle). Returns the solution, None if the residual is then above ``accept |b|_2`` (or not
    finite), and the number of preconditioner solves.
    """
    x = prec(b)
    if not np.all(np.isfinite(x)):
        return None, 1
    r = b - K @ x
    beta = _norm(r)
    bnorm = _norm(b)
    target = tol * bnorm
    if beta <= target:
        return x, 1
    N = len(b)
    V = np.empty((its + 1, N))      # rows written before they are read (no zeroing: 316 solves of the
    Z = np.empty((its, N))          # 100-curve lift zeroed 5 MB each)
    Hm = np.zeros((its + 1, its))
    cs = np.zeros(its)
    sn = np.zeros(its)
    e = np.zeros(its + 1)
    e[0] = beta
    V[0] = r / beta
    j = 0
    for j in range(its):
        Z[j] = prec(V[j])
        w = K @ Z[j]
        for _ in range(2):              # classical Gram-Schmidt, twice (no BLAS: see _norm)
            h = (V[:j + 1] * w).sum(axis=1)
            w -= (h[:, None] * V[:j + 1]).sum(axis=0)
            Hm[:j + 1, j] += h
        Hm[j + 1, j] = _norm(w)
        if Hm[j + 1, j] > 0:
            V[j + 1] = w / Hm[j + 1, j]
        else:
            V[j + 1] = 0.0
        for i in range(j):              # apply the earlier Givens rotations
            a, c = Hm[i, j], Hm[i + 1, j]
            Hm[i, j], Hm[i + 1, j] = cs[i] * a + sn[i] * c, -sn[i] * a + cs[i] * c
        rho = float(np.hypot(Hm[j, j], Hm[j + 1, j]))
        if rho == 0.0:
            return None, j + 2
        cs[j], sn[j] = Hm[j, j] / rho, Hm[j + 1, j] / rho
        Hm[j, j], Hm[j + 1, j] = rho, 0.0
        e[j + 1] = -sn[j] * e[j]
        e[j] = cs[j] * e[j]
        if abs(e[j + 1]) <= target:
            break
    if abs(e[j + 1]) > accept * bnorm:
        return None, j + 2
    m = j + 1
    y = np.linalg.solve(np.triu(Hm[:m, :m]), e[:m])
    x = x + (y[:, None] * Z[:m]).sum(axis=0)
    return (x if np.all(np.isfinite(x)) else None), j + 2


def solve(energy: Poly2, constraints: Poly2, v0: Array, lam0: Array | None = None, *, iterations: int = 60,
          tol: float = 1e-10, kkt_reg: float = 1e-11, hessian_reg: float = 1e-10,
          stat_tol: float = 1e-9, lam_bound: float = 1.0, soc_steps: int = 10, soc_rate: float = 0.5,
          step_growth: float = 2.0, ldl_reg: float = 1e-7, refine_steps: int = 1,
          stall_tol: float = 1e-6, soc_tol: float = 1e-8, refine_inexact: bool = True,
          orderings: Orderings | None = None, first_step_min: float = 0.0) -> SolveResult:
    """Minimise ``sum w_r p_r(v)^2`` subject to ``q(v) = 0`` from ``v0``.

    Each step solves the KKT system
    ``[[H + sum lam_k d2q_k + delta I, Jq^T], [Jq, -kkt_reg I]] [dv, lam'] = [-g, -q]``
    with the energy Hessian ``H = 2 Jp^T W Jp + 2 sum w_r p_r d2p_r + hessian_reg I``
    (the second term from the rows with products, soft orthogonality and
    symmetry; without it Newton converged only linearly there: an orthogonal
    round of a 30 x 4 vase grid stalled after 20 steps, 4 with it) and
    ``g = 2 Jp^T W p``. When the step's curvature ``dv^T (H + ...) dv`` is
    not positive (inertia-free test: a step that need not descend), both
    second-derivative terms are dropped for that step (Gauss-Newton SQP,
    positive semi-definite on the energy's own scale), and if that still fails
    ``delta I`` is added, growing tenfold; after a shortened Gauss-Newton
    step the next step starts with Gauss-Newton. *Measured*: adding ``delta I`` to the
    full Hessian alone settled at delta = 1 on a 30 x 4 vase grid and crawled
    (|dv| ~ 5e-4) for 60 steps; with the Gauss-Newton fallback that solve
    converged in 41 steps to a 5 times lower energy. The step
    length comes from backtracking (Armijo, factor 1/2) on the l1 merit
    ``f + mu |q|_1`` with ``mu`` above the largest multiplier, trying a
    second-order correction (the same factorisation, right-hand side
    ``[0, -q(v + dv)]``) when the trial step is refused, repeated (at most
    ``soc_steps``) while each reduces ``|q|_1`` by ``soc_rate`` (each solved to ``soc_tol``); after
    a shortened step the
    next Gauss-Newton line search starts at ``step_growth`` times that step's length (in the max
    norm), not at the full step (for full Newton steps, whose regularisation changes between
    steps, that cost a 30 x 4 planar round 19 -> 26 steps). A feasible Newton step below
    ``stall_tol`` that the line search shortens ends the solve with the full step (the merit's
    changes are then at its float resolution). The multipliers move
    by the same step length toward ``lam'``, the increment scaled down to at
    most ``lam_bound max(1, |lam|)`` (the paper's bounded multiplier steps,
    relative so that large multipliers are reached in a few steps).
    Converged: ``|q|_inf <= tol`` and either ``|g + Jq^T lam|_inf <= stat_tol`` or a Newton
    step below ``tol`` (taken; the KKT point is within ``tol``: near redundant constraints the
    stationarity residual stalls at the linear solve's rounding), or the line
    search finds no decrease (the merit's changes are below its float
    resolution, about 1e-13 for thousands of rows) while feasible and the
    Newton step is below ``stall_tol`` (1e-6 of the diagonal: the point is
    determined to that).

    Parameters
    ----------
    energy, constraints : Poly2
        The energy's residual rows (weighted) and the constraints (weights unused).
    v0 : (n,) ndarray
        Starting point; ``lam0`` (k,): starting multipliers (default 0).
    iterations : int
        Most Newton steps.
    tol, stat_tol : float
        Feasibility and stationarity tolerances (absolute; the lifting works at diagonal 1).
    stall_tol : float
        Largest remaining Newton step accepted as converged when the line search stalls.
    kkt_reg, hessian_reg : float
        ``-kkt_reg I`` in the constraint block (redundant constraints), ``hessian_reg I`` on the energy
        Hessian (directions no term sees).
    soc_steps, soc_rate : int, float
        Most second-order corrections per trial step; the least reduction of ``|q|_1`` by each.
    step_growth : float
        A Gauss-Newton line search after a shortened step starts at this times that step's length.
    ldl_reg : float
        The regularisation making the KKT matrix quasi-definite for its LDL^T, the preconditioner
        (the system solved is the one with ``-kkt_reg I``); 0: SuperLU alone.
    refine_steps : int
        Steps of iterative refinement from the solution with ``-kkt_reg I`` toward the one without.
    soc_tol : float
        GMRES's relative tolerance in the second-order corrections' solves (0: the steps' own
        ``1e-13``). A correction only proposes a trial point for the merit test, so it need not be
        exact (:class:`~auszug.lifting.params.LiftParams` has the measurements).
    refine_inexact : bool
        Solve each refinement step only to the step's own absolute accuracy: the relative
        tolerance ``1e-13 |rhs| / |residual|`` (at most 0.5) instead of ``1e-13``, since the
        residual the refinement corrects (the ``kkt_reg`` term) is 1e-15 to 1e-9 of the right-hand
        side. False: every refinement solve to ``1e-13`` relative.
    orderings : Orderings, optional
        Given (and ``pymetis`` and the compiled kernels installed): a pattern factorised more than
        twice whose LDL^T costs at least ``ND_MIN_FLOPS`` is factorised from then on by our LDL^T
        (:mod:`auszug.lifting._ldl`) in a nested-dissection ordering where that costs less
        (``ND_SPEED``), the ordering kept in ``orderings`` for the later solves of the same size.
        None: QDLDL's AMD ordering throughout.
    first_step_min : float
        When the first Newton step shortened to this fraction of it does not decrease the merit
        (with its second-order corrections; tried before the line search), the solve ends there
        (``v0``, not converged, ``gave_up``): a caller's early fallback for a solve that starts far
        from its quadratic model (0: never).

    Examples
    --------
    >>> import numpy as np
    >>> e = Poly2(2); _ = e.add([-1.0, -1.0], 1.0, lin=([0, 1], [0, 1], [1.0, 1.0]))  # (x-1)^2 + (y-1)^2
    >>> c = Poly2(2); _ = c.add([-0.5], bil=([0], [0], [1], [1.0]))                    # x y = 1/2
    >>> r = solve(e, c, np.array([1.0, 0.2]))
    >>> r.converged, np.round(r.v, 6).tolist()
    (True, [0.707107, 0.707107])
    """
    v = np.asarray(v0, dtype=float).copy()
    n = len(v)
    k = constraints.rows
    lam = np.zeros(k) if lam0 is None else np.asarray(lam0, dtype=float).copy()
    w = energy.weights
    asm = _Assembly(energy, constraints, hessian_reg, kkt_reg)
    zk = np.zeros(k)
    kkt = _KKT(n, ldl_reg, orderings=orderings if Orderings.available() else None)
    mu = 0.0
    delta = 0.0
    converged = False
    gave_up = False
    it = 0
    stat = np.inf
    sticky = False
    radius = np.inf

    def small_step(d: Array) -> bool:
        return float(np.abs(d).max(initial=0.0)) <= tol

    def merit_parts(x: Array) -> tuple[float, Array]:
        px = energy.value(x)
        return _dot(w, px * px), (constraints.value(x) if k else np.zeros(0))

    for it in range(iterations + 1):
        p = energy.value(v)
        f = _dot(w, p * p)
        g = 2.0 * asm.je.rmatvec(asm.je.values(v), w * p)
        jc = asm.jc.values(v)
        jq = asm.jq.values(v)
        if k:
            q = constraints.value(v)
            gl = g + asm.jq.rmatvec(jq, lam)
        else:
            q = np.zeros(0)
            gl = g
        stat = float(np.abs(gl).max()) if n else 0.0
        feas = float(np.abs(q).max()) if k else 0.0
        if stat <= stat_tol and feas <= tol:
            converged = True
            break
        if it == iterations:
            break
        # the step, with the Hessian regularised until its curvature along the step is positive:
        # first without the constraints' curvature (the energy's own, positive, scale), then + delta I
        # after a shortened Gauss-Newton step the full Hessian is not tried again first (measured: it
        # failed the curvature test on every step of a crawl, one wasted factorisation per step)
        gauss_newton = not k or sticky
        if sticky:
            delta = 0.0
        rhs = np.concatenate([-g, -q])
        while True:
            K = asm.matrix(jc, jq, None if gauss_newton else lam, delta, w * p)
            lu = kkt.factor(K)
            sol = lu(rhs)
            if k:   # iterative refinement toward the unregularised system's solution
                for _ in range(refine_steps):
                    res = rhs - K @ sol - kkt_reg * np.concatenate([np.zeros(n), sol[n:]])
                    rn = _norm(res)
                    if rn == 0.0:
                        break
                    # inexact: the correction to the step's own absolute accuracy, gmres_tol |rhs|
                    sol = sol + lu(res, min(0.5, kkt.gmres_tol * _norm(rhs) / rn) if refine_inexact else None)
            dv = sol[:n]
            curv = _dot(dv, (K @ np.concatenate([dv, zk]))[:n])
            dd = _dot(dv, dv)
            if (np.all(np.isfinite(sol)) and curv >= 1e-10 * dd) or delta > 1e8:
                break
            if not gauss_newton:
                gauss_newton, delta = True, 0.0
                continue
            delta = max(1e-8, GROW * delta)
        lam_new = sol[n:] if k else np.zeros(0)
        if small_step(dv) and feas <= tol:   # the Newton step says v is within tol of the KKT point
            converged = True
            v = v + dv
            break
        # l1 merit with a penalty above the multipliers
        q1 = float(np.abs(q).sum())
        mu = max(mu, 1.5 * float(np.abs(lam_new).max(initial=0.0)) + 1e-8)
        slope = _dot(g, dv) - mu * q1
        phi0 = f + mu * q1
        step = 1.0
        dvmax = float(np.abs(dv).max(initial=0.0))
        if gauss_newton and dvmax > radius:    # start where the last shortened step ended, times step_growth
            step = 0.5 ** np.floor(np.log2(dvmax / radius))
        accepted = False
        v_new = v
        small = dvmax < 1e-12
        slack = 1e-14 * max(1.0, abs(phi0))
        # the caller's early fallback: the first step's merit tried at first_step_min before any longer step
        probe = it == 0 and 0.0 < first_step_min < step
        while step >= 1e-10:
            ts = first_step_min if probe else step
            vt = v + ts * dv
            ft, qt = merit_parts(vt)
            if small or ft + mu * float(np.abs(qt).sum()) <= phi0 + 1e-4 * ts * slope + slack:
                v_new, accepted = vt, True
            elif k:   # second-order corrections: back onto the curved constraints
                vs, qs = vt, qt
                qn = float(np.abs(qt).sum())
                for _ in range(soc_steps):
                    vs = vs + lu(np.concatenate([np.zeros(n), -qs]), soc_tol if soc_tol > 0.0 else None)[:n]
                    fs, qs = merit_parts(vs)
                    qn_new = float(np.abs(qs).sum())
                    if fs + mu * qn_new <= phi0 + 1e-4 * ts * slope + slack:
                        v_new, accepted = vs, True
                        break
                    if not qn_new <= soc_rate * qn:    # the corrections do not contract: give up
                        break
                    qn = qn_new
            if probe:   # passed: the line search proper, from the full step; failed: the solve ends
                probe, gave_up, accepted, v_new = False, not accepted, False, v
                if gave_up:
                    break
                continue
            if accepted:
                break
            step *= 0.5
        if gave_up:
            break
        if not accepted:   # no decrease along the step: stalled
            # at the energy's float resolution with the remaining Newton step below stall_tol: done
            converged = feas <= tol and float(np.abs(dv).max(initial=0.0)) <= stall_tol
            break
        if step < 1.0 and feas <= tol and dvmax <= stall_tol:
            # a feasible Newton step below stall_tol shortened: the merit's changes are at its float
            # resolution (the quadratic model's error, |dv|^3, is far below them), so the full step
            # is taken and the solve ends as at a stall
            converged = True
            v = v + dv
            break
        sticky = bool(k) and gauss_newton and step < 1.0
        radius = np.inf if step == 1.0 else step_growth * step * dvmax
        # Levenberg-Marquardt-like: a short step means a poor quadratic model, so regularise more
        delta = max(GROW * delta, 1e-6) if step < 0.25 else (delta / GROW if delta > 1e-10 else 0.0)
        if k:
            dlam = lam_new - lam
            big = float(np.abs(dlam).max(initial=0.0))
            bound = lam_bound * max(1.0, float(np.abs(lam).max(initial=0.0)))
            lam = lam + step * dlam * (min(1.0, bound / big) if big > 0 else 1.0)
        v = v_new
    p = energy.value(v)
    viol = float(np.abs(constraints.value(v)).max()) if k else 0.0
    return SolveResult(v, lam, _dot(w, p * p), viol, it, converged, stat, kkt.count, gave_up)
