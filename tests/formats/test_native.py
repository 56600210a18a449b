"""The native JSON drawing format (formats.native): lossless round trip, validation, errors."""

from __future__ import annotations

import json
import math
from dataclasses import fields
from itertools import pairwise

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from auszug.errors import DrawingError, FormatError
from auszug.formats import format_for, load, save
from auszug.formats.native import FORMAT_ID, VERSION, from_dict, read_native, to_dict, write_native
from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry
from tests.conftest import CORPUS, corpus_files


def assert_same_drawing(a: Drawing, b: Drawing) -> None:
    """Field by field, so a failure names the field."""
    assert type(a) is type(b)
    for f in fields(Drawing):
        if f.name != "curves":
            assert getattr(a, f.name) == getattr(b, f.name), f.name
    assert len(a.curves) == len(b.curves)
    for i, (ca, cb) in enumerate(zip(a.curves, b.curves, strict=True)):
        for f in (f for f in fields(BasicCurve) if f.compare):  # not where it was read from
            va, vb = getattr(ca, f.name), getattr(cb, f.name)
            assert va == vb, f"curves[{i}].{f.name}: {va!r} != {vb!r}"
            assert type(va) is type(vb), f"curves[{i}].{f.name}"
    assert a == b


@pytest.mark.parametrize("path", corpus_files(), ids=lambda p: str(p.relative_to(CORPUS)))
def test_every_corpus_drawing_round_trips_exactly(path, tmp_path):
    d = load(path)
    text = write_native(d)
    assert json.loads(text) == to_dict(d)
    assert_same_drawing(read_native(text, "x.json"), d)
    assert_same_drawing(from_dict(json.loads(text)), d)
    out = save(d, tmp_path / f"{path.stem}.json")
    assert_same_drawing(load(out), d)
    assert out.read_text(encoding="utf-8") == text


def test_registry_picks_the_drawing_format_for_json_only():
    assert format_for("a/b.json").name == "json"
    assert format_for("a/b.JSON").kind == "drawing"
    assert format_for("b.network.json", kind=None).kind == "network"


def test_document_layout():
    d = load(CORPUS / "legacy" / "U.XI.17.uc")
    doc = json.loads(write_native(d))
    assert list(doc) == ["format", "version", "name", "layer_bottoms", "default_apex", "curves"]
    assert doc["format"] == FORMAT_ID == "auszug.drawing" and doc["version"] == VERSION == 1
    c = doc["curves"][1]
    assert list(c) == ["vertices", "segments", "marks", "symmetry", "layer", "height", "prc",
                       "decoration", "decoration_at", "post_top", "name"]
    assert c["vertices"] == [[-0.5, 0.0], [-0.3, -0.5], [0.1, -0.2]]
    assert c["segments"] == [{"kind": "line", "handles": []}] * 2
    assert c["marks"] == ["ground", "apex", "free"]
    assert c["symmetry"] == {"fold": 2, "mirror": True, "axis": [-0.5, 0.0], "center": [0.0, 0.0],
                             "axis_rule": "first point"}
    assert c["prc"] == [None, None] and c["height"] is None and c["layer"] == 0


def test_optional_keys_take_their_documented_defaults():
    doc = {"format": "auszug.drawing", "version": 1, "curves": [
        {"vertices": [[0, 0], [1, 0]], "segments": [{"kind": "line"}], "marks": ["ground", "apex"]}]}
    d = from_dict(doc, "dir/plain.json")
    assert d == Drawing((BasicCurve(((0.0, 0.0), (1.0, 0.0)), (Segment(),), ("ground", "apex")),),
                        name="plain")
    assert from_dict({**doc, "curves": [{**doc["curves"][0], "symmetry": {"fold": 3}}]}).curves[0].symmetry \
        == Symmetry(3)


# -- hypothesis: arbitrary valid drawings ---------------------------------------------------------
finite = st.floats(-1e6, 1e6)  # the readers' range (auszug.limits.LIMITS.coordinate)
point = st.tuples(finite, finite)
fraction = st.floats(0.0, 1.0, exclude_min=True, exclude_max=True)
NEED = {"line": 0, "arc": 1, "bezier": 2}
NEXT = {"ground": ["ground", "apex"], "apex": ["ground", "apex", "free"], "free": ["apex", "free"]}


