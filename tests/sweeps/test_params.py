"""SweepParams (auszug.sweeps.params): validation of every growth setting, and that each one acts.

The growth settings (grow_steps, grow_share, grow_tolerance, grow_skip, grow_on_mesh, end_gap,
translation_step, translation_steps) are exercised on the clean extrusion of the base moulding: its true motion is a
translation along x, so the ribs a grown sweep may add and the parallel cuts a translational sweep
may take are known exactly (the mesh is 0.8 / diameter long along x).
"""

from __future__ import annotations

from functools import cache

import numpy as np
import pytest

from auszug.errors import GeometryError
from auszug.limits import LIMITS
from auszug.sweeps import DEFAULT, SweepParams, cut, normalise
from auszug.sweeps.fixtures import extruded, with_hole
from auszug.sweeps.general import grow_ribs, translational_patch
from auszug.sweeps.motion import Motion
from auszug.sweeps.patches import MeshTree

STEP = 0.02     # rib step of the seed motion (bounding-box diameters)


@pytest.mark.parametrize("name, value", [
    ("grow_steps", -1), ("grow_steps", LIMITS.sweep_steps + 1), ("grow_steps", 2.5), ("grow_steps", True),
    ("grow_steps", "10"),
    ("grow_share", 0.4), ("grow_share", 1.01), ("grow_share", float("nan")), ("grow_share", "0.9"),
    ("grow_tolerance", 0.0), ("grow_tolerance", 21.0), ("grow_tolerance", float("inf")),
    ("grow_skip", -1), ("grow_skip", 17), ("grow_skip", 1.5),
    ("grow_on_mesh", 0.05), ("grow_on_mesh", 1.2), ("grow_on_mesh", None),
    ("end_gap", 0.0), ("end_gap", 25.0), ("end_gap", float("nan")),
    ("rib_jump", 1.0), ("rib_jump", 0.5), ("rib_jump", float("nan")),
    ("twist_steps", -1), ("twist_steps", 65), ("twist_steps", 2.0), ("twist_steps", True),
    ("twist_tolerance", -1e-9), ("twist_tolerance", 0.01), ("twist_tolerance", float("nan")),
    ("tangent_window", -0.01), ("tangent_window", 1.5), ("tangent_window", float("nan")), ("tangent_window", "0.06"),
    ("tangent_switch", 0.5), ("tangent_switch", -1.0), ("tangent_switch", 2e6), ("tangent_switch", float("nan")),
    ("twist_window", -0.01), ("twist_window", 1.5), ("twist_window", float("nan")),
    ("piece_trim", 0.5), ("piece_trim", 101.0), ("piece_trim", float("inf")), ("piece_trim", "2"),
    ("corner_tolerance", -1e-4), ("corner_tolerance", 0.2), ("corner_tolerance", float("nan")),
    ("translation_step", 0.0), ("translation_step", -0.02), ("translation_step", 0.6),
    ("translation_steps", 0), ("translation_steps", LIMITS.sweep_steps + 1), ("translation_steps", 3.0),
    ("coarse_window", 0.005), ("coarse_window", -0.08), ("coarse_window", float("nan")), ("coarse_window", "0.08"),
    ("coarse_below", -0.1), ("coarse_below", 1.5), ("coarse_below", None),
    ("chord_slack", -0.01), ("chord_slack", 1.5), ("chord_slack", float("inf")),
    ("coverage_samples", -1), ("coverage_samples", 10_000_001), ("coverage_samples", 1e5),
    ("coverage_samples", True),
])
def test_bad_growth_settings_are_refused_with_what_was_expected(name, value):
    with pytest.raises(GeometryError, match=rf"sweep parameter {name} = .*: expected "):
        SweepParams(**{name: value})
    with pytest.raises(GeometryError, match=rf"sweep parameter {name} = "):
        DEFAULT.with_(**{name: value})


def test_the_coverage_samples_edges_are_accepted():
    assert SweepParams(coverage_samples=0).coverage_samples == 0
    assert SweepParams(coverage_samples=10_000_000).coverage_samples == 10_000_000


def test_the_step_limit_is_the_one_in_limits_and_its_edge_is_accepted():
    assert LIMITS.sweep_steps == 10_000
    p = SweepParams(grow_steps=LIMITS.sweep_steps, translation_steps=LIMITS.sweep_steps)
    assert p.grow_steps == p.translation_steps == LIMITS.sweep_steps
    with pytest.raises(GeometryError, match=r"LIMITS\.sweep_steps"):
        SweepParams(grow_steps=LIMITS.sweep_steps + 1)
    assert SweepParams(grow_steps=0).grow_steps == 0    # no growth along the path at all


def test_unknown_parameter_names_the_known_ones():
    with pytest.raises(GeometryError, match="unknown sweep parameter.*grow_step.*known:.*grow_steps"):
        DEFAULT.with_(grow_step=3)


@cache
def _extrusion(sigma=0.0, hole=False):
    """The extruded moulding (with a hole of radius 0.06 in the middle), its profile cut at x = x0 and a
    3-rib seed motion along x from there (x0 = 0, or -0.3 beside the hole)."""
    fx = extruded(sigma=sigma)
    if hole:
        fx = with_hole(fx)
    x0 = -0.3 if hole else 0.0
    mesh = normalise(fx.vertices, fx.faces)
    c = cut(mesh, np.array([[1.0, 0, 0]]), np.array([x0]))
    profile = c.curve(int(np.argmax(np.diff(c.curve_start))))
    t = np.arange(3.0)
    motion = Motion(t, np.repeat(np.eye(3)[None], 3, axis=0), np.outer(t, [STEP, 0, 0]))
    return fx, mesh, profile, motion


