"""Tests of auszug.geometry.reverse: reverse curves (ogee arcs), paper supplement A."""

from __future__ import annotations

import math

import numpy as np
import pytest
from geometry_cases import points, rigid_motions, unit_vectors
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from auszug.errors import GeometryError
from auszug.geometry import (
    Arc,
    Line,
    arc_from_tangent,
    cross2,
    equal_radius_reverse_curve,
    prc_locus,
    reverse_curve_from_radius,
    reverse_curve_through,
    rot90,
    turning_angle,
    winds,
)


def single_arc_fits(A, dA, B, dB, eps=1e-3):
    """One arc (or the line) already joins A and B with both tangents: reverse curves
    degenerate (a zero-length arc), so the random tests keep away from it."""
    try:
        c = arc_from_tangent(A, A + dA, B)
    except GeometryError:
        return False
    return float(np.hypot(*(c.tangent(1.0) - dB))) < eps


@st.composite
def ends(draw, parallel=False):
    """(A, dA, B, dB), |AB| >= 0.1, away from the single-arc configuration."""
    A = draw(points)
    B = draw(points.filter(lambda q: float(np.hypot(*(q - A))) >= 0.1))
    dA = draw(unit_vectors)
    dB = dA.copy() if parallel else draw(unit_vectors)
    assume(not single_arc_fits(A, dA, B, dB))
    if not parallel:  # keep away from nearly parallel tangents (huge radii)
        assume(abs(float(cross2(dA, dB))) > 1e-3)
    if parallel:  # B not straight ahead of A
        assume(abs(float(cross2(dA, B - A))) > 1e-2)
    return A, dA, B, dB


def s_shaped(A, dA, B, dB, eps=1e-3):
    """Tangents on the same side of the chord AB (the ogee configuration)."""
    return float(cross2(B - A, dA)) * float(cross2(B - A, dB)) > eps


def locus_exists(A, dA, B, dB, eps=1e-9):
    """prc_locus's rule: not tangents strictly on opposite sides of AB, not both along AB."""
    u = (B - A) / np.hypot(*(B - A))
    sa, sb = float(cross2(u, dA)), float(cross2(u, dB))
    opposite = (sa > eps and sb < -eps) or (sa < -eps and sb > eps)
    return not opposite and max(abs(sa), abs(sb)) > eps


@st.composite
def s_ends(draw):
    e = draw(ends())
    assume(s_shaped(*e))
    return e


def check_reverse(rc, A, dA, B, dB):
    """Every invariant of a reverse curve, to rounding."""
    scale = 1.0 + rc.radius_a + rc.radius_b
    tol = 1e-11 * scale
    f, s = rc.first, rc.second
    np.testing.assert_allclose(f.start, A, atol=tol)
    np.testing.assert_allclose(s.end, B, atol=tol)
    np.testing.assert_allclose(f.tangent(0.0), dA, atol=1e-9)
    np.testing.assert_allclose(s.tangent(1.0), dB, atol=1e-9)
    # G1 at the PRC: the arcs meet there with one tangent
    np.testing.assert_allclose(f.end, rc.prc, atol=tol)
    np.testing.assert_allclose(s.start, rc.prc, atol=tol)
    np.testing.assert_allclose(f.tangent(1.0), s.tangent(0.0), atol=1e-9)
    # opposite turns; the centres and the PRC collinear, the PRC between the centres
    assert f.sweep * s.sweep < 0
    assert float(f.curvature(0.5)) * float(s.curvature(0.5)) < 0
    oa, ob = rc.center_a, rc.center_b
    assert abs(float(cross2(oa - rc.prc, ob - rc.prc))) <= 1e-10 * scale**2
    assert float((oa - rc.prc) @ (ob - rc.prc)) < 0
    assert np.hypot(*(oa - ob)) == pytest.approx(rc.radius_a + rc.radius_b, abs=tol)
    # the two circles: each through its end point and the PRC
    assert rc.radius_a == f.radius and rc.radius_b == s.radius
    assert np.hypot(*(oa - A)) == pytest.approx(rc.radius_a, abs=tol)
    assert np.hypot(*(ob - B)) == pytest.approx(rc.radius_b, abs=tol)


