"""Applying styles: regions per group and depth, recursion, congruent templates, errors with paths."""

from __future__ import annotations

import numpy as np
import pytest

from auszug.geometry.offset import is_closed, signed_area
from auszug.tracery import ParameterError, build, builtin_style, refine, structure
from tests.tracery.cases import PAPER


def _counts(t):
    out = {}
    for r in t.regions:
        out[r.group] = out.get(r.group, 0) + 1
    return out


def test_structure_is_the_papers_eight_polygons():
    t = structure(PAPER)
    assert [r.group for r in t.regions] == ["arch", "sub-arch", "sub-arch", "circle"] + ["fillet"] * 4
    assert [r.role for r in t.regions] == ["frame"] + ["light"] * 7
    assert all(r.depth == 0 for r in t.regions)


@pytest.mark.parametrize("depth", [0, 1, 2, 3])
def test_recursion_multiplies_the_windows(depth):
    t = build(refine(builtin_style("fig20b"), depth))
    windows = 2 ** (depth + 1) - 1
    assert t.depth == depth
    assert _counts(t) == {"arch": 1, "sub-arch": 2 * windows, "circle": windows, "rosette": windows,
                          "fillet": 4 * windows}
    assert len(t.lights) == 5 * windows + 2 ** (depth + 1)
    # every region closed and counter-clockwise, nested regions inside their parent's floor
    byid = {r.id: r for r in t.regions}
    for r in t.regions:
        assert is_closed(r.curves, 1e-9) and r.area > 0
        if r.parent and r.parent != "arch":
            parent = byid[r.parent]
            assert r.face == pytest.approx(parent.floor_depth)
            lo, hi = parent.polygon().min(0), parent.polygon().max(0)
            pts = r.polygon()
            assert (pts >= lo - 1e-9).all() and (pts <= hi + 1e-9).all()


def test_congruent_regions_share_templates_and_are_translates():
    t = build("fig20g")
    groups = {}
    for r in t.regions:
        if r.template >= 0:
            groups.setdefault(r.template, []).append(r)
    assert any(len(g) >= 4 for g in groups.values())
    for g in groups.values():
        ref = g[0]
        for r in g[1:]:
            d = np.array(r.origin) - np.array(ref.origin)
            for a, b in zip(ref.curves, r.curves, strict=True):
                assert np.allclose(a.start + d, b.start, atol=1e-12)
                assert a.kind == b.kind


def test_nested_windows_scale_with_their_sub_arch():
    t = build("fig20f")
    inner = [r for r in t.regions if r.depth == 1 and r.group == "circle"]
    outer = next(r for r in t.group("circle") if r.depth == 0)
    assert len(inner) == 2 and inner[0].area < 0.3 * outer.area
    assert inner[0].border < t.params.inner


def test_trefoil_and_plain_arch_decorations():
    t = build(builtin_style("fig20a").with_overrides({"arch.decoration": "trefoil"}))
    assert [r.group for r in t.regions] == ["arch", "light"]
    assert len(t.regions[1].curves) == 9
    t = build(builtin_style("fig20a").with_overrides({"arch.decoration": "plain", "fillet.decoration": "blind"}))
    assert [r.group for r in t.regions] == ["arch", "light"]
    t = build(builtin_style("fig20a").with_overrides({"fillet.decoration": "blind"}))
    assert [r.role for r in t.group("fillet")] == ["blind"] * 4


def test_params_argument_replaces_the_styles():
    t = build("fig20a", params=PAPER.scaled(3.0))
    assert t.params.span == 6.0
    assert signed_area(t.regions[0].curves) == pytest.approx(9 * signed_area(build("fig20a").regions[0].curves))


def test_errors_in_nested_windows_carry_the_path():
    over = {"excess": 1.5, "inner": 0.05, "drop": 0.5}
    build(builtin_style("fig20a").with_overrides(over))  # fine at the top level ...
    with pytest.raises(ParameterError) as e:  # ... but the nested windows cannot fit their circle
        build(refine(builtin_style("fig20a"), 2).with_overrides(over))
    assert e.value.name == "arch/sub-arch-left: drop" and "expected a number in [0, " in str(e.value)
    wide = {"profiles.wide": {"points": [[0, 0], [9, 0.5]]}, "sub-arch.profile": "wide"}
    with pytest.raises(ParameterError) as e:
        build(refine(builtin_style("fig20a"), 1).with_overrides(wide))
    assert e.value.name == "sub-arch.profile"
