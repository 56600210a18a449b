"""The gallery: pictures of the built-in style library and of the paper's Fig. 19.

:func:`gallery` returns PNG images as bytes, keyed by file name; it writes
nothing (``auszug tracery --gallery DIR`` writes them). Pictures:

* ``tracery-<style>.png``: every built-in style, rendered in its wall;
* ``tracery-styles.png``: the style library side by side, 2D structure above
  and rendering below (the paper's Fig. 20 a-h);
* ``tracery-fig19.png``: the excess varied at constant height (Fig. 19),
  ending with a parameter set that is rejected, with the error it raises;
* ``tracery-prototype.png``: the construction of the prototype window
  (centres, the ellipse that gives the rosette circle, tangency points) and
  its eight polygons.
"""

from __future__ import annotations

import io
import math
from typing import Any, Callable

import numpy as np

from auszug.tracery.build import build
from auszug.tracery.mesh import window_mesh
from auszug.tracery.model import Tracery
from auszug.tracery.render import shade
from auszug.tracery.style import builtin_style, builtin_styles

__all__ = ["gallery", "render_tracery", "FIG19_EXCESS", "FIG19_REJECTED"]

#: Excess values of the Fig. 19 sequence (total height 6, span 2) and the rejected one.
FIG19_EXCESS = (0.9, 1.1, 1.3, 1.5, 1.7, 1.9)
FIG19_REJECTED = 2.4
FIG19_TOTAL = 6.0


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _png(fig: Any) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=fig.dpi, facecolor="white")
    _plt().close(fig)
    return buf.getvalue()


def render_tracery(t: Tracery, width: int = 500, azimuth: float = -18.0, elevation: float = 8.0) -> np.ndarray:
    """An RGB picture of the window's mesh, shape (h, width, 3)."""
    m = window_mesh(t)
    lo, hi = m.bounds()
    h = int(width * (hi[2] - lo[2]) / max(hi[0] - lo[0], 1e-9) * 1.08)
    return shade(m.vertices, m.faces, width, h, azimuth=azimuth, elevation=elevation)


def _draw2d(ax: Any, t: Tracery) -> None:
    from matplotlib.patches import Polygon

    from auszug.tracery.draw import FILL

    for r in t.regions:
        fill = FILL["stone"] if r.group == "arch" else (FILL["frame"][r.depth % 2] if r.role == "frame"
                                                          else FILL[r.role])
        ax.add_patch(Polygon(r.polygon(), closed=True, fc=fill, ec="#3b3530", lw=0.4))
    lo, hi = t.bounds()
    pad = 0.05 * (hi[0] - lo[0])
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.axis("off")


def _styles_sheet(names: list[str], renders: dict[str, np.ndarray]) -> bytes:
    plt = _plt()
    fig, axs = plt.subplots(2, len(names), figsize=(2.3 * len(names), 9.0), dpi=110,
                            gridspec_kw={"height_ratios": [1, 1.25]})
    for k, name in enumerate(names):
        _draw2d(axs[0, k], build(name))
        axs[0, k].set_title(name, fontsize=11)
        axs[1, k].imshow(renders[name])
        axs[1, k].axis("off")
    fig.suptitle("auszug.tracery built-in styles (Havemann and Fellner, Fig. 20 a-h): structure and mesh", fontsize=12)
    fig.tight_layout()
    return _png(fig)


