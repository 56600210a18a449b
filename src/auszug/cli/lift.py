"""Lift a 2D design sketch to the 3D curve network it depicts (True2Form, Xu et al. 2014).

SKETCH is an SVG as Inkscape or Illustrator write it (paths of any kind,
layers as independent parts; occlusion and flip marker circles and a symmetry
path as annotations, see docs/formats.md) or a .sketch.json. The ending of
OUT picks the network format: .network.json, .obj, .svg, .dxf, .3dm; or a
mesh of the network's curves swept as tubes (--style, --size): .glb, .gltf,
.stl, .ply (.obj is the network's polylines). x and y are the sketch's own
(y up), z is the lifted depth toward the viewer. Without -o the network goes
to <stem>.network.json in the current folder.

One progress line per solve goes to stderr. The output is written
atomically: a sketch that cannot be lifted leaves no file (exit code 2).

examples:
  auszug lift vase.svg -o vase.network.json
  auszug lift vase.svg -o vase.obj --report --render vase.png
  auszug lift vase.svg -o vase.glb --style tube --size 2
  auszug lift vase.svg --cues none        # the baseline: hard orthogonality at smooth crossings only
  auszug lift vase.svg --set family_prior=off --set w_f=0.01   # LiftParams fields (its docstring)
  auszug lift drawn.svg --set close_gaps=0.005   # join stroke ends drawn up to 0.5 % of the diagonal apart,
                                                # and crossings drawn that near one point
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import TYPE_CHECKING

from auszug.cli import _common

if TYPE_CHECKING:
    from auszug.lifting import LiftParams, LiftResult

HELP = "lift a 2D design sketch (.svg, .sketch.json) to a 3D curve network"
#: Output endings written as a mesh of the lifted curves (the rest are network formats).
MESH_SUFFIXES = (".glb", ".gltf", ".stl", ".ply")
#: Mesh output defaults: a lifted piece is one cubic Bezier, so fewer steps than a drawing's member need.
MESH_SEGMENTS = 48
MESH_AROUND = 16
#: ``lifting.CLASSES`` and ``lifting.DEFAULT_CLASSES``, for the help text (a test keeps them equal).
CUE_CLASSES = ("parallel", "orthogonal", "symmetry", "linear", "planar", "plane")
DEFAULT_CUES = ("parallel", "orthogonal", "planar")


def add_args(parser: argparse.ArgumentParser) -> None:
    """Options of ``auszug lift``.

    Building the parser does not import the lifting package (every command builds it): the cue
    classes below are named as text, and tests/cli/test_lift.py checks them against
    ``lifting.CLASSES`` and ``lifting.DEFAULT_CLASSES``.
    """
    parser.add_argument("sketch", metavar="SKETCH", help="a sketch: .svg or .sketch.json")
    parser.add_argument("-o", "--output", metavar="OUT",
                        help="network file: .network.json, .obj, .svg, .dxf, .3dm, or a mesh of the curves: "
                             ".glb, .gltf, .stl, .ply (default <stem>.network.json)")
    parser.add_argument("--style", choices=("tube", "bar", "ribbon"), default="tube",
                        help="cross-section of the curves in a mesh output (default tube)")
    parser.add_argument("--size", type=_common.positive, default=None, metavar="S",
                        help="tube diameter / bar side / ribbon width over 3 in a mesh output, sketch units "
                             "(default 1.2%% of the network's bounding-box diagonal)")
    parser.add_argument("--segments", type=_common.at_least(1), default=MESH_SEGMENTS, metavar="N",
                        help=f"steps along each Bezier piece in a mesh output (default {MESH_SEGMENTS})")
    parser.add_argument("--around", type=_common.at_least(2), default=None, metavar="N",
                        help=f"points around a tube in a mesh output (default {MESH_AROUND}; 4 for bars, ribbons)")
    parser.add_argument("--report", action="store_true",
                        help="print the cues applied and their final angles (and how many were rejected)")
    parser.add_argument("--render", metavar="FIG",
                        help="also draw a figure (.png, .svg, .pdf): the sketch with the regularities found, "
                             "and the lifted network from above and in 3D")
    parser.add_argument("--cues", default=None, metavar="LIST",
                        help=f"cue classes to resolve, comma-separated from {', '.join(CUE_CLASSES)}, or 'none' "
                             f"(default {','.join(DEFAULT_CUES)})")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE", dest="params",
                        help="set a field of auszug.lifting.LiftParams (repeatable), e.g. family_prior=off, "
                             "w_f=0.01, rounds=4; switches take on/off, true/false, yes/no, 1/0; an unknown name lists "
                             "the fields, described in the LiftParams docstring")
    parser.add_argument("--quiet", action="store_true", help="no progress lines")


def _classes(text: str | None) -> tuple[str, ...]:
    from auszug.errors import FormatError
    from auszug.lifting import CLASSES

    if text is None:
        from auszug.lifting import DEFAULT_CLASSES

        return DEFAULT_CLASSES
    if text.strip().lower() == "none":
        return ()
    got = [c.strip() for c in text.split(",") if c.strip()]
    bad = [c for c in got if c not in CLASSES]
    if bad:
        raise FormatError(f"--cues: unknown cue class {bad[0]!r}; expected some of {', '.join(CLASSES)} or 'none'")
    return tuple(c for c in CLASSES if c in got)


_TRUE = ("1", "on", "true", "yes")
_FALSE = ("0", "off", "false", "no")


def parse_params(items: list[str]) -> "LiftParams":
    """``--set NAME=VALUE`` items as :class:`~auszug.lifting.LiftParams` (the defaults elsewhere).

    A field's type is its default's (bool, int or float); an unknown name, a value of the wrong
    kind or one outside the field's limits (``LiftParams.__post_init__``) is a ``GeometryError``
    naming the item (as ``auszug sweeps`` reports its parameters). ``benchmarks/eval_lifting.py
    --params`` reads its items with it too.
    """
    import dataclasses

    from auszug.errors import GeometryError
    from auszug.lifting import LiftParams

    default = LiftParams()
    names = [f.name for f in dataclasses.fields(LiftParams)]
    kw: dict[str, bool | int | float] = {}
    for item in items:
        name, sep, text = item.partition("=")
        name, text = name.strip(), text.strip()
        if not sep or not name or not text:
            raise GeometryError(f"--set {item!r}: expected NAME=VALUE, e.g. family_prior=off")
        if name not in names:
            raise GeometryError(f"--set {item!r}: LiftParams has no field {name!r}; fields: {', '.join(names)}")
        kind = type(getattr(default, name))
        try:
            if kind is bool:
                if text.lower() not in _TRUE + _FALSE:
                    raise ValueError
                kw[name] = text.lower() in _TRUE
            else:
                kw[name] = kind(text)
        except ValueError:
            want = "on or off" if kind is bool else "an integer" if kind is int else "a number"
            raise GeometryError(f"--set {item!r}: {name} must be {want}") from None
    try:
        return LiftParams(**kw)  # type: ignore[arg-type]
    except GeometryError as e:
        raise GeometryError(f"--set: {e}") from None


def run(args: argparse.Namespace) -> int:
    """Read, lift, write; return 0."""
    import time

    from auszug.formats import format_for, load, save, stem
    from auszug.formats.network_json import NetworkFile
    from auszug.lifting import lift

    src = Path(args.sketch)
    classes = _classes(args.cues)
    params = parse_params(args.params)
    format_for(src, "sketch")
    out = Path(args.output) if args.output else Path(stem(src, "sketch") + ".network.json")
    as_mesh = out.name.lower().endswith(MESH_SUFFIXES)
    format_for(out, "mesh" if as_mesh else "network", want="write")
    if args.render:
        fig_fmt = format_for(args.render, "figure", want="write")
        fig_ext = max((s for s in fig_fmt.suffixes if args.render.lower().endswith(s)), key=len)

    def say(line: str) -> None:
        if not args.quiet:
            print(f"lift: {line}", file=sys.stderr, flush=True)

    t0 = time.perf_counter()
    with _common.about(src):
        sketch = load(src, kind="sketch")
    say(f"read {len(sketch.strokes)} strokes, {len(sketch.markers)} markers, "
        f"{max(s.layer for s in sketch.strokes) + 1} layer(s) in {time.perf_counter() - t0:.2f} s")
    with _common.about(src):
        result = lift(sketch, params=params, progress=say, classes=classes)
    n_gaps = sum(len(g.gaps) for g in result.graphs)
    if n_gaps:
        say(f"closed {n_gaps} gap(s) of at most {params.close_gaps:.2%} of the diagonal (close_gaps; see --report)")
    n_junctions = sum(len(g.junctions) for g in result.graphs)
    if n_junctions:
        say(f"made {n_junctions} group(s) of crossings drawn within {params.close_gaps:.2%} of the diagonal one "
            "point each (close_gaps; see --report)")
    for line in _junction_hints(result, params):
        say(line)
    if not result.converged:
        say("warning: not every solve converged; the hard cues may be violated (see --report)")
    with _common.about(out):
        if as_mesh:
            from auszug.meshing import Look, mesh_network

            around = args.around if args.around is not None else MESH_AROUND if args.style == "tube" else None
            look = Look(style=args.style, size=args.size, around=around, segments=args.segments)
            mesh = mesh_network(result.network, look).mesh
            save(mesh, out, kind="mesh")
        else:
            save(NetworkFile(result.network, src.name), out, kind="network")
    if args.render:
        from auszug.formats import atomic_write
        from auszug.formats.lift_figure import render_lift

        with _common.about(args.render):
            atomic_write(args.render, render_lift(sketch, result, fig_ext))
    if args.report:
        _report(result, classes)
    say(f"done in {time.perf_counter() - t0:.2f} s")
    print(f"wrote {out}" + (f" and {args.render}" if args.render else ""))
    return 0


def _junction_hints(result: "LiftResult", params: "LiftParams") -> list[str]:
    """A note per group of crossings of three or more strokes drawn within 1 % of the diagonal, not joined."""
    from auszug.lifting import junction_hints

    lines = []
    for g in result.graphs:
        for spread, strokes, want in junction_hints(g, params):
            names = ", ".join(g.stroke_name(s) for s in strokes)
            lines.append(f"note: {names} cross within {100 * spread:.2g}% of the diagonal of one another, not at "
                         f"one point; if they meet at one point, --set close_gaps={want:g} makes it one intersection")
    return lines


def _report(result: "LiftResult", classes: tuple[str, ...]) -> None:
    """The applied cues, one a line, with their final angles; then the rejected counts."""
    from collections import Counter

    cues = result.cues
    applied = [c for c in cues if c.applied]
    print(f"cues applied: {len(applied)} of {len(cues)} candidates; converged: {result.converged}")
    width = max((len(c.where) for c in applied), default=0)
    for c in applied:
        print(f"  {c.kind:<18} {c.where:<{width}}  {c.angle:8.3f} deg" + (f"  (layer {c.layer})" if c.layer else ""))
    rejected = Counter(c.kind for c in cues if not c.applied and c.kind in classes)
    skipped = Counter(c.kind for c in cues if not c.applied and c.kind not in classes)
    if rejected:
        print("rejected: " + ", ".join(f"{n} {k}" for k, n in sorted(rejected.items())))
    if skipped:
        print("not tried (--cues): " + ", ".join(f"{n} {k}" for k, n in sorted(skipped.items())))
    worst = max((c.angle for c in applied), default=0.0)
    print(f"largest angle of an applied cue: {worst:.3f} deg")
    for g in result.graphs:
        layer = g.strokes[0].layer
        for gap in g.gaps:
            name, other = g.stroke_name(gap.stroke), g.stroke_name(gap.to)
            what = {"trim": f"cut {gap.distance:.3%} of the diagonal beyond its crossing with {other}",
                    "extend": f"moved {gap.distance:.3%} of the diagonal onto {other}",
                    "end": f"moved {gap.distance:.3%} of the diagonal to meet {other}'s end",
                    "close": f"moved {gap.distance:.3%} of the diagonal onto its start (closed)"}[gap.kind]
            print(f"gap closed: {name} {'start' if gap.end == 0 else 'end'} {what}"
                  + (f"  (layer {layer})" if layer else ""))
        for j in g.junctions:
            names = ", ".join(g.stroke_name(s) for s in j.strokes)
            print(f"crossings joined: {names} drawn within {100 * j.spread:.3g}% of the diagonal, made one point "
                  f"(strokes moved at most {100 * j.distance:.3g}%)" + (f"  (layer {layer})" if layer else ""))
    if result.mirror is not None:
        layer, n, d = result.mirror
        print(f"global symmetry: layer {layer} mirrored across the plane "
              f"({n[0]:.6f}, {n[1]:.6f}, {n[2]:.6f}) . p = {d:.6g}")
