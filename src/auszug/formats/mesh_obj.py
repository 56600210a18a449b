"""Wavefront OBJ meshes (``.obj`` of kind ``"mesh"``), with an MTL material library.

One group ``g`` per part of the mesh: per member replica (``0_r1m``, named
like the network's curve ids made OBJ-safe), per face (``face2_0``), the base
plate, or one ``solid``. Members use the material of their basic curve
(``curve0``, ``curve1``, ... in the curve colours of the figures), faces
``face``, the plate ``base``. The OBJ refers to ``<name>.mtl``; write that
file with :func:`mtl` beside it (``auszug mesh`` does). Coordinates are
written as they are, **z up** (the header says so); Blender's importer
needs "Up: Z" to stand the model upright.

(Network polylines have their own OBJ writer, :mod:`auszug.formats.obj`; the
two share the ``.obj`` ending, so pass ``kind="mesh"`` to
:func:`~auszug.formats.save` and :func:`~auszug.formats.load`.)
"""

from __future__ import annotations

import io
import math
import re
from pathlib import PurePath
from typing import Any

import numpy as np

from auszug.errors import FormatError
from auszug.formats._meshcheck import checked_mesh
from auszug.formats._registry import FileFormat, register
from auszug.formats.palette import rgb
from auszug.limits import LIMITS

__all__ = ["as_mesh", "part_colour", "material_name", "dumps", "mtl", "loads"]

_UNSAFE = re.compile(r"[^A-Za-z0-9_.\-]")
FACE_RGB = (0.86, 0.80, 0.66)
BASE_RGB = (0.55, 0.55, 0.55)
SOLID_RGB = (0.80, 0.68, 0.40)


def as_mesh(obj: Any) -> Any:
    """The :class:`~auszug.meshing.Mesh` of a mesh or of anything with a ``.mesh`` (a solid, faces)."""
    from auszug.meshing.mesh import Mesh

    if isinstance(obj, Mesh):
        return obj
    m = getattr(obj, "mesh", None)
    m = m() if callable(m) else m
    if isinstance(m, Mesh):
        return m
    raise TypeError(f"expected a Mesh (or a Solid), got {type(obj).__name__}")


def part_colour(part: Any) -> tuple[float, float, float]:
    """RGB in [0, 1] of a mesh part: its basic curve's colour for members.

    Examples
    --------
    >>> from auszug.meshing.mesh import Part
    >>> part_colour(Part("0/r0", "member", 0, "r0", (0, 0), (0, 0)))
    (0.0, 0.4470588235294118, 0.6980392156862745)
    """
    if part.kind == "member":
        return rgb(part.basic)
    return {"face": FACE_RGB, "base": BASE_RGB}.get(part.kind, SOLID_RGB)


def material_name(part: Any) -> str:
    """``curve<basic>`` for members, else the part's kind."""
    return f"curve{part.basic}" if part.kind == "member" else part.kind


def _parts(mesh: Any) -> list:
    from auszug.meshing.mesh import Part

    return list(mesh.parts) or [Part("mesh", "solid", -1, "", (0, mesh.n_vertices), (0, mesh.n_faces))]


def dumps(obj: Any, name: str = "mesh.obj") -> str:
    """OBJ text of a mesh: ``v`` and ``f`` lines, a group and a material per part.

    Parameters
    ----------
    obj : Mesh or Solid
    name : str
        File name; the material library is referred to as its stem + ``.mtl``.

    Examples
    --------
    >>> from auszug.meshing.mesh import Mesh
    >>> text = dumps(Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]), "t.obj")
    >>> [ln for ln in text.splitlines() if not ln.startswith("#")]
    ['mtllib t.mtl', 'g mesh', 'usemtl solid', 'v 0 0 0', 'v 1 0 0', 'v 0 1 0', 'f 1 2 3']
    """
    mesh = as_mesh(obj)
    out = io.StringIO()
    out.write("# auszug mesh: one group per member replica / face / base plate\n")
    out.write("# coordinates: x, y = top view (drawing units), z = height; Z IS UP\n")
    out.write(f"mtllib {PurePath(name).stem}.mtl\n")
    for p in _parts(mesh):
        v0, v1 = p.vertices
        f0, f1 = p.faces
        out.write(f"g {_UNSAFE.sub('_', p.name)}\nusemtl {material_name(p)}\n")
        np.savetxt(out, mesh.vertices[v0:v1], fmt="v %.10g %.10g %.10g")
        np.savetxt(out, mesh.faces[f0:f1] + 1, fmt="f %d %d %d")
    return out.getvalue()


