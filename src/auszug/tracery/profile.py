"""Profiles: the 2D cross-sections swept along region borders (Havemann and Fellner, Fig. 18).

A profile is a polyline of lines and circular arcs in the plane ``(s, t)``:
``s`` is how far the opening is shrunk (the inset, towards the region's
inside) and ``t`` how far the point lies behind the face, both in units of
the region's border width, so the same profile fits every level of a
recursive window. It starts at ``(0, 0)`` (the edge of the opening in the
face) and never turns back: ``s`` and ``t`` do not decrease along it, so the
cut at every depth is an offset of the opening, which the exact offsets keep
free of self-intersections at sharp corners (their "extrudestable").

A *wall* profile (the reveal of the outer arch in the wall) runs the other way
round: ``s <= 0`` widens the opening towards the wall face, ``t`` goes from 0
at the wall face to 1 at the face of the tracery slab, where ``s`` is 0.

Arcs are given as bulges, DXF-style: the bulge of a segment is
``tan(sweep / 4)``, positive for a counter-clockwise arc in the ``(s, t)``
plane, 0 for a line.

The outline itself is an open :class:`auszug.meshing.Profile` (the one
profile of lines and arcs of auszug, with the sweep model's sampling and
evaluation); a :class:`Moulding` is that profile in its tracery role: where
it starts, which way it runs, whether it is a wall's reveal.

Examples
--------
>>> from auszug.tracery.profile import Moulding
>>> p = Moulding("hollow", [[0, 0], [1, 1], [1, 2]], bulge=[-0.41421356, 0])
>>> p.sample(8).shape
(10, 2)
>>> bool(p.sample(8)[:, 1].min() >= 0)
True
>>> p.profile.closed, p.profile.length > 2.5
(False, True)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.errors import GeometryError
from auszug.meshing import Profile
from auszug.tracery._checks import ParameterError

__all__ = ["Moulding", "profile_from_data"]

Array = NDArray[np.float64]


@dataclass(frozen=True, init=False)
class Moulding:
    """A tracery moulding: an open line/arc :class:`~auszug.meshing.Profile` in the (inset, depth) plane.

    Parameters
    ----------
    name : str
    points : (n, 2) array_like
        Vertices ``(s, t)``, n >= 2.
    bulge : (n - 1,) array_like, optional
        ``tan(sweep / 4)`` of each segment (0: straight). Default all 0.
    wall : bool
        A wall (reveal) profile: ``s <= 0`` ending in ``s = 0`` at ``t = 1``.

    Attributes
    ----------
    profile : auszug.meshing.Profile
        The outline (open, named ``name``): x the inset ``s``, y the depth ``t``.

    Raises
    ------
    ParameterError
        If the profile turns back (``s`` or ``t`` decreasing), does not start
        at the origin (region profiles) or end at ``(0, 1)`` (wall profiles),
        or is no profile at all (see :class:`~auszug.meshing.Profile`).
    """

    name: str
    profile: Profile
    wall: bool

    def __init__(self, name: str, points: ArrayLike, bulge: ArrayLike | None = None, wall: bool = False) -> None:
        where = f"profile {name!r}"
        try:
            pts = np.asarray(points, dtype=float)
        except (TypeError, ValueError):
            raise ParameterError(where, points, "at least two finite (s, t) points") from None
        if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 2 or not np.all(np.isfinite(pts)):
            raise ParameterError(where, pts.tolist(), "at least two finite (s, t) points")
        bul = np.zeros(len(pts) - 1) if bulge is None else np.asarray(bulge, dtype=float)
        if bul.shape != (len(pts) - 1,) or not np.all(np.isfinite(bul)):
            raise ParameterError(where + " bulge", bul.tolist(), f"{len(pts) - 1} finite numbers (one per segment)")
        if np.any(np.abs(bul) > 1.0 + 1e-12):
            raise ParameterError(where + " bulge", bul.tolist(), "bulges in [-1, 1] (arcs of at most a half circle)")
        if wall:
            if abs(pts[0, 1]) > 1e-12 or abs(pts[-1, 1] - 1.0) > 1e-12 or abs(pts[-1, 0]) > 1e-12:
                raise ParameterError(where, pts.tolist(), "a wall profile from t = 0 to (s, t) = (0, 1)")
            if np.any(pts[:, 0] > 1e-12):
                raise ParameterError(where, pts.tolist(), "a wall profile with s <= 0 (it widens the opening)")
        elif np.any(np.abs(pts[0]) > 1e-12):
            raise ParameterError(where, pts.tolist(), "a profile starting at (0, 0), the edge of the opening")
        try:
            prof = Profile(pts, closed=False, name=name, bulge=bul)
        except GeometryError as e:
            raise ParameterError(where, pts.tolist(), "a profile of lines and arcs", str(e)) from None
        ds = np.diff(prof.sample(per_arc=16), axis=0)
        if np.any(ds < -1e-9):
            raise ParameterError(where, pts.tolist(), "a profile whose s and t never decrease",
                                 "each depth must cut an offset of the opening")
        object.__setattr__(self, "name", name)
        object.__setattr__(self, "profile", prof)
        object.__setattr__(self, "wall", bool(wall))

    # -- the outline ---------------------------------------------------------------------
    @property
    def points(self) -> Array:
        """The vertices ``(s, t)``, shape (n, 2)."""
        return self.profile.points

    @property
    def bulge(self) -> Array:
        """``tan(sweep / 4)`` per segment, shape (n - 1,)."""
        return self.profile.bulges

    # -- measures ------------------------------------------------------------------------
    @property
    def end(self) -> Array:
        """The last vertex ``(s, t)``, shape (2,)."""
        return self.points[-1]

    @property
    def depth(self) -> float:
        """Largest ``t``."""
        return float(self.points[-1, 1])

    @property
    def inset(self) -> float:
        """``s`` at the end (for a recess: how far its floor is shrunk)."""
        return float(self.points[-1, 0])

    # -- sampling ------------------------------------------------------------------------
    def sample(self, per_arc: int = 8) -> Array:
        """The polyline: vertices plus ``per_arc - 1`` points inside each arc; shape (m, 2)."""
        return self.profile.sample(per_arc=per_arc)

    def sharp(self, per_arc: int = 8) -> NDArray[np.bool_]:
        """Which points of :meth:`sample` are creases, shape (m,) (see :meth:`auszug.meshing.Profile.sharp`)."""
        return self.profile.sharp(per_arc)

    def scaled(self, ds: float, dt: float) -> Moulding:
        """The profile with s scaled by ``ds`` and t by ``dt`` (arcs stay arcs only if equal)."""
        return Moulding(self.name, self.points * [ds, dt], self.bulge if ds == dt else None, self.wall)

    def to_data(self) -> dict[str, Any]:
        """A TOML/JSON-ready description."""
        d: dict[str, Any] = {"points": self.points.tolist()}
        if self.profile.has_arcs:
            d["bulge"] = self.bulge.tolist()
        if self.wall:
            d["wall"] = True
        return d


def profile_from_data(name: str, data: Mapping[str, Any] | Sequence[Sequence[float]] | ArrayLike) -> Moulding:
    """A profile from its TOML/JSON description.

    The description is a list of points, or a table
    ``{points = [[s, t], ...], bulge = [...], wall = false}``.

    Examples
    --------
    >>> profile_from_data("flat", [[0, 0], [0, 1]]).depth
    1.0
    """
    if isinstance(data, Mapping):
        unknown = set(data) - {"points", "bulge", "wall", "description"}
        if unknown:
            raise ParameterError(f"profile {name!r}", sorted(unknown), "keys among points, bulge, wall, description")
        if "points" not in data:
            raise ParameterError(f"profile {name!r}", dict(data), "a table with points = [[s, t], ...]")
        return Moulding(name, data["points"], data.get("bulge"), bool(data.get("wall", False)))
    return Moulding(name, data)
