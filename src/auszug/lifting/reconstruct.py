"""True2Form's reconstruction: baseline, progressive selective regularisation, depth sign, network.

:func:`lift` takes a :class:`~auszug.lifting.sketch.Sketch` and returns a
:class:`LiftResult` with the 3D curve network (one exact 3D cubic Bezier
piece per segment, x and y in the sketch's units, y up, z the depth toward
the viewer), the cues found and every stage's energy and timing.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace
from typing import Callable

import numpy as np
from numpy.typing import NDArray

from auszug.errors import GeometryError
from auszug.geometry import CubicBezier, SymmetryGroup
from auszug.geometry.heights import SideCoordinate
from auszug.geometry.network import CurveNetwork, Piece
from auszug.lifting import cues as cu
from auszug.lifting.params import DEFAULT, LiftParams
from auszug.lifting.sketch import Sketch, SketchGraph, sketch_graph
from auszug.lifting.solver import Poly2, SolveResult, solve
from auszug.lifting.terms import fidelity, structure

__all__ = ["CueResult", "Stage", "LiftResult", "lift", "lift_graph", "layer_graphs", "from_above", "CLASSES",
           "DEFAULT_CLASSES"]

Array = NDArray[np.float64]

#: The cue classes in the order they are resolved (paper sec. 4 and 5.3).
CLASSES = ("parallel", "orthogonal", "symmetry", "planar", "plane")
#: The classes :func:`lift` resolves by default: local symmetry is implemented but off, since its hard
#: constraints currently stop Newton from converging on the revolve ground truth (docs/lifting.md);
#: plane parallelism / orthogonality ("plane") is off since its round made the arches example worse
#: (9.16 -> 11.07 % depth RMSE, docs/lifting.md).
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
        :func:`from_above`; convexity where that is 0) or a flip marker chose
        the mirror image z -> -z of the solver's solution.
    points : tuple of (n, 3) ndarray
        Per layer: the lifted control points (sketch units).
    graphs : tuple of SketchGraph
    """

    network: CurveNetwork
    cues: tuple[CueResult, ...]
    stages: tuple[Stage, ...]
    converged: bool
    flipped: tuple[bool, ...]
    points: tuple[Array, ...]
    graphs: tuple[SketchGraph, ...]


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

    def X(self, v: Array | None = None) -> Array:
        return (self.v if v is None else v)[: 3 * self.N].reshape(self.N, 3)

    def _normal_anchor(self, P: Poly2) -> None:
        # normals that no cue uses stay where they are (a tiny pull keeps Newton's matrix regular)
        cols = np.arange(3 * self.N, self.n)
        P.add(-self.v[cols], 1e-8, lin=(np.arange(len(cols)), cols, np.ones(len(cols))))

    def run(self, name: str, energy: Poly2, cons: Poly2, applied: int = 0, rejected: int = 0,
            candidate: bool = False) -> SolveResult:
        t0 = time.perf_counter()
        self._normal_anchor(energy)
        lam0 = self.lam if self.lam is not None and len(self.lam) == cons.rows else None
        r = solve(energy, cons, self.v, lam0, iterations=self.params.newton_iterations,
                  tol=self.params.newton_tol, kkt_reg=self.params.kkt_reg, hessian_reg=self.params.hessian_reg)
        self.v, self.lam = r.v, r.lam
        st = Stage(name, time.perf_counter() - t0, r.energy, r.violation, r.iterations, r.converged,
                   applied, rejected, self.layer, candidate and not r.converged)
        self.stages.append(st)
        if self.progress is not None:
            self.progress(f"layer {self.layer} {name}: energy {r.energy:.3g}, {r.iterations} Newton steps"
                          + (f", {applied} applied, {rejected} rejected" if applied or rejected else "")
                          + ("" if r.converged else " (no convergence from this seed: discarded)" if candidate
                             else " (NOT converged)"))
        return r

    def energy(self, w_a: float) -> Poly2:
        base = self.fid[w_a]
        P = Poly2(self.n)
        P.const, P.weight, P.lin, P.bil, P.rows = list(base.const), list(base.weight), list(base.lin), \
            list(base.bil), base.rows
        return P

    def constraints(self) -> Poly2:
        C = Poly2(self.n)
        b = self.base
        C.const, C.weight, C.lin, C.bil, C.rows = list(b.const), list(b.weight), list(b.lin), list(b.bil), b.rows
        return C


