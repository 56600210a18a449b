"""Fuzzing the drawing readers: damaged corpus files and token soup.

A reader must return a Drawing or raise FormatError / DrawingError, never any
other exception; a drawing that builds must give finite points.
"""

from __future__ import annotations

import math
import os

import numpy as np
import pytest
from hypothesis import HealthCheck, event, example, given, settings
from hypothesis import strategies as st

from auszug.errors import DrawingError, FormatError
from auszug.formats.native import read_native, write_native
from auszug.formats.uc import read_uc
from auszug.microarch import Drawing, build
from tests.conftest import CORPUS, corpus_files

FILES = corpus_files()
TEXTS = {str(p.relative_to(CORPUS)): p.read_text() for p in FILES}
KEYWORDS = ["numCurves", "unitCurve", "reflectionPoint", "ref_symmetry_type", "ptPos", "ptTan",
            "ptTangent", "ptLab", "level", "height", "prc_t", "decoration_t", "decoration_height",
            "vertical_line_top", "layer_bottom"]
ODD = ["nan", "NaN", "inf", "-inf", "Infinity", "0", "-0", "1", "2", "3", "-1", "0.5", "1e308",
       "-1e308", "1e-308", "1e400", "1e100", "1e101", "1e-13", "abc", "0x10", "1_0", "\u0663",
       "first", "point", "y", "axis", "", "\t", "#", "1e", "--1", ".", "1.5.5"]
token = st.sampled_from(ODD + KEYWORDS) | st.floats(-5, 5).map(repr) | st.integers(-3, 9).map(str)

