"""Pictures: the rasteriser draws what faces the eye, nearest first."""

from __future__ import annotations

import numpy as np

from auszug.tracery.render import shade, view_matrix


def test_view_matrix_is_a_rotation():
    r = view_matrix(-25.0, 12.0)
    assert np.allclose(r @ r.T, np.eye(3)) and np.linalg.det(r) > 0
    assert np.allclose(view_matrix(0, 0) @ [0, -1, 0], [0, 0, 1])  # the default eye looks along +y


def test_nearest_face_wins_and_back_faces_are_culled():
    # two squares facing the eye (-y), the near one (y = -1) smaller and in front
    sq = lambda y, s: np.array([[-s, y, -s], [s, y, -s], [s, y, s], [-s, y, s]])  # noqa: E731  (a one-line helper)
    v = np.concatenate([sq(0.0, 1.0), sq(-1.0, 0.5)])
    f = np.array([[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]])
    img = shade(v, f, 64, 64, azimuth=0, elevation=0, depth_cue=0.5, supersample=1)
    centre, corner = img[32, 32].astype(int), img[6, 6].astype(int)
    assert (centre > corner).all()  # the near square is brighter (depth cue)
    assert (img[0, 0] == 255).all()  # background
    back = shade(v, f[:, ::-1], 64, 64, azimuth=0, elevation=0, supersample=1)
    assert (back == 255).all()  # all faces turned away
