"""Straight line segments."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from auszug.errors import GeometryError
from auszug.geometry import _tolerance
from auszug.geometry.curve import Array, Curve, as_point

__all__ = ["Line"]


@dataclass(frozen=True, eq=False, repr=False, init=False)
class Line(Curve):
    """The segment from ``p0`` to ``p1``; t is proportional to arc length.

    Parameters
    ----------
    p0, p1 : (2,) array_like
        Start and end point (drawing units); must differ.

    Examples
    --------
    >>> from auszug.geometry import Line
    >>> ln = Line((0, 0), (3, 4))
    >>> ln.length()
    5.0
    >>> ln.point(0.5).tolist()
    [1.5, 2.0]
    """

    p0: Array
    p1: Array
    _len: float = field(init=False)
    kind = "line"

    # the fields hold arrays; the constructor takes any array-like and converts
    def __init__(self, p0: ArrayLike, p1: ArrayLike) -> None:
        object.__setattr__(self, "p0", p0)
        object.__setattr__(self, "p1", p1)
        self.__post_init__()

    def __post_init__(self) -> None:
        p0 = as_point(self.p0, "line start")
        p1 = as_point(self.p1, "line end")
        length = float(np.hypot(*(p1 - p0)))
        if length <= _tolerance.TOL.zero:
            raise GeometryError(f"zero-length line at {p0.tolist()}")
        object.__setattr__(self, "p0", p0)
        object.__setattr__(self, "p1", p1)
        object.__setattr__(self, "_len", length)

    @property
    def direction(self) -> Array:
        """Unit direction, shape (2,)."""
        return (self.p1 - self.p0) / self._len

    def point(self, t: ArrayLike) -> Array:
        """Points at parameters ``t``, shape ``t.shape + (2,)``."""
        t = np.asarray(t, dtype=float)
        return self.p0 + t[..., None] * (self.p1 - self.p0)

    def tangent(self, t: ArrayLike) -> Array:
        """Unit tangents at ``t``: the direction everywhere, shape ``t.shape + (2,)``."""
        t = np.asarray(t, dtype=float)
        return np.broadcast_to(self.direction, t.shape + (2,)).copy()

    def curvature(self, t: ArrayLike) -> Array:
        """Curvature at ``t``: zero everywhere."""
        return np.zeros(np.shape(t))

    def length(self) -> float:
        """Distance between the end points."""
        return self._len

    def split(self, t: float) -> tuple[Line, Line]:
        """The two segments before and after parameter ``t``."""
        m = self.point(t)
        return Line(self.p0, m), Line(m, self.p1)

    def reversed(self) -> Line:
        """The same segment from end to start."""
        return Line(self.p1, self.p0)

    def transformed(self, matrix: ArrayLike, offset: ArrayLike = (0.0, 0.0)) -> Line:
        """The segment mapped by ``x -> matrix @ x + offset``."""
        m = np.asarray(matrix, dtype=float)
        b = np.asarray(offset, dtype=float)
        return Line(m @ self.p0 + b, m @ self.p1 + b)

    def project(self, p: ArrayLike) -> float:
        """Parameter of the point of the segment closest to ``p``."""
        d = self.p1 - self.p0
        return float(np.clip(np.dot(np.asarray(p, float) - self.p0, d) / (self._len**2), 0.0, 1.0))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description: kind, start and end."""
        return {"kind": "line", "start": self.p0.tolist(), "end": self.p1.tolist()}
