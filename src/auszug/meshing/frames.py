"""Rotation-minimising frames along sampled 3D curves (double reflection), vectorised.

The double-reflection method (Wang, Juettler, Zheng, Liu 2008) carries a
frame from sample i to i + 1 by two reflections, which compose to a rotation
taking the tangent t_i exactly to t_{i+1}. Run as a loop it is sequential;
here every step is expressed as an angle in a fixed reference basis of each
sample's normal plane, so the whole propagation is one cumulative sum:

    theta_{i+1} = theta_i + phi_i,

phi_i being the angle, in basis i + 1, of the doubly reflected reference
vector of basis i. No Python loop runs per sample.

:func:`sweep_frames` then turns the whole frame about the tangent so that
each end meets its target direction (a symmetry plane's normal) and spreads
the remaining twist linearly in arc length.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.errors import GeometryError

__all__ = ["Frames", "reference_basis", "rmf_angles", "sweep_frames"]

Array = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class Frames:
    """Orthonormal frames along a curve.

    Attributes
    ----------
    tangent : (n, 3) ndarray
        Unit tangents T.
    width : (n, 3) ndarray
        Unit vectors W (profile x), orthogonal to T.
    depth : (n, 3) ndarray
        D = T x W (profile y), so (W, D, T) is right-handed.
    arclength : (n,) ndarray
        Cumulative chord length from the first sample.
    twist : float
        Total angle (radians) added on top of the rotation-minimising frame
        between the first and the last sample.
    """

    tangent: Array
    width: Array
    depth: Array
    arclength: Array
    twist: float = 0.0


def reference_basis(tangents: ArrayLike) -> tuple[Array, Array]:
    """An orthonormal basis (a, b) of each tangent's normal plane, (t, a, b) right-handed.

    The branchless construction of Duff et al. (2017); it is discontinuous only
    where t_z changes sign, which does not matter to :func:`rmf_angles`.

    Parameters
    ----------
    tangents : (n, 3) array_like
        Unit vectors.

    Returns
    -------
    a, b : (n, 3) ndarray

    Examples
    --------
    >>> a, b = reference_basis([[0.0, 0.0, 1.0]])
    >>> a.tolist(), b.tolist()
    ([[1.0, -0.0, -0.0]], [[-0.0, 1.0, -0.0]])
    """
    t = np.asarray(tangents, dtype=float)
    x, y, z = t[..., 0], t[..., 1], t[..., 2]
    s = np.where(z >= 0.0, 1.0, -1.0)
    a = -1.0 / (s + z)
    b = x * y * a
    e1 = np.stack([1.0 + s * x * x * a, s * b, -s * x], axis=-1)
    e2 = np.stack([b, s + y * y * a, -y], axis=-1)
    return e1, e2


def _dot(u: Array, v: Array) -> Array:
    return np.einsum("...i,...i->...", u, v)


def rmf_angles(points: ArrayLike, tangents: ArrayLike, basis: tuple[Array, Array] | None = None) -> Array:
    """Rotation-minimising frame angles in the :func:`reference_basis`, starting at 0.

    A frame vector at angle theta_0 in basis 0 is carried by double reflection
    to angle ``theta_0 + out[i]`` in basis i.

    Parameters
    ----------
    points : (n, 3) array_like
    tangents : (n, 3) array_like
        Unit tangents at the points.
    basis : (a, b), optional
        :func:`reference_basis` of the tangents, if already at hand.

    Returns
    -------
    (n,) ndarray

    Examples
    --------
    >>> import numpy as np
    >>> z = np.linspace(0, 1, 5)
    >>> pts = np.stack([0 * z, 0 * z, z], 1); tan = np.tile([0.0, 0.0, 1.0], (5, 1))
    >>> rmf_angles(pts, tan).tolist()       # a straight line: no turning at all
    [0.0, 0.0, 0.0, 0.0, 0.0]
    """
    x = np.asarray(points, dtype=float)
    t = np.asarray(tangents, dtype=float)
    n = len(x)
    if n < 2:
        return np.zeros(n)
    a, b = reference_basis(t) if basis is None else basis
    v1 = x[1:] - x[:-1]
    c1 = _dot(v1, v1)
    ok1 = c1 > 0.0
    k1 = np.divide(2.0, c1, out=np.zeros_like(c1), where=ok1)
    a_l = a[:-1] - (k1 * _dot(v1, a[:-1]))[:, None] * v1
    t_l = t[:-1] - (k1 * _dot(v1, t[:-1]))[:, None] * v1
    v2 = t[1:] - t_l
    c2 = _dot(v2, v2)
    k2 = np.divide(2.0, c2, out=np.zeros_like(c2), where=c2 > 1e-30)
    a_n = a_l - (k2 * _dot(v2, a_l))[:, None] * v2
    phi = np.arctan2(_dot(a_n, b[1:]), _dot(a_n, a[1:]))
    return np.concatenate([[0.0], np.cumsum(phi)])


def _angle_in(basis_a: Array, basis_b: Array, v: Array) -> float:
    return math.atan2(float(np.dot(v, basis_b)), float(np.dot(v, basis_a)))


def _nearest(theta: float, target: float, period: float) -> float:
    """``target + k period`` closest to ``theta``."""
    return target + period * round((theta - target) / period)


def sweep_frames(
    points: ArrayLike,
    tangents: ArrayLike,
    width0: ArrayLike,
    start_target: ArrayLike | None = None,
    end_target: ArrayLike | None = None,
    period: float = math.pi,
) -> Frames:
    """Rotation-minimising frames that meet given directions at the ends.

    Parameters
    ----------
    points : (n, 3) array_like
    tangents : (n, 3) array_like
        Unit tangents.
    width0 : (3,) array_like
        Preferred W at the first sample (projected onto its normal plane).
    start_target, end_target : (3,) array_like, optional
        Directions W should take at the first / last sample, up to turns by
        ``period`` (e.g. a symmetry plane's normal; pi for a profile symmetric
        under x -> -x, pi/2 for a square). A target nearly along the tangent
        is ignored.
    period : float
        Turns of the profile that leave it looking the same.

    Returns
    -------
    Frames
        With one end target, the whole rotation-minimising frame is turned (no
        twist); with both, the start is met exactly and the remaining twist
        (at most ``period / 2``) is spread linearly in arc length.

    Raises
    ------
    GeometryError
        If ``width0`` is parallel to the first tangent, or fewer than 2 samples.

    Examples
    --------
    >>> import numpy as np
    >>> z = np.linspace(0, 1, 3)
    >>> f = sweep_frames(np.stack([0 * z, 0 * z, z], 1), np.tile([0.0, 0, 1], (3, 1)), [1.0, 0, 0],
    ...                  end_target=[1.0, 1.0, 0.0])
    >>> np.round(f.width[0], 6) + 0.0, np.round(f.depth[0], 6) + 0.0
    (array([0.707107, 0.707107, 0.      ]), array([-0.707107,  0.707107,  0.      ]))
    """
    x = np.asarray(points, dtype=float)
    t = np.asarray(tangents, dtype=float)
    if len(x) < 2:
        raise GeometryError(f"frames need at least 2 samples, got {len(x)}")
    a, b = reference_basis(t)
    w0 = np.asarray(width0, dtype=float)
    w0 = w0 - np.dot(w0, t[0]) * t[0]
    if np.linalg.norm(w0) <= 1e-12:
        raise GeometryError("the initial width direction is parallel to the curve's tangent")
    theta = rmf_angles(x, t, (a, b))
    th0 = _angle_in(a[0], b[0], w0)

    def target_angle(v: ArrayLike | None, i: int) -> float | None:
        if v is None:
            return None
        v0 = np.asarray(v, dtype=float)
        v = v0 - np.dot(v0, t[i]) * t[i]
        if np.linalg.norm(v) < 0.5 * np.linalg.norm(v0) or np.linalg.norm(v) <= 1e-12:
            return None
        return _angle_in(a[i], b[i], v)

    ts = target_angle(start_target, 0)
    te = target_angle(end_target, -1)
    if ts is not None:
        th0 = _nearest(th0, ts, period)
    theta = theta + th0
    v1 = np.diff(x, axis=0)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(v1, axis=1))])
    twist = 0.0
    if te is not None:
        delta = _nearest(theta[-1], te, period) - theta[-1]
        if ts is not None and s[-1] > 0:
            theta = theta + delta * (s / s[-1])
            twist = float(delta)
        else:
            theta = theta + delta
    c, sn = np.cos(theta)[:, None], np.sin(theta)[:, None]
    w = c * a + sn * b
    d = np.cross(t, w)
    return Frames(t, w, d, s, twist)
