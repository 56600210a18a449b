"""``LiftParams.close_gaps``: stroke ends drawn short of, past or beside where they meet, joined.

Known answers first (a T-junction drawn short and drawn past, a corner drawn short on both strokes, a
loop left open, the box and turret truths with every joined end moved along its tangent), then the
refusals (an occlusion marker, a gap wider than the tolerance, the limit), then random sketches.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from auszug.errors import GeometryError
from auszug.geometry import CubicBezier
from auszug.lifting import LiftParams, layer_graphs, lift
from auszug.lifting.params import CLOSE_GAPS_MAX
from auszug.lifting.sketch import Marker, Sketch, Stroke, sketch_graph
from tests.lifting import truth as T
from tests.lifting.test_fit import _distances
from tests.lifting.test_sketch_graph_properties import _samples, strokes

#: A curved crossbar and a straight stroke through it: the sketch lifts without the strokes below.
BAR = np.array([[[-1.0, 0.0], [-0.3, 0.3], [0.3, 0.3], [1.0, 0.0]]])
POST = np.array([[[-0.6, -0.8], [-0.6, -0.2], [-0.6, 0.4], [-0.6, 1.0]]])


def _line(a, b) -> np.ndarray:
    a, b = np.asarray(a, float), np.asarray(b, float)
    return np.array([[a, a + (b - a) / 3, a + 2 * (b - a) / 3, b]])


def _bar_at(x: float) -> np.ndarray:
    """The point of BAR with abscissa x (BAR's x is monotone in t)."""
    b = CubicBezier.from_array(BAR[0])
    lo, hi = 0.0, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if b.point(mid)[0] < x else (lo, mid)
    return b.point(0.5 * (lo + hi))


def _sketch(*extra: np.ndarray, markers=()) -> Sketch:
    return Sketch((Stroke(BAR, "bar"), Stroke(POST, "post"),
                   *(Stroke(c, f"s{i}") for i, c in enumerate(extra))), tuple(markers))


def _world(g, i: int) -> np.ndarray:
    return g.points[i] * g.scale + g.offset


def _end_point(g, stroke: int, end: int) -> np.ndarray:
    seg = g.segments[g.chains[stroke]]
    return _world(g, seg[0, 0] if end == 0 else seg[-1, 3])


def test_a_stroke_drawn_short_of_another_is_extended_along_its_direction_onto_it():
    hit = _bar_at(0.4)
    short = _line((0.4, 1.2), (0.4, hit[1] + 0.004))            # a straight stroke stopping short of the bar
    sk = _sketch(short)
    with pytest.raises(GeometryError, match="s0: not joined to the rest of layer 0"):
        layer_graphs(sk)
    g = sketch_graph(sk, LiftParams(close_gaps=0.005))
    d = sk.diagonal()
    (gap,) = g.gaps
    assert (gap.stroke, gap.end, gap.kind, gap.to) == (2, 1, "extend", 0)
    assert abs(gap.distance - 0.004 / d) < 1e-9
    end = _end_point(g, 2, 1)
    assert np.linalg.norm(end - hit) < 1e-9 * d                   # on the bar, where the stroke's line meets it
    pieces = g.points[g.segments[g.chains[2]]] * g.scale + g.offset
    assert np.abs(pieces[..., 0] - 0.4).max() < 1e-12            # and the stroke still on its own line
    (x,) = [c for c in g.crossings if 2 in c.strokes]
    assert sorted(x.strokes) == [0, 0, 2] and not x.smooth       # a T-junction: the bar's two halves and the end


def test_a_stroke_drawn_past_another_is_cut_at_the_crossing():
    hit = _bar_at(0.4)
    past = _line((0.4, 1.2), (0.4, hit[1] - 0.003))
    sk = _sketch(past)
    plain = sketch_graph(sk)
    assert len(plain.chains[2]) == 2                              # the stub beyond the bar is a piece of its own
    g = sketch_graph(sk, LiftParams(close_gaps=0.005))
    (gap,) = g.gaps
    assert (gap.stroke, gap.end, gap.kind, gap.to) == (2, 1, "trim", 0)
    assert abs(gap.distance - 0.003 / sk.diagonal()) < 1e-9
    assert len(g.chains[2]) == 1 and np.linalg.norm(_end_point(g, 2, 1) - hit) < 1e-9 * sk.diagonal()


def test_a_corner_drawn_short_on_both_strokes_meets_where_their_lines_cross():
    a = _line((0.2, 1.2), (0.2, 0.6 + 0.003))                     # both end short of the corner (0.2, 0.6)
    b = _line((0.9, 0.9), (0.2 + 0.002, 0.6 + 0.002 * 3 / 7))     # a sloped stroke toward it
    sk = _sketch(a, b, _line((0.1, 0.95), (0.95, 0.7)))           # and a stroke crossing both, so they lift
    g = sketch_graph(sk, LiftParams(close_gaps=0.005))
    kinds = sorted((gp.stroke, gp.end, gp.kind) for gp in g.gaps)
    assert kinds == [(2, 1, "end"), (3, 1, "end")]
    assert np.linalg.norm(_end_point(g, 2, 1) - (0.2, 0.6)) < 1e-12
    assert np.linalg.norm(_end_point(g, 3, 1) - (0.2, 0.6)) < 1e-12
    assert any(sorted(set(c.strokes)) == [2, 3] for c in g.crossings)


def test_a_joint_drawn_exactly_stays_and_a_near_end_comes_to_it():
    hit = _bar_at(0.4)
    exact = _line((0.4, 1.2), hit)                                # drawn onto the bar
    near = _line((0.9, 1.1), hit + (0.002, 0.001))                # a stroke ending 0.2 % of the diagonal beside it
    sk = _sketch(exact, near)
    g = sketch_graph(sk, LiftParams(close_gaps=0.005))
    assert [(gp.stroke, gp.end, gp.kind, gp.to) for gp in g.gaps] == [(3, 1, "extend", 0)]
    assert np.array_equal(_end_point(g, 2, 1), _end_point(g, 3, 1))
    assert np.linalg.norm(_end_point(g, 2, 1) - hit) < 1e-12      # where it was drawn
    (x,) = [c for c in g.crossings if 3 in c.strokes]
    assert sorted(x.strokes) == [0, 0, 2, 3]


def test_a_loop_left_open_is_closed():
    t = np.linspace(0.0, 2 * np.pi, 5)
    r = 0.3
    ring = []
    for t0, t1 in zip(t[:-1], t[1:], strict=True):                # a circle of four cubics around (0.3, -0.3)
        k = 4 / 3 * np.tan((t1 - t0) / 4)
        p0, p3 = np.array([np.cos(t0), np.sin(t0)]), np.array([np.cos(t1), np.sin(t1)])
        d0, d3 = np.array([-np.sin(t0), np.cos(t0)]), np.array([-np.sin(t1), np.cos(t1)])
        ring.append(np.array([p0, p0 + k * d0, p3 - k * d3, p3]) * r + (0.3, -0.3))
    ring = np.array(ring)
    ring[-1, 2:] += (0.0, -0.004)                                  # its end drawn 0.004 below its start
    cross = _line((-0.2, -0.22), (0.8, -0.22))                     # through the ring and the post
    sk = _sketch(ring, cross)
    assert not sketch_graph(sk).closed[2]
    g = sketch_graph(sk, LiftParams(close_gaps=0.005))
    # the ends' tangents continue each other (no corner), so both move halfway: to their mean
    assert sorted((gp.stroke, gp.end, gp.kind) for gp in g.gaps) == [(2, 0, "close"), (2, 1, "close")]
    assert all(abs(gp.distance - 0.002 / sk.diagonal()) < 1e-12 for gp in g.gaps) and g.closed[2]
    assert np.linalg.norm(_end_point(g, 2, 0) - (0.6, -0.302)) < 1e-12


@pytest.mark.parametrize("name", ["box", "turret"])
def test_every_joined_end_moved_along_its_tangent_is_put_back(name):
    """Each end of the truth's sketch at a crossing is drawn 0.2 % of the diagonal short or long along its
    tangent (seeded): without closing, the graph falls apart; with ``close_gaps = 0.5 %`` it is the clean
    sketch's graph again, its crossings the same and every piece's ends where they were (1e-12)."""
    tr = T.box() if name == "box" else T.make(name)
    sk = tr.sketch
    g0 = sketch_graph(sk)
    d = sk.diagonal()
    at_crossing = g0.points[[c.point for c in g0.crossings]] * g0.scale + g0.offset
    rng = np.random.default_rng(1)
    moved, n = [], 0
    for s in sk.strokes:
        c = s.controls.copy()
        for end in (0, 1):
            p = c[0, 0] if end == 0 else c[-1, 3]
            if np.linalg.norm(at_crossing - p, axis=1).min() > 1e-6 * d:
                continue                                            # a free end stays
            u = c[0, 0] - c[0, 1] if end == 0 else c[-1, 3] - c[-1, 2]
            step = u / np.linalg.norm(u) * 0.002 * d * rng.choice([-1.0, 1.0])
            if end == 0:
                c[0, :2] += step
            else:
                c[-1, 2:] += step
            n += 1
        moved.append(Stroke(c, s.id))
    assert n == {"box": 18, "turret": 22}[name]
    sk2 = Sketch(tuple(moved), sk.markers)

    def crossings(g):
        return sorted((tuple(sorted(c.strokes)), c.smooth) for c in g.crossings)

    try:
        assert crossings(sketch_graph(sk2)) != crossings(g0)
    except GeometryError:
        pass
    g = sketch_graph(sk2, LiftParams(close_gaps=0.005))
    assert crossings(g) == crossings(g0)
    assert [len(c) for c in g.chains] == [len(c) for c in g0.chains]
    ends = g.segments[:, [0, 3]]
    assert np.abs(_world(g, ends) - _world(g0, g0.segments[:, [0, 3]])).max() < 1e-12 * d
    assert all(gp.distance <= 0.005 for gp in g.gaps) and {gp.kind for gp in g.gaps} <= {"trim", "end"}
    if name == "box":                   # the box lifts within 2e-5 of the diagonal, drawn clean or closed
        clean = T.depth_rmse(tr, lift(sk))[0]
        closed = T.depth_rmse(T.Truth(sk2, tr.chains3d), lift(sk2, params=LiftParams(close_gaps=0.005)))[0]
        assert clean < 2e-5 and abs(closed - clean) < 1e-7


def test_an_end_past_a_crossing_marked_as_an_occlusion_is_left_as_drawn():
    hit = _bar_at(0.4)
    start = np.array([-0.9, 0.7])                                  # crosses the post, then the bar near its end
    u = (hit - start) / np.linalg.norm(hit - start)
    past = _line(start, hit + 0.003 * u)
    g = sketch_graph(_sketch(past), LiftParams(close_gaps=0.005))
    assert [(gp.stroke, gp.end, gp.kind, gp.to) for gp in g.gaps] == [(2, 1, "trim", 0)]
    g = sketch_graph(_sketch(past, markers=[Marker("occlusion", hit, "behind")]), LiftParams(close_gaps=0.005))
    assert g.gaps == () and len(g.occluded) == 1
    assert len(g.chains[2]) == 2                                  # cut at the post only: it passes behind the bar
    assert np.linalg.norm(_end_point(g, 2, 1) - past[0, 3]) < 1e-12


def test_a_wider_gap_is_left_and_the_error_says_what_would_close_it():
    hit = _bar_at(0.4)
    sk = _sketch(_line((0.4, 1.2), (0.4, hit[1] + 0.004)))
    d = 0.004 / sk.diagonal()
    with pytest.raises(GeometryError) as err:
        layer_graphs(sk, LiftParams(close_gaps=0.001))
    msg = str(err.value)
    assert f"an end of s0 misses bar by {d:.2%} of the diagonal" in msg
    want = float(msg.split("close_gaps=")[1].split(" ")[0])
    assert d < want <= 1.02 * d + 1e-4
    (_, g), = layer_graphs(sk, LiftParams(close_gaps=want))       # the value it names joins it
    assert [gp.kind for gp in g.gaps] == ["extend"]
    with pytest.raises(GeometryError) as err:                    # a gap beyond the limit: no such hint
        layer_graphs(_sketch(_line((0.4, 1.2), (0.4, hit[1] + 0.2))))
    assert "close_gaps" not in str(err.value)


def test_the_limit():
    assert LiftParams(close_gaps=CLOSE_GAPS_MAX).close_gaps == 0.05
    with pytest.raises(GeometryError, match=r"close_gaps must be at most 0.05 \(5 % of the diagonal\), got 0.06"):
        LiftParams(close_gaps=0.06)


@settings(max_examples=120, deadline=None)
@given(strokes(), st.sampled_from([0.005, 0.02, 0.05]))
def test_random_sketches_closed_stay_on_their_strokes_and_every_closed_end_is_joined(cs, tol):
    """Every piece lies within the tolerance of its drawn stroke (ends move at most that far, cuts only cut),
    no piece is point-sized, and every end a gap record names is at a crossing of the graph (or closes
    its stroke)."""
    sk = Sketch(tuple(Stroke(c, f"s{i}") for i, c in enumerate(cs)))
    try:
        g = sketch_graph(sk, LiftParams(close_gaps=tol))
    except GeometryError:
        return          # a documented refusal (no crossing, zero-length or duplicate stroke, ...)
    P = g.points[g.segments]
    assert np.ptp(P, axis=1).max(1).min() > 1e-7
    assert all(gp.distance <= tol for gp in g.gaps)
    at = {c.point for c in g.crossings}
    for si, ch in enumerate(g.chains):
        seg = g.segments[ch]
        assert np.all(seg[1:, 0] == seg[:-1, 3])
        drawn = (np.asarray(cs[si], float) - g.offset) / g.scale
        drawn = np.array([s for s in drawn if np.ptp(s, axis=0).max() > 1e-7])
        retracted = bool(np.any(np.linalg.norm(drawn[:, 1] - drawn[:, 0], axis=1) <= 1e-7)
                         or np.any(np.linalg.norm(drawn[:, 2] - drawn[:, 3], axis=1) <= 1e-7))
        # a retracted handle is given a length (sketch._fix_handles), which moves the curve a little more
        allow = tol + 1e-5 + (4 / 27 * 0.01 * float(np.ptp(drawn.reshape(-1, 2), axis=0).max()) if retracted else 0)
        assert _distances(drawn, _samples(g.points[seg], 9)).max() <= allow
        for gp in g.gaps:
            if gp.stroke == si:
                assert (seg[0, 0] if gp.end == 0 else seg[-1, 3]) in at or g.closed[si]
