"""A fresh clone passes its tests: they read nothing outside the repository and the package."""

from __future__ import annotations

import re

from auszug import examples
from tests.conftest import ANCHOR, CORPUS, REPO, corpus_files

#: What the tests, benchmarks, docs and CI must not name: the data folder next to the checkout, as
#: a relative path or built from this file's parents, or the old variable that moved it (examples
#: of each in the second test; spelled in pieces here so that this file passes its own check).
OUTSIDE = re.compile("|".join([
    r"\.\./+shared\b",
    r"\.parents?(\[\d+\])?(\.parent)*\s*/\s*['\"]shared['\"]",
    "AUSZUG_" + "SHARED",
]))
CHECKED = ("tests", "benchmarks", ".ci", "docs")


def _checked_files():
    for folder in CHECKED:
        for p in sorted((REPO / folder).rglob("*")):
            if p.is_file() and p.suffix not in (".xz", ".gz", ".pyc") and "data" not in p.relative_to(REPO).parts:
                yield p
    yield from (REPO / "Makefile", REPO / "pyproject.toml", REPO / "README.md")


def test_no_test_reads_the_folder_next_to_the_checkout():
    files = list(_checked_files())
    assert len(files) > 50 and REPO / "tests" / "conftest.py" in files
    hits = [f"{p.relative_to(REPO)}:{n}: {line.strip()}"
            for p in files for n, line in enumerate(p.read_text(errors="replace").splitlines(), 1)
            if OUTSIDE.search(line)]
    assert not hits, "paths outside the repository:\n" + "\n".join(hits)


def test_the_pattern_finds_the_old_spellings():
    folder = '"shar' + 'ed"'
    old = ['SHARED = Path(os.environ.get("AUSZUG_' + 'SHARED", REPO.parent / ' + folder + "))",
           "DEFAULT_CORPUS = HERE.parent.parent / " + folder + ' / "corpus"',
           "Path(__file__).parents[2] /" + folder,
           "(../" + "shared/reference/anchor/README.md)"]
    assert all(OUTSIDE.search(s) for s in old)
    assert not OUTSIDE.search("shared = [p for p in warm.pieces]")     # a word, not a path


def test_the_data_is_in_the_repository_and_the_package():
    assert ANCHOR.is_relative_to(REPO) and (ANCHOR / "summary.json").is_file()
    assert CORPUS == examples.path("teaching-sheet/tn-1.uc").parents[1]
    assert len(corpus_files()) == len(examples.names()) == 86
