"""Our reconstructions against the authors' demo (tests/data/reference/anchor).

Every ogee and free-end curve of the 12 teaching-sheet examples and of every
web-format corpus drawing must lie within 1e-6 of the bounding-box diagonal of
the demo's curve, except for the documented deviations below, each explained.
The distance is measured exactly: each reference sample is mapped back to the
basic curve by the inverse symmetry, projected onto our exact top view, and
compared with our exact 3D point there.
"""

from __future__ import annotations

import hashlib
import json

import numpy as np
import pytest

from auszug.formats import load
from auszug.microarch import build
from tests.conftest import ANCHOR, CORPUS
from tests.helpers import our_label, read_reference_obj, read_text

SUMMARY = json.loads((ANCHOR / "summary.json").read_text())
CASES = sorted(k for k, v in SUMMARY.items() if v.get("ok"))

# Documented deviations of the demo from the paper (see ANCHOR/README.md):
# decorated curves: the demo refits the whole ogee between the decoration point
# and the apex and meets the decoration with a corner; we keep the ogee and split
# its lower arc into two equal-radius arcs (G1, suppl. C). So the ogees of
# decorated curves differ by design (our decorations are checked against the
# paper's rule in test_sideview.py); only their other pieces are compared.
DECORATED = {(k, c["index"]) for k, v in SUMMARY.items() if v.get("ok") for c in v["curves"]
             if c["decoration_t"] != 0}


def _distances(net, piece_index, label, ref_pts):
    """Distance of every reference point to our exact curve, and the top-view parameter.

    Each point is mapped back to the basic curve by the inverse symmetry and
    projected onto our exact top view; the 3D distance is then taken to our
    curve densely resampled (segments of ~1e-5 of its length: chord error far
    below the tolerance) in a window around that parameter. This is the true
    distance also near the vertical end tangents, where a rounding error of the
    reference in x and y would otherwise show as a large height error.
    """
    piece = net.pieces[piece_index]
    sym = net.drawing.curves[piece.basic].symmetry
    k = sym.labels().index(our_label(label, sym.fold))
    m = sym.matrices()[k]
    c = np.asarray(sym.center)
    q = (ref_pts[:, :2] - c) @ m + c          # m^T (p - c) + c, row form
    ts = np.array([piece.top.project(p) for p in q])
    ref = np.concatenate([q, ref_pts[:, 2:]], axis=1)
    win = np.clip(ts[:, None] + np.linspace(-0.004, 0.004, 801)[None, :], 0.0, 1.0)
    ours = np.concatenate([piece.top.point(win), piece.height_at_t(win)[..., None]], axis=-1)
    a, b = ours[:, :-1], ours[:, 1:]
    ab = b - a
    w = np.clip(np.einsum("nkd,nkd->nk", ref[:, None] - a, ab) / np.maximum(
        np.einsum("nkd,nkd->nk", ab, ab), 1e-300), 0.0, 1.0)
    d = np.linalg.norm(a + w[..., None] * ab - ref[:, None], axis=-1).min(axis=1)
    return d, ts


@pytest.mark.parametrize("case", CASES)
def test_matches_reference(case):
    drawing = load(CORPUS / case)
    net = build(drawing)
    ref = read_reference_obj(ANCHOR / (case[:-3] + ".obj.xz"))
    allref = np.concatenate(list(ref.values()))
    diag = float(np.linalg.norm(allref.max(0) - allref.min(0)))
    tol = 1e-6 * diag
    compared = 0
    for (basic, kind, label), pts in sorted(ref.items()):
        if kind not in ("ogee", "free_end"):
            continue
        idx = [i for i, p in enumerate(net.pieces) if p.basic == basic and p.kind == kind]
        assert len(idx) == 1, f"{case}: expected one {kind} piece of curve {basic}"
        d, ts = _distances(net, idx[0], label, pts)
        if (case, basic) in DECORATED and kind == "ogee":
            continue
        # the curves must also cover each other: same end points
        piece = net.pieces[idx[0]]
        ends = np.array([ts[0], ts[-1]])
        assert np.allclose(ends, [0.0, 1.0], atol=tol / piece.top.length()), (
            f"{case} curve {basic} {label} {kind}: ends at t = {ends}")
        assert d.max() <= tol, f"{case} curve {basic} {label} {kind}: max distance {d.max():.3g} > {tol:.3g}"
        compared += 1
    assert compared > 0


def test_reference_files_are_the_demos():
    """The stored references decompress to the demo's files, byte for byte (ANCHOR/SHA256SUMS),
    and every drawing the summary lists as read has one."""
    sums = dict(line.split("  ")[::-1] for line in (ANCHOR / "SHA256SUMS").read_text().splitlines())
    stored = {str(p.relative_to(ANCHOR)).removesuffix(".xz") for p in ANCHOR.rglob("*.obj.xz")}
    assert stored == {n for n in sums if n.endswith(".obj")}
    assert stored == {c[:-3] + ".obj" for c in CASES}
    for name, digest in sums.items():
        path = ANCHOR / (name + ".xz" if name.endswith(".obj") else name)
        data = read_text(path).encode("utf-8")
        assert hashlib.sha256(data).hexdigest() == digest, f"{name} differs from the demo's output"
