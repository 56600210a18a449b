"""A scalar root bracket solver for the few 1D equations of the kernel.

``scipy.optimize`` costs half a second to import, more than a whole corpus
build; the equations solved here are smooth and bracketed, so safeguarded
bisection with secant steps (Illinois variant of regula falsi) is enough.
"""

from __future__ import annotations

import math
from typing import Callable

__all__ = ["find_root"]


def find_root(f: Callable[[float], float], a: float, b: float, xtol: float = 1e-15, maxiter: int = 200) -> float:
    """A root of ``f`` in [a, b], where f(a) and f(b) differ in sign.

    Parameters
    ----------
    f : callable
        Continuous scalar function.
    a, b : float
        Bracket.
    xtol : float
        Absolute tolerance on the root (relative to max(1, |x|)).

    Examples
    --------
    >>> round(find_root(lambda x: x * x - 2.0, 0.0, 2.0), 12)
    1.414213562373
    """
    fa, fb = f(a), f(b)
    if fa == 0.0:
        return a
    if fb == 0.0:
        return b
    if (fa > 0.0) == (fb > 0.0) or math.isnan(fa) or math.isnan(fb):
        raise ValueError(f"find_root needs a sign change on [{a}, {b}], got f = {fa}, {fb}")
    side = 0
    for _ in range(maxiter):
        c = (a * fb - b * fa) / (fb - fa)
        if not (min(a, b) < c < max(a, b)):
            c = 0.5 * (a + b)
        fc = f(c)
        if fc == 0.0 or abs(b - a) <= xtol * max(1.0, abs(c)):
            return c
        if (fc > 0.0) == (fb > 0.0):
            b, fb = c, fc
            if side == -1:
                fa *= 0.5
            side = -1
        else:
            a, fa = c, fc
            if side == 1:
                fb *= 0.5
            side = 1
    return 0.5 * (a + b)
