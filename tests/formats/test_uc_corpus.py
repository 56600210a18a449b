"""Every corpus file loads; the web dialect round-trips through write_web; web-dialect errors."""

from __future__ import annotations

import math

import pytest

from auszug.errors import DrawingError, FormatError
from auszug.formats import load, save
from auszug.formats.uc import read_uc, write_web
from auszug.microarch import Drawing, build
from tests.conftest import CORPUS, corpus_files

ALL = corpus_files()


def _dialect(path):
    for line in path.read_text().splitlines():
        toks = line.split()
        if toks and toks[0] == "unitCurve":
            if "ptTangent" in path.read_text():
                return "v1"
            return "web" if len(toks) == 3 else "legacy"
    raise AssertionError(f"no unitCurve in {path}")


WEB = [p for p in ALL if _dialect(p) == "web"]


def test_the_corpus_is_all_there():
    # 36 legacy + 12 teaching sheet + 38 in web/ (37 web dialect, two_curves in v1)
    assert len(ALL) == 86
    assert sorted({_dialect(p) for p in ALL}) == ["legacy", "v1", "web"]
    assert len(WEB) == 49 and [p.name for p in ALL if _dialect(p) == "v1"] == ["two_curves.uc"]
    assert all(_dialect(p) == "legacy" for p in corpus_files("legacy"))


@pytest.mark.parametrize("path", ALL, ids=lambda p: str(p.relative_to(CORPUS)))
def test_every_corpus_file_loads(path):
    d = load(path)
    assert isinstance(d, Drawing)
    text = path.read_text()
    assert len(d.curves) == text.count("unitCurve") >= 1
    assert d.name == path.name[: -len(".uc")]
    # every ptPos is a vertex, except the web dialect's tangent handles (T, T2)
    n_pos = text.count("ptPos")
    n_vert = sum(len(c.vertices) for c in d.curves)
    if _dialect(path) == "web":
        assert n_pos == sum(2 * len(c.vertices) - 1 for c in d.curves)
    else:
        assert n_pos == n_vert


def test_web_facts_checked_by_hand():
    d = load(CORPUS / "teaching-sheet" / "tn-3.uc")
    (c,) = d.curves
    assert c.vertices == ((-1.519996527874141e-16, -0.8274475704246165),
                          (-0.5803660290951242, -7.107433998652036e-17))
    # T lies on the chord A-B (a straight rib): read as a line
    assert c.segments[0].kind == "line" and c.segments[0].handles == ()
    assert (c.symmetry.fold, c.symmetry.mirror, c.symmetry.axis_rule) == (4, True, "first point")
    assert c.height == 1.5738503503452415 and c.prc == (0.5877536420353454,)
    assert d.layer_bottoms == (0.0,)

    d = load(CORPUS / "web" / "U.XI.31.uc")
    c = d.curves[0]
    assert c.segments[0].kind == "arc"
    assert c.segments[0].handles == ((-0.23847012362637346, -0.5111692994507777),)
    assert c.symmetry.axis == c.vertices[0] == (-9.405643257839795e-17, -0.5120193710484999)
    assert (c.symmetry.fold, c.symmetry.mirror, c.symmetry.axis_rule) == (4, True, "first point")
    assert c.prc == (0.6400566489464985,) and d.curves[1].prc == (0.40095498856079886,)

    d = load(CORPUS / "web" / "u.xi.112.uc")
    assert [c.layer for c in d.curves] == [0, 0, 1, 1, 2]
    assert d.layer_bottoms == (0.0, 1.0994042717768442, 2.3331894962744526)
    assert all((c.symmetry.fold, c.symmetry.mirror) == (3, True) for c in d.curves)

    d = load(CORPUS / "web" / "weird_ones" / "flower.uc")
    assert d.curves[0].symmetry.fold == 7
    assert d.curves[0].decoration and d.curves[0].decoration_at == 0.20764500599882615
    assert sum(len(c.marks) == 3 for c in d.curves) == (11 - 3 * len(d.curves)) // 2


# -- round trip ---------------------------------------------------------------------------------
@pytest.mark.parametrize("path", WEB, ids=lambda p: str(p.relative_to(CORPUS)))
def test_web_round_trip_keeps_the_geometry(path):
    d = load(path)
    text = write_web(d, path.name)
    e = read_uc(text, str(path))
    assert e.name == d.name and len(e.curves) == len(d.curves)
    net = build(d)
    for i, (a, b) in enumerate(zip(d.curves, e.curves, strict=True)):
        assert b.vertices == a.vertices
        assert b.segments == a.segments  # kinds and handles, exactly (floats written by repr)
        assert b.marks == a.marks and b.layer == a.layer and b.symmetry == a.symmetry
        assert b.post_top == a.post_top and b.decoration == a.decoration
        # stored heights stay; missing ones are written as the ones the network used
        assert b.height == (a.height if a.height is not None else net.apex_heights[i])
        assert b.prc[0] == (a.prc[0] if a.prc[0] is not None else net.ogee_of(i).prc_fraction)
        if a.decoration_at is not None:
            assert b.decoration_at == pytest.approx(a.decoration_at, abs=1e-14)
    assert e.bottoms() == d.bottoms()
    # writing the result again changes nothing (but float noise in decorations)
    f = read_uc(write_web(e, path.name), str(path))
    assert [c.with_(decoration_at=None) for c in f.curves] == [
        c.with_(decoration_at=None) for c in e.curves]


