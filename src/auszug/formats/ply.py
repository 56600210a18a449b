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
from auszug.formats._meshcheck import check_count, checked_mesh, parse_errors
from auszug.formats._registry import FileFormat, register
from auszug.formats.mesh_obj import as_mesh, part_colour
from auszug.limits import shown

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
        For a missing header, an unsupported format or property type,
        truncated data, or a mesh that fails the shared checks
        (:mod:`auszug.formats._meshcheck`).
    """
    raw = data.encode() if isinstance(data, str) else bytes(data)
    end = raw.find(b"end_header")
    if not raw.startswith(b"ply") or end < 0:
        raise FormatError("not a PLY file (no 'ply' ... 'end_header')", name)
    nl = raw.find(b"\n", end)
    body = raw[nl + 1:] if nl >= 0 else b""
    fmt, elems = _header(raw[:end].decode("ascii", "replace"), name)
    if fmt not in ("binary_little_endian", "ascii"):
        raise FormatError(f"PLY format {shown(fmt)} is not supported; expected binary_little_endian or ascii", name)
    with parse_errors(name, "malformed PLY data"):
        verts, faces = (_ascii(body, elems, name) if fmt == "ascii" else _binary(body, elems, name))
        if verts is None:
            raise FormatError("PLY file has no vertex element", name)
        if faces is None:
            f = np.empty((0, 3), dtype=np.int64)
        elif isinstance(faces, np.ndarray):
            k = faces.shape[1]
            f = np.concatenate([faces[:, [0, j, j + 1]] for j in range(1, k - 1)]) if k > 3 else faces
        else:  # an index beyond int64 is an OverflowError here
            f = np.asarray([[r[0], r[j], r[j + 1]] for r in faces for j in range(1, len(r) - 1)],
                           dtype=np.int64).reshape(-1, 3)
    return checked_mesh(verts, f, name)


_Elem = tuple[str, int, list[tuple[str, str, str | None]]]


def _header(text: str, name: str) -> tuple[str | None, list[_Elem]]:
    """The format and the elements (name, count, [(property, type, list item type)]) of a header."""
    fmt = None
    elems: list[_Elem] = []
    for no, ln in enumerate(text.splitlines(), 1):
        t = ln.split()
        if not t:
            continue
        if t[0] == "format" and len(t) >= 2:
            fmt = t[1]
        elif t[0] == "element":
            if len(t) != 3 or not t[2].isdigit():
                raise FormatError("'element' needs a name and a count", name, no)
            elems.append((t[1], check_count(f"element {t[1]!r} count", int(t[2]), name), []))
        elif t[0] == "property" and elems:
            ok = len(t) == 5 and t[1] == "list" and t[2] in _TYPES and t[3] in _TYPES
            if not ok and (len(t) != 3 or t[1] not in _TYPES):
                raise FormatError(f"'property' needs a type among {', '.join(_TYPES)} and a name "
                                  "(or 'list', two types and a name)", name, no)
            elems[-1][2].append((t[4], t[2], t[3]) if ok else (t[2], t[1], None))
    for el, _, props in elems:
        if sum(item is not None for _, _, item in props) > 1:
            raise FormatError(f"PLY element {el!r} has more than one list property; expected at most one", name)
        if el == "vertex" and not {"x", "y", "z"} <= {p[0] for p in props}:
            raise FormatError("PLY vertex element needs properties x, y and z", name)
    return fmt, elems


def _ascii(body: bytes, elems: list[_Elem], name: str) -> tuple[Any, Any]:
    toks = body.decode("ascii", "replace").split()
    pos = 0
    verts = faces = None
    for el, count, props in elems:
        rows, lists = [], []
        for _ in range(count):
            row: list[float] = []
            for _name, _type, item in props:
                if pos >= len(toks):
                    raise FormatError(f"PLY data ends inside element {el!r}", name)
                if item is None:
                    row.append(float(toks[pos]))
                    pos += 1
                else:
                    k = int(toks[pos])
                    if k < 0 or pos + 1 + k > len(toks):
                        raise FormatError(f"PLY list of {shown(k)} items in element {el!r} runs past the data",
                                          name)
                    lists.append([int(x) for x in toks[pos + 1:pos + 1 + k]])
                    pos += 1 + k
            rows.append(row)
        if el == "vertex":
            names = [p[0] for p in props if p[2] is None]
            verts = np.array([[r[names.index(a)] for a in "xyz"] for r in rows], dtype=float).reshape(-1, 3)
        elif el == "face":
            faces = lists
    return verts, faces


def _binary(body: bytes, elems: list[_Elem], name: str) -> tuple[Any, Any]:
    off = 0
    verts = faces = None
    for el, count, props in elems:
        fields: list[tuple[str, Any] | tuple[str, Any, tuple[int]]] = []
        list_field = None
        for pname, ptype, item in props:
            if item is None:
                fields.append((f"p_{pname}", _TYPES[ptype]))
                continue
            # a list: a fixed count per element is assumed (triangles); it is checked below
            head = np.dtype(fields).itemsize if fields else 0
            ct, it = np.dtype(_TYPES[ptype]), np.dtype(_TYPES[item])
            if count and off + head + ct.itemsize > len(body):
                raise FormatError(f"PLY data ends inside element {el!r}", name)
            k = int(np.frombuffer(body, dtype=ct, count=1, offset=off + head)[0]) if count else 3
            if not 3 <= k <= 255:
                raise FormatError(f"PLY element {el!r} has lists of {k} items; expected 3 to 255", name)
            fields += [("n", ct), ("i", it, (k,))]
            list_field = pname
        dt = np.dtype(fields)
        if off + dt.itemsize * count > len(body):
            raise FormatError(f"PLY data ends inside element {el!r}", name)
        rec = np.frombuffer(body, dtype=dt, count=count, offset=off)
        off += dt.itemsize * count
        if list_field is not None:
            if count and np.any(rec["n"] != rec["n"][0]):
                raise FormatError("binary PLY faces of mixed sizes are not supported", name)
            if el == "face":
                faces = rec["i"].astype(np.int64)
        elif el == "vertex":
            with np.errstate(invalid="ignore"):  # a signalling NaN; checked_mesh refuses it
                verts = np.stack([rec[f"p_{a}"].astype(float) for a in "xyz"], axis=1)
    return verts, faces


def _write(obj: Any, name: str) -> bytes:
    return dumps(obj, name)


register(FileFormat("ply", (".ply",), "mesh", reader=loads, writer=_write, binary=True))