SETTINGS = settings(max_examples=int(os.environ.get("AUSZUG_FUZZ_EXAMPLES", "250")), deadline=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


def _check_reader(read, text: str) -> Drawing | None:
    try:
        d = read(text, "fuzz.uc")
    except (FormatError, DrawingError) as e:
        event(f"rejected: {type(e).__name__}")
        return None
    assert isinstance(d, Drawing)
    event("read")
    return d


def _check_build(d: Drawing) -> None:
    """Build small drawings: DrawingError or finite points, nothing else."""
    if sum(c.symmetry.order * len(c.segments) for c in d.curves) > 96:
        return  # big folds: a resource question, not a correctness one
    try:
        net = build(d, samples=9)
    except DrawingError:
        event("build: DrawingError")
        return
    event("built")
    pts = np.concatenate([p.points for p in net.pieces])
    assert np.isfinite(pts).all()
    for c in net.curves():
        assert np.isfinite(c.points).all() and (c.prc is None or np.isfinite(c.prc).all())


@st.composite
def damaged_corpus_files(draw):
    """A corpus file with a few lines deleted, duplicated, swapped, re-tokenised or cut."""
    name = draw(st.sampled_from(sorted(TEXTS)))
    lines = TEXTS[name].splitlines()
    for _ in range(draw(st.integers(1, 3))):
        if not lines:
            break
        i = draw(st.integers(0, len(lines) - 1))
        op = draw(st.sampled_from(["delete", "duplicate", "swap", "token", "drop token", "add token",
                                   "truncate"]))
        if op == "delete":
            del lines[i]
        elif op == "duplicate":
            lines.insert(draw(st.integers(0, len(lines))), lines[i])
        elif op == "swap":
            j = draw(st.integers(0, len(lines) - 1))
            lines[i], lines[j] = lines[j], lines[i]
        elif op == "truncate":
            lines = lines[:i]
        else:
            toks = lines[i].split()
            if op == "token" and toks:
                toks[draw(st.integers(0, len(toks) - 1))] = draw(token)
            elif op == "drop token" and toks:
                del toks[draw(st.integers(0, len(toks) - 1))]
            else:
                toks.append(draw(token))
            lines[i] = draw(st.sampled_from([" ", "\t"])).join(toks)
    text = "\n".join(lines)
    if draw(st.booleans()):
        text = text[: draw(st.integers(0, len(text)))]
    return text


@SETTINGS
@given(damaged_corpus_files())
@example(TEXTS["web/ribbons/side3-white.uc"].replace("ptPos -0.5652521890828449 0.09966921183982834",
                                                      "ptPos -0.5652521890828449 -1e308"))
def test_damaged_corpus_files(text):
    d = _check_reader(read_uc, text)
    if d is not None:
        _check_build(d)


soup_line = st.tuples(st.sampled_from(KEYWORDS) | token, st.lists(token, max_size=4)).map(
    lambda kt: " ".join([kt[0], *kt[1]]))


@SETTINGS
@given(st.lists(soup_line, max_size=25).map("\n".join))
def test_token_soup(text):
    d = _check_reader(read_uc, text)
    if d is not None:
        _check_build(d)


small = st.integers(-4, 4).map(lambda k: str(k / 2))


@st.composite
def legacy_like(draw):
    """Legacy-dialect files with small, often degenerate numbers, sometimes damaged."""
    lines = []
    for _ in range(draw(st.integers(1, 3))):
        n = draw(st.sampled_from([1] + [2, 3, 4] * 4))
        fold, refl = draw(st.sampled_from([0] + [1, 2, 3, 4] * 4)), draw(st.integers(0, 1))
        lines.append(f"unitCurve\t{n}\t{fold}\t{refl}")
        if refl or draw(st.integers(0, 9)) == 0:
            lines.append(f"reflectionPoint\t{draw(small)}\t{draw(small)}")
        for _ in range(n):
            lines.append(f"ptPos\t{draw(small)}\t{draw(small)}")
            if draw(st.integers(0, 3)) == 0:
                lines.append(f"ptTan\t{draw(small)}\t{draw(small)}")
            lines.append(f"ptLab\t{draw(st.sampled_from([0, 1, 2] * 5 + [3]))}")
    if draw(st.integers(0, 5)) == 0 and lines:
        del lines[draw(st.integers(0, len(lines) - 1))]
    return "\n".join([f"numCurves\t{sum(x.startswith('unitCurve') for x in lines)}", *lines])


@SETTINGS
@given(legacy_like())
def test_legacy_like_files(text):
    """Well-formed keywords with small numbers: reaches the model checks and build."""
    d = _check_reader(read_uc, text)
    if d is not None:
        assert d.default_apex == max(1.0, max(
            math.dist(a, b) for c in d.curves for a, b in zip(c.vertices, c.vertices[1:], strict=False)))
        _check_build(d)


@SETTINGS
@given(st.sampled_from(sorted(TEXTS)), st.data())
def test_damaged_native_json(name, data):
    text = write_native(read_uc(TEXTS[name], name))
    for _ in range(data.draw(st.integers(1, 3))):
        i = data.draw(st.integers(0, len(text)))
        j = data.draw(st.integers(i, min(len(text), i + 12)))
        new = data.draw(st.sampled_from(["", "0", "-1", "1e999", "NaN", "null", "true", '"x"', "[]",
                                         "{}", ",", "]", "}", '"kind"', '"arc"', '"apex"',
                                         "[0, 0]", "2"]))
        text = text[:i] + new + text[j:]
    d = _check_reader(read_native, text)
    if d is not None:
        _check_build(d)
        assert read_native(write_native(d)) == d


@pytest.mark.parametrize("name", ["U.XI.20", "U.XI.22", "U.XI.24", "U.XI.25", "U.XI.29", "U.XI.30",
                                  "U.XI.31", "U.XI.33", "U.XI.34", "U.XI.35"])
def test_bezier_drawings_build(name):
    d = read_uc(TEXTS[f"legacy/{name}.uc"], name)
    net = build(d, samples=17)
    assert all(np.isfinite(p.points).all() for p in net.pieces)
    assert all(math.isfinite(z) for z in net.apex_heights)


def test_degenerate_bezier_drawing_builds():
    """Found by test_legacy_like_files: two curves, one handle vector (0, 0)."""
    text = ("unitCurve 4 1 0\nptPos 0 0\nptLab 0\nptPos -0.5 0\nptTan 0.5 1\nptLab 0\n"
            "ptPos -1.5 0\nptLab 0\nptPos 0 0\nptLab 0\n"
            "unitCurve 4 1 0\nptPos 0 0.5\nptTan 0 0\nptLab 0\nptPos 0 0\nptLab 0\n"
            "ptPos 0 -0.5\nptTan 1 -2\nptLab 0\nptPos 0 0\nptLab 1\n")
    d = read_uc(text, "degenerate.uc")
    net = build(d, samples=9)
    assert all(np.isfinite(p.points).all() for p in net.pieces)