def check_locus_membership(rc, A, dA, B, dB, tol=1e-9):
    """Remark 2: the PRC is on the locus arc exactly when the curve does not wind a
    full extra turn; a winding curve's PRC is on the same circle, other arc."""
    if not locus_exists(A, dA, B, dB):
        with pytest.raises(GeometryError, match="opposite sides|straight ahead"):
            prc_locus(A, dA, B, dB)
        return
    loc = prc_locus(A, dA, B, dB)
    total = rc.first.sweep + rc.second.sweep
    theta = turning_angle(dA, dB)
    assert abs(total - theta) < 1e-7 or abs(abs(total - theta) - 2 * math.pi) < 1e-7
    assert winds(rc, dA, dB) == (abs(total - theta) > 1)
    if not winds(rc, dA, dB):
        assert on_locus(loc, rc.prc, tol)
    elif isinstance(loc, Arc):
        r = np.hypot(*(rc.prc - loc.center))
        assert r == pytest.approx(loc.radius, rel=tol, abs=tol)
        assert not on_locus(loc, rc.prc, 1e-6)


def on_locus(loc, C, tol=1e-9):
    """C lies on the locus, strictly between its ends."""
    t = loc.project(C)
    return float(np.hypot(*(loc.point(t) - C))) <= tol * (1 + getattr(loc, "radius", 0.0)) and (
        0.0 < t < 1.0
    )


# -- the locus of PRCs (Remarks 1 and 2) ------------------------------------------------


@settings(max_examples=200, deadline=None)
@given(ends(), st.sampled_from(["left", "right"]))
def test_equal_radius_curve(e, turn):
    A, dA, B, dB = e
    try:
        rc = equal_radius_reverse_curve(A, dA, B, dB, turn)
    except GeometryError:
        # only impossible for d_A = d_B with the other turn
        assert float(dA @ dB) > 1 - 1e-9
        return
    check_reverse(rc, A, dA, B, dB)
    assert rc.radius_a == pytest.approx(rc.radius_b, rel=1e-12)
    assert rc.first_turn == turn
    check_locus_membership(rc, A, dA, B, dB)


@settings(max_examples=200, deadline=None)
@given(s_ends(), st.floats(0.02, 0.98))
def test_every_locus_point_is_a_prc(e, tau):
    A, dA, B, dB = e
    loc = prc_locus(A, dA, B, dB)
    C = loc.point(tau)
    rc = reverse_curve_through(A, dA, B, dB, C)
    check_reverse(rc, A, dA, B, dB)
    assert rc.prc.tolist() == C.tolist()
    assert not winds(rc, dA, dB)
    # ... and the curve with that first radius and turn is the same curve (A.2 agrees with A.1)
    again = reverse_curve_from_radius(A, dA, B, dB, rc.radius_a, rc.first_turn)
    assert again.radius_b == pytest.approx(rc.radius_b, rel=1e-8, abs=1e-9)
    np.testing.assert_allclose(again.prc, C, atol=1e-8 * (1 + rc.radius_a + rc.radius_b))


@settings(max_examples=200, deadline=None)
@given(ends(), st.floats(0.01, 10.0), st.sampled_from(["left", "right"]))
def test_curves_from_radius_have_their_prc_on_the_locus(e, r, turn):
    A, dA, B, dB = e
    try:
        rc = reverse_curve_from_radius(A, dA, B, dB, r, turn)
    except GeometryError:
        return  # this radius and turn give a same-turn biarc; covered below
    check_reverse(rc, A, dA, B, dB)
    assert rc.radius_a == pytest.approx(r, rel=1e-14)
    check_locus_membership(rc, A, dA, B, dB, tol=1e-8)


def test_remark2_example():
    # A going up, B = (3, 2) going right-up: D = (0, -1); the circumcircle of A, B, D
    # meets the bisector of AB in two points; the locus is centred at the one with
    # angle AOB = 45 degrees (the angle between the tangents), and sweeps -45 degrees
    A, dA, B, dB = np.array([0.0, 0]), np.array([0.0, 1]), np.array([3.0, 2]), np.array([1.0, 1])
    loc = prc_locus(A, dA, B, dB)
    candidates = remark2_candidates(A, B, np.array([0.0, -1.0]))
    angles = [abs(angle_at(o, A, B)) for o in candidates]
    want = candidates[int(np.argmin(np.abs(np.array(angles) - math.pi / 4)))]
    np.testing.assert_allclose(loc.center, want, atol=1e-12)
    assert loc.sweep == pytest.approx(-math.pi / 4, abs=1e-14)


def angle_at(o, A, B):
    """Signed angle AOB."""
    u, v = A - o, B - o
    return math.atan2(float(cross2(u, v)), float(u @ v))


