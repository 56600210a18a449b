"""Pure numpy geometry kernel: lines, arcs, Beziers, intersections, symmetry, reverse curves.

No I/O, no printing, no global state beyond the tolerances in :data:`TOL`.
"""

from auszug.geometry._tolerance import TOL, Tolerances, tolerances
from auszug.geometry.arc import Arc, arc_from_tangent, arc_through
from auszug.geometry.bezier import CubicBezier
from auszug.geometry.curve import Curve, cross2, rot90
from auszug.geometry.intersect import Intersection, intersect, intersect_many
from auszug.geometry.line import Line
from auszug.geometry.offset import OffsetCurves, offset_curves
from auszug.geometry.reverse import (
    ReverseCurve,
    equal_radius_reverse_curve,
    prc_locus,
    reverse_curve_from_radius,
    reverse_curve_through,
    turning_angle,
    winds,
)
from auszug.geometry.symmetry import SymmetryGroup

__all__ = [
    "TOL",
    "Tolerances",
    "tolerances",
    "Curve",
    "Line",
    "Arc",
    "CubicBezier",
    "arc_from_tangent",
    "arc_through",
    "cross2",
    "rot90",
    "Intersection",
    "intersect",
    "intersect_many",
    "OffsetCurves",
    "offset_curves",
    "SymmetryGroup",
    "ReverseCurve",
    "prc_locus",
    "reverse_curve_through",
    "reverse_curve_from_radius",
    "equal_radius_reverse_curve",
    "turning_angle",
    "winds",
]
