"""The one home for tolerances and resolutions used across auszug.

Every comparison against a tolerance in the package reads it from the single
instance :data:`TOL` at call time. :func:`tolerances` overrides fields for a
``with`` block; the test-suite switches on ``strict`` to turn on internal
invariant checks (G1 continuity of reverse curves, replicas exactly on their
basic curve, ...), which cost time and are off by default.
"""

from __future__ import annotations

from contextlib import contextmanager
from dataclasses import dataclass, fields
from typing import Iterator

__all__ = ["Tolerances", "TOL", "tolerances"]


@dataclass
class Tolerances:
    """Tolerances, all relative to a drawing of unit size unless stated.

    Attributes
    ----------
    zero : float
        Lengths below this are zero (coincident points, zero-length curves).
    collinear : float
        Sine of the angle below which three points count as collinear, or two
        directions as parallel.
    intersect : float
        Distance within which two curves are taken to meet; also the tolerance
        of the Newton refinement of Bezier intersections.
    param_equal : float
        Two normalised arc-length parameters closer than this are equal. Used
        for the true/false classification of top-view intersections (t = t',
        paper sec. 4.3.1) and to drop intersections at curve endpoints.
    samples : int
        Default number of samples per curve piece in outputs (>= 64).
    solid_merge : float
        Relative to a united solid's size: its features closer than this are
        merged (manifold3d's tolerance, then a weld that must keep the solid
        a closed 2-manifold). Above float32's resolution (6e-8), so that an
        STL of the solid, read back by position, is still watertight; far
        below anything printable.
    strict : bool
        Turn on internal invariant checks.
    """

    zero: float = 1e-12
    collinear: float = 1e-9
    intersect: float = 1e-9
    param_equal: float = 1e-6
    samples: int = 65
    solid_merge: float = 1e-6
    strict: bool = False


TOL = Tolerances()


@contextmanager
def tolerances(**overrides: object) -> Iterator[Tolerances]:
    """Temporarily override fields of :data:`TOL`.

    Examples
    --------
    >>> from auszug.geometry import TOL, tolerances
    >>> with tolerances(strict=True):
    ...     TOL.strict
    True
    >>> TOL.strict
    False
    """
    names = {f.name for f in fields(Tolerances)}
    unknown = set(overrides) - names
    if unknown:
        raise TypeError(f"unknown tolerance field(s): {sorted(unknown)}; known: {sorted(names)}")
    old = {k: getattr(TOL, k) for k in overrides}
    for k, v in overrides.items():
        setattr(TOL, k, v)
    try:
        yield TOL
    finally:
        for k, v in old.items():
            setattr(TOL, k, v)
