"""glTF 2.0 meshes: binary ``.glb`` and embedded ``.gltf`` (kind ``"mesh"``).

The scene has one root node ``auszug`` that turns the model from auszug's
z-up frame into glTF's y-up frame (a rotation by -90 degrees about x; the
vertex data stay z-up). Under it there is one node per basic curve
(``curve 0``, ``curve 1``, ... holding all replicas of that curve's members,
in the curve's colour), and nodes ``faces`` (double-sided, translucent),
``base`` and ``solid`` as present. Each node's ``extras.parts`` lists the
part names (``0/r1m``...) in vertex order with their vertex and index
ranges, so replicas can still be told apart. Positions are float32, indices
uint32; no normals are written, so viewers shade flat (three.js does when a
mesh has none).
"""

from __future__ import annotations

import base64
import json
import struct
from typing import Any

import numpy as np

from auszug.errors import FormatError
from auszug.formats._meshcheck import check_count, checked_mesh, parse_errors
from auszug.formats._registry import FileFormat, register
from auszug.formats.mesh_obj import as_mesh, part_colour
from auszug.limits import shown

__all__ = ["to_gltf", "pack_glb", "dumps_glb", "dumps_gltf", "loads"]

#: Quaternion (x, y, z, w) of the root node: z-up to y-up.
Z_UP_TO_Y_UP = [-0.7071067811865476, 0.0, 0.0, 0.7071067811865476]


def _groups(mesh: Any) -> list[tuple[str, list]]:
    """Parts grouped into nodes: per basic curve for members, then faces, base, solid."""
    from auszug.meshing.mesh import Part

    parts = list(mesh.parts) or [Part("mesh", "solid", -1, "", (0, mesh.n_vertices), (0, mesh.n_faces))]
    groups: dict[str, list] = {}
    for p in parts:
        key = f"curve {p.basic}" if p.kind == "member" else {"face": "faces"}.get(p.kind, p.kind)
        groups.setdefault(key, []).append(p)
    return list(groups.items())


def to_gltf(obj: Any) -> tuple[dict, bytes]:
    """The glTF JSON document and its binary buffer for a mesh or solid."""
    mesh = as_mesh(obj)
    blobs: list[bytes] = []
    offset = 0
    views, accessors, meshes, nodes, materials = [], [], [], [], []

    def add_view(data: bytes, target: int) -> int:
        nonlocal offset
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data), "target": target})
        pad = (-len(data)) % 4
        blobs.append(data + b"\0" * pad)
        offset += len(data) + pad
        return len(views) - 1

    for name, parts in _groups(mesh):
        vs, fs, extras = [], [], []
        nv = ni = 0
        for p in parts:
            v0, v1 = p.vertices
            f0, f1 = p.faces
            vs.append(mesh.vertices[v0:v1])
            fs.append(mesh.faces[f0:f1] - v0 + nv)
            extras.append({"name": p.name, "replica": p.replica, "vertices": [nv, nv + v1 - v0],
                           "indices": [ni, ni + 3 * (f1 - f0)]})
            nv += v1 - v0
            ni += 3 * (f1 - f0)
        if ni == 0:
            continue
        pos = np.ascontiguousarray(np.concatenate(vs), dtype="<f4")
        idx = np.ascontiguousarray(np.concatenate(fs), dtype="<u4")
        pv = add_view(pos.tobytes(), 34962)
        iv = add_view(idx.tobytes(), 34963)
        accessors.append({"bufferView": pv, "componentType": 5126, "count": len(pos), "type": "VEC3",
                          "min": pos.min(0).tolist(), "max": pos.max(0).tolist()})
        accessors.append({"bufferView": iv, "componentType": 5125, "count": int(idx.size), "type": "SCALAR"})
        r, g, b = part_colour(parts[0])
        mat: dict[str, Any] = {"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": [r, g, b, 1.0], "metallicFactor": 0.1, "roughnessFactor": 0.6}}
        if parts[0].kind == "face":
            mat["pbrMetallicRoughness"]["baseColorFactor"][3] = 0.75
            mat["alphaMode"] = "BLEND"
            mat["doubleSided"] = True
        materials.append(mat)
        meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": len(accessors) - 2},
                                                     "indices": len(accessors) - 1,
                                                     "material": len(materials) - 1, "mode": 4}]})
        extra = {"parts": extras}
        if parts[0].kind == "member":
            extra["basic"] = parts[0].basic
        nodes.append({"name": name, "mesh": len(meshes) - 1, "extras": extra})
    root = {"name": "auszug", "rotation": Z_UP_TO_Y_UP, "children": list(range(1, len(nodes) + 1))}
    doc = {
        "asset": {"version": "2.0", "generator": "auszug"},
        "scene": 0,
        "scenes": [{"name": "auszug", "nodes": [0]}],
        "nodes": [root] + [dict(n) for n in nodes],
        "meshes": meshes,
        "materials": materials,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": offset}],
    }
    if not meshes:
        for k in ("meshes", "materials", "accessors", "bufferViews", "buffers"):
            doc.pop(k)
        root.pop("children")
    return doc, b"".join(blobs)


