"""The ground truths of tests/lifting/truth.py, and the lifts measured against them (issue 12, sec. 4).

The first tests check the truths themselves against closed-form geometry (no lift): every smooth
crossing orthogonal in 3D, every crossing at a knot (so the true position of every graph point is
known, noisy sketches too), the labels of the cue candidates equal to the angles the geometry
gives, generic views accepted and accidental ones rejected. The lift tests pin what was measured
at each truth's own view (docs/lifting.md, "Measured"; the view grid is in benchmarks/eval_lifting.py).
"""

from __future__ import annotations

import functools
from dataclasses import replace

import numpy as np
import pytest

from auszug.errors import GeometryError
from auszug.lifting import DEFAULT, LiftParams, layer_graphs, lift
from tests.lifting import truth as T

NEW = ("spiral", "saddle", "wrinkle", "cross", "turret")


@pytest.mark.parametrize("name", list(T.TRUTHS))
def test_truth_views_are_generic_and_smooth_crossings_orthogonal(name):
    tr = T.make(name)
    assert T.accidental(tr) == []
    lab = T.labels(tr)
    assert len(lab["smooth-orthogonal"]) and lab["smooth-orthogonal-angle"].max() < 1e-9


@pytest.mark.parametrize("name", NEW)
@pytest.mark.parametrize("noise, seed", [(0.005, 1), (0.01, 2)])
def test_noisy_graph_points_are_still_truth_control_points(name, noise, seed):
    """The noise field moves shared control points alike, so every crossing stays at a knot and the noisy
    graph's points are the same 3D points. Every candidate of the clean sketch is one of the noisy
    sketch's too, with the same true angle. The noise adds true ones only: straight strokes curved in
    2D become planarity candidates (a 3D line is planar), and a smooth crossing turned below
    ``min_crossing_deg`` in 2D becomes an orthogonal corner (the spiral at 1 %, seed 2); a stroke whose
    short overshoot the noise turns by more than 10 deg is no longer G1 through a corner, so its two
    halves are candidates each, with the same true angle (the cross at 1 %, seed 2). The parallel
    candidates change with the 2D angles (their threshold) and are not compared."""
    clean, noisy = T.make(name), T.make(name, noise=noise, seed=seed)
    (_, g), = layer_graphs(noisy.sketch)
    X = T.truth_xyz(noisy, g)
    (_, g0), = layer_graphs(clean.sketch)
    X0 = T.truth_xyz(clean, g0)
    assert len(g.points) == len(g0.points)
    # the 3D truth in sketch units is the same point set (graph units differ by the noisy diagonal)
    a = X * g.scale + np.r_[g.offset, 0.0]
    b = X0 * g0.scale + np.r_[g0.offset, 0.0]
    assert np.abs(np.sort(a, axis=0) - np.sort(b, axis=0)).max() < 1e-9 * clean.diagonal()
    la, lb = T.labels(noisy), T.labels(clean)
    for k in ("orthogonal", "planar"):
        extra = sorted(la[k + "-angle"].round(6))
        clean_angles = sorted(lb[k + "-angle"].round(6))
        for x in clean_angles:
            extra.remove(x)          # raises if a clean candidate is missing
        assert all(x == 0 or x in clean_angles for x in extra), (k, extra)


def test_helicoid_rulings_straight_helices_not_planar():
    chains = T.spiral_chains()
    rulings = chains[3:]                     # after the three helices
    for c in rulings:
        P = c.reshape(-1, 3)
        assert np.linalg.svd(P - P.mean(0), compute_uv=False)[1] < 1e-12
    lab = T.labels(T.make("spiral"))
    # the three helices are the planar candidates (curved in 2D), none planar in 3D
    assert len(lab["planar"]) == 3 and lab["planar-angle"].min() > 5.0
    # adjacent rulings turn by 150/4 = 37.5 deg about the axis: every ruling pair is a false candidate
    t = np.radians(37.5)
    assert np.isclose(lab["parallel-angle"], np.degrees(t)).sum() >= 8


def test_enneper_lines_of_curvature_are_planar_and_conformal():
    lab = T.labels(T.make("saddle"))
    assert len(lab["planar"]) == 8 and lab["planar-angle"].max() < 1e-9
    assert len(lab["smooth-orthogonal"]) == 16


def test_extrusion_regularities_are_all_true():
    lab = T.labels(T.make("wrinkle"))
    assert lab["parallel"].all() and len(lab["parallel"]) == 22 and lab["parallel-angle"].max() < 1e-5
    assert lab["planar"].all() and len(lab["planar"]) == 3


def test_cross_vault_corner_angles_are_the_ribs_springing_angles():
    """At each corner five strokes meet. Orthogonality-cue angles (|90 - angle| between the tangents):
    wall-plate lines 0; a rib across a wall line 0; a wall rib (rise 0.8 on half-span 1: springing
    tangent (-0.225, 1)) along its own wall line 90 - atan(1 / 0.225); the diagonal rib (rise 1 on
    half-span sqrt 2: tangent (-0.5, sqrt 2) in its plane) along either wall line; rib against rib."""
    lab = T.labels(T.make("cross"))
    wall = np.array([(1 - 0.64) / 1.6, 1.0, 0.0])             # (half^2 - rise^2) / (2 rise) = R - rise
    diag = np.array([0.5 / np.sqrt(2), np.sqrt(2), 0.5 / np.sqrt(2)])
    other = wall[[2, 1, 0]]                                    # the wall rib of the other wall, same corner

    def dev(u, v):
        c = abs(u @ v) / np.linalg.norm(u) / np.linalg.norm(v)
        return abs(90.0 - np.degrees(np.arccos(min(c, 1.0))))

    x = np.array([1.0, 0.0, 0.0])
    expected = {0.0: 12, round(dev(wall, x), 6): 8, round(dev(diag, x), 6): 8, round(dev(wall, other), 6): 4,
                round(dev(diag, wall), 6): 8}
    got = {}
    for a in lab["orthogonal-angle"]:
        k = min(expected, key=lambda e: abs(e - a))
        assert abs(k - a) < 1e-6, a
        got[k] = got.get(k, 0) + 1
    assert got == expected and int(lab["orthogonal"].sum()) == 12
    assert len(lab["smooth-orthogonal"]) == 1 and len(lab["planar"]) == 6 and lab["planar"].all()


def test_turret_negative_cues():
    """Hexagon corners are 120 deg (an orthogonality angle of 30); the horizontal sections of two faces
    along their shared edge are 60 deg apart in 3D. Both are candidates the lift must reject."""
    lab = T.labels(T.make("turret"))
    o, p = lab["orthogonal-angle"], lab["parallel-angle"]
    assert np.allclose(np.sort(o), [0.0] * 10 + [30.0] * 7, atol=1e-9)
    false_par = p[~lab["parallel"]]
    assert len(false_par) == 7 and np.all(np.isclose(false_par, 60.0) | np.isclose(false_par, 90.0))
    assert len(lab["smooth-orthogonal"]) == 10


