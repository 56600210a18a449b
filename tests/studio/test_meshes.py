"""Meshes, loops and exports: instanced members equal sweep_network's mesh; files load and are what they say."""

from __future__ import annotations

import io
import json
import struct

import numpy as np
import pytest
import trimesh

from auszug import examples
from auszug.formats import load
from auszug.formats.native import read_native
from auszug.formats.network_json import loads as read_network
from auszug.formats.uc import read_uc
from auszug.meshing import default_size, find_loops, network_faces, profile_for, sweep_network
from auszug.meshing.solid import solid
from auszug.microarch import build
from auszug.studio import meshes as M

from .conftest import WS, receive

U28 = "web/U.XI.28.uc"


def _net(name: str):
    return build(load(examples.path(name)))


def _arrays(pay: bytes):
    return np.frombuffer(pay, "<f4"), np.frombuffer(pay, "<u4")


def _get(arr: np.ndarray, ref) -> np.ndarray:
    ref = ref if isinstance(ref, dict) else ref.__dict__
    n = int(np.prod(ref["shape"]))
    return arr[ref["offset"]:ref["offset"] + n].reshape(ref["shape"])


def _instanced(msg, pay: bytes, members_only: bool = True) -> np.ndarray:
    """Every triangle (k, 3, 3) of the sent pieces placed by their transforms, in float64."""
    f4, u4 = _arrays(pay)
    tris = []
    for p in msg.pieces:
        if members_only and p.basic < 0:
            continue
        pos = _get(f4, p.positions).astype(float)
        idx = _get(u4, p.indices).astype(np.int64)
        for t in _get(f4, p.transforms).astype(float).reshape(-1, 4, 4).transpose(0, 2, 1):
            tris.append((pos @ t[:3, :3].T + t[:3, 3])[idx])
    return np.concatenate(tris) if tris else np.empty((0, 3, 3))


def _same_triangles(got: np.ndarray, ref_vertices: np.ndarray, ref_faces: np.ndarray) -> None:
    """``got`` (k, 3, 3) are ``ref``'s triangles, as sets of corner positions (float32 tolerance).

    Orientation and corner order are ignored; every triangle must occur as often in both.
    """
    from scipy.spatial import cKDTree

    scale = float(np.abs(ref_vertices).max())
    # weld exact (rounding-level) duplicates of the reference, e.g. at mirror joints
    key = np.round(ref_vertices / (1e-9 * scale)).astype(np.int64)
    uniq, ref_ids = np.unique(key, axis=0, return_inverse=True)
    pos = uniq * (1e-9 * scale)
    dist, got_ids = cKDTree(pos).query(got.reshape(-1, 3))
    assert dist.max() <= 1e-6 * scale, f"a sent vertex is {dist.max() / scale:.1e} (relative) from the reference"
    a = np.sort(got_ids.reshape(-1, 3), axis=1)
    b = np.sort(ref_ids.reshape(-1)[ref_faces], axis=1)
    np.testing.assert_array_equal(a[np.lexsort(a.T[::-1])], b[np.lexsort(b.T[::-1])])


@pytest.mark.parametrize("name", [U28, "web/3d-scan-final.uc", "legacy/U.XI.22.uc", "teaching-sheet/tn-9.uc"])
@pytest.mark.parametrize("style", ["bar", "tube"])
def test_instanced_members_equal_sweep_network(name, style):
    """Per-piece members with their replica transforms give sweep_network's triangles exactly (float32)."""
    net = _net(name)
    msg, pay = M.mesh_message(net, style=style, faces="none", loops=[], size=None, segments=24)
    ref = sweep_network(net, profile_for(style, default_size(net)), 24)
    got = _instanced(msg, pay)
    assert msg.binary_floats * 4 == len(pay) and msg.faces == 0 and msg.converged
    assert len(got) == ref.n_faces
    # the same triangles, as corner positions (sweep_network also reverses mirrored replicas' triangles)
    _same_triangles(got, ref.vertices, ref.faces)
    # replicas are not re-sent: one piece per swept basic piece
    assert len(msg.pieces) == sum(p.kind in ("ogee", "free_end", "level", "post", "pillar") for p in net.pieces)
    assert sum(p.transforms.shape[0] for p in msg.pieces) == len(ref.parts)


