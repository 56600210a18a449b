"""Tests of auszug.geometry.intersect: brute force, invariances, degenerate cases."""

from __future__ import annotations

import math
import time

import numpy as np
import pytest
from geometry_cases import (
    TAU,
    arcs,
    beziers,
    curves,
    dist_to_curve,
    lines,
    near_degenerate,
    polyline_crossings,
    rigid_motions,
)
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from auszug.geometry import (
    TOL,
    Arc,
    CubicBezier,
    Line,
    cross2,
    intersect,
    intersect_many,
    tolerances,
)

ON_CURVE = 1e-9 * (1 + 1e-6)  # TOL.intersect plus rounding


def check_valid(c1, c2, hits):
    """The invariants every result satisfies."""
    t1s = [h.t1 for h in hits]
    assert t1s == sorted(t1s)
    for h in hits:
        assert 0.0 <= h.t1 <= 1.0 and 0.0 <= h.t2 <= 1.0
        assert h.point.shape == (2,) and np.all(np.isfinite(h.point))
        assert np.hypot(*(c1.point(h.t1) - h.point)) <= ON_CURVE
        assert np.hypot(*(c2.point(h.t2) - h.point)) <= ON_CURVE
    for i, a in enumerate(hits):
        for b in hits[i + 1 :]:  # distinct points, or one double point on two branches
            assert (
                np.hypot(*(a.point - b.point)) > 2 * TOL.intersect
                or max(abs(a.t1 - b.t1), abs(a.t2 - b.t2)) > 1e-3
            )


def params(hits):
    return np.array([(h.t1, h.t2) for h in hits]).reshape(-1, 2)


def same_params(a, b, atol=1e-7):
    """Equal as sets of (t1, t2), in any order."""
    a, b = params(a), params(b)
    if a.shape != b.shape:
        return False
    free = list(range(len(b)))
    for row in a:
        match = [k for k in free if np.all(np.abs(b[k] - row) <= atol)]
        if not match:
            return False
        free.remove(match[0])
    return True


# -- against brute force ----------------------------------------------------------------


@settings(max_examples=300, deadline=None)
@given(curves(), curves())
def test_matches_brute_force(c1, c2):
    assume(not near_degenerate(c1, c2))
    hits = intersect(c1, c2)
    check_valid(c1, c2, hits)
    for h in hits:  # on both curves (distance to the exact curve, not just at t)
        assert dist_to_curve(c1, h.point) <= ON_CURVE
        assert dist_to_curve(c2, h.point) <= ON_CURVE
    brute = polyline_crossings(c1, c2)
    pts = np.array([h.point for h in hits]).reshape(-1, 2)
    for x, y, _sin in brute:  # every crossing of the polylines is found
        assert len(pts) and np.min(np.hypot(*(pts - (x, y)).T)) < 2e-3
    for h in hits:  # every transversal interior hit is a crossing of the polylines
        s = abs(float(cross2(c1.tangent(h.t1), c2.tangent(h.t2))))
        if s > 0.1 and 0.01 < h.t1 < 0.99 and 0.01 < h.t2 < 0.99:
            assert len(brute) and np.min(np.hypot(*(brute[:, :2] - h.point).T)) < 2e-3


def test_brute_force_known_counts():
    # a line through a full circle, a lens of two circles, two crossing segments
    circle = Arc((0, 0), 1.0, 0.3, TAU)
    assert len(intersect(Line((-2, 0.5), (2, 0.5)), circle)) == 2
    assert len(intersect(Arc((0.5, 0), 1.0, 0.0, TAU), circle)) == 2
    hits = intersect(Arc((0.5, 0), 1.0, 0.0, TAU), circle)
    np.testing.assert_allclose(
        sorted(h.point.tolist() for h in hits),
        [[0.25, -math.sqrt(1 - 0.0625)], [0.25, math.sqrt(1 - 0.0625)]],
        atol=1e-15,
    )


# -- invariances ------------------------------------------------------------------------