@pytest.mark.parametrize("make, reason", [
    (lambda: T.make("wrinkle", 25.0, -30.0), "crossing of"),             # a ruling along the profile's slope
    (lambda: T.make("cross", 30.0, 0.0), "edge-on"),                      # the side walls seen edge-on
    (lambda: T.make("revolve", 25.0, -50.0), "edge-on"),
    (lambda: T._project(T.saddle_chains(extent=0.8), T.rotation(25.0, 10.0), 0.0, 0), "two crossings"),
    (lambda: T._project(T.spiral_chains(pitch=0.35), T.rotation(25.0, 20.0), 0.0, 0), "crossing of"),
])
def test_accidental_views_are_rejected(make, reason):
    why = T.accidental(make())
    assert any(reason in w for w in why), why


# (truth, depth RMSE bound, {class: (true positives, applied, true)}) measured 2026-12-03 at each truth's
# own view, noise-free, default cues (docs/lifting.md, "Measured"); the bounds are the measured figure
# plus about 3 % of it. Targets of issue 12: spiral <= 1 %, saddle, wrinkle and cross <= 3 %: all missed but
# the wrinkle's since lift-wrinkle.
LIFTED = [
    ("spiral", 0.3530, {"parallel": (5, 13, 5)}),                      # measured 34.31 %
    # since lift-wrinkle the depth family prior (``family_prior``) moves the saddle, wrinkle and turret along
    # the depth family their smooth crossings leave: saddle 7.47 -> 4.94 %, wrinkle 8.95 -> 1.82 % (the issue's
    # 3 % met), turret 10.28 -> 10.03 % (the cue counts unchanged)
    ("saddle", 0.0510, {"parallel": (12, 24, 12), "planar": (8, 8, 8)}),  # measured 4.94 % (7.45 before)
    ("wrinkle", 0.0190, {"parallel": (22, 22, 22), "planar": (3, 3, 3)}),  # measured 1.82 % (8.95 before)
    # the cross: 22.11 % on main (lifting-speed's solver, every solve converged, no corner applied); since
    # lift-acc every seed is also propagated with w_p = 0.1 and the baseline reaches the truth's own basin
    # (energy 0.0341 against 0.0378): 16.21 %, 16 corners applied (8 true), the planar round unconverged
    # (residual 1.6e-9 > 1e-10)
    ("cross", 0.1670, {"parallel": (20, 70, 20), "orthogonal": (8, 16, 12), "planar": (6, 6, 6)}),
    ("turret", 0.1035, {"parallel": (22, 24, 22), "orthogonal": (8, 12, 10)}),  # measured 10.03 % (10.28 before)
]


@functools.cache
def _clean(name: str):
    tr = T.make(name)
    return tr, lift(tr.sketch)


#: The lift without the rule for the last round's applied cues (``final_hold``, on by default since lift-hold3),
#: and without the depth family prior (``family_prior``, on by default since lift-wrinkle), whose solve follows the
#: rule's: the tests of the rule compare it with ``NOFAM``, the default without that prior.
UNHELD = LiftParams(final_hold=False, family_prior=False)
NOFAM = LiftParams(family_prior=False)


@functools.cache
def _nofam(name: str):
    return lift(T.make(name).sketch, params=NOFAM)


@functools.cache
def _unheld(name: str):
    return lift(T.make(name).sketch, params=UNHELD)


@pytest.mark.parametrize("name, bound, counts", LIFTED)
def test_lift_against_the_truth(name, bound, counts):
    """Depth RMSE (best offset and sign), the sign, the cue counts against the true labels, and the residual
    angles of the applied cues: the smooth crossings' orthogonality holds to 1e-6 deg, and so does every
    applied hard cue, the last class's too (planarity, or corner orthogonality where no stroke is curved: the
    turret), held by ``final_hold`` (on by default since lift-hold3; without it the last round's cues stay
    within I_b only, measured up to 4.7 deg); applied parallelism stays soft (at most 0.31 deg)."""
    tr, r = _clean(name)
    lab = T.labels(tr)
    err, sign = T.depth_rmse(tr, r)
    assert sign == 1 and err <= bound, (err, sign)
    scores = T.cue_scores(r, lab)
    assert {k: scores[k][:3] for k in counts} == counts
    # what is not listed has no candidate or nothing applied and nothing true
    assert all(v[1] == v[2] == 0 for k, v in scores.items() if k not in counts and k != "linear")
    ap = {k: [c.angle for c in r.cues if c.applied and c.kind == k]
          for k in ("smooth-orthogonal", "orthogonal", "planar", "parallel")}
    assert max(ap["smooth-orthogonal"]) < 1e-6
    assert max(ap["orthogonal"] + ap["planar"], default=0.0) < 1e-6
    assert max(ap["parallel"], default=0.0) < 0.35
    if name != "cross":            # the cross's planar round ends unconverged (residual 1.4e-9 > 1e-10)
        assert r.converged


@pytest.mark.parametrize("name", ["spiral", "saddle", "wrinkle", "cross", "turret"])
def test_one_percent_noise_within_twice_the_noise_free_error(name):
    """The issue's noise target, 1 % noise (seed 1) against the same truth noise-free, default cues.

    Measured at 1 % (seeds 0, 1, 2) against noise-free: spiral 27.5 (a solve unconverged, wrong sign),
    33.5, 28.3 against 34.3 %; saddle 8.30, 7.09, 4.80 against 7.45 %; wrinkle 4.07, 6.85, 8.31 against
    8.95 %; cross refused (seed 0), 13.1 (wrong sign), 22.2 against 16.2 % (since lift-acc: refused, 13.1
    (wrong sign), 35.6 against 16.2 %: seed 2 misses the target; on main 22.1 % noise-free); turret 11.5,
    11.8, 17.0 against 10.3 %. Met at seed 1 everywhere, but only because the noise-free errors are large.
    Since lift-wrinkle's depth family prior (on by default): saddle 7.46 (unconverged), 5.07, 4.75 against
    4.94 %; wrinkle 1.50, 1.64, 1.72 against 1.82 % (met with the noise-free error within the issue's 3 %);
    turret 11.48, 11.23, 13.11 against 10.03 %; the others unchanged."""
    tr0, r0 = _clean(name)
    err0, _ = T.depth_rmse(tr0, r0)
    tr = T.make(name, noise=0.01, seed=1)
    err, _ = T.depth_rmse(tr, lift(tr.sketch))
    assert err <= 2 * err0, (err, err0)


def test_cross_with_noise_that_breaks_its_one_smooth_crossing_is_refused():
    """The bay has one smooth crossing (the boss); 1 % noise, seed 0, turns a diagonal rib's tangent at the
    boss by more than 10 deg, so no smooth crossing is left to start from: refused, with the reason."""
    tr = T.make("cross", noise=0.01, seed=0)
    with pytest.raises(GeometryError, match="no smooth crossing"):
        lift(tr.sketch)


