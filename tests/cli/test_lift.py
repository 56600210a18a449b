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


def test_mesh_output_is_the_lifted_curves_swept_as_tubes(cli, tmp_path):
    src = examples.path("sketches/arches.svg")
    net_out, glb = tmp_path / "a.network.json", tmp_path / "a.glb"
    assert cli("lift", src, "-o", net_out, "--quiet", "--cues", "none").code == 0
    r = cli("lift", src, "-o", glb, "--quiet", "--cues", "none", "--size", "0.5", "--segments", "24", "--around", "10")
    assert r.code == 0, r.err
    mesh = load(glb, kind="mesh")
    doc = load(net_out, kind="network")
    # one part per stroke (the GLB has a node per basic curve), 25 rings of 10 per Bezier piece
    assert len(mesh.parts) == len({c["basic"] for c in doc["curves"]}) == 6
    assert len(mesh.vertices) == len(doc["curves"]) * 25 * 10
    # every vertex 0.25 (the tube's radius) from its piece's exact cubic (the network's "exact" record:
    # the sketch's Bezier lifted by its control depths), sampled at 2001 points (their chords stay
    # within 1e-5 of the curve here; float32 in the file: 3e-5 at these coordinates). A part is a
    # stroke, its vertices 250 per piece in the stroke's order.
    pts = np.concatenate([np.asarray(c["points"], float) for c in doc["curves"]])
    d = np.empty(len(mesh.vertices))
    u = np.linspace(0.0, 1.0, 2001)[:, None]
    bern = np.hstack([(1 - u) ** 3, 3 * (1 - u) ** 2 * u, 3 * (1 - u) * u * u, u**3])
    for part in mesh.parts:
        basic = int(part.name.split()[-1])
        pieces = [c["exact"] for c in doc["curves"] if c["basic"] == basic]
        assert part.vertices[1] - part.vertices[0] == 250 * len(pieces)
        for j, ex in enumerate(pieces):
            top = ex["top"]
            ctrl = np.c_[np.array([top["start"], *top["handles"], top["end"]], float), ex["depth"]]
            poly = bern @ ctrl
            lo = part.vertices[0] + 250 * j
            a, ab = poly[:-1], np.diff(poly, axis=0)
            q = np.asarray(mesh.vertices[lo:lo + 250], float)[:, None, :] - a[None]
            t = np.clip(np.einsum("vsk,sk->vs", q, ab) / np.einsum("sk,sk->s", ab, ab), 0.0, 1.0)
            d[lo:lo + 250] = np.linalg.norm(q - t[..., None] * ab[None], axis=2).min(axis=1)
    assert np.abs(d - 0.25).max() < 1e-4      # measured 2.2e-5
    assert np.ptp(mesh.vertices[:, 2]) > 0.9 * np.ptp(pts[:, 2])
    assert files_in(tmp_path) == ["a.glb", "a.network.json"]


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


def test_set_gives_the_lift_those_parameters(cli, tmp_path):
    """``--set family_prior=off`` writes what ``lift(sketch, LiftParams(family_prior=False))`` gives."""
    from auszug.formats import save
    from auszug.formats.network_json import NetworkFile
    from auszug.lifting import LiftParams, lift

    src = examples.path("sketches/ogee-roof.svg")
    on, off, api = tmp_path / "on.network.json", tmp_path / "off.network.json", tmp_path / "api.network.json"
    assert cli("lift", src, "-o", on, "--quiet").code == 0
    r = cli("lift", src, "-o", off, "--quiet", "--set", "family_prior=off", "--set", "w_f=0.001")
    assert r.code == 0, r.err
    result = lift(load(src, kind="sketch"), params=LiftParams(family_prior=False))
    save(NetworkFile(result.network, src.name), api, kind="network")
    # the family prior moves the ogee roof's lift (docs/lifting.md: 3.50 -> 2.13 %), so the switch is seen
    assert off.read_bytes() == api.read_bytes() != on.read_bytes()


