"""Sketch lifting: True2Form (Xu, Chang, Sheffer, Bousseau, McCrae, Singh, SIGGRAPH 2014).

From a single-view 2D design sketch (strokes as cubic Beziers, occlusion and
flip markers) to the 3D curve network it depicts, by optimising sketch
fidelity subject to regularity cues detected by progressive selective
regularisation. The result is the project's one curve network
(:class:`~auszug.geometry.network.CurveNetwork`). Pure numpy/scipy: no file
I/O (SVG sketches are read by :mod:`auszug.formats.sketch_svg`). See
docs/lifting.md.
"""

from auszug.lifting.fit import fit_polyline
from auszug.lifting.params import CLOSE_GAPS_MAX, DEFAULT, LiftParams
from auszug.lifting.reconstruct import (
    CLASSES,
    DEFAULT_CLASSES,
    CueResult,
    LiftResult,
    Stage,
    depth_sign_score,
    from_above,
    junction_hints,
    layer_graphs,
    lift,
    lift_graph,
    vertical_planes,
)
from auszug.lifting.sketch import (
    Crossing,
    Gap,
    Junction,
    Marker,
    Sketch,
    SketchGraph,
    Stroke,
    near_junctions,
    sketch_graph,
)

__all__ = [
    "CLASSES",
    "DEFAULT_CLASSES",
    "CueResult",
    "LiftResult",
    "Stage",
    "depth_sign_score",
    "from_above",
    "junction_hints",
    "layer_graphs",
    "lift",
    "lift_graph",
    "vertical_planes",
    "DEFAULT",
    "CLOSE_GAPS_MAX",
    "LiftParams",
    "Crossing",
    "Gap",
    "Junction",
    "Marker",
    "Sketch",
    "SketchGraph",
    "Stroke",
    "sketch_graph",
    "near_junctions",
    "fit_polyline",
]
