"""OBJ polylines: one group per curve and replica, exact round trip, z-up header, reader errors."""

from __future__ import annotations

import numpy as np
import pytest

from auszug.errors import FormatError
from auszug.formats import load, save
from auszug.formats.network_json import NetworkFile
from auszug.formats.obj import dumps, read_polylines, safe_name
from auszug.microarch import build
from tests.conftest import CORPUS

CASES = ["teaching-sheet/tn-5.uc", "teaching-sheet/tn-9.uc", "web/u.xi.112.uc", "web/weird_ones/flower.uc"]


@pytest.mark.parametrize("name", CASES)
def test_round_trip_gives_every_curve_back_exactly(name, tmp_path):
    net = build(load(CORPUS / name))
    curves = list(net.curves())
    out = save(NetworkFile(net, name), tmp_path / "n.obj")
    text = out.read_text()
    lines = text.splitlines()
    assert sum(ln.startswith("g ") for ln in lines) == len(curves)
    assert sum(ln.startswith("v ") for ln in lines) == sum(len(c.points) for c in curves)
    assert sum(ln.startswith("l ") for ln in lines) == len(curves)
    back = load(out, kind="network")
    assert list(back) == [safe_name(c.id) for c in curves]       # names unique, in order
    for c in curves:
        assert np.array_equal(back[safe_name(c.id)], c.points), c.id


def test_header_says_z_is_up_and_names_the_source():
    net = build(load(CORPUS / "teaching-sheet" / "tn-1.uc"))
    head = [ln for ln in dumps(NetworkFile(net, "tn-1.uc")).splitlines() if ln.startswith("#")]
    assert any("Z IS UP" in ln for ln in head)
    assert "# source: tn-1.uc" in head
    assert dumps(net).splitlines()[1] == "# source: tn-1"


def test_safe_names_have_no_white_space_or_slashes():
    for cid in ["0/r0", "12/r3m.free_end1", "2/r0.pillar", "a b/c"]:
        s = safe_name(cid)
        assert " " not in s and "/" not in s
    assert safe_name("0/r3m") != safe_name("0/r3")


def test_reader_accepts_negative_indices_and_joins_lines_of_a_group():
    text = "v 0 0 0\nv 1 0 0\nv 1 1 0\ng a b\nl -3 -2\nl 2 3\n"
    got = read_polylines(text)
    assert got["a b"].tolist() == [[0, 0, 0], [1, 0, 0], [1, 0, 0], [1, 1, 0]]


@pytest.mark.parametrize("text, line, what", [
    ("v 0 0\n", 1, "3 coordinates"),
    ("v 0 0 0\nv 0 x 0\n", 2, "not numbers"),
    ("v 0 0 0\nv 1 1 1\ng a\nl 1 3\n", 4, "out of range"),
    ("v 0 0 0\nl 1\n", 2, "at least 2"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 4, "faces"),
])
def test_reader_errors_name_the_line(text, line, what):
    with pytest.raises(FormatError, match=what) as e:
        read_polylines(text, "bad.obj")
    assert (e.value.path, e.value.line) == ("bad.obj", line)
