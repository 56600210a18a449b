"""Sketch lifting: the graph, the likelihood, bad input, and ground truth with known depths."""

from __future__ import annotations

import numpy as np
import pytest

from auszug.errors import GeometryError
from auszug.lifting import DEFAULT, Marker, Sketch, Stroke, layer_graphs, lift, sketch_graph
from auszug.lifting.cues import likelihood, parallel_cues
from auszug.lifting.reconstruct import DEFAULT_CLASSES
from tests.lifting.truth import box, depth_rmse, revolve, truth_points

H = Stroke(np.array([[[-1, 0], [-0.4, 0.25], [0.4, 0.25], [1, 0]]], float), "h")
V = Stroke(np.array([[[0.3, -1], [0.1, -0.3], [-0.1, 0.3], [-0.3, 1]]], float), "v")


def test_likelihood_bounds_as_the_paper_states():
    L = likelihood(np.array([0.0, DEFAULT.inner_deg, DEFAULT.outer_deg, DEFAULT.outer_deg + 1e-9]), DEFAULT)
    assert L.tolist()[:2] == [1.0, 1.0]
    assert L[2] == pytest.approx(0.005, rel=1e-12) and L[3] == 0.0
    a = np.linspace(5, 15, 50)
    assert np.all(np.diff(likelihood(a, DEFAULT)) < 0)   # strictly falling between the bounds


def test_graph_splits_strokes_at_the_crossing_and_shares_the_point():
    g = sketch_graph(Sketch((H, V)))
    assert len(g.segments) == 4 and len(g.crossings) == 1
    c = g.crossings[0]
    assert c.smooth and sorted(set(c.strokes)) == [0, 1]
    # the four half-edges end at one shared control point
    assert {int(g.segments[s, 0 if e == 0 else 3]) for s, e in c.ends} == {c.point}
    assert g.joint_g1.all()


@pytest.mark.parametrize("dx", [0.0, 1e-12, 3e-7, 2e-6, 1e-5])
def test_a_crossing_at_a_knot_is_not_split_into_a_point(dx):
    """A stroke crossing another within the merge distance (1e-6 of the diagonal) of its knot meets it at
    the knot: no zero-length piece (once a split at t = 1 - 1e-7 left a segment shrunk to a point and a
    zero handle, and the lift stopped with "Factor is exactly singular"); beyond it, a split there."""
    a = np.array([[[-1.0, 0.2], [-0.6, 0.1], [-0.3, 0.0], [0.0, 0.0]],
                  [[0.0, 0.0], [0.3, 0.0], [0.6, 0.1], [1.0, 0.2]]])           # G1 at its knot (0, 0)
    b = np.array([[[dx - 0.1, -1.0], [dx - 0.05, -0.4], [dx, -0.2], [dx, 0.0]],
                  [[dx, 0.0], [dx, 0.2], [dx + 0.05, 0.4], [dx + 0.1, 1.0]]])  # crosses it there, G1 too
    g = sketch_graph(Sketch((Stroke(a, "a"), Stroke(b, "b"))))
    P = g.points
    ends = np.linalg.norm(P[g.segments[:, 3]] - P[g.segments[:, 0]], axis=1)
    handles = np.linalg.norm(P[g.segments[:, [1, 2]]] - P[g.segments[:, [0, 3]]], axis=2)
    assert ends.min() > 1e-6 and handles.min() > 3e-7          # graph units: the diagonal is 1
    assert len(g.crossings) == 1 and g.crossings[0].smooth
    # at the knot (within the merge distance) both strokes keep their two segments; beyond it, a is split
    assert len(g.segments) == (4 if dx < 1e-6 * g.scale else 5)       # dx = 1e-5: 3.5e-6 of the diagonal


