"""The depth family a lift leaves free, and a prior that picks its member (beyond the paper).

Seen orthographically, a 3D network and its image under a *linear depth map*
``z' = alpha x + beta y + gamma z`` (x, y kept) have the same drawing. Such a
map keeps every affine relation: the accuracy and minimal-variation terms
(Eq. 1-5, affine combinations with 2D weights), straight segments, G1
joints, planarity and (exact) parallelism. It does not keep angles, so the
hard orthogonality of the smooth crossings decides which maps are left (the
applied corners are held again by the solve that follows the map): ``(M a) . (M b) = 0`` for every such pair of tangents
``a, b``, with ``M = [[1, 0, 0], [0, 1, 0], [alpha, beta, gamma]]``, one
quadratic equation in ``(alpha, beta, gamma)`` per pair, met by the identity.
Generic networks leave only the identity and its mirror; an extrusion (its
rulings parallel, its sections' tangents spanning the planes normal to them)
leaves a one-parameter family, every member as good for the fidelity and the
cues, of which the foreshortening term (Eq. 6) picks the flattest
(docs/lifting.md, "Structural diagnosis" 4).

:func:`depth_family` finds that family's direction at the identity (the
near-null space of the pairs' Jacobian), :func:`family_member` follows it,
and :func:`extent_member` picks the member whose two largest extents (along
the principal axes of its curve points) are equal: a prior of isotropy of the
3D extent, in the spirit of the line-drawing literature's preference for
compact, isotropic interpretations (Brady and Yuille 1984, "An extremum
principle for shape from contour"; Li, Pizlo and Steinman 2009, maximal 3D
compactness), reduced to the one dimension the family leaves free: an
extruded object is taken to be as deep as it is wide. It fails, by design,
on objects much longer than wide (a long arcade). On by default since
lift-wrinkle (``LiftParams.family_prior``; the search and the solve after it
in :func:`auszug.lifting.reconstruct.lift_graph`; measured in docs/lifting.md,
"Depth family prior").
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from auszug.lifting.sketch import SketchGraph

__all__ = ["depth_family", "family_member", "extruded", "sample_points", "extent_spread", "extent_member"]

Array = NDArray[np.float64]

IDENTITY = np.array([0.0, 0.0, 1.0])


def _cosines(X: Array, p: NDArray[np.intp], h1: NDArray[np.intp], h2: NDArray[np.intp],
             m: Array) -> tuple[Array, Array]:
    """Cosines of the pairs' tangents under the depth map ``m`` = (alpha, beta, gamma), and their Jacobian (k, 3)."""
    a, b = X[h1] - X[p], X[h2] - X[p]
    az, bz = a @ m, b @ m
    na = np.sqrt(a[:, 0] ** 2 + a[:, 1] ** 2 + az**2)
    nb = np.sqrt(b[:, 0] ** 2 + b[:, 1] ** 2 + bz**2)
    dot = a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1] + az * bz
    c = dot / (na * nb)
    # d(dot)/dm = bz a + az b; d(na)/dm = az a / na
    J = ((bz[:, None] * a + az[:, None] * b) / (na * nb)[:, None]
         - c[:, None] * (az[:, None] * a / na[:, None] ** 2 + bz[:, None] * b / nb[:, None] ** 2))
    return c, J


def depth_family(X: Array, p: NDArray[np.intp], h1: NDArray[np.intp], h2: NDArray[np.intp],
                 tol: float) -> Array:
    """The directions (3, k) of ``(alpha, beta, gamma)`` along which the orthogonal pairs stay orthogonal.

    Parameters
    ----------
    X : (n, 3) ndarray
        Control points (any units).
    p, h1, h2 : (m,) int ndarray
        The pairs: ``X[h1] - X[p]`` orthogonal to ``X[h2] - X[p]``.
    tol : float
        A singular value of the pairs' cosine Jacobian at the identity below ``tol`` times the
        largest (times 1 when the largest is below 1) counts as null.

    Returns
    -------
    (3, k) ndarray
        Orthonormal directions of the first-order family at the identity map; k = 0 for a
        network whose depth the pairs fix (up to offset and mirror). The direction of pure
        depth scaling (the identity itself) is never among them unless every pair is
        degenerate.
    """
    if not len(p):
        return np.eye(3)
    _, J = _cosines(X, p, h1, h2, IDENTITY)
    _, s, Vt = np.linalg.svd(J, full_matrices=len(J) < 3)        # Vt (3, 3) either way
    s = np.concatenate([s, np.zeros(3 - len(s))])
    null = s <= tol * max(float(s[0]), 1.0)
    return np.ascontiguousarray(Vt[null].T)


def family_member(X: Array, p: NDArray[np.intp], h1: NDArray[np.intp], h2: NDArray[np.intp],
                  start: Array, along: Array, iterations: int = 20) -> tuple[Array, float]:
    """The depth map that keeps the pairs orthogonal, found from ``start`` (3,) normal to ``along`` (3, k).

    Gauss-Newton on the pairs' cosines, its steps restricted to the complement of the family's
    directions ``along`` (so the member's coordinate along the family stays the start's).
    Returns the map ``(alpha, beta, gamma)`` and the largest remaining ``|cos|`` of the pairs.
    """
    Q = np.linalg.svd(along, full_matrices=True)[0][:, along.shape[1]:]   # (3, 3 - k): the complement
    m = np.array(start, float)
    for _ in range(iterations):
        c, J = _cosines(X, p, h1, h2, m)
        if not (np.all(np.isfinite(J)) and np.all(np.isfinite(c))) or np.abs(m).max() > 1e6:
            return m, np.inf                      # diverged: no member there
        if np.abs(c).max() < 1e-14:
            break
        m = m - Q @ np.linalg.lstsq(J @ Q, c, rcond=None)[0]
    c = _cosines(X, p, h1, h2, m)[0]
    worst = float(np.abs(c).max())
    return m, worst if np.isfinite(worst) else np.inf


