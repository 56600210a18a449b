"""``auszug sweeps``: a mesh file in, a .sweeps.json (and pictures) out; bad input exits 2, no file."""

from __future__ import annotations

import struct
from functools import cache

import numpy as np
import pytest

from auszug.formats import load, save
from auszug.meshing.mesh import Mesh
from auszug.sweeps.fixtures import extruded, revolved
from tests.cli.conftest import files_in, png_size


@cache
def _mesh(name):
    fx = {"revolved": revolved, "extruded": extruded}[name](sigma=2e-4)
    return Mesh(50.0 * fx.vertices + [3.0, -1.0, 20.0], fx.faces)


@pytest.mark.parametrize("name, suffix", [("revolved", ".stl"), ("extruded", ".ply"), ("revolved", ".obj"),
                                          ("extruded", ".glb")])
def test_kinematic_meshes_give_one_patch_in_every_mesh_format(cli, tmp_path, name, suffix):
    src = tmp_path / f"{name}{suffix}"
    save(_mesh(name), src, kind="mesh")
    out = tmp_path / "r.sweeps.json"
    r = cli("sweeps", src, "-o", out)
    assert r.code == 0, r.err
    assert r.out.startswith(f"wrote {out}: 1 patch(es), coverage ")
    for stage in ("normalise", "cut", "kinematic", "fit"):
        assert f": {stage}\n" in r.err
    rep = load(out, kind="sweeps")
    assert rep.source == src.name and rep.coverage >= 0.95
    (p,) = rep.patches
    assert p.kind == ("rotation" if name == "revolved" else "translation")
    assert p.fit_error <= 2 * 0.005
    # the profile and its last position lie on the input mesh (its coordinates, not normalised ones)
    from auszug.sweeps.patches import closest_distance

    m = load(src, kind="mesh")
    for pts in (p.profile, p.motion.apply(p.profile, [p.motion.t[-1]])[0]):
        d, _ = closest_distance(pts, m.vertices, m.faces)
        assert d.max() <= 2e-3 * rep.bbox_diameter


def test_explain_glb_png_and_default_output_name(cli, tmp_path, monkeypatch):
    src = tmp_path / "base.stl"
    save(_mesh("revolved"), src, kind="mesh")
    monkeypatch.chdir(tmp_path)
    r = cli("sweeps", src, "--glb", "base.glb", "--png", "base.png", "--explain", "--eps-prox", "0.002",
            "--planes", "500", "--quiet")
    assert r.code == 0, r.err
    assert r.err == ""
    assert files_in(tmp_path) == ["base.glb", "base.png", "base.stl", "base.sweeps.json"]
    lines = r.out.splitlines()
    assert [ln.split()[0] for ln in lines[:4]] == ["normalise", "cut", "kinematic", "fit"]
    assert "patch 0: rotation" in r.out
    planes = int(lines[1].split()[3])
    assert 450 <= planes <= 550
    rep = load(tmp_path / "base.sweeps.json", kind="sweeps")
    assert rep.params.eps_prox == 0.002 and rep.params.initial_plane_count == 500
    w, h = png_size((tmp_path / "base.png").read_bytes())
    assert w > 300 and h > 300
    scene = load(tmp_path / "base.glb", kind="mesh")
    assert scene.n_faces > _mesh("revolved").n_faces      # the mesh plus profile and path tubes


def _stl(tris: np.ndarray) -> bytes:
    rec = b"".join(struct.pack("<12fH", 0, 0, 0, *t.ravel(), 0) for t in tris)
    return b"\0" * 80 + struct.pack("<I", len(tris)) + rec


@pytest.mark.parametrize("name, data, message", [
    ("empty.stl", b"\0" * 80 + struct.pack("<I", 0), "non-empty"),
    ("nan.stl", _stl(np.array([[[0, 0, 0], [1, 0, 0], [0, np.nan, 0]]], float)), "non-finite"),
    ("fan.stl", _stl(np.array([[[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 0, 0], [1, 0, 0], [0, -1, 0]],
                               [[0, 0, 0], [1, 0, 0], [0, 0, 1]]], float)), "shared by 3 faces"),
    ("flat.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 1 2\nf 1 2 3\n", "repeats a vertex"),
    ("text.ply", b"hello", "ply"),
    ("mesh.xyz", b"1 2 3", "xyz"),
])
def test_bad_meshes_exit_2_with_the_file_named_and_no_output(cli, tmp_path, name, data, message):
    src = tmp_path / name
    src.write_bytes(data)
    out = tmp_path / "r.sweeps.json"
    r = cli("sweeps", src, "-o", out, "--png", tmp_path / "r.png")
    assert r.code == 2, r.err
    last = r.err.splitlines()[-1]
    assert last.startswith("auszug: ") and name in last and message in last
    assert "Traceback" not in r.err
    assert files_in(tmp_path) == [name]


