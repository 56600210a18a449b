"""``auszug render``: figure files of the requested size and format; bad input."""

from __future__ import annotations

import pytest

from tests.cli.conftest import BAD_LINE, TN, files_in, png_size


def test_png_of_the_requested_size(cli, tmp_path):
    out = tmp_path / "f.png"
    r = cli("render", TN / "tn-9.uc", "-o", out, "--width", "640", "--height", "240", "--dpi", "80")
    assert r.code == 0, r.err
    assert r.out == f"wrote {out}\n"
    assert png_size(out.read_bytes()) == (640, 240)
    assert files_in(tmp_path) == ["f.png"]


def test_default_name_and_size(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert cli("render", TN / "tn-2.uc").code == 0
    assert png_size((tmp_path / "tn-2.png").read_bytes()) == (1800, 620)


@pytest.mark.parametrize("ending, magic", [(".pdf", b"%PDF"), (".svg", b"<?xml")])
def test_pdf_and_svg(cli, tmp_path, ending, magic):
    out = tmp_path / f"f{ending}"
    assert cli("render", TN / "tn-5.uc", "-o", out, "--width", "500", "--height", "200").code == 0
    assert out.read_bytes().startswith(magic)


def test_unknown_ending_and_bad_input_leave_nothing(cli, tmp_path, bad_uc):
    r = cli("render", TN / "tn-1.uc", "-o", tmp_path / "f.obj")
    assert r.code == 2 and "unknown file type; expected one of .pdf, .png, .svg" in r.err
    r = cli("render", bad_uc, "-o", tmp_path / "f.png")
    assert r.code == 2 and r.err.startswith(f"auszug: {bad_uc}:{BAD_LINE}: ")
    assert files_in(tmp_path) == ["bad.uc"]
