"""Meshes, loops and exports of the studio: what ``get_mesh``, ``get_loops`` and ``export`` answer.

Pure functions of a network (no networking, no document state); the server
runs them in a worker thread. A request's style, faces, size and segments
become one :class:`~auszug.meshing.Look` (:func:`look`), and the meshes come
from the pipeline ``auszug mesh`` uses too (:mod:`auszug.meshing.pipeline`).
Members are sent the way the geometry is: each
basic piece swept once (:func:`~auszug.meshing.sweep.sweep_piece`), with the
4x4 transforms of the replicas :func:`~auszug.meshing.sweep.sweep_network`
emits for it, so the client instances it. Instancing gives exactly the
vertex positions of ``sweep_network``'s mesh; ``sweep_network`` also reverses
the triangles of mirrored replicas (their transform has determinant -1), which
a client instancing a mirrored matrix must do itself (or draw double-sided).
Faces come as one extra piece (``basic`` -1, the identity transform).

The binary frame of a mesh or loops reply is little-endian 4-byte values:
float32 for positions, boundaries and transforms, uint32 for indices;
``ArrayRef.offset`` counts 4-byte values from the frame's start.
"""

from __future__ import annotations

import re
from pathlib import PurePosixPath
from typing import Any, Literal, Sequence

import numpy as np
from numpy.typing import NDArray

from auszug._cache import LruCache
from auszug.errors import AuszugError
from auszug.limits import LIMITS
from auszug.microarch.network import Network
from auszug.studio import protocol as P

__all__ = ["MAX_AROUND", "MAX_SEGMENTS", "MIN_AROUND", "MIMES", "Payload", "look", "mesh_message", "loops_message",
           "export_file", "loops_of"]

#: Largest ``segments`` a client may ask for (a sweep grows linearly with it).
MAX_SEGMENTS = LIMITS.mesh_segments  # the limits live in auszug.limits
#: Fewest and most points around a member's profile a client may ask for (``around``).
MIN_AROUND, MAX_AROUND = 3, LIMITS.tube_around
#: MIME type of every export format.
MIMES: dict[str, str] = {
    "glb": "model/gltf-binary",
    "obj": "model/obj",
    "stl": "model/stl",
    "ply": "application/octet-stream",
    "svg": "image/svg+xml",
    "json": "application/json",
    "uc": "text/plain",
    "network.json": "application/json",
    "dxf": "image/vnd.dxf",
    "3dm": "application/octet-stream",
}
MESH_EXPORTS = ("glb", "obj", "stl", "ply")
_COLOUR = re.compile(r"^#[0-9a-fA-F]{6}$")
_IDENTITY = np.eye(4).reshape(1, 16)


class StudioMeshError(AuszugError, ValueError):
    """A mesh, loops or export request that cannot be carried out (bad style, loop index, ...)."""


class Payload:
    """A binary frame being assembled from float32 and uint32 arrays (4 bytes per value)."""

    def __init__(self) -> None:
        self.chunks: list[bytes] = []
        self.size = 0   # in 4-byte values

    def put(self, a: Any, dtype: Literal["f4", "u4"] = "f4") -> P.ArrayRef:
        """Append ``a`` as little-endian ``dtype`` ("f4" or "u4"); its reference into the frame."""
        arr = np.ascontiguousarray(a, dtype="<f4" if dtype == "f4" else "<u4")
        ref = P.ArrayRef(offset=self.size, shape=list(arr.shape), dtype=dtype)
        self.chunks.append(arr.tobytes())
        self.size += arr.size
        return ref

    def bytes(self) -> bytes:
        """The frame."""
        return b"".join(self.chunks)


# ---------------------------------------------------------------- caches (per network object)

#: Loops and faces computed per network object (entries hold the network, so its id stays unique).
_LOOPS = LruCache(16)
_FACES = LruCache(8)


def loops_of(net: Network) -> list:
    """The loops :func:`~auszug.meshing.find_loops` finds in ``net`` (computed once per network).

    Their order is the one ``get_loops`` reports and ``get_mesh(faces="picked", loops=[...])`` uses.
    """
    from auszug.meshing import find_loops

    hit = _LOOPS.get(id(net))
    if hit is not None and hit[0] is net:
        return hit[1]
    loops = find_loops(net) if net.pieces else []
    _LOOPS.put(id(net), (net, loops))
    return loops


def _faces(net: Network, mode: str, picked: Sequence[int]) -> Any:  # Faces or None
    """The faces of a request (``none``, ``auto``, ``picked`` loop indices), computed once per network."""
    from auszug.meshing import Look, faces_of

    if mode == "none":
        return None
    if mode not in ("auto", "picked"):
        raise StudioMeshError(f"faces must be none, auto or picked, got {mode!r}")
    key = (id(net), mode, tuple(picked) if mode == "picked" else ())
    hit = _FACES.get(key)
    if hit is not None and hit[0] is net:
        return hit[1]
    if mode == "auto":
        faces = faces_of(net, Look("curves", faces="auto"))
    else:
        loops = loops_of(net)
        bad = [i for i in picked if not 0 <= i < len(loops)]
        if bad:
            raise StudioMeshError(f"no loop {bad[0]}: the drawing has {len(loops)} loops (ask get_loops)")
        faces = faces_of(net, Look("curves", faces=tuple(loops[i] for i in picked))) if picked else None
    _FACES.put(key, (net, faces))
    return faces


