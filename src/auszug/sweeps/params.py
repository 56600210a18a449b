"""The parameters of sweep detection (Barton, Pottmann, Wallner 2014), in one documented value.

Lengths are relative to the bounding-box diameter of the mesh: :func:`auszug.sweeps.normalise`
scales every mesh to diameter 1 first, so that ``||C|| = 1`` of a velocity state and every length
below mean the same on every input.
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
from typing import Any

import numpy as np

from auszug.errors import GeometryError
from auszug.limits import LIMITS

__all__ = ["SweepParams", "DEFAULT"]


def _whole(x: object) -> bool:
    """True for an int (not a bool, not a float with a whole value)."""
    return isinstance(x, (int, np.integer)) and not isinstance(x, bool)


def _real(x: object) -> bool:
    """True for a finite real number (not a bool)."""
    return isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, bool) and bool(np.isfinite(x))


@dataclass(frozen=True)
class SweepParams:
    """Every knob of the detection stages; defaults are the paper's where it gives one.

    Attributes
    ----------
    beta : float
        Alg. 1 weight update ``w = 1 / (1 + beta f^gamma)`` (paper: 400).
    gamma : float
        Exponent of the weight update (paper: 2).
    iterations : int
        Weight iterations (paper: "mostly 3").
    weight_threshold : float
        A vertex belongs to a movable run if its weight is above this (paper: epsilon = 2/3).
    speed_floor : float
        Eq. 5 as used: ``f = (n . v)^2 / (|v|^2 + speed_floor^2)`` (0: as printed). A floor keeps
        ``f`` from being noise where a vertex barely moves (near the rotation axis).
    gap : float
        Stretches of weight below the threshold spanning at most this arc length, between two
        stretches above it, are bridged (our choice: noise must not split a profile).
    max_sliding : float
        Runs whose velocity has more than this share of its squared length along the curve's
        own tangent are dropped (our choice: a curve sliding along itself is no evidence).
    loop_sliding : float
        Beyond the paper, with ``max_sliding``: a run that is a whole closed cut curve (a loop
        slides along itself only by turning in its own plane) and whose Eq. 4 velocity slides along
        it is still kept when another velocity state glides it with little sliding: when the least
        ``sliding share + mean f / f*`` over all velocity states is at most ``loop_sliding``
        (``mean f``: the run's weighted squared normal speed over its squared speed; ``f* = ((1 /
        weight_threshold - 1) / beta)^(1 / gamma)``, the movability at which Alg. 1's weight falls
        to the threshold, 0.035 at the defaults). A coarse closed cut (a square bar's cut loop of 8
        points, its corners' normals diagonal) nearly glides under the turn in its own plane as
        well as under the motions out of it, and the eigenvector Eq. 4 returns is any mix of them:
        with noise 5e-4 on a member's bar 127 of 140 cut loops within 25 deg of a profile plane
        were dropped as sliding. A loop at angle ``a`` to a tube's normal plane moving along the
        tube slides by about ``sin^2(a) / 2``; default 0.1 (about 27 deg, near ``match_angle``:
        the profile planes' loops, not the oblique ones); 0: the Eq. 4 velocity's share only.
    min_spread : float
        Runs whose normals hardly turn, second eigenvalue of their mean ``n n^T`` below this, are
        dropped (our choice: in a nearly flat strip everything glides). 0.03: normals turning by
        less than about +-17 degrees.
    sphere_frequency : int
        Frequency of the icosahedral geodesic sphere whose vertices give the plane normals (the
        paper takes "one of Buckminster Fuller's geodesic spheres" and names none). Frequency nu
        has ``10 nu^2 + 2`` vertices; antipodes give the same planes, so ``5 nu^2 + 1`` normals,
        about ``63.4 / nu`` degrees apart. Default 4: 81 normals, 16 degrees apart.
    offset_spacing : float
        Spacing of the plane offsets along each normal, over the interval where the plane meets
        the mesh (paper: "regularly sampled", no spacing). Default 0.055: 81 normals x about 18
        offsets is about the paper's 1452 initial planes of Fig. 12 on a unit-diameter mesh.
    initial_plane_count : int or None
        If given, :func:`~auszug.sweeps.detect` picks the offset spacing that gives about this
        many initial planes (``auszug sweeps --planes``), overriding ``offset_spacing``.
    percentile : float
        The share g (percent) of cuts kept as good after each round, lowest gliding energy first
        (paper: g in {1, 3, 5}).
    refinements : int
        Rounds of adaptive refinement (paper: 1-3).
    refine_steps : int
        Per round, each good plane spawns a ``refine_steps^3`` grid of planes (normal tilted about
        two axes, offset shifted) centred on it, itself excluded. Odd; default 3 (26 new planes).
    refine_angle : float
        Half-width (degrees) of the first round's box in normal angle; halved every round.
        Default: half the sphere's spacing, ``31.7 / sphere_frequency``.
    refine_offset : float
        Half-width of the first round's box in offset; halved every round. Default: half the
        offset spacing.
    l_min : float
        Shortest movable run and shortest match, as arc length (paper: 20 % of the diameter).
    eps_match : float
        Matching threshold of Eq. 6: a window matches if mean ``|kappa - kappa'|`` is at most
        ``eps_match`` times the reference energy ``E_kappa,0`` (Fig. 15: 0.01 or 0.1).
    kappa_floor : float
        Floor of ``E_kappa,0`` so that straight pieces (``kappa = 0``) can match: the reference is
        ``max(E_kappa,0, kappa_floor)``. Default 1 (the curvature of a circle of the diameter's
        radius).
    match_spacing : float
        The one arc-length spacing at which curvature plots are compared.
    curvature_window : float
        Arc length over which the discrete curvature is averaged (turning angle over that length):
        our stand-in for the robust integral-invariant curvature of [PWHY09], on the noisy cuts.
    coarse_window : float
        Beyond the paper: when the general sweeps found with ``curvature_window`` cover less than
        ``coarse_below`` of the mesh (within the fit bound), the curvature plots are taken again
        averaged over this arc length, matched again, and the families of both passes fitted;
        the fit stage then keeps the best patches of both (0: no second pass). On noisy cuts the
        turning angle over the short window is mostly noise (sigma 1e-3 of the diameter: 16 of
        16 245 pairs of the letter G matched); over 0.08 it is the shape again (default 0.08).
    coarse_below : float
        The coverage below which the second, coarse pass runs (default 0.95, the clean target of
        the issue).
    family_keep : float
        A family's common part keeps at least this share of its seed's longest match: members
        whose match would trim it shorter stay out (our choice; the paper trims "to equal length").
    match_angle : float
        Pairs of cuts whose planes meet at more than this (degrees) are not matched (sec. 2.2,
        "mostly 25").
    omega : tuple of float
        Weights (omega_1, omega_2) of E_order (sec. 2.2, (0.6, 1)).
    kinematic_gap : float
        A cut's velocity state is well determined (one motion, not a family) when its second
        smallest eigenvalue is at least this many times the smallest. Cuts below it (straight
        lines, circles on cylinders) do not vote for a kinematic axis.
    kinematic_trim : float
        Cuts whose residual under the kinematic consensus exceeds this many times the median are
        left out of it.
    kinematic_share : float
        A cut glides under the consensus if at least this share of its points has weight above
        the threshold.
    translation_ratio : float
        A consensus is a translation if its rotational part changes the velocity over the
        normalised mesh (radius 0.5) by at most this share of ``|c_bar|``: ``0.5 |c| <= r |c_bar|``
        (a rotation about an axis 10 diameters away is a translation at 0.05).
    pitch_tolerance : float
        A screw with ``|pitch|`` at most this (bounding-box diameters per radian) is a rotation.
    kinematic_min_agreement : float
        The mesh is treated as kinematic (its patches come from :func:`kinematic_axis`) when at
        least this share of the cuts glides under the consensus motion (our choice; revolved and
        extruded fixtures score 0.92-1, general sweeps and random bumps 0.09-0.17).
    eps_prox : float
        Proximity threshold of the fit check (sec. 2.3.4, "typically 0.001 to 0.01" of the
        diameter): a face is covered when its vertices lie within it of the swept surface.
    fit_factor : float
        A patch is kept when its fit error (largest distance of the swept profile to the mesh)
        is at most ``fit_factor * eps_prox`` (the issue's bound: 2).
    reciprocal_angle : float
        The fit check's reciprocal test (:meth:`~auszug.sweeps.patches.MeshTree.interior_distance`)
        discounts a swept point farther than ``eps_prox`` from the mesh whose closest mesh point lies
        on another part of the swept surface only where that part lies along the mesh: its normal
        within this angle (degrees, either orientation) of the mesh's normal at the closest point.
        A swept surface folding over itself (a profile or path doubling back) crosses the mesh
        there and discounts nothing. 180: no normal test. Default 30 (our choice).
    min_patch_area : float
        A patch is kept when it covers at least this share of the mesh's area.
    motion_samples : int
        Rigid maps stored per patch, from the first rib to the last (at least 8).
    profile_cuts : int
        Further cuts, spread over a patch's parameter range and mapped back by the motion, whose
        closest points improve the profile (sec. 2.3.3; 0: the one cut as is).
    general_iterations : int
        Rounds of velocity estimation, Hermite interpolation and profile improvement of a
        general sweep (sec. 2.3.4: "performed in an alternating way"), each after the first on
        ribs re-sliced by the fitted motion's profile planes.
    mu : tuple of float
        Weights (mu_1, mu_2) of Eq. 7 (paper: (0.002, 0.1)).
    grow : bool
        Beyond the paper: grow every fitted general sweep across its profile (to the whole cut
        curve, trimmed to the points whose paths stay within ``eps_prox``) and along its path
        (extrapolated rib by rib while the mesh follows), then refit it (docs/sweeps.md).
    grow_steps : int
        Growing a general sweep along its path: at most this many ribs are added at each end
        (each a few cuts of the mesh; at most ``LIMITS.sweep_steps``). Default 200: a rib step
        of a family is about 1-3 % of the diameter, so 200 steps reach beyond any mesh.
    grow_share : float
        A grown rib is accepted when at least this share of the moved profile's points lies
        within ``grow_tolerance * eps_prox`` of the cut curve there (default 0.9).
    grow_tolerance : float
        The distance (in units of ``eps_prox``) within which a grown rib's points must lie of the
        mesh's cut (default 2, the bound of the fit check, ``fit_factor``'s default).
    grow_skip : int
        A failed growth step is retried as 2 .. ``grow_skip + 1`` steps at once, over a gap in
        the mesh that no rib in between can bridge (default 2; 0: no skipping).
    grow_on_mesh : float
        A grown rib needs at least this share of the moved profile's points on the mesh. The others
        lie beyond it: their closest point on the cut is an end of a cut curve (cuts end only on the
        mesh's boundary) and far, as over a hole or past the mesh's end; they count neither for nor
        against ``grow_share`` (default 0.5).
    twist_steps : int
        Beyond the paper: after the fit, each knot's rigid map of a general sweep is refined
        against the mesh (:func:`~auszug.sweeps.general.refine_motion`) by this many
        point-to-plane steps turning the profile about its plane's normal and moving it in its
        plane, then set into the normal plane of its centroid's path and refined again by as many
        steps (a profile small against ``eps_prox`` fits the bound turned the wrong way; default
        4; 0: no refinement).
    twist_tolerance : float
        The refinement's early stop: a knot whose step moves its profile's points by at most
        about this much (bounding-box diameters; its turn times the profile's radius and its
        shift) takes no more steps. Default 1e-7 (2e-5 of the default ``eps_prox``); 0: every
        knot takes all ``twist_steps``.
    tangent_window : float
        The refinement's path tangents: local cubic fits to the moved centroids within this arc
        length (bounding-box diameters) on either side (0: central differences). Default 0.06: on
        a member's mesh with noise 5e-4 the tangents of single knots turned the profile planes by
        2.4 deg (median), over 0.06 by 0.75 deg; clean, 0.02-0.04 deg either way.
    tangent_switch : float
        The refinement's path tangents at a jump of the path's curvature (arcs meeting G1, as a
        member's ogee at its inflection): a point whose centred cubic's residual variance is more
        than this many times a one-sided cubic's (over the window behind or ahead) takes the
        one-sided tangent (:func:`~auszug.sweeps.general.path_tangents`; default 10; 0: centred
        fits only). On U.XI.29's member the centred tangent at the inflection was 1.08 deg off,
        the one-sided 0.02.
    twist_window : float
        The refinement's last step (beyond the paper): each knot's turn about its profile plane's
        normal is set to a robust local line's through the knots' turns within this arc length
        (bounding-box diameters) on either side (:func:`~auszug.sweeps.general.smooth_twists`;
        default 0.1; 0: off). With noise each knot's turn follows the noisy faces about it: on
        tn-2's member at sigma 5e-4 +-0.4 deg per knot (median rotation error 0.62 deg; with the
        lines 0.37); clean the turns lie on such lines already (a member's frames twist linearly
        along the path; U.XI.30's member 0.027 -> 0.028 deg).
    piece_trim : float
        Beyond the paper: the profile improvement (sec. 2.3.3) leaves out the recut pieces of the
        knots whose median distance to the profile is more than this many times the median over
        the knots (a grown sweep's knots where the mesh ends or past it; default 2; 0: every piece
        counts). On a member's square bar the mean of all pieces cut its corners by 1.5e-3.
    corner_tolerance : float
        Beyond the paper: a finished general sweep's closed profile segment gets the median of the recut
        pieces' farthest points from it inserted when that lies farther than this (bounding-box
        diameters; the corner of a square profile between two profile points;
        :func:`~auszug.sweeps.patches.fill_corners`; default 5e-4; 0: none).
    rib_jump : float
        A family's ordered ribs are split where the step between consecutive ribs' centroids is
        more than this many times the median step; each stretch (of at least 3 ribs) is fitted on
        its own (default 3: cuts of one plane family across two parallel stretches of a border
        match, and one sweep through both crosses the opening between them).
    end_gap : float
        Growing and re-slicing a general sweep: a moved profile point whose closest point on the
        cut is an end of a cut curve (cuts end only on the mesh's boundary) farther than
        ``end_gap * eps_prox`` lies beyond the mesh, over a hole or past its end: it is no
        correspondence (default 0.5; a profile's own end point lies at a curve's end, nearer).
    translation_step : float
        Spacing (bounding-box diameters) of the parallel cuts of a translational sweep
        (:func:`~auszug.sweeps.general.translational_patch`; default 0.02).
    translation_steps : int
        At most this many parallel cuts on each side of a translational sweep's first cut (at
        most ``LIMITS.sweep_steps``; default 400: 8 diameters at the default spacing).
    chord_slack : float
        A translational sweep re-found in planes normal to the chord of its path replaces the one in
        the general sweep's (tilted) profile plane when it covers at least the old coverage less
        this (:func:`~auszug.sweeps.general.translational_patch`; default 0.02).
    max_match_runs : int
        At most this many movable runs of the initial planes, longest first, are matched (the
        paper's N_match, good runs only, is 144-229 in Fig. 15).
    max_families : int
        At most this many families, of most support (members times the length of their common
        part) first, are fitted with a general sweep.
    min_sweep_length : float
        A patch is kept when its profile's centroid travels at least this far (bounding-box
        diameters): a short sweep on any smooth surface fits within eps_prox.
    patch_overlap : float
        A patch whose faces' area is covered by this share by a better patch (lower fit error)
        is dropped.
    profile_fit_tolerance : float
        Beyond the paper: every kept patch's profile is fitted with exact lines and arcs
        (:func:`auszug.sweeps.fit_profile`) and the fit kept when its Hausdorff distance to the
        polyline is at most this (bounding-box diameters; its pieces' vertices lie within a
        quarter of it of their line or circle). 0: no fit.
    max_parts : int
        Beyond the paper (:mod:`auszug.sweeps.parts`): at most this many motions are tried for
        parts that are each an extrusion or a surface of revolution, on what the other patches
        leave (0..64; 0: none).
    part_candidates : int
        Velocity states of single cuts scored per motion tried (1..1024).
    part_min_points : int
        A motion is tried only when its candidate moves at least this many cut points.
    part_margin : float
        Growth of a part's box and range around its gliding cut points (bounding-box diameters).
    part_l_min : float
        Shortest profile piece of a part (bounding-box diameters; ``l_min`` is for matching).
    part_slices : int
        A part's range is cut in this many slices, each with its own profile cut (1..16).
    part_blocks : int
        A part's profile, moved over the part's range, may lie on the mesh over several blocks
        (stretches of the motion times pieces of the profile): at most this many, largest first,
        become patches (1..16).
    part_grow : bool
        A part's profile is moved over the whole mesh's range of the motion and its blocks are
        sought on the whole mesh, not only in the part's box: a patch grows over the neighbouring
        faces that the moved profile stays within ``eps_prox`` of.
    part_trim_spacing : float
        Spacing of the rings on which a part's profile is tested for staying on the mesh, in
        multiples of ``eps_prox`` (0.5..8; at most 1024 rings per profile).
    part_profile_cuts : int
        ``profile_cuts`` for a part's profile (default 0: the one cut as is). A part's range may
        hold stretches that are no sweep under its motion (the rest of a window above its jambs),
        whose cuts, mapped back, pulled the improved profile off the mesh: on the tracery window
        the vertical translation found no patch with 8 cuts, 5 with none.
    part_mean_error : float
        A part's block is kept only when its moved profile points lie on average within this share
        of ``eps_prox`` of the mesh (in (0, 1]; 1: no test, every point is within ``eps_prox``): a
        motion that only approximates a smooth surface, a rotation about a Gaussian bump's axis,
        stays within ``eps_prox`` but not near 0 on average.
    part_across : float
        After the parts, each translation that found patches is tried across the planar faces
        along it: the faces whose normals are within this sine of normal to the translation,
        grouped by normal (to 0.01), give the largest group's normal ``n``, and the translation
        along ``n x d`` is tried over the whole mesh (a wall's top and bottom and its face above an
        opening slide along the wall's width; no cut of them glides as a whole). 0 turns it off;
        at most 0.2.
    mirror : bool
        Whether :func:`~auszug.sweeps.detect` adds the mirror images of the candidates that fit in
        the mesh's mirror planes as candidates (beyond the paper, :mod:`auszug.sweeps.mirror`),
        each fitted against the mesh like every other candidate.
    mirror_share : float
        A plane is a mirror plane when the mirror images of the faces' centroids lie within
        ``eps_prox`` of the mesh for at least this share of the area. Default 0.95.
    mirror_planes : int
        At most this many mirror planes, best first (0..3; 0: none, as ``mirror`` false). Default 2.
    arc_axes : int
        At most this many rotation axes of crease arcs tried by the stage ``arcs`` of
        :func:`~auszug.sweeps.detect` (beyond the paper, :mod:`auszug.sweeps.arcs`: sweeps along
        arcs too short for ``min_sweep_length``, a lancet's head). 0 turns the stage off; at most
        256. Default 16.
    arc_crease : float
        An edge is a crease when its two faces' normals differ by at least this many degrees
        (0 < ``arc_crease`` < 180). Default 20.
    arc_fit : float
        A crease chain is an arc when all its vertices lie within this share of ``eps_prox`` of
        its fitted circle, in (0, 1]. Default 0.05.
    arc_sweep_length : float
        The least sweep length (diameters) of a patch about a crease arc's axis, in place of
        ``min_sweep_length`` (the smaller of the two holds). Default 0.03 (0.1 before the crease
        chains were cut into their arcs, :func:`~auszug.sweeps.arcs.circle_pieces`: a foil's lobe
        sweeps 0.04-0.09).
    arc_min_area : float
        The least coverage of a patch about a crease arc's axis, in place of ``min_patch_area``
        (the smaller of the two holds); for the planar patches of ``arc_flat`` the least share of
        the area each adds. Default 0.001 (0.005 before; a foil's lobe covers 0.0016-0.003).
    arc_flat : bool
        Whether the stage ``arcs`` also sweeps the planar faces normal to a crease arc's axis by
        the rotation about it, a straight radial profile from the arc
        (:func:`~auszug.sweeps.arcs.flat_candidates`: a wall's face around an arch). Default true.
    arc_rings : int
        The stage ``arcs`` also proposes the axes of families of at least this many distinct
        coaxial exact circles among the mesh's straightest edge lines over the open faces (a round
        moulding's rings, which meet at no crease: :func:`~auszug.sweeps.arcs.ring_circles`); their
        patches are kept by the area they add. 0 turns it off; at most 64. Default 3.
    arc_ring_fit : float
        Such a circle's vertices lie within this share of ``eps_prox`` of it, in (0, 1]. Default
        0.001: exact circles (the random bumps' edge lines have short pieces within 1e-6 of a
        circle, but no three of them coaxial).
    coverage_samples : int
        The report's ``coverage`` is of the mesh's area, not of whole faces: the faces that no
        kept patch covers whole (all three corners within ``eps_prox`` of its swept surface) are
        sampled, at most this many points over the whole mesh, area-uniform (systematic), and a
        sample counts as covered when it lies within ``eps_prox`` of the swept surface of a patch
        holding at least one of its face's corners (:func:`auszug.sweeps.patches.area_coverage`).
        The per-face figure is reported beside it (``face_coverage``). Bounds the time and memory
        (a few arrays of this length). 0: no samples, the coverage is the per-face one; at most
        10 000 000.
    """

    beta: float = 400.0
    gamma: float = 2.0
    iterations: int = 3
    weight_threshold: float = 2.0 / 3.0
    speed_floor: float = 0.05
    gap: float = 0.01
    max_sliding: float = 0.5
    loop_sliding: float = 0.1
    min_spread: float = 0.03
    sphere_frequency: int = 4
    offset_spacing: float = 0.055
    initial_plane_count: int | None = None
    percentile: float = 5.0
    refinements: int = 3
    refine_steps: int = 3
    refine_angle: float | None = None
    refine_offset: float | None = None
    l_min: float = 0.2
    eps_match: float = 0.1
    kappa_floor: float = 1.0
    match_spacing: float = 0.005
    curvature_window: float = 0.05
    coarse_window: float = 0.08
    coarse_below: float = 0.95
    family_keep: float = 0.8
    match_angle: float = 25.0
    omega: tuple[float, float] = (0.6, 1.0)
    kinematic_gap: float = 10.0
    kinematic_trim: float = 10.0
    kinematic_share: float = 0.95
    translation_ratio: float = 0.05
    pitch_tolerance: float = 1e-3
    kinematic_min_agreement: float = 0.5
    eps_prox: float = 0.005
    fit_factor: float = 2.0
    reciprocal_angle: float = 30.0
    min_patch_area: float = 0.01
    motion_samples: int = 17
    profile_cuts: int = 8
    general_iterations: int = 3
    mu: tuple[float, float] = (0.002, 0.1)
    grow: bool = True
    grow_steps: int = 200
    grow_share: float = 0.9
    grow_tolerance: float = 2.0
    grow_skip: int = 2
    grow_on_mesh: float = 0.5
    twist_steps: int = 4
    twist_tolerance: float = 1e-7
    tangent_window: float = 0.06
    tangent_switch: float = 10.0
    twist_window: float = 0.1
    piece_trim: float = 2.0
    corner_tolerance: float = 5e-4
    rib_jump: float = 3.0
    end_gap: float = 0.5
    translation_step: float = 0.02
    translation_steps: int = 400
    chord_slack: float = 0.02
    max_match_runs: int = 600
    max_families: int = 6
    min_sweep_length: float = 0.2
    patch_overlap: float = 0.8
    profile_fit_tolerance: float = 0.002
    max_parts: int = 8
    part_candidates: int = 128
    part_min_points: int = 200
    part_margin: float = 0.01
    part_l_min: float = 0.03
    part_slices: int = 3
    part_blocks: int = 4
    part_grow: bool = True
    part_trim_spacing: float = 1.0
    part_mean_error: float = 0.25
    part_profile_cuts: int = 0
    part_across: float = 0.02
    coverage_samples: int = 100_000
    mirror: bool = True
    mirror_share: float = 0.95
    mirror_planes: int = 2
    arc_axes: int = 16
    arc_crease: float = 20.0
    arc_fit: float = 0.05
    arc_sweep_length: float = 0.03
    arc_min_area: float = 0.001
    arc_flat: bool = True
    arc_rings: int = 3
    arc_ring_fit: float = 0.001

    def __post_init__(self) -> None:
        checks = [
            ("beta", self.beta > 0, "> 0"),
            ("gamma", self.gamma > 0, "> 0"),
            ("iterations", self.iterations >= 1, ">= 1"),
            ("weight_threshold", 0 < self.weight_threshold < 1, "in (0, 1)"),
            ("speed_floor", self.speed_floor >= 0, ">= 0"),
            ("gap", self.gap >= 0, ">= 0"),
            ("max_sliding", 0 < self.max_sliding <= 1, "in (0, 1]"),
            ("loop_sliding", _real(self.loop_sliding) and 0 <= self.loop_sliding <= 1, "in [0, 1] (a share)"),
            ("min_spread", 0 <= self.min_spread < 0.5, "in [0, 0.5)"),
            ("sphere_frequency", 1 <= self.sphere_frequency <= 64, "in 1..64"),
            ("offset_spacing", 0 < self.offset_spacing <= 1, "in (0, 1]"),
            ("initial_plane_count", self.initial_plane_count is None or 10 <= self.initial_plane_count <= 100_000,
             "None or in 10..100000"),
            ("percentile", 0 < self.percentile <= 100, "in (0, 100]"),
            ("refinements", 0 <= self.refinements <= 8, "in 0..8"),
            ("refine_steps", self.refine_steps >= 3 and self.refine_steps % 2 == 1, "odd and >= 3"),
            ("l_min", 0 < self.l_min <= 10, "in (0, 10]"),
            ("eps_match", self.eps_match > 0, "> 0"),
            ("kappa_floor", self.kappa_floor >= 0, ">= 0"),
            ("match_spacing", 0 < self.match_spacing <= self.l_min / 4, "in (0, l_min / 4]"),
            ("curvature_window", self.curvature_window >= 2 * self.match_spacing, ">= 2 match_spacing"),
            ("coarse_window", _real(self.coarse_window) and (self.coarse_window == 0
                                                               or self.coarse_window >= 2 * self.match_spacing),
             "0 or >= 2 match_spacing"),
            ("coarse_below", _real(self.coarse_below) and 0 <= self.coarse_below <= 1, "in [0, 1]"),
            ("family_keep", 0 < self.family_keep <= 1, "in (0, 1]"),
            ("match_angle", 0 < self.match_angle <= 90, "in (0, 90]"),
            ("kinematic_gap", self.kinematic_gap >= 1, ">= 1"),
            ("kinematic_min_agreement", 0 <= self.kinematic_min_agreement <= 1, "in [0, 1]"),
            ("eps_prox", 1e-5 <= self.eps_prox <= 0.1, "in [1e-5, 0.1] (bounding-box diameters)"),
            ("fit_factor", self.fit_factor >= 1, ">= 1"),
            ("reciprocal_angle", 0 < self.reciprocal_angle <= 180, "in (0, 180]"),
            ("min_patch_area", 0 <= self.min_patch_area <= 1, "in [0, 1]"),
            ("motion_samples", 8 <= self.motion_samples <= 4096, "in 8..4096"),
            ("profile_cuts", 0 <= self.profile_cuts <= 256, "in 0..256"),
            ("general_iterations", 1 <= self.general_iterations <= 16, "in 1..16"),
            ("grow", isinstance(self.grow, bool), "true or false"),
            ("grow_steps", _whole(self.grow_steps) and 0 <= self.grow_steps <= LIMITS.sweep_steps,
             f"a whole number in 0..{LIMITS.sweep_steps} (auszug.limits.LIMITS.sweep_steps)"),
            ("grow_share", _real(self.grow_share) and 0.5 <= self.grow_share <= 1,
             "in [0.5, 1] (a share of the profile's points)"),
            ("grow_tolerance", _real(self.grow_tolerance) and 0.5 <= self.grow_tolerance <= 20,
             "in [0.5, 20] (multiples of eps_prox)"),
            ("grow_skip", _whole(self.grow_skip) and 0 <= self.grow_skip <= 16, "a whole number in 0..16"),
            ("grow_on_mesh", _real(self.grow_on_mesh) and 0.1 <= self.grow_on_mesh <= 1,
             "in [0.1, 1] (a share of the profile's points)"),
            ("twist_steps", _whole(self.twist_steps) and 0 <= self.twist_steps <= 64, "a whole number in 0..64"),
            ("twist_tolerance", _real(self.twist_tolerance) and 0 <= self.twist_tolerance <= 1e-3,
             "in [0, 1e-3] (bounding-box diameters)"),
            ("tangent_window", _real(self.tangent_window) and 0 <= self.tangent_window <= 1,
             "in [0, 1] (bounding-box diameters)"),
            ("tangent_switch",
             _real(self.tangent_switch) and (self.tangent_switch == 0 or 1 <= self.tangent_switch <= 1e6),
             "0 or in [1, 1e6] (a ratio of residual variances)"),
            ("twist_window", _real(self.twist_window) and 0 <= self.twist_window <= 1,
             "in [0, 1] (bounding-box diameters)"),
            ("piece_trim", _real(self.piece_trim) and (self.piece_trim == 0 or 1 <= self.piece_trim <= 100),
             "0 or in [1, 100] (times the median)"),
            ("corner_tolerance", _real(self.corner_tolerance) and 0 <= self.corner_tolerance <= 0.1,
             "in [0, 0.1] (bounding-box diameters)"),
            ("rib_jump", _real(self.rib_jump) and self.rib_jump > 1, "> 1 (times the median rib step)"),
            ("end_gap", _real(self.end_gap) and 0.05 <= self.end_gap <= 20, "in [0.05, 20] (multiples of eps_prox)"),
            ("translation_step", _real(self.translation_step) and 1e-4 <= self.translation_step <= 0.5,
             "in [1e-4, 0.5] (bounding-box diameters)"),
            ("translation_steps", _whole(self.translation_steps) and 1 <= self.translation_steps <= LIMITS.sweep_steps,
             f"a whole number in 1..{LIMITS.sweep_steps} (auszug.limits.LIMITS.sweep_steps)"),
            ("chord_slack", _real(self.chord_slack) and 0 <= self.chord_slack <= 1, "in [0, 1] (a share of the area)"),
            ("max_match_runs", 2 <= self.max_match_runs <= 100000, "in 2..100000"),
            ("max_families", 0 <= self.max_families <= 1000, "in 0..1000"),
            ("min_sweep_length", self.min_sweep_length >= 0, ">= 0"),
            ("patch_overlap", 0 < self.patch_overlap <= 1, "in (0, 1]"),
            ("profile_fit_tolerance", 0 <= self.profile_fit_tolerance <= 0.1, "in [0, 0.1] (bounding-box diameters)"),
            ("max_parts", _whole(self.max_parts) and 0 <= self.max_parts <= 64, "a whole number in 0..64"),
            ("part_candidates", _whole(self.part_candidates) and 1 <= self.part_candidates <= 1024,
             "a whole number in 1..1024"),
            ("part_min_points", _whole(self.part_min_points) and self.part_min_points >= 1, "a whole number >= 1"),
            ("part_margin", _real(self.part_margin) and 0 <= self.part_margin <= 0.5,
             "in [0, 0.5] (bounding-box diameters)"),
            ("part_l_min", _real(self.part_l_min) and 0 < self.part_l_min <= 10, "in (0, 10] (bounding-box diameters)"),
            ("part_slices", _whole(self.part_slices) and 1 <= self.part_slices <= 16, "a whole number in 1..16"),
            ("part_blocks", _whole(self.part_blocks) and 1 <= self.part_blocks <= 16, "a whole number in 1..16"),
            ("part_grow", isinstance(self.part_grow, bool), "true or false"),
            ("part_profile_cuts", _whole(self.part_profile_cuts) and 0 <= self.part_profile_cuts <= 256,
             "a whole number in 0..256"),
            ("part_trim_spacing", _real(self.part_trim_spacing) and 0.5 <= self.part_trim_spacing <= 8,
             "in [0.5, 8] (multiples of eps_prox)"),
            ("part_mean_error", _real(self.part_mean_error) and 0 < self.part_mean_error <= 1,
             "in (0, 1] (a share of eps_prox)"),
            ("part_across", _real(self.part_across) and 0 <= self.part_across <= 0.2, "in [0, 0.2] (a sine)"),
            ("coverage_samples", _whole(self.coverage_samples) and 0 <= self.coverage_samples <= 10_000_000,
             "a whole number in 0..10000000"),
            ("mirror", isinstance(self.mirror, bool), "true or false"),
            ("mirror_share", _real(self.mirror_share) and 0.5 <= self.mirror_share <= 1,
             "in [0.5, 1] (a share of the area)"),
            ("mirror_planes", _whole(self.mirror_planes) and 0 <= self.mirror_planes <= 3, "a whole number in 0..3"),
            ("arc_axes", _whole(self.arc_axes) and 0 <= self.arc_axes <= 256, "a whole number in 0..256"),
            ("arc_crease", _real(self.arc_crease) and 0 < self.arc_crease < 180, "in (0, 180) (degrees)"),
            ("arc_fit", _real(self.arc_fit) and 0 < self.arc_fit <= 1, "in (0, 1] (a share of eps_prox)"),
            ("arc_sweep_length", _real(self.arc_sweep_length) and self.arc_sweep_length >= 0, ">= 0"),
            ("arc_min_area", _real(self.arc_min_area) and 0 <= self.arc_min_area <= 1, "in [0, 1]"),
            ("arc_flat", isinstance(self.arc_flat, bool), "true or false"),
            ("arc_rings", _whole(self.arc_rings) and 0 <= self.arc_rings <= 64, "a whole number in 0..64"),
            ("arc_ring_fit", _real(self.arc_ring_fit) and 0 < self.arc_ring_fit <= 1,
             "in (0, 1] (a share of eps_prox)"),
        ]
        for name, ok, want in checks:
            if not ok:
                raise GeometryError(f"sweep parameter {name} = {getattr(self, name)!r}: expected {want}")

    @property
    def angle0(self) -> float:
        """First round's half-width of the refinement box in normal angle (degrees)."""
        return self.refine_angle if self.refine_angle is not None else 31.7 / self.sphere_frequency

    @property
    def offset0(self) -> float:
        """First round's half-width of the refinement box in offset."""
        return self.refine_offset if self.refine_offset is not None else self.offset_spacing / 2

    def with_(self, **changes: Any) -> "SweepParams":
        """A copy with some fields changed (validated again)."""
        known = {f.name for f in fields(self)}
        bad = sorted(set(changes) - known)
        if bad:
            raise GeometryError(f"unknown sweep parameter(s) {', '.join(bad)}; known: {', '.join(sorted(known))}")
        return replace(self, **changes)

    #: The lengths measured along a cut (a profile's arc length) that :meth:`with_scale` scales.
    PROFILE_LENGTHS = ("l_min", "gap", "match_spacing", "curvature_window", "coarse_window", "part_l_min")

    def with_scale(self, factor: float) -> "SweepParams":
        """A copy for profiles ``factor`` times as long: the lengths along a cut scaled, curvature floor inverse.

        Every length measured along a cut (:attr:`PROFILE_LENGTHS`: ``l_min``, ``gap``,
        ``match_spacing``, ``curvature_window``, ``coarse_window``, ``part_l_min``) is multiplied
        by ``factor`` and ``kappa_floor`` divided by it, so that a profile ``factor`` times the
        size of the defaults' (a thin member's cross-section: its cut loop is 6-12 % of the
        member's diameter, under the default ``l_min`` of 20 %) is matched as the defaults match
        theirs. Tolerances (``eps_prox``), plane spacings and path lengths are kept.

        Parameters
        ----------
        factor : float
            In (0, 1]; 1 gives an equal copy.

        Returns
        -------
        SweepParams

        Raises
        ------
        GeometryError
            A factor outside (0, 1].

        Examples
        --------
        >>> p = DEFAULT.with_scale(0.25)
        >>> p.l_min, p.match_spacing, p.kappa_floor
        (0.05, 0.00125, 4.0)
        """
        if not (_real(factor) and 0 < factor <= 1):
            raise GeometryError(f"sweep parameter scale = {factor!r}: expected a factor in (0, 1]")
        f = float(factor)
        changes: dict[str, Any] = {name: getattr(self, name) * f for name in self.PROFILE_LENGTHS}
        changes["kappa_floor"] = self.kappa_floor / f
        return self.with_(**changes)


#: The defaults.
DEFAULT = SweepParams()
