"""Pictures of a sweep analysis: the mesh coloured by patch, with the profiles and their paths.

:func:`sweeps_scene` builds one :class:`~auszug.meshing.mesh.Mesh` for the glTF writer (a part per
patch in the patch's colour, the uncovered faces grey, thin tubes along every profile and along
the path of its centroid); :func:`render_sweeps` draws the same with matplotlib (``.png``,
``.svg``, ``.pdf``) and returns the bytes. Nothing here touches files.
"""

from __future__ import annotations

import io
from typing import Any

import numpy as np

__all__ = ["sweeps_scene", "render_sweeps"]


def _paths(report: Any) -> list[tuple[int, np.ndarray, np.ndarray]]:
    """Per patch: its id, the profile, and the path of the profile's centroid (dense)."""
    out = []
    for p in report.patches:
        t0, t1 = p.motion.domain
        t = np.linspace(t0, t1, max(2, 8 * (len(p.motion) - 1) + 1))
        c = p.motion.apply(p.profile.mean(axis=0)[None], t)[:, 0]
        out.append((p.id, p.profile, c))
    return out


def sweeps_scene(vertices: Any, faces: Any, report: Any) -> Any:
    """The mesh split into parts by patch (members coloured by patch id), plus profile and path tubes."""
    from auszug.meshing.mesh import Mesh, Part
    from auszug.meshing.profile import circle
    from auszug.meshing.sweepmodel import Path, Sweep

    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    owner = np.full(len(f), -1)
    for p in report.patches:
        free = owner[p.faces] < 0
        owner[p.faces[free]] = p.id
    verts, tris, parts = [], [], []
    nv = nf = 0

    def add(name: str, kind: str, basic: int, pv: np.ndarray, pf: np.ndarray) -> None:
        nonlocal nv, nf
        verts.append(pv)
        tris.append(pf + nv)
        parts.append(Part(name, kind, basic, "", (nv, nv + len(pv)), (nf, nf + len(pf))))
        nv += len(pv)
        nf += len(pf)

    for pid in [*(p.id for p in report.patches), -1]:
        sel = f[owner == pid]
        if len(sel) == 0:
            continue
        used, inv = np.unique(sel, return_inverse=True)
        add(f"patch {pid}" if pid >= 0 else "uncovered", "member" if pid >= 0 else "base", pid, v[used],
            inv.reshape(-1, 3))
    radius = 0.003 * float(report.bbox_diameter)
    for pid, prof, path in _paths(report):
        for what, pts in (("profile", prof), ("path", path)):
            keep = np.concatenate([[True], np.linalg.norm(np.diff(pts, axis=0), axis=1) > 1e-9 * radius])
            pts = pts[keep]
            if len(pts) < 2:
                continue
            m = Sweep(circle(radius, 8), Path.polyline(pts)).mesh()
            add(f"{what} {pid}", "face", pid, m.vertices, m.faces)
    return Mesh(np.vstack(verts), np.vstack(tris), tuple(parts))


def render_sweeps(vertices: Any, faces: Any, report: Any, ext: str = ".png", size: float = 7.0) -> bytes:
    """A perspective picture: faces coloured by patch (grey uncovered), profiles black, paths red."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    from auszug.formats.palette import rgb

    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    colour = np.tile([0.75, 0.75, 0.75, 1.0], (len(f), 1))
    for p in report.patches:
        colour[p.faces, :3] = rgb(p.id)
    # shade by the normal's tilt so the relief reads
    n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    light = 0.55 + 0.45 * np.abs(n @ np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8]))
    colour[:, :3] *= light[:, None]
    fig = plt.figure(figsize=(size, size))
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection(v[f], facecolors=colour, linewidths=0))
    for _, prof, path in _paths(report):
        ax.plot(*prof.T, color="black", lw=1.5)
        ax.plot(*path.T, color="#d62728", lw=1.5)
    lo, hi = v.min(0), v.max(0)
    c, r = (lo + hi) / 2, float(np.max(hi - lo)) / 2
    ax.set_xlim(c[0] - r, c[0] + r)
    ax.set_ylim(c[1] - r, c[1] + r)
    ax.set_zlim(c[2] - r, c[2] + r)
    ax.set_box_aspect((1, 1, 1))
    ax.set_axis_off()
    ax.set_title(f"{len(report.patches)} sweep patch(es), coverage {report.coverage:.1%}")
    buf = io.BytesIO()
    fig.savefig(buf, format=ext.lstrip("."), dpi=110, bbox_inches="tight")
    plt.close(fig)
    return buf.getvalue()
