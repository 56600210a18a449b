"""Ground truth in code: 3D curve networks with known depths, projected orthographically into sketches.

Each network is a set of 3D cubic Bezier chains with knots at the 3D
intersections (Hermite segments with the exact tangents), so the truth is
exactly representable and its crossings are exactly what the method assumes.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from auszug.lifting import Marker, Sketch, Stroke


@dataclass(frozen=True)
class Truth:
    sketch: Sketch
    chains3d: tuple[np.ndarray, ...]   # per stroke (m, 4, 3), in view coordinates (z toward the viewer)

    def diagonal(self) -> float:
        return self.sketch.diagonal()


def rotation(tilt_deg: float, turn_deg: float) -> np.ndarray:
    """View rotation: turn about the vertical (y), then tilt about x (a view from above for tilt > 0)."""
    a, b = np.radians(turn_deg), np.radians(tilt_deg)
    ry = np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])
    rx = np.array([[1, 0, 0], [0, np.cos(b), -np.sin(b)], [0, np.sin(b), np.cos(b)]])
    return rx @ ry


def hermite_chain(p: np.ndarray, dp: np.ndarray, dt: float | np.ndarray) -> np.ndarray:
    """Bezier chain (k-1, 4, 3) through knots p (k, 3) with derivatives dp (k, 3) per unit parameter step dt
    (one step, or each segment's: (k-1, 1))."""
    c0, c3 = p[:-1], p[1:]
    c1 = c0 + dp[:-1] * dt / 3
    c2 = c3 - dp[1:] * dt / 3
    return np.stack([c0, c1, c2, c3], axis=1)


def revolve(n_mer: int = 6, n_par: int = 4, tilt: float = 25.0, turn: float = 15.0, noise: float = 0.0,
            seed: int = 0) -> Truth:
    """Meridians and parallels of a vase (surface of revolution about y), front part, seen from above.

    Every curve overshoots its first and last crossing by half a step, so every
    crossing is a smooth crossing. ``noise``: 2D noise on the sketch's control
    points, relative to its diagonal.
    """
    def radius(h):
        return 1.0 + 0.35 * np.sin(1.3 * h + 0.4)

    def dradius(h):
        return 0.35 * 1.3 * np.cos(1.3 * h + 0.4)

    phis = np.radians(np.linspace(-50, 50, n_mer))
    hs = np.linspace(-1.0, 1.0, n_par)
    dphi, dh = phis[1] - phis[0], hs[1] - hs[0]
    R = rotation(tilt, turn)

    def surf(phi, h):
        r = radius(h)
        return np.stack([r * np.sin(phi), h * np.ones_like(phi), r * np.cos(phi)], axis=-1)

    chains = []
    for phi in phis:   # meridians: parameter h
        h = np.concatenate([[hs[0] - dh / 2], hs, [hs[-1] + dh / 2]])
        p = surf(np.full_like(h, phi), h)
        dp = np.stack([dradius(h) * np.sin(phi), np.ones_like(h), dradius(h) * np.cos(phi)], axis=-1)
        chains.append(hermite_chain(p, dp, dh))
    for h0 in hs:      # parallels: parameter phi
        ph = np.concatenate([[phis[0] - dphi / 2], phis, [phis[-1] + dphi / 2]])
        p = surf(ph, np.full_like(ph, h0))
        r = radius(h0)
        dp = np.stack([r * np.cos(ph), np.zeros_like(ph), -r * np.sin(ph)], axis=-1)
        chains.append(hermite_chain(p, dp, dphi))
    return _project(chains, R, noise, seed)


def _line(a: np.ndarray, b: np.ndarray, over: float = 0.0) -> np.ndarray:
    """A straight chain (1, 4, 3) from a to b, extended by ``over`` of its length at both ends."""
    d = b - a
    a, b = a - over * d, b + over * d
    return np.array([[a, a + (b - a) / 3, a + 2 * (b - a) / 3, b]])


def box(size: tuple[float, float, float] = (2.0, 1.4, 1.0), tilt: float = 25.0, turn: float = 30.0,
        noise: float = 0.0, seed: int = 0, meet: bool = False) -> Truth:
    """A box of straight strokes: its 9 visible edges and two cross-sections through every visible face.

    Edges end at the corners (non-smooth intersections: orthogonal corners, three at the front
    corner); each section crosses the face's two opposite edges (overshooting them by 8 %) and the
    face's other section: every crossing is a smooth crossing, orthogonal in 3D. With ``meet``, the
    sections of two faces cross the three edges from the front corner at one point (three strokes
    there, pairwise orthogonal in 3D).
    """
    hx, hy, hz = (0.5 * np.asarray(size, float)).tolist()
    R = rotation(tilt, turn)
    view = np.array([0.0, 0.0, 1.0]) @ R          # the viewer's direction in object coordinates
    sx, sy, sz = np.sign(view)                      # the visible faces: x = sx hx, y = sy hy, z = sz hz
    corner = np.array([sx * hx, sy * hy, sz * hz])
    chains = []
    ext = np.array([hx, hy, hz])
    for a in range(3):                              # the three edges from the front corner
        b = corner.copy()
        b[a] = -b[a]
        chains.append(_line(corner, b))
    for a in range(3):                              # the silhouette: edges of visible faces not at the corner
        for c in range(3):
            if c == a:
                continue
            p = corner.copy()
            p[c] = -p[c]
            q = p.copy()
            q[a] = -q[a]
            chains.append(_line(p, q))
    # section positions (share of the half extent) on the face normal to f, per other axis; two faces
    # sharing an edge cut it at different places, so no three strokes cross at one point
    pos = {0: {1: 0.2, 2: -0.3}, 1: {0: 0.35, 2: 0.15}, 2: {0: -0.2, 1: -0.1}}
    if meet:
        pos = {0: {1: 0.2, 2: -0.3}, 1: {0: 0.35, 2: -0.3}, 2: {0: 0.35, 1: 0.2}}
    for f in range(3):                              # sections of the face normal to axis f
        u, w = [a for a in range(3) if a != f]
        for along, across in ((u, w), (w, u)):
            p = np.zeros(3)
            p[f] = corner[f]
            p[across] = pos[f][across] * ext[across]
            q = p.copy()
            p[along] = -ext[along]
            q[along] = ext[along]
            chains.append(_line(p, q, 0.08))
    return _project(chains, R, noise, seed)


def shifted(truth: Truth, strokes: range, shift: float, seed: int) -> Truth:
    """The truth with each of ``strokes`` drawn ``shift`` (share of the diagonal) off, in a random direction.

    A hand's slip: strokes meant to pass through one point then cross in a small triangle. The 3D truth
    is kept (the depth at a drawn point is the truth's at its nearest 2D point, :func:`depth_rmse`).
    """
    rng = np.random.default_rng(seed)
    d = truth.diagonal()
    out = []
    for i, s in enumerate(truth.sketch.strokes):
        if i in strokes:
            a = rng.uniform(0.0, 2.0 * np.pi)
            s = Stroke(s.controls + shift * d * np.array([np.cos(a), np.sin(a)]), s.id)
        out.append(s)
    return Truth(Sketch(tuple(out), truth.sketch.markers), truth.chains3d)


def occlusions(view, tol: float, strokes2d=None) -> list[np.ndarray]:
    """2D crossings of two chains (view coordinates) whose depths there differ by more than ``tol``.

    The crossings are those of ``strokes2d`` (the drawn, possibly jittered strokes) when given,
    else of the view's own x, y; the depths are always the view's."""
    return [p for p, dz in crossings2d(view, strokes2d) if dz > tol]


def crossings2d(view, strokes2d=None) -> list[tuple[np.ndarray, float]]:
    """Every 2D crossing of two different chains, with the depth difference of the truth there.

    The crossings are those of ``strokes2d`` when given, else of the view's own x, y; the depths are
    the view's chains' at the crossing's parameters."""
    from auszug.geometry import CubicBezier, intersect_many

    curves, owner = [], []
    for i, c in enumerate(view if strokes2d is None else strokes2d):
        for k, seg in enumerate(c):
            curves.append(CubicBezier.from_array(seg[:, :2]))
            owner.append((i, k))
    out = []
    for (a, b), hits in intersect_many(curves).items():
        (ia, ka), (ib, kb) = owner[a], owner[b]
        if ia == ib:
            continue
        for h in hits:
            za = CubicBezier.from_array(view[ia][ka][:, [0, 2]]).point(h.t1)[1]
            zb = CubicBezier.from_array(view[ib][kb][:, [0, 2]]).point(h.t2)[1]
            out.append((np.asarray(h.point, float), float(abs(za - zb))))
    return out


def wave_field(rng: np.random.Generator, diagonal: float, sd: float):
    """A wobbly hand: a smooth random 2D displacement field over a sketch of this diagonal.

    The sum of 8 plane waves of wavelengths diagonal/4 .. diagonal/2, each coordinate's standard deviation
    ``sd * diagonal``; returns the field as a function of points (..., 2) -> displacements (..., 2).
    """
    k = 8
    ang = rng.uniform(0, 2 * np.pi, k)
    freq = 2 * np.pi / (diagonal * rng.uniform(0.25, 0.5, k))
    wave = np.stack([np.cos(ang), np.sin(ang)], 1) * freq[:, None]      # (k, 2)
    phase = rng.uniform(0, 2 * np.pi, (k, 2))
    amp = rng.normal(0, 1, (k, 2)) * sd * diagonal * np.sqrt(2.0 / k)   # E[sin^2] = 1/2

    def field(xy: np.ndarray) -> np.ndarray:
        return np.einsum("...kc,kc->...c", np.sin((xy @ wave.T)[..., None] + phase), amp)

    return field


def _project(chains, R, noise: float, seed: int) -> Truth:
    view = tuple(c @ R.T for c in chains)
    strokes0 = tuple(Stroke(c[:, :, :2].copy(), f"c{i}") for i, c in enumerate(view))
    d0 = Sketch(strokes0).diagonal()
    marks = tuple(Marker("occlusion", p, f"occlusion-{i + 1}") for i, p in enumerate(occlusions(view, 1e-6 * d0)))
    sk = Sketch(strokes0, marks)
    if noise:
        d = sk.diagonal()
        # applied to every control point, so shared points stay shared and tangents stay continuous
        field = wave_field(np.random.default_rng(seed), d, noise)
        strokes = [Stroke(s.controls + field(s.controls), s.id) for s in sk.strokes]
        # the markers of the drawn (noisy) strokes: a near-tangent 2D crossing of the clean projection
        # can vanish under the noise (its marker would have no crossing) or one appear. Each noisy
        # crossing is what the clean crossing nearest its position (moved by the field, within 1 % of
        # the diagonal) was, an occlusion or not; one without a clean counterpart is an occlusion when
        # the truth's depths at its parameters differ by more than 1 % of the diagonal.
        clean = crossings2d(view)
        moved = np.array([p + field(p) for p, _ in clean]).reshape(-1, 2)
        occluded = np.array([dz > 1e-6 * d0 for _, dz in clean], bool)
        kept = []
        for p, dz in crossings2d(view, [s.controls for s in strokes]):
            dist = np.linalg.norm(moved - p, axis=1) if len(moved) else np.zeros(0)
            if len(dist) and dist.min() <= 0.01 * d:
                if occluded[dist.argmin()]:
                    kept.append(p)
            elif dz > 0.01 * d:
                kept.append(p)
        sk = Sketch(tuple(strokes), tuple(Marker("occlusion", p, f"occlusion-{i + 1}") for i, p in enumerate(kept)))
    return Truth(sk, view)


def depth_rmse(truth: Truth, result) -> tuple[float, int]:
    """RMSE of the lifted depth against the truth at the lifted curves' sample points, relative to the
    sketch's diagonal, after the best depth offset and sign; and that sign (+1: the lift's own)."""
    from auszug.geometry import CubicBezier

    net = result.network
    errs = {}
    for sign in (1, -1):
        zl, zt = [], []
        for piece in net.pieces:
            ts = np.linspace(0, 1, 9)
            xyz = piece.point_t(ts)
            chain = truth.chains3d[piece.basic]
            # the truth depth at the same sketch point: the nearest point of the truth chain in 2D
            best = None
            for seg in chain:
                b = CubicBezier.from_array(seg[:, :2])
                for q in xyz:
                    t = b.project(q[:2])
                    d = np.linalg.norm(b.point(t) - q[:2])
                    m = 1 - t
                    z = m**3 * seg[0, 2] + 3 * m * m * t * seg[1, 2] + 3 * m * t * t * seg[2, 2] + t**3 * seg[3, 2]
                    best = best or {}
                    key = tuple(q[:2])
                    if key not in best or d < best[key][0]:
                        best[key] = (d, z)
            for q in xyz:
                zl.append(sign * q[2])
                zt.append(best[tuple(q[:2])][1])
        zl, zt = np.array(zl), np.array(zt)
        off = np.mean(zt - zl)
        errs[sign] = float(np.sqrt(np.mean((zl + off - zt) ** 2)))
    s = min(errs, key=errs.get)
    return errs[s] / truth.diagonal(), s


def truth_points(truth: Truth, graph) -> np.ndarray:
    """The true 3D position (graph units: diagonal-normalised, as the solver's) of every graph control point.

    Only for truths whose strokes are split exactly at their chains' knots (every crossing at a knot,
    as in :func:`revolve`): each graph point is then one of the truth's control points. Raises when
    a graph point has no truth control point within 1e-9 of the diagonal.
    """
    allc = np.concatenate([c.reshape(-1, 3) for c in truth.chains3d])
    xy = graph.points * graph.scale + graph.offset
    d = np.linalg.norm(xy[:, None, :] - allc[None, :, :2], axis=2)
    if d.min(1).max() > 1e-9 * truth.diagonal():
        raise ValueError("graph points off the truth's control points: the truth is not split at its knots")
    X = np.zeros((len(xy), 3))
    X[:, :2] = graph.points
    X[:, 2] = allc[d.argmin(1), 2] / graph.scale
    return X


def barrel_half(n_mer: int = 5, n_par: int = 3, tilt: float = 25.0, turn: float = 35.0, noise: float = 0.0,
                seed: int = 0, symmetry_drawn: bool = False) -> tuple[Truth, tuple[np.ndarray, ...]]:
    """Half a barrel drawn up to its symmetry plane, for global symmetry (paper sec. 4, Fig. 7).

    The barrel is the surface of revolution r(x) = 1 - 0.3 x^2 about the object's x axis; its
    symmetry plane is x = 0. Drawn: the parallel x = 0 (the symmetry curve, a circle arc), ``n_par
    - 1`` more parallels at x > 0, and ``n_mer`` meridians that start on the symmetry curve and run
    half a step beyond the last parallel. Parallels overshoot the outer meridians by half a step, so
    every crossing off the symmetry curve is a smooth crossing; the meridians meet the symmetry
    curve at their ends (corners, orthogonal in 3D).

    Returns the truth (the symmetry curve in ``sketch.symmetry``, and among the strokes as well if
    ``symmetry_drawn``; ``chains3d`` in the order of the lifted network's curves: the drawn strokes,
    then the symmetry curve when it is not drawn, then the mirrored strokes) and the mirrored chains
    alone (view coordinates).
    """
    R = rotation(tilt, turn)
    drawn, axis = barrel_chains(n_mer, n_par)
    flip = np.diag([-1.0, 1.0, 1.0])
    mirrored = tuple((c @ flip) @ R.T for c in drawn)
    t = _project([*drawn, axis], R, noise, seed)
    strokes = t.sketch.strokes
    sym = Stroke(strokes[-1].controls, "symmetry")
    sk = Sketch(strokes if symmetry_drawn else strokes[:-1], t.sketch.markers, sym)
    return Truth(sk, (*t.chains3d, *mirrored)), mirrored


def barrel_chains(n_mer: int = 5, n_par: int = 3) -> tuple[list[np.ndarray], np.ndarray]:
    """The half barrel of :func:`barrel_half` in object coordinates: the drawn chains (meridians, then
    the parallels at x > 0) and the symmetry curve (the parallel x = 0)."""
    phis = np.radians(np.linspace(-45, 45, n_mer))
    xs = np.linspace(0.0, 1.0, n_par)
    dphi, dx = phis[1] - phis[0], xs[1] - xs[0]

    def surf(x, phi):
        r = 1.0 - 0.3 * x**2
        return np.stack([x * np.ones_like(phi), r * np.sin(phi), r * np.cos(phi)], axis=-1)

    mer, par = [], []
    for phi in phis:
        x = np.concatenate([xs, [xs[-1] + dx / 2]])
        p = surf(x, np.full_like(x, phi))
        dp = np.stack([np.ones_like(x), -0.6 * x * np.sin(phi), -0.6 * x * np.cos(phi)], axis=-1)
        mer.append(hermite_chain(p, dp, dx))
    for x0 in xs:
        ph = np.concatenate([[phis[0] - dphi / 2], phis, [phis[-1] + dphi / 2]])
        p = surf(np.full_like(ph, x0), ph)
        r = 1.0 - 0.3 * x0**2
        dp = np.stack([np.zeros_like(ph), r * np.cos(ph), -r * np.sin(ph)], axis=-1)
        par.append(hermite_chain(p, dp, dphi))
    return mer + par[1:], par[0]


# --------------------------------------------------------------------------------------------------
# More truths (issue 12, sec. 4): helices and lines, curvature lines of a saddle, an inflected
# extrusion, a rib-vaulted square bay, and a negative case. Object coordinates: y up; every crossing
# at a knot of both chains, so graph points are truth control points (truth_xyz).


def _grid_chains(surf, dsu, dsv, us: np.ndarray, vs: np.ndarray) -> list[np.ndarray]:
    """The u-lines (v fixed) and v-lines (u fixed) of a parametric surface, knots at the grid.

    ``surf(u, v) -> (..., 3)``, ``dsu``/``dsv`` its partial derivatives. Every line overshoots its
    first and last crossing by half a step, so every crossing is a smooth crossing.
    """
    du, dv = us[1] - us[0], vs[1] - vs[0]
    uu = np.concatenate([[us[0] - du / 2], us, [us[-1] + du / 2]])
    vv = np.concatenate([[vs[0] - dv / 2], vs, [vs[-1] + dv / 2]])
    chains = []
    for v in vs:                       # u-lines
        vfix = np.full_like(uu, v)
        chains.append(hermite_chain(surf(uu, vfix), dsu(uu, vfix), du))
    for u in us:                       # v-lines
        ufix = np.full_like(vv, u)
        chains.append(hermite_chain(surf(ufix, vv), dsv(ufix, vv), dv))
    return chains


def spiral_chains(n_rulings: int = 5, n_helices: int = 3, pitch: float = 0.15,
                  t_range: tuple[float, float] = (-30.0, 120.0)) -> list[np.ndarray]:
    """A helical stair: the helicoid (r cos t, pitch t, r sin t) about the vertical y axis.

    Its rulings (the treads' radial edges, straight and horizontal) and its helices (r fixed: the
    stringers) cross orthogonally: X_r = (cos t, 0, sin t) and X_t = (-r sin t, pitch, r cos t).
    The rulings at t over ``t_range`` (deg), the helices at r = 0.5 .. 1.1, a gentle rise (steeper
    ramps fold over in a view from above: their silhouette makes crossings tangent in 2D); adjacent
    rulings are *not* parallel in 3D (they turn with t): false parallel candidates where they
    project close.
    """
    ts = np.radians(np.linspace(*t_range, n_rulings))
    rs = np.linspace(0.5, 1.1, n_helices)

    def surf(t, r):
        return np.stack([r * np.cos(t), pitch * t, r * np.sin(t)], axis=-1)

    def d_t(t, r):
        return np.stack([-r * np.sin(t), np.full_like(t, pitch), r * np.cos(t)], axis=-1)

    def d_r(t, r):
        return np.stack([np.cos(t), np.zeros_like(t), np.sin(t)], axis=-1)

    return _grid_chains(surf, d_t, d_r, ts, rs)


def saddle_chains(n: int = 4, extent: float = 0.3) -> list[np.ndarray]:
    """Enneper's minimal surface, a saddle whose parameter lines are its lines of curvature.

    X(u, v) = (u - u^3/3 + u v^2, v - v^3/3 + v u^2, u^2 - v^2), standing like a wall (its saddle
    axis along z, toward the viewer): conformal (X_u . X_v = 0 exactly), and every parameter line
    is a planar curve (a line of curvature). ``n`` u-lines and ``n`` v-lines over
    ``[-extent, extent]^2``. Larger extents fold over in views off the axis (the normal turns by
    2 atan |(u, v)|): at 0.4, 5 of 55 views of tilt 15-35 deg, turn -50..50 deg are generic.
    """
    s = np.linspace(-extent, extent, n)

    def surf(u, v):
        return np.stack([u - u**3 / 3 + u * v * v, v - v**3 / 3 + v * u * u, u * u - v * v], axis=-1)

    def d_u(u, v):
        return np.stack([1 - u * u + v * v, 2 * u * v, 2 * u], axis=-1)

    def d_v(u, v):
        return np.stack([2 * u * v, 1 - v * v + u * u, -2 * v], axis=-1)

    return _grid_chains(surf, d_u, d_v, s, s)


def wrinkle_chains(n_rulings: int = 5, n_sections: int = 3, depth: float = 1.6) -> list[np.ndarray]:
    """An inflected extrusion: the S-profile y = 0.4 sin(1.6 x), |x| <= 1, extruded along z.

    Sections (the profile at z fixed: planar, inflected at x = 0) and rulings (x fixed: straight,
    along z) cross orthogonally; every ruling is parallel to every other, every section to every other.
    """
    xs = np.linspace(-1.0, 1.0, n_rulings)
    zs = np.linspace(0.0, -depth, n_sections)

    def surf(x, z):
        return np.stack([x, 0.4 * np.sin(1.6 * x), z], axis=-1)

    def d_x(x, z):
        return np.stack([np.ones_like(x), 0.64 * np.cos(1.6 * x), np.zeros_like(x)], axis=-1)

    def d_z(x, z):
        return np.stack([np.zeros_like(x), np.zeros_like(x), np.ones_like(x)], axis=-1)

    return _grid_chains(surf, d_x, d_z, xs, zs)


def _arc3(c: np.ndarray, e1: np.ndarray, e2: np.ndarray, r: float, a0: float, a1: float, n: int) -> np.ndarray:
    """A circular arc c + r (cos a e1 + sin a e2), a from a0 to a1, as n Hermite cubics (knots at n + 1 angles)."""
    a = np.linspace(a0, a1, n + 1)[:, None]
    p = c + r * (np.cos(a) * e1 + np.sin(a) * e2)
    dp = r * (-np.sin(a) * e1 + np.cos(a) * e2)
    return hermite_chain(p, dp, (a1 - a0) / n)


def _segmental(p0: np.ndarray, p1: np.ndarray, rise: float, n: int) -> np.ndarray:
    """A segmental (circular) arch in the vertical plane through p0 and p1 (same height), rising ``rise``."""
    c = (p0 + p1) / 2
    half = float(np.linalg.norm(p1 - p0)) / 2
    e1 = (p1 - p0) / (2 * half)
    up = np.array([0.0, 1.0, 0.0])
    r = (half**2 + rise**2) / (2 * rise)
    centre = c + (rise - r) * up
    a0 = np.arctan2(-(rise - r), -half)          # the angle of p0 seen from the centre, in (e1, up)
    return _arc3(centre, e1, up, r, a0, np.pi - a0, n)


def _knotted_line(a: np.ndarray, b: np.ndarray, ts) -> np.ndarray:
    """A straight chain along a + t (b - a) with knots at the sorted fractions ``ts`` (handles at thirds)."""
    p = a + np.sort(np.asarray(ts, float))[:, None] * (b - a)
    return np.stack([p[:-1], p[:-1] + (p[1:] - p[:-1]) / 3, p[:-1] + 2 * (p[1:] - p[:-1]) / 3, p[1:]], axis=1)


def cross_chains(rise_wall: float = 0.8, rise_diagonal: float = 1.0) -> list[np.ndarray]:
    """A rib-vaulted square bay (quadripartite vault) on a 2 x 2 plan.

    Drawn: the four wall-plate lines at the springing height (straight, through the corners with a
    knot there, overshooting them by 8 %), the four wall ribs (segmental arches in the wall planes)
    and the two diagonal ribs (segmental arches in the diagonal planes, rising ``rise_diagonal``) that
    cross at the boss, horizontal and orthogonal there (the one smooth crossing). At each corner five
    strokes meet: the two wall-plate lines (orthogonal), the ribs springing there (not orthogonal to
    the lines in their own planes, orthogonal to the line across: mixed corner candidates).
    """
    corners = np.array([[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]], float)
    chains = []
    for i in range(4):                                   # wall-plate lines: knots at both corners
        a, b = corners[i], corners[(i + 1) % 4]
        chains.append(_knotted_line(a, b, [-0.08, 0.0, 1.0, 1.08]))
    for i in range(4):                                   # wall ribs
        chains.append(_segmental(corners[i], corners[(i + 1) % 4], rise_wall, 4))
    for i in range(2):                                   # diagonal ribs: a knot at the boss (n even)
        chains.append(_segmental(corners[i], corners[i + 2], rise_diagonal, 4))
    return chains


def turret_chains(height: float = 1.4) -> list[np.ndarray]:
    """The negative case: a hexagonal prism (radius 1, vertical axis) with sections on its side faces.

    Drawn: the top hexagon (six edges, meeting at 120 deg: corners that are *not* orthogonal), the
    vertical edges and bottom edges of the faces turned to +z (the front half), and on each front
    face a horizontal and a vertical section crossing each other and the face's edges orthogonally
    (overshooting them by 8 %). Along a vertical edge the horizontal sections of its two faces cross
    it at adjacent intersections: tangents 60 deg apart in 3D that may project close together
    (false parallel candidates). Every crossing is at a knot of both strokes.
    """
    ang = np.radians(np.arange(6) * 60.0 + 30.0)
    top = np.stack([np.cos(ang), np.full(6, height / 2), np.sin(ang)], 1)
    bot = top - [0.0, height, 0.0]
    front = [i for i in range(6) if (top[i, 2] + top[(i + 1) % 6, 2]) / 2 > 0.1]   # faces facing +z
    down = {f: 0.3 + 0.2 * k for k, f in enumerate(front)}       # horizontal section: share of the height down
    along = {f: 0.35 + 0.15 * k for k, f in enumerate(front)}    # vertical section: share along the top edge
    chains = [_knotted_line(top[i], top[(i + 1) % 6], [0, along[i], 1] if i in front else [0, 1])
              for i in range(6)]
    for i in sorted({i for f in front for i in (f, (f + 1) % 6)}):
        cuts = [down[f] for f in front if i in (f, (f + 1) % 6)]
        chains.append(_knotted_line(top[i], bot[i], [0, *cuts, 1]))
    chains += [_knotted_line(bot[f], bot[(f + 1) % 6], [0, along[f], 1]) for f in front]
    for f in front:
        dn = np.array([0.0, down[f] * height, 0.0])
        chains.append(_knotted_line(top[f] - dn, top[(f + 1) % 6] - dn, [-0.08, 0, along[f], 1, 1.08]))
        h = top[f] + (top[(f + 1) % 6] - top[f]) * along[f]
        chains.append(_knotted_line(h, h - [0, height, 0], [-0.08, 0, down[f], 1, 1.08]))
    return chains


def bay_curves(name: str, samples: int) -> list[np.ndarray]:
    """The curves (n, 3) of the network ``microarch.build`` reconstructs from the teaching sheet's drawing
    ``name`` with ``samples`` points per curve, stood upright: plan x, y -> x, -z; height -> y."""
    from importlib.resources import files

    from auszug.formats import load
    from auszug.microarch import build

    net = build(load(Path(str(files("auszug.examples"))) / "teaching-sheet" / f"{name}.uc"), samples=samples)
    up = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])
    return [c.points @ up for c in net.to_curve_network().curves()]


