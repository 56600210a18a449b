"""Gothic window tracery: Havemann and Fellner's compass-and-straightedge constructions.

"Generative Parametric Design of Gothic Window Tracery" (Havemann and Fellner
2004) on auszug's exact geometry kernel: pointed arches by their excess,
offsets that keep the centres, the prototype window (outer arch, sub-arches,
the rosette circle from an ellipse, four fillets), rosettes of round and
pointed foils, the pointed trefoil arch, recursion, styles, profiles and
watertight meshes.

Examples
--------
>>> from auszug import tracery
>>> t = tracery.build("fig20b")
>>> sorted({r.group for r in t.regions})
['arch', 'circle', 'fillet', 'rosette', 'sub-arch']
"""

from auszug.tracery._checks import ParameterError
from auszug.tracery._checks import integer as whole_number
from auszug.tracery.arch import PointedArch, apex_height, arch_kind, trefoil_arch
from auszug.tracery.build import build, structure
from auszug.tracery.mesh import Resolution, window_mesh
from auszug.tracery.model import Region, Tracery
from auszug.tracery.network import border_network
from auszug.tracery.profile import Moulding
from auszug.tracery.rosette import foil_radius, rosette
from auszug.tracery.style import Style, builtin_style, builtin_styles, load_style, parse_style, refine, style_data
from auszug.tracery.window import Prototype, WindowParams, prototype

__all__ = [
    "ParameterError",
    "PointedArch",
    "apex_height",
    "arch_kind",
    "trefoil_arch",
    "foil_radius",
    "rosette",
    "WindowParams",
    "Prototype",
    "prototype",
    "Region",
    "Tracery",
    "border_network",
    "Resolution",
    "window_mesh",
    "build",
    "structure",
    "Moulding",
    "Style",
    "builtin_style",
    "builtin_styles",
    "load_style",
    "parse_style",
    "style_data",
    "refine",
    "whole_number",
]
