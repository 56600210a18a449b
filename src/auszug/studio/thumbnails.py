"""Gallery thumbnails: a drawing's top view as a small SVG document (pure; the server reads the files).

Every curve of the network (all replicas) is projected on the ground plane and drawn as one polyline
in its basic curve's palette colour, the drawing's extent fitted into a square of
:data:`THUMB_PX` pixels with a margin. Polylines keep at most :data:`MAX_POINTS` points (every k-th
sample and the last), so a thumbnail stays a few kilobytes however finely a curve is sampled.
"""

from __future__ import annotations

import numpy as np

from auszug.microarch.network import Network

__all__ = ["MAX_POINTS", "THUMB_PX", "thumbnail_svg"]

#: The thumbnail's width and height (CSS pixels).
THUMB_PX = 96
#: Most points of one polyline.
MAX_POINTS = 32
_MARGIN = 6


def thumbnail_svg(net: Network, size: int = THUMB_PX) -> str:
    """The top view of ``net`` as an SVG document of ``size`` x ``size`` pixels.

    Parameters
    ----------
    net : Network
        The built drawing (drawing units).
    size : int
        Width and height of the picture in pixels.

    Returns
    -------
    str
        ``<svg ...>`` with one ``<polyline>`` per network curve (none for an empty drawing); y grows
        up in the drawing and down on screen, so y is flipped.
    """
    from auszug.formats.palette import colour

    curves = list(net.curves())
    lines = []
    if curves:
        xy = np.concatenate([c.points[:, :2] for c in curves])
        lo, hi = xy.min(axis=0), xy.max(axis=0)
        centre = (lo + hi) / 2
        span = float(max(hi[0] - lo[0], hi[1] - lo[1], 1e-12))
        k = (size - 2 * _MARGIN) / span
        for c in curves:
            pts = c.points[:, :2]
            step = max(1, -(-(len(pts) - 1) // (MAX_POINTS - 1)))
            keep = pts[::step] if (len(pts) - 1) % step == 0 else np.vstack([pts[::step], pts[-1:]])
            px = size / 2 + (keep[:, 0] - centre[0]) * k
            py = size / 2 - (keep[:, 1] - centre[1]) * k
            coords = " ".join(f"{x:.1f},{y:.1f}" for x, y in zip(px, py, strict=True))
            lines.append(f'<polyline points="{coords}" stroke="{colour(c.basic)}"/>')
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{size}" height="{size}" viewBox="0 0 {size} {size}">'
            f'<g fill="none" stroke-width="1" stroke-linejoin="round">{"".join(lines)}</g></svg>')
