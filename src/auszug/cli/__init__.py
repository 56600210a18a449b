"""The ``auszug`` command line.

One module per subcommand, each providing ``HELP`` (a one-line summary),
``add_args(parser)`` and ``run(args) -> int``. :func:`main` parses the
arguments and reports every deliberate auszug error as
``auszug: FILE:LINE: problem`` on stderr with exit code 2 and no traceback.
The command modules import numpy, matplotlib and rich only when they run, so
``auszug --help`` and ``auszug build`` start fast. No geometry happens here:
commands call :mod:`auszug.microarch` and :mod:`auszug.formats`.

Examples
--------
>>> from auszug.cli import main
>>> main(["--version"])  # doctest: +ELLIPSIS
auszug ...
0
"""

from __future__ import annotations

import argparse
import importlib
import sys
from typing import Sequence

__all__ = ["COMMANDS", "make_parser", "main", "unexpected"]

#: Subcommands in the order ``auszug --help`` lists them.
COMMANDS: tuple[str, ...] = ("build", "info", "render", "convert", "demo", "tracery", "mesh", "lift", "sweeps",
                             "studio", "examples")


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("auszug")
    except PackageNotFoundError:  # pragma: no cover - running from a source tree
        return "unknown"


class _VersionAction(argparse.Action):
    """``--version`` that looks the version up only when asked."""

    def __init__(self, option_strings: list[str], dest: str = argparse.SUPPRESS, **kw: object):
        super().__init__(option_strings, dest, nargs=0, default=argparse.SUPPRESS,
                         help="print the version and exit")

    def __call__(self, parser: argparse.ArgumentParser, namespace: argparse.Namespace, values: object,
                 option_string: str | None = None) -> None:
        print(f"auszug {_version()}")
        parser.exit(0)


def make_parser() -> argparse.ArgumentParser:
    """The argument parser with every subcommand."""
    parser = argparse.ArgumentParser(
        prog="auszug",
        description="auszug: computational Gothic design. Symmetric top views to 3D ogee curve networks "
        "(microarchitecture), meshes and solids, window tracery, and a local 3D studio.",
        epilog="Run 'auszug COMMAND --help' for the options of a command.",
    )
    parser.add_argument("--version", action=_VersionAction)
    sub = parser.add_subparsers(title="commands", metavar="COMMAND")
    for name in COMMANDS:
        mod = importlib.import_module(f"auszug.cli.{name}")
        p = sub.add_parser(name, help=mod.HELP, description=mod.__doc__,
                           formatter_class=argparse.RawDescriptionHelpFormatter)
        mod.add_args(p)
        p.set_defaults(_run=mod.run)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line with ``argv`` (default: ``sys.argv[1:]``); return the exit code.

    Exit codes: 0 success, 2 bad input or usage (message on stderr), 1 an
    unexpected error inside auszug (one line naming it; ``AUSZUG_DEBUG=1`` shows
    the traceback), 130 interrupted. Messages are cut to
    :attr:`auszug.limits.Limits.message` characters.
    """
    import os

    from auszug.errors import AuszugError
    from auszug.limits import clip

    parser = make_parser()
    try:
        args = parser.parse_args(None if argv is None else list(argv))
    except SystemExit as e:  # --help, --version and usage errors
        return e.code if isinstance(e.code, int) else (0 if e.code is None else 2)
    if not hasattr(args, "_run"):
        parser.print_help(sys.stderr)
        print("\nauszug: error: a command is required", file=sys.stderr)
        return 2
    try:
        return int(args._run(args))
    except AuszugError as e:
        print(f"auszug: {clip(str(e))}", file=sys.stderr)
        return 2
    except OSError as e:
        where = f"{e.filename}: " if e.filename else ""
        print(f"auszug: {clip(where + str(e.strerror or e))}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("auszug: interrupted", file=sys.stderr)
        return 130
    except MemoryError:
        print("auszug: out of memory (an input beyond what this machine holds; see docs/limits.md)",
              file=sys.stderr)
        return 2
    except Exception as e:  # a bug: one line, not a traceback, unless asked for
        if os.environ.get("AUSZUG_DEBUG"):
            raise
        print(f"auszug: internal error: {clip(unexpected(e))} (AUSZUG_DEBUG=1 shows the traceback)",
              file=sys.stderr)
        return 1


def unexpected(e: BaseException) -> str:
    """One line for an exception auszug did not raise on purpose: its type and message."""
    return f"{type(e).__name__}: {e}" if str(e) else type(e).__name__


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
