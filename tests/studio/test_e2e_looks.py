"""End to end, looks: members and faces from get_mesh drawn as instanced meshes, picked faces, GPU memory.

U.XI.28 (the web file: four basic curves under C_4 with mirrors) is copied into the workspace.
"""

from __future__ import annotations

import shutil
from collections import Counter
from typing import Any

import pytest

from auszug import examples

from .e2e import SHOTS, browser, geometry, needs_browser, open_drawing, page, studio  # noqa: F401  (fixtures)

pytestmark = needs_browser


@pytest.fixture
def uxi28(workspace):
    shutil.copy(examples.path("web/U.XI.28.uc"), workspace / "U.XI.28.uc")
    return "U.XI.28.uc"


def wait_mesh(page: Any, timeout: float = 30000, faces: str = "true") -> dict:
    """Wait until the meshes drawn are those of the current geometry (and ``faces``, JS of ``m``, holds)."""
    page.wait_for_function(f"""() => {{
        const s = window.auszug.store, m = s.mesh, grp = window.auszug.views.scene.getObjectByName('meshes');
        return !!m && !!s.geometry && m.revision === s.geometry.revision && grp.children.length > 0 && ({faces});
    }}""", timeout=timeout)
    return page.evaluate("() => window.auszug.store.mesh")


def next_frame(page: Any) -> None:
    page.evaluate("() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))")


def drawn(page: Any) -> list[dict]:
    """The meshes in the scene: name, instance count, instanced or not, the geometry's position buffer."""
    return page.evaluate("""() => window.auszug.views.scene.getObjectByName('meshes').children.map((o) => ({
        name: o.name, count: o.count, instanced: !!o.isInstancedMesh, basic: o.userData.basic,
        positions: o.geometry.getAttribute('position').uuid ?? o.geometry.getAttribute('position').array.byteOffset,
        doubleSided: o.material.side === 2, color: '#' + o.material.color.getHexString(),
    }))""")


def memory(page: Any) -> dict:
    return page.evaluate("() => ({...window.auszug.views.renderer.info.memory})")


def test_tube_and_faces_are_instanced_per_piece(studio, uxi28, page):
    g = open_drawing(page, studio, uxi28)
    page.select_option("[data-testid=look-style]", "tube")
    page.select_option("[data-testid=look-faces]", "auto")
    mesh = wait_mesh(page, faces="m.faces > 0")
    objs = drawn(page)
    assert all(o["instanced"] for o in objs)
    instances = Counter()
    for o in objs:
        instances[o["name"]] += o["count"]
    replicas = {p["basic"]: p["transforms"]["shape"][0] for p in g["pieces"] if p["kind"] == "ogee"}
    for p in mesh["pieces"]:
        assert instances[p["name"]] == p["transforms"]["shape"][0], p["name"]
        if p["basic"] >= 0:
            assert instances[p["name"]] == replicas[p["basic"]] == 8
    # one geometry per piece (a mirrored replica reuses its positions): instances, not copies
    assert len({(o["name"], o["positions"]) for o in objs}) == len(mesh["pieces"])
    faces = [o for o in objs if o["basic"] == -1]
    assert len(faces) == 1 and faces[0]["count"] == 1 and faces[0]["doubleSided"]
    colors = page.evaluate("() => [0, 1, 2, 3].map((i) => window.auszug.store.color(i))")
    for o in objs:
        if o["basic"] >= 0:
            assert o["color"] == colors[o["basic"]]
    assert "faces" in page.inner_text("[data-testid=look-info]")
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / "test_tube_and_faces_are_instanced_per_piece-tubes.png"))

    # back to curves without faces: the meshes go, and no more requests are made
    page.select_option("[data-testid=look-style]", "curves")
    page.select_option("[data-testid=look-faces]", "none")
    page.wait_for_function("() => window.auszug.views.scene.getObjectByName('meshes').children.length === 0")


def test_gpu_memory_stays_constant_over_edits(studio, uxi28, page):
    open_drawing(page, studio, uxi28)
    page.select_option("[data-testid=side-curve]", "0")
    page.select_option("[data-testid=look-style]", "tube")
    page.select_option("[data-testid=look-faces]", "auto")
    wait_mesh(page)
    seen = []
    for i in range(50):
        rev = geometry(page)["revision"]
        page.fill("[data-testid=apex-height]", f"{1.0 + 0.02 * (i % 5):.2f}")
        page.press("[data-testid=apex-height]", "Enter")
        page.wait_for_function(f"() => window.auszug.store.geometry.revision > {rev}")
        wait_mesh(page)
        next_frame(page)
        seen.append(memory(page))
    first = seen[0]
    assert first["geometries"] > 0
    assert all(m == first for m in seen), f"GPU memory changed over edits: {seen}"
    page.wait_for_timeout(3000)
    next_frame(page)
    assert memory(page) == first


