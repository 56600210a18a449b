"""Mirror candidates (auszug.sweeps.mirror): mirror planes of a mesh, and a patch's mirror image."""

from dataclasses import replace

import numpy as np
import pytest

from auszug.sweeps import SweepParams
from auszug.sweeps.mesh import normalise
from auszug.sweeps.mirror import mirror_candidates, mirror_planes, mirrored
from auszug.sweeps.motion import Motion, screw_motion
from auszug.sweeps.params import DEFAULT
from auszug.sweeps.patches import SweepPatch


def _box(size):
    """A closed box ``[0, a] x [0, b] x [0, c]`` (8 vertices, 12 triangles, diagonals all one way)."""
    a, b, c = size
    v = np.array([[x, y, z] for x in (0, a) for y in (0, b) for z in (0, c)], float)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    f = np.array([t for q in quads for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))], np.int64)
    return v, f


def _reflect(x, n, h):
    n = np.asarray(n, float) / np.linalg.norm(n)
    return x - 2.0 * ((x @ n) - h)[..., None] * n


def _patch(rng, kind):
    """A patch with a random profile and a random rotation (about a random axis) or translation."""
    profile = rng.normal(size=(7, 3))
    t = np.linspace(0.0, 1.5, 9)
    d = rng.normal(size=3)
    d /= np.linalg.norm(d)
    if kind == "rotation":
        r, tr = screw_motion(d, rng.normal(size=3), 0.0, t)
    else:
        r, tr = screw_motion(d, None, 0.0, t)
    return SweepPatch(0, kind, profile, False, Motion(t, r, tr), np.zeros(0, np.int64), 0.0, 0.0)


@pytest.mark.parametrize("kind", ["rotation", "translation"])
def test_the_mirror_image_sweeps_the_mirror_image(kind):
    """The mirrored profile swept by the mirrored motion is the reflection of the swept surface (at
    knots and between them, within 1e-12); the maps are proper rotations, the identity at t[0]; a
    rotation's axis is mirrored (a fixed point on it maps to its mirror image, fixed); mirroring twice
    gives the patch back."""
    rng = np.random.default_rng(3)
    for _ in range(5):
        p = _patch(rng, kind)
        n, h = rng.normal(size=3), float(rng.normal())
        prof, m = mirrored(p, n, h)
        assert np.allclose(prof, _reflect(p.profile, n, h), atol=1e-12)
        ts = np.r_[p.motion.t, rng.uniform(0.0, 1.5, 20)]
        assert np.abs(m.apply(prof, ts) - _reflect(p.swept(ts), n, h)).max() <= 1e-12
        assert np.allclose(np.linalg.det(m.rotation), 1.0, atol=1e-12)
        assert np.abs(m.rotation[0] - np.eye(3)).max() <= 1e-12 and np.abs(m.translation[0]).max() <= 1e-12
        if kind == "rotation":
            # a point on the original axis is fixed by every map; its mirror image by the mirrored maps
            r, t = p.motion.rotation[-1], p.motion.translation[-1]
            q = np.linalg.lstsq(np.eye(3) - r, t, rcond=None)[0]
            assert np.abs(r @ q + t - q).max() <= 1e-9
            qm = _reflect(q, n, h)
            assert np.abs(m.rotation[-1] @ qm + m.translation[-1] - qm).max() <= 1e-9
        back = SweepPatch(0, kind, prof, False, m, p.faces, 0.0, 0.0)
        prof2, m2 = mirrored(back, n, h)
        assert np.abs(prof2 - p.profile).max() <= 1e-12
        assert np.abs(m2.rotation - p.motion.rotation).max() <= 1e-12
        assert np.abs(m2.translation - p.motion.translation).max() <= 1e-12


def test_a_box_has_its_three_mirror_planes_and_a_random_hull_none():
    """A box 1 x 2 x 3: the planes through its centre normal to its edges, each with the whole area
    mirrored on it (share 1); at most ``mirror_planes``. The convex hull of random points: none."""
    from scipy.spatial import ConvexHull

    v, f = _box((1.0, 2.0, 3.0))
    m = normalise(v, f)
    planes = mirror_planes(m, DEFAULT.with_(mirror_planes=3))
    assert len(planes) == 3
    normals = np.array([np.abs(n) for n, _, _ in planes])
    assert np.allclose(np.sort(np.argmax(normals, axis=1)), [0, 1, 2])
    assert np.allclose(normals.max(axis=1), 1.0, atol=1e-9)
    for _n, h, share in planes:
        assert share == pytest.approx(1.0, abs=1e-12)
        # through the box's centre (normalised coordinates: the bounding box's centre is 0)
        assert abs(h) <= 1e-9
    assert len(mirror_planes(m)) == DEFAULT.mirror_planes == 2
    assert mirror_planes(m, DEFAULT.with_(mirror_planes=0)) == []
    rng = np.random.default_rng(5)
    pts = rng.normal(size=(60, 3))
    hull = ConvexHull(pts)
    assert mirror_planes(normalise(pts, hull.simplices)) == []


def _mirror_planes_reference(mesh, params):
    """The plane search as first written: every face's image tested for every candidate normal."""
    from auszug.sweeps.patches import MeshTree, face_areas
    from auszug.sweeps.planes import geodesic_sphere

    tree = MeshTree(mesh.vertices, mesh.faces)
    areas = face_areas(mesh.vertices, mesh.faces)
    c = mesh.vertices[mesh.faces].mean(axis=1)
    w = areas / areas.sum()
    centroid = w @ c
    y = c - centroid
    _, axes = np.linalg.eigh((y * w[:, None]).T @ y)
    sphere = geodesic_sphere(params.sphere_frequency)
    found = []
    for n in np.vstack([axes.T, sphere[sphere @ np.array([0.3, 0.5, 0.8]) > 0]]):
        n = n / np.linalg.norm(n)
        if any(abs(float(n @ m)) > np.cos(np.radians(5.0)) for m, _, _ in found):
            continue
        h = float(n @ centroid)
        d = tree.query(c - 2.0 * ((c @ n) - h)[:, None] * n)[0]
        share = float(w[d <= params.eps_prox].sum())
        if share >= params.mirror_share:
            found.append((n, h, share))
    found.sort(key=lambda x: -x[2])
    return found[:params.mirror_planes]


