"""The curve network: sampling by tolerance, feature vertices, exact descriptions, exports.

For every corpus drawing the polylines sampled to the default export tolerance
(1e-6 of the bounding-box diagonal) must lie within it of the exact curves both
ways: every curve point within T of its polyline, and every polyline point
within T of the curve. The exact curve is evaluated densely inside every
polyline interval (so the bound is checked where it is tightest), and the PRC,
apex and ground ends must be vertices with the heights the drawing prescribes.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from auszug.errors import GeometryError
from auszug.formats import load
from auszug.formats.network_json import dumps, exact_piece, loads
from auszug.formats.obj import dumps as obj_dumps
from auszug.formats.obj import read_polylines, safe_name
from auszug.geometry.network import (
    DEFAULT_REL_TOLERANCE,
    CurveNetwork,
    as_curve_network,
    sample_by_tolerance,
)
from auszug.microarch import build
from tests.conftest import CORPUS, corpus_files

FILES = corpus_files()
IDS = [str(p.relative_to(CORPUS)) for p in FILES]
#: fractions of each polyline interval where the exact curve is probed (ends included)
FRACS = np.concatenate([[0.0, 1e-6, 1e-3, 0.01], np.linspace(0.05, 0.95, 19), [0.99, 0.999, 1 - 1e-6, 1.0]])
#: chord points per polyline segment, and the fine polyline of the curve they are measured against
CHORD = np.linspace(0.0, 1.0, 17)
FINE = 257


def _seg_dist(q: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distances of points q (m, k, 3) to segments a..b (m, 1, 3)."""
    d = b - a
    dd = np.einsum("...i,...i->...", d, d)
    s = np.clip(np.einsum("...i,...i->...", q - a, d) / np.where(dd > 0, dd, 1.0), 0.0, 1.0)
    return np.linalg.norm(q - (a + s[..., None] * d), axis=-1)


def two_sided_error(piece, ts: np.ndarray, pts: np.ndarray) -> tuple[float, float]:
    """(curve -> polyline, polyline -> curve) distance bounds of a polyline at parameters ts."""
    lo, hi = ts[:-1], ts[1:]
    # the exact curve inside each interval against that interval's chord (an upper bound of
    # its distance to the whole polyline)
    tq = lo[:, None] + (hi - lo)[:, None] * FRACS
    q = piece.point_t(tq)
    a, b = pts[:-1, None], pts[1:, None]
    c2p = float(_seg_dist(q, a, b).max())
    # points of each chord against a fine polyline of the curve over the same interval
    tf = lo[:, None] + (hi - lo)[:, None] * np.linspace(0.0, 1.0, 65)
    f = piece.point_t(tf)                                     # (m, 65, 3)
    chord = a + CHORD[None, :, None] * (b - a)                # (m, 17, 3)
    d = _seg_dist(chord[:, :, None, :], f[:, None, :-1, :], f[:, None, 1:, :])   # (m, 17, 64)
    p2c = float(d.min(axis=2).max())
    return c2p, p2c


def _fine(net) -> CurveNetwork:
    cn = net.with_intersections()
    return cn.resampled(tolerance=DEFAULT_REL_TOLERANCE * cn.diagonal())


@pytest.mark.parametrize("path", FILES, ids=IDS)
def test_every_corpus_polyline_is_within_the_tolerance_both_ways(path):
    drawing = load(path)
    net = build(drawing)
    fine = _fine(net)
    T = fine.tolerance
    assert T == pytest.approx(DEFAULT_REL_TOLERANCE * net.to_curve_network().diagonal(), rel=1e-12)
    for pi, (p0, p) in enumerate(zip(net.with_intersections().pieces, fine.pieces, strict=True)):
        if p.top is None:
            assert len(p.points) == 2
            continue
        ts, feats = sample_by_tolerance(p0, T)
        assert np.all(np.diff(ts) > 0) and ts[0] == p.t_span()[0] and ts[-1] == p.t_span()[1]
        np.testing.assert_array_equal(p.point_t(ts), p.points)
        assert tuple(feats) == fine.features[pi]
        c2p, p2c = two_sided_error(p, ts, np.asarray(p.points))
        assert c2p <= T and p2c <= T, (pi, p.kind, c2p / T, p2c / T)
        # the PRC, the apex and the ends are vertices, exactly
        names = dict(fine.features[pi])
        if p.kind == "ogee":
            np.testing.assert_allclose(p.points[names["prc"]], p.prc, rtol=0, atol=1e-12 * fine.size)
            apex = net.apex_heights[p.basic]
            bottom = net.bottoms[fine.layers[p.basic]]
            assert p.points[names["apex"]][2] == pytest.approx(apex, abs=1e-12 * fine.size)
            assert p.points[names["start"]][2] == pytest.approx(bottom, abs=1e-12 * fine.size)
            assert names["start"] == 0 and names["apex"] == len(p.points) - 1


