"""True2Form's reconstruction: baseline, progressive selective regularisation, depth sign, network.

:func:`lift` takes a :class:`~auszug.lifting.sketch.Sketch` and returns a
:class:`LiftResult` with the 3D curve network (one exact 3D cubic Bezier
piece per segment, x and y in the sketch's units, y up, z the depth toward
the viewer), the cues found and every stage's energy and timing.
"""

from __future__ import annotations

import time
import weakref
from dataclasses import dataclass, fields, replace
from typing import Callable

import numpy as np
from numpy.typing import NDArray

from auszug.errors import GeometryError
from auszug.geometry import TOL, CubicBezier, SymmetryGroup
from auszug.geometry.heights import SideCoordinate
from auszug.geometry.network import CurveNetwork, Piece
from auszug.lifting import cues as cu
from auszug.lifting.family import extent_member
from auszug.lifting.params import CLOSE_GAPS_MAX, COLLAPSED, DEFAULT, LiftParams, close_gaps_for
from auszug.lifting.sketch import Sketch, SketchGraph, Stroke, near_junctions, nearest_end_gap, sketch_graph
from auszug.lifting.solver import Orderings, Poly2, SolveResult, solve
from auszug.lifting.terms import fidelity, structure

__all__ = ["CueResult", "Stage", "LiftResult", "lift", "lift_graph", "layer_graphs", "from_above", "depth_sign_score",
           "vertical_planes", "CLASSES", "DEFAULT_CLASSES", "mirror_plane", "symmetry_stroke"]

Array = NDArray[np.float64]

#: The cue classes in the order they are resolved (paper sec. 4 and 5.3).
CLASSES = ("parallel", "orthogonal", "symmetry", "linear", "planar", "plane")
#: The classes :func:`lift` resolves by default: local symmetry is implemented but off, since its hard
#: constraints currently stop Newton from converging on the revolve ground truth (docs/lifting.md);
#: plane parallelism / orthogonality ("plane") is off since its round made the arches example worse
#: (9.16 -> 11.07 % depth RMSE, docs/lifting.md); linearity ("linear") is off since it made the noisy
#: vase worse (1 % noise: 3.08, 3.09, 4.57 -> 3.66, 4.02, 5.48 %) while it helps noisy boxes.
DEFAULT_CLASSES = ("parallel", "orthogonal", "planar")


@dataclass(frozen=True)
class CueResult:
    """One candidate regularity and what became of it.

    Attributes
    ----------
    kind : str
        ``"smooth-orthogonal"`` (always applied) or one of :data:`CLASSES`.
    where : str
        Which curves (their SVG ids).
    applied : bool
    angle : float
        Its angle on the final network, degrees (0 = exactly regular).
    layer : int
    """

    kind: str
    where: str
    applied: bool
    angle: float
    layer: int = 0


@dataclass(frozen=True)
class Stage:
    """One stage of the reconstruction: name, seconds, energy, constraint residual, Newton steps.

    ``discarded``: a solve from a candidate seed crossing that did not converge; that seed is not used.
    """

    name: str
    seconds: float
    energy: float
    violation: float
    iterations: int
    converged: bool
    applied: int = 0
    rejected: int = 0
    layer: int = 0
    discarded: bool = False


@dataclass(frozen=True, eq=False)
class LiftResult:
    """What :func:`lift` found.

    Attributes
    ----------
    network : CurveNetwork
    cues : tuple of CueResult
    stages : tuple of Stage
    converged : bool
        Every solve converged with its hard constraints met.
    flipped : tuple of bool
        Per layer: whether the depth-sign rule (the view from above,
        :func:`depth_sign_score`; convexity where that is 0) or a flip marker chose
        the mirror image z -> -z of the solver's solution.
    points : tuple of (n, 3) ndarray
        Per layer: the lifted control points (sketch units).
    graphs : tuple of SketchGraph
        Per layer; with a global symmetry curve, its layer's graph also holds
        the mirrored strokes (ids ending in ``" (mirror)"``), whose points
        follow the drawn ones in ``points``.
    mirror : tuple or None
        With a global symmetry curve: ``(layer, normal (3,), offset)``, the
        symmetry plane ``normal . p = offset`` in sketch units (unit normal).
    """

    network: CurveNetwork
    cues: tuple[CueResult, ...]
    stages: tuple[Stage, ...]
    converged: bool
    flipped: tuple[bool, ...]
    points: tuple[Array, ...]
    graphs: tuple[SketchGraph, ...]
    mirror: tuple[int, Array, float] | None = None


Progress = Callable[[str], None]


def _components(g: SketchGraph) -> NDArray[np.intp]:
    """Connected component of every stroke (strokes joined by shared points)."""
    ns = len(g.chains)
    parent = list(range(ns))

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    owner: dict[int, int] = {}
    for s, chain in enumerate(g.chains):
        for p in np.unique(g.segments[chain][:, [0, 3]]):
            if int(p) in owner:
                a, b = find(owner[int(p)]), find(s)
                parent[max(a, b)] = min(a, b)
            else:
                owner[int(p)] = s
    return np.array([find(i) for i in range(ns)], dtype=np.intp)


#: The baseline is computed from this many seed crossings; the lowest fidelity energy wins
#: (the paper lifts one; several guard against a poor local minimum, docs/lifting.md).
SEEDS = 4
#: Two seeds' baselines are the same minimum when their energies agree to this relative tolerance;
#: the remaining seeds are then skipped.
SAME_MINIMUM = 1e-7


def _seed(g: SketchGraph, ortho: cu.Orthogonal) -> NDArray[np.intp]:
    """The smooth crossings to lift first, at most :data:`SEEDS`.

    The most oblique ones (2D angle furthest from 90 deg) among those at least
    20 deg from a tangency.
    """
    if not len(ortho):
        raise GeometryError("the sketch has no smooth crossing (two strokes crossing each other, both "
                            "smooth there): True2Form's lifting starts from one")
    bar = g.points
    a = cu.angle_between(np.c_[bar[ortho.h1] - bar[ortho.p], np.zeros(len(ortho))],
                         np.c_[bar[ortho.h2] - bar[ortho.p], np.zeros(len(ortho))])
    off = np.abs(90.0 - a)
    score = np.where(off <= 70.0, off, -1.0)
    return np.argsort(-score, kind="stable")[:SEEDS].astype(np.intp)


def _initial(g: SketchGraph, n: int, ortho: cu.Orthogonal, k: int) -> Array:
    """Sketch positions, z = 0 but at the seed crossing.

    Its two tangents are lifted to orthogonal, equally foreshortened
    (dz_a dz_b = -a.b, |dz_a|/|a| = |dz_b|/|b|).
    """
    v = np.zeros(n)
    N = len(g.points)
    v[: 3 * N].reshape(N, 3)[:, :2] = g.points
    p, ha, hb = int(ortho.p[k]), int(ortho.h1[k]), int(ortho.h2[k])
    a, b = g.points[ha] - g.points[p], g.points[hb] - g.points[p]
    c = float(np.dot(a, b))
    na, nb = float(np.linalg.norm(a)), float(np.linalg.norm(b))
    dza = float(np.sqrt(abs(c) * na / nb)) if c != 0 else 0.0
    dzb = -c / dza if dza else 0.0
    v[3 * ha + 2] = dza
    v[3 * hb + 2] = dzb
    # the opposite handles of the two G1 strokes, collinear through the crossing
    for h, dz, nh in ((ha, dza, na), (hb, dzb, nb)):
        for c_ in g.crossings:
            if c_.point != p:
                continue
            for s, e in c_.ends:
                other = int(g.segments[s, 1] if e == 0 else g.segments[s, 2])
                if other == h:
                    continue
                d = g.points[other] - g.points[p]
                if np.dot(d, g.points[h] - g.points[p]) < -0.99 * np.linalg.norm(d) * nh:
                    v[3 * other + 2] = -dz * np.linalg.norm(d) / nh
    return v


