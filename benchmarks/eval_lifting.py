"""Sketch lifting against ground truth made in code (issue 12, sec. 4). Not a test: prints tables.

The truths (tests/lifting/truth.py): ``revolve`` (a vase's meridians and parallels), ``spiral``
(a helicoid's rulings and helices), ``saddle`` (lines of curvature of Enneper's surface), ``wrinkle``
(an inflected extrusion), ``cross`` (a rib-vaulted square bay) and ``turret`` (the negative case: a
hexagonal prism with 120 deg corners). Each is projected orthographically, its occlusion markers and
the true label of every cue candidate derived from the 3D truth; views that ``truth.accidental``
flags are rejected (and counted).

Measured per lift: depth RMSE relative to the diagonal after the best depth offset and sign
(``truth.depth_rmse``), the sign, convergence, precision / recall / F1 of the applied cues per class
against the true labels, and the largest residual angle of the applied cues per class on the final
network (degrees): smooth-crossing orthogonality (hard), corner orthogonality (hard), planarity (the
last class: its last round's applied cues held by ``LiftParams.final_hold``, on by default since lift-hold3,
docs/lifting.md), parallelism (soft by design) and any applied cue of any class.

Usage (from the repository root)::

    python -m benchmarks.eval_lifting noise [--truths a,b] [--cues default|none] [--markdown]
    python -m benchmarks.eval_lifting views [--truths a,b] [--cues none|default] [--tilts 45,55,65]
    python -m benchmarks.eval_lifting signs [--cues none|default] [--tilts 45,55,65]
    python -m benchmarks.eval_lifting energy [--truths a,b]
    python -m benchmarks.eval_lifting hand [--seeds 0,1,2,3,4,5] [--params k=v,...]
    python -m benchmarks.eval_lifting bay [--bays tn-3,tn-4] [--params k=v,...]

``--params k=v,...`` lifts with those :class:`~auszug.lifting.LiftParams` fields (noise, views and signs modes),
e.g. ``--params parallel_robust_deg=5,w_depth_anchor=10`` (branch lift-energy, docs/lifting.md; with
``robust_max_move=0.12`` the trust bound on its reweighting, branch lift-robust3),
``--params parallel_confirm=1`` (the consistency check of the parallel cues, branch lift-cues2),
``--params parallel_foreshorten=1`` (the foreshortening bound on the parallel candidates, branch lift-parallel) or
``--params sign_plane_weight=0`` (the depth sign by the control-polygon edges alone, the rule before lift-sign2).

``signs``: the depth-sign grid of docs/lifting.md (the bundled examples' objects, the box and the revolve; 3 tilts
x 4 turns, no view rejected), wrong signs and depth RMSE per object.

``hand``: the bundled examples' objects (vase, ogee roof, arches) drawn by hand
(``make_sketches.hand_drawn``, seed 0 is the shipped drawing; a seed whose hand lost or made a crossing is
refused), depth RMSE and sign of the baseline and of the default cues against each drawing's truth (docs/lifting.md,
"The example sketches lifted").

``bay``: the negative case of the project's own square bays (``truth.bay_chains``: the microarchitecture network
of a teaching-sheet drawing, whose ribs cross at equal heights at 39-53 deg, not orthogonally as the method assumes
of a smooth crossing) over the views grid, views rejected for any reason but that one; depth RMSE and wrong signs of
the default cues and of the baseline, the crossings' 3D angle in the truth and the largest deviation from 90 deg of
the lifted smooth crossings.

``energy`` (branch lift-acc): the baseline energy term by term (accuracy, minimal variation,
foreshortening, soft parallelism) at the truth, at the baseline lift, and at the minimum of the
truth's own basin (the baseline solved from the truth), with and without the soft parallelism
(``w_p_baseline = 0``): whether a large error is the energy's (the lift's minimum is lower than the
truth's basin) or the seeding's (the truth's basin is lower and the seeds miss it).
"""

from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np

from auszug.cli.lift import parse_params
from auszug.errors import GeometryError
from auszug.lifting import DEFAULT, DEFAULT_CLASSES, LiftParams, lift
from tests.lifting import truth as T

NOISES = (0.0, 0.005, 0.01)
SEEDS = (0, 1, 2)
TILTS = (15.0, 20.0, 25.0, 30.0, 35.0)
TURNS = tuple(float(t) for t in range(-50, 51, 10))