@settings(max_examples=200, deadline=None)
@given(curves(), curves(), rigid_motions())
def test_rigid_motion_invariance(c1, c2, motion):
    assume(not near_degenerate(c1, c2))
    m, off = motion
    hits = intersect(c1, c2)
    moved = intersect(c1.transformed(m, off), c2.transformed(m, off))
    assert same_params(hits, moved)
    for h, g in zip(sorted(hits, key=lambda h: h.t1), sorted(moved, key=lambda h: h.t1), strict=True):
        np.testing.assert_allclose(m @ h.point + off, g.point, atol=1e-8)


@settings(max_examples=200, deadline=None)
@given(curves(), curves())
def test_swap_symmetry(c1, c2):
    assume(not near_degenerate(c1, c2))
    ab = intersect(c1, c2)
    ba = intersect(c2, c1)
    assert same_params(ab, [h.swapped() for h in ba], atol=1e-12)
    check_valid(c2, c1, ba)


@settings(max_examples=200, deadline=None)
@given(curves(), curves())
def test_reversal_symmetry(c1, c2):
    assume(not near_degenerate(c1, c2))
    hits = intersect(c1, c2)
    rev = intersect(c1.reversed(), c2.reversed())
    assert same_params(hits, [type(h)(1 - h.t1, 1 - h.t2, h.point) for h in rev], atol=1e-12)


@settings(max_examples=100, deadline=None)
@given(st.lists(curves(), min_size=0, max_size=8), st.lists(curves(), min_size=1, max_size=4))
def test_intersect_many_equals_pairwise(cs, others):
    got = intersect_many(cs)
    for i in range(len(cs)):
        for j in range(len(cs)):
            if i < j:
                want = intersect(cs[i], cs[j])
                assert ((i, j) in got) == bool(want)
                if want:
                    assert same_params(got[(i, j)], want, atol=0.0)
            else:
                assert (i, j) not in got
    cross = intersect_many(cs, others)
    for i, a in enumerate(cs):
        for j, b in enumerate(others):
            want = intersect(a, b)
            assert same_params(cross.get((i, j), []), want, atol=0.0)


# -- degenerate cases -------------------------------------------------------------------


def test_parallel_lines_disjoint():
    assert intersect(Line((0, 0), (1, 0)), Line((0, 1e-6), (1, 1e-6))) == []
    assert intersect(Line((0, 0), (1, 0)), Line((2, 0), (3, 0))) == []


@pytest.mark.parametrize(
    "a, b, want",
    [
        # partial overlap: the overlap's end points, in both curves' parameters
        (((0, 0), (2, 0)), ((1, 0), (3, 0)), [(0.5, 0.0), (1.0, 0.5)]),
        # opposite directions
        (((0, 0), (2, 0)), ((3, 0), (1, 0)), [(0.5, 1.0), (1.0, 0.5)]),
        # containment
        (((0, 0), (4, 0)), ((1, 0), (3, 0)), [(0.25, 0.0), (0.75, 1.0)]),
        # identical, and identical reversed
        (((0, 0), (1, 1)), ((0, 0), (1, 1)), [(0.0, 0.0), (1.0, 1.0)]),
        (((0, 0), (1, 1)), ((1, 1), (0, 0)), [(0.0, 1.0), (1.0, 0.0)]),
        # collinear, touching end to end
        (((0, 0), (1, 0)), ((1, 0), (2, 0)), [(1.0, 0.0)]),
    ],
)
def test_collinear_overlap_reports_end_points(a, b, want):
    l1, l2 = Line(*a), Line(*b)
    hits = intersect(l1, l2)
    check_valid(l1, l2, hits)
    assert [(h.t1, h.t2) for h in hits] == want


def test_near_parallel_long_lines_cross():
    # sin(angle) = 1e-10, below TOL.collinear, yet the segments cross in the middle
    l1 = Line((-100, -1e-8), (100, 1e-8))
    l2 = Line((-100, 0), (100, 0))
    hits = intersect(l1, l2)
    check_valid(l1, l2, hits)
    assert len(hits) == 1 and abs(hits[0].point[0]) < 1e-3


