"""Fuzzing tracery styles: mutated TOML and JSON style files, random ``--set`` values.

Each case runs ``auszug tracery STYLE [--set K=V] -o OUT`` in-process under the
command-line contract of tests/fuzzing.py: exit 0 with a finite drawing or
mesh, or exit 2 with one line naming the file (or the ``--set`` key), no
traceback and no output file.
"""

from __future__ import annotations

import json
import random
import re
import tomllib
from collections import Counter
from importlib.resources import files
from pathlib import Path

import pytest

from auszug.formats import stl
from auszug.tracery import builtin_style, builtin_styles
from auszug.tracery.style import DEFAULTS
from tests.fuzzing import ODD_NUMBERS, case, cases, mutate_json, mutate_text, run_cli

STYLES = sorted(builtin_styles())
TOML = {n: (files("auszug.tracery") / "styles" / f"{n}.toml").read_text() for n in STYLES}
#: Words of the style language: keys, decorations, orientations, profile and style names.
WORDS = sorted({k for t in DEFAULTS.values() if isinstance(t, dict) for k in t} | set(DEFAULTS) | {
    "extends", "window", "plain", "rosette", "trefoil", "blind", "lying", "standing", "true", "false",
    "chamfer", "splay", "orders", "fig18", '"chamfer"', '"fig20d"', '"window"', "[params]", "[circle]",
    "[sub-arch]", "[[x]]", "=", '"', "[", "]", "{", "}", "inf", "nan", "-inf", "1e308"} | set(STYLES))
#: Cases per fuzzer in a ``make test`` run (each is a style build, milliseconds to a tenth of a second).
N = 60

_NONFINITE = re.compile(r"(?<![a-z])(nan|inf)(?![a-z])", re.IGNORECASE)


def _run_tracery(tmp: Path, seed: int, style: str, name: str, sets: list[str] = ()) -> str:  # type: ignore[assignment]
    """One CLI run; half the cases write an SVG, half an STL (read back: the reader refuses NaN)."""
    out = tmp / (f"w{seed}.svg" if seed % 2 else f"w{seed}.stl")
    argv = ["tracery", style, *(a for s in sets for a in ("--set", s)), "-o", str(out)]
    res = run_cli(argv, name, [out])
    if res.kind == "ok":
        if out.suffix == ".svg":
            text = out.read_text()
            assert "<svg" in text and not _NONFINITE.search(text.split(">", 2)[2]), "non-finite SVG"
        else:
            m = stl.loads(out.read_bytes(), str(out))  # checks finite, in-range, indices
            assert m.n_faces > 0
    return res.kind


def test_mutated_toml_styles(tmp_path):
    seen: Counter = Counter()
    for seed in cases(N):
        rnd = random.Random(seed)
        base = rnd.choice(STYLES)
        path = tmp_path / f"s{seed}.toml"
        path.write_text(mutate_text(TOML[base], rnd, tokens=WORDS))
        with case(f"toml seed {seed} from {base}"):
            seen[_run_tracery(tmp_path, seed, str(path), str(path))] += 1
    assert seen["ok"] and seen["refused"], seen


def test_mutated_json_styles(tmp_path):
    keys = sorted({k for t in DEFAULTS.values() if isinstance(t, dict) for k in t}) + ["extends", "nope"]
    seen: Counter = Counter()
    for seed in cases(N):
        rnd = random.Random(seed)
        base = rnd.choice(STYLES)
        path = tmp_path / f"s{seed}.json"
        path.write_text(json.dumps(mutate_json(builtin_style(base).data, rnd, keys=keys)))
        with case(f"json seed {seed} from {base}"):
            seen[_run_tracery(tmp_path, seed, str(path), str(path))] += 1
    assert seen["ok"] and seen["refused"], seen


def _set_keys() -> list[str]:
    out = ["span", "height", "excess", "drop", "outer", "inner", "name", "extends", "nope", "circle", "params.x"]
    for group, table in DEFAULTS.items():
        if isinstance(table, dict):
            out += [f"{group}.{k}" for k in table]
    return out


SET_VALUES = ODD_NUMBERS + ["true", "false", '"x"', '"plain"', '"window"', '"rosette"', "lying", "[1, 2]",
                            "[[0, 0], [1, 1]]", "{a = 1}", '"fig20d"', "fig20d", "chamfer", "2", "3", "6",
                            "1024", "1025", "0.05", "0.3", "1.25", "4.0"]


def test_random_set_values(tmp_path):
    keys = _set_keys()
    seen: Counter = Counter()
    for seed in cases(3 * N):
        rnd = random.Random(seed)
        sets = [f"{rnd.choice(keys)}={rnd.choice(SET_VALUES)}" for _ in range(rnd.randint(1, 3))]
        with case(f"--set seed {seed}: {sets}"):
            out = tmp_path / f"w{seed}.svg"
            res = run_cli(["tracery", rnd.choice(STYLES), *(a for s in sets for a in ("--set", s)), "-o", str(out)],
                          "", [out])
            if res.kind == "refused":
                # the message names one of the keys the user set (its last part, as the style says it)
                named = [s.split("=", 1)[0] for s in sets]
                assert any(k.split(".")[-1] in res.message for k in named), res.message
            seen[res.kind] += 1
    assert seen["ok"] and seen["refused"], seen


def test_toml_of_the_library_parses():
    """The TOML the fuzzer starts from is the library itself, unmutated (so mutations are near-misses)."""
    for n in STYLES:
        assert isinstance(tomllib.loads(TOML[n]), dict)


@pytest.mark.parametrize("sets, named", [
    (["params.span=1e999"], "span"), (["circle.foils=nan"], "foils"), (["excess=[1, 2]"], "excess"),
    (["circle=1"], "circle"), (["extends=7"], "extends"),
    (["sub-arch.window=1e400", "sub-arch.decoration=window"], "sub-arch.window"),  # blamed 'style'
    (["params.inner=1e-20"], "inner"),  # fig20f's mesh: "arc radius must be positive", blaming the output
    # fig20h's rosettes cross themselves (strict mode's check) and the error blamed foils alone
    (["circle.displacement=3", "style=fig20h"], "circle.displacement=3"),
])
def test_found_set_cases(tmp_path, sets, named):
    out = tmp_path / "w.stl"
    style = "fig20h" if "style=fig20h" in sets else "fig20a"
    args = [a for s in sets if s != "style=fig20h" for a in ("--set", s)]
    res = run_cli(["tracery", style, *args, "-o", str(out)], named, [out])
    assert res.kind == "refused"


def test_found_style_file_cases(tmp_path):
    """A JSON style whose sub-arch is a number (an AttributeError); a TOML style whose window does not
    fit (the error did not name the file)."""
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({**builtin_style("fig20g").data, "sub-arch": 0.5}))
    assert run_cli(["tracery", str(bad)], "bad.json").message.endswith("sub-arch: expected a table, got 0.5")
    misfit = tmp_path / "misfit.toml"
    misfit.write_text(TOML["fig20e"].replace("lobe = ", "lobe = 0.06 #"))
    res = run_cli(["tracery", str(misfit), "-o", str(tmp_path / "w.svg")], "misfit.toml", [tmp_path / "w.svg"])
    assert "lobe" in res.message
