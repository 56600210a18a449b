"""Figures of a network (``.png``, ``.pdf``, ``.svg`` of kind ``"figure"``) with matplotlib.

Like the paper's Fig. 9: the top view and the side view (orthographic, the
side view onto the x-z plane) and a perspective 3D view, side by side, each
replica in its basic curve's colour, equal aspect in every panel. The contact
sheet puts several drawings in one grid, one column of three views each.

matplotlib is imported only when a figure is drawn, with the Agg backend (no
display needed); importing this module costs nothing.
"""

from __future__ import annotations

import io
import os
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np

from auszug.errors import FormatError
from auszug.formats._registry import FileFormat, register
from auszug.formats.network_json import unpack
from auszug.formats.palette import colour
from auszug.limits import LIMITS

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from mpl_toolkits.mplot3d import Axes3D

    from auszug.geometry.network import CurveNetwork

__all__ = ["FIGURE_FORMATS", "draw_views", "render", "contact_sheet"]

FIGURE_FORMATS = ("png", "pdf", "svg")
_GREY = "#9a9a9a"
#: Camera of the 3D view (degrees) and its perspective focal length.
ELEVATION, AZIMUTH, FOCAL = 22.0, -60.0, 1.0


def _figure(width: float, height: float, dpi: float) -> "Figure":
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure

    return Figure(figsize=(width / dpi, height / dpi), dpi=dpi, facecolor="white")


def _fmt(fmt: str) -> str:
    f = fmt.lower().lstrip(".")
    if f not in FIGURE_FORMATS:
        raise FormatError(f"figure format must be one of {', '.join(FIGURE_FORMATS)}, got {fmt!r}")
    return f


def _lines(net: "CurveNetwork") -> tuple[list, list, list, list]:
    """Per curve: points, colour, line width, z-order (basic curves on top)."""
    pts, cols, widths, order = [], [], [], []
    for c in net.curves():
        basic = c.rotation == 0 and not c.mirrored
        pts.append(np.asarray(c.points, dtype=float))
        cols.append(colour(c.basic))
        widths.append(1.7 if basic else 1.0)
        order.append(1 if basic else 0)
    idx = np.argsort(order, kind="stable")
    return [pts[i] for i in idx], [cols[i] for i in idx], [widths[i] for i in idx], [order[i] for i in idx]


def _prcs(net: "CurveNetwork") -> tuple[np.ndarray, list[str]]:
    ps, cs = [], []
    for c in net.curves():
        if c.prc is not None:
            ps.append(np.asarray(c.prc, dtype=float))
            cs.append(colour(c.basic))
    return (np.array(ps) if ps else np.empty((0, 3))), cs


def _plain_axes(ax: "Axes", label: str) -> None:
    ax.set_aspect("equal", adjustable="box")
    ax.set_xticks([])
    ax.set_yticks([])
    for s in ax.spines.values():
        s.set_visible(False)
    ax.set_title(label, fontsize=9, color="#555", loc="left")