def dumps_glb(obj: Any, name: str = "") -> bytes:
    """Binary glTF (GLB) bytes.

    Examples
    --------
    >>> from auszug.meshing.mesh import Mesh
    >>> data = dumps_glb(Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]))
    >>> data[:4], loads(data).n_faces
    (b'glTF', 1)
    """
    return pack_glb(*to_gltf(obj))


def pack_glb(doc: dict, binary: bytes) -> bytes:
    """A glTF document and its binary buffer as one GLB file (JSON and BIN chunks, 4-byte aligned)."""
    js = json.dumps(doc, separators=(",", ":")).encode("utf-8")
    js += b" " * ((-len(js)) % 4)
    chunks = struct.pack("<I4s", len(js), b"JSON") + js
    if binary:
        chunks += struct.pack("<I4s", len(binary), b"BIN\0") + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def dumps_gltf(obj: Any, name: str = "") -> str:
    """Serialise to glTF JSON text with the buffer embedded as a base64 data URI."""
    doc, binary = to_gltf(obj)
    if "buffers" in doc:
        doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(binary).decode()
    return json.dumps(doc, indent=1)


_COMPONENT = {5126: "<f4", 5125: "<u4", 5123: "<u2", 5121: "u1"}
_WIDTH = {"SCALAR": 1, "VEC3": 3}


def _list(doc: dict, key: str, name: str) -> list:
    v = doc.get(key, [])
    if not isinstance(v, list):
        raise FormatError(f"glTF {key!r} must be a list, got {shown(v)}", name)
    return v


def _item(seq: list, i: Any, what: str, name: str) -> dict:
    if isinstance(i, bool) or not isinstance(i, int) or not 0 <= i < len(seq) or not isinstance(seq[i], dict):
        raise FormatError(f"glTF {what} {shown(i)} does not exist (the file has {len(seq)})", name)
    return seq[i]


def _whole(d: dict, key: str, what: str, name: str, default: int | None = None) -> int:
    v = d.get(key, default)
    if isinstance(v, bool) or not isinstance(v, int) or v < 0:
        raise FormatError(f"glTF {what} {key!r} must be a whole number >= 0, got {shown(v)}", name)
    return v


