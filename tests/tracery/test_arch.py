"""Pointed arches: the apex formula, exact offsets that keep the centres, the pointed trefoil."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from auszug.geometry import Arc
from auszug.geometry.offset import is_closed, offset_curves, signed_area
from auszug.tracery import ParameterError, PointedArch, apex_height, arch_kind, trefoil_arch
from tests.tracery.cases import ARCHES, spans, valid_excess


@given(spans, valid_excess, st.floats(-5, 5), st.floats(-5, 5))
def test_apex_height_is_half_span_times_sqrt_4e_minus_1(w, e, x, y):
    a = PointedArch(x - w / 2, x + w / 2, y, e)
    expected = (w / 2) * math.sqrt(4 * e - 1)
    # both arcs end exactly at the apex, at the predicted height on the axis
    for p in (a.right_arc().end, a.left_arc().start):
        assert p[0] == pytest.approx(x, abs=1e-12 * (1 + abs(x) + w))
        assert p[1] - y == pytest.approx(expected, rel=1e-12, abs=1e-12 * w)
    assert apex_height(w, e) == pytest.approx(expected, rel=1e-15)


@given(spans, valid_excess)
def test_centres_lie_on_the_springing_line_and_arcs_are_tangent_to_the_jambs(w, e):
    a = PointedArch(-w / 2, w / 2, 1.0, e, bottom=0.0)
    cl, cr = a.centers
    assert cl[1] == cr[1] == 1.0
    assert math.hypot(*(a.right_arc().start - [w / 2, 1.0])) <= 1e-12 * w
    # tangent at the springers is vertical (G1 with the jambs)
    assert abs(a.right_arc().tangent(0.0)[0]) <= 1e-12
    assert abs(a.left_arc().tangent(1.0)[0]) <= 1e-12
    assert is_closed(a.curves())


def test_kinds_by_excess():
    assert [arch_kind(e) for e in (0.5, 0.7, 1.0, 1.4)] == ["round", "four-centred", "equilateral", "lancet"]
    # the round arch: both centres at the midpoint, apex = half the span
    r = ARCHES["round"]
    assert r.centers.tolist() == [[0.0, 4.0], [0.0, 4.0]]
    assert r.rise == 1.0
    # the equilateral arch: centres on the springers, apex and springers an equilateral triangle
    eq = ARCHES["equilateral"]
    assert eq.centers.tolist() == [[1.0, 4.0], [-1.0, 4.0]]
    assert eq.rise == pytest.approx(math.sqrt(3.0), rel=1e-15)


@pytest.mark.parametrize("name", sorted(ARCHES))
@pytest.mark.parametrize("d", [-0.2, 0.05, 0.3])
def test_offset_keeps_the_centres_and_changes_the_excess(name, d):
    a = ARCHES[name]
    if 2 * d >= a.span * (1 - 1e-9):
        with pytest.raises(ParameterError):
            a.offset(d)
        return
    o = a.offset(d)
    assert np.array_equal(o.centers, a.centers) or np.allclose(o.centers, a.centers, rtol=0, atol=1e-15)
    assert o.radius == pytest.approx(a.radius - d, rel=1e-14)
    assert o.excess == pytest.approx((a.radius - d) / (a.span - 2 * d), rel=1e-14)
    if name != "round" and d > 0:
        assert o.excess != pytest.approx(a.excess)  # Fig. 7c: simple scaling would keep it
    if name == "round":
        assert o.excess == pytest.approx(0.5, rel=1e-14)  # a round arch stays round


@settings(max_examples=60)
@given(st.sampled_from(sorted(ARCHES)), st.floats(-0.3, 0.28).filter(lambda d: abs(d) > 1e-3))
def test_analytic_offset_equals_the_generic_offset_of_the_loop(name, d):
    a = ARCHES[name]
    generic = offset_curves(a.curves(), d)
    analytic = a.offset(d).curves()
    assert len(generic.curves) == len(analytic)
    for g, h in zip(generic.curves, analytic, strict=True):
        assert g.kind == h.kind
        assert np.allclose(g.start, h.start, atol=1e-12) and np.allclose(g.end, h.end, atol=1e-12)
        if isinstance(g, Arc):
            assert np.allclose(g.center, h.center, atol=1e-13) and g.radius == pytest.approx(h.radius)


def test_offset_wider_than_the_arch_is_rejected_naming_the_border():
    with pytest.raises(ParameterError) as e:
        ARCHES["equilateral"].offset(1.0)
    assert e.value.name == "border" and "< 1" in str(e.value)


@pytest.mark.parametrize("bad, name", [(dict(excess=0.49), "excess"), (dict(right=-2.0), "span"),
                                       (dict(bottom=5.0), "height")])
def test_invalid_arches_name_the_parameter(bad, name):
    kw = dict(left=-1.0, right=1.0, springing=4.0, excess=1.0, bottom=0.0)
    kw.update(bad)
    with pytest.raises(ParameterError) as e:
        PointedArch(**kw)
    assert e.value.name == name


# -- the pointed trefoil arch (Fig. 12) ------------------------------------------------------

@pytest.mark.parametrize("name, params", [
    (n, p) for n in ("equilateral", "lancet", "off-centre")
    for p in ((0.5, 0.5, 0.55), (0.6, 0.55, 0.35), (0.7, 0.6, 0.25))
    if (n, p) != ("off-centre", (0.7, 0.6, 0.25))
])
def test_trefoil_is_closed_symmetric_and_tangent_where_the_paper_says(name, params):
    a = ARCHES[name]
    t = trefoil_arch(a, *params)
    assert is_closed(t) and signed_area(t) > 0
    sill, jamb_r, lobe, close, top, top_l, close_l, lobe_l, jamb_l = t
    # side lobe: centre on the springing line, tangent to the jamb at the springer
    assert lobe.center[1] == pytest.approx(a.springing, abs=1e-12)
    assert np.allclose(lobe.tangent(0.0), jamb_r.tangent(1.0), atol=1e-12)
    # upper lobe: the arch's own arc above the split, entered tangentially
    assert np.allclose(top.center, a.centers[1], atol=1e-12) and top.radius == pytest.approx(a.radius)
    assert np.allclose(close.tangent(1.0), top.tangent(0.0), atol=1e-9)
    # cusp: a sharp corner pointing into the opening (a right turn)
    t_in, t_out = lobe.tangent(1.0), close.tangent(0.0)
    assert t_in[0] * t_out[1] - t_in[1] * t_out[0] < -1e-3
    # mirror symmetry about the axis
    pts = np.concatenate([c.sample(9) for c in t])
    mir = pts * [-1, 1] + [2 * a.mid, 0]
    d = np.min(np.hypot(*(mir[:, None, :] - pts[None]).transpose(2, 0, 1)), axis=1)
    assert d.max() < 2e-2 * a.span
    # the trefoil stays inside the arch
    assert signed_area(t) < signed_area(a.curves())


def test_trefoil_parameters_are_validated():
    with pytest.raises(ParameterError) as e:  # too narrow a lancet for these lobes
        trefoil_arch(ARCHES["off-centre"], 0.7, 0.6, 0.25)
    assert e.value.name == "lobe" and "try a larger lobe or upper" in str(e.value)
    with pytest.raises(ParameterError) as e:
        trefoil_arch(ARCHES["lancet"], split=1.2)
    assert e.value.name == "split"
    with pytest.raises(ParameterError) as e:
        trefoil_arch(ARCHES["lancet"], 0.5, lobe=0.05, upper=0.05)
    assert e.value.name == "lobe"
