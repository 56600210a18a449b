"""Curvature plots, partial congruence (sec. 2.1) and families (sec. 2.2), with known answers."""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from auszug.sweeps import cut, movability, normalise
from auszug.sweeps.fixtures import gothic_base_profile, moulding_along_cubic
from auszug.sweeps.matching import (
    CurvaturePlots,
    curvature_plots,
    families,
    match_cuts,
    order_ribs,
    resample,
    signed_curvature,
)
from auszug.sweeps.params import DEFAULT


def _plots(kappas, normals=None, h=DEFAULT.match_spacing):
    ks = [np.asarray(k, float) for k in kappas]
    start = np.concatenate([[0], np.cumsum([len(k) for k in ks])]).astype(np.int64)
    nrm = np.tile([0, 0, 1.0], (len(ks), 1)) if normals is None else np.asarray(normals, float)
    return CurvaturePlots(np.zeros((start[-1], 3)), np.concatenate(ks), start, np.arange(len(ks)), nrm, h)


def _plot_of(points, normal, p=DEFAULT):
    q = resample(points, p.match_spacing)
    k = signed_curvature(q, normal, max(1, int(round(p.curvature_window / (2 * p.match_spacing)))))
    return q, k


def test_curvature_of_arcs_and_lines():
    h = 0.005
    r = 0.15
    t = np.arange(0, 1.2 * r * np.pi, h) / r
    arc = np.column_stack([r * np.cos(t), r * np.sin(t), 0 * t])
    k = signed_curvature(arc, [0, 0, 1], 5)
    assert np.allclose(k[5:-5], 1 / r, rtol=2e-3)
    assert np.allclose(signed_curvature(arc[::-1], [0, 0, 1], 5)[5:-5], -1 / r, rtol=2e-3)
    line = np.column_stack([np.arange(0, 0.4, h), 0.3 * np.arange(0, 0.4, h), np.zeros(80)])
    assert np.abs(signed_curvature(line, [0, 0, 1], 5)).max() < 1e-9
    q = resample(arc, 0.01)
    assert np.allclose(np.linalg.norm(np.diff(q, axis=0), axis=1), 0.01, rtol=2e-3)  # chords of an arc


def _brute(ka, kb, eps, kfloor, min_len):
    best = (0, np.inf)
    for var in range(4):
        b = (-1 if var & 1 else 1) * (kb[::-1] if var & 2 else kb)
        for o in range(-len(ka) + 1, len(b)):
            i0, i1 = max(0, -o), min(len(ka), len(b) - o)
            for s in range(i0, i1):
                for e in range(s + min_len, i1 + 1):
                    d = np.abs(ka[s:e] - b[s + o:e + o])
                    ref = 0.5 * (np.abs(ka[s:e]) + np.abs(b[s + o:e + o]))
                    ok = d.sum() <= eps * ref.sum() + 1e-9 or d.mean() <= eps * kfloor + 1e-12
                    if ok and (e - s > best[0] or (e - s == best[0] and d.mean() < best[1])):
                        best = (e - s, d.mean())
    return best


def test_longest_window_per_diagonal_equals_brute_force():
    rng = np.random.default_rng(7)
    p = DEFAULT.with_(l_min=0.02, match_spacing=0.005, curvature_window=0.01, eps_match=0.3, kappa_floor=0.5)
    for _ in range(25):
        ka = rng.normal(0, 1, rng.integers(10, 16))
        kb = np.r_[rng.normal(0, 1, 3), ka[2:9][::-1] * -1 + rng.normal(0, 0.1, 7), rng.normal(0, 1, 2)]
        m = match_cuts(_plots([ka, kb]), p)
        want_len, want_e = _brute(ka, kb, p.eps_match, p.kappa_floor, 4)
        got = int(m.length[0]) if m.n_matches else 0
        assert got == want_len
        if got:
            assert np.isclose(m.energy[0], want_e, atol=1e-9)
            ia, ib = m.correspondence(0)
            kb2 = (-1 if m.flipped[0] else 1) * kb[ib]
            assert np.isclose(np.abs(ka[ia] - kb2).mean(), m.energy[0])


