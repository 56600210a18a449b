"""The tokens of ``.uc`` text.

Shared by the web dialect (:mod:`auszug.formats.uc`) and the legacy/v1 reader
(:mod:`auszug.formats.uc_legacy`), which would otherwise import each other. Lines are
whitespace-separated tokens; a line is a key and its numbers.
"""

from __future__ import annotations

import io
import math
import re
from typing import Iterator

from auszug.errors import FormatError
from auszug.limits import LIMITS, check_text_size, shown

__all__ = ["MAX_NUMBER", "numbers", "integer", "lines", "iter_lines", "stem"]

_TOKEN = re.compile(r"\S+")

#: Largest magnitude of a coordinate or height in a drawing file (:attr:`auszug.limits.Limits.coordinate`).
MAX_NUMBER = LIMITS.coordinate


def numbers(tokens: list[str], n: int | None, key: str, path: str, line: int,
            bound: float | None = LIMITS.coordinate) -> list[float]:
    """The tokens of line ``line`` as finite numbers (exactly ``n`` of them unless None).

    ``bound``: the largest magnitude allowed (default the coordinate limit);
    None for counts and fractions, which their own checks bound.

    Raises
    ------
    FormatError
        Naming ``key``, the file, the line, the value and the limit.
    """
    if n is not None and len(tokens) != n:
        raise FormatError(f"'{key}' needs {n} number(s), got {len(tokens)}", path, line)
    out = []
    for tok in tokens:
        try:
            v = float(tok)
        except ValueError:
            raise FormatError(f"'{key}': {shown(tok)} is not a number", path, line) from None
        if not math.isfinite(v):
            raise FormatError(f"'{key}': {_bare(tok)} is not a finite number", path, line)
        if bound is not None and abs(v) > bound:
            raise FormatError(f"'{key}': {_bare(tok)} is beyond the limit of +-{bound:g} for coordinates "
                              "and heights (auszug.limits.LIMITS.coordinate)", path, line)
        out.append(v)
    return out


def _bare(tok: str) -> str:
    """A number's token as written, shortened if long."""
    return tok if len(tok) <= LIMITS.quoted else shown(tok)


def integer(v: float, key: str, path: str, line: int, minimum: int, limit: str | None = None,
            offset: int = 0) -> int:
    """The number ``v`` as a whole number >= ``minimum``, else a :class:`FormatError`.

    ``limit`` names a field of :class:`auszug.limits.Limits` that ``v + offset``
    may not exceed (``"fold"``; ``"layers"`` with offset 1 for a layer index).
    """
    if v != int(v) or v < minimum:
        raise FormatError(f"'{key}' must be a whole number >= {minimum}, got {v:g}", path, line)
    if limit is not None:
        top = getattr(LIMITS, limit) - offset
        if v > top:
            raise FormatError(f"'{key}' {v:g} is above the limit of {top} (auszug.limits.LIMITS.{limit})",
                              path, line)
    return int(v)


def lines(text: str) -> list[tuple[int, list[str]]]:
    r"""The non-blank lines of ``text`` as (1-based line number, whitespace-separated tokens).

    Examples
    --------
    >>> lines("numCurves 1\n\n  ptPos 0 1\n")
    [(1, ['numCurves', '1']), (3, ['ptPos', '0', '1'])]
    """
    return list(iter_lines(text))


def iter_lines(text: str, path: str | None = None) -> Iterator[tuple[int, list[str]]]:
    r""":func:`lines`, one at a time: a large file never exists as a list of its tokens.

    With ``path``, refuses text longer than :attr:`auszug.limits.Limits.file_bytes`.

    Examples
    --------
    >>> next(iter_lines("\n ptPos 0 1\n"))
    (2, ['ptPos', '0', '1'])
    """
    if path is not None:
        check_text_size(text, path)
    for no, raw in enumerate(io.StringIO(text, newline=None), 1):
        toks = _TOKEN.findall(raw)
        if toks:
            yield no, toks


def stem(path: str) -> str:
    """The drawing name of a file path: its last part without ``.uc``.

    Examples
    --------
    >>> stem("corpus/legacy/tn-3.uc")
    'tn-3'
    """
    name = path.replace("\\", "/").rsplit("/", 1)[-1]
    return name[:-3] if name.lower().endswith(".uc") else name
