"""Heights over a planar curve: side views and the side-view coordinate.

A 3D curve of a curve network is often a planar top-view curve lifted by a
height function: ``(x(t), y(t), z(g(t)))``. Two values describe the lift:

- :class:`SideCoordinate`, the rule g(t) that maps the top curve's parameter
  to the horizontal coordinate of the side view (top-view arc length, the
  parameter itself, or an orthographic projection), with its inverse t(g);
- :class:`SideView`, a chain of circular arcs, each the graph of z(g) over its
  g-interval (an ogee biarc, a decorated ogee, a free end).

Both are pure values with vectorised evaluation; the inverse t(g) lives here
and nowhere else.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.geometry.curve import Curve

__all__ = ["SideView", "SideCoordinate", "SIDE_MODES"]

Array = NDArray[np.float64]
SideMode = Literal["arclength", "u", "orthographic"]
SIDE_MODES: tuple[str, ...] = ("arclength", "u", "orthographic")

#: Newton steps of the orthographic inverse t(g) after its monotone table lookup.
_NEWTON_STEPS = 6
#: Table size of the orthographic inverse's first guess.
_TABLE = 513


@dataclass(frozen=True)
class SideView:
    """A chain of k arcs, each a graph z(g), joined G1 (or in a cusp).

    Attributes
    ----------
    breaks : (k + 1,) ndarray
        g at the start and end of each arc (increasing, breaks[0] = 0).
    centers : (k, 2) ndarray
        Arc centres (g, z).
    radii : (k,) ndarray
    upper : (k,) ndarray of float
        +1 where the arc is on the upper half of its circle, -1 on the lower.
    vertical : (k,) ndarray
        g of a point where each arc's circle has a vertical tangent (c_g - r or
        c_g + r): heights are measured from there, exactly.

    Examples
    --------
    >>> import numpy as np
    >>> sv = SideView(np.array([0.0, 1.0]), np.array([[1.0, 0.0]]), np.array([1.0]),
    ...               np.array([1.0]), np.array([0.0]))
    >>> float(sv.height(1.0)), sv.extent
    (1.0, 1.0)
    """

    breaks: Array
    centers: Array
    radii: Array
    upper: Array
    vertical: Array

    @property
    def extent(self) -> float:
        """Total horizontal extent G."""
        return float(self.breaks[-1])

    def height(self, g: ArrayLike) -> Array:
        """Heights z at side-view coordinates ``g`` (clamped to [0, G]), shape preserved.

        Evaluated as c_z +- sqrt(d (2 r - d)), d the horizontal distance from the
        circle's nearest vertical-tangent point, so heights at the vertical end
        tangents are exact (no cancellation in r^2 - (g - c_g)^2).
        """
        g = np.clip(np.asarray(g, dtype=float), 0.0, self.breaks[-1])
        i = np.clip(np.searchsorted(self.breaks, g, side="right") - 1, 0, len(self.radii) - 1)
        r = self.radii[i]
        d = np.abs(g - self.vertical[i])
        return self.centers[i, 1] + self.upper[i] * np.sqrt(np.maximum(d * (2.0 * r - d), 0.0))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description: ``{"breaks", "centers", "radii", "upper", "vertical"}``."""
        return {
            "breaks": np.asarray(self.breaks, dtype=float).tolist(),
            "centers": np.asarray(self.centers, dtype=float).tolist(),
            "radii": np.asarray(self.radii, dtype=float).tolist(),
            "upper": np.asarray(self.upper, dtype=float).tolist(),
            "vertical": np.asarray(self.vertical, dtype=float).tolist(),
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> "SideView":
        """Inverse of :meth:`to_dict`."""
        return cls(
            np.asarray(d["breaks"], dtype=float).reshape(-1),
            np.asarray(d["centers"], dtype=float).reshape(-1, 2),
            np.asarray(d["radii"], dtype=float).reshape(-1),
            np.asarray(d["upper"], dtype=float).reshape(-1),
            np.asarray(d["vertical"], dtype=float).reshape(-1),
        )


@dataclass(frozen=True)
class SideCoordinate:
    """The rule g(t) from a top curve's parameter to its side-view coordinate.

    Attributes
    ----------
    mode : {"arclength", "u", "orthographic"}
        ``"arclength"``: g = a u(t), u the normalised arc length and ``a`` the
        top curve's length; ``"u"``: g = t; ``"orthographic"``: g is ``sign``
        times the projection of ``top(t) - top(0)`` onto the direction
        ``(a, b)`` (a one-to-one map, checked by the producer).
    a, b, sign : float

    Examples
    --------
    >>> from auszug.geometry import Line
    >>> top = Line((0.0, 0.0), (2.0, 0.0))
    >>> rule = SideCoordinate("arclength", 2.0)
    >>> float(rule.g_of_t(top, 0.25)), float(rule.t_of_g(top, 1.5))
    (0.5, 0.75)
    """

    mode: str
    a: float = 1.0
    b: float = 0.0
    sign: float = 1.0

    def g_of_t(self, top: Curve, t: ArrayLike) -> Array:
        """Side-view coordinate g at top-view parameter(s) ``t``, shape preserved."""
        t = np.asarray(t, dtype=float)
        if self.mode == "arclength":
            return top.u_at_t(t) * self.a
        if self.mode == "u":
            return t
        p = top.point(t) - top.start
        return self.sign * (p[..., 0] * self.a + p[..., 1] * self.b)

    def t_of_g(self, top: Curve, g: ArrayLike) -> Array:
        """Top-view parameter(s) at side-view coordinate(s) ``g`` (clamped to the curve).

        Exact for the arc-length and ``u`` rules (through the curve's own
        ``t_at_u``); Newton on the monotone projection for the orthographic rule.
        """
        g = np.asarray(g, dtype=float)
        if self.mode == "arclength":
            return np.asarray(top.t_at_u(np.clip(g / self.a, 0.0, 1.0)), dtype=float)
        if self.mode == "u":
            return np.clip(g, 0.0, 1.0)
        tt = np.linspace(0.0, 1.0, _TABLE)
        gg = self.g_of_t(top, tt)
        t = np.interp(g, gg, tt)
        for _ in range(_NEWTON_STEPS):
            dg = self.dg_dt(top, t)
            with np.errstate(divide="ignore", invalid="ignore"):
                step = np.where(dg > 0.0, (self.g_of_t(top, t) - g) / dg, 0.0)
            t = np.clip(t - step, 0.0, 1.0)
        return t

    def dg_dt(self, top: Curve, t: ArrayLike) -> Array:
        """Derivative dg/dt at ``t`` (exact: from the top curve's speed and tangent)."""
        t = np.asarray(t, dtype=float)
        if self.mode == "u":
            return np.ones_like(t)
        speed = _speed(top, t)
        if self.mode == "arclength":
            return speed * self.a / max(top.length(), 1e-300)
        tan = top.tangent(t)
        return self.sign * speed * (tan[..., 0] * self.a + tan[..., 1] * self.b)

    def ds_dg(self, top: Curve, t: ArrayLike) -> Array:
        """Top-view arc length per unit side-view coordinate at ``t``."""
        t = np.asarray(t, dtype=float)
        if self.mode == "arclength":
            return np.full(t.shape, top.length() / self.a)
        with np.errstate(divide="ignore", invalid="ignore"):
            return _speed(top, t) / self.dg_dt(top, t)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description ``{"mode", "a", "b", "sign"}``."""
        return {"mode": self.mode, "a": float(self.a), "b": float(self.b), "sign": float(self.sign)}


def _speed(top: Curve, t: Array) -> Array:
    """|d top / dt| (drawing units per unit parameter)."""
    speed = getattr(top, "speed", None)
    if speed is not None:
        return np.asarray(speed(t), dtype=float)
    return np.full(np.shape(t), top.length())  # t proportional to arc length (lines, arcs)


def orthographic_rule(top: Curve, theta: float, check: int = 129) -> tuple[SideCoordinate, float] | None:
    """The orthographic rule at angle ``theta`` and its extent, or None if not one-to-one.

    Parameters
    ----------
    top : Curve
    theta : float
        Angle (radians) of the side view's horizontal axis to the x-axis.
    check : int
        Samples used to check that g(t) is monotone.
    """
    a, b = math.cos(theta), math.sin(theta)
    p = top.point(np.linspace(0.0, 1.0, check))
    g = p[:, 0] * a + p[:, 1] * b
    sign = 1.0 if g[-1] >= g[0] else -1.0
    if np.any(np.diff(g) * sign <= 0.0):
        return None
    return SideCoordinate("orthographic", a, b, sign), abs(float(g[-1] - g[0]))