def test_congruent_copies_match_in_every_variant():
    prof, _ = gothic_base_profile(200)
    x = np.column_stack([prof[:, 0], np.zeros(len(prof)), prof[:, 1]])  # in the plane y = 0
    qa, ka = _plot_of(x, [0, 1.0, 0])
    rot = Rotation.from_rotvec([0.2, 0.3, -0.4])
    for reverse in (False, True):
        for mirror_normal in (False, True):
            y = rot.apply(x[::-1] if reverse else x) + [0.1, -0.2, 0.3]
            nb = rot.apply([0, -1.0, 0] if mirror_normal else [0, 1.0, 0])
            qb, kb = _plot_of(y, nb)
            m = match_cuts(_plots([ka, kb], [[0, 1.0, 0], nb]), DEFAULT.with_(match_angle=90))
            assert m.n_matches == 1
            assert m.length[0] >= min(len(ka), len(kb)) - 1
            assert m.reversed[0] == reverse and m.flipped[0] == (reverse != mirror_normal)
            ia, ib = m.correspondence(0)
            # corresponding samples are the same points of the profile (within a sample)
            da = np.linalg.norm(qa[ia] - qa[ia[0]], axis=1)
            db = np.linalg.norm(qb[ib] - qb[ib[0]], axis=1)
            assert np.abs(da - db).max() < 2 * DEFAULT.match_spacing


def test_straight_pieces_match_only_with_a_floor():
    rng = np.random.default_rng(2)
    ka, kb = rng.normal(0, 0.05, 80), rng.normal(0, 0.05, 70)  # noisy straight lines: kappa ~ 0
    assert match_cuts(_plots([ka, kb]), DEFAULT.with_(kappa_floor=0.0)).n_matches == 0
    m = match_cuts(_plots([ka, kb]))
    assert m.n_matches == 1 and m.length[0] == 70


def test_angle_pruning():
    t = np.linspace(0, 1, 60)
    k = np.sin(5 * t) * 10
    tilt = [[0, np.sin(np.radians(a)), np.cos(np.radians(a))] for a in (0, 20, 30)]
    m = match_cuts(_plots([k, k, k], tilt))
    assert m.tested == 2 and m.pairs.tolist() == [[0, 1], [1, 2]]


@cache
def _profile_plots(sigma):
    fx = moulding_along_cubic(sigma=sigma)
    m = normalise(fx.vertices, fx.faces)
    c = cut(m, fx.planes[:, :3], fx.planes[:, 3])
    return fx, curvature_plots(c, movability(c))


@pytest.mark.parametrize("sigma", [0.0, 5e-4])
def test_profile_cuts_of_a_general_sweep_match_whole(sigma):
    fx, plots = _profile_plots(sigma)
    m = match_cuts(plots)
    normals = plots.normal
    close = np.degrees(np.arccos(np.clip(np.abs(normals @ normals.T), 0, 1))) <= 25
    assert m.tested == (close.sum() - len(close)) // 2
    frac = m.length * plots.spacing / fx.profile_length
    assert m.n_matches / m.tested >= (1.0 if sigma == 0 else 0.9)
    assert np.median(frac) >= 0.99 and frac.min() >= (0.99 if sigma == 0 else 0.5)
    fam = families(m)
    biggest = max(fam, key=lambda f: len(f.members))
    assert len(biggest.members) >= 25
    assert biggest.length * plots.spacing >= (0.99 if sigma == 0 else 0.8) * fx.profile_length
    # members' curvature along the family's correspondence is the seed's
    ks = plots.curvature(biggest.seed)[biggest.indices(0)]
    for j in range(1, len(biggest.members)):
        kj = plots.curvature(int(biggest.members[j]))[biggest.indices(j)] * (-1 if biggest.flipped[j] else 1)
        assert np.abs(ks - kj).mean() <= 0.2 * max(np.abs(ks).mean(), DEFAULT.kappa_floor)


