"""Sketch lifting speed (issue 12, sec. 5): time per stage for a generated 100-curve sketch. Not a test.

The sketch: meridians and parallels of a vase of revolution (every crossing a
smooth crossing, orthogonal in 3D), seen from above (tilt 25, turn 15 deg),
written as SVG text and read back, so the reader is timed too. The default,
96 meridians x 4 parallels, is 100 curves with 384 crossings. Goal: <= 3 s
for 100 curves on a 2-core machine; the paper (Xu et al. 2014) reports 3-30 s
per model.

Usage: python benchmarks/bench_lifting.py [--meridians M] [--parallels P] [--markdown] [--progress]
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import platform
import resource
import sys
import time
from collections import defaultdict

import numpy as np

from auszug.formats.sketch_svg import read_sketch_svg
from auszug.lifting import DEFAULT_CLASSES, LiftParams, layer_graphs, lift

TARGET_S = 3.0
#: The paper's times per model (Xu et al. 2014: "3 to 30 seconds").
PAPER_S = (3.0, 30.0)
#: The gap tolerance of the opt-in row: below the 0.21 % between the nearest two stroke ends of this sketch.
CLOSE_GAPS = 0.001


def vase_svg(n_mer: int, n_par: int, tilt: float = 25.0, turn: float = 15.0) -> str:
    """The front half of a vase, n_mer meridians and n_par parallels, as an SVG of cubic paths."""
    a, b = np.radians(turn), np.radians(tilt)
    R = np.array([[1, 0, 0], [0, np.cos(b), -np.sin(b)], [0, np.sin(b), np.cos(b)]]) @ \
        np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])
    phis, hs = np.radians(np.linspace(-60, 60, n_mer)), np.linspace(-1, 1, n_par)
    dphi, dh = phis[1] - phis[0], hs[1] - hs[0]

    def r(h):
        return 1 + 0.35 * np.sin(1.3 * h + 0.4)

    def dr(h):
        return 0.455 * np.cos(1.3 * h + 0.4)

    def chain(p, dp, dt):
        c0, c3 = p[:-1], p[1:]
        return np.stack([c0, c0 + dp[:-1] * dt / 3, c3 - dp[1:] * dt / 3, c3], 1) @ R.T

    paths = []
    h = np.concatenate([[hs[0] - dh / 2], hs, [hs[-1] + dh / 2]])
    for phi in phis:
        p = np.stack([r(h) * np.sin(phi), h, r(h) * np.cos(phi)], -1)
        dp = np.stack([dr(h) * np.sin(phi), np.ones_like(h), dr(h) * np.cos(phi)], -1)
        paths.append(chain(p, dp, dh))
    ph = np.concatenate([[phis[0] - dphi / 2], phis, [phis[-1] + dphi / 2]])
    for h0 in hs:
        p = np.stack([r(h0) * np.sin(ph), np.full_like(ph, h0), r(h0) * np.cos(ph)], -1)
        dp = np.stack([r(h0) * np.cos(ph), np.zeros_like(ph), -r(h0) * np.sin(ph)], -1)
        paths.append(chain(p, dp, dphi))
    body = []
    for i, c in enumerate(paths):
        xy = c[:, :, :2] * [100, -100]
        d = f"M {float(xy[0, 0, 0])!r} {float(xy[0, 0, 1])!r} " + " ".join(
            "C " + " ".join(f"{float(x)!r} {float(y)!r}" for x, y in seg[1:]) for seg in xy)
        body.append(f'<path id="c{i}" d="{d}"/>')
    return '<svg xmlns="http://www.w3.org/2000/svg">' + "".join(body) + "</svg>"


def main() -> None:
    """Lift the generated sketch once and print the time of every stage."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--meridians", type=int, default=96)
    ap.add_argument("--parallels", type=int, default=4)
    ap.add_argument("--markdown", action="store_true")
    ap.add_argument("--progress", action="store_true", help="print the lift's progress lines (stderr) as they come")
    args = ap.parse_args()
    load0 = os.getloadavg()[0]
    text = vase_svg(args.meridians, args.parallels)
    rows: list[tuple[str, float, str]] = []
    t0 = time.perf_counter()
    sketch = read_sketch_svg(text, "vase.svg")       # includes the same validation lift does
    t_read = time.perf_counter() - t0
    t0 = time.perf_counter()
    # on an equal copy: layer_graphs memoises per sketch object, so the reader's graph serves the lift
    (_, g), = layer_graphs(dataclasses.replace(sketch))
    t_graph = time.perf_counter() - t0
    rows.append(("read SVG (+ validation graph)", t_read, f"{len(sketch.strokes)} curves"))
    rows.append(("curve graph (again, not in the lift)", t_graph,
                 f"{len(g.crossings)} crossings, {len(g.segments)} segments, {3 * len(g.points)} unknowns"))
    t0 = time.perf_counter()
    (_, gc), = layer_graphs(dataclasses.replace(sketch), LiftParams(close_gaps=CLOSE_GAPS))
    rows.append((f"curve graph, close_gaps {CLOSE_GAPS:g} (opt-in)", time.perf_counter() - t0,
                 f"{len(gc.gaps)} gaps closed, {len(gc.junctions)} crossings joined, {len(gc.crossings)} crossings "
                 "(off by default: not in the lift)"))
    t0 = time.perf_counter()
    t_start = time.perf_counter()

    def show(line: str) -> None:
        print(f"  [{time.perf_counter() - t_start:7.2f} s] {line}", file=sys.stderr, flush=True)

    r = lift(sketch, progress=show if args.progress else None)
    t_lift = time.perf_counter() - t0
    by: dict[str, list[float]] = defaultdict(lambda: [0.0, 0, 0, 0, 0])
    for st in r.stages:
        key = st.name.split(" round")[0].split(" ")[0] if st.name.startswith("seed") else st.name.split(" round")[0]
        by[key][0] += st.seconds
        by[key][1] += st.iterations
        by[key][2] += 1
        by[key][3] += 0 if st.converged or st.discarded else 1
        by[key][4] += 1 if st.discarded else 0
    for k, (sec, it, n, bad, dropped) in by.items():
        rows.append((k, sec, f"{n} solves, {it} Newton steps" + (f", {bad} not converged" if bad else "")
                     + (f", {dropped} of a discarded seed (not converged)" if dropped else "")))
    solves = sum(st.seconds for st in r.stages)
    rows.append(("lift: graph, network, stacking", t_lift - solves, ""))
    rows.append(("**total lift**", t_lift, f"paper {PAPER_S[0]:g}-{PAPER_S[1]:g} s; goal <= {TARGET_S:g} s: "
                                           f"{'met' if t_lift <= TARGET_S else 'NOT met'}; converged: {r.converged}"))
    host = (f"{platform.python_version()}, {os.cpu_count()} cores, cues {','.join(DEFAULT_CLASSES)}, "
            f"load average {load0:.1f} before, {os.getloadavg()[0]:.1f} after, "
            f"peak RSS {resource.getrusage(resource.RUSAGE_SELF).ru_maxrss // 1024} MB")
    if args.markdown:
        print("| stage | seconds | |\n|---|---|---|")
        for name, sec, note in rows:
            print(f"| {name} | {sec:.2f} | {note} |")
        print(f"\n({host})")
    else:
        for name, sec, note in rows:
            print(f"{name:<34} {sec:8.2f} s  {note}")
        print(host)


if __name__ == "__main__":
    main()