class _Problem:
    """One layer's unknowns, fixed terms and the running solution."""

    def __init__(self, g: SketchGraph, params: LiftParams, layer: int, progress: Progress | None):
        self.g, self.params, self.layer, self.progress = g, params, layer, progress
        self.N = len(g.points)
        self.n = 3 * (self.N + len(g.chains)) + len(g.chains)   # points, normals, plane offsets
        self.smooth = cu.smooth_orthogonal(g)
        self.stages: list[Stage] = []
        self.seeds = _seed(g, self.smooth)
        self.seed = int(self.seeds[0])
        self.pin = int(self.smooth.p[self.seed])
        self.base = structure(g, self.n, params, self.pin)
        self.fid = {w: fidelity(g, self.n, params, w) for w in (params.w_a, params.w_a_baseline)}
        self.v = _initial(g, self.n, self.smooth, self.seed)
        self.lam: Array | None = None
        self.orderings = Orderings() if params.nd_ordering else None

    def X(self, v: Array | None = None) -> Array:
        return (self.v if v is None else v)[: 3 * self.N].reshape(self.N, 3)

    def _normal_anchor(self, P: Poly2) -> None:
        # normals that no cue uses stay where they are (a tiny pull keeps Newton's matrix regular)
        cols = np.arange(3 * self.N, self.n)
        P.add(-self.v[cols], 1e-8, lin=(np.arange(len(cols)), cols, np.ones(len(cols))))

    def run(self, name: str, energy: Poly2, cons: Poly2, applied: int = 0, rejected: int = 0,
            candidate: bool = False, first_step_min: float = 0.0) -> SolveResult:
        t0 = time.perf_counter()
        self._normal_anchor(energy)
        lam0 = self.lam if self.lam is not None and len(self.lam) == cons.rows else None
        r = solve(energy, cons, self.v, lam0, iterations=self.params.newton_iterations,
                  tol=self.params.newton_tol, kkt_reg=self.params.kkt_reg, hessian_reg=self.params.hessian_reg,
                  soc_tol=self.params.soc_tol, refine_inexact=bool(self.params.refine_inexact),
                  orderings=self.orderings, first_step_min=first_step_min)
        self.v, self.lam = r.v, r.lam
        st = Stage(name, time.perf_counter() - t0, r.energy, r.violation, r.iterations, r.converged,
                   applied, rejected, self.layer, candidate and not r.converged)
        self.stages.append(st)
        if self.progress is not None:
            self.progress(f"layer {self.layer} {name}: energy {r.energy:.3g}, {r.iterations} Newton steps"
                          + (f", {applied} applied, {rejected} rejected" if applied or rejected else "")
                          + ("" if r.converged else " (no convergence from this seed: discarded)" if candidate
                             else " (given up in its first line search)" if r.gave_up else " (NOT converged)"))
        return r

    def energy(self, w_a: float, anchor: Array | None = None, w_anchor: float | None = None) -> Poly2:
        """Fidelity with accuracy weight ``w_a``; with ``anchor``, ``w (z - anchor)^2`` (w: ``w_anchor``)."""
        base = self.fid[w_a]
        P = Poly2(self.n)
        P.const, P.weight, P.lin, P.bil, P.rows = list(base.const), list(base.weight), list(base.lin), \
            list(base.bil), base.rows
        w = self.params.w_depth_anchor if w_anchor is None else w_anchor   # by default the class's anchor
        if anchor is not None:
            self.add_anchor(P, anchor, w)
        return P

    def add_anchor(self, P: Poly2, anchor: Array, w: float) -> None:
        """Add ``w sum_k (z_k - anchor_k)^2`` over the control points' depths to ``P`` (nothing if w <= 0)."""
        if w > 0:
            cols = 3 * np.arange(self.N) + 2
            P.add(-anchor, w, lin=(np.arange(self.N), cols, np.ones(self.N)))

    def constraints(self) -> Poly2:
        C = Poly2(self.n)
        b = self.base
        C.const, C.weight, C.lin, C.bil, C.rows = list(b.const), list(b.weight), list(b.lin), list(b.bil), b.rows
        return C


@dataclass(frozen=True)
class _Forced:
    """The cues a global symmetry curve applies (masks into the families, and its Eq. 8 rows)."""

    parallel: NDArray[np.bool_]
    orthogonal: NDArray[np.bool_]
    planar: NDArray[np.bool_]
    symmetry: cu.Symmetry


@dataclass(frozen=True, eq=False)
class _Pending:
    """The cues a class's last round applied, not yet held by a solve (``LiftParams.final_hold``).

    ``acc`` (k,) the cues' indices in the class's family and ``ang0`` (k,) their angles (degrees) in that
    round's solution; ``mask`` (m,) the class's applied flags (rejected cues are cleared in place);
    ``hard_add`` / ``soft_add`` the class's callbacks; ``rest`` the round's undecided cues, soft with
    weights ``w``; ``anchor`` the class's depth anchor (None without ``w_depth_anchor``).
    """

    name: str
    acc: NDArray[np.intp]
    ang0: Array
    mask: NDArray[np.bool_]
    hard_add: Callable[[NDArray[np.intp]], None]
    soft_add: Callable[[Poly2, NDArray[np.intp], Array], None]
    rest: NDArray[np.intp]
    w: Array
    anchor: Array | None


def _take(fam, keep: NDArray[np.bool_]):
    """The candidates of a cue family where ``keep`` (every array field indexed, ``where`` filtered)."""
    out = {}
    for f in fields(fam):
        v = getattr(fam, f.name)
        out[f.name] = tuple(x for x, k in zip(v, keep, strict=True) if k) if isinstance(v, tuple) else v[keep]
    return type(fam)(**out)


def _handle_strokes(g: SketchGraph) -> NDArray[np.intp]:
    """Per control point: the stroke whose handle it is, -1 for segment ends."""
    out = np.full(len(g.points), -1, dtype=np.intp)
    out[g.segments[:, 1]] = g.seg_stroke
    out[g.segments[:, 2]] = g.seg_stroke
    return out


def _about(g: SketchGraph, sym: cu.Symmetry, s: int) -> NDArray[np.bool_]:
    """Local symmetry rows whose symmetry plane is stroke ``s`` (its far points on s, the other curve not s)."""
    ends = np.unique(g.segments[g.chains[s]][:, [0, 3]])
    hs = _handle_strokes(g)
    return np.isin(sym.f_out, ends) & np.isin(sym.f_in, ends) & np.isin(sym.p, ends) & (hs[sym.h] != s)


def _symmetry_forced(g: SketchGraph, s: int | None, smooth: cu.Orthogonal, par: cu.Parallel, orth: cu.Orthogonal,
                     pla: cu.Planar) -> _Forced:
    """What a global symmetry curve (stroke ``s`` of ``g``) applies.

    The paper's sec. 4 "planarity, orthogonality, and symmetry along the marked curve", and the
    parallelism of the curves that cross it at adjacent crossings (all normal to its plane).
    """
    if s is None:
        return _Forced(np.zeros(len(par), bool), np.zeros(len(orth), bool), np.zeros(len(pla), bool),
                       cu.symmetry_cues(g, []))
    ends = np.unique(g.segments[g.chains[s]][:, [0, 3]])
    hs = _handle_strokes(g)
    f_par = np.isin(par.p1, ends) & np.isin(par.p2, ends) & (hs[par.h1] != s) & (hs[par.h2] != s)
    f_orth = np.isin(orth.p, ends) & ((hs[orth.h1] == s) ^ (hs[orth.h2] == s))
    f_pla = pla.stroke == s
    pairs = [(int(p), int(a), int(b)) for p, a, b in zip(smooth.p, smooth.h1, smooth.h2, strict=True)
             if p in ends and (hs[a] == s) != (hs[b] == s)]
    pairs += [(int(orth.p[i]), int(orth.h1[i]), int(orth.h2[i])) for i in np.nonzero(f_orth)[0]]
    sym = cu.symmetry_cues(g, pairs)
    return _Forced(f_par, f_orth, f_pla, _take(sym, _about(g, sym, s)))


def foreshortening_bound(f: Array, delta_deg: float) -> Array:
    """The largest 2D angle between the projections of two 3D directions at most ``delta_deg`` apart.

    Orthographic projection along z: the directions within ``delta`` of a unit vector whose projection has length
    ``f`` (its foreshortening, ``sin`` of its angle to the view direction) project within
    ``arcsin(sin(delta) / f)`` of its own projection's direction (the azimuthal half-width of a spherical cap of
    radius ``delta`` about a point ``arcsin f`` from the pole), and anywhere when ``f <= sin(delta)``.

    Parameters
    ----------
    f : ndarray, shape (m,)
        Foreshortening of the reference direction, in [0, 1].
    delta_deg : float
        Largest 3D angle, degrees.

    Returns
    -------
    ndarray, shape (m,)
        The bound, degrees, in (0, 90].
    """
    s = np.sin(np.radians(delta_deg))
    return np.asarray(np.degrees(np.arcsin(np.minimum(1.0, s / np.maximum(f, 1e-300)))), dtype=float)


def parallel_beyond_foreshortening(par: cu.Parallel, X: Array, params: LiftParams = DEFAULT) -> NDArray[np.bool_]:
    """Parallel candidates whose drawn 2D angle no pair of 3D tangents within I_b can project to.

    Under orthographic projection, parallel 3D tangents are drawn parallel, and two tangents within
    ``params.inner_deg`` of each other are drawn at most :func:`foreshortening_bound` apart, their
    foreshortening taken from ``X`` (the less foreshortened of the two: the looser bound). A candidate whose 2D
    angle exceeds that bound by more than ``params.parallel_2d_slack_deg`` cannot be within I_b in 3D at these
    foreshortenings unless the sketch is that inaccurate.

    Parameters
    ----------
    par : Parallel
        The candidates (their ``angle2d``, degrees, on the drawn sketch).
    X : ndarray, shape (n, 3)
        Control points (the baseline lift), giving each tangent's foreshortening.
    params : LiftParams
        ``inner_deg`` and ``parallel_2d_slack_deg``.

    Returns
    -------
    ndarray of bool, shape (len(par),)
        True for the candidates beyond the bound.
    """
    if not len(par):
        return np.zeros(0, dtype=bool)
    t1, t2 = X[par.h1] - X[par.p1], X[par.h2] - X[par.p2]
    f1 = np.linalg.norm(t1[:, :2], axis=1) / np.maximum(np.linalg.norm(t1, axis=1), 1e-300)
    f2 = np.linalg.norm(t2[:, :2], axis=1) / np.maximum(np.linalg.norm(t2, axis=1), 1e-300)
    bound = foreshortening_bound(np.minimum(f1, f2), params.inner_deg)
    return np.asarray(par.angle2d > bound + params.parallel_2d_slack_deg, dtype=bool)


