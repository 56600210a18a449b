"""Meshing speed (issue: meshes). Prints a table; not a test.

1. Sweeping every member of the 7-fold chancel (web/3d-scan-final.uc) at the
   authors' default resolution, 200 segments x 40 around, square bar and round
   tube. Target < 100 ms.
2. Re-sweeping one basic curve with all its replicas (what one edit needs),
   per basic curve of the chancel. Target < 5 ms; the authors' demo spends
   1.2-4.6 ms per edit, mostly on its meshes. Also shown: the edit, the
   network rebuild and the re-sweep together.
3. All faces of U.XI.28, converged minimal surfaces. Target < 300 ms.
4. Faces and printable solids over the whole corpus: counts, convergence,
   residuals, watertightness, volumes.

Times are the minimum and the median of repeated in-process runs after a
warm-up (other processes on the machine make the median noisy).

Usage: python benchmarks/bench_meshing.py [--corpus DIR (default: the bundled examples)] [--reps N] [--quick]
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import sys
import time
from importlib.resources import files
from pathlib import Path

import numpy as np

from auszug.errors import AuszugError
from auszug.formats import load, stl
from auszug.meshing import default_size, network_faces, profile_for, sweep_network
from auszug.meshing.solid import solid
from auszug.microarch import build, edit

from _timing import timed

#: The drawings bundled with the package (auszug.examples): the whole corpus.
DEFAULT_CORPUS = Path(str(files("auszug.examples")))


def timed_ms(fn, reps: int) -> tuple[float, float]:
    """(min, median) milliseconds of ``fn()`` over ``reps`` runs after two warm-ups."""
    t = timed(fn, reps)
    return t.min * 1e3, t.median * 1e3


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--corpus", type=Path, default=DEFAULT_CORPUS)
    ap.add_argument("--reps", type=int, default=30)
    ap.add_argument("--quick", action="store_true", help="skip the corpus-wide part")
    a = ap.parse_args(argv)
    print(f"# machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
          f"numpy {np.__version__}, {platform.platform()}; {time.strftime('%Y-%m-%d')}; "
          f"load average {os.getloadavg()[0]:.1f}\n")

    chancel = build(load(a.corpus / "web" / "3d-scan-final.uc"))
    size = default_size(chancel)
    print("| sweep (chancel, 200 x 40) | vertices | triangles | min (ms) | median (ms) | target |")
    print("|---|---|---|---|---|---|")
    for style in ("bar", "tube"):
        prof = profile_for(style, size, 40)
        m = sweep_network(chancel, prof, 200)
        lo, med = timed_ms(lambda prof=prof: sweep_network(chancel, prof, 200), a.reps)
        print(f"| all members, {style} | {m.n_vertices} | {m.n_faces} | {lo:.1f} | {med:.1f} | < 100 |")
    prof = profile_for("bar", size, 40)
    for b in range(len(chancel.drawing.curves)):
        m = sweep_network(chancel, prof, 200, basics=[b])
        lo, med = timed_ms(lambda b=b: sweep_network(chancel, prof, 200, basics=[b]), a.reps)
        print(f"| one basic curve ({b}) and its {len(m.parts)} replicas, bar | {m.n_vertices} | {m.n_faces} "
              f"| {lo:.2f} | {med:.2f} | < 5 |")
    d = chancel.drawing
    h = d.apex_height(0)

    def edit_rebuild_resweep(k=[0]):  # noqa: B006  (the default list is the call counter)
        k[0] += 1
        # a fresh height every call, as a real drag gives (no cached curve pieces to reuse)
        net = build(edit.set_apex_height(d, 0, h * (1.0 + 1e-4 * k[0])))
        return sweep_network(net, prof, 200, basics=[0])

    lo, med = timed_ms(edit_rebuild_resweep, a.reps)
    print(f"| apex drag: edit + rebuild network + re-sweep curve 0 | | | {lo:.2f} | {med:.2f} | |")

    u28 = build(load(a.corpus / "web" / "U.XI.28.uc"))
    fs = network_faces(u28)
    lo, med = timed_ms(lambda: network_faces(u28), max(5, a.reps // 3))
    tri = sum(len(f.faces) for f in fs.faces)
    print("\n| faces | loops | solves | triangles | converged | worst residual | min (ms) | median (ms) | target |")
    print("|---|---|---|---|---|---|---|---|---|")
    print(f"| U.XI.28, all faces | {len(fs.faces)} | {fs.families} | {tri} | {fs.converged} | {fs.residual:.1e} "
          f"| {lo:.0f} | {med:.0f} | < 300 |")
    if a.quick:
        return 0

    files = sorted(a.corpus.rglob("*.uc"))
    rows = []
    for f in files:
        try:
            net = build(load(f))
        except AuszugError as e:
            print(f"skip {f}: {e}", file=sys.stderr)
            continue
        t0 = time.perf_counter()
        fs = network_faces(net, resolution=64)
        t1 = time.perf_counter()
        s = solid(net, profile_for("bar", default_size(net), 4), 64, base=True)
        t2 = time.perf_counter()
        back = stl.loads(stl.dumps(s.mesh))   # float32 corners read back by position, as a printer does
        rows.append((str(f.relative_to(a.corpus)), len(fs.faces), fs.converged, fs.residual,
                     (t1 - t0) * 1e3, s.watertight and s.mesh.is_manifold, s.volume, s.components, (t2 - t1) * 1e3,
                     back.is_manifold and back.n_faces == s.mesh.n_faces))
    with_loops = [r for r in rows if r[1]]
    print(f"\n{len(rows)} corpus drawings; {len(with_loops)} have loops, {sum(r[1] for r in rows)} faces in all.")
    print("\n| corpus | result |")
    print("|---|---|")
    print(f"| faces converged | {sum(r[2] for r in rows)} of {len(rows)} drawings "
          f"(worst residual {max(r[3] for r in rows):.1e}) |")
    print(f"| faces time per drawing (64 boundary points) | median {statistics.median(r[4] for r in rows):.0f} ms, "
          f"worst {max(r[4] for r in rows):.0f} ms |")
    print(f"| solids watertight and manifold (bar, 64 segments, base plate) "
          f"| {sum(r[5] for r in rows)} of {len(rows)} |")
    print(f"| the same read back from binary STL (welded by position) | {sum(r[9] for r in rows)} of {len(rows)} |")
    print(f"| solid volumes | {min(r[6] for r in rows):.4g} to {max(r[6] for r in rows):.4g} (all > 0: "
          f"{all(r[6] > 0 for r in rows)}); one shell: {sum(r[7] == 1 for r in rows)} of {len(rows)} |")
    print(f"| solid time per drawing | median {statistics.median(r[8] for r in rows):.0f} ms, "
          f"worst {max(r[8] for r in rows):.0f} ms |")
    print("\n| drawing | faces | converged | residual | solid volume | shells |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r[0]} | {r[1]} | {r[2]} | {r[3]:.1e} | {r[6]:.5f} | {r[7]} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
