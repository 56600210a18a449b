"""Sweep detection over the issue's fixture matrix (issue 11, sec. 3). Prints a table; not a test.

Every general-sweep fixture (the base moulding along the cubic with 120 deg of twist, the letter G
along it, the double translational arch) in every variant the issue names: clean, normal noise
sigma 1e-4 / 5e-4 / 1e-3 (of the bounding-box diameter 1), remeshed (irregular triangles, vertices
on the surface), with a hole, decimated to 6000 triangles; and the kinematic ones (revolved 300 deg,
extruded) clean, noisy, holed and decimated. ``detect`` runs at eps_prox = 0.005 (the tests' value)
with the defaults otherwise. Columns: coverage of the area (targets >= 0.95 clean, >= 0.85 noisy) and
the per-face figure beside it (a face counted only when one patch holds its three corners), plane recall
(true profile planes within 2 deg and 0.005 found, of the general ones: >= 0.95 clean, >= 0.85 at
5e-4), the axis / direction error of the kinematic ones (<= 0.2 deg), the largest patch fit error,
the patches kept and the time of ``detect`` (one run, on a shared machine: not a benchmark).

The tests in tests/sweeps assert the rows they cover; this script shows the whole matrix.

The group ``members`` (docs/sweeps.md, "Microarch members") runs the project's own members: bundled
networks' members swept in the ``bar`` look (``sweeps.fixtures.swept_members``), whose profile and
motion are known exactly, with ``SweepParams.with_scale(0.25)`` and 2000 match runs; columns then add
the profile's Hausdorff distance and the median rotation / translation errors of the motions
(``sweeps.fixtures.sweep_errors``; targets <= 1e-3, <= 0.5 deg, <= 1e-3).

Usage: python benchmarks/eval_sweeps.py [--only NAME[,NAME]] [--markdown]
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import time
from typing import Callable

import numpy as np

from auszug.sweeps import DEFAULT, detect
from auszug.sweeps.fixtures import (
    Fixture,
    decimated,
    double_translational,
    extruded,
    letter_g_along_cubic,
    moulding_along_cubic,
    revolved,
    with_hole,
)
from auszug.sweeps.general import motion_planes
from auszug.sweeps.planes import plane_recall

EPS_PROX = 0.005
NOISE = (1e-4, 5e-4, 1e-3)

Maker = Callable[..., Fixture]


def _variants(name: str, make: Maker, remesh: Maker | None) -> list[tuple[str, Callable[[], Fixture]]]:
    out: list[tuple[str, Callable[[], Fixture]]] = [(f"{name}", lambda: make())]
    out += [(f"{name}, sigma {s:g}", lambda s=s: make(sigma=s)) for s in NOISE]
    if remesh is not None:
        out.append((f"{name}, remeshed", remesh))
        out.append((f"{name}, remeshed, sigma 5e-4", lambda: remesh(sigma=5e-4)))
    out.append((f"{name}, hole", lambda: with_hole(make())))
    out.append((f"{name}, hole, sigma 5e-4", lambda: with_hole(make(sigma=5e-4))))
    out.append((f"{name}, decimated 6000", lambda: decimated(make(), 6000)))
    out.append((f"{name}, decimated 6000, sigma 5e-4", lambda: decimated(make(sigma=5e-4), 6000)))
    return out


def cases() -> list[tuple[str, str, Callable[[], Fixture]]]:
    """(group, row label, fixture maker) for every row of the matrix."""
    rows: list[tuple[str, str, Callable[[], Fixture]]] = []
    for group, make, remesh in (
        ("cubic", moulding_along_cubic, lambda **kw: moulding_along_cubic(jitter=0.4, **kw)),
        ("letter_g", letter_g_along_cubic, None),
        ("double_translational", double_translational, None),
        ("revolved", revolved, None),
        ("extruded", extruded, None),
    ):
        rows += [(group, label, mk) for label, mk in _variants(group, make, remesh)]
    return rows


def _angle(a: np.ndarray, b: np.ndarray) -> float:
    c = abs(float(np.dot(a, b)) / (np.linalg.norm(a) * np.linalg.norm(b)))
    return math.degrees(math.acos(min(1.0, float(c))))


def evaluate(fx: Fixture) -> dict[str, float | int | str]:
    t0 = time.perf_counter()
    r = detect((fx.vertices, fx.faces), DEFAULT.with_(eps_prox=EPS_PROX))
    dt = time.perf_counter() - t0
    out: dict[str, float | int | str] = {"coverage": r.coverage, "patches": len(r.patches), "seconds": dt,
                                         "faces": r.face_coverage if r.face_coverage is not None else float("nan"),
                                         "fit": max((p.fit_error for p in r.patches), default=float("nan")),
                                         "recall": float("nan"), "axis": float("nan"),
                                         "kinds": ",".join(sorted({p.kind for p in r.patches})) or "-"}
    if len(fx.planes) and r.patches:
        normals, offsets = [], []
        for p in r.patches:
            if fx.name.startswith("double_translational"):
                # the profile's own best-fit plane carried by the motion (as tests/sweeps/
                # test_translational.py): for a translation along a curved path the profile planes
                # are x = const, not the planes across the path
                o = p.profile.mean(axis=0)
                n = np.linalg.svd(p.profile - o)[2][2]
                rot, tr = p.motion.at(np.linspace(*p.motion.domain, 8 * len(p.motion)))
                nt = rot @ n
                normals.append(nt)
                offsets.append(np.einsum("ij,ij->i", nt, rot @ o + tr))
            else:   # the sweep's profile planes, as tests/sweeps/test_more_fixtures.py
                nn, dd = motion_planes(p.profile, p.motion, 8)
                normals.append(nn)
                offsets.append(dd)
        out["recall"] = plane_recall(fx.planes, np.vstack(normals), np.concatenate(offsets))
    elif len(fx.planes):
        out["recall"] = 0.0
    if fx.axis_direction is not None and r.patches:
        # the axis of the patch of most coverage, from its motion's last map: the rotation's axis,
        # or the translation's direction
        from scipy.spatial.transform import Rotation

        best = max(r.patches, key=lambda p: p.coverage)
        rot, tr = best.motion.rotation[-1], best.motion.translation[-1]
        rv = Rotation.from_matrix(rot).as_rotvec()
        ax = rv if np.linalg.norm(rv) > 1e-3 else tr
        out["axis"] = _angle(np.asarray(ax, float), np.asarray(fx.axis_direction, float))
    return out


#: (row label, bundled drawing, member indices or None for all, sigma, eps_prox) of the group ``members``.
MEMBERS: tuple[tuple[str, str, tuple[int, ...] | None, float, float], ...] = (
    ("U.XI.30, 1 member", "legacy/U.XI.30.uc", None, 0.0, 0.005),
    ("U.XI.30, 1 member, eps 0.002", "legacy/U.XI.30.uc", None, 0.0, 0.002),
    ("U.XI.30, 1 member, sigma 5e-4", "legacy/U.XI.30.uc", None, 5e-4, 0.005),
    ("U.XI.30, 1 member, sigma 5e-4, eps 0.002", "legacy/U.XI.30.uc", None, 5e-4, 0.002),
    ("tn-2, 1 member", "teaching-sheet/tn-2.uc", None, 0.0, 0.005),
    ("tn-2, 1 member, eps 0.002", "teaching-sheet/tn-2.uc", None, 0.0, 0.002),
    ("tn-2, 1 member, sigma 5e-4", "teaching-sheet/tn-2.uc", None, 5e-4, 0.005),
    ("tn-2, 1 member, sigma 5e-4, eps 0.002", "teaching-sheet/tn-2.uc", None, 5e-4, 0.002),
    ("U.XI.29, 2 members", "web/U.XI.29.uc", None, 0.0, 0.005),
    ("U.XI.91, 4 members", "web/U.XI.91.uc", None, 0.0, 0.005),
)
MEMBER_SCALE, MEMBER_RUNS = 0.25, 2000


def evaluate_members(drawing: str, members: tuple[int, ...] | None, sigma: float,
                     eps: float) -> dict[str, float | int | str]:
    """One row of the group ``members``: detect on the swept members, errors against their truth."""
    from auszug import examples
    from auszug.formats import load
    from auszug.microarch import build
    from auszug.sweeps.fixtures import sweep_errors, swept_members

    fx = swept_members(build(load(examples.path(drawing))), members, sigma=sigma)
    params = DEFAULT.with_(eps_prox=eps, max_match_runs=MEMBER_RUNS).with_scale(MEMBER_SCALE)
    t0 = time.perf_counter()
    r = detect((fx.vertices, fx.faces), params)
    dt = time.perf_counter() - t0
    e = sweep_errors(r, fx)

    def worst(a: np.ndarray) -> float:
        return float(a.max()) if len(a) else float("nan")

    return {"coverage": r.coverage, "recall": e.recall, "hausdorff": worst(e.hausdorff),
            "rotation": e.median_rotation, "translation": e.median_translation, "patches": len(r.patches),
            "fit": max((p.fit_error for p in r.patches), default=float("nan")), "seconds": dt,
            "vertices": len(fx.vertices)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--only", default=None, help="comma-separated groups (cubic, letter_g, double_translational, "
                                                 "revolved, extruded, members)")
    ap.add_argument("--markdown", action="store_true", help="a markdown table")
    args = ap.parse_args()
    want = None if args.only is None else set(args.only.split(","))
    load0 = os.getloadavg()[0]
    print(f"# eval_sweeps: Python {platform.python_version()}, {os.cpu_count()} cores, "
          f"load average {load0:.1f} at the start, eps_prox {EPS_PROX}")
    head = ["fixture", "coverage", "whole faces", "plane recall", "axis (deg)", "fit error", "patches", "kinds",
            "detect (s)"]
    if args.markdown and (want is None or want - {"members"}):
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
    for group, label, mk in cases():
        if want is not None and group not in want:
            continue
        res = evaluate(mk())

        def f(v: object, fmt: str) -> str:
            return "-" if isinstance(v, float) and math.isnan(v) else format(v, fmt)

        cells = [label, f(res["coverage"], ".3f"), f(res["faces"], ".3f"), f(res["recall"], ".2f"),
                 f(res["axis"], ".3f"), f(res["fit"], ".1e"), str(res["patches"]), str(res["kinds"]),
                 f(res["seconds"], ".1f")]
        print(("| " + " | ".join(cells) + " |") if args.markdown else "  ".join(cells), flush=True)
    if want is None or "members" in want:
        head = ["members", "vertices", "coverage", "plane recall", "profile Hausdorff (worst)",
                "rotation (deg, median)", "translation (median)", "fit error", "patches", "detect (s)"]
        print(f"# members: with_scale({MEMBER_SCALE}), max_match_runs {MEMBER_RUNS}")
        if args.markdown:
            print("| " + " | ".join(head) + " |")
            print("|" + "---|" * len(head))
        for label, drawing, members, sigma, eps in MEMBERS:
            m = evaluate_members(drawing, members, sigma, eps)
            cells = [label, str(m["vertices"]), f"{m['coverage']:.3f}", f"{m['recall']:.2f}", f"{m['hausdorff']:.1e}",
                     f"{m['rotation']:.2f}", f"{m['translation']:.1e}", f"{m['fit']:.1e}", str(m["patches"]),
                     f"{m['seconds']:.1f}"]
            print(("| " + " | ".join(cells) + " |") if args.markdown else "  ".join(cells), flush=True)
    print(f"# load average {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
