"""The colours of the basic curves: one palette for every file, figure and the studio.

Presentation, not geometry: the SVG views, figures, OBJ materials, PLY and glTF
colours, DXF and Rhino layers, and the studio (which sends each curve's colour
in its geometry message) all colour basic curve ``i`` with :func:`colour`.
"""

from __future__ import annotations

__all__ = ["PALETTE", "colour", "rgb"]

#: One colour per basic curve, cycled (colour-blind safe: Okabe-Ito, then Tol's muted set).
PALETTE: tuple[str, ...] = (
    "#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9",
    "#882255", "#117733", "#332288", "#999933", "#AA4499", "#44AA99",
)


def colour(basic: int) -> str:
    """The colour of basic curve ``basic`` (hex ``#RRGGBB``).

    Examples
    --------
    >>> colour(0), colour(len(PALETTE))
    ('#0072B2', '#0072B2')
    """
    return PALETTE[basic % len(PALETTE)]


def rgb(basic: int) -> tuple[float, float, float]:
    """The colour of basic curve ``basic`` as RGB in [0, 1].

    Examples
    --------
    >>> rgb(0)
    (0.0, 0.4470588235294118, 0.6980392156862745)
    """
    h = colour(basic).lstrip("#")
    r, g, b = (int(h[i:i + 2], 16) / 255.0 for i in (0, 2, 4))
    return r, g, b