@pytest.mark.parametrize(("item", "message"), [
    ("nope=1", "--set 'nope=1': LiftParams has no field 'nope'; fields: w_a, w_v,"),
    ("family_prior=maybe", "--set 'family_prior=maybe': family_prior must be on or off"),
    ("rounds=2.5", "--set 'rounds=2.5': rounds must be an integer"),
    ("w_f=abc", "--set 'w_f=abc': w_f must be a number"),
    ("w_a", "--set 'w_a': expected NAME=VALUE, e.g. family_prior=off"),
    ("w_a=-1", "--set: lifting parameter w_a must be a finite number >= 0, got -1.0"),
    ("w_a=nan", "--set: lifting parameter w_a must be a finite number >= 0, got nan"),
    ("rounds=101", "--set: lifting parameter rounds must be a whole number in 0..100 "
                   "(auszug.limits.LIMITS.lift_steps), got 101"),
])
def test_set_refuses_bad_parameters_before_any_work(cli, tmp_path, item, message):
    out = tmp_path / "o.network.json"
    r = cli("lift", examples.path("sketches/arches.svg"), "-o", out, "--set", item)
    assert r.code == 2 and r.err.startswith(f"auszug: {message}"), r.err
    assert "Traceback" not in r.err and files_in(tmp_path) == []


def test_a_lift_that_shrinks_a_segment_to_a_point_is_an_error_naming_the_stroke(cli, tmp_path, monkeypatch):
    # found by fuzzing (nine random strokes, 253 segments, no solve converged): the unconverged lift shrank
    # three segments to points in the sketch's plane and the network's Bezier check stopped the run with
    # "control points all coincide at [x, y]", naming no stroke; the lift is forced astray here the same way
    from auszug.lifting import reconstruct

    svg = tmp_path / "cross.svg"
    svg.write_text('<svg xmlns="http://www.w3.org/2000/svg">'
                   '<path id="h" d="M -100 0 C -40 -25 40 -25 100 0"/>'
                   '<path id="v" d="M 30 100 C 10 30 -10 -30 -30 -100"/></svg>')
    out = tmp_path / "cross.network.json"
    assert cli("lift", svg, "-o", out).code == 0 and out.exists()   # as drawn it lifts
    out.unlink()
    real = reconstruct.lift_graph

    def astray(g, *args, **kw):
        X, *rest = real(g, *args, **kw)
        X = X.copy()
        seg = g.segments[g.chains[1][1]]           # the second piece of stroke "v"
        X[seg[1:], :2] = X[seg[0], :2]             # its handles and end onto its start, in x and y
        return (X, *rest)

    monkeypatch.setattr(reconstruct, "lift_graph", astray)
    r = cli("lift", svg, "-o", out)
    assert r.code == 2 and "Traceback" not in r.err
    assert r.err.strip().splitlines()[-1] == (
        f"auszug: {svg}: stroke v: the lift shrank its segment 2 of 2 (split at the crossings) to a point in the "
        "sketch's plane (every solve converged): the solve went astray, the result is no lift of the drawing")
    assert files_in(tmp_path) == ["cross.svg"]


def test_a_stroke_drawn_short_of_another_is_refused_with_the_close_gaps_that_joins_it(cli, tmp_path):
    """The refusal names the gap and the ``--set close_gaps`` that closes it; with it, the lift reports the gap."""
    src = tmp_path / "t.svg"
    src.write_text('<svg xmlns="http://www.w3.org/2000/svg" viewBox="-120 -120 240 240">'
                   '<path id="bar" d="M -100 0 C -30 -30 30 -30 100 0"/><path id="post" d="M -60 80 L -60 -100"/>'
                   '<path id="s0" d="M 40 -100 L 40 -23"/></svg>')
    out = tmp_path / "t.network.json"
    r = cli("lift", src, "-o", out, "--quiet")
    assert r.code == 2 and files_in(tmp_path) == ["t.svg"]
    assert r.err.startswith(f"auszug: {src}: s0: not joined to the rest of layer 0 by any intersection;"), r.err
    assert "an end of s0 misses bar by 1.56% of the diagonal: close_gaps=0.0158 joins it" in r.err
    r = cli("lift", src, "-o", out, "--quiet", "--report", "--set", "close_gaps=0.0158")
    assert r.code == 0, r.err
    assert "gap closed: s0 end moved 1.555% of the diagonal onto bar" in r.out.splitlines()
    doc = load(out, kind="network")
    pieces = {b: [np.asarray(c["points"], float) for c in doc["curves"] if c["basic"] == b] for b in (0, 1, 2)}
    assert [len(pieces[b]) for b in (0, 1, 2)] == [3, 2, 1]           # the bar cut at the post and at s0's end
    # in 3D too, s0 ends where two of the bar's pieces meet
    assert np.array_equal(pieces[2][0][-1], pieces[0][1][-1]) and np.array_equal(pieces[0][1][-1], pieces[0][2][0])


