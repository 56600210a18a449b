"""Rosettes: the foil radius formula, tangency of neighbouring foils, pointed foils, orientation."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from auszug.geometry import Arc
from auszug.geometry.offset import is_closed, signed_area
from auszug.tracery import ParameterError, foil_radius, rosette
from auszug.tracery.rosette import foil_tangency_residual


@pytest.mark.parametrize("n", range(2, 13))
def test_foil_radius_formula_and_its_derivation(n):
    a = 2 * math.pi / n
    r = foil_radius(n)
    assert r == pytest.approx(math.sin(a / 2) / (1 + math.sin(a / 2)), rel=1e-15)
    # Fig. 9b: the perpendicular from m (at 1 - r from c) on the line at angle a/2 has length r
    assert (1 - r) * math.sin(a / 2) == pytest.approx(r, rel=1e-14)


@given(st.integers(3, 12), st.booleans(), st.sampled_from(["standing", "lying"]),
       st.floats(0.1, 5), st.floats(-3, 3), st.floats(-3, 3))
def test_foils_touch_each_other_and_the_circle(n, pointed, orientation, radius, x, y):
    (loop,) = rosette((x, y), radius, n, pointed=pointed, orientation=orientation)
    assert len(loop) == (2 * n if pointed else n)
    assert is_closed(loop, 1e-9 * radius) and foil_tangency_residual(loop) <= 1e-12 * (1 + radius + abs(x) + abs(y))
    assert signed_area(loop) > 0
    c = np.array([x, y])
    pts = np.concatenate([a.sample(257) for a in loop])
    far = np.hypot(*(pts - c).T)
    # inscribed: the foils reach the circle and stay inside it
    assert far.max() == pytest.approx(radius, rel=1e-4)
    assert far.max() <= radius * (1 + 1e-12)
    if not pointed:
        # neighbouring foils are tangent where they meet: the loop is G1 up to the reversal
        for i in range(n):
            t_in, t_out = loop[i].tangent(1.0), loop[(i + 1) % n].tangent(0.0)
            assert np.allclose(t_in, -t_out, atol=1e-9)
            assert loop[i].radius == pytest.approx(radius * foil_radius(n), rel=1e-12)


def test_pointed_foils_use_the_displaced_centres():
    (loop,) = rosette((0, 0), 1.0, 4, pointed=True, displacement=1.15)
    r = foil_radius(4)
    for arc in loop:
        assert isinstance(arc, Arc)
    # all arcs share the radius 1.15 r, scaled down so that the tips touch the circle
    radii = {round(a.radius, 12) for a in loop}
    assert len(radii) == 1
    scale = next(iter(radii)) / (1.15 * r)
    tips = np.array([loop[i].end for i in range(0, len(loop), 2)])
    assert np.allclose(np.hypot(*tips.T), 1.0, atol=1e-12)
    assert 0.5 < scale < 1.0
    # tips are corners (pointed), feet a, b are tangent joints
    for i in range(0, len(loop), 2):
        t_in, t_out = loop[i].tangent(1.0), loop[i + 1].tangent(0.0)
        assert abs(t_in[0] * t_out[1] - t_in[1] * t_out[0]) > 0.05


def test_standing_has_a_foil_on_top_and_lying_a_cusp():
    top = np.array([0.0, 1.0])
    (stand,) = rosette((0, 0), 1.0, 4, orientation="standing")
    (lie,) = rosette((0, 0), 1.0, 4, orientation="lying")
    d_stand = min(float(np.hypot(*(a.sample(721) - top).T).min()) for a in stand)
    d_lie = min(float(np.hypot(*(a.sample(721) - top).T).min()) for a in lie)
    assert d_stand < 1e-5 < 0.1 < d_lie


def test_two_foils_are_two_loops():
    loops = rosette((0, 0), 1.0, 2)
    assert len(loops) == 2 and all(len(lp) == 1 and abs(lp[0].sweep) == pytest.approx(2 * math.pi) for lp in loops)


@pytest.mark.parametrize("kw, name", [(dict(foils=1), "foils"), (dict(foils=2.5), "foils"),
                                      (dict(displacement=0.9, pointed=True), "displacement"),
                                      (dict(orientation="upside-down"), "orientation"), (dict(radius=0), "radius")])
def test_invalid_rosettes_name_the_parameter(kw, name):
    args = dict(center=(0, 0), radius=1.0, foils=4)
    args.update(kw)
    with pytest.raises(ParameterError) as e:
        rosette(**args)
    assert e.value.name == name and "expected" in str(e.value)