def lift_graph(g: SketchGraph, params: LiftParams = DEFAULT, layer: int = 0,
               progress: Progress | None = None,
               classes: tuple[str, ...] = CLASSES,
               symmetry: int | None = None) -> tuple[Array, list[CueResult], list[Stage], bool, bool]:
    """Lift one layer's graph; return control points (normalised), cues, stages, converged, flipped.

    ``symmetry``: index (into ``g.strokes``) of the global symmetry curve, if
    the layer has one. Then, from the baseline on, the paper's sec. 4
    "planarity, orthogonality, and symmetry along the marked curve" are
    applied, not resolved: the curve's planarity (when it is curved in 2D)
    and the orthogonality of every curve meeting it are hard constraints, the
    local symmetry (Eq. 8) of those curves about the curve's plane is hard
    wherever the curve is curved there, and the tangent parallelism of the
    curves at adjacent crossings along it is applied (soft with w_c, as every
    applied parallelism). The caller mirrors the result (:func:`mirror_plane`).

    The stages (paper sec. 5.3):

    1. *seed*: the most oblique smooth crossing is lifted (its two tangents
       orthogonal and equally foreshortened), then propagated by minimising
       fidelity (w_a = ``params.w_a_baseline``, 1; the paper: 10) with soft
       parallelism w_p = 5 exp(-alpha^2 / sigma^2) subject to orthogonality at
       the seed only;
    2. *baseline*: fidelity (the same w_a) with soft parallelism
       w_p = 0.1 exp(-alpha^2 / sigma^2) subject to orthogonality at every
       smooth crossing. Stages 1-2 run from up to :data:`SEEDS` seed crossings,
       the lowest converged baseline kept; a seed that does not converge is
       discarded, and once two seeds reach the same minimum (energies within
       :data:`SAME_MINIMUM`) the others are skipped. If none do and one of
       their baselines converged, every seed whose propagation converged is
       propagated once more with w_p = ``params.w_p_propagate_second`` (0.1;
       our addition: over mostly false candidates w_p = 5 can lead to a worse
       basin) and the same rules go on over these starts;
    3. one progressive resolution per cue class of :data:`CLASSES`, with
       w_a = 1: each round minimises fidelity + w_c sum L(alpha) C^2 over the
       undecided cues, subject to the applied ones; L = 1 applies a cue
       (parallelism stays soft with weight w_c), L = 0 or no increase rejects
       it; after ``params.rounds`` rounds the rest is rejected. Cues applied
       in a class's final round are held by the next class's solves; those of
       the last round run only within I_b, unless ``params.final_hold`` (our
       rule, on by default): one more solve of that round with them hard, the
       round's energy kept (its soft terms and class depth anchor), its depths
       held near its solution by ``params.w_final_anchor`` (given up at its first step by
       ``params.hold_first_step``), kept if it converges and every
       applied cue then holds within ``params.applied_tol_deg``; otherwise the
       round's solution stays and its applied cues beyond that angle there are
       rejected. ``params.final_solve`` instead solves fidelity and the kept
       cues once more with every applied cue hard and no depth anchor (the
       paper's fixed point). The class
       ``"plane"`` (plane parallelism and orthogonality) comes after planarity:
       its candidates are the single-linkage clusters of the applied planar
       strokes' normals (:func:`~auszug.lifting.cues.plane_cues`);
    4. the depth sign (decided on the last round's solution, before
       ``final_hold``'s solve): the solution or its mirror z -> -z, whichever is seen
       from above (:func:`depth_sign_score`: the edges of :func:`from_above`
       and the vertical planes of :func:`vertical_planes`; where that score is not above
       ``params.above_min``, whichever is more convex seen from the viewer),
       flipped once more per flip marker.
    """
    pr = _Problem(g, params, layer, progress)
    par = cu.parallel_cues(g, params)
    wfac = np.exp(-(par.angle2d**2) / params.sigma_p_deg**2)
    all_par = np.arange(len(par))
    ok = True

    # 1. seed and propagation, 2. baseline: from each seed crossing, the lowest energy kept
    best: tuple[float, Array, Array | None, list[Stage]] | None = None
    start_stages = list(pr.stages)

    def baseline(robust: Array | None = None, name: str = "baseline") -> SolveResult:
        E = pr.energy(params.w_a_baseline)
        par.add(E, all_par, params.w_p_baseline * wfac * (1.0 if robust is None else robust))
        C = pr.constraints()
        pr.smooth.add(C, np.arange(len(pr.smooth)), 1.0)
        pr.lam = None
        return pr.run(name, E, C, candidate=True)

    first_v: Array | None = None   # the first seed's propagation, when its baseline was skipped
    # every seed propagated with the paper's over-emphasised parallelism; then, unless two of those reached the
    # same minimum and provided one of their baselines converged, every seed whose propagation converged again
    # with the baseline's own parallel weight (lift-acc, docs/lifting.md)
    starts = [(int(k), params.w_p_propagate, f"seed {int(k)}") for k in pr.seeds]
    n_first = len(starts)
    w2 = params.w_p_propagate_second
    propagated: list[int] = []
    i = 0
    while True:
        if i == n_first and w2 > 0 and w2 != params.w_p_propagate and best is not None and np.isfinite(best[0]):
            starts += [(k_, w2, f"seed {k_} (w_p {w2:g})") for k_ in propagated]
        if i >= len(starts):
            break
        k, w_prop, label = starts[i]
        i += 1
        pr.v = _initial(g, pr.n, pr.smooth, k)
        pr.lam = None
        pr.stages = list(start_stages)
        E = pr.energy(params.w_a_baseline)
        par.add(E, all_par, w_prop * wfac)
        C = pr.constraints()
        pr.smooth.add(C, np.array([k]), 1.0)
        r1 = pr.run(label, E, C, candidate=True)
        if not r1.converged:
            # a seed whose propagation does not converge is discarded whatever its baseline does, so that
            # solve is skipped (it is run at the end only if no seed converges: the first seed's is kept)
            if i == 1:
                first_v = pr.v.copy()
            start_stages = list(pr.stages)
            continue
        if i <= n_first:
            propagated.append(k)
        r2 = baseline()
        score = r2.energy if r2.converged else np.inf
        start_stages = list(pr.stages)
        if best is not None and np.isfinite(score) and np.isfinite(best[0]) \
                and abs(score - best[0]) <= SAME_MINIMUM * abs(best[0]):
            break   # a second seed reached the same minimum: the others are not tried
        if best is None or score < best[0]:
            best = (score, pr.v.copy(), pr.lam, list(pr.stages))
    if first_v is not None and (best is None or not np.isfinite(best[0])):
        pr.v, pr.stages = first_v, list(start_stages)
        baseline()
        start_stages = list(pr.stages)
        best = (np.inf, pr.v.copy(), pr.lam, list(pr.stages))
    assert best is not None
    _, pr.v, pr.lam, pr.stages = best[0], best[1], best[2], start_stages
    if not np.isfinite(best[0]):
        ok = False
        if progress is not None:
            progress(f"layer {layer}: no seed's baseline converged (NOT converged)")
    anchored = params.w_depth_anchor > 0   # the class depth anchor (beyond the paper, off by default)
    if ok and params.parallel_robust_deg > 0:
        # beyond the paper (off by default): the kept baseline reweighted by its candidates' 3D angles
        c2 = params.parallel_robust_deg**2
        z_base = pr.X()[:, 2].copy()
        spread = float(np.std(z_base))
        reach = params.robust_max_move * spread
        kept = 0
        for k_ in range(params.robust_rounds):
            gm = (c2 / (c2 + par.angles(pr.X()) ** 2)) ** 2
            keep = (pr.v.copy(), pr.lam)
            if not baseline(gm, f"baseline reweighted {k_ + 1}").converged:
                pr.v, pr.lam = keep     # an unconverged reweighting is discarded (its stage says so)
                break
            moved = float(np.std(pr.X()[:, 2] - z_base))
            if reach > 0 and moved > reach:
                # the reweighting left the baseline's basin (robust_max_move): the previous solve is kept
                pr.v, pr.lam = keep
                pr.stages[-1] = replace(pr.stages[-1], discarded=True)
                if progress is not None:
                    progress(f"layer {layer} baseline reweighted {k_ + 1}: depths moved {moved / spread:.3g} of "
                             f"their spread (> {params.robust_max_move:g}): discarded")
                break
            kept += moved > UNMOVED * spread
        if reach > 0 and not kept:
            anchored = False    # with the bound, the class depth anchor holds a reweighted baseline only
    hard: list[Callable[[Poly2], None]] = [lambda c: pr.smooth.add(c, np.arange(len(pr.smooth)), 1.0)]
    soft_kept: list[Callable[[Poly2], None]] = []
    results: list[CueResult] = []
    orth = cu.orthogonal_cues(g)
    pla = cu.planar_cues(g, pr.N)
    forced = _symmetry_forced(g, symmetry, pr.smooth, par, orth, pla)

    # cues applied after the last solve (a class's final round): the next class's first solve holds
    # them; after the last class one more solve does (see the docstring, 3.)
    pending: _Pending | None = None

    def resolve(name: str, fam, hard_add, soft_add, pre: NDArray[np.bool_] | None = None,
                skip: NDArray[np.bool_] | None = None, confirm: bool = False) -> NDArray[np.bool_]:
        nonlocal ok, pending
        m = len(fam)
        applied = np.zeros(m, dtype=bool) if pre is None else pre.copy()   # pre: applied by global symmetry
        if not m or name not in classes:
            return applied
        undecided = ~applied if skip is None else ~applied & ~skip
        if not undecided.any():
            return applied
        Lp = cu.likelihood(fam.angles(pr.X()), params)
        anchor = pr.X()[:, 2].copy() if anchored else None
        check_anchor = pr.X()[:, 2].copy() if confirm and params.w_confirm_anchor > 0 else None
        for rnd in range(params.rounds):
            E = pr.energy(params.w_a, anchor)
            for f in soft_kept:
                f(E)
            idx = np.nonzero(undecided)[0]
            w_round = params.w_c * Lp
            soft_add(E, idx, w_round[idx])
            C = pr.constraints()
            for f in hard:
                f(C)
            r = pr.run(f"{name} round {rnd + 1}", E, C)
            k_round = len(pr.stages) - 1
            pending = None
            ok &= r.converged
            ang = fam.angles(pr.X())
            L = cu.likelihood(ang, params)
            acc = undecided & (L >= 1.0)
            rej = undecided & ~acc & ((L <= 0.0) | (L <= Lp))
            if confirm and acc.any():
                # consistency check (beyond the paper, off by default): the round solved again without the pull
                # of the cues it would apply, its depths held near the class's first ones; a cue whose angle
                # then leaves I_b was made regular by its own pull only, and is rejected
                keep_v, keep_lam = pr.v.copy(), pr.lam
                E = pr.energy(params.w_a, check_anchor, params.w_confirm_anchor)
                for f in soft_kept:
                    f(E)
                rest = np.nonzero(undecided & ~acc & ~rej)[0]
                soft_add(E, rest, params.w_c * L[rest])
                C = pr.constraints()
                for f in hard:
                    f(C)
                rc = pr.run(f"{name} round {rnd + 1} check", E, C)
                if rc.converged:
                    bad = acc & (cu.likelihood(fam.angles(pr.X()), params) < 1.0)
                    acc &= ~bad
                    rej |= bad
                pr.v, pr.lam = keep_v, keep_lam
            applied |= acc
            undecided &= ~(acc | rej)
            Lp = L
            pr.stages[k_round] = replace(pr.stages[k_round], applied=int(acc.sum()), rejected=int(rej.sum()))
            if acc.any():
                sel = np.nonzero(applied)[0]
                hard_add(sel)
                rest = idx[~acc[idx]]
                pending = _Pending(name, np.nonzero(acc)[0], ang[acc], applied, hard_add, soft_add, rest,
                                   w_round[rest], anchor)
            if not undecided.any():
                break
        return applied

    # parallelism: applied cues stay soft with weight w_c (paper sec. 5.3)
    par_state = {"sel": np.zeros(0, np.intp)}

    def par_apply(sel: NDArray[np.intp]) -> None:
        par_state["sel"] = sel

    soft_kept.append(lambda E: par.add(E, par_state["sel"], params.w_c))
    orth_state = {"sel": np.zeros(0, np.intp)}
    hard.append(lambda c: orth.add(c, orth_state["sel"], 1.0))
    pla_state = {"sel": np.zeros(0, np.intp)}

    offset_slot = 3 * (pr.N + len(g.chains)) + pla.stroke   # one plane offset unknown per candidate

    def pla_apply(sel: NDArray[np.intp], refresh: bool = False) -> None:
        new = sel if refresh else np.setdiff1d(sel, pla_state["sel"])
        if len(new):   # the normal and offset variables start at the best fit
            X = pr.X()
            nrm = pla.normals(X)
            for i in new:
                ns = int(pla.normal_slot[i])
                pr.v[3 * ns: 3 * ns + 3] = nrm[i]
                pr.v[offset_slot[i]] = float(nrm[i] @ X[pla.points[i]].mean(0))
        pla_state["sel"] = sel

    def pla_soft(E: Poly2, idx: NDArray[np.intp], w: Array) -> None:
        X = pr.X()
        nrm = pla.normals(X)
        for i in idx:   # offsets start at their optimum, n . mean X
            pr.v[offset_slot[i]] = float(nrm[i] @ X[pla.points[i]].mean(0))
        pla.add_soft(E, idx, w, X, offset_slot)

    def held_solve(name: str, applied: int = 0) -> SolveResult:
        """A solve of fidelity and the kept soft cues subject to every hard cue held so far."""
        E = pr.energy(params.w_a)
        for f in soft_kept:
            f(E)
        C = pr.constraints()
        for f in hard:
            f(C)
        return pr.run(name, E, C, applied=applied)

    def hold_last(last: _Pending, worst_applied: Callable[[], float]) -> None:
        """The rule of ``params.final_hold`` for the cues the last round run applied (``last``).

        That round is solved again with them hard, its depths held near its solution (weight
        ``params.w_final_anchor``); kept if it converges and every applied cue (``worst_applied``, degrees)
        then holds within ``params.applied_tol_deg``, else the round's solution is kept and its applied
        cues that do not hold there within that angle are rejected (as L = 0 would).
        """
        name, acc, ang0, mask, anchor = last.name, last.acc, last.ang0, last.mask, last.anchor
        keep_v, keep_lam = pr.v.copy(), pr.lam
        z0 = pr.X()[:, 2].copy()
        # a solve that does not converge is tried once more from the round's solution with a third of the weight
        for k, w_anchor in enumerate((params.w_final_anchor, params.w_final_anchor / 3.0)):
            if k:
                pr.v, pr.lam = keep_v.copy(), keep_lam
            # the round's own energy (its class depth anchor too, when ``w_depth_anchor`` > 0: without it the
            # held solve drifts along the fidelity's flat directions that anchor holds), plus the hold's anchor
            E = pr.energy(params.w_a, anchor)
            pr.add_anchor(E, z0, w_anchor)
            for f in soft_kept:
                f(E)
            last.soft_add(E, last.rest, last.w)
            C = pr.constraints()
            for f in hard:
                f(C)
            r = pr.run(f"{name} held" + (f" (anchor {w_anchor:.3g})" if k else ""), E, C, applied=len(acc),
                       first_step_min=params.hold_first_step)
            if r.converged or r.gave_up or w_anchor == 0:
                break
            pr.stages[-1] = replace(pr.stages[-1], applied=0, discarded=True)
        worst = worst_applied() if r.converged else np.inf
        if progress is not None:
            after = f"largest applied angle after {worst:.3g} deg" if r.converged else "no angle after"
            progress(f"layer {layer} {name} held: largest angle before {ang0.max():.3g} deg, {len(acc)} cues, "
                     f"converged {r.converged}, {after}")
        if worst <= params.applied_tol_deg:
            return
        pr.v, pr.lam = keep_v, keep_lam
        drop = acc[ang0 > params.applied_tol_deg]
        mask[drop] = False
        last.hard_add(np.nonzero(mask)[0])
        pr.stages[-1] = replace(pr.stages[-1], applied=len(acc) - len(drop), rejected=len(drop), discarded=True)
        if progress is not None:
            why = "an applied cue broken" if r.converged else "given up" if r.gave_up else "not converged"
            progress(f"layer {layer} {name} held: {why}; "
                     f"the round's solution kept, {len(drop)} of its "
                     f"{len(acc)} cues rejected (beyond {params.applied_tol_deg:g} deg there)")

    # global symmetry: its cues hold from here on (the paper's sec. 4), before any class is resolved
    sym_glob = forced.symmetry
    if symmetry is not None:
        par_apply(np.nonzero(forced.parallel)[0])
        orth_state["sel"] = np.nonzero(forced.orthogonal)[0]
        if forced.planar.any():
            pla_apply(np.nonzero(forced.planar)[0])
        hard.append(lambda c: sym_glob.add(c, np.arange(len(sym_glob)), 1.0))
        hard.append(lambda c: pla.add_hard(c, pla_state["sel"], offset_slot))
        n_forced = int(forced.parallel.sum() + forced.orthogonal.sum() + forced.planar.sum()) + len(sym_glob)
        ok &= held_solve("global symmetry", n_forced).converged

    # beyond the paper (off by default): a candidate whose drawn tangents' 2D angle no pair of 3D tangents within I_b of
    # each other can project to, at the baseline's foreshortening, is not resolved (docs/lifting.md, "Foreshortening
    # bound of the parallel candidates")
    par_skip = parallel_beyond_foreshortening(par, pr.X(), params) if params.parallel_foreshorten else None
    if par_skip is not None and progress is not None:
        progress(f"layer {layer} parallel: {int(par_skip.sum())} of {len(par)} candidates' 2D angles beyond the "
                 f"foreshortening bound")
    par_applied = resolve("parallel", par, par_apply, lambda E, i, w: par.add(E, i, w), forced.parallel,
                          skip=par_skip, confirm=params.parallel_confirm)

    orth_applied = resolve("orthogonal", orth, lambda s: orth_state.update(sel=s),
                           lambda E, i, w: orth.add(E, i, w), forced.orthogonal)

    pairs = [(int(p), int(a), int(b)) for p, a, b in zip(pr.smooth.p, pr.smooth.h1, pr.smooth.h2, strict=True)]
    pairs += [(int(orth.p[i]), int(orth.h1[i]), int(orth.h2[i])) for i in np.nonzero(orth_applied)[0]]
    sym = cu.symmetry_cues(g, pairs)
    if symmetry is not None:   # the global symmetry's own rows are in sym_glob already
        sym = _take(sym, ~_about(g, sym, symmetry))
    sym_state = {"sel": np.zeros(0, np.intp)}
    hard.append(lambda c: sym.add(c, sym_state["sel"], 1.0))
    sym_applied = resolve("symmetry", sym, lambda s: sym_state.update(sel=s), lambda E, i, w: sym.add(E, i, w))

    # linearity (class "linear", off by default; our order: before planarity, whose plane a straight
    # curve leaves free; the paper resolves the curve-level cues together). Applied linearity stays soft
    # with weight w_c like parallelism: hard, with the 2D fractions fixed, it made noisy boxes diverge
    lin = cu.linear_cues(g, params)
    lin_state = {"sel": np.zeros(0, np.intp)}
    soft_kept.append(lambda E: lin.add(E, lin_state["sel"], params.w_c))
    lin_applied = resolve("linear", lin, lambda s: lin_state.update(sel=s), lambda E, i, w: lin.add(E, i, w))

    if symmetry is None:
        hard.append(lambda c: pla.add_hard(c, pla_state["sel"], offset_slot))
    pla_applied = resolve("planar", pla, pla_apply, pla_soft, forced.planar,
                          skip=np.isin(pla.stroke, lin.stroke[lin_applied]))

    # plane parallelism / orthogonality: single-linkage clusters of the applied planar strokes' normals
    slots = 3 * pla.normal_slot[:, None] + np.arange(3)
    names = tuple(w.removesuffix(" planar") for w in pla.where)
    pp = cu.plane_cues(pla, pla_applied, pr.v[slots] if len(pla) else np.zeros((0, 3)), names,
                       params.plane_cluster_deg, pr.X(), float(np.tan(np.radians(params.inner_deg))))
    pp_state = {"sel": np.zeros(0, np.intp)}
    hard.append(lambda c: pp.add(c, pp_state["sel"], 1.0))
    pp_applied = resolve("plane", pp, lambda s: pp_state.update(sel=s), lambda E, i, w: pp.add(E, i, w))

    # the depth sign is decided on the last round's solution, before the held solve: the hold only meets the
    # applied cues near that solution (within its anchor), it is not a new shape to decide the sign on (held,
    # the cross's from-above score under the robust baseline and the depth anchor went -0.016 -> +0.011, the
    # wrong sign; docs/lifting.md "Applied cues within 0.5 deg")
    X_sign = pr.X().copy()

    def worst_applied() -> float:
        X = pr.X()
        fams = ((par, par_applied), (orth, orth_applied), (sym, sym_applied), (lin, lin_applied),
                (pla, pla_applied), (pp, pp_applied), (sym_glob, np.ones(len(sym_glob), bool)),
                (pr.smooth, np.ones(len(pr.smooth), bool)))
        return max((float(fam.angles(X)[app].max()) for fam, app in fams if app.any()), default=0.0)

    def ref_energy() -> float:
        """The energy a depth family leaves unchanged: fidelity without foreshortening, plus the kept soft cues."""
        E = fidelity(g, pr.n, replace(params, w_f=0.0), params.w_a)
        for f in soft_kept:
            f(E)
        return float((E.weights * E.value(pr.v) ** 2).sum())

    if pending is not None and params.final_hold and not params.final_solve:
        hold_last(pending, worst_applied)
    elif pending is not None and params.final_solve:
        # the last class's cues applied in its final round have not been held by a solve yet: one
        # more solve, every applied cue hard (parallelism and linearity soft with w_c, as before)
        ok &= held_solve("final").converged

    if params.family_prior and not (sym_applied.any() or len(sym_glob) or pp_applied.any()):
        # beyond the paper (on by default since lift-wrinkle): the lift moved along the depth family its hard orthogonal
        # pairs leave free (an extrusion), to the member whose two largest extents are equal
        m = _family_map(g, pr.X(), pr.smooth, params, layer, progress)
        if m is not None:
            keep_v, keep_lam = pr.v.copy(), pr.lam
            e_before = ref_energy()
            Z = pr.X() @ m
            pr.v[2: 3 * pr.N: 3] = Z - Z[pr.pin]
            pla_apply(pla_state["sel"], refresh=True)
            pr.lam = None
            z_member, v_member = pr.X()[:, 2].copy(), pr.v.copy()
            # a solve that does not converge is tried once more from the member with a third of the weight
            for k, w_anchor in enumerate((params.w_final_anchor, params.w_final_anchor / 3.0)):
                if k:
                    pr.stages[-1] = replace(pr.stages[-1], discarded=True)
                    pr.v, pr.lam = v_member.copy(), None
                E = pr.energy(params.w_a, z_member, w_anchor)
                for f in soft_kept:
                    f(E)
                C = pr.constraints()
                for f in hard:
                    f(C)
                r = pr.run("family prior" + (f" (anchor {w_anchor:.3g})" if k else ""), E, C)
                if r.converged or w_anchor == 0:
                    break
            e_after = ref_energy()
            worst = worst_applied() if r.converged else np.inf
            good = worst <= params.applied_tol_deg and e_after <= e_before * (1 + params.family_energy_tol) + 1e-12
            if progress is not None:
                progress(f"layer {layer} family prior: converged {r.converged}, largest applied angle {worst:.3g} deg, "
                         f"energy without foreshortening {e_before:.4g} -> {e_after:.4g}: "
                         + ("kept" if good else "the lift kept"))
            if good:
                Zs = X_sign @ m
                X_sign = X_sign.copy()
                X_sign[:, 2] = Zs - Zs[pr.pin]
            else:
                pr.v, pr.lam = keep_v, keep_lam
                pr.stages[-1] = replace(pr.stages[-1], discarded=True)

    X = pr.X().copy()
    for kind, fam, app in (("parallel", par, par_applied), ("orthogonal", orth, orth_applied),
                           ("symmetry", sym, sym_applied), ("linear", lin, lin_applied), ("planar", pla, pla_applied),
                           ("plane", pp, pp_applied)):
        ang = fam.angles(X) if len(fam) else np.zeros(0)
        results += [CueResult(kind, w, bool(a), float(x), layer) for w, a, x in zip(fam.where, app, ang, strict=True)]
    results += [CueResult("symmetry", f"{w} (global symmetry)", True, float(x), layer)
                for w, x in zip(sym_glob.where, sym_glob.angles(X) if len(sym_glob) else [], strict=True)]
    results = [CueResult("smooth-orthogonal", w, True, float(x), layer)
               for w, x in zip(pr.smooth.where, pr.smooth.angles(X), strict=True)] + results

    flip = _flip_to_view_from_above(g, X if params.final_solve else X_sign, pr.smooth, params)
    flip ^= sum(c.flipped for c in g.crossings) % 2 == 1
    if flip:
        X[:, 2] *= -1.0
        X[:, 2] -= X[pr.pin, 2]
    return X, results, pr.stages, bool(ok), bool(flip)