def test_mirrored_transforms_are_the_reversed_replicas():
    """What instancing must know: transforms with determinant -1 are the replicas sweep_network reverses."""
    net = _net("teaching-sheet/tn-2.uc")
    msg, pay = M.mesh_message(net, style="bar", faces="none", loops=[], size=None, segments=8)
    f4, _ = _arrays(pay)
    t = _get(f4, msg.pieces[0].transforms).astype(float).reshape(-1, 4, 4)
    det = np.linalg.det(t[:, :3, :3])
    labels = net.drawing.curves[0].symmetry.labels()
    assert np.allclose(det, [-1.0 if lab.endswith("m") else 1.0 for lab in labels], atol=1e-6)


def test_curves_style_sends_no_members():
    msg, pay = M.mesh_message(_net(U28), style="curves", faces="none", loops=[], size=None, segments=64)
    assert (msg.pieces, msg.binary_floats, pay, msg.style) == ([], 0, b"", "curves")


def test_faces_auto_and_picked_match_get_loops():
    net = _net(U28)
    loops = find_loops(net)
    lmsg, lpay = M.loops_message(net, revision=3, msg_id=2)
    assert (lmsg.revision, lmsg.id, len(lmsg.loops)) == (3, 2, len(loops)) and len(loops) >= 2
    f4, _ = _arrays(lpay)
    for info, lp in zip(lmsg.loops, loops, strict=True):
        b = _get(f4, info.boundary)
        want, _ = lp.boundary(96)
        np.testing.assert_allclose(b, want, atol=1e-6 * np.abs(want).max())
        np.testing.assert_allclose(info.centre, want.mean(axis=0), atol=1e-12)
        assert info.rim == lp.has_rim
    auto, apay = M.mesh_message(net, style="curves", faces="auto", loops=[], size=None, segments=64)
    ref = network_faces(net)
    assert auto.faces == len(ref.faces) and auto.converged == ref.converged
    (face_piece,) = auto.pieces
    assert face_piece.basic == -1 and face_piece.transforms.shape == [1, 16]
    f4, u4 = _arrays(apay)
    np.testing.assert_array_equal(_get(f4, face_piece.transforms), np.eye(4, dtype="f4").reshape(1, 16))
    assert face_piece.indices.shape == [ref.mesh().n_faces, 3] and face_piece.indices.dtype == "u4"
    np.testing.assert_array_equal(_get(u4, face_piece.indices), ref.mesh().faces)
    picked, ppay = M.mesh_message(net, style="bar", faces="picked", loops=[1], size=0.05, segments=16)
    one = network_faces(net, [loops[1]])
    assert picked.faces == 1 and picked.pieces[-1].basic == -1
    f4, _ = _arrays(ppay)
    np.testing.assert_allclose(_get(f4, picked.pieces[-1].positions), one.mesh().vertices, atol=1e-6)
    with pytest.raises(M.StudioMeshError, match=f"no loop 99: the drawing has {len(loops)} loops"):
        M.mesh_message(net, style="bar", faces="picked", loops=[99], size=None, segments=16)


@pytest.mark.parametrize("bad,problem", [
    (dict(style="cable"), "style must be one of curves, tube, bar, ribbon, got 'cable'"),
    (dict(size=-1.0), "member size must be positive"),
    (dict(segments=0), "segments must lie in 1..1000, got 0"),
])
def test_bad_mesh_requests(bad, problem):
    kw = dict(style="bar", faces="none", loops=[], size=None, segments=16) | bad
    with pytest.raises(M.StudioMeshError, match=problem):
        M.mesh_message(_net(U28), **kw)


# ---------------------------------------------------------------- exports


def test_export_glb_loads_with_the_triangle_count():
    net = _net(U28)
    name, mime, data = M.export_file(net, "U.XI.28.uc", format="glb", style="bar")
    assert (name, mime, data[:4]) == ("U.XI.28.glb", "model/gltf-binary", b"glTF")
    scene = trimesh.load(io.BytesIO(data), file_type="glb")
    want = sweep_network(net, profile_for("bar", default_size(net)), 200).n_faces
    assert sum(len(g.faces) for g in scene.geometry.values()) == want


def _glb_materials(data: bytes) -> dict[str, dict]:
    """Material of every mesh node of a GLB, by node name."""
    jl = struct.unpack("<I", data[12:16])[0]
    doc = json.loads(data[20:20 + jl])
    return {n["name"]: doc["materials"][doc["meshes"][n["mesh"]]["primitives"][0]["material"]]
            for n in doc["nodes"] if "mesh" in n}


