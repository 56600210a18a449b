"""Fixtures of the CLI tests: in-process runs of ``main`` and small good and bad drawings."""

from __future__ import annotations

import struct
from pathlib import Path

import pytest

from tests.conftest import CORPUS

TN = CORPUS / "teaching-sheet"

BAD_LINE = 4
BAD_UC = "numCurves 1\nunitCurve 4 1\nptPos 0 0\nptPos 1 x\nptPos 2 0\n"
#: Reads fine, fails when built: the apex lies below the bottom (a drawing error).
LOW_APEX_UC = "numCurves 1\nunitCurve 4 0\nptPos 0 1\nptPos 1 1.5\nptPos 1 2\nheight -1\n"
#: The line of its apex height, which the apex error names.
LOW_APEX_LINE = 6

#: (the in-process ``cli`` fixture is in tests/conftest.py, shared with tests/test_limits.py)


@pytest.fixture
def bad_uc(tmp_path) -> Path:
    p = tmp_path / "bad.uc"
    p.write_text(BAD_UC)
    return p


@pytest.fixture
def low_apex_uc(tmp_path) -> Path:
    p = tmp_path / "low.uc"
    p.write_text(LOW_APEX_UC)
    return p


def png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", data[16:24])


def files_in(folder: Path) -> list[str]:
    """Every file below ``folder`` as sorted relative paths (temporary files included)."""
    return sorted(str(p.relative_to(folder)) for p in folder.rglob("*") if p.is_file())