def draw_views(ax_top: "Axes | None", ax_side: "Axes | None", ax_3d: "Axes3D | None",
               network: Any, *, labels: bool = True) -> None:
    """Draw a network's top view, side view and 3D view into the given axes.

    Parameters
    ----------
    ax_top, ax_side : matplotlib Axes or None
        2D axes for the top view (x, y) and the side view (x, z).
    ax_3d : mpl_toolkits.mplot3d Axes3D or None
        3D axes; drawn with a perspective camera.
    network : CurveNetwork or NetworkFile (or a producer of a curve network)
    labels : bool
        Whether to title the panels.
    """
    from matplotlib.collections import LineCollection

    net, _ = unpack(network)
    pts, cols, widths, _ = _lines(net)
    prc, prc_cols = _prcs(net)
    if pts:
        allp = np.concatenate(pts)
        lo, hi = allp.min(0), allp.max(0)
    else:
        lo, hi = np.zeros(3), np.ones(3)
    size = float(max(hi - lo)) or 1.0
    pad = 0.04 * size
    if ax_top is not None:
        ax_top.add_collection(LineCollection([p[:, :2] for p in pts], colors=cols, linewidths=widths,
                                             capstyle="round", joinstyle="round"))
        if len(prc):
            ax_top.scatter(prc[:, 0], prc[:, 1], s=14, c=prc_cols, edgecolors="white",
                           linewidths=0.6, zorder=3)
        ax_top.set_xlim(lo[0] - pad, hi[0] + pad)
        ax_top.set_ylim(lo[1] - pad, hi[1] + pad)
        _plain_axes(ax_top, "top view" if labels else "")
    if ax_side is not None:
        for z in net.bottoms:
            ax_side.axhline(z, color="#cfcfcf", lw=0.8, ls=(0, (4, 3)), zorder=0)
        ax_side.add_collection(LineCollection([p[:, [0, 2]] for p in pts], colors=cols,
                                              linewidths=widths, capstyle="round", joinstyle="round"))
        if len(prc):
            ax_side.scatter(prc[:, 0], prc[:, 2], s=14, c=prc_cols, edgecolors="white",
                            linewidths=0.6, zorder=3)
        ax_side.set_xlim(lo[0] - pad, hi[0] + pad)
        ax_side.set_ylim(lo[2] - pad, hi[2] + pad)
        _plain_axes(ax_side, "side view" if labels else "")
    if ax_3d is not None:
        from mpl_toolkits.mplot3d.art3d import Line3DCollection

        z0 = float(net.bottoms[0]) if net.bottoms else float(lo[2])
        shadow = [np.column_stack([p[:, :2], np.full(len(p), z0)]) for p in pts]
        ax_3d.add_collection3d(Line3DCollection(shadow, colors="#d9d9d9", linewidths=0.6))
        ax_3d.add_collection3d(Line3DCollection(pts, colors=cols, linewidths=widths))
        ext = np.maximum(hi - lo, 1e-3 * size)
        ax_3d.set_xlim(lo[0], lo[0] + ext[0])
        ax_3d.set_ylim(lo[1], lo[1] + ext[1])
        ax_3d.set_zlim(lo[2], lo[2] + ext[2])
        ax_3d.set_box_aspect(tuple(ext), zoom=1.0)
        ax_3d.set_proj_type("persp", focal_length=FOCAL)
        ax_3d.view_init(elev=ELEVATION, azim=AZIMUTH)
        ax_3d.set_axis_off()
        if labels:
            ax_3d.set_title("3D (perspective)", fontsize=9, color="#555", loc="left")


def _caption(fig: "Figure", cell: Any, text: str) -> None:
    box = cell.get_position(fig)
    fig.text((box.x0 + box.x1) / 2.0, 0.035, text, ha="center", va="bottom", fontsize=10, color="#555")


def _save(fig: "Figure", fmt: str) -> bytes:
    buf = io.BytesIO()
    meta = {"Software": "auszug"} if fmt == "png" else {}
    fig.savefig(buf, format=fmt, dpi=fig.dpi, facecolor="white", metadata=meta or None)
    return buf.getvalue()


