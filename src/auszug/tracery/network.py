"""A window's border curves as the project's curve network.

:func:`border_network` lays the window's elevation flat: x across, y up the
window (the tracery's own 2D coordinates), z the depth of each region's face
behind the plate's face, negated (0 on the plate, negative in the recesses).
Every region is one basic curve with the trivial symmetry group, its loop of
lines and arcs one piece each (kind ``"border"``, at constant height), so the
curves are exact: network JSON, OBJ, SVG, DXF (exact ARC and LINE entities)
and Rhino exports of a window need nothing tracery-specific.
"""

from __future__ import annotations

import numpy as np

from auszug.geometry.heights import SideCoordinate
from auszug.geometry.network import CurveNetwork, Piece
from auszug.geometry.symmetry import SymmetryGroup
from auszug.tracery.model import Tracery

__all__ = ["border_network"]


def border_network(tracery: Tracery) -> CurveNetwork:
    """The window's region borders as a :class:`~auszug.geometry.network.CurveNetwork`.

    Parameters
    ----------
    tracery : Tracery

    Returns
    -------
    CurveNetwork
        Basic curve i is ``tracery.regions[i]`` (``meta["regions"]`` names it);
        its pieces run along its counter-clockwise loop, each with 65 samples.

    Examples
    --------
    >>> from auszug import tracery
    >>> net = border_network(tracery.build("fig20a"))
    >>> net.meta["regions"][0]["id"], sorted({p.top.kind for p in net.pieces})
    ('arch', ['arc', 'line'])
    """
    pieces: list[Piece] = []
    regions = []
    for i, r in enumerate(tracery.regions):
        z = -float(r.face)
        for j, c in enumerate(r.curves):
            u = np.linspace(0.0, 1.0, 65)
            pts = np.concatenate([c.point_at(u), np.full((65, 1), z)], axis=1)
            pts.setflags(write=False)
            pieces.append(Piece(i, j, "border", c, None, SideCoordinate("arclength", c.length()), pts,
                                z_const=z))
        regions.append({"index": i, "id": r.id, "group": r.group, "role": r.role, "depth": r.depth,
                        "face": float(r.face), "border": float(r.border), "profile": r.profile.name})
    lo, hi = tracery.bounds()
    size = max(1e-9, float(np.max(np.abs([lo, hi]))))
    n = len(tracery.regions)
    return CurveNetwork(tuple(pieces), tuple(SymmetryGroup(1) for _ in range(n)), tuple(0 for _ in range(n)),
                        (0.0,), size, "window", {"regions": regions})