def test_view_from_above_score_of_every_truth_over_the_view_grid():
    """``from_above`` on the exact truths (no lift) over the evaluation grid, tilts 15-35 deg x turns
    -50..50 deg: positive everywhere (measured minimum 0.012, the revolve at tilt 15, and 0.013, the
    saddle): the truths' geometry agrees with the rule. The lifts' depth scale did not always (24 wrong signs of
    the wrinkle, 12 on the depth-sign grid before lift-sign2, fixed by the vertical planes of
    ``depth_sign_score``: next tests)."""
    from auszug.lifting import from_above

    for name in T.TRUTHS:
        chains = T.make(name).chains3d if name == "revolve" else T.TRUTHS[name]()
        R0 = T.rotation(*T.VIEWS[name]) if name == "revolve" else np.eye(3)
        obj = [c @ R0 for c in chains]              # back to object coordinates (R is orthogonal)
        for tilt in (15.0, 20.0, 25.0, 30.0, 35.0):
            for turn in range(-50, 51, 10):
                R = T.rotation(tilt, float(turn))
                net = np.concatenate([c @ R.T for c in obj])
                s = from_above(net)
                assert s > 0.01, (name, tilt, turn, s)
                assert from_above(net * [1.0, 1.0, -1.0]) == -s


def _object_chains(name: str) -> list[np.ndarray]:
    """A truth's chains in object coordinates (y up), to be seen from any view."""
    chains = T.make(name).chains3d if name == "revolve" else T.TRUTHS[name]()
    R0 = T.rotation(*T.VIEWS[name]) if name == "revolve" else np.eye(3)
    return [c @ R0 for c in chains]              # back to object coordinates (R is orthogonal)


def test_a_vertical_planes_vote_is_its_tilt_at_any_depth_scale():
    """``vertical_planes`` on curves in known planes: a curve in a vertical plane turned by t from the picture,
    seen from tilt b, votes ``n_x^2 sin 2b_k`` with ``tan b_k = k tan b`` (the vertical (0, cos b, k sin b))
    and n the plane's unit normal, whatever the depth scale z -> k z (the ambiguity the foreshortening leaves:
    the vote's sign stays), and the mirror votes the opposite; a horizontal curve does not vote (its normal is
    the vertical, drawn vertical: n_x = 0), nor does a straight one (no plane)."""
    from auszug.lifting import from_above, vertical_planes

    s = np.linspace(0.0, 1.0, 4)
    bump = np.stack([s, 0.3 * np.sin(np.pi * s) + 0.2 * s, 0 * s], axis=1)     # a curve in the x-y plane
    one = np.array([0])
    edges_mirrored = 0
    for b in (10.0, 30.0, 50.0, 70.0, 85.0):
        for t in (-70.0, -40.0, 20.0, 60.0):
            R = T.rotation(b, t)
            wall = (bump @ R.T)[None]                                   # the x-y plane turned by t, tilted by b
            ring = (bump[:, [0, 2, 1]] @ R.T)[None]                    # a curve in a horizontal plane
            for k in (0.3, 1.0, 3.0):
                n = R @ [0.0, 0.0, 1.0] / [1.0, 1.0, k]                 # the scaled plane's normal
                n /= np.linalg.norm(n)
                b_k = np.arctan(k * np.tan(np.radians(b)))
                v, a = vertical_planes(wall * [1, 1, k], one)
                m, _ = vertical_planes(wall * [1, 1, -k], one)
                assert v > 0 and v / a == pytest.approx(n[0] ** 2 * np.sin(2 * b_k), abs=1e-9), (b, t, k)
                assert m == pytest.approx(-v, abs=1e-15)
                edges_mirrored += from_above(wall * [1, 1, k]) < 0
                assert vertical_planes(ring * [1, 1, k], one)[0] == pytest.approx(0.0, abs=1e-12)
    assert edges_mirrored > 0                                            # the edges alone read some as the mirror
    assert vertical_planes(np.stack([s, 0.5 * s, 0.2 * s], axis=1)[None], one) == (0.0, 0.0)


def test_depth_sign_score_of_every_truth_over_the_view_grid():
    """``depth_sign_score`` (the edges of ``from_above`` and the vertical planes, lift-sign2) on the exact truths
    over the evaluation grid (tilts 15-35 deg, turns -50..50): positive everywhere, the mirror's its negative.
    On the truths with planar strokes in vertical planes (the revolve, saddle, cross; the vase of the
    examples) it stays positive also at tilts 45 and 60 deg and at depth scales 0.5 and 1.5 (z -> k z, the
    depth the foreshortening leaves free; measured minimum 0.008, the revolve at k = 1.5), where
    ``from_above`` is negative at many views (measured: revolve 78, saddle 64, cross 66, vase 75 of the 231
    per object). At k = 2 the revolve seen from 60 deg above, turn 50, scores -0.0003; the wrinkle (its
    sections the only planes, all parallel) is negative at tilt 60 from turns -10..10 and, at k = 0.5, at
    tilts 30-35 near turn 0, where the sections face the picture (n_x small)."""
    from auszug.lifting import depth_sign_score, from_above
    from tests.lifting import make_sketches as ms

    for name in T.TRUTHS:
        obj = _object_chains(name)
        strokes = np.concatenate([np.full(len(c), i) for i, c in enumerate(obj)])
        for tilt in (15.0, 20.0, 25.0, 30.0, 35.0):
            for turn in range(-50, 51, 10):
                R = T.rotation(tilt, float(turn))
                net = np.concatenate([c @ R.T for c in obj])
                s = depth_sign_score(net, strokes)
                assert s > 0.0, (name, tilt, turn, s)
                assert depth_sign_score(net * [1.0, 1.0, -1.0], strokes) == pytest.approx(-s, abs=1e-12)
    objects = {name: _object_chains(name) for name in ("revolve", "saddle", "cross")} | {"vase": ms.vase()}
    for name, obj in objects.items():
        strokes = np.concatenate([np.full(len(c), i) for i, c in enumerate(obj)])
        wrong_edges = 0
        for k in (0.5, 1.0, 1.5):
            for tilt in (15.0, 20.0, 25.0, 30.0, 35.0, 45.0, 60.0):
                for turn in range(-50, 51, 10):
                    net = np.concatenate([c @ T.rotation(tilt, float(turn)).T for c in obj]) * [1.0, 1.0, k]
                    assert depth_sign_score(net, strokes) > 0.0, (name, k, tilt, turn)
                    wrong_edges += from_above(net) < 0
        assert wrong_edges >= 50, (name, wrong_edges)