@pytest.mark.parametrize("sigma", [0.0, 5e-4])
def test_ribs_of_a_general_sweep_come_out_in_path_order(sigma):
    fx, plots = _profile_plots(sigma)
    # the family's members come in order of overlap with the seed, not along the path
    m = match_cuts(plots)
    fam = max(families(m), key=lambda f: len(f.members))
    ribs = order_ribs(fam, plots)
    seq = plots.run[ribs.plots]  # run k is the cut of true plane k (one run per plane, in order)
    assert len(seq) >= 0.8 * len(fam.members)
    steps = np.diff(seq)
    assert np.all(steps > 0) or np.all(steps < 0)  # monotone along the path
    # successive ribs alternate: the previous and the next lie on opposite sides of each rib's plane
    cen = np.array([plots.samples(int(p)).mean(0) for p in ribs.plots])
    nrm = plots.normal[ribs.plots]
    for i in range(1, len(cen) - 1):
        assert (nrm[i] @ (cen[i - 1] - cen[i])) * (nrm[i] @ (cen[i + 1] - cen[i])) < 0


def _loop_plot(points, normal, p=DEFAULT):
    """A closed curve's plot as :func:`curvature_plots` makes it (``h`` apart round the loop)."""
    q = resample(points, p.match_spacing, closed=True)
    if np.linalg.norm(q[-1] - q[0]) < 0.5 * p.match_spacing:
        q = q[:-1]
    return q, signed_curvature(q, normal, max(1, int(round(p.curvature_window / (2 * p.match_spacing)))), True)


def test_closed_curves_match_whole_under_every_shift_and_variant():
    """A closed curve against a rigidly moved copy started elsewhere (every shift), reversed and with its
    plane's normal turned: one match, a whole period long, whose correspondence pairs the same points."""
    from auszug.sweeps.fixtures import closed_profile

    prof = closed_profile(240, 0.075)
    x = np.column_stack([prof[:, 0], np.zeros(len(prof)), prof[:, 1]])
    qa, ka = _loop_plot(x, [0, 1.0, 0])
    rot = Rotation.from_rotvec([0.2, 0.3, -0.4])
    for shift in (0, 37, 120, 201):
        for reverse in (False, True):
            for mirror_normal in (False, True):
                y = np.roll(x, -shift, axis=0)
                y = rot.apply(y[::-1] if reverse else y) + [0.1, -0.2, 0.3]
                nb = rot.apply([0, -1.0, 0] if mirror_normal else [0, 1.0, 0])
                qb, kb = _loop_plot(y, nb)
                pl = _plots([ka, kb], [[0, 1.0, 0], nb])     # the loops taken as open runs, and as loops
                pl = CurvaturePlots(np.vstack([qa, qb]), pl.kappa, pl.start, pl.run, pl.normal, pl.spacing,
                                    np.array([len(ka), len(kb)], np.int64), np.vstack([qa, qb]), np.r_[ka, kb])
                m = match_cuts(pl, DEFAULT.with_(match_angle=90))
                assert m.n_matches == 1 and m.cyclic is not None and bool(m.cyclic[0])
                assert m.length[0] == min(len(ka), len(kb))
                assert m.reversed[0] == reverse and m.flipped[0] == (reverse != mirror_normal)
                ia, ib = m.correspondence(0)
                assert ia.max() < len(ka) and ib.max() < len(kb) and len(np.unique(ia)) == len(ia)
                # the same points of the profile: b's samples moved back onto a's, within 2 samples
                back = rot.inv().apply(qb[ib] - [0.1, -0.2, 0.3])
                assert np.linalg.norm(back - qa[ia], axis=1).max() < 2 * DEFAULT.match_spacing