def _family_map(g: SketchGraph, X: Array, smooth: cu.Orthogonal, params: LiftParams, layer: int,
                progress: Progress | None) -> Array | None:
    """``params.family_prior``: the depth map ``(alpha, beta, gamma)`` to the family member the prior picks.

    The family is that of the smooth crossings' orthogonality (:mod:`auszug.lifting.family`); None where they
    leave no one-parameter family of linear depth maps, or the lift is its member of most isotropic extent.
    """
    max_cos = float(np.sin(np.radians(params.family_max_deg)))
    found = extent_member(X, g, smooth.p, smooth.h1, smooth.h2, params.family_tol, params.family_span,
                          max_cos, params.family_parallel_deg)
    if found is None:
        if progress is not None:
            progress(f"layer {layer} family prior: no extrusion's depth family, or the lift is its best member")
        return None
    m, before, after = found
    if progress is not None:
        progress(f"layer {layer} family prior: depth map ({m[0]:.4g}, {m[1]:.4g}, {m[2]:.4g}), "
                 f"extent score {before:.4g} -> {after:.4g}")
    return m


#: A reweighted baseline whose depths moved by less than this share of the baseline's depth spread
#: changed nothing (round-off; measured 1e-11 to 1e-9 where no candidate's weight changed): with
#: ``LiftParams.robust_max_move``, no class depth anchor then (docs/lifting.md, "Robust baseline").
UNMOVED = 1e-6