def test_too_many_triangles_is_refused_before_any_work(cli, tmp_path, monkeypatch):
    import importlib

    import auszug.limits

    det = importlib.import_module("auszug.sweeps.detect")
    monkeypatch.setattr(det, "LIMITS", auszug.limits.Limits(sweep_faces=1000))
    src = tmp_path / "big.stl"
    save(_mesh("extruded"), src, kind="mesh")
    r = cli("sweeps", src, "-o", tmp_path / "r.sweeps.json")
    assert r.code == 2 and "more than the limit of 1000" in r.err and "big.stl" in r.err
    assert files_in(tmp_path) == ["big.stl"]


def test_two_million_triangles_refused_without_running_out_of_memory():
    """The documented limit holds at the issue's size: 2 M triangles are refused at once."""
    from auszug.errors import GeometryError
    from auszug.sweeps import detect

    faces = np.zeros((2_000_000, 3), np.int64)
    with pytest.raises(GeometryError, match="2000000 triangles: more than the limit of 1000000"):
        detect((np.zeros((3, 3)), faces))


@pytest.mark.parametrize("args, message", [
    (["--eps-prox", "0.5"], "(0, 0.1]"),
    (["--eps-prox", "nan"], "finite"),
    (["--planes", "3"], ">= 10"),
    (["-o", "x.json"], "x.json"),
    (["--png", "x.gif"], "x.gif"),
    (["--parts", "65"], "max_parts = 65: expected a whole number in 0..64"),
    (["--parts", "-1"], ">= 0"),
    (["--match-scale", "1.5"], "(0, 1]"),
    (["--match-scale", "0"], "> 0"),
    (["--match-runs", "1"], ">= 2"),
    (["--match-scale", "0.25", "--l-min", "0.001"], "match_spacing"),
    (["--mirror-planes", "4"], "mirror_planes = 4: expected a whole number in 0..3"),
    (["--mirror-planes", "-1"], ">= 0"),
    (["--coverage-samples", "10000001"], "coverage_samples = 10000001"),
    (["--twist-steps", "65"], "twist_steps = 65: expected a whole number in 0..64"),
    (["--twist-steps", "-2"], ">= 0"),
    (["--arc-axes", "257"], "arc_axes = 257: expected a whole number in 0..256"),
    (["--arc-crease", "180"], "arc_crease = 180"),
    (["--arc-crease", "0"], "> 0"),
])
def test_bad_options_exit_2(cli, tmp_path, args, message):
    src = tmp_path / "a.stl"
    save(_mesh("extruded"), src, kind="mesh")
    r = cli("sweeps", src, *args)
    assert r.code == 2 and message in r.err
    assert files_in(tmp_path) == ["a.stl"]


def test_outputs_are_all_or_nothing_when_the_picture_fails(cli, tmp_path, monkeypatch):
    """The result file is written together with --glb / --png: a failing picture leaves no file at all."""
    import auszug.formats.sweeps_figure as figure
    from auszug.errors import GeometryError

    src = tmp_path / "a.stl"
    save(_mesh("extruded"), src, kind="mesh")

    def broken(*args, **kwargs):
        raise GeometryError("cannot draw this")

    monkeypatch.setattr(figure, "render_sweeps", broken)
    r = cli("sweeps", src, "-o", tmp_path / "r.sweeps.json", "--glb", tmp_path / "r.glb", "--png", tmp_path / "r.png")
    assert r.code == 2 and "cannot draw this" in r.err and "r.png" in r.err
    assert "Traceback" not in r.err
    assert files_in(tmp_path) == ["a.stl"]


