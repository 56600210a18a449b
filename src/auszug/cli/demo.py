"""Build and render the bundled teaching sheet and Basel drawings (what ``make run`` does).

Writes into OUT (default ./out):

  OUT/teaching-sheet.png           the 12 examples of the teaching sheet U.XI.11 in one
                                   contact sheet (3D, side and top view each; paper Fig. 9)
  OUT/teaching-sheet/<name>.network.json, <name>.png
  OUT/basel/<name>.network.json, <name>.png
                                   the Basel goldsmith drawings redrawn by the paper's
                                   authors (U.XI.*) and the Basel Minster chancel

The drawings ship inside the package (auszug/examples). Several drawings are
rendered at once, one per processor (--jobs).
"""

from __future__ import annotations

import argparse
import os
import re
import sys
from pathlib import Path
from typing import Any

HELP = "build and render the bundled teaching sheet and Basel drawings"

#: Bundled folders and which of their drawings the demo shows.
SETS: tuple[tuple[str, str, str], ...] = (
    ("teaching-sheet", "teaching-sheet", r".*\.uc"),
    ("basel", "web", r"(?i)(u\.xi\..*|3d_scan_final_final)\.uc"),
)


def add_args(parser: argparse.ArgumentParser) -> None:
    """Options of ``auszug demo``."""
    from auszug.cli._common import at_least

    parser.add_argument("-o", "--output", metavar="OUT", default="out",
                        help="output folder (default ./out; created if needed)")
    parser.add_argument("--jobs", type=at_least(1), default=None, metavar="N",
                        help="drawings rendered at once (default: number of processors, at most 4)")


def _natural(name: str) -> list[Any]:
    return [int(t) if t.isdigit() else t.lower() for t in re.split(r"(\d+)", name)]


def bundled() -> list[tuple[str, str, str]]:
    """``(set, file name, text)`` of every demo drawing, read with importlib.resources."""
    from importlib.resources import files

    root = files("auszug") / "examples"
    out = []
    for set_name, folder, pattern in SETS:
        entries = [e for e in (root / folder).iterdir() if e.is_file() and re.fullmatch(pattern, e.name)]
        for e in sorted(entries, key=lambda e: _natural(e.name)):
            out.append((set_name, e.name, e.read_text(encoding="utf-8")))
    return out


def _network(name: str, text: str) -> Any:
    """Read bundled drawing text and build its network (a NetworkFile)."""
    from auszug.formats import format_for
    from auszug.formats.network_json import NetworkFile
    from auszug.microarch.network import build

    fmt = format_for(name, "drawing")
    assert fmt.reader is not None
    return NetworkFile(build(fmt.reader(text, name)), name)


def _job(set_name: str, name: str, text: str, out_dir: str) -> tuple[list[str], str | None]:
    """Build one drawing and write its network JSON and figure; return (paths, error)."""
    from auszug.cli._common import stem
    from auszug.errors import AuszugError
    from auszug.formats import save

    try:
        nf = _network(name, text)
        base = Path(out_dir) / set_name / stem(name)
        paths = [save(nf, base.with_name(base.name + ".network.json"), kind="network"),
                 save(nf, base.with_name(base.name + ".png"), kind="figure")]
    except AuszugError as e:
        return [], str(e)
    return [str(p) for p in paths], None


def run(args: argparse.Namespace) -> int:
    """Write everything; return 0, or 2 if a drawing failed."""
    from auszug.formats import atomic_write

    out = Path(args.output)
    if out.exists() and not out.is_dir():
        from auszug.errors import FormatError

        raise FormatError("the demo needs an output folder, but this is a file", str(out))
    drawings = bundled()
    jobs = args.jobs or max(1, min(4, os.cpu_count() or 1))
    results: list[tuple[list[str], str | None]] = []
    sheet_items = [(name, text) for s, name, text in drawings if s == "teaching-sheet"]
    if jobs > 1:
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        ctx = multiprocessing.get_context("spawn")
        with ProcessPoolExecutor(max_workers=jobs, mp_context=ctx) as pool:
            futures = [pool.submit(_job, s, n, t, str(out)) for s, n, t in drawings]
            sheet = _sheet(sheet_items)          # meanwhile, here
            results = [f.result() for f in futures]
    else:
        results = [_job(s, n, t, str(out)) for s, n, t in drawings]
        sheet = _sheet(sheet_items)
    sheet_path = out / "teaching-sheet.png"
    atomic_write(sheet_path, sheet)
    errors = [e for _, e in results if e]
    for e in errors:
        print(f"auszug: {e}", file=sys.stderr)
    counts = {s: sum(1 for (d, _, _), (p, _) in zip(drawings, results, strict=True) if d == s and p)
              for s, _, _ in SETS}
    print(f"demo: {counts['teaching-sheet']} teaching-sheet and {counts['basel']} Basel drawings in {out}/")
    print(f"  {sheet_path}  contact sheet of the teaching sheet (cf. paper Fig. 9)")
    for s, _, _ in SETS:
        print(f"  {out / s}/  <name>.network.json and <name>.png per drawing")
    return 2 if errors else 0


def _sheet(items: list[tuple[str, str]]) -> bytes:
    from auszug.formats.figure import contact_sheet

    nets = [(Path(n).stem, _network(n, t)) for n, t in items]
    return contact_sheet(nets, ncols=6, title="Teaching sheet U.XI.11: the 12 examples (3D, side and top views)")