@functools.lru_cache(maxsize=8)
def bay_chains(name: str = "tn-3", segments: int = 8, samples: int = 400) -> tuple[np.ndarray, ...]:
    """A square bay of the project's own microarchitecture: the negative case its ogee ribs make.

    The curves of :func:`bay_curves` (``samples`` points each). Each curve becomes
    a Hermite chain of a cubic spline through its samples by arc length: knots at ``segments`` equal
    steps and at the curve's 3D crossings with the others (found on the splines; a step knot within
    half a step of a crossing gives way), the crossing's point shared by both chains. Unlike every
    truth in :data:`TRUTHS`, its smooth crossings are *not* orthogonal in 3D (two ribs rising from
    different posts cross at equal heights at whatever angle their ogees give): the method's hard
    assumption fails there, and the lift measures what that costs.
    """
    from scipy.interpolate import CubicSpline
    from scipy.optimize import minimize
    from scipy.spatial import cKDTree

    P = bay_curves(name, samples)
    size = float(np.ptp(np.vstack(P), axis=0).max())
    splines = []
    for p in P:
        s = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))]
        splines.append(CubicSpline(s / s[-1], p))
    knots: list[dict[float, np.ndarray | None]] = [dict.fromkeys(np.linspace(0, 1, segments + 1)) for _ in P]
    for i in range(len(P)):
        for j in range(i + 1, len(P)):
            d, k = cKDTree(P[j]).query(P[i])
            m = int(d.argmin())
            a0, b0 = m / (len(P[i]) - 1), int(k[m]) / (len(P[j]) - 1)
            if d[m] > 2e-3 * size or (min(a0, 1 - a0) < 0.02 and min(b0, 1 - b0) < 0.02):
                continue                       # apart, or ends shared (at a post or the apex)
            si, sj = splines[i], splines[j]
            r = minimize(lambda x, si=si, sj=sj: float(np.sum((si(x[0]) - sj(x[1])) ** 2)), [a0, b0],
                         method="Nelder-Mead", options={"xatol": 1e-13, "fatol": 1e-30, "maxiter": 4000})
            a, b = (float(v) for v in np.clip(r.x, 0.0, 1.0))
            point = (si(a) + sj(b)) / 2
            for kk, t in ((i, a), (j, b)):
                for u in [u for u, q in knots[kk].items() if q is None and 0 < u < 1 and abs(u - t) < 0.5 / segments]:
                    del knots[kk][u]
                knots[kk][t] = point
    chains = []
    for sp, kn in zip(splines, knots, strict=True):
        ts = np.array(sorted(kn))
        p, dp = sp(ts), sp(ts, 1)
        for n, t in enumerate(ts):
            if kn[float(t)] is not None:
                p[n] = kn[float(t)]
        chain = hermite_chain(p, dp, np.diff(ts)[:, None])
        chain.flags.writeable = False          # shared by the cache
        chains.append(chain)
    return tuple(chains)