def test_outputs_are_all_or_nothing_when_a_target_cannot_be_written(cli, tmp_path):
    """The picture's name is a folder: nothing is written, no temporary file is left, exit 2."""
    src = tmp_path / "a.stl"
    save(_mesh("extruded"), src, kind="mesh")
    (tmp_path / "r.png").mkdir()
    r = cli("sweeps", src, "-o", tmp_path / "r.sweeps.json", "--png", tmp_path / "r.png")
    assert r.code == 2 and "r.png" in r.err and "Traceback" not in r.err
    assert files_in(tmp_path) == ["a.stl"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.stl", "r.png"]


def test_atomic_write_all_removes_what_it_renamed_when_a_later_rename_fails(tmp_path, monkeypatch):
    import os

    from auszug.formats import atomic_write_all

    real = os.replace
    calls = []

    def flaky(a, b):
        calls.append(b)
        if len(calls) == 2:
            raise PermissionError(13, "denied")
        return real(a, b)

    monkeypatch.setattr(os, "replace", flaky)
    with pytest.raises(PermissionError) as e:
        atomic_write_all([(tmp_path / "a.json", "{}"), (tmp_path / "b.png", b"png")])
    assert e.value.filename == str(tmp_path / "b.png")
    assert files_in(tmp_path) == []


def test_parts_option_is_recorded_in_the_result(cli, tmp_path):
    """``--parts N`` sets ``max_parts``; the result file carries it and reads it back."""
    src = tmp_path / "a.stl"
    save(_mesh("extruded"), src, kind="mesh")
    out = tmp_path / "a.sweeps.json"
    r = cli("sweeps", src, "-o", out, "--parts", "3", "--quiet")
    assert r.code == 0, r.err
    rep = load(out, kind="sweeps")
    assert rep.params.max_parts == 3
    assert [p.kind for p in rep.patches] == ["translation"]


def test_mirror_and_coverage_options_are_recorded_in_the_result(cli, tmp_path):
    """``--mirror-planes N`` is ``mirror_planes``, ``--coverage-samples N`` is ``coverage_samples``;
    with 0 samples the coverage is the whole-face figure."""
    src = tmp_path / "a.stl"
    save(_mesh("extruded"), src, kind="mesh")
    out = tmp_path / "a.sweeps.json"
    r = cli("sweeps", src, "-o", out, "--mirror-planes", "0", "--coverage-samples", "0", "--quiet")
    assert r.code == 0, r.err
    rep = load(out, kind="sweeps")
    assert rep.params.mirror_planes == 0 and rep.params.coverage_samples == 0
    assert rep.coverage == rep.face_coverage
    assert [p.kind for p in rep.patches] == ["translation"]


def test_twist_and_arc_options_are_recorded_in_the_result(cli, tmp_path):
    """``--twist-steps N`` is ``twist_steps``, ``--arc-axes N`` is ``arc_axes``, ``--arc-crease DEG`` is
    ``arc_crease``; the result file carries them and reads them back."""
    src = tmp_path / "a.stl"
    save(_mesh("extruded"), src, kind="mesh")
    out = tmp_path / "a.sweeps.json"
    r = cli("sweeps", src, "-o", out, "--twist-steps", "0", "--arc-axes", "3", "--arc-crease", "35.5", "--quiet")
    assert r.code == 0, r.err
    rep = load(out, kind="sweeps")
    assert (rep.params.twist_steps, rep.params.arc_axes, rep.params.arc_crease) == (0, 3, 35.5)
    assert [p.kind for p in rep.patches] == ["translation"]


def test_match_scale_and_runs_options_are_recorded_and_l_min_wins(cli, tmp_path):
    """``--match-scale F`` is ``SweepParams.with_scale(F)``, ``--match-runs N`` is ``max_match_runs``; an
    explicit ``--l-min`` wins over the scale (the rest of the scaled lengths stay scaled)."""
    from auszug.sweeps import DEFAULT

    src = tmp_path / "a.stl"
    save(_mesh("extruded"), src, kind="mesh")
    want = DEFAULT.with_(max_match_runs=900).with_scale(0.25)
    for extra, l_min in (([], 0.05), (["--l-min", "0.1"], 0.1)):
        out = tmp_path / f"a{len(extra)}.sweeps.json"
        r = cli("sweeps", src, "-o", out, "--match-scale", "0.25", "--match-runs", "900", "--quiet", *extra)
        assert r.code == 0, r.err
        rep = load(out, kind="sweeps")
        assert rep.params == want.with_(l_min=l_min)
        assert rep.params.max_match_runs == 900 and rep.params.match_spacing == 0.00125
        assert [p.kind for p in rep.patches] == ["translation"]
