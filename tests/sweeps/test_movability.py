"""Movability (Eq. 3-5, Alg. 1) and the search for movable cuts (sec. 1.3), with known answers."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from auszug.errors import GeometryError
from auszug.sweeps.cut import Cuts, cut
from auszug.sweeps.fixtures import extruded, moulding_along_cubic, revolved
from auszug.sweeps.mesh import normalise
from auszug.sweeps.movability import movability, velocities, velocity_state
from auszug.sweeps.params import DEFAULT, SweepParams
from auszug.sweeps.planes import initial_planes
from auszug.sweeps.search import good_planes, search_planes


def _one_curve(points, normals, closed):
    p = np.asarray(points, float)
    return Cuts(np.array([[0, 0, 1.0]]), np.zeros(1), p, np.asarray(normals, float), np.zeros(len(p), np.int64),
                np.array([0, len(p)]), np.zeros(1, np.int64), np.array([closed]))


def _on_cone(t, k=0.5):
    """A wavy curve on the cone z = k rho about z, with the cone's unit normals."""
    rho = 0.3 + 0.05 * np.sin(3 * t)
    x = np.column_stack([rho * np.cos(t), rho * np.sin(t), k * rho])
    n = np.column_stack([np.cos(t), np.sin(t), -k + 0 * t]) / np.hypot(1, k)
    return x, n


def test_velocity_state_of_a_screw_motion():
    # points of a helicoid's profile: the screw motion about z with pitch h moves them within it
    rng = np.random.default_rng(3)
    h = 0.2
    r = rng.uniform(0.1, 0.5, 40)
    phi = rng.uniform(0, 2 * np.pi, 40)
    x = np.column_stack([r * np.cos(phi), r * np.sin(phi), h * phi])
    # helicoid x(r, phi) = (r cos, r sin, h phi): normal = x_r x x_phi
    xr = np.column_stack([np.cos(phi), np.sin(phi), 0 * phi])
    xp = np.column_stack([-r * np.sin(phi), r * np.cos(phi), h + 0 * phi])
    n = np.cross(xr, xp)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    c, lam = velocity_state(x, n)
    assert lam[0] < 1e-14 and lam[1] > 1e-4
    want = np.array([0, 0, 1.0, 0, 0, h]) / np.hypot(1, h)
    assert np.allclose(np.abs(c @ want), 1, atol=1e-10)
    assert np.allclose(np.einsum("ij,ij->i", velocities(c, x), n), 0, atol=1e-10)


def test_every_cut_of_an_extrusion_moves_by_the_translation():
    fx = extruded(n_profile=40, n_path=40)
    m = normalise(fx.vertices, fx.faces)
    c = cut(m, [[1.0, 0, 0], [0.8, 0, 0.6], [0.6, 0.0, 0.8]], [0.0, 0.02, 0.05])
    mv = movability(c)
    # the oblique cuts move by the translation along x only; the cut across (normals in its own
    # plane) also by rotations about axes in that plane: a 3-dimensional null space
    assert np.abs(np.abs(mv.velocity[1:, 3]) - 1).max() < 1e-9
    assert np.abs(mv.eigenvalues[0, :3]).max() < 1e-12 and mv.eigenvalues[0, 3] > 1e-3
    assert np.abs(mv.velocity[0, [0, 4, 5]]).max() < 1e-9
    assert mv.f.max() < 1e-18 and np.all(mv.weights > 1 - 1e-12)
    # one run per curve that reaches l_min, the whole curve, gliding energy zero
    for r in range(mv.n_runs):
        k = mv.run_curve[r]
        assert mv.run_start[r] == 0 and mv.run_end[r] == c.curve_start[k + 1] - c.curve_start[k] - 1
        assert np.isclose(mv.run_length[r], c.curve_lengths()[k])
    assert mv.run_energy.max() < 1e-30


