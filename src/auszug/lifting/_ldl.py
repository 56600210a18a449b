"""Sparse LDL^T without pivoting in a given ordering, for the lifting's KKT matrices (C, loaded with ctypes).

QDLDL's Python wrapper orders every matrix by its own AMD; on the KKT matrices of the 100-curve
benchmark a nested-dissection ordering (METIS) leaves L a third smaller and its factorisation a
third of the multiply-adds. The kernels in ``_ldl.c`` (ours; ``make install`` compiles them into
``ldl-kernels.so`` beside this file) factorise a symmetric matrix, given by the upper triangle of its
permuted form, by the up-looking algorithm: the elimination tree and the column counts once per
sparsity pattern, then per matrix the rows of L one after the other, each a sparse triangular
solve along the tree. A quasi-definite matrix (``[[H, A^T], [A, -C]]``, H and C positive definite)
has such a factorisation in every symmetric ordering. Without the compiled library
:data:`available` is False and the solver keeps QDLDL.
"""

from __future__ import annotations

import ctypes
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

Array = NDArray[np.float64]
Index = NDArray[np.int64]

LIBRARY = Path(__file__).with_name("ldl-kernels.so")

_i64 = np.ctypeslib.ndpointer(np.int64, flags="C_CONTIGUOUS")
_i32 = np.ctypeslib.ndpointer(np.int32, flags="C_CONTIGUOUS")
_f64 = np.ctypeslib.ndpointer(np.float64, flags="C_CONTIGUOUS")


def _load() -> ctypes.CDLL | None:
    try:
        lib = ctypes.CDLL(str(LIBRARY))
    except OSError:
        return None
    lib.ldl_symbolic.argtypes = [ctypes.c_int64, _i64, _i64, _i64, _i64, _i64]
    lib.ldl_symbolic.restype = None
    lib.ldl_numeric.argtypes = [ctypes.c_int64, _i64, _i64, _f64, _i64, _i64, _i32, _f64, _f64, _f64, _i64,
                                _i64, _i64]
    lib.ldl_numeric.restype = ctypes.c_int64
    lib.ldl_solve.argtypes = [ctypes.c_int64, _i64, _i32, _f64, _f64, _f64]
    lib.ldl_solve.restype = None
    return lib


_lib = _load()
#: Whether the compiled kernels are there (``make install`` builds them).
available = _lib is not None


class LDL:
    """The LDL^T of symmetric matrices of one sparsity pattern in one ordering.

    ``perm``: the ordering (the factorised matrix is ``A[perm][:, perm]``); ``Ap``, ``Ai``: that
    permuted matrix's upper triangle in CSC form (int64). The symbolic factorisation is done here;
    :meth:`factor` takes the values, :meth:`solve` solves with the original (unpermuted) matrix.

    Attributes
    ----------
    Lp, Li, Lx, D : ndarray
        The unit lower triangle below its diagonal in CSC form and the diagonal D (permuted order).
    flops : float
        ``sum(c_j^2)`` over L's column counts ``c_j``: the factorisation's multiply-adds up to
        lower-order terms.
    """

    def __init__(self, perm: Index, Ap: Index, Ai: Index) -> None:
        if _lib is None:
            raise RuntimeError(f"the LDL^T kernels are not built ({LIBRARY.name}: run `make install`)")
        n = len(perm)
        self.n = n
        self.perm = np.ascontiguousarray(perm, dtype=np.int64)
        self.Ap = np.ascontiguousarray(Ap, dtype=np.int64)
        self.Ai = np.ascontiguousarray(Ai, dtype=np.int64)
        self.parent = np.empty(n, np.int64)
        counts = np.empty(n, np.int64)
        self._flag = np.empty(n, np.int64)
        _lib.ldl_symbolic(n, self.Ap, self.Ai, self.parent, counts, self._flag)
        c = counts.astype(float)
        self.flops = float(np.sum(c * c))
        self.Lp = np.zeros(n + 1, np.int64)
        np.cumsum(counts, out=self.Lp[1:])
        self.Li = np.empty(self.Lp[-1], np.int32)
        self.Lx = np.empty(self.Lp[-1])
        self.D = np.empty(n)
        self._y = np.zeros(n)
        self._pattern = np.empty(n, np.int64)
        self._filled = np.empty(n, np.int64)

    @property
    def nnz(self) -> int:
        """Non-zeros of L below the diagonal."""
        return int(self.Lp[-1])

    def factor(self, Ax: Array) -> bool:
        """Factorise the permuted upper triangle's values ``Ax``; False at a zero pivot."""
        assert _lib is not None
        Ax = np.ascontiguousarray(Ax, dtype=np.float64)
        return _lib.ldl_numeric(self.n, self.Ap, self.Ai, Ax, self.parent, self.Lp, self.Li, self.Lx, self.D,
                                self._y, self._flag, self._pattern, self._filled) == 0

    def solve(self, b: Array) -> Array:
        """``x`` with ``A x = b`` for the last factorised matrix ``A`` (unpermuted)."""
        assert _lib is not None
        z = np.ascontiguousarray(b[self.perm], dtype=np.float64)
        _lib.ldl_solve(self.n, self.Lp, self.Li, self.Lx, self.D, z)
        x = np.empty(self.n)
        x[self.perm] = z
        return x
