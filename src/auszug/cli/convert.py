"""Convert a drawing between drawing formats; the file endings pick the formats.

Reads any drawing format (.uc in the web, legacy or v1 dialect; .json, auszug's
native format) and writes a writable one (.uc in the web dialect, .json).
Automatic PRCs are written as Algorithm 1 chose them. A drawing that cannot
be built (an apex at or below its bottom, ...) is refused, and OUT may not be
the input. The output is written atomically: a failure leaves no file.

examples:
  auszug convert legacy/tn-3.uc tn-3.json
  auszug convert tn-3.json tn-3.uc
"""

from __future__ import annotations

import argparse

from auszug.cli import _common

HELP = "convert a drawing between drawing formats (.uc, .json)"


def add_args(parser: argparse.ArgumentParser) -> None:
    """Arguments of ``auszug convert``."""
    parser.add_argument("input", metavar="IN", help="drawing to read")
    parser.add_argument("output", metavar="OUT", help="drawing to write")


def run(args: argparse.Namespace) -> int:
    """Read, write; return 0."""
    import os
    from pathlib import Path

    from auszug.errors import FormatError
    from auszug.formats import format_for, save
    from auszug.microarch.network import build

    _common.check_drawing_name(args.output)
    format_for(args.output, "drawing", want="write")
    src, dst = Path(args.input), Path(args.output)
    if dst.exists() and src.exists() and os.path.samefile(src, dst) or src.resolve() == dst.resolve():
        raise FormatError("is the input too: convert writes a new file and never overwrites its input "
                          "(give another OUT)", args.output)
    drawing = _common.read_drawing(args.input)
    with _common.about(args.input, drawing):   # a drawing that cannot be built is not written
        build(drawing)
    with _common.about(args.input):   # writer errors name OUT themselves; others are the drawing's
        save(drawing, args.output, kind="drawing")
    print(f"wrote {args.output}")
    return 0
