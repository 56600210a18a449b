"""Least-squares fit of sampled curves (polylines) by G1 cubic Bezier chains.

A curve drawn or traced as many short straight segments (a tablet's or a tracing tool's polyline)
is refitted as a clamped cubic B-spline (C2 inside, so G1 at every knot) through its end points,
fitted by least squares to its vertices at their chord-length parameters with equal spans, the
spans doubled until every vertex lies within the tolerance; the spline is returned as the Bezier
chain of its spans. scipy builds the B-spline basis (``BSpline.design_matrix``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["fit_polyline"]

Array = NDArray[np.float64]


def fit_polyline(points: ArrayLike, tol: float, max_spans: int | None = None) -> Array | None:
    """A G1 cubic Bezier chain through a polyline's end points within ``tol`` of its vertices.

    Parameters
    ----------
    points : (n, d) array_like
        The polyline's vertices, n >= 2, consecutive vertices distinct (any units).
    tol : float
        The largest distance allowed between a vertex and the chain's point at the vertex's
        chord-length parameter (an upper bound of its distance to the chain), same units.
    max_spans : int, optional
        The most cubics to use; default ``max(1, (n - 1) // 2)`` (a fit, not an interpolation).

    Returns
    -------
    (m, 4, d) ndarray or None
        Bezier control points of the m spans, 1 <= m <= max_spans, a power of two or
        ``max_spans``: the chain starts at ``points[0]``, ends at ``points[-1]`` (exactly) and
        is G1 (C1 in its parameter) at every inner knot. None when ``max_spans`` spans do not
        bring every vertex within ``tol``.

    Examples
    --------
    >>> t = np.linspace(0.0, np.pi / 2, 41)
    >>> c = fit_polyline(np.c_[np.cos(t), np.sin(t)], 1e-4)
    >>> c.shape, c[0, 0].tolist(), np.allclose(c[-1, 3], [0.0, 1.0])
    ((4, 4, 2), [1.0, 0.0], True)
    """
    from scipy.interpolate import BSpline

    P = np.asarray(points, dtype=float)
    if P.ndim != 2 or len(P) < 2:
        raise ValueError(f"a polyline of at least 2 points (n, d), not shape {P.shape}")
    step = np.linalg.norm(np.diff(P, axis=0), axis=1)
    if not np.all(step > 0):
        raise ValueError("consecutive polyline points coincide")
    u = np.r_[0.0, np.cumsum(step)]
    u /= u[-1]
    top = max(1, (len(P) - 1) // 2) if max_spans is None else int(max_spans)
    spans = 1
    while True:
        spans = min(spans, top)
        knots = np.r_[[0.0] * 4, np.linspace(0.0, 1.0, spans + 1)[1:-1], [1.0] * 4]
        A = BSpline.design_matrix(u, knots, 3).toarray()            # (n, spans + 3)
        coef = np.empty((spans + 3, P.shape[1]))
        coef[0], coef[-1] = P[0], P[-1]                               # clamped: the ends interpolated
        rhs = P - np.outer(A[:, 0], P[0]) - np.outer(A[:, -1], P[-1])
        coef[1:-1] = np.linalg.lstsq(A[:, 1:-1], rhs, rcond=None)[0]
        err = float(np.linalg.norm(A @ coef - P, axis=1).max())
        if err <= tol:
            break
        if spans >= top:
            return None
        spans *= 2
    s = BSpline(knots, coef, 3)
    b = np.linspace(0.0, 1.0, spans + 1)
    p, dp = s(b), s.derivative()(b)
    p[0], p[-1] = P[0], P[-1]
    h = 1.0 / spans
    return np.stack([p[:-1], p[:-1] + dp[:-1] * h / 3, p[1:] - dp[1:] * h / 3, p[1:]], axis=1)