def test_occlusion_marker_removes_the_crossing():
    p = sketch_graph(Sketch((H, V))).points[sketch_graph(Sketch((H, V))).crossings[0].point]
    g = sketch_graph(Sketch((H, V)))
    xy = p * g.scale + g.offset
    with pytest.raises(GeometryError, match="no intersection"):
        sketch_graph(Sketch((H, V), (Marker("occlusion", xy, "m1"),)))


@pytest.mark.parametrize("sketch, message", [
    (Sketch(()), "no strokes"),
    (Sketch((H, Stroke(np.full((1, 4, 2), np.nan), "bad"))), "bad: coordinates are not finite"),
    (Sketch((H, V, Stroke(V.controls.copy(), "v2"))), "v2: duplicate of v"),
    (Sketch((H, Stroke(H.controls + [0, 5], "far"))), "no intersection"),
    (Sketch((H, V), (Marker("flip", np.array([0.9, 0.9]), "lonely"),)), "flip marker lonely"),
    (Sketch((H, Stroke(np.zeros((1, 4, 2)), "dot"))), "dot: zero-length"),
])
def test_bad_sketches_name_the_element(sketch, message):
    with pytest.raises(GeometryError, match=message):
        lift(sketch)


def test_disconnected_parts_without_layers_are_refused():
    far = Sketch((H, V, Stroke(H.controls + [10, 0], "h2"), Stroke(V.controls + [10, 0], "v2")))
    with pytest.raises(GeometryError, match="h2, v2: not joined"):
        lift(far)
    layered = Sketch((H, V, Stroke(H.controls + [10, 0], "h2", 1), Stroke(V.controls + [10, 0], "v2", 1)))
    assert lift(layered).converged


@pytest.fixture(scope="module")
def truth():
    return revolve()


@pytest.fixture(scope="module")
def baseline(truth):
    return lift(truth.sketch, classes=())


@pytest.fixture(scope="module")
def default_lift(truth):
    return lift(truth.sketch)


def test_revolve_baseline_recovers_the_depth(truth, baseline):
    """Meridians and parallels of a vase: fidelity + hard orthogonality at the smooth crossings."""
    err, sign = depth_rmse(truth, baseline)
    assert baseline.converged
    # every solve converged (KKT residual), none from a discarded seed; measured 4 solves, 31 Newton steps
    assert all(s.converged and not s.discarded for s in baseline.stages)
    assert sum(s.iterations for s in baseline.stages) <= 50
    assert sign == 1                       # the view from above picks the true sign
    assert err <= 0.018                    # measured 1.78 % of the diagonal (1.27 % with the paper's w_a = 10)
    ortho = [c.angle for c in baseline.cues if c.kind == "smooth-orthogonal"]
    assert len(ortho) == 24 and max(ortho) < 1e-6


def test_revolve_with_the_default_cues(truth, default_lift):
    r = default_lift
    err, sign = depth_rmse(truth, r)
    assert r.converged and sign == 1
    assert err <= 0.032                    # measured 3.11 %: the progressive stage costs accuracy here
    applied = [c for c in r.cues if c.applied]
    assert all(c.angle <= DEFAULT.inner_deg for c in applied if c.kind != "parallel")
    stages = [s.name for s in r.stages]
    assert stages[0].startswith("seed") and "baseline" in stages


def test_network_is_the_lift_and_lies_on_the_sketch(truth, baseline):
    net = baseline.network
    assert {p.kind for p in net.pieces} == {"sketch"}
    assert len({p.basic for p in net.pieces}) == len(truth.sketch.strokes)
    # seen along z, every curve is within 2 % of the diagonal of its stroke (projection accuracy is soft)
    d = truth.diagonal()
    for p in net.pieces:
        stroke = truth.sketch.strokes[p.basic].controls
        q = p.point_t(np.linspace(0, 1, 5))[:, :2]
        from auszug.geometry import CubicBezier
        dist = [min(np.linalg.norm(CubicBezier.from_array(s).point(CubicBezier.from_array(s).project(x)) - x)
                    for s in stroke) for x in q]
        assert max(dist) < 0.02 * d