@pytest.mark.parametrize("eps", [0.0, 1e-13, -1e-13, 5e-10])
@pytest.mark.parametrize("angle", [0.0, 0.7, 2.0])
def test_line_tangent_to_circle_is_one_point(eps, angle):
    u = np.array([math.cos(angle), math.sin(angle)])
    n = np.array([-u[1], u[0]])
    c = np.array([0.3, -0.2])
    circle = Arc(c, 1.5, angle - 2.0, TAU)
    foot = c + (1.5 + eps) * n
    ln = Line(foot - 2 * u, foot + 2 * u)
    for a, b in ((ln, circle), (circle, ln)):
        hits = intersect(a, b)
        check_valid(a, b, hits)
        assert len(hits) == 1
        np.testing.assert_allclose(hits[0].point, foot, atol=2e-9)
    assert intersect(Line(foot - 2 * u + 2e-9 * n, foot + 2 * u + 2e-9 * n), circle) == []


@pytest.mark.parametrize("internal", [False, True])
@pytest.mark.parametrize("eps", [0.0, 1e-12, -1e-12])
def test_tangent_circles_one_point(internal, eps):
    u = np.array([0.6, 0.8])
    c1 = np.array([0.1, 0.2])
    r1, r2 = 1.0, 0.4
    d = (r1 - r2 if internal else r1 + r2) + eps
    c2 = c1 + d * u
    a1, a2 = Arc(c1, r1, 0.0, TAU), Arc(c2, r2, 1.0, TAU)
    for x, y in ((a1, a2), (a2, a1)):
        hits = intersect(x, y)
        check_valid(x, y, hits)
        assert len(hits) == 1
        np.testing.assert_allclose(hits[0].point, c1 + r1 * u, atol=1e-11)


def test_concentric_circles_do_not_meet():
    assert intersect(Arc((1, 1), 1.0, 0.0, TAU), Arc((1, 1), 2.0, 0.0, TAU)) == []
    assert intersect(Arc((1, 1), 1.0, 0.0, 3.0), Arc((1, 1), 1.0 + 1e-6, 0.0, 3.0)) == []


def test_same_circle_overlap_end_points():
    a = Arc((0, 0), 1.0, 0.0, math.pi)  # upper half
    b = Arc((0, 0), 1.0, math.pi / 2, math.pi)  # left half
    hits = intersect(a, b)
    check_valid(a, b, hits)
    assert [(h.t1, h.t2) for h in hits] == [(0.5, 0.0), (1.0, 0.5)]
    # opposite orientation
    hits = intersect(a, b.reversed())
    assert [(h.t1, h.t2) for h in hits] == [(0.5, 1.0), (1.0, 0.5)]
    # two overlapping pieces: arcs of 300 degrees each, offset by 180 degrees
    c = Arc((0, 0), 1.0, 0.0, 5 * math.pi / 3)
    d = Arc((0, 0), 1.0, math.pi, 5 * math.pi / 3)
    hits = intersect(c, d)
    check_valid(c, d, hits)
    assert len(hits) == 4
    # identical arcs: the two end points
    assert [(h.t1, h.t2) for h in intersect(a, a)] == [(0.0, 0.0), (1.0, 1.0)]
    # disjoint arcs of one circle
    assert intersect(Arc((0, 0), 1.0, 0.0, 1.0), Arc((0, 0), 1.0, 2.0, 1.0)) == []


def test_full_circles_never_nan():
    a = Arc((0, 0), 1.0, 0.0, TAU)
    for b in (a, Arc((0, 0), 1.0, 1.0, -TAU), Arc((0, 0), 1.0 + 1e-12, 0.0, TAU)):
        hits = intersect(a, b)
        check_valid(a, b, hits)
        assert 1 <= len(hits) <= 2


