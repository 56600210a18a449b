"""Ground truth in code: 3D curve networks with known depths, projected orthographically into sketches.

Each network is a set of 3D cubic Bezier chains with knots at the 3D
intersections (Hermite segments with the exact tangents), so the truth is
exactly representable and its crossings are exactly what the method assumes.
"""

from __future__ import annotations

from dataclasses import dataclass

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


def hermite_chain(p: np.ndarray, dp: np.ndarray, dt: float) -> np.ndarray:
    """Bezier chain (k-1, 4, 3) through knots p (k, 3) with derivatives dp (k, 3) per unit parameter step dt."""
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
        noise: float = 0.0, seed: int = 0) -> Truth:
    """A box of straight strokes: its 9 visible edges and two cross-sections through every visible face.

    Edges end at the corners (non-smooth intersections: orthogonal corners, three at the front
    corner); each section crosses the face's two opposite edges (overshooting them by 8 %) and the
    face's other section: every crossing is a smooth crossing, orthogonal in 3D.
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


def occlusions(view, tol: float, strokes2d=None) -> list[np.ndarray]:
    """2D crossings of two chains (view coordinates) whose depths there differ by more than ``tol``.

    The crossings are those of ``strokes2d`` (the drawn, possibly jittered strokes) when given,
    else of the view's own x, y; the depths are always the view's."""
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
            if abs(za - zb) > tol:
                out.append(np.asarray(h.point, float))
    return out


def _project(chains, R, noise: float, seed: int) -> Truth:
    view = tuple(c @ R.T for c in chains)
    strokes0 = tuple(Stroke(c[:, :, :2].copy(), f"c{i}") for i, c in enumerate(view))
    d0 = Sketch(strokes0).diagonal()
    marks = tuple(Marker("occlusion", p, f"occlusion-{i + 1}") for i, p in enumerate(occlusions(view, 1e-6 * d0)))
    sk = Sketch(strokes0, marks)
    if noise:
        rng = np.random.default_rng(seed)
        d = sk.diagonal()
        # a wobbly hand: a smooth random displacement field over the sketch (sum of 8 plane waves of
        # wavelengths diagonal/4 .. diagonal/2, each coordinate's standard deviation noise * diagonal)
        # applied to every control point, so shared points stay shared and tangents stay continuous
        k = 8
        ang = rng.uniform(0, 2 * np.pi, k)
        freq = 2 * np.pi / (d * rng.uniform(0.25, 0.5, k))
        wave = np.stack([np.cos(ang), np.sin(ang)], 1) * freq[:, None]      # (k, 2)
        phase = rng.uniform(0, 2 * np.pi, (k, 2))
        amp = rng.normal(0, 1, (k, 2)) * noise * d * np.sqrt(2.0 / k)        # E[sin^2] = 1/2

        def field(xy: np.ndarray) -> np.ndarray:
            arg = xy @ wave.T                                                  # (..., k)
            return np.einsum("...kc,kc->...c", np.sin(arg[..., None] + phase), amp)

        strokes = [Stroke(s.controls + field(s.controls), s.id) for s in sk.strokes]
        sk = Sketch(tuple(strokes), tuple(Marker(m.kind, m.point + field(m.point), m.id) for m in marks))
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