def test_export_glb_colours():
    net = _net(U28)
    got = _glb_materials(M.export_file(net, "x", format="glb", style="tube", colors=["#ff0000", "#00FF80"])[2])
    plain = _glb_materials(M.export_file(net, "x", format="glb", style="tube")[2])
    assert got["curve 0"]["pbrMetallicRoughness"]["baseColorFactor"] == [1.0, 0.0, 0.0, 1.0]
    assert got["curve 1"]["pbrMetallicRoughness"]["baseColorFactor"] == [0.0, 1.0, 128 / 255, 1.0]
    assert got["curve 2"] == plain["curve 2"] and got["curve 3"] == plain["curve 3"]   # the others keep theirs
    assert plain["curve 0"] != got["curve 0"]
    with pytest.raises(M.StudioMeshError, match=r"colors\[1\]: expected #rrggbb, got 'red'"):
        M.export_file(net, "x", format="glb", colors=["#000000", "red"])


@pytest.mark.parametrize("name,style", [("teaching-sheet/tn-2.uc", "tube"), (U28, "bar")])
def test_export_stl_solid_is_watertight(name, style):
    net = _net(name)
    fname, mime, data = M.export_file(net, name, format="stl", style=style, solid=True)
    assert (fname, mime) == (name.split("/")[-1].replace(".uc", ".stl"), "model/stl")
    m = trimesh.load(io.BytesIO(data), file_type="stl")
    want = solid(net, profile_for(style, default_size(net)), 64)
    assert m.is_watertight and m.is_volume and len(m.faces) == want.mesh.n_faces
    assert m.volume == pytest.approx(want.volume, rel=1e-4)


def test_export_obj_and_ply():
    net = _net("teaching-sheet/tn-2.uc")
    n = sweep_network(net, profile_for("tube", default_size(net)), 200).n_faces
    name, _, obj = M.export_file(net, "tn-2.uc", format="obj", style="tube")
    text = obj.decode()
    assert name == "tn-2.obj" and sum(ln.startswith("f ") for ln in text.splitlines()) == n
    name, _, ply = M.export_file(net, "tn-2.uc", format="ply", style="tube", faces="none")
    assert name == "tn-2.ply" and len(trimesh.load(io.BytesIO(ply), file_type="ply").faces) == n


def test_export_drawing_formats():
    d = load(examples.path(U28))
    net = build(d)
    name, mime, data = M.export_file(net, "U.XI.28.uc", format="json")
    assert (name, mime) == ("U.XI.28.json", "application/json") and read_native(data.decode(), name) == d
    name, _, data = M.export_file(net, "U.XI.28.uc", format="uc")
    assert name == "U.XI.28.uc" and [c.vertices for c in read_uc(data.decode(), name).curves] == \
        [c.vertices for c in d.curves]
    name, mime, data = M.export_file(net, "U.XI.28.uc", format="network.json")
    assert (name, mime) == ("U.XI.28.network.json", "application/json")
    doc = read_network(data.decode(), name)
    assert len(doc["curves"]) == len(list(net.curves()))
    # sampled to the default tolerance, as `auszug build` writes it (not the page's 65 samples)
    diag = net.to_curve_network().diagonal()
    assert doc["tolerance"] == 1e-6 * diag and all(len(c["points"]) > 65 for c in doc["curves"])
    name, mime, data = M.export_file(net, "U.XI.28.uc", format="svg")
    assert (name, mime) == ("U.XI.28.svg", "image/svg+xml")
    assert b"<svg" in data[:400] and data.rstrip().endswith(b"</svg>")


def test_export_cad_formats():
    import ezdxf
    import rhino3dm

    net = build(load(examples.path(U28)))
    n = len(list(net.curves()))
    name, mime, data = M.export_file(net, "U.XI.28.uc", format="dxf")
    assert (name, mime) == ("U.XI.28.dxf", "image/vnd.dxf")
    doc = ezdxf.read(io.StringIO(data.decode()))
    assert len(doc.modelspace().query("POLYLINE")) == n and doc.header.custom_vars.get("source") == "U.XI.28.uc"
    name, mime, data = M.export_file(net, "U.XI.28.uc", format="3dm")
    assert name == "U.XI.28.3dm" and len(rhino3dm.File3dm.FromByteArray(data).Objects) == n


