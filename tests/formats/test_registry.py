"""The formats registry: endings, kinds and stems, and a new drawing format recognised everywhere."""

from __future__ import annotations

import pytest

from auszug.formats import FileFormat, _registry, kind_of, native, register, stem, suffix_of, suffixes


@pytest.mark.parametrize("name, kind, expected", [
    ("tn-2.uc", "drawing", ".uc"),
    ("TN-2.UC", "drawing", ".uc"),
    ("a/b/tn-2.json", "drawing", ".json"),
    ("tn-2.network.json", "drawing", None),        # the longest ending decides: a network
    ("tn-2.network.json", "network", ".network.json"),
    ("w.tracery.json", "drawing", None),
    ("w.tracery.json", None, ".tracery.json"),
    ("x.json", "tracery", ".json"),                # tracery styles may end in plain .json too
    ("notes.txt", None, None),
    ("uc", None, None),                            # no dot: no ending
    ("folder.uc/notes.txt", "drawing", None),      # only the file name counts
])
def test_suffix_of(name, kind, expected):
    assert suffix_of(name, kind) == expected


def test_kind_of_and_suffixes():
    assert [kind_of(n) for n in ("a.uc", "a.json", "a.network.json", "a.tracery.json", "a.stl", "a.obj",
                                 "a.svg", "a.png", "a.txt")] == \
        ["drawing", "drawing", "network", "tracery", "mesh", "network", "network", "figure", None]
    assert suffixes("drawing") == [".uc", ".json"]
    assert set(suffixes("mesh")) == {".obj", ".stl", ".ply", ".glb", ".gltf"}
    assert len(suffixes()) == len(set(suffixes()))


@pytest.mark.parametrize("name, kind, expected", [
    ("U.XI.28.fixed.uc", "drawing", "U.XI.28.fixed"),
    ("dir/tn-2.network.json", None, "tn-2"),
    ("tn-2.network.json", "drawing", "tn-2.network"),
    ("tn-2.tracery.json", None, "tn-2"),
    (".uc", "drawing", ".uc"),
    ("notes.txt", None, "notes"),
])
def test_stem(name, kind, expected):
    assert stem(name, kind) == expected


@pytest.fixture
def sketch_format(monkeypatch):
    """A made-up drawing format ``.sketch`` (native JSON inside), registered for one test."""
    monkeypatch.setattr(_registry, "_FORMATS", dict(_registry._FORMATS))
    return register(FileFormat("sketch", (".sketch",), "drawing", native.read_native, native.write_native))


def test_a_new_drawing_format_is_recognised_everywhere(sketch_format, tmp_path):
    from auszug import examples
    from auszug.cli import _common
    from auszug.formats import load, save
    from auszug.studio.meshes import export_file
    from auszug.studio.session import Workspace, drawing_endings, open_document

    d = load(examples.path("teaching-sheet/tn-2.uc"))
    save(d, tmp_path / "sub" / "tn-2.sketch")
    (tmp_path / "tn-2.network.json").write_text("{}")
    assert suffix_of("x.sketch", "drawing") == ".sketch"
    assert _common.find_drawings([str(tmp_path)]) == [(tmp_path / "sub" / "tn-2.sketch", _common.Path("sub"))]
    assert _common.stem("tn-2.sketch") == "tn-2"
    ws = Workspace(tmp_path)
    assert ws.drawings() == ["sub/tn-2.sketch"]
    assert drawing_endings() == ".uc or .json or .sketch"
    doc = open_document(ws, "sub/tn-2.sketch")
    assert doc.drawing.curves == d.curves
    assert doc.save("copy.sketch") == "copy.sketch"
    assert load(tmp_path / "copy.sketch").curves == d.curves
    assert export_file(doc.net, doc.name, format="json")[0] == "copy.json"