def make_bay(name: str = "tn-3", tilt: float = 20.0, turn: float = 20.0, noise: float = 0.0, seed: int = 0) -> Truth:
    """:func:`bay_chains` seen from (tilt, turn), with 2D noise (as :func:`make`)."""
    return _project(bay_chains(name), rotation(tilt, turn), noise, seed)


#: The truths of the evaluation (benchmarks/eval_lifting.py) by name: their chains in object
#: coordinates (the revolve's are built inside :func:`revolve`); :func:`make` projects them.
TRUTHS = {"revolve": None, "spiral": spiral_chains, "saddle": saddle_chains, "wrinkle": wrinkle_chains,
          "cross": cross_chains, "turret": turret_chains}
#: The view (tilt, turn) of each truth in the tests: generic (:func:`accidental` finds nothing).
VIEWS = {"revolve": (25.0, 15.0), "spiral": (25.0, 20.0), "saddle": (25.0, 10.0), "wrinkle": (25.0, 30.0),
         "cross": (30.0, 20.0), "turret": (25.0, 10.0)}


def make(name: str, tilt: float | None = None, turn: float | None = None, noise: float = 0.0,
         seed: int = 0) -> Truth:
    """The named truth of :data:`TRUTHS`, seen from (tilt, turn) (default: :data:`VIEWS`), with 2D noise."""
    t0, u0 = VIEWS[name]
    tilt = t0 if tilt is None else tilt
    turn = u0 if turn is None else turn
    if name == "revolve":
        return revolve(tilt=tilt, turn=turn, noise=noise, seed=seed)
    return _project(TRUTHS[name](), rotation(tilt, turn), noise, seed)


