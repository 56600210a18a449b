"""Global symmetry (paper sec. 4, Fig. 7): half a barrel drawn up to its symmetry curve, lifted and mirrored.

The truth (tests/lifting/truth.py, ``barrel_half``) is a surface of revolution whose symmetry plane is
known; the invariants checked are exact (the mirror, the shared points, the hard cues), the accuracy
figures are measured ones (docs/lifting.md, "Global symmetry").
"""

from __future__ import annotations

import numpy as np
import pytest

from auszug.errors import FormatError, GeometryError
from auszug.formats.sketch_json import dumps, loads
from auszug.formats.sketch_svg import read_sketch_svg
from auszug.lifting import Sketch, Stroke, layer_graphs, lift
from tests.lifting import truth as T


@pytest.fixture(scope="module")
def barrel():
    tr, mirrored = T.barrel_half()
    return tr, mirrored, lift(tr.sketch)


def test_the_mirror_is_exact_and_shares_the_points_on_the_symmetry_curve(barrel):
    tr, _, r = barrel
    assert r.converged and r.mirror is not None
    layer, n, d = r.mirror
    assert layer == 0 and abs(np.linalg.norm(n) - 1) < 1e-12
    g, X = r.graphs[0], r.points[0]
    drawn = len(tr.sketch.strokes)
    ids = [s.id for s in g.strokes]
    assert ids == [*(s.id for s in tr.sketch.strokes), "symmetry", *(f"{s.id} (mirror)" for s in tr.sketch.strokes)]
    diag = tr.diagonal()
    sym_pts = np.unique(g.segments[g.chains[drawn]])
    assert np.abs(X[sym_pts] @ n - d).max() <= 1e-7 * diag          # the symmetry curve lies in the plane
    for k in range(drawn):
        a, b = g.segments[g.chains[k]], g.segments[g.chains[drawn + 1 + k]]
        reflected = X[a] - 2.0 * ((X[a] @ n) - d)[..., None] * n
        assert np.abs(X[b] - reflected).max() <= 1e-9 * diag          # exactly the mirror image
        shared = np.isin(a, sym_pts)
        assert np.array_equal(a[shared], b[shared])                    # ends on the curve are the same points
    meridians = [k for k in range(drawn) if np.isin(g.segments[g.chains[k]][0, 0], sym_pts)]
    assert len(meridians) == 5                                         # the five meridians start on it
    for k in meridians:                                                # ... normal to the symmetry plane
        s0 = g.segments[g.chains[k]][0]
        t = X[s0[1]] - X[s0[0]]
        assert np.degrees(np.arccos(min(1.0, abs(t @ n) / np.linalg.norm(t)))) <= 0.5
    assert len(r.network.groups) == 2 * drawn + 1
    assert r.network.meta["lifting"]["symmetry_plane"]["normal"] == n.tolist()


def test_the_global_symmetry_cues_are_applied_within_half_a_degree(barrel):
    _, _, r = barrel
    glob = [c for c in r.cues if c.where.endswith("(global symmetry)")]
    corners = [c for c in r.cues if c.kind == "orthogonal" and "x symmetry" in c.where]
    assert len(glob) == 5 and len(corners) == 5
    assert all(c.applied and c.angle <= 0.5 for c in glob + corners)
    assert [c.applied for c in r.cues if c.where == "symmetry planar"] == [True]


def test_the_plane_and_depths_against_the_truth(barrel):
    # measured 2026-12-03: plane 3.4 deg off the truth's, depth RMSE 5.6 % of the diagonal over both halves
    # (the drawn half alone 6.0 %; without the symmetry annotation 7.0 %): asserted with some room
    tr, _, r = barrel
    n_true = T.rotation(25.0, 35.0)[:, 0]
    assert np.degrees(np.arccos(min(1.0, abs(r.mirror[1] @ n_true)))) <= 4.0
    err, sign = T.depth_rmse(tr, r)
    assert sign == 1 and err <= 0.06


def test_a_drawn_stroke_on_the_symmetry_curve_serves_as_it(barrel):
    _, _, r = barrel
    tr2, _ = T.barrel_half(symmetry_drawn=True)
    r2 = lift(tr2.sketch)
    assert len(r2.graphs[0].strokes) == len(r.graphs[0].strokes)       # not added twice
    assert np.allclose(r2.mirror[1], r.mirror[1], atol=1e-9) and abs(r2.mirror[2] - r.mirror[2]) < 1e-9