def test_movability_is_invariant_under_rigid_motion():
    fx = revolved(n_profile=30, n_path=40, sigma=5e-4)
    rot = Rotation.from_rotvec([0.4, 0.2, -0.9])
    m0 = normalise(fx.vertices, fx.faces)
    m1 = normalise(rot.apply(fx.vertices), fx.faces)
    k = m0.scale / m1.scale
    shift = m1.vertices[0] - k * rot.apply(m0.vertices[0])
    n = np.array([[0.3, 0.5, 0.81], [1.0, 0.0, 0.0]])
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    d = np.array([0.01, 0.1])
    c0 = cut(m0, n, d)
    c1 = cut(m1, rot.apply(n), k * d + rot.apply(n) @ shift)
    # f and the weights are angles: invariant under the motion; the scale changes the velocity
    # mix a little (||C|| = 1 weighs rotation against translation by the diameter), so compare loosely
    p0 = DEFAULT.with_(speed_floor=0.0)
    f0, f1 = movability(c0, p0).f, movability(c1, p0).f
    assert len(f0) == len(f1)
    assert np.allclose(np.sort(f0), np.sort(f1), atol=1e-3)


def test_weight_iteration_drops_a_bad_stretch_and_runs_wrap_around_a_closed_curve():
    # a wavy closed curve on a cone about z (moves by rotation about z only); normals spoiled on a stretch
    t = np.linspace(0, 2 * np.pi, 200, endpoint=False)
    x, n = _on_cone(t)
    bad = slice(95, 101)  # (Alg. 1 starts from equal weights: a tenth of bad normals would spoil the first fit)
    n[bad] = np.column_stack([-np.sin(t), np.cos(t), 0 * t])[bad]  # along the motion: f = 1
    mv = movability(_one_curve(x, n, True), DEFAULT.with_(gap=0.0, max_sliding=1.0))  # it slides: allow that
    assert np.all(mv.weights[bad] < 0.01) and np.all(np.delete(mv.weights, np.r_[bad]) > 0.99)
    assert mv.n_runs == 1
    assert (mv.run_start[0], mv.run_end[0]) == (101, 94)  # wraps over the start
    seg = np.linalg.norm(np.diff(x[np.r_[101:200, 0:95]], axis=0), axis=1)
    assert np.isclose(mv.run_length[0], seg.sum())
    idx = mv.run_indices(_one_curve(x, n, True), 0)
    assert len(idx) == 194 and idx[0] == 101 and idx[-1] == 94
    # the velocity state is the rotation about z
    assert abs(abs(mv.velocity[0, 2]) - 1) < 1e-3


def test_short_gaps_are_bridged_long_ones_are_not():
    t = np.linspace(0, np.pi, 300)
    x, n = _on_cone(t)
    n[150] = [-np.sin(t[150]), np.cos(t[150]), 0]  # one bad vertex
    p = DEFAULT.with_(gap=0.01, max_sliding=1.0)
    assert movability(_one_curve(x, n, False), p).n_runs == 1
    assert movability(_one_curve(x, n, False), p.with_(gap=0.0)).n_runs == 2


def test_sliding_and_flat_runs_are_dropped():
    # a helix on the surface whose normals are its binormals moves only by sliding along itself
    a, h = 0.3, 0.1
    t = np.linspace(0, 3, 200)
    x = np.column_stack([a * np.cos(t), a * np.sin(t), h * t])
    n = np.column_stack([h * np.sin(t), -h * np.cos(t), a + 0 * t]) / np.hypot(a, h)
    assert movability(_one_curve(x, n, False), DEFAULT.with_(max_sliding=1.0, min_spread=0.0)).n_runs == 1
    mv = movability(_one_curve(x, n, False))
    assert mv.n_runs == 0
    # a straight line in a plane: every in-plane motion glides; its normals do not turn
    line = np.column_stack([np.linspace(-0.3, 0.3, 100), np.zeros(100), np.zeros(100)])
    up = np.tile([0, 0, 1.0], (100, 1))
    assert movability(_one_curve(line, up, False), DEFAULT.with_(max_sliding=1.0)).n_runs == 0
    assert movability(_one_curve(line, up, False), DEFAULT.with_(max_sliding=1.0, min_spread=0.0)).n_runs == 1


@pytest.mark.parametrize("sigma", [0.0, 5e-4])
def test_true_profile_planes_of_a_general_sweep_are_movable_whole(sigma):
    fx = moulding_along_cubic(sigma=sigma)
    m = normalise(fx.vertices, fx.faces)
    c = cut(m, fx.planes[:, :3], fx.planes[:, 3])
    mv = movability(c)
    # each true profile plane cuts the mesh in the profile; it is one movable run, whole
    on_profile = c.curve_lengths() > 0.9 * fx.profile_length
    assert on_profile.sum() == len(fx.planes)
    runs = np.zeros(c.n_curves, int)
    np.add.at(runs, mv.run_curve, 1)
    assert np.all(runs[on_profile] == 1)
    full = mv.run_length / c.curve_lengths()[mv.run_curve]
    assert full.min() > 0.999
    assert np.median(mv.run_energy) < (1e-16 if sigma == 0 else 1e-5)