@st.composite
def basic_curves(draw):
    n = draw(st.integers(2, 5))
    verts = draw(st.lists(point, min_size=n, max_size=n).filter(
        lambda vs: all(math.hypot(b[0] - a[0], b[1] - a[1]) > 1e-12 for a, b in pairwise(vs))))
    kinds = draw(st.lists(st.sampled_from(sorted(NEED)), min_size=n - 1, max_size=n - 1))
    segs = tuple(Segment(k, tuple(draw(point) for _ in range(NEED[k]))) for k in kinds)
    marks = [draw(st.sampled_from(["ground", "apex", "free"]))]
    for _ in range(n - 1):
        marks.append(draw(st.sampled_from(NEXT[marks[-1]])))
    mirror = draw(st.booleans())
    axis = draw(point.filter(lambda a: not mirror or math.hypot(*a) > 1e-12))
    sym = Symmetry(draw(st.integers(1, 64)), mirror, axis, draw(point),
                   draw(st.sampled_from(["first point", "last point", "y axis", "fixed"])))
    return BasicCurve(
        verts, segs, tuple(marks), sym, layer=draw(st.integers(0, 6)),
        height=draw(st.none() | finite), prc=tuple(draw(st.none() | fraction) for _ in segs),
        decoration=draw(st.booleans()), decoration_at=draw(st.none() | fraction),
        post_top=draw(st.none() | finite), name=draw(st.text(max_size=8)),
    )


drawings = st.builds(
    Drawing,
    curves=st.lists(basic_curves(), max_size=4).map(tuple),
    layer_bottoms=st.lists(finite, max_size=4).map(tuple),
    name=st.text(max_size=12),
    default_apex=st.none() | finite,
)


@settings(max_examples=300, deadline=None)
@given(drawings)
def test_hypothesis_drawings_round_trip_exactly(d):
    text = write_native(d, "h.json")
    assert_same_drawing(read_native(text, "h.json"), d)
    assert_same_drawing(read_native(text.encode("utf-8"), "h.json"), d)
    assert_same_drawing(from_dict(json.loads(json.dumps(to_dict(d)))), d)
    assert write_native(read_native(text)) == text


def test_a_non_finite_default_apex_cannot_be_made():
    with pytest.raises(DrawingError, match="default apex height must be a finite number, got inf"):
        Drawing((), default_apex=math.inf)


# -- errors ---------------------------------------------------------------------------------------
TEXT = write_native(load(CORPUS / "legacy" / "U.XI.20.uc"))


def _line_of(needle, occurrence=0):
    """Line of the occurrence-th line of TEXT holding needle ("{": the curve objects' first lines)."""
    if needle == "{":
        lines = [i for i, s in enumerate(TEXT.splitlines(), 1) if s == "    {"]
    else:
        lines = [i for i, s in enumerate(TEXT.splitlines(), 1) if needle in s]
    return lines[occurrence]


def _err(text, path="bad.json"):
    with pytest.raises(FormatError) as info:
        read_native(text, path)
    e = info.value
    assert e.path == path
    assert str(e).startswith(f"{path}:{e.line}: " if e.line is not None else f"{path}: ")
    return e


def _nth_replace(text, old, new, n):
    parts = text.split(old)
    return old.join(parts[: n + 1]) + new + old.join(parts[n + 1:])


def test_syntax_errors_give_the_json_line():
    e = _err(TEXT.replace('"layer": 0,', '"layer": 0', 1))
    assert e.line == _line_of('"layer": 0') + 1 and e.problem.startswith("not valid JSON: Expecting ',' ")
    assert _err("").problem.startswith("not valid JSON")
    assert _err("{\n\n  \"format\": }").line == 3


def test_wrong_format_and_version():
    e = _err(TEXT.replace('"auszug.drawing"', '"auszug.network"'))
    assert e.problem == ("format: not an auszug drawing: 'format' is 'auszug.network', "
                         "expected 'auszug.drawing'") and e.line == 2
    e = _err(TEXT.replace('"version": 1', '"version": 2'))
    assert e.problem == "version: unsupported version 2; this auszug reads version 1" and e.line == 3
    assert "unsupported version '1'" in _err(TEXT.replace('"version": 1', '"version": "1"')).problem
    assert "unsupported version true" in _err(TEXT.replace('"version": 1', '"version": true')).problem
    assert "no 'format' key" in _err('{"version": 1, "curves": []}').problem
    assert "expected a JSON object holding a drawing, got an array of 0" in _err("[]").problem