@pytest.mark.parametrize("classes, bound", [((), 3e-5), (("parallel", "orthogonal", "planar"), 5e-5)])
def test_box_of_straight_strokes_lifts(classes, bound):
    """Nine edges and six face sections, all straight: every crossing orthogonal in 3D.

    Measured: depth RMSE 2.5e-5 (baseline; 3.5e-6 with the paper's baseline w_a = 10) and 1.7e-5
    (default cues) of the diagonal, the residue of
    the foreshortening term; all solves converged; the hard orthogonality met to 1e-11 deg.
    """
    tr = box()
    r = lift(tr.sketch, classes=classes)
    err, sign = depth_rmse(tr, r)
    assert r.converged and all(s.converged and not s.discarded for s in r.stages)
    assert sign == 1 and err <= bound
    smooth = [c.angle for c in r.cues if c.kind == "smooth-orthogonal"]
    assert len(smooth) == 15 and max(smooth) < 1e-9
    # the occlusion marker removed the one accidental crossing (two sections' overshoots)
    assert len(tr.sketch.markers) == 1
    applied = [c for c in r.cues if c.applied and c.kind != "smooth-orthogonal"]
    assert all(c.angle < 1e-3 for c in applied)


@pytest.mark.parametrize("noise, seed", [(0.005, 0), (0.005, 1), (0.005, 2), (0.01, 0), (0.01, 1), (0.01, 2)])
def test_revolve_baseline_with_noise(truth, baseline, noise, seed):
    """2D noise of 0.5 % and 1 % of the diagonal (a smooth random displacement field, truth.py) on the vase.

    The issue's target: at most twice the noise-free error. Measured (baseline w_a = 1): 1.82, 1.61,
    1.74 % at 0.5 % and 2.38, 1.79, 2.29 % at 1 % for seeds 0-2, against 1.78 % noise-free; every
    solve converges. With the paper's baseline w_a = 10: 1.37, 1.47, 1.63 % and 4.78, 1.51, 6.18 %
    against 1.27 %, so 1 % noise missed the target (docs/lifting.md).
    """
    err0, _ = depth_rmse(truth, baseline)
    tr = revolve(noise=noise, seed=seed)
    r = lift(tr.sketch, classes=())
    err, sign = depth_rmse(tr, r)
    assert r.converged and sign == 1
    assert err <= 2 * err0, (err, err0)


@pytest.mark.parametrize("seed", range(3))
def test_revolve_default_cues_with_one_percent_noise(truth, default_lift, seed):
    """The default cues on the vase with 1 % noise: within twice the noise-free error (measured 3.93, 3.09,
    4.57 % against 3.11 %; with the paper's baseline w_a = 10: 2.62, 8.61, 4.58 % against 3.13 %). Every
    solve converges since the solver uses the exact Hessian of the soft orthogonality rows (lifting8);
    before, seed 0's orthogonal round ran 60 Gauss-Newton steps without converging (3.08 % there)."""
    err0, _ = depth_rmse(truth, default_lift)
    tr = revolve(noise=0.01, seed=seed)
    r = lift(tr.sketch)
    err, sign = depth_rmse(tr, r)
    assert sign == 1 and r.converged
    assert err <= 2 * err0, (err, err0)


@pytest.mark.parametrize("seed", range(3))
def test_box_with_half_a_percent_of_noise_and_the_cues(seed):
    """The box with 0.5 % noise: the cues pull it back (measured 0.50, 0.71, 0.99 % with the default
    cues against 1.36, 1.13, 0.71 % for the baseline). The sign is right for every seed: the view from
    above decides it (``from_above``); the convexity votes alone picked the mirror for seed 1, since a
    noisy straight stroke's curvature votes at random."""
    tr = box(noise=0.005, seed=seed)
    r = lift(tr.sketch)
    err, sign = depth_rmse(tr, r)
    assert r.converged
    assert err <= 0.011
    assert sign == 1


