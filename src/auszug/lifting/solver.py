"""Least squares with equality constraints, all polynomials of degree <= 2, by Newton on the KKT system.

Every term of sketch lifting is a polynomial of degree at most two in the
unknowns (control points and plane normals): the fidelity terms are linear,
orthogonality and symmetry are dot products of two linear vectors, planarity
with a free normal is bilinear. :class:`Poly2` holds many such polynomials at
once in sparse coordinate form; :func:`solve` minimises
``sum_r w_r p_r(v)^2`` subject to ``q_k(v) = 0`` by Newton's method on the
Karush-Kuhn-Tucker system (Gauss-Newton Hessian of the energy, exact Hessian
of the constraints' Lagrangian term), with the paper's bound on the
multiplier increments (sec. 5.3: normalised by the largest when above one).
The sparse system is factorised by SuperLU (``scipy.sparse.linalg.splu``)
with the COLAMD fill-reducing ordering.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray
from scipy.sparse.linalg import splu

__all__ = ["Poly2", "SolveResult", "solve"]

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
    converged : bool
    """

    v: Array
    lam: Array
    energy: float
    violation: float
    iterations: int
    converged: bool


def solve(energy: Poly2, constraints: Poly2, v0: Array, lam0: Array | None = None, *, iterations: int = 60,
          tol: float = 1e-10, kkt_reg: float = 1e-11, hessian_reg: float = 1e-10) -> SolveResult:
    """Minimise ``sum w_r p_r(v)^2`` subject to ``q(v) = 0`` from ``v0``.

    Each step solves the KKT system
    ``[[H + sum lam_k d2q_k - ... , Jq^T], [Jq, -kkt_reg I]] [dv, lam'] = [-g, -q]``
    with the Gauss-Newton Hessian ``H = 2 Jp^T W Jp + hessian_reg I`` and
    ``g = 2 Jp^T W p``; the step is scaled so that no multiplier changes by more
    than one (the paper's bounded multiplier increments).

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
    reg = sp.identity(n, format="csr") * hessian_reg
    creg = sp.identity(k, format="csr") * (-kkt_reg)
    converged = False
    it = 0
    last = np.inf
    for it in range(1, iterations + 1):  # noqa: B007 - the count is reported
        p = energy.value(v)
        Jp = energy.jacobian(v)
        WJ = Jp.multiply(w[:, None]).tocsr() if len(w) else Jp
        H = 2.0 * (Jp.T @ WJ) + reg
        g = 2.0 * (Jp.T @ (w * p))
        if k:
            q = constraints.value(v)
            Jq = constraints.jacobian(v)
            K = sp.bmat([[H + constraints.hessian(lam), Jq.T], [Jq, creg]], format="csc")
            rhs = np.concatenate([-g, -q])
        else:
            q = np.zeros(0)
            K = H.tocsc()
            rhs = -g
        sol = splu(K, permc_spec="COLAMD").solve(rhs)
        dv = sol[:n]
        step = 1.0
        if k:
            dlam = sol[n:] - lam
            big = float(np.abs(dlam).max())
            if big > 1.0:
                step = 1.0 / big
            lam = lam + step * dlam
        v = v + step * dv
        last = step * float(np.abs(dv).max())
        if step == 1.0 and float(np.abs(dv).max()) < tol and (not k or float(np.abs(q).max()) < tol):
            converged = True
            break
    p = energy.value(v)
    viol = float(np.abs(constraints.value(v)).max()) if k else 0.0
    if not converged and viol < 1e-9 and last < 1e-7:   # stalled at float resolution: as good as it gets
        converged = bool(np.all(np.isfinite(v)))
    return SolveResult(v, lam, float(np.dot(w, p * p)), viol, it, converged)
