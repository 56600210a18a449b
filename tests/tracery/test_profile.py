"""Profiles: lines and arcs in the (inset, depth) plane that never turn back."""

from __future__ import annotations

import math

import numpy as np
import pytest

from auszug.meshing import Profile
from auszug.tracery import Moulding, ParameterError
from auszug.tracery.profile import profile_from_data

Q = math.tan(math.pi / 8)  # the bulge of a quarter circle


def test_arcs_from_bulges_are_exact_quarter_circles():
    p = Moulding("round", [[0, 0], [1, 1], [1, 2]], bulge=[Q, 0])
    pts = p.sample(16)[:17]
    # a counter-clockwise quarter circle from (0, 0) to (1, 1): centre (0, 1)
    assert np.allclose(np.hypot(pts[:, 0], pts[:, 1] - 1), 1.0, atol=1e-12)
    assert p.sharp(16).tolist() == [True] + [False] * 16 + [True]  # tangent to the wall below: smooth
    hollow = Moulding("hollow", [[0, 0], [1, 1], [1, 2]], bulge=[-Q, 0])
    assert hollow.sharp(4)[4]  # the cavetto meets the wall with a kink
    assert (p.depth, p.inset) == (2.0, 1.0)


@pytest.mark.parametrize("points, bulge, wall", [
    ([[0, 0]], None, False),
    ([[0.1, 0], [1, 1]], None, False),  # not starting at the opening's edge
    ([[0, 0], [1, 1], [0.5, 2]], None, False),  # turns back
    ([[0, 0], [1, 1]], [1.5], False),  # more than a half circle
    ([[0, 0], [1, 1]], [0.5, 0.5], False),  # one bulge per segment
    ([[-1, 0], [0, 0.5]], None, True),  # a wall profile must end at (0, 1)
    ([[0, 0], [1, 1], [0, 1]], None, True),  # and have s <= 0
])
def test_invalid_profiles(points, bulge, wall):
    with pytest.raises(ParameterError):
        Moulding("p", points, bulge, wall)


def test_from_data_and_back():
    p = profile_from_data("x", {"points": [[0, 0], [0.5, 0.5], [0.5, 1]], "bulge": [-0.2, 0]})
    q = profile_from_data("x", p.to_data())
    assert p == q and hash(p) == hash(q)
    assert profile_from_data("y", [[0, 0], [0, 1]]).depth == 1.0
    with pytest.raises(ParameterError):
        profile_from_data("z", {"pts": []})


def test_a_moulding_is_the_one_meshing_profile_in_its_tracery_role():
    m = profile_from_data("round", {"points": [[0, 0], [0.6, 0.6], [0.6, 1.2]], "bulge": [Q, 0]})
    assert isinstance(m.profile, Profile) and not m.profile.closed and m.profile.name == "round"
    # the quarter round's exact length: a quarter circle of radius 0.6 plus the 0.6 fillet
    assert m.profile.length == pytest.approx(0.3 * math.pi + 0.6, rel=1e-14)
    assert np.array_equal(m.sample(4), m.profile.sample(per_arc=4))
