"""Describe a drawing and its network: symmetry, curves, heights, PRCs, top-view intersections.

The PRC table says where each point of reverse curvature came from: the
drawing file, or the branch of Algorithm 1 (paper suppl. C) that chose it
(the true intersection with the curve's own replicas, an intersection with
another basic curve, or the midpoint). The intersection table lists every
top-view intersection of a basic segment with a replica and whether the 3D
curves really meet there (true) or only cross in the top view (false).

examples:
  auszug info tn-11.uc
  auszug info U.XI.28.uc --limit 0
"""

from __future__ import annotations

import argparse
import math
import sys
from typing import Any

from auszug.cli import _common

HELP = "describe a drawing: symmetry, curves, intersections, PRCs, heights"

#: Intersection rows shown by default.
MAX_ROWS = 24


def add_args(parser: argparse.ArgumentParser) -> None:
    """Options of ``auszug info``."""
    parser.add_argument("drawing", metavar="DRAWING", help="a drawing file (.uc, .json)")
    parser.add_argument("--limit", type=_common.at_least(0), default=MAX_ROWS, metavar="N",
                        help=f"list at most N intersections (default {MAX_ROWS}; 0: all)")
    _common.add_network_args(parser)


def _num(v: float | None, digits: int = 4) -> str:
    return "-" if v is None else f"{v:.{digits}f}"


def _symmetry(s: Any) -> str:
    text = f"C{s.fold}"
    if s.mirror:
        ang = math.degrees(math.atan2(s.axis[1], s.axis[0])) % 180.0
        text += f" + mirror (axis {ang:.1f} deg)"
    if tuple(s.center) != (0.0, 0.0):
        text += f" about ({s.center[0]:g}, {s.center[1]:g})"
    return text


def _intersections(drawing: Any) -> tuple[list[Any] | None, str]:
    """The top-view intersections, or None and why they are not available."""
    try:
        from auszug.microarch.prc import intersections
    except ImportError as e:
        return None, f"not available: {e}"
    return list(intersections(drawing)), ""


def run(args: argparse.Namespace) -> int:
    """Print the tables; return 0."""
    from rich import box
    from rich.console import Console
    from rich.table import Table

    nf = _common.network_of(args.drawing, args)
    net, d = nf.network, nf.network.drawing
    with _common.about(args.drawing):
        inters, why = _intersections(d)
    curves = list(net.curves())
    console = Console(width=None if sys.stdout.isatty() else 120, highlight=False)

    groups = sorted({_symmetry(c.symmetry) for c in d.curves})
    console.print(f"[bold]{nf.source}[/bold]: {len(d.curves)} basic curves, "
                  f"{len(curves)} network curves, {len(net.bottoms)} layer(s); "
                  f"parameterization {net.parameterization}")
    console.print(f"symmetry: {'; '.join(groups)}")

    t = Table(title="basic curves", box=box.SIMPLE_HEAD, title_justify="left")
    for col in ("curve", "symmetry", "layer", "segments", "replicas", "bottom", "apex", "post top"):
        t.add_column(col, justify="right" if col in ("curve", "layer", "replicas", "bottom", "apex", "post top")
                     else "left")
    for i, c in enumerate(d.curves):
        kinds = ", ".join(c.segment_kind(s) for s in range(len(c.segments)))
        extra = [k for k in ("decoration",) if getattr(c, k)]
        t.add_row(str(i), _symmetry(c.symmetry), str(c.layer), kinds + (f" ({', '.join(extra)})" if extra else ""),
                  str(c.symmetry.order), _num(net.bottoms[c.layer]), _num(net.apex_heights[i]),
                  _num(c.post_top))
    console.print(t)

    t = Table(title="layers", box=box.SIMPLE_HEAD, title_justify="left")
    t.add_column("layer", justify="right")
    t.add_column("bottom", justify="right")
    t.add_column("curves", justify="left")
    for li, z in enumerate(net.bottoms):
        t.add_row(str(li), _num(z), ", ".join(str(i) for i, c in enumerate(d.curves) if c.layer == li))
    console.print(t)

    t = Table(title="points of reverse curvature", box=box.SIMPLE_HEAD, title_justify="left")
    for col in ("curve", "segment", "fraction", "x", "y", "height", "chosen by"):
        t.add_column(col, justify="left" if col == "chosen by" else "right")
    for p in net.pieces:
        if p.kind != "ogee" or p.prc is None:
            continue
        ch = net.prc_choices.get((p.basic, p.segment))
        how = "drawing file" if ch is None else f"Algorithm 1: {getattr(ch, 'branch', ch)}"
        t.add_row(str(p.basic), str(p.segment), _num(p.prc_fraction), _num(p.prc[0]), _num(p.prc[1]),
                  _num(p.prc[2]), how)
    console.print(t)

    if inters is None:
        console.print(f"top-view intersections: {why}")
    else:
        n_true = sum(1 for r in inters if getattr(r, "true", False))
        console.print(f"top-view intersections: {len(inters)} ({n_true} true, {len(inters) - n_true} false)")
        if inters:
            t = Table(box=box.SIMPLE_HEAD)
            for col in ("curve.segment", "meets", "replica", "u", "u other", "x", "y", "true"):
                t.add_column(col, justify="right")
            rows = inters[:args.limit] if args.limit else inters
            for r in rows:
                u = getattr(r, "u", getattr(r, "t", None))
                uo = getattr(r, "u_other", getattr(r, "t_other", None))
                pt = getattr(r, "point", (math.nan, math.nan))
                t.add_row(f"{r.curve}.{r.segment}", f"{r.other_curve}.{r.other_segment}",
                          str(getattr(r, "replica", "")), _num(u), _num(uo), _num(pt[0]), _num(pt[1]),
                          "true" if r.true else "false")
            console.print(t)
            if len(rows) < len(inters):
                console.print(f"({len(inters) - len(rows)} more; use --limit 0 to list all)")
    return 0
