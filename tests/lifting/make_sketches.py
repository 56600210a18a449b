"""Write the example sketches of src/auszug/examples/sketches from 3D truths.

Run: python -m tests.lifting.make_sketches

Each object is a 3D curve network whose crossings are orthogonal in 3D (a vase
of meridians and parallels, an ogee roof's S-shaped sections joined by
straight generators, a pointed barrel vault's two arches joined the same way), seen orthographically
from a generic view. The vase, the ogee roof and the arches are drawn *by hand* (:func:`hand_drawn`:
a wobbly hand, the pen's own segments, straight strokes ruled between wobbly ends; the issue's
"hand-drawn-style" examples); the half barrel is the exact projection (its symmetry curve is the
subject). 2D crossings that are not 3D intersections get an occlusion marker, derived from
the truth. The SVG is written as Inkscape would: a layer, ids, cubic paths.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from scipy.interpolate import make_lsq_spline

from auszug.geometry import CubicBezier
from tests.lifting.truth import (
    barrel_chains,
    crossings2d,
    hermite_chain,
    occlusions,
    revolve,
    rotation,
    wave_field,
)

JITTER = 0.0
HAND = {"vase": 0, "ogee-roof": 0, "arches": 0}     # the seed of each hand-drawn example (see hand_drawn)
VIEWS = {"vase": rotation(25.0, 15.0), "ogee-roof": rotation(26.0, -34.0), "arches": rotation(24.0, 32.0),
         "barrel-half": rotation(25.0, 35.0)}
OUT = Path(__file__).resolve().parents[2] / "src" / "auszug" / "examples" / "sketches"


def line(a: np.ndarray, b: np.ndarray, over: float = 0.08) -> np.ndarray:
    """A straight stroke from a to b, overshooting both ends by ``over`` of its length."""
    d = b - a
    a, b = a - over * d, b + over * d
    return np.array([[a, a + (b - a) / 3, a + 2 * (b - a) / 3, b]])


def arc(c: np.ndarray, r: float, a0: float, a1: float, n: int) -> np.ndarray:
    """A circular arc in the x-y plane (z = c[2]) as n Hermite cubics."""
    t = np.linspace(a0, a1, n + 1)
    p = np.stack([c[0] + r * np.cos(t), c[1] + r * np.sin(t), np.full_like(t, c[2])], -1)
    dp = np.stack([-r * np.sin(t), r * np.cos(t), np.zeros_like(t)], -1)
    return hermite_chain(p, dp, (a1 - a0) / n)


def arches() -> list[np.ndarray]:
    """A pointed (equilateral) barrel vault: two arches on posts, four straight generators."""
    chains = []
    depth = 2.2
    for z in (0.0, -depth):
        post_l = np.array([[[-1, -1, z], [-1, -2 / 3, z], [-1, -1 / 3, z], [-1, 0, z]]], float)
        left = arc(np.array([1.0, 0.0, z]), 2.0, np.pi, 2 * np.pi / 3, 3)
        right = arc(np.array([-1.0, 0.0, z]), 2.0, np.pi / 3, 0.0, 3)
        post_r = post_l[::-1, ::-1] * [-1, 1, 1]
        chains.append(np.concatenate([post_l, left, right, post_r]))
    a = np.radians(25)        # the flank generators: 25 deg up each arc from its springing
    fx, fy = 1 - 2 * np.cos(a), 2 * np.sin(a)
    for x, y in ((-1.0, -0.55), (fx, fy), (-fx, fy), (1.0, -0.55)):
        chains.append(line(np.array([x, y, 0.0]), np.array([x, y, -depth]), 0.1))
    return chains


def ogee_roof() -> list[np.ndarray]:
    """An ogee roof: three S-shaped (ogee) cross-sections of an extrusion, pointed at the ridge, joined by
    four straight generators on the flanks (an extrusion's generators cross its sections at right angles)."""
    half = np.array([[-1.0, 0.0], [-0.55, 0.05], [-0.45, 0.9], [0.0, 1.3]])   # one S-curve: eave to ridge
    b = CubicBezier.from_array(half)
    chains = []
    depth = 1.8
    for z in (0.0, -depth / 2, -depth):
        left = np.c_[half, np.full(4, z)]
        right = left[::-1] * [-1, 1, 1]
        chains.append(np.stack([left, right]))
    for t, sx in ((0.3, 1), (0.7, 1), (0.3, -1), (0.7, -1)):
        x, y = b.point(t)
        chains.append(line(np.array([sx * x, y, 0.0]), np.array([sx * x, y, -depth]), 0.1))
    return chains


def vase() -> list[np.ndarray]:
    """Five meridians and three parallels of the revolve ground truth (object coordinates)."""
    t = revolve(5, 3, tilt=0.0, turn=0.0)
    return [np.asarray(c) for c in t.chains3d]


def project(chains: list[np.ndarray], R: np.ndarray, jitter: float, seed: int) -> list[np.ndarray]:
    """Orthographic view along z of R @ X, with seeded jitter (relative to the diagonal), chains kept joined."""
    view = [c @ R.T for c in chains]
    flat = np.concatenate([v.reshape(-1, 3) for v in view])[:, :2]
    diag = float(np.linalg.norm(np.ptp(flat, axis=0)))
    rng = np.random.default_rng(seed)
    out = []
    for v in view:
        c = v[:, :, :2].copy()
        c[:, 1:3] += rng.normal(0.0, jitter * diag, c[:, 1:3].shape)   # handles only: ends stay joined
        out.append(c)
    return out, view  # type: ignore[return-value]


def _bezier_points(seg: np.ndarray, t: np.ndarray) -> np.ndarray:
    m = (1 - t)[:, None]
    t = t[:, None]
    return m**3 * seg[0] + 3 * m * m * t * seg[1] + 3 * m * t * t * seg[2] + t**3 * seg[3]


def _smooth_runs(chain: np.ndarray, corner_deg: float = 5.0) -> list[np.ndarray]:
    """The chain (m, 4, 3) split at its knots where the 2D tangent turns by more than ``corner_deg``."""
    cuts = [0]
    for k in range(1, len(chain)):
        a = chain[k - 1][3, :2] - chain[k - 1][2, :2]
        b = chain[k][1, :2] - chain[k][0, :2]
        if a @ b < np.cos(np.radians(corner_deg)) * np.linalg.norm(a) * np.linalg.norm(b):
            cuts.append(k)
    cuts.append(len(chain))
    return [chain[i:j] for i, j in zip(cuts[:-1], cuts[1:], strict=True)]


def _pen_fit(P: np.ndarray, u: np.ndarray, spans: int) -> np.ndarray:
    """The pen's curve: a least-squares cubic spline (C2, ``spans`` equal spans of ``u`` in [0, 1]) through
    the samples P (n, 3), its ends kept, as a Bezier chain (spans, 4, 3)."""
    knots = np.r_[[0.0] * 4, np.linspace(0, 1, spans + 1)[1:-1], [1.0] * 4]
    w = np.ones(len(u))
    w[[0, -1]] = 1e4
    s = make_lsq_spline(u, P, knots, k=3, w=w)
    b = np.linspace(0, 1, spans + 1)
    p, dp, h = s(b), s.derivative()(b), np.diff(b)[:, None]
    return np.stack([p[:-1], p[:-1] + dp[:-1] * h / 3, p[1:] - dp[1:] * h / 3, p[1:]], 1)


def hand_drawn(chains: list[np.ndarray], R: np.ndarray, seed: int, wobble: float = 0.004,
               tremor: float = 0.001, span: float = 0.2) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """The object seen along z after R, drawn by a hand: (2D strokes, their 3D truth), Bezier chains.

    The hand: a smooth displacement of the whole page (``truth.wave_field``, each coordinate's standard
    deviation ``wobble`` of the diagonal, as the noise of tests/lifting/truth.py), and along each curved
    stroke a tremor of its own (3 waves along its arc length, wavelengths 1/10-1/5 of the diagonal,
    standard deviation ``tremor``) normal to it. The pen: each curved stroke's smooth runs (split at its
    corners, kept) refitted by least squares with one cubic per ``span`` of the diagonal, knots where
    the pen put them, not at the crossings; a straight stroke ruled between its displaced ends. The
    depth of each drawn point is the truth's at the point it was drawn for, so the 3D truth of a drawn
    stroke is its 2D stroke lifted by the object's depth (within the hand's displacement: at a 3D
    intersection the two drawn strokes cross up to 2.4 % of the diagonal apart in the truth's depth, the
    ogee roof's ruled generators).
    """
    view = [c @ R.T for c in chains]
    flat = np.concatenate([v.reshape(-1, 3) for v in view])[:, :2]
    diag = float(np.linalg.norm(np.ptp(flat, axis=0)))
    rng = np.random.default_rng(seed)
    field = wave_field(rng, diag, wobble)
    out2, out3 = [], []
    for v in view:
        chord, inner = v[0, 3, :2] - v[0, 0, :2], v[0, 1:3, :2] - v[0, 0, :2]
        off_chord = np.abs(inner[:, 0] * chord[1] - inner[:, 1] * chord[0])
        straight = len(v) == 1 and bool(np.all(off_chord <= 1e-9 * diag**2))
        lam = diag * rng.uniform(0.1, 0.2, 3)
        ph = rng.uniform(0, 2 * np.pi, 3)
        ta = rng.normal(0, 1, 3) * tremor * diag * np.sqrt(2.0 / 3)
        pieces, s0 = [], 0.0
        for run in _smooth_runs(v):
            t = np.linspace(0, 1, 33)
            P = np.concatenate([_bezier_points(seg, t)[(1 if i else 0):] for i, seg in enumerate(run)])
            s = s0 + np.r_[0, np.cumsum(np.linalg.norm(np.diff(P[:, :2], axis=0), axis=1))]
            s0 = s[-1]
            Q = P.copy()
            Q[:, :2] += field(P[:, :2])
            if straight:
                a, b = Q[0], Q[-1]
                pieces.append(np.array([[a, a + (b - a) / 3, a + 2 * (b - a) / 3, b]]))
                continue
            d = np.gradient(P[:, :2], axis=0)
            nrm = np.stack([-d[:, 1], d[:, 0]], 1) / np.linalg.norm(d, axis=1)[:, None]
            Q[:, :2] += (np.sin(2 * np.pi * s[:, None] / lam + ph) @ ta)[:, None] * nrm
            spans = max(1, int(round((s[-1] - s[0]) / (span * diag))))
            pieces.append(_pen_fit(Q, (s - s[0]) / (s[-1] - s[0]), spans))
        c = np.concatenate(pieces)
        c[1:, 0] = c[:-1, 3]                              # the runs joined at the stroke's corners
        out3.append(c)
        out2.append(c[:, :, :2].copy())
    return out2, out3


def hand_occlusions(view: list[np.ndarray], drawn3d: list[np.ndarray]) -> list[np.ndarray]:
    """The occlusion markers of a hand-drawn sketch: each 2D crossing of the drawn strokes is what the
    exact projection's crossing nearest to it is (an occlusion where the truth's depths there differ by
    more than 1 % of the diagonal: measured at most 1.7e-4 at the examples' 3D intersections, whose
    Hermite arcs are not exactly circles, at least 0.5 at their occlusions); raises where the hand lost
    or made a crossing (another seed)."""
    diag = float(np.linalg.norm(np.ptp(np.concatenate([v.reshape(-1, 3) for v in view])[:, :2], axis=0)))

    def unique(cs: list[tuple[np.ndarray, float]]) -> list[tuple[np.ndarray, float]]:
        out: list[tuple[np.ndarray, float]] = []
        for p, dz in cs:                                   # a crossing at a knot is found on both segments
            if all(np.linalg.norm(p - q) > 1e-6 * diag for q, _ in out):
                out.append((p, dz))
        return out

    exact, drawn = unique(crossings2d(view)), unique(crossings2d(drawn3d, [c[:, :, :2] for c in drawn3d]))
    if len(exact) != len(drawn):
        raise ValueError(f"the hand made {len(drawn)} crossings of the projection's {len(exact)}")
    marks = []
    for p, _ in drawn:
        j = int(np.argmin([np.linalg.norm(p - q) for q, _ in exact]))
        if exact[j][1] > 0.01 * diag:
            marks.append(p)
    return marks


def drawn(name: str, seed: int | None = None) -> tuple[list[np.ndarray], list[np.ndarray], list[np.ndarray]]:
    """The hand-drawn example ``name``: (2D strokes, their 3D truth, occlusion markers).

    ``seed``: the hand's (default :data:`HAND`'s, the shipped drawing); raises ValueError where that hand
    lost or made a crossing (:func:`hand_occlusions`)."""
    chains = {"vase": vase, "ogee-roof": ogee_roof, "arches": arches}[name]()
    s2, s3 = hand_drawn(chains, VIEWS[name], HAND[name] if seed is None else seed)
    view = [c @ VIEWS[name].T for c in chains]
    return s2, s3, hand_occlusions(view, s3)


def spurious(strokes2d: list[np.ndarray], view: list[np.ndarray], tol: float) -> list[np.ndarray]:
    """2D crossings whose two curves are farther than ``tol`` apart in depth: occlusions."""
    return occlusions(view, tol, strokes2d)


def svg(name: str, strokes2d: list[np.ndarray], markers: list[np.ndarray], ids: list[str],
        symmetry: np.ndarray | None = None) -> str:
    """The sketch as an Inkscape-style SVG: y down, fitted in a 600 px wide page with a margin.

    ``symmetry``: the global symmetry curve (2D chain), written as ``<path class="symmetry">`` in the
    annotations layer (its last stroke of ``strokes2d`` too: the page is fitted to all of them).
    """
    pts = np.concatenate([s.reshape(-1, 2) for s in strokes2d])
    lo, hi = pts.min(0), pts.max(0)
    scale = 520.0 / float(max(hi - lo))
    w, h = (hi - lo) * scale + 80

    def tr(p: np.ndarray) -> tuple[float, float]:
        return (float((p[0] - lo[0]) * scale + 40), float((hi[1] - p[1]) * scale + 40))

    def f(v: float) -> str:
        return f"{v:.2f}".rstrip("0").rstrip(".")

    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             '<svg xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"',
             f'     width="{f(w)}" height="{f(h)}" viewBox="0 0 {f(w)} {f(h)}">',
             f'  <title>{name}: an auszug example sketch (lift with: auszug lift {name}.svg -o {name}.network.json)'
             '</title>',
             f'  <g inkscape:groupmode="layer" inkscape:label="{name}" id="layer-{name}"',
             '     style="fill:none;stroke:#222;stroke-width:2;stroke-linecap:round">']
    def path(c: np.ndarray) -> str:
        d = "M " + " ".join(f(x) for x in tr(c[0, 0]))
        for seg in c:
            d += " C " + " ".join(" ".join(f(x) for x in tr(p)) for p in seg[1:])
        return d

    for sid, c in zip(ids, strokes2d[:len(ids)], strict=True):
        lines.append(f'    <path id="{sid}" d="{path(c)}"/>')
    lines.append("  </g>")
    if markers or symmetry is not None:
        lines.append('  <g inkscape:groupmode="layer" inkscape:label="annotations" id="layer-annotations"'
                     ' style="fill:none;stroke:#d33;stroke-width:1.5">')
        for i, m in enumerate(markers):
            x, y = tr(m)
            lines.append(f'    <circle class="occlusion" id="occlusion-{i + 1}" cx="{f(x)}" cy="{f(y)}" r="6"/>')
        if symmetry is not None:
            lines.append(f'    <path class="symmetry" id="symmetry" d="{path(symmetry)}" '
                         'style="stroke-dasharray:8 4"/>')
        lines.append("  </g>")
    lines.append("</svg>")
    return "\n".join(lines) + "\n"