def test_tiny_sagitta_arc():
    # radius 1e6, length 1: sagitta 1.25e-7, far above TOL.intersect
    r, sw = 1e6, 1e-6
    arc = Arc((0, -r), r, math.pi / 2 - sw / 2, sw)
    chord = Line(arc.start, arc.end)
    hits = intersect(arc, chord)
    check_valid(arc, chord, hits)
    assert [(h.t1, h.t2) for h in hits] == [(0.0, 0.0), (1.0, 1.0)]
    sag = r * (1 - math.cos(sw / 2))
    mid = Line((-1, -sag / 2), (1, -sag / 2))  # halfway between chord and apex
    hits = intersect(arc, mid)
    check_valid(arc, mid, hits)
    assert len(hits) == 2
    for h in hits:
        assert dist_to_curve(arc, h.point) <= ON_CURVE


def test_arcs_meeting_at_end_points_exact():
    a = Arc((0, 0), 1.0, 0.0, 1.0)
    b = Arc(2 * a.end, 1.0, 1.0 + math.pi, -1.2)  # G1 reverse pair meeting at a.end
    hits = intersect(a, b)
    assert [(h.t1, h.t2) for h in hits] == [(1.0, 0.0)]
    assert hits[0].point.tolist() == a.point(1.0).tolist()
    ln = Line(a.end, (3, 3))
    assert [(h.t1, h.t2) for h in intersect(ln, a)] == [(0.0, 1.0)]
    # an overshoot by less than the tolerance is clamped
    ln = Line(a.end + 1e-10 * a.tangent(1.0), (3, 3))
    assert [(h.t1, h.t2) for h in intersect(a, ln)] == [(1.0, 0.0)]


@given(lines(), st.floats(0.0, 1.0))
def test_lines_sharing_a_point(ln, t):
    p = ln.point(t)
    other = Line(p, p + np.array([0.3, -0.7]))
    assume(abs(float(np.dot(ln.direction, [0.7, 0.3]))) > 1e-3)  # not parallel
    hits = intersect(ln, other)
    check_valid(ln, other, hits)
    assert len(hits) == 1
    h = hits[0]  # within tolerance of the shared point, in both parameters
    assert h.t2 * other.length() <= 2 * TOL.intersect
    assert abs(h.t1 - t) * ln.length() <= 2 * TOL.intersect


@given(arcs())
def test_arc_with_itself(a):
    hits = intersect(a, a)
    check_valid(a, a, hits)
    closed = np.hypot(*(a.start - a.end)) <= TOL.intersect  # one point: start = end
    want = [(0.0, 0.0)] if closed else [(0.0, 0.0), (1.0, 1.0)]
    assert [(h.t1, h.t2) for h in hits] == want


def test_tolerance_is_read_at_call_time():
    l1, l2 = Line((0, 0), (1, 0)), Line((0.5, 1e-7), (0.5, 1))
    assert intersect(l1, l2) == []
    with tolerances(intersect=1e-6):
        assert [(h.t1, h.t2) for h in intersect(l1, l2)] == [(0.5, 0.0)]


def test_unsupported_curve_type():
    with pytest.raises(TypeError, match="intersect supports"):
        intersect(Line((0, 0), (1, 0)), object())


def test_intersect_many_is_fast():
    rng = np.random.default_rng(1)
    cs = []
    for k in range(60):
        if k % 2:
            cs.append(Line(rng.uniform(-1, 1, 2), rng.uniform(-1, 1, 2)))
        else:
            cs.append(Arc(rng.uniform(-1, 1, 2), rng.uniform(0.2, 1), rng.uniform(-3, 3), 2.0))
    intersect_many(cs)
    t0 = time.perf_counter()
    res = intersect_many(cs)
    dt = time.perf_counter() - t0
    assert sum(map(len, res.values())) > 100
    assert dt < 0.05  # typically ~5 ms for all 1770 pairs; generous bound for slow CI


# -- Beziers ----------------------------------------------------------------------------


def pairs_with_bezier():
    return st.tuples(beziers(), curves(bezier=True), st.booleans()).map(
        lambda x: (x[0], x[1]) if x[2] else (x[1], x[0])
    )