def _check_segments(segments: int) -> int:
    if not 1 <= segments <= MAX_SEGMENTS:
        raise StudioMeshError(f"segments must lie in 1..{MAX_SEGMENTS}, got {segments}")
    return segments


def look(net: Network, *, style: str, faces: str = "none", loops: Sequence[int] = (), size: float | None = None,
         segments: int | None = None, solid: bool = False, around: int | None = None) -> Any:  # a meshing.Look
    """The :class:`~auszug.meshing.Look` of a ``get_mesh`` or ``export`` request, checked.

    Size, segments and around count only for members (the ``curves`` style
    ignores them); segments are at most :data:`MAX_SEGMENTS`, around (points
    round the profile) :data:`MIN_AROUND` .. :data:`MAX_AROUND`.

    Raises
    ------
    StudioMeshError
        For what :class:`~auszug.meshing.Look` refuses, too many segments, no
        default size, or a loop index that ``get_loops`` did not report.
    """
    from auszug.errors import GeometryError
    from auszug.meshing import Look, profile_of

    members = style != "curves"
    if members and segments is not None:
        _check_segments(segments)
    if members and around is not None and not MIN_AROUND <= around <= MAX_AROUND:
        raise StudioMeshError(f"around (points round a member's profile) must lie in {MIN_AROUND}..{MAX_AROUND}, "
                              f"got {around}")
    fs: Any = "none"
    if faces == "auto":
        fs = "auto"
    elif faces == "picked":
        all_loops = loops_of(net)
        fs = tuple(all_loops[i] for i in loops if 0 <= i < len(all_loops)) or "none"
    try:
        lk = Look(style, size=size if members else None, faces=fs, segments=segments if members else None,
                  solid=solid, around=around if members else None)
        profile_of(net, lk)   # no default size for a drawing without extent
    except GeometryError as e:
        raise StudioMeshError(str(e)) from None
    return lk


def _transforms(net: Network, basic: int, replicas: Sequence[int]) -> NDArray[np.float64]:
    from auszug.studio.session import replica_transforms

    return replica_transforms(net.drawing, basic)[list(replicas)]


def members(net: Network, style: str, size: float | None, segments: int) -> list:
    """Every swept basic piece (:class:`~auszug.meshing.sweep.Member`, not replicated)."""
    from auszug.meshing import members_of

    return members_of(net, look(net, style=style, size=size, segments=segments))


def _member_name(net: Network, mb: Any) -> str:
    p = net.pieces[mb.piece]
    return f"{mb.basic}/{p.kind}{p.segment if p.segment >= 0 else ''}"


def mesh_message(net: Network, *, style: str, faces: str, loops: Sequence[int], size: float | None,
                 segments: int, revision: int = 0, msg_id: int = 0) -> tuple[P.MeshGeometry, bytes]:
    """The :class:`~auszug.studio.protocol.MeshGeometry` of ``net`` and its binary frame.

    Raises
    ------
    StudioMeshError
        For an unknown style or faces mode, a bad size or segment count, or a
        loop index that ``get_loops`` did not report.
    """
    from auszug.meshing import members_of

    lk = look(net, style=style, size=size, segments=segments)   # check before any work
    fs = _faces(net, faces, loops)
    out = Payload()
    pieces = []
    for mb in members_of(net, lk):
        pieces.append(P.MeshPiece(
            basic=mb.basic, name=_member_name(net, mb), positions=out.put(mb.vertices),
            indices=out.put(mb.faces, "u4"), transforms=out.put(_transforms(net, mb.basic, mb.replicas))))
    n_faces, converged, residual = 0, True, 0.0
    if fs is not None and fs.faces:
        m = fs.mesh()
        pieces.append(P.MeshPiece(basic=-1, name="faces", positions=out.put(m.vertices),
                                  indices=out.put(m.faces, "u4"), transforms=out.put(_IDENTITY)))
        n_faces, converged, residual = len(fs.faces), bool(fs.converged), float(fs.residual)
    msg = P.MeshGeometry(revision=revision, style=style, pieces=pieces, faces=n_faces, converged=converged,
                         residual=residual, binary_floats=out.size, id=msg_id)
    return msg, out.bytes()


def loops_message(net: Network, *, revision: int = 0, msg_id: int = 0,
                  resolution: int = 96) -> tuple[P.Loops, bytes]:
    """The :class:`~auszug.studio.protocol.Loops` of ``net`` (boundaries as (n, 3) float32) and its frame."""
    out = Payload()
    infos = []
    for i, lp in enumerate(loops_of(net)):
        b, _ = lp.boundary(resolution)
        infos.append(P.LoopInfo(index=i, boundary=out.put(b), centre=[float(v) for v in b.mean(axis=0)],
                                rim=bool(lp.has_rim)))
    return P.Loops(revision=revision, loops=infos, binary_floats=out.size, id=msg_id), out.bytes()


