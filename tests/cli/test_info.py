"""``auszug info``: curve counts, symmetry, heights, PRCs with their origin, intersections."""

from __future__ import annotations

from auszug.formats import load
from auszug.microarch import build
from tests.cli.conftest import BAD_LINE, TN
from tests.conftest import CORPUS


def test_prints_counts_symmetry_heights_and_prcs(cli):
    r = cli("info", TN / "tn-11.uc")
    assert r.code == 0, r.err
    net = build(load(TN / "tn-11.uc"))
    n = len(list(net.curves()))
    assert r.out.splitlines()[0].startswith(f"tn-11.uc: 3 basic curves, {n} network curves, 1 layer(s)")
    assert "C2 + mirror (axis 90.0 deg)" in r.out
    assert f"{net.apex_heights[0]:.4f}" in r.out
    assert r.out.count("drawing file") == 3            # every PRC is stored in this file


def test_automatic_prcs_name_the_algorithm1_branch(cli, tmp_path):
    text = (TN / "tn-11.uc").read_text()
    src = tmp_path / "auto.uc"
    src.write_text("\n".join(ln for ln in text.splitlines() if not ln.startswith("prc_t")))
    r = cli("info", src)
    assert r.code == 0
    net = build(load(src))
    for ch in net.prc_choices.values():
        assert f"Algorithm 1: {ch.branch}" in r.out


def test_intersections_are_counted_and_classified(cli):
    from auszug.microarch.prc import intersections

    inter = intersections(load(CORPUS / "web" / "U.XI.49.F.uc"))
    n_true = sum(i.true for i in inter)
    r = cli("info", CORPUS / "web" / "U.XI.49.F.uc", "--limit", "0")
    assert f"top-view intersections: {len(inter)} ({n_true} true, {len(inter) - n_true} false)" in r.out
    assert " false" in r.out and n_true < len(inter)


def test_long_intersection_lists_are_cut_at_the_limit(cli):
    from auszug.microarch.prc import intersections

    n = len(intersections(load(CORPUS / "web" / "U.XI.49.F.uc")))
    short = cli("info", CORPUS / "web" / "U.XI.49.F.uc", "--limit", "5")
    full = cli("info", CORPUS / "web" / "U.XI.49.F.uc", "--limit", "0")
    assert f"({n - 5} more; use --limit 0 to list all)" in short.out and "more;" not in full.out
    assert len(full.out.splitlines()) == len(short.out.splitlines()) + n - 5 - 1


def test_layers_and_posts(cli):
    r = cli("info", CORPUS / "web" / "u.xi.112.uc")
    assert r.code == 0 and "3 layer(s)" in r.out.splitlines()[0]


def test_bad_input(cli, bad_uc):
    r = cli("info", bad_uc)
    assert r.code == 2 and r.err.startswith(f"auszug: {bad_uc}:{BAD_LINE}: ") and r.out == ""


def test_without_the_intersection_module_the_rest_still_prints(cli, monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "auszug.microarch.prc", None)      # import raises ImportError
    r = cli("info", TN / "tn-1.uc")
    assert r.code == 0 and "top-view intersections: not available" in r.out
    assert "points of reverse curvature" in r.out