def test_revolve_parallel_cues_against_the_truth(truth):
    """Precision and recall of tangent parallelism on the vase, labels from the 3D truth (angle <= I_b).

    Of 38 candidates 23 are parallel in 3D (18 exactly, 5 at 1.2 deg); the other 15 (5.4-8.2 deg, the
    taper of the vase) are applied too: the cue term outweighs fidelity, which hardly resists depth
    changes (docs/lifting.md). Measured precision 23/38, recall 1, F1 0.75 (issue target 0.9: not met).
    """
    (_, g), = layer_graphs(truth.sketch)
    par = parallel_cues(g, DEFAULT)
    true_parallel = par.angles(truth_points(truth, g)) <= DEFAULT.inner_deg
    r = lift(truth.sketch)
    applied = np.array([c.applied for c in r.cues if c.kind == "parallel"])
    assert len(applied) == len(par) == 38 and true_parallel.sum() == 23
    tp = int((applied & true_parallel).sum())
    assert tp == 23 and int(applied.sum()) == 38


def test_parallel_resolution_follows_the_paper_on_the_vase(truth, baseline):
    """Sec. 5.3's rounding checked step by step on the vase (lifting5 audit, docs/lifting.md).

    The likelihood is taken on the 3D angles of the network each round's solve returns: a cue is
    applied exactly when its 3D angle after the round is within I_b (L = 1). The 15 false candidates
    (taper, 5.4-8.2 deg in the truth) are not kept soft for many rounds: 12 of them are already within
    I_b on the baseline (1.3-4.2 deg: L = 1 before any cue round; 7 with the paper's baseline
    w_a = 10), and one round of w_c L C^2 pulls the other 3 (5.3-6.6 deg) within I_b too, so all 38
    are applied in round 1. Measured depth RMSE with parallelism alone 3.08 % of the diagonal.
    """
    (_, g), = layer_graphs(truth.sketch)
    par = parallel_cues(g, DEFAULT)
    true_parallel = par.angles(truth_points(truth, g)) <= DEFAULT.inner_deg
    base = np.array([c.angle for c in baseline.cues if c.kind == "parallel"])
    assert len(base) == 38 and not any(c.applied for c in baseline.cues if c.kind == "parallel")
    assert base[true_parallel].max() < 1.7 and base[~true_parallel].max() > 6.5
    assert int((base[~true_parallel] <= DEFAULT.inner_deg).sum()) == 12  # L = 1 on the baseline already
    r = lift(truth.sketch, classes=("parallel",))
    rounds = [s for s in r.stages if s.name.startswith("parallel round")]
    assert [(s.applied, s.rejected) for s in rounds] == [(38, 0)]
    # nothing is solved after the last round: the reported angles are the 3D angles it was classified on
    ang = np.array([c.angle for c in r.cues if c.kind == "parallel"])
    app = np.array([c.applied for c in r.cues if c.kind == "parallel"])
    assert np.array_equal(app, likelihood(ang, DEFAULT) >= 1.0)
    err, sign = depth_rmse(truth, r)
    assert sign == 1 and 0.030 <= err <= 0.032   # measured 3.08 %


def _example_truth(name: str, R: np.ndarray | None = None):
    """The 3D truth of a bundled example sketch, projected exactly as tests/lifting/make_sketches.py does.

    ``R``: another view rotation than the example's own.
    """
    from tests.lifting import make_sketches as ms
    from tests.lifting.truth import Truth

    chains = {"vase": ms.vase, "ogee-roof": ms.ogee_roof, "arches": ms.arches}[name]()
    s2, view = ms.project(chains, ms.VIEWS[name] if R is None else R, 0.0, 0)
    diag = float(np.linalg.norm(np.ptp(np.concatenate([v.reshape(-1, 3) for v in view]), axis=0)))
    marks = ms.spurious(s2, view, 0.02 * diag)
    sk = Sketch(tuple(Stroke(c, f"c{i}") for i, c in enumerate(s2)),
                tuple(Marker("occlusion", m, f"o{i}") for i, m in enumerate(marks)))
    return Truth(sk, tuple(view))