def evaluate(tr: T.Truth, classes: tuple[str, ...], params: LiftParams = DEFAULT) -> dict:
    """One lift of a truth's sketch, scored against the truth."""
    try:
        lab = T.labels(tr)
        t0 = time.perf_counter()
        r = lift(tr.sketch, params=params, classes=classes)
        sec = time.perf_counter() - t0
    except GeometryError as e:       # refused, e.g. noise left no smooth crossing to start from
        return {"refused": str(e).split(":")[0]}
    err, sign = T.depth_rmse(tr, r)
    scores = T.cue_scores(r, lab)
    worst = {k: max((c.angle for c in r.cues if c.applied and c.kind == k), default=0.0)
             for k in ("smooth-orthogonal", "orthogonal", "planar", "parallel")}
    worst["any"] = max((c.angle for c in r.cues if c.applied), default=0.0)
    return {"err": err, "sign": sign, "converged": r.converged, "seconds": sec, "scores": scores, "worst": worst,
            "classes": classes}


def _fmt_err(e: dict) -> str:
    if "refused" in e:
        return "refused"
    return f"{100 * e['err']:.2f}{'' if e['converged'] else ' !'}{'' if e['sign'] == 1 else ' (-)'}"


def _f1(rows: list[dict], k: str) -> str:
    if not any(r["classes"] and k in r["classes"] for r in rows):
        return "-"
    tp = sum(r["scores"][k][0] for r in rows if k in r["scores"])
    na = sum(r["scores"][k][1] for r in rows if k in r["scores"])
    nt = sum(r["scores"][k][2] for r in rows if k in r["scores"])
    if not na + nt:
        return "-"
    p = tp / na if na else 1.0
    rc = tp / nt if nt else 1.0
    return f"{2 * tp / (na + nt):.2f} (P {p:.2f}, R {rc:.2f}; {tp}/{na}/{nt})"


def _worst(rows: list[dict]) -> str:
    return ", ".join(f"{max((r['worst'][k] for r in rows), default=0.0):.2g}"
                     for k in ("smooth-orthogonal", "orthogonal", "planar", "parallel", "any"))


def noise_table(names: list[str], classes: tuple[str, ...], out, params: LiftParams = DEFAULT) -> None:
    """Depth RMSE at noise 0, 0.5 %, 1 % (3 seeds) at each truth's own view, and cue scores."""
    print("| truth | view | depth spread | no noise | 0.5 % noise | 1 % noise | 1 % / none (worst) | "
          "F1 parallel (tp/applied/true) | F1 corner orthogonal | F1 planar | largest applied angle (deg): smooth, "
          "corner, planar, parallel | s per lift |", file=out)
    print("|---|---|---|---|---|---|---|---|---|---|---|---|", file=out)
    for name in names:
        rows: list[dict] = []
        cells = []
        for noise in NOISES:
            seeds = (0,) if noise == 0 else SEEDS
            es = []
            for s in seeds:
                tr = T.make(name, noise=noise, seed=s)
                e = evaluate(tr, classes, params)
                es.append(e)
                if "refused" in e:
                    print(f"# {name} noise {noise} seed {s}: refused: {e['refused']}", file=sys.stderr, flush=True)
                    continue
                rows.append(e)
                print(f"# {name} noise {noise} seed {s}: {_fmt_err(e)} % {e['scores']} "
                      f"worst applied {e['worst']} {e['seconds']:.1f} s", file=sys.stderr, flush=True)
            cells.append(", ".join(_fmt_err(e) for e in es) + " %")
            if noise == 0:
                e0 = es[0].get("err", np.nan)
            if noise == NOISES[-1]:
                ratio = max((e["err"] for e in es if "err" in e), default=np.nan) / e0
        tr0 = T.make(name)
        z = np.concatenate([c[..., 2].ravel() for c in tr0.chains3d])
        spread = float(np.std(z)) / tr0.diagonal()
        tilt, turn = T.VIEWS[name]
        secs = np.mean([r["seconds"] for r in rows]) if rows else np.nan
        print(f"| {name} | {tilt:g}, {turn:g} | {100 * spread:.1f} % | {cells[0]} | {cells[1]} | {cells[2]} | "
              f"{ratio:.2f} | {_f1(rows, 'parallel')} | {_f1(rows, 'orthogonal')} | {_f1(rows, 'planar')} | "
              f"{_worst(rows)} | {secs:.1f} |",
              file=out, flush=True)


