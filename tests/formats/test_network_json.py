"""Network JSON: required keys and types, samples, ids, exact transforms, round trip, errors."""

from __future__ import annotations

import json

import numpy as np
import pytest

from auszug.errors import FormatError
from auszug.formats import load, save
from auszug.formats.network_json import KINDS, NetworkFile, dumps, loads, network_from_dict, to_dict
from auszug.microarch import BasicCurve, Drawing, Segment, Symmetry, build
from tests.conftest import CORPUS, corpus_files

WEB = [p for p in corpus_files("teaching-sheet", "web")
       if p.name != "two_curves.uc"]        # two_curves.uc is v1 (legacy reader)

TOP = {"format": str, "version": int, "source": str, "up": str, "layers": list, "curves": list}
CURVE = {"id": str, "basic": int, "layer": int, "kind": str, "rotation": int, "mirrored": bool,
         "transform": list, "points": list}


def _doc(path):
    return loads(dumps(build(load(path)), path.name), path.name)


def _decorated_free_end_post() -> Drawing:
    """One curve with an ogee, a free end, a decoration and a post; off-origin centre."""
    c = BasicCurve(((1.0, 0.0), (0.2, 0.9), (-0.1, 0.5)),
                   (Segment("arc", ((0.9, 0.5),)), Segment("line")),
                   ("ground", "apex", "free"), Symmetry(3, True, (1.0, 0.2), (0.1, -0.2)),
                   height=1.5, prc=(0.45, None), decoration=True, post_top=2.0)
    return Drawing((c,), name="synthetic")


