"""The compiled LDL^T in a given ordering and the solver's switch to nested dissection (lift-speed5)."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from auszug.lifting import solver as S


def test_the_kernels_are_built():
    """``make install`` (and so ``make test``) compiles src/auszug/lifting/_ldl.c; without it the lift
    falls back to QDLDL alone, which this checks is not what the tests run."""
    assert S.Orderings.available()


def _quasi_definite(rng: np.random.Generator, n: int, k: int, density: float) -> np.ndarray:
    """A sparse symmetric [[H, J^T], [J, -C]], H (n, n) and C (k, k) positive definite, as a dense array."""
    B = sp.random(n, n, density=density, random_state=rng).toarray()
    H = B @ B.T + np.diag(rng.uniform(0.5, 2.0, n))
    J = sp.random(k, n, density=density, random_state=rng).toarray() * 3.0
    C = np.diag(rng.uniform(1e-3, 1.0, k))
    return np.block([[H, J.T], [J, -C]])


def _dense_ldl(A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The textbook LDL^T without pivoting (column by column), unit lower L and D."""
    N = len(A)
    L, D = np.eye(N), np.zeros(N)
    for j in range(N):
        D[j] = A[j, j] - np.sum(L[j, :j] ** 2 * D[:j])
        for i in range(j + 1, N):
            L[i, j] = (A[i, j] - np.sum(L[i, :j] * L[j, :j] * D[:j])) / D[j]
    return L, D


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_ldl_is_the_dense_factorisation_of_the_permuted_matrix(seed):
    """L and D equal the dense LDL^T of A[perm][:, perm]; L's pattern is the symbolic one; solves are A's."""
    from auszug.lifting import _ldl

    rng = np.random.default_rng(seed)
    A = _quasi_definite(rng, 30, 12, 0.08)
    N = len(A)
    perm = rng.permutation(N)
    U = sp.csc_matrix(np.triu(A))
    Ap, Ai, where = S._permuted_upper(U.indptr, U.indices, perm)
    f = _ldl.LDL(perm, Ap, Ai)
    assert f.factor(U.data[where])
    L_ref, D_ref = _dense_ldl(A[perm][:, perm])
    L = sp.csc_matrix((f.Lx, f.Li, f.Lp), shape=(N, N)).toarray() + np.eye(N)
    assert np.abs(D_ref - f.D).max() < 1e-12 * np.abs(D_ref).max()
    assert np.abs(L_ref - L).max() < 1e-11 * max(1.0, np.abs(L_ref).max())
    outside = np.tril(np.ones((N, N), bool), -1) & (L == 0)           # not in the symbolic pattern
    assert np.abs(L_ref[outside]).max(initial=0.0) < 1e-12
    assert f.nnz == len(f.Lx) and f.flops == float(np.sum(np.diff(f.Lp) ** 2))
    b = rng.normal(size=N)
    x = f.solve(b)
    assert np.abs(A @ x - b).max() < 1e-10 * np.abs(b).max()


def test_ldl_reports_a_zero_pivot():
    """[[0, 1], [1, 0]] has no LDL^T without pivoting."""
    from auszug.lifting import _ldl

    perm = np.arange(2)
    U = sp.csc_matrix(np.array([[0.0, 1.0], [0.0, 0.0]]))
    U.sort_indices()
    Ap, Ai, where = S._permuted_upper(U.indptr, U.indices, perm)
    assert not _ldl.LDL(perm, Ap, Ai).factor(U.data[where])


def _kkt_pattern(rng: np.random.Generator, n: int, k: int, mask: np.ndarray) -> sp.csc_matrix:
    """A KKT matrix with the sparsity ``mask`` of a fixed random pattern, new values each call."""
    A = np.where(mask, rng.normal(size=mask.shape), 0.0)
    H = A[:n, :n] @ A[:n, :n].T + np.eye(n)
    H = np.where(mask[:n, :n] | np.eye(n, dtype=bool), H, 0.0) + n * np.eye(n)   # diagonally dominant
    J = A[n:, :n]
    K = np.block([[H, J.T], [J, -1e-11 * np.eye(k)]])
    return sp.csc_matrix(K)


def test_kkt_switches_to_nested_dissection_and_keeps_the_ordering():
    """From a pattern's third factorisation on (forced: no flop thresholds), then from the first in the
    next solve of the same size; the solves stay those of K."""
    rng = np.random.default_rng(5)
    n, k = 40, 15
    mask = rng.random((n + k, n + k)) < 0.1
    mask = mask | mask.T
    orderings = S.Orderings(min_flops=0.0, speed=0.0)
    kkt = S._KKT(n, orderings=orderings)
    for step in range(4):
        K = _kkt_pattern(rng, n, k, mask)
        b = rng.normal(size=n + k)
        x = kkt.factor(K)(b)
        assert np.abs(K @ x - b).max() < 1e-10 * np.abs(b).max()
        assert (kkt.nd is not None) == (step >= 1)                # decided after the second QDLDL factorisation
    assert kkt.ldl_count == 2 and kkt.lu_count == 0
    assert orderings.get(n + k) is not None
    again = S._KKT(n, orderings=orderings)
    K = _kkt_pattern(rng, n, k, mask)
    b = rng.normal(size=n + k)
    x = again.factor(K)(b)
    assert again.nd is not None and again.ldl_count == 0
    assert np.abs(K @ x - b).max() < 1e-10 * np.abs(b).max()


def test_kkt_keeps_amd_where_nested_dissection_costs_more():
    """With the default speed ratio a small pattern (far below ``ND_MIN_FLOPS``) never leaves QDLDL."""
    rng = np.random.default_rng(6)
    n, k = 40, 15
    mask = rng.random((n + k, n + k)) < 0.1
    mask = mask | mask.T
    kkt = S._KKT(n, orderings=S.Orderings())
    for _ in range(4):
        kkt.factor(_kkt_pattern(rng, n, k, mask))(rng.normal(size=n + k))
    assert kkt.nd is None and kkt.ldl_count == 4 and kkt.nd_tried


def test_a_lift_with_nested_dissection_is_the_lift_with_amd(monkeypatch):
    """Forced on every solve of more than two Newton steps, our LDL^T in nested dissection (only
    GMRES's preconditioner changes) leaves the lift as QDLDL's: the vase truth with 1 % noise (seed 2,
    cues applied and rejected) with the same cues, flags and stages, the control points within 1e-9 of
    the diagonal."""
    from auszug.lifting import LiftParams, _ldl, lift
    from tests.lifting.truth import revolve

    calls = {"n": 0}
    factor = _ldl.LDL.factor

    def counted(self, Ax):
        calls["n"] += 1
        return factor(self, Ax)

    monkeypatch.setattr(_ldl.LDL, "factor", counted)
    tr = revolve(noise=0.01, seed=2)
    amd = lift(tr.sketch, LiftParams(nd_ordering=False))
    assert calls["n"] == 0
    monkeypatch.setattr(S, "ND_MIN_FLOPS", 0.0)
    monkeypatch.setattr(S, "ND_SPEED", 0.0)
    nd = lift(tr.sketch)
    assert calls["n"] > 0
    assert amd.converged and nd.converged and amd.flipped == nd.flipped
    assert [(c.kind, c.where, c.applied) for c in amd.cues] == [(c.kind, c.where, c.applied) for c in nd.cues]
    assert [(s.name, s.converged) for s in amd.stages] == [(s.name, s.converged) for s in nd.stages]
    diag = tr.sketch.diagonal()
    for a, b in zip(amd.points, nd.points, strict=True):
        assert np.abs(a - b).max() <= 1e-9 * diag
