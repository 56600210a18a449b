"""The one validation every mesh reader (STL, PLY, glTF, OBJ) ends with.

A mesh read from a file is checked here before it becomes a
:class:`~auszug.meshing.mesh.Mesh`: counts within
:attr:`~auszug.limits.Limits.mesh_triangles`, coordinates finite and within
:attr:`~auszug.limits.Limits.coordinate`, faces of three indices into the
vertex array. Each problem is a :class:`~auszug.errors.FormatError` naming
the file and the first offending vertex or face (numbered from 0, as the
file stores them for PLY and glTF; OBJ messages carry the line instead).

:data:`PARSE_ERRORS` are the exceptions the parsing libraries (float,
int, json, base64, numpy) raise on damaged data, as fuzzing found them
(docs/limits.md, "Fuzzing"); a reader turns exactly these into a
FormatError naming the file, with :func:`parse_errors`.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from typing import Any

import numpy as np

from auszug.errors import FormatError
from auszug.limits import LIMITS, shown

__all__ = ["PARSE_ERRORS", "parse_errors", "check_count", "check_points", "checked_mesh"]

#: Exceptions of damaged data inside a parse, as fuzzing found them: numbers that do not
#: parse (ValueError; json.JSONDecodeError, UnicodeDecodeError and binascii.Error are
#: ValueErrors too) or do not fit an int64 (OverflowError). Structure (counts, indices,
#: JSON types and keys) is checked explicitly, so KeyError, IndexError or TypeError stay bugs.
PARSE_ERRORS: tuple[type[Exception], ...] = (ValueError, OverflowError)


@contextlib.contextmanager
def parse_errors(name: str, what: str) -> Iterator[None]:
    """Turn :data:`PARSE_ERRORS` raised inside the block into ``FormatError("WHAT: detail", name)``.

    FormatErrors pass unchanged; any other exception is a bug and propagates.
    """
    try:
        yield
    except FormatError:
        raise
    except PARSE_ERRORS as e:
        detail = shown(str(e), 120) if str(e) else type(e).__name__
        raise FormatError(f"{what}: {detail.strip(chr(39))}", name) from None


def check_count(what: str, n: Any, name: str) -> int:
    """``n`` as an int if it is a whole number in ``0 .. LIMITS.mesh_triangles``.

    Raises
    ------
    FormatError
        Naming the file, ``what`` (e.g. ``"vertex count"``), the value and the limit.
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
        raise FormatError(f"{what} must be a whole number, got {shown(n)}", name)
    if n < 0:
        raise FormatError(f"{what} must be >= 0, got {shown(n)}", name)
    if n > LIMITS.mesh_triangles:
        raise FormatError(f"{what} {shown(int(n))} is above the limit of {LIMITS.mesh_triangles} "
                          "(auszug.limits.LIMITS.mesh_triangles)", name)
    return int(n)


def check_points(v: np.ndarray, name: str) -> None:
    """Refuse a non-finite coordinate or one beyond :attr:`~auszug.limits.Limits.coordinate`.

    Parameters
    ----------
    v : (n, 3) ndarray of float
        Vertices (drawing units), numbered from 0 in the message.
    name : str
        The file, for messages.
    """
    bad = ~np.isfinite(v).all(axis=1)
    if bad.any():
        i = int(np.argmax(bad))
        raise FormatError(f"vertex {i} has a non-finite coordinate {shown(v[i].tolist())}", name)
    far = (np.abs(v) > LIMITS.coordinate).any(axis=1)
    if far.any():
        i = int(np.argmax(far))
        raise FormatError(f"vertex {i} coordinate {shown(float(np.abs(v[i]).max()))} is beyond the limit of "
                          f"+-{LIMITS.coordinate:g} (auszug.limits.LIMITS.coordinate)", name)


def checked_mesh(vertices: Any, faces: Any, name: str, parts: tuple = ()) -> Any:
    """A :class:`~auszug.meshing.mesh.Mesh` of checked arrays.

    Parameters
    ----------
    vertices : (n, 3) array_like of float
        Drawing units.
    faces : (m, 3) array_like of int
        Indices into ``vertices``.
    name : str
        The file, for messages.
    parts : tuple of Part
        The reader's parts (their ranges are the reader's own, not the file's).

    Raises
    ------
    FormatError
        For too many vertices or faces, a non-finite coordinate or one beyond
        :attr:`~auszug.limits.Limits.coordinate`, or a face index out of range.

    Examples
    --------
    >>> checked_mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], "t.stl").n_faces
    1
    >>> checked_mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 3]], "t.stl")
    Traceback (most recent call last):
    ...
    auszug.errors.FormatError: t.stl: face 0 refers to vertex 3; the mesh has 3 vertices (0..2)
    """
    from auszug.meshing.mesh import Mesh

    v = np.asarray(vertices, dtype=np.float64)
    f = np.asarray(faces)
    if v.size == 0:
        v = v.reshape(0, 3)
    if f.size == 0:
        f = f.reshape(0, 3)
    if v.ndim != 2 or v.shape[1] != 3:
        raise FormatError(f"vertices must have 3 coordinates each, got an array of shape {v.shape}", name)
    if f.ndim != 2 or f.shape[1] != 3:
        raise FormatError(f"faces must have 3 corners each, got an array of shape {f.shape}", name)
    check_count("vertex count", len(v), name)
    check_count("triangle count", len(f), name)
    check_points(v, name)
    if len(f):
        if not np.issubdtype(f.dtype, np.integer):
            raise FormatError(f"face indices must be whole numbers, got {f.dtype}", name)
        out = (f < 0) | (f >= len(v))
        if out.any():
            i, j = np.argwhere(out)[0]
            raise FormatError(f"face {int(i)} refers to vertex {int(f[i, j])}; the mesh has {len(v)} vertices"
                              f" (0..{len(v) - 1})", name)
    return Mesh._unchecked(np.ascontiguousarray(v), np.ascontiguousarray(f, dtype=np.int64), tuple(parts))
