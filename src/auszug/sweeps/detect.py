"""The whole analysis in one call: :func:`detect` runs every stage and returns a :class:`SweepReport`.

Stages (each also callable alone, see :mod:`auszug.sweeps`):

1. ``normalise``: centre, bounding-box diameter 1, edge topology;
2. ``cut``: the initial planes (geodesic sphere x offsets) and the movability of every cut;
3. ``kinematic``: the consensus motion of all cuts; if at least ``kinematic_min_agreement`` of
   them glide under it, the mesh is a surface of revolution, an extrusion or a helical surface and
   its patches come from :func:`~auszug.sweeps.patches.kinematic_patches`;
4. otherwise (or when no kinematic candidate fits within ``fit_factor * eps_prox`` and covers
   ``min_patch_area``: a translation along a curved path glides like a turn) ``match``
   (curvature plots of every movable run of the initial cuts, Eq. 6),
   ``families`` (sec. 2.2, most support first) with their ribs ordered, and ``motion`` (sec. 2.3:
   velocities by Eq. 7, Hermite interpolation, projection to rigid motions, profile improvement,
   fit check; each fitted sweep grown along its path and across its profile, and, when the cuts
   glided under one turn that fit nothing, also tried as pure translations). The paper's
   adaptive plane refinement (:func:`~auszug.sweeps.search_planes`) is not run: its good planes,
   ranked by gliding energy, miss the profile planes (docs/sweeps.md). When the sweeps found
   cover less than ``coarse_below`` of the mesh, match, families and motion run once more with
   the curvature averaged over ``coarse_window`` (noisy cuts), and the fit stage ranks the
   candidates of both passes together;
5. ``parts`` (beyond the paper; only where the patches so far that pass the fit leave at least
   ``min_patch_area`` of the mesh): :func:`~auszug.sweeps.parts.kinematic_parts`, the pieces that
   are each a surface of revolution or an extrusion, such as a moulding's straight and arched
   stretches along a window's border;
6. ``mirror`` (beyond the paper; with ``mirror`` on, where the candidates that fit still leave at
   least ``min_patch_area``): the mesh's mirror planes (:func:`~auszug.sweeps.mirror.mirror_planes`)
   and the mirror images of the candidates that fit, each fitted against the mesh
   (:func:`~auszug.sweeps.mirror.mirror_candidates`): a sweep found on one side of a symmetric
   piece is sought on the other;
7. ``arcs`` (beyond the paper; with ``arc_axes`` above 0, where the candidates that fit still leave
   at least ``min_patch_area``): rotations about the axes of the exact circular arcs among the mesh's
   creases beside the faces left (:func:`~auszug.sweeps.arcs.crease_circles`), searched as parts
   (:func:`~auszug.sweeps.arcs.arc_candidates`): sweeps along arcs too short for
   ``min_sweep_length``, such as a lancet's head; such a patch is kept when it sweeps at least
   ``arc_sweep_length`` and covers ``arc_min_area``; with ``arc_flat``, also the planar faces
   normal to such an axis swept about it by radial lines (:func:`~auszug.sweeps.arcs.flat_candidates`);
   with ``arc_rings``, also rotations about the axes of exact coaxial rings among the mesh's edge
   lines (:func:`~auszug.sweeps.arcs.ring_circles`: round mouldings, which have no crease);
8. ``fit``: patches whose fit error exceeds ``fit_factor * eps_prox`` or that cover less than
   ``min_patch_area`` of the mesh (the arcs' patches: ``arc_min_area``) are dropped, and of those
   left, most coverage first, each whose faces the ones before hold (``patch_overlap``); then
   the planar patches about the arcs' axes and the patches about the rings' axes, each while it
   adds ``arc_min_area`` of the area (:func:`~auszug.sweeps.patches.add_by_area`), then so the
   mirror images of those taken (in the stage ``mirror``'s planes); the rest are converted to the input's
   coordinates, each profile fitted with exact lines and arcs (``profile_fit_tolerance``,
   docs/sweeps.md section 6).

Each stage reports what it kept in a :class:`Stage` (for ``auszug sweeps --explain``).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np
from numpy.typing import NDArray

from auszug.errors import GeometryError
from auszug.limits import LIMITS
from auszug.sweeps.arcs import arc_bounds, arc_candidates, crease_circles, flat_candidates, ring_circles
from auszug.sweeps.cut import cut
from auszug.sweeps.kinematic import kinematic_axis
from auszug.sweeps.mesh import SweepMesh, normalise
from auszug.sweeps.mirror import mirror_candidates, mirror_planes
from auszug.sweeps.movability import movability
from auszug.sweeps.params import DEFAULT, SweepParams
from auszug.sweeps.patches import MeshTree, SweepPatch, add_by_area, area_coverage, face_areas, kinematic_patches
from auszug.sweeps.planes import initial_planes, spacing_for
from auszug.sweeps.stage import Stage

__all__ = ["Stage", "SweepReport", "detect", "sweep_length", "STAGES"]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: The stages in the order :func:`detect` runs them (the general ones only on non-kinematic meshes).
STAGES = ("normalise", "cut", "kinematic", "match", "families", "motion", "parts", "mirror", "arcs", "fit")

Progress = Callable[[str, int, int], None]


@dataclass(frozen=True)
class SweepReport:
    """The result of :func:`detect`: sweep patches in the input's coordinates, and the stages.

    Attributes
    ----------
    patches : tuple of SweepPatch
        Profiles and motions in input coordinates (``fit_error`` relative to the diameter).
    coverage : float
        Share of the mesh's area covered by the patches, 0..1: the faces some patch covers whole,
        and on the others the share of their area within ``eps_prox`` of the swept surface of a
        patch holding one of their corners (sampled, at most ``params.coverage_samples`` points;
        :func:`~auszug.sweeps.patches.area_coverage`).
    bbox_diameter : float
        Of the input mesh.
    centre : (3,) float array
        Bounding-box centre of the input mesh.
    n_vertices, n_faces : int
    stages : tuple of Stage
    params : SweepParams
    source : str
        The mesh file's name ("" when not from a file).
    face_coverage : float or None
        The per-face figure: share of the area of the union of the patches' ``faces`` (each face
        counted only when one patch holds its three corners); None when not known (a file
        without it).
    face_shares : (n_faces,) float array or None
        Per face the share of its area covered (1 for the patches' faces); its area-weighted
        mean is ``coverage``. None when not known (read from a file).
    """

    patches: tuple[SweepPatch, ...]
    coverage: float
    bbox_diameter: float
    centre: Array
    n_vertices: int
    n_faces: int
    stages: tuple[Stage, ...]
    params: SweepParams = DEFAULT
    source: str = ""
    face_coverage: float | None = None
    face_shares: Array | None = None

    def stage(self, name: str) -> Stage | None:
        """The stage called ``name`` (None if it did not run)."""
        return next((s for s in self.stages if s.name == name), None)

    def explain(self) -> str:
        """One line per stage: name, time, what it kept; then the patches."""
        lines = [f"{s.name:<10} {s.seconds:7.2f} s  {s.summary}" for s in self.stages]
        for p in self.patches:
            lines.append(f"patch {p.id}: {p.kind}, profile {len(p.profile)} points"
                         f"{' (closed)' if p.closed else ''}, {len(p.motion)} motion samples, "
                         f"{len(p.faces)} faces, coverage {p.coverage:.3f}, fit error {p.fit_error:.2e}")
        whole = "" if self.face_coverage is None else f" ({self.face_coverage:.3f} in whole faces)"
        lines.append(f"coverage {self.coverage:.3f} of the mesh's area{whole} by {len(self.patches)} patch(es)")
        return "\n".join(lines)


def _as_vf(mesh: Any) -> tuple[Any, Any]:
    if hasattr(mesh, "vertices") and hasattr(mesh, "faces"):
        return mesh.vertices, mesh.faces
    v, f = mesh
    return v, f


def sweep_length(p: SweepPatch) -> float:
    """Length of the path of the profile's centroid over the patch's motion (at its knots)."""
    c = p.motion.apply(p.profile.mean(axis=0)[None], p.motion.t)[:, 0]
    return float(np.linalg.norm(np.diff(c, axis=0), axis=1).sum())


def _to_input(p: SweepPatch, m: SweepMesh, new_id: int, tolerance: float) -> SweepPatch:
    fit = None
    if tolerance > 0:
        from auszug.sweeps.profilefit import fit_profile

        fit = fit_profile(p.profile, p.closed, tolerance, name=f"patch {new_id}")
    return SweepPatch(new_id, p.kind, m.to_input(p.profile), p.closed, p.motion.transformed(m.scale, m.centre),
                      p.faces, p.fit_error, p.coverage,
                      None if fit is None else fit.scaled(m.scale, m.centre))


def _fits(p: SweepPatch, params: SweepParams) -> bool:
    """A candidate the fit stage keeps (before overlaps are dropped)."""
    return (p.fit_error <= params.fit_factor * params.eps_prox and p.coverage >= params.min_patch_area
            and sweep_length(p) >= params.min_sweep_length)


def _covered(patches: list[SweepPatch], areas: Array, params: SweepParams) -> float:
    """Share of the area ``areas (m,)`` covered by the union of the candidates that fit (:func:`_fits`)."""
    covered = np.zeros(len(areas), bool)
    for p in patches:
        if _fits(p, params):
            covered[p.faces] = True
    total = float(areas.sum())
    return float(areas[covered].sum()) / total if total > 0 else 0.0


def detect(mesh: Any, params: SweepParams = DEFAULT, progress: Progress | None = None,
           source: str = "") -> SweepReport:
    """Find the sweep patches of a triangle mesh.

    Parameters
    ----------
    mesh : object with ``vertices (n, 3)`` and ``faces (m, 3)``, or a tuple ``(V, F)``
    params : SweepParams
    progress : callable, optional
        ``progress(stage, done, total)``, called as each stage starts (done = its index) and once
        at the end (done = total).
    source : str
        Recorded in the report (the mesh file's name).

    Returns
    -------
    SweepReport

    Raises
    ------
    auszug.errors.GeometryError
        The mesh has more than :attr:`auszug.limits.Limits.sweep_faces` triangles, is empty, has
        non-finite coordinates, bad indices, a face repeating a vertex, no extent, or an edge
        with more than two faces (see :func:`~auszug.sweeps.normalise`).

    Examples
    --------
    >>> from auszug.sweeps.fixtures import extruded
    >>> fx = extruded(n_profile=40, n_path=40)
    >>> r = detect((fx.vertices, fx.faces))
    >>> [p.kind for p in r.patches], round(r.coverage, 6)
    (['translation'], 1.0)
    """
    total = len(STAGES)

    def step(name: str) -> float:
        if progress is not None:
            progress(name, STAGES.index(name), total)
        return time.perf_counter()

    stages: list[Stage] = []
    t = step("normalise")
    v, f = _as_vf(mesh)
    n_faces = len(f) if hasattr(f, "__len__") else 0
    if n_faces > LIMITS.sweep_faces:
        raise GeometryError(f"mesh has {n_faces} triangles: more than the limit of {LIMITS.sweep_faces} for sweep "
                            "analysis (auszug.limits.LIMITS.sweep_faces); decimate it first")
    m = normalise(v, f)
    areas = face_areas(m.vertices, m.faces)
    stages.append(Stage("normalise", time.perf_counter() - t,
                        f"{m.n_vertices} vertices, {len(m.faces)} faces, {len(m.edges)} edges, "
                        f"bounding-box diameter {m.scale:.6g}",
                        {"vertices": m.n_vertices, "faces": len(m.faces), "edges": len(m.edges),
                         "bbox_diameter": m.scale}))

    t = step("cut")
    if params.initial_plane_count is not None:
        params = params.with_(offset_spacing=spacing_for(m.vertices, params.sphere_frequency,
                                                         params.initial_plane_count))
    normals, offsets = initial_planes(m.vertices, params.sphere_frequency, params.offset_spacing)
    cuts = cut(m, normals, offsets)
    mov = movability(cuts, params)
    stages.append(Stage("cut", time.perf_counter() - t,
                        f"{cuts.n_planes} initial planes (offsets {params.offset_spacing:.4g} apart), "
                        f"{cuts.n_curves} curves, {mov.n_runs} movable runs",
                        {"planes": cuts.n_planes, "curves": cuts.n_curves, "runs": mov.n_runs}))

    t = step("kinematic")
    axis = kinematic_axis(cuts, mov, params)
    raw: list[SweepPatch] = []
    kinematic = axis is not None and axis.agreement >= params.kinematic_min_agreement
    if axis is None:
        stages.append(Stage("kinematic", time.perf_counter() - t, "no cuts: nothing glides", {"agreement": 0.0}))
    else:
        if kinematic:
            raw = kinematic_patches(m, axis, params)
        what = (f"{axis.kind}, direction {np.round(axis.direction, 4).tolist()}"
                + (f", through {np.round(m.to_input(axis.point), 6).tolist()}" if axis.point is not None else "")
                + (f", pitch {axis.pitch * m.scale:.6g}" if axis.kind == "screw" else ""))
        verdict = (f"kinematic: {len(raw)} candidate patch(es)" if kinematic
                   else f"not kinematic (below {params.kinematic_min_agreement})")
        stages.append(Stage("kinematic", time.perf_counter() - t,
                            f"{axis.agreement:.3f} of the cuts glide under one {what}: {verdict}",
                            {"agreement": axis.agreement, "kind": axis.kind, "kinematic": int(kinematic),
                             "candidates": len(raw)}))

    bound = params.fit_factor * params.eps_prox
    if not kinematic or not any(p.fit_error <= bound and p.coverage >= params.min_patch_area for p in raw):
        # not kinematic, or kinematic cuts whose motion sweeps nothing that fits (a translation along a
        # curved path glides like a turn): general sweeps
        from auszug.sweeps.general import general_stages

        more, general = general_stages(m, cuts, mov, params, step, translations=kinematic)
        raw.extend(more)
        stages.extend(general)
        w = params.coarse_window
        if w > 0 and w != params.curvature_window and _covered(raw, areas, params) < params.coarse_below:
            # the short window's turning angles were mostly noise (or matched only short pieces):
            # the curvature plots again over the coarse window; the fit stage keeps the best of both
            more, general = general_stages(m, cuts, mov, params.with_(curvature_window=w), step,
                                           translations=kinematic)
            raw.extend(more)
            stages.extend(Stage(s.name, s.seconds, f"coarse pass (curvature over {w:g}): {s.summary}",
                                {**s.numbers, "curvature_window": w}) for s in general)

    free = np.ones(len(m.faces), bool)
    for p in raw:
        if _fits(p, params):
            free[p.faces] = False
    if params.max_parts > 0 and areas.sum() > 0 and float(areas[free].sum() / areas.sum()) >= params.min_patch_area:
        # what the whole-mesh consensus and the general sweeps leave: parts that are each a
        # surface of revolution or an extrusion (beyond the paper, docs/sweeps.md)
        from auszug.sweeps.parts import kinematic_parts

        t = step("parts")
        # on the whole mesh, not only the faces left: a small patch fitted before (the coarse pass
        # found 2 % of the tracery border's arch once its coordinates were rounded to float32) must
        # not cut the arcs' parts short; the fit stage keeps the patch that covers more
        found, tried = kinematic_parts(m, cuts, mov, params, first_id=len(raw))
        raw.extend(found)
        fits = sum(_fits(p, params) for p in found)
        stages.append(Stage("parts", time.perf_counter() - t,
                            f"{tried} motion(s) tried on the {float(areas[free].sum() / areas.sum()):.3f} of the area "
                            f"left, {len(found)} part patch(es), {fits} within fit error {bound:.3g}, covering "
                            f">= {params.min_patch_area:.3g} and sweeping >= {params.min_sweep_length:.3g}",
                            {"tried": tried, "candidates": len(found), "fit": fits}))

    planes: list[tuple[Array, float, float]] = []
    tree: MeshTree | None = None
    free = np.ones(len(m.faces), bool)
    for p in raw:
        if _fits(p, params):
            free[p.faces] = False
    if params.mirror and params.mirror_planes > 0 and areas.sum() > 0 \
            and float(areas[free].sum() / areas.sum()) >= params.min_patch_area:
        # the mirror images of the candidates that fit, in the mesh's mirror planes (beyond the
        # paper, docs/sweeps.md): a sweep found on one side of a symmetric piece, sought on the other
        t = step("mirror")
        tree = MeshTree.of(m)
        planes = mirror_planes(m, params, tree)
        found = mirror_candidates(m, [p for p in raw if _fits(p, params)], planes, params, tree, first_id=len(raw))
        raw.extend(found)
        fits = sum(_fits(p, params) for p in found)
        where = "; ".join(f"normal {np.round(n, 3).tolist()} ({share:.3f} of the area mirrored on the mesh)"
                          for n, _, share in planes)
        stages.append(Stage("mirror", time.perf_counter() - t,
                            f"{len(planes)} mirror plane(s){': ' + where if where else ''}; {len(found)} mirror "
                            f"image(s) fitted on faces the candidates leave, {fits} within fit error {bound:.3g}, "
                            f"covering >= {params.min_patch_area:.3g} and sweeping >= {params.min_sweep_length:.3g}",
                            {"planes": len(planes), "candidates": len(found), "fit": fits}))

    free = np.ones(len(m.faces), bool)
    for p in raw:
        if _fits(p, params):
            free[p.faces] = False
    arcs: list[SweepPatch] = []
    flats: list[SweepPatch] = []
    by_rings: list[SweepPatch] = []
    short = arc_bounds(params)
    if params.arc_axes > 0 and areas.sum() > 0 and float(areas[free].sum() / areas.sum()) >= params.min_patch_area:
        # rotations about the axes of the exact arcs among the creases beside the faces left: sweeps
        # along arcs too short for min_sweep_length (a lancet's head; beyond the paper, docs/sweeps.md),
        # and the planar faces normal to such an axis swept about it by radial lines (a wall's face
        # around an arch)
        t = step("arcs")
        axes = crease_circles(m, free, params)
        tree = MeshTree.of(m) if tree is None else tree
        arcs, tried = arc_candidates(m, free, params, tree, first_id=len(raw), axes=axes)
        if params.arc_flat:
            flats = flat_candidates(m, free, axes, params, tree, first_id=len(raw) + len(arcs))
        # the axes of exact coaxial rings among the edge lines (round mouldings: no crease); their
        # patches are counted by the area they add, as the planar ones
        rings = ring_circles(m, free, params)
        by_rings, _ = arc_candidates(m, free, params, tree, first_id=len(raw) + len(arcs) + len(flats), axes=rings)
        fits = sum(_fits(p, short) for p in arcs)
        flat_fits = sum(p.fit_error <= bound and sweep_length(p) >= short.min_sweep_length for p in flats)
        ring_fits = sum(p.fit_error <= bound and sweep_length(p) >= short.min_sweep_length for p in by_rings)
        stages.append(Stage("arcs", time.perf_counter() - t,
                            f"{len(axes)} axis/axes of crease arcs within {params.arc_fit * params.eps_prox:.3g} "
                            f"of a circle; {len(arcs)} patch(es), {fits} within fit error {bound:.3g}, covering "
                            f">= {short.min_patch_area:.3g} and sweeping >= {short.min_sweep_length:.3g}; "
                            f"{len(flats)} planar patch(es) about them, {flat_fits} within fit error {bound:.3g} "
                            f"and sweeping >= {short.min_sweep_length:.3g}; {len(rings)} axis/axes of >= "
                            f"{params.arc_rings} exact coaxial rings, {len(by_rings)} patch(es) about them, "
                            f"{ring_fits} within fit error {bound:.3g} and sweeping >= {short.min_sweep_length:.3g}",
                            {"axes": len(axes), "tried": tried, "candidates": len(arcs), "fit": fits,
                             "flat_candidates": len(flats), "flat_fit": flat_fits, "ring_axes": len(rings),
                             "ring_candidates": len(by_rings), "ring_fit": ring_fits}))

    t = step("fit")
    good = [p for p in raw if _fits(p, params)]
    n_good = len(good)
    good += [p for p in arcs if _fits(p, short)]
    raw = raw + arcs
    kept: list[SweepPatch] = []
    taken = np.zeros(len(m.faces), bool)
    for p in sorted(good, key=lambda p: (-p.coverage, p.fit_error)):
        a = areas[p.faces]
        if a.sum() > 0 and float(a[taken[p.faces]].sum() / a.sum()) >= params.patch_overlap:
            continue
        kept.append(p)
        taken[p.faces] = True
    # the planar patches about the crease arcs' axes, each kept when it adds arc_min_area of the area
    # to what the others cover (their long faces are mostly not theirs whole; docs/sweeps.md)
    flat_ok = [p for p in flats + by_rings if p.fit_error <= bound and sweep_length(p) >= short.min_sweep_length]
    added = add_by_area(m, kept, flat_ok, params.eps_prox, params.coverage_samples, short.min_patch_area, areas)
    raw = raw + flats + by_rings
    if added and planes:
        # their mirror images in the mesh's mirror planes (the stage mirror ran before them), each
        # fitted against the mesh and kept, as they, by the area it adds
        tree = MeshTree.of(m) if tree is None else tree
        images = mirror_candidates(m, added, planes, params, tree, first_id=len(raw))
        raw = raw + images
        ok = [p for p in images if p.fit_error <= bound and sweep_length(p) >= short.min_sweep_length]
        added += add_by_area(m, kept + added, ok, params.eps_prox, params.coverage_samples, short.min_patch_area,
                             areas)
    kept += added
    patches = tuple(_to_input(p, m, i, params.profile_fit_tolerance) for i, p in enumerate(kept))
    fitted = sum(p.profile_fit is not None for p in patches)
    covered = np.zeros(len(m.faces), bool)
    for p in patches:
        covered[p.faces] = True
    area = float(areas.sum())
    face_coverage = float(areas[covered].sum() / area) if area > 0 else 0.0
    # the faces a patch holds whole, and the sampled share of the others (docs/sweeps.md, "Coverage")
    shares = area_coverage(m, kept, params.eps_prox, params.coverage_samples, areas)
    coverage = float(min(1.0, (shares * areas).sum() / area)) if area > 0 else 0.0
    of_arcs = (f", {len(good) - n_good} of them arcs' patches covering >= {short.min_patch_area:.3g} and sweeping "
               f">= {short.min_sweep_length:.3g}" if arcs else "")
    of_arcs += (f"; {len(added)} planar patch(es) about crease arcs' axes, patches about rings' axes and their "
                f"mirror images adding >= "
                f"{short.min_patch_area:.3g} of the area each" if flats or by_rings else "")
    stages.append(Stage("fit", time.perf_counter() - t,
                        f"{len(patches)} of {len(raw)} patch(es) kept ({len(good)} within fit error {bound:.3g}, "
                        f"covering >= {params.min_patch_area:.3g} and sweeping >= {params.min_sweep_length:.3g}"
                        f"{of_arcs}; then overlaps dropped); coverage {coverage:.3f} of the area "
                        f"({face_coverage:.3f} in whole faces, {params.coverage_samples} samples); {fitted} "
                        f"profile(s) fitted with lines and arcs within {params.profile_fit_tolerance:.3g}",
                        {"candidates": len(raw), "patches": len(patches), "coverage": coverage, "flat": len(added),
                         "face_coverage": face_coverage, "profile_fits": fitted}))
    if progress is not None:
        progress("fit", total, total)
    return SweepReport(patches, coverage, m.scale, m.centre, m.n_vertices, len(m.faces), tuple(stages), params,
                       source, face_coverage, shares)