@pytest.mark.parametrize(("segments", "around"), [(48, 10), (24, 6), (7, 3)])
def test_export_resolution_sets_steps_and_points_round_the_tube(segments, around):
    """A light export is the sweep at that resolution: triangles and vertex positions match exactly."""
    net = _net(U28)
    _, _, data = M.export_file(net, "U.XI.28.uc", format="glb", style="tube", segments=segments, around=around)
    _, _, fine = M.export_file(net, "U.XI.28.uc", format="glb", style="tube")
    want = sweep_network(net, profile_for("tube", default_size(net), around), segments)
    scene = trimesh.load(io.BytesIO(data), file_type="glb")
    assert sum(len(g.faces) for g in scene.geometry.values()) == want.n_faces
    got = np.concatenate([g.vertices for g in scene.geometry.values()])
    assert len(got) == len(want.vertices)
    np.testing.assert_allclose(np.sort(got, axis=0), np.sort(want.vertices, axis=0), atol=1e-5)
    assert len(data) < len(fine) / 10


def test_export_resolution_limits():
    net = _net(U28)
    for around in (2, 65):
        with pytest.raises(M.StudioMeshError, match=f"around .* must lie in 3..64, got {around}"):
            M.export_file(net, "x", format="glb", style="tube", around=around)
    with pytest.raises(M.StudioMeshError, match="segments must lie in 1..1000, got 1001"):
        M.export_file(net, "x", format="glb", style="tube", segments=1001)


def test_export_refusals():
    net = _net(U28)
    with pytest.raises(M.StudioMeshError, match="format must be one of glb, obj"):
        M.export_file(net, "x", format="fbx")
    with pytest.raises(M.StudioMeshError, match="nothing to export: style curves without faces"):
        M.export_file(net, "x", format="stl", style="curves")
    with pytest.raises(M.StudioMeshError, match="a solid needs members"):
        M.export_file(net, "x", format="stl", style="curves", solid=True)


# ---------------------------------------------------------------- over the socket


def _frames(ws, kind: str) -> tuple[dict, bytes]:
    msg, payload = receive(ws)
    assert msg["type"] == kind, msg
    assert payload is not None, f"{kind} came without its payload"
    return msg, payload


def test_mesh_loops_export_over_the_socket(client):
    net = _net(U28)
    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "open_example", "name": U28})
        g, _ = _frames(ws, "geometry")
        ws.send_json({"type": "get_loops", "id": 1})
        ws.send_json({"type": "get_mesh", "style": "bar", "faces": "picked", "loops": [0], "segments": 16, "id": 2})
        ws.send_json({"type": "set_apex_height", "curve": 0, "height": 3.0, "id": 3})   # not held up by the jobs
        seen = {}
        for _ in range(3):
            msg, payload = receive(ws)
            seen[msg["id"]] = (msg, payload)
        loops, lpay = seen[1]
        assert loops["type"] == "loops" and loops["revision"] == g["revision"]
        assert len(loops["loops"]) == len(find_loops(net)) and len(lpay) == 4 * loops["binary_floats"]
        mesh, mpay = seen[2]
        assert mesh["type"] == "mesh" and mesh["faces"] == 1 and mesh["pieces"][-1]["basic"] == -1
        assert mesh["pieces"][0]["indices"]["dtype"] == "u4" and len(mpay) == 4 * mesh["binary_floats"]
        assert seen[3][0]["type"] == "geometry"
        ws.send_json({"type": "export", "format": "glb", "style": "tube", "id": 4})
        ex, data = _frames(ws, "exported")
        assert (ex["id"], ex["name"], ex["mime"], ex["size"]) == (4, "U.XI.28.glb", "model/gltf-binary", len(data))
        assert len(trimesh.load(io.BytesIO(data), file_type="glb").geometry) == 4
        ws.send_json({"type": "get_mesh", "style": "cable", "id": 5})
        err = ws.receive_json()
        assert err["type"] == "error" and err["id"] == 5 and "'cable'" in err["message"]
        ws.send_json({"type": "export", "format": "fbx", "id": 6})
        err = ws.receive_json()
        assert err["type"] == "error" and err["id"] == 6 and "export.format" in err["message"]
        ws.send_json({"type": "get_mesh", "faces": "picked", "loops": [42], "id": 7})
        err = ws.receive_json()
        assert err["id"] == 7 and err["message"].startswith("U.XI.28.uc: no loop 42")
        ws.send_json({"type": "undo", "id": 8})
        assert _frames(ws, "geometry")[0]["id"] == 8   # the server lives


def test_mesh_needs_a_drawing(client):
    with client.websocket_connect(WS) as ws:
        ws.send_json({"type": "get_mesh", "id": 3})
        err = ws.receive_json()
        assert err == {"type": "error", "id": 3, "message": "no drawing is open: send an 'open' message first"}