def lift_graph(g: SketchGraph, params: LiftParams = DEFAULT, layer: int = 0,
               progress: Progress | None = None,
               classes: tuple[str, ...] = CLASSES) -> tuple[Array, list[CueResult], list[Stage], bool, bool]:
    """Lift one layer's graph; return control points (normalised), cues, stages, converged, flipped.

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
       :data:`SAME_MINIMUM`) the others are skipped;
    3. one progressive resolution per cue class of :data:`CLASSES`, with
       w_a = 1: each round minimises fidelity + w_c sum L(alpha) C^2 over the
       undecided cues, subject to the applied ones; L = 1 applies a cue
       (parallelism stays soft with weight w_c), L = 0 or no increase rejects
       it; after ``params.rounds`` rounds the rest is rejected. The class
       ``"plane"`` (plane parallelism and orthogonality) comes after planarity:
       its candidates are the single-linkage clusters of the applied planar
       strokes' normals (:func:`~auszug.lifting.cues.plane_cues`);
    4. the depth sign: the solution or its mirror z -> -z, whichever is seen
       from above (:func:`from_above`; where that score is not above
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

    def baseline() -> SolveResult:
        E = pr.energy(params.w_a_baseline)
        par.add(E, all_par, params.w_p_baseline * wfac)
        C = pr.constraints()
        pr.smooth.add(C, np.arange(len(pr.smooth)), 1.0)
        pr.lam = None
        return pr.run("baseline", E, C, candidate=True)

    first_v: Array | None = None   # the first seed's propagation, when its baseline was skipped
    for i, k in enumerate(pr.seeds):
        pr.v = _initial(g, pr.n, pr.smooth, int(k))
        pr.lam = None
        pr.stages = list(start_stages)
        E = pr.energy(params.w_a_baseline)
        par.add(E, all_par, params.w_p_propagate * wfac)
        C = pr.constraints()
        pr.smooth.add(C, np.array([int(k)]), 1.0)
        r1 = pr.run(f"seed {int(k)}", E, C, candidate=True)
        if not r1.converged:
            # a seed whose propagation does not converge is discarded whatever its baseline does, so that
            # solve is skipped (it is run at the end only if no seed converges: the first seed's is kept)
            if i == 0:
                first_v = pr.v.copy()
            start_stages = list(pr.stages)
            continue
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
    hard: list[Callable[[Poly2], None]] = [lambda c: pr.smooth.add(c, np.arange(len(pr.smooth)), 1.0)]
    soft_kept: list[Callable[[Poly2], None]] = []
    results: list[CueResult] = []

    def resolve(name: str, fam, hard_add, soft_add) -> NDArray[np.bool_]:
        nonlocal ok
        m = len(fam)
        applied = np.zeros(m, dtype=bool)
        if not m or name not in classes:
            return applied
        undecided = np.ones(m, dtype=bool)
        Lp = cu.likelihood(fam.angles(pr.X()), params)
        for rnd in range(params.rounds):
            E = pr.energy(params.w_a)
            for f in soft_kept:
                f(E)
            idx = np.nonzero(undecided)[0]
            soft_add(E, idx, params.w_c * Lp[idx])
            C = pr.constraints()
            for f in hard:
                f(C)
            r = pr.run(f"{name} round {rnd + 1}", E, C)
            ok &= r.converged
            L = cu.likelihood(fam.angles(pr.X()), params)
            acc = undecided & (L >= 1.0)
            rej = undecided & ~acc & ((L <= 0.0) | (L <= Lp))
            applied |= acc
            undecided &= ~(acc | rej)
            Lp = L
            pr.stages[-1] = replace(pr.stages[-1], applied=int(acc.sum()), rejected=int(rej.sum()))
            if acc.any():
                sel = np.nonzero(applied)[0]
                hard_add(sel)
            if not undecided.any():
                break
        return applied

    # parallelism: applied cues stay soft with weight w_c (paper sec. 5.3)
    par_state = {"sel": np.zeros(0, np.intp)}

    def par_apply(sel: NDArray[np.intp]) -> None:
        par_state["sel"] = sel

    soft_kept.append(lambda E: par.add(E, par_state["sel"], params.w_c))
    par_applied = resolve("parallel", par, par_apply, lambda E, i, w: par.add(E, i, w))

    orth = cu.orthogonal_cues(g)
    orth_state = {"sel": np.zeros(0, np.intp)}
    hard.append(lambda c: orth.add(c, orth_state["sel"], 1.0))
    orth_applied = resolve("orthogonal", orth, lambda s: orth_state.update(sel=s),
                           lambda E, i, w: orth.add(E, i, w))

    pairs = [(int(p), int(a), int(b)) for p, a, b in zip(pr.smooth.p, pr.smooth.h1, pr.smooth.h2, strict=True)]
    pairs += [(int(orth.p[i]), int(orth.h1[i]), int(orth.h2[i])) for i in np.nonzero(orth_applied)[0]]
    sym = cu.symmetry_cues(g, pairs)
    sym_state = {"sel": np.zeros(0, np.intp)}
    hard.append(lambda c: sym.add(c, sym_state["sel"], 1.0))
    sym_applied = resolve("symmetry", sym, lambda s: sym_state.update(sel=s), lambda E, i, w: sym.add(E, i, w))

    pla = cu.planar_cues(g, pr.N)
    pla_state = {"sel": np.zeros(0, np.intp)}

    offset_slot = 3 * (pr.N + len(g.chains)) + pla.stroke   # one plane offset unknown per candidate

    def pla_apply(sel: NDArray[np.intp]) -> None:
        new = np.setdiff1d(sel, pla_state["sel"])
        if len(new):   # the normal and offset variables start at the best fit
            X = pr.X()
            nrm = pla.normals(X)
            for i in new:
                ns = int(pla.normal_slot[i])
                pr.v[3 * ns: 3 * ns + 3] = nrm[i]
                pr.v[offset_slot[i]] = float(nrm[i] @ X[pla.points[i]].mean(0))
        pla_state["sel"] = sel

    hard.append(lambda c: pla.add_hard(c, pla_state["sel"], offset_slot))
    def pla_soft(E: Poly2, idx: NDArray[np.intp], w: Array) -> None:
        X = pr.X()
        nrm = pla.normals(X)
        for i in idx:   # offsets start at their optimum, n . mean X
            pr.v[offset_slot[i]] = float(nrm[i] @ X[pla.points[i]].mean(0))
        pla.add_soft(E, idx, w, X, offset_slot)

    pla_applied = resolve("planar", pla, pla_apply, pla_soft)

    # plane parallelism / orthogonality: single-linkage clusters of the applied planar strokes' normals
    slots = 3 * pla.normal_slot[:, None] + np.arange(3)
    names = tuple(w.removesuffix(" planar") for w in pla.where)
    pp = cu.plane_cues(pla, pla_applied, pr.v[slots] if len(pla) else np.zeros((0, 3)), names,
                       params.plane_cluster_deg, pr.X(), float(np.tan(np.radians(params.inner_deg))))
    pp_state = {"sel": np.zeros(0, np.intp)}
    hard.append(lambda c: pp.add(c, pp_state["sel"], 1.0))
    pp_applied = resolve("plane", pp, lambda s: pp_state.update(sel=s), lambda E, i, w: pp.add(E, i, w))

    X = pr.X().copy()
    for kind, fam, app in (("parallel", par, par_applied), ("orthogonal", orth, orth_applied),
                           ("symmetry", sym, sym_applied), ("planar", pla, pla_applied), ("plane", pp, pp_applied)):
        ang = fam.angles(X) if len(fam) else np.zeros(0)
        results += [CueResult(kind, w, bool(a), float(x), layer) for w, a, x in zip(fam.where, app, ang, strict=True)]
    results = [CueResult("smooth-orthogonal", w, True, float(x), layer)
               for w, x in zip(pr.smooth.where, pr.smooth.angles(X), strict=True)] + results

    flip = _flip_to_view_from_above(g, X, pr.smooth, params)
    flip ^= sum(c.flipped for c in g.crossings) % 2 == 1
    if flip:
        X[:, 2] *= -1.0
        X[:, 2] -= X[pr.pin, 2]
    return X, results, pr.stages, bool(ok), bool(flip)


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
    c = np.asarray(controls, dtype=float)
    d = (c[:, 1:] - c[:, :-1]).reshape(-1, 3)
    r2 = d[:, 1] ** 2 + d[:, 2] ** 2
    total = float(r2.sum())
    if total <= 0.0:
        return 0.0
    phi = np.arctan2(d[:, 2], d[:, 1])
    return float(np.dot(r2, np.sin(4.0 * phi)) / total)


def _flip_to_view_from_above(g: SketchGraph, X: Array, smooth: cu.Orthogonal, params: LiftParams) -> bool:
    """Whether to mirror ``X`` (z -> -z): the paper's "view from above" preference, then convexity.

    :func:`from_above` decides when its score is above ``params.above_min`` in
    magnitude (by default: unless it is exactly 0); otherwise the convexity
    votes of :func:`_concave` do.
    """
    score = from_above(X[g.segments])
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
    for layer, g in layers:
        X, cues_, st, conv, flip = lift_graph(g, params, layer, progress, classes)
        results += cues_
        stages += st
        ok &= conv
        Xs = X.copy()
        Xs[:, :2] = X[:, :2] * g.scale + g.offset
        Xs[:, 2] = X[:, 2] * g.scale
        pts.append(Xs)
        graphs.append(g)
        flips.append(flip)
    _stack(graphs, pts)
    net = _network(sketch, graphs, pts, results)
    return LiftResult(net, tuple(results), tuple(stages), bool(ok), tuple(flips), tuple(pts), tuple(graphs))


def layer_graphs(sketch: Sketch, params: LiftParams = DEFAULT) -> tuple[tuple[int, SketchGraph], ...]:
    """The curve graph of every layer of ``sketch`` that has strokes, with its layer index, back to front.

    This is the whole validation :func:`lift` does before it solves, so a
    reader can refuse a sketch that cannot be lifted without solving it.

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
    nlayers = max(s.layer for s in sketch.strokes) + 1
    used_markers: set[int] = set()
    out: list[tuple[int, SketchGraph]] = []
    for layer in range(nlayers):
        strokes = tuple(s for s in sketch.strokes if s.layer == layer)
        if not strokes:
            continue
        sub = Sketch(strokes, sketch.markers, None, sketch.name)
        g, snapped = _graph_with_markers(sub, params)
        used_markers |= snapped
        comp = _components(g)
        if len(np.unique(comp)) > 1:
            main = np.bincount(comp).argmax()
            lone = [strokes[i].id or f"stroke #{i}" for i in np.nonzero(comp != main)[0]]
            raise GeometryError(f"{', '.join(lone[:3])}{' ...' if len(lone) > 3 else ''}: not joined to the rest "
                                f"of layer {layer} by any intersection; put independent parts in their own layers")
        out.append((layer, g))
    missing = [m for i, m in enumerate(sketch.markers) if i not in used_markers]
    if missing:
        m = missing[0]
        raise GeometryError(f"{m.kind} marker {m.id or '(no id)'} at {np.asarray(m.point).tolist()}: no "
                            f"crossing within {params.snap:.0%} of the sketch's diagonal in any layer")
    return tuple(out)


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


def _network(sketch: Sketch, graphs: list[SketchGraph], pts: list[Array], results: list[CueResult]) -> CurveNetwork:
    """One exact 3D Bezier piece per segment; one basic curve per stroke."""
    pieces: list[Piece] = []
    groups: list[SymmetryGroup] = []
    layers: list[int] = []
    size = 1e-9
    rule = SideCoordinate("u")
    for g, X in zip(graphs, pts, strict=True):
        for chain in g.chains:
            basic = len(groups)
            stroke = g.strokes[int(g.seg_stroke[chain[0]])]
            for k, s in enumerate(chain):
                c = X[g.segments[s]]
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
