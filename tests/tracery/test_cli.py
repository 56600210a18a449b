"""``auszug tracery``: list, structure, drawings, meshes, pictures, errors (in-process)."""

from __future__ import annotations

import json

import pytest

from auszug.cli import main
from tests.cli.conftest import png_size


@pytest.fixture
def cli(capsys):
    def run(*args):
        code = main([str(a) for a in args])
        cap = capsys.readouterr()
        return code, cap.out, cap.err

    return run


def test_list_shows_styles_and_profiles(cli):
    code, out, _ = cli("tracery", "--list")
    assert code == 0
    for name in [f"fig20{c}" for c in "abcdefgh"] + ["fig18", "splay"]:
        assert name in out


def test_summary_without_output(cli):
    code, out, _ = cli("tracery", "fig20h")
    assert code == 0 and "depth 3" in out and "91 lights" in out


@pytest.mark.parametrize("suffix", [".obj", ".stl", ".ply", ".glb"])
def test_mesh_outputs(cli, tmp_path, suffix):
    out = tmp_path / f"w{suffix}"
    code, text, err = cli("tracery", "fig20b", "-o", out)
    assert code == 0, err
    data = out.read_bytes()
    assert len(data) > 1000
    import trimesh

    m = trimesh.load(out, force="mesh", process=True)
    assert m.is_watertight and m.euler_number == 2 - 2 * 7
    assert (tmp_path / "w.mtl").exists() == (suffix == ".obj")


def test_svg_png_and_structure_with_overrides(cli, tmp_path):
    code, _, err = cli("tracery", "fig20d", "--set", "circle.foils=6", "--excess", "1.0", "-o", tmp_path / "w.svg")
    assert code == 0, err
    assert (tmp_path / "w.svg").read_text().count("<path") == 9
    code, _, err = cli("tracery", "fig20a", "--depth", "1", "-o", tmp_path / "w.json")
    assert code == 0, err
    d = json.loads((tmp_path / "w.json").read_text())
    assert max(r["depth"] for r in d["regions"]) == 1
    code, _, err = cli("tracery", "fig20c", "-o", tmp_path / "w.png", "--width", "120")
    assert code == 0, err
    w, h = png_size((tmp_path / "w.png").read_bytes())
    assert w == 120 and h > 200


def test_style_file(cli, tmp_path):
    f = tmp_path / "mine.toml"
    f.write_text('extends = "fig20b"\n[circle]\nfoils = 5\n')
    code, out, err = cli("tracery", f)
    assert code == 0, err
    assert "style mine" in out


@pytest.mark.parametrize("args, message", [
    (("tracery", "fig20a", "--excess", "0.3"), "excess: expected a number >= 0.5, got 0.3"),
    (("tracery", "fig20a", "--set", "circle.foils=1"), "circle.foils: expected a whole number >= 2"),
    (("tracery", "fig20a", "--inner", "0.2"), "inner: expected a number in [2e-06, "),
    (("tracery", "nosuch"), "expected a built-in style"),
    (("tracery", "fig20a", "-o", "x.doc"), "unknown output type"),
    (("tracery",), "a STYLE is required"),
])
def test_errors_are_one_line_with_exit_code_2(cli, args, message):
    code, out, err = cli(*args)
    assert code == 2 and message in err and "Traceback" not in err
    assert err.startswith("auszug: ")


def test_bad_style_file_names_the_file(cli, tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text("[circle\n")
    code, _, err = cli("tracery", f)
    assert code == 2 and "bad.toml" in err