def remark2_candidates(A, B, D):
    """The two points where the bisector of AB meets the circumcircle of A, B, D."""
    m = np.array([[2 * (B - A)[0], 2 * (B - A)[1]], [2 * (D - A)[0], 2 * (D - A)[1]]])
    cc = np.linalg.solve(m, [B @ B - A @ A, D @ D - A @ A])  # circumcentre
    rc = np.hypot(*(A - cc))
    mid = (A + B) / 2
    n = rot90(B - A) / np.hypot(*(B - A))
    h = (cc - mid) @ n
    return mid + (h + rc) * n, mid + (h - rc) * n


@settings(max_examples=200, deadline=None)
@given(s_ends())
def test_locus_is_remark2_construction(e):
    A, dA, B, dB = e
    den = float(cross2(dA, dB))
    assume(abs(den) > 1e-3)
    D = A + (float(cross2(B - A, dB)) / den) * dA
    u = (B - A) / np.hypot(*(B - A))
    assume(abs(float(cross2(u, D - A))) > 1e-3)  # triangle ABD not degenerate
    loc = prc_locus(A, dA, B, dB)
    assert isinstance(loc, Arc)
    o1, o2 = remark2_candidates(A, B, D)
    # the right O: angle AOB = alpha, the angle between the tangents; the arc sweeps theta
    theta = turning_angle(dA, dB)
    o = min((o1, o2), key=lambda c: abs(abs(angle_at(c, A, B)) - abs(theta)))
    assert abs(abs(angle_at(o, A, B)) - abs(theta)) < 1e-7
    scale = 1 + np.hypot(*o)
    np.testing.assert_allclose(loc.center, o, atol=1e-9 * scale)
    assert loc.radius == pytest.approx(np.hypot(*(A - o)), rel=1e-9)
    assert loc.sweep == pytest.approx(theta, abs=1e-9)
    np.testing.assert_allclose(loc.start, A, atol=1e-9 * scale)
    np.testing.assert_allclose(loc.end, B, atol=1e-9 * scale)
    # F, where the normals meet, is on the circumcircle too (proof of Remark 2)
    nA, nB = rot90(dA), rot90(dB)
    f = A + (float(cross2(B - A, nB)) / float(cross2(nA, nB))) * nA
    cc_r = np.hypot(*(o1 - o2)) / 2
    assert np.hypot(*(f - (o1 + o2) / 2)) == pytest.approx(cc_r, rel=1e-7)


@settings(max_examples=200, deadline=None)
@given(ends())
def test_c_shaped_configuration_has_no_locus(e):
    A, dA, B, dB = e
    assume(float(cross2(B - A, dA)) * float(cross2(B - A, dB)) < -1e-3)
    with pytest.raises(GeometryError, match="opposite sides of the chord"):
        prc_locus(A, dA, B, dB)


@settings(max_examples=100, deadline=None)
@given(ends(parallel=True), st.floats(0.02, 0.98))
def test_parallel_tangents_prc_on_segment(e, tau):
    A, dA, B, dB = e
    loc = prc_locus(A, dA, B, dB)
    assert isinstance(loc, Line)  # Remark 1
    assert loc.p0.tolist() == A.tolist() and loc.p1.tolist() == B.tolist()
    rc = reverse_curve_through(A, dA, B, dB, loc.point(tau))
    check_reverse(rc, A, dA, B, dB)
    for turn in ("left", "right"):
        try:
            rc = equal_radius_reverse_curve(A, dA, B, dB, turn)
        except GeometryError:
            continue
        check_reverse(rc, A, dA, B, dB)
        u = float((rc.prc - A) @ (B - A)) / float((B - A) @ (B - A))
        assert abs(float(cross2(rc.prc - A, B - A))) < 1e-10 and 0 < u < 1
        # equal radii and parallel tangents: the PRC is the midpoint of AB
        np.testing.assert_allclose(rc.prc, (A + B) / 2, atol=1e-10)


def test_parallel_tangents_examples():
    # the classic ogee: both tangents vertical
    rc = reverse_curve_from_radius((0, 0), (0, 1), (3, 3), (0, 1), 1.0)
    assert rc.first_turn == "right" and rc.radius_b == pytest.approx(2.0)
    np.testing.assert_allclose(rc.prc, [1, 1], atol=1e-15)
    with pytest.raises(GeometryError, match="straight ahead"):
        prc_locus((0, 0), (0, 1), (0, 3), (0, 1))
    with pytest.raises(GeometryError, match="straight ahead"):
        equal_radius_reverse_curve((0, 0), (0, 1), (0, 3), (0, 1), "left")
    with pytest.raises(GeometryError, match="must turn right first"):
        equal_radius_reverse_curve((0, 0), (0, 1), (2, 2), (0, 1), "left")


