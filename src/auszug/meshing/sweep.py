"""Members: profiles swept along the 3D curves of a network, replicated by the symmetries.

Each *basic* piece of a :class:`~auszug.microarch.Network` (ogee, free end,
level segment, post, pillar; decoration pieces are part of their ogee) is
swept once, and the mesh is then mapped by its curve's symmetry group, the
2x2 top-view transforms extended to 3x3 with z kept. Replicas are therefore
exact images of each other, and a mirrored replica gets its triangles
reversed so that every member stays outward-oriented.

Sampling
    Ogee and free-end pieces are sampled evenly along their side view (the
    chain of circular arcs in the (g, z) plane), which for the arc-length
    parameterisation is the 3D arc length, so the vertical ends are as finely
    resolved as the middle. Positions and unit tangents are exact (the side
    view's arcs give the tangent in closed form; at the vertical ends it is
    exactly vertical). A corner of a side view (the cusp of a decorated ogee)
    splits the member there.
Frames
    Rotation-minimising (double reflection, :mod:`auszug.meshing.frames`),
    starting from the Darboux frame of the vertical surface over the top
    view: profile x along that surface, profile y along the horizontal
    top-view normal. Where an end lies on a mirror axis of its curve's group,
    the frame is turned there so that the profile's x axis is the mirror
    plane's normal; with both ends on mirrors the remaining twist is spread
    linearly in arc length.
Joints
    A member whose end lies on a mirror axis meets its mirror image there.
    Both are cut by the vertical mirror plane, each keeping its own side, so
    they join along one planar outline without overlap; since the image is the
    exact mirror of the cut member, the two outlines coincide to rounding.
    Only the stretch of member next to that end is cut. Other ends (on the
    ground, free ends, posts) are closed by flat caps.

Everything per sample is vectorised; the loops are over pieces and replicas.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Iterable, Sequence

import numpy as np
from numpy.typing import NDArray

from auszug.errors import GeometryError
from auszug.geometry import TOL, CubicBezier
from auszug.geometry.network import CurveNetwork, Piece, as_curve_network
from auszug.meshing._clip import clip_halfspace, compact
from auszug.meshing.frames import Frames, sweep_frames
from auszug.meshing.mesh import Mesh, Part
from auszug.meshing.profile import Profile, circle, ribbon, square
from auszug.meshing.sweepmodel import Path, RigidFrames, Sweep, sweep_grid

__all__ = [
    "SWEPT_KINDS",
    "CurveSamples",
    "Cut",
    "Member",
    "sample_piece",
    "sweep_profile",
    "sweep_piece",
    "sweep_members",
    "sweep_network",
    "profile_for",
    "default_size",
]

Array = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Piece kinds that become members (decorations are part of their ogee).
SWEPT_KINDS: tuple[str, ...] = ("ogee", "free_end", "level", "post", "pillar", "sketch")
#: Relative tolerance (of the drawing size) for "an end lies on a mirror axis".
AXIS_TOL = 1e-6
#: Side-view corners sharper than this (radians) split a member.
CORNER_ANGLE = 1e-6


# -- sampling ----------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class CurveSamples:
    """Samples of one smooth run of a piece.

    Attributes
    ----------
    points : (n, 3) ndarray
        Exactly on the network's curve.
    tangents : (n, 3) ndarray
        Unit tangents, in the direction of travel.
    """

    points: Array
    tangents: Array


def _wrap(a: Array) -> Array:
    return (a + np.pi) % (2.0 * np.pi) - np.pi


def sample_piece(piece: Piece, segments: int) -> list[CurveSamples]:
    """Sample a network piece for sweeping: ``segments`` steps in all, split at corners.

    Parameters
    ----------
    piece : Piece
        A piece of :attr:`CurveNetwork.pieces`.
    segments : int
        Number of steps along the piece (>= 1; posts and pillars use 1).

    Returns
    -------
    list of CurveSamples
        One per smooth run (more than one only at side-view corners).
    """
    if piece.top is None:  # post or pillar: a vertical straight member
        p = np.asarray(piece.points[[0, -1]], dtype=float)
        d = p[1] - p[0]
        ln = float(np.linalg.norm(d))
        if ln <= TOL.zero:
            raise GeometryError(f"zero-length {piece.kind}")
        return [CurveSamples(p, np.tile(d / ln, (2, 1)))]
    top = piece.top
    if piece.depth is not None:  # a lifted sketch segment: a 3D cubic Bezier
        assert isinstance(top, CubicBezier)   # Piece.from_dict and the lifting package make it so
        return [_sample_bezier3(piece, top, segments)]
    if piece.side is None:  # level: constant height
        u = np.linspace(0.0, 1.0, max(1, segments) + 1)
        t = top.t_at_u(u)
        xy = top.point(t)
        pts = np.concatenate([xy, np.full((len(u), 1), piece.z_const)], axis=1)
        tan = np.concatenate([top.tangent(t), np.zeros((len(u), 1))], axis=1)
        return [CurveSamples(pts, tan)]
    side = piece.side
    G = float(piece.g_of_t(1.0))
    br = np.asarray(side.breaks, dtype=float)
    ga = np.minimum(br[:-1], G)
    gb = np.minimum(br[1:], G)
    use = gb - ga > 1e-12 * max(G, 1.0)
    ga, gb = ga[use], gb[use]
    cg, cz = side.centers[use, 0], side.centers[use, 1]
    r = side.radii[use]
    za, zb = side.height(ga), side.height(gb)
    pa = np.arctan2(za - cz, ga - cg)
    pb = np.arctan2(zb - cz, gb - cg)
    dphi = _wrap(pb - pa)
    lens = r * np.abs(dphi)
    k = np.maximum(1, np.round(max(1, segments) * lens / lens.sum())).astype(int)
    # per arc: angles, then exact g at the ends
    arc_id = np.repeat(np.arange(len(k)), k + 1)
    frac = np.concatenate([np.arange(n + 1) / n for n in k])
    phi = pa[arc_id] + dphi[arc_id] * frac
    g = cg[arc_id] + r[arc_id] * np.cos(phi)
    first = np.concatenate([[0], np.cumsum(k + 1)[:-1]])
    last = first + k
    g[first] = ga
    g[last] = gb
    g = np.clip(g, 0.0, G)
    z = side.height(g)
    sgn = np.sign(dphi)[arc_id]
    tau = sgn[:, None] * np.stack([-(z - cz[arc_id]), g - cg[arc_id]], axis=1) / r[arc_id, None]
    t = piece.t_of_g(g)
    xy = top.point(t)
    th = top.tangent(t)
    tg = tau[:, 0] * piece.rule.ds_dg(top, t)
    tan = np.concatenate([th * tg[:, None], tau[:, 1:2]], axis=1)
    tan /= np.linalg.norm(tan, axis=1, keepdims=True)
    pts = np.concatenate([xy, z[:, None]], axis=1)
    # join the arcs: drop the repeated joint sample unless the side view has a corner there
    runs: list[CurveSamples] = []
    start = 0
    keep_idx: list[IntArray] = []
    for a in range(len(k)):
        idx = np.arange(first[a], last[a] + 1)
        if a > 0:
            c = float(np.dot(tau[last[a - 1]], tau[first[a]]))
            if c < math.cos(CORNER_ANGLE):
                sel = np.concatenate(keep_idx)
                runs.append(CurveSamples(pts[sel], tan[sel]))
                keep_idx = []
            else:
                idx = idx[1:]
        keep_idx.append(idx)
        start = a
    del start
    sel = np.concatenate(keep_idx)
    runs.append(CurveSamples(pts[sel], tan[sel]))
    return runs


def _sample_bezier3(piece: Piece, top: CubicBezier, segments: int) -> CurveSamples:
    """``segments`` steps along a lifted sketch piece (a 3D cubic Bezier), even in arc length.

    The arc length is the chord length of a fine polygon (32 times ``segments``
    chords); samples are the piece's own points (:meth:`Piece.point_t`), exactly
    on the curve, and the tangents its derivative: the top view's and that of the
    depths' Bernstein polynomial.
    """
    n = max(1, segments)
    dz = np.diff(np.asarray(piece.depth, dtype=float))

    def deriv(t: Array) -> Array:
        m = 1.0 - t
        z = 3.0 * (m * m * dz[0] + 2.0 * m * t * dz[1] + t * t * dz[2])
        return np.concatenate([top.derivative(t), z[:, None]], axis=1)

    fine = np.linspace(0.0, 1.0, 32 * n + 1)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(piece.point_t(fine), axis=0), axis=1))])
    if s[-1] <= TOL.zero:
        raise GeometryError("zero-length sketch piece")
    t = np.interp(np.linspace(0.0, s[-1], n + 1), s, fine)
    t[0], t[-1] = 0.0, 1.0
    d = deriv(t)
    ln = np.linalg.norm(d, axis=1)
    # a vanishing derivative (a handle on its end point): the chord's direction stands in
    bad = ln <= TOL.zero * max(1.0, s[-1])
    if bad.any():
        d[bad] = piece.point_t(np.minimum(t[bad] + 1e-6, 1.0)) - piece.point_t(np.maximum(t[bad] - 1e-6, 0.0))
        ln = np.linalg.norm(d, axis=1)
    return CurveSamples(piece.point_t(t), d / ln[:, None])


# -- the sweep kernel ---------------------------------------------------------------------------


def sweep_profile(points: Array, frames: Frames, profile: Profile, cap_start: bool = True,
                  cap_end: bool = True) -> tuple[Array, IntArray]:
    """The surface swept by ``profile`` along sampled points with their frames.

    Parameters
    ----------
    points : (n, 3) ndarray
    frames : Frames
        n frames; profile (x, y) maps to ``x W + y D``.
    profile : Profile
    cap_start, cap_end : bool
        Close the ends with the profile's triangulation (closed profiles only).

    Returns
    -------
    vertices : (n m, 3) ndarray
        Ring after ring.
    faces : (k, 3) ndarray
        Outward-oriented for a closed (counter-clockwise) profile.

    Examples
    --------
    >>> import numpy as np
    >>> from auszug.meshing.frames import sweep_frames
    >>> from auszug.meshing.profile import square
    >>> from auszug.meshing.mesh import Mesh
    >>> p = np.array([[0, 0, 0], [0, 0, 1.0]]); t = np.tile([0, 0, 1.0], (2, 1))
    >>> v, f = sweep_profile(p, sweep_frames(p, t, [1.0, 0, 0]), square(1.0))
    >>> m = Mesh(v, f); m.is_watertight, round(m.volume, 12)
    (True, 1.0)
    """
    cap = profile.cap if profile.closed else None
    return sweep_grid(np.asarray(points, dtype=float), frames.width, frames.depth, profile.points, profile.closed,
                      cap, cap_start, cap_end)


# -- members ------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Cut:
    """A mirror plane at a member's end: the member keeps ``(x - origin) . normal >= 0``.

    Attributes
    ----------
    origin : (3,) ndarray
        The end point (on the plane).
    normal : (3,) ndarray
        Horizontal unit normal towards the kept side.
    end : int
        0 for the first sample's end, 1 for the last.
    element : int
        Index (into the symmetry's :meth:`~auszug.microarch.Symmetry.matrices`)
        of the reflection: the replica met there is this element's image.
    """

    origin: Array
    normal: Array
    end: int
    element: int


@dataclass(frozen=True, eq=False)
class Member:
    """One basic piece swept (before replication).

    Attributes
    ----------
    piece : int
        Index into :attr:`Network.pieces`.
    basic : int
    kind : str
    vertices : (n, 3) ndarray
    faces : (m, 3) ndarray
    frames : list of Frames
        One per smooth run.
    samples : list of CurveSamples
    cuts : tuple of Cut
    replicas : tuple of int
        Group elements whose images are emitted (duplicates of self-symmetric
        members, such as posts on a mirror axis, left out).
    name : str
        Suffix for part names: ``""`` for a curve's first ogee, else
        ``".<kind><segment>"`` as in network curve ids.
    closed : bool
        Whether the profile is closed.
    sweeps : tuple of Sweep
        The sweep model of each smooth run (profile, sampled path, frames),
        before cuts: ``sweeps[k].point(s, v)`` is the exact member surface.
    """

    piece: int
    basic: int
    kind: str
    vertices: Array
    faces: IntArray
    frames: list[Frames]
    samples: list[CurveSamples]
    cuts: tuple[Cut, ...]
    replicas: tuple[int, ...]
    name: str = ""
    closed: bool = field(default=True)
    sweeps: tuple[Sweep, ...] = ()


def _reflection_axis(m: Array) -> Array:
    """Unit direction of the axis of a 2x2 reflection."""
    s = m + np.eye(2)
    c = s[:, 0] if np.linalg.norm(s[:, 0]) >= np.linalg.norm(s[:, 1]) else s[:, 1]
    return c / np.linalg.norm(c)


def _scale(network: CurveNetwork) -> float:
    return max(1.0, network.size)


def _mirror_cuts(network: CurveNetwork, pi: int, runs: list[CurveSamples]) -> list[tuple[int, int, Array]]:
    """(end, element, plane normal) for each end of piece ``pi`` on a mirror axis of its group."""
    piece = network.pieces[pi]
    sym = network.groups[piece.basic]
    mats = sym.matrices()
    cen = np.asarray(sym.center)
    tol = AXIS_TOL * _scale(network)
    pts = np.concatenate([r.points for r in runs])
    probe = pts[[0, len(pts) // 3, (2 * len(pts)) // 3, -1], :2] - cen
    mirror = np.linalg.det(mats) < 0
    out = []
    for end, p in ((0, pts[0]), (1, pts[-1])):
        q = p[:2] - cen
        if np.hypot(*q) <= tol:
            continue  # at the centre every replica meets: left overlapping (documented)
        imgs = np.einsum("kij,j->ki", mats, q)
        fix = np.flatnonzero(mirror & (np.hypot(*(imgs - q).T) <= tol))
        if len(fix) != 1:
            continue
        k = int(fix[0])
        # the mirror image must be another curve, not the piece itself
        img = probe @ mats[k].T
        if np.abs(img - probe).max() <= tol or np.abs(img[::-1] - probe).max() <= tol:
            continue
        ax = _reflection_axis(mats[k])
        out.append((end, k, np.array([-ax[1], ax[0], 0.0])))
    return out


def _width0(piece: Piece, s: CurveSamples, cut_normal: Array | None) -> Array:
    if piece.top is not None:
        th = piece.top.tangent(0.0)
        nh = np.array([-th[1], th[0], 0.0])
        w = np.cross(nh, s.tangents[0])
        if np.linalg.norm(w) > 1e-6:
            return w
        # a tangent along the view (a lifted piece seen end-on): any normal of the tangent
        t0 = s.tangents[0]
        a = np.eye(3)[int(np.argmin(np.abs(t0)))]
        return np.cross(t0, a)
    if cut_normal is not None:
        return cut_normal
    p = s.points[0]
    w = np.array([-p[1], p[0], 0.0])
    return w / np.linalg.norm(w) if np.linalg.norm(w) > TOL.zero else np.array([1.0, 0.0, 0.0])


def _replica_set(network: CurveNetwork, pi: int, pts: Array, tol: float) -> tuple[int, ...]:
    """Group elements with distinct images of the piece (self-symmetric duplicates dropped)."""
    piece = network.pieces[pi]
    sym = network.groups[piece.basic]
    mats = sym.matrices()
    cen = np.asarray(sym.center)
    probe = pts[[0, len(pts) // 2, -1], :2] - cen
    imgs = np.einsum("kij,nj->kni", mats, probe)
    fwd = np.abs(imgs[:, None] - imgs[None]).max(axis=(2, 3))
    bwd = np.abs(imgs[:, None] - imgs[None, :, ::-1]).max(axis=(2, 3))
    same = (fwd <= tol) | (bwd <= tol)
    keep: list[int] = []
    for k in range(len(mats)):
        if not any(same[k, j] for j in keep):
            keep.append(k)
    return tuple(keep)


def sweep_piece(network: Any, pi: int, profile: Profile, segments: int = 200, caps: bool = True,
                cut: bool = True) -> Member:
    """Sweep one basic piece: frames, caps, mirror-plane cuts; not yet replicated.

    Parameters
    ----------
    network : CurveNetwork (or a producer of one, e.g. ``microarch.Network``)
    pi : int
        Index into ``network.pieces``.
    profile : Profile
    segments : int
        Steps along the piece.
    caps : bool
        Close free ends (closed profiles).
    cut : bool
        Cut at mirror planes (else replicas overlap at their joints).

    Returns
    -------
    Member
    """
    network = as_curve_network(network)
    piece = network.pieces[pi]
    if piece.kind not in SWEPT_KINDS:
        raise GeometryError(f"piece {pi} is a {piece.kind}; only {', '.join(SWEPT_KINDS)} pieces are swept")
    runs = sample_piece(piece, segments)
    scale = _scale(network)
    tol = AXIS_TOL * scale
    cuts_raw = _mirror_cuts(network, pi, runs) if cut else []
    by_end = {e: (k, nrm) for e, k, nrm in cuts_raw}
    period = math.pi / 2 if profile.quarter_symmetric else math.pi
    verts: list[Array] = []
    faces: list[IntArray] = []
    frames_l: list[Frames] = []
    sweeps: list[Sweep] = []
    ring: list[IntArray] = []
    fring: list[IntArray] = []
    off = 0
    n_rings = 0
    m = profile.n
    per_step = 2 * (m if profile.closed else m - 1)
    for ri, s in enumerate(runs):
        first, last = ri == 0, ri == len(runs) - 1
        st = by_end[0][1] if first and 0 in by_end else None
        en = by_end[1][1] if last and 1 in by_end else None
        w0 = _width0(piece, s, st if st is not None else en)
        fr = sweep_frames(s.points, s.tangents, w0, st, en, period)
        # the run as a value of the sweep model; its mesh is the model's kernel on the same frames
        sw = Sweep(profile, Path._unchecked(s.points, s.tangents, fr.arclength),
                   RigidFrames.from_frames(s.points, fr, trusted=True))
        v, f = sweep_grid(s.points, fr.width, fr.depth, profile.points, profile.closed,
                          profile.cap if profile.closed else None, caps, caps)
        sweeps.append(sw)
        ns = len(s.points)
        verts.append(v)
        faces.append(f + off)
        ring.append(np.repeat(np.arange(ns) + n_rings, m))
        # per face: the lower ring of its step; caps belong to their end ring
        fr_ring = np.repeat(np.arange(ns - 1) + n_rings, per_step)
        ncap = (len(f) - len(fr_ring)) // 2
        fring.append(np.concatenate([fr_ring, np.full(ncap, n_rings), np.full(ncap, n_rings + ns - 1)]))
        n_rings += ns
        frames_l.append(fr)
        off += len(v)
    V = np.concatenate(verts)
    F = np.concatenate(faces)
    R = np.concatenate(ring)
    RF = np.concatenate(fring)
    n_last = n_rings - 1
    cuts: list[Cut] = []
    eps = 1e-12 * scale
    for end, (k, nrm) in sorted(by_end.items()):
        s = runs[0] if end == 0 else runs[-1]
        c = s.points if end == 0 else s.points[::-1]
        origin = c[0]
        dc = (c - origin) @ nrm
        far = np.nonzero(np.abs(dc) > profile.radius * 1.0000001)[0]
        sign = np.sign(dc[far[0]]) if len(far) else np.sign(dc[np.argmax(np.abs(dc))])
        if sign == 0:
            continue
        nrm = nrm * sign
        d = (V - origin) @ nrm
        # the zone: rings from this end up to the first ring entirely on the kept side
        rings = R if end == 0 else n_last - R
        touch = np.zeros(n_rings + 1, dtype=bool)
        touch[rings[d <= eps]] = True
        limit = int(np.argmin(touch))
        frings = RF if end == 0 else n_last - 1 - RF
        zone = frings < limit
        zi, ri_ = np.flatnonzero(zone), np.flatnonzero(~zone)
        V, fz, src, fsrc = clip_halfspace(V, F.take(zi, axis=0), origin, nrm, eps)
        R = R[src]
        F = np.concatenate([F.take(ri_, axis=0), fz])
        RF = np.concatenate([RF.take(ri_), RF.take(zi)[fsrc]])
        cuts.append(Cut(origin, nrm, end, k))
    if cuts:
        V, F = compact(V, F)
    pts = np.concatenate([s.points for s in runs])
    return Member(pi, piece.basic, piece.kind, V, F, frames_l, runs, tuple(cuts),
                  _replica_set(network, pi, pts, tol), network.suffix(pi), profile.closed, tuple(sweeps))


def sweep_members(network: Any, profile: Profile, segments: int = 200, kinds: Iterable[str] = SWEPT_KINDS,
                  basics: Sequence[int] | None = None, caps: bool = True, cut: bool = True) -> list[Member]:
    """Sweep every basic piece of the given kinds (optionally of some basic curves only)."""
    network = as_curve_network(network)
    ks = set(kinds)
    bad = ks - set(SWEPT_KINDS)
    if bad:
        raise GeometryError(f"unknown member kinds {sorted(bad)}; expected some of {SWEPT_KINDS}")
    return [
        sweep_piece(network, pi, profile, segments, caps, cut)
        for pi, p in enumerate(network.pieces)
        if p.kind in ks and (basics is None or p.basic in basics)
    ]


def replicate(network: Any, members: Sequence[Member]) -> Mesh:
    """All replicas of the members as one mesh, one part per member replica.

    Mirrored replicas have their triangles reversed (outward orientation kept).
    """
    network = as_curve_network(network)
    plan = []
    nv = nf = 0
    for mb in members:
        sym = network.groups[mb.basic]
        k = list(mb.replicas)
        plan.append((mb, sym, k, nv, nf))
        nv += len(k) * len(mb.vertices)
        nf += len(k) * len(mb.faces)
    V = np.empty((nv, 3))
    F = np.empty((nf, 3), dtype=np.int64)
    parts: list[Part] = []
    for mb, sym, ks, v0, f0 in plan:
        mats = sym.matrices()[ks]
        labels = sym.labels()
        cen = np.asarray(sym.center)
        nrep, n, m = len(ks), len(mb.vertices), len(mb.faces)
        x = mb.vertices[:, 0] - cen[0]
        y = mb.vertices[:, 1] - cen[1]
        z = mb.vertices[:, 2]
        rev = np.ascontiguousarray(mb.faces[:, ::-1])
        dets = mats[:, 0, 0] * mats[:, 1, 1] - mats[:, 0, 1] * mats[:, 1, 0]
        for j in range(nrep):
            a, b = v0 + j * n, v0 + (j + 1) * n
            mj = mats[j]
            V[a:b, 0] = mj[0, 0] * x + mj[0, 1] * y + cen[0]
            V[a:b, 1] = mj[1, 0] * x + mj[1, 1] * y + cen[1]
            V[a:b, 2] = z
            np.add(rev if dets[j] < 0 else mb.faces, a, out=F[f0 + j * m:f0 + (j + 1) * m])
        for j, kk in enumerate(ks):
            parts.append(Part(f"{mb.basic}/{labels[kk]}{mb.name}", "member", mb.basic, labels[kk],
                              (v0 + j * n, v0 + (j + 1) * n), (f0 + j * m, f0 + (j + 1) * m)))
    return Mesh._unchecked(V, F, tuple(parts))


def sweep_network(network: Any, profile: Profile, segments: int = 200, kinds: Iterable[str] = SWEPT_KINDS,
                  basics: Sequence[int] | None = None, caps: bool = True, cut: bool = True) -> Mesh:
    """Every member of a network: swept once per basic piece, replicated by its symmetries.

    Parameters
    ----------
    network : CurveNetwork (or a producer of one, e.g. ``microarch.Network``)
    profile : Profile
        See :func:`profile_for` for the built-in looks.
    segments : int
        Steps along each piece (the authors' demo: 200).
    kinds : iterable of str
        Which pieces become members (default all of :data:`SWEPT_KINDS`).
    basics : sequence of int, optional
        Only these basic curves (re-sweeping one edited curve).
    caps, cut : bool
        Close free ends; cut replicas at mirror planes.

    Returns
    -------
    Mesh
        One part per member replica, named like the network's curve ids
        (``"0/r1m"``, ``"2/r0.free_end1"``).

    Examples
    --------
    >>> from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry, build
    >>> c = BasicCurve(((1.0, 0.0), (0.0, 1.0)), (Segment("line"),), ("ground", "apex"),
    ...                Symmetry(fold=2), height=1.0)
    >>> m = sweep_network(build(Drawing((c,))), circle(0.02, 8), segments=16)
    >>> [p.name for p in m.parts], m.is_watertight
    (['0/r0', '0/r1'], True)
    """
    if int(segments) < 1:
        raise GeometryError(f"need at least 1 segment along each member, got {segments}")
    members = sweep_members(network, profile, int(segments), kinds, basics, caps, cut)
    return replicate(network, members)


# -- built-in looks -----------------------------------------------------------------------------


def default_size(network: Any) -> float:
    """A member thickness that reads well: 1.2 % of the network's bounding-box diagonal."""
    b = as_curve_network(network).bounds()
    return 0.012 * float(np.linalg.norm(b[1] - b[0]))


def profile_for(style: str, size: float, around: int | None = None) -> Profile:
    """A built-in profile: ``"tube"`` (diameter ``size``), ``"bar"`` (side ``size``), ``"ribbon"``.

    The ribbon is ``3 size`` wide, ``size / 4`` thick (printable).

    Examples
    --------
    >>> profile_for("bar", 0.1).n, profile_for("tube", 0.1, 12).n
    (4, 12)
    >>> profile_for("cable", 0.1)
    Traceback (most recent call last):
    ...
    auszug.errors.GeometryError: style must be one of tube, bar, ribbon, got 'cable'
    """
    if style == "tube":
        return circle(size / 2.0, 40 if around is None else around)
    if style == "bar":
        return square(size, 4 if around is None else around)
    if style == "ribbon":
        return ribbon(3.0 * size, size / 4.0, 4 if around is None else around)
    raise GeometryError(f"style must be one of tube, bar, ribbon, got {style!r}")
