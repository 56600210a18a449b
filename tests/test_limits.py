"""auszug.limits: one set of limits, enforced by readers, model, CLI and studio, with clear errors.

Each measured failure of issue 14 (sections 2 and 3) has a test here, and the
largest accepted inputs run under a 2 GB memory limit.
"""

from __future__ import annotations

import os
import resource
import shutil
import subprocess
import sys
import time
from dataclasses import fields
from pathlib import Path

import pytest

from auszug import examples
from auszug.errors import AuszugError, DrawingError, FormatError
from auszug.formats import load
from auszug.formats.uc import read_uc
from auszug.limits import LIMITS, Limits, clip, shown
from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry
from tests.cli.conftest import TN
from tests.conftest import CORPUS

ROOT = Path(__file__).resolve().parents[1]
TN2 = (TN / "tn-2.uc").read_text()
TN2_FOLD_LINE = 2  # "unitCurve 4 1"




def _with(text: str, old: str, new: str) -> str:
    assert old in text
    return text.replace(old, new)


def _scaled(text: str, factor: float) -> str:
    out = []
    for ln in text.splitlines():
        key, *vals = ln.split()
        if key in ("ptPos", "reflectionPoint", "height"):
            ln = " ".join([key, *(repr(float(v) * factor) for v in vals)])
        out.append(ln)
    return "\n".join(out) + "\n"


# -- the module and its documentation ----------------------------------------------------------
def test_every_limit_is_documented_with_its_reason_and_in_docs():
    doc = Limits.__doc__ or ""
    table = (ROOT / "docs" / "limits.md").read_text()
    for f in fields(Limits):
        assert f"    {f.name} :" in doc, f.name
        assert f"`{f.name}`" in table, f.name
    assert "docs/limits.md" in (ROOT / "README.md").read_text()


def test_limits_are_frozen():
    with pytest.raises(AttributeError):
        LIMITS.fold = 5  # type: ignore[misc]  # frozen: the point of the test


def test_a_200_mb_token_makes_a_short_message():
    token = "x" * (200 * 2**20)
    assert len(shown(token)) < 2 * LIMITS.quoted
    assert len(clip("bad: " + token)) <= LIMITS.message


# -- drawings: fold, layers, coordinates, curves ----------------------------------------------
@pytest.mark.parametrize("fold", ["100000", "1000000000", "1e300"])
def test_fold_beyond_the_limit_is_refused_at_its_line_at_once(fold):
    t0 = time.perf_counter()
    with pytest.raises(FormatError) as info:
        read_uc(_with(TN2, "unitCurve 4 1", f"unitCurve {fold} 1"), "big.uc")
    assert time.perf_counter() - t0 < 1.0
    e = info.value
    assert e.path == "big.uc" and e.line == TN2_FOLD_LINE
    assert "above the limit of 1024" in e.problem and "LIMITS.fold" in e.problem


def test_fold_at_the_limit_is_accepted():
    assert read_uc(_with(TN2, "unitCurve 4 1", "unitCurve 1024 1")).curves[0].symmetry.fold == 1024


def test_level_1e99_is_refused_by_info(cli, tmp_path):
    p = tmp_path / "level.uc"
    p.write_text(_with(TN2, "level 0", "level 1e99"))
    r = cli("info", p)
    assert r.code == 2 and r.err.startswith(f"auszug: {p}:8: 'level' 1e+99 is above the limit of 63")


def test_coordinates_beyond_the_limit_are_refused_with_their_line():
    with pytest.raises(FormatError) as info:
        read_uc(_scaled(TN2, 1e90), "huge.uc")
    assert info.value.line == 3 and "beyond the limit of +-1e+06" in info.value.problem  # reflectionPoint


def test_apex_1e90_is_refused_at_its_line():
    with pytest.raises(FormatError) as info:
        read_uc(_with(TN2, "height 1.8216572932489614", "height 1e90"), "apex.uc")
    assert info.value.line == 9 and "'height': 1e90 is beyond the limit" in info.value.problem


