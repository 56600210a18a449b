"""List the drawings bundled with auszug and the folder they are in.

The teaching sheet (teaching-sheet/), the Basel goldsmith drawings in the web
dialect (web/) and the legacy and v1 dialects (legacy/) ship inside the
package. Each line is a path that every command accepts, so the example lines
of the README and of the commands' --help work when typed.

examples:
  auszug examples
  auszug examples teaching-sheet
  auszug build $(auszug examples --path teaching-sheet/tn-2.uc) -o tn-2.obj
"""

from __future__ import annotations

import argparse

HELP = "list the bundled example drawings and where they are"


def add_args(parser: argparse.ArgumentParser) -> None:
    """Options of ``auszug examples``."""
    parser.add_argument("folder", nargs="?", default="", metavar="FOLDER",
                        help="only the drawings below this folder (teaching-sheet, web, legacy)")
    parser.add_argument("--path", metavar="NAME", default=None,
                        help="print the full path of one bundled drawing, e.g. teaching-sheet/tn-2.uc")


def run(args: argparse.Namespace) -> int:
    """Print the folder and the drawings' paths; return 0."""
    from pathlib import Path

    from auszug import examples
    from auszug.errors import FormatError

    root = Path(examples.path("teaching-sheet/tn-1.uc")).parent.parent
    if args.path is not None:
        try:
            print(examples.path(args.path))
        except FileNotFoundError:
            raise FormatError("no such bundled drawing; 'auszug examples' lists them", args.path) from None
        return 0
    names = examples.names(args.folder) if args.folder else examples.names()
    if not names:
        raise FormatError("no bundled drawings in this folder; there are teaching-sheet, web and legacy",
                          args.folder)
    print(f"bundled drawings in {root}:")
    for name in names:
        print(f"  {root / name}")
    return 0
