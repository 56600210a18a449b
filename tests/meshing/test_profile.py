"""Profiles: built-in looks, lines and arcs, JSON, orientation, caps, and clear errors for bad ones."""

from __future__ import annotations

import math

import numpy as np
import pytest

from auszug.errors import GeometryError
from auszug.meshing.mesh import triangle_areas
from auszug.meshing.profile import (
    Profile,
    circle,
    from_dict,
    from_segments,
    polygon,
    rectangle,
    ribbon,
    square,
    triangulate_polygon,
)
from auszug.meshing.sweep import profile_for

#: A Gothic moulding of lines and arcs: a roll between two fillets over a flat back.
MOULDING = {
    "name": "roll and fillets",
    "closed": True,
    "start": [-1.0, 0.0],
    "segments": [
        {"line": [1.0, 0.0]},
        {"line": [1.0, 0.4]},
        {"line": [0.5, 0.4]},
        {"arc": [-0.5, 0.4], "center": [0.0, 0.4]},
        {"line": [-1.0, 0.4]},
    ],
    "scale": 0.01,
}


def _area(p: np.ndarray) -> float:
    x, y = p[:, 0], p[:, 1]
    return 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def test_square_bar_is_the_counter_clockwise_square_centred_on_the_curve():
    p = square(2.0)
    assert p.points.tolist() == [[-1, -1], [1, -1], [1, 1], [-1, 1]]
    assert p.closed and p.quarter_symmetric
    assert p.area == 4.0


def test_circle_points_lie_on_the_circle_and_turn_counter_clockwise():
    p = circle(0.5, 12)
    assert np.allclose(np.linalg.norm(p.points, axis=1), 0.5, rtol=0, atol=1e-15)
    assert p.area == pytest.approx(0.5 * 12 * 0.25 * math.sin(2 * math.pi / 12), rel=1e-14)
    assert p.quarter_symmetric and not circle(0.5, 10).quarter_symmetric


def test_clockwise_input_is_reversed():
    cw = polygon([[0, 0], [0, 1], [1, 1], [1, 0]])
    assert _area(cw.points) == 1.0


def test_ribbon_is_a_sheet_without_thickness_and_a_thin_box_with_it():
    sheet = ribbon(0.3)
    assert not sheet.closed and sheet.points[:, 1].tolist() == [0.0, 0.0]
    assert sheet.points[:, 0].tolist() == [-0.15, 0.15]
    box = ribbon(0.3, 0.02)
    assert box.closed and box.area == pytest.approx(0.006, rel=1e-12)
    assert not box.quarter_symmetric


def test_subdividing_a_rectangle_keeps_its_corners_and_shape():
    p = rectangle(2.0, 1.0, around=40)
    assert p.n == 40
    for c in ([-1, -0.5], [1, -0.5], [1, 0.5], [-1, 0.5]):
        assert np.min(np.linalg.norm(p.points - c, axis=1)) == 0.0
    assert p.area == pytest.approx(2.0, rel=1e-14)


def test_moulding_of_lines_and_arcs_from_json():
    p = from_dict(MOULDING, around=64)
    assert p.closed and p.name == "roll and fillets"
    # area: 2 x 0.4 rectangle plus a half disk of radius 0.5 (sampled), scaled by 0.01^2
    half_disk = 0.5 * math.pi * 0.25
    assert p.area == pytest.approx((0.8 + half_disk) * 1e-4, rel=5e-3)
    # the roll's samples lie on its circle
    roll = p.points[p.points[:, 1] > 0.0041]
    assert np.allclose(np.linalg.norm(roll - [0.0, 0.004], axis=1), 0.005, atol=1e-15)
    again = from_dict(p.to_dict())
    assert np.array_equal(again.points, p.points)