@settings(max_examples=100, deadline=None)
@given(pairs_with_bezier())
def test_bezier_matches_brute_force(pair):
    c1, c2 = pair
    assume(not near_degenerate(c1, c2, 1e-3))
    hits = intersect(c1, c2)
    check_valid(c1, c2, hits)
    for h in hits:
        assert dist_to_curve(c1, h.point) <= ON_CURVE
        assert dist_to_curve(c2, h.point) <= ON_CURVE
    brute = polyline_crossings(c1, c2, n=800)
    pts = np.array([h.point for h in hits]).reshape(-1, 2)
    for x, y, _sin in brute:
        assert len(pts) and np.min(np.hypot(*(pts - (x, y)).T)) < 2e-3
    for h in hits:
        s = abs(float(cross2(c1.tangent(h.t1), c2.tangent(h.t2))))
        if s > 0.1 and 0.01 < h.t1 < 0.99 and 0.01 < h.t2 < 0.99:
            assert len(brute) and np.min(np.hypot(*(brute[:, :2] - h.point).T)) < 2e-3


@settings(max_examples=100, deadline=None)
@given(pairs_with_bezier(), rigid_motions())
def test_bezier_invariances(pair, motion):
    c1, c2 = pair
    assume(not near_degenerate(c1, c2, 1e-3))
    m, off = motion
    hits = intersect(c1, c2)
    assert same_params(hits, intersect(c1.transformed(m, off), c2.transformed(m, off)))
    assert same_params(hits, [h.swapped() for h in intersect(c2, c1)])
    rev = intersect(c1.reversed(), c2.reversed())
    assert same_params(hits, [type(h)(1 - h.t1, 1 - h.t2, h.point) for h in rev])


APEX = CubicBezier((0, 0), (1, 2), (3, 2), (4, 0))  # apex (2, 1.5), radius of curvature 1.6875


def test_bezier_overlaps_report_end_points():
    b = APEX
    assert [(h.t1, h.t2) for h in intersect(b, b)] == [(0.0, 0.0), (1.0, 1.0)]
    assert [(h.t1, h.t2) for h in intersect(b, b.reversed())] == [(0.0, 1.0), (1.0, 0.0)]
    hits = intersect(b, b.segment(0.2, 0.7))
    check_valid(b, b.segment(0.2, 0.7), hits)
    np.testing.assert_allclose(params(hits), [[0.2, 0.0], [0.7, 1.0]], atol=1e-9)
    left, right = b.segment(0.0, 0.6), b.segment(0.4, 1.0)  # partial overlap
    np.testing.assert_allclose(params(intersect(left, right)), [[2 / 3, 0.0], [1.0, 1 / 3]],
                               atol=1e-9)
    straight = CubicBezier((0, 0), (0.5, 0), (2.5, 0), (3, 0))  # non-uniform speed
    ln = Line((1, 0), (5, 0))
    hits = intersect(straight, ln)
    check_valid(straight, ln, hits)
    assert len(hits) == 2 and hits[1].t1 == 1.0
    np.testing.assert_allclose(hits[0].point, [1, 0], atol=1e-12)
    np.testing.assert_allclose(hits[1].t2, 0.5)


@pytest.mark.parametrize(
    "other",
    [
        Line((0, 1.5), (4, 1.5)),  # tangent line at the apex
        Arc((2, 0.5), 1.0, 0.0, TAU),  # circle inside, touching at the apex
        Arc((2, 2.5), 1.0, -3.0, 2.5),  # arc above, touching at the apex
        CubicBezier((0, 3), (1, 1), (3, 1), (4, 3)),  # mirrored Bezier touching at the apex
    ],
)
def test_bezier_tangency_is_one_point(other):
    for x, y in ((APEX, other), (other, APEX)):
        hits = intersect(x, y)
        check_valid(x, y, hits)
        assert len(hits) == 1
        np.testing.assert_allclose(hits[0].point, [2, 1.5], atol=1e-7)


