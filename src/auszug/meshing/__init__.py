"""Meshes from curve networks: swept members, minimal-surface faces, printable solids.

``meshing.mesh_network(network, meshing.Look(...))`` is the one pipeline from a network to
its mesh (members, faces, solid), used by ``auszug mesh`` and the studio;
The sweep model (:mod:`auszug.meshing.sweepmodel`): one :class:`Profile` of lines and arcs,
moved by :class:`RigidFrames` along a :class:`Path`, is a :class:`Sweep`; members and tracery
mouldings are values of it, and :func:`triangulate_polygon` is the one triangulator.

``meshing.solid.solid(...)`` makes a printable solid (the module is imported here).

Pure numpy/scipy kernels (no I/O); the writers for OBJ, STL, PLY and glTF live
in :mod:`auszug.formats`.
"""

from auszug.meshing.faces import Face, Faces, common_group, network_faces
from auszug.meshing.frames import Frames, reference_basis, rmf_angles, sweep_frames
from auszug.meshing.loops import Loop, NetworkGraph, find_loops, loop_through, network_graph
from auszug.meshing.mesh import Mesh, Part, concatenate
from auszug.meshing.minimal import MinimalSurface, flat_area, minimal_surface
from auszug.meshing.pipeline import Look, MeshResult, faces_of, members_of, mesh_network, profile_of
from auszug.meshing.profile import (
    Profile,
    circle,
    from_dict,
    from_segments,
    polygon,
    rectangle,
    ribbon,
    square,
    triangulate_polygon,
)
from auszug.meshing.solid import Solid, unite
from auszug.meshing.sweep import Member, default_size, profile_for, sweep_network, sweep_piece
from auszug.meshing.sweepmodel import Loft, Path, RigidFrames, Sweep, offset_loft, sweep_grid

__all__ = [
    "Look",
    "MeshResult",
    "mesh_network",
    "profile_of",
    "faces_of",
    "members_of",
    "Face",
    "Faces",
    "common_group",
    "network_faces",
    "Loop",
    "NetworkGraph",
    "find_loops",
    "loop_through",
    "network_graph",
    "MinimalSurface",
    "flat_area",
    "minimal_surface",
    "Frames",
    "reference_basis",
    "rmf_angles",
    "sweep_frames",
    "Mesh",
    "Part",
    "concatenate",
    "Profile",
    "circle",
    "square",
    "rectangle",
    "ribbon",
    "polygon",
    "from_segments",
    "from_dict",
    "triangulate_polygon",
    "Sweep",
    "Path",
    "RigidFrames",
    "Loft",
    "offset_loft",
    "sweep_grid",
    "Member",
    "default_size",
    "profile_for",
    "sweep_network",
    "sweep_piece",
    "Solid",
    "unite",
]
