"""Closed loops of a 3D curve network: the boundaries that faces fill.

:func:`network_graph` turns a network into a graph whose nodes are the curves'
end points and their true meeting points (top-view intersections where both
3D curves have the same height), merged within a tolerance, and whose edges
are the stretches of curve between consecutive nodes. Every curve of every
replica takes part (ogees, free ends, level segments; posts and pillars are
vertical and bound nothing).

:func:`find_loops` finds the faces of that graph from the planar embedding of
its top view: at every node the edges are ordered by the angle at which they
leave it in the top view, and each face is traced by turning as far
clockwise as possible at every node. The bounded faces (counter-clockwise in
the top view) are the loops. Curves that pass over or under each other in
3D (false crossings in the top view) are no nodes, so a loop may enclose the
top view of another curve.

Open rims: a chain of curves whose two loose ends (nodes of degree one) are
at the same height is closed by a straight, level *rim* edge between them, if
that line crosses no curve in the top view; loops then include it (the
space under an arch whose feet stand on the ground, for instance).

:func:`loop_through` builds a loop from an explicit list of nodes or points.

A drawing without loops simply gives none.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from auszug.errors import GeometryError
from auszug.geometry import Curve
from auszug.geometry.network import CurveNetwork, Piece, as_curve_network
from auszug.meshing._work import check_curves

__all__ = ["Strand", "GraphEdge", "NetworkGraph", "Loop", "network_graph", "find_loops", "loop_through"]

Array = NDArray[np.float64]
#: Pieces that take part in loops.
LOOP_KINDS = ("ogee", "free_end", "level")


@dataclass(frozen=True, eq=False)
class Strand:
    """One network curve: a basic piece under one element of its symmetry group.

    Attributes
    ----------
    piece : int
        Index into :attr:`CurveNetwork.pieces` (-1 for a rim).
    element : int
        Index into the group's matrices.
    label : str
        Replica label (``r1m``...).
    matrix : (2, 2) ndarray
    center : (2,) ndarray
    top : Curve
        The replica's top view (same parameter as the basic piece's).
    layer : int
    """

    piece: int
    element: int
    label: str
    matrix: Array
    center: Array
    top: Curve
    layer: int
    _piece: Piece | None = field(repr=False, default=None)

    def points(self, u: ArrayLike) -> Array:
        """3D points at normalised top-view arc length u of the basic piece, shape (..., 3)."""
        assert self._piece is not None  # network_graph gives every strand its piece
        p = self._piece.point3(np.asarray(u, dtype=float))
        out = np.array(p, dtype=float)
        out[..., :2] = (p[..., :2] - self.center) @ self.matrix.T + self.center
        return out

    def top_tangent(self, u: float) -> Array:
        """Unit top-view tangent at u, shape (2,)."""
        return self.top.tangent(float(self.top.t_at_u(u)))


@dataclass(frozen=True)
class GraphEdge:
    """A stretch of a strand between two nodes (or a straight rim).

    Attributes
    ----------
    strand : int
        Index into :attr:`NetworkGraph.strands`; -1 for a rim.
    u0, u1 : float
        Parameter range on the strand (u0 < u1), from node ``a`` to node ``b``.
    a, b : int
        End nodes.
    """

    strand: int
    u0: float
    u1: float
    a: int
    b: int

    @property
    def rim(self) -> bool:
        """Whether the edge is a straight rim closing an open chain."""
        return self.strand < 0


@dataclass(frozen=True, eq=False)
class NetworkGraph:
    """Nodes and edges of a network's curves (see the module docstring).

    Attributes
    ----------
    nodes : (k, 3) ndarray
    edges : tuple of GraphEdge
    strands : tuple of Strand
    size : float
        Size of the drawing (for tolerances).
    tol : float
        Distance within which points are one node.
    meet_tol : float
        Height difference within which crossing curves meet (absolute).
    """

    nodes: Array
    edges: tuple[GraphEdge, ...]
    strands: tuple[Strand, ...]
    size: float
    tol: float
    meet_tol: float = 0.0

    def edge_points(self, e: int, n: int, reverse: bool = False) -> Array:
        """``n`` points along edge ``e`` (exactly on its curve), from a to b, shape (n, 3)."""
        ed = self.edges[e]
        s = np.linspace(0.0, 1.0, n)
        if ed.rim:
            p = self.nodes[ed.a] + s[:, None] * (self.nodes[ed.b] - self.nodes[ed.a])
        else:
            # exactly on the curve, also at the ends (a node where curves meet within the
            # height tolerance is their mean, which lies on neither)
            p = self.strands[ed.strand].points(ed.u0 + s * (ed.u1 - ed.u0))
        return p[::-1] if reverse else p

    @cached_property
    def edge_lengths(self) -> Array:
        """3D length of every edge, shape (m,)."""
        return np.array([float(np.linalg.norm(np.diff(self.edge_points(i, 33), axis=0), axis=1).sum())
                         for i in range(len(self.edges))])

    def degree(self) -> NDArray[np.int64]:
        """Edges at each node (a loop edge counts twice)."""
        d = np.zeros(len(self.nodes), dtype=np.int64)
        for e in self.edges:
            d[e.a] += 1
            d[e.b] += 1
        return d

    def leaving(self, e: int, at_a: bool) -> tuple[float, float]:
        """Angle in the cylinder chart at which edge ``e`` leaves node a (or b), and a tie-breaker.

        The chart at a node is the vertical plane tangent to the cylinder about
        the vertical axis through it: (horizontal direction of increasing polar
        angle, up). The angle is that of the chord to a point a little along
        the edge (vertical end tangents are told apart by how the curves bend
        away); the tie-breaker uses a point further along.
        """
        ed = self.edges[e]
        p0 = self.nodes[ed.a if at_a else ed.b]
        e1, e2 = _chart_basis(p0, self.centre)
        if ed.rim:
            d = self.nodes[ed.b] - self.nodes[ed.a]
            d = d if at_a else -d
            a = math.atan2(float(d @ e2), float(d @ e1))
            return a, a
        st = self.strands[ed.strand]
        du = ed.u1 - ed.u0
        fr = np.array([1e-4, 0.05])
        u = ed.u0 + fr * du if at_a else ed.u1 - fr * du
        q = st.points(u) - p0
        a0 = math.atan2(float(q[0] @ e2), float(q[0] @ e1))
        a1 = math.atan2(float(q[1] @ e2), float(q[1] @ e1))
        return a0, a1

    @cached_property
    def centre(self) -> Array:
        """The vertical axis of the chart (the symmetry centre), shape (2,)."""
        cs = [s.center for s in self.strands]
        return np.asarray(cs[0], dtype=float) if cs else np.zeros(2)


def _chart_basis(p: Array, centre: Array) -> tuple[Array, Array]:
    """(increasing polar angle, up) at ``p``; the x axis stands in for the angle at the axis."""
    r = np.array([p[0] - centre[0], p[1] - centre[1], 0.0])
    n = float(np.linalg.norm(r))
    e1 = np.array([-r[1], r[0], 0.0]) / n if n > 1e-12 else np.array([1.0, 0.0, 0.0])
    return e1, np.array([0.0, 0.0, 1.0])


@dataclass(frozen=True, eq=False)
class Loop:
    """A closed loop of the graph: half-edges (edge, forward) head to tail.

    Attributes
    ----------
    graph : NetworkGraph
    halfedges : tuple of (int, bool)
        ``(edge, True)`` runs the edge from a to b.
    """

    graph: NetworkGraph
    halfedges: tuple[tuple[int, bool], ...]

    @property
    def nodes(self) -> list[int]:
        """Nodes in loop order (each once)."""
        g = self.graph
        return [g.edges[e].a if fw else g.edges[e].b for e, fw in self.halfedges]

    @property
    def length(self) -> float:
        """3D length."""
        return float(sum(self.graph.edge_lengths[e] for e, _ in self.halfedges))

    @property
    def has_rim(self) -> bool:
        """Whether a rim edge closes it."""
        return any(self.graph.edges[e].rim for e, _ in self.halfedges)

    def boundary(self, n: int = 160) -> tuple[Array, NDArray[np.int64]]:
        """About ``n`` boundary points spaced evenly by 3D length, exactly on the curves.

        Returns
        -------
        points : (N, 3) ndarray
            Closed polygon (first point not repeated); starts at the first node.
        corners : (k,) ndarray of int
            Indices of the loop's nodes in ``points``.
        """
        g = self.graph
        lens = np.array([g.edge_lengths[e] for e, _ in self.halfedges])
        total = float(lens.sum())
        pts: list[Array] = []
        corners: list[int] = []
        for (e, fw), ln in zip(self.halfedges, lens, strict=True):
            k = max(2, int(round(n * ln / total)))
            corners.append(sum(len(p) for p in pts))
            pts.append(g.edge_points(e, k + 1, reverse=not fw)[:-1])
        return np.concatenate(pts), np.asarray(corners, dtype=np.int64)

    def chart(self, n: int = 96) -> tuple[float, int]:
        """Signed area of the loop in the cylinder chart (polar angle, height) and its winding.

        Returns
        -------
        area : float
            Positive when the loop runs counter-clockwise seen from outside
            (angle to the right, height up); scaled by the mean radius.
        winding : int
            How often the loop goes around the vertical axis.
        """
        p, _ = self.boundary(n)
        c = self.graph.centre
        th = np.unwrap(np.arctan2(p[:, 1] - c[1], p[:, 0] - c[0]))
        closing = th[0] - th[-1]
        step = (closing + np.pi) % (2 * np.pi) - np.pi
        winding = int(round((th[-1] + step - th[0]) / (2 * np.pi)))
        r = float(np.mean(np.hypot(p[:, 0] - c[0], p[:, 1] - c[1])))
        x, z = th * r, p[:, 2]
        area = 0.5 * float(np.sum(x * np.roll(z, -1) - np.roll(x, -1) * z))
        return area, winding

    def key(self) -> frozenset[int]:
        """The set of its edges (identifies the loop whatever its start and direction)."""
        return frozenset(e for e, _ in self.halfedges)


# -- building the graph -----------------------------------------------------------------------


def _strands(network: CurveNetwork) -> list[Strand]:
    out: list[Strand] = []
    for pi, p in enumerate(network.pieces):
        if p.kind not in LOOP_KINDS:
            continue
        assert p.top is not None  # the loop kinds run along a top curve
        sym = network.groups[p.basic]
        mats, labels = sym.matrices(), sym.labels()
        c = np.asarray(sym.center)
        seen: list[Array] = []
        probe = p.points[[0, len(p.points) // 2, -1], :2]
        for k, (m, lab) in enumerate(zip(mats, labels, strict=True)):
            img = (probe - c) @ m.T + c
            if any(np.allclose(img, q, atol=1e-9) or np.allclose(img[::-1], q, atol=1e-9) for q in seen):
                continue
            seen.append(img)
            out.append(Strand(pi, k, lab, m, c, p.top.transformed(m, c - m @ c), network.layers[p.basic], p))
    return out


def _polyline_hits(a: Array, b: Array) -> list[tuple[float, float]]:
    """Crossings of two sampled top views as (s_a, s_b) fractions of their samples."""
    p, r = a[:-1], a[1:] - a[:-1]
    q, s = b[:-1], b[1:] - b[:-1]
    den = r[:, None, 0] * s[None, :, 1] - r[:, None, 1] * s[None, :, 0]
    w = q[None] - p[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (w[..., 0] * s[None, :, 1] - w[..., 1] * s[None, :, 0]) / den
        u = (w[..., 0] * r[:, None, 1] - w[..., 1] * r[:, None, 0]) / den
    ok = (den != 0) & (t >= 0) & (t <= 1) & (u >= 0) & (u <= 1)
    i, j = np.nonzero(ok)
    na, nb = len(a) - 1, len(b) - 1
    return [((ii + t[ii, jj]) / na, (jj + u[ii, jj]) / nb) for ii, jj in zip(i, j, strict=True)]


def _top_hits(strands: Sequence[Strand]) -> dict[tuple[int, int], list[tuple[float, float]]]:
    """Top-view intersections of every pair of strands, as (u_i, u_j)."""
    from auszug.geometry import intersect_many

    tops = [s.top for s in strands]
    try:
        raw = intersect_many(tops)
        return {k: [(float(tops[k[0]].u_at_t(h.t1)), float(tops[k[1]].u_at_t(h.t2))) for h in v]
                for k, v in raw.items()}
    except TypeError:  # a curve type without an analytic routine: sampled polylines
        n = 257
        u = np.linspace(0.0, 1.0, n)
        pts = [s.top.point_at(u) for s in strands]
        out: dict[tuple[int, int], list[tuple[float, float]]] = {}
        for i in range(len(strands)):
            for j in range(i + 1, len(strands)):
                a, b = pts[i], pts[j]
                if (a.max(0) < b.min(0)).any() or (b.max(0) < a.min(0)).any():
                    continue
                h = _polyline_hits(a, b)
                if h:
                    out[(i, j)] = h
        return out


def network_graph(network: Any, meet_tol: float = 1e-2) -> NetworkGraph:
    """The graph of a network's curves (see the module docstring).

    Parameters
    ----------
    network : Network
    meet_tol : float
        Relative to the drawing size: two curves crossing in the top view meet
        in 3D where their heights differ by less than this, and points closer
        than this are one node.

    Returns
    -------
    NetworkGraph

    Raises
    ------
    DrawingError
        For a network of more curves than
        :attr:`~auszug.limits.Limits.face_solid_curves` (the graph compares
        curves pairwise).
    """
    network = as_curve_network(network)
    check_curves(network, "the loop graph (for faces)")
    strands = _strands(network)
    size = network.size
    tol = 1e-7 * size
    mtol = meet_tol * size
    splits: list[list[float]] = [[0.0, 1.0] for _ in strands]
    meets: list[tuple[int, float, int, float]] = []
    for (i, j), hs in _top_hits(strands).items():
        if strands[i].layer != strands[j].layer:
            continue
        for ui, uj in hs:
            zi = strands[i].points(np.array([ui]))[0]
            zj = strands[j].points(np.array([uj]))[0]
            if np.linalg.norm(zi - zj) <= mtol:
                splits[i].append(ui)
                splits[j].append(uj)
                meets.append((i, ui, j, uj))
    # node candidates: every split point; a meeting joins its two candidates
    cand: list[Array] = []
    owner: list[tuple[int, int]] = []
    first: list[int] = []
    for si, (st, sp) in enumerate(zip(strands, splits, strict=True)):
        u = np.unique(np.clip(np.asarray(sp), 0.0, 1.0))
        keep = np.concatenate([[True], np.diff(u) > 1e-9])
        u = u[keep]
        u[-1] = 1.0 if u[-1] > 1.0 - 1e-9 else u[-1]
        splits[si] = list(u)
        first.append(sum(len(c) for c in cand))
        cand.append(st.points(u))
        owner.extend((si, k) for k in range(len(u)))
    if not cand:
        return NetworkGraph(np.empty((0, 3)), (), tuple(strands), size, tol, mtol)
    P = np.concatenate(cand)
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    pairs = cKDTree(P).query_pairs(tol, output_type="ndarray").reshape(-1, 2)
    extra = []
    for i, ui, j, uj in meets:
        a = first[i] + int(np.argmin(np.abs(np.asarray(splits[i]) - ui)))
        b = first[j] + int(np.argmin(np.abs(np.asarray(splits[j]) - uj)))
        extra.append((a, b))
    if extra:
        pairs = np.concatenate([pairs, np.asarray(extra, dtype=pairs.dtype)])
    g = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(P), len(P)))
    nlab, lab = connected_components(g, directed=False)
    nodes = np.zeros((nlab, 3))
    np.add.at(nodes, lab, P)
    nodes /= np.bincount(lab, minlength=nlab)[:, None]
    # an end point that is an exact curve point keeps that position (first one wins)
    edges: list[GraphEdge] = []
    k = 0
    for si, u in enumerate(splits):
        ids = lab[k:k + len(u)]
        k += len(u)
        for a in range(len(u) - 1):
            if ids[a] == ids[a + 1] and len(u) == 2:
                # a closed strand on its own: keep it as a loop edge
                edges.append(GraphEdge(si, u[a], u[a + 1], int(ids[a]), int(ids[a + 1])))
            elif ids[a] != ids[a + 1] or u[a + 1] - u[a] > 1e-6:
                edges.append(GraphEdge(si, u[a], u[a + 1], int(ids[a]), int(ids[a + 1])))
    return NetworkGraph(nodes, tuple(edges), tuple(strands), size, tol, mtol)


# -- faces of the top-view embedding ----------------------------------------------------------------


def _trace_faces(graph: NetworkGraph) -> list[list[tuple[int, bool]]]:
    """All faces of the rotation system given by top-view angles (each half-edge once)."""
    out_he: dict[int, list[tuple[float, float, int, bool]]] = {}
    for e, ed in enumerate(graph.edges):
        a0, a1 = graph.leaving(e, True)
        b0, b1 = graph.leaving(e, False)
        out_he.setdefault(ed.a, []).append((a0, a1, e, True))
        out_he.setdefault(ed.b, []).append((b0, b1, e, False))
    order: dict[tuple[int, bool], tuple[int, int]] = {}
    rot: dict[int, list[tuple[int, bool]]] = {}
    for v, lst in out_he.items():
        lst.sort(key=lambda x: (round(x[0], 9), x[1]))
        rot[v] = [(e, fw) for _, _, e, fw in lst]
        for i, h in enumerate(rot[v]):
            order[h] = (v, i)
    faces: list[list[tuple[int, bool]]] = []
    used: set[tuple[int, bool]] = set()
    for start in order:
        if start in used:
            continue
        face = []
        h = start
        while h not in used:
            used.add(h)
            face.append(h)
            e, fw = h
            ed = graph.edges[e]
            twin = (e, not fw)
            v, i = order[twin]
            h = rot[v][(i - 1) % len(rot[v])]
        faces.append(face)
    return faces


def _simple_cycles(graph: NetworkGraph, walk: list[tuple[int, bool]]) -> list[list[tuple[int, bool]]]:
    """Split a closed walk into simple cycles: drop edges walked both ways, cut at repeated nodes."""
    cnt: dict[int, int] = {}
    for e, _ in walk:
        cnt[e] = cnt.get(e, 0) + 1
    w = [h for h in walk if cnt[h[0]] == 1]
    if not w:
        return []
    out: list[list[tuple[int, bool]]] = []
    stack: list[tuple[int, bool]] = []
    pos: dict[int, int] = {}
    for h in w:
        e, fw = h
        ed = graph.edges[e]
        tail = ed.a if fw else ed.b
        if tail in pos:
            i = pos[tail]
            cyc = stack[i:]
            del stack[i:]
            for hh in cyc:
                ee, ff = hh
                pos.pop(graph.edges[ee].a if ff else graph.edges[ee].b, None)
            out.append(cyc)
        pos[tail] = len(stack)
        stack.append(h)
    if stack:
        out.append(stack)
    return [c for c in out if _closed(graph, c)]


def _closed(graph: NetworkGraph, cyc: list[tuple[int, bool]]) -> bool:
    if not cyc:
        return False
    heads = [graph.edges[e].b if fw else graph.edges[e].a for e, fw in cyc]
    tails = [graph.edges[e].a if fw else graph.edges[e].b for e, fw in cyc]
    return all(heads[i] == tails[(i + 1) % len(cyc)] for i in range(len(cyc)))


def _add_rims(graph: NetworkGraph) -> NetworkGraph:
    """Close open chains: level rims between consecutive loose ends of equal height on a face."""
    deg = graph.degree()
    loose = set(np.flatnonzero(deg == 1).tolist())
    if len(loose) < 2:
        return graph
    new: set[tuple[int, int]] = set()
    for walk in _trace_faces(graph):
        ends = []
        for e, fw in walk:
            ed = graph.edges[e]
            head = ed.b if fw else ed.a
            if head in loose:
                ends.append(head)
        if len(ends) < 2:
            continue
        for i in range(len(ends)):
            a, b = ends[i], ends[(i + 1) % len(ends)]
            if a == b or (len(ends) == 2 and i == 1):
                continue
            if abs(graph.nodes[a, 2] - graph.nodes[b, 2]) <= max(graph.meet_tol, graph.tol):
                new.add((min(a, b), max(a, b)))
    if not new:
        return graph
    # a rim must not cross any curve in the top view
    samples = [graph.edge_points(e, 65)[:, :2] for e in range(len(graph.edges))]
    edges = list(graph.edges)
    for a, b in sorted(new):
        seg = np.stack([graph.nodes[a, :2], graph.nodes[b, :2]])
        if np.linalg.norm(seg[1] - seg[0]) <= graph.tol:
            continue
        clear = True
        for s in samples:
            for sa, _ in _polyline_hits(seg, s):
                if 1e-6 < sa < 1 - 1e-6:
                    clear = False
                    break
            if not clear:
                break
        if clear:
            edges.append(GraphEdge(-1, 0.0, 1.0, a, b))
    return NetworkGraph(graph.nodes, tuple(edges), graph.strands, graph.size, graph.tol, graph.meet_tol)


def _fillable(lp: Loop) -> bool:
    """Whether the loop is a simple polygon in the cylinder chart, its best-fit plane or the top view."""
    from auszug.meshing.minimal import _simple_projection

    b, _ = lp.boundary(96)
    return _simple_projection(b, lp.graph.centre) is not None


def find_loops(network_or_graph: Any, rims: bool = True, meet_tol: float = 1e-2,
               simple: bool = True) -> list[Loop]:
    """The closed loops of a network: the bounded faces of its top-view embedding.

    Parameters
    ----------
    network_or_graph : CurveNetwork (or a producer of one) or NetworkGraph
    rims : bool
        Close open chains whose loose ends are at the same height with level
        rim edges (see the module docstring).
    meet_tol : float
        See :func:`network_graph`.
    simple : bool
        Keep only loops that are simple polygons in some view (the cylinder
        chart, their best-fit plane or the top view): a loop whose every view
        crosses itself (curves at different radii crossing in the chart) does
        not bound a sensible face.

    Returns
    -------
    list of Loop
        Simple cycles, counter-clockwise in the cylinder chart (seen from
        outside); empty when the network has none.

    Examples
    --------
    >>> from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry, build
    >>> arch = BasicCurve(((-1.0, 2.0), (0.0, 3.0)), (Segment("line"),), ("ground", "apex"),
    ...                   Symmetry(fold=1, mirror=True), height=1.0)   # and its mirror image
    >>> loops = find_loops(build(Drawing((arch,))))   # closed by a rim on the ground
    >>> len(loops), len(loops[0].halfedges), loops[0].has_rim
    (1, 3, True)
    """
    graph = network_or_graph if isinstance(network_or_graph, NetworkGraph) else network_graph(
        network_or_graph, meet_tol)
    if rims:
        graph = _add_rims(graph)
    loops: list[Loop] = []
    seen: set[frozenset[int]] = set()
    for walk in _trace_faces(graph):
        for cyc in _simple_cycles(graph, walk):
            lp = Loop(graph, tuple(cyc))
            if lp.key() in seen:
                continue
            area, winding = lp.chart()
            if winding == 0 and area > graph.tol * graph.size and (not simple or _fillable(lp)):
                seen.add(lp.key())
                loops.append(lp)
    return loops


def loop_through(graph: NetworkGraph, vertices: Sequence[int] | ArrayLike) -> Loop:
    """A loop through given nodes (indices, or 3D points snapped to the nearest node), in order.

    Consecutive nodes are joined by the shortest path of graph edges between
    them (a direct edge if there is one).

    Raises
    ------
    GeometryError
        For fewer than 2 nodes, a point that is no node, or nodes that no
        path joins.
    """
    arr = np.asarray(vertices)
    if arr.ndim == 2:
        if arr.shape[1] != 3:
            raise GeometryError(f"loop points must be 3D, got shape {arr.shape}")
        d = np.linalg.norm(graph.nodes[None] - arr[:, None], axis=2)
        ids = d.argmin(1)
        far = d[np.arange(len(arr)), ids] > 1e-3 * graph.size
        if far.any():
            i = int(np.flatnonzero(far)[0])
            raise GeometryError(f"loop point {i} {arr[i].tolist()} is no node of the network")
        ids = ids.tolist()
    else:
        ids = [int(i) for i in arr.reshape(-1)]
    if len(ids) < 2:
        raise GeometryError(f"a loop needs at least 2 nodes, got {len(ids)}")
    if any(not 0 <= i < len(graph.nodes) for i in ids):
        raise GeometryError(f"node indices must lie in 0..{len(graph.nodes) - 1}")
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import shortest_path

    n = len(graph.nodes)
    w = graph.edge_lengths
    best: dict[tuple[int, int], tuple[float, int]] = {}
    for e, ed in enumerate(graph.edges):
        key = (min(ed.a, ed.b), max(ed.a, ed.b))
        if key not in best or w[e] < best[key][0]:
            best[key] = (float(w[e]), e)
    rows = [k[0] for k in best] + [k[1] for k in best]
    cols = [k[1] for k in best] + [k[0] for k in best]
    vals = [v[0] for v in best.values()] * 2
    mat = coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsr()
    used: set[int] = set()
    halfedges: list[tuple[int, bool]] = []
    for a, b in zip(ids, ids[1:] + ids[:1], strict=True):
        if a == b:
            continue
        _, pred = shortest_path(mat, indices=a, return_predecessors=True)
        if pred[b] < 0:
            raise GeometryError(f"no curves join node {a} to node {b}")
        path = [b]
        while path[-1] != a:
            path.append(int(pred[path[-1]]))
        path.reverse()
        for x, y in zip(path, path[1:], strict=False):
            e = best[(min(x, y), max(x, y))][1]
            if e in used:
                raise GeometryError(f"the loop uses the curve between nodes {x} and {y} twice")
            used.add(e)
            halfedges.append((e, graph.edges[e].a == x))
    if not halfedges:
        raise GeometryError("the loop has no edges")
    return Loop(graph, tuple(halfedges))
