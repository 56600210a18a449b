"""Parameter validation at the public boundary: errors name the parameter and its valid range.

Havemann and Fellner leave the validity of parameters "to a higher software
layer" (their Fig. 19); this is that layer. Every check raises
:class:`auszug.errors.DrawingError` with ``where`` set to the parameter name
and a message stating the valid range and the value given.
"""

from __future__ import annotations

import math
from typing import Any

from auszug.errors import DrawingError

__all__ = ["ParameterError", "require", "number", "integer", "choice"]


class ParameterError(DrawingError):
    """A tracery parameter outside its valid range.

    Attributes
    ----------
    name : str
        The parameter (``"excess"``, ``"circle.foils"``, ...).
    value : object
        The value given.
    valid : str
        The valid range in words (``">= 0.5"``, ``"in [0, 3.2)"``).
    """

    def __init__(self, name: str, value: Any, valid: str, why: str = "") -> None:
        self.name = name
        self.value = value
        self.valid = valid
        shown = f"{value:.6g}" if isinstance(value, float) else repr(value)
        text = f"expected {valid}, got {shown}"
        if why:
            text += f" ({why})"
        super().__init__(text, where=name)


def require(ok: bool, name: str, value: Any, valid: str, why: str = "") -> None:
    """Raise :class:`ParameterError` unless ``ok``."""
    if not ok:
        raise ParameterError(name, value, valid, why)


def number(name: str, value: Any, lo: float | None = None, hi: float | None = None,
           lo_open: bool = False, hi_open: bool = False, why: str = "") -> float:
    """A finite float within the given bounds.

    Examples
    --------
    >>> number("excess", 0.75, 0.5)
    0.75
    >>> number("excess", 0.3, 0.5)
    Traceback (most recent call last):
    ...
    auszug.tracery._checks.ParameterError: excess: expected a number >= 0.5, got 0.3
    """
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(name, value, "a number") from None
    if isinstance(value, bool) or not math.isfinite(v):
        raise ParameterError(name, value, "a finite number")
    parts = []
    if lo is not None:
        parts.append(f"{'>' if lo_open else '>='} {lo:g}")
    if hi is not None:
        parts.append(f"{'<' if hi_open else '<='} {hi:g}")
    valid = "a number " + " and ".join(parts) if parts else "a number"
    if lo is not None and (v < lo or (lo_open and v == lo)):
        raise ParameterError(name, v, valid, why)
    if hi is not None and (v > hi or (hi_open and v == hi)):
        raise ParameterError(name, v, valid, why)
    return v


def integer(name: str, value: Any, lo: int | None = None, hi: int | None = None) -> int:
    """An int within the given bounds (floats with integral value are accepted)."""
    ok = isinstance(value, int) and not isinstance(value, bool)
    if not ok and isinstance(value, float) and value.is_integer():
        value, ok = int(value), True
    valid = "a whole number" + (f" >= {lo}" if lo is not None else "") + (f" <= {hi}" if hi is not None else "")
    if not ok:
        raise ParameterError(name, value, valid)
    if (lo is not None and value < lo) or (hi is not None and value > hi):
        raise ParameterError(name, value, valid)
    return int(value)


def choice(name: str, value: Any, options: tuple[str, ...]) -> str:
    """One of ``options``."""
    if value not in options:
        raise ParameterError(name, value, "one of " + ", ".join(repr(o) for o in options))
    return str(value)
