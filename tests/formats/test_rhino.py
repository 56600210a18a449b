"""Rhino .3dm: one named curve object per network curve, exact arcs and lines re-read onto the exact curves."""

from __future__ import annotations

import math
from collections import defaultdict

import numpy as np
import pytest
import rhino3dm as r
from cad_cases import CASES, RESOLUTION, distance_to_exact, level_arcs, mapped_runs, network, with_nan

from auszug.errors import FormatError
from auszug.formats import format_for, load, save
from auszug.formats.network_json import NetworkFile
from auszug.formats.rhino import FILE_VERSION, dumps, layer_name
from auszug.microarch import build
from tests.conftest import CORPUS


def v(p) -> np.ndarray:
    return np.array([p.X, p.Y, p.Z])


def check_network(net, data: bytes) -> dict[str, int]:
    """Every re-read object against the network; returns counts of what was checked."""
    diag = net.diagonal()
    f = r.File3dm.FromByteArray(data)
    objs = list(f.Objects)
    curves = list(net.curves())
    assert [o.Attributes.Name for o in objs] == [c.id for c in curves]     # one object each, in order
    layers = [ly.Name for ly in f.Layers]
    counts: dict[str, int] = defaultdict(int)
    for o, c in zip(objs, curves, strict=True):
        g = o.Geometry
        assert layers[o.Attributes.LayerIndex] == layer_name(c.basic)
        assert o.Attributes.GetUserString("kind") == c.kind
        assert o.Attributes.GetUserString("mirrored") == ("true" if c.mirrored else "false")
        runs = mapped_runs(net, c)
        if runs:
            assert isinstance(g, r.PolyCurve) and g.SegmentCount == len(runs), c.id
            assert g.IsValid and not g.HasGap, c.id
            for i, run in enumerate(runs):
                seg = g.SegmentCurve(i)
                assert isinstance(seg, r.ArcCurve)
                arc = seg.Arc
                res = RESOLUTION * diag
                assert np.allclose(v(arc.Center), run["center"], rtol=0, atol=1e-12 * diag)
                assert np.allclose(v(arc.Plane.ZAxis), run["normal"], rtol=0, atol=1e-12)
                assert math.isclose(arc.Radius, run["radius"], rel_tol=1e-12)
                assert math.isclose(arc.AngleRadians, run["angle"], rel_tol=0, abs_tol=res / run["radius"])
                assert np.allclose([v(arc.StartPoint), v(arc.EndPoint)], [run["start"], run["end"]], rtol=0, atol=res)
                # points of the re-read arc lie on the exact curve (a wrong orientation gives the other arc)
                dom = arc.AngleDomain   # not always [0, angle]: rhino3dm may move the plane's x axis
                assert math.isclose(dom.T1 - dom.T0, arc.AngleRadians, rel_tol=1e-15)
                q = np.array([v(arc.PointAt(t)) for t in np.linspace(dom.T0, dom.T1, 17)])
                assert np.allclose(q[[0, -1]], [v(arc.StartPoint), v(arc.EndPoint)], rtol=0, atol=1e-12 * diag)
                d = distance_to_exact(net, c, run["t0"], run["t1"], q)
                assert d.max() <= 1e-9 * diag, (c.id, d.max() / diag)
                counts["arcs mirrored" if c.mirrored else "arcs"] += 1
            ends = [(v(g.SegmentCurve(i).PointAtStart), v(g.SegmentCurve(i).PointAtEnd)) for i in range(len(runs))]
            assert np.allclose(ends[0][0], c.points[0], rtol=0, atol=1e-12 * diag)
            assert np.allclose(ends[-1][1], c.points[-1], rtol=0, atol=1e-12 * diag)
            assert np.allclose([e[1] for e in ends[:-1]], [e[0] for e in ends[1:]], rtol=0, atol=1e-12 * diag)
        elif net.pieces[c.piece].is_straight():
            assert isinstance(g, r.LineCurve)
            assert np.array_equal([v(g.PointAtStart), v(g.PointAtEnd)], c.points[[0, -1]])
            counts["lines"] += 1
        else:
            assert isinstance(g, r.PolylineCurve)
            assert np.array_equal(np.array([v(g.Point(i)) for i in range(g.PointCount)]), c.points), c.id
            counts["polylines"] += 1
    return dict(counts)


@pytest.mark.parametrize("name", CASES)
def test_corpus_drawings_round_trip_with_exact_arcs(name, tmp_path):
    net = network(name)
    out = save(NetworkFile(net, name), tmp_path / "n.3dm")
    counts = check_network(net, out.read_bytes())
    assert counts.get("arcs", 0) > 0
    if any(g.mirror for g in net.groups):
        assert counts.get("arcs mirrored", 0) > 0
    assert r.File3dm.ReadArchiveVersion(str(out)) == 10 * FILE_VERSION


def test_horizontal_arcs_both_ways_under_a_skew_mirror_and_lines():
    net = level_arcs()
    assert check_network(net, dumps(net)) == {"arcs": 6, "arcs mirrored": 6, "lines": 4}


@pytest.mark.parametrize("name", ["web/U.XI.34.uc", "legacy/U.XI.24.uc"])
def test_curves_without_an_exact_form_are_polylines_through_the_points(name):
    counts = check_network(network(name), dumps(network(name)))
    assert counts.get("polylines", 0) > 0


def test_units_tolerance_layers_and_source():
    net = build(load(CORPUS / "web" / "u.xi.112.uc")).to_curve_network()
    f = r.File3dm.FromByteArray(dumps(NetworkFile(net, "u.xi.112.uc")))
    assert f.Settings.ModelUnitSystem == getattr(r.UnitSystem, "None")
    assert math.isclose(f.Settings.ModelAbsoluteTolerance, 1e-6 * net.diagonal(), rel_tol=1e-12)
    assert f.Strings["source"] == "u.xi.112.uc" and f.Strings["up"] == "z"
    assert [ly.Name for ly in f.Layers] == [layer_name(i) for i in range(len(net.groups))]
    colours = [tuple(ly.Color) for ly in f.Layers]
    assert len(set(colours)) == len(colours)
    assert format_for("x.3DM", "network", want="write").name == "3dm"


def test_non_finite_coordinate_is_a_format_error_and_writes_nothing(tmp_path):
    bad = with_nan(network("web/u.xi.112.uc"))
    with pytest.raises(FormatError, match="non-finite"):
        dumps(bad)
    with pytest.raises(FormatError, match="non-finite"):
        save(bad, tmp_path / "bad.3dm")
    assert list(tmp_path.iterdir()) == []
