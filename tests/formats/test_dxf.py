"""DXF: a 3D polyline per curve on its basic curve's layer, exact ARCs and LINEs re-read onto the exact curves."""

from __future__ import annotations

import io
import math
from collections import defaultdict

import ezdxf
import numpy as np
import pytest
from cad_cases import CASES, RESOLUTION, distance_to_exact, level_arcs, mapped_runs, network, with_nan
from ezdxf.lldxf.validator import is_valid_layer_name
from ezdxf.math import OCS

from auszug.errors import FormatError
from auszug.formats import format_for, load, save
from auszug.formats.dxf import APPID, dumps, exact_layer_name, layer_name
from auszug.formats.network_json import NetworkFile
from auszug.geometry.network import as_curve_network
from auszug.microarch import build
from tests.conftest import CORPUS


def read(text: str) -> ezdxf.document.Drawing:
    return ezdxf.read(io.StringIO(text))


def entities(doc) -> dict[str, dict[str, list]]:
    """Model space entities by curve id (their XDATA), then by what they are."""
    out: dict[str, dict[str, list]] = defaultdict(lambda: defaultdict(list))
    for e in doc.modelspace():
        tags = [t.value for t in e.get_xdata(APPID)]
        out[tags[0]][tags[1]].append((tags[2] if len(tags) > 2 else 0, e))
    return out


def arc_points(e, angles_deg: np.ndarray) -> np.ndarray:
    """WCS points of a re-read ARC at OCS angles (degrees), from its re-read centre, radius and extrusion."""
    ocs = OCS(e.dxf.extrusion)
    c = np.array(e.dxf.center)
    a = np.radians(angles_deg)
    local = np.stack([c[0] + e.dxf.radius * np.cos(a), c[1] + e.dxf.radius * np.sin(a), np.full_like(a, c[2])], 1)
    return np.array([tuple(ocs.to_wcs(tuple(p))) for p in local])


def sweep_deg(e) -> float:
    return (e.dxf.end_angle - e.dxf.start_angle) % 360.0


def check_network(net, text: str) -> dict[str, int]:
    """Every re-read entity against the network; returns counts of what was checked."""
    diag = net.diagonal()
    doc = read(text)
    ents = entities(doc)
    curves = list(net.curves())
    assert list(ents) == [c.id for c in curves]                       # one polyline each, in order
    counts = defaultdict(int)
    for c in curves:
        got = ents[c.id]
        (_, pl), = got["polyline"]
        assert pl.dxftype() == "POLYLINE" and pl.is_3d_polyline
        assert pl.dxf.layer == layer_name(c.basic)
        assert np.array_equal(np.array([tuple(v) for v in pl.points()]), c.points), c.id
        runs = mapped_runs(net, c)
        arcs = [e for _, e in sorted(got["arc"], key=lambda x: x[0])]
        assert len(arcs) == len(runs), c.id
        for run, e in zip(runs, arcs, strict=True):
            assert e.dxf.layer == exact_layer_name(c.basic)
            ocs = OCS(e.dxf.extrusion)
            assert np.allclose(np.array(e.dxf.extrusion), run["normal"], rtol=0, atol=1e-12)
            assert np.allclose(tuple(ocs.to_wcs(e.dxf.center)), run["center"], rtol=0, atol=1e-12 * diag)
            assert e.dxf.radius == run["radius"]
            res = RESOLUTION * diag
            assert math.isclose(math.radians(sweep_deg(e)), run["angle"], rel_tol=0, abs_tol=res / run["radius"])
            ends = arc_points(e, np.array([e.dxf.start_angle, e.dxf.start_angle + sweep_deg(e)]))
            assert np.allclose(ends, [run["start"], run["end"]], rtol=0, atol=res)
            # points of the re-read arc lie on the exact curve (a wrong orientation gives the other arc)
            q = arc_points(e, e.dxf.start_angle + sweep_deg(e) * np.linspace(0.0, 1.0, 17))
            d = distance_to_exact(net, c, run["t0"], run["t1"], q)
            assert d.max() <= 1e-9 * diag, (c.id, d.max() / diag)
            counts["arcs mirrored" if c.mirrored else "arcs"] += 1
        if arcs:                                                       # end to end, the whole curve
            starts = [arc_points(e, np.array([e.dxf.start_angle]))[0] for e in arcs]
            stops = [arc_points(e, np.array([e.dxf.end_angle]))[0] for e in arcs]
            assert np.allclose(starts[0], c.points[0], rtol=0, atol=1e-12 * diag)
            assert np.allclose(stops[-1], c.points[-1], rtol=0, atol=1e-12 * diag)
            assert np.allclose(starts[1:], stops[:-1], rtol=0, atol=1e-12 * diag)
        lines = got["line"]
        if net.pieces[c.piece].is_straight():
            (_, ln), = lines
            assert ln.dxf.layer == exact_layer_name(c.basic)
            assert np.array_equal([tuple(ln.dxf.start), tuple(ln.dxf.end)], c.points[[0, -1]])
            counts["lines"] += 1
        else:
            assert not lines
    return dict(counts)


