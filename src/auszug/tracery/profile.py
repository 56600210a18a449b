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

Examples
--------
>>> from auszug.tracery.profile import Profile
>>> p = Profile("hollow", [[0, 0], [1, 1], [1, 2]], bulge=[-0.41421356, 0])
>>> p.sample(8).shape
(10, 2)
>>> bool(p.sample(8)[:, 1].min() >= 0)
True
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.tracery._checks import ParameterError

__all__ = ["Profile", "profile_from_data"]

Array = NDArray[np.float64]


@dataclass(frozen=True, eq=False, init=False)
class Profile:
    """A line/arc polyline in the (inset, depth) plane.

    Parameters
    ----------
    name : str
    points : (n, 2) array_like
        Vertices ``(s, t)``, n >= 2.
    bulge : (n - 1,) array_like, optional
        ``tan(sweep / 4)`` of each segment (0: straight). Default all 0.
    wall : bool
        A wall (reveal) profile: ``s <= 0`` ending in ``s = 0`` at ``t = 1``.

    Raises
    ------
    ParameterError
        If the profile turns back (``s`` or ``t`` decreasing), does not start
        at the origin (region profiles) or end at ``(0, 1)`` (wall profiles).
    """

    name: str
    points: Array
    bulge: Array
    wall: bool

    # the fields hold arrays; the constructor takes any array-like (no bulge: straight segments)
    def __init__(self, name: str, points: ArrayLike, bulge: ArrayLike | None = None, wall: bool = False) -> None:
        object.__setattr__(self, "name", name)
        object.__setattr__(self, "points", points)
        object.__setattr__(self, "bulge", bulge)
        object.__setattr__(self, "wall", wall)
        self.__post_init__()

    def __post_init__(self) -> None:
        pts = np.asarray(self.points, dtype=float)
        where = f"profile {self.name!r}"
        if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 2 or not np.all(np.isfinite(pts)):
            raise ParameterError(where, pts.tolist(), "at least two finite (s, t) points")
        bul = np.zeros(len(pts) - 1) if self.bulge is None else np.asarray(self.bulge, dtype=float)
        if bul.shape != (len(pts) - 1,) or not np.all(np.isfinite(bul)):
            raise ParameterError(where + " bulge", bul.tolist(), f"{len(pts) - 1} finite numbers (one per segment)")
        if np.any(np.abs(bul) > 1.0 + 1e-12):
            raise ParameterError(where + " bulge", bul.tolist(), "bulges in [-1, 1] (arcs of at most a half circle)")
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "bulge", bul)
        if self.wall:
            if abs(pts[0, 1]) > 1e-12 or abs(pts[-1, 1] - 1.0) > 1e-12 or abs(pts[-1, 0]) > 1e-12:
                raise ParameterError(where, pts.tolist(), "a wall profile from t = 0 to (s, t) = (0, 1)")
            if np.any(pts[:, 0] > 1e-12):
                raise ParameterError(where, pts.tolist(), "a wall profile with s <= 0 (it widens the opening)")
        elif np.any(np.abs(pts[0]) > 1e-12):
            raise ParameterError(where, pts.tolist(), "a profile starting at (0, 0), the edge of the opening")
        poly = self.sample(16)
        ds = np.diff(poly, axis=0)
        if np.any(ds < -1e-9):
            raise ParameterError(where, pts.tolist(), "a profile whose s and t never decrease",
                                 "each depth must cut an offset of the opening")

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Profile):
            return NotImplemented
        return (self.name == other.name and self.wall == other.wall and self.points.shape == other.points.shape
                and bool(np.array_equal(self.points, other.points)) and bool(np.array_equal(self.bulge, other.bulge)))

    def __hash__(self) -> int:
        return hash((self.name, self.wall, self.points.tobytes(), self.bulge.tobytes()))

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
        out = [self.points[:1]]
        for i in range(len(self.points) - 1):
            a, b, k = self.points[i], self.points[i + 1], self.bulge[i]
            if abs(k) < 1e-12 or per_arc < 2:
                out.append(b[None])
                continue
            sweep = 4.0 * math.atan(k)
            chord = b - a
            c_len = math.hypot(*chord)
            r = c_len / (2.0 * math.sin(abs(sweep) / 2.0))
            mid = 0.5 * (a + b)
            nrm = np.array([-chord[1], chord[0]]) / c_len
            # centre on the left of the chord for a counter-clockwise arc
            h = r * math.cos(sweep / 2.0)
            ctr = mid + math.copysign(h, sweep) * nrm
            th0 = math.atan2(a[1] - ctr[1], a[0] - ctr[0])
            th = th0 + sweep * np.linspace(0.0, 1.0, per_arc + 1)[1:]
            pts = ctr + r * np.stack([np.cos(th), np.sin(th)], axis=-1)
            pts[-1] = b
            out.append(pts)
        return np.concatenate(out)

    def sharp(self, per_arc: int = 8) -> NDArray[np.bool_]:
        """Which points of :meth:`sample` are creases, shape (m,).

        The end points are creases, and every vertex where the tangent turns
        by more than 1 degree; points inside arcs and tangent-continuous
        vertices are smooth.
        """
        pts = self.points
        n = len(pts)
        chord = np.diff(pts, axis=0)
        ang = np.arctan2(chord[:, 1], chord[:, 0])
        sweep = 4.0 * np.arctan(self.bulge)
        t_start = ang - 0.5 * sweep
        t_end = ang + 0.5 * sweep
        turn = np.abs((t_start[1:] - t_end[:-1] + np.pi) % (2 * np.pi) - np.pi)
        vsharp = np.ones(n, dtype=bool)
        vsharp[1:-1] = turn > math.radians(1.0)
        out = [vsharp[:1]]
        for i in range(n - 1):
            k = per_arc if abs(self.bulge[i]) >= 1e-12 and per_arc >= 2 else 1
            seg = np.zeros(k, dtype=bool)
            seg[-1] = vsharp[i + 1]
            out.append(seg)
        return np.concatenate(out)

    def scaled(self, ds: float, dt: float) -> Profile:
        """The profile with s scaled by ``ds`` and t by ``dt`` (arcs stay arcs only if equal)."""
        return Profile(self.name, self.points * [ds, dt], self.bulge if ds == dt else None, self.wall)

    def to_data(self) -> dict[str, Any]:
        """A TOML/JSON-ready description."""
        d: dict[str, Any] = {"points": self.points.tolist()}
        if np.any(self.bulge != 0):
            d["bulge"] = self.bulge.tolist()
        if self.wall:
            d["wall"] = True
        return d


def profile_from_data(name: str, data: Mapping[str, Any] | Sequence[Sequence[float]] | ArrayLike) -> Profile:
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
        return Profile(name, data["points"], data.get("bulge"), bool(data.get("wall", False)))
    return Profile(name, data)