def _stem(name: str) -> str:
    """The drawing's name without the ending of any registered format (``tn-2.uc`` -> ``tn-2``)."""
    from auszug.formats import stem, suffix_of

    base = PurePosixPath(name).name or "drawing"
    return stem(base) if suffix_of(base) else base


def _parse_colours(colors: Sequence[str]) -> list[tuple[float, float, float]]:
    out = []
    for i, c in enumerate(colors):
        if not isinstance(c, str) or not _COLOUR.match(c):
            raise StudioMeshError(f"colors[{i}]: expected #rrggbb, got {c!r}")
        r, g, b = (int(c[k:k + 2], 16) / 255.0 for k in (1, 3, 5))
        out.append((r, g, b))
    return out


def _glb(mesh: Any, colours: list[tuple[float, float, float]]) -> bytes:
    """GLB bytes of ``mesh`` with the members of basic curve i in ``colours[i]`` (others unchanged)."""
    from auszug.formats.gltf import dumps_glb, pack_glb, to_gltf

    if not colours:
        return dumps_glb(mesh)
    doc, binary = to_gltf(mesh)
    for node in doc.get("nodes", []):
        b = node.get("extras", {}).get("basic")
        if b is not None and 0 <= b < len(colours) and "mesh" in node:
            mat = doc["meshes"][node["mesh"]]["primitives"][0]["material"]
            doc["materials"][mat]["pbrMetallicRoughness"]["baseColorFactor"][:3] = list(colours[b])
    return pack_glb(doc, binary)


def export_file(net: Network, name: str, *, format: str, style: str = "bar", faces: str = "none",
                loops: Sequence[int] = (), solid: bool = False, colors: Sequence[str] = (),
                segments: int | None = None, around: int | None = None) -> tuple[str, str, bytes]:
    """Export ``net`` (whose drawing is called ``name``): (suggested file name, MIME type, bytes).

    Mesh formats (glb, obj, stl, ply) sweep the members in ``style`` with
    ``segments`` steps (default 200, 64 for a solid) and ``around`` points round the
    profile (default 40 for tubes, 4 otherwise; see :func:`look`) and add the faces;
    ``solid`` unites everything into one watertight solid. ``colors`` (#rrggbb per
    basic curve) colour the glb's members; OBJ is sent without its .mtl (one file
    per export), so it carries no colours; STL and PLY have none. svg: top and side
    views; json / uc: the drawing; network.json: the 3D curve network; dxf / 3dm:
    the curve network for CAD programs, with exact arcs and lines where the curves
    have them. The curve exports (svg, network.json, dxf, 3dm) are sampled to the
    default tolerance (1e-6 of the bounding-box diagonal, every feature point a
    vertex).

    Raises
    ------
    StudioMeshError
        For an unknown format or style, nothing to export, or a bad colour.
    FormatError
        If the format cannot hold the drawing (e.g. a .uc of a feature the web format lacks).
    """
    from pathlib import Path

    from auszug.formats import format_for

    if format not in MIMES:
        raise StudioMeshError(f"format must be one of {', '.join(MIMES)}, got {format!r}")
    colours = _parse_colours(colors)
    fname = f"{_stem(name)}.{format}"
    if format in MESH_EXPORTS:
        mesh = _export_mesh(net, style, faces, loops, solid, segments, around)
        if format == "glb":
            data: bytes | str = _glb(mesh, colours)
        else:
            fmt = format_for(Path(fname), "mesh", want="write")
            data = fmt.write(mesh, fname)
    elif format in ("svg", "dxf", "3dm", "network.json"):
        from auszug.formats.network_json import NetworkFile

        # curve exports are exact to the default tolerance, as `auszug build` writes them
        exact = net.with_intersections().resampled() if net.pieces else net
        data = format_for(Path(fname), "network", want="write").write(NetworkFile(exact, name), fname)
    else:
        data = format_for(Path(fname), "drawing", want="write").write(net.drawing, fname)
    raw = data.encode("utf-8") if isinstance(data, str) else bytes(data)
    return fname, MIMES[format], raw


def _export_mesh(net: Network, style: str, faces: str, loops: Sequence[int], solid: bool,
                 segments: int | None, around: int | None = None) -> Any:  # a Mesh
    from auszug.meshing import mesh_network

    fs = _faces(net, faces, loops)
    if style == "curves" and not solid and (fs is None or not fs.faces):
        raise StudioMeshError("nothing to export: style curves without faces makes no mesh")
    lk = look(net, style=style, faces=faces, loops=loops, segments=segments or None, solid=solid, around=around)
    if lk.members and not net.pieces:
        raise StudioMeshError("nothing to export: the drawing has no curves")
    return mesh_network(net, lk, faces=fs).mesh