def views_table(names: list[str], classes: tuple[str, ...], out, params: LiftParams = DEFAULT,
                tilts: tuple[float, ...] = TILTS) -> None:
    """Wrong-sign rate and depth RMSE over the grid ``tilts`` x TURNS (noise-free), accidental views rejected."""
    print("| truth | views lifted (rejected) | wrong sign | depth RMSE median / max | F1 parallel | "
          "F1 corner orthogonal | F1 planar | largest applied angle (deg): smooth, corner, planar, parallel, any | "
          "not converged |", file=out)
    print("|---|---|---|---|---|---|---|---|---|", file=out)
    total = wrong_total = 0
    for name in names:
        rows, rejected, refused, wrong = [], 0, 0, []
        for tilt in tilts:
            for turn in TURNS:
                tr = T.make(name, tilt, turn)
                why = T.accidental(tr)
                if why:
                    rejected += 1
                    print(f"# {name} {tilt:g} {turn:g}: rejected: {'; '.join(why)}", file=sys.stderr, flush=True)
                    continue
                e = evaluate(tr, classes, params)
                if "refused" in e:
                    refused += 1
                    print(f"# {name} {tilt:g} {turn:g}: refused: {e['refused']}", file=sys.stderr, flush=True)
                    continue
                rows.append(e)
                if e["sign"] != 1:
                    wrong.append(f"{tilt:g}/{turn:g} ({100 * e['err']:.1f} %)")
                print(f"# {name} {tilt:g} {turn:g}: {_fmt_err(e)} % {e['seconds']:.1f} s", file=sys.stderr, flush=True)
        errs = np.array([r["err"] for r in rows] or [np.nan])
        total += len(rows)
        wrong_total += len(wrong)
        ref = f", {refused} refused" if refused else ""
        print(f"| {name} | {len(rows)} ({rejected}{ref}) | {len(wrong)}{': ' + ', '.join(wrong) if wrong else ''} | "
              f"{100 * np.median(errs):.2f} / {100 * errs.max():.2f} % | {_f1(rows, 'parallel')} | "
              f"{_f1(rows, 'orthogonal')} | {_f1(rows, 'planar')} | {_worst(rows)} | "
              f"{sum(not r['converged'] for r in rows)} |", file=out, flush=True)
    print(f"\nwrong sign: {wrong_total} of {total} lifts ({100 * wrong_total / max(total, 1):.1f} %)", file=out)


SIGN_TILTS = (15.0, 25.0, 35.0)
SIGN_TURNS = (-50.0, -25.0, 25.0, 50.0)
SIGN_OBJECTS = ("vase", "ogee-roof", "arches", "box", "revolve")


def signs_table(classes: tuple[str, ...], out, params: LiftParams = DEFAULT,
                tilts: tuple[float, ...] = SIGN_TILTS) -> None:
    """The depth-sign grid of docs/lifting.md ("Depth sign"): the three bundled examples' objects, the box and the
    revolve at ``tilts`` (default 15, 25, 35 deg) and turns -50, -25, 25, 50 deg (60 lifts by default, noise-free,
    no view rejected)."""
    from tests.lifting.test_lifting import _example_truth

    print("| object | wrong sign | depth RMSE mean / max | not converged |", file=out)
    print("|---|---|---|---|", file=out)
    total = 0
    for name in SIGN_OBJECTS:
        errs, wrong, unconv = [], [], 0
        for tilt in tilts:
            for turn in SIGN_TURNS:
                if name == "box":
                    tr = T.box(tilt=tilt, turn=turn)
                elif name == "revolve":
                    tr = T.revolve(tilt=tilt, turn=turn)
                else:
                    tr = _example_truth(name, T.rotation(tilt, turn))
                r = lift(tr.sketch, params=params, classes=classes)   # no labels: crossings off the examples' knots
                err, sign = T.depth_rmse(tr, r)
                errs.append(err)
                unconv += not r.converged
                if sign != 1:
                    wrong.append(f"{tilt:g}/{turn:g} ({100 * err:.1f} %)")
                e = {"err": err, "sign": sign, "converged": r.converged}
                print(f"# {name} {tilt:g} {turn:g}: {_fmt_err(e)} %", file=sys.stderr, flush=True)
        total += len(wrong)
        print(f"| {name} | {len(wrong)}{': ' + ', '.join(wrong) if wrong else ''} | {100 * np.mean(errs):.2f} / "
              f"{100 * np.max(errs):.2f} % | {unconv} |", file=out, flush=True)
    n = len(SIGN_OBJECTS) * len(tilts) * len(SIGN_TURNS)
    print(f"\nwrong sign: {total} of {n} lifts ({100 * total / n:.1f} %)", file=out)