def truth_xyz(truth: Truth, graph) -> np.ndarray:
    """The true 3D position (graph units) of every graph control point, noisy sketches too.

    Every crossing must be at a knot of both chains (as in every truth here): each graph point is
    then one of the sketch's control points (the noise moves control points, shared ones alike),
    and the truth's control point of the same index is its 3D position. Raises when a graph point
    is farther than 1e-9 of the diagonal from every sketch control point.
    """
    drawn = np.concatenate([s.controls.reshape(-1, 2) for s in truth.sketch.strokes])
    allc = np.concatenate([c.reshape(-1, 3) for c in truth.chains3d[:len(truth.sketch.strokes)]])
    xy = graph.points * graph.scale + graph.offset
    d = np.linalg.norm(xy[:, None, :] - drawn[None, :, :], axis=2)
    if d.min(1).max() > 1e-9 * truth.diagonal():
        raise ValueError("graph points off the sketch's control points: a crossing is not at a knot")
    P = allc[d.argmin(1)]
    return np.column_stack([(P[:, :2] - graph.offset) / graph.scale, P[:, 2] / graph.scale])


def labels(truth: Truth, params=None) -> dict[str, np.ndarray]:
    """The true label of every cue candidate of the lift, per class, from the 3D truth.

    For each class the candidates are those the lift detects on the sketch's graph (in the order of
    its ``cues`` of that kind); a candidate is truly regular when its angle on the truth's control
    points is within ``params.inner_deg`` (L = 1 there). Also ``"<kind>-angle"``: those true angles
    (degrees), and ``"parallel-2d"``: the parallel candidates' 2D angles. One layer only.
    """
    from auszug.lifting import DEFAULT, layer_graphs
    from auszug.lifting import cues as cu

    params = DEFAULT if params is None else params
    (_, g), = layer_graphs(truth.sketch, params)
    X = truth_xyz(truth, g)
    fams = {"parallel": cu.parallel_cues(g, params), "orthogonal": cu.orthogonal_cues(g),
            "planar": cu.planar_cues(g, len(g.points)), "linear": cu.linear_cues(g, params),
            "smooth-orthogonal": cu.smooth_orthogonal(g)}
    out = {}
    for k, fam in fams.items():
        ang = fam.angles(X) if len(fam) else np.zeros(0)
        out[k] = ang <= params.inner_deg
        out[k + "-angle"] = ang
    out["parallel-2d"] = fams["parallel"].angle2d
    return out


