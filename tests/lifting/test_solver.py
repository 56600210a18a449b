"""The KKT Newton solver: known answers, redundant constraints, far starts, the convergence test."""

from __future__ import annotations

import numpy as np
import pytest

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