@pytest.mark.parametrize("name, tilt, turn, bound", [
    ("wrinkle", 30.0, 20.0, 0.105),     # measured 10.0 % (24.2 % at the sign the edges alone give)
    ("wrinkle", 35.0, 40.0, 0.055),     # 5.2 % (23.9 %)
    ("revolve", 35.0, 25.0, 0.035),     # 3.1 % (40.4 %): the depth-sign grid of eval_lifting signs
])
def test_vertical_planes_give_the_depth_sign_of_lifts_the_edges_mirror(name, tilt, turn, bound):
    """Lifts (default cues) whose sign the edges alone (``sign_plane_weight = 0``, the rule before lift-sign2)
    take wrong: the wrinkle with its rulings flattened below 45 deg out of the page, the revolve lifted deeper
    than the truth (its meridian planes and rings read as a tilt of 46 deg instead of 25-35). With the
    vertical planes the sign is right and the lift within its measured error of the truth. These are the lifts
    without the depth family prior (lift-wrinkle, ``family_prior``), which lifts the two wrinkles unflattened
    (1.87 and 1.93 %, measured; the edges then read them right too) and leaves the revolve as it is."""
    tr = T.revolve(tilt=tilt, turn=turn) if name == "revolve" else T.make(name, tilt, turn)
    r = lift(tr.sketch, params=NOFAM)
    err, sign = T.depth_rmse(tr, r)
    assert r.converged and sign == 1 and err <= bound, (err, sign)
    if name == "wrinkle":
        err1, sign1 = T.depth_rmse(tr, lift(tr.sketch))
        assert sign1 == 1 and err1 < 0.02, (err1, sign1)
    r0 = lift(tr.sketch, params=LiftParams(sign_plane_weight=0.0, family_prior=False))
    err0, sign0 = T.depth_rmse(tr, r0)
    assert sign0 == -1 and err0 == pytest.approx(err, abs=1e-9), (err0, sign0)     # the same lift, mirrored
    P, P0 = r.points[0], r0.points[0]
    assert np.array_equal(P[:, :2], P0[:, :2]) and np.allclose(P[:, 2], -P0[:, 2], atol=1e-12 * np.ptp(P[:, :2]))


@pytest.mark.parametrize("name", list(T.TRUTHS))
def test_baseline_finds_less_energy_than_the_truth(name):
    """The truth is feasible for the baseline (its smooth crossings orthogonal, its G1 joints at the
    sketch's handle ratios, to 1e-12) and costs more energy than the lift finds: the baseline's
    errors are the energy's, not the solver's. Measured (accuracy, variation, foreshortening, soft
    parallelism; lift | truth): the truth pays for parallelism on its false candidates (revolve
    0.010 | 0.034, spiral 0.023 | 0.14, saddle 0.0026 | 0.024, cross 0.018 | 1.1, turret 0.0061 |
    0.14), the wrinkle, whose candidates are all true, for foreshortening (1.0e-4 | 1.9e-4)."""
    from auszug.lifting import cues as cu
    from auszug.lifting.terms import fidelity, structure

    tr = T.make(name)
    (_, g), = layer_graphs(tr.sketch)
    r = lift(tr.sketch, classes=())
    e_lift = [s.energy for s in r.stages if s.name == "baseline" and not s.discarded]
    n = 3 * (len(g.points) + len(g.chains)) + len(g.chains)
    E = fidelity(g, n, DEFAULT, DEFAULT.w_a_baseline)
    par = cu.parallel_cues(g, DEFAULT)
    par.add(E, np.arange(len(par)), DEFAULT.w_p_baseline * np.exp(-(par.angle2d**2) / DEFAULT.sigma_p_deg**2))
    smooth = cu.smooth_orthogonal(g)
    X = T.truth_xyz(tr, g)
    X[:, 2] -= X[smooth.p[0], 2]                      # the energy does not see a depth offset
    v = np.zeros(n)
    v[: 3 * len(g.points)] = X.ravel()
    C = structure(g, n, DEFAULT, int(smooth.p[0]))     # pinned depth, G1 joints, straight segments
    smooth.add(C, np.arange(len(smooth)), 1.0)
    assert np.abs(C.value(v)).max() < 1e-12
    e_truth = float((E.weights * E.value(v) ** 2).sum())
    assert min(e_lift) < e_truth, (min(e_lift), e_truth)


def test_the_final_solve_meets_every_applied_hard_cue():
    """LiftParams(final_solve=True): one more solve after the last class holds the cues it applied in its
    final round, so every applied hard cue is met (issue 12: within 0.5 deg); without it and without
    ``final_hold`` the revolve's planar cues stay as their last round left them (up to 3.85 deg measured).
    Measured on the revolve truth: 3.11 % -> 2.76 % depth RMSE (docs/lifting.md, "Final solve", for the cases
    it makes worse). Without the depth family prior (lift-wrinkle), whose solve would come last."""
    tr = T.make("revolve")
    r0, r1 = _unheld("revolve"), lift(tr.sketch, params=LiftParams(final_solve=True, family_prior=False))
    hard0 = [c.angle for c in r0.cues if c.applied and c.kind not in ("parallel", "linear")]
    hard1 = [c.angle for c in r1.cues if c.applied and c.kind not in ("parallel", "linear")]
    assert r1.converged and max(hard1) < 1e-3 and max(hard0) > 1.0
    assert [(c.kind, c.where, c.applied) for c in r1.cues] == [(c.kind, c.where, c.applied) for c in r0.cues]
    err, sign = T.depth_rmse(tr, r1)
    assert sign == 1 and err <= 0.0285
    assert r1.stages[-1].name == "final" and all(s.name != "final" for s in r0.stages)


#: The rule for the last round's applied cues (lift-final, docs/lifting.md "Applied cues within 0.5 deg"): the
#: default since lift-hold3.
HOLD = LiftParams(final_hold=True)


def test_the_rule_for_the_last_rounds_cues_is_the_default():
    assert DEFAULT.final_hold and HOLD == DEFAULT and not UNHELD.final_hold


@pytest.mark.parametrize("name", list(T.TRUTHS))
def test_every_applied_cue_holds_within_half_a_degree(name):
    """Issue 12's target "applied cues within 0.5 deg" with ``LiftParams(final_hold=True)`` (lift-final; the
    default since lift-hold3, docs/lifting.md):
    the last round's applied cues are held by that round solved once more with them hard, its depths held
    near its solution, so on every truth at its own view, noise-free, every applied hard cue holds to
    1e-6 deg and applied parallelism (soft) within 0.1 deg (measured at most 0.05); at 1 % noise (seed 1)
    every applied cue holds within 0.5 deg. Without the rule the revolve's planar cues end up to 3.85 deg
    off, the cross's 4.73, the saddle's 0.91 (measured); the depth RMSE moves by at most 0.17 % points
    (the cross: 16.21 -> 16.38 %; docs/lifting.md). The angles are the default lift's (with the depth family
    prior of lift-wrinkle, whose solve holds every applied cue too); the rule's effect on the depth is measured
    without that prior."""
    tr, r = _clean(name)
    applied = [c for c in r.cues if c.applied]
    assert applied and r.stages
    assert max(c.angle for c in applied if c.kind not in ("parallel", "linear")) < 1e-6
    assert max((c.angle for c in applied if c.kind == "parallel"), default=0.0) < 0.1
    # the depth RMSE within 0.2 % points of the lift's without the rule (measured -0.03 to +0.17, the cross's
    # the +0.17)
    r = _nofam(name)
    err, sign = T.depth_rmse(tr, r)
    err0, sign0 = T.depth_rmse(tr, _unheld(name))
    assert sign == sign0 == 1 and abs(err - err0) <= 0.002, (err, err0)
    tr1 = T.make(name, noise=0.01, seed=1)
    r1 = lift(tr1.sketch)
    assert max(c.angle for c in r1.cues if c.applied) <= DEFAULT.applied_tol_deg
    if name == "revolve":   # the test can fail: the same lift without the rule
        r0 = _unheld(name)
        assert max(c.angle for c in r0.cues if c.applied) > 1.0
        assert [s.name for s in r.stages] == [s.name for s in r0.stages] + ["planar held"]


