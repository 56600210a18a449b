"""SVG drawing of a network (``.svg``): its top view and its side view, side by side.

The top view is the orthographic projection onto the ground plane (x, y); the
side view is the orthographic projection onto the vertical x-z plane, seen
from -y (x to the right, height up). Both panels share one scale, so lengths
compare across them. The file is plain SVG 1.1 with a ``viewBox`` in drawing
units: it scales without loss and needs no fonts beyond a generic sans-serif.

Structure (what tests and stylesheets can rely on)::

    <svg>
      <g id="top-view" class="view">
        <g id="top-view-curve-0" class="basic-curve" data-basic="0" stroke="#...">
          <polyline class="ogee replica" data-curve="0/r1m" points="..."/> ...
          <circle class="prc" .../> ...
        </g> ...                       one group per basic curve
      </g>
      <g id="side-view" class="view"> ... the same ... </g>
    </svg>

Every replica is drawn in its basic curve's colour; the basic curve itself
(``r0``) is drawn a little heavier, on top. Round markers are the points of
reverse curvature. Styling is in presentation attributes only (no CSS, no
``vector-effect``), with line widths in drawing units worked out from the
nominal pixel width, so every renderer draws the same picture.
"""

from __future__ import annotations

import math
from typing import Any
from xml.sax.saxutils import escape, quoteattr

import numpy as np
from numpy.typing import NDArray

from auszug.formats._registry import FileFormat, register
from auszug.formats.network_json import unpack
from auszug.formats.palette import PALETTE, colour

__all__ = ["PALETTE", "colour", "dumps"]   # PALETTE and colour live in formats.palette


def _symmetry_text(g: Any) -> str:
    return f"C{g.n}" + (" + mirror" if g.mirror else "")


def dumps(network: Any, source: str = "", width_px: float = 1000.0) -> str:
    """SVG text of the network's top and side views.

    Parameters
    ----------
    network : CurveNetwork or NetworkFile (or a producer of a curve network)
    source : str
        Drawing file name for the title (default: from ``network``).
    width_px : float
        Nominal width in pixels (the drawing scales freely).
    """
    net, src = unpack(network)
    source = source or src
    curves = list(net.curves())
    nb = len(net.groups)
    if curves:
        allp = np.concatenate([c.points for c in curves])
        lo, hi = allp.min(0), allp.max(0)
    else:
        lo, hi = np.zeros(3), np.ones(3)
    size = float(max(hi - lo)) or 1.0
    ext = np.maximum(hi - lo, 1e-3 * size)
    m = 0.08 * size                         # margin
    th = 0.09 * size                        # title band
    font = 0.045 * size
    dec = max(0, 4 - math.floor(math.log10(size)))
    if net.tolerance is not None:   # enough digits that rounding stays below a 40th of the tolerance
        dec = max(dec, math.ceil(-math.log10(net.tolerance / 20.0)))
    ox_side = ext[0] + 3.0 * m              # x offset of the side panel
    W = ox_side + ext[0] + m
    H = th + max(ext[1], ext[2]) + 2.0 * m
    y0 = th + m

    def top_xy(p: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.stack([p[..., 0] - lo[0] + m, hi[1] - p[..., 1] + y0], -1)

    def side_xy(p: NDArray[np.float64]) -> NDArray[np.float64]:
        return np.stack([p[..., 0] - lo[0] + ox_side, hi[2] - p[..., 2] + y0], -1)

    def pts_attr(q: NDArray[np.float64]) -> str:
        return " ".join(f"{x:.{dec}f},{y:.{dec}f}" for x, y in q.tolist())

    px = W / width_px                       # one nominal pixel in drawing units
    r_prc = 3.5 * px
    lw, lw_basic, lw_thin = 1.1 * px, 2.0 * px, 0.8 * px

    def f(v: float) -> str:
        return f"{v:.{dec + 1}f}"

    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" '
        f'viewBox="0 0 {f(W)} {f(H)}" width="{width_px:.0f}" height="{width_px * H / W:.0f}">',
        f"<title>{escape(f'auszug network: {source}')}</title>",
        f"<desc>Top view (x, y) and side view (x, z; orthographic onto the x-z plane), "
        f"{len(curves)} curves of {nb} basic curves; z up, drawing units.</desc>",
        f'<rect width="{f(W)}" height="{f(H)}" fill="#ffffff"/>',
    ]
    # text is laid out in pixels and scaled into drawing units: renderers hint glyphs at
    # the laid-out size, and a font size of 0.1 units would come out garbled
    text_attrs = f'font-family="sans-serif" font-size="{font / px:.1f}" fill="#444444"'
    for view, proj, title in (("top-view", top_xy, "top view"), ("side-view", side_xy, "side view (x-z plane)")):
        out.append(f'<g id="{view}" class="view">')
        tx = m if view == "top-view" else ox_side
        out.append(f'<text transform="translate({f(tx)} {f(th * 0.75)}) scale({px:.6g})" '
                   f'{text_attrs}>{title}</text>')
        if view == "side-view":
            for z in net.bottoms:
                y = hi[2] - z + y0
                out.append(f'<line class="ground" x1="{f(ox_side - 0.5 * m)}" x2="{f(ox_side + ext[0] + 0.5 * m)}" '
                           f'y1="{f(y)}" y2="{f(y)}" stroke="#bbbbbb" stroke-width="{f(lw_thin)}" '
                           f'stroke-dasharray="{f(4 * px)} {f(3 * px)}"/>')
        for b in range(nb):
            mine = [c for c in curves if c.basic == b]
            col = colour(b)
            out.append(f'<g id="{view}-curve-{b}" class="basic-curve" data-basic="{b}" stroke="{col}" '
                       f'fill="none" stroke-width="{f(lw)}" stroke-linecap="round" stroke-linejoin="round">')
            out.append(f"<title>curve {b}: {_symmetry_text(net.groups[b])}, layer {net.layers[b]}</title>")
            # replicas first, the basic curve (r0) last so it lies on top
            mine.sort(key=lambda c: (c.rotation == 0 and not c.mirrored))
            for c in mine:
                basic = c.rotation == 0 and not c.mirrored
                style = f'stroke-width="{f(lw_basic)}"' if basic else 'stroke-opacity="0.8"'
                out.append(f'<polyline class="{c.kind} {"basic" if basic else "replica"}" '
                           f'data-curve={quoteattr(c.id)} {style} '
                           f'points="{pts_attr(proj(np.asarray(c.points)))}"/>')
            for c in mine:
                if c.prc is not None:
                    x, y = proj(np.asarray(c.prc)).tolist()
                    out.append(f'<circle class="prc" data-curve={quoteattr(c.id)} cx="{f(x)}" cy="{f(y)}" '
                               f'r="{f(r_prc)}" fill="{col}" stroke="#ffffff" stroke-width="{f(lw_thin)}"/>')
            out.append("</g>")
        out.append("</g>")
    out.append("</svg>")
    return "\n".join(out) + "\n"


def _write(obj: Any, name: str) -> str:
    return dumps(obj)


register(FileFormat("svg", (".svg",), "network", writer=_write))
