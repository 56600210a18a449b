"""Sweep detection speed (issue 11, sec. 4) beside the paper's Fig. 15. Prints a table; not a test.

The paper's row for Fig. 12 (3.33 GHz desktop): 32k vertices, 1452 initial planes, g = 1 %,
3 refinement rounds: 286 s to cut and weigh (T_ini), 234 s to match (T_match). The goal is 20x
faster on this machine: 14.3 s and 11.7 s.

1. Cut and weigh: the whole plane search (initial planes, then the refinement rounds, every cut
   through Alg. 1) on the general-sweep fixture at ~32k vertices, initial planes ~1452 (the offset
   spacing is chosen to give that count), g = 1 %, 3 rounds.
2. Match: curvature plots of the good runs, all pairs within 25 degrees matched, families; and the
   same for the 167 lowest-energy runs (the paper's N_match), for a like-for-like time.
3. Build the sweeps (sec. 2.3): from the initial planes' cuts, match every movable run, order the
   ribs of the ``--families`` families of most support and fit each a general sweep (Eq. 7
   velocities, Hermite interpolation, projection to rigid motions, profile improvement, 3 rounds
   of re-slicing, the fit check with exact closest points on the mesh), not grown. The paper optimised
   N_opt = 152 sweeps in T_opt = 86 s (0.57 s each); we compare per sweep. Then the same with
   growing (the default: the first family grows over the mesh, the others are skipped), and the
   whole ``detect``.
4. Scaling of cut + weigh in vertices x planes (fixed planes, 4 mesh sizes; fixed mesh, 3 plane
   counts): time per (vertex x plane) should stay flat.

Times are the minimum of ``--reps`` in-process runs after a warm-up run (numba compiles, or
loads its on-disk cache, on the first call).

With ``--build-only`` only row 3 (not grown) runs: the motion stage ``--reps`` times (after a
warm-up), printing each run's wall and CPU time (``time.process_time``, all threads) per sweep and
their medians; the machine is shared, so compare old and new code in the same minutes. The mesh's
closest-point tree is built once per mesh (by the warm-up's stage, then shared): its build is
timed apart and printed beside the stage, and the median with it shared out over the sweeps.

Usage: python benchmarks/bench_sweeps.py [--reps N] [--quick] [--build-only]
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np

from auszug.sweeps import (
    DEFAULT,
    curvature_plots,
    cut,
    families,
    initial_planes,
    match_cuts,
    movability,
    normalise,
    search_planes,
)
from auszug.sweeps.fixtures import moulding_along_cubic


def best_of(fn, reps):
    fn()
    ts = []
    out = None
    for _ in range(reps):
        t0 = time.perf_counter()
        out = fn()
        ts.append(time.perf_counter() - t0)
    return min(ts), out


def spacing_for(vertices, frequency, target):
    lo, hi = 0.005, 0.5
    for _ in range(40):
        mid = (lo * hi) ** 0.5
        n = len(initial_planes(vertices, frequency, mid)[1])
        lo, hi = (mid, hi) if n > target else (lo, mid)
    return hi


def build_only(mesh, params, spacing, n_families, reps):
    """Row 3 alone, twice: the paper's stages (``twist_steps`` 0) and with the motion's refinement against the
    mesh (beyond the paper, sweeps-members3; the default), each by :func:`_build_only`."""
    for label, steps in (("the paper's stages (twist_steps 0)", 0),
                         (f"with the motion's refinement (twist_steps {params.twist_steps}, beyond the paper)",
                          params.twist_steps)):
        print(f"-- build, {label}", flush=True)
        _build_only(mesh, params.with_(twist_steps=steps), spacing, n_families, reps)


def _build_only(mesh, params, spacing, n_families, reps):
    """Row 3 alone: the motion stage of ``general_stages`` (not grown), ``reps`` timed runs after a warm-up.

    The mesh's closest-point tree (``MeshTree.of``) is built once per mesh, by the first stage that
    queries the mesh (here the warm-up's motion stage), and shared by every later stage on that mesh:
    the timed runs do not build it. Its build is timed on its own in each run (``MeshTree.built``,
    a new tree: its fine and coarse face grids, which every closest-point query and the motion's
    refinement search) and reported beside the stage, and added to it shared out over the run's sweeps.
    """
    from auszug.sweeps.general import general_stages
    from auszug.sweeps.patches import MeshTree

    c0 = cut(mesh, *initial_planes(mesh.vertices, params.sphere_frequency, spacing))
    mv0 = movability(c0, params)
    pb = params.with_(max_families=n_families, eps_prox=0.005, grow=False)
    cpu0 = {}

    def step(name):
        if name == "motion":
            cpu0["t"] = time.process_time()
        return time.perf_counter()

    general_stages(mesh, c0, mv0, pb, step)
    walls, cpus, tree_walls, tree_cpus, n = [], [], [], [], 0
    for _ in range(reps):
        pats, stages = general_stages(mesh, c0, mv0, pb, step)
        cpu = time.process_time() - cpu0["t"]
        t0, c0_ = time.perf_counter(), time.process_time()
        MeshTree.built(mesh)            # its face grids (the refinement's too), built once per mesh
        tree_walls.append(time.perf_counter() - t0)
        tree_cpus.append(time.process_time() - c0_)
        n = max(len(pats), 1)
        walls.append(stages[-1].seconds / n)
        cpus.append(cpu / n)
        print(f"build: {len(pats)} sweeps, {stages[-1].seconds:.3f} s wall ({walls[-1]:.4f} s each), "
              f"{cpu:.3f} s CPU ({cpus[-1]:.4f} s each); the mesh's tree (once per mesh, not in the stage) "
              f"{tree_walls[-1]:.3f} s wall, {tree_cpus[-1]:.3f} s CPU; load {os.getloadavg()[0]:.2f}", flush=True)
    w, c = float(np.median(walls)), float(np.median(cpus))
    tw, tc = float(np.median(tree_walls)), float(np.median(tree_cpus))
    print(f"median per sweep: {w:.4f} s wall, {c:.4f} s CPU "
          f"({0.566 / w:.1f}x the paper's 0.566 s by wall clock; goal 20x: 0.0283 s); "
          f"the mesh's tree {tw:.4f} s wall, {tc:.4f} s CPU once per mesh: with it shared out over the {n} sweeps "
          f"{w + tw / n:.4f} s wall, {c + tc / n:.4f} s CPU ({0.566 / (w + tw / n):.1f}x by wall clock); "
          f"fit errors {', '.join(f'{p.fit_error:.3e}' for p in pats)}; "
          f"coverage {', '.join(f'{p.coverage:.4f}' for p in pats)}")


def preprocessing(fx, reps):
    """The paper's "pre-proc" column (Fig. 15: Fig. 12's row, 32k vertices, 0.6 s), our work once per mesh.

    :func:`normalise` (validation, centring and scaling, edge topology, vertex normals), the closest-point
    tree (``MeshTree.built``: its fine and coarse face grids, the fine one the motion refinement's too, since
    sweeps-tree4) and ``MeshTree.face_grid`` (then already built: ~0 s): each timed in ``reps`` runs (after a
    warm-up run), medians of wall and CPU time. Returns the median total wall time and the row's text.
    """
    from auszug.sweeps.patches import MeshTree

    def once():
        t = [time.perf_counter(), time.process_time()]
        m = normalise(fx.vertices, fx.faces)
        t += [time.perf_counter(), time.process_time()]
        tree = MeshTree.built(m)
        t += [time.perf_counter(), time.process_time()]
        tree.face_grid()
        t += [time.perf_counter(), time.process_time()]
        return np.diff(np.array(t).reshape(4, 2), axis=0)       # (3 parts, wall / CPU)

    once()
    runs = np.array([once() for _ in range(max(1, reps))])
    med = np.median(runs, axis=0)
    total = float(med[:, 0].sum())
    text = (f"| preprocessing, once per mesh (normalise {med[0, 0]:.4f} s, closest-point tree {med[1, 0]:.4f} s, "
            f"face grid {med[2, 0]:.4f} s wall; CPU {med[:, 1].sum():.4f} s) | 0.6 s (pre-proc, 32k vertices) | "
            f"{total:.4f} s | {0.6 / total:.0f}x | 20x |")
    return total, text


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="8k vertices instead of 32k")
    ap.add_argument("--families", type=int, default=24, help="sweeps to build in row 3 (default 24)")
    ap.add_argument("--build-only", action="store_true",
                    help="time only the build (row 3, not grown): --reps runs, each and the median")
    args = ap.parse_args(argv)
    n_prof, n_path = (64, 128) if args.quick else (128, 256)
    fx = moulding_along_cubic(n_profile=n_prof, n_path=n_path, sigma=5e-4)
    mesh = normalise(fx.vertices, fx.faces)
    spacing = spacing_for(mesh.vertices, DEFAULT.sphere_frequency, 1452)
    params = DEFAULT.with_(offset_spacing=spacing, percentile=1.0, refinements=3)
    n_ini = len(initial_planes(mesh.vertices, params.sphere_frequency, spacing)[1])
    if args.build_only:
        build_only(mesh, params, spacing, args.families, args.reps)
        print("| stage | paper | auszug (median) | speed-up | goal |\n|---|---|---|---|---|")
        print(preprocessing(fx, args.reps)[1] + f" load {os.getloadavg()[0]:.2f}")
        return
    print(f"machine: {platform.machine()}, {os.cpu_count()} cores (shared), load {os.getloadavg()[0]:.1f}; "
          f"numba threads {os.environ.get('NUMBA_NUM_THREADS', 'default')}")
    print(f"mesh: general sweep (cubic path, 120 deg twist, sigma 5e-4), {mesh.n_vertices} vertices, "
          f"{len(mesh.faces)} faces")

    t_ini, search = best_of(lambda: search_planes(mesh, params), args.reps)
    good = search.good_runs

    def match():
        plots = curvature_plots(search.cuts, search.movability, good, params)
        m = match_cuts(plots, params)
        return plots, m, families(m, params)

    t_match, (plots, m, fams) = best_of(match, args.reps)
    # the paper matched 167 curves: the same number of our lowest-energy runs, for a like-for-like time
    top = np.argsort(search.movability.run_energy, kind="stable")[:167]

    def match_top():
        pl = curvature_plots(search.cuts, search.movability, top, params)
        mm = match_cuts(pl, params)
        return pl, mm, families(mm, params)

    t_top, (plots2, m2, fams2) = best_of(match_top, args.reps)
    print()
    print("| stage | paper (Fig. 15, Fig. 12 row) | auszug | speed-up | goal |")
    print("|---|---|---|---|---|")
    print(preprocessing(fx, args.reps)[1])
    print(f"| cut and weigh (T_ini): {n_ini} initial planes, g = 1 %, 3 rounds, {search.n_planes} planes cut "
          f"in all, {search.cuts.n_curves} curves | 286 s (1452 initial) | {t_ini:.2f} s | {286 / t_ini:.0f}x | 20x |")
    print(f"| match (T_match): {plots.n_runs} good runs, {m.tested} pairs within 25 deg, {m.n_matches} matched, "
          f"{len(fams)} families | 234 s (N_match 167, 536 families) | {t_match:.2f} s | {234 / t_match:.0f}x | 20x |")
    print(f"| match, the paper's N_match: the {plots2.n_runs} lowest-energy runs, {m2.tested} pairs within 25 deg, "
          f"{m2.n_matches} matched, {len(fams2)} families | 234 s | {t_top:.2f} s | {234 / t_top:.0f}x | 20x |")
    print(f"rounds: {search.rounds}")

    from auszug.sweeps import detect
    from auszug.sweeps.general import general_stages

    c0 = cut(mesh, *initial_planes(mesh.vertices, params.sphere_frequency, spacing))
    mv0 = movability(c0, params)
    # per sweep like the paper's N_opt: every family fitted, none grown (growing makes one family cover the
    # mesh and skips the rest; its own row follows)
    pb = params.with_(max_families=args.families, eps_prox=0.005, grow=False)
    t_build, (pats, stages) = best_of(lambda: general_stages(mesh, c0, mv0, pb, lambda name: time.perf_counter()),
                                      max(1, args.reps - 2))
    t_motion = stages[-1].seconds
    each = t_motion / max(len(pats), 1)
    print(f"| build the sweeps (sec. 2.3): {len(pats)} families fitted (Eq. 7, Hermite, 3 rounds of re-slicing, "
          f"fit check), fit errors {min(p.fit_error for p in pats):.1e}-{max(p.fit_error for p in pats):.1e} | "
          f"86 s for N_opt = 152 (0.57 s each) | {t_motion:.2f} s ({each:.3f} s each) | {0.566 / each:.2f}x per sweep "
          f"| 20x |")
    from auszug.sweeps.patches import MeshTree

    t_tree, _ = best_of(lambda: MeshTree.built(mesh), max(1, args.reps - 2))
    with_tree = (t_motion + t_tree) / max(len(pats), 1)
    print(f"| the mesh's closest-point tree, built once per mesh (by the warm-up's build above, then shared; not in "
          f"the row above) | | {t_tree:.3f} s ({with_tree:.3f} s per sweep with it) | | |")
    print(f"| match + families + build from the initial cuts ({stages[0].numbers['runs']} runs, "
          f"{stages[0].numbers['pairs']} pairs) | 234 + 86 s | {t_build:.2f} s | {(234 + 86) / t_build:.0f}x | 20x |")
    t_grow, (gpats, gstages) = best_of(
        lambda: general_stages(mesh, c0, mv0, pb.with_(grow=True), lambda name: time.perf_counter()), 1)
    skipped = gstages[-1].summary.split(" families on grown patches skipped")[0].rsplit("(", 1)[-1]
    print(f"| build, grown (the default): {len(gpats)} sweep(s) fitted and grown, {skipped} families skipped; "
          f"fit errors "
          f"{', '.join(f'{p.fit_error:.1e}' for p in gpats)}, coverage {max(p.coverage for p in gpats):.3f} | "
          f"86 s | {gstages[-1].seconds:.2f} s | | |")
    t_all, rep = best_of(lambda: detect(mesh, params.with_(eps_prox=0.005)), 1)
    print(f"| whole detect (defaults, eps_prox 0.005): {len(rep.patches)} patches, coverage {rep.coverage:.3f} | "
          f"606 s (286 + 234 + 86) | {t_all:.2f} s | {606 / t_all:.0f}x | |")

    print()
    print("scaling of cut + weigh (one pass, no refinement):")
    print("| vertices | planes | seconds | ns per vertex x plane |")
    print("|---|---|---|---|")
    sizes = [(32, 64), (64, 128), (128, 256)] + ([] if args.quick else [(256, 512)])
    n0, d0 = initial_planes(mesh.vertices, params.sphere_frequency, spacing)
    for a, b in sizes:
        f2 = moulding_along_cubic(n_profile=a, n_path=b, sigma=5e-4)
        m2 = normalise(f2.vertices, f2.faces)
        t, _ = best_of(lambda m2=m2: movability(cut(m2, n0, d0), params), args.reps)
        print(f"| {m2.n_vertices} | {len(d0)} | {t:.3f} | {t / (m2.n_vertices * len(d0)) * 1e9:.1f} |")
    for k in (2, 4):
        shifts = np.tile(np.linspace(0, spacing, k, endpoint=False), len(d0))
        nk, dk = np.repeat(n0, k, axis=0), np.repeat(d0, k) + shifts
        t, _ = best_of(lambda nk=nk, dk=dk: movability(cut(mesh, nk, dk), params), args.reps)
        print(f"| {mesh.n_vertices} | {len(dk)} | {t:.3f} | {t / (mesh.n_vertices * len(dk)) * 1e9:.1f} |")


if __name__ == "__main__":
    main()
