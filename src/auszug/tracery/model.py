"""The 2D structure of a window: regions bounded by exact lines and arcs.

A :class:`Tracery` is what a style makes of a window: a flat list of
:class:`Region` values, each a closed counter-clockwise loop of lines and arcs
with its group, nesting depth and role:

* ``"frame"``: the region holds further tracery (the outer arch, a sub-arch
  refined as a window, a circle holding a rosette); in 3D it is a recess
  shaped by its profile, whose floor carries the nested regions;
* ``"light"``: an opening through the tracery plate, its border cut by its
  profile;
* ``"blind"``: a recess without an opening (blind tracery).

Polygons are made only at the very end, by :meth:`Region.polygon`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from auszug.geometry import Arc, Curve
from auszug.geometry.offset import signed_area
from auszug.tracery.profile import Moulding

if TYPE_CHECKING:  # style and window import this module
    from auszug.tracery.style import Style
    from auszug.tracery.window import WindowParams

__all__ = ["Region", "Tracery", "GROUPS", "ROLES", "polygon"]

#: Region groups: the paper's four and the decorations that refine them.
GROUPS = ("arch", "sub-arch", "circle", "fillet", "rosette", "light")
ROLES = ("frame", "light", "blind")

Array = NDArray[np.float64]


def polygon(curves: tuple[Curve, ...], max_angle: float = math.pi / 64, chord: float | None = None) -> Array:
    """The closed loop as a polygon (first point not repeated), shape (m, 2).

    Lines contribute their start point; an arc of sweep ``s`` and radius ``r``
    contributes ``ceil(|s| / step)`` points, the step being ``max_angle`` or,
    if ``chord`` is given, the angle whose chord deviates ``chord`` from the
    arc (whichever is larger, at most ``pi / 4``).

    Examples
    --------
    >>> from auszug.geometry import Line
    >>> sq = (Line((0, 0), (1, 0)), Line((1, 0), (1, 1)), Line((1, 1), (0, 1)), Line((0, 1), (0, 0)))
    >>> polygon(sq).tolist()
    [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    """
    parts = []
    for c in curves:
        if isinstance(c, Arc):
            step = max_angle
            if chord is not None and chord < c.radius:
                step = max(step, 2.0 * math.acos(1.0 - chord / c.radius))
            step = min(step, math.pi / 4)
            n = max(1, math.ceil(abs(c.sweep) / step - 1e-9))
            parts.append(c.point(np.arange(n) / n))
        else:
            parts.append(c.start[None])
    return np.concatenate(parts)


@dataclass(frozen=True, eq=False)
class Region:
    """One region of a window's structure.

    Attributes
    ----------
    id : str
        Path of the region in the window tree (``"arch/sub-arch-left/circle"``).
    group : str
        One of :data:`GROUPS`.
    depth : int
        Nesting depth of the window it belongs to (0 = the outer window).
    curves : tuple of Line or Arc
        The boundary in the region's face, a closed counter-clockwise loop.
    role : str
        One of :data:`ROLES`.
    border : float
        The region's border width: the unit of its profile.
    profile : Moulding
        The cross-section cut along the border.
    face : float
        How far the region's face lies behind the face of the tracery plate
        (the floors of the recesses it is nested in).
    template : int
        Regions with the same template are translates of each other (congruent
        sub-windows are constructed once); -1 if unique.
    origin : (float, float)
        The translation from the template's position to this region.
    """

    id: str
    group: str
    depth: int
    curves: tuple[Curve, ...]
    role: str
    border: float
    profile: Moulding
    face: float = 0.0
    template: int = -1
    origin: tuple[float, float] = (0.0, 0.0)

    def polygon(self, max_angle: float = math.pi / 64, chord: float | None = None) -> Array:
        """The boundary as a polygon, shape (m, 2); see :func:`polygon`."""
        return polygon(self.curves, max_angle, chord)

    @cached_property
    def area(self) -> float:
        """Exact area enclosed."""
        return signed_area(self.curves)

    @property
    def parent(self) -> str | None:
        """Id of the region this one is nested in (None for the arch)."""
        return self.id.rsplit("/", 1)[0] if "/" in self.id else None

    @property
    def floor_depth(self) -> float:
        """Depth of the recess floor behind the plate's face (frames and blind regions)."""
        return self.face + self.profile.depth * self.border


@dataclass(frozen=True, eq=False)
class Tracery:
    """A window's structure: its regions, and the style and parameters it was made with.

    Attributes
    ----------
    regions : tuple of Region
        Depth-first: each frame before the regions nested in it.
    params : WindowParams
    style : Style
    """

    regions: tuple[Region, ...]
    params: WindowParams
    style: Style

    def group(self, name: str) -> list[Region]:
        """The regions of one group."""
        return [r for r in self.regions if r.group == name]

    @property
    def lights(self) -> list[Region]:
        """The openings through the plate."""
        return [r for r in self.regions if r.role == "light"]

    @property
    def depth(self) -> int:
        """Deepest nesting level."""
        return max(r.depth for r in self.regions)

    def bounds(self) -> Array:
        """``[[xmin, ymin], [xmax, ymax]]`` of all regions."""
        pts = np.concatenate([r.polygon() for r in self.regions])
        return np.array([pts.min(0), pts.max(0)])
