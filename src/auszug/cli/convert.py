"""Convert a drawing between drawing formats; the file endings pick the formats.

Reads any drawing format (.uc in the web, legacy or v1 dialect; .json, auszug's
native format) and writes a writable one (.uc in the web dialect, .json).
Automatic PRCs are written as Algorithm 1 chose them. The output is written
atomically: a failure leaves no file.

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
    from auszug.formats import format_for, save

    _common.check_drawing_name(args.output)
    format_for(args.output, "drawing", want="write")
    drawing = _common.read_drawing(args.input)
    with _common.about(args.input):   # writer errors name OUT themselves; others are the drawing's
        save(drawing, args.output, kind="drawing")
    print(f"wrote {args.output}")
    return 0
