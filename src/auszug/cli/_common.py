"""Helpers shared by the commands: options, reading drawings, finding drawings in folders.

Nothing here computes geometry; building a network is one call to
:func:`auszug.microarch.build`.
"""

from __future__ import annotations

import argparse
import math
import os
import re
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Callable, Iterator, Sequence

from auszug.errors import AuszugError, DrawingError, FormatError

if TYPE_CHECKING:
    from auszug.formats.network_json import NetworkFile
    from auszug.microarch.model import Drawing

PARAMETERIZATIONS = ("arclength", "u", "orthographic")
#: ``--format`` names of the network formats and the file ending each writes.
NETWORK_SUFFIX = {"json": ".network.json", "obj": ".obj", "svg": ".svg", "dxf": ".dxf", "3dm": ".3dm"}


def at_least(minimum: int) -> Callable[[str], int]:
    """An argparse type: an integer >= ``minimum``."""

    def parse(text: str) -> int:
        try:
            v = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None
        if v < minimum:
            raise argparse.ArgumentTypeError(f"expected a whole number >= {minimum}, got {v}")
        return v

    return parse


def finite(text: str) -> float:
    """An argparse type: a finite number."""
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(v):
        raise argparse.ArgumentTypeError(f"expected a finite number, got {text!r}")
    return v


def positive(text: str) -> float:
    """An argparse type: a finite number > 0."""
    v = finite(text)
    if not v > 0.0:
        raise argparse.ArgumentTypeError(f"expected a number > 0, got {text!r}")
    return v


def add_network_args(parser: argparse.ArgumentParser, export: bool = False) -> None:
    """The options of :func:`auszug.microarch.build`: --param, --theta, --samples.

    With ``export``, also --tolerance: the network is then sampled by tolerance
    unless --samples is given.
    """
    g = parser.add_argument_group("reconstruction")
    g.add_argument("--param", choices=PARAMETERIZATIONS, default="arclength",
                   help="side-view coordinate p(u) of Eq. (1): top-view arc length (default), "
                        "the top curve's own parameter, or the orthographic projection at --theta")
    g.add_argument("--theta", type=finite, default=0.0, metavar="DEG",
                   help="angle of the vertical projection plane to the x-axis for "
                        "--param orthographic, in degrees (default 0)")
    if not export:
        g.add_argument("--samples", type=at_least(2), default=None, metavar="N",
                       help="samples per curve piece (default 65)")
        return
    g.add_argument("--tolerance", type=positive, default=None, metavar="T",
                   help="every written polyline lies within T (drawing units) of its exact curve, "
                        "both ways, with every end, apex, PRC, decoration cusp, free-end turn and "
                        "true 3D intersection a vertex (default: 1e-6 of the network's "
                        "bounding-box diagonal)")
    g.add_argument("--samples", type=at_least(2), default=None, metavar="N",
                   help="instead of --tolerance: N points per curve piece at equal arc-length steps")


def pixels(text: str) -> int:
    """An argparse type: a picture size in pixels, 50 to :attr:`auszug.limits.Limits.pixels`."""
    from auszug.limits import LIMITS

    v = at_least(50)(text)
    if v > LIMITS.pixels:
        raise argparse.ArgumentTypeError(f"{v} pixels is above the limit of {LIMITS.pixels} "
                                         "(auszug.limits.LIMITS.pixels)")
    return v


_WHERE = re.compile(r"curve (\d+)(?:, segment (-?\d+))?")


def placed(e: DrawingError, drawing: "Drawing", path: str | os.PathLike[str]) -> FormatError:
    """``e`` (about ``"curve 2, segment 1"``) as a FormatError at the line of the file it came from.

    Segments are named by the file's own point numbers (a web ``.uc`` curve's
    segment 1 runs from point 2 to point 4) and apex errors point at the line of
    the curve's height, where the curves were read with a
    :class:`~auszug.microarch.model.Source`.
    """
    where, line = e.where, None
    m = _WHERE.fullmatch(where or "")
    if m and int(m[1]) < len(drawing.curves) and (src := drawing.curves[int(m[1])].source) is not None:
        line = src.line
        if m[2] is not None and int(m[2]) >= 0:
            si = int(m[2])
            if src.segment(si):
                where = f"{where} ({src.segment(si)})"
                line = src.point_lines[si]
        elif "apex" in e.problem and src.height_line is not None:
            line = src.height_line
    return FormatError(f"{where}: {e.problem}" if where else e.problem, os.fspath(path), line)


@contextmanager
def about(path: str | os.PathLike[str], drawing: "Drawing | None" = None) -> Iterator[None]:
    """Name ``path`` in auszug errors raised inside the block that do not name a file yet.

    With the ``drawing`` read from ``path``, errors about one of its curves get
    the line it was read from (:func:`placed`).
    """
    try:
        yield
    except FormatError as e:
        if e.path is None:
            raise FormatError(e.problem, os.fspath(path), e.line) from None
        raise
    except DrawingError as e:
        if drawing is not None:
            raise placed(e, drawing, path) from None
        raise FormatError(str(e), os.fspath(path)) from None
    except AuszugError as e:
        raise FormatError(str(e), os.fspath(path)) from None


