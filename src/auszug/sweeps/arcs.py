"""Short arcs: rotation candidates from the mesh's crease circles, for sweeps too short for the parts.

Beyond the paper. The heads of a window's lancets and the fillets between them are mouldings
swept along arcs that turn by less than a radian at a small radius: their profiles' centroids
travel about 0.12-0.16 of the mesh's diameter, under ``min_sweep_length`` (0.2, the bound that
keeps smooth bumps from passing as sweeps), and none of the cuts through them glides as a whole
curve under their rotations, so the stage ``parts`` proposes no such axis
(:mod:`auszug.sweeps.parts`). Here the axis comes from the mesh itself:

1. :func:`crease_circles`: the creases (edges whose faces' normals differ by at least
   ``arc_crease`` degrees) beside the faces left open, chained at vertices with two crease edges
   and split where a chain turns by more than 30 degrees at a vertex, then cut into its longest
   circles (:func:`circle_pieces`: tangent arcs, a foil's lobes, meet at no corner); each piece of
   at least 4 vertices is fitted with a circle (plane by SVD, circle by least squares in it), and it is an
   arc when every vertex lies within ``arc_fit * eps_prox`` of the circle, the piece bends away
   from its chord by at least ``eps_prox`` and the radius is at most the mesh's diameter. On a
   surface of revolution the profile's corners sweep such circles about the axis exactly. The
   arcs' axes (the circle's normal through its centre), merged within 0.5 degrees and
   ``eps_prox``, are the candidates, most crease vertices first, at most ``arc_axes``;
2. :func:`arc_candidates`: each axis is a rotation part whose gliding points are the vertices of
   the open faces within ``part_l_min`` of its arcs, searched as the stage ``parts`` searches one
   (:func:`~auszug.sweeps.parts._part_patches`: profile cuts, trimming, the fit check), with
   ``arc_sweep_length`` and ``arc_min_area`` in place of ``min_sweep_length`` and
   ``min_patch_area``, and a patch is a candidate only when its faces hold one of the axis' arcs
   whole (every vertex); :func:`~auszug.sweeps.detect` keeps such a patch when it fits within
   ``fit_factor * eps_prox``, covers ``arc_min_area`` and sweeps ``arc_sweep_length``;
3. :func:`flat_candidates` (``arc_flat``): the planar faces normal to an axis, in the plane of one
   of its arcs, swept about it by a straight radial profile from the arc (a wall's face around an
   arch, where the translations' rectangular blocks do not reach); ``detect`` keeps such a patch
   when it adds ``arc_min_area`` of the area to the others (:func:`~auszug.sweeps.patches.add_by_area`).
4. :func:`ring_circles` (``arc_rings``): the axes of families of exact coaxial circles among the
   mesh's straightest edge lines (:func:`edge_lines`), a round moulding's rings, which meet at no
   crease; their patches (:func:`arc_candidates`) are kept, as the planar ones, by the area they add.

The lower bounds hold only for axes that the mesh's own creases give as exact circles, and the
creases are what keeps smooth bumps out: a Gaussian bump is locally a surface of revolution, and
given the random bumps' own 40 axes the relaxed bounds of branch sweeps-window6 (0.1, 0.005) keep
4 patches at ``eps_prox`` 0.005 (0.0077-0.0097 of the area each; none at 0.001), but no edge of the
bumps turns by even 13 degrees, so no axis is proposed, whatever the bounds
(``tests/sweeps/test_arcs.py``; docs/sweeps.md, "Short arcs" and "Planar patches about crease arcs").
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from numpy.typing import NDArray
from scipy.spatial import cKDTree

from auszug.sweeps._kernels import straightest_next, walk_lines
from auszug.sweeps.mesh import SweepMesh, edge_topology
from auszug.sweeps.motion import Motion
from auszug.sweeps.params import DEFAULT, SweepParams
from auszug.sweeps.parts import _axis, _part_patches, _trimmed
from auszug.sweeps.patches import MeshTree, SweepPatch, face_areas
from auszug.sweeps.profilefit import fit_circle_2d

__all__ = ["ArcAxis", "arc_bounds", "arc_candidates", "circle_pieces", "crease_circles", "edge_lines", "fit_circle",
           "flat_candidates", "ring_circles"]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: A crease chain is split where it turns by more than this at a vertex (degrees).
CHAIN_TURN = 30.0
#: Least number of vertices of an arc.
ARC_VERTICES = 4
#: Axes within this angle (degrees) and ``eps_prox`` of each other are one.
SAME_AXIS = 0.5
#: Least number of vertices of a ring circle (:func:`ring_circles`).
RING_VERTICES = 5


@dataclass(frozen=True)
class ArcAxis:
    """A rotation axis proposed by crease arcs (normalised mesh coordinates).

    Attributes
    ----------
    direction : (3,) float array
        Unit direction (signed so that it has a positive dot product with (0.3, 0.5, 0.8)).
    point : (3,) float array
        The axis' point nearest the origin.
    chains : tuple of (k,) int arrays
        The arcs' vertex indices.
    error : float
        Largest distance of an arc's vertex from its fitted circle.
    """

    direction: Array
    point: Array
    chains: tuple[IntArray, ...]
    error: float

    @property
    def n_vertices(self) -> int:
        """Crease vertices on the arcs of this axis."""
        return int(sum(len(c) for c in self.chains))


def fit_circle(points: Array) -> tuple[Array, Array, float, float]:
    """The least-squares circle through ``points (k, 3)``: centre, unit normal, radius and largest error.

    The plane by SVD, the circle in it by :func:`~auszug.sweeps.profilefit.fit_circle_2d` (the
    profile fit's: algebraic, refined geometrically); the error is the larger of the points'
    distances from the plane and from the circle within it.

    Examples
    --------
    >>> t = np.linspace(0.0, 1.0, 6)
    >>> c, n, r, e = fit_circle(np.c_[2 * np.cos(t) + 1, 2 * np.sin(t), np.full(6, 3.0)])
    >>> (np.round(c, 9) + 0.0).tolist(), np.round(np.abs(n), 9).tolist(), round(r, 9), e < 1e-12
    ([1.0, 0.0, 3.0], [0.0, 0.0, 1.0], 2.0, True)
    """
    p = np.asarray(points, float)
    c0 = p.mean(axis=0)
    _, _, vt = np.linalg.svd(p - c0)
    e1, e2, n = vt
    cc, r, err = fit_circle_2d(np.column_stack([(p - c0) @ e1, (p - c0) @ e2]))
    err = max(err, float(np.abs((p - c0) @ n).max()))
    return c0 + cc[0] * e1 + cc[1] * e2, n, r, err


def _chains(edges: IntArray) -> list[list[int]]:
    """The edges ``(k, 2)`` as vertex chains, broken at vertices of other than two of them."""
    inc: dict[int, list[int]] = {}
    for i, (a, b) in enumerate(edges.tolist()):
        inc.setdefault(a, []).append(i)
        inc.setdefault(b, []).append(i)
    used = np.zeros(len(edges), bool)
    out: list[list[int]] = []
    for s in range(len(edges)):
        if used[s]:
            continue
        used[s] = True
        path = [int(edges[s, 0]), int(edges[s, 1])]
        for forward in (True, False):
            while True:
                x = path[-1] if forward else path[0]
                nxt = [i for i in inc[x] if not used[i]]
                if len(inc[x]) != 2 or not nxt or path[0] == path[-1]:
                    break
                i = nxt[0]
                used[i] = True
                y = int(edges[i, 1] if edges[i, 0] == x else edges[i, 0])
                if forward:
                    path.append(y)
                else:
                    path.insert(0, y)
        out.append(path)
    return out


def _split(path: list[int], vertices: Array) -> list[list[int]]:
    """A chain cut where it turns by more than :data:`CHAIN_TURN` degrees at a vertex."""
    p = vertices[path]
    seg = np.diff(p, axis=0)
    seg /= np.maximum(np.linalg.norm(seg, axis=1, keepdims=True), 1e-300)
    turn = np.einsum("ij,ij->i", seg[:-1], seg[1:]) < np.cos(np.radians(CHAIN_TURN))
    cuts = np.flatnonzero(turn) + 1            # vertex index where a new piece starts (shared)
    bounds = [0, *cuts.tolist(), len(path) - 1]
    return [path[a:b + 1] for a, b in zip(bounds[:-1], bounds[1:], strict=True)]


def circle_pieces(path: list[int], vertices: Array, tol: float) -> list[list[int]]:
    """A vertex chain cut into its longest pieces that are circles within ``tol``, from its start on.

    Greedy: from the first vertex the piece grows (by doubling, then bisection) as long as the
    least-squares circle (:func:`fit_circle`) of its vertices stays within ``tol`` of every one; the
    next piece starts at its last vertex. A chain of tangent arcs (a foil's lobes, a lancet's head
    running into its jamb: no corner splits them) is so cut into its arcs and lines; a piece of
    fewer than :data:`ARC_VERTICES` vertices is dropped.

    Examples
    --------
    A quarter circle running tangentially into a line (collinear points fit no circle):

    >>> t = np.linspace(np.pi / 2, 0.0, 9)
    >>> line = np.c_[np.ones(8), -0.25 * np.arange(1, 9), np.zeros(8)]
    >>> v = np.vstack([np.c_[np.cos(t), np.sin(t), np.zeros(9)], line])
    >>> [(p[0], p[-1]) for p in circle_pieces(list(range(17)), v, 1e-9)]
    [(0, 8)]
    """
    n = len(path)
    p = vertices[path]

    def ok(i: int, j: int) -> bool:
        return j - i < 2 or fit_circle(p[i:j + 1])[3] <= tol

    out: list[list[int]] = []
    i = 0
    while i < n - 1:
        lo, step = min(i + 2, n - 1), 1
        if not ok(i, lo):
            i += 1
            continue
        hi = lo
        while hi < n - 1:
            nxt = min(hi + step, n - 1)
            if not ok(i, nxt):
                hi = nxt
                break
            lo = hi = nxt
            step *= 2
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if ok(i, mid):
                lo = mid
            else:
                hi = mid
        if lo + 1 - i >= ARC_VERTICES:
            out.append(path[i:lo + 1])
        i = lo
    return out


def arc_bounds(params: SweepParams) -> SweepParams:
    """``params`` with the arcs' least sweep length and area as ``min_sweep_length`` and ``min_patch_area``.

    Each the smaller of ``arc_sweep_length`` and ``min_sweep_length`` (``arc_min_area`` and
    ``min_patch_area``).
    """
    return params.with_(min_sweep_length=min(params.arc_sweep_length, params.min_sweep_length),
                        min_patch_area=min(params.arc_min_area, params.min_patch_area))


def crease_circles(mesh: SweepMesh, free: NDArray[np.bool_] | None = None,
                   params: SweepParams = DEFAULT) -> list[ArcAxis]:
    """The rotation axes of the exact circular arcs among the creases beside the open faces.

    Parameters
    ----------
    mesh : SweepMesh
    free : (m,) bool array, optional
        The faces left open (default all): a crease counts when one of its faces is open.
    params : SweepParams
        ``arc_crease``, ``arc_fit``, ``arc_axes`` and ``eps_prox``.

    Returns
    -------
    list of ArcAxis
        Most crease vertices first, at most ``arc_axes``.

    Examples
    --------
    A box has creases but no arcs:

    >>> from auszug.sweeps.mesh import normalise
    >>> v = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    >>> f = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
    ...               [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]])
    >>> crease_circles(normalise(v, f))
    []
    """
    if params.arc_axes == 0 or len(mesh.faces) == 0:
        return []
    free_f = np.ones(len(mesh.faces), bool) if free is None else np.asarray(free, bool)
    tri = mesh.vertices[mesh.faces]
    fn = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    fn /= np.maximum(np.linalg.norm(fn, axis=1, keepdims=True), 1e-300)
    ef = mesh.edge_faces
    inner = np.flatnonzero((ef >= 0).all(axis=1))
    a, b = ef[inner, 0], ef[inner, 1]
    crease = (np.einsum("ij,ij->i", fn[a], fn[b]) <= np.cos(np.radians(params.arc_crease))) & (free_f[a] | free_f[b])
    edges = mesh.edges[inner[crease]]
    eps = params.eps_prox
    up = np.array([0.3, 0.5, 0.8])
    found: list[tuple[Array, Array, list[IntArray], list[float]]] = []
    pieces = [c for chain in _chains(edges) for piece in _split(chain, mesh.vertices)
              for c in circle_pieces(piece, mesh.vertices, params.arc_fit * eps)]
    for piece in pieces:
        if len(set(piece)) < ARC_VERTICES:
            continue
        p = mesh.vertices[piece]
        chord = p[-1] - p[0]
        lc = float(np.linalg.norm(chord))
        off = p - p[0]
        bend = (np.linalg.norm(off - np.outer(off @ chord, chord) / lc**2, axis=1).max() if lc > 0
                else np.linalg.norm(off, axis=1).max())
        if bend < eps:
            continue            # (nearly) straight: no circle is determined
        centre, n, r, err = fit_circle(p)
        if err > params.arc_fit * eps or r > 1.0:
            continue
        n = n if n @ up >= 0 else -n
        point = centre - (centre @ n) * n
        ids = np.asarray(piece, np.int64)
        for d, q, chains, errs in found:
            if abs(float(d @ n)) >= np.cos(np.radians(SAME_AXIS)) and float(np.linalg.norm(q - point)) <= eps:
                chains.append(ids)
                errs.append(err)
                break
        else:
            found.append((n, point, [ids], [err]))
    axes = [ArcAxis(d, q, tuple(c), max(e)) for d, q, c, e in found]
    axes.sort(key=lambda x: -x.n_vertices)
    return axes[:params.arc_axes]


def arc_candidates(mesh: SweepMesh, free: NDArray[np.bool_], params: SweepParams = DEFAULT,
                   tree: MeshTree | None = None, first_id: int = 0,
                   axes: list[ArcAxis] | None = None) -> tuple[list[SweepPatch], int]:
    """Rotation patches about the crease arcs' axes (normalised coordinates), fitted, not filtered.

    Parameters
    ----------
    mesh : SweepMesh
    free : (m,) bool array
        The faces the candidates so far leave open.
    params : SweepParams
    tree : MeshTree, optional
        The whole mesh's tree (built here if not given).
    first_id : int
        Id of the first patch.
    axes : list of ArcAxis, optional
        The axes (default :func:`crease_circles` of ``mesh`` and ``free``).

    Returns
    -------
    patches : list of SweepPatch
        Faces index ``mesh.faces``; trimmed with ``arc_sweep_length`` as the least sweep.
    tried : int
        Axes tried.
    """
    free_f = np.asarray(free, bool)
    axes = crease_circles(mesh, free_f, params) if axes is None else axes
    if not axes:
        return [], 0
    areas = face_areas(mesh.vertices, mesh.faces)
    arc_params = arc_bounds(params)
    part_params = arc_params.with_(l_min=params.part_l_min, profile_cuts=params.part_profile_cuts)
    grow = (tree if tree is not None else MeshTree.of(mesh)) if params.part_grow else None
    open_v = np.unique(mesh.faces[free_f].ravel())
    out: list[SweepPatch] = []
    for ax in axes:
        c = np.r_[ax.direction, np.cross(ax.point, ax.direction)]
        axis = _axis(c / np.linalg.norm(c), params)
        if axis.kind != "rotation":
            continue
        near = cKDTree(mesh.vertices[np.concatenate(ax.chains)]).query(mesh.vertices[open_v],
                                                                      distance_upper_bound=params.part_l_min)[0]
        pts = mesh.vertices[open_v[np.isfinite(near)]]
        if len(pts) < ARC_VERTICES:
            continue
        for p in _part_patches(mesh, axis, pts, free_f, areas, part_params, arc_params, grow):
            # the patch must hold one of the arcs that gave its axis whole (the evidence it sweeps)
            on = np.zeros(len(mesh.vertices), bool)
            on[mesh.faces[p.faces].ravel()] = True
            if any(bool(on[c].all()) for c in ax.chains):
                out.append(replace(p, id=first_id + len(out)))
    return out, len(axes)


def flat_candidates(mesh: SweepMesh, free: NDArray[np.bool_], axes: list[ArcAxis], params: SweepParams = DEFAULT,
                    tree: MeshTree | None = None, first_id: int = 0) -> list[SweepPatch]:
    """Rotations of straight radial profiles over the planar faces normal to the crease arcs' axes.

    A flat face is swept by a straight line under every motion in its plane: a translation along it
    (the stage ``parts`` tries those, ``part_across``), or a rotation about an axis normal to it. A
    crease arc lying in a plane of the mesh (a wall's face meeting the reveal of an arch, a plate's
    face meeting a foil's moulding) says which rotation: the one about that arc's axis, whose
    circles run along the face's curved border, where no translation's block reaches. Per axis and
    arc, when the faces whose normals lie within ``part_across`` (a sine) of the axis and whose
    vertices lie within ``arc_fit * eps_prox`` of the arc's plane hold an open face, the profile is
    the segment of the ray from the axis through the arc's middle vertex that lies on those faces,
    from the arc outwards and from the arc inwards, in steps of ``eps_prox``; each at least
    ``part_l_min`` long is trimmed over a whole turn on the whole mesh (the blocks of the stage
    ``parts``, with the arcs' bounds: :func:`arc_bounds`) and fitted.

    Parameters
    ----------
    mesh : SweepMesh
    free : (m,) bool array
        The faces the candidates so far leave open.
    axes : list of ArcAxis
        From :func:`crease_circles`.
    params : SweepParams
    tree : MeshTree, optional
        The whole mesh's tree (built here if not given).
    first_id : int

    Returns
    -------
    list of SweepPatch
        Rotations; faces index ``mesh.faces`` (a face is the patch's when all its corners lie on
        the swept surface, so a long face of the plane, reaching beyond the block, is not: the fit
        stage of :func:`~auszug.sweeps.detect` counts these patches by the area they cover).
    """
    free_f = np.asarray(free, bool)
    if not axes or not free_f.any():
        return []
    tree = tree if tree is not None else MeshTree.of(mesh)
    eps = params.eps_prox
    tol = params.arc_fit * eps
    tri = mesh.vertices[mesh.faces]
    fn = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    fn /= np.maximum(np.linalg.norm(fn, axis=1, keepdims=True), 1e-300)
    arc_params = arc_bounds(params)
    part_params = arc_params.with_(l_min=params.part_l_min, profile_cuts=params.part_profile_cuts)
    still = Motion(np.array([0.0, 1.0]), np.stack([np.eye(3)] * 2), np.zeros((2, 3)))   # _trimmed reads the profile
    out: list[SweepPatch] = []
    for ax in axes:
        c = np.r_[ax.direction, np.cross(ax.point, ax.direction)]
        axis = _axis(c / np.linalg.norm(c), params)
        if axis.kind != "rotation" or axis.point is None:
            continue
        d, q = axis.direction / np.linalg.norm(axis.direction), axis.point
        across = np.linalg.norm(np.cross(fn, d), axis=1) <= params.part_across
        h_v = (mesh.vertices - q) @ d
        done: set[tuple[int, int, int]] = set()
        for chain in ax.chains:
            h0 = float(h_v[chain].mean())
            plane = across & (np.abs(h_v[mesh.faces] - h0) <= tol).all(axis=1)
            if not (plane & free_f).any():
                continue
            mid = mesh.vertices[chain[len(chain) // 2]] - q
            u = mid - (mid @ d) * d
            r0 = float(np.linalg.norm(u))
            if r0 <= 0:
                continue
            u /= r0
            flat = MeshTree(mesh.vertices, mesh.faces[plane])
            for side in (1, -1):
                key = (int(round(h0 / tol)), side, int(round(r0 / eps)))
                if key in done:
                    continue        # another piece of the same circle in the same plane: its rings are the same
                done.add(key)
                reach = float(np.max(np.abs((mesh.vertices - q) @ u))) + eps if side > 0 else r0
                s = np.arange(0.0, reach, eps)
                pts = q + h0 * d + (r0 + side * s)[:, None] * u
                on = flat.query(pts)[0] <= tol
                n_on = int(np.argmin(on)) if not on.all() else len(on)
                if n_on < 2 or s[n_on - 1] < params.part_l_min:
                    continue
                stub = SweepPatch(0, "rotation", pts[:n_on], False, still, np.zeros(0, np.int64), 0.0, 0.0)
                for p in _trimmed(mesh, tree, axis, stub, part_params, (-np.pi, np.pi)):
                    out.append(replace(p, id=first_id + len(out)))
    return out


def edge_lines(mesh: SweepMesh, free: NDArray[np.bool_] | None = None, turn: float = CHAIN_TURN) -> list[IntArray]:
    """The mesh's straightest edge lines over the open faces, as vertex chains.

    Among the edges of the open faces, an edge ``(a, b)`` continues at ``b`` with the edge ``(b, c)``
    that turns least from it, when that turn is below ``turn`` degrees and the choice is mutual
    (from ``(c, b)`` the straightest continuation at ``b`` is ``(b, a)``); so every edge lies on at
    most one line. On a loft's grid (a moulding's rings and the edges across them) the lines run
    along the rings and across them; a triangle's diagonal turns more and is no one's continuation.

    Parameters
    ----------
    mesh : SweepMesh
    free : (m,) bool array, optional
        The faces whose edges count (default all).
    turn : float
        Largest turn at a vertex (degrees).

    Returns
    -------
    list of (k,) int arrays
        Vertex indices along each line (a closed line repeats its first vertex), at least 2 each.

    Examples
    --------
    Two squares side by side, each cut by a diagonal: the two long sides, the three rungs and the two
    diagonals (a line of one edge each: at 45 degrees to every neighbour).

    >>> from auszug.sweeps.mesh import normalise
    >>> v = np.array([[x, y, 0.0] for y in (0, 1) for x in (0, 1, 2)])
    >>> f = np.array([[0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4]])
    >>> sorted(len(line) for line in edge_lines(normalise(v, f)))
    [2, 2, 2, 2, 2, 3, 3]
    """
    faces = mesh.faces if free is None else mesh.faces[np.asarray(free, bool)]
    if len(faces) == 0:
        return []
    e = edge_topology(faces, len(mesh.vertices))[0]                # the open faces' edges, in (low, high) order
    k = len(e)
    src, dst = np.r_[e[:, 0], e[:, 1]], np.r_[e[:, 1], e[:, 0]]      # directed; the reverse of i is (i + k) % 2k
    u = mesh.vertices[dst] - mesh.vertices[src]
    u /= np.maximum(np.linalg.norm(u, axis=1, keepdims=True), 1e-300)
    rev = (np.arange(2 * k) + k) % (2 * k)
    order = np.argsort(src, kind="stable")                          # outgoing edges grouped by their start
    first = np.searchsorted(src[order], np.arange(len(mesh.vertices) + 1))
    # per directed edge the straightest continuation at its end (one compiled pass), kept where mutual
    nxt = straightest_next(dst, u, order, first, rev, float(np.cos(np.radians(turn))))
    has = nxt >= 0
    mutual = np.zeros(2 * k, bool)
    mutual[has] = nxt[rev[nxt[has]]] == rev[np.flatnonzero(has)]
    nxt[~mutual] = -1
    prev = np.full(2 * k, -1, np.int64)
    prev[nxt[nxt >= 0]] = np.flatnonzero(nxt >= 0)
    verts, offs = walk_lines(src, dst, nxt, rev, prev)             # open lines first, then cycles
    return [verts[offs[i]:offs[i + 1]] for i in range(len(offs) - 1)]


def _ring_pieces(p: Array, tol: float) -> list[tuple[int, int]]:
    """The runs of exact circles along a line's points ``p (n, 3)``.

    A run ``(i, j)`` (the points ``p[i:j + 1]``, at least :data:`RING_VERTICES`) is where consecutive
    triples share one circumcircle within ``tol`` (centre and plane).
    """
    if len(p) < RING_VERTICES:
        return []
    a, b, c = p[:-2], p[1:-1], p[2:]
    ab, ac = b - a, c - a
    n = np.cross(ab, ac)
    nn = np.einsum("ij,ij->i", n, n)
    good = nn > 0
    safe = np.where(good, nn, 1.0)[:, None]
    centre = a + (np.cross(n, ab) * np.einsum("ij,ij->i", ac, ac)[:, None]
                  + np.cross(ac, n) * np.einsum("ij,ij->i", ab, ab)[:, None]) / (2 * safe)
    good &= np.linalg.norm(centre - a, axis=1) <= 1.0
    unit = n / np.sqrt(safe)
    same = (good[:-1] & good[1:] & (np.linalg.norm(np.diff(centre, axis=0), axis=1) <= tol)
            & (np.linalg.norm(np.cross(unit[:-1], unit[1:]), axis=1) * np.linalg.norm(b[1:] - centre[1:], axis=1)
               <= tol))
    out = []
    t = 0
    while t < len(good):
        if not good[t]:
            t += 1
            continue
        s = t
        while t < len(same) and same[t]:
            t += 1
        if t + 3 - s >= RING_VERTICES:
            out.append((s, t + 2))
        t += 1
    return out


def ring_circles(mesh: SweepMesh, free: NDArray[np.bool_] | None = None,
                 params: SweepParams = DEFAULT) -> list[ArcAxis]:
    """The rotation axes of families of exact coaxial circles among the straightest edge lines.

    A moulding swept about an axis whose profile is round (a quarter circle leaving a plate's face
    tangentially) has no crease, so :func:`crease_circles` gives it no axis; but its mesh's rings
    (the profile's points swept along the arc) are exact circles about that axis, several of them,
    at different radii and heights. Here the edge lines of the open faces (:func:`edge_lines`) are
    cut into their runs whose consecutive vertex triples share one circumcircle within
    ``arc_ring_fit * eps_prox`` (at least :data:`RING_VERTICES` vertices, every vertex within that
    of the run's least-squares circle, bending away from its chord by ``eps_prox``, radius at most
    the diameter); circles about one axis (within 0.5 deg and ``eps_prox``) make a family, and an
    axis is proposed when its family holds at least ``arc_rings`` distinct circles (radius or height
    along the axis differing by more than ``eps_prox``). An axis may be a crease arc's too: its
    chains, the rings, say where it sweeps (:func:`arc_candidates` searches the part about them).

    The gate is the exactness and the repetition: on the random bumps (clean or noisy, ``eps_prox``
    0.001 or 0.005) no run of an edge line is such a circle at all (``tests/sweeps/test_arcs.py``).

    Parameters
    ----------
    mesh : SweepMesh
    free : (m,) bool array, optional
        The faces left open (default all).
    params : SweepParams
        ``arc_rings``, ``arc_ring_fit``, ``arc_axes`` and ``eps_prox``.

    Returns
    -------
    list of ArcAxis
        Most ring vertices first, at most ``arc_axes``.
    """
    if params.arc_rings == 0 or params.arc_axes == 0 or len(mesh.faces) == 0:
        return []
    eps = params.eps_prox
    tol = params.arc_ring_fit * eps
    up = np.array([0.3, 0.5, 0.8])
    found: list[tuple[Array, Array, list[IntArray], list[tuple[float, float]], list[float]]] = []
    for line in edge_lines(mesh, free):
        p_line = mesh.vertices[line]
        for i, j in _ring_pieces(p_line, tol):
            ids = line[i:j + 1]
            if len(np.unique(ids)) < RING_VERTICES:
                continue
            p = p_line[i:j + 1]
            chord = p[-1] - p[0]
            lc = float(np.linalg.norm(chord))
            off = p - p[0]
            bend = (np.linalg.norm(off - np.outer(off @ chord, chord) / lc**2, axis=1).max() if lc > 0
                    else np.linalg.norm(off, axis=1).max())
            if bend < eps:
                continue
            centre, n, r, err = fit_circle(p)
            if err > tol or r > 1.0:
                continue
            n = n if n @ up >= 0 else -n
            point = centre - (centre @ n) * n
            ring = (r, float(centre @ n))
            for d, q, chains, rings, errs in found:
                if abs(float(d @ n)) >= np.cos(np.radians(SAME_AXIS)) and float(np.linalg.norm(q - point)) <= eps:
                    chains.append(ids)
                    rings.append(ring)
                    errs.append(err)
                    break
            else:
                found.append((n, point, [ids], [ring], [err]))
    axes = []
    for d, q, chains, rings, errs in found:
        distinct: list[tuple[float, float]] = []
        for r, h in rings:
            if all(abs(r - r2) > eps or abs(h - h2) > eps for r2, h2 in distinct):
                distinct.append((r, h))
        if len(distinct) < params.arc_rings:
            continue
        axes.append(ArcAxis(d, q, tuple(chains), max(errs)))
    axes.sort(key=lambda x: -x.n_vertices)
    return axes[:params.arc_axes]
