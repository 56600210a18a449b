"""Rigid motions sampled at parameters (auszug.sweeps.motion): SE(3) log/exp, screw interpolation."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from auszug.errors import GeometryError
from auszug.sweeps.motion import Motion, screw_motion, se3_exp, se3_log


def test_log_exp_round_trip_on_random_maps():
    rng = np.random.default_rng(3)
    w = rng.normal(size=(50, 3))
    w *= (rng.uniform(0.0, 3.0, 50) / np.linalg.norm(w, axis=1))[:, None]
    v = rng.normal(size=(50, 3))
    r, t = se3_exp(w, v)
    assert np.allclose(np.linalg.det(r), 1.0, atol=1e-12)
    w2, v2 = se3_log(r, t)
    assert np.allclose(w2, w, atol=1e-10) and np.allclose(v2, v, atol=1e-9)


@pytest.mark.parametrize("pitch", [0.0, 0.07])
def test_screw_is_exact_between_sparse_knots(pitch):
    """A rotation (or screw) sampled at 3 knots is reproduced exactly at every parameter in between."""
    d, p = np.array([0.2, -0.3, 1.0]), np.array([0.4, 0.1, -0.2])
    knots = np.array([0.0, 1.3, 2.9])
    m = Motion(knots, *screw_motion(d, p, pitch, knots))
    t = np.linspace(0.0, 2.9, 37)
    r, tr = m.at(t)
    r0, t0 = screw_motion(d, p, pitch, t)
    assert np.abs(r - r0).max() < 1e-12 and np.abs(tr - t0).max() < 1e-12


def test_maps_are_rigid_and_hit_the_knots():
    rng = np.random.default_rng(5)
    r = Rotation.random(6, random_state=7).as_matrix()
    tr = rng.normal(size=(6, 3))
    m = Motion(np.arange(6.0), r, tr)
    ri, ti = m.at(np.arange(6.0))
    assert np.abs(ri - r).max() < 1e-12 and np.abs(ti - tr).max() < 1e-12
    rq, _ = m.at(rng.uniform(0, 5, 40))
    assert np.abs(np.einsum("kji,kjl->kil", rq, rq) - np.eye(3)).max() < 1e-12
    assert np.allclose(np.linalg.det(rq), 1.0, atol=1e-12)


def test_inverse_apply_undoes_apply_and_change_of_coordinates():
    rng = np.random.default_rng(1)
    knots = np.linspace(0, 2, 5)
    m = Motion(knots, *screw_motion([0, 1.0, 0], [1.0, 0, 0], 0.05, knots))
    x = rng.normal(size=(8, 3))
    t = rng.uniform(0, 2, 8)
    moved = np.stack([m.apply(x[i : i + 1], [t[i]])[0, 0] for i in range(8)])
    assert np.allclose(m.inverse_apply(moved, t), x, atol=1e-12)
    # the same motion seen in coordinates y = 3 x + c moves 3 x + c to 3 (R x + T) + c
    c = np.array([1.0, -2.0, 0.5])
    big = m.transformed(3.0, c)
    assert np.allclose(big.apply(3 * x + c, [0.7])[0], 3 * m.apply(x, [0.7])[0] + c, atol=1e-12)


def test_bad_motions_are_refused():
    with pytest.raises(GeometryError, match="increase"):
        Motion(np.array([0.0, 0.0]), np.stack([np.eye(3)] * 2), np.zeros((2, 3)))
    with pytest.raises(GeometryError, match="not a rotation"):
        Motion(np.array([0.0, 1.0]), np.stack([np.eye(3), np.diag([1.0, 1, -1])]), np.zeros((2, 3)))
    with pytest.raises(GeometryError, match="k >= 2"):
        Motion(np.array([0.0]), np.eye(3)[None], np.zeros((1, 3)))


@pytest.mark.parametrize("bad", [np.diag([1.0, 1.0, -1.0]), np.zeros((3, 3)), np.full((3, 3), np.nan)])
def test_se3_log_refuses_a_matrix_that_is_no_rotation(bad: np.ndarray) -> None:
    """A reflection, a singular matrix and NaNs are no rigid map: an error, not a twist."""
    good, t = se3_exp([0.1, -0.2, 0.3], [0.5, 0.0, -1.0])
    with pytest.raises(GeometryError, match="determinant"):
        se3_log(np.stack([good, bad]), np.stack([t, t]))
    w, _ = se3_log(good, t)
    assert np.allclose(w, [0.1, -0.2, 0.3], atol=1e-12)


def _at_numpy(m: Motion, t: object) -> tuple[np.ndarray, np.ndarray]:
    """Motion.at's definition in numpy: clamp, interval by searchsorted, the knot's map, the screw inside."""
    tt = np.clip(np.atleast_1d(np.asarray(t, float)), m.t[0], m.t[-1])
    i = np.clip(np.searchsorted(m.t, tt, side="right") - 1, 0, len(m.t) - 2)
    f = (tt - m.t[i]) / (m.t[i + 1] - m.t[i])
    r, tr = m.rotation[i], m.translation[i]
    at1 = f >= 1.0
    r[at1], tr[at1] = m.rotation[i[at1] + 1], m.translation[i[at1] + 1]
    inner = np.flatnonzero((f > 0.0) & ~at1)
    if len(inner):
        ii, ff = i[inner], f[inner]
        r1, t1 = m.rotation[ii + 1], m.translation[ii + 1]
        r0, t0 = m.rotation[ii], m.translation[ii]
        r0t = np.swapaxes(r0, -1, -2)
        w, v = se3_log(r0t @ r1, np.einsum("kij,kj->ki", r0t, t1 - t0))
        dr, dt = se3_exp(w * ff[:, None], v * ff[:, None])
        r[inner] = r0 @ dr
        tr[inner] = t0 + np.einsum("kij,kj->ki", r0, dt)
    return r, tr


def test_at_is_its_numpy_definition_bit_for_bit():
    """The compiled interval search of Motion.at: the same maps bit for bit as numpy's clip, searchsorted and
    fancy indexing give, at knots, between them, outside the domain, just below the last knot and at nan."""
    rng = np.random.default_rng(0)
    for trial in range(60):
        k = int(rng.integers(2, 40))
        t = np.unique(np.sort(rng.uniform(-3, 3, k))) if trial % 2 else np.arange(k) / 8.0
        if len(t) < 2:
            continue
        r, tr = screw_motion(rng.normal(size=3), rng.normal(size=3), float(rng.normal()),
                             np.cumsum(rng.uniform(0, 0.3, len(t))))
        m = Motion(t, r, tr)
        for q in (t, rng.uniform(-4, 4, 50), np.r_[(t[1:] + t[:-1]) / 2, t[0] - 1, t[-1] + 1, np.nextafter(t[-1], 0)],
                  t[::3], np.array([np.nan, t[1]]), np.zeros(0), 0.5):
            want, got = _at_numpy(m, q), m.at(q)
            for a, b in zip(want, got, strict=True):
                assert a.shape == b.shape and np.array_equal(a, b, equal_nan=True)
