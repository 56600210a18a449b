"""The tokens of ``.uc`` text.

Shared by the web dialect (:mod:`auszug.formats.uc`) and the legacy/v1 reader
(:mod:`auszug.formats.uc_legacy`), which would otherwise import each other. Lines are
whitespace-separated tokens; a line is a key and its numbers.
"""

from __future__ import annotations

import math
import re

from auszug.errors import FormatError

__all__ = ["MAX_NUMBER", "numbers", "integer", "lines", "stem"]

_TOKEN = re.compile(r"\S+")

# Largest magnitude a number in a drawing file may have: squared distances of
# larger coordinates overflow in the geometry kernel (NaN or OverflowError).
MAX_NUMBER = 1e100


def numbers(tokens: list[str], n: int | None, key: str, path: str, line: int) -> list[float]:
    """The tokens of line ``line`` as finite numbers within +-MAX_NUMBER (exactly ``n`` of them unless None).

    Raises
    ------
    FormatError
        Naming ``key``, the file and the line.
    """
    if n is not None and len(tokens) != n:
        raise FormatError(f"'{key}' needs {n} number(s), got {len(tokens)}", path, line)
    out = []
    for tok in tokens:
        try:
            v = float(tok)
        except ValueError:
            raise FormatError(f"'{key}': {tok!r} is not a number", path, line) from None
        if not math.isfinite(v):
            raise FormatError(f"'{key}': {tok} is not a finite number", path, line)
        if abs(v) > MAX_NUMBER:
            raise FormatError(f"'{key}': {tok} is too large; expected a number within "
                              f"+-{MAX_NUMBER:g}", path, line)
        out.append(v)
    return out


def integer(v: float, key: str, path: str, line: int, minimum: int) -> int:
    """The number ``v`` as a whole number >= ``minimum``, else a :class:`FormatError`."""
    if v != int(v) or v < minimum:
        raise FormatError(f"'{key}' must be a whole number >= {minimum}, got {v:g}", path, line)
    return int(v)


def lines(text: str) -> list[tuple[int, list[str]]]:
    r"""The non-blank lines of ``text`` as (1-based line number, whitespace-separated tokens).

    Examples
    --------
    >>> lines("numCurves 1\n\n  ptPos 0 1\n")
    [(1, ['numCurves', '1']), (3, ['ptPos', '0', '1'])]
    """
    out = []
    for no, raw in enumerate(text.splitlines(), 1):
        toks = _TOKEN.findall(raw)
        if toks:
            out.append((no, toks))
    return out


def stem(path: str) -> str:
    """The drawing name of a file path: its last part without ``.uc``.

    Examples
    --------
    >>> stem("corpus/legacy/tn-3.uc")
    'tn-3'
    """
    name = path.replace("\\", "/").rsplit("/", 1)[-1]
    return name[:-3] if name.lower().endswith(".uc") else name
