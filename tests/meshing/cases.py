"""Shared fixtures of the meshing tests: corpus networks (cached) and small canonical drawings."""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from auszug.formats import load
from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry, build
from tests.conftest import CORPUS, corpus_files

ALL = corpus_files()
IDS = [str(p.relative_to(CORPUS)) for p in ALL]


@lru_cache(maxsize=None)
def network(path: str | Path, samples: int | None = None):
    """The network of a corpus drawing (every corpus drawing must build: a failure fails the test)."""
    p = Path(path)
    if not p.is_absolute():
        p = CORPUS / p
    return build(load(p), samples=samples)


def arch() -> Drawing:
    """An ogee and its mirror image standing on the ground: no loop but a rim closes one."""
    c = BasicCurve(((-1.0, 2.0), (0.0, 3.0)), (Segment("line"),), ("ground", "apex"),
                   Symmetry(fold=1, mirror=True), height=1.0)
    return Drawing((c,), name="arch")


def star() -> Drawing:
    """Four ogees meeting at the ground on one mirror axis and at the apex on the other (C2 + mirror)."""
    c = BasicCurve(((1.0, 0.0), (0.0, 1.0)), (Segment("line"),), ("ground", "apex"),
                   Symmetry(fold=2, mirror=True, axis=(1.0, 0.0)), height=1.0)
    return Drawing((c,), name="rhombus")


def arc_curve() -> Drawing:
    """One ogee over a circular arc, C4 with mirror, ground on an axis (tn-1 like)."""
    c = BasicCurve(((1.0, 0.0), (0.0, 0.8)), (Segment("arc", ((0.9, 0.5),)),), ("ground", "apex"),
                   Symmetry(fold=4, mirror=True, axis=(1.0, 0.0)), height=1.2)
    return Drawing((c,), name="arcs")