def _read(doc: Any, binary: bytes, name: str) -> Any:
    from auszug.meshing.mesh import Part

    if not isinstance(doc, dict):
        raise FormatError(f"a glTF document is a JSON object, got {type(doc).__name__}", name)
    views = _list(doc, "bufferViews", name)
    accs = _list(doc, "accessors", name)
    meshes = _list(doc, "meshes", name)

    def arr(i: Any, width: int, kinds: str) -> np.ndarray:
        a = _item(accs, i, "accessor", name)
        v = _item(views, _whole(a, "bufferView", f"accessor {i}", name), "bufferView", name)
        ct, kind = a.get("componentType"), a.get("type")
        dt = _COMPONENT.get(ct) if isinstance(ct, int) else None
        if dt is None or np.dtype(dt).kind not in kinds or not isinstance(kind, str) or _WIDTH.get(kind) != width:
            raise FormatError(f"glTF accessor {i} has componentType {shown(a.get('componentType'))} and type "
                              f"{shown(a.get('type'))}; expected {'VEC3 float' if width == 3 else 'SCALAR unsigned'}",
                              name)
        count = check_count(f"glTF accessor {i} count", _whole(a, "count", f"accessor {i}", name), name)
        start = _whole(v, "byteOffset", "bufferView", name, 0) + _whole(a, "byteOffset", f"accessor {i}", name, 0)
        if start + count * width * np.dtype(dt).itemsize > len(binary):
            raise FormatError(f"glTF accessor {i} reaches past the end of its buffer", name)
        out = np.frombuffer(binary, dtype=dt, count=count * width, offset=start)
        return out.reshape(-1, width) if width > 1 else out

    vs, fs, parts = [], [], []
    nv = nf = 0
    for node in _list(doc, "nodes", name):
        if not isinstance(node, dict):
            raise FormatError(f"a glTF node is a JSON object, got {shown(node)}", name)
        if "mesh" not in node:
            continue
        prims = _item(meshes, node["mesh"], "mesh", name).get("primitives")
        if not isinstance(prims, list):
            raise FormatError(f"glTF mesh {node['mesh']} needs a list of primitives", name)
        for prim in prims:
            attrs = prim.get("attributes") if isinstance(prim, dict) else None
            if not isinstance(attrs, dict) or "POSITION" not in attrs or "indices" not in prim:
                raise FormatError(f"glTF mesh {node['mesh']} has a primitive without POSITION or indices", name)
            p = arr(attrs["POSITION"], 3, "f").astype(float)
            idx = arr(prim["indices"], 1, "u")
            if len(idx) % 3:
                raise FormatError(f"glTF accessor {prim['indices']} holds {len(idx)} indices, not whole triangles",
                                  name)
            f = idx.astype(np.int64).reshape(-1, 3)
            if len(f) and f.max() >= len(p):
                raise FormatError(f"glTF accessor {prim['indices']} refers to vertex {int(f.max())}; its "
                                  f"primitive has {len(p)}", name)
            vs.append(p)
            fs.append(f + nv)
            parts.append(Part(str(node.get("name", "")), "member", -1, "", (nv, nv + len(p)), (nf, nf + len(f))))
            nv += len(p)
            nf += len(f)
            check_count("vertex count", nv, name)
            check_count("triangle count", nf, name)
    if not vs:
        return checked_mesh(np.empty((0, 3)), np.empty((0, 3), dtype=np.int64), name)
    return checked_mesh(np.concatenate(vs), np.concatenate(fs), name, tuple(parts))


def loads(data: bytes | str, name: str = "<bytes>") -> Any:
    """Read a GLB or an embedded glTF written by auszug (positions as stored, z up): one part per node.

    Raises
    ------
    FormatError
        For a bad header or chunk, a buffer that is not embedded, a document
        that does not describe triangle meshes, or a mesh that fails the
        shared checks (:mod:`auszug.formats._meshcheck`).
    """
    raw = data.encode() if isinstance(data, str) else bytes(data)
    if raw[:4] == b"glTF":
        if len(raw) < 20:
            raise FormatError("truncated GLB header", name)
        _, version, length = struct.unpack("<4sII", raw[:12])
        if version != 2 or length != len(raw):
            raise FormatError(f"GLB version {version}, length {length} for {len(raw)} bytes", name)
        jl, jt = struct.unpack("<I4s", raw[12:20])
        if jt != b"JSON":
            raise FormatError("the first GLB chunk is not JSON", name)
        with parse_errors(name, "malformed GLB JSON chunk"):
            doc = json.loads(raw[20:20 + jl])
        rest = raw[20 + jl:]
        binary = b""
        if len(rest) >= 8:
            bl, bt = struct.unpack("<I4s", rest[:8])
            if bt != b"BIN\0":
                raise FormatError("the second GLB chunk is not BIN", name)
            binary = rest[8:8 + bl]
        return _read(doc, binary, name)
    with parse_errors(name, "not glTF JSON"):
        doc = json.loads(raw.decode("utf-8"))
    binary = b""
    for buf in _list(doc, "buffers", name) if isinstance(doc, dict) else []:
        uri = buf.get("uri", "") if isinstance(buf, dict) else None
        if not isinstance(uri, str) or not uri.startswith("data:") or "," not in uri:
            raise FormatError("only embedded (data URI) glTF buffers can be read", name)
        with parse_errors(name, "malformed glTF data URI"):
            binary = base64.b64decode(uri.split(",", 1)[1], validate=True)
    return _read(doc, binary, name)


register(FileFormat("glb", (".glb",), "mesh", reader=loads, writer=dumps_glb, binary=True))
register(FileFormat("gltf", (".gltf",), "mesh", reader=loads, writer=dumps_gltf))
