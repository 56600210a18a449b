"""Cubic Bezier curves, with an accurate arc-length parameterisation.

The legacy corpus stores some top views as cubic Beziers (``ptTan`` handles).
Unlike lines and arcs, the Bezier parameter ``t`` is not proportional to arc
length; :meth:`CubicBezier.u_at_t` and :meth:`CubicBezier.t_at_u` convert
between ``t`` and the normalised arc length ``u`` to about 1e-13, from a table
of Gauss-Legendre integrals on adaptively refined knots plus a safeguarded
Newton iteration.
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.errors import GeometryError
from auszug.geometry import _tolerance
from auszug.geometry.curve import Array, Curve, as_point, cross2

__all__ = ["CubicBezier", "t_at_u_many"]

# 16-point Gauss-Legendre rule on [-1, 1]; exact for polynomials of degree 31.
_GL_X, _GL_W = np.polynomial.legendre.leggauss(16)

# Arc-length table: a knot interval is accepted when its 16-point integral and
# the sum over its two halves agree to this fraction of the curve length.
_TABLE_REL = 1e-15
_TABLE_MAX_LEVELS = 60
_I2 = np.eye(2)
#: Up to this many values, u_at_t runs in floats (numpy's per-call cost is larger).
_FEW = 8
#: project's samples of t, and the Bernstein weights of :meth:`CubicBezier.point` there, shape (n, 1)
_PROJ_N = 129
_PROJ_T = np.linspace(0.0, 1.0, _PROJ_N)
_PROJ_M = (1.0 - _PROJ_T)[:, None]
_PROJ_W = (_PROJ_M * _PROJ_M * _PROJ_M, 3.0 * _PROJ_M * _PROJ_M * _PROJ_T[:, None],
           3.0 * _PROJ_M * _PROJ_T[:, None] * _PROJ_T[:, None],
           _PROJ_T[:, None] * _PROJ_T[:, None] * _PROJ_T[:, None])


def _bracketed_newton(f: Array, sp: Array, t: Array, lo: Array, hi: Array,
                      eps_f: Array | float) -> tuple[Array, Array, Array, NDArray[np.bool_]]:
    """One safeguarded Newton step of the arc-length inversion, elementwise.

    ``f (n,)`` is the arc length from 0 to ``t (n,)`` minus the target and ``sp (n,)`` the speed
    there; the root stays bracketed by ``[lo, hi]``. Returns the next ``t`` (the Newton step,
    or the bracket's middle where that leaves it), the narrowed ``lo`` and ``hi``, and which
    values are done (``|f| <= eps_f`` or a bracket of 1e-16). Call under
    ``np.errstate(invalid="ignore", divide="ignore")`` (a zero speed gives a non-finite step).
    """
    pos = f > 0
    hi = np.where(pos, t, hi)
    lo = np.where(pos, lo, t)
    tn = t - f / sp
    ok = np.isfinite(tn) & (tn > lo) & (tn < hi)
    tn = np.where(ok, tn, 0.5 * (lo + hi))
    done = (np.abs(f) <= eps_f) | (hi - lo <= 1e-16)
    return tn, lo, hi, done


@dataclass(frozen=True, eq=False, repr=False, init=False)
class CubicBezier(Curve):
    """The cubic Bezier curve with control points ``p0, p1, p2, p3``.

    ``t`` is the Bezier parameter; ``u`` (normalised arc length) is available
    through :meth:`u_at_t`, :meth:`t_at_u` and the derived :meth:`point_at`.

    Parameters
    ----------
    p0, p1, p2, p3 : (2,) array_like
        Start point, the two handles and the end point (drawing units). The four
        must not all coincide.

    Examples
    --------
    >>> from auszug.geometry import CubicBezier
    >>> b = CubicBezier((0, 0), (1, 2), (3, 2), (4, 0))
    >>> b.point(0.5).tolist()
    [2.0, 1.5]
    >>> round(b.length(), 12)
    5.268365543019
    >>> round(float(b.u_at_t(b.t_at_u(0.3))), 14)
    0.3
    """

    p0: Array
    p1: Array
    p2: Array
    p3: Array
    kind = "bezier"

    # the fields hold arrays; the constructor takes any array-like and converts
    def __init__(self, p0: ArrayLike, p1: ArrayLike, p2: ArrayLike, p3: ArrayLike) -> None:
        for name, p in (("p0", p0), ("p1", p1), ("p2", p2), ("p3", p3)):
            object.__setattr__(self, name, p)
        self.__post_init__()

    def __post_init__(self) -> None:
        pts = [as_point(p, f"Bezier control point {i}") for i, p in enumerate(
            (self.p0, self.p1, self.p2, self.p3))]
        spread = max(float(np.hypot(*(q - pts[0]))) for q in pts[1:])
        if spread <= _tolerance.TOL.zero:
            raise GeometryError(
                f"Bezier control points all coincide at {pts[0].tolist()}: expected a curve"
            )
        for name, p in zip(("p0", "p1", "p2", "p3"), pts, strict=True):
            object.__setattr__(self, name, p)

    # -- construction ---------------------------------------------------------------------
    @classmethod
    def from_array(cls, controls: ArrayLike) -> CubicBezier:
        """Bezier from control points of shape (4, 2).

        Examples
        --------
        >>> CubicBezier.from_array([[0, 0], [1, 1], [2, 1], [3, 0]]).end.tolist()
        [3.0, 0.0]
        """
        c = np.asarray(controls, dtype=float)
        if c.shape != (4, 2):
            raise GeometryError(f"Bezier control points must have shape (4, 2), got {c.shape}")
        return cls(c[0], c[1], c[2], c[3])

    @property
    def controls(self) -> Array:
        """The control points, shape (4, 2)."""
        return np.stack([self.p0, self.p1, self.p2, self.p3])

    # -- evaluation -----------------------------------------------------------------------
    def point(self, t: ArrayLike) -> Array:
        """Points at parameters ``t`` (Bernstein form), shape ``t.shape + (2,)``."""
        t = np.asarray(t, dtype=float)[..., None]
        m = 1.0 - t
        return (m * m * m) * self.p0 + (3.0 * m * m * t) * self.p1 + (
            3.0 * m * t * t) * self.p2 + (t * t * t) * self.p3

    def derivative(self, t: ArrayLike, order: int = 1) -> Array:
        """Derivative d^k B / dt^k for k = ``order`` in {1, 2, 3}: shape (...,) -> (..., 2).

        Examples
        --------
        >>> b = CubicBezier((0, 0), (1, 0), (2, 0), (3, 0))
        >>> b.derivative(0.5).tolist(), b.derivative(0.5, 2).tolist()
        ([3.0, 0.0], [0.0, 0.0])
        """
        t = np.asarray(t, dtype=float)[..., None]
        a, b, c = self.p1 - self.p0, self.p2 - self.p1, self.p3 - self.p2
        if order == 1:
            m = 1.0 - t
            return 3.0 * ((m * m) * a + (2.0 * m * t) * b + (t * t) * c)
        if order == 2:
            return 6.0 * ((1.0 - t) * (b - a) + t * (c - b))
        if order == 3:
            return np.broadcast_to(6.0 * (c - 2.0 * b + a), t.shape[:-1] + (2,)).copy()
        raise ValueError(f"derivative order must be 1, 2 or 3, got {order}")

    def tangent(self, t: ArrayLike) -> Array:
        """Unit tangent(s) at ``t``: shape (...,) -> (..., 2).

        Where the derivative vanishes (a handle on its end point, or a cusp) the
        one-sided limit of the direction is returned: from the right, except at
        ``t = 1`` where it is from the left.
        """
        t = np.asarray(t, dtype=float)
        d1 = self.derivative(t)
        n1 = np.hypot(d1[..., 0], d1[..., 1])
        zero = _tolerance.TOL.zero
        if np.all(n1 > zero):
            return d1 / n1[..., None]
        # d1 ~ d2 (t - t0): its direction is -d2 from the left, +d2 from the right
        side = np.where(t >= 1.0, -1.0, 1.0)[..., None]
        d2 = side * self.derivative(t, 2)
        n2 = np.hypot(d2[..., 0], d2[..., 1])
        d3 = self.derivative(t, 3)  # d1 ~ d3 (t - t0)^2 / 2: same direction on both sides
        n3 = np.hypot(d3[..., 0], d3[..., 1])
        use1 = (n1 > zero)[..., None]
        use2 = (n2 > zero)[..., None]
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(
                use1, d1 / n1[..., None], np.where(use2, d2 / n2[..., None], d3 / n3[..., None])
            )

    def curvature(self, t: ArrayLike) -> Array:
        """Signed curvature at ``t`` (positive = turning left): shape (...,) -> (...,).

        Unbounded (``+-inf``) at a cusp, where the derivative vanishes.
        """
        t = np.asarray(t, dtype=float)
        d1 = self.derivative(t)
        d2 = self.derivative(t, 2)
        n1 = np.hypot(d1[..., 0], d1[..., 1])
        cr = cross2(d1, d2)
        with np.errstate(invalid="ignore", divide="ignore"):
            k = cr / (n1 * n1 * n1)
        bad = n1 <= _tolerance.TOL.zero
        if np.any(bad):
            s = np.sign(cross2(d2, self.derivative(t, 3)))
            k = np.where(bad, np.where(s > 0, np.inf, np.where(s < 0, -np.inf, 0.0)), k)
        return k

    def speed(self, t: ArrayLike) -> Array:
        """|dB/dt|, the arc length per unit of t: shape (...,) -> (...,).

        The same floating-point operations as :meth:`derivative`, per coordinate (numpy's cost
        of the trailing axis of 2 was most of the arc-length table's and :meth:`t_at_u`'s time).
        """
        t = np.asarray(t, dtype=float)
        ax, ay, bx, by, cx, cy = self._dfloats
        m = 1.0 - t
        p, q, r = m * m, 2.0 * m * t, t * t
        return np.hypot(3.0 * (p * ax + q * bx + r * cx), 3.0 * (p * ay + q * by + r * cy))

    @cached_property
    def _dfloats(self) -> tuple[float, float, float, float, float, float]:
        """The control polygon's edges p1 - p0, p2 - p1, p3 - p2 as 6 floats (ax, ay, bx, by, cx, cy)."""
        a, b, c = self.p1 - self.p0, self.p2 - self.p1, self.p3 - self.p2
        return (float(a[0]), float(a[1]), float(b[0]), float(b[1]), float(c[0]), float(c[1]))

    # -- arc length -----------------------------------------------------------------------
    def _integral(self, lo: Array, hi: Array) -> Array:
        """Arc length between parameters ``lo`` and ``hi`` (same shape) by 16-point GL."""
        half = 0.5 * (hi - lo)
        ts = (0.5 * (hi + lo))[..., None] + half[..., None] * _GL_X
        return half * (self.speed(ts) @ _GL_W)

    @cached_property
    def _table(self) -> tuple[Array, Array]:
        """(knots (k+1,), cumulative arc length at the knots (k+1,)), computed on first use.

        A rigid image of a curve (:meth:`transformed` by an orthogonal matrix: the
        replicas of a symmetry) has the same speed at every ``t``, so it shares the
        table of the curve it was made from instead of computing its own.
        """
        src = self.__dict__.get("_arc_source")
        if src is not None:
            return src._table
        # Knots at the extrema of the speed, so that a cusp (where |B'| has a kink
        # rather than being smooth) is always at a knot, never inside an interval.
        knots = np.unique(np.concatenate([np.linspace(0.0, 1.0, 17), self._speed_extrema()]))
        for _ in range(_TABLE_MAX_LEVELS):
            a, b = knots[:-1], knots[1:]
            m = 0.5 * (a + b)
            whole = self._integral(a, b)
            halves = self._integral(a, m) + self._integral(m, b)
            bad = np.abs(whole - halves) > _TABLE_REL * max(float(halves.sum()), 1e-300)
            if not bad.any():
                break
            knots = np.sort(np.concatenate([knots, m[bad]]))
        cum = np.concatenate([[0.0], np.cumsum(halves)])
        return knots, cum

    def _speed_extrema(self) -> Array:
        """Parameters in (0, 1) where |B'|^2 is stationary: roots of the cubic B' . B''."""
        coef = self._extrema_cubic()
        if len(coef) < 2:
            return np.zeros(0)
        return _in_unit(np.roots(coef))

    def _extrema_cubic(self) -> Array:
        """The coefficients of B' . B'' / 3, scaled to a largest of 1, negligible leading ones dropped."""
        a, b, c = self.p1 - self.p0, self.p2 - self.p1, self.p3 - self.p2
        q0, q1, q2 = a, 2.0 * (b - a), c - 2.0 * b + a  # B' / 3 = q0 + q1 t + q2 t^2
        coef = [2.0 * q2 @ q2, 3.0 * q1 @ q2, 2.0 * q0 @ q2 + q1 @ q1, q0 @ q1]
        scale = max(abs(x) for x in coef)
        if scale == 0.0:
            return np.zeros(0)
        out = np.array(coef) / scale
        while len(out) > 1 and abs(out[0]) <= 1e-13:  # negligible leading terms
            out = out[1:]
        return out

    def length(self) -> float:
        """Arc length, from the arc-length table."""
        return float(self._table[1][-1])

    def u_at_t(self, t: ArrayLike) -> Array:
        """Normalised arc length at parameter ``t`` in [0, 1]: shape (...,) -> (...,).

        Examples
        --------
        >>> b = CubicBezier((0, 0), (0, 1), (1, 1), (1, 0))
        >>> b.u_at_t([0.0, 0.5, 1.0]).round(15).tolist()
        [0.0, 0.5, 1.0]
        """
        t = np.clip(np.asarray(t, dtype=float), 0.0, 1.0)
        if t.size <= _FEW:
            return np.array([self._u_at_t_scalar(x) for x in t.ravel().tolist()]).reshape(t.shape)
        knots, cum = self._table
        k = np.clip(np.searchsorted(knots, t, side="right") - 1, 0, len(knots) - 2)
        s = cum[k] + self._integral(knots[k], t)
        return np.where(t >= 1.0, 1.0, np.clip(s / cum[-1], 0.0, 1.0))

    def t_at_u(self, u: ArrayLike) -> Array:
        """Parameter ``t`` at normalised arc length ``u`` in [0, 1]: shape (...,) -> (...,).

        Newton's method on the arc-length integral, kept inside the bracketing
        knot interval (bisection where a step would leave it).

        Examples
        --------
        >>> b = CubicBezier((0, 0), (0, 1), (1, 1), (1, 0))
        >>> float(b.t_at_u(0.5))
        0.5
        """
        u = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
        if u.ndim == 0 and 0.0 < float(u) < 1.0:
            return np.asarray(self._t_at_u_scalar(float(u)))
        knots, cum = self._table
        total = cum[-1]
        target = u * total
        k = np.clip(np.searchsorted(cum, target, side="right") - 1, 0, len(knots) - 2)
        lo, hi = knots[k].copy(), knots[k + 1].copy()
        seg = cum[k + 1] - cum[k]
        with np.errstate(invalid="ignore", divide="ignore"):
            t = np.where(seg > 0, lo + (hi - lo) * (target - cum[k]) / seg, lo)
        t = np.clip(t, lo, hi)
        base, start = cum[k], knots[k]
        eps_f = 1e-15 * total
        with np.errstate(invalid="ignore", divide="ignore"):
            for _ in range(100):
                f = base + self._integral(start, t) - target
                tn, lo, hi, done = _bracketed_newton(f, self.speed(t), t, lo, hi, eps_f)
                if done.all():
                    break
                t = np.where(done, t, tn)
        return np.where(u >= 1.0, 1.0, np.where(u <= 0.0, 0.0, t))

    @cached_property
    def _scalar_table(self) -> tuple[list[float], list[float], tuple[float, ...], list[tuple[float, float]]]:
        """The arc-length table, the derivative's coefficients and the Gauss-Legendre rule as floats."""
        knots, cum = self._table
        return knots.tolist(), cum.tolist(), self._dfloats, list(zip(_GL_X.tolist(), _GL_W.tolist(), strict=True))

    def _speed_integral(self, lo: float, hi: float) -> float:
        """:meth:`_integral` of one interval in floats (16-point Gauss-Legendre)."""
        _, _, (ax, ay, bx, by, cx, cy), rule = self._scalar_table
        half, mid = 0.5 * (hi - lo), 0.5 * (hi + lo)
        acc = 0.0
        for x, w in rule:
            t = mid + half * x
            m = 1.0 - t
            p, q, r = m * m, 2.0 * m * t, t * t
            acc += w * math.hypot(p * ax + q * bx + r * cx, p * ay + q * by + r * cy)
        return 3.0 * half * acc

    def _u_at_t_scalar(self, t: float) -> float:
        """:meth:`u_at_t` of one ``t`` in [0, 1] in floats."""
        if t >= 1.0:
            return 1.0
        knots, cum, _, _ = self._scalar_table
        k = min(max(bisect.bisect_right(knots, t) - 1, 0), len(knots) - 2)
        s = cum[k] + self._speed_integral(knots[k], t)
        return min(max(s / cum[-1], 0.0), 1.0)

    def _t_at_u_scalar(self, u: float) -> float:
        """:meth:`t_at_u` of one ``u`` in (0, 1) in floats: the same Newton iteration without arrays.

        (An edit rebuilds a curve's PRC and intersection heights through a few single
        values; numpy's per-call cost was most of their time.)
        """
        knots, cum, (ax, ay, bx, by, cx, cy), rule = self._scalar_table
        hyp = math.hypot

        def speed(t: float) -> float:
            m = 1.0 - t
            p, q, r = m * m, 2.0 * m * t, t * t
            return 3.0 * hyp(p * ax + q * bx + r * cx, p * ay + q * by + r * cy)

        def integral(lo: float, hi: float) -> float:
            half, mid = 0.5 * (hi - lo), 0.5 * (hi + lo)
            return half * sum(w * speed(mid + half * x) for x, w in rule)

        total = cum[-1]
        target = u * total
        k = min(max(bisect.bisect_right(cum, target) - 1, 0), len(knots) - 2)
        lo, hi = knots[k], knots[k + 1]
        seg = cum[k + 1] - cum[k]
        t = lo + (hi - lo) * (target - cum[k]) / seg if seg > 0 else lo
        t = min(max(t, lo), hi)
        base, start = cum[k], knots[k]
        for _ in range(100):
            f = base + integral(start, t) - target
            sp = speed(t)
            if f > 0:
                hi = t
            else:
                lo = t
            tn = t - f / sp if sp != 0.0 else math.nan
            if not (math.isfinite(tn) and lo < tn < hi):
                tn = 0.5 * (lo + hi)
            if abs(f) <= 1e-15 * total or hi - lo <= 1e-16:
                break
            t = tn
        return t

    # -- editing --------------------------------------------------------------------------
    def split(self, t: float) -> tuple[CubicBezier, CubicBezier]:
        """The pieces on [0, t] and [t, 1] (de Casteljau), each a CubicBezier.

        Examples
        --------
        >>> b = CubicBezier((0, 0), (1, 2), (3, 2), (4, 0))
        >>> left, right = b.split(0.25)
        >>> bool(np.allclose(left.point(1.0), b.point(0.25)))
        True
        """
        t = float(t)
        a01 = self.p0 + t * (self.p1 - self.p0)
        a12 = self.p1 + t * (self.p2 - self.p1)
        a23 = self.p2 + t * (self.p3 - self.p2)
        b0 = a01 + t * (a12 - a01)
        b1 = a12 + t * (a23 - a12)
        m = b0 + t * (b1 - b0)
        return CubicBezier(self.p0, a01, b0, m), CubicBezier(m, b1, a23, self.p3)

    def segment(self, t0: float, t1: float) -> CubicBezier:
        """The piece on [t0, t1] (t1 < t0 gives it reversed), reparameterised to [0, 1].

        Examples
        --------
        >>> b = CubicBezier((0, 0), (1, 2), (3, 2), (4, 0))
        >>> bool(np.allclose(b.segment(0.2, 0.6).point(0.5), b.point(0.4)))
        True
        """
        c = _segment_controls(self.controls, float(t0), float(t1))
        return CubicBezier(c[0], c[1], c[2], c[3])

    def reversed(self) -> CubicBezier:
        """The same curve from end to start (control points in reverse order)."""
        return CubicBezier(self.p3, self.p2, self.p1, self.p0)

    def transformed(self, matrix: ArrayLike, offset: ArrayLike = (0.0, 0.0)) -> CubicBezier:
        """The curve mapped by ``x -> matrix @ x + offset`` (applied to the control points)."""
        m = np.asarray(matrix, dtype=float)
        c = self.controls @ m.T + np.asarray(offset, dtype=float)
        if m.shape == (2, 2) and np.abs(m @ m.T - _I2).max() <= 1e-12:   # rigid: the same arc-length table
            # a rigid image of a valid curve is valid (finite, control points as far apart):
            # the fields are set without the constructor's checks
            if not np.isfinite(c).all():
                raise GeometryError(f"Bezier control points must be finite, got {c.tolist()}")
            out = object.__new__(CubicBezier)
            for name, p in zip(("p0", "p1", "p2", "p3"), c, strict=True):
                object.__setattr__(out, name, p)
            object.__setattr__(out, "_arc_source", self.__dict__.get("_arc_source", self))
            return out
        return CubicBezier(c[0], c[1], c[2], c[3])

    def project(self, p: ArrayLike) -> float:
        """Parameter ``t`` of the point of the curve closest to ``p``.

        Examples
        --------
        >>> b = CubicBezier((0, 0), (1, 2), (3, 2), (4, 0))
        >>> b.project((2, 5))
        0.5
        """
        p = np.asarray(p, dtype=float)
        n = _PROJ_N
        ts = _PROJ_T
        w0, w1, w2, w3 = _PROJ_W   # :meth:`point` at ts, its Bernstein weights computed once
        d = w0 * self.p0 + w1 * self.p1 + w2 * self.p2 + w3 * self.p3 - p
        d2 = np.einsum("ij,ij->i", d, d)
        # refine every local minimum of the sampled distance (a near-cusp passes a
        # point twice, and the sample nearest to it may lie on the wrong branch)
        pad = np.concatenate([[np.inf], d2, [np.inf]])
        mins = np.nonzero((pad[1:-1] <= pad[:-2]) & (pad[1:-1] <= pad[2:]))[0]
        c8 = self._floats
        px, py = float(p[0]), float(p[1])
        best_t, best_d = 0.0, math.inf
        for i in mins[np.argsort(d2[mins])][:4].tolist():
            lo, hi = float(ts[max(i - 1, 0)]), float(ts[min(i + 1, n - 1)])
            # from an end sample start inside the interval: the speed may vanish at the end
            start = float(ts[i]) if 0 < i < n - 1 else 0.5 * (lo + hi)
            for t in (_closest_newton(c8, px, py, start, lo, hi), float(ts[i])):
                x, y, _, _, _, _ = _eval_floats(c8, t)
                d = math.hypot(x - px, y - py)
                if d < best_d:
                    best_t, best_d = t, d
        for t in (0.0, 1.0):
            x, y, _, _, _, _ = _eval_floats(c8, t)
            d = math.hypot(x - px, y - py)
            if d < best_d:
                best_t, best_d = t, d
        lo, hi = max(0.0, best_t - 2.0 / (n - 1)), min(1.0, best_t + 2.0 / (n - 1))
        if best_d > _tolerance.TOL.zero and _folds(c8, lo, hi):
            # a near-cusp folds back within a sample step, and the closest point may sit on the fold the
            # samples passed over (5 in 100 000 points of random loops, up to 1e-4 of the curve's size): the
            # two sample steps on either side of the best parameter are sampled 16 times finer where the
            # curve turns back there; a point found there wins only by more than the zero length
            fine = np.linspace(lo, hi, 65)
            m = 1.0 - fine
            q = (np.outer(m * m * m, self.p0) + np.outer(3.0 * m * m * fine, self.p1)
                 + np.outer(3.0 * m * fine * fine, self.p2) + np.outer(fine * fine * fine, self.p3) - p)
            f2 = np.einsum("ij,ij->i", q, q)
            fpad = np.concatenate([[np.inf], f2, [np.inf]])
            for j in np.nonzero((fpad[1:-1] <= fpad[:-2]) & (fpad[1:-1] <= fpad[2:]))[0].tolist():
                a, b = float(fine[max(j - 1, 0)]), float(fine[min(j + 1, 64)])
                t = _closest_newton(c8, px, py, float(fine[j]) if 0 < j < 64 else 0.5 * (a + b), a, b)
                x, y, _, _, _, _ = _eval_floats(c8, t)
                d = math.hypot(x - px, y - py)
                if d < best_d - _tolerance.TOL.zero:
                    best_t, best_d = t, d
        return best_t

    @cached_property
    def _floats(self) -> tuple[float, ...]:
        """The control points as 8 Python floats (x0, y0, ..., x3, y3)."""
        return tuple(self.controls.ravel().tolist())

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description: kind, start, the two handles and end."""
        return {
            "kind": "bezier",
            "start": self.p0.tolist(),
            "handles": [self.p1.tolist(), self.p2.tolist()],
            "end": self.p3.tolist(),
        }


def _eval_floats(c: tuple[float, ...], t: float) -> tuple[float, float, float, float, float, float]:
    """Point, first and second derivative at ``t`` of the Bezier with controls ``c`` (8 floats)."""
    x0, y0, x1, y1, x2, y2, x3, y3 = c
    m = 1.0 - t
    b0, b1, b2, b3 = m * m * m, 3.0 * m * m * t, 3.0 * m * t * t, t * t * t
    ax, ay, bx, by, cx, cy = x1 - x0, y1 - y0, x2 - x1, y2 - y1, x3 - x2, y3 - y2
    return (
        b0 * x0 + b1 * x1 + b2 * x2 + b3 * x3,
        b0 * y0 + b1 * y1 + b2 * y2 + b3 * y3,
        3.0 * (m * m * ax + 2.0 * m * t * bx + t * t * cx),
        3.0 * (m * m * ay + 2.0 * m * t * by + t * t * cy),
        6.0 * (m * (bx - ax) + t * (cx - bx)),
        6.0 * (m * (by - ay) + t * (cy - by)),
    )


def _folds(c: tuple[float, ...], lo: float, hi: float) -> bool:
    """Whether the Bezier ``c`` (8 floats) turns back on [lo, hi].

    There its chord is below 0.9 of the length of its polygon through 5 equally spaced points.
    """
    pts = [_eval_floats(c, lo + (hi - lo) * k / 4.0)[:2] for k in range(5)]
    arc = sum(math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(pts[:-1], pts[1:], strict=True))
    return math.hypot(pts[4][0] - pts[0][0], pts[4][1] - pts[0][1]) < 0.9 * arc


def _closest_newton(c: tuple[float, ...], px: float, py: float, t: float, lo: float,
                    hi: float) -> float:
    """Newton on g(t) = (B(t) - p) . B'(t) = 0, kept in [lo, hi] (bisection fallback)."""
    for _ in range(60):
        x, y, dx, dy, ddx, ddy = _eval_floats(c, t)
        qx, qy = x - px, y - py
        g = qx * dx + qy * dy
        dg = dx * dx + dy * dy + qx * ddx + qy * ddy
        if g > 0:
            hi = min(hi, t)
        else:
            lo = max(lo, t)
        tn = t - g / dg if dg > 0 else 0.5 * (lo + hi)
        if not (lo <= tn <= hi):
            tn = 0.5 * (lo + hi)
        if abs(tn - t) <= 1e-16:
            return tn
        t = tn
    return t


def _segment_controls(c: Array, t0: float, t1: float) -> Array:
    """Control points (4, 2) of the piece of the Bezier ``c`` (4, 2) on [t0, t1].

    Uses the blossom: the controls are B(t0,t0,t0), B(t0,t0,t1), B(t0,t1,t1), B(t1,t1,t1).
    """

    def blossom(a: float, b: float, cc: float) -> Array:
        q = [c[i] + a * (c[i + 1] - c[i]) for i in range(3)]
        r = [q[i] + b * (q[i + 1] - q[i]) for i in range(2)]
        return r[0] + cc * (r[1] - r[0])

    return np.stack([blossom(t0, t0, t0), blossom(t0, t0, t1), blossom(t0, t1, t1),
                     blossom(t1, t1, t1)])


def _speed_cols(d: tuple[Array, ...], t: Array) -> Array:
    """:meth:`CubicBezier.speed` with the derivative's coefficients ``d`` (6 arrays broadcasting with t)."""
    ax, ay, bx, by, cx, cy = d
    m = 1.0 - t
    p, q, r = m * m, 2.0 * m * t, t * t
    return np.hypot(3.0 * (p * ax + q * bx + r * cx), 3.0 * (p * ay + q * by + r * cy))


#: Rows per block of :func:`_integral_rows` (its (rows, 16) temporaries then stay in the cache: 3x faster
#: than whole arrays of 3 * 10^4 rows)
_ROWS_BLOCK = 1024


def _integral_rows(D: Array, lo: Array, hi: Array) -> Array:
    """:meth:`CubicBezier._integral` of one interval per row: D (k, 6) coefficients, lo, hi (k,) -> (k,)."""
    out = np.empty(len(lo))
    for a in range(0, len(lo), _ROWS_BLOCK):
        b = a + _ROWS_BLOCK
        half = 0.5 * (hi[a:b] - lo[a:b])
        ts = (0.5 * (hi[a:b] + lo[a:b]))[:, None] + half[:, None] * _GL_X
        out[a:b] = half * (_speed_cols(tuple(D[a:b, j, None] for j in range(6)), ts) @ _GL_W)
    return out


def _tables(curves: list[CubicBezier]) -> list[tuple[Array, Array]]:
    """The arc-length tables of many curves (each :attr:`CubicBezier._table`), refined together.

    The same knots, refinement test and sums as the property, per curve; the tables computed here
    are stored as the curves' own (a cached property), those already there are used.
    """
    out: list[tuple[Array, Array] | None] = [c.__dict__.get("_table") if "_arc_source" not in c.__dict__
                                             else c._table for c in curves]
    todo = [i for i, t in enumerate(out) if t is None]
    if todo:
        D = np.array([curves[i]._dfloats for i in todo], dtype=float)
        knots = [np.unique(np.concatenate([np.linspace(0.0, 1.0, 17), e]))
                 for e in _speed_extrema_many([curves[i] for i in todo])]
        halves_of: list[Array] = [np.zeros(0)] * len(todo)
        active = list(range(len(todo)))
        for _ in range(_TABLE_MAX_LEVELS):
            if not active:
                break
            lens = np.array([len(knots[j]) - 1 for j in active])
            rows = np.repeat(np.asarray(active), lens)
            a = np.concatenate([knots[j][:-1] for j in active])
            b = np.concatenate([knots[j][1:] for j in active])
            mid = 0.5 * (a + b)
            whole = _integral_rows(D[rows], a, b)
            halves = _integral_rows(D[rows], a, mid) + _integral_rows(D[rows], mid, b)
            ends = np.cumsum(lens)
            still = []
            for j, e, ln in zip(active, ends, lens, strict=True):
                h = halves[e - ln:e]
                bad = np.abs(whole[e - ln:e] - h) > _TABLE_REL * max(float(h.sum()), 1e-300)
                halves_of[j] = h
                if bad.any():
                    knots[j] = np.sort(np.concatenate([knots[j], mid[e - ln:e][bad]]))
                    still.append(j)
            active = still
        for j, i in enumerate(todo):
            tab = (knots[j], np.concatenate([[0.0], np.cumsum(halves_of[j])]))
            curves[i].__dict__["_table"] = tab
            out[i] = tab
    return [t for t in out if t is not None]


def t_at_u_many(curves: list[CubicBezier], u: ArrayLike) -> Array:
    """:meth:`CubicBezier.t_at_u` of many curves at once.

    The arc-length tables and the safeguarded Newton iteration of the method, per curve and per
    value, run on all curves together (a network's hundreds of pieces took most of their
    resampling's time in numpy's per-call cost). The same operations in the same order per value,
    so the same results up to the order BLAS sums the 16 Gauss-Legendre terms in.

    Parameters
    ----------
    curves : list of CubicBezier, length m
    u : (n,) or (m, n) array_like
        Normalised arc lengths in [0, 1] (clipped), the same for every curve or one row per curve.

    Returns
    -------
    (m, n) ndarray
        The parameters ``t``.

    Examples
    --------
    >>> b = [CubicBezier((0, 0), (0, 1), (1, 1), (1, 0)), CubicBezier((0, 0), (1, 2), (3, 2), (4, 0))]
    >>> t = t_at_u_many(b, [0.0, 0.5, 1.0])     # the first is symmetric: t = 1/2 halves it
    >>> bool(np.abs(t[1] - b[1].t_at_u(np.array([0.0, 0.5, 1.0]))).max() < 1e-15), t[0].round(12).tolist()
    (True, [0.0, 0.5, 1.0])
    """
    m = len(curves)
    uu = np.clip(np.asarray(u, dtype=float), 0.0, 1.0)
    if uu.ndim == 1:
        uu = np.broadcast_to(uu, (m, len(uu)))
    if uu.shape[0] != m or uu.ndim != 2:
        raise GeometryError(f"u: expected shape (n,) or ({m}, n), got {np.shape(u)}")
    n = uu.shape[1]
    if m == 0 or n == 0:
        return np.zeros((m, n))
    tables = _tables(curves)
    lo_, hi_, base_, start_, target_, t_, eps_ = (np.empty((m, n)) for _ in range(7))
    for i, (knots, cum) in enumerate(tables):
        total = cum[-1]
        target = uu[i] * total
        k = np.clip(np.searchsorted(cum, target, side="right") - 1, 0, len(knots) - 2)
        lo, hi = knots[k], knots[k + 1]
        seg = cum[k + 1] - cum[k]
        with np.errstate(invalid="ignore", divide="ignore"):
            t = np.where(seg > 0, lo + (hi - lo) * (target - cum[k]) / seg, lo)
        t_[i] = np.clip(t, lo, hi)
        lo_[i], hi_[i], base_[i], start_[i], target_[i] = lo, hi, cum[k], knots[k], target
        eps_[i] = 1e-15 * total
    D = np.array([c._dfloats for c in curves], dtype=float)
    lo, hi, base, start, target, t, eps_f = (x.reshape(-1) for x in (lo_, hi_, base_, start_, target_, t_, eps_))
    Dr = D[np.repeat(np.arange(m), n)]
    act = np.arange(m * n)           # the values still iterating (a finished one keeps its t: the method's
    with np.errstate(invalid="ignore", divide="ignore"):   # later passes recompute the same f and keep it)
        for _ in range(100):
            ta, la, ha, Da = t[act], lo[act], hi[act], Dr[act]
            f = base[act] + _integral_rows(Da, start[act], ta) - target[act]
            sp = _speed_cols(tuple(Da[:, j] for j in range(6)), ta)
            tn, la, ha, done = _bracketed_newton(f, sp, ta, la, ha, eps_f[act])
            lo[act], hi[act] = la, ha
            if done.all():
                break
            t[act] = np.where(done, ta, tn)
            act = act[~done]
    t = t.reshape(m, n)
    return np.where(uu >= 1.0, 1.0, np.where(uu <= 0.0, 0.0, t))


def _in_unit(r: np.ndarray) -> Array:
    """The real roots (imaginary part within 1e-9) among ``r`` (real or complex) strictly inside (0, 1)."""
    r = r.real[np.abs(r.imag) <= 1e-9]
    return r[(r > 0.0) & (r < 1.0)]


def _speed_extrema_many(curves: list[CubicBezier]) -> list[Array]:
    """:meth:`CubicBezier._speed_extrema` of many curves.

    The cubics with a non-zero leading and constant coefficient (the usual case) have their
    roots as the eigenvalues of one stack of companion matrices, those ``np.roots`` builds (LAPACK
    runs the same routine on each); the others go through ``np.roots`` one by one.
    """
    coefs = [c._extrema_cubic() for c in curves]
    out: list[Array] = [np.zeros(0)] * len(curves)
    full = [i for i, c in enumerate(coefs) if len(c) == 4 and c[0] != 0.0 and c[3] != 0.0]
    if full:
        p = np.array([coefs[i] for i in full])
        A = np.zeros((len(full), 3, 3))
        A[:, 1, 0] = A[:, 2, 1] = 1.0
        A[:, 0, :] = -p[:, 1:] / p[:, :1]
        roots = np.linalg.eigvals(A)
        for i, r in zip(full, roots, strict=True):
            out[i] = _in_unit(r)
    for i, c in enumerate(coefs):
        if len(c) >= 2 and not (len(c) == 4 and c[0] != 0.0 and c[3] != 0.0):
            out[i] = _in_unit(np.roots(c))
    return out