@pytest.mark.parametrize("make, words", [
    (lambda: Symmetry(100000), "rotation fold 100000 is above the limit of 1024"),
    (lambda: BasicCurve(((0, 0), (1e90, 0)), (Segment(),), ("ground", "apex")), "coordinate 1e+90"),
    (lambda: BasicCurve(((0, 0), (1, 0)), (Segment(),), ("ground", "apex"), height=1e300), "apex height 1e+300"),
    (lambda: BasicCurve(((0, 0), (1, 0)), (Segment(),), ("ground", "apex"), layer=10**99), "layer 1e+99"),
    (lambda: Segment("arc", ((1e7, 0),)), "segment handle coordinate 1e+07"),
    (lambda: Drawing((), default_apex=1e90), "default apex height 1e+90"),
    (lambda: Drawing((BasicCurve(((0, 0), (1, 0)), (Segment(),), ("ground", "apex"), Symmetry(1024, True)),) * 40),
     "network curves"),
])
def test_the_model_refuses_what_the_readers_refuse(make, words):
    """The API (and the studio, whose edits make drawings) meet the same limits."""
    with pytest.raises(DrawingError, match="limit") as info:
        make()
    assert words in str(info.value)


def test_too_many_curves_are_refused_while_reading():
    curve = TN2.split("\n", 1)[1].rsplit("layer_bottom", 1)[0]
    text = "".join(curve for _ in range(LIMITS.curves + 1))
    with pytest.raises(FormatError, match="more than 1024 curves"):
        read_uc(text, "many.uc")


# -- file size ---------------------------------------------------------------------------------
def _sparse(path: Path, size: int) -> Path:
    with open(path, "wb") as fh:
        fh.write(b"numCurves 1\n")
        fh.truncate(size)  # a hole: quick to make, no disk used
    return path


@pytest.mark.parametrize("name", ["big.uc", "big.json"])
def test_a_200_mb_file_is_refused_before_it_is_read(tmp_path, name):
    p = _sparse(tmp_path / name, 200 * 2**20)
    t0 = time.perf_counter()
    with pytest.raises(FormatError) as info:
        load(p)
    assert time.perf_counter() - t0 < 0.5
    assert info.value.path == str(p) and "200 MB is larger than the limit of 64 MB" in info.value.problem


def test_a_200_mb_file_fails_alone_in_a_batch(cli, tmp_path):
    src = tmp_path / "in"
    src.mkdir()
    shutil.copy(TN / "tn-2.uc", src / "good.uc")
    _sparse(src / "big.uc", 200 * 2**20)
    r = cli("build", src, "-o", tmp_path / "out")
    assert r.code == 2 and "big.uc: file of 200 MB" in r.err
    assert (tmp_path / "out" / "good.network.json").exists()


def test_a_200_mb_style_file_is_refused(cli, tmp_path):
    p = _sparse(tmp_path / "big.toml", 200 * 2**20)
    r = cli("tracery", p)
    assert r.code == 2 and "larger than the limit" in r.err


# -- the command line ---------------------------------------------------------------------------
def test_samples_beyond_the_limit(cli, tmp_path):
    r = cli("info", TN / "tn-2.uc", "--samples", "100000000")
    assert r.code == 2 and "samples per curve piece: 100000000 is above the limit of 10000" in r.err


def test_a_tolerance_that_makes_too_many_points_is_refused(cli, tmp_path):
    p = tmp_path / "f.uc"
    p.write_text(_with(TN2, "unitCurve 4 1", "unitCurve 1024 1"))
    r = cli("build", p, "-o", tmp_path / "f.obj", "--tolerance", "1e-5")
    assert r.code == 2 and "more than 2000000 points" in r.err and "give a larger tolerance" in r.err
    assert not (tmp_path / "f.obj").exists()


