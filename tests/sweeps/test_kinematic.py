"""Kinematic surfaces (auszug.sweeps.kinematic): every cut moves; the axis or direction is the answer."""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from auszug.sweeps import cut, initial_planes, movability, normalise
from auszug.sweeps.fixtures import bumps, extruded, moulding_along_cubic, revolved
from auszug.sweeps.kinematic import axis_angle, kinematic_axis, motion_of


@cache
def _axis(name, sigma, turn=None):
    fx = {"revolved": revolved, "extruded": extruded, "cubic": moulding_along_cubic, "bumps": bumps}[name](sigma=sigma)
    v = fx.vertices if turn is None else Rotation.from_rotvec(turn).apply(fx.vertices)
    m = normalise(v, fx.faces)
    c = cut(m, *initial_planes(m.vertices, 4, 0.055))
    return fx, m, kinematic_axis(c, movability(c))


@pytest.mark.parametrize("sigma", [0.0, 5e-4, 1e-3])
def test_surface_of_revolution_axis_within_0_2_degrees(sigma):
    fx, m, k = _axis("revolved", sigma)
    assert k.kind == "rotation"
    assert axis_angle(k.direction, fx.axis_direction) <= (0.01 if sigma == 0 else 0.2)
    # the fixture's axis passes through its axis point (normalised coordinates of the fixture = of m)
    dv = fx.axis_point - k.point
    assert np.linalg.norm(dv - (dv @ k.direction) * k.direction) <= 2e-3
    assert k.agreement >= (0.999 if sigma == 0 else 0.95)


@pytest.mark.parametrize("sigma", [0.0, 5e-4, 1e-3])
def test_extrusion_direction_within_0_2_degrees(sigma):
    fx, m, k = _axis("extruded", sigma)
    assert k.kind == "translation" and k.point is None
    assert axis_angle(k.direction, fx.axis_direction) <= (1e-6 if sigma == 0 else 0.2)
    assert k.agreement >= (0.999 if sigma == 0 else 0.9)


def test_axis_follows_a_rigid_motion_of_the_mesh():
    turn = (0.3, -0.8, 0.5)
    fx, m, k = _axis("revolved", 5e-4, turn)
    assert axis_angle(k.direction, Rotation.from_rotvec(turn).apply(fx.axis_direction)) <= 0.2


@pytest.mark.parametrize("name", ["cubic", "bumps"])
def test_no_kinematic_motion_on_a_general_sweep_or_bumps(name):
    for sigma in (0.0, 5e-4):
        _, _, k = _axis(name, sigma)
        assert k.agreement < 0.25


def test_motion_of_screw_and_translation():
    axis = np.array([0, 0.6, 0.8])
    p = np.array([0.1, 0.2, -0.15])
    c = np.r_[axis, np.cross(p, axis) + 0.3 * axis]
    kind, d, q, h = motion_of(c / np.linalg.norm(c))
    assert kind == "screw" and np.isclose(h, 0.3) and axis_angle(d, axis) < 1e-9
    dq = q - p
    assert np.linalg.norm(dq - (dq @ d) * d) < 1e-12
    assert motion_of([0.01, 0, 0, 0, 1.0, 0])[0] == "translation"
    assert motion_of([0.2, 0, 0, 0, 1.0, 0])[0] == "rotation"


@pytest.mark.parametrize("ext", ["stl", "obj", "ply", "glb"])
def test_axis_of_a_mesh_read_from_a_file(tmp_path, ext):
    """The way a user gets there: a mesh file through auszug.formats, then the sweeps stages on (V, F)."""
    from auszug.formats import load, save
    from auszug.meshing import Mesh

    fx = revolved(n_profile=40, n_path=60)
    path = save(Mesh(fx.vertices * 3.0 + [1.0, 2.0, 3.0], fx.faces), tmp_path / f"base.{ext}", kind="mesh")
    mesh = load(path, kind="mesh")
    m = normalise(mesh.vertices, mesh.faces)
    c = cut(m, *initial_planes(m.vertices, 4, 0.055))
    k = kinematic_axis(c, movability(c))
    assert k.kind == "rotation" and k.agreement > 0.95
    # float32 files (STL, PLY, glTF) cost a little accuracy; glTF turns z up into y up only in its scene graph
    assert axis_angle(k.direction, fx.axis_direction) <= 0.05