@pytest.mark.parametrize("name, sign, base_bound, cue_bound", [
    ("vase", 1, 0.020, 0.031),          # measured 1.96 % baseline, 2.95 % default cues (the family prior rejected)
    ("ogee-roof", 1, 0.023, 0.021),     # measured 2.18 %, 1.96 % (3.48, 3.34 % before lift-wrinkle's family prior)
    ("arches", 1, 0.043, 0.041),        # measured 4.15 %, 3.97 % (9.96, 9.17 % before it)
])
def test_bundled_examples_against_their_truth(name, sign, base_bound, cue_bound):
    """Depth RMSE and depth sign of the three example sketches against the 3D truths they were drawn from.

    Measured on branch lifting6 (docs/lifting.md): none meets the issue's accuracy targets. The sign is
    right for all three since lifting6 (the view-from-above rule, ``from_above``); the convexity votes
    alone picked the mirror image for the ogee roof and the arches. These are the exact projections of
    the objects the bundled SVGs draw by hand (``make_sketches.hand_drawn``; those files:
    ``test_shipped_example_svgs_lift_with_the_true_depth_sign``). The arches came out flatter
    than the truth (docs/lifting.md); since lift-wrinkle the depth family prior (``family_prior``: the
    ogee roof and the arches are extrusions) takes the member of isotropic extent instead of the flattest.
    """
    tr = _example_truth(name)
    for classes, bound in (((), base_bound), (DEFAULT_CLASSES, cue_bound)):
        r = lift(tr.sketch, classes=classes)
        err, s = depth_rmse(tr, r)
        assert r.converged and s == sign and err <= bound, (name, classes, err, s)


@pytest.mark.parametrize("name, bound", [("vase", 0.031), ("ogee-roof", 0.028), ("arches", 0.080)])
def test_shipped_example_svgs_lift_with_the_true_depth_sign(name, bound):
    """The bundled SVG files themselves (as a user opens them) against their 3D truths: right sign.

    The files are drawn by hand (make_sketches.hand_drawn, seed 0 of each): their truth is the drawn
    strokes lifted by the object's depth. make_sketches.svg maps the view coordinates to SVG pixels by
    a uniform scale, a shift and the y flip that the reader undoes, so the truth in the reader's
    coordinates is the drawn 3D strokes scaled by the same factor. Measured depth RMSE (default cues):
    2.91, 2.62, 7.63 % (the same drawings unrounded: 2.91, 3.41, 10.08 %; the exact projections of
    the same objects as the files were before the hand: 2.95, 2.13, 6.96 %); six seeds of the hand in
    docs/lifting.md.
    """
    from auszug import examples
    from auszug.formats import load
    from tests.lifting import make_sketches as ms
    from tests.lifting.truth import Truth

    s2, s3, marks = ms.drawn(name)
    pts = np.concatenate([s.reshape(-1, 2) for s in s2])
    lo, hi = pts.min(0), pts.max(0)
    scale = 520.0 / float(max(hi - lo))
    shift = np.array([40.0 - lo[0] * scale, -hi[1] * scale - 40.0, 0.0])
    sketch = load(examples.path(f"sketches/{name}.svg"), kind="sketch")
    assert [s.id for s in sketch.strokes] and len(sketch.strokes) == len(s3)
    assert len(sketch.markers) == len(marks) == {"vase": 0, "ogee-roof": 7, "arches": 2}[name]
    tr = Truth(sketch, tuple(v * scale + shift for v in s3))
    # the reader's strokes are the drawn strokes (to the SVG's 0.01 px rounding)
    for s, v in zip(sketch.strokes, tr.chains3d, strict=True):
        assert np.abs(s.controls - v[:, :, :2]).max() <= 0.006
    r = lift(sketch)
    err, sign = depth_rmse(tr, r)
    assert r.converged and sign == 1 and err <= bound, (err, sign)


