"""Binary STL (``.stl`` of kind ``"mesh"``): triangles for slicers and 3D printers.

Little-endian: an 80-byte header, the triangle count, then per triangle its
unit normal and three corners as float32 and a zero attribute word. Units
are drawing units, z up. STL has no shared vertices and no parts; the reader
merges identical corners again, so a watertight mesh reads back watertight.
ASCII STL is read too.
"""

from __future__ import annotations

import struct
from typing import Any

import numpy as np

from auszug.errors import FormatError
from auszug.formats._meshcheck import check_count, check_points, checked_mesh
from auszug.formats._registry import FileFormat, register
from auszug.formats.mesh_obj import as_mesh

__all__ = ["dumps", "loads"]

_TRI = np.dtype([("normal", "<f4", (3,)), ("v", "<f4", (3, 3)), ("attr", "<u2")])
HEADER = b"auszug mesh, binary STL, z up"


def dumps(obj: Any, name: str = "") -> bytes:
    """Binary STL bytes of a mesh or solid.

    Examples
    --------
    >>> from auszug.meshing.mesh import Mesh
    >>> data = dumps(Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]))
    >>> len(data), loads(data).n_faces
    (134, 1)
    """
    from auszug.meshing.mesh import triangle_normals

    mesh = as_mesh(obj)
    rec = np.zeros(mesh.n_faces, dtype=_TRI)
    rec["normal"] = triangle_normals(mesh.vertices, mesh.faces)
    rec["v"] = mesh.vertices[mesh.faces]
    head = HEADER.ljust(80, b" ")
    return head + struct.pack("<I", mesh.n_faces) + rec.tobytes()


def loads(data: bytes | str, name: str = "<bytes>") -> Any:
    """Read binary or ASCII STL; identical corners become one vertex.

    Raises
    ------
    FormatError
        For a truncated file, a count that does not match its size, or a
        mesh that fails the shared checks (:mod:`auszug.formats._meshcheck`).
    """
    from auszug.meshing.mesh import weld

    raw = data.encode() if isinstance(data, str) else bytes(data)
    if len(raw) < 84:
        if raw.lstrip().startswith(b"solid"):
            return _ascii(raw.decode("utf-8", "replace"), name)
        raise FormatError(f"too short for an STL file ({len(raw)} bytes)", name)
    (n,) = struct.unpack("<I", raw[80:84])
    if len(raw) != 84 + 50 * n:
        if raw.lstrip().startswith(b"solid"):
            return _ascii(raw.decode("utf-8", "replace"), name)
        raise FormatError(f"binary STL says {n} triangles but has {(len(raw) - 84) / 50:g}", name)
    check_count("triangle count", n, name)
    rec = np.frombuffer(raw, dtype=_TRI, count=n, offset=84)
    v = rec["v"].astype(float).reshape(-1, 3)
    check_points(v, name)  # finite, within the limit, before welding
    vv, ff = weld(v, np.arange(3 * n).reshape(-1, 3))
    return checked_mesh(vv, ff, name)


def _ascii(text: str, name: str) -> Any:
    from auszug.meshing.mesh import weld

    pts = []
    for no, ln in enumerate(text.splitlines(), 1):
        t = ln.split()
        if t and t[0] == "vertex":
            try:
                if len(t) != 4:
                    raise ValueError
                pts.append([float(x) for x in t[1:4]])
            except ValueError:
                raise FormatError("'vertex' needs 3 numbers", name, no) from None
    if len(pts) % 3:
        raise FormatError(f"{len(pts)} vertices do not make whole triangles", name)
    check_count("triangle count", len(pts) // 3, name)
    v = np.asarray(pts, dtype=float).reshape(-1, 3)
    check_points(v, name)
    vv, ff = weld(v, np.arange(len(v)).reshape(-1, 3))
    return checked_mesh(vv, ff, name)


def _write(obj: Any, name: str) -> bytes:
    return dumps(obj, name)


register(FileFormat("stl", (".stl",), "mesh", reader=loads, writer=_write, binary=True))