def _same_lift(r, r0) -> None:
    ts = np.linspace(0.0, 1.0, 5)
    for a, b in zip(r.network.pieces, r0.network.pieces, strict=True):
        assert np.array_equal(a.point_t(ts), b.point_t(ts))
    assert [(c.kind, c.where) for c in r.cues] == [(c.kind, c.where) for c in r0.cues]


def test_a_held_round_that_breaks_an_applied_cue_rejects_its_cues_beyond_half_a_degree():
    """The rule's fallback when the held round converges but breaks another applied cue: the spiral seen at
    tilt 30, turn 30, whose last planar round applies one (false) helix planarity at 3.43 deg; held hard, it
    converges but pulls an applied (soft) tangent parallelism 14.5 deg off (measured). So the round's
    solution stays (the lift is the one without the rule, to the bit) and that cue is rejected."""
    tr = T.make("spiral", 30.0, 30.0)
    r, r0 = lift(tr.sketch, params=NOFAM), lift(tr.sketch, params=UNHELD)
    held = r.stages[-1]
    assert held.name == "planar held" and held.converged and held.discarded
    assert (held.applied, held.rejected) == (0, 1)
    _same_lift(r, r0)
    dropped = [(c0.kind, c0.angle) for c, c0 in zip(r.cues, r0.cues, strict=True) if c0.applied and not c.applied]
    assert len(dropped) == 1 and dropped[0][0] == "planar" and dropped[0][1] > DEFAULT.applied_tol_deg
    assert max(c.angle for c in r.cues if c.applied) <= DEFAULT.applied_tol_deg
    assert max(c.angle for c in r0.cues if c.applied) > 1.0


def test_a_held_round_that_does_not_converge_keeps_the_rounds_solution():
    """The rule's fallback when the held round does not converge (at the anchor weight nor a third of it): the
    saddle at 1 % noise (seed 0), whose last planar round applies one cue at 0.24 deg. The round's
    solution stays (to the bit) and the cue, within 0.5 deg there, stays applied; a solve that does not
    converge at the first weight and does at the second is kept (the wrinkle at 1 % noise, seeds 0 and 1)."""
    tr = T.make("saddle", noise=0.01, seed=0)
    r, r0 = lift(tr.sketch, params=NOFAM), lift(tr.sketch, params=UNHELD)
    held = [s for s in r.stages if "held" in s.name]
    assert [(s.converged, s.discarded) for s in held] == [(False, True), (False, True)]
    assert (held[-1].applied, held[-1].rejected) == (1, 0)
    _same_lift(r, r0)
    assert [c.applied for c in r.cues] == [c.applied for c in r0.cues]
    assert 0.1 < max(c.angle for c in r.cues if c.applied) <= DEFAULT.applied_tol_deg
    tr = T.make("wrinkle", noise=0.01, seed=1)
    r = lift(tr.sketch)
    held = [s for s in r.stages if "held" in s.name]
    assert [(s.converged, s.discarded, s.applied) for s in held] == [(False, True, 0), (True, False, 8)]
    assert max(c.angle for c in r.cues if c.applied and c.kind == "planar") < 1e-6


def test_a_held_solve_given_up_at_its_first_step_is_not_retried():
    """The rule's early fallback (lift-final2, ``LiftParams.hold_first_step``): a held solve whose first Newton
    step, shortened to that fraction, does not decrease the merit is given up at once, not retried at the
    second weight, and the fallback for a solve that does not converge follows. The wrinkle at 1 % noise,
    seed 2: at 1/64 the probe fails (measured), so the round's solution stays (to the bit) and its applied
    cues beyond 0.5 deg there are rejected; at the default 1/128 it passes and the held solve converges
    (13 steps, measured), every cue kept."""
    tr = T.make("wrinkle", noise=0.01, seed=2)
    r0 = lift(tr.sketch, params=UNHELD)
    r = lift(tr.sketch, params=LiftParams(hold_first_step=1 / 64, family_prior=False))
    held = [s for s in r.stages if "held" in s.name]
    assert [(s.iterations, s.converged, s.discarded) for s in held] == [(0, False, True)]
    assert held[0].rejected > 0 and held[0].applied + held[0].rejected == 8
    _same_lift(r, r0)
    dropped = [c0.angle for c, c0 in zip(r.cues, r0.cues, strict=True) if c0.applied and not c.applied]
    assert len(dropped) == held[0].rejected and min(dropped) > DEFAULT.applied_tol_deg
    assert max(c.angle for c in r.cues if c.applied) <= DEFAULT.applied_tol_deg
    r1 = lift(tr.sketch)
    held = [s for s in r1.stages if "held" in s.name]
    assert [(s.converged, s.discarded, s.applied) for s in held] == [(True, False, 8)]


# Structural diagnosis (branch lift-acc, docs/lifting.md "Structural diagnosis"): where the large errors of
# the spiral, the cross and the wrinkle come from.


@pytest.mark.parametrize("name", list(T.TRUTHS))
def test_the_baseline_reaches_the_truths_own_basin_or_a_lower_minimum(name):
    """The baseline solved from the truth (the truth's own basin) never finds less energy than the lift does,
    with the soft parallelism and without it: the large errors are the energy's, not the seeding's. Before
    lift-acc the rib vault's one seed, propagated with w_p = 5 over 73 parallel candidates of which 53 are
    false, missed its basin: 0.0378 against 0.0341 (w_p = 0: 0.0052 against 0.000146); every seed is now
    also propagated with w_p = 0.1 (``LiftParams.w_p_propagate_second``)."""
    for wp in (DEFAULT.w_p_baseline, 0.0):
        d = T.baseline_energies(T.make(name), LiftParams(w_p_baseline=wp))
        assert d["basin_converged"]
        assert d["lift_energy"] <= d["basin_energy"] * (1 + 1e-6), (wp, d["lift_energy"], d["basin_energy"])