@pytest.mark.parametrize("case", ["extruded", "hole", "bumps", "box"])
def test_mirror_planes_give_up_early_and_find_what_testing_every_face_finds(case):
    """A plane is given up once the area off the mesh exceeds ``1 - mirror_share`` (chunks of faces in
    a shuffled order): the same planes, offsets and shares (to round-off of the summing order) as
    testing every face's image, on meshes with three, one and no mirror planes; on the extrusion
    with a hole (a plane with 0.9976 of the area mirrored on the mesh) also at a ``mirror_share``
    just below and just above that share."""
    from auszug.sweeps import fixtures

    if case == "box":
        v, f = _box((1.0, 2.0, 3.0))
    else:
        fx = {"extruded": lambda: fixtures.extruded(n_profile=60, n_path=60),
              "hole": lambda: fixtures.with_hole(fixtures.extruded(n_profile=60, n_path=60)),
              "bumps": lambda: fixtures.bumps(n=60)}[case]()
        v, f = fx.vertices, fx.faces
    m = normalise(v, f)
    settings = [DEFAULT.with_(mirror_planes=3), DEFAULT.with_(mirror_planes=3, mirror_share=0.5)]
    if case == "hole":
        share = _mirror_planes_reference(m, settings[1])[0][2]
        assert 0.99 < share < 0.999
        settings += [DEFAULT.with_(mirror_planes=3, mirror_share=share - 1e-9),
                     DEFAULT.with_(mirror_planes=3, mirror_share=share + 1e-9)]
    counts = []
    for params in settings:
        got, want = mirror_planes(m, params), _mirror_planes_reference(m, params)
        assert len(got) == len(want), case
        for (n1, h1, s1), (n2, h2, s2) in zip(got, want, strict=True):
            assert np.array_equal(n1, n2) and h1 == h2 and s1 == pytest.approx(s2, abs=1e-12)
        counts.append(len(got))
    assert counts == {"box": [3, 3], "extruded": [1, 1], "hole": [1, 1, 1, 0], "bumps": [0, 0]}[case]


def test_mirror_candidates_are_fitted_against_the_mesh():
    """On the box, a translation patch along one wall's edge mirrored in the plane across the wall:
    the image lies on the opposite wall and fits (error 0, its faces that wall's two triangles); a
    patch far from the mesh mirrored stays far and covers nothing (not returned); an image on faces
    the candidates hold already is dropped, one on faces they leave is kept."""
    v, f = _box((1.0, 2.0, 3.0))
    m = normalise(v, f)
    lo = m.vertices.min(axis=0)
    hi = m.vertices.max(axis=0)
    # the wall x = lo[0]: a profile along y at x = lo[0], swept along z
    prof = np.array([[lo[0], y, lo[2]] for y in np.linspace(lo[1], hi[1], 5)])
    t = np.linspace(0.0, hi[2] - lo[2], 8)
    r, tr = screw_motion([0, 0, 1.0], None, 0.0, t)
    good = SweepPatch(0, "translation", prof, False, Motion(t, r, tr), np.zeros(0, np.int64), 0.0, 0.0)
    far = SweepPatch(1, "translation", prof + [-0.5, 0.0, 0.0], False, Motion(t, r, tr), np.zeros(0, np.int64),
                     0.0, 0.0)
    planes = [pl for pl in mirror_planes(m, DEFAULT.with_(mirror_planes=3)) if abs(pl[0][0]) > 0.99]
    assert len(planes) == 1
    out = mirror_candidates(m, [good, far], planes, DEFAULT, first_id=10)
    # the far patch's image is fitted too (its swept surface 0.5 off the mesh) and covers no face:
    # it adds nothing and is not returned
    assert [p.id for p in out] == [10] and [p.kind for p in out] == ["translation"]
    assert out[0].fit_error <= 1e-12
    wall = np.flatnonzero(np.all(np.isclose(m.vertices[m.faces][:, :, 0], hi[0]), axis=1))
    assert sorted(out[0].faces.tolist()) == sorted(wall.tolist())
    prof_far, motion_far = mirrored(far, *planes[0][:2])
    from auszug.sweeps.patches import fit_patch

    fit_far = fit_patch(m, prof_far, False, motion_far)
    assert fit_far.fit_error >= 0.4 and len(fit_far.faces) == 0
    # a candidate whose faces hold the opposite wall already: its image there adds nothing, dropped
    holding = replace(good, faces=wall)
    assert mirror_candidates(m, [holding, far], planes, DEFAULT) == []
    part = replace(good, faces=wall[:1])        # half the wall held: the image stays
    assert len(mirror_candidates(m, [part], planes, DEFAULT)) == 1


@pytest.mark.parametrize("name, value", [
    ("mirror", 1), ("mirror", None), ("mirror_share", 0.49), ("mirror_share", 1.01), ("mirror_share", float("nan")),
    ("mirror_planes", -1), ("mirror_planes", 4), ("mirror_planes", 2.0),
])
def test_bad_mirror_settings_are_refused(name, value):
    from auszug.errors import GeometryError

    with pytest.raises(GeometryError, match=rf"sweep parameter {name} = .*: expected "):
        SweepParams(**{name: value})
