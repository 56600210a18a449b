"""``auszug mesh``: formats by ending, styles, faces, solids, folders, errors (run in-process)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from auszug.cli import main
from auszug.formats import load
from tests.conftest import CORPUS

TN = CORPUS / "teaching-sheet"


@pytest.fixture
def cli(capsys):
    def run(*args):
        code = main([str(a) for a in args])
        cap = capsys.readouterr()
        return code, cap.out, cap.err
    return run


@pytest.mark.parametrize("ending", [".glb", ".gltf", ".obj", ".stl", ".ply"])
def test_output_ending_picks_the_mesh_format(cli, tmp_path, ending):
    out = tmp_path / f"tn-1{ending}"
    code, text, err = cli("mesh", TN / "tn-1.uc", "--segments", "24", "-o", out)
    assert code == 0, err
    assert text.startswith(f"wrote {out}; ")
    m = load(out, kind="mesh")
    assert m.n_faces == int(text.split("; ")[2].split()[0])
    if ending == ".obj":
        assert (tmp_path / "tn-1.mtl").read_text().count("newmtl") == 1


def test_a_network_file_meshes_as_its_drawing_does(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    net = tmp_path / "tn-5.network.json"
    assert cli("build", TN / "tn-5.uc", "-o", net)[0] == 0
    code, text, err = cli("mesh", net, "--segments", "24", "--style", "tube", "--faces", "auto",
                          "-o", tmp_path / "n.stl")
    assert code == 0, err
    code2, text2, _ = cli("mesh", TN / "tn-5.uc", "--segments", "24", "--style", "tube", "--faces", "auto",
                          "-o", tmp_path / "d.stl")
    assert code2 == 0 and text.split("; ")[1:] == text2.split("; ")[1:]     # counts, faces, residual
    a, b = load(tmp_path / "d.stl", kind="mesh"), load(tmp_path / "n.stl", kind="mesh")
    np.testing.assert_allclose(b.vertices, a.vertices, rtol=0, atol=1e-6)
    # without -o: <stem>.glb, the network file's whole ending dropped
    code, text, err = cli("mesh", net, "--segments", "8", "--format", "ply")
    assert code == 0 and text.startswith("wrote tn-5.ply; ") and (tmp_path / "tn-5.ply").exists()
    (tmp_path / "old.network.json").write_text(net.read_text().replace('"exact":', '"exact_":'))
    code, _, err = cli("mesh", tmp_path / "old.network.json", "-o", tmp_path / "o.glb")
    assert code == 2 and "old.network.json" in err and "no exact curve" in err
    assert not (tmp_path / "o.glb").exists()


def test_solid_with_base_reports_a_watertight_volume(cli, tmp_path):
    out = tmp_path / "tn-1.stl"
    code, text, err = cli("mesh", TN / "tn-1.uc", "--style", "tube", "--around", "8", "--solid", "--base",
                          "--segments", "24", "-o", out)
    assert code == 0, err
    assert "watertight" in text and "NOT" not in text
    m = load(out, kind="mesh")
    assert m.is_watertight and m.volume == pytest.approx(float(text.split("volume ")[1].split(",")[0]), rel=1e-5)


def test_faces_auto_and_a_profile_file(cli, tmp_path):
    prof = tmp_path / "roll.json"
    prof.write_text(json.dumps({"start": [-0.01, 0], "segments": [
        {"line": [0.01, 0]}, {"arc": [-0.01, 0], "center": [0, 0]}]}))
    out = tmp_path / "tn-1.glb"
    code, text, err = cli("mesh", TN / "tn-1.uc", "--style", prof, "--faces", "auto", "--face-resolution", "32",
                          "--segments", "16", "-o", out)
    assert code == 0, err
    assert "8 faces (converged" in text
    names = [p.name for p in load(out, kind="mesh").parts]
    assert names == ["curve 0", "faces"]


def test_explicit_loops_file(cli, tmp_path):
    from auszug.meshing import find_loops
    from auszug.microarch import build

    net = build(load(TN / "tn-1.uc"))
    lp = find_loops(net)[0]
    loops = tmp_path / "loops.json"
    loops.write_text(json.dumps([lp.graph.nodes[lp.nodes].tolist()]))
    code, text, err = cli("mesh", TN / "tn-1.uc", "--faces", loops, "--segments", "8", "-o", tmp_path / "x.ply")
    assert code == 0, err
    assert "1 faces (converged" in text


def test_a_folder_gives_one_mesh_per_drawing(cli, tmp_path):
    code, text, err = cli("mesh", TN, "-o", tmp_path / "out", "--format", "ply", "--segments", "8")
    assert code == 0, err
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == sorted(f.stem + ".ply" for f in TN.glob("*.uc"))
    assert text.strip().endswith("wrote 12 of 12 meshes to " + str(tmp_path / "out"))


def test_picture(cli, tmp_path):
    out = tmp_path / "tn-1.png"
    code, _, err = cli("mesh", TN / "tn-1.uc", "--segments", "8", "-o", out)
    assert code == 0, err
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("args, message", [
    (["--style", "cable"], "--style must be one of tube, bar, ribbon or a profile .json file"),
    (["--style", "missing.json"], "missing.json: no such profile file"),
    (["-o", "x.fbx"], "unknown mesh file type"),
    (["--format", "stl", "-o", "x.glb"], "--format stl does not match"),
    (["--solid", "--style", "ribbon", "--size", "0"], "positive number"),
])
def test_bad_options_give_clear_errors(cli, tmp_path, monkeypatch, args, message):
    monkeypatch.chdir(tmp_path)
    code, _, err = cli("mesh", TN / "tn-1.uc", *args)
    assert code == 2
    assert message in err and "Traceback" not in err


def test_an_open_profile_file_cannot_make_a_solid(cli, tmp_path):
    prof = tmp_path / "open.json"
    prof.write_text(json.dumps({"points": [[0, 0], [0.01, 0], [0.01, 0.01]], "closed": False}))
    code, _, err = cli("mesh", TN / "tn-1.uc", "--style", prof, "--solid", "-o", tmp_path / "x.stl")
    assert code == 2 and "is open; a solid needs a closed profile" in err
    assert np.isfinite(1.0)
