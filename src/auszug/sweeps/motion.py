"""Rigid motions sampled at parameters, evaluable in between (screw interpolation on SE(3)).

A :class:`Motion` holds rigid maps ``x -> R_k x + T_k`` at increasing parameters ``t_k``. Between
two knots the relative motion ``M_k^{-1} M_{k+1}`` is a screw (a rotation about an axis combined
with a translation along it, Chasles); :meth:`Motion.at` moves along that screw at constant speed,
``M(t) = M_k exp(f log(M_k^{-1} M_{k+1}))``. So a motion that *is* a rotation about a fixed axis,
a translation or a helical screw (the kinematic surfaces) is reproduced exactly between its knots,
and every evaluated map is a proper rigid motion (``R^T R = I``, ``det R = +1``).

The functions :func:`se3_log` and :func:`se3_exp` are the twist coordinates ``(omega, v)`` of
SE(3), vectorised over leading axes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.errors import GeometryError
from auszug.sweeps._kernels import apply_maps, knot_maps, rotation_defects, rotations_of, rotvecs_of

__all__ = ["Motion", "se3_exp", "se3_log", "screw_motion", "rotation_about"]

Array = NDArray[np.float64]

#: Largest deviation of a motion's rotation from a rotation (``R^T R - I``, ``det R - 1``).
ROTATION_TOL = 1e-9


def _hat(w: Array) -> Array:
    """Cross-product matrices ``(..., 3, 3)`` of vectors ``(..., 3)``."""
    out = np.zeros(w.shape[:-1] + (3, 3))
    out[..., 0, 1], out[..., 0, 2] = -w[..., 2], w[..., 1]
    out[..., 1, 0], out[..., 1, 2] = w[..., 2], -w[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -w[..., 1], w[..., 0]
    return out


def _v_coeffs(theta: Array) -> tuple[Array, Array]:
    """``(1 - cos t) / t^2`` and ``(t - sin t) / t^3``, with their series near 0."""
    small = theta < 1e-4
    th = np.where(small, 1.0, theta)
    a = np.where(small, 0.5 - theta**2 / 24.0, (1.0 - np.cos(th)) / th**2)
    b = np.where(small, 1.0 / 6.0 - theta**2 / 120.0, (th - np.sin(th)) / th**3)
    return a, b


def se3_exp(omega: ArrayLike, v: ArrayLike) -> tuple[Array, Array]:
    """Rigid maps ``(R (..., 3, 3), T (..., 3))`` of twists ``(omega (..., 3), v (..., 3))``.

    Examples
    --------
    A quarter turn about z with a lift of 1 along it:

    >>> r, t = se3_exp([0, 0, np.pi / 2], [0, 0, 1.0])
    >>> np.round(r @ [1.0, 0, 0], 12).tolist(), np.round(t, 12).tolist()
    ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0])
    """
    w = np.asarray(omega, float)
    vv = np.asarray(v, float)
    theta = np.linalg.norm(w, axis=-1)
    # compiled: bit for bit scipy's Rotation.from_rotvec(w).as_matrix(), without its per-call overhead
    r = rotations_of(np.ascontiguousarray(w.reshape(-1, 3))).reshape(w.shape[:-1] + (3, 3))
    a, b = _v_coeffs(theta)
    k = _hat(w)
    vmat = np.eye(3) + a[..., None, None] * k + b[..., None, None] * (k @ k)
    return r, np.einsum("...ij,...j->...i", vmat, vv)


def se3_log(rotation: ArrayLike, translation: ArrayLike) -> tuple[Array, Array]:
    """Twists ``(omega (..., 3), v (..., 3))`` of rigid maps (rotation angle below pi).

    Raises
    ------
    GeometryError
        A rotation whose determinant is not positive or that has a non-finite entry.

    Examples
    --------
    >>> r, t = se3_exp([0.1, -0.2, 0.3], [0.5, 0.0, -1.0])
    >>> w, v = se3_log(r, t)
    >>> (np.round(w, 12) + 0.0).tolist(), (np.round(v, 12) + 0.0).tolist()   # + 0.0: no -0.0
    ([0.1, -0.2, 0.3], [0.5, 0.0, -1.0])
    """
    r = np.asarray(rotation, float)
    t = np.asarray(translation, float)
    # compiled: bit for bit scipy's Rotation.from_matrix(r).as_rotvec() for orthogonal r (|R^T R - I| <= 1e-12)
    w = rotvecs_of(np.ascontiguousarray(r.reshape(-1, 3, 3))).reshape(r.shape[:-2] + (3,))
    if not np.isfinite(w).all():
        raise GeometryError("se3_log: a rotation has a determinant <= 0 (or a non-finite entry): not a rigid map")
    theta = np.linalg.norm(w, axis=-1)
    a, b = _v_coeffs(theta)
    k = _hat(w)
    vmat = np.eye(3) + a[..., None, None] * k + b[..., None, None] * (k @ k)
    return w, np.linalg.solve(vmat, t[..., None])[..., 0]


def rotation_about(axis: ArrayLike, angle: ArrayLike) -> Array:
    """Rotations ``(..., 3, 3)`` by ``angle`` (radians, shape (...)) about the unit ``axis (3,)``."""
    a = np.asarray(axis, float)
    a = a / np.linalg.norm(a)
    ang = np.asarray(angle, float)
    return rotations_of(np.ascontiguousarray(ang.reshape(-1)[:, None] * a)).reshape(ang.shape + (3, 3))


def screw_motion(direction: ArrayLike, point: ArrayLike | None, pitch: float, t: ArrayLike) -> tuple[Array, Array]:
    """The kinematic motions ``R (k, 3, 3)``, ``T (k, 3)`` at parameters ``t (k,)``.

    Rotation by ``t`` about the axis through ``point`` along ``direction`` with ``pitch`` (length
    per radian), or with ``point`` None a translation by ``t`` along ``direction``.

    Examples
    --------
    >>> r, tr = screw_motion([0, 0, 1.0], [1.0, 0, 0], 0.0, [np.pi])
    >>> np.round(r[0] @ [2.0, 0, 0] + tr[0], 12).tolist()     # (2, 0, 0) half-way round (1, 0, 0)
    [0.0, 0.0, 0.0]
    """
    d = np.asarray(direction, float)
    d = d / np.linalg.norm(d)
    tt = np.atleast_1d(np.asarray(t, float))
    if point is None:
        return np.broadcast_to(np.eye(3), (len(tt), 3, 3)).copy(), tt[:, None] * d
    p = np.asarray(point, float)
    r = rotation_about(d, tt)
    return r, p - np.einsum("kij,j->ki", r, p) + (pitch * tt)[:, None] * d


@dataclass(frozen=True)
class Motion:
    """Rigid maps ``x -> R_k x + T_k`` at increasing parameters ``t_k``.

    Attributes
    ----------
    t : (k,) float array
        Strictly increasing parameters, k >= 2 (the sweep's first rib at ``t[0]``).
    rotation : (k, 3, 3) float array
        Proper rotations.
    translation : (k, 3) float array

    Raises
    ------
    GeometryError
        Shapes that do not match, parameters that do not increase, or a matrix that is not a
        rotation within 1e-9.

    Examples
    --------
    A half turn about z sampled at its ends only; half-way it is the quarter turn:

    >>> r, tr = screw_motion([0, 0, 1.0], [0.0, 0, 0], 0.0, [0.0, 3.0])
    >>> m = Motion(np.array([0.0, 1.0]), r, tr)
    >>> np.round(m.apply([[1.0, 0, 0]], [0.5])[0, 0], 6).tolist()
    [0.070737, 0.997495, 0.0]
    """

    t: Array
    rotation: Array
    translation: Array

    def __post_init__(self) -> None:
        t = np.asarray(self.t, float)
        r = np.asarray(self.rotation, float)
        tr = np.asarray(self.translation, float)
        k = len(t)
        if t.ndim != 1 or k < 2 or r.shape != (k, 3, 3) or tr.shape != (k, 3):
            raise GeometryError(f"a motion needs t (k,), rotation (k, 3, 3), translation (k, 3) with k >= 2; "
                                f"got {t.shape}, {r.shape}, {tr.shape}")
        if not (np.isfinite(t).all() and np.isfinite(r).all() and np.isfinite(tr).all()):
            raise GeometryError("a motion must be finite")
        if not np.all(np.diff(t) > 0):
            raise GeometryError("motion parameters must increase strictly")
        # compiled: |R^T R - I| and det R per map (within round-off of numpy's einsum and det)
        err, det = rotation_defects(np.ascontiguousarray(r))
        bad = np.flatnonzero((err > ROTATION_TOL) | (np.abs(det - 1.0) > ROTATION_TOL))
        if len(bad):
            i = int(bad[0])
            raise GeometryError(f"motion map {i} is not a rotation: |R^T R - I| = {err[i]:.3g}, det R = {det[i]:.6g}")
        object.__setattr__(self, "t", t)
        object.__setattr__(self, "rotation", r)
        object.__setattr__(self, "translation", tr)

    def __len__(self) -> int:
        return len(self.t)

    @property
    def domain(self) -> tuple[float, float]:
        """First and last parameter."""
        return float(self.t[0]), float(self.t[-1])

    def at(self, t: ArrayLike) -> tuple[Array, Array]:
        """The maps at parameters ``t (q,)`` (clamped to the domain): ``R (q, 3, 3)``, ``T (q, 3)``."""
        tt = np.ascontiguousarray(np.atleast_1d(np.asarray(t, float)))
        # compiled: the clamped parameters' intervals and fractions as numpy's searchsorted and clip give them, the
        # knots' maps (copies: exact at knots), and the parameters inside an interval
        r, tr, inner, ii, ff = knot_maps(self.t, self.rotation, self.translation, tt)
        # between knots the screw motion between them (log and exp only where needed)
        if len(inner):
            r0, t0 = self.rotation[ii], self.translation[ii]
            wi, vi = self._interval_twists()
            w, v = wi[ii], vi[ii]
            dr, dt = se3_exp(w * ff[:, None], v * ff[:, None])
            r[inner] = r0 @ dr
            tr[inner] = t0 + np.einsum("kij,kj->ki", r0, dt)
        return r, tr

    def _interval_twists(self) -> tuple[Array, Array]:
        """The twists ``(omega (k - 1, 3), v (k - 1, 3))`` of the screw between each pair of knots (computed once).

        The log of ``M_k^{-1} M_{k+1}``, row by row as :meth:`at` took it for the intervals it needed.
        """
        got: tuple[Array, Array] | None = self.__dict__.get("_twists")
        if got is None:
            r0, r1 = self.rotation[:-1], self.rotation[1:]
            r0t = np.swapaxes(r0, -1, -2)
            got = se3_log(r0t @ r1, np.einsum("kij,kj->ki", r0t, self.translation[1:] - self.translation[:-1]))
            object.__setattr__(self, "_twists", got)      # frozen: a cache of the knots, not a field
        return got

    def apply(self, points: ArrayLike, t: ArrayLike) -> Array:
        """``points (n, 3)`` moved by the maps at ``t (q,)``: shape ``(q, n, 3)``."""
        x = np.ascontiguousarray(np.asarray(points, float).reshape(-1, 3))
        r, tr = self.at(t)
        # compiled: np.einsum("qij,nj->qni", r, x) + tr[:, None, :] bit for bit
        out: Array = apply_maps(np.ascontiguousarray(r), np.ascontiguousarray(tr), x)
        return out

    def inverse_apply(self, points: ArrayLike, t: ArrayLike) -> Array:
        """Each point ``(n, 3)`` mapped back by the inverse of the map at its own ``t (n,)``: ``(n, 3)``."""
        x = np.asarray(points, float)
        r, tr = self.at(t)
        return np.einsum("nji,nj->ni", r, x - tr)

    def transformed(self, scale: float, centre: ArrayLike) -> "Motion":
        """The same motion in coordinates ``y = scale x + centre`` (R kept, T = scale T + centre - R centre)."""
        c = np.asarray(centre, float)
        return Motion(self.t.copy(), self.rotation.copy(),
                      scale * self.translation + c - np.einsum("kij,j->ki", self.rotation, c))
