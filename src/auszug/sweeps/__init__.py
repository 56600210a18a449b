"""Sweep analysis: which parts of a mesh a planar profile sweeps (Barton, Pottmann, Wallner 2014).

The detection stages, each callable alone, each returning a frozen dataclass:

1. :func:`normalise` the mesh ``(V, F)`` (bounding-box diameter 1) and :func:`cut` it by many
   planes at once (compiled, parallel over planes);
2. :func:`movability` of every cut curve (Eq. 3-5, Alg. 1) and :func:`search_planes`, the coarse
   plane sampling with adaptive refinement (sec. 1.3);
3. :func:`kinematic_axis`: surfaces of revolution, extrusions and helical surfaces, where every cut
   moves, scored by the axis or direction their velocity states agree on;
4. :func:`match_cuts` (sec. 2.1, curvature plots) and :func:`families` of near-congruent cuts
   (sec. 2.2, angle pruning), :func:`order_ribs`;
5. :func:`kinematic_patches` (revolution, extrusion, helical) and :func:`general_patch` (sec. 2.3:
   velocities by Eq. 7, Hermite interpolation of motions, profile improvement, fit check), each
   a :class:`SweepPatch`: profile, :class:`Motion`, faces covered, fit error, coverage.

:func:`detect` runs them all and returns a :class:`SweepReport`. Beyond the paper, every patch's
profile is fitted with exact lines and arcs (:func:`fit_profile`, a :class:`FittedProfile` holding
meshing's :class:`~auszug.meshing.profile.Profile`), so a found moulding can be swept again.

Parameters live in one :class:`SweepParams`. Pure numpy/scipy/numba; no file I/O (meshes are read
by :mod:`auszug.formats`).
"""

from auszug.sweeps.cut import Cuts, cut
from auszug.sweeps.detect import STAGES, Stage, SweepReport, detect, sweep_length
from auszug.sweeps.general import GeneralSweep, general_patch, hermite_motion, kabsch, rib_velocities, rib_velocity
from auszug.sweeps.kinematic import KinematicAxis, axis_angle, kinematic_axis, motion_of
from auszug.sweeps.matching import (
    CurvaturePlots,
    Family,
    Matches,
    Ribs,
    curvature_plots,
    families,
    match_cuts,
    order_energy,
    order_ribs,
    resample,
    signed_curvature,
)
from auszug.sweeps.mesh import SweepMesh, normalise, vertex_normals
from auszug.sweeps.motion import Motion, screw_motion, se3_exp, se3_log
from auszug.sweeps.movability import Movability, movability, velocities, velocity_state
from auszug.sweeps.params import DEFAULT, SweepParams
from auszug.sweeps.patches import Fit, SweepPatch, fit_patch, kinematic_patches, polyline_hausdorff
from auszug.sweeps.planes import geodesic_sphere, hemisphere, initial_planes, plane_recall, refine_box, spacing_for
from auszug.sweeps.profilefit import FittedProfile, ProfileFit, fit_lines_arcs, fit_profile, profile_frame
from auszug.sweeps.search import PlaneSearch, good_planes, search_planes

__all__ = [
    "Cuts",
    "cut",
    "STAGES",
    "Stage",
    "SweepReport",
    "detect",
    "sweep_length",
    "GeneralSweep",
    "general_patch",
    "hermite_motion",
    "kabsch",
    "rib_velocities",
    "rib_velocity",
    "Motion",
    "screw_motion",
    "se3_exp",
    "se3_log",
    "Fit",
    "SweepPatch",
    "fit_patch",
    "kinematic_patches",
    "polyline_hausdorff",
    "KinematicAxis",
    "axis_angle",
    "kinematic_axis",
    "motion_of",
    "CurvaturePlots",
    "Family",
    "Matches",
    "Ribs",
    "curvature_plots",
    "families",
    "match_cuts",
    "order_energy",
    "order_ribs",
    "resample",
    "signed_curvature",
    "SweepMesh",
    "normalise",
    "vertex_normals",
    "Movability",
    "movability",
    "velocities",
    "velocity_state",
    "DEFAULT",
    "SweepParams",
    "FittedProfile",
    "ProfileFit",
    "fit_lines_arcs",
    "fit_profile",
    "profile_frame",
    "geodesic_sphere",
    "hemisphere",
    "initial_planes",
    "plane_recall",
    "refine_box",
    "spacing_for",
    "PlaneSearch",
    "good_planes",
    "search_planes",
]
