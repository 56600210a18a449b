"""``auszug lift``: every example sketch through the command line, the report, the figure, bad input."""

from __future__ import annotations

import numpy as np
import pytest

from auszug import examples
from auszug.formats import load
from tests.cli.conftest import files_in, png_size

EXAMPLES = ["arches", "barrel-half", "ogee-roof", "vase"]


@pytest.mark.parametrize("name", EXAMPLES)
def test_each_example_lifts_and_its_network_reads_back(cli, tmp_path, name):
    src = examples.path(f"sketches/{name}.svg")
    out = tmp_path / f"{name}.network.json"
    r = cli("lift", src, "-o", out, "--report")
    assert r.code == 0, r.err
    assert r.out.splitlines()[-1] == f"wrote {out}"
    assert "lift: layer 0 baseline" in r.err and "NOT converged" not in r.err
    doc = load(out, kind="network")
    sketch = load(src, kind="sketch")
    assert doc["source"] == f"{name}.svg"
    # one curve per stroke; a half with a symmetry curve: that curve and the mirrored strokes too
    n = len(sketch.strokes) * (2 if sketch.symmetry is not None else 1) + (sketch.symmetry is not None)
    assert {c["basic"] for c in doc["curves"]} == set(range(n))
    assert ("global symmetry: layer 0 mirrored" in r.out) == (sketch.symmetry is not None)
    pts = np.concatenate([np.asarray(c["points"], float) for c in doc["curves"]])
    assert np.isfinite(pts).all() and np.ptp(pts[:, 2]) > 0.05 * np.ptp(pts[:, :2], axis=0).max()  # lifted
    # --report: every applied hard cue within 0.5 deg, smooth crossings exactly orthogonal
    lines = [ln.split() for ln in r.out.splitlines() if ln.startswith("  smooth-orthogonal")]
    assert lines and max(float(ln[-2]) for ln in lines) < 1e-3


def test_obj_output_and_the_figure(cli, tmp_path):
    out, fig = tmp_path / "a.obj", tmp_path / "a.png"
    r = cli("lift", examples.path("sketches/arches.svg"), "-o", out, "--render", fig, "--quiet", "--cues", "none")
    assert r.code == 0, r.err
    assert r.err == "" and r.out == f"wrote {out} and {fig}\n"
    assert len({k.split(".")[0] for k in load(out, kind="network")}) == 6 and png_size(fig.read_bytes()) == (1800, 640)
    assert files_in(tmp_path) == ["a.obj", "a.png"]


def test_bad_sketches_exit_2_and_write_nothing(cli, tmp_path):
    bad = tmp_path / "bad.svg"
    bad.write_text('<svg xmlns="http://www.w3.org/2000/svg"><path id="p" d="M 0 0 L nan 1"/></svg>')
    r = cli("lift", bad, "-o", tmp_path / "out.network.json")
    assert r.code == 2 and r.err.strip() == f"auszug: {bad}: p: NaN or infinity in its 'd' attribute"
    (tmp_path / "empty.svg").write_text("")
    assert cli("lift", tmp_path / "empty.svg", "-o", tmp_path / "o.obj").code == 2
    assert cli("lift", examples.path("sketches/arches.svg"), "-o", tmp_path / "x.txt").code == 2
    assert cli("lift", examples.path("sketches/arches.svg"), "--cues", "wobbly").code == 2
    assert files_in(tmp_path) == ["bad.svg", "empty.svg"]


def test_the_help_names_the_lifting_packages_cue_classes():
    from auszug import lifting
    from auszug.cli import lift as cli_lift

    assert cli_lift.CUE_CLASSES == lifting.CLASSES and cli_lift.DEFAULT_CUES == lifting.DEFAULT_CLASSES


def test_other_commands_do_not_import_the_lifting_package():
    import subprocess
    import sys

    code = ("import sys; from auszug.cli import make_parser; make_parser(); import auszug.formats; "
            "print(any(m.startswith('auszug.lifting') for m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.stdout.strip() == "False", out.stderr
