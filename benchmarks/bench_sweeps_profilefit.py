"""Profiles fitted with exact lines and arcs (beyond the paper): pieces, radii, Hausdorff, time. Not a test.

The base moulding of ``auszug.sweeps.fixtures`` is 6 lines and 3 arcs (radii 0.04, 0.0358, 0.025
before normalisation). For the sampled profile itself and for the patch ``detect`` finds on the
extruded, revolved and helical fixtures (clean and noisy), print the pieces found, the largest
radius error (bounding-box diameters), the fit's Hausdorff distance to the polyline and the time
of the fit alone (``fit_profile`` on the normalised patch profile, best of 3).

Usage: python benchmarks/bench_sweeps_profilefit.py [--tolerance T]
"""

from __future__ import annotations

import argparse
import os
import platform
import time

import numpy as np

from auszug.sweeps import DEFAULT, detect, fit_lines_arcs, fit_profile
from auszug.sweeps.fixtures import extruded, gothic_base_profile, helical, revolved

KINDS = ("line", "line", "arc", "line", "arc", "line", "arc", "line", "line")
RADII = np.array([0.04, np.hypot(0.02, 0.06) / (2 * np.sin(2 * np.arctan(0.6))), 0.025])


def _radii(profile):
    pts, b = profile.points, profile.bulges
    return [float(np.linalg.norm(pts[(i + 1) % len(pts)] - pts[i]) * (1 + g * g) / (4 * abs(g)))
            for i, g in enumerate(b) if g]


def _row(label, fit, scale, seconds):
    if fit is None:
        print(f"| {label} | no fit within the tolerance | | | | {seconds * 1e3:.1f} |")
        return
    kinds = tuple("arc" if g else "line" for g in fit.profile.bulges)
    r = _radii(fit.profile)
    ok = kinds in (KINDS, KINDS[::-1])
    err = float(np.max(np.abs(np.array(r if kinds == KINDS else r[::-1]) - scale * RADII))) if ok else float("nan")
    print(f"| {label} | {kinds.count('line')} lines + {kinds.count('arc')} arcs | {'yes' if ok else 'no'} | "
          f"{err:.2e} | {fit.hausdorff:.2e} | {seconds * 1e3:.1f} |")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tolerance", type=float, default=DEFAULT.profile_fit_tolerance)
    a = ap.parse_args(argv)
    print(f"{platform.node()} {platform.processor() or platform.machine()}, {os.cpu_count()} cores, "
          f"{time.strftime('%Y-%m-%d')}; tolerance {a.tolerance:g} (bounding-box diameters)\n")
    print("| input | pieces | the moulding's 9 in order | max radius error | Hausdorff | fit (ms) |")
    print("|---|---|---|---|---|---|")
    for n in (40, 60, 100, 200):
        p, _ = gothic_base_profile(n)
        fit_lines_arcs(p, tolerance=a.tolerance)
        t0 = time.perf_counter()
        f = fit_lines_arcs(p, tolerance=a.tolerance)
        dt = time.perf_counter() - t0
        _row(f"sampled profile, {n} points (raw units)", f, 1.0, dt)
    makers = {"extruded": extruded, "revolved": revolved, "helical": helical}
    for name, make in makers.items():
        for sigma in (0.0, 2e-4, 1e-3):
            fx = make(sigma=sigma)
            scale = fx.profile_length / gothic_base_profile(60)[1][-1]
            r = detect((fx.vertices, fx.faces), params=DEFAULT.with_(profile_fit_tolerance=0.0))
            for p in r.patches:
                prof = (np.asarray(p.profile) - r.centre) / r.bbox_diameter
                ts = []
                for _ in range(3):
                    t0 = time.perf_counter()
                    f = fit_profile(prof, p.closed, a.tolerance)
                    ts.append(time.perf_counter() - t0)
                _row(f"{name}, sigma {sigma:g}: patch {p.id} ({len(prof)} points)", f, scale, min(ts))


if __name__ == "__main__":
    main()