@pytest.mark.parametrize("opt", ["--width", "--height"])
def test_render_size_beyond_the_limit(cli, tmp_path, opt):
    r = cli("render", TN / "tn-2.uc", opt, "100000", "-o", tmp_path / "r.png")
    assert r.code == 2 and "above the limit of 16384" in r.err and "Traceback" not in r.err


def test_tracery_picture_width_beyond_the_limit(cli, tmp_path):
    r = cli("tracery", "fig20a", "--width", "100000", "-o", tmp_path / "w.png")
    assert r.code == 2 and "above the limit of 16384" in r.err


@pytest.mark.parametrize("setting, name", [("excess=big", "excess"), ("x=1e308", "x"), ("span=1e300", "span"),
                                            ("height=-1e308", "height")])
def test_tracery_set_errors_name_the_parameter(cli, setting, name):
    r = cli("tracery", "fig20a", "--set", setting)
    assert r.code == 2 and r.err.startswith(f"auszug: {name}: expected ") and "Traceback" not in r.err


def test_a_tracery_toml_string_value_names_the_parameter(cli, tmp_path):
    p = tmp_path / "s.toml"
    p.write_text('extends = "fig20a"\n[params]\nexcess = "big"\n')
    r = cli("tracery", p)
    assert r.code == 2 and r.err == f"auszug: {p}: excess: expected a number, got 'big'\n"


def test_an_empty_style_is_refused_saying_so(cli, tmp_path):
    p = tmp_path / "empty.toml"
    p.write_text("# nothing here\n")
    r = cli("tracery", p, "-o", tmp_path / "w.glb")
    assert r.code == 2 and "empty style" in r.err and not (tmp_path / "w.glb").exists()


@pytest.mark.parametrize("extra", [[], ["--faces", "auto"]])
def test_mesh_of_a_drawing_scaled_to_1e90_is_refused(cli, tmp_path, extra):
    p = tmp_path / "huge.uc"
    p.write_text(_scaled(TN2, 1e90))
    r = cli("mesh", p, *extra, "-o", tmp_path / "m.glb")
    assert r.code == 2 and r.err.startswith(f"auszug: {p}:3: 'reflectionPoint'") and "limit" in r.err
    assert not (tmp_path / "m.glb").exists()


def test_mesh_of_apex_1e90_is_refused(cli, tmp_path):
    p = tmp_path / "apex.uc"
    p.write_text(_with(TN2, "height 1.8216572932489614", "height 1e90"))
    r = cli("mesh", p, "-o", tmp_path / "m.glb")
    assert r.code == 2 and r.err.startswith(f"auszug: {p}:9: 'height'")


@pytest.mark.parametrize("opt, words", [("--thickness", "expected a number > 0"), ("--size", "positive number")])
def test_mesh_refuses_a_negative_size(cli, tmp_path, opt, words):
    r = cli("mesh", TN / "tn-2.uc", "--solid", opt, "-1", "-o", tmp_path / "m.stl")
    assert r.code == 2 and words in r.err and not (tmp_path / "m.stl").exists()


def test_convert_refuses_to_overwrite_its_input(cli, tmp_path):
    p = tmp_path / "x.uc"
    p.write_text(TN2)
    for out in (p, tmp_path / "." / "x.uc"):
        r = cli("convert", p, out)
        assert r.code == 2 and "never overwrites its input" in r.err
    assert p.read_text() == TN2


def test_convert_refuses_a_drawing_that_cannot_be_built(cli, tmp_path):
    p = tmp_path / "low.uc"
    p.write_text(_with(TN2, "height 1.8216572932489614", "height 0"))
    r = cli("convert", p, tmp_path / "low.json")
    assert r.code == 2 and r.err.startswith(f"auszug: {p}:9: curve 0: apex height 0 is not above")
    assert not (tmp_path / "low.json").exists()