#: Bernstein basis of a cubic at the sample parameters of :func:`sample_points` (17 per segment).
_T = np.linspace(0.0, 1.0, 17)
_BERN = np.stack([(1 - _T) ** 3, 3 * (1 - _T) ** 2 * _T, 3 * (1 - _T) * _T**2, _T**3], axis=1)


def sample_points(X: Array, g: SketchGraph) -> Array:
    """Every segment of the network sampled at 17 parameters, (17 segments, 3)."""
    return np.einsum("tk,skd->std", _BERN, X[g.segments]).reshape(-1, 3)


def extent_spread(X: Array, g: SketchGraph) -> float:
    """The prior's score, lower is better: ``log(e1 / e2)^2`` (0: equal).

    ``e1, e2`` are the network's extents (max - min of the sampled curve points, :func:`sample_points`)
    along its first two principal axes (those of the points' covariance): the object as deep as it
    is wide, in its two largest dimensions.
    """
    pts = sample_points(X, g)
    pts = pts - pts.mean(axis=0)
    _, _, Vt = np.linalg.svd(pts, full_matrices=False)
    e = np.ptp(pts @ Vt[:2].T, axis=0)
    return float(np.log(e[0] / e[1]) ** 2) if e[1] > 0 else np.inf


def extruded(X: Array, p: NDArray[np.intp], h1: NDArray[np.intp], h2: NDArray[np.intp], tol_deg: float) -> bool:
    """Whether one 3D direction runs through every pair: one of its two tangents within ``tol_deg`` of it.

    The structure of an extrusion (every crossing on a ruling, the rulings parallel), whose depth family is
    exact; the near-families of other networks (a vase seen from the front) do not have it. The
    candidates for the direction are the pairs' own tangents (as lines, either sign).
    """
    if not len(p):
        return False
    t = np.concatenate([X[h1] - X[p], X[h2] - X[p]])
    t /= np.linalg.norm(t, axis=1)[:, None]
    c = np.abs(t @ t.T) >= np.cos(np.radians(tol_deg))          # (2m, 2m): candidate k covers tangent j
    m = len(p)
    covered = c[:, :m] | c[:, m:]                                   # candidate k covers pair i
    return bool(covered.all(axis=1).any())


def _mapped(X: Array, m: Array) -> Array:
    Y = X.copy()
    Y[:, 2] = X @ m
    return Y


def extent_member(X: Array, g: SketchGraph, p: NDArray[np.intp], h1: NDArray[np.intp],
                  h2: NDArray[np.intp], tol: float, span: float, max_cos: float, parallel_deg: float = 1.0,
                  steps: int = 40) -> tuple[Array, float, float] | None:
    """The member of a one-parameter depth family of least :func:`extent_spread` (the most isotropic extent).

    Parameters
    ----------
    X : (n, 3) ndarray
        The lift's control points.
    g : SketchGraph
    p, h1, h2 : (m,) int ndarray
        The orthogonal pairs the family keeps (smooth crossings, applied corners).
    tol : float
        Null-space threshold of :func:`depth_family`.
    span : float
        The family is searched over maps ``(alpha, beta, gamma)`` within this distance of the
        identity (before projection onto the family), with ``gamma > 0`` (no mirror).
    max_cos : float
        A member is admissible when every pair's ``|cos|`` is at most this.
    parallel_deg : float
        The family is searched only on an extrusion (:func:`extruded` within this angle).
    steps : int
        Grid points on each side of the identity; the best is refined by golden-section search.

    Returns
    -------
    (alpha, beta, gamma), score of the lift, score of the member; or None
        None when the pairs leave no one-parameter family (k != 1), the network is not an extrusion,
        or no member scores lower.
    """
    N = depth_family(X, p, h1, h2, tol)
    if N.shape[1] != 1 or not extruded(X, p, h1, h2, parallel_deg):
        return None
    n = N[:, 0]
    base = extent_spread(X, g)

    def at(t: float) -> tuple[float, Array]:
        m, worst = family_member(X, p, h1, h2, IDENTITY + t * n, N)
        if worst > max_cos or m[2] <= 0:
            return np.inf, m
        return extent_spread(_mapped(X, m), g), m

    ts = np.linspace(-span, span, 2 * steps + 1)
    vals = [at(float(t))[0] for t in ts]
    k = int(np.argmin(vals))
    if not np.isfinite(vals[k]):
        return None
    lo, hi = float(ts[max(k - 1, 0)]), float(ts[min(k + 1, len(ts) - 1)])
    r = (np.sqrt(5.0) - 1) / 2
    a, b = hi - r * (hi - lo), lo + r * (hi - lo)
    fa, fb = at(a)[0], at(b)[0]
    for _ in range(40):
        if fa <= fb:
            hi, b, fb = b, a, fa
            a = hi - r * (hi - lo)
            fa = at(a)[0]
        else:
            lo, a, fa = a, b, fb
            b = lo + r * (hi - lo)
            fb = at(b)[0]
    cands = [(vals[k], float(ts[k])), (fa, a), (fb, b)]
    best, t = min(cands)
    if not best < base:
        return None
    return at(t)[1], base, best
