"""Faces on the whole corpus: every loop filled, converged, not larger than the flat fill, boundary on
the curves, symmetric families exact."""

from __future__ import annotations

import math

import numpy as np
import pytest

from auszug.meshing.faces import common_group, network_faces
from auszug.meshing.minimal import RESIDUAL_TOL
from tests.meshing.cases import ALL, IDS, network


@pytest.mark.parametrize("path", ALL, ids=IDS)
def test_every_corpus_drawing_gets_converged_faces(path):
    net = network(path)
    fs = network_faces(net, resolution=64)
    assert fs.converged, [f.surface.residual for f in fs.faces]
    assert fs.residual < RESIDUAL_TOL
    for fc in fs.faces:
        s = fc.surface
        if not math.isnan(fc.flat_area):
            assert s.area <= fc.flat_area * (1 + 1e-9)
        assert s.area <= s.start_area * (1 + 1e-12)
        # the boundary vertices are the loop's own boundary points (exactly on its curves): for a
        # face mapped from its family's solve, the same point set in another order, except that at
        # a corner where two curves meet only within the height tolerance the point may come from
        # the other curve
        g = fc.loop.graph
        b, corners = fc.loop.boundary(64)
        got = fc.vertices[fc.boundary]
        assert len(got) == len(b)
        d = np.linalg.norm(got[:, None] - b[None], axis=2).min(axis=1)
        off = d > 1e-12 * g.size
        assert off.sum() <= len(corners) and d.max() <= g.meet_tol + 1e-12 * g.size


def test_faces_of_one_family_are_images_of_each_other():
    net = network("web/U.XI.28.uc")
    fs = network_faces(net, resolution=48)
    assert len(fs.faces) == 8 and fs.families == 2
    mats, c = common_group(net)
    assert len(mats) == 8
    for fam in range(fs.families):
        members = [f for f in fs.faces if f.family == fam]
        areas = [float(np.sum(np.linalg.norm(np.cross(f.vertices[f.faces[:, 1]] - f.vertices[f.faces[:, 0]],
                                                       f.vertices[f.faces[:, 2]] - f.vertices[f.faces[:, 0]]),
                                              axis=1)) / 2) for f in members]
        assert max(areas) - min(areas) < 1e-12


def test_face_mesh_parts_and_orientation():
    fs = network_faces(network("teaching-sheet/tn-1.uc"), resolution=48)
    m = fs.mesh()
    assert sorted(p.name for p in m.parts)[:2] == ["face0/0", "face0/1"]
    assert all(p.kind == "face" for p in m.parts)
    assert m.area == pytest.approx(sum(f.area for f in fs.faces), rel=1e-12)


def test_no_loops_no_faces():
    fs = network_faces(network("web/U.XI.29.uc"))
    assert fs.faces == () and fs.converged and fs.residual == 0.0 and fs.mesh().n_faces == 0
