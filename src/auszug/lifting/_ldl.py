"""Sparse LDL^T without pivoting in a given ordering (numba, cached on disk), for the lifting's KKT matrices.

QDLDL's Python wrapper orders every matrix by its own AMD; on the KKT matrices of the 100-curve
benchmark a nested-dissection ordering (METIS) leaves L a third smaller. This module factorises a
symmetric matrix, given by the upper triangle of its permuted form, by the up-looking algorithm:
the elimination tree and the column counts once per sparsity pattern (:func:`symbolic`), then per
matrix the rows of L one after the other, each a sparse triangular solve along the tree
(:func:`numeric`). A matrix that is quasi-definite (``[[H, A^T], [A, -C]]`` with H and C positive
definite) has such a factorisation in every symmetric ordering.
"""

from __future__ import annotations

import numpy as np
from numba import njit
from numpy.typing import NDArray

Array = NDArray[np.float64]
Index = NDArray[np.int64]


@njit(cache=True)
def symbolic(n: int, Ap: Index, Ai: Index) -> tuple[Index, Index, float]:
    """The elimination tree, the column counts of L (below the diagonal) and the flop count.

    ``Ap``, ``Ai``: the upper triangle (diagonal included) of a symmetric (n, n) matrix in CSC
    form. Returns ``parent`` (-1 at the roots), ``counts`` and ``sum(counts**2)`` (the numeric
    factorisation's multiply-adds, up to lower-order terms).
    """
    parent = np.full(n, -1, np.int64)
    flag = np.empty(n, np.int64)
    counts = np.zeros(n, np.int64)
    for k in range(n):
        flag[k] = k
        for p in range(Ap[k], Ap[k + 1]):
            i = Ai[p]
            while i < k and flag[i] != k:      # up the tree from i to the first node seen for row k
                if parent[i] == -1:
                    parent[i] = k
                counts[i] += 1
                flag[i] = k
                i = parent[i]
    flops = 0.0
    for i in range(n):
        flops += float(counts[i]) * float(counts[i])
    return parent, counts, flops


@njit(cache=True)
def numeric(n: int, Ap: Index, Ai: Index, Ax: Array, parent: Index, Lp: Index, Li: NDArray[np.uint32],
            Lx: Array, D: Array) -> bool:
    """Fill ``Li``, ``Lx`` (CSC of the unit lower triangle, columns starting at ``Lp``) and ``D``.

    Row k of L solves ``L[:k, :k] D[:k] l_k = A[:k, k]`` by the sparse triangular solve whose
    pattern is the reach of ``A[:k, k]``'s rows in the elimination tree. Returns False at a zero
    pivot (the matrix is then not quasi-definite in this ordering).
    """
    y = np.zeros(n)
    flag = np.empty(n, np.int64)
    pattern = np.empty(n, np.int64)
    filled = np.zeros(n, np.int64)
    for k in range(n):
        flag[k] = k
        top = n
        for p in range(Ap[k], Ap[k + 1]):
            i = Ai[p]
            if i > k:
                continue
            y[i] += Ax[p]
            length = 0
            while flag[i] != k:                # the path from i up to an already marked node
                pattern[length] = i
                length += 1
                flag[i] = k
                i = parent[i]
            while length > 0:                  # pushed in reverse, so pattern[top:] is topological
                top -= 1
                length -= 1
                pattern[top] = pattern[length]
        d = y[k]
        y[k] = 0.0
        for t in range(top, n):
            i = pattern[t]
            yi = y[i]
            y[i] = 0.0
            end = Lp[i] + filled[i]
            for p in range(Lp[i], end):
                y[Li[p]] -= Lx[p] * yi
            lki = yi / D[i]
            d -= lki * yi
            Li[end] = k
            Lx[end] = lki
            filled[i] += 1
        if d == 0.0:
            return False
        D[k] = d
    return True


@njit(cache=True)
def solve(n: int, Lp: Index, Li: NDArray[np.uint32], Lx: Array, D: Array, b: Array) -> Array:
    """``x`` with ``L D L^T x = b`` (in the factorised, permuted ordering)."""
    x = b.copy()
    for j in range(n):
        xj = x[j]
        if xj != 0.0:
            for p in range(Lp[j], Lp[j + 1]):
                x[Li[p]] -= Lx[p] * xj
    for j in range(n):
        x[j] /= D[j]
    for j in range(n - 1, -1, -1):
        s = x[j]
        for p in range(Lp[j], Lp[j + 1]):
            s -= Lx[p] * x[Li[p]]
        x[j] = s
    return x


class LDL:
    """The LDL^T of symmetric matrices of one sparsity pattern in one ordering.

    ``perm``: the ordering (the factorised matrix is ``A[perm][:, perm]``); ``Ap``, ``Ai``: that
    permuted matrix's upper triangle in CSC form. :meth:`factor` takes its values, :meth:`solve`
    solves with the original (unpermuted) matrix.
    """

    def __init__(self, perm: Index, Ap: Index, Ai: Index) -> None:
        self.n = len(perm)
        self.perm = perm
        self.Ap, self.Ai = Ap, Ai
        self.parent, counts, self.flops = symbolic(self.n, Ap, Ai)
        self.Lp = np.zeros(self.n + 1, np.int64)
        np.cumsum(counts, out=self.Lp[1:])
        self.Li = np.empty(self.Lp[-1], np.uint32)    # unsigned: numba's indexing skips the wraparound test
        self.Lx = np.empty(self.Lp[-1])
        self.D = np.empty(self.n)

    @property
    def nnz(self) -> int:
        """Non-zeros of L below the diagonal."""
        return int(self.Lp[-1])

    def factor(self, Ax: Array) -> bool:
        """Factorise the permuted upper triangle's values ``Ax``; False at a zero pivot."""
        return bool(numeric(self.n, self.Ap, self.Ai, Ax, self.parent, self.Lp, self.Li, self.Lx, self.D))

    def solve(self, b: Array) -> Array:
        """``x`` with ``A x = b`` for the last factorised matrix ``A`` (unpermuted)."""
        x = np.empty(self.n)
        x[self.perm] = solve(self.n, self.Lp, self.Li, self.Lx, self.D, np.ascontiguousarray(b[self.perm]))
        return x
