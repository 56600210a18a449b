"""Styles: the built-in library, composition (extends), nesting, overrides, files, errors."""

from __future__ import annotations

import json

import pytest

from auszug.errors import FormatError
from auszug.tracery import ParameterError, builtin_style, builtin_styles, load_style, parse_style, refine
from auszug.tracery.style import DEFAULTS, builtin_profiles, parse_overrides, style_from_data

FIG20 = [f"fig20{c}" for c in "abcdefgh"]


def test_the_library_reproduces_fig20_a_to_h():
    assert list(builtin_styles()) == FIG20
    s = {n: builtin_style(n) for n in FIG20}
    assert s["fig20a"].circle.decoration == "plain" and s["fig20a"].sub_arch.decoration == "plain"
    assert len({s["fig20a"].sub_arch.profile.name, s["fig20a"].circle.profile.name,
                s["fig20a"].fillet.profile.name}) == 1  # one profile for all groups
    assert (s["fig20b"].circle.decoration, s["fig20b"].circle.pointed) == ("rosette", False)
    assert s["fig20c"].circle.pointed and s["fig20c"].circle.foil_profile.name == "fig18"
    assert (s["fig20d"].circle.foils, s["fig20d"].sub_arch.decoration) == (4, "trefoil")
    assert s["fig20d"].sub_arch.profile.name != s["fig20c"].sub_arch.profile.name
    assert s["fig20e"].sub_arch.profile.name != s["fig20d"].sub_arch.profile.name
    assert (s["fig20e"].sub_arch.split, s["fig20e"].sub_arch.lobe) != (s["fig20d"].sub_arch.split,
                                                                     s["fig20d"].sub_arch.lobe)
    # f: c's rosette and fillets, sub-arches refined by d; g and h one and two levels more
    assert s["fig20f"].circle == s["fig20c"].circle and s["fig20f"].fillet == s["fig20c"].fillet
    assert s["fig20f"].sub_arch.window.name == "fig20d"
    assert [s[n].depth() for n in FIG20] == [0, 0, 0, 0, 0, 1, 2, 3]


def test_extends_merges_key_by_key():
    s = parse_style('extends = "fig20c"\n[circle]\nfoils = 5\n')
    c = builtin_style("fig20c")
    assert s.circle.foils == 5 and s.circle.pointed == c.circle.pointed
    assert s.sub_arch == c.sub_arch and s.params == c.params
    assert s.description == c.description  # inherited


def test_overrides_by_dotted_names_and_bare_parameters():
    s = builtin_style("fig20b").with_overrides({"excess": 1.0, "circle.foils": 6, "wall.slab": 0.3})
    assert (s.params.excess, s.circle.foils, s.wall.slab) == (1.0, 6, 0.3)
    assert builtin_style("fig20b").params.excess == 1.25  # the original is unchanged
    nested = builtin_style("fig20f").with_overrides({"sub-arch.window.circle.foils": 5})
    assert nested.sub_arch.window.circle.foils == 5


def test_parse_overrides_reads_toml_values():
    assert parse_overrides(["a=1", "b=2.5", "c=true", "d=lying", 'e="x y"', "f=[1, 2]"]) == {
        "a": 1, "b": 2.5, "c": True, "d": "lying", "e": "x y", "f": [1, 2]}
    with pytest.raises(ParameterError):
        parse_overrides(["novalue"])


def test_refine_nests_the_style_in_itself():
    for depth in range(4):
        s = refine(builtin_style("fig20c"), depth)
        assert s.depth() == depth
    leaf = refine(builtin_style("fig20d"), 2).sub_arch.window.sub_arch.window
    assert leaf.sub_arch.decoration == "trefoil"


def test_style_files_toml_and_json_with_relative_references(tmp_path):
    (tmp_path / "base.toml").write_text(
        'extends = "fig20a"\ndescription = "mine"\n[circle]\ndecoration = "rosette"\nfoils = 5\n')
    (tmp_path / "top.json").write_text(json.dumps({
        "extends": "base.toml", "sub-arch": {"decoration": "window", "window": "base.toml"},
        "profiles": {"deep": {"points": [[0, 0], [0.5, 0.5], [0.5, 2.5]]}}, "fillet": {"profile": "deep"}}))
    s = load_style(tmp_path / "top.json")
    assert s.name == "top" and s.circle.foils == 5 and s.description == "mine"
    assert s.sub_arch.window.circle.foils == 5 and s.sub_arch.window.name == "base"
    assert s.fillet.profile.depth == 2.5
    # the data is self-contained: rebuilding from it gives the same style
    again = style_from_data(s.data)
    assert again.sub_arch.window.circle == s.sub_arch.window.circle and again.fillet == s.fillet


@pytest.mark.parametrize("text, name", [
    ('[circle]\nfoils = 1\n', "circle.foils"),
    ('[circle]\ndecoration = "star"\n', "circle.decoration"),
    ('[circle]\npointed = "yes"\n', "circle.pointed"),
    ('[fillet]\nprofile = "nosuch"\n', "fillet.profile"),
    ('[wall]\nprofile = "chamfer"\n', "wall.profile"),
    ('[sub-arch]\nprofile = "splay"\n', "sub-arch.profile"),
    ('[wall]\nslab = 2.0\n', "wall.slab"),
    ('[params]\nexcess = 0.1\n', "excess"),
    ('[params]\ncolour = 1\n', "params.colour"),
    ('[circle]\nfoil = 3\n', "circle.foil"),
    ('colour = 1\n', "colour"),
    ('[sub-arch]\ndecoration = "window"\n', "sub-arch.window"),
    ('[profiles.bad]\npoints = [[0, 0], [1, 1], [0.5, 2]]\n[fillet]\nprofile = "bad"\n', "profile 'bad'"),
])
def test_invalid_styles_name_the_key(text, name):
    with pytest.raises(ParameterError) as e:
        parse_style(text)
    assert e.value.name == name and "expected" in str(e.value)


def test_cyclic_and_unknown_references(tmp_path):
    (tmp_path / "a.toml").write_text('extends = "b.toml"\n')
    (tmp_path / "b.toml").write_text('extends = "a.toml"\n')
    with pytest.raises(ParameterError, match="does not refer to itself"):
        load_style(tmp_path / "a.toml")
    with pytest.raises(ParameterError) as e:
        load_style("fig21z")
    assert "fig20a" in str(e.value)
    with pytest.raises(FormatError):
        parse_style("[circle\n")
    with pytest.raises(FormatError):
        parse_style("{", suffix=".json")


def test_builtin_profiles_are_valid_and_monotone():
    lib = builtin_profiles()
    assert {"flat", "chamfer", "round", "hollow", "step", "fig18", "square", "splay", "orders"} <= set(lib)
    for p in lib.values():
        pts = p.sample(8)
        assert (pts[1:] - pts[:-1] >= -1e-12).all()
        if p.wall:
            assert pts[-1].tolist() == [0.0, 1.0]
        else:
            assert pts[0].tolist() == [0.0, 0.0]


def test_defaults_cover_every_group():
    assert {"params", "wall", "arch", "sub-arch", "circle", "fillet"} <= set(DEFAULTS)
