"""Meshes from curve networks: swept members, minimal-surface faces, printable solids.

Pure numpy/scipy kernels (no I/O); the writers for OBJ, STL, PLY and glTF live
in :mod:`auszug.formats`.
"""

from auszug.meshing.frames import Frames, reference_basis, rmf_angles, sweep_frames
from auszug.meshing.mesh import Mesh, Part, concatenate
from auszug.meshing.profile import Profile, circle, from_dict, from_segments, polygon, rectangle, ribbon, square
from auszug.meshing.sweep import Member, default_size, profile_for, sweep_network, sweep_piece

__all__ = [
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
    "Member",
    "default_size",
    "profile_for",
    "sweep_network",
    "sweep_piece",
]