#: Normal curvature (diagonal 1) below which a crossing's curves count as straight (no convexity vote).
CURVED = 1e-6


def from_above(controls: Array) -> float:
    """How clearly a 3D network is seen from above, in [-1, 1] (the depth sign's main rule).

    An upright object seen from above with a tilt b in (0, 45) deg: every
    horizontal direction of the object has ``dz = -cot(b) dy`` in view
    coordinates (higher in the picture is farther), every vertical one
    ``dz = tan(b) dy`` (its top is nearer). Writing a control-polygon edge's
    (y, z) part as ``r (cos phi, sin phi)``, both give ``sin(4 phi) > 0``
    (phi = -(90 - b) and phi = b), and the mirror image z -> -z gives
    ``sin(4 phi) < 0`` for both. The score is
    ``sum r^2 sin(4 phi) / sum r^2`` over the edges of every segment's
    control polygon: positive when the network is seen from above, and the
    mirror image's score is its negative. It presumes the object stands
    upright in the picture (its vertical drawn vertical) and is made mostly
    of horizontal and vertical directions (buildings, furniture, vessels);
    edges in between vote with less weight or the other way.

    Parameters
    ----------
    controls : (s, 4, 3) ndarray
        The cubic Bezier segments' control points (x, y as drawn, z the
        depth toward the viewer).

    Returns
    -------
    float
        The score; 0 for a flat network.

    Examples
    --------
    A floor receding from the viewer (higher in the picture is farther), and its mirror image:

    >>> import numpy as np
    >>> from auszug.lifting.reconstruct import from_above
    >>> floor = np.array([[[0, 0, 0], [0, 1, -2], [1, 2, -4], [1, 3, -6]]], float)
    >>> round(from_above(floor), 6), round(from_above(floor * [1, 1, -1]), 6)
    (0.96, -0.96)
    """
    num, total = _edge_votes(np.asarray(controls, dtype=float))
    return num / total if total > 0.0 else 0.0


def _edge_votes(c: Array) -> tuple[float, float]:
    """:func:`from_above`'s sums over the control-polygon edges of ``c`` (s, 4, 3).

    The vote ``sum r^2 sin(4 phi)`` and the weight ``sum r^2`` (``r``, ``phi`` the polar form of an
    edge's (y, z)); both 0 for a flat network.
    """
    d = (c[:, 1:] - c[:, :-1]).reshape(-1, 3)
    r2 = d[:, 1] ** 2 + d[:, 2] ** 2
    total = float(r2.sum())
    if total <= 0.0:
        return 0.0, 0.0
    return float(np.dot(r2, np.sin(4.0 * np.arctan2(d[:, 2], d[:, 1])))), total


