"""Tests of auszug.geometry.bezier.CubicBezier."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from geometry_cases import beziers, rigid_motions
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st
from scipy.integrate import IntegrationWarning, quad
from scipy.optimize import minimize_scalar

from auszug.errors import GeometryError
from auszug.geometry import CubicBezier, cross2
from auszug.geometry.bezier import _speed_extrema_many, t_at_u_many

ts = st.floats(0.0, 1.0)


def speed_minima(b, n=4001):
    """Local minima of the speed, found independently (dense scan + bounded minimisation)."""
    t = np.linspace(0, 1, n)
    v = b.speed(t)
    out = []
    for i in np.nonzero((v[1:-1] <= v[:-2]) & (v[1:-1] <= v[2:]))[0] + 1:
        r = minimize_scalar(lambda x: float(b.speed(x)), bounds=(t[i - 1], t[i + 1]),
                            method="bounded", options={"xatol": 1e-14})
        out.append(float(r.x))
    return out


def quad_length(b, t0=0.0, t1=1.0):
    """Reference arc length: adaptive quadrature (QUADPACK), independent of the GL table.

    Break points at the independently found speed minima (a cusp is a kink of
    the speed, and a near-cusp a narrow dip).
    """
    cuts = [x for x in speed_minima(b) if t0 < x < t1]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)
        return quad(lambda t: float(b.speed(t)), t0, t1, points=cuts or None, limit=1000,
                    epsabs=1e-15, epsrel=1e-14)[0]


def no_cusp(b, margin=1e-3):
    """The speed stays away from zero (the arc-length map is then well conditioned)."""
    return float(np.min(b.speed(np.linspace(0, 1, 2001)))) > margin


# -- evaluation -------------------------------------------------------------------------


@given(beziers())
def test_end_points_exact(b):
    assert b.point(0.0).tolist() == b.p0.tolist()
    assert b.point(1.0).tolist() == b.p3.tolist()
    assert b.start.tolist() == b.p0.tolist() and b.end.tolist() == b.p3.tolist()


def test_known_values():
    b = CubicBezier((0, 0), (1, 2), (3, 2), (4, 0))
    assert b.point(0.5).tolist() == [2.0, 1.5]
    np.testing.assert_allclose(b.derivative(0.0), [3.0, 6.0])
    np.testing.assert_allclose(b.derivative(1.0), [3.0, -6.0])
    np.testing.assert_allclose(b.tangent(0.5), [1.0, 0.0])
    # curvature at the apex: |B''| / |B'|^2 with B'(.5) = (4.5, 0), B''(.5) = (0, -12)
    assert float(b.curvature(0.5)) == pytest.approx(-12 / 4.5**2, rel=1e-14)
    assert b.point(np.zeros((3, 2))).shape == (3, 2, 2)


@settings(deadline=None)
@given(beziers(), st.floats(0.02, 0.98))
def test_tangent_and_curvature_match_finite_differences(b, t):
    assume(float(b.speed(t)) > 1e-2)
    h = 1e-6
    fd = (b.point(t + h) - b.point(t - h)) / (2 * h)
    np.testing.assert_allclose(b.derivative(t), fd, atol=1e-7)
    np.testing.assert_allclose(b.tangent(t), fd / np.hypot(*fd), atol=1e-6)
    # curvature = d(angle)/ds
    h = 1e-5
    a0, a1 = b.tangent(t - h), b.tangent(t + h)
    dang = math.atan2(float(cross2(a0, a1)), float(a0 @ a1))
    ds = quad_length(b, t - h, t + h)
    assert float(b.curvature(t)) == pytest.approx(dang / ds, rel=1e-4, abs=1e-4)


def test_tangent_at_degenerate_handles():
    b = CubicBezier((0, 0), (0, 0), (1, 1), (2, 0))  # first handle on the start point
    np.testing.assert_allclose(b.tangent(0.0), [math.sqrt(0.5), math.sqrt(0.5)])
    c = CubicBezier((0, 0), (1, 1), (2, 0), (2, 0))  # second handle on the end point
    np.testing.assert_allclose(c.tangent(1.0), [math.sqrt(0.5), -math.sqrt(0.5)])
    np.testing.assert_allclose(c.tangent(1.0), c.tangent(1 - 1e-7), atol=1e-6)
    d = CubicBezier((0, 0), (0, 0), (0, 0), (3, 4))  # straight, both handles at the start
    np.testing.assert_allclose(d.tangent([0.0, 0.5, 1.0]), [[0.6, 0.8]] * 3, atol=1e-15)
    # a cusp: speed 0 at t = 0.5
    e = CubicBezier((0, 0), (1, 1), (0, 1), (1, 0))
    assert float(e.speed(0.5)) == 0.0
    assert np.all(np.isfinite(e.tangent(np.linspace(0, 1, 11))))
    assert np.isinf(e.curvature(0.5))


def test_invalid_input():
    with pytest.raises(GeometryError, match="coincide"):
        CubicBezier((1, 1), (1, 1), (1, 1), (1, 1))
    with pytest.raises(GeometryError, match="finite"):
        CubicBezier((0, 0), (math.nan, 0), (1, 1), (2, 2))
    with pytest.raises(GeometryError, match="shape"):
        CubicBezier.from_array(np.zeros((3, 2)))
    with pytest.raises(ValueError, match="order"):
        CubicBezier((0, 0), (1, 0), (2, 0), (3, 0)).derivative(0.5, 4)


# -- arc length -------------------------------------------------------------------------


@settings(max_examples=60, deadline=None)
@given(beziers())
def test_length_matches_quadrature(b):
    assume(no_cusp(b, 1e-2))  # near-cusps: exact values in test_length_near_cusp
    assert b.length() == pytest.approx(quad_length(b), rel=1e-12, abs=1e-13)


def test_length_at_a_cusp():
    # y(t) = (1-t)^3 + t^3 on x = 0: down from 1 to 1/4 (t = 1/2), then back up
    b = CubicBezier((0, 1), (0, 0), (0, 0), (0, 1))
    assert b.length() == pytest.approx(1.5, rel=1e-15)
    assert float(b.u_at_t(0.5)) == pytest.approx(0.5, rel=1e-15)
    assert float(b.u_at_t(0.875)) * 1.5 == pytest.approx(1.171875, rel=1e-15)
    assert float(b.t_at_u(0.5)) == pytest.approx(0.5, abs=1e-12)


@pytest.mark.parametrize("eps", [1e-3, 1e-5, 6e-8, 0.0])
def test_length_near_cusp(eps):
    # x = eps t^3, y = 3(1-t)^2 t + t^3: speed 3 sqrt((1-2t)^4 + eps^2 t^4), a narrow
    # dip at t = 1/2. Exact length 1 + the integral of a cancellation-free remainder.
    b = CubicBezier((0, 0), (0, 1), (0, 0), (eps, 1))

    def rest(t):
        e = eps**2 * t**4
        return 3 * e / (math.sqrt((1 - 2 * t) ** 4 + e) + (1 - 2 * t) ** 2)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", IntegrationWarning)
        want = 1 + quad(rest, 0, 1, points=[0.5], epsabs=1e-20, epsrel=1e-13, limit=1000)[0]
    assert b.length() == pytest.approx(want, rel=1e-14)


def test_straight_bezier_length_and_uniform_u():
    b = CubicBezier((0, 0), (1, 0), (2, 0), (3, 0))  # uniform speed: t = u
    assert b.length() == pytest.approx(3.0, rel=1e-15)
    u = np.linspace(0, 1, 11)
    np.testing.assert_allclose(b.t_at_u(u), u, atol=1e-15)
    c = CubicBezier((0, 0), (0, 0), (3, 0), (3, 0))  # same segment, non-uniform speed
    assert c.length() == pytest.approx(3.0, rel=1e-14)
    np.testing.assert_allclose(c.point_at(u)[:, 0], 3 * u, atol=1e-12)


@settings(max_examples=60, deadline=None)
@given(beziers(), st.lists(ts, min_size=1, max_size=20))
def test_arc_length_maps_are_inverse(b, tlist):
    t = np.array(tlist)
    u = b.u_at_t(t)
    assert np.all((0 <= u) & (u <= 1))
    np.testing.assert_allclose(b.u_at_t(b.t_at_u(t)), t, atol=1e-12)  # t used as u values
    if no_cusp(b):
        np.testing.assert_allclose(b.t_at_u(u), t, atol=1e-10)
    # u_at_t agrees with an independent quadrature (near-cusps: test_length_near_cusp)
    for ti, ui in zip(t[:3] if no_cusp(b, 1e-2) else [], u[:3], strict=False):
        assert ui * b.length() == pytest.approx(quad_length(b, 0.0, ti), abs=1e-11)


@settings(max_examples=40, deadline=None)
@given(beziers())
def test_u_monotone_and_sample_equally_spaced(b):
    t = np.linspace(0, 1, 201)
    assert np.all(np.diff(b.u_at_t(t)) >= 0)
    assert b.u_at_t(0.0) == 0.0 and b.u_at_t(1.0) == 1.0
    assert b.t_at_u(0.0) == 0.0 and b.t_at_u(1.0) == 1.0
    tk = b.t_at_u(np.linspace(0, 1, 9))
    if no_cusp(b, 1e-2):  # the reference quadrature is not reliable at near-cusps
        pieces = [quad_length(b, a, c) for a, c in zip(tk[:-1], tk[1:], strict=True)]
        np.testing.assert_allclose(pieces, b.length() / 8, atol=1e-11)
    np.testing.assert_allclose(b.sample(9), b.point(tk), atol=0)


# -- editing ----------------------------------------------------------------------------


@settings(deadline=None)
@given(beziers(), st.floats(0.01, 0.99), ts)
def test_split_reproduces_the_curve(b, t, s):
    left, right = b.split(t)
    np.testing.assert_allclose(left.point(s), b.point(s * t), atol=1e-14)
    np.testing.assert_allclose(right.point(s), b.point(t + s * (1 - t)), atol=1e-14)
    assert left.end.tolist() == right.start.tolist()
    assert left.length() + right.length() == pytest.approx(b.length(), rel=1e-12, abs=1e-13)
    if abs(s - t) > 1e-6:
        seg = b.segment(t, s)
        np.testing.assert_allclose(seg.point(0.3), b.point(t + 0.3 * (s - t)), atol=1e-14)


@settings(deadline=None)
@given(beziers(), ts)
def test_reversed(b, t):
    r = b.reversed()
    np.testing.assert_allclose(r.point(t), b.point(1 - t), atol=1e-15)
    assert r.length() == pytest.approx(b.length(), rel=1e-13)
    assert float(r.u_at_t(t)) == pytest.approx(1 - float(b.u_at_t(1 - t)), abs=1e-13)
    if float(b.speed(t)) > 1e-6:
        np.testing.assert_allclose(r.tangent(1 - t), -b.tangent(t), atol=1e-9)
        # curvature carries a rounding error ~ eps |B''| / |B'|^2
        err = 1e-12 * (1 + float(np.hypot(*b.derivative(t, 2)))) / float(b.speed(t)) ** 2
        assert float(r.curvature(1 - t)) == pytest.approx(-float(b.curvature(t)), rel=1e-9, abs=err)
    assert r.reversed().controls.tolist() == b.controls.tolist()


@settings(deadline=None)
@given(beziers(), rigid_motions(), ts)
def test_rigid_motion(b, motion, t):
    m, off = motion
    c = b.transformed(m, off)
    np.testing.assert_allclose(c.point(t), m @ b.point(t) + off, atol=1e-13)
    assert c.length() == pytest.approx(b.length(), rel=1e-12)
    np.testing.assert_allclose(c.u_at_t(t), b.u_at_t(t), atol=1e-13)
    if float(b.speed(t)) > 1e-3:
        det = np.linalg.det(m)
        k = float(b.curvature(t))
        err = 1e-12 * (1 + float(np.hypot(*b.derivative(t, 2)))) / float(b.speed(t)) ** 2
        assert float(c.curvature(t)) == pytest.approx(det * k, rel=1e-9, abs=err)


@settings(max_examples=60, deadline=None)
@given(beziers(), st.tuples(st.floats(-2, 2), st.floats(-2, 2)).map(np.array))
def test_project_is_the_closest_point(b, p):
    t = b.project(p)
    d = np.hypot(*(b.point(t) - p))
    dense = b.point(np.linspace(0, 1, 20001))
    assert d <= np.min(np.hypot(*(dense - p).T)) + 1e-12


def test_project_finds_points_on_the_fold_of_a_near_cusp():
    # found by the sketch graph's property test: this loop turns back near t = 0.81 within one of the
    # 129 samples' steps; points on the fold projected onto the other branch, up to 4.8e-5 away (1 in 150
    # of its points; 5 in 100 000 points of random loops)
    b = CubicBezier((0.0, 0.859), (0.875, -0.844), (-0.312, 0.586), (0.203, 0.0))
    t = np.linspace(0.79, 0.82, 301)
    got = np.array([b.project(q) for q in b.point(t)])
    assert np.hypot(*(b.point(got) - b.point(t)).T).max() <= 1e-12
    rng = np.random.default_rng(5)
    worst = 0.0
    for _ in range(300):
        p0 = rng.uniform(-1, 1, 2)
        c = CubicBezier(p0, rng.uniform(-1, 1, 2), rng.uniform(-1, 1, 2), p0 + rng.normal(0, 0.2, 2))
        for q in c.point(rng.uniform(size=5)):
            worst = max(worst, float(np.hypot(*(c.point(c.project(q)) - q))))
    assert worst <= 1e-12


def test_to_dict():
    b = CubicBezier((0, 0), (1, 2), (3, 2), (4, 0))
    assert b.to_dict() == {
        "kind": "bezier",
        "start": [0.0, 0.0],
        "handles": [[1.0, 2.0], [3.0, 2.0]],
        "end": [4.0, 0.0],
    }
    c = CubicBezier(b.to_dict()["start"], *b.to_dict()["handles"], b.to_dict()["end"])
    assert c.controls.tolist() == b.controls.tolist()


# -- many curves at once -------------------------------------------------------------------


@settings(max_examples=40, deadline=None)
@given(st.lists(beziers(), min_size=1, max_size=12), st.lists(ts, min_size=1, max_size=9))
# hypothesis found it: one u row per curve and one shared row differ in the last bits there
@example(bs=[CubicBezier([0.0, 0.0], [0.0, 0.0], [0.0, 0.0], [0.0, 1.0]),
             CubicBezier([0.0, 0.0], [0.0, 0.060546875], [0.0, 0.0], [0.0, 0.0])], us=[0.625, 0.625, 0.25])
def test_t_at_u_many_is_t_at_u_of_each(bs, us):
    """The batched arc-length inversion is each curve's own, to the order BLAS sums the Gauss-Legendre terms."""
    u = np.array([0.0, *us, 1.0])
    fresh = [CubicBezier(*b.controls) for b in bs]     # no table yet: t_at_u_many builds them
    got = t_at_u_many(fresh, u)
    assert got.shape == (len(bs), len(u))
    for b, f, row in zip(bs, fresh, got, strict=True):
        assert np.abs(row - b.t_at_u(u)).max() <= 4e-15
        assert row[0] == 0.0 and row[-1] == 1.0
        kb, cb = b._table
        kf, cf = f._table                               # the table t_at_u_many stored
        assert np.array_equal(kb, kf)
        assert np.abs(cb - cf).max() <= 4e-15 * cb[-1]
        assert np.array_equal(_speed_extrema_many([b])[0], b._speed_extrema())
    rows = t_at_u_many(fresh, np.tile(u, (len(bs), 1))[:, ::-1])   # one row per curve
    assert np.abs(rows - got[:, ::-1]).max() <= 4e-15


def test_t_at_u_many_degenerate_and_empty():
    cusp = CubicBezier((0, 1), (0, 0), (0, 0), (0, 1))
    straight = CubicBezier((0, 0), (1, 0), (2, 0), (3, 0))
    retracted = CubicBezier((0, 0), (0, 0), (1, 1), (1, 1))
    bs = [cusp, straight, retracted]
    ex = _speed_extrema_many(bs)
    assert [e.tolist() for e in ex] == [b._speed_extrema().tolist() for b in bs]
    t = t_at_u_many([CubicBezier(*b.controls) for b in bs], [0.0, 0.25, 0.5, 1.0])
    assert t[1].tolist() == pytest.approx([0.0, 0.25, 0.5, 1.0], abs=1e-15)
    assert t[0, 2] == pytest.approx(0.5, abs=1e-12)
    assert t_at_u_many([], [0.5]).shape == (0, 1)
    with pytest.raises(GeometryError):
        t_at_u_many(bs, np.zeros((2, 3)))