@settings(max_examples=100, deadline=None)
@given(points, unit_vectors, points, st.sampled_from(["left", "right"]))
def test_opposite_tangents(A, dA, B, turn):
    # d_B = -d_A: a C-shaped configuration (no locus), yet reverse curves exist
    assume(np.hypot(*(B - A)) > 0.1 and abs(float(cross2(dA, B - A))) > 1e-2)
    dB = -dA
    assume(not single_arc_fits(A, dA, B, dB))
    with pytest.raises(GeometryError, match="opposite sides"):
        prc_locus(A, dA, B, dB)
    rc = equal_radius_reverse_curve(A, dA, B, dB, turn)
    check_reverse(rc, A, dA, B, dB)


# -- A.2: the law of cosines, and its misprint -----------------------------------------


@settings(max_examples=200, deadline=None)
@given(ends(), st.floats(0.01, 10.0), st.sampled_from(["left", "right"]))
def test_a2_relation_holds(e, r, turn):
    """The signed law of cosines in the triangle F O_A O_B, F computed independently."""
    A, dA, B, dB = e
    nA, nB = rot90(dA), rot90(dB)
    den = float(cross2(nA, nB))
    assume(abs(den) > 1e-3)
    try:
        rc = reverse_curve_from_radius(A, dA, B, dB, r, turn)
    except GeometryError:
        return
    ts = float(cross2(B - A, nB)) / den  # F = A + ts nA = B + ss nB
    F = A + ts * nA
    ss = float((F - B) @ nB)
    rho_a = rc.radius_a if turn == "left" else -rc.radius_a
    rho_b = -rho_a / abs(rho_a) * rc.radius_b
    fa, fb = rho_a - ts, rho_b - ss  # signed |F O_A|, |F O_B| along the normals
    np.testing.assert_allclose(F + fa * nA, rc.center_a, atol=1e-9 * (1 + abs(fa)))
    lhs = (rc.radius_a + rc.radius_b) ** 2
    rhs = fa**2 + fb**2 - 2 * fa * fb * float(nA @ nB)
    assert lhs == pytest.approx(rhs, rel=1e-9, abs=1e-9)


def paper_configuration(alpha, t, s, r_a):
    """Fig. A.2: F at the origin, A at distance t, B at distance s, angle AFB = alpha.

    n_A = (A - F)/t, n_B = (F - B)/s, O_A = A + r_A n_A, O_B = B + r_B n_B.
    """
    F = np.zeros(2)
    A = np.array([t, 0.0])
    B = s * np.array([math.cos(alpha), math.sin(alpha)])
    return F, A, B, (A - F) / t, (F - B) / s


def solve_paper(alpha, t, s, r_a, misprint):
    """Roots 0 < r_B < s of the A.2 relation, in either version:

    (r_A + r_B)^2 = (s - r_B)^2 + (t + r_A)^2 - 2 (s - r_B)(t + X) cos(alpha),
    X = r_B as printed (quadratic in r_B), X = r_A as the law of cosines says (linear).
    """
    c = math.cos(alpha)
    const = r_a**2 - s**2 - (t + r_a) ** 2
    if misprint:  # 2 c (s - r)(t + r) = 2 c (s t + (s - t) r - r^2)
        roots = np.roots([-2 * c, 2 * r_a + 2 * s + 2 * c * (s - t), const + 2 * c * s * t])
        roots = roots[np.isreal(roots)].real
    else:
        roots = np.array([-(const + 2 * c * s * (t + r_a)) / (2 * r_a + 2 * s - 2 * c * (t + r_a))])
    return [float(r) for r in roots if 0 < r < s]


def tangency_gap(alpha, t, s, r_a, r_b):
    """Build O_A, O_B, C as A.2 says; how far C is from lying on both circles."""
    F, A, B, nA, nB = paper_configuration(alpha, t, s, r_a)
    oa, ob = A + r_a * nA, B + r_b * nB
    C = (r_b * oa + r_a * ob) / (r_a + r_b)
    return max(abs(np.hypot(*(C - oa)) - r_a), abs(np.hypot(*(C - ob)) - r_b)), C