def energy_table(names: list[str], out) -> None:
    """The baseline energy by term at the truth, at the lift and at the truth's own basin (docs/lifting.md)."""
    print("| truth | w_p | energy: truth (acc, var, fore, par) | lift: energy, depth RMSE | truth's basin: energy, "
          "depth RMSE | lowest |", file=out)
    print("|---|---|---|---|---|---|", file=out)
    for name in names:
        tr = T.make(name)
        for wp in (DEFAULT.w_p_baseline, 0.0):
            d = T.baseline_energies(tr, LiftParams(w_p_baseline=wp))
            t = d["truth"]
            lowest = "lift" if d["lift_energy"] <= d["basin_energy"] * (1 + 1e-9) else "truth's basin"
            print(f"| {name} | {wp:g} | {sum(t.values()):.3g} ({t['accuracy']:.2g}, {t['variation']:.2g}, "
                  f"{t['foreshortening']:.2g}, {t['parallel']:.2g}) | {d['lift_energy']:.3g}, "
                  f"{100 * d['lift_rmse']:.2f} % | {d['basin_energy']:.3g}, {100 * d['basin_rmse']:.2f} % | {lowest} |",
                  file=out, flush=True)


HAND_OBJECTS = ("vase", "ogee-roof", "arches")


def hand_table(seeds: tuple[int, ...], out, params: LiftParams = DEFAULT) -> None:
    """Depth RMSE (%) of the hand-drawn examples, baseline and default cues, one column per seed of the hand."""
    from auszug.lifting import Marker, Sketch, Stroke
    from tests.lifting import make_sketches as ms

    print("| example | cues | " + " | ".join(f"seed {k}" for k in seeds) + " |", file=out)
    print("|---|---|" + "---|" * len(seeds), file=out)
    for name in HAND_OBJECTS:
        cells: dict[str, list[str]] = {"none": [], "default": []}
        for k in seeds:
            try:
                s2, s3, marks = ms.drawn(name, k)
            except ValueError as e:
                print(f"# {name} seed {k}: refused: {e}", file=sys.stderr, flush=True)
                for v in cells.values():
                    v.append("-")
                continue
            sk = Sketch(tuple(Stroke(c, f"c{i}") for i, c in enumerate(s2)),
                        tuple(Marker("occlusion", m, f"o{i}") for i, m in enumerate(marks)))
            tr = T.Truth(sk, tuple(s3))
            for label, classes in (("none", ()), ("default", DEFAULT_CLASSES)):
                r = lift(sk, params=params, classes=classes)
                err, sign = T.depth_rmse(tr, r)
                e = {"err": err, "sign": sign, "converged": r.converged}
                cells[label].append(_fmt_err(e))
                print(f"# {name} seed {k} {label}: {_fmt_err(e)} %", file=sys.stderr, flush=True)
        for label, v in cells.items():
            print(f"| {name} | {label} | " + " | ".join(f"{x} %" if x != "-" else x for x in v) + " |",
                  file=out, flush=True)


