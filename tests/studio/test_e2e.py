"""End to end, basics: the studio page shows a drawing with every replica in both views."""

from __future__ import annotations

import numpy as np

from auszug.formats import load
from auszug.microarch import build

from .e2e import browser, needs_browser, open_drawing, page, studio  # noqa: F401  (fixtures)

pytestmark = needs_browser


def test_studio_renders_drawing(studio, workspace, page, tmp_path):  # noqa: F811  (fixtures from e2e.py)
    expected = len(list(build(load(workspace / "tn-2.uc")).curves()))
    g = open_drawing(page, studio, "tn-2.uc")
    assert g["n_replicas"] == expected
    status = page.locator("#status")
    assert status.get_attribute("data-replicas") == str(expected)
    assert f"{expected} replicas" in status.inner_text()
    box = page.locator("canvas").bounding_box()
    assert box is not None and box["width"] > 900 and box["height"] > 600
    # every replica is one three.js line in the scene
    assert page.evaluate("() => window.auszug.views.network.children.length") == expected
    page.wait_for_function("() => window.auszug.views.frames > 0")
    shot = tmp_path / "studio.png"
    page.locator("canvas").screenshot(path=str(shot))
    import matplotlib.image

    img = matplotlib.image.imread(shot)[..., :3]
    background = np.array([0xF4, 0xF1, 0xEA]) / 255
    ink = np.abs(img - background).max(axis=-1) > 0.15
    h, w = ink.shape
    body = ink[40 : h - 10]  # leave out the view labels
    split = int(page.evaluate("() => window.auszug.views.rect('top').w / window.auszug.views.host.clientWidth") * w)
    left, right = body[:, :split].sum(), body[:, split:].sum()
    assert left > 200 and right > 200, f"lines drawn: top view {left} px, 3D view {right} px"