def test_profile_cuts_of_a_closed_sweep_form_one_closed_family():
    """The true profile planes' cuts of the closed fixture (loops started wherever the cutter starts them)
    match whole and give a closed family whose members agree in curvature along its correspondence."""
    from auszug.sweeps.fixtures import closed_along_cubic

    fx = closed_along_cubic()
    c = cut(normalise(fx.vertices, fx.faces), fx.planes[:, :3], fx.planes[:, 3])
    plots = curvature_plots(c, movability(c))
    assert np.all(plots.periods() > 0)
    m = match_cuts(plots)
    assert m.n_matches == m.tested > 0 and m.cyclic is not None and m.cyclic.all()
    assert np.all(m.length == np.minimum(plots.periods()[m.pairs[:, 0]], plots.periods()[m.pairs[:, 1]]))
    biggest = max(families(m), key=lambda f: len(f.members))
    assert biggest.closed and len(biggest.members) >= 25
    assert biggest.length * plots.spacing >= 0.97 * fx.profile_length
    ks = plots.loop(biggest.seed)[1][biggest.indices(0)]
    for j in range(1, len(biggest.members)):
        kj = plots.loop(int(biggest.members[j]))[1][biggest.indices(j)] * (-1 if biggest.flipped[j] else 1)
        assert np.abs(ks - kj).mean() <= 0.2 * max(np.abs(ks).mean(), DEFAULT.kappa_floor)


def _square_loop(n_side=12, half=0.01):
    side = np.linspace(-half, half, n_side + 1)[:-1]
    one = np.full(n_side, half)
    return np.column_stack([np.r_[side, one, -side, -one], np.r_[-one, side, one, -side], np.zeros(4 * n_side)])


def test_align_loops_undoes_a_square_loops_quarter_turns_and_flips_but_not_a_true_turn():
    """A square's loop matches itself under 8 alignments (4 shifts, each also reversed); cuts a small
    true turn apart, their samples shifted by quarter turns and reversed, are aligned back, the true
    turn kept. A profile without symmetry (the closed quatrefoil) keeps its alignment."""
    from auszug.sweeps.fixtures import closed_profile
    from auszug.sweeps.matching import align_loops

    sq = _square_loop()
    n = len(sq)
    turn = Rotation.from_rotvec([0.05, -0.03, np.radians(4.0)]).as_matrix()
    true = [sq @ Rotation.from_rotvec([0.0, 0.0, np.radians(3.0 * i)]).as_matrix().T @ turn.T + [0.0, 0.0, 0.01 * i]
            for i in range(5)]
    given = [true[0], np.roll(true[1], 12, axis=0), np.roll(true[2], 24, axis=0), true[3][::-1],
             np.roll(true[4][::-1], 36, axis=0)]
    out = align_loops(np.stack(given), 1e-3)
    # each aligned to the first sample for sample: the given one re-indexed, the true correspondence
    for i in range(5):
        assert np.allclose(out[i], true[i], atol=1e-12), i
    # with no tolerance only exact ties would count: the shifts here are exact (the square's symmetry)
    assert np.allclose(align_loops(np.stack(given), 0.0), np.stack(true), atol=1e-12)
    assert n == 48
    # the quatrefoil (four lobes of different sizes): its cut turned 30 deg about its normal keeps the
    # given alignment (a quarter turn of its samples is the nearest other, farther than eps_prox 0.005);
    # the square in its place is turned back to the least turn (0 deg: the square's 90 is its 0)
    q = np.column_stack([closed_profile(96), np.zeros(96)])
    r30 = Rotation.from_rotvec([0, 0, np.radians(30.0)]).as_matrix()
    qs = np.stack([q, q @ r30.T + [0.02, 0.0, 0.0]])
    assert np.array_equal(align_loops(qs, 0.005), qs)
    r60 = Rotation.from_rotvec([0, 0, np.radians(60.0)]).as_matrix()
    ss = np.stack([sq, sq @ r60.T])
    got = align_loops(ss, 1e-3)
    assert np.allclose(got[1], sq @ Rotation.from_rotvec([0, 0, np.radians(-30.0)]).as_matrix().T, atol=1e-12)