def test_good_planes_percentile():
    e = np.array([5.0, np.inf, 1.0, 3.0, 2.0, np.inf, 4.0, 0.5, 6.0, 7.0])
    good, thr = good_planes(e, 20.0)
    assert good.tolist() == [2, 7] and thr == 1.0
    assert good_planes(np.full(4, np.inf), 50.0)[0].size == 0


def test_search_refines_around_good_planes():
    fx = extruded(n_profile=30, n_path=40)
    m = normalise(fx.vertices, fx.faces)
    p = DEFAULT.with_(refinements=2, percentile=3.0)
    s = search_planes(m, p)
    assert s.rounds[0] == len(initial_planes(m.vertices, 4, 0.055)[1]) and len(s.rounds) == 3
    assert s.n_planes == sum(s.rounds) == len(s.plane_energy)
    # every refined plane lies in a box around a plane of an earlier round
    ang = np.degrees(np.arccos(np.clip(np.abs(s.cuts.plane_normals[s.plane_round == 1] @
                                              s.cuts.plane_normals[s.plane_round == 0].T), 0, 1)))
    assert ang.min(1).max() <= np.sqrt(2) * p.angle0 + 1e-9
    # the good planes are the lowest percentile of all planes
    assert len(s.good) == round(s.n_planes * 0.03)
    assert np.all(s.plane_energy[s.good].max() <= np.sort(s.plane_energy)[len(s.good) - 1])
    assert len(s.good_runs) >= len(s.good)


def test_bad_parameters_say_what_was_expected():
    with pytest.raises(GeometryError, match="refine_steps = 4: expected odd"):
        SweepParams(refine_steps=4)
    with pytest.raises(GeometryError, match="unknown sweep parameter"):
        DEFAULT.with_(betta=3)
    with pytest.raises(GeometryError, match="grow = 'yes': expected true or false"):
        DEFAULT.with_(grow="yes")


def test_a_loop_that_also_glides_out_of_its_plane_is_not_dropped_as_sliding():
    """A round loop in z = 0 whose normals tilt by ``eps sin 3t`` out of its plane: the turn about
    z glides it exactly and slides (share 1), so Eq. 4 returns the turn; a translation along z
    glides it within Alg. 1's tolerance when eps is small (mean f = eps^2 / 2 against f* = 0.035)
    and does not slide. ``loop_sliding`` keeps such a whole closed run, a loop that glides only by
    its turn (eps 0.2: mean f 0.02, 0.56 f*) stays dropped, and open runs are judged as before."""
    t = np.linspace(0, 2 * np.pi, 120, endpoint=False)
    x = 0.1 * np.column_stack([np.cos(t), np.sin(t), 0 * t])
    for eps, kept in ((0.05, True), (0.2, False)):
        n = np.column_stack([np.cos(t), np.sin(t), eps * np.sin(3 * t)])
        n /= np.linalg.norm(n, axis=1, keepdims=True)
        curve = _one_curve(x, n, True)
        off = movability(curve, DEFAULT.with_(loop_sliding=0.0))
        assert off.n_runs == 0 and abs(abs(off.velocity[0, 2]) - 1) < 1e-6       # Eq. 4: the turn about z
        assert np.all(off.weights > 0.99)                                         # it glides the whole loop
        on = movability(curve)
        assert on.n_runs == int(kept)
        if kept:
            assert on.run_length[0] == pytest.approx(2 * np.pi * 0.1, rel=1e-3)
            assert on.run_sliding[0] <= DEFAULT.loop_sliding
        # the same points as an open curve (half the loop): no second look, dropped as before
        half = _one_curve(x[:60], n[:60], False)
        assert movability(half).n_runs == movability(half, DEFAULT.with_(loop_sliding=0.0)).n_runs == 0
    with pytest.raises(GeometryError):
        SweepParams(loop_sliding=-0.1)
