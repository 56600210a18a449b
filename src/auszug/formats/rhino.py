"""Rhino 3D model (``.3dm``): the curve network as one curve object per network curve.

Written with rhino3dm (OpenNURBS; the ``cad`` extra) as a version 7 file,
which Rhino 7 and later open (and Grasshopper, Blender's import_3dm, ...).

One layer per basic curve, ``curve-<b>``, in the basic curve's colour (the
SVG palette). Each network curve is one curve object on its layer, named
after the curve's id (``0/r1m``), with the user strings ``basic``, ``kind``,
``rotation`` and ``mirrored``. Its geometry is exact where an exact
description exists:

* a PolyCurve of arcs where the curve is a chain of planar circular arcs
  (level arcs, ogees and free ends over a straight top view): one arc per
  circular run, end to end from the curve's start to its end, each in the
  plane through its centre with its normal (mirrored replicas keep the
  orientation, see :mod:`auszug.formats._cad`);
* a LineCurve from start to end for a straight curve (post, pillar, level
  line);
* otherwise a PolylineCurve (degree 1) through the network's points: curves
  over Bezier or arc top views with a side view have no exact NURBS form here
  and are written as sampled, within the network's sampling tolerance.

The model's unit system is *None* (unitless: coordinates are drawing units),
z is up (Rhino's world z: the top view is Rhino's Top viewport, the height is
z), and the absolute tolerance is 1e-6 of the network's bounding-box
diagonal (the default export tolerance), so Rhino does not take the exact
arcs' joins for gaps. The document user text holds ``source`` (the drawing's
file name), ``generator`` and ``up``.
"""

from __future__ import annotations

import base64
import math
from typing import Any

import numpy as np

from auszug.errors import FormatError
from auszug.formats._cad import Arc3, CadCurve, cad_curves, network_and_source
from auszug.formats._registry import FileFormat, register
from auszug.formats.palette import PALETTE
from auszug.geometry.network import DEFAULT_REL_TOLERANCE

__all__ = ["FILE_VERSION", "layer_name", "dumps"]

#: 3dm archive version written (Rhino 7 and later read it).
FILE_VERSION = 7


def layer_name(basic: int) -> str:
    """The layer of basic curve ``basic``.

    Examples
    --------
    >>> layer_name(2)
    'curve-2'
    """
    return f"curve-{basic}"


def _rgba(basic: int) -> tuple[int, int, int, int]:
    h = PALETTE[basic % len(PALETTE)]
    return int(h[1:3], 16), int(h[3:5], 16), int(h[5:7], 16), 255


def _arc(r: Any, a: Arc3) -> Any:
    """The rhino3dm Arc of ``a``: plane at the centre, x axis through the start, z axis the normal."""
    x = (a.start - a.center) / np.linalg.norm(a.start - a.center)
    y = np.cross(a.normal, x)
    arc = r.Arc(r.Point3d(*a.center.tolist()), a.radius, a.angle)
    arc.Plane = r.Plane(r.Point3d(*a.center.tolist()), r.Vector3d(*x.tolist()), r.Vector3d(*y.tolist()))
    return arc


def _geometry(r: Any, cc: CadCurve) -> Any:
    if cc.arcs:
        pc = r.PolyCurve()
        for a in cc.arcs:
            pc.Append(_arc(r, a))
        return pc
    if cc.line is not None:
        return r.LineCurve(r.Point3d(*cc.line[0].tolist()), r.Point3d(*cc.line[1].tolist()))
    return r.PolylineCurve([r.Point3d(*p) for p in np.asarray(cc.curve.points, dtype=float).tolist()])


def dumps(network: Any, source: str = "") -> bytes:
    """The bytes of a .3dm file of a network (see the module docstring).

    Parameters
    ----------
    network : NetworkFile, Network or CurveNetwork
    source : str
        File name of the drawing, recorded as document user text (default: the network's).

    Raises
    ------
    FormatError
        If a coordinate is not finite (nothing is written), or rhino3dm is missing.
    """
    net, src = network_and_source(network)
    source = source or src
    curves = list(cad_curves(net, source))  # checks every number before anything is made
    try:
        import rhino3dm as r
    except ImportError:  # pragma: no cover - the cad extra is part of dev
        raise FormatError("writing .3dm needs rhino3dm: pip install 'auszug[cad]'", source) from None

    f = r.File3dm()
    f.ApplicationName = "auszug"
    f.Settings.ModelUnitSystem = getattr(r.UnitSystem, "None")
    diag = net.diagonal()
    if math.isfinite(diag) and diag > 0.0:
        f.Settings.ModelAbsoluteTolerance = DEFAULT_REL_TOLERANCE * diag
    f.Strings["source"] = source
    f.Strings["generator"] = "auszug"
    f.Strings["up"] = "z"
    layers: dict[int, int] = {}
    for b in sorted({c.curve.basic for c in curves}):
        layers[b] = f.Layers.AddLayer(layer_name(b), _rgba(b))
    for cc in curves:
        c = cc.curve
        att = r.ObjectAttributes()
        att.Name = c.id
        att.LayerIndex = layers[c.basic]
        att.SetUserString("basic", str(c.basic))
        att.SetUserString("kind", c.kind)
        att.SetUserString("rotation", str(c.rotation))
        att.SetUserString("mirrored", "true" if c.mirrored else "false")
        f.Objects.AddCurve(_geometry(r, cc), att)
    opts = r.File3dmWriteOptions()
    opts.Version = FILE_VERSION
    return base64.b64decode(f.Encode(opts))


def _write(obj: Any, name: str) -> bytes:
    return dumps(obj)


register(FileFormat("3dm", (".3dm",), "network", writer=_write, binary=True))
