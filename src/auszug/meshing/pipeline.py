"""The mesh pipeline: a network and a :class:`Look` -> members, faces and solid, in one place.

``auszug mesh`` and the studio (its ``get_mesh`` and ``export`` answers) both
turn a network into a mesh through these functions, so a look means the same
mesh everywhere and is validated once, in :class:`Look`:

- :func:`profile_of`: the members' cross-section (None for the ``"curves"`` look);
- :func:`faces_of`: the minimal-surface faces the look asks for (None for none);
- :func:`members_of`: every swept basic piece, not replicated (for clients
  that instance the replicas, like the studio's 3D view);
- :func:`mesh_network`: the whole mesh (members replicated, plus faces), or
  with ``solid`` one watertight solid, as a :class:`MeshResult`.

Examples
--------
>>> from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry, build
>>> c = BasicCurve(((1.0, 0.0), (0.0, 1.0)), (Segment("line"),), ("ground", "apex"),
...                Symmetry(fold=2), height=1.0)
>>> r = mesh_network(build(Drawing((c,))), Look("tube", size=0.04, around=8, segments=16))
>>> [p.name for p in r.parts], r.mesh.is_watertight, r.faces is None, r.solid is None
(['0/r0', '0/r1'], True, True, True)
>>> Look("cable")
Traceback (most recent call last):
...
auszug.errors.GeometryError: style must be one of curves, tube, bar, ribbon, got 'cable'
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal

from auszug.errors import GeometryError
from auszug.geometry.network import as_curve_network
from auszug.meshing._work import check_curves, check_triangles, curve_count, member_triangles
from auszug.meshing.faces import Faces, network_faces
from auszug.meshing.loops import Loop
from auszug.meshing.mesh import Mesh, Part, concatenate
from auszug.meshing.profile import STYLES, Profile
from auszug.meshing.solid import Solid, solid
from auszug.meshing.sweep import Member, default_size, profile_for, sweep_members, sweep_network

__all__ = ["LOOK_STYLES", "FacesMode", "Look", "MeshResult", "profile_of", "faces_of", "members_of",
           "mesh_network"]

#: The named looks: ``"curves"`` (no members) and the built-in member styles.
LOOK_STYLES: tuple[str, ...] = ("curves", *STYLES)
#: Steps along each member: a rendered mesh, a solid.
SEGMENTS, SOLID_SEGMENTS = 200, 64
#: Boundary points per face (at least 12).
RESOLUTION, MIN_RESOLUTION = 96, 12

FacesMode = Literal["none", "auto"]


def _optional_positive(name: str, v: float | None) -> None:
    if v is None:
        return
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v > 0):
        raise GeometryError(f"{name} must be positive (a positive number of drawing units), got {v!r}")


def _whole(name: str, v: Any, minimum: int) -> None:
    if isinstance(v, bool) or not isinstance(v, int) or v < minimum:
        raise GeometryError(f"{name} must be a whole number >= {minimum}, got {v!r}")


@dataclass(frozen=True)
class Look:
    """How a network becomes a mesh; every field is checked here.

    Attributes
    ----------
    style : str or Profile
        ``"curves"`` (no members: only faces), ``"tube"``, ``"bar"``,
        ``"ribbon"`` (see :func:`~auszug.meshing.sweep.profile_for`) or any
        :class:`~auszug.meshing.profile.Profile` in drawing units.
    size : float, optional
        Tube diameter / bar side / ribbon width over 3, in drawing units
        (default :func:`~auszug.meshing.sweep.default_size`). Not for a Profile.
    around : int, optional
        Points around a built-in profile (default 40 for tubes, 4 for bars and ribbons).
    faces : "none", "auto" or sequence of Loop
        No faces, a minimal surface in every loop
        :func:`~auszug.meshing.loops.find_loops` finds, or in these loops.
    resolution : int
        Boundary points per face (>= 12).
    segments : int, optional
        Steps along each member (default 200; 64 for a solid).
    solid : bool
        Unite members, thickened faces (and the base) into one watertight solid.
    thickness : float, optional
        Face thickness in the solid (default half the profile).
    base : bool
        Add a base plate to the solid.

    Raises
    ------
    GeometryError
        Naming the field and what it must be.
    """

    style: str | Profile = "bar"
    size: float | None = None
    around: int | None = None
    faces: FacesMode | tuple[Loop, ...] = "none"
    resolution: int = RESOLUTION
    segments: int | None = None
    solid: bool = False
    thickness: float | None = None
    base: bool = False

    def __post_init__(self) -> None:
        if not isinstance(self.style, Profile) and self.style not in LOOK_STYLES:
            raise GeometryError(f"style must be one of {', '.join(LOOK_STYLES)}, got {self.style!r}")
        _optional_positive("member size", self.size)
        if self.around is not None:
            _whole("points around the profile", self.around, 2)
        if isinstance(self.faces, str):
            if self.faces not in ("none", "auto"):
                raise GeometryError(f"faces must be none, auto or a list of loops, got {self.faces!r}")
        else:
            loops = tuple(self.faces)
            if not all(isinstance(lp, Loop) for lp in loops):
                raise GeometryError("faces must be none, auto or a list of loops (meshing.Loop)")
            object.__setattr__(self, "faces", loops)
        _whole("face resolution", self.resolution, MIN_RESOLUTION)
        if self.segments is not None:
            _whole("segments", self.segments, 1)
        _optional_positive("face thickness", self.thickness)
        if self.solid and self.style == "curves":
            raise GeometryError("a solid needs members: pick the style tube, bar or ribbon")

    @property
    def members(self) -> bool:
        """Whether the look has members (every style but ``"curves"``)."""
        return self.style != "curves"

    @property
    def steps(self) -> int:
        """Steps along each member: ``segments``, else 200 (64 for a solid)."""
        if self.segments is not None:
            return self.segments
        return SOLID_SEGMENTS if self.solid else SEGMENTS


@dataclass(frozen=True, eq=False)
class MeshResult:
    """What :func:`mesh_network` made.

    Attributes
    ----------
    mesh : Mesh
        The members (one part per replica) and faces, or the solid (part ``"solid"``).
    profile : Profile or None
        The members' cross-section (None for the ``"curves"`` look).
    faces : Faces or None
        The faces (None when the look has none).
    solid : Solid or None
        With ``Look.solid``: the united solid (volume, watertight, shells).
    """

    mesh: Mesh
    profile: Profile | None
    faces: Faces | None
    solid: Solid | None

    @property
    def parts(self) -> tuple[Part, ...]:
        """The mesh's named parts."""
        return self.mesh.parts