def test_write_errors_name_the_target(cli, tmp_path):
    (tmp_path / "file").write_text("")
    out = tmp_path / "file" / "x.obj"
    r = cli("build", TN / "tn-2.uc", "-o", out)
    assert r.code == 2 and r.err.startswith(f"auszug: {out}: cannot write") and ".tmp" not in r.err


def test_a_web_segment_error_names_the_files_points_and_line(cli, tmp_path):
    p = tmp_path / "free.uc"
    # a free end (A, T, B, T2, C) far longer than the upper arc it continues
    p.write_text(_with(TN2, "ptPos 0.9124859446451907 0\n",
                       "ptPos 0.9124859446451907 0\nptPos 3 0\nptPos 9 0\n"))
    r = cli("build", p, "-o", tmp_path / "x.obj")
    assert r.code == 2 and r.err.startswith(f"auszug: {p}:7: curve 0, segment 1 (points 2 to 4, line 7): ")


@pytest.mark.parametrize("command", ["build", "mesh"])
@pytest.mark.parametrize("kind", [MemoryError, ValueError, ZeroDivisionError, DrawingError])
def test_a_batch_goes_on_after_a_failed_file_of_any_kind(cli, tmp_path, monkeypatch, command, kind):
    from auszug.microarch import network

    src = tmp_path / "in"
    src.mkdir()
    for name in ("a", "b", "c"):
        shutil.copy(TN / "tn-2.uc", src / f"{name}.uc")
    real = network.build

    def build(drawing, *a, **kw):
        if drawing.name == "b":
            raise kind("deep down")
        return real(drawing, *a, **kw)

    monkeypatch.setattr(network, "build", build)
    r = cli(command, src, "-o", tmp_path / "out", "--segments" if command == "mesh" else "--samples", "8")
    assert r.code == 2 and "Traceback" not in r.err
    assert f"{src / 'b.uc'}" in r.err
    written = sorted(p.name for p in (tmp_path / "out").iterdir())
    assert written == (["a.network.json", "c.network.json"] if command == "build" else ["a.glb", "c.glb"])
    assert "wrote 2 of 3" in r.out and "(1 failed)" in r.out


def test_an_unexpected_error_is_one_line(cli, monkeypatch):
    from auszug.microarch import network

    def build(*a, **kw):
        raise ZeroDivisionError("a bug")

    monkeypatch.setattr(network, "build", build)
    r = cli("info", TN / "tn-2.uc")
    assert r.code == 1 and r.err == ("auszug: internal error: ZeroDivisionError: a bug "
                                     "(AUSZUG_DEBUG=1 shows the traceback)\n")


