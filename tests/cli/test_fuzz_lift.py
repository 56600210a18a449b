"""Fuzzing ``auszug lift`` end to end: random sketches and damaged example sketches.

The contract: exit 0 with the network written (finite, one curve per stroke), or exit 2 with one line
naming the file and no output; never an internal error (exit 1) or a traceback. Seeded, so a failure
is reproducible; ``AUSZUG_FUZZ_SCALE`` multiplies the case counts for a longer search (the search of
2026-12-05: 300 random sketches of 1-27 strokes and 450 damaged examples, docs/limits.md).
"""

from __future__ import annotations

import os

import numpy as np
import pytest

from auszug import examples
from auszug.formats import load
from auszug.formats.sketch_json import dumps
from auszug.lifting import Marker, Sketch, Stroke

SCALE = int(os.environ.get("AUSZUG_FUZZ_SCALE", "1"))
NAMES = ["vase", "ogee-roof", "arches", "barrel-half"]


def _random_svg(rng: np.random.Generator) -> str:
    """2-5 strokes of 1-3 segments (lines, cubics, quadratics, arcs) on a page of random size."""
    w = float(rng.choice([1.0, 100.0, 600.0, 1e5]))

    def p() -> str:
        return f"{rng.uniform(0, w):.4g} {rng.uniform(0, w):.4g}"

    paths = []
    for k in range(int(rng.integers(2, 6))):
        d = f"M {p()}"
        for _ in range(int(rng.integers(1, 4))):
            kind = rng.integers(0, 4)
            d += (f" L {p()}" if kind == 0 else f" C {p()} {p()} {p()}" if kind == 1 else f" Q {p()} {p()}"
                  if kind == 2 else f" A {rng.uniform(0.1, 1) * w:.4g} {rng.uniform(0.1, 1) * w:.4g} 0 "
                  f"{rng.integers(0, 2)} {rng.integers(0, 2)} {p()}")
        paths.append(f'<path id="p{k}" d="{d}"/>')
    if rng.random() < 0.3:
        paths.append(f'<circle class="{rng.choice(["occlusion", "flip"])}" id="m" cx="{rng.uniform(0, w):.4g}" '
                     f'cy="{rng.uniform(0, w):.4g}" r="1"/>')
    return f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {w:g} {w:g}">' + "".join(paths) + "</svg>"


def _damaged(rng: np.random.Generator) -> str:
    """An example sketch with strokes dropped, noise, a far shift, a rotation, a straightened stroke,
    markers or layers removed: as sketch JSON."""
    sk = load(examples.path(f"sketches/{rng.choice(NAMES)}.svg"), kind="sketch")
    strokes = [s.controls.copy() for s in sk.strokes]
    layers = [s.layer for s in sk.strokes]
    ids = [s.id for s in sk.strokes]
    diag = sk.diagonal()
    if rng.random() < 0.5:
        for _ in range(int(rng.integers(1, 3))):
            if len(strokes) > 1:
                i = int(rng.integers(len(strokes)))
                del strokes[i], layers[i], ids[i]
    if rng.random() < 0.4:
        strokes = [c + rng.normal(0, float(rng.choice([0.001, 0.01, 0.03])) * diag, c.shape) for c in strokes]
    shift = np.array([float(rng.choice([0.0, 1e4, 9e5])), 0.0])
    th = float(rng.uniform(0, 2 * np.pi)) if rng.random() < 0.3 else 0.0
    R = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
    strokes = [c @ R.T + shift for c in strokes]
    if rng.random() < 0.2:
        i = int(rng.integers(len(strokes)))
        strokes[i][:, [1, 2]] = strokes[i][:, [0, 3]]
    markers = tuple(Marker(m.kind, np.asarray(m.point) @ R.T + shift, m.id) for m in sk.markers) \
        if rng.random() < 0.8 else ()
    if rng.random() < 0.2:
        layers = [0] * len(layers)
    sym = None
    if sk.symmetry is not None and rng.random() < 0.8:
        sym = Stroke(sk.symmetry.controls @ R.T + shift, sk.symmetry.id, sk.symmetry.layer)
    out = Sketch(tuple(Stroke(c, i, lay) for c, i, lay in zip(strokes, ids, layers, strict=True)),
                 markers, sym, sk.name, sk.layers)
    return dumps(out)


def _check(cli, tmp_path, src, seen, *extra: str) -> None:
    out = tmp_path / "out.network.json"
    r = cli("lift", src, "-o", out, "--quiet", *extra)
    assert r.code in (0, 2) and "Traceback" not in r.err, r.err
    if r.code == 2:
        seen["refused"] += 1
        assert r.err.startswith(f"auszug: {src}: ") and r.err.count("\n") == 1, r.err
        assert not out.exists()
        return
    seen["ok"] += 1
    doc = load(out, kind="network")
    pts = np.concatenate([np.asarray(c["points"], float) for c in doc["curves"]])
    assert np.isfinite(pts).all()
    sketch = load(src, kind="sketch")
    n = len(sketch.strokes) * (2 if sketch.symmetry is not None else 1) + (sketch.symmetry is not None)
    assert {c["basic"] for c in doc["curves"]} == set(range(n))
    out.unlink()


@pytest.mark.parametrize("kind", ["random", "damaged", "closed"])
def test_lift_keeps_its_contract_on_odd_sketches(cli, tmp_path, kind):
    """``closed``: the damaged examples again, lifted with gaps closed (``--set close_gaps``, 0.2-5 %)."""
    rng = np.random.default_rng(20261205 + ("random", "damaged", "closed").index(kind))
    seen = {"ok": 0, "refused": 0}
    for i in range(24 * SCALE):
        src = tmp_path / (f"r{i}.svg" if kind == "random" else f"d{i}.sketch.json")
        src.write_text(_random_svg(rng) if kind == "random" else _damaged(rng))
        extra = ("--set", f"close_gaps={rng.choice([0.002, 0.01, 0.05])}") if kind == "closed" else ()
        _check(cli, tmp_path, src, seen, *extra)
    assert seen["ok"] and seen["refused"], seen     # the fuzzer reaches both ends of the contract