def _span(ribs):
    """Extent along x of the ribs' centroids."""
    x = ribs.mean(axis=1)[:, 0]
    return float(x.max() - x.min())


def test_grow_steps_bounds_the_ribs_added_at_each_end():
    fx, mesh, profile, motion = _extrusion()
    half = 0.5 * np.ptp(fx.vertices[:, 0])
    none = grow_ribs(mesh, profile, motion, DEFAULT.with_(grow_steps=0)).ribs
    two = grow_ribs(mesh, profile, motion, DEFAULT.with_(grow_steps=2)).ribs
    every = grow_ribs(mesh, profile, motion, DEFAULT).ribs
    assert len(none) == 3 and len(two) == 3 + 2 * 2
    assert _span(two) == pytest.approx(6 * STEP, abs=1e-9)
    # by default the growth runs to both ends of the mesh (the last step may be a half or a quarter)
    assert _span(every) >= 2 * half - 2 * STEP and _span(every) <= 2 * half + 1e-9
    # every rib lies on the mesh: the extrusion's cuts are exact copies of the profile
    assert np.abs(every[:, :, 1:] - profile[None, :, 1:]).max() <= 1e-9


def test_grow_tolerance_and_share_decide_where_a_noisy_sweep_stops():
    """With noise 1e-3 a strict tolerance (0.5 eps_prox for every point) stops the growth early
    (measured: 10 ribs, 0.24 along x); the defaults (2 eps_prox for 90 % of the points) grow it to
    the ends (45 ribs, 0.88 of the mesh's 0.91)."""
    fx, mesh, profile, motion = _extrusion(1e-3)
    strict = grow_ribs(mesh, profile, motion, DEFAULT.with_(grow_tolerance=0.5, grow_share=1.0)).ribs
    loose = grow_ribs(mesh, profile, motion, DEFAULT).ribs
    assert len(strict) < len(loose) / 3
    assert _span(loose) >= np.ptp(fx.vertices[:, 0]) - 2 * STEP


def test_translation_step_and_steps_set_the_parallel_cuts():
    fx, mesh, profile, motion = _extrusion()
    tree = MeshTree(mesh.vertices, mesh.faces)
    few = translational_patch(mesh, profile, motion, DEFAULT.with_(translation_steps=3), tree)
    wide = translational_patch(mesh, profile, motion, DEFAULT.with_(translation_step=0.05, translation_steps=3), tree)
    full = translational_patch(mesh, profile, motion, DEFAULT, tree)
    assert few is not None and wide is not None and full is not None
    # 3 cuts on each side of the first: 7 translations, 0.02 or 0.05 apart along x
    assert len(few.motion) == len(wide.motion) == 7
    assert np.allclose(np.diff(few.motion.translation[:, 0]), 0.02, atol=1e-9)
    assert np.allclose(np.diff(wide.motion.translation[:, 0]), 0.05, atol=1e-9)
    assert np.allclose(few.motion.rotation, np.eye(3))
    assert full.coverage > wide.coverage > few.coverage
    assert full.coverage >= 0.95


def test_grow_on_mesh_and_grow_skip_decide_whether_a_hole_is_crossed():
    """A hole of radius 0.06 in the middle of the extrusion, the seed beside it (x = -0.3): by default
    the ribs across the hole count the points over it as beyond the mesh and the growth reaches the
    far end; asking every point to be on the mesh stops it at the hole, unless steps may skip it
    (12 steps of 0.02 span its 0.12); so does a large ``end_gap`` (points over the hole then count
    as on the mesh, and far from it)."""
    fx, mesh, profile, motion = _extrusion(hole=True)
    right = 0.5 * np.ptp(fx.vertices[:, 0])
    reach = {}
    for name, p in [("default", DEFAULT), ("strict", DEFAULT.with_(grow_on_mesh=1.0, grow_skip=0)),
                    ("skip", DEFAULT.with_(grow_on_mesh=1.0, grow_skip=12)),
                    ("no gap", DEFAULT.with_(end_gap=20.0, grow_skip=0))]:
        reach[name] = float(grow_ribs(mesh, profile, motion, p).ribs.mean(axis=1)[:, 0].max())
    assert reach["default"] >= right - STEP and reach["skip"] >= right - STEP
    assert reach["strict"] <= -0.06 + STEP        # stopped before the hole (centred at x = 0)
    # with end_gap 20 (0.1 of the diameter) the points over the hole are taken as on the mesh, and
    # far from it: the step fails there too
    assert reach["no gap"] <= -0.06 + STEP


def test_with_scale_scales_the_lengths_along_a_cut_and_nothing_else():
    from dataclasses import fields

    p = DEFAULT.with_(l_min=0.16, eps_prox=0.003)
    q = p.with_scale(0.25)
    for f in fields(SweepParams):
        a, b = getattr(p, f.name), getattr(q, f.name)
        if f.name in SweepParams.PROFILE_LENGTHS:
            assert b == a * 0.25, f.name
        elif f.name == "kappa_floor":
            assert b == a / 0.25
        else:
            assert b == a, f.name
    assert p.with_scale(1.0) == p
    for bad in (0, -0.5, 1.5, float("nan"), True):
        with pytest.raises(GeometryError, match="scale"):
            p.with_scale(bad)
