"""The figure of a lifted sketch (``auszug lift --render``): the sketch with its regularities, two other views.

Left: the input sketch as drawn (x, y), its intersections marked by what the
lift made of them (a filled dot: a smooth crossing, orthogonal in 3D; a
square: a corner found orthogonal; a hollow dot: an intersection with no
orthogonality applied; a red cross: an occlusion marker), strokes found
planar drawn in colour, the others in grey. Middle: the lifted network seen
from above (x, depth z). Right: a perspective 3D view, y up. matplotlib is
imported only when a figure is drawn.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from auszug.formats.figure import _figure, _fmt, _plain_axes, _save
from auszug.formats.palette import colour
from auszug.geometry import CubicBezier

if TYPE_CHECKING:
    from auszug.lifting import LiftResult, Sketch

__all__ = ["render_lift"]

_GREY = "#8a8a8a"


def _sample(controls: np.ndarray, n: int = 24) -> np.ndarray:
    t = np.linspace(0.0, 1.0, n)
    return np.concatenate([CubicBezier.from_array(c).point(t) for c in controls])


def render_lift(sketch: "Sketch", result: "LiftResult", fmt: str = "png", *, width: int = 1800, height: int = 640,
                dpi: float = 150.0, title: str | None = None) -> bytes:
    """The figure (see the module docstring) as encoded bytes of ``fmt`` (png, pdf, svg)."""
    from matplotlib.collections import LineCollection
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    fmt = _fmt(fmt)
    fig = _figure(width, height, dpi)
    gs = fig.add_gridspec(1, 3, left=0.02, right=0.98, bottom=0.1, top=0.86, wspace=0.08)
    ax = fig.add_subplot(gs[0])
    planar = {c.where.rsplit(" planar", 1)[0] for c in result.cues if c.kind == "planar" and c.applied}
    for i, s in enumerate(sketch.strokes):
        p = _sample(np.asarray(s.controls, float))
        on = s.id in planar
        ax.plot(p[:, 0], p[:, 1], color=colour(i) if on else _GREY, lw=1.8 if on else 1.1, zorder=1)
    orth_where = {c.where.replace(" (corner)", "") for c in result.cues if c.kind == "orthogonal" and c.applied}
    smooth, corner, plain = [], [], []
    for g in result.graphs:
        names = [g.strokes[int(g.seg_stroke[s])].id for s in range(len(g.segments))]
        for c in g.crossings:
            xy = g.points[c.point] * g.scale + g.offset
            ids = sorted({names[s] for s, _ in c.ends})
            if c.smooth:
                smooth.append(xy)
            elif any(f"{a} x {b}" in orth_where or f"{b} x {a}" in orth_where for a in ids for b in ids if a < b):
                corner.append(xy)
            else:
                plain.append(xy)
    for pts, kw in ((smooth, dict(marker="o", s=22, c="#1f5fbf")), (corner, dict(marker="s", s=24, c="#2a9d4b")),
                    (plain, dict(marker="o", s=22, facecolors="none", edgecolors="#555"))):
        if pts:
            a = np.array(pts)
            ax.scatter(a[:, 0], a[:, 1], zorder=3, linewidths=0.8, **kw)  # type: ignore[arg-type]
    if sketch.symmetry is not None:   # the global symmetry curve, dashed (a stroke drawn there shows too)
        p = _sample(np.asarray(sketch.symmetry.controls, float))
        ax.plot(p[:, 0], p[:, 1], color="#d33", lw=1.4, ls=(0, (4, 2)), zorder=2)
    occ = [m.point for m in sketch.markers if m.kind == "occlusion"]
    if occ:
        a = np.array(occ, float)
        ax.scatter(a[:, 0], a[:, 1], marker="x", s=30, c="#d33", zorder=3, linewidths=1.2)
    _plain_axes(ax, "the sketch" if result.mirror is None else "the sketch (half; dashed: symmetry)")
    stats = (f"{len(smooth)} smooth crossings (dots), {len(corner)} orthogonal corners (squares), "
             f"{len(planar)} planar strokes (coloured)")

    net = result.network
    lines = [np.asarray(c.points, float) for c in net.curves()]
    cols = [colour(c.basic) for c in net.curves()]
    ax2 = fig.add_subplot(gs[1])
    ax2.add_collection(LineCollection([p[:, [0, 2]] for p in lines], colors=cols, linewidths=1.4))
    allp = np.concatenate(lines)
    lo, hi = allp.min(0), allp.max(0)
    pad = 0.04 * float(max(hi - lo))
    ax2.set_xlim(lo[0] - pad, hi[0] + pad)
    ax2.set_ylim(lo[2] - pad, hi[2] + pad)
    _plain_axes(ax2, "lifted, from above (x, depth)")
    ax3 = fig.add_subplot(gs[2], projection="3d")
    ax3.add_collection3d(Line3DCollection([p[:, [0, 2, 1]] for p in lines], colors=cols, linewidths=1.4))
    ext = np.maximum(hi - lo, 1e-3 * float(max(hi - lo)))
    ax3.set_xlim(lo[0], lo[0] + ext[0])
    ax3.set_ylim(lo[2], lo[2] + ext[2])
    ax3.set_zlim(lo[1], lo[1] + ext[1])
    ax3.set_box_aspect((ext[0], ext[2], ext[1]))
    ax3.set_proj_type("persp", focal_length=1.0)
    ax3.view_init(elev=20.0, azim=-60.0)
    ax3.set_axis_off()
    ax3.set_title("lifted, 3D (y up)", fontsize=9, color="#555", loc="left")
    fig.suptitle(title if title is not None else f"{sketch.name}: {len(sketch.strokes)} strokes lifted; {stats}",
                 fontsize=11, x=0.02, ha="left")
    return _save(fig, fmt)
