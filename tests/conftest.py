"""Shared fixtures and paths for the auszug test-suite.

Everything a test reads is in the repository (or the installed package): a fresh clone passes.
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from importlib.resources import files
from pathlib import Path

import pytest
from hypothesis import settings

from auszug import examples
from auszug.geometry import tolerances

# No wall-clock deadline anywhere: on a loaded 2-core machine (CI, or a developer's laptop running
# the suite with -n 2 next to other jobs) an example's first call can take seconds, and hypothesis'
# default 200 ms deadline then fails a correct test. Slow code is the benchmarks' business.
# "default" (developers): no deadline, fresh random examples each run, so the search goes on.
# "ci": no deadline, and derandomised, since CI runs on a fresh clone without hypothesis'
# example database: a run there is reproducible.
settings.register_profile("default", deadline=None)
settings.register_profile("ci", deadline=None, derandomize=True)
settings.load_profile("ci" if os.environ.get("CI") else "default")

REPO = Path(__file__).resolve().parents[1]
#: The drawings: the examples bundled with the package (``auszug.examples``).
CORPUS = Path(str(files("auszug.examples")))
#: The authors' demo's own outputs for those drawings, compressed (see its PROVENANCE.md).
ANCHOR = REPO / "tests" / "data" / "reference" / "anchor"


def corpus_files(*folders: str) -> list[Path]:
    """All .uc files below the given corpus folders (all folders if none given).

    Raises
    ------
    FileNotFoundError
        When a folder holds no drawing: a parametrisation over it would test nothing.
    """
    found = []
    for folder in folders or ("",):
        names = [CORPUS / n for n in examples.names(folder)]
        if not names:
            raise FileNotFoundError(f"no .uc drawing below {CORPUS / folder}")
        found += names
    return sorted(found)


@pytest.fixture(autouse=True)
def _strict_mode():
    """Run every test with the internal invariant checks switched on."""
    with tolerances(strict=True):
        yield


@dataclass
class Result:
    code: int
    out: str
    err: str


@pytest.fixture
def cli(capsys):
    """``cli(*args)`` runs ``main(args)`` in-process and returns code, stdout, stderr."""

    def run(*args: str | Path) -> Result:
        from auszug.cli import main

        code = main([str(a) for a in args])
        cap = capsys.readouterr()
        return Result(code, cap.out, cap.err)

    return run


