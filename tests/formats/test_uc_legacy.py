"""The legacy and v1 .uc readers (formats.uc_legacy): corpus facts, conventions, errors.

Expected values were read by hand from the corpus text files.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from auszug.errors import FormatError
from auszug.formats import load
from auszug.formats.uc import read_uc
from auszug.formats.uc_legacy import read_legacy
from tests.conftest import CORPUS, corpus_files

LEGACY = CORPUS / "legacy"


def _cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def _legacy(name):
    return load(LEGACY / f"{name}.uc")


def _longest_chord(d):
    return max(math.dist(a, b) for c in d.curves for a, b in zip(c.vertices[:-1], c.vertices[1:], strict=True))


# -- every legacy file ---------------------------------------------------------------------------
@pytest.mark.parametrize("path", corpus_files("legacy"), ids=lambda p: p.name)
def test_legacy_heights_follow_the_prototype_rule(path):
    d = load(path)
    n_units = path.read_text().count("unitCurve")
    assert len(d.curves) == n_units
    assert d.default_apex == max(1.0, _longest_chord(d))
    assert d.layer_bottoms == () and d.bottoms() == (0.0,)
    for c in d.curves:
        assert c.layer == 0 and c.height is None and c.prc == (None,) * len(c.segments)
        assert c.symmetry.center == (0.0, 0.0)
        assert not c.decoration and c.post_top is None
    assert d.name == path.name[:-3]


# -- concrete facts, checked by hand against the text -----------------------------------------
def test_u_xi_20_bezier_handles_and_axis_rules():
    d = _legacy("U.XI.20")
    assert len(d.curves) == 4
    c0, c1, c2, c3 = d.curves
    assert c0.vertices == ((-0.15, 1.1), (1.0, 0.6))
    assert c0.marks == ("apex", "apex")
    assert c0.symmetry.fold == 4 and c0.symmetry.mirror
    assert c0.symmetry.axis == (0.0, 1.0) and c0.symmetry.axis_rule == "y axis"
    assert c0.segments[0].kind == "bezier"
    # ptTan (0.1, -0.2) at (-0.15, 1.1) and (-0.5, 0) at (1, 0.6): each points into the segment
    np.testing.assert_allclose(c0.segments[0].handles, [(-0.05, 0.9), (0.5, 0.6)], atol=1e-15)
    assert c1.marks == ("ground", "apex") and c1.symmetry.axis_rule == "first point"
    np.testing.assert_allclose(c1.segments[0].handles, [(0.8, 0.0), (1.0, 0.4)], atol=1e-15)
    assert c2.segments[0].kind == "line"  # no ptTan
    assert c3.vertices == ((1.2, 0.0), (1.0, 0.18))
    assert d.default_apex == pytest.approx(math.hypot(1.15, 0.5))  # curve 0's chord


def test_u_xi_22_seven_curves_levels_and_unmirrored():
    d = _legacy("U.XI.22")
    assert len(d.curves) == 7
    assert [c.symmetry.fold for c in d.curves] == [4, 4, 4, 4, 4, 2, 2]
    assert [c.symmetry.mirror for c in d.curves] == [False, False, False, True, True, True, True]
    assert [c.marks for c in d.curves][2] == ("apex", "apex")
    assert d.curves[5].marks == ("ground", "ground")
    assert d.curves[6].symmetry.axis == (1.8, 0.0) and d.curves[6].symmetry.axis_rule == "first point"
    assert d.curves[2].segment_kind(0) == "level" and d.curves[0].segment_kind(0) == "ogee"
    assert d.default_apex == pytest.approx(math.hypot(2.1, 0.4))  # (0.4, 0.4)-(2.5, 0)


def test_u_xi_28_five_point_polyline():
    d = _legacy("U.XI.28")
    (c,) = d.curves
    assert len(c.vertices) == 5 and len(c.segments) == 4
    assert c.marks == ("ground", "apex", "ground", "apex", "ground")
    assert all(s.kind == "line" for s in c.segments)
    assert [c.segment_kind(i) for i in range(4)] == ["ogee"] * 4
    assert (c.symmetry.fold, c.symmetry.mirror) == (4, True)


def test_u_xi_17_free_end_label():
    c = _legacy("U.XI.17").curves[1]
    assert c.vertices == ((-0.5, 0.0), (-0.3, -0.5), (0.1, -0.2))
    assert c.marks == ("ground", "apex", "free")
    assert c.segment_kind(1) == "free_end"
    assert (c.symmetry.fold, c.symmetry.mirror, c.symmetry.axis) == (2, True, (-0.5, 0.0))


def test_reflection_point_rounded_to_six_decimals_snaps_to_its_vertex():
    # U.XI.24 curve 1: reflectionPoint 1.125833 0.650000, last ptPos 1.125833024920 0.65
    s = _legacy("U.XI.24").curves[1].symmetry
    assert s.axis == (1.12583302492, 0.65) and s.axis_rule == "last point"
    # tn-10: reflectionPoint -0.866025 -0.5 is the first point -0.866025403784 -0.5
    s = _legacy("tn-10").curves[0].symmetry
    assert s.axis == (-0.866025403784, -0.5) and s.axis_rule == "first point"
    # U.XI.23: the axis passes through a middle vertex: kept as given, rule fixed
    s = _legacy("U.XI.23").curves[0].symmetry
    assert s.axis == (-1.0, -1.0) and s.axis_rule == "fixed"


def test_v1_two_curves_absolute_control_points():
    d = load(CORPUS / "web" / "two_curves.uc")
    assert len(d.curves) == 2 and d.name == "two_curves"
    c0, c1 = d.curves
    assert c0.vertices == ((0.03141201393737509, -0.4829961833433339),
                           (-0.7292043925307743, -0.04739825023005989))
    assert c0.segments[0].kind == "bezier"
    assert c0.segments[0].handles == ((-0.14522522611828884, -0.38403219657078796),
                                      (-0.5770563570855491, -0.09456590657404791))
    assert c1.segments[0].handles == ((-0.17741133420871513, -0.0528036510765276),
                                      (-0.37960396415552855, -0.7286983596601453))
    for c in d.curves:
        assert c.marks == ("ground", "apex")
        assert (c.symmetry.fold, c.symmetry.mirror) == (2, True)
        assert c.symmetry.axis == (-0.471455422235723, -0.030661452004875286)
    assert c0.symmetry.axis_rule == "fixed" and c1.symmetry.axis_rule == "first point"
    assert d.default_apex == 1.0


def test_v1_handles_lie_near_the_chord_of_the_straight_rib():
    # evidence for "absolute": curve 0's handles are within 0.04 of its chord
    c = load(CORPUS / "web" / "two_curves.uc").curves[0]
    a, b = np.array(c.vertices)
    d = (b - a) / np.linalg.norm(b - a)
    for h in np.array(c.segments[0].handles):
        assert abs(d[0] * (h - a)[1] - d[1] * (h - a)[0]) < 0.04


# -- the ptTan convention, from the drawings ----------------------------------------------------
def test_opposite_ptTan_vectors_join_smoothly():
    # U.XI.22 curves 0 and 1 start at (0.4, 0.4) with vectors (-0.1, 0.25) and (0.1, -0.25)
    c0, c1 = _legacy("U.XI.22").curves[:2]
    assert c0.vertices[0] == c1.vertices[0] == (0.4, 0.4)
    t0 = c0.top_curve(0).tangent(0.0)
    t1 = c1.top_curve(0).tangent(0.0)
    np.testing.assert_allclose(t0, -t1, atol=1e-15)


@pytest.mark.parametrize("name, ci, vi", [("U.XI.25", 0, 1), ("U.XI.30", 0, 0), ("U.XI.31", 0, 0),
                                          ])
def test_mirror_replicas_meet_with_common_tangent_on_the_axis(name, ci, vi):
    c = _legacy(name).curves[ci]
    p = np.array(c.vertices[vi])
    axis = np.array(c.symmetry.axis) / np.hypot(*c.symmetry.axis)
    assert abs(_cross(axis, p)) < 1e-12  # the point is on the axis
    top = c.top_curve(0)
    t = top.tangent(0.0 if vi == 0 else 1.0)
    assert abs(t @ axis) < 1e-12
    # and the curve leaves the point towards its own other end, not across the axis
    other = np.array(c.vertices[1 - vi])
    inner = top.point(0.05 if vi == 0 else 0.95)
    assert np.sign(_cross(axis, inner)) == np.sign(_cross(axis, other))


def _angle(u, v):
    u, v = np.asarray(u, float), np.asarray(v, float)
    return math.degrees(math.acos(np.clip(u @ v / np.linalg.norm(u) / np.linalg.norm(v), -1, 1)))


@pytest.mark.parametrize("name, legacy_curve, web_curve", [
    ("U.XI.29", 0, 0), ("U.XI.29", 1, 1), ("U.XI.31", 0, 0), ("U.XI.31", 1, 1), ("U.XI.34", 0, 2)])
def test_handles_agree_with_the_authors_web_redraw(name, legacy_curve, web_curve):
    """End tangent vs chord (invariant under the rescaling/mirroring between the two drawings)."""
    leg = _legacy(name).curves[legacy_curve]
    web = load(CORPUS / "web" / f"{name}.uc").curves[web_curve]
    p = [np.array(v) for v in leg.vertices]
    h = [np.array(v) for v in leg.segments[0].handles]
    if leg.marks[0] != "ground":
        p, h = p[::-1], h[::-1]
    wa, wb = (np.array(v) for v in web.vertices)
    arc = web.top_curve(0)
    for end, (vec, chord, wtan, wchord) in enumerate([
        (h[0] - p[0], p[1] - p[0], arc.tangent(0.0), wb - wa),
        (h[1] - p[1], p[0] - p[1], -arc.tangent(1.0), wa - wb),
    ]):
        if np.hypot(*vec) == 0.0:
            continue
        web_angle = _angle(wtan, wchord)
        assert abs(_angle(vec, chord) - web_angle) < 35.0, end  # P + t: the reading we use
        assert abs(_angle(-vec, chord) - web_angle) > 75.0, end  # P - t: rejected


def test_zero_tangent_vector_keeps_the_handle_on_its_point():
    c = _legacy("U.XI.31").curves[1]  # ptTan 0 0 at the apex (-0.7, 0.2)
    assert c.segments[0].handles[1] == (-0.7, 0.2)
    np.testing.assert_allclose(c.top_curve(0).point(1.0), (-0.7, 0.2))


def test_interior_ptTan_is_the_direction_of_travel():
    text = ("unitCurve 3 1 0\nptPos 0 0\nptLab 0\nptPos 1 0\nptTan 0 1\nptLab 1\n"
            "ptPos 2 0\nptLab 0\n")
    c = read_legacy(text).curves[0]
    assert c.segments[0].handles == ((0.0, 0.0), (1.0, -1.0))
    assert c.segments[1].handles == ((1.0, 1.0), (2.0, 0.0))
    np.testing.assert_allclose(c.top_curve(0).tangent(1.0), c.top_curve(1).tangent(0.0))


def test_read_uc_dispatches_on_the_unitCurve_line():
    text = "numCurves 1\nunitCurve 2 3 0\nptPos 1 0\nptLab 0\nptPos 0 1\nptLab 1\n"
    assert read_uc(text, "x.uc") == read_legacy(text, "x.uc")


# -- errors -----------------------------------------------------------------------------------
GOOD = ("numCurves\t1\nunitCurve\t2\t4\t1\nreflectionPoint\t-0.8\t0\n"
        "ptPos\t-0.8\t0\nptLab\t0\nptPos\t0\t-0.5\nptTan\t-0.2\t0\nptLab\t1\n")
GOOD_V1 = ("numCurves 1\nunitCurve 4 2 1\nreflectionPoint 1 0\nptPos 1 0\nptTangent 1 0.5\n"
           "ptTangent 0.5 1\nptPos 0 1\nptLab 0\nptLab 1\n")


def test_the_error_fixtures_are_good():
    assert read_legacy(GOOD, "g.uc").curves[0].segments[0].kind == "bezier"
    assert read_legacy(GOOD_V1, "g.uc").curves[0].segments[0].handles == ((1.0, 0.5), (0.5, 1.0))


def _err(text, path="bad.uc"):
    with pytest.raises(FormatError) as info:
        read_uc(text, path)
    e = info.value
    assert e.path == path
    assert str(e).startswith(f"{path}:{e.line}: " if e.line is not None else f"{path}: ")
    return e


@pytest.mark.parametrize("text, line, words", [
    (GOOD.replace("ptLab\t1\n", ""), 2, "1 'ptLab' labels for 2"),                # truncated
    (GOOD[: GOOD.index("ptPos\t0")], 2, "only 1 follow"),                           # truncated
    (GOOD.replace("ptTan", "ptTanx"), 7, "unknown keyword 'ptTanx'"),
    (GOOD.replace("ptPos\t0\t-0.5", "ptPos\tnan\t-0.5"), 6, "not a finite number"),
    (GOOD.replace("ptTan\t-0.2", "ptTan\tinf"), 7, "not a finite number"),
    (GOOD.replace("ptPos\t0\t-0.5", "ptPos\t0\tabc"), 6, "'abc' is not a number"),
    (GOOD.replace("ptPos\t0\t-0.5", "ptPos\t0"), 6, "needs 2 number(s), got 1"),
    (GOOD.replace("unitCurve\t2", "unitCurve\t1"), 2, "a curve needs at least 2"),
    (GOOD.replace("ptPos\t0\t-0.5", "ptPos\t-0.8\t0"), 6, "coincides with point 0"),
    (GOOD.replace("\t4\t1", "\t0\t1"), 2, "rotation fold' must be a whole number >= 1, got 0"),
    (GOOD.replace("\t4\t1", "\t2.5\t1"), 2, "whole number"),
    (GOOD.replace("\t4\t1", "\t4\t2"), 2, "reflection flag must be 0 or 1"),
    (GOOD.replace("reflectionPoint\t-0.8\t0", "reflectionPoint\t0\t0"), 3, "mirror axis of zero length"),
    (GOOD.replace("reflectionPoint\t-0.8\t0\n", ""), 2, "no 'reflectionPoint'"),
    (GOOD.replace("ptLab\t1", "ptLab\t3"), 8, "must be 0 (ground), 1 (apex) or 2 (free end)"),
    (GOOD.replace("numCurves\t1", "numCurves\t2"), 1, "'numCurves 2' but 1 curves follow"),
    (GOOD.replace("ptLab\t1", "ptLab\t2"), 2, "joins a ground point to a free end"),
    (GOOD + "ptPos\t1\t1\n", 9, "declares 2 points but this is point number 3"),
    (GOOD + "ptLab\t1\n", 9, "this is 'ptLab' number 3"),
    (GOOD.replace("ptTan\t-0.2\t0\n", "ptTan\t-0.2\t0\nptTan\t1\t1\n"), 8, "a second 'ptTan'"),
    (GOOD + "ptTangent 1 1\n", 9, "'ptTangent' mixed with 'ptTan' (line 7)"),
    ("numCurves 1\nptPos 1 1\n", 2, "before the first 'unitCurve'"),
    ("numCurves 0\n", None, "no 'unitCurve'"),
])
def test_legacy_errors_name_line_and_problem(text, line, words):
    e = _err(text)
    assert e.line == line, str(e)
    assert words in e.problem, str(e)


@pytest.mark.parametrize("text, line, words", [
    (GOOD_V1[: GOOD_V1.index("ptPos 0 1")], 2, "only 3 follow"),                   # truncated
    (GOOD_V1.replace("ptTangent 0.5 1\n", "").replace("unitCurve 4", "unitCurve 3"), 5,
     "needs 2 'ptTangent' control points"),
    (GOOD_V1 + "ptTangent 0 0\n", 10, "'ptTangent' after the last point"),
    (GOOD_V1.replace("ptTangent 1 0.5", "ptTangent 1 -nan"), 5, "not a finite number"),
    (GOOD_V1.replace("ptLab 1\n", ""), 2, "1 'ptLab' labels for 2"),
    (GOOD_V1.replace("ptPos 0 1", "ptPos 1 0"), 7, "coincides with point 0"),
    (GOOD_V1.replace("ptTangent 0.5 1\n", "ptTangent 0.5 1\nptTangent 0 0\n"), 7, "a third 'ptTangent'"),
    (GOOD_V1.replace("ptLab 0", "ptLabel 0"), 8, "unknown keyword 'ptLabel'"),
    (GOOD_V1.replace("4 2 1", "4 0 1"), 2, "got 0"),
])
def test_v1_errors_name_line_and_problem(text, line, words):
    e = _err(text)
    assert e.line == line, str(e)
    assert words in e.problem, str(e)


def test_empty_and_blank_files():
    assert _err("").problem.startswith("empty file")
    assert _err("\n\t \n").problem.startswith("empty file")


def test_coordinates_beyond_the_limit_are_refused():
    text = "unitCurve 2 1 0\nptPos -1000001 0\nptLab 0\nptPos 1e6 0\nptLab 1\n"
    e = _err(text)
    assert e.line == 2 and e.problem == ("'ptPos': -1000001 is beyond the limit of +-1e+06 for coordinates "
                                         "and heights (auszug.limits.LIMITS.coordinate)")
    assert read_legacy(text.replace("-1000001", "-4e5").replace("1e6", "4e5")).default_apex == 8e5
    assert "apex height of the curves" in _err(text.replace("-1000001", "-1e6")).problem