@pytest.mark.parametrize("seg", [
    {"arc": [-0.5, 0.4], "through": [0.0, 0.9]},
    {"arc": [-0.5, 0.4], "bulge": 1.0},
    {"arc": [-0.5, 0.4], "center": [0.0, 0.4], "ccw": True},
])
def test_three_ways_to_give_the_same_arc(seg):
    p = from_segments([0.5, 0.4], [seg], closed=False, around=8)
    assert np.allclose(np.linalg.norm(p.points - [0.0, 0.4], axis=1), 0.5, atol=1e-12)
    assert p.points[:, 1].max() == pytest.approx(0.9, abs=1e-12)   # passes over the top


def test_cap_triangles_cover_the_profile_exactly():
    for p in (square(1.0), circle(1.0, 17), from_dict(MOULDING), rectangle(1, 2, 9)):
        pts3 = np.concatenate([p.points, np.zeros((p.n, 1))], axis=1)
        assert triangle_areas(pts3, p.cap).sum() == pytest.approx(p.area, rel=1e-12)
        assert len(p.cap) == p.n - 2


def test_earcut_triangles_are_counter_clockwise_for_a_concave_polygon():
    poly = np.array([[0, 0], [4, 0], [4, 3], [2, 1], [0, 3.0]])
    t = triangulate_polygon(poly)
    a, b, c = poly[t[:, 0]], poly[t[:, 1]], poly[t[:, 2]]
    cross = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    assert np.all(cross > 0) and 0.5 * cross.sum() == pytest.approx(_area(poly))


def test_the_non_manifold_fill_is_counter_clockwise_and_covers_the_polygon_and_holes_exactly():
    """``manifold=False`` (earcut as it is, the live previews): still a fill of exactly the area."""
    outer = np.array([[0, 0], [2, 0], [4, 0], [4, 3], [2, 1], [0, 3.0]])   # a collinear vertex (2, 0)
    holes = [np.array([[3.0, 0.5], [3.0, 1.0], [3.5, 1.0], [3.5, 0.5]]),   # clockwise
             np.array([[0.5, 0.5], [1.0, 0.5], [1.0, 1.0]])]               # counter-clockwise
    pts = np.concatenate([outer, *holes])
    for hs in ([], holes):
        t = triangulate_polygon(outer, hs, manifold=False)
        assert t.min() >= 0 and t.max() < len(pts)
        a, b, c = pts[t[:, 0]], pts[t[:, 1]], pts[t[:, 2]]
        cross = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
        want = _area(outer) - sum(abs(_area(h)) for h in hs)
        assert np.all(cross >= 0) and 0.5 * cross.sum() == pytest.approx(want, rel=1e-12)


@pytest.mark.parametrize("make, message", [
    (lambda: polygon([[0, 0], [1, 1], [1, 0], [0, 1]]), "self-intersecting: edges 0 and 2"),
    (lambda: polygon([[0, 0], [0, 0], [0, 0]]), "zero size"),
    (lambda: polygon([[0, 0], [1, 0], [2, 0]]), "zero size: it encloses no area"),
    (lambda: polygon([[0, 0], [1, 0], [1, 0], [0, 1]]), "edge 1 from point 1 [1.0, 0.0] has zero length"),
    (lambda: polygon([[0, 0], [1, 0]]), "a closed profile needs at least 3 points"),
    (lambda: polygon([[0, 0], [1, 0], [float("nan"), 1]]), "finite"),
    (lambda: circle(0.0), "zero size is not a profile"),
    (lambda: square(-1.0), "positive number"),
    (lambda: ribbon(0.1, -0.01), "ribbon thickness must be a positive number"),
    (lambda: from_dict({"segments": []}), "needs a 'start' point"),
    (lambda: from_dict({"start": [0, 0], "segments": [{"spline": [1, 1]}]}), "'line' or 'arc' key"),
    (lambda: from_dict({"start": [0, 0], "segments": [{"arc": [1, 0]}]}), "'through', 'bulge' or 'center'"),
    (lambda: from_dict({"start": [0, 0], "segments": [{"arc": [1, 0], "center": [0, 5]}]}),
     "not equally far from the centre"),
    (lambda: from_dict({"points": [[0, 0], [2, 0], [2, 1], [1, -1]]}), "self-intersecting"),
    (lambda: from_dict({"points": [[0, 0], [1, 0], [0, 1]], "scale": 0}), "scale must be a positive"),
    (lambda: from_dict([1, 2]), "must be a JSON object"),
    (lambda: profile_for("cable", 0.1), "style must be one of tube, bar, ribbon"),
])
def test_bad_profiles_give_clear_errors(make, message):
    with pytest.raises(GeometryError, match=message.replace("[", r"\[").replace("]", r"\]")):
        make()


