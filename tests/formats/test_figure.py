"""Figures: sizes, formats, contact sheets, and that matplotlib loads only when drawing."""

from __future__ import annotations

import struct
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest

from auszug.errors import FormatError
from auszug.formats import load, save
from auszug.formats.figure import contact_sheet, render
from auszug.formats.network_json import NetworkFile
from auszug.microarch import build
from tests.conftest import CORPUS


def png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


@pytest.fixture(scope="module")
def net():
    return NetworkFile(build(load(CORPUS / "web" / "u.xi.112.uc")), "u.xi.112.uc")


@pytest.mark.parametrize("size", [(900, 300), (1800, 620), (401, 257)])
def test_png_has_the_requested_size(net, size):
    assert png_size(render(net, "png", width=size[0], height=size[1], dpi=100)) == size


def test_pdf_and_svg(net):
    assert render(net, "pdf", width=600, height=200).startswith(b"%PDF")
    root = ET.fromstring(render(net, "svg", width=600, height=200))
    assert root.tag.endswith("svg")


def test_registered_writer_picks_the_format_from_the_name(net, tmp_path):
    p = save(net, tmp_path / "f.png", kind="figure")
    assert png_size(p.read_bytes()) == (1800, 620)
    assert save(net, tmp_path / "f.pdf", kind="figure").read_bytes().startswith(b"%PDF")


def test_contact_sheet_grid(net):
    items = [(str(i), net) for i in range(5)]
    w, h = png_size(contact_sheet(items, ncols=3, cell=200, dpi=100))
    assert w == 600 and h > 400


@pytest.mark.parametrize("call", [
    lambda n: render(n, "jpg"),
    lambda n: render(n, "png", width=10),
    lambda n: contact_sheet([]),
])
def test_bad_requests_raise_format_errors(net, call):
    with pytest.raises(FormatError):
        call(net)


def test_formats_import_no_matplotlib():
    code = "import sys, auszug.formats; print('matplotlib' in sys.modules, 'rich' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.split() == ["False", "False"]
