"""SVG drawings of a window's 2D structure, with exact arcs.

Every region becomes one ``<path>`` whose lines and arcs are SVG line and
elliptical-arc commands, so the drawing is as exact as the construction.
Stone is grey, lights are pale blue, blind recesses darker grey; frames
(regions holding further tracery) are drawn as recessed panels.

Examples
--------
>>> from auszug.tracery import build
>>> from auszug.tracery.draw import svg
>>> text = svg(build("fig20a"))
>>> text.count("<path"), 'data-group="fillet"' in text
(8, True)
"""

from __future__ import annotations

import math
from xml.sax.saxutils import quoteattr

import numpy as np

from auszug.geometry import Arc, Curve
from auszug.tracery.model import Tracery

__all__ = ["svg", "path_data", "FILL"]

#: Fill colours by role (frames by depth parity, so nested panels stand out).
FILL = {"stone": "#cfc6b8", "frame": ("#e4ddd2", "#d9d1c4"), "light": "#a9c9e8", "blind": "#b3a997"}


def _fmt(v: float) -> str:
    return f"{v:.10f}".rstrip("0").rstrip(".") if v != 0 else "0"


def path_data(curves: tuple[Curve, ...]) -> str:
    """SVG path data (y up: the caller flips) of a closed loop of lines and arcs.

    Examples
    --------
    >>> from auszug.geometry import Line
    >>> path_data((Line((0, 0), (1, 0)), Line((1, 0), (0, 1)), Line((0, 1), (0, 0))))
    'M0 0 L1 0 L0 1 L0 0 Z'
    """
    p0 = curves[0].start
    parts = [f"M{_fmt(p0[0])} {_fmt(p0[1])}"]
    for c in curves:
        if isinstance(c, Arc):
            # in y-up coordinates a counter-clockwise arc has SVG sweep-flag 1; the
            # y-flip applied by the caller mirrors it into what the eye sees as CCW
            sweeps = [c.sweep] if abs(c.sweep) < 2 * math.pi - 1e-9 else [c.sweep / 2, c.sweep / 2]
            th = c.theta0
            r = _fmt(c.radius)
            for s in sweeps:
                th += s
                q = c.center + c.radius * np.array([math.cos(th), math.sin(th)])
                large = 1 if abs(s) > math.pi else 0
                flag = 1 if s > 0 else 0
                parts.append(f"A{r} {r} 0 {large} {flag} {_fmt(q[0])} {_fmt(q[1])}")
        else:
            q = c.end
            parts.append(f"L{_fmt(q[0])} {_fmt(q[1])}")
    parts.append("Z")
    return " ".join(parts)


def svg(tracery: Tracery, width_px: float = 600.0, margin: float = 0.05, stroke: float | None = None) -> str:
    """SVG text of the window's regions (drawing units, y up on screen).

    Parameters
    ----------
    tracery : Tracery
    width_px : float
        Nominal width in pixels (the drawing scales freely).
    margin : float
        Border round the window, as a fraction of its width.
    stroke : float, optional
        Line width in drawing units (default: a thousandth of the span... x3).
    """
    lo, hi = tracery.bounds()
    w, h = hi - lo
    m = margin * max(w, h)
    x0, y0 = lo[0] - m, lo[1] - m
    vw, vh = w + 2 * m, h + 2 * m
    sw = stroke if stroke is not None else 0.003 * w
    height_px = width_px * vh / vw
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width_px:.0f}" height="{height_px:.0f}" '
        f'viewBox="{_fmt(x0)} {_fmt(-(y0 + vh))} {_fmt(vw)} {_fmt(vh)}">',
        f"<title>{getattr(tracery.style, 'name', tracery.style)}</title>",
        f'<g transform="scale(1,-1)" stroke="#3b3530" stroke-width="{_fmt(sw)}" stroke-linejoin="round">',
    ]
    for r in tracery.regions:
        if r.group == "arch":
            fill = FILL["stone"]
        elif r.role == "frame":
            fill = FILL["frame"][r.depth % 2]
        else:
            fill = FILL[r.role]
        out.append(
            f'<path id={quoteattr(r.id)} data-group="{r.group}" data-depth="{r.depth}" data-role="{r.role}" '
            f'fill="{fill}" d="{path_data(r.curves)}"/>'
        )
    out.append("</g>")
    out.append("</svg>")
    return "\n".join(out) + "\n"
