"""The KKT Newton solver: known answers, redundant constraints, far starts, the convergence test."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from auszug.lifting.solver import Poly2, solve


def _nearest_on_sphere(p: np.ndarray, duplicate: bool = False) -> tuple[Poly2, Poly2]:
    """min |x - p|^2 subject to |x|^2 = 1 (answer p / |p|), optionally with the constraint twice."""
    n = len(p)
    e = Poly2(n)
    e.add(-p, 1.0, lin=(np.arange(n), np.arange(n), np.ones(n)))
    c = Poly2(n)
    for _ in range(2 if duplicate else 1):
        c.add([-1.0], bil=(np.zeros(n, int), np.arange(n), np.arange(n), np.ones(n)))
    return e, c


@pytest.mark.parametrize("duplicate", [False, True])
@pytest.mark.parametrize("seed", range(5))
def test_nearest_point_on_a_sphere_from_far_starts(seed, duplicate):
    rng = np.random.default_rng(seed)
    p = rng.normal(size=6) * 3
    e, c = _nearest_on_sphere(p, duplicate)
    v0 = rng.normal(size=6) * 10          # far from the sphere, any side
    r = solve(e, c, v0)
    assert r.converged and r.violation < 1e-10
    # the two KKT points are +-p/|p|; the line search must not leave the start's basin for a worse one
    best = p / np.linalg.norm(p)
    assert min(np.abs(r.v - best).max(), np.abs(r.v + best).max()) < 1e-9
    assert r.iterations <= 30


def test_redundant_constraints_are_met_exactly():
    """The -kkt_reg I block alone leaves |q| ~ kkt_reg |lam|; iterative refinement removes that bias."""
    p = np.array([30.0, -40.0, 0.0])                  # |lam| = |p| - 1 = 49
    e, c = _nearest_on_sphere(p, duplicate=True)
    r = solve(e, c, np.array([1.0, 0.0, 0.0]), kkt_reg=1e-8)
    assert r.converged and r.violation < 1e-12
    assert np.allclose(r.v, p / 50.0, atol=1e-12)
    assert r.stationarity < 1e-9


def test_no_constraints_is_one_newton_step_for_a_quadratic():
    e = Poly2(3)
    e.add([1.0, -2.0, 3.0], [1.0, 2.0, 4.0], lin=([0, 1, 2], [0, 1, 2], [1.0, 1.0, 1.0]))
    r = solve(e, Poly2(3), np.zeros(3))
    assert r.converged and r.iterations == 1
    assert np.allclose(r.v, [-1.0, 2.0, -3.0], atol=1e-12)


def test_an_iteration_limit_is_reported_as_not_converged():
    p = np.array([3.0, 4.0])
    e, c = _nearest_on_sphere(p)
    r = solve(e, c, np.array([10.0, -7.0]), iterations=1)
    assert not r.converged and r.iterations == 1


def _kkt(rng: np.random.Generator, n: int, k: int) -> sp.csc_matrix:
    """A random KKT matrix [[H, J^T], [J, -1e-11 I]] with H positive definite (n, n), J (k, n) of full rank.

    The constraint block's diagonal is stored, as in the solver's assembly.
    """
    A = rng.normal(size=(n, n))
    J = rng.normal(size=(k, n))
    return sp.csc_matrix(np.block([[A @ A.T + np.eye(n), J.T], [J, -1e-11 * np.eye(k)]]))


@pytest.mark.parametrize("ldl_reg, gmres_its", [(1e-8, 30), (1.0, 1), (0.0, 30)])
def test_kkt_solves_are_of_the_unregularised_matrix(ldl_reg, gmres_its):
    """LDL^T + GMRES, a preconditioner too poor for one GMRES step (SuperLU takes over), SuperLU alone."""
    from auszug.lifting.solver import _KKT

    rng = np.random.default_rng(3)
    n, k = 12, 5
    kkt = _KKT(n, ldl_reg=ldl_reg, gmres_its=gmres_its)
    for _ in range(2):                                  # the second factorisation reuses the first's analysis
        K = _kkt(rng, n, k)
        b = rng.normal(size=n + k)
        x = kkt.factor(K)(b)
        assert np.abs(K @ x - b).max() < 1e-10 * np.abs(b).max()
    assert kkt.count == 2
    assert kkt.lu_count == (2 if ldl_reg == 0.0 or gmres_its == 1 else 0)


def test_kkt_falls_back_to_lu_on_a_zero_pivot():
    """H = [[1, 1], [1, 1]] - ldl_reg I: the regularised matrix is singular (no LDL^T), K is not."""
    from auszug.lifting.solver import _KKT

    reg = 1e-8
    K = sp.csc_matrix(np.array([[1.0 - reg, 1.0, 1.0], [1.0, 1.0 - reg, 0.0], [1.0, 0.0, 0.0]]))
    kkt = _KKT(2, ldl_reg=reg)
    b = np.array([1.0, 2.0, 3.0])
    x = kkt.factor(K)(b)
    assert np.allclose(K @ x, b, atol=1e-12) and kkt.lu_count == 1


@pytest.mark.parametrize("duplicate", [False, True])
def test_ldl_and_lu_reach_the_same_point(duplicate):
    """The preconditioned solves change rounding only: the same KKT point as with SuperLU alone."""
    rng = np.random.default_rng(7)
    p = rng.normal(size=6) * 3
    e, c = _nearest_on_sphere(p, duplicate)
    v0 = rng.normal(size=6) * 10
    a = solve(e, c, v0)
    b = solve(e, c, v0, ldl_reg=0.0)
    assert a.converged and b.converged
    assert np.abs(a.v - b.v).max() < 1e-10


def test_a_first_step_cut_below_first_step_min_gives_up_at_the_start():
    """``first_step_min`` (final_hold's early fallback, lift-final2): from (1e-3, 2e-3), next to the sphere's
    centre, the first Newton step overshoots and the line search cuts it below 1/64 (measured), so the solve
    ends there: not converged, ``gave_up``, no step taken. Where the step shortened to that fraction does
    decrease the merit (1/1024 here), the solve is the one without the rule, to the bit."""
    p = np.array([3.0, 4.0])
    e, c = _nearest_on_sphere(p)
    v0 = np.array([1e-3, 2e-3])
    r0 = solve(e, c, v0)
    assert r0.converged and not r0.gave_up and np.allclose(r0.v, p / 5.0, atol=1e-9)
    r = solve(e, c, v0, first_step_min=1 / 64)
    assert r.gave_up and not r.converged and r.iterations == 0 and np.array_equal(r.v, v0)
    r1 = solve(e, c, v0, first_step_min=1 / 1024)
    assert not r1.gave_up and r1.converged and r1.iterations == r0.iterations and np.array_equal(r1.v, r0.v)