def mtl(obj: Any) -> str:
    """The MTL material library for :func:`dumps` (one diffuse colour per material)."""
    mesh = as_mesh(obj)
    seen: dict[str, tuple[float, float, float]] = {}
    for p in _parts(mesh):
        seen.setdefault(material_name(p), part_colour(p))
    lines = ["# auszug materials"]
    for nm, (r, g, b) in seen.items():
        lines += [f"newmtl {nm}", f"Kd {r:.4f} {g:.4f} {b:.4f}", "Ka 0 0 0", "Ks 0.1 0.1 0.1", "Ns 20", "d 1", ""]
    return "\n".join(lines)


def loads(text: str, name: str = "<string>") -> Any:
    """Read an OBJ mesh (triangles; polygons are fanned): groups become parts.

    Raises
    ------
    FormatError
        For malformed ``v``/``f`` lines, indices out of range, or a mesh that
        fails the shared checks (:mod:`auszug.formats._meshcheck`).
    """
    from auszug.meshing.mesh import Part

    verts: list[list[float]] = []
    faces: list[list[int]] = []
    groups: list[tuple[str, int]] = []
    for no, raw in enumerate(text.splitlines(), 1):
        toks = raw.split("#", 1)[0].split()
        if not toks:
            continue
        key = toks[0]
        if key == "v":
            try:
                verts.append([float(t) for t in toks[1:4]])
            except ValueError:
                raise FormatError("'v' needs 3 numbers", name, no) from None
            if len(verts[-1]) != 3:
                raise FormatError("'v' needs 3 numbers", name, no)
            if not all(math.isfinite(x) and abs(x) <= LIMITS.coordinate for x in verts[-1]):
                raise FormatError(f"'v' coordinates must be finite and within +-{LIMITS.coordinate:g} "
                                  f"(auszug.limits.LIMITS.coordinate), got {' '.join(toks[1:4])[:LIMITS.quoted]}",
                                  name, no)
        elif key == "f":
            try:
                idx = [int(t.split("/")[0]) for t in toks[1:]]
            except ValueError:
                raise FormatError("'f' needs vertex indices", name, no) from None
            if len(idx) < 3:
                raise FormatError("'f' needs at least 3 vertices", name, no)
            idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
            if not all(0 <= i < len(verts) for i in idx):
                raise FormatError(f"'f' refers to a vertex out of range 1..{len(verts)}", name, no)
            faces.extend([idx[0], idx[j], idx[j + 1]] for j in range(1, len(idx) - 1))
        elif key == "g":
            if groups and groups[-1][1] == len(faces):
                groups.pop()
            groups.append((" ".join(toks[1:]), len(faces)))
    v = np.asarray(verts, dtype=float).reshape(-1, 3)
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    parts = []
    bounds = [(g, s) for g, s in groups] + [("", len(f))]
    for (g, s), (_, e) in zip(bounds[:-1], bounds[1:], strict=True):
        if e > s:
            lo, hi = int(f[s:e].min()), int(f[s:e].max()) + 1
            parts.append(Part(g, "member", -1, "", (lo, hi), (s, e)))
    return checked_mesh(v, f, name, tuple(parts))


def _write(obj: Any, name: str) -> str:
    return dumps(obj, name)


register(FileFormat("mesh-obj", (".obj",), "mesh", reader=loads, writer=_write))