@settings(max_examples=300, deadline=None)
@given(st.floats(0.3, 2.8), st.floats(0.2, 3.0), st.floats(0.5, 5.0), st.floats(0.05, 3.0))
def test_law_of_cosines_misprint(alpha, t, s, r_a):
    """Which cosine term is right: build the curve from each version of A.2 and check.

    The paper prints ``- 2 (s - r_B)(t + r_B) cos(alpha)``. Solving that for r_B and
    building O_A = A + r_A n_A, O_B = B + r_B n_B, C = (r_B O_A + r_A O_B) / (r_A + r_B)
    gives circles that are not tangent (C is not on both, so no G1 at C) unless
    r_B = r_A. With ``(t + r_A)``, the law of cosines proper, they always are, and
    the result is what reverse_curve_from_radius computes.
    """
    # t = s: one arc centred at F joins A and B, reverse curves degenerate
    assume(abs(t - s) > 1e-2)
    F, A, B, nA, nB = paper_configuration(alpha, t, s, r_a)
    dA, dB = -rot90(nA), rot90(nB)  # O_A on the left of dA, O_B on the right of dB
    for r_b in solve_paper(alpha, t, s, r_a, misprint=False):
        gap, C = tangency_gap(alpha, t, s, r_a, r_b)
        assert gap < 1e-9  # tangent circles: G1 at C
        rc = reverse_curve_from_radius(A, dA, B, dB, r_a, "left")
        assert rc.radius_b == pytest.approx(r_b, rel=1e-9)
        np.testing.assert_allclose(rc.prc, C, atol=1e-9)
        check_reverse(rc, A, dA, B, dB)
    # The two versions differ by 2 cos(alpha) (s - r_B)(r_B - r_A): they agree only for a
    # right angle at F, r_B = r_A or r_B = s. Elsewhere the misprint misses tangency.
    for r_b in solve_paper(alpha, t, s, r_a, misprint=True):
        if abs(r_b - r_a) > 1e-3 and abs(math.cos(alpha)) > 1e-2 and s - r_b > 1e-3:
            assert tangency_gap(alpha, t, s, r_a, r_b)[0] > 1e-9  # not a reverse curve


def test_misprint_concrete_numbers():
    # alpha = 60 deg, t = 1, s = 3, r_A = 1/2:
    #   law of cosines: (1/2 + r)^2 = (3 - r)^2 + (3/2)^2 - (3 - r)(3/2), r_B = 13/11;
    #   as printed:     (1/2 + r)^2 = (3 - r)^2 + (3/2)^2 - (3 - r)(1 + r), r_B = 1.
    alpha, t, s, r_a = math.pi / 3, 1.0, 3.0, 0.5
    (good,) = solve_paper(alpha, t, s, r_a, misprint=False)
    (bad,) = solve_paper(alpha, t, s, r_a, misprint=True)
    assert good == pytest.approx(13 / 11, rel=1e-14) and bad == pytest.approx(1.0, rel=1e-14)
    assert tangency_gap(alpha, t, s, r_a, good)[0] < 1e-14
    assert tangency_gap(alpha, t, s, r_a, bad)[0] > 0.05
    F, A, B, nA, nB = paper_configuration(alpha, t, s, r_a)
    rc = reverse_curve_from_radius(A, -rot90(nA), B, rot90(nB), r_a)
    assert rc.radius_b == pytest.approx(13 / 11, rel=1e-13)


# -- reverse_curve_through: errors, symmetry, invariance --------------------------------


@settings(max_examples=100, deadline=None)
@given(ends(), st.floats(0.05, 0.95), st.floats(0.01, 0.2))
def test_off_locus_point_is_refused(e, tau, off):
    assume(s_shaped(*e))
    A, dA, B, dB = e
    loc = prc_locus(A, dA, B, dB)
    C = loc.point(tau)
    n = rot90(loc.tangent(tau))
    with pytest.raises(GeometryError, match="not a point of reverse curvature|tangent line"):
        reverse_curve_through(A, dA, B, dB, C + off * n)


@settings(max_examples=100, deadline=None)
@given(ends(), st.floats(0.02, 0.98))
def test_reversal_symmetry(e, tau):
    A, dA, B, dB = e
    assume(s_shaped(*e))
    C = prc_locus(A, dA, B, dB).point(tau)
    rc = reverse_curve_through(A, dA, B, dB, C)
    back = reverse_curve_through(B, -dB, A, -dA, C)
    check_reverse(back, B, -dB, A, -dA)
    assert back.radius_a == pytest.approx(rc.radius_b, rel=1e-9)
    assert back.radius_b == pytest.approx(rc.radius_a, rel=1e-9)
    np.testing.assert_allclose(back.center_a, rc.center_b, atol=1e-9 * (1 + rc.radius_b))


