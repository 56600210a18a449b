"""Loops of the 3D network: found on the corpus, closed and simple, on the curves, rims, explicit lists."""

from __future__ import annotations

import numpy as np
import pytest

from auszug.errors import GeometryError
from auszug.meshing.loops import find_loops, loop_through, network_graph
from auszug.microarch import build
from tests.meshing.cases import arch, network, star


def _dense(net, n=4097):
    return np.concatenate([net.replicate(p).reshape(-1, 3) for p in build(net.drawing, samples=n).pieces
                           if p.kind in ("ogee", "free_end", "level")])


def test_arch_on_the_ground_is_closed_by_a_level_rim():
    loops = find_loops(build(arch()))
    assert len(loops) == 1
    lp = loops[0]
    assert lp.has_rim and len(lp.halfedges) == 3
    rim = [lp.graph.edges[e] for e, _ in lp.halfedges if lp.graph.edges[e].rim][0]
    a, b = lp.graph.nodes[rim.a], lp.graph.nodes[rim.b]
    assert a[2] == b[2] == 0.0 and sorted([a[0], b[0]]) == [-1.0, 1.0]
    assert find_loops(build(arch()), rims=False) == []


def test_a_ring_around_the_axis_bounds_no_face():
    """Four arches round the centre: a closed ring, but it winds round the vertical axis."""
    assert find_loops(build(star())) == []


def test_a_drawing_without_loops_has_none():
    assert find_loops(network("web/U.XI.29.uc")) == []


@pytest.mark.parametrize("name, count", [
    ("teaching-sheet/tn-1.uc", 8), ("web/U.XI.28.uc", 8), ("web/U.XI.91.uc", 16), ("web/u.xi.112.uc", 6),
    ("web/3d-scan-final.uc", 42),
])
def test_loops_of_drawings_the_demo_cannot_fill(name, count):
    net = network(name)
    loops = find_loops(net)
    assert len(loops) == count
    dense = _dense(net)
    from scipy.spatial import cKDTree

    tree = cKDTree(dense)
    for lp in loops:
        b, corners = lp.boundary(96)
        heads = [lp.graph.edges[e].b if fw else lp.graph.edges[e].a for e, fw in lp.halfedges]
        tails = [lp.graph.edges[e].a if fw else lp.graph.edges[e].b for e, fw in lp.halfedges]
        assert heads == tails[1:] + tails[:1]                # closed, head to tail
        assert len(set(tails)) == len(tails)                 # simple
        if not lp.has_rim:
            d, _ = tree.query(b)
            assert d.max() < 2e-3 * lp.graph.size            # on the curves (dense samples)


def test_boundary_points_are_exactly_on_their_strands():
    net = network("web/U.XI.28.uc")
    lp = find_loops(net)[0]
    g = lp.graph
    for e, _ in lp.halfedges:
        ed = g.edges[e]
        st = g.strands[ed.strand]
        pts = g.edge_points(e, 9)
        u = ed.u0 + np.linspace(0, 1, 9) * (ed.u1 - ed.u0)
        piece = net.pieces[st.piece]
        basic = piece.point3(u)
        xy = (basic[:, :2] - st.center) @ st.matrix.T + st.center
        assert np.array_equal(pts[:, :2], xy) and np.array_equal(pts[:, 2], basic[:, 2])


def test_explicit_vertex_list_gives_the_same_loop():
    net = network("teaching-sheet/tn-1.uc")
    g = network_graph(net)
    auto = find_loops(g)[0]
    nodes = auto.nodes
    again = loop_through(g, nodes)
    assert again.key() == auto.key()
    by_points = loop_through(g, g.nodes[nodes])
    assert by_points.key() == auto.key()


def test_explicit_vertex_list_errors():
    g = network_graph(network("teaching-sheet/tn-1.uc"))
    with pytest.raises(GeometryError, match="at least 2 nodes"):
        loop_through(g, [3])
    with pytest.raises(GeometryError, match="node indices must lie in"):
        loop_through(g, [0, 999])
    with pytest.raises(GeometryError, match="is no node of the network"):
        loop_through(g, [[5.0, 5.0, 5.0], [0.0, 0.0, 0.0]])


def test_meeting_tolerance_is_relative_to_the_drawing():
    tight = network_graph(network("web/U.XI.91.uc"), meet_tol=1e-9)
    loose = network_graph(network("web/U.XI.91.uc"), meet_tol=1e-2)
    assert len(loose.nodes) > len(tight.nodes) - 0 and len(loose.edges) > len(tight.edges)