def vertical_planes(controls: Array, seg_stroke: NDArray[np.intp], params: LiftParams = DEFAULT) -> tuple[float, float]:
    """The planar strokes' votes for a view from above, each stroke's plane read as a vertical plane.

    An upright object's vertical ``u = (0, cos b, sin b)`` in view
    coordinates (drawn vertical; ``b`` the tilt, positive seen from above) lies
    in every vertical plane, so a vertical plane of unit normal ``n`` gives
    ``u`` parallel to ``(0, n_z, -n_y)`` and ``sin 2b = -2 n_y n_z / (n_y^2 +
    n_z^2)``, which the mirror image z -> -z negates. A horizontal plane's
    normal is ``u`` itself, with ``n_x = 0``, and read as a vertical one it
    gives the mirror's tilt; so each plane votes ``n_x^2 sin 2b``: only as
    much as its normal leaves the y-z plane, i.e. as it cannot be horizontal.
    (Read this way, the planar strokes do not need the tilt below 45 deg that
    :func:`from_above` assumes.) A stroke's plane is the least-squares plane
    of its segments' control points (4 per segment), with singular values
    ``s1 >= s2 >= s3``; it votes when ``s3 <= params.sign_plane_flat s2``
    (planar) and ``s2 >= params.sign_plane_straight s1`` (not straight), with
    weight ``A = s1 s2``.

    Parameters
    ----------
    controls : (s, 4, 3) ndarray
        The cubic Bezier segments' control points (x, y as drawn, z toward the
        viewer).
    seg_stroke : (s,) int ndarray
        The stroke of each segment.
    params : LiftParams
        ``sign_plane_flat`` and ``sign_plane_straight``: the planarity and
        straightness bounds above.

    Returns
    -------
    tuple of float
        ``sum A n_x^2 sin 2b`` and ``sum A`` over the voting strokes.

    Examples
    --------
    A curve in a wall (a vertical plane turned 45 deg from the picture) seen
    from 30 deg above, and its mirror image: ``n_x^2 sin 2b = 0.5 sin 60 deg``.

    >>> import numpy as np
    >>> from auszug.lifting.reconstruct import vertical_planes
    >>> b = np.radians(30)
    >>> u, h = np.array([0, np.cos(b), np.sin(b)]), np.array([1, -np.sin(b), np.cos(b)]) / 2 ** 0.5
    >>> arc = np.array([[[0, 0, 0], u, u + h, 2 * h]])   # one segment, in the plane of u and h
    >>> v, a = vertical_planes(arc, np.array([0]))
    >>> round(v / a, 4), round(vertical_planes(arc * [1, 1, -1], np.array([0]))[0] / a, 4)
    (0.433, -0.433)
    """
    c = np.asarray(controls, dtype=float)
    ids = np.asarray(seg_stroke)
    flat, straight = params.sign_plane_flat, params.sign_plane_straight
    vote = area = 0.0
    for k in np.unique(ids):
        q = c[ids == k].reshape(-1, 3)
        if len(q) < 3:
            continue
        _, sv, vt = np.linalg.svd(q - q.mean(axis=0), full_matrices=False)
        if sv[0] <= 0.0 or sv[1] < straight * sv[0] or sv[2] > flat * sv[1]:
            continue
        n = vt[2]
        a = float(sv[0] * sv[1])
        yz = float(n[1] ** 2 + n[2] ** 2)
        if yz > 0.0:
            vote += a * float(n[0] ** 2) * (-2.0 * float(n[1] * n[2]) / yz)
        area += a
    return vote, area


def depth_sign_score(controls: Array, seg_stroke: NDArray[np.intp], params: LiftParams = DEFAULT) -> float:
    """The depth sign's score in [-1, 1]: positive when the network is seen from above.

    The weighted mean of :func:`from_above`'s votes (every control-polygon
    edge, weight ``r^2``) and :func:`vertical_planes`' (every planar stroke,
    weight ``params.sign_plane_weight A``)::

        (sum r^2 sin 4 phi + w sum A n_x^2 sin 2b) / (sum r^2 + w sum A)

    The mirror image's score is its negative. With ``sign_plane_weight = 0``
    it is :func:`from_above`. Why the planes (lift-sign2, docs/lifting.md,
    Depth sign): :func:`from_above` reads an edge near the y axis as a
    vertical and one near z as a horizontal, so it takes a lift whose depth
    scale makes the object look tilted by more than 45 deg for its mirror
    (the revolve lifted too deep at tilts 25-35 deg, the wrinkle's rulings
    flattened); a vertical plane gives the tilt at any angle.

    Parameters
    ----------
    controls : (s, 4, 3) ndarray
        The cubic Bezier segments' control points.
    seg_stroke : (s,) int ndarray
        The stroke of each segment.
    params : LiftParams
        ``sign_plane_weight``, ``sign_plane_flat``, ``sign_plane_straight``.

    Returns
    -------
    float
        The score; 0 for a flat network.

    Examples
    --------
    The curve in a wall of :func:`vertical_planes`, seen from 70 deg above:
    its edges alone read as the mirror, the plane outweighs them.

    >>> import numpy as np
    >>> from auszug.lifting.reconstruct import depth_sign_score, from_above
    >>> b = np.radians(70)
    >>> u, h = np.array([0, np.cos(b), np.sin(b)]), np.array([1, -np.sin(b), np.cos(b)]) / 2 ** 0.5
    >>> arc = np.array([[[0, 0, 0], u, u + h, 2 * h]])
    >>> round(from_above(arc), 3), round(depth_sign_score(arc, np.array([0])), 3)
    (-0.164, 0.228)
    """
    c = np.asarray(controls, dtype=float)
    num, edges = _edge_votes(c)
    w = params.sign_plane_weight
    vote = area = 0.0
    if w > 0.0:
        vote, area = vertical_planes(c, seg_stroke, params)
    total = edges + w * area
    if total <= 0.0:
        return 0.0
    return (num + w * vote) / total


def _flip_to_view_from_above(g: SketchGraph, X: Array, smooth: cu.Orthogonal, params: LiftParams) -> bool:
    """Whether to mirror ``X`` (z -> -z): the paper's "view from above" preference, then convexity.

    :func:`depth_sign_score` decides when its score is above
    ``params.above_min`` in magnitude (by default: unless it is exactly 0);
    otherwise the convexity votes of :func:`_concave` do.
    """
    score = depth_sign_score(X[g.segments], g.seg_stroke, params)
    if abs(score) > params.above_min:
        return score < 0
    return _concave(g, X, smooth)


def _concave(g: SketchGraph, X: Array, smooth: cu.Orthogonal) -> bool:
    """The convexity rule (the fallback of the depth sign): True when the solution is concave seen from +z.

    At every smooth crossing the surface normal n = t_a x t_b is oriented
    toward the viewer (n_z > 0); the normal curvatures of both curves
    (second derivative of their outgoing Bezier at the crossing, along n) vote
    convex when their sum is negative (the curves bend away from the viewer).
    Ties: the normals' mean y (a surface seen from above faces up) decides.
    """
    seg = g.segments
    at: dict[int, list[int]] = {}
    for s in range(len(seg)):
        at.setdefault(int(seg[s, 0]), []).append(s)
        at.setdefault(int(seg[s, 3]), []).append(s)
    votes = 0
    up = 0.0
    for p, ha, hb in zip(smooth.p, smooth.h1, smooth.h2, strict=True):
        ta, tb = X[ha] - X[p], X[hb] - X[p]
        n = np.cross(ta, tb)
        if n[2] < 0:
            n = -n
        nn = np.linalg.norm(n)
        if nn == 0:
            continue
        n /= nn
        kn = 0.0
        for h in (ha, hb):
            for s in at.get(int(p), []):
                c = X[seg[s]]
                if int(seg[s, 0]) == int(p) and int(seg[s, 1]) == int(h):
                    d1, d2 = 3 * (c[1] - c[0]), 6 * (c[0] - 2 * c[1] + c[2])
                elif int(seg[s, 3]) == int(p) and int(seg[s, 2]) == int(h):
                    d1, d2 = 3 * (c[3] - c[2]), 6 * (c[1] - 2 * c[2] + c[3])
                else:
                    continue
                kn += float(np.dot(d2, n)) / max(float(np.dot(d1, d1)), 1e-300)
        votes += 1 if kn < -CURVED else (-1 if kn > CURVED else 0)   # straight strokes do not vote
        up += n[1]
    return votes < 0 or (votes == 0 and up < 0)


def lift(sketch: Sketch, params: LiftParams = DEFAULT, progress: Progress | None = None,
         classes: tuple[str, ...] = DEFAULT_CLASSES) -> LiftResult:
    """Lift a sketch to a 3D curve network (True2Form, Xu et al. 2014).

    Layers are independent parts, each lifted alone; the layers' depths are
    then stacked back to front (each layer's depth shifted so that it lies
    in front of the layers behind it wherever they overlap in the sketch).
    A sketch with a global symmetry curve (``sketch.symmetry``: half the
    object is drawn) has that curve's layer lifted with the curve's cues
    applied and then mirrored across its plane (:func:`lift_graph`,
    :func:`mirror_plane`; the plane is in ``LiftResult.mirror``).

    Parameters
    ----------
    sketch : Sketch
    params : LiftParams
    progress : callable, optional
        Called with one line per solve (stage, energy, Newton steps).
    classes : tuple of str
        The cue classes to resolve, a subset of :data:`CLASSES` in that order.

    Raises
    ------
    GeometryError
        For an invalid sketch (see :func:`~auszug.lifting.sketch.sketch_graph`),
        a layer whose strokes fall into parts not joined by any intersection
        (draw them in separate layers), or a marker that snaps to no crossing.

    Examples
    --------
    >>> import numpy as np
    >>> from auszug.lifting import Sketch, Stroke, lift
    >>> h = Stroke(np.array([[[-1, 0], [-0.4, 0.25], [0.4, 0.25], [1, 0]]], float), "h")
    >>> v = Stroke(np.array([[[0.3, -1], [0.1, -0.3], [-0.1, 0.3], [-0.3, 1]]], float), "v")
    >>> r = lift(Sketch((h, v)))
    >>> r.converged, [c.kind for c in r.cues][:1], round(r.cues[0].angle, 6)
    (True, ['smooth-orthogonal'], 0.0)
    """
    layers = layer_graphs(sketch, params)
    results: list[CueResult] = []
    stages: list[Stage] = []
    pts: list[Array] = []
    graphs: list[SketchGraph] = []
    flips: list[bool] = []
    ok = True
    sym_at: tuple[int, int, Array, NDArray[np.intp]] | None = None   # layer, its index, normal, curve points
    for layer, g in layers:
        s_sym = symmetry_stroke(sketch, g, params)
        X, cues_, st, conv, flip = lift_graph(g, params, layer, progress, classes, s_sym)
        results += cues_
        stages += st
        ok &= conv
        if s_sym is not None:
            nrm, off = mirror_plane(g, X, s_sym)
            g, X = _mirrored(g, X, s_sym, nrm, off)
            sym_at = (layer, len(pts), nrm, np.unique(g.segments[g.chains[s_sym]]))
        Xs = X.copy()
        Xs[:, :2] = X[:, :2] * g.scale + g.offset
        Xs[:, 2] = X[:, 2] * g.scale
        pts.append(Xs)
        graphs.append(g)
        flips.append(flip)
    _stack(graphs, pts)
    mirror: tuple[int, Array, float] | None = None
    if sym_at is not None:   # the plane in sketch units, after the layers' depth shifts
        lay, k, nrm, on = sym_at
        mirror = (lay, nrm, float(np.mean(pts[k][on] @ nrm)))
    net = _network(sketch, graphs, pts, results, bool(ok), params)
    if mirror is not None:
        net = replace(net, meta={**net.meta, "lifting": {**net.meta["lifting"], "symmetry_plane": {
            "layer": mirror[0], "normal": mirror[1].tolist(), "offset": mirror[2]}}})
    return LiftResult(net, tuple(results), tuple(stages), bool(ok), tuple(flips), tuple(pts), tuple(graphs), mirror)


