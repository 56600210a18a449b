"""SVG top and side views: well-formed, one group per basic curve, exact projections, PRC markers."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from auszug.formats import load, save
from auszug.formats.network_json import NetworkFile
from auszug.formats.svg import PALETTE, colour, dumps
from auszug.microarch import build
from tests.conftest import CORPUS

NS = {"s": "http://www.w3.org/2000/svg"}
CASES = ["teaching-sheet/tn-11.uc", "teaching-sheet/tn-7.uc", "web/U.XI.28.uc", "web/3d_scan_final_final.uc"]


def _pts(el):
    return np.array([[float(v) for v in p.split(",")] for p in el.get("points").split()])


@pytest.mark.parametrize("name", CASES)
def test_views_have_one_coloured_group_per_basic_curve(name, tmp_path):
    net = build(load(CORPUS / name))
    curves = list(net.curves())
    root = ET.parse(save(NetworkFile(net, name), tmp_path / "n.svg", kind="network")).getroot()
    assert root.tag == "{http://www.w3.org/2000/svg}svg"
    w, h = map(float, root.get("viewBox").split()[2:])
    assert w > 0 and h > 0
    for view in ("top-view", "side-view"):
        v = root.find(f".//s:g[@id='{view}']", NS)
        groups = v.findall("s:g[@class='basic-curve']", NS)
        assert [int(g.get("data-basic")) for g in groups] == list(range(len(net.drawing.curves)))
        assert [g.get("stroke") for g in groups] == [colour(b) for b in range(len(groups))]
        for g in groups:
            b = int(g.get("data-basic"))
            ids = sorted(p.get("data-curve") for p in g.findall("s:polyline", NS))
            assert ids == sorted(c.id for c in curves if c.basic == b)
            # the basic curve's pieces are marked and drawn last (on top)
            classes = [p.get("class").split()[1] for p in g.findall("s:polyline", NS)]
            assert classes == sorted(classes, key=lambda c: c == "basic")
        n_prc = sum(c.prc is not None for c in curves)
        assert len(v.findall(".//s:circle[@class='prc']", NS)) == n_prc


def test_distinct_colours_for_up_to_twelve_basic_curves():
    assert len(set(PALETTE)) == len(PALETTE) == 12
    assert all(re.fullmatch(r"#[0-9A-F]{6}", c) for c in PALETTE)


def test_top_and_side_views_are_the_orthographic_projections():
    net = build(load(CORPUS / "teaching-sheet" / "tn-9.uc"))
    root = ET.fromstring(dumps(net))
    curves = {c.id: c for c in net.curves()}
    top = root.find(".//s:g[@id='top-view']", NS)
    side = root.find(".//s:g[@id='side-view']", NS)
    tol = 1e-4 * 1.01          # 4 decimals for a drawing of size ~2
    # screen = (x, -y) + offset and (x, -z) + offset: recover the offsets from one curve
    first = next(iter(curves))
    t0 = _pts(top.find(f".//s:polyline[@data-curve='{first}']", NS))[0] - curves[first].points[0, :2] * [1, -1]
    s0 = _pts(side.find(f".//s:polyline[@data-curve='{first}']", NS))[0] - curves[first].points[0, [0, 2]] * [1, -1]
    for cid, c in curves.items():
        t = _pts(top.find(f".//s:polyline[@data-curve='{cid}']", NS))
        s = _pts(side.find(f".//s:polyline[@data-curve='{cid}']", NS))
        np.testing.assert_allclose(t, c.points[:, :2] * [1, -1] + t0, atol=2 * tol)
        np.testing.assert_allclose(s, c.points[:, [0, 2]] * [1, -1] + s0, atol=2 * tol)


def test_title_names_the_source_and_special_characters_are_escaped():
    net = build(load(CORPUS / "teaching-sheet" / "tn-1.uc"))
    root = ET.fromstring(dumps(NetworkFile(net, "a<b>&c.uc")))
    assert root.find("s:title", NS).text == "auszug network: a<b>&c.uc"
