"""What one stage of :func:`auszug.sweeps.detect` did (for ``auszug sweeps --explain``)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

__all__ = ["Stage"]


@dataclass(frozen=True)
class Stage:
    """What one stage did.

    Attributes
    ----------
    name : str
        One of :data:`auszug.sweeps.STAGES`.
    seconds : float
        Wall time.
    summary : str
        One line: what the stage kept.
    numbers : dict
        The same as numbers (JSON-ready: str keys, int/float/str values).
    """

    name: str
    seconds: float
    summary: str
    numbers: dict[str, Any] = field(default_factory=dict)