#: :func:`accidental`'s reason for a truth that breaks the method's assumption (the bays of :func:`bay_chains`).
NOT_ORTHOGONAL = "a smooth crossing is not orthogonal in 3D"


def accidental(truth: Truth, params=None) -> list[str]:
    """Why a noise-free projection is an accidental view (empty: generic).

    - two graph intersections or occlusion points closer than 1 % of the diagonal, the markers'
      snap radius (a crossing that is a projection coincidence near another: a marker could snap
      to the wrong one);
    - a crossing of two strokes both passing through it, not a smooth crossing or within 5 deg of
      ``params.min_crossing_deg`` (tangents projected nearly parallel);
    - a parallel candidate whose tangents are more than ``params.inner_deg`` apart in 3D but
      within 1 deg in 2D (non-parallel tangents projected parallel);
    - a truly orthogonal smooth crossing (every one here) whose 3D tangents are not orthogonal to
      1e-6 deg (a truth that breaks the method's assumption);
    - a planar stroke whose plane is within 2 deg of edge-on.
    """
    from auszug.lifting import DEFAULT, layer_graphs

    params = DEFAULT if params is None else params
    (_, g), = layer_graphs(truth.sketch, params)
    why = []
    pts = np.concatenate([g.points[[c.point for c in g.crossings]], g.occluded.reshape(-1, 2)])
    d = np.linalg.norm(pts[:, None] - pts[None], axis=2) + np.eye(len(pts)) * 9
    if d.min() < 0.01:
        why.append(f"two crossings {d.min():.4f} of the diagonal apart")
    for c in g.crossings:
        if len(set(c.strokes)) == 2 and len(c.ends) == 4:
            t = [g.points[g.segments[s, 1 if e == 0 else 2]] - g.points[c.point] for s, e in c.ends]
            by = {}
            for (s, _), v in zip(c.ends, t, strict=True):
                by.setdefault(int(g.seg_stroke[s]), v)
            a, b = by.values()
            ang = np.degrees(np.arccos(min(1.0, abs(a @ b) / np.linalg.norm(a) / np.linalg.norm(b))))
            if not c.smooth or ang < params.min_crossing_deg + 5:
                why.append(f"crossing of {sorted(by)} at {ang:.1f} deg in 2D")
    lab = labels(truth, params)
    bad = (lab["parallel-angle"] > params.inner_deg) & (lab["parallel-2d"] < 1.0)
    if bad.any():
        why.append(f"{int(bad.sum())} non-parallel tangent pairs within 1 deg in 2D")
    if len(lab["smooth-orthogonal-angle"]) and lab["smooth-orthogonal-angle"].max() > 1e-6:
        why.append(NOT_ORTHOGONAL)
    for k, c in enumerate(truth.chains3d[:len(truth.sketch.strokes)]):
        P = c.reshape(-1, 3)
        sv = np.linalg.svd(P - P.mean(0), full_matrices=True)
        if sv[1][-1] <= 1e-9 * sv[1][0] and sv[1][1] > 1e-3 * sv[1][0]:
            n = sv[2][-1]
            if abs(n[2]) < np.sin(np.radians(2.0)):
                why.append(f"stroke c{k} seen within 2 deg of edge-on")
    return why


