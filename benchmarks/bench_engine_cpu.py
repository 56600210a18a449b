"""Point-drag CPU time per drawing, for comparing two versions of the engine on a loaded machine.

The same edit as `bench_engine.py` (the end point of curve 0 moved to a fresh value every
repetition, then a full `build`), timed with `time.process_time` (the process's own CPU time,
less disturbed than wall-clock time by other jobs) and wall-clock time. Prints one line per
drawing: median and fastest of each. To compare with another checkout, run it there too, e.g.
`PYTHONPATH=../other/src python benchmarks/bench_engine_cpu.py DIR`, alternating the two.

Usage: python benchmarks/bench_engine_cpu.py [DIR (default: the bundled examples)] [--reps N]
"""

from __future__ import annotations

import argparse
import statistics
import time
from importlib.resources import files
from pathlib import Path

from auszug.formats import load
from auszug.microarch import build, edit


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("corpus", nargs="?", type=Path, default=Path(str(files("auszug.examples"))))
    ap.add_argument("--reps", type=int, default=30)
    a = ap.parse_args(argv)
    for f in sorted(a.corpus.rglob("*.uc")):
        d = load(f)
        c = d.curves[0]
        x, y = c.vertices[-1]
        size = max(1e-9, max(abs(v) for cc in d.curves for p in cc.vertices for v in p))

        def moved(k: int, d=d, c=c, x=x, y=y, size=size):
            return edit.move_vertex(d, 0, len(c.vertices) - 1, (x + 1e-5 * size * (k + 1), y))

        for k in range(5):   # warm up the unedited curves' caches, values never used again
            build(moved(a.reps + 10 + k))
        cpu, wall = [], []
        for k in range(a.reps):
            dd = moved(k)
            c0, w0 = time.process_time(), time.perf_counter()
            build(dd)
            cpu.append(time.process_time() - c0)
            wall.append(time.perf_counter() - w0)
        print(f"{f.relative_to(a.corpus)}: cpu median {statistics.median(cpu) * 1e3:.2f} min {min(cpu) * 1e3:.2f} "
              f"| wall median {statistics.median(wall) * 1e3:.2f} min {min(wall) * 1e3:.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
