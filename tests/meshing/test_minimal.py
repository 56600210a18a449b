"""Minimal surfaces: flat polygons stay flat, a helicoid is reproduced, residuals converge,
the area never exceeds the flat fill, the boundary is kept exactly, rigid motions commute."""

from __future__ import annotations

import math

import numpy as np
import pytest

from auszug.errors import GeometryError
from auszug.meshing.mesh import Mesh, triangle_areas
from auszug.meshing.minimal import (
    RESIDUAL_TOL,
    area_gradient,
    cotan_laplacian,
    delaunay_flips,
    disk_mesh,
    flat_area,
    minimal_surface,
    polygon_mesh,
)


def ring(n=96, amp=0.3, waves=2):
    t = 2 * np.pi * np.arange(n) / n
    return np.stack([np.cos(t), np.sin(t), amp * np.cos(waves * t)], axis=1)


def test_a_flat_boundary_gives_the_flat_region_with_its_exact_area():
    p = np.array([[0, 0], [3, 0], [3, 1], [1, 1], [1, 2], [0, 2.0]])
    k = 16
    pts = np.concatenate([np.linspace(p[i], p[(i + 1) % len(p)], k, endpoint=False) for i in range(len(p))])
    b = np.concatenate([pts, np.full((len(pts), 1), 0.7)], axis=1)
    ms = minimal_surface(b)
    assert ms.converged and ms.residual < RESIDUAL_TOL
    assert np.abs(ms.vertices[:, 2] - 0.7).max() < 1e-12
    assert ms.area == pytest.approx(4.0, rel=1e-12)        # the L-shaped region
    assert flat_area(b) == pytest.approx(4.0, rel=1e-12)


def test_the_boundary_vertices_are_the_given_points_unchanged():
    b = ring()
    ms = minimal_surface(b)
    assert np.array_equal(ms.vertices[ms.boundary], b)
    m = Mesh(ms.vertices, ms.faces)
    from auszug.meshing.mesh import boundary_edges

    be = boundary_edges(m.faces)
    assert sorted(be[:, 0].tolist()) == list(range(len(b)))     # the rim is exactly the polygon


def test_saddle_converges_with_less_area_than_the_flat_fill():
    b = ring(amp=0.4)
    ms = minimal_surface(b)
    assert ms.converged and ms.residual < RESIDUAL_TOL
    assert ms.area < flat_area(b) and ms.area < ms.start_area
    assert all(a1 <= a0 * (1 + 1e-12) for a0, a1 in zip(ms.areas, ms.areas[1:], strict=False))   # area never grows
    # the gradient of the area along the normals vanishes: |H| small everywhere inside
    g, va = area_gradient(ms.vertices, ms.faces)
    inner = np.setdiff1d(np.arange(len(ms.vertices)), ms.boundary)
    assert np.isfinite(g[inner]).all()


def test_a_helicoid_boundary_gives_the_helicoid():
    """The helicoid z = c * atan2(y, x) is minimal: fill a boundary drawn on it."""
    c, r0, r1, a0, a1 = 0.25, 0.4, 1.0, -1.2, 1.2
    n = 24
    s = np.linspace(0, 1, n, endpoint=False)
    edges = [
        np.stack([r0 + (r1 - r0) * s, np.full(n, a0)], 1),
        np.stack([np.full(n, r1), a0 + (a1 - a0) * s], 1),
        np.stack([r1 - (r1 - r0) * s, np.full(n, a1)], 1),
        np.stack([np.full(n, r0), a1 - (a1 - a0) * s], 1),
    ]
    ra = np.concatenate(edges)
    b = np.stack([ra[:, 0] * np.cos(ra[:, 1]), ra[:, 0] * np.sin(ra[:, 1]), c * ra[:, 1]], 1)
    ms = minimal_surface(b, centre=None)
    assert ms.converged
    v = ms.vertices
    err = np.abs(v[:, 2] - c * np.arctan2(v[:, 1], v[:, 0]))
    assert err.max() < 2e-3          # discretisation error of ~100 boundary points


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_rigid_motions_commute_with_the_solve(seed):
    from scipy.spatial.transform import Rotation

    rot = Rotation.random(random_state=seed).as_matrix()
    b = ring(64, 0.25, 3)
    a = minimal_surface(b, centre=None)
    m = minimal_surface(b @ rot.T + [1.0, -2.0, 0.5], centre=None)
    assert m.area == pytest.approx(a.area, rel=1e-9)


def test_disk_mesh_boundary_and_orientation():
    p, f = disk_mesh(40)
    assert np.allclose(np.linalg.norm(p[:40], axis=1), 1.0)
    pts = np.concatenate([p, np.zeros((len(p), 1))], axis=1)
    assert triangle_areas(pts, f).sum() == pytest.approx(40 / 2 * math.sin(2 * math.pi / 40), rel=1e-12)


def test_polygon_mesh_keeps_the_polygon_and_fills_it():
    t = np.linspace(0, 2 * np.pi, 60, endpoint=False)
    star = np.stack([(1 + 0.4 * np.cos(5 * t)) * np.cos(t), (1 + 0.4 * np.cos(5 * t)) * np.sin(t)], 1)
    pts, f = polygon_mesh(star)
    assert np.array_equal(pts[:60], star)
    area = 0.5 * np.sum(star[:, 0] * np.roll(star[:, 1], -1) - np.roll(star[:, 0], -1) * star[:, 1])
    p3 = np.concatenate([pts, np.zeros((len(pts), 1))], axis=1)
    assert triangle_areas(p3, f).sum() == pytest.approx(area, rel=1e-12)
    assert len(pts) > 120


def test_cotan_laplacian_of_a_flat_mesh_annihilates_linear_functions():
    p, f = disk_mesh(30)
    pts = np.concatenate([p, np.zeros((len(p), 1))], axis=1)
    L = cotan_laplacian(pts, f)
    lin = 2 * p[:, 0] - 3 * p[:, 1] + 1
    assert np.abs((L @ lin)[30:]).max() < 1e-12
    assert np.abs(L.sum(axis=1)).max() < 1e-12


def test_delaunay_flips_make_every_cotan_weight_non_negative():
    rng = np.random.default_rng(3)
    p, f = disk_mesh(40)
    p = p.copy()
    p[40:] += rng.normal(scale=0.01, size=(len(p) - 40, 2))
    pts = np.concatenate([p, np.zeros((len(p), 1))], axis=1)
    before = cotan_laplacian(pts, f)
    g = delaunay_flips(pts, f)
    L = cotan_laplacian(pts, g)
    from auszug.meshing.mesh import edge_counts

    e, fw, bw = edge_counts(g)
    inner = e[(fw + bw) == 2]
    assert np.asarray(L[inner[:, 0], inner[:, 1]]).max() <= 1e-12     # L_ij = -w_ij <= 0
    e0, fw0, bw0 = edge_counts(f)
    inner0 = e0[(fw0 + bw0) == 2]
    assert np.asarray(before[inner0[:, 0], inner0[:, 1]]).max() > 0     # there was something to flip
    assert triangle_areas(pts, g).sum() == pytest.approx(triangle_areas(pts, f).sum(), rel=1e-12)


def test_errors():
    with pytest.raises(GeometryError, match="at least 3 3D points"):
        minimal_surface(np.zeros((2, 3)))
    with pytest.raises(GeometryError, match="finite"):
        minimal_surface([[0, 0, 0], [1, 0, 0], [0, np.nan, 0]])
    with pytest.raises(GeometryError, match="repeated points"):
        minimal_surface([[0, 0, 0], [1, 0, 0], [1, 0, 0], [0, 1, 0]])
