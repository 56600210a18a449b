"""The drawings bundled with auszug: the teaching sheet and the Basel corpus (all three .uc dialects).

Examples
--------
>>> from auszug import examples
>>> examples.path("teaching-sheet/tn-2.uc").name
'tn-2.uc'
>>> len(examples.names("teaching-sheet"))
12
"""

from __future__ import annotations

from importlib.resources import files
from pathlib import Path

__all__ = ["path", "names"]


def path(name: str) -> Path:
    """File system path of a bundled drawing, e.g. ``"web/U.XI.28.uc"``.

    Raises
    ------
    FileNotFoundError
        Naming the bundled drawings' folders when there is no such drawing.
    """
    p = Path(str(files(__name__).joinpath(name)))
    if not p.is_file():
        raise FileNotFoundError(f"no bundled drawing {name!r}; see auszug.examples.names()")
    return p


def names(folder: str = "") -> list[str]:
    """Names (relative paths) of the bundled drawings, optionally below one folder."""
    root = Path(str(files(__name__)))
    base = root / folder if folder else root
    return sorted(str(p.relative_to(root)) for p in base.rglob("*.uc"))
