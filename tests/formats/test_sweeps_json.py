"""Sweeps JSON (auszug.formats.sweeps_json): the keys of issue 11, lossless round trip, clear errors."""

from __future__ import annotations

from functools import cache

import numpy as np
import orjson
import pytest

from auszug.errors import FormatError
from auszug.formats import load, save
from auszug.formats.sweeps_json import dumps, loads
from auszug.sweeps import detect
from auszug.sweeps.fixtures import revolved


@cache
def _report():
    fx = revolved(n_profile=40, n_path=60, sigma=2e-4)
    v = 3.0 * fx.vertices + [1.0, 2.0, -5.0]
    return detect((v, fx.faces), source="ring.stl")


def test_document_has_the_required_keys():
    doc = orjson.loads(dumps(_report()))
    assert doc["format"] == "auszug.sweeps" and doc["version"] == 1 and doc["source"] == "ring.stl"
    assert doc["bbox_diameter"] == pytest.approx(3.0, rel=1e-2)   # noise moves the box a little
    assert 0.95 <= doc["coverage"] <= 1.0
    # the per-face figure beside the area's: never above it
    assert 0.95 <= doc["face_coverage"] <= doc["coverage"]
    (p,) = doc["patches"]
    assert set(p) >= {"id", "profile", "motion", "faces", "fit_error"}
    assert len(p["motion"]) >= 8 and set(p["motion"][0]) == {"t", "rotation", "translation"}
    assert np.allclose(p["motion"][0]["rotation"], np.eye(3)) and np.allclose(p["motion"][0]["translation"], 0)
    assert np.asarray(p["profile"]).shape[1] == 3 and all(isinstance(f, int) for f in p["faces"])


def test_round_trip_is_lossless(tmp_path):
    r = _report()
    text = dumps(r)
    back = loads(text)
    assert dumps(back) == text
    (p,), (q,) = r.patches, back.patches
    assert np.array_equal(p.profile, q.profile) and np.array_equal(p.faces, q.faces)
    assert np.array_equal(p.motion.rotation, q.motion.rotation) and np.array_equal(p.motion.t, q.motion.t)
    assert np.array_equal(p.motion.translation, q.motion.translation)
    assert (p.fit_error, p.coverage, p.kind, p.closed) == (q.fit_error, q.coverage, q.kind, q.closed)
    assert back.params == r.params and [s.name for s in back.stages] == [s.name for s in r.stages]
    assert (back.coverage, back.face_coverage) == (r.coverage, r.face_coverage) and back.face_shares is None
    # through the registry, by file name
    out = save(r, tmp_path / "ring.sweeps.json", kind="sweeps")
    again = load(out, kind="sweeps")
    assert dumps(again) == text


def test_profile_fit_round_trips_exactly():
    """The optional profile_fit key: written, read back to the same exact Profile, absent when off."""
    r = _report()
    (p,) = r.patches
    assert p.profile_fit is not None and p.profile_fit.profile.has_arcs
    doc = orjson.loads(dumps(r))
    fit = doc["patches"][0]["profile_fit"]
    assert set(fit) == {"origin", "axes", "closed", "points", "bulges", "hausdorff"}
    back = loads(dumps(r)).patches[0].profile_fit
    assert back == p.profile_fit and back.profile == p.profile_fit.profile
    assert np.array_equal(back.vertices(), p.profile_fit.vertices())
    # the fit's vertices are in the input's coordinates: on the profile polyline's plane
    assert np.abs((np.asarray(p.profile) - back.origin) @ back.axes[:, 2]).max() <= 1e-9 * r.bbox_diameter
    del doc["patches"][0]["profile_fit"]
    old = loads(orjson.dumps(doc))
    assert old.patches[0].profile_fit is None and "profile_fit" not in orjson.loads(dumps(old))["patches"][0]


def _broken(change):
    doc = orjson.loads(dumps(_report()))
    change(doc)
    return orjson.dumps(doc)


@pytest.mark.parametrize("change, message", [
    (lambda d: d.update(format="auszug.network"), "format"),
    (lambda d: d.update(version=2), "version 2"),
    (lambda d: d.update(coverage="all"), "coverage"),
    (lambda d: d["patches"][0].update(profile=[[0, 0]]), r"patches\[0\].profile"),
    (lambda d: d["patches"][0]["motion"][3].update(rotation=[[1, 0, 0], [0, 1, 0], [0, 0, -1]]),
     r"patches\[0\].motion: motion map 3 is not a rotation"),
    (lambda d: d["patches"][0].update(faces=[0, -1]), r"patches\[0\].faces"),
    (lambda d: d["patches"][0].update(kind="spiral"), r"patches\[0\].kind"),
    (lambda d: d["patches"][0]["motion"][1].update(t=-1.0), "increase"),
    (lambda d: d["patches"][0]["motion"][1].update(t="soon"), r"motion\[\]\.t"),
    (lambda d: d["stages"][1].update(seconds="long"), r"stages\[1\]"),
    (lambda d: d.update(stages={}), "stages: expected a list"),
    (lambda d: d.update(n_faces=-3), "n_faces"),
    (lambda d: d["params"].update(eps_prox=7.0), "params: sweep parameter eps_prox"),
    (lambda d: d.update(patches=[1]), r"patches\[0\]: expected an object"),
    (lambda d: d["patches"][0].update(profile_fit=3), r"patches\[0\].profile_fit: expected an object or null"),
    (lambda d: d["patches"][0]["profile_fit"].update(axes=[[2, 0, 0], [0, 1, 0], [0, 0, 1]]),
     r"patches\[0\].profile_fit.axes: expected orthonormal"),
    (lambda d: d["patches"][0]["profile_fit"].update(bulges=[0.0]), r"patches\[0\].profile_fit: profile bulge"),
    (lambda d: d["patches"][0]["profile_fit"].update(points=[[0, 0, 0]]), r"patches\[0\].profile_fit.points"),
    (lambda d: d["patches"][0]["profile_fit"].update(hausdorff=-1), r"patches\[0\].profile_fit.hausdorff"),
    (lambda d: d["patches"][0]["profile_fit"].update(closed="no"), r"patches\[0\].profile_fit.closed"),
])
def test_bad_documents_name_the_place(change, message):
    with pytest.raises(FormatError, match=message):
        loads(_broken(change), "bad.sweeps.json")


def test_not_json():
    with pytest.raises(FormatError, match="not JSON"):
        loads("{", "x.sweeps.json")
