"""Write the example sketches of src/auszug/examples/sketches from 3D truths.

Run: python -m tests.lifting.make_sketches

Each object is a 3D curve network whose crossings are orthogonal in 3D (a vase
of meridians and parallels, an ogee roof's S-shaped sections joined by
straight generators, a pointed barrel vault's two arches joined the same way), seen orthographically
from a generic view (``JITTER`` adds seeded 2D noise; 0: the bundled examples are noise-free
projections; the noise measurements are in tests/lifting/test_lifting.py and docs/lifting.md).
2D crossings that are not 3D intersections get an occlusion marker, derived from
the truth. The SVG is written as Inkscape would: a layer, ids, cubic paths.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from auszug.geometry import CubicBezier
from tests.lifting.truth import barrel_chains, hermite_chain, occlusions, revolve, rotation

JITTER = 0.0
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
        s2, view = project(chains, R, JITTER, seed)
        diag = float(np.linalg.norm(np.ptp(np.concatenate([v.reshape(-1, 3) for v in view]), axis=0)))
        marks = spurious(s2, view, 0.02 * diag)
        sym = s2[-1] if len(ids) < len(s2) else None   # a chain without an id: the symmetry curve
        (OUT / f"{name}.svg").write_text(svg(name, s2, marks, ids, sym))
        print(f"{name}: {len(s2)} strokes, {len(marks)} occlusion markers")


if __name__ == "__main__":
    main()