def symmetry_stroke(sketch: Sketch, g: SketchGraph, params: LiftParams = DEFAULT) -> int | None:
    """Index in ``g.strokes`` of the sketch's global symmetry curve, or None if ``g`` has none.

    The curve is a stroke of its layer's graph: :func:`layer_graphs` adds it
    there unless a drawn stroke already is that curve (the same control
    points, either direction, within ``100 * params.merge`` of the diagonal,
    the duplicate test), which then serves as it.
    """
    sym = sketch.symmetry
    if sym is None:
        return None
    for i, t in enumerate(g.strokes):
        if t is sym:
            return i
    for i, t in enumerate(g.strokes):
        if t.layer == sym.layer and _same_curve(t.controls, sym.controls, params, g.scale):
            return i
    return None


def _same_curve(a: Array, b: Array, params: LiftParams, diagonal: float) -> bool:
    """Whether two strokes are one curve.

    The same control points, either direction, within ``100 * params.merge`` of the diagonal (the
    grid of the duplicate-stroke test).
    """
    tol = 100.0 * params.merge * diagonal
    a, b = np.asarray(a, float), np.asarray(b, float)
    if a.shape != b.shape:
        return False
    return bool(np.abs(a - b).max() <= tol or np.abs(a - b[::-1, ::-1]).max() <= tol)


def mirror_plane(g: SketchGraph, X: Array, s: int) -> tuple[Array, float]:
    """The symmetry plane of a lifted layer: unit normal (3,) and offset, ``n . p = offset`` (graph units).

    The plane holds the symmetry curve (stroke ``s``) and is normal to the
    curves that meet it: ``n`` is the eigenvector of the smallest eigenvalue
    of ``A - B``, where ``A`` is the curve's control points' scatter divided
    by its trace (0 along its plane's normal) and ``B`` the mean outer product
    of the unit tangents of the other curves where they meet it (1 along
    their common direction). A curve straight in 3D leaves ``A`` two zero
    directions and ``B`` picks the plane; a planar one with hard orthogonality
    and local symmetry agrees with ``B`` exactly. The sign of ``n`` is made
    to point toward the drawn half.

    Examples
    --------
    >>> import numpy as np
    >>> from auszug.lifting import Sketch, Stroke, layer_graphs
    >>> from auszug.lifting.reconstruct import mirror_plane
    >>> axis = Stroke(np.array([[[0, -1], [0, -0.3], [0, 0.3], [0, 1]]], float), "axis")
    >>> rib = Stroke(np.array([[[0, 0], [0.3, 0], [0.6, 0.05], [1, 0.1]]], float), "rib")
    >>> (_, g), = layer_graphs(Sketch((axis, rib)))
    >>> X = np.c_[g.points, np.zeros(len(g.points))]
    >>> n, d = mirror_plane(g, X, 0)
    >>> np.round(n, 6).tolist(), round(d, 6)    # graph units: x = (0 - 0.5) / sqrt(5)
    ([1.0, 0.0, 0.0], -0.223607)
    """
    ends = np.unique(g.segments[g.chains[s]][:, [0, 3]])
    P = X[np.unique(g.segments[g.chains[s]])]
    Y = P - P.mean(0)
    A = Y.T @ Y
    A /= max(float(np.trace(A)), 1e-300)
    hs = _handle_strokes(g)
    t: list[Array] = []
    for c in g.crossings:
        if c.point not in ends:
            continue
        for seg, end in c.ends:
            if int(g.seg_stroke[seg]) == s:
                continue
            h = int(g.segments[seg, 1] if end == 0 else g.segments[seg, 2])
            if hs[h] != s:
                v = X[h] - X[c.point]
                if np.linalg.norm(v) > 0:
                    t.append(v / np.linalg.norm(v))
    T = np.array(t).reshape(-1, 3)
    B = T.T @ T / max(len(T), 1)
    w, V = np.linalg.eigh(A - B)
    n = V[:, 0]
    others = np.setdiff1d(np.arange(len(X)), np.unique(g.segments[g.chains[s]]))
    if len(others) and float(np.mean((X[others] - P.mean(0)) @ n)) < 0:
        n = -n
    return n, float(n @ P.mean(0))


def _mirrored(g: SketchGraph, X: Array, s: int, n: Array, d: float) -> tuple[SketchGraph, Array]:
    """The layer's graph and points with every stroke but the symmetry curve mirrored across ``n . p = d``.

    Points of the symmetry curve stay shared (a mirrored curve that ends on it
    starts where the drawn one does); the others are reflected. The mirrored
    strokes follow the drawn ones, ids with ``" (mirror)"``.
    """
    on_s = np.unique(g.segments[g.chains[s]])
    others = [k for k in range(len(g.chains)) if k != s]
    used = np.unique(np.concatenate([g.segments[g.chains[k]].reshape(-1) for k in others])) if others \
        else np.zeros(0, np.intp)
    new = np.setdiff1d(used, on_s)
    remap = np.arange(len(X))
    remap[new] = len(X) + np.arange(len(new))
    R = X[new] - 2.0 * ((X[new] @ n) - d)[:, None] * n
    X2 = np.concatenate([X, R])
    segs, seg_stroke, chains, closed, strokes = [g.segments], [g.seg_stroke], list(g.chains), list(g.closed), \
        list(g.strokes)
    joints, g1 = [g.joints], [g.joint_g1]
    S = len(g.segments)
    for k in others:
        ch = g.chains[k]
        base = S + sum(len(g.chains[j]) for j in others[: others.index(k)])
        segs.append(remap[g.segments[ch]])
        seg_stroke.append(np.full(len(ch), len(strokes), dtype=np.intp))
        newid = {int(a): base + i for i, a in enumerate(ch)}
        chains.append(np.array([newid[int(a)] for a in ch], dtype=np.intp))
        closed.append(bool(g.closed[k]))
        sel = np.isin(g.joints[:, 0], ch) if len(g.joints) else np.zeros(0, bool)
        joints.append(np.vectorize(newid.get, otypes=[np.intp])(g.joints[sel]).reshape(-1, 2))
        g1.append(g.joint_g1[sel])
        st = g.strokes[k]
        xy = X2[remap[g.segments[ch]]][..., :2] * g.scale + g.offset
        strokes.append(Stroke(xy, f"{st.id or f'stroke #{k}'} (mirror)", st.layer))
    g2 = replace(g, points=X2[:, :2].copy(), segments=np.concatenate(segs), seg_stroke=np.concatenate(seg_stroke),
                 chains=tuple(chains), closed=np.array(closed, dtype=bool), joints=np.concatenate(joints),
                 joint_g1=np.concatenate(g1), strokes=tuple(strokes))
    return g2, X2


#: The memo of :func:`layer_graphs`: per sketch object (held weakly), its fingerprint, the parameters
#: and the graphs built from them.
_GRAPHS: weakref.WeakKeyDictionary[Sketch, tuple[str, LiftParams, tuple[tuple[int, SketchGraph], ...]]] = \
    weakref.WeakKeyDictionary()


def _read_only(g: SketchGraph) -> SketchGraph:
    """``g`` with its arrays made read-only (a memoised graph is shared by its callers)."""
    for a in (g.points, g.segments, g.seg_stroke, g.closed, g.joints, g.joint_g1, g.occluded, g.offset, *g.chains):
        if isinstance(a, np.ndarray):
            a.flags.writeable = False
    return g