def render(network: Any, fmt: str = "png", *, width: int = 1800, height: int = 620,
           dpi: float = 150.0, title: str | None = None) -> bytes:
    """A figure of top, side and perspective 3D views side by side.

    Parameters
    ----------
    network : CurveNetwork or NetworkFile (or a producer of a curve network)
    fmt : {"png", "pdf", "svg"}
    width, height : int
        Size in pixels (PNG) or in 1/dpi inches (PDF, SVG).
    dpi : float
    title : str, optional
        Figure title (default: the drawing's file name).

    Returns
    -------
    bytes
        The encoded figure.
    """
    fmt = _fmt(fmt)
    if width < 50 or height < 50:
        raise FormatError(f"figure size must be at least 50 x 50 pixels, got {width} x {height}")
    if max(width, height) > LIMITS.pixels:
        raise FormatError(f"figure size {width} x {height} is above the limit of {LIMITS.pixels} pixels "
                          "a side (auszug.limits.LIMITS.pixels)")
    net, source = unpack(network)
    fig = _figure(width, height, dpi)
    lo, hi = net.bounds() if net.pieces else (np.zeros(3), np.ones(3))
    ext = np.maximum(hi - lo, 1e-3 * (float(max(hi - lo)) or 1.0))
    # panel widths in proportion to their equal-aspect content at one common height
    ratios = [ext[0] / ext[1], ext[0] / ext[2], 1.25 * max(ext[0], ext[1]) / ext[2]]
    ratios = np.clip(np.asarray(ratios) / max(ratios), 0.35, 1.0)
    gs = fig.add_gridspec(1, 3, width_ratios=ratios, left=0.02, right=0.98, bottom=0.1,
                          top=0.88, wspace=0.08)
    ax_top = fig.add_subplot(gs[0])
    ax_side = fig.add_subplot(gs[1])
    ax_3d = fig.add_subplot(gs[2], projection="3d")
    draw_views(ax_top, ax_side, ax_3d, net, labels=False)
    for k, text in enumerate(("top view", "side view (x-z plane)", "3D view (perspective)")):
        _caption(fig, gs[k], text)
    sym = ", ".join(sorted({f"C{g.n}" + ("+mirror" if g.mirror else "") for g in net.groups}))
    fig.suptitle(title if title is not None else f"{source}   ({len(net.groups)} basic curves; {sym})",
                 fontsize=11, x=0.02, ha="left")
    return _save(fig, fmt)


def contact_sheet(items: Sequence[tuple[str, Any]], fmt: str = "png", *, ncols: int = 6,
                  cell: float = 300.0, dpi: float = 100.0, title: str | None = None) -> bytes:
    """Several networks in one grid, each a column of 3D, side and top views (paper Fig. 9).

    Parameters
    ----------
    items : sequence of (label, CurveNetwork or NetworkFile)
    fmt : {"png", "pdf", "svg"}
    ncols : int
        Drawings per row.
    cell : float
        Width of one drawing's column in pixels.
    dpi : float
    title : str, optional
    """
    fmt = _fmt(fmt)
    if not items:
        raise FormatError("a contact sheet needs at least one drawing")
    ncols = max(1, min(int(ncols), len(items)))
    nrows = -(-len(items) // ncols)
    heights = [1.05, 0.6, 1.0]                     # 3D, side, top per drawing
    head = 0.35 if title else 0.1
    fig = _figure(ncols * cell, (nrows * (sum(heights) + 0.25) + head) * cell, dpi)
    gs = fig.add_gridspec(nrows * 4, ncols, height_ratios=(heights + [0.25]) * nrows,
                          left=0.01, right=0.99, bottom=0.005,
                          top=1.0 - head / (nrows * (sum(heights) + 0.25) + head),
                          hspace=0.05, wspace=0.05)
    for k, (label, net) in enumerate(items):
        r, c = divmod(k, ncols)
        ax_3d = fig.add_subplot(gs[4 * r, c], projection="3d")
        ax_side = fig.add_subplot(gs[4 * r + 1, c])
        ax_top = fig.add_subplot(gs[4 * r + 2, c])
        draw_views(ax_top, ax_side, ax_3d, net, labels=False)
        ax_3d.set_title(label, fontsize=11, color="#222")
    if title:
        fig.suptitle(title, fontsize=14)
    return _save(fig, fmt)


def _write(obj: Any, name: str) -> bytes:
    return render(obj, os.path.splitext(name)[1] or "png")


register(FileFormat("figure", (".png", ".pdf", ".svg"), "figure", writer=_write, binary=True))
