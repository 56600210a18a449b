"""Seeded fuzzing: mutate valid inputs, then hold the code to auszug's error contract.

The contract (issue 14, docs/limits.md "Fuzzing"): every input either succeeds
with finite output, or ends in an :class:`auszug.errors.AuszugError` whose
message names the file (on the command line: exit code 2, one line naming the
file, no traceback, and no output file left behind). Any other exception is a
bug and fails the test with the seed that reproduces it.

Mutations are drawn from :class:`random.Random` seeded per case, so a failing
case is reproduced by its seed alone: ``mutate_bytes(data, Random(seed))``.
The number of cases of each fuzzer is ``cases(n)``: ``n`` by default (sized
so that every fuzzer together adds well under 30 s to ``make test`` on two
cores), multiplied by the environment variable ``AUSZUG_FUZZ_SCALE`` for a
longer search (e.g. ``AUSZUG_FUZZ_SCALE=20``).
"""

from __future__ import annotations

import contextlib
import io
import math
import os
import random
import struct
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from auszug.errors import AuszugError

__all__ = ["cases", "mutate_bytes", "mutate_text", "mutate_json", "Outcome", "expect_contract",
           "run_cli", "assert_finite", "ODD_NUMBERS", "ODD_VALUES", "case"]

#: Number tokens at the edges: non-finite, huge, tiny, negative, integer overflow, not numbers.
ODD_NUMBERS = ["nan", "NaN", "inf", "-inf", "Infinity", "1e308", "-1e308", "1e400", "1e-320", "0", "-0",
               "-1", "1e6", "1.000001e6", "1e7", "2147483648", "4294967296", "-2147483649",
               "18446744073709551616", "99999999999999999999999", "0.5", "1e", "--1", "0x10", "1_0",
               "", "x", ".", "\u0663"]

#: JSON values at the edges: wrong types, non-finite (Python's json writes NaN/Infinity), huge, empty.
ODD_VALUES: list[Any] = [None, True, False, 0, -1, 1, 2, 3, 0.5, -0.5, 1e308, -1e308, 1e7, 1e-320,
                         float("nan"), float("inf"), float("-inf"), 10**20, 2**63, "", "x", "1",
                         "nan", [], {}, [0], [0, 0], [0, 0, 0], [[0, 0]], [[0, 0], [1, 0]],
                         {"x": 1}, [None], ["a", "b"], "a" * 200]

_INT32 = [0, 1, 3, 0x7F, 0x80, 0xFF, 0x7FFF, 0xFFFF, 0x7FFFFFFF, 0x80000000, 0xFFFFFFFF]
_FLOAT32 = [float("nan"), float("inf"), -float("inf"), 3.4e38, -3.4e38, 1e30, 1e7, 0.0, -0.0, 1e-40]


def cases(n: int) -> range:
    """Seeds ``0 .. n * AUSZUG_FUZZ_SCALE - 1`` (``AUSZUG_FUZZ_SCALE`` defaults to 1)."""
    return range(max(1, round(n * float(os.environ.get("AUSZUG_FUZZ_SCALE", "1")))))


def mutate_bytes(data: bytes, rnd: random.Random, k: int | None = None) -> bytes:
    """``data`` with ``k`` (1-4 by default) byte-level mutations.

    Bit flips, interesting bytes, interesting 32-bit integers or float32 values
    written over four bytes (counts, indices, coordinates of binary formats),
    deleted, duplicated or inserted runs, and truncation.
    """
    b = bytearray(data)
    for _ in range(k if k is not None else rnd.randint(1, 4)):
        if not b:
            b.extend(rnd.randbytes(rnd.randint(1, 8)))
            continue
        i = rnd.randrange(len(b))
        op = rnd.randrange(8)
        if op == 0:
            b[i] ^= 1 << rnd.randrange(8)
        elif op == 1:
            b[i] = rnd.choice([0, 1, 0x7F, 0x80, 0xFF, 0x20, 0x0A])
        elif op == 2:
            b[i:i + 4] = struct.pack("<I", rnd.choice(_INT32))
        elif op == 3:
            b[i:i + 4] = struct.pack("<f", rnd.choice(_FLOAT32))
        elif op == 4:
            del b[i:i + rnd.randint(1, 64)]
        elif op == 5:
            j = min(len(b), i + rnd.randint(1, 64))
            b[i:i] = b[i:j]
        elif op == 6:
            b[i:i] = rnd.randbytes(rnd.randint(1, 8))
        else:
            del b[i:]
    return bytes(b)


def _split_tokens(text: str) -> list[str]:
    """Whitespace and non-whitespace runs, so a token can be replaced keeping the layout."""
    out: list[str] = []
    cur = ""
    for ch in text:
        if cur and (ch.isspace() != cur[-1].isspace()):
            out.append(cur)
            cur = ""
        cur += ch
    if cur:
        out.append(cur)
    return out