def layer_graphs(sketch: Sketch, params: LiftParams = DEFAULT) -> tuple[tuple[int, SketchGraph], ...]:
    """The curve graph of every layer of ``sketch`` that has strokes, with its layer index, back to front.

    This is the whole validation :func:`lift` does before it solves, so a
    reader can refuse a sketch that cannot be lifted without solving it.
    The result is memoised per sketch object while its content
    (:meth:`~auszug.lifting.sketch.Sketch.fingerprint`) and ``params`` stay
    the same: a second call (a reader's validation, then :func:`lift`)
    returns the same graphs, whose arrays are read-only.

    Raises
    ------
    GeometryError
        For no strokes, non-finite, zero-length or duplicate strokes (naming
        the stroke), a layer without intersections, a layer whose strokes fall
        into parts not joined by any intersection (naming them), or a marker
        that snaps to no crossing of any layer (naming it).

    Examples
    --------
    >>> import numpy as np
    >>> from auszug.lifting import Sketch, Stroke, layer_graphs
    >>> h = Stroke(np.array([[[-1, 0], [-0.4, 0.25], [0.4, 0.25], [1, 0]]], float), "h")
    >>> v = Stroke(np.array([[[0.3, -1], [0.1, -0.3], [-0.1, 0.3], [-0.3, 1]]], float), "v")
    >>> [(layer, len(g.crossings)) for layer, g in layer_graphs(Sketch((h, v)))]
    [(0, 1)]
    """
    if not sketch.strokes:
        raise GeometryError("the sketch has no strokes")
    fp = sketch.fingerprint()
    hit = _GRAPHS.get(sketch)
    if hit is not None and hit[0] == fp and hit[1] == params:
        return hit[2]
    nlayers = max(s.layer for s in sketch.strokes) + 1
    used_markers: set[int] = set()
    out: list[tuple[int, SketchGraph]] = []
    for layer in range(nlayers):
        strokes = tuple(s for s in sketch.strokes if s.layer == layer)
        if not strokes:
            continue
        sym = sketch.symmetry
        if sym is not None and sym.layer == layer:
            scale = Sketch(strokes).diagonal()
            if not any(_same_curve(t.controls, sym.controls, params, scale) for t in strokes):
                strokes = (*strokes, sym)
        sub = Sketch(strokes, sketch.markers, None, sketch.name)
        g, snapped = _graph_with_markers(sub, params)
        if sym is not None and sym.layer == layer:
            k = symmetry_stroke(sketch, g, params)
            assert k is not None
            if not any(k in c.strokes for c in g.crossings):
                raise GeometryError(f"symmetry path {sym.id or '(no id)'}: meets no stroke of layer {layer}; the "
                                    "drawn half's curves must meet the symmetry curve")
        used_markers |= snapped
        comp = _components(g)
        if len(np.unique(comp)) > 1:
            main = np.bincount(comp).argmax()
            lone = [strokes[i].id or f"stroke #{i}" for i in np.nonzero(comp != main)[0]]
            raise GeometryError(f"{', '.join(lone[:3])}{' ...' if len(lone) > 3 else ''}: not joined to the rest "
                                f"of layer {layer} by any intersection; put independent parts in their own layers"
                                + _gap_hint(g, comp, int(main), params))
        out.append((layer, g))
    if sketch.symmetry is not None and sketch.symmetry.layer not in {lay for lay, _ in out}:
        raise GeometryError(f"symmetry path {sketch.symmetry.id or '(no id)'}: its layer "
                            f"{sketch.symmetry.layer} has no strokes")
    missing = [m for i, m in enumerate(sketch.markers) if i not in used_markers]
    if missing:
        m = missing[0]
        raise GeometryError(f"{m.kind} marker {m.id or '(no id)'} at {np.asarray(m.point).tolist()}: no "
                            f"crossing within {params.snap:.0%} of the sketch's diagonal in any layer")
    res = tuple((lay, _read_only(g)) for lay, g in out)
    _GRAPHS[sketch] = (fp, params, res)
    return res


def _gap_hint(g: SketchGraph, comp: NDArray[np.intp], main: int, params: LiftParams) -> str:
    """For the error of a layer in parts: how far the nearest end misses the main part, if within reach."""
    rest = set(np.nonzero(comp != main)[0].tolist())
    part = set(np.nonzero(comp == main)[0].tolist())
    d, si, sj = min(nearest_end_gap(g, rest, part), nearest_end_gap(g, part, rest))
    if not params.close_gaps < d <= CLOSE_GAPS_MAX:
        return ""
    name, other = g.stroke_name(si), g.stroke_name(sj)
    want = close_gaps_for(d)
    return (f"; or, if they were meant to meet, an end of {name} misses {other} by {d:.2%} of the diagonal: "
            f"close_gaps={want:g} joins it (auszug lift --set close_gaps={want:g}; LiftParams.close_gaps)")


def junction_hints(g: SketchGraph, params: LiftParams = DEFAULT) -> list[tuple[float, tuple[int, ...], float]]:
    """The groups of crossings of three or more strokes drawn near one point that ``params`` leaves apart.

    For messages: :func:`auszug.lifting.sketch.near_junctions` within ``params.snap`` (1 % of the diagonal),
    those that a ``close_gaps`` up to its limit, and above ``params.close_gaps``, would join.

    Returns
    -------
    list of (spread, strokes, close_gaps)
        The group's spread (share of the diagonal), its strokes (indices into ``g.strokes``) and the
        ``close_gaps`` that joins it (:func:`~auszug.lifting.params.close_gaps_for`), by spread.
    """
    return [(spread, strokes, close_gaps_for(spread)) for spread, strokes in near_junctions(g, params.snap)
            if spread <= CLOSE_GAPS_MAX and close_gaps_for(spread) > params.close_gaps]


def _junction_hint(g: SketchGraph, params: LiftParams) -> str:
    """For a lift that went astray: the groups of crossings of three or more strokes drawn near one point."""
    found = junction_hints(g, params)
    if not found:
        return ""
    spread, strokes, want = found[-1]
    names = ", ".join(g.stroke_name(s) for s in strokes)
    how = f"(auszug lift --set close_gaps={want:g}; LiftParams.close_gaps)"
    if len(found) == 1:
        return (f"; {names} cross within {100 * spread:.2g}% of the diagonal of one another, not at one point: if "
                f"they meet at one point, close_gaps={want:g} makes it one intersection {how}")
    return (f"; {len(found)} groups of strokes cross near one point each, not at it (the widest: {names}, within "
            f"{100 * spread:.2g}% of the diagonal): if each meets at one point, close_gaps={want:g} makes "
            f"each one intersection {how}")


def _graph_with_markers(sub: Sketch, params: LiftParams) -> tuple[SketchGraph, set[int]]:
    """The layer's graph with the markers that snap to one of its crossings (the others belong elsewhere)."""
    g = sketch_graph(sub, params, require_markers=False)
    return g, set(g.marked)


def _stack(graphs: list[SketchGraph], pts: list[Array]) -> None:
    """Shift each layer's depth so it lies in front of (z above) the layers behind it where they overlap.

    Overlap is judged on a grid of cells of 2 % of the sketch's diagonal over
    the control polygons' points; a layer that overlaps none keeps its depth.
    """
    if len(pts) < 2:
        return
    allxy = np.concatenate([p[:, :2] for p in pts])
    diag = float(np.linalg.norm(np.ptp(allxy, axis=0)))
    cell = 0.02 * max(diag, 1e-300)
    lo = allxy.min(0)
    front: dict[tuple[int, int], float] = {}
    for k, X in enumerate(pts):
        keys = [tuple(c) for c in np.floor((X[:, :2] - lo) / cell).astype(int).tolist()]
        if k:
            need = [front[c] - z for c, z in zip(keys, X[:, 2], strict=True) if c in front]
            if need:
                shift = max(0.0, max(need) + 0.01 * diag)
                X[:, 2] += shift
        for c, z in zip(keys, X[:, 2], strict=True):
            front[c] = max(front.get(c, -np.inf), float(z))


def _network(sketch: Sketch, graphs: list[SketchGraph], pts: list[Array], results: list[CueResult],
             converged: bool = True, params: LiftParams = DEFAULT) -> CurveNetwork:
    """One exact 3D Bezier piece per segment; one basic curve per stroke.

    Raises GeometryError, naming the stroke, where the lift shrank a segment to
    a point in the sketch's plane (seen along z it would no longer be a curve),
    and, naming the layer, where it shrank a layer to less than
    ``COLLAPSED`` of its drawn extent there: a solve that went astray, not a
    lift of the drawing (the fidelity term keeps x, y near the drawing).
    """
    pieces: list[Piece] = []
    groups: list[SymmetryGroup] = []
    layers: list[int] = []
    size = 1e-9
    rule = SideCoordinate("u")
    why = "not every solve converged" if not converged else "every solve converged"
    for g, X in zip(graphs, pts, strict=True):
        drawn = float(np.linalg.norm(np.ptp(g.points, axis=0))) * g.scale
        ratio = float(np.linalg.norm(np.ptp(X[:, :2], axis=0))) / drawn
        if ratio < COLLAPSED:
            raise GeometryError(f"layer {g.strokes[0].layer}: the lift collapsed: its curves span {ratio:.2g} of the "
                                f"drawing's extent in the sketch's plane ({why}): the solve went astray, the result "
                                f"is no lift of the drawing" + _junction_hint(g, params))
        for chain in g.chains:
            basic = len(groups)
            stroke = g.strokes[int(g.seg_stroke[chain[0]])]
            for k, s in enumerate(chain):
                c = X[g.segments[s]]
                spread = float(np.ptp(c[:, :2], axis=0).max())
                if not spread > TOL.zero:     # what the Bezier below would refuse, without the stroke's name
                    raise GeometryError(
                        f"stroke {stroke.id or '(no id)'}: the lift shrank its segment {k + 1} of {len(chain)} "
                        f"(split at the crossings) to a point in the sketch's plane ({why}): the solve went "
                        f"astray, the result is no lift of the drawing")
                top = CubicBezier.from_array(c[:, :2])
                pieces.append(Piece(basic, k, "sketch", top, None, rule, c[[0, 3]].copy(), depth=c[:, 2].copy()))
                size = max(size, float(np.abs(c[:, :2]).max()))
            groups.append(SymmetryGroup(1))
            layers.append(int(stroke.layer))
    nlay = max(layers) + 1 if layers else 1
    ids = [g.strokes[int(g.seg_stroke[ch[0]])].id for g in graphs for ch in g.chains]
    applied = {k: sum(1 for c in results if c.kind == k and c.applied) for k in ("smooth-orthogonal", *CLASSES)}
    meta = {"lifting": {"method": "True2Form (Xu et al. 2014)", "strokes": ids, "applied_cues": applied}}
    net = CurveNetwork(tuple(pieces), tuple(groups), tuple(layers), tuple(0.0 for _ in range(nlay)), size,
                       sketch.name, meta)
    return net.resampled(samples=33)
