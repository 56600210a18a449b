"""From a drawing to the 3D curve network (paper sec. 4.3-4.4, Eq. (1)).

:func:`build` turns every segment of every basic curve into a 3D piece,
``(x(u), y(u), h(g^{-1}(p(u))))``: the top view is kept exactly and the height
comes from the segment's side view (an ogee biarc, a mirrored ogee for a free
end, a constant for a level segment). Replicas are the images of the basic
pieces under their curve's symmetry group; they are stored as 2x2 transforms,
and their points are computed on demand in one vectorised product.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass, field, replace
from typing import Iterator, Literal

import numpy as np
from numpy.typing import NDArray

from auszug._cache import LruCache
from auszug.errors import DrawingError
from auszug.geometry import TOL, Curve
from auszug.geometry.heights import SideCoordinate, orthographic_rule
from auszug.geometry.network import CurveNetwork, NetworkCurve, Piece
from auszug.limits import check_count
from auszug.microarch import sideview as sv
from auszug.microarch.model import BasicCurve, Drawing

__all__ = ["Parameterization", "Piece", "NetworkCurve", "Network", "build"]

Array = NDArray[np.float64]
Parameterization = Literal["arclength", "u", "orthographic"]
PARAMETERIZATIONS = ("arclength", "u", "orthographic")


@dataclass(frozen=True, eq=False)
class Network:
    """The 3D curve network of a drawing.

    Attributes
    ----------
    drawing : Drawing
    pieces : list of Piece
        Basic pieces, ordered by basic curve, then segment; posts and pillars last per curve.
    bottoms : tuple of float
        Layer bottom heights.
    apex_heights : tuple of float
        Per basic curve.
    parameterization : str
    prc_choices : dict
        ``(curve, segment) -> PrcChoice`` for PRCs chosen by Algorithm 1.
    """

    drawing: Drawing
    pieces: list[Piece]
    bottoms: tuple[float, ...]
    apex_heights: tuple[float, ...]
    parameterization: str = "arclength"
    prc_choices: dict = field(default_factory=dict)

    def to_curve_network(self) -> CurveNetwork:
        """The domain-neutral :class:`~auszug.geometry.network.CurveNetwork` (cached).

        Its pieces are this network's pieces; each basic curve's symmetry group
        and layer, the layer bottoms and the drawing's size come along, and the
        drawing's basic curves, heights and PRC choices go into ``meta`` for
        network JSON. The true 3D intersections are not in it: see
        :meth:`with_intersections`.
        """
        got = self.__dict__.get("_curve_network")
        if got is None or got[0] != len(self.pieces):
            d = self.drawing
            got = (len(self.pieces), CurveNetwork(
                pieces=tuple(self.pieces),
                groups=tuple(c.symmetry.group for c in d.curves),
                layers=tuple(c.layer for c in d.curves),
                bottoms=tuple(self.bottoms),
                size=drawing_size(d),
                name=d.name,
                meta=_meta(self),
            ))
            self.__dict__["_curve_network"] = got
        return got[1]

    def with_intersections(self) -> CurveNetwork:
        """The curve network whose pieces also mark the true 3D intersections.

        Each top-view intersection of two curves on one layer whose 3D points
        coincide (own replicas at t = t', other curves at equal heights, within
        :data:`MEET_TOL` of the drawing's size) becomes a feature ``intersection``
        of both pieces, so sampling by tolerance makes it a vertex of both.
        """
        from auszug.microarch.prc import intersections

        net = self.to_curve_network()
        tol = MEET_TOL * net.size
        by_seg: dict[tuple[int, int], list[int]] = {}
        for pi, p in enumerate(self.pieces):
            if p.top is not None and p.kind != "decoration":
                by_seg.setdefault((p.basic, p.segment), []).append(pi)
        marks: dict[int, set[float]] = {}
        for h in intersections(self.drawing, layer_only=True):
            a = by_seg.get((h.curve, h.segment))
            b = by_seg.get((h.other_curve, h.other_segment))
            if not a or not b:
                continue
            pa, pb = self.pieces[a[0]], self.pieces[b[0]]
            za = float(pa.height_at_t(pa.top.t_at_u(h.u)))  # type: ignore[union-attr]  # top set
            zb = float(pb.height_at_t(pb.top.t_at_u(h.u_other)))  # type: ignore[union-attr]  # top set
            if abs(za - zb) > tol:
                continue
            for pi in a:
                marks.setdefault(pi, set()).add(float(h.u))
            for pi in b:
                marks.setdefault(pi, set()).add(float(h.u_other))
        pieces = tuple(
            replace(p, marks=p.marks + tuple(("intersection", u) for u in sorted(marks[pi])))
            if pi in marks else p
            for pi, p in enumerate(net.pieces))
        return replace(net, pieces=pieces)

    def group(self, basic: int) -> tuple[Array, list[str]]:
        """Replica transforms (k, 2, 2) and labels of basic curve ``basic``."""
        return self.to_curve_network().group(basic)

    def ogee_of(self, basic: int) -> Piece:
        """The first ogee piece of basic curve ``basic``."""
        for p in self.pieces:
            if p.basic == basic and p.kind == "ogee":
                return p
        raise DrawingError(f"curve {basic} has no ogee segment")

    def replicate(self, piece: Piece) -> Array:
        """All replicas of a piece's points: (k, n, 3)."""
        return self.to_curve_network().replicate(piece)

    def curves(self) -> Iterator[NetworkCurve]:
        """Every curve of the network (all pieces under all symmetry elements)."""
        return self.to_curve_network().curves()

    def bounds(self) -> Array:
        """Axis-aligned bounds of all curves, shape (2, 3): min and max corner."""
        return self.to_curve_network().bounds()


#: Two curves crossing in the top view meet in 3D where their heights differ by less
#: than this share of the drawing's size.
MEET_TOL = 1e-9


def drawing_size(d: Drawing) -> float:
    """The drawing's size: its largest absolute vertex coordinate (at least 1e-9)."""
    pts = [v for c in d.curves for v in c.vertices]
    return max(1e-9, float(np.max(np.abs(pts)))) if pts else 1.0


def _meta(net: "Network") -> dict:
    """The microarch extras of network JSON: parameterisation, basic curves, PRC choices."""
    d = net.drawing
    basics = []
    for i, b in enumerate(d.curves):
        s = b.symmetry
        basics.append({
            "index": i,
            "layer": b.layer,
            "fold": s.fold,
            "mirror": s.mirror,
            "axis": list(s.axis) if s.mirror else None,
            "center": list(s.center),
            "vertices": [list(v) for v in b.vertices],
            "marks": list(b.marks),
            "apex": float(net.apex_heights[i]),
            "post_top": b.post_top,
            "decoration": b.decoration,
        })
    return {"parameterization": net.parameterization, "basic_curves": basics,
            "prc_choices": dict(net.prc_choices)}


def _g_setup(top: Curve, mode: str, theta: float) -> tuple[SideCoordinate, float]:
    """Side-view coordinate rule for a top curve and the extent G."""
    if mode == "arclength":
        L = top.length()
        return SideCoordinate("arclength", L), L
    if mode == "u":
        return SideCoordinate("u"), 1.0
    got = orthographic_rule(top, theta)
    if got is None:
        raise DrawingError(
            f"the orthographic side view at angle {math.degrees(theta):g} deg is not one-to-one "
            "on this curve; use the arc-length parameterisation")
    return got


_UNIFORM_T: "weakref.WeakKeyDictionary[Curve, dict[int, Array]]" = weakref.WeakKeyDictionary()


def _uniform_t(top: Curve, n: int) -> Array:
    """Parameters of ``n`` samples at equal arc-length steps, cached per (immutable) curve."""
    per = _UNIFORM_T.get(top)
    if per is None:
        per = _UNIFORM_T.setdefault(top, {})
    t = per.get(n)
    if t is None:
        t = per[n] = np.asarray(top.t_at_u(np.linspace(0.0, 1.0, n)), dtype=float)
    return t


def _sample_piece(top: Curve, side: sv.SideView | None, gs: SideCoordinate, n: int,
                  z_const: float = 0.0) -> Array:
    t = _uniform_t(top, n)
    xy = top.point(t)
    z = np.full(n, z_const) if side is None else side.height(gs.g_of_t(top, t))
    return np.concatenate([xy, z[:, None]], axis=1)


def _project_many(top: Curve, q: Array) -> Array:
    """Parameters of the points of ``top`` nearest to each of ``q`` (k, 2)."""
    from auszug.geometry import Arc, Line

    if isinstance(top, Line):
        d = top.p1 - top.p0
        return np.clip((q - top.p0) @ d / (d @ d), 0.0, 1.0)
    if isinstance(top, Arc):
        v = q - top.center
        t = top.t_of_angle(np.arctan2(v[:, 1], v[:, 0]))
        inside = (t >= 0.0) & (t <= 1.0)
        d0 = np.linalg.norm(q - top.start, axis=1)
        d1 = np.linalg.norm(q - top.end, axis=1)
        return np.where(inside, t, np.where(d0 <= d1, 0.0, 1.0))
    return np.array([top.project(p) for p in q])


def build(
    drawing: Drawing,
    parameterization: Parameterization = "arclength",
    theta: float = 0.0,
    samples: int | None = None,
) -> Network:
    """Reconstruct the 3D curve network of ``drawing``.

    Parameters
    ----------
    drawing : Drawing
    parameterization : {"arclength", "u", "orthographic"}
        The choice of p(u) in Eq. (1): top-view arc length (default, view
        independent), the top curve's own parameter, or the orthographic
        projection onto the vertical plane at angle ``theta`` to the x-axis.
    theta : float
        Angle (radians) for the orthographic choice.
    samples : int, optional
        Samples per piece (default ``TOL.samples``, at least 2).

    Returns
    -------
    Network

    Raises
    ------
    DrawingError
        For invalid heights (an apex at or below its bottom, a post below its
        apex), a PRC outside its curve, or a parameterisation that is not
        one-to-one.
    """
    if parameterization not in PARAMETERIZATIONS:
        raise DrawingError(f"parameterization must be one of {PARAMETERIZATIONS}, got {parameterization!r}")
    n = int(samples or TOL.samples)
    if n < 2:
        raise DrawingError(f"need at least 2 samples per piece, got {n}")
    check_count("samples per curve piece:", n, "samples")
    check_count(f"sampled points ({n} per curve piece, times the drawing's network curves):",
                n * sum(len(c.segments) * c.symmetry.order for c in drawing.curves), "network_points")
    bottoms = drawing.bottoms()
    apex = tuple(drawing.apex_height(i, bottoms) for i in range(len(drawing.curves)))
    pieces: list[Piece] = []
    choices: dict = {}
    auto: dict[tuple[int, int], float] = {}
    if any(
        c.prc[si] is None and c.segment_kind(si) == "ogee"
        for c in drawing.curves
        for si in range(len(c.segments))
    ):
        from auszug.microarch.prc import algorithm1

        for key, ch in algorithm1(drawing).items():
            choices[key] = ch
            auto[key] = ch.fraction
    tol_key = tuple(vars(TOL).values())
    for ci, c in enumerate(drawing.curves):
        autos = tuple(auto.get((ci, si)) for si in range(len(c.segments)))
        key = (ci, c, bottoms[c.layer], apex[ci], autos, parameterization, theta, n, tol_key)
        got = _CURVE_PIECES.get(key)
        if got is None:
            got = tuple(_build_curve(drawing, ci, c, bottoms, apex[ci], auto, parameterization, theta, n))
            for p in got:
                p.points.setflags(write=False)
                if p.prc is not None:
                    p.prc.setflags(write=False)
            _CURVE_PIECES.put(key, got)
        pieces.extend(got)
    net = Network(drawing, pieces, bottoms, apex, parameterization, choices)
    _add_pillars(net, n)
    return net


_CURVE_PIECES = LruCache(1024)


def _heights(c: BasicCurve, bottom: float, apex: float, where: str) -> list[float]:
    if not apex > bottom:
        raise DrawingError(f"apex height {apex:g} is not above its layer bottom {bottom:g}", where)
    return [bottom if m == "ground" else apex for m in c.marks]


def _build_curve(
    drawing: Drawing,
    ci: int,
    c: BasicCurve,
    bottoms: tuple[float, ...],
    apex: float,
    auto: dict[tuple[int, int], float],
    mode: str,
    theta: float,
    n: int,
) -> list[Piece]:
    where = f"curve {ci}"
    bottom = bottoms[c.layer]
    zs = _heights(c, bottom, apex, where)
    out: list[Piece] = []
    ogee_sides: dict[int, sv.SideView] = {}
    kinds = [c.segment_kind(i) for i in range(len(c.segments))]
    order = [i for i in range(len(kinds)) if kinds[i] == "ogee"] + [
        i for i in range(len(kinds)) if kinds[i] != "ogee"
    ]
    built: dict[int, list[Piece]] = {}
    for si in order:
        kind = kinds[si]
        top = c.top_curve(si, oriented=True)
        try:
            if kind == "ogee":
                gs, G = _g_setup(top, mode, theta)
                f = c.prc[si]
                f = auto[(ci, si)] if f is None else f
                t_c = float(top.t_at_u(f))
                g_c = float(gs.g_of_t(top, t_c))
                side = sv.ogee(G, bottom, apex, g_c)
                deco = None
                pieces_here = []
                if c.decoration:
                    f_d = c.decoration_at if c.decoration_at is not None else f / 2.0
                    g_d = float(gs.g_of_t(top, float(top.t_at_u(f_d))))
                    side, (g_d, z_d) = sv.decorated(side, g_d)
                    deco = (float(top.u_at_t(gs.t_of_g(top, g_d))), z_d)
                ogee_sides[si] = side
                prc = np.array([*top.point(t_c), float(side.height(g_c))])
                pts = _sample_piece(top, side, gs, n)
                pc = Piece(ci, si, "ogee", top, side, gs, pts, prc, float(f), deco)
                pieces_here.append(pc)
                if deco is not None:
                    # the decoration: the two equal arcs below the PRC (also part of the ogee)
                    dpts = pc.point3(np.linspace(0.0, 1.0, n) * f)
                    pieces_here.append(Piece(ci, si, "decoration", top, side, gs, dpts, None, None, deco,
                                             u_end=float(f)))
                built[si] = pieces_here
            elif kind == "free_end":
                flip = c.marks[si] == "free"
                apex_vertex = si + 1 if flip else si
                # the ogee that ends at this apex
                nb = [j for j in (apex_vertex - 1, apex_vertex) if 0 <= j < len(kinds) and kinds[j] == "ogee"]
                if not nb:
                    raise DrawingError(f"segment {si} is a free end that follows no ogee")
                side = sv.free_end(ogee_sides[nb[0]])
                gs, G = _g_setup(top, mode, theta)
                if G > side.extent * (1.0 + 1e-12):
                    raise DrawingError(
                        f"the free end (side-view extent {G:g}) is longer than the diameter "
                        f"{side.extent:g} of the ogee's upper arc it continues")
                pts = _sample_piece(top, side, gs, n)
                built[si] = [Piece(ci, si, "free_end", top, side, gs, pts)]
            else:
                z = zs[si]
                gs, _ = _g_setup(top, "arclength", theta)
                pts = _sample_piece(top, None, gs, n, z_const=z)
                built[si] = [Piece(ci, si, "level", top, None, gs, pts, z_const=z)]
        except DrawingError as e:
            raise DrawingError(e.problem, f"{where}, segment {si}") from None
    for si in range(len(kinds)):
        out.extend(built[si])
    if c.post_top is not None:
        tops = [i for i, m in enumerate(c.marks) if m == "apex"]
        if c.post_top <= apex:
            raise DrawingError(f"post top {c.post_top:g} is not above the apex {apex:g}", where)
        for vi in tops:
            x, y = c.vertices[vi]
            pts = np.array([[x, y, apex], [x, y, c.post_top]])
            out.append(Piece(ci, -1, "post", None, None, SideCoordinate("u"), pts))
    return out


PILLAR_SNAP = 0.01


def _add_pillars(net: Network, n: int) -> None:
    """Vertical pillars under the ground points of curves above layer 0.

    A pillar drops from a ground point of layer l > 0 to the highest curve of
    the layers below that passes under it, or else to the bottom of layer 0.
    Ground points of traced drawings sit on lower curves only approximately, so
    a curve passing within ``PILLAR_SNAP`` of the drawing's size counts (its
    height at the nearest point is taken), as in the authors' demo.
    """
    d = net.drawing
    if not d.curves:
        return
    pts_all = np.array([v for c in d.curves for v in c.vertices])
    size = max(1e-12, float(np.abs(pts_all).max()))
    tol = PILLAR_SNAP * size
    new: list[Piece] = []
    for ci, c in enumerate(d.curves):
        if c.layer == 0:
            continue
        z_top = net.bottoms[c.layer]
        below = [p for p in net.pieces if p.top is not None and d.curves[p.basic].layer < c.layer]
        for vi, mk in enumerate(c.marks):
            if mk != "ground":
                continue
            q = np.asarray(c.vertices[vi])
            z_bot = net.bottoms[0]
            for p in below:
                assert p.top is not None  # below keeps the pieces with a top curve
                sym = d.curves[p.basic].symmetry
                cen = np.asarray(sym.center)
                # q lies on a replica iff its pre-image m^T (q - c) + c lies on the basic piece
                pre = np.einsum("kji,j->ki", sym.matrices(), q - cen) + cen
                ts = _project_many(p.top, pre)
                near = np.linalg.norm(p.top.point(ts) - pre, axis=1) <= tol
                if near.any():
                    zs = p.height_at_t(ts[near])
                    zs = zs[zs <= z_top + tol]
                    if zs.size:
                        z_bot = max(z_bot, float(zs.max()))
            if z_top - z_bot > 1e-9 * size:
                pts = np.array([[q[0], q[1], z_bot], [q[0], q[1], z_top]])
                new.append(Piece(ci, -1, "pillar", None, None, SideCoordinate("u"), pts))
    net.pieces.extend(new)
