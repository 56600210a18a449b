"""SVG drawings: the path data reproduces the exact lines and arcs."""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET

import pytest

from auszug.geometry import Arc
from auszug.tracery import build
from auszug.tracery.draw import path_data, svg


def _svg_arc_center(x1, y1, rx, large, sweep, x2, y2):
    """Centre of an SVG arc from its end-point form (SVG 1.1, F.6.5, circles)."""
    mx, my = (x1 - x2) / 2, (y1 - y2) / 2
    h2 = max(rx * rx - mx * mx - my * my, 0.0)
    coef = math.sqrt(h2 / (mx * mx + my * my)) * (-1 if large == sweep else 1)
    cxp, cyp = coef * my, -coef * mx
    return cxp + (x1 + x2) / 2, cyp + (y1 + y2) / 2


@pytest.mark.parametrize("style", ["fig20a", "fig20d", "fig20f"])
def test_paths_reproduce_the_arcs(style):
    t = build(style)
    for r in t.regions:
        d = path_data(r.curves)
        tokens = re.findall(r"[MLAZ]|-?[\d.]+(?:e-?\d+)?", d)
        assert tokens[0] == "M" and tokens[-1] == "Z"
        x, y = float(tokens[1]), float(tokens[2])
        i = 3
        arcs = [c for c in r.curves if isinstance(c, Arc)]
        k = 0
        while tokens[i] != "Z":
            if tokens[i] == "L":
                x, y = float(tokens[i + 1]), float(tokens[i + 2])
                i += 3
                continue
            rx, _, _, large, flag, x2, y2 = (float(v) for v in tokens[i + 1:i + 8])
            cx, cy = _svg_arc_center(x, y, rx, large, flag, x2, y2)
            c = arcs[k]
            assert (cx, cy) == pytest.approx(tuple(c.center), abs=2e-5)
            assert rx == pytest.approx(c.radius, abs=1e-6)
            assert (flag == 1) == (c.sweep > 0)
            x, y = x2, y2
            i += 8
            if abs(arcs[k].sweep) < 2 * math.pi - 1e-9 or (x, y) == pytest.approx(tuple(c.start), abs=1e-6):
                k += 1


def test_svg_document_structure():
    text = svg(build("fig20b"))
    root = ET.fromstring(text.split("\n", 1)[1])
    paths = root.findall(".//{http://www.w3.org/2000/svg}path")
    groups = ["arch", "sub-arch", "sub-arch", "circle", "rosette"] + ["fillet"] * 4
    assert [p.get("data-group") for p in paths] == groups
    assert paths[3].get("data-role") == "frame" and paths[4].get("data-role") == "light"
    assert root.find(".//{http://www.w3.org/2000/svg}g").get("transform") == "scale(1,-1)"
    vb = [float(v) for v in root.get("viewBox").split()]
    assert vb[2] > 2.0 and vb[3] > 6.0
