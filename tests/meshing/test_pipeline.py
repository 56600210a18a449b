"""The one mesh pipeline: Look validation, the same meshes as the kernels, and the CLI and studio agree."""

from __future__ import annotations

import numpy as np
import pytest

from auszug import examples
from auszug.cli import main
from auszug.errors import GeometryError
from auszug.formats import load
from auszug.meshing import (
    Look,
    concatenate,
    default_size,
    faces_of,
    find_loops,
    members_of,
    mesh_network,
    network_faces,
    profile_for,
    profile_of,
    sweep_network,
)
from auszug.meshing.profile import square
from auszug.meshing.solid import solid
from auszug.meshing.sweep import replicate
from auszug.microarch import Drawing, build
from auszug.studio import meshes as studio_meshes

U28 = "web/U.XI.28.uc"
TN1 = "teaching-sheet/tn-1.uc"


def _net(name: str):
    return build(load(examples.path(name)))


def _same(a, b) -> None:
    np.testing.assert_array_equal(a.vertices, b.vertices)
    np.testing.assert_array_equal(a.faces, b.faces)
    assert a.parts == b.parts


@pytest.mark.parametrize("name", [U28, TN1])
@pytest.mark.parametrize("style", ["tube", "bar", "ribbon"])
def test_members_and_faces_are_the_kernels_meshes(name, style):
    net = _net(name)
    prof = profile_for(style, default_size(net))
    r = mesh_network(net, Look(style, faces="auto", segments=40))
    want = concatenate([sweep_network(net, prof, 40), network_faces(net).mesh()])
    _same(r.mesh, want)
    np.testing.assert_array_equal(r.profile.points, prof.points)
    assert r.solid is None and len(r.faces.faces) == len(network_faces(net).faces)
    assert r.parts == want.parts
    # the unreplicated members replicate to the same members
    _same(replicate(net, members_of(net, Look(style, segments=40))), sweep_network(net, prof, 40))


def test_defaults_and_picked_loops():
    net = _net(U28)
    prof = profile_for("bar", default_size(net))
    _same(mesh_network(net, Look()).mesh, sweep_network(net, prof, 200))   # bar, 200 steps, no faces
    loops = find_loops(net)
    r = mesh_network(net, Look("curves", faces=(loops[1], loops[3]), resolution=48))
    _same(r.mesh, network_faces(net, [loops[1], loops[3]], resolution=48).mesh())
    assert r.profile is None and members_of(net, Look("curves")) == []
    assert faces_of(net, Look()) is None
    assert faces_of(build(Drawing(())), Look(faces="auto")) is None


def test_solid_is_the_kernels_solid():
    net = _net(TN1)
    prof = profile_for("tube", default_size(net), 8)
    r = mesh_network(net, Look("tube", around=8, solid=True, base=True, segments=24))
    want = solid(net, prof, 24, base=True)
    _same(r.mesh, want.mesh)
    assert (r.solid.volume, r.solid.watertight, r.solid.components) == (want.volume, want.watertight, want.components)
    assert Look(solid=True).steps == 64 and Look().steps == 200 and Look(segments=7, solid=True).steps == 7


def test_a_profile_look():
    net = _net(TN1)
    prof = square(0.02)
    _same(mesh_network(net, Look(prof, segments=12)).mesh, sweep_network(net, prof, 12))
    with pytest.raises(GeometryError, match="a profile has its own size"):
        profile_of(net, Look(prof, size=0.1))


@pytest.mark.parametrize("kw, problem", [
    (dict(style="cable"), "style must be one of curves, tube, bar, ribbon, got 'cable'"),
    (dict(size=0.0), r"member size must be positive \(a positive number"),
    (dict(size=float("nan")), "member size must be positive"),
    (dict(around=1), "points around the profile must be a whole number >= 2, got 1"),
    (dict(faces="picked"), "faces must be none, auto or a list of loops, got 'picked'"),
    (dict(faces=[1, 2]), "faces must be none, auto or a list of loops"),
    (dict(resolution=8), "face resolution must be a whole number >= 12, got 8"),
    (dict(segments=0), "segments must be a whole number >= 1, got 0"),
    (dict(segments=2.5), "segments must be a whole number >= 1, got 2.5"),
    (dict(thickness=-1.0), "face thickness must be positive"),
    (dict(style="curves", solid=True), "a solid needs members: pick the style tube, bar or ribbon"),
])
def test_bad_looks_say_what_is_expected(kw, problem):
    with pytest.raises(GeometryError, match=problem):
        Look(**kw)


def test_no_extent_no_default_size():
    one_point = Look("bar")
    with pytest.raises(GeometryError, match="no extent"):
        profile_of(build(Drawing(())), one_point)


@pytest.mark.parametrize("fmt, args", [
    ("stl", ["--style", "tube"]),
    ("stl", ["--style", "bar", "--solid"]),
    ("ply", ["--style", "ribbon", "--faces", "auto"]),
])
def test_the_cli_and_the_studio_write_the_same_file(tmp_path, fmt, args, capsys):
    src = examples.path(TN1)
    out = tmp_path / f"tn-1.{fmt}"
    assert main(["mesh", str(src), *args, "-o", str(out)]) == 0
    capsys.readouterr()
    style = args[1]
    faces = "auto" if "--faces" in args else "none"
    _, _, data = studio_meshes.export_file(_net(TN1), "tn-1.uc", format=fmt, style=style, faces=faces,
                                           solid="--solid" in args)
    assert out.read_bytes() == data
