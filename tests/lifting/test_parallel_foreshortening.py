"""The foreshortening bound on the parallel candidates (``LiftParams.parallel_foreshorten``, off by default; branch
lift-parallel, docs/lifting.md "Foreshortening bound of the parallel candidates").

Under orthographic projection parallel 3D tangents are drawn parallel, and two tangents within I_b of each other
are drawn at most ``arcsin(sin I_b / f)`` apart, f the foreshortening of the less foreshortened one. With the switch
on, a candidate whose drawn 2D angle exceeds that bound at the baseline's foreshortening is not resolved. The
first test checks the bound on sampled directions (no lift); the others pin what was measured on the truths.
"""

from __future__ import annotations

import numpy as np
import pytest

from auszug.lifting import LiftParams, lift
from auszug.lifting import cues as cu
from auszug.lifting.reconstruct import foreshortening_bound
from tests.lifting import truth as T

GATE = LiftParams(parallel_foreshorten=True)
GATE_ROBUST = LiftParams(parallel_foreshorten=True, parallel_robust_deg=5.0, w_depth_anchor=10.0,
                         robust_max_move=0.12)


def _angle2d(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    c = (u[..., :2] * v[..., :2]).sum(-1) / (np.linalg.norm(u[..., :2], axis=-1) * np.linalg.norm(v[..., :2], axis=-1))
    return np.degrees(np.arccos(np.clip(c, -1.0, 1.0)))


@pytest.mark.parametrize("delta", [2.0, 5.0, 10.0])
@pytest.mark.parametrize("f", [0.05, 0.15, 0.3, 0.6, 0.9, 1.0])
def test_foreshortening_bound_is_the_width_of_the_projected_cap(delta, f):
    """Directions within ``delta`` of a unit vector of foreshortening f, sampled on the cap's rim and inside it at a
    random azimuth: their projections are never farther from its projection than the bound, and the rim reaches it
    (to 0.01 deg); where ``f <= sin(delta)`` the cap holds the view direction and the bound is 90 deg."""
    rng = np.random.default_rng(int(100 * delta + 10 * f))
    az = rng.uniform(0, 2 * np.pi)
    t1 = np.array([f * np.cos(az), f * np.sin(az), np.sqrt(1 - f * f)])
    e1 = np.cross(t1, [0.0, 0.0, 1.0]) if f > 0 else np.array([1.0, 0.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(t1, e1)
    psi = np.linspace(0, 2 * np.pi, 20001)[:, None]
    d = np.radians(delta) * np.r_[np.ones(len(psi)), rng.uniform(0, 1, 5000)][:, None]
    psi = np.r_[psi, rng.uniform(0, 2 * np.pi, (5000, 1))]
    t2 = np.cos(d) * t1 + np.sin(d) * (np.cos(psi) * e1 + np.sin(psi) * e2)
    a = _angle2d(np.broadcast_to(t1, t2.shape), t2)
    bound = float(foreshortening_bound(np.array([f]), delta)[0])
    if f <= np.sin(np.radians(delta)):
        assert bound == 90.0 and a.max() >= 90.0
    else:
        assert a.max() <= bound + 1e-9 and a.max() >= bound - 0.01, (a.max(), bound)


# noise-free at each truth's own view (measured 2026-12-05, branch lift-parallel): depth RMSE (the default's in
# brackets) revolve 1.05 (3.08), spiral 41.80 (34.31), saddle 3.45 (4.94), wrinkle 1.82 (1.82), cross 7.68 (16.38 !),
# turret 8.64 (10.03) %; parallel cues (true applied, applied, true) against the default's 23/38/23, 5/13/5,
# 12/24/12, 22/22/22, 20/70/20, 22/24/22
GATE_LIFTED = [
    ("revolve", 0.0110, {"parallel": (23, 29, 23), "planar": (7, 7, 10)}),
    ("spiral", 0.4200, {"parallel": (5, 5, 5)}),
    ("saddle", 0.0350, {"parallel": (12, 14, 12), "planar": (8, 8, 8)}),
    ("wrinkle", 0.0190, {"parallel": (22, 22, 22), "planar": (3, 3, 3)}),
    ("cross", 0.0790, {"parallel": (20, 29, 20), "orthogonal": (6, 10, 12), "planar": (4, 4, 6)}),
    ("turret", 0.0880, {"parallel": (22, 22, 22), "orthogonal": (8, 10, 10)}),
]


@pytest.mark.parametrize("name, bound, counts", GATE_LIFTED)
def test_foreshortening_bound_against_the_truth(name, bound, counts):
    """Noise-free, the bound rejects no true candidate on any truth (recall 1) and most false ones: parallel
    precision up on every truth with a false candidate (revolve 0.61 -> 0.79, saddle 0.50 -> 0.86, F1 0.92; cross
    0.29 -> 0.69, spiral 0.38 -> 1, turret 0.92 -> 1), every applied cue within 0.5 deg."""
    tr = T.make(name)
    r = lift(tr.sketch, params=GATE)
    err, sign = T.depth_rmse(tr, r)
    assert r.converged and sign == 1 and err <= bound, (err, sign)
    scores = T.cue_scores(r, T.labels(tr))
    assert {k: scores[k][:3] for k in counts} == counts
    assert scores["parallel"][0] == scores["parallel"][2]
    assert max(c.angle for c in r.cues if c.applied) <= GATE.applied_tol_deg


def test_foreshortening_bound_with_the_robust_baseline_meets_the_saddles_target():
    """With the robust baseline, its depth anchor and the trust bound (lift-robust3's package, off by default): the
    saddle 2.70 % (issue 12: at most 3 %; 3.05 % with the package alone), the revolve 1.05 % (target 1 %)."""
    for name, bound in (("saddle", 0.0275), ("revolve", 0.0110)):
        tr = T.make(name)
        r = lift(tr.sketch, params=GATE_ROBUST)
        err, sign = T.depth_rmse(tr, r)
        assert r.converged and sign == 1 and err <= bound, (name, err, sign)


def test_foreshortening_bound_under_noise_is_why_it_is_off():
    """The recorded reason the switch is off by default: at 1 % noise the drawn tangents turn by up to 25 deg, true
    candidates' 2D angles pass the bound and are rejected, and the rest of the false ones stay: the revolve at 1 %,
    seed 2, applies 13 of its 23 true candidates and 7 false ones, 6.54 % (default 4.57 %), more than twice its
    noise-free 1.05 %."""
    tr = T.make("revolve", noise=0.01, seed=2)
    r = lift(tr.sketch, params=GATE)
    err, _ = T.depth_rmse(tr, r)
    assert T.cue_scores(r, T.labels(tr))["parallel"][:3] == (13, 20, 23)
    assert err > 2 * 0.0105


def test_true_parallel_candidates_alone_do_not_meet_both_targets(monkeypatch):
    """An oracle: the lift with only the truly parallel candidates (every stage: baseline and cue classes). The
    revolve reaches 0.77 % noise-free (the issue's 1 %) but 3.75 % (unconverged) at 1 % noise, seed 0, so no rule
    that classifies the parallel candidates meets both "1 %" and "1 % noise at most twice the noise-free error" on
    it; the saddle stays at 3.52 % noise-free (target 3 %)."""
    orig = cu.parallel_cues
    keep: dict[str, np.ndarray] = {}

    def only_true(g, params):
        p = orig(g, params)
        m = keep["mask"]
        assert len(m) == len(p)
        return cu.Parallel(p.p1[m], p.h1[m], p.p2[m], p.h2[m], p.sign[m], p.n1[m], p.n2[m], p.angle2d[m],
                           tuple(w for w, k in zip(p.where, m, strict=True) if k))

    errs = {}
    for name, noise, seed in (("revolve", 0.0, 0), ("revolve", 0.01, 0), ("saddle", 0.0, 0)):
        tr = T.make(name, noise=noise, seed=seed)
        keep["mask"] = T.labels(tr)["parallel"]
        with monkeypatch.context() as mp:
            mp.setattr(cu, "parallel_cues", only_true)
            r = lift(tr.sketch)
        errs[name, noise] = T.depth_rmse(tr, r)[0]
    assert errs["revolve", 0.0] <= 0.0080                       # measured 0.77 %
    assert errs["revolve", 0.01] > 2 * 0.0100                   # measured 3.75 %
    assert errs["saddle", 0.0] > 0.0300                         # measured 3.52 %


def test_foreshortening_bound_on_the_bundled_vase():
    """The bundled vase rebuilt from its truth: 2.95 % by default (all 22 parallel cues applied), 1.67 % with the
    bound (16 applied); the ogee roof and the arches keep every candidate (measured 1.96, 3.97 %, as by default)."""
    from tests.lifting.test_lifting import _example_truth

    for name, bound, applied in (("vase", 0.0170, 16), ("ogee-roof", 0.0200, 17), ("arches", 0.0400, 10)):
        tr = _example_truth(name)
        r = lift(tr.sketch, params=GATE)
        err, sign = T.depth_rmse(tr, r)
        assert r.converged and sign == 1 and err <= bound, (name, err, sign)
        assert sum(c.applied for c in r.cues if c.kind == "parallel") == applied