@pytest.mark.parametrize("path", WEB[:3], ids=lambda p: p.name)
def test_save_and_load_through_the_registry(path, tmp_path):
    d = load(path)
    out = save(d, tmp_path / path.name)
    assert [c.vertices for c in load(out).curves] == [c.vertices for c in d.curves]


def test_write_web_refuses_beziers_before_building():
    d = load(CORPUS / "web" / "two_curves.uc")
    with pytest.raises(FormatError, match="cannot be written in the web .uc dialect"):
        write_web(d, "two_curves.uc")


def test_write_web_keeps_a_fixed_axis_fixed():
    d = load(CORPUS / "web" / "u.xi.19-design1.uc")  # no ref_symmetry_type: fixed
    assert {c.symmetry.axis_rule for c in d.curves} == {"fixed"}
    text = write_web(d)
    assert "ref_symmetry_type" not in text
    assert [c.symmetry for c in read_uc(text).curves] == [c.symmetry for c in d.curves]


# -- web-dialect errors -------------------------------------------------------------------------
GOOD = ("numCurves 1\nunitCurve 4 1\nreflectionPoint 0 -1\nref_symmetry_type first point\n"
        "ptPos 0 -1\nptPos -0.2 -0.8\nptPos -0.7 0\nlevel 0\nheight 1.5\nprc_t 0.5\n"
        "layer_bottom 0\n")


def test_the_web_fixture_is_good():
    assert read_uc(GOOD, "g.uc").curves[0].segments[0].kind == "arc"


@pytest.mark.parametrize("text, line, words", [
    (GOOD[: GOOD.index("ptPos -0.7")], 2, "has 2 'ptPos' points; expected 3"),      # truncated
    (GOOD.replace("level", "lvl"), 8, "unknown keyword 'lvl'"),
    (GOOD.replace("height 1.5", "height nan"), 9, "not a finite number"),
    (GOOD.replace("ptPos -0.7 0", "ptPos -0.7 -inf"), 7, "not a finite number"),
    (GOOD.replace("ptPos -0.7 0", "ptPos -0.7 zero"), 7, "'zero' is not a number"),
    (GOOD.replace("unitCurve 4 1", "unitCurve 0 1"), 2, "got 0"),
    (GOOD.replace("ptPos -0.7 0", "ptPos 0 -1"), 7, "end point (point 2) coincides with point 0"),
    (GOOD.replace("ptPos -0.2 -0.8", "ptPos 0 -1"), 6, "tangent handle (point 1) coincides"),
    (GOOD.replace("reflectionPoint 0 -1", "reflectionPoint 0 0"), 3, "mirror axis of zero length"),
    (GOOD.replace("prc_t 0.5", "prc_t 1"), 10, "strictly between 0 and 1"),
])
def test_web_errors_name_line_and_problem(text, line, words):
    with pytest.raises(FormatError) as info:
        read_uc(text, "bad.uc")
    e = info.value
    assert e.path == "bad.uc" and e.line == line, str(e)
    assert words in e.problem and str(e).startswith(f"bad.uc:{line}: "), str(e)


@pytest.mark.parametrize("height", ["0", "-0.5"])
def test_apex_at_or_below_its_bottom_is_a_clear_drawing_error(height):
    d = read_uc(GOOD.replace("height 1.5", f"height {height}"), "low.uc")
    with pytest.raises(DrawingError) as info:
        build(d)
    e = info.value
    assert e.where == "curve 0"
    assert str(e) == f"curve 0: apex height {float(height):g} is not above its layer bottom 0"


def test_apex_below_a_higher_layer_bottom():
    text = GOOD.replace("level 0", "level 1").replace("height 1.5", "height 0.4") + "layer_bottom 0.5\n"
    with pytest.raises(DrawingError, match=r"^curve 0: apex height 0.4 is not above its layer "
                                           r"bottom 0.5$"):
        build(read_uc(text))


def test_legacy_heights_are_always_above_the_ground():
    for p in corpus_files("legacy"):
        d = load(p)
        assert d.apex_height(0) >= 1.0 > d.bottoms()[0] == 0.0
        assert math.isfinite(d.default_apex)
