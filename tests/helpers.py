"""Test helpers: reading the reference outputs of the authors' demo."""

from __future__ import annotations

import gzip
import lzma
import re
from pathlib import Path

import numpy as np

_GROUP = re.compile(r"curve(\d+)_(biarc|decoration|free_end|pillar|vertical_line)_rot(\d+)(_ref)?$")
KIND = {"biarc": "ogee", "decoration": "decoration", "free_end": "free_end", "pillar": "pillar",
        "vertical_line": "post"}


def read_text(path: Path) -> str:
    """The text of a file, decompressed when its name ends in ``.xz`` or ``.gz``."""
    opener = {".xz": lzma.open, ".gz": gzip.open}.get(path.suffix, open)
    with opener(path, "rt", encoding="utf-8") as f:
        return f.read()


def read_reference_obj(path: Path) -> dict[tuple[int, str, str], np.ndarray]:
    """Polylines of a reference OBJ keyed by (basic curve, kind, replica label).

    The reference uses y = height; points are returned as (x, y, z) with z = height.
    Replica labels are returned as the demo writes them: ``rot<k>`` -> ``r<k>``,
    ``rot<k>_ref`` -> ``r<k>m``. The demo works in a y-up frame, where its
    rotation by +2 pi k / n about the up axis is, in our right-handed z-up frame,
    the rotation by -2 pi k / n: use :func:`our_label` to translate.
    ``path`` is a plain ``.obj`` or a compressed ``.obj.xz`` / ``.obj.gz`` (as
    ``tests/data/reference/anchor`` stores them).
    """
    out: dict[tuple[int, str, str], list] = {}
    cur = None
    for line in read_text(path).splitlines():
        if line.startswith("g "):
            m = _GROUP.match(line[2:].strip())
            assert m, f"unexpected group name {line!r} in {path}"
            key = (int(m.group(1)), KIND[m.group(2)], f"r{m.group(3)}{'m' if m.group(4) else ''}")
            cur = out.setdefault(key, [])
        elif line.startswith("v "):
            x, h, y = map(float, line.split()[1:4])
            cur.append((x, y, h))
    return {k: np.array(v) for k, v in out.items()}


def our_label(label: str, fold: int) -> str:
    """Our replica label for the demo's ``r<k>[m]`` (rotation sense flipped by its y-up frame)."""
    mirrored = label.endswith("m")
    k = int(label[1:-1] if mirrored else label[1:])
    return f"r{(fold - k) % fold}{'m' if mirrored else ''}"