def test_halving_the_tolerance_refines_by_about_sqrt2():
    """Chord error ~ h^2: half the tolerance needs ~1.41x the points (a check that T drives it)."""
    cn = build(load(CORPUS / "teaching-sheet" / "tn-1.uc")).with_intersections()
    T = 1e-5 * cn.diagonal()
    n1 = sum(len(p.points) for p in cn.resampled(tolerance=T).pieces)
    n2 = sum(len(p.points) for p in cn.resampled(tolerance=T / 2).pieces)
    assert 1.25 < n2 / n1 < 1.6


def test_true_intersections_are_vertices_of_both_curves():
    net = build(load(CORPUS / "teaching-sheet" / "tn-1.uc"))
    fine = _fine(net)
    curves = list(fine.curves())
    pts = {c.id: [c.points[i] for n, i in c.features if n == "intersection"] for c in curves}
    assert sum(map(len, pts.values())) > 0
    allv = np.concatenate([c.points for c in curves])
    for cid, qs in pts.items():
        for q in qs:
            # some other curve has a vertex at the same 3D point
            d = np.linalg.norm(allv - q, axis=1)
            assert np.sum(d <= 1e-9 * fine.size) >= 2, cid


def test_tolerance_below_float_resolution_is_refused():
    cn = build(load(CORPUS / "teaching-sheet" / "tn-1.uc")).to_curve_network()
    with pytest.raises(GeometryError, match="below"):
        cn.resampled(tolerance=1e-14 * cn.diagonal())
    with pytest.raises(GeometryError, match="not both"):
        cn.resampled(tolerance=1.0, samples=3)


@pytest.mark.parametrize("name", ["teaching-sheet/tn-1.uc", "web/U.XI.28.uc", "web/u.xi.112.uc",
                                  "legacy/U.XI.31.uc", "web/weird_ones/flower.uc"])
def test_network_json_v2_exact_curves_reevaluate_every_point(name):
    net = build(load(CORPUS / name))
    fine = _fine(net)
    doc = loads(dumps(fine, name))
    assert doc["version"] == 2 and doc["tolerance"] == fine.tolerance
    marked = net.with_intersections().pieces
    for rec, c in zip(doc["curves"], fine.curves(), strict=True):
        assert rec["id"] == c.id
        p = exact_piece(rec)
        pts = np.asarray(rec["points"])
        if p.top is None:
            np.testing.assert_allclose(p.points, pts[[0, -1]], rtol=0, atol=1e-12 * fine.size)
            continue
        t, _ = sample_by_tolerance(marked[c.piece], fine.tolerance)   # the vertices' parameters
        np.testing.assert_allclose(p.point_t(t), pts, rtol=0, atol=1e-12 * fine.size)
        feats = dict(rec["features"])
        if c.prc is not None and c.kind == "ogee":
            np.testing.assert_allclose(pts[feats["prc"]], c.prc, rtol=0, atol=1e-12 * fine.size)


def test_network_json_version_1_documents_still_read():
    net = build(load(CORPUS / "teaching-sheet" / "tn-2.uc"), samples=9)
    doc = json.loads(dumps(net))
    doc["version"] = 1
    for c in doc["curves"]:
        del c["exact"], c["features"]
    back = loads(json.dumps(doc))
    assert back["version"] == 1 and len(back["curves"]) == len(doc["curves"])


def test_obj_export_is_within_the_tolerance():
    net = build(load(CORPUS / "web" / "U.XI.28.uc"))
    fine = _fine(net)
    lines = read_polylines(obj_dumps(fine))
    for c in fine.curves():
        got = lines[safe_name(c.id)]
        np.testing.assert_array_equal(got, c.points)   # written with repr: exact
    assert "# tolerance:" in obj_dumps(fine)


def test_svg_export_writes_enough_digits_for_the_tolerance():
    import re

    net = build(load(CORPUS / "web" / "U.XI.28.uc"))
    fine = _fine(net)
    from auszug.formats.svg import dumps as svg_dumps

    text = svg_dumps(fine)
    c = next(iter(fine.curves()))
    poly = re.search(r'data-curve="%s"[^>]*points="([^"]+)"' % re.escape(c.id), text)
    assert poly is not None
    xy = np.array([[float(v) for v in pair.split(",")] for pair in poly.group(1).split()])
    assert len(xy) == len(c.points)
    # the top view panel is the curve shifted: differences between points are kept to T / 10
    d = np.diff(xy, axis=0) * [1, -1]
    np.testing.assert_allclose(d, np.diff(c.points[:, :2], axis=0), rtol=0, atol=0.1 * fine.tolerance)


def test_as_curve_network_refuses_other_values():
    with pytest.raises(TypeError, match="CurveNetwork"):
        as_curve_network(42)
