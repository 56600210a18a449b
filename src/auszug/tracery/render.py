"""Pictures of tracery meshes: a small vectorised z-buffer rasteriser (no OpenGL needed).

:func:`shade` turns a triangle mesh into an RGB image array (orthographic
view, Lambert shading with a key and a fill light, supersampled); it returns
pixels and writes nothing. Triangles are rasterised in batches of similar
size, each batch as one numpy computation over a grid of candidate pixels.

Examples
--------
>>> import numpy as np
>>> from auszug.tracery.render import shade
>>> v = np.array([[0, 0, 0], [1, 0, 0], [0, 0, 1.0]])
>>> img = shade(v, np.array([[0, 1, 2]]), width=40, height=40, azimuth=0, elevation=0)
>>> img.shape, img.dtype.name
((40, 40, 3), 'uint8')
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["shade", "view_matrix"]


def _raster(
    P: NDArray[np.float64], tris: NDArray[np.int64], W: int, H: int
) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
    """Index of the nearest triangle at every pixel centre (-1: none) and its depth, shapes (W * H,).

    Scanline spans: every (triangle, pixel row) pair gets its x-span from the
    two edges crossing the row; the spans are expanded into pixels, and per
    pixel the largest screen z (nearest the eye) wins.
    """
    A, B, C = P[tris[:, 0]], P[tris[:, 1]], P[tris[:, 2]]
    ys = np.stack([A[:, 1], B[:, 1], C[:, 1]], axis=1)
    r0 = np.maximum(np.ceil(ys.min(1) - 0.5), 0).astype(np.int64)
    r1 = np.minimum(np.floor(ys.max(1) - 0.5), H - 1).astype(np.int64)
    nrow = np.maximum(r1 - r0 + 1, 0)
    t = np.repeat(np.arange(len(tris)), nrow)
    row = r0[t] + (np.arange(len(t)) - np.repeat(np.cumsum(nrow) - nrow, nrow))
    yc = row + 0.5
    xl = np.full(len(t), np.inf)
    xr = np.full(len(t), -np.inf)
    for a, b in ((A, B), (B, C), (C, A)):
        ya, yb = a[t, 1], b[t, 1]
        cross = (np.minimum(ya, yb) <= yc) & (yc <= np.maximum(ya, yb)) & (ya != yb)
        den = np.where(ya != yb, yb - ya, 1.0)
        x = a[t, 0] + (yc - ya) * (b[t, 0] - a[t, 0]) / den
        xl = np.where(cross, np.minimum(xl, x), xl)
        xr = np.where(cross, np.maximum(xr, x), xr)
    c0 = np.maximum(np.ceil(xl - 0.5), 0)
    c1 = np.minimum(np.floor(xr - 0.5), W - 1)
    ok = np.isfinite(c0) & np.isfinite(c1) & (c1 >= c0)
    t, row, c0, c1 = t[ok], row[ok], c0[ok].astype(np.int64), c1[ok].astype(np.int64)
    ncol = c1 - c0 + 1
    tt = np.repeat(t, ncol)
    col = np.repeat(c0, ncol) + (np.arange(len(tt)) - np.repeat(np.cumsum(ncol) - ncol, ncol))
    rr = np.repeat(row, ncol)
    # depth from the triangle's plane z = gx * x + gy * y + g0 in screen space
    e1, e2 = B - A, C - A
    nz = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    nz = np.where(np.abs(nz) > 1e-18, nz, 1e-18)
    gx = -(e1[:, 1] * e2[:, 2] - e1[:, 2] * e2[:, 1]) / nz
    gy = -(e1[:, 2] * e2[:, 0] - e1[:, 0] * e2[:, 2]) / nz
    z = A[tt, 2] + gx[tt] * (col + 0.5 - A[tt, 0]) + gy[tt] * (rr + 0.5 - A[tt, 1])
    pix = rr * W + col
    out = np.full(W * H, -1, dtype=np.int64)
    depth = np.full(W * H, -np.inf)
    if len(pix):
        order = np.lexsort((-z, pix))
        pix, tt, z = pix[order], tt[order], z[order]
        first = np.ones(len(pix), dtype=bool)
        first[1:] = pix[1:] != pix[:-1]
        out[pix[first]] = tt[first]
        depth[pix[first]] = z[first]
    return out, depth


def view_matrix(azimuth: float, elevation: float) -> NDArray[np.float64]:
    """Rotation taking world (x right, y into the picture, z up) to screen (x right, y up, z towards the eye).

    ``azimuth`` turns the eye about the vertical axis (degrees, positive: from
    the right), ``elevation`` raises it (degrees).
    """
    a, e = math.radians(azimuth), math.radians(elevation)
    # eye direction (from the scene towards the eye), default -y
    d = np.array([math.sin(a) * math.cos(e), -math.cos(a) * math.cos(e), math.sin(e)])
    up = np.array([0.0, 0.0, 1.0])
    right = np.cross(up, d)
    right /= np.linalg.norm(right)
    up2 = np.cross(d, right)
    return np.stack([right, up2, d])


def shade(
    vertices: ArrayLike,
    faces: ArrayLike,
    width: int = 800,
    height: int = 1000,
    azimuth: float = -25.0,
    elevation: float = 12.0,
    color: tuple[float, float, float] = (0.86, 0.80, 0.70),
    background: tuple[float, float, float] = (1.0, 1.0, 1.0),
    supersample: int = 2,
    margin: float = 0.04,
    depth_cue: float = 0.35,
) -> NDArray[np.uint8]:
    """Render a mesh to an RGB image.

    Parameters
    ----------
    vertices : (n, 3) array_like
    faces : (m, 3) array_like of int
        Counter-clockwise seen from outside (back faces are culled).
    width, height : int
        Image size in pixels.
    azimuth, elevation : float
        View direction (degrees), see :func:`view_matrix`.
    color, background : (3,) tuple of float
        Stone and background colours in [0, 1].
    supersample : int
        Samples per pixel along each axis (anti-aliasing).
    margin : float
        Empty border, as a fraction of the image size.
    depth_cue : float
        How much darker the farthest faces are than the nearest (0 to 1).

    Returns
    -------
    (height, width, 3) ndarray of uint8
    """
    v = np.asarray(vertices, dtype=float)
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    R = view_matrix(azimuth, elevation)
    p = v @ R.T
    W, H = width * supersample, height * supersample
    lo, hi = p[:, :2].min(0), p[:, :2].max(0)
    scale = min(W * (1 - 2 * margin) / max(hi[0] - lo[0], 1e-12), H * (1 - 2 * margin) / max(hi[1] - lo[1], 1e-12))
    cx, cy = 0.5 * (lo + hi)
    sx = (p[:, 0] - cx) * scale + 0.5 * W
    sy = (cy - p[:, 1]) * scale + 0.5 * H
    sz = p[:, 2]
    # normals and shading
    a, b, c = p[f[:, 0]], p[f[:, 1]], p[f[:, 2]]
    n = np.cross(b - a, c - a)
    ln = np.linalg.norm(n, axis=1)
    ok = ln > 0
    n[ok] /= ln[ok, None]
    front = ok & (n[:, 2] > 0)
    key = np.array([-0.45, 0.55, 0.7])
    key /= np.linalg.norm(key)
    fill = np.array([0.6, -0.2, 0.75])
    fill /= np.linalg.norm(fill)
    lum = 0.28 + 0.62 * np.clip(n @ key, 0, None) + 0.22 * np.clip(n @ fill, 0, None)
    col = np.clip(lum[:, None] * np.asarray(color)[None], 0, 1)
    fi = np.nonzero(front)[0]
    cbuf, zbuf = _raster(np.stack([sx, sy, sz], axis=1), f[fi], W, H)
    if len(fi):
        cbuf = np.where(cbuf >= 0, fi[np.maximum(cbuf, 0)], -1)
    img = np.empty((W * H, 3))
    hit = cbuf >= 0
    # depth cue: further from the eye a little darker (recesses read as recesses)
    zr = max(float(sz.max() - sz.min()), 1e-12)
    img[hit] = col[cbuf[hit]] * (1.0 - depth_cue * (sz.max() - zbuf[hit]) / zr)[:, None]
    img[~hit] = background
    img = img.reshape(H, W, 3)
    if supersample > 1:
        img = img.reshape(height, supersample, width, supersample, 3).mean(axis=(1, 3))
    return (np.clip(img, 0, 1) * 255 + 0.5).astype(np.uint8)
