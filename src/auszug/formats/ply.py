"""PLY meshes (``.ply`` of kind ``"mesh"``): binary little-endian, with vertex colours.

Vertices as float32 ``x y z`` plus ``red green blue`` (uchar, the part's
colour: its basic curve's for members), faces as a ``uchar`` count and three
``int`` indices. z is up. The reader takes binary little-endian and ASCII
files with at least ``x y z`` and triangle or polygon faces.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from auszug.errors import FormatError
from auszug.formats._registry import FileFormat, register
from auszug.formats.mesh_obj import as_mesh, part_colour

__all__ = ["dumps", "loads"]

_VERT = np.dtype([("p", "<f4", (3,)), ("c", "u1", (3,))])
_FACE = np.dtype([("n", "u1"), ("i", "<i4", (3,))])


def dumps(obj: Any, name: str = "") -> bytes:
    """Binary PLY bytes of a mesh or solid.

    Examples
    --------
    >>> from auszug.meshing.mesh import Mesh
    >>> m = loads(dumps(Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])))
    >>> m.n_vertices, m.n_faces
    (3, 1)
    """
    mesh = as_mesh(obj)
    vr = np.zeros(mesh.n_vertices, dtype=_VERT)
    vr["p"] = mesh.vertices
    rgb = np.full((mesh.n_vertices, 3), 200, dtype=np.uint8)
    for p in mesh.parts:
        rgb[p.vertices[0]:p.vertices[1]] = np.round(np.asarray(part_colour(p)) * 255).astype(np.uint8)
    vr["c"] = rgb
    fr = np.zeros(mesh.n_faces, dtype=_FACE)
    fr["n"] = 3
    fr["i"] = mesh.faces
    head = (
        "ply\nformat binary_little_endian 1.0\ncomment auszug mesh, z up\n"
        f"element vertex {mesh.n_vertices}\nproperty float x\nproperty float y\nproperty float z\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\n"
        f"element face {mesh.n_faces}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    return head.encode("ascii") + vr.tobytes() + fr.tobytes()


_TYPES = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1", "short": "<i2", "int16": "<i2",
          "ushort": "<u2", "uint16": "<u2", "int": "<i4", "int32": "<i4", "uint": "<u4", "uint32": "<u4",
          "float": "<f4", "float32": "<f4", "double": "<f8", "float64": "<f8"}


def loads(data: bytes | str, name: str = "<bytes>") -> Any:
    """Read a PLY mesh (binary little-endian or ASCII).

    Raises
    ------
    FormatError
        For a missing header, an unsupported format, or truncated data.
    """
    from auszug.meshing.mesh import Mesh

    raw = data.encode() if isinstance(data, str) else bytes(data)
    end = raw.find(b"end_header")
    if not raw.startswith(b"ply") or end < 0:
        raise FormatError("not a PLY file (no 'ply' ... 'end_header')", name)
    nl = raw.find(b"\n", end)
    body = raw[nl + 1:]
    fmt = None
    elems: list[tuple[str, int, list[tuple[str, str, str | None]]]] = []
    for ln in raw[:end].decode("ascii", "replace").splitlines():
        t = ln.split()
        if not t:
            continue
        if t[0] == "format":
            fmt = t[1]
        elif t[0] == "element":
            elems.append((t[1], int(t[2]), []))
        elif t[0] == "property" and elems:
            if t[1] == "list":
                elems[-1][2].append((t[4], t[2], t[3]))
            else:
                elems[-1][2].append((t[2], t[1], None))
    if fmt not in ("binary_little_endian", "ascii"):
        raise FormatError(f"PLY format {fmt!r} is not supported; expected binary_little_endian or ascii", name)
    verts = faces = None
    if fmt == "ascii":
        toks = body.decode("ascii", "replace").split()
        pos = 0
        for el, count, props in elems:
            rows = []
            for _ in range(count):
                row = []
                for _name, _type, item in props:
                    if item is None:
                        row.append(float(toks[pos]))
                        pos += 1
                    else:
                        k = int(toks[pos])
                        row.extend(int(x) for x in toks[pos + 1:pos + 1 + k])
                        pos += 1 + k
                rows.append(row)
            if el == "vertex":
                names = [p[0] for p in props]
                verts = np.array([[r[names.index(a)] for a in "xyz"] for r in rows], dtype=float)
            elif el == "face":
                faces = rows
    else:
        off = 0
        for el, count, props in elems:
            if any(item is not None for _, _, item in props):
                # faces: assume a fixed count per list (triangles); check it
                (pname, cnt_t, item_t), = [p for p in props if p[2] is not None]
                assert item_t is not None
                ct = np.dtype(_TYPES[cnt_t])
                it = np.dtype(_TYPES[item_t])
                k = int(np.frombuffer(body, dtype=ct, count=1, offset=off)[0]) if count else 3
                dt = np.dtype([("n", ct), ("i", it, (k,))])
                rec = np.frombuffer(body, dtype=dt, count=count, offset=off)
                if count and np.any(rec["n"] != k):
                    raise FormatError("binary PLY faces of mixed sizes are not supported", name)
                off += dt.itemsize * count
                if el == "face":
                    faces = rec["i"].astype(np.int64)
            else:
                dt = np.dtype([(p[0], _TYPES[p[1]]) for p in props])
                if off + dt.itemsize * count > len(body):
                    raise FormatError(f"PLY data ends inside element {el!r}", name)
                rec = np.frombuffer(body, dtype=dt, count=count, offset=off)
                off += dt.itemsize * count
                if el == "vertex":
                    verts = np.stack([rec[a].astype(float) for a in "xyz"], axis=1)
    if verts is None:
        raise FormatError("PLY file has no vertex element", name)
    if faces is None:
        f = np.empty((0, 3), dtype=np.int64)
    elif isinstance(faces, np.ndarray):
        k = faces.shape[1]
        f = np.concatenate([faces[:, [0, j, j + 1]] for j in range(1, k - 1)]) if k > 3 else faces
    else:
        f = np.asarray([[r[0], r[j], r[j + 1]] for r in faces for j in range(1, len(r) - 1)],
                       dtype=np.int64).reshape(-1, 3)
    return Mesh(verts, f)


def _write(obj: Any, name: str) -> bytes:
    return dumps(obj, name)


register(FileFormat("ply", (".ply",), "mesh", reader=loads, writer=_write, binary=True))
