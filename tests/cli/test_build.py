"""``auszug build``: formats by ending, folders, default names, options, and bad input."""

from __future__ import annotations

import math
import shutil
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from auszug.formats import load
from auszug.microarch import build
from tests.cli.conftest import BAD_LINE, LOW_APEX_LINE, TN, files_in
from tests.conftest import CORPUS


@pytest.mark.parametrize("ending, check", [
    (".network.json", lambda p: load(p, kind="network")["source"] == "tn-7.uc"),
    (".obj", lambda p: len(load(p, kind="network")) == len(list(build(load(TN / "tn-7.uc")).curves()))),
    (".svg", lambda p: ET.parse(p).getroot().tag.endswith("svg")),
    (".dxf", lambda p: p.read_text().startswith("  0\nSECTION\n") and "AUSZUG" in p.read_text()),
    (".3dm", lambda p: p.read_bytes().startswith(b"3D Geometry File Format")),
])
def test_output_ending_picks_the_format(cli, tmp_path, ending, check):
    out = tmp_path / f"sub/tn-7{ending}"
    r = cli("build", TN / "tn-7.uc", "-o", out)
    assert r.code == 0, r.err
    assert r.out == f"wrote {out}\n"
    assert check(out)
    assert files_in(tmp_path) == [f"sub/tn-7{ending}"]          # no temporary file left


