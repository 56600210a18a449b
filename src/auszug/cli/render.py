"""Render a drawing's network as a figure: top view, side view and a perspective 3D view.

Like the paper's Fig. 9, side by side, every replica in its basic curve's
colour, equal aspect in each view; round markers are the points of reverse
curvature. The ending of OUT picks the format: .png, .svg or .pdf. Without -o
the figure goes to <stem>.png in the current folder.

examples:
  auszug render tn-11.uc -o tn-11.png
  auszug render U.XI.28.uc -o fig.pdf --width 2400 --height 800
"""

from __future__ import annotations

import argparse
from pathlib import Path

from auszug.cli import _common

HELP = "draw a figure of top, side and 3D views (.png, .svg, .pdf)"


def _dpi(text: str) -> int:
    """10 to 2400 dots per inch: beyond, matplotlib draws letters larger than the figure."""
    v = _common.at_least(10)(text)
    if v > 2400:
        raise argparse.ArgumentTypeError(f"expected at most 2400 dots per inch, got {v}")
    return v


def add_args(parser: argparse.ArgumentParser) -> None:
    """Options of ``auszug render``."""
    parser.add_argument("drawing", metavar="DRAWING",
                        help="a drawing file (.uc, .json) or a network file (.network.json)")
    parser.add_argument("-o", "--output", metavar="FIG", help="figure file: .png, .svg or .pdf")
    g = parser.add_argument_group("figure")
    g.add_argument("--width", type=_common.pixels, default=1800, metavar="PX",
                   help="width in pixels (default 1800)")
    g.add_argument("--height", type=_common.pixels, default=620, metavar="PX",
                   help="height in pixels (default 620)")
    g.add_argument("--dpi", type=_dpi, default=150,
                   help="dots per inch: text and line size relative to the pixels (default 150)")
    g.add_argument("--title", default=None, help="figure title (default: the file name)")
    _common.add_network_args(parser)


def run(args: argparse.Namespace) -> int:
    """Render and write the figure; return 0."""
    from auszug.formats import atomic_write, format_for

    out = Path(args.output) if args.output else Path(_common.stem(args.drawing) + ".png")
    fmt = format_for(out, "figure", want="write")
    ext = max((s for s in fmt.suffixes if out.name.lower().endswith(s)), key=len)
    nf = _common.network_of(args.drawing, args, networks=True)
    from auszug.formats.figure import render

    with _common.about(out):
        data = render(nf, ext, width=args.width, height=args.height, dpi=args.dpi, title=args.title)
        atomic_write(out, data)
    print(f"wrote {out}")
    return 0
