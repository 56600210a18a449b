"""Make docs/img/lift-junction.png: the box whose sections meet its edges, drawn with a slip, lifted as
drawn (refused: the solve collapses it) and with ``close_gaps`` (docs/lifting.md, "Crossings drawn near one
point").

Run from the repository's root: ``python docs/img/make_junction_png.py`` (it uses the test truths).
"""

from __future__ import annotations

import sys
import textwrap
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from auszug.errors import GeometryError  # noqa: E402
from auszug.lifting import LiftParams, lift, sketch_graph  # noqa: E402
from tests.lifting import truth as T  # noqa: E402

TOL = 0.005


def _curve(c: np.ndarray, n: int = 24) -> np.ndarray:
    t = np.linspace(0, 1, n)[:, None]
    m = 1 - t
    return np.concatenate([m**3 * s[0] + 3 * m * m * t * s[1] + 3 * m * t * t * s[2] + t**3 * s[3] for s in c])


def main() -> None:
    tr = T.shifted(T.box(meet=True), range(9, 15), 0.002, 0)
    g = sketch_graph(tr.sketch, LiftParams(close_gaps=TOL), require_markers=False)
    j = max(g.junctions, key=lambda j: j.spread)
    q = j.point * g.scale + g.offset
    fig, ax = plt.subplots(1, 3, figsize=(14.5, 4.6))
    # (a) one junction, drawn and joined
    r = 4 * j.spread * g.scale
    for si, s in enumerate(tr.sketch.strokes):
        p = _curve(s.controls)
        ax[0].plot(p[:, 0], p[:, 1], color="0.65", lw=3, label="drawn" if si == 0 else None)
        pg = _curve(g.points[g.segments[g.chains[si]]] * g.scale + g.offset)
        ax[0].plot(pg[:, 0], pg[:, 1], color="k", lw=1, label="joined" if si == 0 else None)
    ax[0].plot(*q, "o", color="tab:red", ms=5, label="the point")
    ax[0].set_xlim(q[0] - r, q[0] + r)
    ax[0].set_ylim(q[1] - r, q[1] + r)
    ax[0].set_aspect("equal")
    ax[0].set_title(f"the largest of three triangles ({j.spread:.2%} of the diagonal)", fontsize=10)
    ax[0].legend(loc="lower right", fontsize=8)
    # (b, c) the lifts seen from the side: depth against x, the truth dashed
    z0 = tr.chains3d[0][0, 0, 2]
    for k, (params, name) in enumerate(((LiftParams(), "as drawn"), (LiftParams(close_gaps=TOL), f"close_gaps {TOL}"))):
        a = ax[k + 1]
        for c in tr.chains3d:
            p = _curve(c)
            a.plot(p[:, 0], p[:, 2] - z0, "--", color="0.6", lw=1)
        a.set_aspect("equal")
        a.set_xlabel("x (sketch units)")
        a.set_ylabel("depth (truth dashed)")
        try:
            res = lift(tr.sketch, params=params)
        except GeometryError as e:          # the lift refuses a network that collapsed
            a.set_title(f"lifted {name}: refused", fontsize=9)
            why = str(e).split(":")[1].strip() + ": " + str(e).split(":")[2].split("(")[0].strip()
            a.text(0.5, 0.05, textwrap.fill(why, 48), transform=a.transAxes, ha="center", fontsize=8, color="tab:red")
            continue
        err, sign = T.depth_rmse(tr, res)
        pts = np.concatenate([piece.point_t(np.linspace(0, 1, 24)) for piece in res.network.pieces])
        zt = np.concatenate([_curve(c)[:, 2] for c in tr.chains3d]) - z0
        off = float(np.mean(zt) - sign * np.mean(pts[:, 2]))
        for piece in res.network.pieces:
            p = piece.point_t(np.linspace(0, 1, 24))
            a.plot(p[:, 0], sign * p[:, 2] + off, color="tab:blue", lw=1.2)
        extent = float(np.ptp(pts, axis=0).max()) / tr.diagonal()
        if extent < 1e-3:
            a.plot(pts[:, 0].mean(), off, "o", color="tab:blue", ms=5)
        a.set_title(f"lifted {name}: depth RMSE {err:.2%}" + ("" if res.converged else ", not converged"), fontsize=9)
    fig.tight_layout()
    out = ROOT / "docs" / "img" / "lift-junction.png"
    fig.savefig(out, dpi=90)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
