"""Wavefront OBJ polylines (``.obj``): the curve network as ``v`` and ``l`` lines.

One group ``g`` per network curve (every piece under every symmetry element),
named after the curve's id made OBJ-safe (``0/r1m`` -> ``0_r1m``,
``0/r0.free_end1`` -> ``0_r0.free_end1``). Coordinates are written as they
are: x, y in the top-view plane and **z = height (z up)**; viewers that assume
y up (Blender's OBJ importer with default settings, three.js) show the network
lying on its side unless told that z is up. The header comment says so.

The reader returns the polylines by group name, which is what the tests use to
check a round trip; faces are not part of this format.
"""

from __future__ import annotations

import re
from typing import Any

import numpy as np
from numpy.typing import NDArray

from auszug.errors import FormatError
from auszug.formats._registry import FileFormat, register
from auszug.formats.network_json import unpack

__all__ = ["safe_name", "dumps", "read_polylines"]

_UNSAFE = re.compile(r"[^A-Za-z0-9_.\-]")


def safe_name(curve_id: str) -> str:
    """An OBJ group name for a network curve id (no white space, no slashes).

    Examples
    --------
    >>> safe_name("0/r1m"), safe_name("2/r0.free_end1")
    ('0_r1m', '2_r0.free_end1')
    """
    return _UNSAFE.sub("_", curve_id)


def dumps(network: Any, source: str = "") -> str:
    """OBJ text of a network's polylines (see the module docstring).

    Parameters
    ----------
    network : CurveNetwork or NetworkFile (or a producer of a curve network)
    source : str
        File name of the drawing, recorded in the header.
    """
    net, src = unpack(network)
    source = source or src
    out = [
        "# auszug curve network: polylines, one group per curve and replica",
        f"# source: {source}",
        "# coordinates: x, y = top view (drawing units), z = height; Z IS UP",
        f"# parameterization: {net.meta.get('parameterization', 'arclength')}",
        *([f"# tolerance: {net.tolerance!r} (every polyline within it of its exact curve)"]
          if net.tolerance is not None else []),
    ]
    base = 1
    for c in net.curves():
        pts = np.asarray(c.points, dtype=float)
        out.append(f"g {safe_name(c.id)}")
        out.extend(f"v {x!r} {y!r} {z!r}" for x, y, z in pts.tolist())
        out.append("l " + " ".join(map(str, range(base, base + len(pts)))))
        base += len(pts)
    return "\n".join(out) + "\n"


def _write(obj: Any, name: str) -> str:
    return dumps(obj)


def read_polylines(text: str, name: str = "<string>") -> dict[str, NDArray[np.float64]]:
    r"""The polylines of OBJ text by group name.

    Parameters
    ----------
    text : str
    name : str
        File name for messages.

    Returns
    -------
    dict of str to (n, 3) ndarray
        Points of each group's polyline in ``l`` order; several ``l`` lines in
        one group are joined end to end. Lines before any ``g`` belong to
        group ``""``.

    Raises
    ------
    FormatError
        For a malformed ``v`` or ``l`` line, an index out of range, or faces.

    Examples
    --------
    >>> read_polylines("v 0 0 0\nv 1 0 0\ng a\nl 1 2\n")["a"].tolist()
    [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]
    """
    verts: list[tuple[float, float, float]] = []
    groups: dict[str, list[int]] = {}
    group = ""
    for no, raw in enumerate(text.splitlines(), 1):
        toks = raw.split("#", 1)[0].split()
        if not toks:
            continue
        key, args = toks[0], toks[1:]
        if key == "v":
            if len(args) < 3:
                raise FormatError(f"'v' needs 3 coordinates, got {len(args)}", name, no)
            try:
                verts.append((float(args[0]), float(args[1]), float(args[2])))
            except ValueError:
                raise FormatError(f"'v': {' '.join(args[:3])!r} are not numbers", name, no) from None
        elif key == "g":
            group = " ".join(args)
            groups.setdefault(group, [])
        elif key == "l":
            try:
                idx = [int(a.split("/")[0]) for a in args]
            except ValueError:
                raise FormatError("'l' needs vertex indices", name, no) from None
            if len(idx) < 2:
                raise FormatError(f"'l' needs at least 2 vertices, got {len(idx)}", name, no)
            idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
            if not all(0 <= i < len(verts) for i in idx):
                raise FormatError(f"'l' refers to a vertex out of range 1..{len(verts)}", name, no)
            groups.setdefault(group, []).extend(idx)
        elif key == "f":
            raise FormatError("faces ('f') found; expected polylines only", name, no)
    v = np.asarray(verts, dtype=float).reshape(-1, 3)
    return {g: v[np.asarray(i, dtype=int)] for g, i in groups.items() if i}


register(FileFormat("obj", (".obj",), "network", reader=read_polylines, writer=_write))
