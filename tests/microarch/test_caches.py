"""The engine's caches (pair intersections, whole results, per-curve pieces) never change a result."""

from __future__ import annotations

import numpy as np
import pytest

from auszug import examples
from auszug.formats import load
from auszug.microarch import build, edit, network, prc

NAMES = ["web/U.XI.28.uc", "web/3d-scan-final.uc", "legacy/U.XI.22.uc", "web/U.XI.91.uc"]


def _cold() -> None:
    prc._PAIRS.data.clear()
    prc._BLOCKS.data.clear()
    prc._RESULTS.data.clear()
    prc._CHOICES.data.clear()
    network._CURVE_PIECES.data.clear()


def _key(x: prc.TopIntersection) -> tuple:
    return (x.curve, x.segment, x.other_curve, x.other_segment, x.replica, x.u, x.u_other,
            tuple(x.point.tolist()), x.same_family, x.true)


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("layer_only", [False, True])
def test_intersections_cold_warm_and_after_an_edit(name, layer_only):
    d = load(examples.path(name))
    moved = edit.move_vertex(d, 0, 0, tuple(np.add(d.curves[0].vertices[0], (1e-3, -2e-3))))
    _cold()
    cold = [_key(x) for x in prc.intersections(moved, layer_only)]
    _cold()
    prc.intersections(d, layer_only)                     # warm the pairs the edit does not touch
    warm = [_key(x) for x in prc.intersections(moved, layer_only)]
    again = [_key(x) for x in prc.intersections(moved, layer_only)]   # the whole-result cache
    assert cold == warm == again and cold


def test_one_layer_layer_only_is_the_same_result():
    d = load(examples.path("web/U.XI.28.uc"))
    assert len({c.layer for c in d.curves}) == 1
    assert [_key(x) for x in prc.intersections(d, True)] == [_key(x) for x in prc.intersections(d, False)]


@pytest.mark.parametrize("name", NAMES)
def test_build_with_cached_curves_equals_a_cold_build(name):
    d = load(examples.path(name))
    h = d.apex_height(1)
    edited = edit.set_apex_height(d, 1, h * 1.01)
    _cold()
    cold = build(edited)
    _cold()
    build(d)
    warm = build(edited)
    assert len(cold.pieces) == len(warm.pieces)
    for a, b in zip(cold.pieces, warm.pieces, strict=True):
        assert (a.basic, a.segment, a.kind) == (b.basic, b.segment, b.kind)
        np.testing.assert_array_equal(a.points, b.points)
    shared = [p for p in warm.pieces if p.basic != 1 and p.kind not in ("pillar",)]
    assert shared and all(p in build(d).pieces for p in shared)   # unchanged curves' pieces are reused
    assert not shared[0].points.flags.writeable                       # and read-only


def test_cached_pieces_follow_the_tolerances():
    from auszug.geometry import tolerances

    d = load(examples.path("teaching-sheet/tn-2.uc"))
    n0 = len(build(d).pieces[0].points)
    with tolerances(samples=11):
        assert len(build(d).pieces[0].points) == 11
    assert len(build(d).pieces[0].points) == n0


@pytest.mark.parametrize("name", ["legacy/U.XI.29.uc", "legacy/U.XI.34.uc", "legacy/U.XI.20.uc", "web/two_curves.uc",
                                  "web/3d-scan-final.uc"])
def test_pairs_derived_the_other_way_round_equal_computed_ones(name, monkeypatch):
    """A pair taken from its mirror pair (replica k of i against j = image of i against k^-1 of j)
    has the records the kernel computes directly, to rounding."""
    d = load(examples.path(name))
    moved = edit.move_vertex(d, 0, len(d.curves[0].vertices) - 1,
                             tuple(np.add(d.curves[0].vertices[-1], (1e-3, -2e-3))))
    _cold()
    derived = prc.intersections(moved)
    _cold()
    monkeypatch.setattr(prc, "_inverses", lambda sym_j, sym_i: (-1,) * len(sym_j.matrices()))
    direct = prc.intersections(moved)
    _cold()
    assert len(derived) == len(direct) > 0
    for a, b in zip(derived, direct, strict=True):
        assert (a.curve, a.segment, a.other_curve, a.other_segment, a.replica, a.same_family, a.true) == (
            b.curve, b.segment, b.other_curve, b.other_segment, b.replica, b.same_family, b.true)
        assert abs(a.u - b.u) <= 1e-12 and abs(a.u_other - b.u_other) <= 1e-12
        assert np.abs(a.point - b.point).max() <= 1e-12


def test_a_rigid_replica_shares_the_arc_length_table():
    from auszug.geometry import CubicBezier

    b = CubicBezier((0, -1), (0.1, -1.1), (0.9, -1.0), (1.1, -0.6))
    c, s = np.cos(0.7), np.sin(0.7)
    rot = b.transformed([[c, -s], [s, c]], (0.3, 0.2))
    fresh = CubicBezier(*rot.controls)   # the same curve, its table computed on its own
    t = np.linspace(0, 1, 11)
    assert rot._table is b._table and fresh._table is not b._table
    assert np.abs(rot.u_at_t(t) - fresh.u_at_t(t)).max() <= 1e-14
    assert "_arc_source" not in b.transformed([[2, 0], [0, 1]]).__dict__   # not rigid: its own table


@pytest.mark.parametrize(("n_j", "n_i", "axis_i"),
                         [(1024, 1024, (0.0, 1.0)), (512, 1024, (1.0, 0.0)), (3, 5, (0.0, 1.0))])
def test_inverse_replicas_of_large_groups_by_key_equal_every_product(n_j, n_i, axis_i):
    """The keyed lookup of large groups (fold 1024 with a mirror: 2048 maps) finds, for every map
    of one group, the one map of the other that is its inverse: the same answer as checking every
    product, as the small groups' path does (a quadratic loop there built fold 1019 in 33 s)."""
    from auszug.geometry import SymmetryGroup

    gj, gi = SymmetryGroup(n_j, True), SymmetryGroup(n_i, True, axis=axis_i)
    got = prc._inverse_indices(gj.matrices().tobytes(), gi.matrices().tobytes())
    mj, mi = gj.matrices(), gi.matrices()
    want = []
    for mk in mj:
        hit = np.flatnonzero(np.abs(mk @ mi - np.eye(2)).max(axis=(1, 2)) <= 1e-12)
        want.append(int(hit[0]) if len(hit) == 1 else -1)
    assert list(got) == want
    assert sum(w >= 0 for w in want) == (min(n_j, n_i) * 2 if n_i % n_j == 0 or n_j % n_i == 0 else 2)
