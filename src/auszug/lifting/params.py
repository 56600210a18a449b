"""The one home of sketch lifting's weights, thresholds and limits.

The values are the paper's (Xu et al. 2014, sec. 5.2-5.3) where it gives one;
the others are this implementation's choices, each documented here and in
docs/lifting.md. All lengths are relative to the sketch's bounding-box
diagonal: the solver works on the sketch scaled to diagonal 1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

from auszug.errors import GeometryError
from auszug.limits import LIMITS

__all__ = ["LiftParams", "DEFAULT", "CLOSE_GAPS_MAX", "COLLAPSED", "close_gaps_for"]

#: The largest ``LiftParams.close_gaps``: 5 % of the diagonal (a gap wider than that is a drawn free end).
CLOSE_GAPS_MAX = 0.05


def close_gaps_for(distance: float) -> float:
    """The ``close_gaps`` a message names to join what is drawn ``distance`` apart (shares of the diagonal).

    1 % more than ``distance``, rounded up to 1e-4, at most :data:`CLOSE_GAPS_MAX`.
    """
    return min(CLOSE_GAPS_MAX, math.ceil(distance * 1.01 * 1e4) / 1e4)


#: A lifted layer whose curves span (bounding-box diagonal in x, y) less than this share of the drawn
#: layer's is refused as collapsed: the fidelity term keeps x, y near the drawing, so only a solve gone
#: astray shrinks it (measured 2026-12-06 over 338 lifts, converged or not: 0.94-1.003 for the bundled
#: examples, the six truths' view grid, the depth-sign grid at tilts 15-65 deg and the truths with 0.5 and 1 %
#: noise; the box drawn with its sections off, which collapses, 5e-6 to 3e-5).
COLLAPSED = 0.5


@dataclass(frozen=True)
class LiftParams:
    """Weights and thresholds of :func:`auszug.lifting.lift`.

    Attributes
    ----------
    w_a, w_v, w_f : float
        Fidelity weights (Eq. 7): projection accuracy 1, minimal variation 2,
        foreshortening 0.001.
    w_a_baseline : float
        Accuracy weight of the seed propagation and the baseline
        reconstruction. The paper uses 10; *our choice* is 1, the weight of
        the later stages. Measured on the vase ground truth with 1 % 2D noise
        (seeds 0-2), the baseline's depth RMSE is 2.38, 1.79 and 2.29 %
        against 1.78 % noise-free; with 10 it was 4.78, 1.51 and 6.18 %
        against 1.27 % (docs/lifting.md). A noisy stroke held at its drawn
        place bends the hard orthogonality's depths; held more loosely, the
        orthogonality straightens it.
    sigma : float
        sigma of omega_d (Eq. 2), relative to the diagonal (1/3, the three-sigma rule).
    eps : float
        epsilon of omega_d (0.01).
    w_c : float
        Weight of the soft likelihood-weighted cues, and of accepted tangent
        parallelism, which stays soft (50).
    w_p_baseline, sigma_p_deg : float
        Baseline soft parallelism weight w_p = 0.1 exp(-alpha^2 / sigma^2) by
        the 2D angle alpha, sigma = 15 deg.
    w_p_propagate : float
        Parallelism weight while the seed crossing's lift is propagated (5).
    w_p_propagate_second : float
        *Our addition* (0: off): every seed whose propagation with
        ``w_p_propagate`` converged is propagated a second time with this
        parallelism weight (default: the baseline's 0.1), after all of those,
        unless two of them reached the same minimum or none of their baselines
        converged; the lowest converged baseline energy is kept as before.
        Over-emphasised parallelism over mostly false candidates can lead the
        baseline into a worse basin: on the rib-vault truth (one seed, 53 of
        73 parallel candidates false) 0.0378 against 0.0341, the minimum of
        the truth's own basin (docs/lifting.md, "Structural diagnosis").
    inner_deg, outer_deg : float
        Likelihood bounds I_b = 5 deg (L = 1 within) and O_b = 15 deg (L = 0.005
        there, 0 beyond).
    outer_value : float
        L at the outer bound (0.005).
    rounds : int
        Most rounds of the progressive resolution of one cue class (the paper:
        "four iterations typically suffice"; we allow 8, then the remaining
        cues are inapplicable, the conservative choice).
    final_solve : bool
        One more solve after the last class, with its cues applied in its
        final round hard (the paper's fixed point: every applied cue met, not
        only within ``inner_deg``), without the round's soft terms and depth
        anchor. Off by default: measured, it costs accuracy (docs/lifting.md,
        "Applied cues within 0.5 deg"). When on, it replaces ``final_hold``.
    final_hold : bool
        Our rule for the cues applied in the last round run (branch
        lift-final; on by default since lift-hold3): that round solved once
        more with them hard, its energy kept (soft terms and the class's
        depth anchor, ``w_depth_anchor``) and its depths held near its solution
        (``w_final_anchor``; if it does not converge, once more with a third
        of the weight), kept if every applied cue then holds within
        ``applied_tol_deg``; else the round's solution stays and its applied
        cues beyond that angle there are rejected. The depth sign is decided
        on the round's solution, before that solve (lift-hold3). Meets
        "applied cues within 0.5 deg" on every lift measured, the depth RMSE
        within +-0.06 % points but the cross's +0.17. Its cost on the
        100-curve benchmark sketch: the held solve given up at its first step
        (``hold_first_step``), one KKT factorisation, about +0.1 s CPU
        (docs/lifting.md, "Applied cues within 0.5 deg"). Off: the last
        round's cues are reported after the soft solve that accepted them,
        within ``inner_deg`` only (up to 4.9 deg measured).
    w_final_anchor : float
        Weight of ``(z - z_round)^2`` per point in that solve (10; 3 and 100
        measured, docs/lifting.md); 0: the round's own anchor, if any.
    applied_tol_deg : float
        The angle within which ``final_hold`` requires every applied cue to
        hold (0.5 deg, issue 12's target), and beyond which its fallback
        rejects the last round's cues.
    hold_first_step : float
        ``final_hold``'s early fallback (lift-final2): a held solve whose first
        Newton step, shortened to this fraction, does not decrease the merit
        is given up there (not retried at the lower weight), as a solve that
        does not converge. 1/128: on the 100-curve benchmark sketch that
        probe fails (its line search accepts 1/256 first, then the solve
        crawls: 60 + 60 steps, not converged); on the 41 noise and 159 views
        lifts of the truths no held solve is given up (at 1/64 one is: the
        wrinkle at 1 %, seed 2, whose held solve converges in 13 steps); on
        the bundled arches and ogee roof sketches it gives up held solves
        that converge in 12 and 10 steps (the arches then reject 2 of 6
        cues; docs/lifting.md). 0: never.
    parallel_2d_deg : float
        Tangent pairs whose 2D angle is below this are parallelism candidates
        (our choice: twice O_b, since foreshortening changes angles).
    plane_cluster_deg : float
        Plane parallelism and orthogonality (the curve-level cues after
        planarity): the applied planar strokes' normals are clustered by
        single linkage at this angle, and two clusters whose mean normals are
        within it of 90 deg are orthogonality candidates (the paper: 15 deg).
    smooth_joint_deg : float
        A stroke is G1 at a node where its tangents turn by less than this
        (our choice: 10 deg).
    min_crossing_deg : float
        A crossing of two G1 strokes is a smooth crossing (hard orthogonality)
        when their 2D tangents are at least this far from parallel (our
        choice: 10 deg; below, it is a touching, not a crossing).
    straight_tol : float
        Control points within this (relative to the diagonal) of their
        segment's chord make the segment straight (a hard linear constraint).
    snap : float
        Annotation markers snap to the nearest crossing within this share of
        the diagonal (1 %, the issue's value).
    merge : float
        Stroke ends and crossings closer than this (relative to the diagonal)
        are one point.
    close_gaps : float
        *Our addition* for hand-drawn sketches (0: off, the default; at most
        ``CLOSE_GAPS_MAX``, 5 % of the diagonal): a stroke end that misses
        another stroke of its layer (or its own other end) by at most this
        share of the diagonal is moved onto it with its handle, and a piece
        at most this long beyond a stroke's last crossing is cut off, so
        that near misses and overshoots meet where they were meant to
        (:class:`auszug.lifting.sketch.Gap`; ends at an occlusion marker
        stay as drawn). Before that, crossings of three or more strokes
        drawn within this distance of one point (a small triangle where
        they were meant to meet) are joined into one point
        (:class:`auszug.lifting.sketch.Junction`). Off by default: the
        bundled examples' intended free ends lie 0.08-0.9 % of the
        diagonal from other strokes, so no one tolerance tells a near miss
        from a free end (docs/lifting.md, "Closing gaps").
    above_min : float
        The depth sign follows the "view from above" score
        (:func:`auszug.lifting.reconstruct.depth_sign_score`, in [-1, 1]:
        :func:`~auszug.lifting.reconstruct.from_above`'s edges and the
        vertical planes) when its magnitude is above this; otherwise the
        convexity votes decide (0: only for a score of exactly 0, a flat
        network. Measured over 130 lifts of the ground truths, the convexity
        votes picked the wrong sign far more often; docs/lifting.md).
    sign_plane_weight : float
        Weight of the planar strokes' votes (each stroke's plane read as a
        vertical plane, :func:`~auszug.lifting.reconstruct.vertical_planes`)
        against the control-polygon edges' votes of
        :func:`~auszug.lifting.reconstruct.from_above` in the depth sign's
        score (lift-sign2: 8, the middle of the range 6-10 that measured the
        same on both sign grids and the noise table; 0: the edges alone, the
        rule before).
    sign_plane_flat : float
        A stroke votes as a plane only when its control points' third
        singular value is at most this share of the second: the strokes the
        lift made planar (applied planarity holds to the solver's
        precision); a curve left bent out of its plane by noise or by the
        energy does not vote (0.002: the middle of the measured range
        0.0005-0.005; at 0.04, 4-5 more noisy lifts of the spiral and the
        cross took the mirror).
    sign_plane_straight : float
        ... and their second singular value at least this share of the
        first (a straight stroke has no plane; 0-0.05 measured the same).
    newton_iterations : int
        Most Newton steps of one solve.
    newton_tol : float
        A solve has converged when every constraint residual and every step
        is below this.
    kkt_reg : float
        Regularisation of the KKT system's constraint block (-kkt_reg I), so
        that redundant constraints keep it non-singular.
    hessian_reg : float
        Added to the energy Hessian's diagonal (keeps Newton's matrix non-singular
        along directions no energy sees).
    soc_tol : float
        GMRES's relative tolerance in the solves of the line search's second-order
        corrections (0: the Newton steps' own 1e-13). A correction only proposes a
        trial point for the merit test, so it need not be exact. *Our choice*
        (lift-speed4): 1e-8; with ``refine_inexact`` on the 100-curve benchmark
        1143 -> 843 preconditioner solves, the lifted points within 1e-12 of the
        diagonal. 1e-6 saved 130 more but changed a crawling seed propagation of
        the spiral truth at 1 % noise (converged in 22 steps, then not in 60),
        and with it that lift's flip flag (docs/lifting.md).
    refine_inexact : bool
        Solve each step of the iterative refinement (toward the KKT system without
        ``kkt_reg``) only to the Newton step's own absolute accuracy, a relative
        tolerance of 1e-13 |rhs| / |residual| (at most 0.5), instead of 1e-13
        relative: the residual it corrects is 1e-15 to 1e-9 of the right-hand side.
        *Our choice* (lift-speed4): on; 1488 -> 1143 preconditioner solves on the
        100-curve benchmark, the lifted points within 6.3e-13 of the diagonal
        (docs/lifting.md).
    parallel_robust_deg : float
        *Beyond the paper* (0: off, the paper's baseline). With c > 0, the kept
        baseline is solved ``robust_rounds`` more times, each candidate's soft
        parallel weight multiplied by the Geman-McClure weight
        ``(c^2 / (c^2 + a^2))^2`` of its 3D angle ``a`` (degrees) on the
        previous solve (iteratively reweighted least squares), so that
        candidates far from parallel in 3D stop pulling. Measured with 5 deg
        and ``w_depth_anchor`` 10 (docs/lifting.md, "Robust baseline and depth
        anchor", "The packages re-measured"): not adopted, the wrong signs rise
        (depth-sign grid 0 -> 14 of 60 on lift-robust3; with ``robust_max_move``
        0.12 none, but the noisy revolve and saddle miss "at most twice the
        noise-free error").
    robust_rounds : int
        Reweighted baseline solves with ``parallel_robust_deg`` (3).
    robust_max_move : float
        *Beyond the paper* (0: off; lift-robust3). With ``parallel_robust_deg``: a
        trust bound on the reweighting. When a reweighted baseline's depths differ
        from the paper's baseline by more than this share of the baseline's depth
        spread (standard deviations of the control points' depths, the difference's
        mean removed), the reweighting has left the baseline's basin: it is discarded
        and the reweighting stops (the previous solve kept). When no reweighting was
        kept, or none moved the depths beyond round-off
        (:data:`auszug.lifting.reconstruct.UNMOVED`), the class depth anchor
        (``w_depth_anchor``) is not used either, so the lift is the paper's. Measured
        (docs/lifting.md, "The packages re-measured"): the accepted moves at the
        revolve's and the saddle's own views 0.02-0.10, those that led the vase and
        the revolve to the wrong sign 0.18-0.44; with 0.12 the depth-sign grid has 0
        wrong signs of 60 (14 without), the revolve and the saddle keep 1.33 and
        3.05 %, the cross loses its 13.5 % (16.4 %, the default's).
    w_depth_anchor : float
        *Beyond the paper* (0: off). In every round of a cue class's
        progressive resolution, the term ``w sum_k (z_k - z0_k)^2`` over the
        control points' depths, ``z0`` the depths when the class's resolution
        began: the class's cues bend the network in depth only against it
        (the fidelity energy hardly resists depth changes; docs/lifting.md).
    parallel_confirm : bool
        *Beyond the paper* (off: the paper's rule). A consistency check in the
        tangent-parallelism class: after each round, the round is solved once
        more without the soft pull of the cues it would apply (every other
        term and cue as in the round, the depths held by
        ``w_confirm_anchor``), and a cue whose angle then leaves I_b is
        rejected instead of applied (its likelihood rose by its own pull
        only); the round's own solution is kept. A check solve that does not
        converge checks nothing. Measured (docs/lifting.md, "Consistency
        check"): it raises the parallel F1 of the noise-free truths, but the
        depth error goes both ways and noise costs recall, so it is not the
        default; since ``final_hold`` it also takes the 100-curve benchmark's
        lift from 2.3-2.5 to 24-25 s CPU (lift-robust3).
    w_confirm_anchor : float
        Weight of ``sum_k (z_k - z0_k)^2`` in the check solves of
        ``parallel_confirm``, z0 the depths when the class's resolution began
        (10, the measured setting; 0: none). Without it the check solve is
        free along the fidelity's near-null space in depth, and true cues
        leave I_b too (the revolve loses 12 of its 23 true cues).
    parallel_foreshorten : bool
        *Beyond the paper* (off: the paper's candidates; branch lift-parallel). Under orthographic projection
        parallel 3D tangents are drawn parallel, and two within ``inner_deg`` of each other at most
        ``arcsin(sin(inner_deg) / f)`` apart, f the foreshortening of the less foreshortened one
        (:func:`auszug.lifting.reconstruct.foreshortening_bound`). With this on, a parallel candidate whose drawn
        2D angle exceeds that bound (plus ``parallel_2d_slack_deg``) at the baseline's foreshortening is not
        resolved (never applied). Measured (docs/lifting.md, "Foreshortening bound of the parallel candidates"):
        noise-free it rejects no true candidate on the six truths and most false ones (revolve 3.08 -> 1.05 %,
        saddle 4.94 -> 3.45 %, cross 16.38 -> 7.68 %, turret 10.03 -> 8.64 %, but spiral 34.31 -> 41.80 %), but
        1 % noise turns drawn tangents by up to 25 deg, true candidates are rejected, and "1 % noise at most twice
        the noise-free error" is missed (revolve 6.24, saddle 4.61), so it is not the default.
    parallel_2d_slack_deg : float
        The sketch's angular inaccuracy allowed on top of that bound, degrees (0; 2 measured: the revolve
        1.05 -> 6.45 %, a part of its false candidates applied).
    family_prior : bool
        *Beyond the paper* (on by default since lift-wrinkle). Where the lift's smooth crossings
        leave a one-parameter family of linear depth maps ``z' = alpha x + beta y + gamma z`` (an
        extrusion seen orthographically: every member has the same accuracy, variation and cues,
        and foreshortening picks the flattest), the member whose two largest extents along its
        principal axes are equal (isotropy of the 3D extent: as deep as wide) is solved once more
        and replaces the lift, before the depth sign (:mod:`auszug.lifting.family`; not with
        applied symmetry or plane cues, which such maps do not keep). Measured (docs/lifting.md,
        "Depth family prior"): the wrinkle 8.95 -> 1.82 % (grid median 10.5 -> 1.9 %, its 5 wrong
        signs -> 0), the saddle 7.47 -> 4.94 %, the ogee roof 3.50 -> 2.13 %, the arches 9.56 ->
        6.96 %; worse: the revolve from turn 0 (5.4 -> 9.0 %) and the vase at tilt 35, turn +-50
        (5.0 -> 13.0 %). False: the paper's lift.
    family_tol : float
        A singular value of the smooth crossings' Jacobian (their cosines by ``(alpha, beta, gamma)``
        at the identity) below this share of the largest counts as a free direction (1e-3; measured
        shares: the wrinkle 5e-7 noise-free and 1.1-1.6e-4 at 1 % noise, the turret 4e-6 to 1e-4,
        the saddle 5e-5 to 2e-4, the revolve 1.5e-4 to 7e-4, whose near-family the energy test of
        ``family_energy_tol`` then rejects).
    family_span : float
        The family is searched over depth maps ``(alpha, beta, gamma)`` within this distance of the
        identity (2: 81 grid points, then golden-section refinement; :func:`auszug.lifting.family.extent_member`),
        with ``gamma > 0`` (no mirror).
    family_max_deg : float
        A member is admissible only if every smooth crossing stays within this of 90 deg under the
        map (0.1 deg; before the solve that follows it, which holds them again).
    family_parallel_deg : float
        ... and only on an extrusion: one 3D direction along one of the two tangents of every smooth
        crossing, within this angle (1 deg; :func:`auszug.lifting.family.extruded`). A lift that
        applied false parallels can be one (the revolve seen from turn 0, its meridians' tangents
        lifted parallel at the crossings), so this does not keep the prior off every false family.
    family_energy_tol : float
        The member is solved once more (every hard cue held, its depths held by ``w_final_anchor``)
        and kept only if that solve converges, every applied cue holds within ``applied_tol_deg``,
        and the energy a depth family leaves unchanged (fidelity without foreshortening, plus the
        kept soft cues) rose by at most this share (0.01: the revolve's and the bundled vase's
        near-families cost 9 and 19 %; on the wrinkle, turret, saddle, ogee roof and arches it fell
        or stayed).
    nd_ordering : bool
        Factorise the KKT matrices of the solves that take more than two Newton steps in a
        nested-dissection ordering (METIS, by ``pymetis``) with our compiled LDL^T
        (``auszug.lifting._ldl``, built by ``make install``) where that costs fewer multiply-adds
        than QDLDL's AMD (``auszug.lifting.solver.Orderings``; without ``pymetis`` or the compiled
        kernels, QDLDL throughout). Only GMRES's preconditioner changes, so the lift moves by
        round-off. *Our choice* (lift-speed5): on (docs/lifting.md, benchmarks/RESULTS.md).
    """

    w_a: float = 1.0
    w_v: float = 2.0
    w_f: float = 0.001
    w_a_baseline: float = 1.0
    sigma: float = 1.0 / 3.0
    eps: float = 0.01
    w_c: float = 50.0
    w_p_baseline: float = 0.1
    sigma_p_deg: float = 15.0
    w_p_propagate: float = 5.0
    w_p_propagate_second: float = 0.1
    inner_deg: float = 5.0
    outer_deg: float = 15.0
    outer_value: float = 0.005
    rounds: int = 8
    final_solve: bool = False
    final_hold: bool = True
    w_final_anchor: float = 10.0
    applied_tol_deg: float = 0.5
    hold_first_step: float = 1.0 / 128.0
    parallel_2d_deg: float = 30.0
    plane_cluster_deg: float = 15.0
    smooth_joint_deg: float = 10.0
    min_crossing_deg: float = 10.0
    straight_tol: float = 1e-6
    snap: float = 0.01
    merge: float = 1e-7
    close_gaps: float = 0.0
    above_min: float = 0.0
    sign_plane_weight: float = 8.0
    sign_plane_flat: float = 0.002
    sign_plane_straight: float = 0.02
    newton_iterations: int = 60
    newton_tol: float = 1e-10
    kkt_reg: float = 1e-11
    hessian_reg: float = 1e-10
    soc_tol: float = 1e-8
    refine_inexact: bool = True
    nd_ordering: bool = True
    parallel_robust_deg: float = 0.0
    robust_rounds: int = 3
    robust_max_move: float = 0.0
    w_depth_anchor: float = 0.0
    parallel_confirm: bool = False
    w_confirm_anchor: float = 10.0
    parallel_foreshorten: bool = False
    parallel_2d_slack_deg: float = 0.0
    family_prior: bool = True
    family_tol: float = 1e-3
    family_span: float = 2.0
    family_max_deg: float = 0.1
    family_parallel_deg: float = 1.0
    family_energy_tol: float = 0.01

    def __post_init__(self) -> None:
        for f in fields(self):
            v = getattr(self, f.name)
            if not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
                raise GeometryError(f"lifting parameter {f.name} must be a finite number >= 0, got {v!r}")
        if not 0 < self.inner_deg < self.outer_deg:
            raise GeometryError(f"need 0 < inner_deg < outer_deg, got {self.inner_deg}, {self.outer_deg}")
        if not self.soc_tol < 1:
            raise GeometryError(f"soc_tol must lie in [0, 1), got {self.soc_tol}")
        if self.close_gaps > CLOSE_GAPS_MAX:
            raise GeometryError(f"close_gaps must be at most {CLOSE_GAPS_MAX} (5 % of the diagonal), "
                                f"got {self.close_gaps}")
        if not 0 < self.outer_value < 1:
            raise GeometryError(f"outer_value must lie in (0, 1), got {self.outer_value}")
        for name in ("rounds", "robust_rounds", "newton_iterations"):
            v = getattr(self, name)
            if v != int(v) or v > LIMITS.lift_steps:
                raise GeometryError(f"lifting parameter {name} must be a whole number in 0..{LIMITS.lift_steps} "
                                    f"(auszug.limits.LIMITS.lift_steps), got {v!r}")

    @property
    def exponent(self) -> float:
        """B of L(alpha) = min(1, a alpha^b) (Eq. 10): L(I_b) = 1, L(O_b) = outer_value."""
        return math.log(self.outer_value) / math.log(self.outer_deg / self.inner_deg)

    @property
    def coefficient(self) -> float:
        """A of L(alpha) = min(1, a alpha^b) (Eq. 10)."""
        return float(self.inner_deg ** (-self.exponent))


#: The paper's values.
DEFAULT = LiftParams()
