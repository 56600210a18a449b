"""Fuzzing the sketch readers (SVG and sketch JSON) with damaged example sketches.

A reader must return a Sketch or raise FormatError naming the file, never any other exception; a sketch
it returns has finite control points of shape (m, 4, 2) within the coordinate limit, and its lifting
graphs build (the readers run their checks).
"""

from __future__ import annotations

import copy
import json
import os
import re
import warnings
from collections import Counter

import numpy as np
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from auszug import examples
from auszug.errors import FormatError
from auszug.formats.sketch_json import dumps, from_dict
from auszug.formats.sketch_svg import read_sketch_svg
from auszug.lifting import Sketch
from auszug.lifting.reconstruct import layer_graphs
from auszug.limits import LIMITS

NAMES = ["vase", "ogee-roof", "arches", "barrel-half"]
SVGS = {n: examples.path(f"sketches/{n}.svg").read_text() for n in NAMES}
ODD = ["nan", "NaN", "inf", "-inf", "1e308", "-1e308", "1e-308", "1e400", "0", "-0", "", " ", "M", "Z",
       "C", "L", "A", "Q", "S", "T", "H", "V", "m", "z", "1e", "--1", ".", "1.5.5", ",", "translate(1e9)",
       "scale(0)", "matrix(1 0 0 1 nan 0)", "rotate(90)", "skewX(89.9999)", "occlusion", "flip", "symmetry",
       "layer", "<", ">", "&amp;", "\"", "'", "\u0663"]
token = st.sampled_from(ODD) | st.floats(-1e6, 1e6).map(repr) | st.integers(-3, 9).map(str)
SETTINGS = settings(max_examples=int(os.environ.get("AUSZUG_FUZZ_EXAMPLES", "250")), deadline=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?")


def _check_sketch(sk: Sketch) -> None:
    """A sketch a reader returned: finite (m, 4, 2) strokes within the coordinate limit, markers of the two
    kinds, and the lifting graph builds (the readers run its checks, so it must not fail now)."""
    assert isinstance(sk, Sketch) and sk.strokes
    for s in sk.strokes:
        c = np.asarray(s.controls)
        assert c.ndim == 3 and c.shape[1:] == (4, 2) and np.isfinite(c).all()
        assert np.abs(c).max() <= LIMITS.coordinate
    for m in sk.markers:
        assert m.kind in ("occlusion", "flip") and np.isfinite(np.asarray(m.point, float)).all()
    assert layer_graphs(sk)


@st.composite
def damaged_svgs(draw) -> str:
    """An example SVG with numbers, tokens or whole lines changed, deleted, duplicated or cut."""
    lines = SVGS[draw(st.sampled_from(NAMES))].splitlines()
    for _ in range(draw(st.integers(1, 3))):
        i = draw(st.integers(0, len(lines) - 1))
        op = draw(st.sampled_from(["number", "number", "token", "delete", "duplicate", "truncate", "attribute"]))
        if op == "number" and NUMBER.search(lines[i]):
            hits = list(NUMBER.finditer(lines[i]))
            h = hits[draw(st.integers(0, len(hits) - 1))]
            lines[i] = lines[i][:h.start()] + draw(token) + lines[i][h.end():]
        elif op == "token":
            k = draw(st.integers(0, len(lines[i])))
            lines[i] = lines[i][:k] + draw(token) + lines[i][k:]
        elif op == "delete":
            del lines[i]
        elif op == "duplicate":
            lines.insert(draw(st.integers(0, len(lines))), lines[i])
        elif op == "truncate":
            lines = lines[:i] + [lines[i][:draw(st.integers(0, len(lines[i])))]]
        else:
            lines[i] = re.sub(r'(class|id|d|transform|viewBox|cx|cy|r)="[^"]*"',
                              lambda m: f'{m.group(1)}="{draw(token)}"', lines[i], count=1)
        if not lines:
            break
    return "\n".join(lines)


def _run(strategy, read, name: str) -> Counter:
    """Run the fuzzer; count the sketches read and the files refused."""
    seen: Counter = Counter()

    @SETTINGS
    @given(strategy)
    def one(text: str) -> None:
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("error", RuntimeWarning)      # an overflow is a value not checked
                sk = read(text, name)
        except FormatError as e:
            assert str(e).startswith(name)
            event("rejected")
            seen["refused"] += 1
            return
        event("read")
        seen["ok"] += 1
        _check_sketch(sk)

    one()
    return seen


def test_damaged_sketch_svgs_read_or_fail_with_a_format_error():
    seen = _run(damaged_svgs(), read_sketch_svg, "fuzz.svg")
    assert seen["ok"] and seen["refused"], seen      # the fuzzer reaches both ends of the contract


@st.composite
def damaged_json(draw) -> str:
    """An example sketch as sketch JSON with one value replaced by an odd one."""
    doc = json.loads(dumps(read_sketch_svg(SVGS[draw(st.sampled_from(NAMES))], "x.svg")))
    odd = st.sampled_from([None, True, 0, -1, 1.5, 1e308, "", "x", [], {}, [[0, 0]], [[[0, 0]] * 4],
                           [[[0, 0], [1, 1], [2, 2], [3, 3]]], float("nan")])
    for _ in range(draw(st.integers(1, 3))):
        node, path = doc, []
        while isinstance(node, (dict, list)) and node and draw(st.booleans()):
            key = draw(st.sampled_from(sorted(node))) if isinstance(node, dict) else draw(
                st.integers(0, len(node) - 1))
            path.append(key)
            node = node[key]
        if not path:
            continue
        parent = doc
        for k in path[:-1]:
            parent = parent[k]
        parent[path[-1]] = copy.deepcopy(draw(odd))
    return json.dumps(doc)


def test_damaged_sketch_json_reads_or_fails_with_a_format_error():
    seen = _run(damaged_json(), lambda text, name: from_dict(json.loads(text), name), "fuzz.sketch.json")
    assert seen["ok"] and seen["refused"], seen
