"""Microarch members as sweep fixtures (issue 11, evaluation): the project's own members, whose profile and
motion are known exactly (``sweeps.fixtures.swept_members``, meshing's sweep model on a bundled network).

Targets of the issue: plane recall >= 0.95 clean / >= 0.85 at sigma 5e-4, profile Hausdorff <= 1e-3
clean, median rotation error <= 0.5 deg, translation <= 1e-3, coverage >= 95 % clean. Measured
(docs/sweeps.md, "Microarch members"); asserted here is what holds, with the measured values beside.
"""

from __future__ import annotations

from functools import cache

import numpy as np

from auszug import examples
from auszug.formats import load
from auszug.meshing import Look, members_of
from auszug.microarch import build
from auszug.sweeps import DEFAULT, detect
from auszug.sweeps.detect import SweepReport
from auszug.sweeps.fixtures import sweep_errors, swept_members
from auszug.sweeps.motion import Motion
from auszug.sweeps.patches import SweepPatch

U30 = "legacy/U.XI.30.uc"          # one ogee member, cut at a mirror plane at both ends
U29 = "web/U.XI.29.uc"             # two ogee members, free ends
U91 = "web/U.XI.91.uc"             # four members


@cache
def _net(name):
    return build(load(examples.path(name)))


@cache
def _fixture(name, sigma=0.0):
    return swept_members(_net(name), sigma=sigma)


def test_the_fixture_is_the_members_mesh_normalised_with_its_exact_truth():
    net = _net(U30)
    fx = _fixture(U30)
    (mb,) = members_of(net, Look("bar"))
    assert len(fx.vertices) == len(mb.vertices) and np.array_equal(fx.faces, mb.faces)
    ext = np.ptp(fx.vertices, axis=0)
    assert abs(float(np.linalg.norm(ext)) - 1.0) < 1e-12
    assert np.allclose(fx.vertices.max(axis=0), -fx.vertices.min(axis=0), atol=1e-12)
    # every ring of the swept square away from the cut ends is the true profile in the true frame
    (run,) = fx.runs
    scale = float(np.linalg.norm(np.ptp(mb.vertices, axis=0)))
    corners = np.asarray(mb.sweeps[0].profile.points, float) / scale
    for k in range(20, len(run.s) - 20, 20):
        ring = run.origin[k] + corners @ run.rotation[k][:, :2].T
        d = np.linalg.norm(ring[:, None, :] - fx.vertices[None], axis=2).min(axis=1)
        assert d.max() < 1e-12
    # the true profile is the square (densely), its length the square's perimeter
    assert fx.closed and abs(fx.profile_length - 4 * np.linalg.norm(corners[1] - corners[0])) < 1e-12
    assert np.allclose(np.abs(fx.profile).max(axis=0), np.abs(corners).max(axis=0))
    # 20 planes per run, normal to the path: each passes through the path's point there
    assert fx.planes.shape == (20, 4) and np.allclose(np.linalg.norm(fx.planes[:, :3], axis=1), 1.0)
    noisy = _fixture(U30, 5e-4)
    dev = np.linalg.norm(noisy.vertices - fx.vertices, axis=1)
    assert 3e-4 < float(np.sqrt(np.mean(dev**2))) < 7e-4


