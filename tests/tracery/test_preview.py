"""The live preview mesh (auszug.tracery.preview): faithful to the finished window, wound to be culled."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import ndimage

from auszug.geometry import Arc
from auszug.tracery import build, builtin_style, builtin_styles, window_mesh
from auszug.tracery.model import polygon
from auszug.tracery.preview import PREVIEW_CHORD, PREVIEW_MAX_ANGLE, _flat_out, _sample, preview_mesh

#: Pixels across the window's height in the silhouette test.
RASTER = 800


def _normals(v: np.ndarray, f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit normals (counter-clockwise winding) and areas of the triangles."""
    v = v.astype(float)
    n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    a = np.linalg.norm(n, axis=1)
    return n / np.where(a > 0, a, 1.0)[:, None], 0.5 * a


def _coverage(v: np.ndarray, f: np.ndarray, lo: np.ndarray, px: float, shape: tuple[int, int]) -> np.ndarray:
    """The front view (orthographic along y): pixels (rows z, columns x) whose centre a triangle covers."""
    p = v[:, [0, 2]].astype(float)
    a, b, c = p[f[:, 0]], p[f[:, 1]], p[f[:, 2]]
    d = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    ok = np.abs(d) > 1e-14
    a, b, c, d = a[ok], b[ok], c[ok], d[ok]
    mn = np.maximum(np.ceil((np.minimum(np.minimum(a, b), c) - lo) / px - 0.5).astype(int), 0)
    mx = np.minimum(np.floor((np.maximum(np.maximum(a, b), c) - lo) / px - 0.5).astype(int),
                    np.array(shape[::-1]) - 1)
    w, h = np.maximum(mx[:, 0] - mn[:, 0] + 1, 0), np.maximum(mx[:, 1] - mn[:, 1] + 1, 0)
    cnt = w * h
    tri = np.repeat(np.arange(len(a)), cnt)
    k = np.arange(cnt.sum()) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    ix = mn[tri, 0] + k % np.maximum(w, 1)[tri]
    iz = mn[tri, 1] + k // np.maximum(w, 1)[tri]
    q = lo + (np.stack([ix, iz], axis=1) + 0.5) * px
    A, B, C, D = a[tri], b[tri], c[tri], d[tri]
    l1 = ((B[:, 0] - q[:, 0]) * (C[:, 1] - q[:, 1]) - (B[:, 1] - q[:, 1]) * (C[:, 0] - q[:, 0])) / D
    l2 = ((C[:, 0] - q[:, 0]) * (A[:, 1] - q[:, 1]) - (C[:, 1] - q[:, 1]) * (A[:, 0] - q[:, 0])) / D
    inside = (l1 >= -1e-9) & (l2 >= -1e-9) & (1.0 - l1 - l2 >= -1e-9)
    img = np.zeros(shape, dtype=bool)
    img[iz[inside], ix[inside]] = True
    return img


def _chord_error(t) -> float:
    """How far the preview's border polygons may lie from the exact arcs (the documented bound)."""
    chord = PREVIEW_CHORD * float(t.params.span)
    worst = 0.0
    for r in t.regions:
        for c in r.curves:
            if isinstance(c, Arc):
                step = PREVIEW_MAX_ANGLE
                if chord < c.radius:
                    step = max(step, 2.0 * math.acos(1.0 - chord / c.radius))
                step = min(step, math.pi / 4)
                n = max(1, math.ceil(abs(c.sweep) / step - 1e-9))
                worst = max(worst, c.radius * (1.0 - math.cos(abs(c.sweep) / n / 2.0)))
    return worst


