"""The prototype window: the rosette circle from the ellipse, the partition, validation."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings

from auszug.errors import DrawingError
from auszug.geometry.offset import is_closed, signed_area
from auszug.tracery import ParameterError, WindowParams, prototype
from auszug.tracery.window import CELLS, ellipse_axis_point
from tests.tracery.cases import PAPER, dist_to_curves, window_params


def _tangency(w):
    """Distances of the circle centre to E's arcs and the sub-arches' inner arcs, minus the radius."""
    c, rc = w.circle_center, w.circle_radius
    e, (sl, sr) = w.ensemble, w.sub_arches
    out = []
    for arc in (e.right_arc(), e.left_arc(), sl.right_arc(), sr.left_arc()):
        out.append(dist_to_curves(c, [arc]) - rc)
    return np.array(out)


def test_paper_call_circle_touches_the_arch_and_both_sub_arches():
    w = prototype(PAPER)
    assert np.abs(_tangency(w)).max() < 1e-9
    assert w.tangency_residual() < 1e-9
    assert w.circle_center[0] == 0.0  # on the axis


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(window_params())
def test_circle_touches_the_arch_and_both_sub_arches_for_any_valid_window(p):
    try:
        w = prototype(p)
    except ParameterError:
        assume(False)
    assert np.abs(_tangency(w)).max() < 1e-9 * max(1.0, p.span)
    # the centre is on the ellipse with foci m_R, m_LR and radius sum r_E + r_s
    f1, f2 = w.ensemble.centers[1], w.sub_arches[1].centers[0]
    s = np.hypot(*(w.circle_center - f1)) + np.hypot(*(w.circle_center - f2))
    assert s == pytest.approx(w.ensemble.radius + w.sub_arches[1].radius, rel=1e-12)
    assert w.circle_center[0] == pytest.approx(p.x, abs=1e-12 * (1 + abs(p.x)))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(window_params())
def test_the_seven_cells_partition_the_ensemble(p):
    try:
        w = prototype(p)
    except ParameterError:
        assume(False)
    total = 0.0
    for name in CELLS:
        cell = w.cells[name]
        assert is_closed(cell, 1e-9), name
        a = signed_area(cell)
        assert a > 0, name  # counter-clockwise
        total += a
    assert total == pytest.approx(signed_area(w.ensemble.curves()), rel=1e-11)
    # each region (the cell offset by inner) keeps the border from its cell
    for name in CELLS:
        reg = w.regions[name]
        pts = np.concatenate([c.sample(9) for c in reg])
        d = np.array([dist_to_curves(q, w.cells[name]) for q in pts])
        assert d.min() >= p.inner - 1e-9, name
        assert signed_area(reg) < signed_area(w.cells[name])


def test_ellipse_axis_point_is_on_the_ellipse():
    f1, f2 = np.array([-1.3, 4.0]), np.array([0.45, 3.8])
    p = ellipse_axis_point(f1, f2, 3.5, 0.0)
    assert p[0] == 0.0
    assert np.hypot(*(p - f1)) + np.hypot(*(p - f2)) == pytest.approx(3.5, rel=1e-14)
    assert ellipse_axis_point(f1, f2, 1.0, 0.0) is None  # sum below the focal distance
    assert ellipse_axis_point(f1, f2, 3.5, 50.0) is None  # the line misses it


def test_excess_one_puts_the_centres_on_the_springers():
    w = prototype(WindowParams(excess=1.0, drop=0.0, outer=0.0, inner=0.05))
    sl, sr = w.sub_arches
    assert w.arch.centers.tolist() == [[1.0, 4.0], [-1.0, 4.0]]
    assert sl.centers.tolist() == [[0.0, 4.0], [-1.0, 4.0]]
    assert sr.centers.tolist() == [[1.0, 4.0], [0.0, 4.0]]


def test_drop_sets_the_sub_arches_down_and_enlarges_the_circle():
    r = [prototype(PAPER, drop=d).circle_radius for d in (0.0, 0.2, 0.4)]
    assert r[0] < r[1] < r[2]
    assert prototype(PAPER, drop=0.4).sub_arches[0].springing == pytest.approx(3.6)


@pytest.mark.parametrize("kw, name, valid", [
    (dict(excess=0.4), "excess", ">= 0.5"),
    (dict(span=-2.0), "span", "> 0"),
    (dict(inner=0.0), "inner", "> 0"),
    (dict(inner=0.3), "inner", "< 0.225"),
    (dict(outer=-0.1), "outer", ">= 0"),
    (dict(drop=3.9), "drop", "< 3.8"),
    (dict(drop=-0.1), "drop", ">= 0"),
])
def test_invalid_parameters_name_the_parameter_and_its_range(kw, name, valid):
    with pytest.raises(ParameterError) as e:
        prototype(PAPER, **kw)
    assert e.value.name == name
    assert str(e.value).startswith(f"{name}: expected") and valid in str(e.value)
    assert isinstance(e.value, DrawingError)


@pytest.mark.parametrize("kw, names", [
    (dict(inner=0.2), ("inner",)),  # the top fillet vanishes
    (dict(excess=2.5), ("drop", "excess")),  # the circle would touch beyond the sub-arch apexes
    (dict(drop=3.0), ("drop",)),  # no circle fits
    (dict(excess=0.5, drop=0.0), ("excess", "drop")),  # the circle would reach the apex
])
def test_geometric_misfits_report_a_valid_interval_of_the_blamed_parameter(kw, names):
    with pytest.raises(ParameterError) as e:
        prototype(PAPER, **kw)
    name = e.value.name
    assert name in names
    text = str(e.value)
    assert "expected a number in" in text
    lo, hi = (float(t) for t in text.split("in ")[1].split("]")[0].strip("[(").split(", "))
    # the interval is right: inside it the window fits, just beyond its upper end it does not
    prototype(PAPER, **{**kw, name: hi * (1 - 1e-6)})
    prototype(PAPER, **{**kw, name: 0.5 * (lo + hi)})
    with pytest.raises(ParameterError):
        prototype(PAPER, **{**kw, name: hi * 1.002})


def test_params_from_mapping_rejects_unknown_names():
    with pytest.raises(ParameterError) as e:
        WindowParams.from_mapping({"spam": 2.0})
    assert e.value.name == "spam" and "excess" in str(e.value)
    assert WindowParams.from_mapping(PAPER.as_dict()) == PAPER
    assert PAPER.scaled(2.0).span == 4.0 and PAPER.scaled(2.0).excess == PAPER.excess


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(window_params())
def test_the_left_fillet_is_the_offset_of_its_cell_and_the_right_ones_mirror_image(p):
    """regions mirrors the right fillet's opening (one offset fewer): the exact offset of the left cell."""
    from auszug.geometry.offset import offset_curves
    from auszug.tracery.model import polygon

    try:
        w = prototype(p)
    except ParameterError:
        assume(False)
    left, right = w.regions["fillet-left"], w.regions["fillet-right"]
    direct = offset_curves(w.cells["fillet-left"], p.inner, closed=True).curves
    assert list(w.regions) == list(CELLS) and is_closed(left) and signed_area(left) > 0
    pts = polygon(left, max_angle=np.pi / 256)
    span = p.span
    assert max(dist_to_curves(q, direct) for q in pts) < 1e-9 * span
    assert max(dist_to_curves(q, left) for q in polygon(direct, max_angle=np.pi / 256)) < 1e-9 * span
    mirrored = pts * [-1.0, 1.0] + [2.0 * w.ensemble.mid, 0.0]
    assert max(dist_to_curves(q, right) for q in mirrored) < 1e-9 * span
