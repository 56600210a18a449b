"""Side views: ogee biarcs, decorations (suppl. C) and free ends, exactly."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from auszug.errors import DrawingError
from auszug.microarch import sideview as sv


def _tangent(view: sv.SideView, i: int, g: float) -> np.ndarray:
    """Unit tangent (towards increasing g) of arc i of a side view at g."""
    c = view.centers[i]
    z = c[1] + view.upper[i] * math.sqrt(max(view.radii[i] ** 2 - (g - c[0]) ** 2, 0.0))
    rad = np.array([g - c[0], z - c[1]])
    t = np.array([-rad[1], rad[0]])
    t = t if t[0] > 0 or (t[0] == 0 and t[1] > 0) else -t
    return t / np.linalg.norm(t)


def test_symmetric_ogee_is_two_quarter_circles():
    v = sv.ogee(2.0, 1.0, 3.0, 1.0)
    assert v.radii.tolist() == [1.0, 1.0]
    assert float(v.height(1.0)) == 2.0
    assert float(v.height(0.0)) == 1.0 and float(v.height(2.0)) == 3.0


@pytest.mark.parametrize("bad", [(0.0, 0.0, 1.0, 0.5), (1.0, 1.0, 1.0, 0.5), (1.0, 0.0, 1.0, 1.0),
                                 (1.0, 2.0, 1.0, 0.5)])
def test_ogee_rejects_degenerate(bad):
    with pytest.raises(DrawingError):
        sv.ogee(*bad)


@settings(max_examples=200, deadline=None)
@given(st.floats(0.2, 3.0), st.floats(0.2, 4.0), st.floats(0.15, 0.85), st.floats(0.1, 0.9))
def test_decoration_equal_radii_keeps_ends_and_tangents(G, H, f, fd):
    base = sv.ogee(G, 0.0, H, f * G)
    gc = base.breaks[1]
    try:
        dec, (gd, zd) = sv.decorated(base, fd * gc)
    except DrawingError:
        assume(False)
    # two arcs of one radius, then the ogee's upper arc unchanged
    assert dec.radii[0] == dec.radii[1]
    np.testing.assert_array_equal(dec.centers[2], base.centers[1])
    # end points kept
    assert float(dec.height(0.0)) == 0.0
    assert math.isclose(float(dec.height(gc)), float(base.height(gc)), abs_tol=1e-12)
    # tangents kept: vertical at the bottom (centre on the bottom horizontal), the ogee's at C
    assert dec.centers[0, 1] == 0.0 and dec.centers[0, 0] == dec.radii[0]
    np.testing.assert_allclose(_tangent(dec, 1, gc), _tangent(base, 0, gc), atol=1e-9)
    # the cusp lies on both arcs, strictly between bottom and PRC, and is continuous
    assert 0.0 < gd < gc
    for i in (0, 1):
        assert math.isclose(math.dist(dec.centers[i], (gd, zd)), dec.radii[i], rel_tol=1e-9)
    # still a graph over g: heights finite everywhere
    assert np.all(np.isfinite(dec.height(np.linspace(0, G, 513))))


def test_decoration_reproduces_teaching_sheet_cusp():
    # U.XI.11 (2,3) = corpus tn-5: the demo stores its cusp at (0.18774 L, 0.24527);
    # the paper's equal-radius split through the same g puts it at z = 0.24572.
    L, H, f = 1.3063973828043032, 1.3088148665989052, 0.37548707508574464
    dec, (gd, zd) = sv.decorated(sv.ogee(L, 0.0, H, f * L), 0.18774353754287232 * L)
    assert math.isclose(gd / L, 0.18774353754287232, rel_tol=1e-12)
    assert abs(zd - 0.24526766608442982) < 1e-3


def test_free_end_continues_upper_arc():
    base = sv.ogee(1.0, 0.0, 2.0, 0.4)
    fe = sv.free_end(base)
    assert fe.radii[0] == base.radii[1]
    assert float(fe.height(0.0)) == 2.0
    # mirror image of the upper arc about the apex
    for g in np.linspace(0.0, 0.6, 13):
        assert math.isclose(float(fe.height(g)), float(base.height(1.0 - g)), abs_tol=1e-12)
