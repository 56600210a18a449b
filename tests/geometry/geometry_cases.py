"""Shared hypothesis strategies, brute-force references and cases for the geometry tests."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import assume
from hypothesis import strategies as st

from auszug.geometry import Arc, CubicBezier, Curve, Line, cross2

TAU = 2.0 * math.pi

coord = st.floats(-1.0, 1.0, allow_nan=False, allow_infinity=False)
points = st.tuples(coord, coord).map(np.array)
angles = st.floats(-math.pi, math.pi, allow_nan=False)
unit_vectors = angles.map(lambda a: np.array([math.cos(a), math.sin(a)]))


@st.composite
def lines(draw: st.DrawFn, min_length: float = 0.05) -> Line:
    p0 = draw(points)
    p1 = draw(points.filter(lambda q: float(np.hypot(*(q - p0))) >= min_length))
    return Line(p0, p1)


@st.composite
def arcs(draw: st.DrawFn) -> Arc:
    c = draw(points)
    r = draw(st.floats(0.1, 1.5))
    th0 = draw(angles)
    sweep = draw(st.floats(0.05, TAU)) * draw(st.sampled_from([1.0, -1.0]))
    return Arc(c, r, th0, sweep)


@st.composite
def beziers(draw: st.DrawFn, min_size: float = 0.05) -> CubicBezier:
    """Beziers with control points in [-1, 1]^2 (loops, cusps and inflections included)."""
    c = [draw(points) for _ in range(4)]
    spread = max(float(np.hypot(*(q - c[0]))) for q in c[1:])
    assume(spread >= min_size)
    return CubicBezier(*c)


def curves(bezier: bool = False) -> st.SearchStrategy[Curve]:
    return st.one_of(lines(), arcs(), beziers()) if bezier else st.one_of(lines(), arcs())


@st.composite
def rigid_motions(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray]:
    """(matrix (2, 2) orthogonal, offset (2,)), reflections included."""
    a = draw(angles)
    m = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    if draw(st.booleans()):
        m = m @ np.diag([1.0, -1.0])
    off = np.array([draw(st.floats(-10, 10)), draw(st.floats(-10, 10))])
    return m, off


# -- brute force ------------------------------------------------------------------------


def dist_to_curve(c: Curve, p: np.ndarray) -> float:
    """Distance from ``p`` to the curve via its ``project``."""
    return float(np.hypot(*(c.point(c.project(p)) - p)))


def polyline_crossings(c1: Curve, c2: Curve, n: int = 600) -> np.ndarray:
    """Crossing points, shape (k, 3): (x, y, sin of crossing angle), of dense polylines."""
    p = c1.point(np.linspace(0.0, 1.0, n))
    q = c2.point(np.linspace(0.0, 1.0, n))
    a0, a1 = p[:-1, None, :], p[1:, None, :]
    b0, b1 = q[None, :-1, :], q[None, 1:, :]
    d, e = a1 - a0, b1 - b0
    w = b0 - a0
    den = d[..., 0] * e[..., 1] - d[..., 1] * e[..., 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (w[..., 0] * e[..., 1] - w[..., 1] * e[..., 0]) / den
        u = (w[..., 0] * d[..., 1] - w[..., 1] * d[..., 0]) / den
    ok = (den != 0) & (s >= 0) & (s <= 1) & (u >= 0) & (u <= 1)
    i, j = np.nonzero(ok)
    pts = a0[i, 0] + s[i, j, None] * d[i, 0]
    sin = np.abs(den[i, j]) / (np.hypot(*d[i, 0].T) * np.hypot(*e[0, j].T))
    return np.column_stack([pts, sin]) if len(i) else np.zeros((0, 3))


def min_distance(c1: Curve, c2: Curve, n: int = 2000) -> float:
    """Approximate distance between two curves (dense samples against exact projection)."""
    p = c1.point(np.linspace(0.0, 1.0, n))
    return min(dist_to_curve(c2, x) for x in p)


def near_degenerate(c1: Curve, c2: Curve, eps: float = 1e-4) -> bool:
    """True when the pair is within ``eps`` of a tangency, overlap or end-point touch.

    The brute-force comparisons exclude these (they are ill-conditioned by nature)
    and the degenerate cases get their own exact tests.
    """
    for a, b in ((c1, c2), (c2, c1)):
        for e in (a.start, a.end):
            if dist_to_curve(b, e) < eps:
                return True
    kinds = {c1.kind, c2.kind}
    if "bezier" in kinds:
        return near_tangent_samples(c1, c2, eps)
    if kinds == {"line"}:
        return abs(float(cross2(c1.direction, c2.direction))) < eps
    if kinds == {"line", "arc"}:
        ln, ar = (c1, c2) if c1.kind == "line" else (c2, c1)
        h = abs(float(cross2(ln.direction, ar.center - ln.p0)))
        return abs(h - ar.radius) < eps
    if kinds == {"arc"}:
        d = float(np.hypot(*(c1.center - c2.center)))
        return (
            d < eps
            or abs(d - c1.radius - c2.radius) < eps
            or abs(d - abs(c1.radius - c2.radius)) < eps
        )
    return False


def near_tangent_samples(c1: Curve, c2: Curve, eps: float, n: int = 500) -> bool:
    """Sampled test: somewhere the curves come within 50 eps of each other while
    running nearly parallel (|sin| < 0.05), or within 50 eps at a cusp of either."""
    t = np.linspace(0.0, 1.0, n)
    p, q = c1.point(t), c2.point(t)
    d = np.hypot(p[:, None, 0] - q[None, :, 0], p[:, None, 1] - q[None, :, 1])
    i, j = np.nonzero(d < 50 * eps)
    if len(i) == 0:
        return False
    s1 = c1.speed(t[i]) if hasattr(c1, "speed") else np.ones(len(i))
    s2 = c2.speed(t[j]) if hasattr(c2, "speed") else np.ones(len(j))
    if np.any(s1 < 1e-2) or np.any(s2 < 1e-2):
        return True
    sin = np.abs(cross2(c1.tangent(t[i]), c2.tangent(t[j])))
    return bool(np.any(sin < 0.05))
