"""Mesh kernels: areas, volumes, closedness, manifold vertices, welding, parts."""

from __future__ import annotations

import numpy as np
import pytest

from auszug.errors import GeometryError
from auszug.meshing.mesh import Mesh, Part, boundary_edges, concatenate, edge_counts, is_closed, weld

TET_V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
TET_F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def test_tetrahedron_measures():
    m = Mesh(TET_V, TET_F)
    assert m.is_watertight and m.is_manifold
    assert m.volume == pytest.approx(1 / 6, rel=1e-15)
    assert m.area == pytest.approx(1.5 + np.sqrt(3) / 2, rel=1e-15)
    assert Mesh(TET_V, TET_F[:, ::-1]).volume == pytest.approx(-1 / 6, rel=1e-15)


def test_volume_is_translation_invariant_far_from_the_origin():
    assert Mesh(TET_V + 1e6, TET_F).volume == pytest.approx(1 / 6, rel=1e-9)


def test_open_and_inconsistent_meshes_are_not_watertight():
    assert not is_closed(TET_F[:3])
    flipped = TET_F.copy()
    flipped[0] = flipped[0, ::-1]
    assert not is_closed(flipped)
    assert boundary_edges(TET_F[:3]).shape == (3, 2)
    e, fw, bw = edge_counts(TET_F)
    assert len(e) == 6 and np.all(fw == 1) and np.all(bw == 1)


def test_two_tetrahedra_sharing_only_a_vertex_are_not_manifold():
    v = np.concatenate([TET_V, TET_V[1:] * -1])
    f = np.concatenate([TET_F, np.array([[0, 5, 4], [0, 4, 6], [0, 6, 5], [4, 5, 6]])])
    m = Mesh(v, f)
    assert m.is_watertight and not m.is_manifold


def test_weld_merges_duplicates_and_drops_collapsed_faces():
    v = np.concatenate([TET_V, TET_V])
    f = np.concatenate([TET_F[:2], TET_F[2:] + 4, [[0, 4, 1]]])
    vv, ff = weld(v, f)
    assert len(vv) == 4 and len(ff) == 4 and is_closed(ff)


def test_parts_and_concatenate():
    a = Mesh(TET_V, TET_F, (Part("a", "member", 0, "r0", (0, 4), (0, 4)),))
    b = Mesh(TET_V + 2, TET_F, (Part("b", "face", 1, "0", (0, 4), (0, 4)),))
    m = concatenate([a, b])
    assert [p.name for p in m.parts] == ["a", "b"]
    assert m.parts[1].vertices == (4, 8) and m.parts[1].faces == (4, 8)
    assert np.array_equal(m.part("b").vertices, TET_V + 2)
    assert m.select(["face"]).n_faces == 4
    with pytest.raises(KeyError, match="no part 'c'"):
        m.part("c")


def test_indices_out_of_range_are_refused():
    with pytest.raises(GeometryError, match="face indices must lie in 0..3"):
        Mesh(TET_V, TET_F + 1)


def test_weld_merges_close_vertices_wherever_they_lie():
    """Points within tol merge even when a grid of cell tol would split them (0.5 tol apart across a
    cell boundary), chains of close points become one, and collapsed faces go."""
    from auszug.meshing.mesh import weld

    tol = 1e-6
    v = [[0.5e-6 - 1e-9, 0, 0], [0.5e-6 + 1e-9, 0, 0], [1, 0, 0], [0, 1, 0], [1, 0, 0.9e-6], [1, 0, 1.8e-6]]
    out, f = weld(v, [[0, 2, 3], [1, 3, 2], [0, 1, 2], [2, 4, 5]], tol)
    assert len(out) == 3                        # {0, 1}, {2, 4, 5} (a chain), {3}
    assert f.tolist() == [[0, 1, 2], [0, 2, 1]]  # the faces between merged vertices collapsed
    np.testing.assert_array_equal(out[0], v[0])  # a group keeps its first vertex
