"""File formats: one module per format, registered by extension; :func:`load` / :func:`save` dispatch."""

from auszug.formats import uc as _uc  # noqa: F401  (registers .uc)
from auszug.formats._registry import FileFormat, atomic_write, format_for, formats, load, register, save

__all__ = ["FileFormat", "atomic_write", "format_for", "formats", "load", "register", "save"]