@settings(max_examples=100, deadline=None)
@given(ends(), st.floats(0.02, 0.98), rigid_motions())
def test_rigid_motion_invariance(e, tau, motion):
    A, dA, B, dB = e
    assume(s_shaped(*e))
    m, off = motion
    rc = reverse_curve_through(A, dA, B, dB, prc_locus(A, dA, B, dB).point(tau))
    moved = reverse_curve_through(m @ A + off, m @ dA, m @ B + off, m @ dB, m @ rc.prc + off)
    scale = 1 + rc.radius_a + rc.radius_b
    assert moved.radius_a == pytest.approx(rc.radius_a, rel=1e-7, abs=1e-9)
    np.testing.assert_allclose(moved.center_a, m @ rc.center_a + off, atol=1e-7 * scale)
    flipped = np.linalg.det(m) < 0
    assert (moved.first_turn != rc.first_turn) == flipped
    loc = prc_locus(m @ A + off, m @ dA, m @ B + off, m @ dB)
    assert on_locus(loc, m @ rc.prc + off, tol=1e-8)


def test_input_validation():
    A, dA, B, dB = (0, 0), (0, 1), (3, 2), (1, 1)
    with pytest.raises(GeometryError, match="coincide"):
        prc_locus(A, dA, A, dB)
    with pytest.raises(GeometryError, match="non-zero"):
        prc_locus(A, (0, 0), B, dB)
    with pytest.raises(GeometryError, match="positive"):
        reverse_curve_from_radius(A, dA, B, dB, 0.0)
    with pytest.raises(GeometryError, match="positive"):
        reverse_curve_from_radius(A, dA, B, dB, math.nan)
    with pytest.raises(GeometryError, match="'left' or 'right'"):
        equal_radius_reverse_curve(A, dA, B, dB, "up")
    with pytest.raises(GeometryError, match="coincides with A"):
        reverse_curve_through(A, dA, B, dB, A)
    with pytest.raises(GeometryError, match="tangent line at A"):
        reverse_curve_through(A, dA, B, dB, (0, 1))


def test_single_arc_configuration_has_no_proper_reverse_curve():
    # A quarter circle already joins A and B with both tangents: every "reverse curve"
    # has an arc of zero length
    A, dA, B, dB = (0, 0), (0, 1), (2, 2), (1, 0)
    for turn in ("left", "right"):
        with pytest.raises(GeometryError, match="zero length|opposite signs"):
            equal_radius_reverse_curve(A, dA, B, dB, turn)
    with pytest.raises(GeometryError, match="no reverse curve"):
        reverse_curve_from_radius(A, dA, B, dB, 1.0)


def test_default_turn_follows_the_paper():
    # F = intersection of the normals; O_A = A + r_A (A - F)/|AF| (away from F)
    F, A, B, nA, nB = paper_configuration(1.0, 1.0, 3.0, 0.5)
    dA, dB = -rot90(nA), rot90(nB)
    rc = reverse_curve_from_radius(A, dA, B, dB, 0.5)
    np.testing.assert_allclose(rc.center_a, A + 0.5 * nA, atol=1e-12)
    assert np.hypot(*(rc.center_a - F)) > np.hypot(*(A - F))


def test_to_dict_and_length():
    rc = equal_radius_reverse_curve((0, 0), (0, 1), (2, 2), (0, 1), "right")
    assert not winds(rc, (0, 1), (0, 1)) and turning_angle((0, 1), (0, 1)) == 0.0
    d = rc.to_dict()
    assert d["kind"] == "reverse_curve" and d["prc"] == [1.0, 1.0]
    assert rc.length() == pytest.approx(math.pi)
    assert rc.arcs == (rc.first, rc.second)


def test_strict_mode_checks_run():
    from auszug.geometry import tolerances

    with tolerances(strict=True):
        rc = equal_radius_reverse_curve((0, 0), (0, 1), (3, 1), (1, -1), "left")
    check_reverse(rc, np.zeros(2), np.array([0.0, 1]), np.array([3.0, 1]),
                  np.array([1, -1]) / math.sqrt(2))