def test_default_output_is_network_json_in_the_current_folder(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert cli("build", TN / "tn-3.uc").code == 0
    assert cli("build", TN / "tn-4.uc", "--format", "obj").code == 0
    assert files_in(tmp_path) == ["tn-3.network.json", "tn-4.obj"]


def test_a_folder_gives_one_file_per_drawing_keeping_subfolders(cli, tmp_path):
    src = tmp_path / "in"
    shutil.copytree(CORPUS / "web" / "ribbons", src / "ribbons")
    shutil.copy(TN / "tn-1.uc", src / "tn-1.uc")
    (src / "notes.txt").write_text("not a drawing")
    (src / "old.network.json").write_text("{}")          # an output, not a drawing
    r = cli("build", src, "-o", tmp_path / "out")
    assert r.code == 0, r.err
    want = sorted(["tn-1.network.json"] + [f"ribbons/{p.name[:-3]}.network.json"
                                           for p in (src / "ribbons").glob("*.uc")])
    assert files_in(tmp_path / "out") == want
    assert r.out == f"wrote {len(want)} of {len(want)} networks to {tmp_path / 'out'}\n"


def test_several_files_and_an_svg_folder(cli, tmp_path):
    r = cli("build", TN / "tn-1.uc", TN / "tn-10.uc", "-o", tmp_path / "o/", "--format", "svg")
    assert r.code == 0
    assert files_in(tmp_path / "o") == ["tn-1.svg", "tn-10.svg"]


def test_one_drawing_into_an_existing_folder(cli, tmp_path):
    assert cli("build", TN / "tn-2.uc", "-o", tmp_path).code == 0
    assert files_in(tmp_path) == ["tn-2.network.json"]


def test_reconstruction_options_reach_the_network(cli, tmp_path):
    out = tmp_path / "n.network.json"
    assert cli("build", TN / "tn-1.uc", "-o", out, "--samples", "129", "--param", "u").code == 0
    doc = load(out, kind="network")
    ref = build(load(TN / "tn-1.uc"), "u", samples=129)
    assert doc["parameterization"] == "u"
    assert all(len(c["points"]) == 129 for c in doc["curves"])
    np.testing.assert_array_equal(doc["curves"][0]["points"], ref.pieces[0].points)


def test_theta_is_in_degrees(cli, tmp_path):
    out = tmp_path / "n.network.json"
    args = ("--param", "orthographic", "--theta", "30", "--samples", "65")
    assert cli("build", TN / "tn-3.uc", "-o", out, *args).code == 0
    got = load(out, kind="network")["curves"][0]["points"]
    d = load(TN / "tn-3.uc")
    np.testing.assert_array_equal(got, build(d, "orthographic", theta=math.radians(30.0)).pieces[0].points)
    assert not np.array_equal(got, build(d, "orthographic", theta=0.0).pieces[0].points)


def test_a_side_view_that_is_not_one_to_one_is_a_drawing_error(cli, tmp_path):
    src = tmp_path / "diagonal.uc"
    src.write_text("numCurves 1\nunitCurve 4 0\nptPos 0 1\nptPos 0.3 1.3\nptPos 1 2\nheight 1\n")
    r = cli("build", src, "-o", tmp_path / "d.obj", "--param", "orthographic", "--theta", "135")
    assert r.code == 2
    # the file's own point numbers and the line of the segment's first point
    assert r.err.startswith(f"auszug: {src}:3: curve 0, segment 0 (points 0 to 2, line 3): ") and \
        "not one-to-one" in r.err
    assert not (tmp_path / "d.obj").exists()


def test_bad_drawing_names_file_and_line_and_leaves_no_output(cli, tmp_path, bad_uc):
    out = tmp_path / "o" / "bad.network.json"
    r = cli("build", bad_uc, "-o", out)
    assert r.code == 2
    assert r.err == f"auszug: {bad_uc}:{BAD_LINE}: 'ptPos': 'x' is not a number\n"
    assert "Traceback" not in r.err and r.out == ""
    assert not out.exists() and not out.parent.exists()


def test_invalid_drawing_names_the_file_and_the_curve(cli, tmp_path, low_apex_uc):
    r = cli("build", low_apex_uc, "-o", tmp_path / "low.obj")
    assert r.code == 2
    assert r.err.startswith(f"auszug: {low_apex_uc}:{LOW_APEX_LINE}: curve 0") and "apex height -1" in r.err
    assert files_in(tmp_path) == ["low.uc"]


def test_in_a_folder_a_bad_drawing_fails_alone(cli, tmp_path, bad_uc, low_apex_uc):
    shutil.copy(TN / "tn-1.uc", tmp_path / "good.uc")
    r = cli("build", tmp_path, "-o", tmp_path / "out")
    assert r.code == 2
    assert files_in(tmp_path / "out") == ["good.network.json"]
    assert f"auszug: {bad_uc}:{BAD_LINE}:" in r.err and f"auszug: {low_apex_uc}:{LOW_APEX_LINE}: curve 0" in r.err
    assert "wrote 1 of 3 networks" in r.out and "(2 failed)" in r.out


@pytest.mark.parametrize("out, message", [
    ("x.xyz", "unknown file type; expected one of .3dm, .dxf, .network.json, .obj, .svg"),
    ("x.json", "unknown file type; expected one of .3dm, .dxf, .network.json, .obj, .svg"),
    ("x.png", "unknown file type; expected one of .3dm, .dxf, .network.json, .obj, .svg"),
])
def test_unknown_output_ending_is_refused_before_any_work(cli, tmp_path, out, message):
    r = cli("build", TN / "tn-1.uc", "-o", tmp_path / out)
    assert r.code == 2 and r.err == f"auszug: {tmp_path / out}: {message}\n"
    assert files_in(tmp_path) == []


def test_format_must_agree_with_the_output_ending(cli, tmp_path):
    r = cli("build", TN / "tn-1.uc", "-o", tmp_path / "x.obj", "--format", "svg")
    assert r.code == 2 and "does not match" in r.err


@pytest.mark.parametrize("make_args, message", [
    (lambda t: ["build", t / "missing.uc"], "no such file or folder"),
    (lambda t: ["build", t / "empty"], "no drawings (.json, .uc) in this folder"),
    (lambda t: ["build", TN / "tn-1.uc", TN / "tn-2.uc", "-o", t / "f.network.json"], "need an output folder"),
    (lambda t: ["build", TN / "tn-1.uc", TN / "tn-1.uc", "-o", t / "o"], "would both be written"),
])
def test_folder_mistakes(cli, tmp_path, make_args, message):
    (tmp_path / "empty").mkdir()
    r = cli(*make_args(tmp_path))
    assert r.code == 2 and message in r.err and "Traceback" not in r.err
    assert files_in(tmp_path) == []


def test_progress_bar_on_a_terminal(cli, tmp_path, monkeypatch):
    import sys

    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)
    r = cli("build", TN / "tn-1.uc", TN / "tn-2.uc", "-o", tmp_path)
    assert r.code == 0
    assert files_in(tmp_path) == ["tn-1.network.json", "tn-2.network.json"]


def test_a_network_file_is_not_taken_for_a_drawing(cli, tmp_path):
    net = tmp_path / "a.network.json"
    assert cli("build", TN / "tn-1.uc", "-o", net).code == 0
    r = cli("build", net, "-o", tmp_path / "b.obj")
    assert r.code == 2 and r.err == f"auszug: {net}: not a drawing file name; drawings end in .json, .uc\n"
    assert files_in(tmp_path) == ["a.network.json"]


@pytest.mark.parametrize("fmt, ending", [("dxf", ".dxf"), ("3dm", ".3dm")])
def test_cad_formats_by_name_in_a_folder(cli, tmp_path, fmt, ending):
    r = cli("build", TN / "tn-1.uc", TN / "tn-10.uc", "-o", tmp_path / "o/", "--format", fmt)
    assert r.code == 0, r.err
    assert files_in(tmp_path) == [f"o/tn-1{ending}", f"o/tn-10{ending}"]