def test_an_open_profile_where_a_closed_one_is_needed():
    p = from_dict({"points": [[0, 0], [1, 0], [1, 1]], "closed": False})
    with pytest.raises(GeometryError, match="profile 'profile' is open; a solid needs a closed profile"):
        p.require_closed("a solid")
    with pytest.raises(GeometryError, match="caps and solids need a closed profile"):
        p.cap  # noqa: B018  (the property raises)
    assert Profile(p.points, False).closed is False


def test_the_one_triangulator_fills_holes_on_a_shared_line_with_collinear_points():
    """Two lights whose sills lie on one line, every edge subdivided: earcut alone drops the collinear
    vertices and bridges along the line; the result must still use every ring edge once, no slivers."""
    def ring(x0, x1, y0, y1, k):
        t = np.arange(k) / k
        return np.concatenate([np.stack([x0 + (x1 - x0) * t, 0 * t + y0], 1),
                               np.stack([0 * t + x1, y0 + (y1 - y0) * t], 1),
                               np.stack([x1 - (x1 - x0) * t, 0 * t + y1], 1),
                               np.stack([0 * t + x0, y1 - (y1 - y0) * t], 1)])
    outer = ring(0.0, 10.0, 0.0, 6.0, 5)
    holes = [ring(1.0, 4.0, 1.0, 5.0, 4), ring(6.0, 9.0, 1.0, 5.0, 4)]
    t = triangulate_polygon(outer, holes)
    pts = np.concatenate([outer, *holes])
    n = len(pts)
    assert len(t) == n - 2 + 2 * len(holes)
    a, b, c = pts[t[:, 0]], pts[t[:, 1]], pts[t[:, 2]]
    cross = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    assert np.all(cross > 1e-9) and 0.5 * cross.sum() == pytest.approx(60.0 - 24.0, rel=1e-12)
    e = np.sort(np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    assert (counts == 1).sum() == n and counts.max() == 2   # each ring edge once, inner edges twice


@pytest.mark.parametrize("deg", [160.0, 200.0, 300.0, -200.0, -300.0])
def test_arcs_over_half_a_turn_end_at_their_vertices(deg):
    """An arc of more than 180 deg has its centre on the far side of the chord: the sampled arc runs
    from vertex to vertex on one circle, through the point at half its sweep."""
    p = Profile(np.array([[1.0, 0.0], [-1.0, 0.0]]), closed=False, bulge=[np.tan(np.radians(deg) / 4)])
    q = p.sample(per_arc=64)
    assert np.abs(q[0] - [1, 0]).max() <= 1e-12 and np.abs(q[-1] - [-1, 0]).max() <= 1e-12
    th = np.radians(deg)
    r = 1 / abs(np.sin(th / 2))
    centre = np.array([0.0, -np.sign(th) * r * np.cos(th / 2)])
    assert np.abs(np.linalg.norm(q - centre, axis=1) - r).max() <= 1e-12
    # the midpoint of a counter-clockwise arc from (1, 0) to (-1, 0) is above the centre, below for clockwise
    assert np.abs(p.point([0.5])[0] - (centre + [0.0, np.sign(th) * r])).max() <= 1e-12
    assert p.length == pytest.approx(r * abs(th), rel=1e-12)