def mutate_text(text: str, rnd: random.Random, k: int | None = None, tokens: list[str] | None = None) -> str:
    """``text`` with ``k`` (1-3 by default) line- and token-level mutations.

    A token replaced by an odd number (:data:`ODD_NUMBERS`) or one of
    ``tokens`` (a format's keywords), deleted or duplicated; a line deleted,
    duplicated or swapped; the text cut short.
    """
    extra = tokens or []
    for _ in range(k if k is not None else rnd.randint(1, 3)):
        lines = text.split("\n")
        op = rnd.randrange(6)
        i = rnd.randrange(len(lines))
        if op <= 2:
            toks = _split_tokens(lines[i])
            words = [j for j, t in enumerate(toks) if not t.isspace()]
            if not words:
                lines.insert(i, rnd.choice(extra + ODD_NUMBERS))
            else:
                j = rnd.choice(words)
                if op == 0:
                    toks[j] = rnd.choice(ODD_NUMBERS + extra)
                elif op == 1:
                    toks[j] = ""
                else:
                    toks[j] = toks[j] + " " + rnd.choice([toks[j], *extra, *ODD_NUMBERS])
                lines[i] = "".join(toks)
        elif op == 3:
            del lines[i]
        elif op == 4:
            lines.insert(rnd.randrange(len(lines) + 1), lines[i])
        else:
            j = rnd.randrange(len(lines))
            lines[i], lines[j] = lines[j], lines[i]
        text = "\n".join(lines)
    if rnd.random() < 0.1:
        text = text[: rnd.randrange(len(text) + 1)]
    return text


def _paths(value: Any, here: tuple = ()) -> Iterator[tuple]:
    yield here
    if isinstance(value, dict):
        for key, v in value.items():
            yield from _paths(v, (*here, key))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from _paths(v, (*here, i))


def mutate_json(value: Any, rnd: random.Random, k: int | None = None, keys: list[str] | None = None) -> Any:
    """A mutated copy of a JSON-like ``value`` (``k``, 1-3 by default, mutations).

    A value anywhere in the tree replaced by one of :data:`ODD_VALUES`, a
    number scaled by a power of ten or negated, a key deleted or added (from
    ``keys``), a list item deleted or duplicated.
    """
    import copy

    value = copy.deepcopy(value)
    for _ in range(k if k is not None else rnd.randint(1, 3)):
        paths = [p for p in _paths(value) if p]
        if not paths:
            return rnd.choice(ODD_VALUES)
        path = rnd.choice(paths)
        parent = value
        for key in path[:-1]:
            parent = parent[key]
        last = path[-1]
        old = parent[last]
        op = rnd.randrange(6)
        if op <= 1:
            parent[last] = copy.deepcopy(rnd.choice(ODD_VALUES))
        elif op == 2 and isinstance(old, (int, float)) and not isinstance(old, bool):
            parent[last] = old * rnd.choice([-1, 10.0 ** rnd.randint(1, 12), 10.0 ** -rnd.randint(1, 12), 1e400])
        elif op == 3:
            del parent[last]
        elif op == 4 and isinstance(parent, list):
            parent.insert(last, copy.deepcopy(old))
        elif isinstance(old, dict):
            old[rnd.choice(keys or ["x"])] = copy.deepcopy(rnd.choice(ODD_VALUES))
        else:
            parent[last] = copy.deepcopy(rnd.choice(ODD_VALUES))
    return value


@dataclass
class Outcome:
    """What one fuzz case did: ``"ok"`` with a value, or ``"refused"`` with the message."""

    kind: str
    value: Any = None
    message: str = ""


@contextlib.contextmanager
def case(what: str) -> Iterator[None]:
    """Name the fuzz case (``what``: fuzzer, seed) on any exception raised inside the block."""
    try:
        yield
    except BaseException as e:
        e.add_note(f"fuzz case: {what}")
        raise


def expect_contract(fn: Callable[..., Any], *args: Any, name: str, **kwargs: Any) -> Outcome:
    """Call ``fn``: it must return, or raise an AuszugError whose message names ``name``.

    Any other exception propagates (the test fails with it).
    """
    try:
        v = fn(*args, **kwargs)
    except AuszugError as e:
        msg = str(e)
        assert name in msg, f"error does not name {name!r}: {msg}"
        assert "\n" not in msg.strip(), f"error of more than one line: {msg!r}"
        return Outcome("refused", message=msg)
    return Outcome("ok", v)


def assert_finite(*arrays: Any) -> None:
    """Every given array (or number) is all finite."""
    for a in arrays:
        a = np.asarray(a, dtype=float)
        assert np.isfinite(a).all(), f"non-finite values in output ({np.size(a) - np.isfinite(a).sum()})"


def run_cli(argv: list[str], name: str, outputs: list[Path] = ()) -> Outcome:  # type: ignore[assignment]
    """Run ``auszug argv`` in-process under the command-line contract.

    Exit code 0 (every output written) or 2 with one message line that names
    ``name`` and no traceback, and then none of ``outputs`` exists (and no
    temporary file beside them). AUSZUG_DEBUG is set, so a bug raises its
    exception here instead of printing "internal error".
    """
    from auszug.cli import main

    out, err = io.StringIO(), io.StringIO()
    before = {p.parent: set(p.parent.iterdir()) for p in outputs if p.parent.exists()}
    old = os.environ.get("AUSZUG_DEBUG")
    os.environ["AUSZUG_DEBUG"] = "1"
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(argv)
    finally:
        if old is None:
            del os.environ["AUSZUG_DEBUG"]
        else:
            os.environ["AUSZUG_DEBUG"] = old
    text = err.getvalue()
    assert code in (0, 2), f"exit code {code}: {text}"
    if code == 0:
        for p in outputs:
            assert p.exists(), f"exit 0 but {p} not written"
        return Outcome("ok", out.getvalue())
    assert "Traceback" not in text and text.startswith("auszug: "), text
    assert name in text, f"message does not name {name!r}: {text}"
    for p in outputs:
        assert not p.exists(), f"exit 2 but {p} was written"
    for folder, seen in before.items():
        assert set(folder.iterdir()) <= seen | set(outputs), "a temporary file was left behind"
    return Outcome("refused", message=text.strip())


def is_number(x: Any) -> bool:
    """Whether ``x`` is a finite int or float (not a bool)."""
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)
