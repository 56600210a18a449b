"""Tracery speed (issue: window tracery). Prints a table; not a test.

1. The 2D structure of the most complex window, Fig. 20h (three levels of
   refinement, 121 regions): ``build(style)``. Target: < 20 ms.
2. Fig. 20h as a finished mesh (2D structure and the watertight manifold
   mesh with the elaborate profile, wall included). Target: < 0.5 s on a
   2-core machine; Havemann and Fellner (2004): "not much more than a second
   or two on a state-of-the-art PC".
3. Tangency residuals of the rosette circle (distance from its centre to the
   outer arch and both sub-arches minus its radius): the paper's call, and
   the largest over many random valid windows.
4. Every built-in style: 2D and mesh time, mesh size.

Usage: python benchmarks/bench_tracery.py [--reps N] [--markdown]
"""

from __future__ import annotations

import argparse
import os
import platform

import numpy as np

from auszug.errors import AuszugError
from auszug.tracery import WindowParams, build, builtin_style, builtin_styles, prototype, window_mesh

from _timing import timed

TARGET_2D_MS = 20.0
TARGET_MESH_S = 0.5


def residuals(n: int, seed: int = 1) -> tuple[float, float, int]:
    """(paper call residual, worst residual over n random windows, number of valid windows)."""
    paper = prototype(WindowParams(span=2, height=4, excess=1.25, drop=0.2, outer=0.1, inner=0.05))
    rng = np.random.default_rng(seed)
    worst, valid = 0.0, 0
    for _ in range(n):
        span = rng.uniform(0.5, 4.0)
        p = dict(span=span, height=span * rng.uniform(0.8, 4), excess=rng.uniform(0.9, 2.0),
                 drop=span * rng.uniform(0, 0.2), outer=span * rng.uniform(0, 0.08),
                 inner=span * rng.uniform(0.005, 0.03), x=rng.uniform(-5, 5), y=rng.uniform(-5, 5))
        try:
            w = prototype(WindowParams(**p))
        except AuszugError:
            continue
        valid += 1
        worst = max(worst, w.tangency_residual() / max(1.0, span))
    return paper.tangency_residual(), worst, valid


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reps", type=int, default=30)
    ap.add_argument("--markdown", action="store_true", help="print RESULTS.md-ready markdown")
    args = ap.parse_args(argv)

    h = builtin_style("fig20h")
    t2d = timed(lambda: build(h), args.reps)
    t_load = timed(lambda: build("fig20h"), args.reps)  # style resolved by name each time
    tmesh = timed(lambda: window_mesh(build(h)), max(5, args.reps // 3))
    m = window_mesh(build(h))
    r_paper, r_worst, n_valid = residuals(2000)
    rows = []
    for name in builtin_styles():
        st = builtin_style(name)
        a = timed(lambda st=st: build(st), max(5, args.reps // 3))[0]
        b = timed(lambda st=st: window_mesh(build(st)), 5)[0]
        mm = window_mesh(build(st))
        rows.append((name, len(build(st).regions), a * 1e3, b * 1e3, mm.n_vertices, mm.n_faces))

    cpu = f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}"
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    if args.markdown:
        print("## Tracery (benchmarks/bench_tracery.py)\n")
        print(f"Machine: {cpu}; load average at the start {load:.1f}. Median (minimum) of repeated runs.\n")
        print("| measure | result | target |")
        print("|---|---|---|")
        print(f"| Fig. 20h 2D structure (121 regions) | {t2d[0] * 1e3:.1f} ms ({t2d[1] * 1e3:.1f} ms) "
              f"| < {TARGET_2D_MS:g} ms |")
        print(f"| ... with the style read by name | {t_load[0] * 1e3:.1f} ms ({t_load[1] * 1e3:.1f} ms) | |")
        print(f"| Fig. 20h finished mesh ({m.n_vertices} vertices, {m.n_faces} triangles, genus 91) | "
              f"{tmesh[0]:.3f} s ({tmesh[1]:.3f} s) | < {TARGET_MESH_S:g} s (paper: 1-2 s) |")
        print(f"| tangency residual, the paper's call | {r_paper:.1e} | < 1e-9 |")
        print(f"| tangency residual, worst of {n_valid} random windows (relative to the span) "
              f"| {r_worst:.1e} | < 1e-9 |")
        print("\n| style | regions | 2D (ms) | mesh (ms) | vertices | triangles |")
        print("|---|---|---|---|---|---|")
        for r in rows:
            print(f"| {r[0]} | {r[1]} | {r[2]:.1f} | {r[3]:.0f} | {r[4]} | {r[5]} |")
        return 0
    print(f"{cpu}; load {load:.1f}")
    print(f"Fig. 20h 2D structure:      median {t2d[0] * 1e3:7.1f} ms  min {t2d[1] * 1e3:7.1f} ms"
          f"   (target < {TARGET_2D_MS:g} ms)")
    print(f"  style read by name:       median {t_load[0] * 1e3:7.1f} ms  min {t_load[1] * 1e3:7.1f} ms")
    print(f"Fig. 20h finished mesh:     median {tmesh[0]:7.3f} s   min {tmesh[1]:7.3f} s"
          f"    (target < {TARGET_MESH_S:g} s)"
          f"  {m.n_vertices} vertices, {m.n_faces} triangles")
    print(f"tangency residual: paper {r_paper:.1e}, worst of {n_valid} random windows {r_worst:.1e}")
    print(f"{'style':8} {'regions':>7} {'2D ms':>7} {'mesh ms':>8} {'vertices':>9} {'triangles':>10}")
    for r in rows:
        print(f"{r[0]:8} {r[1]:7d} {r[2]:7.1f} {r[3]:8.0f} {r[4]:9d} {r[5]:10d}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