def check_drawing_name(path: str | os.PathLike[str]) -> None:
    """Refuse a file name that is not a drawing's (``x.network.json`` ends in ``.json`` too)."""
    from auszug.formats import suffix_of, suffixes

    if suffix_of(path, "drawing") is None:
        raise FormatError(f"not a drawing file name; drawings end in {', '.join(sorted(suffixes('drawing')))}",
                          os.fspath(path))


def read_drawing(path: str | os.PathLike[str]) -> "Drawing":
    """Read a drawing file in any registered drawing format."""
    from auszug.formats import load

    check_drawing_name(path)
    with about(path):
        return load(path, kind="drawing")


def build_network(drawing: "Drawing", source: str | os.PathLike[str], args: argparse.Namespace) -> "NetworkFile":
    """The network of ``drawing`` with the --param/--theta/--samples options in ``args``."""
    from auszug.formats.network_json import NetworkFile
    from auszug.microarch.network import build

    with about(source, drawing):
        if getattr(args, "tolerance", None) is not None and args.samples is not None:
            raise FormatError("give --tolerance or --samples, not both")
        net = build(drawing, args.param, math.radians(args.theta), args.samples)
        if hasattr(args, "tolerance") and args.samples is None:   # an export: sampled by tolerance
            return NetworkFile(net.with_intersections().resampled(tolerance=args.tolerance),
                               Path(source).name)
    return NetworkFile(net, Path(source).name)


def is_network_file(path: str | os.PathLike[str]) -> bool:
    """Whether ``path`` names a network JSON file (``x.network.json``), which holds exact curves."""
    return os.fspath(path).lower().endswith(".network.json")


def network_of(path: str | os.PathLike[str], args: argparse.Namespace, networks: bool = False) -> "NetworkFile":
    """Read the drawing at ``path`` and build its network; with ``networks``, read a ``.network.json`` as it is.

    A network file (written by ``auszug build`` or ``auszug lift``) gives its exact curves back
    with their symmetry groups; the reconstruction options do not apply to it. Without
    ``networks`` it is refused as not a drawing.
    """
    if networks and is_network_file(path):
        from auszug.formats import load
        from auszug.formats.network_json import NetworkFile, network_from_dict

        with about(path):
            doc = load(path, kind="network")
            return NetworkFile(network_from_dict(doc, os.fspath(path)), doc["source"])
    return build_network(read_drawing(path), path, args)


def stem(path: str | os.PathLike[str]) -> str:
    """File name without its drawing (or network file) ending: ``U.XI.28.fixed.uc`` -> ``U.XI.28.fixed``."""
    from auszug.formats import stem as file_stem

    return file_stem(path, "network" if is_network_file(path) else "drawing")


def find_drawings(inputs: Sequence[str]) -> list[tuple[Path, Path]]:
    """Drawing files named by ``inputs`` (files or folders searched recursively).

    Returns
    -------
    list of (path, relative folder)
        Each drawing and the folder, relative to the input folder it was found
        in, where its outputs go (``.`` for files named directly).

    Raises
    ------
    FormatError
        For a path that does not exist, or a folder without drawings.
    """
    from auszug.formats import suffix_of, suffixes

    out: list[tuple[Path, Path]] = []
    for arg in inputs:
        p = Path(arg)
        if p.is_dir():
            found = sorted(q for q in p.rglob("*") if q.is_file() and suffix_of(q.name, "drawing"))
            if not found:
                raise FormatError(f"no drawings ({', '.join(sorted(suffixes('drawing')))}) in this folder", arg)
            out.extend((q, q.parent.relative_to(p)) for q in found)
        elif p.exists():
            out.append((p, Path(".")))
        else:
            raise FormatError("no such file or folder", arg)
    return out


def run_jobs(jobs: Sequence[tuple[Path, Path]], verb: str, one: "Callable[[Path, Path], None]") -> list[str]:
    """Run ``one(src, dst)`` for every job, with a progress bar on a terminal.

    Returns the messages of the errors raised, of any kind, each naming its
    file (each job fails alone; KeyboardInterrupt stops the batch).
    """
    import sys

    from auszug.cli import unexpected
    from auszug.limits import clip

    errors: list[str] = []

    def guarded(src: Path, dst: Path) -> None:
        # a failed file of any kind is reported with its name, and the batch goes on
        try:
            one(src, dst)
        except AuszugError as e:
            errors.append(clip(str(e)))
        except OSError as e:
            errors.append(clip(f"{e.filename or src}: {e.strerror or e}"))
        except MemoryError:
            errors.append(f"{src}: out of memory")
        except Exception as e:  # a bug deep inside: name the file, go on with the others
            errors.append(clip(f"{src}: internal error: {unexpected(e)}"))

    if len(jobs) > 1 and sys.stderr.isatty():
        from rich.console import Console
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

        cols = (TextColumn(verb), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                TextColumn("{task.description}"))
        with Progress(*cols, console=Console(stderr=True), transient=True) as bar:
            task = bar.add_task("", total=len(jobs))
            for src, dst in jobs:
                bar.update(task, description=src.name)
                guarded(src, dst)
                bar.advance(task)
    else:
        for src, dst in jobs:
            guarded(src, dst)
    return errors
