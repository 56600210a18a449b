"""``auszug demo``: the bundled drawings built and rendered, with the teaching-sheet contact sheet."""

from __future__ import annotations

import pytest

from auszug.cli.demo import bundled
from auszug.formats import load
from tests.cli.conftest import png_size


def test_bundled_drawings_come_from_the_package():
    got = bundled()
    sheet = [n for s, n, _ in got if s == "teaching-sheet"]
    assert sheet == [f"tn-{i}.uc" for i in range(1, 13)]          # natural order
    basel = [n for s, n, _ in got if s == "basel"]
    assert "U.XI.28.uc" in basel and "3d_scan_final_final.uc" in basel
    assert all(text.startswith("numCurves") for _, _, text in got)


@pytest.mark.parametrize("jobs", ["2"])
def test_demo_writes_networks_figures_and_the_contact_sheet(cli, tmp_path, jobs):
    out = tmp_path / "out"
    r = cli("demo", "-o", out, "--jobs", jobs)
    assert r.code == 0, r.err
    drawings = bundled()
    for s, name, _ in drawings:
        stem = name[:-3]
        assert load(out / s / f"{stem}.network.json", kind="network")["source"] == name
        assert png_size((out / s / f"{stem}.png").read_bytes()) == (1800, 620)
    w, h = png_size((out / "teaching-sheet.png").read_bytes())
    assert w == 1800 and h > 1500
    assert str(out / "teaching-sheet.png") in r.out
    assert not list(out.rglob(".*.tmp"))