def main() -> None:
    """Write the example sketches (the half barrel with its symmetry curve, the last of its chains)."""
    OUT.mkdir(parents=True, exist_ok=True)
    jobs = {
        "vase": (vase(), VIEWS["vase"], [f"meridian-{i + 1}" for i in range(5)] +
                 [f"parallel-{i + 1}" for i in range(3)]),
        "ogee-roof": (ogee_roof(), VIEWS["ogee-roof"], ["section-front", "section-middle", "section-back",
                                                        "flank-1", "flank-2", "flank-3", "flank-4"]),
        "arches": (arches(), VIEWS["arches"], ["arch-front", "arch-back", "post-line-left", "flank-left",
                                               "flank-right", "post-line-right"]),
        "barrel-half": ([*barrel_chains()[0], barrel_chains()[1]], VIEWS["barrel-half"],
                        [f"meridian-{i + 1}" for i in range(5)] + ["parallel-1", "parallel-2"]),
    }
    for seed, (name, (chains, R, ids)) in enumerate(jobs.items()):
        if name in HAND:
            s2, _, marks = drawn(name)
        else:
            s2, view = project(chains, R, JITTER, seed)
            diag = float(np.linalg.norm(np.ptp(np.concatenate([v.reshape(-1, 3) for v in view]), axis=0)))
            marks = spurious(s2, view, 0.02 * diag)
        sym = s2[-1] if len(ids) < len(s2) else None   # a chain without an id: the symmetry curve
        (OUT / f"{name}.svg").write_text(svg(name, s2, marks, ids, sym))
        print(f"{name}: {len(s2)} strokes, {len(marks)} occlusion markers")


if __name__ == "__main__":
    main()
