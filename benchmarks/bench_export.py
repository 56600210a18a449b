"""Exports exact to a tolerance: how many points the default gives on the corpus and what it costs.

For every bundled drawing: the network is built (65 samples per piece, the
interactive default), then sampled by tolerance (default 1e-6 of the bounding-box
diagonal, every feature point a vertex). Reported per folder and in total: points
written (all curves, replicas included), the time to sample by tolerance
(intersections included, after a warm-up build), the time to write network JSON,
and the largest distance of the 65-sample polylines from the exact curves (the
old export) against the tolerance polylines' own.

    .venv/bin/python benchmarks/bench_export.py [--rel 1e-6] [--reps 3]
"""

from __future__ import annotations

import argparse
import time
from collections import defaultdict
from pathlib import Path

import numpy as np

from auszug.formats import load
from auszug.formats.network_json import dumps
from auszug.geometry.network import sample_by_tolerance
from auszug.microarch import build

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent / "src" / "auszug" / "examples"


def chord_error(piece, ts: np.ndarray) -> float:
    """Largest distance of the exact curve inside each interval from its chord (33 probes each)."""
    lo, hi = ts[:-1], ts[1:]
    fr = np.linspace(0.0, 1.0, 33)
    q = piece.point_t(lo[:, None] + (hi - lo)[:, None] * fr)
    a, b = piece.point_t(lo)[:, None], piece.point_t(hi)[:, None]
    d = b - a
    s = np.clip(np.einsum("...i,...i->...", q - a, d) / np.maximum(np.einsum("...i,...i->...", d, d), 1e-300), 0, 1)
    return float(np.linalg.norm(q - (a + s[..., None] * d), axis=-1).max())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rel", type=float, default=1e-6, help="tolerance relative to the diagonal")
    ap.add_argument("--reps", type=int, default=3)
    args = ap.parse_args()
    rows: dict[str, list] = defaultdict(lambda: [0, 0, 0, 0.0, 0.0, 0.0, 0.0])
    files = sorted(p for p in ROOT.rglob("*.uc"))
    assert files, "no bundled drawings"
    for path in files:
        folder = path.relative_to(ROOT).parts[0]
        net = build(load(path))
        cn = net.to_curve_network()
        diag = cn.diagonal()
        T = args.rel * diag
        best = np.inf
        for _ in range(args.reps):
            # fresh networks each repetition: a new build (cached pieces reused, as in the studio)
            # and the intersections and sampling redone
            t0 = time.perf_counter()
            fine = build(load(path)).with_intersections().resampled(tolerance=T)
            best = min(best, time.perf_counter() - t0)
        t0 = time.perf_counter()
        dumps(fine, path.name)
        t_json = time.perf_counter() - t0
        pts = sum(len(c.points) for c in fine.curves())
        old = sum(len(c.points) for c in cn.curves())
        e_old = e_new = 0.0
        for p0, p in zip(net.with_intersections().pieces, fine.pieces, strict=True):
            if p.top is None:
                continue
            t_old = p.top.t_at_u(np.linspace(0.0, p.u_end, 65))
            e_old = max(e_old, chord_error(p, np.asarray(t_old)) / diag)
            ts, _ = sample_by_tolerance(p0, T)
            e_new = max(e_new, chord_error(p, ts) / diag)
        r = rows[folder]
        r[0] += 1
        r[1] += old
        r[2] += pts
        r[3] += best
        r[4] += t_json
        r[5] = max(r[5], e_old)
        r[6] = max(r[6], e_new)
    tot = [sum(r[i] for r in rows.values()) for i in range(5)] + [
        max(r[5] for r in rows.values()), max(r[6] for r in rows.values())]
    print(f"tolerance {args.rel:g} x diagonal, best of {args.reps}\n")
    print("| folder | drawings | points, 65 per piece | points, by tolerance | sample (s) | JSON (s) "
          "| max error 65 / diag | max error tol / diag |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for name, r in sorted(rows.items()) + [("**all**", tot)]:
        print(f"| {name} | {r[0]} | {r[1]} | {r[2]} | {r[3]:.3f} | {r[4]:.3f} | {r[5]:.2e} | {r[6]:.2e} |")


if __name__ == "__main__":
    main()
