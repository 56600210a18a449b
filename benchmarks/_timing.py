"""Shared timing helper of the benchmark scripts (run as scripts: this folder is on sys.path)."""

from __future__ import annotations

import statistics
import time
from typing import Callable, NamedTuple


class Timing(NamedTuple):
    """Median and minimum wall-clock seconds of repeated runs."""

    median: float
    min: float


def timed(fn: Callable[[], object], reps: int) -> Timing:
    """Time ``fn()`` over ``reps`` runs after two warm-up runs."""
    fn()
    fn()
    ts = []
    for _ in range(reps):
        t0 = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t0)
    return Timing(statistics.median(ts), min(ts))