def profile_of(network: Any, look: Look) -> Profile | None:
    """The members' cross-section of ``look`` on ``network`` (None for ``"curves"``).

    Raises
    ------
    GeometryError
        A size given for a Profile, or no default size (a drawing without extent).
    """
    if isinstance(look.style, Profile):
        if look.size is not None:
            raise GeometryError("a profile has its own size; give size only with tube, bar or ribbon")
        return look.style
    if look.style == "curves":
        return None
    s = look.size if look.size is not None else default_size(network)
    if not s > 0:
        raise GeometryError("the drawing has no extent, so members have no default size; give a size")
    return profile_for(look.style, s, look.around)


def faces_of(network: Any, look: Look) -> Faces | None:
    """The minimal-surface faces ``look`` asks for (None for ``"none"``, or ``"auto"`` without curves)."""
    if look.faces == "none":
        return None
    if look.faces == "auto":
        if not as_curve_network(network).pieces:
            return None
        return network_faces(network, None, resolution=look.resolution)
    return network_faces(network, list(look.faces), resolution=look.resolution)


def members_of(network: Any, look: Look) -> list[Member]:
    """Every swept basic piece of ``look``, not replicated (none for ``"curves"``).

    Replicating them (:func:`~auszug.meshing.sweep.replicate`) gives the members
    of :func:`mesh_network`.
    """
    prof = profile_of(network, look)
    return [] if prof is None else sweep_members(network, prof, look.steps)


def mesh_network(network: Any, look: Look, *, faces: Faces | None = None) -> MeshResult:
    """The mesh of ``network`` in ``look``: members and faces, or one watertight solid.

    Parameters
    ----------
    network : CurveNetwork (or a producer of one, e.g. ``microarch.Network``)
    look : Look
    faces : Faces, optional
        Faces computed already by :func:`faces_of` for this network and look
        (a cache); default: computed here.

    Returns
    -------
    MeshResult

    Raises
    ------
    GeometryError
        As :func:`profile_of`; an open profile for a solid.
    """
    prof = profile_of(network, look)
    if prof is not None and not look.solid:   # solid() checks its own members
        check_triangles(member_triangles(curve_count(network), look.steps, prof.n), "the members",
                        "fewer segments, fewer points around, a lower fold or fewer curves")
    if look.solid:
        check_curves(network, "a solid")    # before the faces, which a solid includes
    fs = faces if faces is not None else faces_of(network, look)
    if look.solid:
        assert prof is not None   # Look refuses a solid without members
        s = solid(network, prof, look.steps, faces=fs, thickness=look.thickness, base=look.base)
        return MeshResult(s.mesh, prof, fs, s)
    parts: list[Mesh] = [] if prof is None else [sweep_network(network, prof, look.steps)]
    if fs is not None and fs.faces:
        parts.append(fs.mesh())
    return MeshResult(concatenate(parts), prof, fs, None)
