"""Rotation-minimising frames: orthonormal, continuous, equal to sequential double reflection,
twist-free on a helix, end targets met with the twist spread, invariant under rigid motions."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from auszug.errors import GeometryError
from auszug.meshing.frames import reference_basis, rmf_angles, sweep_frames


def helix(n: int = 400, turns: float = 2.0, r: float = 1.0, c: float = 0.5):
    s = np.linspace(0.0, 2 * np.pi * turns, n)
    p = np.stack([r * np.cos(s), r * np.sin(s), c * s], axis=1)
    t = np.stack([-r * np.sin(s), r * np.cos(s), np.full(n, c)], axis=1)
    return p, t / np.linalg.norm(t, axis=1, keepdims=True)


def double_reflection(x, t, r0):
    """The textbook sequential double-reflection method (Wang et al. 2008), for reference."""
    r = [np.asarray(r0, dtype=float)]
    for i in range(len(x) - 1):
        v1 = x[i + 1] - x[i]
        c1 = v1 @ v1
        rl = r[-1] - 2 / c1 * (v1 @ r[-1]) * v1
        tl = t[i] - 2 / c1 * (v1 @ t[i]) * v1
        v2 = t[i + 1] - tl
        c2 = v2 @ v2
        r.append(rl - 2 / c2 * (v2 @ rl) * v2 if c2 > 1e-30 else rl)
    return np.array(r)


def check_orthonormal(f):
    dots = [np.einsum("ij,ij->i", a, b) for a, b in ((f.tangent, f.width), (f.tangent, f.depth), (f.width, f.depth))]
    assert max(np.abs(d).max() for d in dots) < 1e-12
    for v in (f.tangent, f.width, f.depth):
        assert np.abs(np.linalg.norm(v, axis=1) - 1).max() < 1e-12
    assert np.allclose(np.cross(f.width, f.depth), f.tangent, atol=1e-12)   # (W, D, T) right-handed


def test_reference_basis_is_orthonormal_and_right_handed_everywhere():
    rng = np.random.default_rng(1)
    t = rng.normal(size=(1000, 3))
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    t[:4] = [[0, 0, 1], [0, 0, -1], [1, 0, 0], [0, -1, 0]]
    a, b = reference_basis(t)
    assert np.allclose(np.cross(t, a), b, atol=1e-12)
    assert np.abs(np.einsum("ij,ij->i", a, t)).max() < 1e-12


def test_vectorised_frames_equal_the_sequential_double_reflection():
    p, t = helix()
    f = sweep_frames(p, t, [1.0, 0.0, 0.0])
    ref = double_reflection(p, t, f.width[0])
    assert np.abs(ref - f.width).max() < 1e-12
    check_orthonormal(f)


def test_frames_do_not_turn_about_the_tangent_on_a_helix():
    p, t = helix(2000)
    f = sweep_frames(p, t, [1.0, 0.0, 0.0])
    dw = np.diff(f.width, axis=0)
    ds = np.diff(f.arclength)
    twist_rate = np.einsum("ij,ij->i", dw, 0.5 * (f.depth[1:] + f.depth[:-1])) / ds
    assert np.abs(twist_rate).max() < 1e-5         # rotation-minimising: dW/ds has no D part
    angle = np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", f.width[1:], f.width[:-1]), -1, 1)))
    assert angle.max() < 0.5                        # continuous


def test_a_straight_line_keeps_its_frame():
    z = np.linspace(0, 3, 7)
    p = np.stack([0 * z, 0 * z, z], 1)
    assert rmf_angles(p, np.tile([0.0, 0.0, 1.0], (7, 1))).tolist() == [0.0] * 7


@pytest.mark.parametrize("period", [math.pi, math.pi / 2])
def test_end_targets_are_met_and_the_twist_is_spread_linearly(period):
    p, t = helix(300, turns=0.7)
    free = sweep_frames(p, t, [1.0, 0.0, 0.0])
    start, end = np.array([0.0, 0.0, 1.0]), np.array([0.3, 0.2, 0.9])
    f = sweep_frames(p, t, [1.0, 0.0, 0.0], start, end, period)
    check_orthonormal(f)

    def meets(w, tan, target):
        v = target - (target @ tan) * tan
        v /= np.linalg.norm(v)
        ang = math.atan2(np.cross(v, w) @ tan, v @ w)
        return abs((ang + period / 2) % period - period / 2) < 1e-9

    assert meets(f.width[0], f.tangent[0], start) and meets(f.width[-1], f.tangent[-1], end)
    assert abs(f.twist) <= period / 2 + 1e-12
    # the angle between the free and the twisted frame grows linearly in arc length
    rel = np.arctan2(np.einsum("ij,ij->i", np.cross(free.width, f.width), f.tangent),
                     np.einsum("ij,ij->i", free.width, f.width))
    rel = np.unwrap(rel)
    lin = rel[0] + (rel[-1] - rel[0]) * f.arclength / f.arclength[-1]
    assert np.abs(rel - lin).max() < 1e-9


def test_one_end_target_turns_the_whole_frame_without_twist():
    p, t = helix(200, turns=0.5)
    f = sweep_frames(p, t, [1.0, 0.0, 0.0], end_target=[0.0, 1.0, 0.0])
    assert f.twist == 0.0
    free = sweep_frames(p, t, f.width[0])
    assert np.abs(free.width - f.width).max() < 1e-12


@settings(max_examples=25, deadline=None)
@given(st.floats(-3, 3), st.floats(-3, 3), st.floats(-3, 3), st.floats(-5, 5), st.floats(-5, 5), st.floats(-5, 5))
def test_frames_move_with_the_curve_under_rigid_motions(a, b, c, dx, dy, dz):
    from scipy.spatial.transform import Rotation

    rot = Rotation.from_euler("xyz", [a, b, c]).as_matrix()
    p, t = helix(120, turns=0.6)
    f = sweep_frames(p, t, [1.0, 0.0, 0.0])
    g = sweep_frames(p @ rot.T + [dx, dy, dz], t @ rot.T, rot @ [1.0, 0.0, 0.0])
    assert np.abs(g.width - f.width @ rot.T).max() < 1e-9
    assert np.abs(g.depth - f.depth @ rot.T).max() < 1e-9


def test_errors():
    p, t = helix(10)
    with pytest.raises(GeometryError, match="parallel to the curve's tangent"):
        sweep_frames(p, t, t[0])
    with pytest.raises(GeometryError, match="at least 2 samples"):
        sweep_frames(p[:1], t[:1], [1.0, 0, 0])