def test_python_m_auszug_and_auszug_alone_list_the_commands():
    from auszug.cli import COMMANDS

    r = subprocess.run([sys.executable, "-m", "auszug"], capture_output=True, text=True)
    assert r.returncode == 2 and all(f"    {c} " in r.stderr for c in COMMANDS), r.stderr
    r = subprocess.run([sys.executable, "-m", "auszug", "--version"], capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.startswith("auszug ")


def test_auszug_examples_prints_paths_that_work(cli, tmp_path):
    from auszug import examples

    r = cli("examples")
    lines = r.out.splitlines()
    assert r.code == 0 and lines[0].startswith("bundled drawings in ")
    assert len(lines) - 1 == len(examples.names()) and all(Path(s.strip()).is_file() for s in lines[1:])
    r = cli("examples", "--path", "teaching-sheet/tn-2.uc")
    assert Path(r.out.strip()) == examples.path("teaching-sheet/tn-2.uc")
    assert cli("build", r.out.strip(), "-o", tmp_path / "t.obj").code == 0


# -- the studio ---------------------------------------------------------------------------------
@pytest.mark.parametrize("message, words", [
    ('{"type": "set_symmetry", "curve": 0, "fold": 100000}', "rotation fold 100000 is above the limit of 1024"),
    ('{"type": "set_apex_height", "curve": 0, "height": 1e300}', "apex height 1e+300 is beyond the limit"),
    ('{"type": "move_vertex", "curve": 0, "vertex": 0, "xy": [1e90, 0]}', "coordinate 1e+90 is beyond"),
])
def test_a_studio_edit_beyond_a_limit_changes_nothing(tmp_path, message, words):
    from auszug.studio import protocol as P
    from auszug.studio.session import Session, Workspace

    shutil.copy(TN / "tn-2.uc", tmp_path / "tn-2.uc")
    s = Session(Workspace(tmp_path))
    s.open("tn-2.uc")
    d0, rev = s.drawing, s.revision
    with pytest.raises(AuszugError) as info:
        s.apply(P.decode(message))
    assert words in str(info.value)
    assert s.drawing is d0 and s.revision == rev


def test_a_long_token_in_a_studio_message_makes_a_short_error():
    from auszug.studio import protocol as P

    with pytest.raises(P.ProtocolError) as info:
        P.decode('{"type": "set_apex_height", "curve": 0, "height": "' + "9" * 5_000_000 + '"}')
    assert len(str(info.value)) < 300


# -- memory: the largest accepted inputs stay below 2 GB -----------------------------------------
_RUN = """
import resource, sys
resource.setrlimit(resource.RLIMIT_AS, (2 * 2**30, 2 * 2**30))
from auszug.cli import main
sys.exit(main(sys.argv[1:]))
"""


@pytest.mark.skipif(not hasattr(resource, "RLIMIT_AS") or sys.platform != "linux", reason="Linux address limit")
@pytest.mark.parametrize("args", [
    ["info", "{fold}", "--samples", "976"],                                         # largest fold, most points
    ["build", "{fold}", "-o", "{out}/f.obj", "--samples", "976"],                   # 2 M points written
    ["build", "{tn}", "-o", "{out}/t.network.json", "--samples", str(LIMITS.samples)],
    ["render", "{fold}", "-o", "{out}/f.png", "--width", "16384", "--height", "4096"],
    ["mesh", "{fold}", "-o", "{out}/f.glb"],
], ids=["info-fold", "build-fold-points", "build-samples", "render-pixels", "mesh-fold"])
def test_largest_accepted_inputs_run_in_2_gb(tmp_path, args):
    fold = tmp_path / "fold.uc"
    fold.write_text(_with(TN2, "unitCurve 4 1", f"unitCurve {LIMITS.fold} 1"))
    argv = [a.format(fold=fold, out=tmp_path, tn=TN / "tn-2.uc") for a in args]
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
    r = subprocess.run([sys.executable, "-c", _RUN, *argv], capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 0, r.stderr[-2000:]


# -- work limits of the mesh stages: refused up front, in 2 GB and seconds ----------------------
@pytest.mark.skipif(not hasattr(resource, "RLIMIT_AS") or sys.platform != "linux", reason="Linux address limit")
@pytest.mark.parametrize("args, words", [
    (["--faces", "auto"], "above the limit of 512 curves (auszug.limits.LIMITS.face_solid_curves)"),
    (["--solid"], "a solid of a network of 2048 curves is above the limit of 512"),
    (["--solid", "--faces", "auto"], "a solid of a network of 2048 curves is above the limit of 512"),
    (["--segments", "10000"], "the members would have about 163,840,000 triangles, above the limit"),
    (["--style", "tube", "--around", "1000"], "use fewer segments, fewer points around"),
], ids=["faces", "solid", "solid-faces", "segments", "around"])
def test_mesh_stages_of_a_fold_1024_drawing_are_refused_at_once_in_2_gb(tmp_path, args, words):
    """Before: fold 256 --faces auto took 188 s and 5.2 GB, --segments 10000 on fold 1024 ran out of memory."""
    import time

    fold = tmp_path / "fold.uc"
    fold.write_text(_with(TN2, "unitCurve 4 1", f"unitCurve {LIMITS.fold} 1"))
    out = tmp_path / "f.glb"
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
    t0 = time.monotonic()
    r = subprocess.run([sys.executable, "-c", _RUN, "mesh", str(fold), *args, "-o", str(out)],
                       capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 2 and words in r.stderr and str(fold) in r.stderr, r.stderr[-2000:]
    assert "Traceback" not in r.stderr and not out.exists()
    assert time.monotonic() - t0 < 120  # refused before the work (about 1 s alone; generous under load)


@pytest.mark.parametrize("name", examples.names())
def test_the_loop_bound_bounds_the_loops_found(name):
    """The estimate the faces stage checks is never below the loops find_loops returns."""
    from auszug.meshing.faces import _loop_bound
    from auszug.meshing.loops import _add_rims, find_loops, network_graph
    from auszug.microarch import build

    try:
        g = _add_rims(network_graph(build(load(CORPUS / name))))
    except AuszugError:
        return  # a drawing that does not build has no faces to bound
    n = len(find_loops(g, rims=False))
    assert n <= _loop_bound(g), (n, _loop_bound(g))


def test_the_loop_bound_of_a_fold_16_drawing():
    from auszug.meshing.faces import _loop_bound
    from auszug.meshing.loops import _add_rims, find_loops, network_graph
    from auszug.microarch import build

    g = _add_rims(network_graph(build(read_uc(_with(TN2, "unitCurve 4 1", "unitCurve 16 1"), "t.uc"))))
    assert len(find_loops(g, rims=False)) == 176 <= _loop_bound(g) <= 190


def test_given_loops_beyond_the_faces_limit_are_refused(monkeypatch):
    from auszug.meshing.faces import network_faces
    from auszug.meshing.loops import find_loops
    from auszug.microarch import build

    net = build(read_uc(TN2, "t.uc"))
    loops = find_loops(net)
    monkeypatch.setattr("auszug.meshing.faces.LIMITS", Limits(faces=len(loops) - 1))
    with pytest.raises(DrawingError, match=f"{len(loops)} faces are above the limit of {len(loops) - 1}"):
        network_faces(net, loops)


# -- lifting: strokes and crossings of a sketch ---------------------------------------------------
def _grid_svg(rows: int, cols: int) -> str:
    """``rows`` near-horizontal and ``cols`` near-vertical straight strokes: rows x cols crossings."""
    paths = [f'<path id="h{i}" d="M -1 {10 * i + 0.3 * i * i / rows:.3f} '
             f'L {10 * cols + 5} {10 * i + 2 + 0.1 * i:.3f}"/>' for i in range(rows)]
    paths += [f'<path id="v{j}" d="M {10 * j + 0.2 * j * j / cols:.3f} -1 '
              f'L {10 * j + 3 + 0.1 * j:.3f} {10 * rows + 5}"/>' for j in range(cols)]
    return ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="-10 -10 400 400"><g fill="none" stroke="black">'
            + "".join(paths) + "</g></svg>")


def _long_strokes_svg(n: int) -> str:
    """Two straight strokes crossing once, each ``n`` cubic segments (``C`` commands with their handles at
    thirds: not line commands, so the reader does not refit them as one sampled curve)."""
    def d(p0: tuple[float, float], p1: tuple[float, float]) -> str:
        pts = [(p0[0] + (p1[0] - p0[0]) * i / (3 * n), p0[1] + (p1[1] - p0[1]) * i / (3 * n)) for i in range(3 * n + 1)]
        return f"M {pts[0][0]:.6f} {pts[0][1]:.6f} " + " ".join(
            "C " + " ".join(f"{x:.6f} {y:.6f}" for x, y in pts[3 * k + 1:3 * k + 4]) for k in range(n))
    return ('<svg xmlns="http://www.w3.org/2000/svg" viewBox="-10 -60 120 120"><g fill="none" stroke="black">'
            f'<path id="a" d="{d((0.0, 0.0), (100.0, 0.0))}"/><path id="b" d="{d((50.0, -50.0), (50.0, 50.0))}"/>'
            '</g></svg>')


@pytest.mark.skipif(not hasattr(resource, "RLIMIT_AS") or sys.platform != "linux", reason="Linux address limit")
@pytest.mark.parametrize("rows, cols, words", [
    (21, 20, "the sketch has 420 crossings: more than the limit of 400 (auszug.limits.LIMITS.sketch_crossings)"),
    (1, LIMITS.sketch_strokes, "the sketch has 257 strokes: more than the limit of 256 "
                               "(auszug.limits.LIMITS.sketch_strokes)"),
    (0, 0, "the sketch has 4098 Bezier segments: more than the limit of 4096 (auszug.limits.LIMITS.sketch_segments)"),
], ids=["crossings", "strokes", "segments"])
def test_lift_beyond_its_limits_is_refused_at_once_in_2_gb(tmp_path, rows, cols, words):
    """Beyond the limits the time grows without bound (a 20 x 20 grid of straight strokes, 400 crossings,
    now the crossing limit: 445 s without converging; docs/limits.md)."""
    import time

    src = tmp_path / "grid.svg"
    src.write_text(_grid_svg(rows, cols) if rows else _long_strokes_svg(LIMITS.sketch_segments // 2 + 1))
    out = tmp_path / "grid.network.json"
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
    t0 = time.monotonic()
    r = subprocess.run([sys.executable, "-c", _RUN, "lift", str(src), "-o", str(out), "--quiet"],
                       capture_output=True, text=True, env=env, timeout=600)
    assert r.returncode == 2 and r.stderr == f"auszug: {src}: {words}\n", r.stderr[-2000:]
    assert not out.exists()
    assert time.monotonic() - t0 < 60  # refused before any solve (about 2 s alone; generous under load)


def test_a_sketch_at_the_crossing_limit_passes_the_check():
    from auszug.formats.sketch_svg import read_sketch_svg
    from auszug.lifting import sketch_graph

    g = sketch_graph(read_sketch_svg(_grid_svg(20, 20), "grid.svg"))
    assert len(g.crossings) == LIMITS.sketch_crossings == 400


def test_a_sketch_at_the_segment_limit_passes_the_check():
    from auszug.formats.sketch_svg import read_sketch_svg
    from auszug.lifting import sketch_graph

    sk = read_sketch_svg(_long_strokes_svg(LIMITS.sketch_segments // 2), "long.svg")
    assert sum(len(s.controls) for s in sk.strokes) == LIMITS.sketch_segments == 4096
    assert len(sketch_graph(sk).crossings) == 1


@pytest.mark.parametrize("far, ok", [(1e6, True), (2e6, False)])
def test_sketch_coordinates_are_within_the_coordinate_limit(cli, tmp_path, far, ok):
    """A sketch's coordinates are held to LIMITS.coordinate like a drawing's (its network is exported as
    float32 meshes too); found by fuzzing the sketch reader: 1e308 overflowed the diagonal's norm."""
    src = tmp_path / "far.svg"
    src.write_text('<svg xmlns="http://www.w3.org/2000/svg">'
                   f'<path id="a" d="M {-far:.0f} 0 C -1 -3 1 -3 {far:.0f} 0"/>'
                   '<path id="b" d="M 1 -5 C 0.5 -1 -0.5 1 -1 5"/></svg>')
    out = tmp_path / "far.network.json"
    r = cli("lift", src, "-o", out, "--quiet", "--cues", "none")
    if ok:
        assert r.code == 0 and out.exists(), r.err
    else:
        assert r.code == 2 and r.err == (f"auszug: {src}: a: coordinate 2e+06 is beyond the limit of +-1e+06 "
                                         "(auszug.limits.LIMITS.coordinate)\n")
        assert not out.exists()