@pytest.mark.parametrize("old, new, n, place, words, line_key", [
    ("[[0.7, 0.0], [0.0, 0.5]]", '[[0.7, 0.0], ["a", 0.5]]', 0, "curves[2].vertices[1][0]",
     "expected a number, got 'a'", ('"vertices"', 2)),
    ("[[0.7, 0.0], [0.0, 0.5]]", "[[0.7, 0.0], [0.0]]", 0, "curves[2].vertices[1]",
     "expected a point [x, y], got an array of 1", ('"vertices"', 2)),
    ("[[0.7, 0.0], [0.0, 0.5]]", "[[0.7, 0.0], [0.0, NaN]]", 0, "curves[2].vertices[1][1]",
     "expected a finite number, got nan", ('"vertices"', 2)),
    ("[[0.7, 0.0], [0.0, 0.5]]", "[[0.7, 0.0], [0.0, 1e999]]", 0, "curves[2].vertices[1][1]",
     "expected a finite number, got inf", ('"vertices"', 2)),
    ("[[0.7, 0.0], [0.0, 0.5]]", "[[0.7, 0.0], [0.0, -2e100]]", 0, "curves[2].vertices[1][1]",
     "-2e+100 is beyond the limit of +-1e+06 for coordinates and heights", ('"vertices"', 2)),
    ("[[0.7, 0.0], [0.0, 0.5]]", "[[0.7, 0.0], [0.7, 0.0]]", 0, "curves[2].vertices[1]",
     "coincides with vertex 0", ('"vertices"', 2)),
    ("[[0.7, 0.0], [0.0, 0.5]]", "[[0.7, 0.0]]", 0, "curves[2].vertices",
     "a curve needs at least 2 vertices, got 1", ('"vertices"', 2)),
    ('"vertices"', '"verts"', 1, "curves[1]", "unknown key 'verts'", ('"vertices"', 1)),
    ('"marks": ["ground", "apex"],\n', "", 1, "curves[2]", "missing key 'marks'", ("{", 2)),
    ('"ground"', '"floor"', 0, "curves[1].marks[0]", "unknown mark 'floor'", ('"marks"', 1)),
    ('"fold": 4', '"fold": 0', 2, "curves[2].symmetry.fold", "expected a whole number >= 1, got 0",
     ('"symmetry"', 2)),
    ('"fold": 4', '"fold": 2.5', 0, "curves[0].symmetry.fold", "whole number", ('"symmetry"', 0)),
    ('"axis": [0.7, 0.0]', '"axis": [0.0, 0.0]', 0, "curves[1].symmetry.axis",
     "a mirror axis needs a direction of non-zero length", ('"symmetry"', 1)),
    ('"mirror": true', '"mirror": 1', 3, "curves[3].symmetry.mirror", "expected true or false, got 1",
     ('"symmetry"', 3)),
    ('"axis_rule": "y axis"', '"axis_rule": "x axis"', 0, "curves[0].symmetry.axis_rule",
     "unknown axis rule 'x axis'", ('"symmetry"', 0)),
    ('"kind": "bezier"', '"kind": "spline"', 0, "curves[0].segments[0].kind",
     "unknown segment kind 'spline'", ('"segments"', 0)),
    ('"kind": "line", "handles": []', '"kind": "arc", "handles": []', 0, "curves[2].segments[0].handles",
     "a arc segment needs 1 handle(s), got 0", ('"segments"', 2)),
    ('"prc": [null]', '"prc": [1.5]', 1, "curves[1].prc[0]", "strictly between 0 and 1",
     ('"prc"', 1)),
    ('"prc": [null]', '"prc": []', 1, "curves[1].prc", "one entry", ('"prc"', 1)),
    ('"layer": 0', '"layer": -1', 0, "curves[0].layer", ">= 0", ('"layer"', 0)),
    ('"height": null', '"height": "high"', 0, "curves[0].height", "expected a number", ('"height"', 0)),
    ('"layer_bottoms": []', '"layer_bottoms": [0, null]', 0, "layer_bottoms[1]",
     "expected a number, got null", ('"layer_bottoms"', 0)),
    ('"marks": ["ground", "apex"]', '"marks": ["ground", "free"]', 0, "curves[1]",
     "joins a ground point to a free end", ("{", 1)),
])
def test_content_errors_name_the_json_path_and_line(old, new, n, place, words, line_key):
    assert TEXT.count(old) > n
    e = _err(_nth_replace(TEXT, old, new, n))
    assert e.problem.startswith(f"{place}: "), e.problem
    assert words in e.problem, e.problem
    assert e.line == _line_of(*line_key), str(e)


def test_duplicate_keys_are_refused():
    e = _err(TEXT.replace('"layer": 0,', '"layer": 0, "layer": 1,', 1))
    assert e.problem == "key 'layer' appears twice in one object" and e.line == _line_of('"layer"')


def test_unknown_top_level_key_and_missing_curves():
    assert "unknown key 'extra'" in _err(TEXT.replace('"name"', '"extra": 1, "name"')).problem
    assert _err('{"format": "auszug.drawing", "version": 1}').problem == "missing key 'curves'"


def test_plain_data_errors_have_no_line():
    with pytest.raises(FormatError) as info:
        from_dict({"format": "auszug.drawing", "version": 1, "curves": [{"vertices": []}]}, "d")
    assert info.value.line is None and str(info.value).startswith("d: curves[0]: missing key")


def test_deep_nesting_and_bad_bytes():
    assert "nested too deeply" in _err("[" * 100000 + "]" * 100000).problem
    assert "not UTF-8" in _err(b"\xff\xfe{").problem