@pytest.mark.parametrize("name", ["fig20a", "fig20c", "fig20h"])
def test_the_preview_shows_the_finished_windows_silhouette(name):
    """Seen from the front, the preview's stone and openings are the finished mesh's, within the chord error.

    Both meshes are rasterised in the front view (orthographic, 800 pixels high); every pixel where
    they disagree lies within the border polygons' chord error (plus a pixel) of the finished
    mesh's silhouette, and the openings' areas agree to 1 %.
    """
    t = build(name)
    ref = window_mesh(t)
    v, f = preview_mesh(t, back=False)
    lo3, hi3 = ref.vertices.min(0), ref.vertices.max(0)
    lo, ext = lo3[[0, 2]], (hi3 - lo3)[[0, 2]]
    px = float(ext[1]) / RASTER
    shape = (math.ceil(ext[1] / px), math.ceil(ext[0] / px))
    fin = _coverage(ref.vertices, ref.faces, lo, px, shape)
    pre = _coverage(v, f, lo, px, shape)
    # distance (model units) from each pixel to the nearest pixel of the other kind in the finished view
    edge = np.where(fin, ndimage.distance_transform_edt(fin), ndimage.distance_transform_edt(~fin)) * px
    off = fin != pre
    assert (~fin).sum() > 0.05 * fin.size                         # the lights are there to compare
    assert edge[off].max() <= _chord_error(t) + 1.5 * px
    assert abs(int((~pre).sum()) - int((~fin).sum())) <= 0.01 * (~fin).sum()


@pytest.mark.parametrize("name", builtin_styles())
def test_every_triangle_faces_out_of_the_stone(name):
    """Wound to be culled: in the front half every face looks to the front or sideways, never back.

    The faces parallel to the wall (the wall's face, the plate, the recess floors and the profiles'
    flat steps) all face -y; the wall's sides face away from it; only slivers where a sharp concave
    corner folds (a vertex offset, not an exact one) may look back, at most 1e-4 of the area.
    """
    t = build(name)
    v, f = preview_mesh(t, back=False)
    n, area = _normals(v, f)
    assert area.min() > 0.0
    flat = np.abs(n[:, 1]) > 1.0 - 1e-9
    assert flat.sum() > 0 and np.all(n[flat, 1] < 0)
    back = n[:, 1] > 1e-9
    assert area[back].sum() <= 1e-4 * area.sum()
    # the wall's four sides: their outward normals (the box round the arch, margin wide)
    c = v.astype(float)[f].mean(axis=1)
    lo, hi = v.min(0), v.max(0)
    for axis, side, sign in ((0, lo[0], -1), (0, hi[0], 1), (2, lo[2], -1), (2, hi[2], 1)):
        on = np.all(np.abs(v[f][:, :, axis] - side) < 1e-6, axis=1)
        assert on.sum() == 2 and np.allclose(n[on, axis], sign)
    # the back half is the mirror image, wound so that it, too, faces out (+y for the flat faces)
    vb, fb = preview_mesh(t)
    nb, _ = _normals(vb, fb[len(f):])
    assert np.all(nb[flat, 1] > 0) and np.allclose(nb[:, [0, 2]], n[:, [0, 2]], atol=1e-6)
    assert np.allclose(c[:, 1], -vb.astype(float)[fb[len(f):]].mean(axis=1)[:, 1], atol=1e-6)


def test_the_border_is_sampled_as_polygon_samples_it():
    """The preview's one-pass arc sampling gives exactly :func:`tracery.model.polygon`'s points."""
    for name in builtin_styles():
        for st in (builtin_style(name), builtin_style(name).with_overrides({"params.excess": 0.9})):
            t = build(st)
            chord = PREVIEW_CHORD * float(t.params.span)
            for r in t.regions:
                assert np.array_equal(_sample(r.curves, PREVIEW_MAX_ANGLE, chord),
                                      polygon(r.curves, PREVIEW_MAX_ANGLE, chord))


def test_a_flat_face_needs_no_samples_along_it():
    """Profile points inside a straight run go; corners, reversals and the ends stay."""
    lv = np.array([[0.0, 0.0], [0.3, 0.3], [0.6, 0.6], [0.6, 1.2], [0.6, 1.2], [0.6, 2.0], [0.9, 2.0]])
    assert _flat_out(lv).tolist() == [[0.0, 0.0], [0.6, 0.6], [0.6, 2.0], [0.9, 2.0]]
    back = np.array([[0.0, 0.0], [0.0, 1.0], [0.0, 0.5]])          # a reversal is a corner
    assert _flat_out(back).tolist() == back.tolist()
    assert _flat_out(lv[:2]).tolist() == lv[:2].tolist()