def test_the_spirals_truth_is_not_the_baselines_minimum():
    """The helical stair. With the soft parallelism the truth's own basin is 8.65 % off (depth RMSE at the
    control points) at twice the lift's energy (0.0639 against 0.0321): at the truth the soft parallelism
    costs 0.14, 260 times the minimal variation, on the 14 false ruling pairs (37.5 deg apart in 3D,
    16-28 deg in 2D) and on near-parallel helix tangents seen nearly edge-on (76 deg out of the page: the
    2D-normalised residual ``a / |a_2d| - b / |b_2d|`` of two tangents 6 deg apart is then 1.0). Without it the
    basin is 1.06 % off, but a minimum 35.8 % off is lower (0.00055 against 0.00061): the helices' torsion
    costs minimal variation (5.3e-4 at the truth)."""
    tr = T.make("spiral")
    d = T.baseline_energies(tr)
    t = d["truth"]
    assert t["parallel"] > 200 * t["variation"] > 0 and t["accuracy"] < 1e-20
    assert 0.08 < d["basin_rmse"] < 0.095 and d["lift_rmse"] > 0.3
    assert 1.8 * d["lift_energy"] < d["basin_energy"]
    d0 = T.baseline_energies(tr, LiftParams(w_p_baseline=0.0))
    assert d0["basin_rmse"] < 0.0115 and d0["lift_rmse"] > 0.3
    assert d0["lift_energy"] < 0.95 * d0["basin_energy"]


def test_the_cross_depth_is_left_free_by_its_one_smooth_crossing():
    """The rib vault's ribs are planar circular arcs, affine images of their drawings, so the truth has zero
    accuracy and variation; with one smooth crossing so does a lift 13 % off: without foreshortening and soft
    parallelism the depth is a family of exact interpretations (energy 5e-30), and only those two terms and
    the cues choose a member. The soft parallelism costs the truth 1.06 (53 false candidates at the corners,
    where five strokes meet, 14-104 deg apart in 3D and 2-30 deg in 2D)."""
    d = T.baseline_energies(T.make("cross"), LiftParams(w_p_baseline=0.0, w_f=0.0))
    t = d["truth"]
    assert t["accuracy"] + t["variation"] < 1e-20
    assert d["lift_energy"] < 1e-20 and d["lift_rmse"] > 0.1
    assert T.baseline_energies(T.make("cross"))["truth"]["parallel"] > 1.0


def test_the_wrinkle_is_lifted_as_an_extrusion_with_less_foreshortening():
    """An extrusion seen orthographically is a one-parameter family of exact interpretations: the rulings' slope
    out of the page, the sections in the planes normal to them; every member has the same accuracy, variation
    and orthogonality, and the foreshortening term picks one. Over the 43 generic views the lifted rulings lie
    27-51 deg out of the page, the truth's 32-75 deg (benchmarks/RESULTS.md, lift-acc). Seen from (25, 0) the
    truth's rulings are 65 deg out of the page, the lift's 36 deg: below 45 deg a receding horizontal reads as
    a vertical in ``from_above``'s sin(4 phi), so the rule takes the mirror; that lift is 16.7 % off at its best
    sign. The wrong signs of the wrinkle (24 of 43 views before lift-sign2) were this depth scale read by the
    edges; the vertical planes of ``depth_sign_score`` fix 19 of them but not this view, where every section's
    normal lies in the y-z plane (turn 0) and votes nothing. That is the paper's lift (``family_prior`` off);
    the depth family prior (lift-wrinkle, on by default) takes the family's member of isotropic extent instead:
    its rulings 66.9 deg out of the page, 2.05 % off at the right sign (measured)."""
    from auszug.lifting import from_above

    tr = T.make("wrinkle", 25.0, 0.0)
    r = lift(tr.sketch, params=NOFAM)
    err, sign = T.depth_rmse(tr, r)
    g = r.graphs[0]
    X, Xt = r.points[0] / g.scale, T.truth_xyz(tr, g)

    def chord(P, s):
        ch = g.chains[s]
        return P[int(g.segments[ch[-1], 3])] - P[int(g.segments[ch[0], 0])]

    rulings = [s for s, t in enumerate(g.strokes) if t.id in {"c3", "c4", "c5", "c6", "c7"}]
    u = np.array([chord(X, s) for s in rulings])
    u /= np.linalg.norm(u, axis=1)[:, None]
    assert np.abs(u @ u.T).min() > np.cos(np.radians(0.01))              # the rulings are parallel
    for s in (0, 1, 2):                                                    # the sections planar, normal to them
        P = X[np.unique(g.segments[g.chains[s]])]
        sv = np.linalg.svd(P - P.mean(0))
        assert sv[1][-1] < 1e-5 and abs(sv[2][-1] @ u[0]) > np.cos(np.radians(0.01))

    def out_of_page(v):
        return np.degrees(np.arctan2(abs(v[2]), np.linalg.norm(v[:2])))

    assert 30 < out_of_page(u[0]) < 40 and np.isclose(np.mean([out_of_page(chord(Xt, s)) for s in rulings]), 65.0)
    assert from_above(np.concatenate(tr.chains3d)) > 0.98 and from_above(r.points[0][g.segments]) > 0.5
    assert sign == -1 and 0.16 < err < 0.175
    r1 = lift(tr.sketch)
    err1, sign1 = T.depth_rmse(tr, r1)
    u1 = chord(r1.points[0] / g.scale, rulings[0])
    assert sign1 == 1 and err1 < 0.022 and 65 < out_of_page(u1) < 69, (err1, sign1, out_of_page(u1))


def test_the_second_propagation_reaches_the_vaults_lower_basin():
    """``LiftParams.w_p_propagate_second``: the rib vault has one smooth crossing, so one seed; propagated with
    the paper's w_p = 5 its baseline stops at energy 0.0378 (flat: every depth 0), propagated again with
    w_p = 0.1 at 0.0341, the minimum of the truth's own basin, which is kept. Off (0), the lift is main's."""
    tr = T.make("cross")

    def baselines(r):
        return [s.energy for s in r.stages if s.name == "baseline" and s.converged and not s.discarded]

    r0 = lift(tr.sketch, params=LiftParams(w_p_propagate_second=0.0), classes=())
    r1 = lift(tr.sketch, classes=())
    assert [s.name for s in r0.stages] == ["seed 0", "baseline"]
    assert [s.name for s in r1.stages] == ["seed 0", "baseline", "seed 0 (w_p 0.1)", "baseline"]
    assert np.ptp(r0.points[0][:, 2]) < 1e-9 * tr.diagonal()
    e0, e1 = min(baselines(r0)), min(baselines(r1))
    assert e1 < 0.95 * e0 and np.isclose(e1, baselines(r1)[1])
    assert T.depth_rmse(tr, r1)[0] < T.depth_rmse(tr, r0)[0]


