"""The one small curve protocol every planar curve of auszug follows.

``t`` is always a curve's own parameter in [0, 1]; ``u`` always the normalised
arc length in [0, 1]. For lines and arcs the two coincide; for Beziers they do
not. Everything else (arc-length evaluation, sampling) derives from the few
abstract methods.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["Curve", "as_point", "rot90", "cross2"]

Array = NDArray[np.float64]


def as_point(p: ArrayLike, name: str = "point") -> Array:
    """Validate and return a finite 2D point as a float array of shape (2,)."""
    a = np.asarray(p, dtype=float)
    if a.shape != (2,):
        from auszug.errors import GeometryError

        raise GeometryError(f"{name} must have shape (2,), got {a.shape}")
    if not (math.isfinite(a[0]) and math.isfinite(a[1])):  # scalar checks: 10x faster than numpy here
        from auszug.errors import GeometryError

        raise GeometryError(f"{name} must be finite, got {a.tolist()}")
    return a


def rot90(v: Array) -> Array:
    """Rotate vectors of shape (..., 2) by +90 degrees (the left normal)."""
    v = np.asarray(v, dtype=float)
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def cross2(a: Array, b: Array) -> Array:
    """z-component of the cross product of vectors of shape (..., 2)."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


class Curve(ABC):
    """A planar parametric curve on t in [0, 1].

    Subclasses implement :meth:`point`, :meth:`tangent`, :meth:`length`,
    :meth:`split`, :meth:`reversed`, :meth:`transformed`, :meth:`to_dict`,
    :meth:`curvature`, :meth:`project`, and,
    when t is not proportional to arc length, :meth:`u_at_t` and :meth:`t_at_u`.
    """

    kind: str = "curve"

    # -- abstract core -----------------------------------------------------------------
    @abstractmethod
    def point(self, t: ArrayLike) -> Array:
        """Point(s) at parameter ``t``: shape (...,) -> (..., 2)."""

    @abstractmethod
    def tangent(self, t: ArrayLike) -> Array:
        """Unit tangent(s) at ``t``: shape (...,) -> (..., 2)."""

    @abstractmethod
    def length(self) -> float:
        """Arc length (drawing units)."""

    @abstractmethod
    def split(self, t: float) -> tuple["Curve", "Curve"]:
        """The pieces on [0, t] and [t, 1], each reparameterised to [0, 1]."""

    @abstractmethod
    def reversed(self) -> "Curve":
        """The same point set traversed from end to start."""

    @abstractmethod
    def transformed(self, matrix: ArrayLike, offset: ArrayLike = (0.0, 0.0)) -> "Curve":
        """Image under x -> matrix @ x + offset, with matrix orthogonal (2, 2)."""

    @abstractmethod
    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready description (``{"kind": ..., ...}``)."""

    @abstractmethod
    def curvature(self, t: ArrayLike) -> Array:
        """Signed curvature at ``t`` (positive = turning left): shape (...,) -> (...,)."""

    @abstractmethod
    def project(self, p: ArrayLike) -> float:
        """Parameter ``t`` of the point of the curve closest to the point ``p``."""

    # -- arc-length parameter ----------------------------------------------------------
    def u_at_t(self, t: ArrayLike) -> Array:
        """Normalised arc length at parameter ``t`` (identity unless overridden)."""
        return np.asarray(t, dtype=float)

    def t_at_u(self, u: ArrayLike) -> Array:
        """Parameter ``t`` at normalised arc length ``u`` (identity unless overridden)."""
        return np.asarray(u, dtype=float)

    # -- derived ----------------------------------------------------------------------
    @property
    def start(self) -> Array:
        """First point, shape (2,)."""
        return self.point(0.0)

    @property
    def end(self) -> Array:
        """Last point, shape (2,)."""
        return self.point(1.0)

    def point_at(self, u: ArrayLike) -> Array:
        """Point(s) at normalised arc length ``u``: shape (...,) -> (..., 2)."""
        return self.point(self.t_at_u(u))

    def tangent_at(self, u: ArrayLike) -> Array:
        """Unit tangent(s) at normalised arc length ``u``."""
        return self.tangent(self.t_at_u(u))

    def sample(self, n: int) -> Array:
        """``n`` points at equal arc-length steps from start to end, shape (n, 2)."""
        if n < 2:
            raise ValueError(f"sample needs n >= 2, got {n}")
        return self.point_at(np.linspace(0.0, 1.0, n))

    def __repr__(self) -> str:  # pragma: no cover - cosmetic
        return f"{type(self).__name__}({self.to_dict()})"