def cue_scores(result, lab: dict[str, np.ndarray]) -> dict[str, tuple[int, int, int, float]]:
    """Per class: (true positives, applied, true, F1) of the lift's applied cues against the labels."""
    out = {}
    for k in ("parallel", "orthogonal", "planar", "linear"):
        app = np.array([c.applied for c in result.cues if c.kind == k and "(global" not in c.where], bool)
        if len(app) != len(lab[k]):
            if not len(app):       # the class was not resolved
                continue
            raise ValueError(f"{k}: {len(app)} cues in the lift, {len(lab[k])} labels")
        tp, na, nt = int((app & lab[k]).sum()), int(app.sum()), int(lab[k].sum())
        f1 = 2 * tp / (na + nt) if na + nt else 1.0
        out[k] = (tp, na, nt, f1)
    return out


def _cp_rmse(X: np.ndarray, Y: np.ndarray) -> float:
    """Depth RMSE between two sets of graph points (graph units: relative to the diagonal), best offset and sign."""
    a = X[:, 2] - X[:, 2].mean()
    b = Y[:, 2] - Y[:, 2].mean()
    return float(min(np.sqrt(np.mean((a - b) ** 2)), np.sqrt(np.mean((a + b) ** 2))))


def baseline_energies(truth: Truth, params=None) -> dict:
    """The baseline energy (paper sec. 5.3) of a one-layer truth, term by term, at three places.

    - ``truth``: at the truth's control points (its smooth crossings orthogonal and G1 joints at the
      sketch's ratios, so it is feasible), per term: ``accuracy`` (w_a = ``params.w_a_baseline``),
      ``variation``, ``foreshortening`` and ``parallel`` (the soft w_p = w_p_baseline exp(-a^2 / s^2)
      over every parallel candidate);
    - ``lift_energy``, ``lift_rmse``: the lowest converged baseline of ``lift(..., classes=())``;
    - ``basin_energy``, ``basin_rmse``: the minimum the baseline solve reaches when started at the
      truth (the truth's own basin), and ``basin_converged``.

    RMSEs are of the depths at the graph's control points, relative to the diagonal, best offset and sign.
    """
    from dataclasses import replace

    from auszug.lifting import DEFAULT, layer_graphs, lift
    from auszug.lifting import cues as cu
    from auszug.lifting.solver import Poly2, solve
    from auszug.lifting.terms import fidelity, structure

    p = DEFAULT if params is None else params
    (_, g), = layer_graphs(truth.sketch, p)
    N = len(g.points)
    n = 3 * (N + len(g.chains)) + len(g.chains)
    par = cu.parallel_cues(g, p)
    wp = p.w_p_baseline * np.exp(-(par.angle2d**2) / p.sigma_p_deg**2)
    wa = p.w_a_baseline
    terms = {"accuracy": fidelity(g, n, replace(p, w_v=0.0, w_f=0.0), wa),
             "variation": fidelity(g, n, replace(p, w_f=0.0), 0.0),
             "foreshortening": fidelity(g, n, replace(p, w_v=0.0), 0.0)}
    P = Poly2(n)
    par.add(P, np.arange(len(par)), wp)
    terms["parallel"] = P
    smooth = cu.smooth_orthogonal(g)
    X = truth_xyz(truth, g)
    pin = int(smooth.p[0])
    X[:, 2] -= X[pin, 2]
    v = np.zeros(n)
    v[: 3 * N] = X.ravel()

    def value(Q: Poly2, x: np.ndarray) -> float:
        return float((Q.weights * Q.value(x) ** 2).sum())

    at_truth = {k: value(Q, v) for k, Q in terms.items()}
    E = fidelity(g, n, p, wa)
    par.add(E, np.arange(len(par)), wp)
    cols = np.arange(3 * N, n)       # the normals and plane offsets no baseline row uses: held where they are
    E.add(np.zeros(len(cols)), 1e-8, lin=(np.arange(len(cols)), cols, np.ones(len(cols))))
    C = structure(g, n, p, pin)
    smooth.add(C, np.arange(len(smooth)), 1.0)
    r = solve(E, C, v, None, iterations=p.newton_iterations, tol=p.newton_tol, kkt_reg=p.kkt_reg,
              hessian_reg=p.hessian_reg)
    res = lift(truth.sketch, params=p, classes=())
    Xl = res.points[0].copy()
    Xl[:, 2] /= g.scale
    e_lift = min(s.energy for s in res.stages if s.name == "baseline" and s.converged and not s.discarded)
    return {"truth": at_truth, "lift_energy": e_lift, "lift_rmse": _cp_rmse(Xl, X),
            "basin_energy": r.energy, "basin_rmse": _cp_rmse(r.v[: 3 * N].reshape(N, 3), X),
            "basin_converged": r.converged}