def test_hand_drawn_sketch_is_drawn_by_a_hand():
    """make_sketches.hand_drawn: the strokes are the object's within the hand's reach, not its projection.

    Each drawn point lies within 1.5 % of the diagonal of the exact projection (measured 0.78-1.14 %;
    the wobble's standard deviation is 0.4 %, the tremor's 0.1 %), the pen's knots are its own (a
    curved stroke has one cubic per fifth of the diagonal, so the vase's strokes are not split at its
    crossings), corners stay
    corners (the ogee roof's ridges), straight strokes stay straight, the drawn depth is the truth's
    at the drawn point's origin (linear in the 3D stroke), and the same seed draws the same sketch.
    """
    from auszug.geometry import CubicBezier
    from tests.lifting import make_sketches as ms

    for name, make in (("vase", ms.vase), ("ogee-roof", ms.ogee_roof), ("arches", ms.arches)):
        chains = make()
        R = ms.VIEWS[name]
        s2, s3 = ms.hand_drawn(chains, R, 0)
        again, _ = ms.hand_drawn(chains, R, 0)
        other, _ = ms.hand_drawn(chains, R, 1)
        view = [c @ R.T for c in chains]
        diag = float(np.linalg.norm(np.ptp(np.concatenate([v.reshape(-1, 3) for v in view])[:, :2], axis=0)))
        ts = np.linspace(0, 1, 201)
        moved = []
        for c2, c3, v in zip(s2, s3, view, strict=True):
            assert np.array_equal(c2, c3[:, :, :2]) and np.array_equal(c3[1:, 0], c3[:-1, 3])
            d = [CubicBezier.from_array(seg[:, :2]) for seg in v]
            for seg in c2:
                for q in CubicBezier.from_array(seg).point(ts):
                    moved.append(min(np.linalg.norm(b.point(b.project(q)) - q) for b in d))
            if len(v) == 1 and name != "vase":       # ruled: the drawn segment is straight too
                a, b = c2[0, 0], c2[0, 3]
                u = (b - a) / np.linalg.norm(b - a)
                assert np.abs((c2[0] - a) @ [-u[1], u[0]]).max() <= 1e-12 * diag
        moved = np.array(moved)
        assert 1e-3 * diag <= moved.max() <= 0.015 * diag, (name, moved.max() / diag)
        assert all(np.array_equal(a, b) for a, b in zip(s2, again, strict=True))
        assert any(not np.array_equal(a, b) for a, b in zip(s2, other, strict=True))
    # the vase's meridians: 4 cubics each in the truth (knots at the parallels), 3-4 by the pen, knots elsewhere
    s2, _ = ms.hand_drawn(ms.vase(), ms.VIEWS["vase"], 0)
    assert [len(c) for c in s2[:5]] != [4] * 5
    # the ogee roof's sections keep their pointed ridge: the tangents there more than 60 deg apart
    s2, _ = ms.hand_drawn(ms.ogee_roof(), ms.VIEWS["ogee-roof"], 0)
    for c in s2[:3]:
        turns = []
        for a, b in zip(c[:-1], c[1:], strict=True):
            ta, tb = a[3] - a[2], b[1] - b[0]
            turns.append(np.degrees(np.arccos(np.clip(ta @ tb / np.linalg.norm(ta) / np.linalg.norm(tb), -1, 1))))
        assert max(turns) > 60.0 and sorted(turns)[-2] < 1e-4, turns


