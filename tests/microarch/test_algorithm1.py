"""Algorithm 1 (PRC choice) on the legacy drawings, which store no PRC.

Every legacy drawing is checked against an independent brute-force oracle:
the curves are flattened into dense polylines, all crossings with every
replica are found by segment-segment tests, own-replica crossings count as
true when both parameters agree to 1e-4, and the crossing closest to the
midpoint (own replicas first, then other curves of the layer, else the
midpoint) must be the one Algorithm 1 chose. U.XI.26 is also checked by hand.
"""

from __future__ import annotations

import numpy as np
import pytest

from auszug.formats import load
from auszug.microarch import build
from auszug.microarch.prc import algorithm1, oriented_segments
from tests.conftest import CORPUS, corpus_files

LEGACY = corpus_files("legacy")
N = 1201


def _crossings(p: np.ndarray, q: np.ndarray) -> list[tuple[float, float, np.ndarray]]:
    """Crossings of two polylines (n, 2) and (m, 2): (u on p, u on q, point), u by index."""
    lo = np.minimum(p[:-1], p[1:]).min(0), np.maximum(p[:-1], p[1:]).max(0)
    lq = np.minimum(q[:-1], q[1:]).min(0), np.maximum(q[:-1], q[1:]).max(0)
    # keep only the segments inside the other polyline's bounding box
    ip = np.nonzero(np.all((np.maximum(p[:-1], p[1:]) >= lq[0]) & (np.minimum(p[:-1], p[1:]) <= lq[1]), axis=1))[0]
    iq = np.nonzero(np.all((np.maximum(q[:-1], q[1:]) >= lo[0]) & (np.minimum(q[:-1], q[1:]) <= lo[1]), axis=1))[0]
    if len(ip) == 0 or len(iq) == 0:
        return []
    a, b = p[ip], p[ip + 1]
    c, d = q[iq], q[iq + 1]
    r = b - a
    s = d - c
    den = r[:, None, 0] * s[None, :, 1] - r[:, None, 1] * s[None, :, 0]
    w = c[None, :, :] - a[:, None, :]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (w[..., 0] * s[None, :, 1] - w[..., 1] * s[None, :, 0]) / den
        v = (w[..., 0] * r[:, None, 1] - w[..., 1] * r[:, None, 0]) / den
    ok = (np.abs(den) > 1e-15) & (t >= 0) & (t < 1) & (v >= 0) & (v < 1)
    out = []
    for i, j in zip(*np.nonzero(ok), strict=True):
        out.append(((ip[i] + t[i, j]) / (len(p) - 1), (iq[j] + v[i, j]) / (len(q) - 1), a[i] + t[i, j] * r[i]))
    return out


def _oracle(drawing):
    segs = oriented_segments(drawing)
    dense = {(ci, si): top.point_at(np.linspace(0, 1, N)) for ci, si, top in segs}
    out = {}
    for ci, si, _ in segs:
        c = drawing.curves[ci]
        if c.segment_kind(si) != "ogee":
            continue
        own, other = [], []
        for cj, sj, _ in segs:
            if drawing.curves[cj].layer != c.layer:
                continue
            sym = drawing.curves[cj].symmetry
            for k, m in enumerate(sym.matrices()):
                same = (ci, si) == (cj, sj)
                if same and k == 0:
                    continue
                rep = (dense[(cj, sj)] - sym.center) @ m.T + sym.center
                here = dense[(ci, si)]
                if same and (np.abs(rep - here).max() < 1e-9 or np.abs(rep[::-1] - here).max() < 1e-9):
                    continue
                for u, u2, pt in _crossings(dense[(ci, si)], rep):
                    if not 1e-3 < u < 1 - 1e-3:
                        continue
                    if same:
                        if abs(u - u2) < 1e-4:
                            own.append((u, pt))
                    else:
                        other.append((u, pt))
        for branch, cands in (("own replicas", own), ("other curves", other)):
            if cands:
                u, pt = min(cands, key=lambda x: (abs(x[0] - 0.5), x[0]))
                out[(ci, si)] = (branch, u, pt)
                break
        else:
            out[(ci, si)] = ("midpoint", 0.5, None)
    return out


@pytest.mark.parametrize("path", LEGACY, ids=[p.name for p in LEGACY])
def test_algorithm1_matches_brute_force(path):
    drawing = load(path)
    chosen = algorithm1(drawing)
    expect = _oracle(drawing)
    assert set(chosen) == set(expect)
    for key, (branch, u, pt) in expect.items():
        ch = chosen[key]
        assert ch.branch == branch, f"{path.name} {key}: {ch.branch} != {branch}"
        assert abs(ch.fraction - u) < 2e-4, f"{path.name} {key}: u {ch.fraction} != {u}"
        if pt is not None:
            assert np.linalg.norm(ch.point - pt) < 1e-3
    # the network uses these choices (no PRC is stored in legacy files)
    net = build(drawing)
    for (ci, si), ch in chosen.items():
        piece = next(p for p in net.pieces if p.basic == ci and p.segment == si and p.kind == "ogee")
        assert piece.prc_fraction == ch.fraction


def test_algorithm1_uxi26_by_hand():
    # curve 0: (-1, 0) -> (-0.6, -0.9), C4 with the mirror in the x axis. Its replica
    # "mirror, then rotate by 90 deg" runs (0, -1) -> (-0.9, -0.6); solving
    # (-1 + 0.4 s, -0.9 s) = (-0.9 t, -1 + 0.4 t) gives s = t = 10/13: a true
    # intersection at (-9/13, -9/13), the only interior one with its own replicas.
    ch = algorithm1(load(CORPUS / "legacy" / "U.XI.26.uc"))[(0, 0)]
    assert ch.branch == "own replicas"
    assert abs(ch.fraction - 10 / 13) < 1e-12
    np.testing.assert_allclose(ch.point, [-9 / 13, -9 / 13], atol=1e-12)
    assert ch.intersection.replica in ("r1m", "r3m") and ch.intersection.true
