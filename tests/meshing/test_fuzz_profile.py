"""Fuzzing profile JSON (``mesh --style PROFILE.json``, :func:`auszug.meshing.profile.from_dict`).

A mutated profile description must give a valid profile (finite points within
LIMITS.coordinate, a cap that covers a closed profile's area exactly, an exact
JSON round trip) or a GeometryError; through the command line, exit 0 with a
finite mesh or exit 2 naming the profile file (tests/fuzzing.py).
"""

from __future__ import annotations

import json
import random
from collections import Counter

import numpy as np
import pytest

from auszug.errors import GeometryError
from auszug.formats import stl
from auszug.limits import LIMITS
from auszug.meshing.mesh import triangle_areas
from auszug.meshing.profile import Profile, circle, from_dict, rectangle, ribbon
from tests.conftest import CORPUS
from tests.fuzzing import case, cases, expect_contract, mutate_json, run_cli

MOULDING = {"name": "roll and fillets", "closed": True, "start": [-1.0, 0.0], "scale": 0.01, "segments": [
    {"line": [1.0, 0.0]}, {"line": [1.0, 0.4]}, {"line": [0.5, 0.4]},
    {"arc": [-0.5, 0.4], "center": [0.0, 0.4]}, {"line": [-1.0, 0.4]}]}
ARCS = {"start": [0.5, 0.0], "closed": False, "segments": [
    {"arc": [-0.5, 0.0], "through": [0.0, 0.5]}, {"arc": [-0.5, -0.4], "bulge": 0.3},
    {"arc": [0.5, -0.4], "center": [0.0, -0.4], "ccw": False}]}
BASES = [MOULDING, ARCS, circle(0.02, 8).to_dict(), rectangle(0.04, 0.02, 6).to_dict(), ribbon(0.05).to_dict()]
KEYS = ["points", "bulge", "closed", "start", "segments", "line", "arc", "through", "center", "ccw", "scale", "name"]
#: Cases of the API fuzzer and of the command-line fuzzer in a ``make test`` run.
N_API, N_CLI = 1000, 40


def check_profile(p: Profile) -> None:
    """Finite, within the coordinate limit, capped exactly when closed, an exact JSON round trip."""
    assert np.isfinite(p.points).all() and np.isfinite(p.bulges).all()
    assert np.abs(p.points).max() <= LIMITS.coordinate
    if p.closed:
        pts3 = np.concatenate([p.points, np.zeros((p.n, 1))], axis=1)
        assert triangle_areas(pts3, p.cap).sum() == pytest.approx(p.area, rel=1e-9)
    assert from_dict(json.loads(json.dumps(p.to_dict()))) == p


def _mutated(seed: int) -> object:
    rnd = random.Random(seed)
    return mutate_json(rnd.choice(BASES), rnd, keys=KEYS)


def test_mutated_profiles_api():
    seen: Counter = Counter()
    for seed in cases(N_API):
        d = _mutated(seed)
        with case(f"profile seed {seed}: {json.dumps(d)[:300]}"):
            try:
                p = from_dict(d)  # type: ignore[arg-type]
            except GeometryError as e:
                assert str(e) and "\n" not in str(e)
                seen["refused"] += 1
                continue
            check_profile(p)
            seen["ok"] += 1
    assert seen["ok"] and seen["refused"], seen


def test_mutated_profiles_cli(tmp_path):
    """A few cases through ``auszug mesh DRAWING --style P.json -o OUT.stl``: the file named, or a finite mesh."""
    drawing = CORPUS / "teaching-sheet" / "tn-2.uc"
    seen: Counter = Counter()
    for seed in cases(N_CLI):
        prof = tmp_path / f"p{seed}.json"
        prof.write_text(json.dumps(_mutated(seed)))
        out = tmp_path / f"m{seed}.stl"
        with case(f"profile cli seed {seed}"):
            res = run_cli(["mesh", str(drawing), "--style", str(prof), "--samples", "9", "-o", str(out)],
                          str(prof), [out])
            if res.kind == "ok":
                assert stl.loads(out.read_bytes(), str(out)).n_faces > 0  # the reader refuses NaN
        seen[res.kind] += 1
    assert seen["ok"] and seen["refused"], seen


@pytest.mark.parametrize("d, message", [
    ({"points": [[0, 0], [1e7, 0], [0, 1]]}, "beyond the limit"),
    ({"points": [[0, 0], [1, 0], [0, 1]], "scale": 1e300}, "beyond the limit"),
    ({**MOULDING, "scale": 1e9}, "beyond the limit"),
    ({**ARCS, "segments": [{"arc": [-0.5, 0.0], "bulge": 1e308}]}, "segment 0: bulge 1e.308 puts"),  # overflow
    ({"points": [[0, 0], [1, 0]], "closed": False, "bulge": [1e12]}, "diameter"),
    ({**ARCS, "segments": [{"arc": [-0.5, 0.0], "center": [1e308, 0]}]}, "centre .* beyond the limit"),
])
def test_found_cases(d, message):
    with pytest.raises(GeometryError, match=message):
        from_dict(d)


def test_bases_are_valid():
    for d in BASES:
        check_profile(from_dict(d))
    assert expect_contract(from_dict, {"points": "x"}, name="points").kind == "refused"