def bay_table(bays: list[str], out, params: LiftParams = DEFAULT, tilts: tuple[float, ...] = TILTS) -> None:
    """The square bays of the microarchitecture package over the views grid: how far the lift is off where the
    method's orthogonality at smooth crossings is false (default cues and baseline)."""
    print("| bay | crossings in 3D (deg) | views lifted (rejected) | "
          "default cues: depth RMSE median / max, wrong sign | baseline: median / max, wrong sign | "
          "lifted crossings, largest from 90 deg | not converged |", file=out)
    print("|---|---|---|---|---|---|---|", file=out)
    for name in bays:
        rows: dict[str, list[dict]] = {"default": [], "none": []}
        rejected, crossing = 0, ""
        for tilt in tilts:
            for turn in TURNS:
                tr = T.make_bay(name, tilt, turn)
                why = [w for w in T.accidental(tr) if w != T.NOT_ORTHOGONAL]
                if why:
                    rejected += 1
                    print(f"# {name} {tilt:g} {turn:g}: rejected: {'; '.join(why)}", file=sys.stderr, flush=True)
                    continue
                ang = 90.0 - T.labels(tr)["smooth-orthogonal-angle"]
                crossing = f"{ang.min():.2f}-{ang.max():.2f}" if np.ptp(ang) > 0.005 else f"{ang[0]:.2f}"
                for label, classes in (("default", DEFAULT_CLASSES), ("none", ())):
                    e = evaluate(tr, classes, params)
                    rows[label].append(e)
                    print(f"# {name} {tilt:g} {turn:g} {label}: {_fmt_err(e)} %", file=sys.stderr, flush=True)
        cells = []
        for label in ("default", "none"):
            ok = [e for e in rows[label] if "refused" not in e]
            errs = np.array([e["err"] for e in ok] or [np.nan])
            ref = len(rows[label]) - len(ok)
            cells.append(f"{100 * np.median(errs):.2f} / {100 * errs.max():.2f} %, {sum(e['sign'] != 1 for e in ok)}"
                         f"{f' ({ref} refused)' if ref else ''}")
        ok = [e for e in rows["default"] if "refused" not in e]
        print(f"| {name} | {crossing} | {len(rows['default'])} ({rejected}) | {cells[0]} | {cells[1]} | "
              f"{max((e['worst']['smooth-orthogonal'] for e in ok), default=0.0):.2g} | "
              f"{sum(not e['converged'] for e in ok)} |", file=out, flush=True)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mode", choices=("noise", "views", "signs", "energy", "hand", "bay"))
    ap.add_argument("--truths", default=",".join(T.TRUTHS))
    ap.add_argument("--cues", default="default", choices=("default", "none"))
    ap.add_argument("--params", default="", help="LiftParams fields, e.g. parallel_robust_deg=5,w_depth_anchor=10")
    ap.add_argument("--tilts", default="",
                    help="views and signs modes: the tilts from above (deg, in [0, 90)), e.g. 45,55,65 "
                         "(default: 15,20,25,30,35 for views, 15,25,35 for signs)")
    ap.add_argument("--bays", default="tn-3,tn-4", help="bay mode: teaching-sheet drawings, e.g. tn-3")
    ap.add_argument("--seeds", default="0,1,2,3,4,5", help="hand mode: the seeds of the hand, e.g. 0,1,2")
    a = ap.parse_args(argv)
    try:
        seeds = tuple(int(k) for k in a.seeds.split(","))
    except ValueError:
        ap.error(f"--seeds: not a list of whole numbers: {a.seeds!r}")
    if not seeds or not all(0 <= k < 2**32 for k in seeds):
        ap.error(f"--seeds: each seed must lie in [0, 2**32): {a.seeds!r}")
    try:
        tilts = tuple(float(t) for t in a.tilts.split(",")) if a.tilts else ()
    except ValueError:
        ap.error(f"--tilts: not a list of numbers: {a.tilts!r}")
    if not all(0.0 <= t < 90.0 for t in tilts):
        ap.error(f"--tilts: each tilt must lie in [0, 90) deg: {a.tilts!r}")
    classes = DEFAULT_CLASSES if a.cues == "default" else ()
    params = parse_params([x for x in a.params.split(",") if x])     # auszug lift --set's items
    names = a.truths.split(",")
    print(f"cues: {a.cues}; params: {a.params or 'default'}; load {os.getloadavg()[0]:.1f} at start", file=sys.stdout)
    if a.mode == "energy":
        energy_table(names, sys.stdout)
    elif a.mode == "hand":
        hand_table(seeds, sys.stdout, params)
    elif a.mode == "bay":
        bay_table(a.bays.split(","), sys.stdout, params, tilts or TILTS)
    elif a.mode == "signs":
        signs_table(classes, sys.stdout, params, tilts or SIGN_TILTS)
    elif a.mode == "views":
        views_table(names, classes, sys.stdout, params, tilts or TILTS)
    else:
        noise_table(names, classes, sys.stdout, params)
    print(f"load {os.getloadavg()[0]:.1f} at the end", file=sys.stdout)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
