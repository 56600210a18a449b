"""Find the parts of a mesh that a planar profile sweeps (Barton, Pottmann, Wallner 2014).

MESH is a triangle mesh (.obj, .stl, .ply, .glb, .gltf): a scan of a moulding, a pier, a tracery
border. The result, OUT.sweeps.json (default <stem>.sweeps.json), lists the sweep patches: per
patch the profile, the rigid motion that sweeps it (at least 8 maps from its first rib to its
last), the mesh faces it covers and its fit error; and the coverage of the mesh (see
docs/formats.md). Surfaces of revolution, extrusions and helical surfaces are recognised as such
(every cut moves); other sweeps go through the paper's plane search, matching, rib ordering and
motion fit (see docs/sweeps.md).

--glb and --png also write the mesh coloured by patch with the profiles (black) and the paths of
their centroids (red). --explain prints what each stage kept. One progress line per stage goes to
stderr (a bar on a terminal). Outputs are written only when the analysis succeeded: a mesh that
cannot be analysed (empty, NaN coordinates, an edge of three faces, a face repeating a vertex,
more than 1 000 000 triangles, an unknown format) leaves no file and exits with code 2.

examples:
  auszug sweeps base.stl -o base.sweeps.json --explain
  auszug sweeps pier.ply --eps-prox 0.002 --png pier.png --glb pier.glb
  auszug sweeps scan.obj --planes 1452 --percentile 1
  auszug sweeps member.stl --match-scale 0.25 --match-runs 2000 --eps-prox 0.002   # a thin bar
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any

from auszug.cli import _common

HELP = "find swept parts of a mesh: profiles, motions, covered faces (.sweeps.json)"


def _fraction(text: str) -> float:
    v = _common.positive(text)
    if v > 0.1:
        raise argparse.ArgumentTypeError(f"expected a share of the bounding-box diameter in (0, 0.1], got {v:g}")
    return v


def _scale(text: str) -> float:
    v = _common.positive(text)
    if v > 1:
        raise argparse.ArgumentTypeError(f"expected a factor in (0, 1], got {v:g}")
    return v


def add_args(parser: argparse.ArgumentParser) -> None:
    """Options of ``auszug sweeps`` (the analysis is imported only when it runs)."""
    parser.add_argument("mesh", metavar="MESH", help="a triangle mesh: .obj, .stl, .ply, .glb, .gltf")
    parser.add_argument("-o", "--output", metavar="OUT", help="result file .sweeps.json (default <stem>.sweeps.json)")
    parser.add_argument("--glb", metavar="F", help="also write the mesh coloured by patch, profiles and paths (.glb)")
    parser.add_argument("--png", metavar="F", help="also draw the mesh coloured by patch (.png, .svg, .pdf)")
    parser.add_argument("--explain", action="store_true", help="print what every stage kept, and the patches")
    parser.add_argument("--quiet", action="store_true", help="no progress")
    g = parser.add_argument_group("analysis (lengths are shares of the bounding-box diameter)")
    g.add_argument("--eps-prox", type=_fraction, default=None, metavar="X",
                   help="fit threshold: faces within X of a swept surface are covered; patches must fit within "
                        "2 X (default 0.005; the paper: 0.001-0.01)")
    g.add_argument("--planes", type=_common.at_least(10), default=None, metavar="N",
                   help="about N initial planes (default: offsets 0.055 apart, 800-1100 planes)")
    g.add_argument("--percentile", type=_common.positive, default=None, metavar="G",
                   help="share g (percent) of the planes kept as good each round (default 5; the paper: 1, 3, 5)")
    g.add_argument("--refinements", type=_common.at_least(0), default=None, metavar="R",
                   help="rounds of plane refinement (default 3)")
    g.add_argument("--eps-match", type=_common.positive, default=None, metavar="E",
                   help="matching threshold of Eq. 6 (default 0.1; the paper: 0.01 or 0.1)")
    g.add_argument("--l-min", type=_common.positive, default=None, metavar="L",
                   help="shortest movable run and match (default 0.2)")
    g.add_argument("--match-scale", type=_scale, default=None, metavar="F",
                   help="profiles F times as long as the defaults expect, F in (0, 1]: l-min, the curvature "
                        "windows and the match spacing times F (a thin member: 0.25; an explicit --l-min wins)")
    g.add_argument("--match-runs", type=_common.at_least(2), default=None, metavar="N",
                   help="at most N movable runs, longest first, are matched (default 600)")
    g.add_argument("--match-angle", type=_common.positive, default=None, metavar="DEG",
                   help="cuts whose planes meet at more than DEG are not matched (default 25)")
    g.add_argument("--parts", type=_common.at_least(0), default=None, metavar="N",
                   help="at most N motions tried for kinematic parts, 0 = none (default 8; beyond the paper: "
                        "pieces that are each an extrusion or a surface of revolution, docs/sweeps.md)")
    g.add_argument("--mirror-planes", type=_common.at_least(0), default=None, metavar="N",
                   help="at most N mirror planes whose images of fitting candidates are tried, 0 = none "
                        "(default 2, at most 3; beyond the paper, docs/sweeps.md)")
    g.add_argument("--coverage-samples", type=_common.at_least(0), default=None, metavar="N",
                   help="at most N area samples for the coverage of faces no patch covers whole "
                        "(default 100000, at most 10000000; 0: whole faces only)")
    g.add_argument("--twist-steps", type=_common.at_least(0), default=None, metavar="N",
                   help="point-to-plane steps refining each knot's rigid map of a general sweep, 0 = the "
                        "paper's motion only (default 4, at most 64; beyond the paper, docs/sweeps.md)")
    g.add_argument("--arc-axes", type=_common.at_least(0), default=None, metavar="N",
                   help="at most N axes of crease arcs tried as short rotations, 0 = no stage 'arcs' "
                        "(default 16, at most 256; beyond the paper, docs/sweeps.md)")
    g.add_argument("--arc-crease", type=_common.positive, default=None, metavar="DEG",
                   help="an edge is a crease for the stage 'arcs' when its faces' normals differ by at "
                        "least DEG (default 20, below 180)")


def _params(args: argparse.Namespace) -> Any:
    from auszug.sweeps import DEFAULT

    changes = {name: getattr(args, opt) for opt, name in (
        ("eps_prox", "eps_prox"), ("planes", "initial_plane_count"), ("percentile", "percentile"),
        ("refinements", "refinements"), ("eps_match", "eps_match"), ("match_runs", "max_match_runs"),
        ("match_angle", "match_angle"), ("parts", "max_parts"), ("mirror_planes", "mirror_planes"),
        ("coverage_samples", "coverage_samples"), ("twist_steps", "twist_steps"), ("arc_axes", "arc_axes"),
        ("arc_crease", "arc_crease")) if getattr(args, opt) is not None}
    params = DEFAULT.with_(**changes)
    if args.match_scale is not None:
        params = params.with_scale(args.match_scale)
    if args.l_min is not None:     # an explicit --l-min wins over the scale
        params = params.with_(l_min=args.l_min)
    return params


def run(args: argparse.Namespace) -> int:
    """Read, analyse, write; return 0."""
    from auszug.errors import FormatError
    from auszug.formats import atomic_write_all, format_for, load, stem
    from auszug.sweeps import detect

    src = Path(args.mesh)
    format_for(src, "mesh")
    out = Path(args.output) if args.output else Path(stem(src, "mesh") + ".sweeps.json")
    format_for(out, "sweeps", want="write")
    if args.glb:
        format_for(args.glb, "mesh", want="write")
    fig_ext = ""
    if args.png:
        fig = format_for(args.png, "figure", want="write")
        fig_ext = max((s for s in fig.suffixes if args.png.lower().endswith(s)), key=len)
    for extra in (args.glb, args.png):
        if extra and Path(extra).resolve() in (src.resolve(), out.resolve()):
            raise FormatError("an extra output must not be the input or the result file", extra)
    with _common.about(src):
        params = _params(args)
    t0 = time.perf_counter()
    with _common.about(src):
        mesh = load(src, kind="mesh")
    _say(args, f"read {mesh.n_vertices} vertices, {mesh.n_faces} triangles in {time.perf_counter() - t0:.2f} s")
    with _common.about(src):
        report = _detect(args, detect, mesh, params, src.name)
    # every output made in memory first, then all written together (all or nothing: a failing
    # picture leaves no result file behind)
    outputs: list[tuple[Path, str | bytes]] = []
    with _common.about(out):
        outputs.append((out, _encode(report, out, "sweeps")))
    if args.glb:
        from auszug.formats.sweeps_figure import sweeps_scene

        glb = Path(args.glb)
        with _common.about(glb):
            outputs.append((glb, _encode(sweeps_scene(mesh.vertices, mesh.faces, report), glb, "mesh")))
    if args.png:
        from auszug.formats.sweeps_figure import render_sweeps

        with _common.about(args.png):
            outputs.append((Path(args.png), render_sweeps(mesh.vertices, mesh.faces, report, fig_ext)))
    with _common.about(out):
        atomic_write_all(outputs)
    if args.explain:
        print(report.explain())
    _say(args, f"done in {time.perf_counter() - t0:.2f} s")
    extras = [str(x) for x in (args.glb, args.png) if x]
    print(f"wrote {out}" + (f" and {', '.join(extras)}" if extras else "")
          + f": {len(report.patches)} patch(es), coverage {report.coverage:.3f}")
    return 0


def _encode(obj: Any, path: Path, kind: str) -> str | bytes:
    """``obj`` as the file ``path`` would hold it (the format its name says), not written."""
    from auszug.formats import format_for

    fmt = format_for(path, kind, want="write")
    assert fmt.writer is not None
    return fmt.writer(obj, path.name)


def _say(args: argparse.Namespace, line: str) -> None:
    if not args.quiet:
        print(f"sweeps: {line}", file=sys.stderr, flush=True)


def _detect(args: argparse.Namespace, detect: Any, mesh: Any, params: Any, source: str) -> Any:
    """Run the analysis with a progress bar per stage (terminal) or a line per stage (else)."""
    if args.quiet:
        return detect(mesh, params, source=source)
    if sys.stderr.isatty():
        from rich.console import Console
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

        cols = (TextColumn("sweeps"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                TextColumn("{task.description}"))
        with Progress(*cols, console=Console(stderr=True), transient=True) as bar:
            task = bar.add_task("", total=None)

            def show(name: str, done: int, total: int) -> None:
                bar.update(task, completed=done, total=total, description=name)

            return detect(mesh, params, progress=show, source=source)

    def line(name: str, done: int, total: int) -> None:
        if done < total:
            print(f"sweeps: stage {done + 1}/{total}: {name}", file=sys.stderr, flush=True)

    return detect(mesh, params, progress=line, source=source)