# Robust baseline and depth anchor (branch lift-energy, docs/lifting.md "Robust baseline and depth anchor"):
# beyond the paper, off by default. Measured noise-free at each truth's own view, default cues (the default
# lift in brackets): revolve 1.23 (3.11), spiral 34.42 (34.31), saddle 2.93 (7.45), wrinkle 8.96 (8.95),
# cross 13.66, every solve converged (16.21, the planar round unconverged), turret 11.01 (10.28) %. Since
# final_hold is the default (lift-hold3; the held solve keeps the class's depth anchor and the sign is decided
# before it): revolve 1.33 (3.08), spiral 34.42, saddle 3.05 (7.47), wrinkle 8.98 (8.95), cross 13.53 (16.38),
# turret 11.01 (10.28) %.
ROBUST = LiftParams(parallel_robust_deg=5.0, w_depth_anchor=10.0)
ROBUST_LIFTED = [
    ("revolve", 0.0137, {"parallel": (23, 38, 23), "planar": (9, 9, 10)}),
    ("spiral", 0.3460, {"parallel": (5, 13, 5)}),
    # 3.05 %; 3.12 % with the held solve's class depth anchor replaced by the hold's (lift-final)
    ("saddle", 0.0309, {"parallel": (12, 24, 12), "planar": (8, 8, 8)}),
    ("wrinkle", 0.0905, {"parallel": (22, 22, 22), "planar": (3, 3, 3)}),
    ("cross", 0.1380, {"parallel": (20, 60, 20), "orthogonal": (4, 12, 12), "planar": (6, 6, 6)}),
    ("turret", 0.1110, {"parallel": (22, 22, 22), "orthogonal": (8, 9, 10)}),
]


@pytest.mark.parametrize("name, bound, counts", ROBUST_LIFTED)
def test_robust_baseline_and_depth_anchor_against_the_truth(name, bound, counts):
    """``parallel_robust_deg`` = 5 (the kept baseline reweighted three times by the Geman-McClure weight of each
    parallel candidate's 3D angle) and ``w_depth_anchor`` = 10 (each cue class's rounds held near the depths
    the class started from). The saddle comes within 3.05 % of the issue's 3 % (2.93 % without ``final_hold``:
    its planar cues, all true, held hard cost 0.12 % points) and the revolve within 1.33 % of its 1 % (1.23 %);
    the default lift of both without the depth family prior (lift-wrinkle) is 2.3 and 2.4 times as far off.
    Every applied cue within ``applied_tol_deg``. Not
    the default: over the view grid 27 of 159 signs are wrong instead of 24, and the bundled arches get worse
    (docs/lifting.md); re-measured on lift-robust3 against today's default, 14 of 60 wrong signs on the depth-sign
    grid (0) and 8 of 159 on the views (5)."""
    tr = T.make(name)
    r = lift(tr.sketch, params=ROBUST)
    err, sign = T.depth_rmse(tr, r)
    assert r.converged and sign == 1 and err <= bound, (err, sign)
    scores = T.cue_scores(r, T.labels(tr))
    assert {k: scores[k][:3] for k in counts} == counts
    names = [s.name for s in r.stages]
    k = names.index("baseline reweighted 1")
    assert names[k: k + 3] == ["baseline reweighted 1", "baseline reweighted 2", "baseline reweighted 3"]
    assert all(s.converged for s in r.stages[k: k + 3])
    assert max(c.angle for c in r.cues if c.applied) <= ROBUST.applied_tol_deg
    if name in ("revolve", "saddle"):
        err0, _ = T.depth_rmse(tr, _nofam(name))
        assert err < 0.45 * err0, (err, err0)



#: The robust package with the trust bound on its reweighting (branch lift-robust3, docs/lifting.md).
GUARDED = replace(ROBUST, robust_max_move=0.12)


@pytest.mark.parametrize("case, same_as", [
    (("revolve", None), "robust"),      # the reweighting moves the depths by 0.046 of their spread: kept, 1.33 %
    (("saddle", None), "robust"),       # 0.071: kept, 3.05 %
    (("vase", (15.0, -50.0)), "default"),    # 0.375: discarded; ROBUST 20.0 % and the wrong sign, default 12.45 %
    (("revolve", (15.0, -50.0)), "default"),  # 0.188: discarded; ROBUST 22.8 % and the wrong sign
])
def test_robust_reweighting_within_its_trust_bound(case, same_as):
    """``robust_max_move`` (lift-robust3): a reweighted baseline whose depths moved by more than 0.12 of the
    baseline's depth spread is discarded, and with no reweighting kept the class depth anchor is off, so the lift
    is the default lift (to round-off: the reweighting's factorisations fill the ordering cache); within the bound
    it is ``ROBUST``'s. Where ROBUST takes the wrong sign on the depth-sign grid (14 of 60 lifts: the vase at tilt
    15-25 and at 35/+-25, the revolve at 15/+-50, where the reweighting deepens the lift by 0.18-0.44 of its spread
    into another basin; the arches at 35/+-25, whose reweighting moves nothing, by the class depth anchor alone)
    the guard keeps the default's right sign (0 of 60); at the truths' own views it keeps ROBUST's gains."""
    from tests.lifting.test_lifting import _example_truth

    name, view = case
    if view is None:
        tr = T.make(name)
    elif name == "revolve":
        tr = T.revolve(tilt=view[0], turn=view[1])
    else:
        tr = _example_truth(name, T.rotation(*view))
    r = lift(tr.sketch, params=GUARDED)
    ref = lift(tr.sketch, params=ROBUST if same_as == "robust" else DEFAULT)
    assert r.converged and ref.converged
    assert np.abs(r.points[0] - ref.points[0]).max() <= 1e-8, np.abs(r.points[0] - ref.points[0]).max()
    assert [c.applied for c in r.cues] == [c.applied for c in ref.cues]
    err, sign = T.depth_rmse(tr, r)
    assert sign == 1, err
    discarded = [s for s in r.stages if s.name.startswith("baseline reweighted") and s.discarded]
    assert bool(discarded) == (same_as == "default")
    if same_as == "default":   # and ROBUST itself takes the mirror there, without the depth family prior
        # (lift-wrinkle, on by default): with it ROBUST's revolve at 15/-50 is an extrusion-like lift that the
        # prior moves to 5.76 % at the right sign (22.8 % and the mirror without it; measured)
        assert T.depth_rmse(tr, lift(tr.sketch, params=replace(ROBUST, family_prior=False)))[1] == -1