def _true_patch(fx, a, b, knots=65, turn=0.0):
    """A patch made from the truth: the profile at parameter ``a`` moved to ``b`` by the true motion,
    at every knot but the middle one (the reference of ``sweep_errors``) turned ``turn`` degrees more
    about the path's tangent through the path's point."""
    from scipy.spatial.transform import Rotation

    run = fx.runs[0]
    s = np.linspace(a, b, knots)
    rot, org = run.at(s)
    prof = org[0] + fx.profile @ rot[0][:, :2].T
    rel = rot @ rot[0].T
    tr = org - np.einsum("kij,j->ki", rel, org[0])
    ang = np.radians(turn) * (np.arange(knots) != knots // 2)
    extra = Rotation.from_rotvec(rot[:, :, 2] * ang[:, None]).as_matrix()
    # x -> E (x - o_k) + o_k after the true map
    rel, tr = extra @ rel, np.einsum("kij,kj->ki", extra, tr - org) + org
    return SweepPatch(0, "general", prof, True, Motion(np.arange(knots, dtype=float), rel, tr),
                      np.arange(len(fx.faces)), 0.0, 1.0)


def _report(patches):
    return SweepReport(tuple(patches), 1.0, 1.0, np.zeros(3), 0, 0, ())


def test_sweep_errors_are_zero_for_the_truth_and_see_a_turn_about_the_path():
    fx = _fixture(U30)
    run = fx.runs[0]
    lo, hi = run.s[0], run.s[-1]
    e = sweep_errors(_report([_true_patch(fx, lo, hi)]), fx)
    assert e.recall == 1.0 and e.run.tolist() == [0]
    assert e.hausdorff[0] < 1e-6 and e.rotation[0] < 1e-3 and e.translation[0] < 1e-6
    # half the path: half the planes (those of the other half missed)
    e = sweep_errors(_report([_true_patch(fx, lo, (lo + hi) / 2)]), fx)
    assert 0.4 <= e.recall <= 0.6
    # a turn of 2 deg about the path after the first knot: the rotation error sees it
    e = sweep_errors(_report([_true_patch(fx, lo, hi, turn=2.0)]), fx)
    assert 1.99 < e.rotation[0] < 2.01 and e.translation[0] < 1e-6
    assert np.isnan(sweep_errors(_report([]), fx).median_rotation)


def test_families_are_split_per_mesh_component():
    """Two members (two mesh components) share the square profile: families of the initial cuts mix
    them, and ``_per_component`` leaves each family on one component, every member kept once."""
    from auszug.sweeps import curvature_plots, cut, families, initial_planes, match_cuts, movability, normalise
    from auszug.sweeps.general import _per_component
    from auszug.sweeps.matching import split_family
    from auszug.sweeps.mesh import face_components

    fx = _fixture(U29)
    m = normalise(fx.vertices, fx.faces)
    comp = face_components(m)
    assert sorted(np.bincount(comp).tolist()) == [len(fx.faces) // 2] * 2          # two members, equal
    p = DEFAULT.with_scale(0.25)
    cuts = cut(m, *initial_planes(m.vertices, p.sphere_frequency, p.offset_spacing))
    mov = movability(cuts, p)
    runs = np.sort(np.argsort(-mov.run_length, kind="stable")[:150])
    plots = curvature_plots(cuts, mov, runs, p)
    fams = families(match_cuts(plots, p), p)
    of_plot = comp[m.edge_faces[cuts.edges[cuts.curve_start[mov.run_curve[plots.run]]], 0]]
    mixed = [f for f in fams if len(set(of_plot[f.members].tolist())) > 1]
    assert mixed                                                                    # else the test tests nothing
    split = _per_component(fams, m, cuts, mov, plots)
    assert all(len(set(of_plot[f.members].tolist())) == 1 for f in split)
    assert len(split) == len(fams) + len(mixed)                                     # two components: one more each
    for f in mixed:
        parts = split_family(f, of_plot[f.members])
        assert sorted(np.concatenate([q.members for q in parts]).tolist()) == sorted(f.members.tolist())
        for q in parts:
            j = [int(np.flatnonzero(f.members == x)[0]) for x in q.members]
            assert np.array_equal(q.start, f.start[j]) and np.array_equal(q.reversed, f.reversed[j])
            assert q.length == f.length and q.seed == q.members[0]


@cache
def _detected(name, sigma, eps):
    fx = swept_members(_net(name), sigma=sigma)
    r = detect((fx.vertices, fx.faces), DEFAULT.with_(eps_prox=eps, max_match_runs=2000).with_scale(0.25))
    return fx, r, sweep_errors(r, fx)


def test_a_member_at_the_defaults_is_no_general_sweep():
    """At the default l_min (0.2 of the diameter) the member's cut loops (its profile: 6 % of the
    diameter) are too short to match: only 12 lengthwise runs, no general sweep. The kinematic parts
    cover pieces of the ogee as turns (its side view is circular arcs) with partial profiles (measured
    first: coverage 0.778 in whole faces, plane recall 0.85, profile Hausdorff 6.6e-3 and 4.4e-3; on
    main before the stage arcs: 0.907 of the area, recall 0.90, 4 patches). The stage arcs adds the
    turn about one more of the ogee's arcs (its axis from the member's crease circles): 0.989 of the
    area, recall 1.00, 5 rotations within the fit bound, but the profiles stay partial (Hausdorff
    3.0e-3 to 1.1e-2): what with_scale is for."""
    fx = _fixture("teaching-sheet/tn-2.uc")
    assert fx.profile_length < DEFAULT.l_min / 2
    r = detect((fx.vertices, fx.faces), DEFAULT.with_(eps_prox=0.002))
    assert r.stage("cut").numbers["runs"] < 20
    assert r.stage("motion").numbers["candidates"] == 0
    assert all(p.kind == "rotation" for p in r.patches)
    e = sweep_errors(r, fx)
    assert e.hausdorff.min() > 1e-3
    assert r.coverage >= 0.95 and r.stage("arcs").numbers["fit"] >= 1
    r0 = detect((fx.vertices, fx.faces), DEFAULT.with_(eps_prox=0.002, arc_axes=0))
    assert r0.coverage < 0.95 and len(r0.patches) < len(r.patches)


def test_one_member_clean_meets_every_target_at_eps_prox_0_002():
    """tn-2's member, clean, with_scale(0.25), eps_prox 0.002: measured coverage 0.999, plane recall
    1.00, fit error 9.8e-4, profile Hausdorff 4.6e-4, rotation 0.03 deg, translation 8.0e-7 (one patch,
    closed; before the motion's refinement 0.998, 1.00, 5.2e-4, 4.5e-4, 0.46 deg, 4.7e-5); since
    sweeps-members4 (pieces off the profile left out, corners put back, one-sided tangents) 0.999,
    1.00, fit error 5.5e-5, Hausdorff 4.0e-4, 0.02 deg, 6.1e-7. Every target of the issue met."""
    fx, r, e = _detected("teaching-sheet/tn-2.uc", 0.0, 0.002)
    assert r.coverage >= 0.95 and e.recall >= 0.95
    assert len(r.patches) == 1 and r.patches[0].closed
    assert e.hausdorff.max() <= 5e-4
    assert e.median_rotation <= 0.05 and e.median_translation <= 2e-6


def test_the_square_bar_is_not_turned_the_wrong_way_at_eps_prox_0_005():
    """At eps_prox 0.005 the fit bound (0.01) is half the bar's side: a sweep turned the wrong way
    fits. Before the loops' alignment (``matching.align_loops``) and the refinement of the motion
    against the mesh (``general.refine_motion``) tn-2's patch was 84 deg off (its family's ribs a
    quarter turn and a flip apart), U.XI.30's 0.65 deg. Measured after: tn-2 rotation 0.052 deg,
    translation 1.6e-6, profile Hausdorff 6.2e-4, coverage 0.999, recall 1.00 (one closed patch);
    U.XI.30 0.024 deg, 2.3e-7, 5.3e-4, 0.999, 1.00. With the pieces of the knots off the profile left
    out of its improvement, the corners put back and the one-sided tangents (sweeps-members4): tn-2
    0.029 deg, 1.1e-6, Hausdorff 4.6e-4; U.XI.30 0.027 deg, 2.6e-7, 3.6e-4 (coverage, recall kept).
    Every target of the issue met at eps_prox 0.005. Since branch sweeps-noisy30 (whole closed cut
    loops kept when a velocity state glides them with little sliding, ``loop_sliding``: more of the
    loops near the profile planes match, the families are larger) tn-2 0.125 deg, 1.4e-5, Hausdorff
    4.2e-4; U.XI.30 0.079 deg, 3.5e-7, 4.7e-4 (fit error 7.1e-3: the grown patch's last 6 knots, over
    the member's cut end, 2.8-7.4e-3 off): still 4-6x inside the rotation target."""
    for name, rot, trans in (("teaching-sheet/tn-2.uc", 0.15, 2e-5), (U30, 0.1, 1e-6)):
        fx, r, e = _detected(name, 0.0, 0.005)
        assert r.coverage >= 0.99 and e.recall >= 0.95, name
        assert len(r.patches) == 1 and r.patches[0].closed, name
        assert e.hausdorff.max() <= 5e-4, name
        assert e.median_rotation <= rot and e.median_translation <= trans, (name, e.median_rotation,
                                                                            e.median_translation)
        assert r.stage("motion").numbers["refined"] >= 1, name


def test_one_member_with_noise_meets_the_rotation_target():
    """tn-2's member, normal noise 5e-4, eps_prox 0.005: measured coverage 1.000, plane recall 1.00,
    profile Hausdorff 7.3e-4, rotation 0.74 deg (49 deg before), translation 1.9e-4 (one closed patch);
    since sweeps-members4 6.7e-4 and 0.64 deg (the pieces of the knots off the profile left out of
    its improvement, the one-sided tangents; 0.62 on main at 77eb6b2). Per knot the twist followed the
    noisy faces (+-0.4 deg against the truth's, the tilt 0.26 deg); since sweeps-members5 the knots'
    twists are robust local lines over 0.1 of arc length (``twist_window``): 0.37 deg (twist per knot
    0.10 deg, median), Hausdorff 6.6e-4, translation 1.8e-4: the rotation target (0.5 deg) met.
    Since sweeps-noisy30 (``loop_sliding``: many more noisy cut loops near the profile planes are
    movable runs, larger families): rotation 0.30 deg, translation 4.8e-4, Hausdorff 8.0e-4, but plane
    recall 1.00 -> 0.85 (the issue's target with noise, met at its bound), coverage 1.000."""
    fx, r, e = _detected("teaching-sheet/tn-2.uc", 5e-4, 0.005)
    assert r.coverage >= 0.95 and e.recall >= 0.85, e.recall
    assert e.hausdorff.max() <= 9e-4, e.hausdorff
    assert e.median_rotation <= 0.35 and e.median_translation <= 6e-4, (e.median_rotation, e.median_translation)


def test_two_members_clean_meet_every_target():
    """U.XI.29's two members (two mesh components), clean, eps_prox 0.005: before sweeps-members4 the
    profile Hausdorff was 8.6e-4 and 1.8e-3 (the mean of all recut pieces, the grown sweep's ends and
    the other member among them, cut the square's corners; the improvement never put a corner back)
    and the rotation 0.32 and 1.07 deg (the middle knot, the reference, lies at the ogee's
    inflection, where the centred cubics turned the path's tangent by 1.08 deg). Measured after:
    coverage 1.000, plane recall 0.97, Hausdorff 4.2e-4 and 3.2e-4, rotation 0.03 and 0.01 deg,
    translation 6.9e-8 and 2.0e-7, two closed patches (median 0.02 deg, 1.3e-7). Since sweeps-noisy30
    (``loop_sliding``): recall 1.00, Hausdorff 6.0e-4 (worst), rotation 0.076 deg and translation 3.1e-7
    (medians)."""
    fx, r, e = _detected(U29, 0.0, 0.005)
    assert r.coverage >= 0.99 and e.recall >= 0.95
    assert len(r.patches) == 2 and all(p.closed for p in r.patches)
    assert e.hausdorff.max() <= 7e-4, e.hausdorff
    assert e.rotation.max() <= 0.2 and e.translation.max() <= 1e-5, (e.rotation, e.translation)


def test_u30_clean_meets_every_target_at_eps_prox_0_002():
    """U.XI.30's member, clean, eps_prox 0.002: measured coverage 0.998, plane recall 1.00, profile
    Hausdorff 3.6e-4, rotation 0.33 deg, translation 3.1e-7, one patch (before the alignment and the
    refinement: coverage 0.758, recall 0.75, Hausdorff 3.8e-3, 0.59 deg, two patches); since
    sweeps-members4 0.998, 1.00, 3.3e-4, 0.03 deg (the middle knot at the ogee's inflection: its
    one-sided tangent), 3.6e-7. Since sweeps-noisy30 (``loop_sliding``): two patches, Hausdorff
    3.6e-4, 0.057 deg, 4.2e-6 (coverage 0.998, recall 1.00)."""
    fx, r, e = _detected(U30, 0.0, 0.002)
    assert r.coverage >= 0.99 and e.recall >= 0.95
    assert len(r.patches) <= 2
    assert e.hausdorff.max() <= 5e-4, e.hausdorff
    assert e.median_rotation <= 0.08 and e.median_translation <= 1e-5, (e.median_rotation, e.median_translation)


def test_u30_with_noise_meets_every_target():
    """U.XI.30's member, normal noise 5e-4. On main (77eb6b2) the match stage matched 40 of 9587
    pairs (clean 2142 of 13478) and the kept patches were open profiles of oblique cuts: rotation
    63.6 deg at eps_prox 0.005 (coverage 0.985, recall 0.90, Hausdorff 1.9e-2, 3 patches), 16.6 deg at
    0.002 (0.772, 0.75, 1.2e-2). The cause was the movability stage: 127 of the 140 closed cut loops
    within 25 deg of a profile plane were dropped as sliding (their Eq. 4 velocity a mix of the
    loop's turn in its plane and the motions out of it). With ``loop_sliding`` (branch
    sweeps-noisy30) measured at 0.005: one closed patch, coverage 0.998, rotation 0.495 deg,
    Hausdorff 6.5e-4, fit error 4.9e-3; at 0.002: two patches, coverage 0.992, recall 1.00, 0.389
    deg, translation 2.4e-4, Hausdorff 6.4e-4, fit error 1.8e-3. Every target of the issue met (the
    rotation at 0.005 by 0.005 deg); with ``loop_sliding`` 0 the loops are dropped as before."""
    for eps, rot, patches in ((0.005, 0.5, 1), (0.002, 0.45, 2)):
        fx, r, e = _detected(U30, 5e-4, eps)
        assert r.coverage >= 0.95 and e.recall >= 0.85, (eps, r.coverage, e.recall)
        assert len(r.patches) <= patches and all(p.closed for p in r.patches), eps
        assert max(p.fit_error for p in r.patches) <= 2 * eps, eps
        assert e.hausdorff.max() <= 1e-3, (eps, e.hausdorff)
        assert e.median_rotation <= rot and e.median_translation <= 1e-3, (eps, e.median_rotation,
                                                                           e.median_translation)


def test_four_members_clean_meet_every_target():
    """U.XI.91's four members, clean, eps_prox 0.005: before sweeps-members4 coverage 1.000, plane
    recall 1.00, profile Hausdorff 1.1e-3 (worst patch), rotation 0.04 deg, translation 7.5e-8
    (medians); after 1.000, 1.00, 4.9e-4, 0.10 deg, 5.3e-6, four patches."""
    fx, r, e = _detected(U91, 0.0, 0.005)
    assert r.coverage >= 0.99 and e.recall >= 0.95
    assert len(r.patches) == 4
    assert e.hausdorff.max() <= 6e-4
    assert e.median_rotation <= 0.2 and e.median_translation <= 1e-5
