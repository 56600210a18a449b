"""DXF (``.dxf``): the curve network for CAD programs, with exact arcs and lines where they exist.

Written with ezdxf (the ``cad`` extra) as DXF R2010 (AC1024, UTF-8 text).

Layers, two per basic curve ``b`` (names are plain ASCII, valid in every DXF
version), both in the basic curve's colour (the SVG palette as true colour,
and the nearest distinct AutoCAD colour index for older programs)::

    curve-<b>         one 3D POLYLINE per network curve, through its points
    curve-<b>-exact   the exact parts: an ARC per circular run of the curve,
                      or one LINE for a straight curve (post, pillar, level line)

So every network curve is one complete entity on ``curve-<b>`` (what a user
picks to trace or sweep), and where the curve *is* a chain of circular arcs
(level arcs, ogees over a straight top view) or a straight segment, the exact
entities on ``curve-<b>-exact`` describe it without sampling error; curves
over Bezier or arc top views with a side view are not planar circles and
have only their polyline. The ARCs of one curve run end to end from the
curve's start to its end.

ARC entities live in their object coordinate system (OCS): the extrusion is
the arc's plane normal (horizontal for an arc in a vertical plane), the centre
is written in OCS coordinates (x, y and the elevation z) and the angles in
degrees, counter-clockwise about the extrusion from the start angle to the
end angle, as DXF prescribes. Mirrored replicas keep that orientation (see
:mod:`auszug.formats._cad`).

Every entity carries XDATA of the application ``AUSZUG``: the network curve's
id (``0/r1m``), what the entity is (``polyline``, ``arc``, ``line``) and, for
an arc, its index along the curve.

Header: ``$INSUNITS`` = 0 (unitless: coordinates are drawing units), the
drawing's extents in ``$EXTMIN``/``$EXTMAX``, and the custom properties
``source`` (the drawing's file name), ``generator`` and ``up`` (``z``). DXF's
world coordinate system is z up already: the top view is the plan view (the
initial view of the model space), the height is z. Coordinates are written
with Python's shortest round-trip representation, so a reader gets back the
network's numbers exactly.
"""

from __future__ import annotations

import io
import math
from typing import Any

import numpy as np

from auszug.errors import FormatError
from auszug.formats._cad import Arc3, cad_curves, network_and_source
from auszug.formats._registry import FileFormat, register
from auszug.formats.palette import PALETTE

__all__ = ["APPID", "DXF_VERSION", "ACI", "layer_name", "exact_layer_name", "dumps"]

#: XDATA application name of the entities' curve ids.
APPID = "AUSZUG"
#: DXF version written (R2010).
DXF_VERSION = "R2010"
#: AutoCAD colour index nearest to each colour of :data:`~auszug.formats.palette.PALETTE` (all distinct).
ACI: tuple[int, ...] = (142, 32, 122, 241, 30, 151, 245, 114, 187, 43, 223, 123)


def layer_name(basic: int) -> str:
    """The layer of basic curve ``basic``'s polylines.

    Examples
    --------
    >>> layer_name(0), exact_layer_name(3)
    ('curve-0', 'curve-3-exact')
    """
    return f"curve-{basic}"


def exact_layer_name(basic: int) -> str:
    """The layer of basic curve ``basic``'s exact arcs and lines."""
    return f"curve-{basic}-exact"


def _rgb(basic: int) -> tuple[int, int, int]:
    h = PALETTE[basic % len(PALETTE)]
    return int(h[1:3], 16), int(h[3:5], 16), int(h[5:7], 16)


def _arc_attribs(arc: Arc3) -> tuple[tuple[float, float, float], float, float, tuple[float, float, float]]:
    """OCS centre, start and end angle (degrees) and extrusion of an arc."""
    from ezdxf.math import OCS

    n = tuple(float(v) for v in arc.normal)
    ocs = OCS(n)
    c = ocs.from_wcs(tuple(arc.center.tolist()))
    s = ocs.from_wcs(tuple(arc.start.tolist()))
    e = ocs.from_wcs(tuple(arc.end.tolist()))
    a0 = math.degrees(math.atan2(s.y - c.y, s.x - c.x)) % 360.0
    a1 = math.degrees(math.atan2(e.y - c.y, e.x - c.x)) % 360.0
    return (c.x, c.y, c.z), a0, a1, n  # type: ignore[return-value]


def dumps(network: Any, source: str = "") -> str:
    """DXF text of a network (see the module docstring).

    Parameters
    ----------
    network : NetworkFile, Network or CurveNetwork
    source : str
        File name of the drawing, recorded in the header (default: the network's).

    Raises
    ------
    FormatError
        If a coordinate is not finite (nothing is written), or ezdxf is missing.
    """
    net, src = network_and_source(network)
    source = source or src
    curves = list(cad_curves(net, source))  # checks every number before anything is made
    try:
        import ezdxf
        from ezdxf.colors import rgb2int
    except ImportError:  # pragma: no cover - the cad extra is part of dev
        raise FormatError("writing DXF needs ezdxf: pip install 'auszug[cad]'", source) from None

    doc = ezdxf.new(DXF_VERSION, setup=False)
    doc.units = 0
    doc.header["$INSUNITS"] = 0
    doc.header.custom_vars.append("source", source)
    doc.header.custom_vars.append("generator", "auszug")
    doc.header.custom_vars.append("up", "z")
    doc.appids.add(APPID)
    for b in sorted({c.curve.basic for c in curves}):
        for name in (layer_name(b), exact_layer_name(b)):
            doc.layers.add(name, color=ACI[b % len(ACI)], true_color=rgb2int(_rgb(b)))
    msp = doc.modelspace()
    for cc in curves:
        c = cc.curve
        pts = np.asarray(c.points, dtype=float)
        pl = msp.add_polyline3d([tuple(p) for p in pts.tolist()], dxfattribs={"layer": layer_name(c.basic)})
        pl.set_xdata(APPID, [(1000, c.id), (1000, "polyline")])
        exact = {"layer": exact_layer_name(c.basic)}
        for i, arc in enumerate(cc.arcs):
            centre, a0, a1, n = _arc_attribs(arc)
            e = msp.add_arc(centre, arc.radius, a0, a1, dxfattribs={**exact, "extrusion": n})
            e.set_xdata(APPID, [(1000, c.id), (1000, "arc"), (1070, i)])
        if cc.line is not None:
            e = msp.add_line(tuple(cc.line[0].tolist()), tuple(cc.line[1].tolist()), dxfattribs=exact)
            e.set_xdata(APPID, [(1000, c.id), (1000, "line")])
    if curves:
        allp = np.concatenate([np.asarray(cc.curve.points, dtype=float) for cc in curves])
        lo, hi = allp.min(0), allp.max(0)
        msp.dxf.extmin = tuple(lo.tolist())   # ezdxf copies the model space's extents into the header
        msp.dxf.extmax = tuple(hi.tolist())
        size = float(max(hi[0] - lo[0], hi[1] - lo[1])) or 1.0
        doc.set_modelspace_vport(1.1 * size, center=(float(lo[0] + hi[0]) / 2, float(lo[1] + hi[1]) / 2))
    out = io.StringIO()
    doc.write(out)
    return out.getvalue()


def _write(obj: Any, name: str) -> str:
    return dumps(obj)


register(FileFormat("dxf", (".dxf",), "network", writer=_write))