@pytest.mark.parametrize("tilt", [5.0, 10.0, 20.0, 30.0])
def test_view_from_above_score_on_the_exact_truths(tilt):
    """``from_above`` on the true 3D networks (no lift): positive seen from above, the mirror's is its negative.

    Five objects (the three example objects, the box, the revolve), 7 turns from -80 to 70 deg at each
    tilt: measured minimum scores 0.12 (tilt 5) to 0.28 (tilt 30). The rule assumes a tilt below 45 deg:
    at tilt 40 the revolve's score is already negative (measured -0.13 to -0.24 for turns -35..40).
    """
    from auszug.lifting import from_above
    from tests.lifting import make_sketches as ms
    from tests.lifting.truth import rotation

    objects = [ms.vase(), ms.ogee_roof(), ms.arches()]
    for turn in (-80.0, -60.0, -35.0, -10.0, 15.0, 40.0, 70.0):
        R = rotation(tilt, turn)
        nets = [np.concatenate([c @ R.T for c in chains]) for chains in objects]
        nets += [np.concatenate(box(tilt=tilt, turn=turn).chains3d),
                 np.concatenate(revolve(tilt=tilt, turn=turn).chains3d)]
        for k, net in enumerate(nets):
            s = from_above(net)
            assert s > 0.1, (k, turn, s)
            assert from_above(net * [1.0, 1.0, -1.0]) == -s          # exactly antisymmetric under z -> -z
            assert from_above(net * 7.5 + [3.0, -2.0, 1.0]) == pytest.approx(s, abs=1e-12)   # scale, shift
    assert from_above(np.zeros((2, 4, 3))) == 0.0


def test_depth_sign_over_views():
    """Wrong-sign rate of the lifts (baseline) over 16 views: the three example objects and the box at
    tilts 20 and 30 deg, turns -40 and 30 deg. Measured: 0 wrong (the issue's target: at most 5 %),
    every solve converged. With the convexity votes alone (the rule before lifting6) the ogee roof and
    the arches came out mirrored in most views. On a wider grid (tilts 15, 25, 35; turns +-25, +-50;
    60 lifts with the revolve): 4 of 60 wrong now, all in lifts 14-19 % off the truth at either sign;
    25 of 60 before (docs/lifting.md).
    """
    from tests.lifting.truth import rotation

    wrong = []
    for tilt in (20.0, 30.0):
        for turn in (-40.0, 30.0):
            truths = [(n, _example_truth(n, rotation(tilt, turn))) for n in ("vase", "ogee-roof", "arches")]
            truths.append(("box", box(tilt=tilt, turn=turn)))
            for name, tr in truths:
                r = lift(tr.sketch, classes=())
                err, sign = depth_rmse(tr, r)
                assert r.converged, (name, tilt, turn)
                if sign != 1:
                    wrong.append((name, tilt, turn, err))
    assert wrong == []


@pytest.mark.parametrize("name, tilt, turn, bound", [
    # measured with final_hold (on by default since lift-hold3; without it in brackets) | default cues
    ("revolve", 25.0, 25.0, 0.0315),   # 3.04 % (2.92 %) | 6.19 %, the wrong sign
    ("revolve", 35.0, -25.0, 0.0370),  # 3.57 % (3.48 %) | 3.11 %, the wrong sign
    ("vase", 25.0, 50.0, 0.0620),      # 5.98 % (6.20 %) | 9.77 %, the wrong sign
    ("vase", 35.0, -50.0, 0.0910),     # 8.85 % (8.60 %) | 5.08 %, the wrong sign
])
def test_consistency_check_lifts_of_the_depth_sign_grid(name, tilt, turn, bound):
    """The depth-sign grid of docs/lifting.md with the cues (branch lift-cues2, ``eval_lifting signs``): the
    default cues got 12 of its 60 signs wrong before lift-sign2 (the vase and the revolve at tilts 25 and 35 deg;
    none since, by the vertical planes of ``depth_sign_score``), the baseline 4, the consistency check of the
    parallel cues (``parallel_confirm``, off by default) none. Four of those views; every applied cue within
    ``applied_tol_deg`` (the last round's held by ``final_hold``; without it up to 4.45 deg measured on these
    four)."""
    from auszug.lifting import LiftParams
    from tests.lifting.truth import rotation

    tr = revolve(tilt=tilt, turn=turn) if name == "revolve" else _example_truth(name, rotation(tilt, turn))
    r = lift(tr.sketch, LiftParams(parallel_confirm=True))
    err, sign = depth_rmse(tr, r)
    assert sign == 1 and err <= bound, (err, sign)
    assert max(c.angle for c in r.cues if c.applied) <= LiftParams().applied_tol_deg


