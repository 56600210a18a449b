"""geometry.offset: exact offsets of line/arc loops (the kernel the tracery builds on).

Kept with the tracery tests, whose regions and profiles are its main users.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from auszug.errors import GeometryError
from auszug.geometry import Arc, Line
from auszug.geometry.offset import is_closed, offset_curves, signed_area
from auszug.tracery import rosette
from auszug.tracery.window import prototype
from tests.tracery.cases import CIRCLE, PAPER, SQUARE, dist_to_curves


def _samples(curves, n=7):
    return np.concatenate([c.sample(n) for c in curves])


def test_circle_offset_changes_only_the_radius():
    (c,) = offset_curves(CIRCLE, 0.4).curves
    assert np.array_equal(c.center, CIRCLE[0].center) and c.radius == pytest.approx(1.1)
    (c,) = offset_curves(CIRCLE, -0.4).curves
    assert c.radius == pytest.approx(1.9)
    with pytest.raises(GeometryError):
        offset_curves(CIRCLE, 1.6)


@pytest.mark.parametrize("d", [0.1, 0.5, 0.99])
def test_square_inset_is_the_exact_smaller_square(d):
    off = offset_curves(SQUARE, d)
    starts = np.array([c.start for c in off.curves])
    assert np.allclose(starts, [[d, d], [2 - d, d], [2 - d, 2 - d], [d, 2 - d]], rtol=0, atol=1e-15)
    assert signed_area(off.curves) == pytest.approx((2 - 2 * d) ** 2, rel=1e-12)


def test_square_outset_mitres_or_rounds_by_the_limit():
    mitred = offset_curves(SQUARE, -0.5)
    assert len(mitred.curves) == 4 and not mitred.is_join.any()
    assert signed_area(mitred.curves) == pytest.approx(9.0)
    rounded = offset_curves(SQUARE, -0.5, miter_limit=1.2)  # sqrt(2) > 1.2: round joins
    assert rounded.is_join.sum() == 4
    assert signed_area(rounded.curves) == pytest.approx(4 + 4 * 2 * 0.5 + math.pi * 0.25, rel=1e-12)
    for c in rounded.curves:
        if isinstance(c, Arc):
            assert c.radius == 0.5 and c.sweep == pytest.approx(math.pi / 2)


def test_a_region_narrower_than_twice_the_offset_is_rejected():
    thin = (Line((0, 0), (2, 0)), Line((2, 0), (2, 0.4)), Line((2, 0.4), (0, 0.4)), Line((0, 0.4), (0, 0)))
    assert signed_area(offset_curves(thin, 0.15).curves) == pytest.approx(1.7 * 0.1)
    with pytest.raises(GeometryError, match="narrower than 0.6"):
        offset_curves(thin, 0.3)


def test_vanishing_pieces_are_removed_and_neighbours_reintersected():
    # a trapezoid whose short top edge disappears: the inset is a triangle
    trap = (Line((0, 0), (4, 0)), Line((4, 0), (2.2, 1.8)), Line((2.2, 1.8), (1.8, 1.8)), Line((1.8, 1.8), (0, 0)))
    off = offset_curves(trap, 0.6)
    assert off.source.tolist() == [0, 1, 3]
    assert is_closed(off.curves)
    for p in _samples(off.curves):
        assert dist_to_curves(p, trap) >= 0.6 - 1e-9


def test_rosette_cusps_get_round_joins_and_fillet_tips_are_trimmed():
    (loop,) = rosette((0, 0), 1.0, 4)
    off = offset_curves(loop, 0.05)
    assert off.is_join.sum() == 4  # the four spikes between the foils
    w = prototype(PAPER)
    top = offset_curves(w.cells["fillet-top"], PAPER.inner)
    assert not top.is_join.any() and len(top.curves) == 3  # three arcs, the tips cut off


CASES = {
    "square": SQUARE,
    "circle": CIRCLE,
    "quatrefoil": rosette((0, 0), 1.0, 4)[0],
    "pointed trefoil": rosette((0.5, -1), 2.0, 3, pointed=True)[0],
    **{name: cell for name, cell in prototype(PAPER).cells.items()},
}


@settings(max_examples=80, deadline=None)
@given(st.sampled_from(sorted(CASES)), st.floats(-0.05, 0.05).filter(lambda d: abs(d) > 1e-4))
def test_every_offset_point_keeps_the_offset_distance(name, d):
    base = CASES[name]
    try:
        off = offset_curves(base, d, check=True)
    except GeometryError:
        # only a region thinner than 2|d| may vanish: check it really is that thin somewhere
        assert d > 0 and name.startswith("fillet")
        return
    assert is_closed(off.curves, 1e-9)
    dist = np.array([dist_to_curves(p, base) for p in _samples(off.curves)])
    # exactly |d| from the input, except on mitres at separating corners (at most the limit)
    assert dist.min() >= abs(d) - 1e-9 and dist.max() <= 4.0 * abs(d) + 1e-9
    assert np.mean(np.abs(dist - abs(d)) <= 1e-9) > 0.7
    # inwards shrinks, outwards grows
    assert (signed_area(off.curves) < signed_area(base)) == (d > 0)


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(["square", "quatrefoil", "pointed trefoil", "fillet-top", "sub-arch-left"]),
       st.floats(-math.pi, math.pi), st.floats(-9, 9), st.floats(-9, 9))
def test_offsets_commute_with_rigid_motions(name, angle, dx, dy):
    base = CASES[name]
    m = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
    off = offset_curves(base, 0.02).curves
    moved = offset_curves([c.transformed(m, (dx, dy)) for c in base], 0.02).curves
    assert len(off) == len(moved)
    for a, b in zip(off, moved, strict=True):
        assert np.allclose(m @ a.start + [dx, dy], b.start, atol=1e-9)


@pytest.mark.parametrize("name", ["square", "quatrefoil", "fillet-right", "sub-arch-right"])
def test_reversed_loop_offset_the_other_way_is_the_same_curve(name):
    base = CASES[name]
    a = offset_curves(base, 0.03).curves
    b = offset_curves([c.reversed() for c in reversed(base)], -0.03).curves
    pa, pb = _samples(a), _samples(b)
    d = np.hypot(*(pa[:, None, :] - pb[None]).transpose(2, 0, 1)).min(axis=1)
    assert d.max() < 1e-3  # same point set (different sampling)
    assert signed_area(a) == pytest.approx(-signed_area(b), rel=1e-12)


def test_open_chain_offset_keeps_the_centres():
    right = Arc.from_center((-1.0, 0.0), 2.0, 0.0, math.pi / 3)
    left = Arc.from_center((1.0, 0.0), 2.0, 2 * math.pi / 3, math.pi)
    arch = offset_curves([right, left], 0.25)
    assert not arch.closed
    assert [c.center.tolist() for c in arch.curves] == [[-1.0, 0.0], [1.0, 0.0]]
    assert arch.curves[0].end == pytest.approx(arch.curves[1].start)
    assert arch.curves[0].end[0] == pytest.approx(0.0, abs=1e-12)