@pytest.mark.parametrize("name", CASES)
def test_corpus_drawings_round_trip_with_exact_arcs(name, tmp_path):
    net = network(name)
    out = save(NetworkFile(net, name), tmp_path / "n.dxf")
    counts = check_network(net, out.read_text(encoding="utf-8"))
    assert counts.get("arcs", 0) > 0
    if any(g.mirror for g in net.groups):
        assert counts.get("arcs mirrored", 0) > 0


def test_horizontal_arcs_both_ways_under_a_skew_mirror_and_lines():
    net = level_arcs()
    counts = check_network(net, dumps(net))
    assert counts == {"arcs": 6, "arcs mirrored": 6, "lines": 4}   # 2 arcs x 6 elements; a line and a post x 2
    doc = read(dumps(net))
    normals = {round(e.dxf.extrusion.z) for e in doc.modelspace().query("ARC")}
    assert normals == {-1, 1}


def test_network_of_the_cli_builds_writes_one_polyline_per_curve():
    net = build(load(CORPUS / "teaching-sheet" / "tn-1.uc"))
    doc = read(dumps(net))
    curves = list(net.curves())
    assert len(doc.modelspace().query("POLYLINE")) == len(curves)
    assert len(doc.modelspace().query("ARC")) == sum(
        len(as_curve_network(net).pieces[c.piece].circular_runs()) for c in curves)


def test_header_layers_and_source():
    net = build(load(CORPUS / "web" / "u.xi.112.uc")).to_curve_network()
    doc = read(dumps(NetworkFile(net, "u.xi.112.uc")))
    assert doc.dxfversion == "AC1024"
    assert doc.header["$INSUNITS"] == 0
    assert doc.header.custom_vars.get("source") == "u.xi.112.uc"
    assert doc.header.custom_vars.get("up") == "z"
    b = net.bounds()
    assert np.allclose(doc.header["$EXTMIN"], b[0]) and np.allclose(doc.header["$EXTMAX"], b[1])
    names = [layer_name(i) for i in range(len(net.groups))] + [exact_layer_name(i) for i in range(len(net.groups))]
    layers = {ly.dxf.name: ly for ly in doc.layers}
    assert set(names) <= set(layers)
    assert all(is_valid_layer_name(n) for n in names)
    colours = [(layers[layer_name(i)].dxf.color, layers[layer_name(i)].rgb) for i in range(len(net.groups))]
    assert len(set(colours)) == len(colours)
    assert format_for("x.DXF", "network", want="write").name == "dxf"


def test_non_finite_coordinate_is_a_format_error_and_writes_nothing(tmp_path):
    bad = with_nan(network("web/u.xi.112.uc"))
    with pytest.raises(FormatError, match="non-finite"):
        dumps(bad)
    with pytest.raises(FormatError, match="non-finite"):
        save(bad, tmp_path / "bad.dxf")
    assert list(tmp_path.iterdir()) == []
