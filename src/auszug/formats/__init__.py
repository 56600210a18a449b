"""File formats: one module per format, registered by extension; :func:`load` / :func:`save` dispatch."""

# Each format module registers its extensions when imported. The order is precedence: where
# two formats share an ending (.obj polylines and meshes, .svg views and figures), the one
# registered first is chosen when no kind is asked for, so the import sorter leaves it be.
# isort: off
from auszug.formats import uc as _uc  # noqa: F401  (registers .uc)
from auszug.formats import uc_legacy as _uc_legacy  # noqa: F401  (legacy/v1 .uc, read through .uc)
from auszug.formats import native as _native  # noqa: F401  (registers .json drawings)
from auszug.formats import network_json as _network_json  # noqa: F401  (registers .network.json)
from auszug.formats import obj as _obj  # noqa: F401  (registers .obj polylines)
from auszug.formats import svg as _svg  # noqa: F401  (registers .svg top/side views)
from auszug.formats import figure as _figure  # noqa: F401  (registers .png/.pdf/.svg figures)
from auszug.formats import tracery_json as _tracery_json  # noqa: F401  (registers .tracery.json windows)
from auszug.formats import mesh_obj as _mesh_obj  # noqa: F401  (registers .obj meshes)
from auszug.formats import stl as _stl  # noqa: F401  (registers .stl meshes)
from auszug.formats import ply as _ply  # noqa: F401  (registers .ply meshes)
from auszug.formats import gltf as _gltf  # noqa: F401  (registers .glb/.gltf meshes)
from auszug.formats import dxf as _dxf  # noqa: F401  (registers .dxf: polylines, exact arcs and lines)
from auszug.formats import rhino as _rhino  # noqa: F401  (registers .3dm: exact arcs and lines, else polylines)
from auszug.formats import sketch_svg as _sketch_svg  # noqa: F401  (reads .svg sketches, kind "sketch")
from auszug.formats import sketch_json as _sketch_json  # noqa: F401  (registers .sketch.json sketches)
from auszug.formats import sweeps_json as _sweeps_json  # noqa: F401  (registers .sweeps.json sweep analyses)
# isort: on
from auszug.formats._registry import (
    FileFormat,
    atomic_write,
    atomic_write_all,
    format_for,
    formats,
    kind_of,
    load,
    register,
    save,
    stem,
    suffix_of,
    suffixes,
)

__all__ = ["FileFormat", "atomic_write", "atomic_write_all", "format_for", "formats", "kind_of", "load", "register",
           "save", "stem", "suffix_of", "suffixes"]