def test_beziers_meeting_at_end_points():
    b = APEX
    c = CubicBezier(b.end, 2 * b.end - b.p2, (6, -3), (7, 0))  # G1 continuation
    hits = intersect(b, c)
    assert [(h.t1, h.t2) for h in hits] == [(1.0, 0.0)]
    assert hits[0].point.tolist() == b.end.tolist()
    hits = intersect(Line((4, 0), (4, 5)), b)
    assert [(h.t1, h.t2) for h in hits] == [(0.0, 1.0)]


def test_bezier_crossings_known():
    # the apex Bezier and the line y = 1: y(t) = 6 t (1 - t) = 1
    hits = intersect(APEX, Line((-1, 1), (5, 1)))
    r = (1 - math.sqrt(1 / 3)) / 2
    np.testing.assert_allclose(params(hits)[:, 0], [r, 1 - r], atol=1e-14)
    # a loop crossing a line four... the S curve meets its chord in three points
    s = CubicBezier((0, 0), (1, 1), (2, -1), (3, 0))
    hits = intersect(s, Line((0, 0), (3, 0)))
    np.testing.assert_allclose(params(hits), [[0, 0], [0.5, 0.5], [1, 1]], atol=1e-14)


def test_intersect_many_with_beziers():
    rng = np.random.default_rng(7)
    cs = [CubicBezier(*rng.uniform(-1, 1, (4, 2))) for _ in range(10)]
    cs += [Line(rng.uniform(-1, 1, 2), rng.uniform(-1, 1, 2)) for _ in range(10)]
    got = intersect_many(cs)
    for i in range(len(cs)):
        for j in range(i + 1, len(cs)):
            assert same_params(got.get((i, j), []), intersect(cs[i], cs[j]), atol=0.0)


def test_handles_on_end_points_do_not_break_newton():
    # both derivatives vanish at the shared start: Newton must step off, not divide by 0
    a = CubicBezier((0, 0), (0, 0), (1, 1), (2, 0))
    b = CubicBezier((0, 0), (0, 0), (1, -1), (2, 0))
    for x, y in ((a, b), (b, a), (a, a.reversed())):
        hits = intersect(x, y)
        check_valid(x, y, hits)
    assert [(h.t1, h.t2) for h in intersect(a, b)] == [(0.0, 0.0), (1.0, 1.0)]
    c = CubicBezier((0, 0.5), (0, 0.5), (0, 0.2), (0, 0))  # straight, both speeds 0 at ends
    d = CubicBezier((0, 0), (0, 0), (0, -0.3), (0, -0.5))
    assert [(h.t1, h.t2) for h in intersect(c, d)] == [(1.0, 0.0)]
    assert [(h.t1, h.t2) for h in intersect(c, Line((0, 1), (0, -1)))] == [(0.0, 0.25), (1.0, 0.5)]


def test_arcs_flatter_than_their_evaluation_error_are_lines():
    """A handle off the chord by a sine below ARC_MIN_SINE gives a Line, above it an Arc whose
    points lie on its circle to ~1e-16 of the radius and within the chord's sagitta bound."""
    from auszug.geometry import arc_from_tangent, arc_through
    from auszug.geometry.arc import ARC_MIN_SINE

    a, b = np.array([0.0, 0.5]), np.array([0.0, -1.0])
    assert arc_from_tangent(a, (-1e-9, 0.0), b).kind == "line"
    assert arc_through(a, (1e-9, -0.25), b).kind == "line"
    h = (-0.5 * 4 * ARC_MIN_SINE, 0.0)   # the handle 0.5 below a: sine 4 ARC_MIN_SINE
    arc = arc_from_tangent(a, h, b)
    assert arc.kind == "arc"
    np.testing.assert_allclose(arc.point(np.array([0.0, 1.0])), [a, b], atol=1e-9)
    mid = arc.point(0.5)
    assert abs(mid[0]) <= 1.5 * 4 * ARC_MIN_SINE / 4 * 1.01    # sagitta ~ chord * sine / 4