def test_picked_faces_toggle_by_click(studio, uxi28, page):
    open_drawing(page, studio, uxi28)
    page.select_option("[data-testid=look-style]", "curves")   # faces alone (tubes are the default)
    page.select_option("[data-testid=look-faces]", "picked")
    page.wait_for_function("""() => { const s = window.auszug.store;
        return s.loops && s.loops.revision === s.geometry.revision && s.loops.loops.length > 0
            && window.auszug.views.scene.getObjectByName('loops').children.length > 0; }""", timeout=30000)
    next_frame(page)
    # the loop whose centre lies farthest from the others' on screen, in the 3D view
    index, x, y = pick_target(page)
    page.mouse.click(x, y)
    page.wait_for_function(f"() => window.auszug.store.looks.loops.includes({index})")
    mesh = wait_mesh(page, faces="m.faces === 1")
    assert [p["basic"] for p in mesh["pieces"]] == [-1]
    page.mouse.click(x, y)
    page.wait_for_function("() => window.auszug.store.looks.loops.length === 0")
    page.wait_for_function("() => { const m = window.auszug.store.mesh; return m && m.faces === 0; }")


def pick_target(page: Any) -> tuple[int, float, float]:
    """A loop's index and the client position of its centre in the 3D view, far from the other centres."""
    return page.evaluate("""() => {
        const { store, views } = window.auszug;
        const v = views.persp.position.clone();
        const pts = store.loops.loops.map((l) => [l.index, views.worldToClient('persp', v.set(...l.centre))]);
        let best = null, bestD = -1;
        for (const [i, p] of pts) {
            const d = Math.min(...pts.filter(([j]) => j !== i).map(([, q]) => Math.hypot(p[0] - q[0], p[1] - q[1])));
            if (d > bestD) [best, bestD] = [[i, p[0], p[1]], d];
        }
        return best;
    }""")


def ink_per_view(page: Any, path: Any) -> list[int]:
    """Pixels off the background in each view of the current mode."""
    import matplotlib.image
    import numpy as np

    page.locator("canvas").screenshot(path=str(path))
    img = matplotlib.image.imread(path)[..., :3]
    ink = np.abs(img - np.array([0xF4, 0xF1, 0xEA]) / 255).max(axis=-1) > 0.15
    rects = page.evaluate("() => ['persp', 'top', 'side'].map((v) => window.auszug.views.rect(v)).filter(Boolean)")
    return [int(ink[30 : r["h"] - 10, r["x"] + 4 : r["x"] + r["w"] - 4].sum()) for r in rects]


def test_preview_shows_meshes_in_all_three_views(studio, uxi28, page, tmp_path):
    open_drawing(page, studio, uxi28)
    in_views = """() => { const v = window.auszug.views, ms = v.scene.getObjectByName('meshes').children;
        return ['top', 'persp', 'side'].map((c) => ms.every((m) => m.layers.test(v[c].layers))); }"""
    page.select_option("[data-testid=look-style]", "curves")   # 1 px lines first (tubes are the default)
    page.wait_for_function("() => window.auszug.views.scene.getObjectByName('meshes').children.length === 0")
    page.click("[data-testid=mode-preview]")
    next_frame(page)
    lines = ink_per_view(page, tmp_path / "lines.png")
    page.select_option("[data-testid=look-style]", "bar")
    wait_mesh(page)
    assert page.evaluate(in_views) == [True, True, True]
    next_frame(page)
    bars = ink_per_view(page, tmp_path / "bars.png")
    assert len(bars) == 3, f"ink: lines {lines}, bars {bars}"
    assert all(b > 1.5 * n for b, n in zip(bars, lines, strict=True)), f"ink: lines {lines}, bars {bars}"
    page.click("[data-testid=mode-design]")
    assert page.evaluate(in_views) == [False, True, False]  # design: members only in the 3D view
    page.click("[data-testid=mode-preview]")
    assert page.evaluate(in_views) == [True, True, True]
