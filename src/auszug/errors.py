"""The auszug exception hierarchy.

Every error auszug raises on purpose derives from :class:`AuszugError`; its
message says what was expected. Errors about input files carry the file name
and line so the CLI can print ``FILE:LINE: problem`` and exit with code 2.
"""

from __future__ import annotations

__all__ = ["AuszugError", "GeometryError", "DrawingError", "FormatError"]


class AuszugError(Exception):
    """Base class of all deliberate auszug errors."""


class GeometryError(AuszugError, ValueError):
    """Degenerate or invalid geometry (zero-length curve, coincident points, ...)."""


class DrawingError(AuszugError, ValueError):
    """A drawing that is well formed but not valid (fold 0, apex below its bottom, ...).

    Parameters
    ----------
    problem : str
        What is wrong, saying what was expected.
    where : str, optional
        Which part of the drawing, e.g. ``"curve 2"``.
    """

    def __init__(self, problem: str, where: str | None = None):
        self.problem = problem
        self.where = where
        super().__init__(f"{where}: {problem}" if where else problem)


class FormatError(AuszugError, ValueError):
    """A file that cannot be read: names the file, the line and the problem.

    Parameters
    ----------
    problem : str
        What is wrong, saying what was expected.
    path : str, optional
        The file name (``"<string>"`` when parsing text).
    line : int, optional
        1-based line number, if the problem has a place.
    """

    def __init__(self, problem: str, path: str | None = None, line: int | None = None):
        self.problem = problem
        self.path = path
        self.line = line
        place = path or "<input>"
        if line is not None:
            place = f"{place}:{line}"
        super().__init__(f"{place}: {problem}")