def test_the_inexact_inner_solves_leave_the_lift_as_the_exact_ones():
    """``soc_tol`` and ``refine_inexact`` (lift-speed4) only loosen inner GMRES solves: the vase truth
    with 1 % noise (seed 2; its rounds apply some cues and reject others) lifts with the same
    cues, flags and solves as with every solve to 1e-13, the control points within 1e-9 of the
    diagonal (measured 1.2e-11 on this sketch; on the 100-curve benchmark 1e-12)."""
    from auszug.lifting import LiftParams

    tr = revolve(noise=0.01, seed=2)
    fast = lift(tr.sketch)
    exact = lift(tr.sketch, LiftParams(soc_tol=0.0, refine_inexact=False))
    assert DEFAULT.soc_tol > 0 and DEFAULT.refine_inexact   # the defaults are the inexact ones
    assert [(c.kind, c.where, c.applied) for c in fast.cues] == [(c.kind, c.where, c.applied) for c in exact.cues]
    resolved = [c.applied for c in fast.cues if c.kind != "smooth-orthogonal"]
    assert any(resolved) and not all(resolved)              # cues applied and cues rejected
    assert fast.converged and exact.converged and fast.flipped == exact.flipped
    assert [s.name for s in fast.stages] == [s.name for s in exact.stages]
    diag = tr.sketch.diagonal()
    for a, b in zip(fast.points, exact.points, strict=True):
        assert np.abs(a - b).max() <= 1e-9 * diag


def test_layer_graphs_are_memoised_per_sketch_while_its_content_stays():
    """A second call on the same sketch returns the same graphs (read-only arrays); a stroke changed in
    place, other parameters or an equal copy of the sketch build them again."""
    h, v = Stroke(H.controls.copy(), "h"), Stroke(V.controls.copy(), "v")
    sk = Sketch((h, v))
    (_, g), = layer_graphs(sk)
    assert layer_graphs(sk)[0][1] is g
    assert not g.points.flags.writeable and not g.segments.flags.writeable
    with pytest.raises(ValueError):
        g.points[0, 0] = 1.0
    copy = Sketch((Stroke(H.controls.copy(), "h"), Stroke(V.controls.copy(), "v")))
    assert copy.fingerprint() == sk.fingerprint()
    (_, g_copy), = layer_graphs(copy)
    assert g_copy is not g and np.array_equal(g_copy.points, g.points)
    from auszug.lifting import LiftParams
    assert layer_graphs(sk, LiftParams(snap=0.02))[0][1] is not g
    h.controls[0, 0] += [0.0, 0.1]          # in place: the fingerprint changes, the graph is rebuilt
    assert sk.fingerprint() != copy.fingerprint()
    (_, g2), = layer_graphs(sk)
    assert g2 is not g and not np.array_equal(g2.points, g.points)


@pytest.mark.parametrize("kw, message", [
    ({"soc_tol": 1.0}, "soc_tol must lie in"),
    ({"soc_tol": -1e-8}, "soc_tol must be a finite number >= 0"),
    ({"soc_tol": float("nan")}, "soc_tol must be a finite number >= 0"),
])
def test_solver_tolerances_are_validated(kw, message):
    from auszug.lifting import LiftParams

    with pytest.raises(GeometryError, match=message):
        LiftParams(**kw)