def test_strokes_drawn_near_one_point_get_a_note_and_close_gaps_makes_it_one(cli, tmp_path):
    """Three lines meant to meet at one point drawn as a small triangle: the lift says which strokes and which
    ``--set close_gaps`` joins them; with it, ``--report`` lists the junction and the network has one point
    where all three lines' pieces meet."""
    h, paths, ends = 0.5, [], []
    for i in range(3):
        a = 0.2 + i * 2 * np.pi / 3
        u, n = np.array([np.cos(a), np.sin(a)]), np.array([-np.sin(a), np.cos(a)])
        p, q = h * n - 100 * u, h * n + 100 * u
        ends += [p, q]
        paths.append(f'<path id="l{i}" d="M {float(p[0])!r} {float(-p[1])!r} L {float(q[0])!r} {float(-q[1])!r}"/>')
    paths.append('<path id="bar" d="M -100 60 C -40 30 40 30 100 60"/>')       # crosses the lines far off
    src = tmp_path / "star.svg"
    src.write_text('<svg xmlns="http://www.w3.org/2000/svg">' + "".join(paths) + "</svg>")
    pts = np.array(ends + [[-100, -60], [-40, -30], [40, -30], [100, -60]])
    spread = 2 * np.sqrt(3) * h / float(np.linalg.norm(np.ptp(pts, axis=0)))
    want = np.ceil(spread * 1.01 * 1e4) / 1e4
    out = tmp_path / "star.network.json"
    r = cli("lift", src, "-o", out)
    assert r.code == 0, r.err
    note = (f"lift: note: l0, l1, l2 cross within {100 * spread:.2g}% of the diagonal of one another, not at one "
            f"point; if they meet at one point, --set close_gaps={want:g} makes it one intersection")
    assert note in r.err.splitlines()
    r = cli("lift", src, "-o", out, "--report", "--set", f"close_gaps={want:g}")
    assert r.code == 0, r.err
    assert "note:" not in r.err and "lift: made 1 group(s) of crossings drawn within" in r.err
    (line,) = [x for x in r.out.splitlines() if x.startswith("crossings joined:")]
    assert line == (f"crossings joined: l0, l1, l2 drawn within {100 * spread:.3g}% of the diagonal, made one point "
                    f"(strokes moved at most {100 * h / float(np.linalg.norm(np.ptp(pts, axis=0))):.3g}%)")
    doc = load(out, kind="network")
    meet = [np.asarray(c["points"], float)[e] for c in doc["curves"] if c["basic"] in (0, 1, 2) for e in (0, -1)]
    centre = [p for p in meet if np.linalg.norm(p[:2]) < h]
    assert len(centre) == 6 and all(np.array_equal(p, centre[0]) for p in centre)   # six pieces, one 3D point


def test_a_lift_that_collapses_is_refused_naming_the_crossings_drawn_near_one_point(cli, tmp_path):
    """The box with its sections drawn 0.2 % off the points where they meet its edges: as drawn, the solve
    collapses the network to a point; the lift refuses it (exit 2, no output), naming what joins the
    crossings; with that value it lifts."""
    from auszug.formats import save
    from tests.lifting import truth as T

    src = tmp_path / "box.sketch.json"
    save(T.shifted(T.box(meet=True), range(9, 15), 0.002, 0).sketch, src, kind="sketch")
    out = tmp_path / "box.network.json"
    r = cli("lift", src, "-o", out, "--quiet")
    assert r.code == 2 and "Traceback" not in r.err and files_in(tmp_path) == ["box.sketch.json"]
    (line,) = r.err.strip().splitlines()
    assert line.startswith(f"auszug: {src}: layer 0: the lift collapsed: its curves span ")
    assert "(auszug lift --set close_gaps=0.005; LiftParams.close_gaps)" in line
    assert cli("lift", src, "-o", out, "--quiet", "--set", "close_gaps=0.005").code == 0 and out.exists()
