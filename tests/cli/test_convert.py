"""``auszug convert``: between drawing formats, atomically; bad input and unknown endings."""

from __future__ import annotations

import numpy as np

from auszug.formats import load
from auszug.microarch import build
from tests.cli.conftest import BAD_LINE, TN, files_in


def _same_network(a, b):
    na, nb = build(load(a)), build(load(b))
    assert [c.id for c in na.curves()] == [c.id for c in nb.curves()]
    for ca, cb in zip(na.curves(), nb.curves(), strict=True):
        np.testing.assert_allclose(ca.points, cb.points, rtol=0, atol=1e-12)


def test_uc_to_uc_keeps_the_network(cli, tmp_path):
    out = tmp_path / "tn-6.uc"
    r = cli("convert", TN / "tn-6.uc", out)
    assert r.code == 0 and r.out == f"wrote {out}\n"
    _same_network(TN / "tn-6.uc", out)


def test_uc_to_native_json_and_back(cli, tmp_path):
    assert cli("convert", TN / "tn-10.uc", tmp_path / "a.json").code == 0
    assert cli("convert", tmp_path / "a.json", tmp_path / "b.uc").code == 0
    _same_network(TN / "tn-10.uc", tmp_path / "b.uc")


def test_errors(cli, tmp_path, bad_uc):
    r = cli("convert", bad_uc, tmp_path / "x.uc")
    assert r.code == 2 and r.err.startswith(f"auszug: {bad_uc}:{BAD_LINE}: ")
    r = cli("convert", TN / "tn-1.uc", tmp_path / "x.network.json")
    assert r.code == 2 and "not a drawing file name; drawings end in .json, .uc" in r.err
    r = cli("convert", TN / "tn-1.uc", tmp_path / "x.obj")
    assert r.code == 2 and "not a drawing file name" in r.err
    r = cli("convert", tmp_path / "missing.uc", tmp_path / "y.uc")
    assert r.code == 2 and "no such file" in r.err
    assert files_in(tmp_path) == ["bad.uc"]