def test_the_depth_sign_is_decided_before_the_held_solve():
    """``final_hold``'s solve only meets the last round's applied cues near that round's solution; the depth sign is
    decided on the round's solution. On the cross with the robust baseline and the depth anchor the from-above score
    is small (0.016) and the held solve moves it across 0 (measured +0.011 against -0.016 unflipped): decided after
    it, the sign came out wrong (13.58 %, lift-final). Decided before it, the held lift has the sign of the lift
    without the rule and scores slightly below 0 from above, the right sign at 13.53 % (13.66 % unheld)."""
    from auszug.lifting.reconstruct import from_above

    tr = T.make("cross")
    (_, g), = layer_graphs(tr.sketch)
    r, r0 = lift(tr.sketch, params=ROBUST), lift(tr.sketch, params=replace(ROBUST, final_hold=False))
    assert r.stages[-1].name == "planar held" and not r.stages[-1].discarded
    assert r.flipped == r0.flipped == (True,)
    assert from_above(r.points[0][g.segments]) < 0.0 < from_above(r0.points[0][g.segments])
    (err, sign), (err0, sign0) = T.depth_rmse(tr, r), T.depth_rmse(tr, r0)
    assert sign == sign0 == 1 and err < err0 < 0.1370, (err, err0)


# Consistency check of the parallel cues (branch lift-cues2, docs/lifting.md "Consistency check"): beyond the
# paper, off by default. Each parallel round is solved once more without the pull of the cues it would apply, the
# depths held near the class's first ones (w_confirm_anchor 10), and the cues whose angle then leaves I_b are
# rejected. Measured noise-free at each truth's own view: alone (CHECK), the parallel F1 rises on every truth with
# a false candidate (revolve 0.75 -> 0.85, spiral 0.56 -> 0.80, saddle 0.67 -> 0.69, cross 0.44 -> 0.85, turret
# 0.96 -> 1.00) and one true cue is lost (the spiral's), but the depth RMSE goes both ways: revolve 3.14 (3.11),
# spiral 41.21 (34.31), saddle 7.45, wrinkle 8.95, cross 4.43 (16.21), turret 15.09 (10.28) %. With the robust
# baseline and the per-class depth anchor (CONFIRM; ROBUST alone in brackets): revolve 1.15 (1.23), spiral 34.14
# (34.42), saddle 2.93 (2.93), wrinkle 8.96 (8.96), cross 13.63 (13.66), turret 11.01 (11.01) %, parallel cues
# applied revolve 28 (38), spiral 6 (13), saddle 23 (24), cross 27 (60). Since final_hold is the default
# (lift-hold3): CHECK revolve 3.11, spiral 41.17, saddle 7.47, wrinkle 8.95, cross 4.36, turret 15.09 %; CONFIRM
# revolve 1.18, spiral 34.01, saddle 3.06, wrinkle 8.98, cross 13.51, turret 11.01 %.
CHECK = LiftParams(parallel_confirm=True)
CONFIRM = LiftParams(parallel_robust_deg=5.0, w_depth_anchor=10.0, parallel_confirm=True)
CONFIRM_LIFTED = [
    (CHECK, "revolve", 0.0316, {"parallel": (23, 31, 23), "planar": (9, 9, 10)}),
    (CHECK, "spiral", 0.4140, {"parallel": (4, 5, 5), "planar": (0, 2, 0)}),
    (CHECK, "saddle", 0.0750, {"parallel": (12, 23, 12), "planar": (8, 8, 8)}),
    (CHECK, "wrinkle", 0.0900, {"parallel": (22, 22, 22), "planar": (3, 3, 3)}),
    (CHECK, "cross", 0.0450, {"parallel": (20, 27, 20), "orthogonal": (8, 18, 12), "planar": (2, 2, 6)}),
    (CHECK, "turret", 0.1520, {"parallel": (22, 22, 22), "orthogonal": (8, 12, 10)}),
    (CONFIRM, "revolve", 0.0120, {"parallel": (23, 28, 23), "planar": (9, 9, 10)}),
    (CONFIRM, "spiral", 0.3440, {"parallel": (5, 6, 5), "planar": (0, 2, 0)}),
    (CONFIRM, "saddle", 0.0309, {"parallel": (12, 23, 12), "planar": (8, 8, 8)}),  # 3.06 % (lift-final 3.13)
    (CONFIRM, "wrinkle", 0.0900, {"parallel": (22, 22, 22), "planar": (3, 3, 3)}),
    (CONFIRM, "cross", 0.1370, {"parallel": (20, 27, 20), "orthogonal": (4, 12, 12), "planar": (6, 6, 6)}),
    (CONFIRM, "turret", 0.1105, {"parallel": (22, 22, 22), "orthogonal": (8, 9, 10)}),
]


@pytest.mark.parametrize("params, name, bound, counts", CONFIRM_LIFTED)
def test_parallel_consistency_check_against_the_truth(params, name, bound, counts):
    """``parallel_confirm``: every truth with a false candidate applies fewer false ones than the paper's rule (the
    default lift's counts are pinned in ``LIFTED``), and only the spiral loses a true one (alone); with ``CONFIRM`` the
    revolve's parallel F1 reaches the issue's 0.9 and its depth RMSE 1.15 %. Every check solve converges, and the
    rounds' stage counts add up to the applied cues."""
    tr = T.make(name)
    r = lift(tr.sketch, params=params)
    err, sign = T.depth_rmse(tr, r)
    # the cross with CONFIRM is mirrored since lift-sign2: a tie for the sign rule (edges -0.005 for the mirror,
    # its rib planes +0.008 for the lift as solved), a lift 13.6 % off at either sign (docs/lifting.md, Depth sign)
    want = -1 if (params is CONFIRM and name == "cross") else 1
    assert r.converged and sign == want and err <= bound, (err, sign)
    scores = T.cue_scores(r, T.labels(tr))
    assert {k: scores[k][:3] for k in counts} == counts
    checks = [s for s in r.stages if s.name.startswith("parallel round") and s.name.endswith(" check")]
    assert checks and all(s.converged for s in checks)
    rounds = [s for s in r.stages if s.name.startswith("parallel round") and not s.name.endswith(" check")]
    assert sum(s.applied for s in rounds) == scores["parallel"][1]
    assert max(c.angle for c in r.cues if c.applied) <= params.applied_tol_deg
    if params is CONFIRM and name == "revolve":
        assert scores["parallel"][3] >= 0.9


def test_parallel_consistency_check_without_its_depth_anchor():
    """With ``w_confirm_anchor`` 0 the check solve is free in depth: on the cross it rejects 48 of the 50 false
    parallel cues the default lift applies (F1 0.95 against 0.44) and the lift comes within 3.65 % of the truth
    (16.21 % by default), but on the revolve it rejects 12 of the 23 true cues too (11.45 %, the wrong sign)."""
    free = LiftParams(parallel_confirm=True, w_confirm_anchor=0.0)
    tr = T.make("cross")
    r = lift(tr.sketch, params=free)
    err, sign = T.depth_rmse(tr, r)
    assert r.converged and sign == 1 and err <= 0.0370, (err, sign)
    assert T.cue_scores(r, T.labels(tr))["parallel"][:3] == (20, 22, 20)
    tr = T.make("revolve")
    r = lift(tr.sketch, params=free)
    assert T.cue_scores(r, T.labels(tr))["parallel"][:3] == (11, 15, 23)
    assert T.depth_rmse(tr, r)[0] > 0.10
