"""Sweep detection end to end at the size limit (``LIMITS.sweep_faces``): time and memory. Prints a table; not a test.

Issue 11 sec. 5 asks that a huge mesh not run out of memory, and the brief that time stay bounded
within every documented limit. The worst case is a mesh that is no sweep: every stage runs all the
way and keeps nothing (the plane search, both matching passes, the kinematic parts, the mirror
planes, the crease arcs). The rows: the bump surface (:func:`~auszug.sweeps.fixtures.bumps`) at
about 28k, 124k and 997k triangles, and a surface of revolution of 999 000 triangles (the kinematic
path), each through :func:`~auszug.sweeps.detect` at the defaults in a fresh process (its own peak
memory, ``ru_maxrss``, the fixture's making included); the stages' seconds from the report. The
anchor is docs/limits.md's table (2 December 2026, through ``auszug sweeps`` on binary STL, while
other jobs ran) and its re-measurement of 5 December (in process, before this benchmark):

=====================  ===========  ==========================================
mesh                   triangles    before (docs/limits.md)
=====================  ===========  ==========================================
bumps(n=120)           28 322       66 s CPU (5 December)
bumps(n=250)           124 002      270-290 s CPU, 539 MB (5 December)
bumps(n=707)           996 872      70 s wall / 798 MB (2 December); not finished in 600 s (5 December)
revolved(1000, 501)    999 000      39.7 s wall / 803 MB (2 December); 7.5 s / 949 MB (5 December)
=====================  ===========  ==========================================

Usage (from the repository root): python -m benchmarks.bench_sweeps_limits [--only bumps120,bumps250,bumps707,revolved]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import subprocess
import sys
import time

CASES = {    # name: (the fixture as printed, its keyword arguments, the figures before)
    "bumps120": ("bumps(n=120)", {"n": 120}, "66 s CPU"),
    "bumps250": ("bumps(n=250)", {"n": 250}, "270-290 s CPU, 539 MB"),
    "bumps707": ("bumps(n=707)", {"n": 707}, "70 s / 798 MB (2 Dec); > 600 s (5 Dec)"),
    "revolved": ("revolved(n_profile=1000, n_path=501, sigma=2e-4)", {"n_profile": 1000, "n_path": 501, "sigma": 2e-4},
                 "39.7 s / 803 MB (2 Dec); 7.5 s / 949 MB (5 Dec)"),
}


def one(name: str) -> dict:
    """Run one case in this process; the figures as a dict."""
    from auszug.sweeps import detect, fixtures

    label, kwargs, _ = CASES[name]
    fx = getattr(fixtures, label.split("(")[0])(**kwargs)
    c0, w0 = time.process_time(), time.perf_counter()
    r = detect((fx.vertices, fx.faces))
    wall, cpu = time.perf_counter() - w0, time.process_time() - c0
    stages: dict[str, float] = {}
    for s in r.stages:
        stages[s.name] = stages.get(s.name, 0.0) + s.seconds
    return {"faces": len(fx.faces), "patches": len(r.patches), "coverage": r.coverage, "wall": wall, "cpu": cpu,
            "rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, "stages": stages}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default=",".join(CASES), help="comma-separated cases (default all)")
    ap.add_argument("--one", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.one:
        print(json.dumps(one(args.one)))
        return
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores (shared), load {os.getloadavg()[0]:.1f}\n")
    print("| mesh | triangles | patches, coverage | wall / CPU | peak RSS | largest stages (s) | before |")
    print("|---|---|---|---|---|---|---|")
    for name in args.only.split(","):
        out = subprocess.run([sys.executable, "-m", "benchmarks.bench_sweeps_limits", "--one", name],
                             capture_output=True, text=True, check=True)
        got = json.loads(out.stdout.strip().splitlines()[-1])
        top = sorted(got["stages"].items(), key=lambda kv: -kv[1])[:4]
        print(f"| {CASES[name][0]} | {got['faces']} | {got['patches']}, {got['coverage']:.3f} | "
              f"{got['wall']:.1f} / {got['cpu']:.1f} s | {got['rss_mb']:.0f} MB | "
              f"{', '.join(f'{k} {v:.1f}' for k, v in top)} | {CASES[name][2]} |", flush=True)
    print(f"\nload {os.getloadavg()[0]:.2f} at the end")


if __name__ == "__main__":
    main()
