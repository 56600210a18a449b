"""The network: Eq. (1) with the three choices of p(u), pieces, ids, errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from auszug.errors import DrawingError
from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry, build


def _line_drawing(angle: float, **kw) -> Drawing:
    a = np.array([0.2, 0.1])
    b = a + 1.3 * np.array([math.cos(angle), math.sin(angle)])
    c = BasicCurve((tuple(a), tuple(b)), (Segment("line"),), ("ground", "apex"),
                   Symmetry(3, True, (1.0, 0.0)), height=1.7, prc=(0.35,), **kw)
    return Drawing((c,))


@pytest.mark.parametrize("angle", [0.0, 0.7, 2.5, -1.2])
def test_orthographic_along_a_straight_curve_equals_arclength(angle):
    d = _line_drawing(angle)
    a = build(d, "arclength")
    o = build(d, "orthographic", theta=angle)
    # the side-view plane contains the straight top view: p(u) is its arc length
    np.testing.assert_allclose(a.pieces[0].points, o.pieces[0].points, rtol=0, atol=1e-12)


def test_u_parameterisation_equals_arclength_on_lines_and_arcs_scaled():
    # p(u) = u is the arc length divided by L: the side view is the same ogee scaled
    # horizontally by 1/L, so the PRC and end heights agree and the interior differs
    d = _line_drawing(0.4)
    a, u = build(d, "arclength").pieces[0], build(d, "u").pieces[0]
    np.testing.assert_array_equal(a.points[:, :2], u.points[:, :2])
    assert a.points[0, 2] == u.points[0, 2] and a.points[-1, 2] == u.points[-1, 2]
    assert math.isclose(a.prc[2], u.prc[2], rel_tol=1e-12)


def test_orthographic_not_one_to_one_is_an_error():
    d = Drawing((BasicCurve(((1.0, 0.0), (-1.0, 0.0)), (Segment("arc", ((1.0, 1.0),)),),
                            ("ground", "apex"), height=1.0, prc=(0.5,)),))
    with pytest.raises(DrawingError, match="not one-to-one"):
        build(d, "orthographic", theta=math.pi / 2)   # a half circle seen along y folds over
    assert build(d, "orthographic", theta=0.0).pieces[0].points.shape == (65, 3)


def test_apex_at_or_below_bottom_is_a_clear_error():
    c = BasicCurve(((0, 0), (1, 0)), (Segment(),), ("ground", "apex"), height=0.0)
    with pytest.raises(DrawingError, match=r"curve 0.*apex height 0 is not above its layer bottom 0"):
        build(Drawing((c,)))


def test_ids_unique_and_labels():
    net = build(_line_drawing(0.3, post_top=2.5))
    ids = [c.id for c in net.curves()]
    assert len(ids) == len(set(ids))
    assert ids[:2] == ["0/r0", "0/r0m"]
    posts = [c for c in net.curves() if c.kind == "post"]
    assert len(posts) == 6 and all(np.all(p.points[:, :2] == p.points[0, :2]) for p in posts)
    assert all(p.points[0, 2] == 1.7 and p.points[1, 2] == 2.5 for p in posts)


def test_pillar_under_upper_layer_lands_on_lower_curve():
    low = BasicCurve(((1.0, 0.0), (0.0, 0.0)), (Segment("line"),), ("ground", "apex"), height=1.0, prc=(0.5,))
    up = BasicCurve(((0.5, 0.0), (0.0, 0.5)), (Segment("line"),), ("ground", "apex"), layer=1,
                    height=3.0, prc=(0.5,))
    net = build(Drawing((low, up), layer_bottoms=(0.0, 2.0)))
    (pillar,) = [p for p in net.pieces if p.kind == "pillar"]
    # the lower ogee's height half way: its PRC, on the chord -> 0.5
    np.testing.assert_allclose(pillar.points, [[0.5, 0.0, 0.5], [0.5, 0.0, 2.0]], atol=1e-12)