def _fig19(width: int) -> bytes:
    from auszug.errors import AuszugError

    plt = _plt()
    values = (*FIG19_EXCESS, FIG19_REJECTED)
    fig, axs = plt.subplots(1, len(values), figsize=(2.1 * len(values), 5.6), dpi=110)
    base = builtin_style("fig20c")
    for ax, e in zip(axs, values, strict=True):
        h = FIG19_TOTAL - math.sqrt(4.0 * e - 1.0)
        ax.axis("off")
        try:
            t = build(base.with_overrides({"excess": e, "height": h}))
        except AuszugError as err:
            ax.text(0.5, 0.5, f"excess {e:g}\nrejected:\n\n" + _wrap(str(err), 26), ha="center", va="center",
                    fontsize=7.5, family="monospace", transform=ax.transAxes, color="#8b1a1a")
            continue
        ax.imshow(render_tracery(t, width, azimuth=0.0, elevation=0.0))
        ax.set_title(f"excess {e:g}", fontsize=10)
    fig.suptitle(f"Fig. 19: excess varied at constant height {FIG19_TOTAL:g} (span 2); the last set is rejected",
                 fontsize=11)
    fig.tight_layout()
    return _png(fig)


def _wrap(text: str, n: int) -> str:
    import textwrap

    return "\n".join(textwrap.wrap(text, n))


def _prototype() -> bytes:
    from auszug.tracery.build import structure
    from auszug.tracery.window import prototype

    plt = _plt()
    w = prototype()
    t = structure()
    fig, axs = plt.subplots(1, 2, figsize=(9.0, 7.6), dpi=110)
    ax = axs[0]
    for cell in w.cells.values():
        pts = np.concatenate([c.sample(64) for c in cell])
        ax.plot(pts[:, 0], pts[:, 1], color="0.55", lw=0.8)
    pts = np.concatenate([c.sample(64) for c in w.arch.curves()])
    ax.plot(pts[:, 0], pts[:, 1], color="k", lw=1.2)
    e, (_, sr) = w.ensemble, w.sub_arches
    f1, f2 = e.centers[1], sr.centers[0]
    a = 0.5 * (e.radius + sr.radius)
    c = 0.5 * (f1 + f2)
    fc = 0.5 * float(np.hypot(*(f2 - f1)))
    b = math.sqrt(a * a - fc * fc)
    u = (f2 - f1) / (2 * fc)
    th = np.linspace(0, 2 * math.pi, 200)
    ell = c + np.outer(a * np.cos(th), u) + np.outer(b * np.sin(th), [-u[1], u[0]])
    ax.plot(ell[:, 0], ell[:, 1], ":", color="#0072B2", lw=1.0, label="ellipse, foci $m_R$, $m_{LR}$")
    ax.plot(*np.array([f1, f2]).T, "o", color="#0072B2", ms=4)
    ax.plot(*w.circle_center, "o", color="#D55E00", ms=5, label="$m_C$ on the axis")
    for p in w.tangency.values():
        ax.plot(*p, "s", color="#009E73", ms=4)
    ax.axvline(e.mid, color="0.7", lw=0.6, ls="--")
    ax.set_aspect("equal")
    ax.set_title(f"construction (tangency residual {w.tangency_residual():.1e})", fontsize=10)
    ax.legend(loc="upper left", fontsize=8, frameon=False)
    ax.axis("off")
    _draw2d(axs[1], t)
    axs[1].set_title("the eight polygons of (-1,0,2) (1,0,2) 4.0 1.25\n(0,-1,0) 0.2 0.1 0.05 gothic-window",
                     fontsize=10)
    fig.tight_layout()
    return _png(fig)


def gallery(width: int = 500, progress: Callable[[str], None] | None = None) -> dict[str, bytes]:
    """PNG bytes of the gallery pictures, keyed by file name (see the module docstring)."""
    plt = _plt()
    out: dict[str, bytes] = {}
    names = list(builtin_styles())
    renders = {}
    for name in names:
        renders[name] = render_tracery(build(name), width)
        buf = io.BytesIO()
        plt.imsave(buf, renders[name], format="png")
        out[f"tracery-{name}.png"] = buf.getvalue()
        if progress:
            progress(f"tracery-{name}.png")
    out["tracery-styles.png"] = _styles_sheet(names, renders)
    out["tracery-fig19.png"] = _fig19(width)
    out["tracery-prototype.png"] = _prototype()
    return out
