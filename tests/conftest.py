"""Shared fixtures and paths for the auszug test-suite."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from hypothesis import settings

from auszug.geometry import tolerances

# CI runs on a fresh clone without hypothesis' example database: derandomise there so a run is
# reproducible; developers' runs keep searching with fresh random examples.
settings.register_profile("ci", derandomize=True)
if os.environ.get("CI"):
    settings.load_profile("ci")

REPO = Path(__file__).resolve().parents[1]
SHARED = Path(os.environ.get("AUSZUG_SHARED", REPO.parent / "shared"))
CORPUS = SHARED / "corpus"
ANCHOR = SHARED / "reference" / "anchor"


def corpus_files(*folders: str) -> list[Path]:
    """All .uc files below the given corpus folders (all folders if none given)."""
    roots = [CORPUS / f for f in folders] if folders else [CORPUS]
    return sorted(p for r in roots for p in r.rglob("*.uc"))


@pytest.fixture(autouse=True)
def _strict_mode():
    """Run every test with the internal invariant checks switched on."""
    with tolerances(strict=True):
        yield
