"""Tracery JSON, and the oracle: the paper's call gives exactly its eight polygons."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from auszug.cli import main
from auszug.errors import FormatError
from auszug.formats import format_for, load, save
from auszug.formats.tracery_json import dumps, loads
from auszug.tracery import build, structure
from tests.tracery.cases import PAPER

# The construction of the paper's call, recomputed independently (brentq on the axis
# instead of the ellipse-line intersection): outer arch span 2, radius 2.5, centres
# (-+1.5, 4); ensemble radius 2.4; sub-arch cells span 0.9, radius 1.125, springing 3.8.
F1, R_E = np.array([-1.5, 4.0]), 2.4  # E's right arc
F2, R_S = np.array([1.125, 3.8]), 1.125  # right sub-arch's left arc
Y_C = brentq(lambda y: math.hypot(*([0, y] - F1)) + math.hypot(*([0, y] - F2)) - (R_E + R_S), 4.5, 6.0)
R_C = R_E - math.hypot(*([0, Y_C] - F1))


def _arcs(seg):
    return [(tuple(np.round(s["center"], 9)), round(math.hypot(*np.subtract(s["start"], s["center"])), 9))
            for s in seg if s["kind"] == "arc"]


@pytest.fixture(scope="module")
def oracle(tmp_path_factory):
    out = tmp_path_factory.mktemp("cli") / "window.json"
    code = main(["tracery", "prototype", "--span", "2", "--height", "4", "--excess", "1.25", "--drop", "0.2",
                 "--outer", "0.1", "--inner", "0.05", "-o", str(out)])
    assert code == 0
    return json.loads(out.read_text())


def test_the_worked_call_yields_exactly_eight_polygons(oracle):
    assert oracle["format"] == "auszug.tracery" and oracle["version"] == 1
    regions = oracle["regions"]
    assert [r["group"] for r in regions] == ["arch", "sub-arch", "sub-arch", "circle"] + ["fillet"] * 4
    assert [r["depth"] for r in regions] == [0] * 8
    for r in regions:
        assert set(r) >= {"group", "depth", "boundary", "segments"}
        for s in r["segments"]:
            assert set(s) >= {"kind", "start", "end", "center"}
            assert (s["center"] is None) == (s["kind"] == "line")
        # the segments chain into a closed loop and the boundary polygon follows them
        for a, b in zip(r["segments"], r["segments"][1:] + r["segments"][:1], strict=True):
            assert np.allclose(a["end"], b["start"], atol=1e-12)
        assert np.allclose(r["boundary"][0], r["segments"][0]["start"])


def test_the_eight_polygons_are_the_papers_construction(oracle):
    arch, sub_l, sub_r, circle, top, bottom, left, right = oracle["regions"]
    # the arch: sill, jambs to the springers at height 4, arcs about (+-1.5, 4) of radius 2.5, apex (0, 6)
    assert [s["kind"] for s in arch["segments"]] == ["line", "line", "arc", "arc", "line"]
    assert _arcs(arch["segments"]) == [((-1.5, 4.0), 2.5), ((1.5, 4.0), 2.5)]
    assert arch["segments"][2]["end"] == pytest.approx([0.0, 6.0], abs=1e-12)
    # sub-arches: offset by 0.05 from cells of span 0.9, excess 1.25: same centres, radius 1.075
    assert _arcs(sub_l["segments"]) == [((-1.125, 3.8), 1.075), ((0.225, 3.8), 1.075)]
    assert _arcs(sub_r["segments"]) == [((-0.225, 3.8), 1.075), ((1.125, 3.8), 1.075)]
    xs = [p[0] for p in sub_l["boundary"]]
    assert min(xs) == pytest.approx(-0.85) and max(xs) == pytest.approx(-0.05)
    assert min(p[1] for p in sub_l["boundary"]) == pytest.approx(0.15)
    # the circle on the axis, touching E and the sub-arches, shrunk by 0.05
    (c,) = circle["segments"]
    assert c["center"] == pytest.approx([0.0, Y_C], abs=1e-12)
    assert math.hypot(*np.subtract(c["start"], c["center"])) == pytest.approx(R_C - 0.05, abs=1e-12)
    # fillets of three arcs each (on E's, the circle's and the sub-arches' offset circles)
    assert sorted(_arcs(top["segments"])) == sorted([((-1.5, 4.0), 2.35), ((1.5, 4.0), 2.35),
                                                      ((0.0, round(Y_C, 9)), round(R_C + 0.05, 9))])
    assert sorted(_arcs(bottom["segments"])) == sorted([((1.125, 3.8), 1.175), ((-1.125, 3.8), 1.175),
                                                         ((0.0, round(Y_C, 9)), round(R_C + 0.05, 9))])
    # the side fillets' cells have five pieces (E's arc and jamb, the circle, both sub-arch
    # arcs); the offset by 0.05 removes the jamb and the short arc between the circle and the
    # sub-arch's apex: three arcs, as the paper says
    for side, sx in ((left, -1), (right, 1)):
        assert [s["kind"] for s in side["segments"]] == ["arc", "arc", "arc"]
        assert sorted(_arcs(side["segments"])) == sorted([
            ((-sx * 1.5, 4.0), 2.35), ((0.0, round(Y_C, 9)), round(R_C + 0.05, 9)), ((-sx * 0.225, 3.8), 1.175)])
    # left and right are mirror images
    lb = np.array(left["boundary"]) * [-1, 1]
    rb = np.array(right["boundary"])
    d = np.hypot(*(lb[:, None] - rb[None]).transpose(2, 0, 1)).min(axis=1)
    assert d.max() < 1e-2


def test_write_read_round_trip_is_exact_and_does_not_mutate(tmp_path):
    t = build("fig20g")
    before = [r.curves[0].start.copy() for r in t.regions]
    p = save(t, tmp_path / "w.tracery.json", kind="tracery")
    back = load(p, kind="tracery")
    assert back.style == "fig20g" and back.params == t.params
    assert [r.id for r in back.regions] == [r.id for r in t.regions]
    for a, b in zip(t.regions, back.regions, strict=True):
        assert (a.group, a.depth, a.role, a.border, a.face, a.profile) == (b.group, b.depth, b.role, b.border,
                                                                          b.face, b.profile)
        for ca, cb in zip(a.curves, b.curves, strict=True):
            assert ca.kind == cb.kind
            assert np.array_equal(ca.start, cb.start) or np.allclose(ca.start, cb.start, rtol=0, atol=1e-15)
            assert np.allclose(ca.end, cb.end, rtol=0, atol=1e-14)
    assert [r.curves[0].start.tolist() for r in t.regions] == [x.tolist() for x in before]
    # writing what was read gives the same document, to rounding
    d1, d2 = json.loads(dumps(back)), json.loads(dumps(loads(dumps(back))))
    for r1, r2 in zip(d1["regions"], d2["regions"], strict=True):
        assert np.allclose(r1["boundary"], r2["boundary"], rtol=0, atol=1e-12)
        for s1, s2 in zip(r1["segments"], r2["segments"], strict=True):
            assert np.allclose(s1["start"] + s1["end"], s2["start"] + s2["end"], rtol=0, atol=1e-12)


def test_json_suffix_is_a_tracery_only_for_tracery_kind():
    assert format_for("x.tracery.json").name == "tracery_json"
    assert format_for("x.json", "tracery").name == "tracery_json"
    assert format_for("x.json").kind == "drawing"  # the drawing format keeps plain .json


@pytest.mark.parametrize("text, problem", [
    ("{", "not valid JSON"),
    ('{"format": "other"}', "not a tracery document"),
    ('{"format": "auszug.tracery", "version": 9}', "unsupported version"),
    ('{"format": "auszug.tracery", "version": 1, "params": {}, "regions": [{"group": "x"}]}', "missing"),
])
def test_bad_documents_are_format_errors(text, problem):
    with pytest.raises(FormatError, match=problem):
        loads(text, "bad.json")


def test_open_loops_are_rejected():
    d = json.loads(dumps(structure(PAPER)))
    d["regions"][1]["segments"].pop()
    with pytest.raises(FormatError, match="closed loop"):
        loads(json.dumps(d))