@pytest.mark.parametrize("path", WEB, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_corpus_document_has_the_required_keys_and_types(path):
    doc = _doc(path)
    for key, typ in TOP.items():
        assert type(doc[key]) is typ, key
    assert (doc["format"], doc["version"], doc["source"], doc["up"]) == ("auszug.network", 2, path.name, "z")
    for i, lay in enumerate(doc["layers"]):
        assert lay["index"] == i and type(lay["bottom"]) is float
    assert doc["curves"]
    for c in doc["curves"]:
        for key, typ in CURVE.items():
            assert type(c[key]) is typ, (c["id"], key)
        assert c["kind"] in KINDS
        assert "prc" in c and (c["prc"] is None or (len(c["prc"]) == 3 and all(type(v) is float for v in c["prc"])))
        assert np.shape(c["transform"]) == (2, 2)
        assert all(len(p) == 3 and all(type(v) is float for v in p) for p in c["points"])


@pytest.mark.parametrize("path", WEB, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_ogees_run_bottom_to_apex_with_at_least_64_samples_and_ids_are_unique(path):
    net = build(load(path))
    doc = loads(dumps(net), "x")
    ids = [c["id"] for c in doc["curves"]]
    assert len(set(ids)) == len(ids)
    assert ids == [c.id for c in net.curves()]
    for c in doc["curves"]:
        if c["kind"] == "ogee":
            pts = np.array(c["points"])
            assert len(pts) >= 64
            assert pts[0, 2] == doc["layers"][c["layer"]]["bottom"]
            assert pts[-1, 2] == net.apex_heights[c["basic"]]


@pytest.mark.parametrize("path", WEB, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_transform_maps_the_basic_top_view_onto_every_replica(path):
    doc = _doc(path)
    basic = {(c["piece"]): c for c in doc["curves"] if c["rotation"] == 0 and not c["mirrored"]}
    for c in doc["curves"]:
        b = basic[c["piece"]]
        ctr = np.array(c["center"])
        p0 = np.array(b["points"])[:, :2]
        want = np.array(c["points"])
        got = (p0 - ctr) @ np.array(c["transform"]).T + ctr
        np.testing.assert_allclose(got, want[:, :2], rtol=0, atol=1e-12, err_msg=c["id"])
        np.testing.assert_array_equal(want[:, 2], np.array(b["points"])[:, 2])
        if b["prc"] is not None:
            q = (np.array(b["prc"][:2]) - ctr) @ np.array(c["transform"]).T + ctr
            np.testing.assert_allclose(q, c["prc"][:2], rtol=0, atol=1e-12)


def test_transform_and_kinds_of_a_drawing_with_every_piece_kind_and_an_off_origin_centre():
    net = build(_decorated_free_end_post(), samples=70)
    doc = loads(dumps(net, "synthetic.json"))
    assert {c["kind"] for c in doc["curves"]} == {"ogee", "free_end", "decoration", "post"}
    assert len(doc["curves"]) == 4 * 6
    basic = {c["piece"]: c for c in doc["curves"] if c["id"].split("/")[1].startswith("r0") and not c["mirrored"]}
    for c in doc["curves"]:
        b = basic[c["piece"]]
        got = (np.array(b["points"])[:, :2] - c["center"]) @ np.array(c["transform"]).T + c["center"]
        np.testing.assert_allclose(got, np.array(c["points"])[:, :2], rtol=0, atol=1e-12)
        if c["kind"] in ("ogee", "free_end", "decoration"):
            assert len(c["points"]) == 70
        # a mirrored transform has determinant -1, a rotation +1
        assert np.linalg.det(c["transform"]) == pytest.approx(-1.0 if c["mirrored"] else 1.0, abs=1e-12)


def test_round_trip_is_exact_and_does_not_touch_the_network(tmp_path):
    net = build(load(CORPUS / "teaching-sheet" / "tn-5.uc"))
    before = [p.points.copy() for p in net.pieces]
    text = dumps(net, "tn-5.uc")
    doc = loads(text, "tn-5.network.json")
    assert doc == json.loads(json.dumps(to_dict(net, "tn-5.uc")))
    for c, nc in zip(doc["curves"], net.curves(), strict=True):
        assert np.array_equal(np.array(c["points"]), nc.points)    # floats survive exactly
    assert all(np.array_equal(a, p.points) for a, p in zip(before, net.pieces, strict=True))
    out = save(NetworkFile(net, "tn-5.uc"), tmp_path / "tn-5.network.json")
    assert out.read_text() == text
    assert load(out, kind="network") == doc
    assert dumps(net, "tn-5.uc") == text                              # deterministic


MESHED = ["teaching-sheet/tn-2.uc", "web/U.XI.28.uc", "web/3d-scan-final.uc", "web/ribbons/side6-drawing-cube.uc",
          "legacy/U.XI.25.uc"]


@pytest.mark.parametrize("name", MESHED)
def test_the_network_read_back_from_a_file_meshes_as_the_drawing_does(name):
    from auszug.geometry.network import as_curve_network
    from auszug.meshing import Look, mesh_network

    net = build(load(CORPUS / name))
    back = network_from_dict(loads(dumps(net, name)))
    cn = as_curve_network(net)
    assert back.groups == cn.groups and back.layers == cn.layers and back.bottoms == cn.bottoms
    assert back.size == cn.size and [c.id for c in back.curves()] == [c.id for c in cn.curves()]
    # members with their mirror-plane joints: the same mesh (the exact curves' floats round-trip to 1 ulp)
    look = Look(style="bar", segments=16)
    a, b = mesh_network(net, look).mesh, mesh_network(back, look).mesh
    assert [p.name for p in a.parts] == [p.name for p in b.parts] and np.array_equal(a.faces, b.faces)
    np.testing.assert_allclose(b.vertices, a.vertices, rtol=0, atol=1e-14)


def test_every_piece_kind_reads_back_exactly():
    net = build(_decorated_free_end_post(), samples=70)
    back = network_from_dict(loads(dumps(net, "synthetic.json")))
    t = np.linspace(0.0, 1.0, 33)
    for p, q in zip(net.pieces, back.pieces, strict=True):
        assert (p.kind, p.basic, p.segment) == (q.kind, q.basic, q.segment)
        np.testing.assert_allclose(q.point_t(t), p.point_t(t), rtol=0, atol=1e-14)
    from auszug.geometry.network import as_curve_network

    assert back.groups == as_curve_network(net).groups


def test_a_network_without_exact_curves_is_refused_naming_the_curve():
    doc = loads(dumps(build(_decorated_free_end_post(), samples=9), "synthetic.json"))
    del doc["curves"][3]["exact"]
    with pytest.raises(FormatError, match=r"curves\[3\] \(0/r1m?\S*\): no exact curve"):
        network_from_dict(doc, "x.network.json")


def test_extras_record_the_parameterization_and_algorithm1_choices():
    text = (CORPUS / "teaching-sheet" / "tn-11.uc").read_text()
    auto = "\n".join(ln for ln in text.splitlines() if not ln.startswith("prc_t"))
    from auszug.formats.uc import read_uc

    net = build(read_uc(auto, "tn-11.uc"), "u")
    doc = loads(dumps(net))
    assert doc["parameterization"] == "u"
    assert doc["samples"] == 65
    assert doc["source"] == "tn-11"                   # a bare network: the drawing's name
    keys = {(ch["curve"], ch["segment"]) for ch in doc["prc_choices"]}
    assert keys == set(net.prc_choices) and len(keys) == 3
    for ch in doc["prc_choices"]:
        assert ch["branch"] in ("own replicas", "other curves", "midpoint")
        assert ch["fraction"] == net.prc_choices[(ch["curve"], ch["segment"])].fraction
    assert [b["fold"] for b in doc["basic_curves"]] == [2, 2, 2]
    assert all(c["segment"] == 0 for c in doc["curves"])


GOOD = dumps(build(load(CORPUS / "teaching-sheet" / "tn-1.uc")), "tn-1.uc")


@pytest.mark.parametrize("edit, where", [
    (lambda d: d.update(format="other"), "format"),
    (lambda d: d.update(version=3), "version"),
    (lambda d: d.update(version=True), "version"),
    (lambda d: d.update(up="y"), "up"),
    (lambda d: d.pop("layers"), "layers"),
    (lambda d: d["layers"][0].update(bottom="0"), "layers[0]"),
    (lambda d: d["curves"][1].update(id=d["curves"][0]["id"]), "curves[1].id"),
    (lambda d: d["curves"][0].update(kind="spline"), "curves[0].kind"),
    (lambda d: d["curves"][0].update(mirrored=0), "curves[0].mirrored"),
    (lambda d: d["curves"][0].update(layer=3), "curves[0].layer"),
    (lambda d: d["curves"][0].update(transform=[[1, 0]]), "curves[0].transform"),
    (lambda d: d["curves"][0]["points"][3].append(1.0), "curves[0].points"),
    (lambda d: d["curves"][0].pop("prc"), "curves[0].prc"),
    (lambda d: d["curves"][0].update(prc=[1, 2]), "curves[0].prc"),
])
def test_reader_names_the_first_bad_key(edit, where):
    doc = json.loads(GOOD)
    edit(doc)
    with pytest.raises(FormatError, match=rf"^bad\.network\.json: {where.replace('[', '.').replace(']', '.')}"):
        loads(json.dumps(doc), "bad.network.json")


def test_reader_gives_the_line_of_a_syntax_error():
    text = GOOD.replace('"up": "z"', '"up": z')
    with pytest.raises(FormatError) as e:
        loads(text, "x.network.json")
    assert e.value.line == 5 and e.value.path == "x.network.json"
    assert str(e.value).startswith("x.network.json:5: not JSON")


@pytest.mark.parametrize("edit, message", [
    (lambda b: b.update(fold=100000), r"basic_curves \(curve 0\): not a symmetry .*fold 100000 is above the limit"),
    (lambda b: b.update(fold="four"), r"basic_curves \(curve 0\): not a symmetry .*whole number"),
    (lambda b: b.update(center=[float("nan"), 0.0]), r"basic_curves \(curve 0\): not a symmetry .*finite"),
    (lambda b: b.pop("mirror"), r"basic_curves \(curve 0\): not a symmetry \(KeyError"),
])
def test_a_bad_symmetry_in_basic_curves_is_a_format_error(edit, message):
    doc = loads(dumps(build(_decorated_free_end_post(), samples=9), "synthetic.json"))
    edit(doc["basic_curves"][0])
    with pytest.raises(FormatError, match=message):
        network_from_dict(doc, "x.network.json")
