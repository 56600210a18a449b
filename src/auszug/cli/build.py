"""Build the 3D curve network of drawings and write it as network JSON, OBJ polylines or SVG.

One drawing and OUT a file: the ending of OUT picks the format
(.network.json, .obj, .svg). Several drawings or a folder (searched
recursively for drawings): OUT is a folder (created if needed) and every
drawing gives OUT/<subfolder>/<stem>.network.json, or the --format chosen.
Without -o the output goes to the current folder.

Each output file is written atomically: a drawing that fails leaves no file;
the others are still written, and the exit code is 2.

examples:
  auszug build tn-1.uc -o tn-1.network.json
  auszug build tn-1.uc -o tn-1.obj --tolerance 1e-5
  auszug build tn-1.uc -o tn-1.obj --samples 129
  auszug build corpus/ -o out/ --format svg
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from auszug.cli import _common

HELP = "build 3D curve networks from drawings (network JSON, OBJ, SVG)"


def add_args(parser: argparse.ArgumentParser) -> None:
    """Options of ``auszug build``."""
    parser.add_argument("drawings", nargs="+", metavar="DRAWING",
                        help="drawing files (.uc, .json) or folders of them")
    parser.add_argument("-o", "--output", metavar="OUT",
                        help="output file (one drawing) or folder (several drawings or a folder)")
    parser.add_argument("--format", choices=sorted(_common.NETWORK_SUFFIX), default=None,
                        help="output format in a folder, or without -o (default json)")
    _common.add_network_args(parser, export=True)


def _is_folder_target(out: str | None) -> bool:
    return out is not None and (Path(out).is_dir() or out.endswith(("/", os.sep)))


def run(args: argparse.Namespace) -> int:
    """Build and write; return 0, or 2 if any drawing failed."""
    from auszug.errors import FormatError
    from auszug.formats import format_for

    items = _common.find_drawings(args.drawings)
    several = len(items) > 1 or any(Path(d).is_dir() for d in args.drawings)
    if not several and not _is_folder_target(args.output):
        src = items[0][0]
        if args.output:
            out = Path(args.output)
            fmt = format_for(out, "network", want="write")
            if args.format and _common.NETWORK_SUFFIX[args.format] not in fmt.suffixes:
                raise FormatError(f"--format {args.format} does not match the file ending of the output",
                                  args.output)
        else:
            out = Path(_common.stem(src) + _common.NETWORK_SUFFIX[args.format or "json"])
        _write_one(src, out, args)
        print(f"wrote {out}")
        return 0

    out_dir = Path(args.output) if args.output else Path(".")
    if out_dir.exists() and not out_dir.is_dir():
        raise FormatError("several drawings need an output folder, but this is a file", str(out_dir))
    if not out_dir.exists() and args.output and not _is_folder_target(args.output):
        try:
            format_for(out_dir, "network", want="write")
        except FormatError:
            pass
        else:
            raise FormatError("several drawings need an output folder, not a file name "
                              "(give a folder, e.g. 'out/')", args.output)
    suffix = _common.NETWORK_SUFFIX[args.format or "json"]
    jobs: list[tuple[Path, Path]] = []
    seen: dict[Path, Path] = {}
    for src, rel in items:
        dst = out_dir / rel / (_common.stem(src) + suffix)
        if dst in seen:
            raise FormatError(f"{seen[dst]} and {src} would both be written to {dst}; "
                              "build them separately", str(src))
        seen[dst] = src
        jobs.append((src, dst))
    errors = _write_many(jobs, args)
    for msg in errors:
        print(f"auszug: {msg}", file=sys.stderr)
    done = len(jobs) - len(errors)
    print(f"wrote {done} of {len(jobs)} networks to {out_dir}" + (f" ({len(errors)} failed)" if errors else ""))
    return 2 if errors else 0


def _write_one(src: Path, out: Path, args: argparse.Namespace) -> None:
    from auszug.formats import save

    nf = _common.network_of(src, args)
    with _common.about(out):
        save(nf, out, kind="network")


def _write_many(jobs: list[tuple[Path, Path]], args: argparse.Namespace) -> list[str]:
    """Build every (drawing, output) job; return the error messages of those that failed."""
    return _common.run_jobs(jobs, "building", lambda src, dst: _write_one(src, dst, args))
