"""A window's border curves as the curve network: exact, and exported exactly."""

from __future__ import annotations

import io

import numpy as np
import pytest

from auszug import tracery
from auszug.formats.network_json import dumps, exact_piece, loads
from auszug.geometry import Arc
from auszug.tracery.network import border_network

STYLES = tracery.builtin_styles()


@pytest.mark.parametrize("style", STYLES)
def test_every_border_curve_is_a_piece_on_its_region(style):
    t = tracery.build(style)
    net = border_network(t)
    assert len(net.groups) == len(t.regions)
    want = [(i, j) for i, r in enumerate(t.regions) for j in range(len(r.curves))]
    assert [(p.basic, p.segment) for p in net.pieces] == want
    for p in net.pieces:
        r = t.regions[p.basic]
        c = r.curves[p.segment]
        u = np.linspace(0.0, 1.0, 17)
        np.testing.assert_allclose(p.point3(u)[:, :2], c.point_at(u), rtol=0, atol=1e-12)
        assert np.all(p.point3(u)[:, 2] == -r.face)
    ids = [c.id for c in net.curves()]
    assert len(set(ids)) == len(ids) == len(net.pieces)


def test_border_network_exports_exactly():
    import ezdxf

    t = tracery.build("fig20h")
    net = border_network(t).resampled()
    doc = loads(dumps(net, "fig20h"))
    for rec, p in zip(doc["curves"], net.pieces, strict=True):
        q = exact_piece(rec)
        np.testing.assert_allclose(q.point3(np.linspace(0, 1, 9)), p.point3(np.linspace(0, 1, 9)), rtol=0,
                                   atol=1e-12)
    from auszug.formats.dxf import dumps as dxf_dumps

    dxf = ezdxf.read(io.StringIO(dxf_dumps(net, "fig20h")))
    arcs = dxf.modelspace().query("ARC")
    n_arcs = sum(isinstance(c, Arc) for r in t.regions for c in r.curves)
    assert len(arcs) == n_arcs
    radii = sorted(round(a.dxf.radius, 9) for a in arcs)
    assert radii == sorted(round(c.radius, 9) for r in t.regions for c in r.curves if isinstance(c, Arc))
