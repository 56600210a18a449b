"""End to end, the 3D view: tubes by default, a raised three-quarter camera framing the model, a refit
only when the model grows out of the view, and the resizable split between the top and 3D views."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .e2e import browser, geometry, needs_browser, open_drawing, page, studio, wait_revision  # noqa: F401  (fixtures)

pytestmark = needs_browser

#: The opening view (web/src/scene.ts VIEW3D): elevation, azimuth (degrees) and the fill of the binding axis.
ELEVATION, AZIMUTH, FILL = 35.0, 35.0, 0.8

CAMERA_JS = """() => {
  const v = window.auszug.views, p = v.persp.position, t = v.orbit.target, b = v.bounds;
  v.persp.updateMatrixWorld();
  const points = [];   // every point of the network's lines (all replicas), projected
  for (const line of v.network.children) {
    const pos = line.geometry.getAttribute('position');
    for (let i = 0; i < pos.count; i++) {
      const n = p.clone().fromBufferAttribute(pos, i).applyMatrix4(line.matrix).project(v.persp);
      points.push([n.x, n.y, n.z]);
    }
  }
  return {position: [p.x, p.y, p.z], target: [t.x, t.y, t.z], centre: b.getCenter(p.clone()).toArray(),
          points, refits: v.refits, persp: v.rect('persp'), top: v.rect('top'), width: v.host.clientWidth};
}"""


def camera(page: Any) -> dict:
    return page.evaluate(CAMERA_JS)


def direction(c: dict) -> np.ndarray:
    d = np.subtract(c["position"], c["target"])
    return d / np.linalg.norm(d)


def settle(page: Any) -> None:
    page.evaluate("() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))")


def test_opens_on_tubes_in_a_raised_three_quarter_view_framing_the_model(studio, page):
    g = open_drawing(page, studio, "tn-2.uc")
    # tubes by default: the select says so, the URL leaves the default out, meshes are in the scene
    assert page.eval_on_selector("[data-testid=look-style]", "e => e.value") == "tube"
    page.wait_for_function("""() => {
        const s = window.auszug.store, grp = window.auszug.views.scene.getObjectByName('meshes');
        return s.mesh && s.mesh.style === 'tube' && s.mesh.revision === s.geometry.revision
          && grp.children.length > 0 && grp.children.every((o) => o.isInstancedMesh && o.count > 0);
    }""", timeout=30000)
    assert "style=" not in page.url
    c = camera(page)
    # the 3D pane takes half of the viewport by default
    assert c["persp"]["w"] >= c["width"] / 2 - 1 and c["top"]["w"] + c["persp"]["w"] == c["width"]
    # the camera looks at the box's centre from 35 degrees up, 35 degrees round from the front
    np.testing.assert_allclose(c["target"], c["centre"], atol=1e-9)
    d = direction(c)
    assert abs(math.degrees(math.asin(d[2])) - ELEVATION) < 1e-6
    assert abs(math.degrees(math.atan2(d[0], -d[1])) - AZIMUTH) < 1e-6
    # every point of the curves is in view, and the binding one sits at exactly FILL
    ndc = np.array(c["points"])
    assert len(ndc) > 100
    assert np.all(ndc[:, 2] < 1) and np.all(ndc[:, 2] > -1), "a point is clipped by the near or far plane"
    extent = np.abs(ndc[:, :2]).max()
    assert abs(extent - FILL) < 1e-4, f"the curves reach {extent:.4f} of the half view, wanted {FILL}"
    # the model fills a good part of the pane (not a speck in a corner)
    span = (ndc[:, :2].max(axis=0) - ndc[:, :2].min(axis=0)) / 2
    assert span.max() > 0.7, f"the projected curves span {span} of the view"
    assert g["n_curves"] > 0


def test_refits_only_when_the_model_grows_out_of_the_view(studio, page):
    g = open_drawing(page, studio, "tn-2.uc")
    settle(page)
    c0 = camera(page)
    # the user orbits the 3D view (a real drag in it)
    p = c0["persp"]
    box = page.locator("canvas").bounding_box()
    x, y = box["x"] + p["x"] + p["w"] / 2, box["y"] + p["y"] + p["h"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    for k in range(1, 11):
        page.mouse.move(x + 8 * k, y + 3 * k)
    page.mouse.up()
    settle(page)
    c1 = camera(page)
    assert np.linalg.norm(direction(c1) - direction(c0)) > 0.05, "the drag did not orbit the camera"
    # an edit that shrinks the model keeps the user's camera exactly
    page.select_option("[data-testid=side-curve]", "0")
    apex = g["curves"][0]["apex"]
    page.fill("[data-testid=apex-height]", f"{apex * 0.9:.6g}")
    page.press("[data-testid=apex-height]", "Enter")
    g = wait_revision(page, g["revision"])
    settle(page)
    c2 = camera(page)
    assert c2["position"] == c1["position"] and c2["target"] == c1["target"] and c2["refits"] == 0
    # an edit that raises the model far out of the view refits it, seen from where the user looked
    size = np.subtract(g["bounds"][3:], g["bounds"][:3])
    high = apex + 3 * float(max(size))
    page.fill("[data-testid=apex-height]", f"{high:.6g}")
    page.press("[data-testid=apex-height]", "Enter")
    g = wait_revision(page, g["revision"])
    assert g["bounds"][5] > c1["target"][2] + float(max(size))
    settle(page)
    c3 = camera(page)
    assert c3["refits"] == 1
    np.testing.assert_allclose(direction(c3), direction(c1), atol=1e-9)
    np.testing.assert_allclose(c3["target"], c3["centre"], atol=1e-9)
    ndc = np.array(c3["points"])
    assert abs(np.abs(ndc[:, :2]).max() - FILL) < 1e-4
    # undo shrinks it again: no refit, the camera stays
    page.keyboard.press("Control+z")
    wait_revision(page, g["revision"])
    settle(page)
    c4 = camera(page)
    assert c4["refits"] == 1 and c4["position"] == c3["position"]


def test_split_handle_resizes_the_views_and_the_url_keeps_it(studio, page):
    open_drawing(page, studio, "tn-2.uc")
    handle = page.locator("[data-testid=split-handle]")
    hb = handle.bounding_box()
    vb = page.locator("#viewport").bounding_box()
    c = camera(page)
    assert abs(hb["x"] + hb["width"] / 2 - (vb["x"] + c["persp"]["x"])) <= 1
    x, y = hb["x"] + hb["width"] / 2, hb["y"] + hb["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    target = vb["x"] + 0.3 * vb["width"]
    for k in range(1, 9):
        page.mouse.move(x + (target - x) * k / 8, y)
    page.mouse.up()
    settle(page)
    c = camera(page)
    assert abs(c["top"]["w"] - 0.3 * c["width"]) <= 1 and c["top"]["w"] + c["persp"]["w"] == c["width"]
    split = page.evaluate("() => window.auszug.store.split")
    assert abs(split - 0.3) < 1 / vb["width"] + 1e-9
    assert f"split={split:.3f}".rstrip("0") in page.url
    # the geometry is still drawn in both views: no edit came from the drag
    assert page.evaluate("() => window.auszug.store.geometry.revision") == geometry(page)["revision"]
    # a reload comes back to the same split; the handle cannot leave 20-80 %
    page.reload()
    page.wait_for_function("() => window.auszug && window.auszug.store.geometry !== null")
    assert page.evaluate("() => window.auszug.store.split") == float(f"{split:.3f}")
    hb = handle.bounding_box()
    x = hb["x"] + hb["width"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(vb["x"] + vb["width"] - 2, y, steps=5)
    page.mouse.up()
    assert page.evaluate("() => window.auszug.store.split") == 0.8
    # double click: half and half again (the default, left out of the URL)
    handle.dblclick()
    assert page.evaluate("() => window.auszug.store.split") == 0.5
    assert "split=" not in page.url


def test_export_resolution_makes_a_light_glb(studio, workspace, page, tmp_path):
    import trimesh

    from auszug.formats import load
    from auszug.meshing import default_size, profile_for, sweep_network
    from auszug.microarch import build

    open_drawing(page, studio, "tn-2.uc")
    sizes = {}
    for res in ("fine", "light"):
        page.click("[data-testid=export]")
        page.select_option("[data-testid=export-resolution]", res)
        with page.expect_download(timeout=60000) as dl:
            page.click("[data-testid=export-glb]")
        path = tmp_path / f"{res}.glb"
        dl.value.save_as(path)
        sizes[res] = path.stat().st_size
    # the light file is the tubes swept 48 steps along, 10 points round: exactly that many triangles
    net = build(load(workspace / "tn-2.uc"))
    want = sweep_network(net, profile_for("tube", default_size(net), 10), 48).n_faces
    scene = trimesh.load(tmp_path / "light.glb", file_type="glb")
    assert sum(len(g.faces) for g in scene.geometry.values()) == want
    assert sizes["light"] * 10 < sizes["fine"], sizes