def test_a_symmetry_curve_that_meets_no_stroke_is_refused():
    h = Stroke(np.array([[[-1, 0], [-0.4, 0.25], [0.4, 0.25], [1, 0]]], float), "h")
    v = Stroke(np.array([[[0.3, -1], [0.1, -0.3], [-0.1, 0.3], [-0.3, 1]]], float), "v")
    far = Stroke(np.array([[[5, -1], [5, -0.3], [5, 0.3], [5, 1]]], float), "axis")
    with pytest.raises(GeometryError, match="symmetry path axis: meets no stroke of layer 0"):
        layer_graphs(Sketch((h, v), symmetry=far))
    with pytest.raises(GeometryError, match="symmetry path axis: its layer 1 has no strokes"):
        layer_graphs(Sketch((h, v), symmetry=Stroke(far.controls, "axis", 1)))


NS = 'xmlns="http://www.w3.org/2000/svg" xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape"'
CROSS = '<path id="h{k}" d="M {x0} 50 C {x1} 40 {x2} 40 {x3} 50"/><path id="v{k}" d="M {a} 0 C {b} 30 {b} 70 {c} 100"/>'


def _cross(k: int, dx: float) -> str:
    return CROSS.format(k=k, x0=dx, x1=dx + 30, x2=dx + 70, x3=dx + 100, a=dx + 45, b=dx + 50, c=dx + 55)


def test_the_symmetry_path_joins_its_layer_or_the_layer_it_overlaps():
    layers = (f'<g inkscape:groupmode="layer" id="A">{_cross(1, 0)}</g>'
              f'<g inkscape:groupmode="layer" id="B">{_cross(2, 300)}{{inB}}</g>'
              f'<g inkscape:groupmode="layer" id="notes">{{inNotes}}</g>')
    axis = '<path class="symmetry" id="axis" d="M 350 -5 C 340 30 340 70 350 105"/>'

    def read(body: str) -> Sketch:
        return read_sketch_svg(f'<svg {NS} viewBox="0 0 400 100">{body}</svg>', "s.svg")

    assert read(layers.format(inB=axis, inNotes="")).symmetry.layer == 1          # its own layer
    assert read(layers.format(inB="", inNotes=axis)).symmetry.layer == 1          # an annotation layer: overlap
    assert read(layers.format(inB="", inNotes="") + axis).symmetry.layer == 1     # outside every layer: overlap
    lone = '<path class="symmetry" id="axis" d="M 1350 -5 L 1350 105"/>'
    with pytest.raises(FormatError, match="axis: the symmetry path overlaps no layer's strokes"):
        read(layers.format(inB="", inNotes=lone))


def test_sketch_json_keeps_the_symmetry_curves_layer():
    tr, _ = T.barrel_half()
    s = tr.sketch
    s = Sketch(tuple(Stroke(t.controls, t.id, 1) for t in s.strokes), s.markers,
               Stroke(s.symmetry.controls, "axis", 1), "barrel")
    back = loads(dumps(s), "b.sketch.json")
    assert back.symmetry is not None and (back.symmetry.id, back.symmetry.layer) == ("axis", 1)
    assert np.array_equal(back.symmetry.controls, s.symmetry.controls) and dumps(back) == dumps(s)


def test_the_bundled_half_barrel_is_mirrored_across_the_truths_plane():
    """examples/sketches/barrel-half.svg (tests/lifting/make_sketches.py, the truth above as an Inkscape file,
    coordinates rounded to 0.01 px, the symmetry curve in the annotations layer): measured 3.4 deg."""
    from auszug import examples
    from auszug.formats import load

    sketch = load(examples.path("sketches/barrel-half.svg"), kind="sketch")
    assert sketch.symmetry is not None and sketch.symmetry.layer == 0 and len(sketch.strokes) == 7
    r = lift(sketch)
    assert r.converged and r.mirror is not None and len(r.network.groups) == 15
    n_true = T.rotation(25.0, 35.0)[:, 0]
    assert np.degrees(np.arccos(min(1.0, abs(r.mirror[1] @ n_true)))) <= 4.0



def test_the_plane_follows_its_layer_when_the_layers_are_stacked(barrel, monkeypatch):
    """Stacking shifts a layer's depth after the mirror (a layer in front of another where they overlap):
    the reported plane must still hold the symmetry curve. The shift is forced here (stacking proper is
    tested with the layers)."""
    from auszug.lifting import reconstruct

    tr, _, r = barrel

    def shifted(graphs, pts):
        for X in pts:
            X[:, 2] += 0.37
    monkeypatch.setattr(reconstruct, "_stack", shifted)
    r2 = lift(tr.sketch)
    layer, n, d = r2.mirror
    g, X = r2.graphs[0], r2.points[0]
    on = np.unique(g.segments[g.chains[len(tr.sketch.strokes)]])
    assert np.allclose(X[:, 2], r.points[0][:, 2] + 0.37)
    assert np.abs(X[on] @ n - d).max() <= 1e-7 * tr.diagonal()
    assert abs(d - r.mirror[2] - 0.37 * n[2]) <= 1e-9 * tr.diagonal()
