"""End to end, the tube look (the default): the selected curve's members are highlighted, in the
server's mesh and in the tubes the page sweeps itself while the drawing changes (web/src/tubes.ts).

U.XI.28 (the web file: four basic curves under C_4 with mirrors) is copied into the workspace.
"""

from __future__ import annotations

import io
import shutil
from typing import Any

import pytest

from auszug import examples

from .e2e import SHOTS, browser, geometry, needs_browser, open_drawing, page, studio  # noqa: F401  (fixtures)

pytestmark = needs_browser

#: The highlight colour of the selected curve (web/src/scene.ts SELECTED), written out here.
HIGHLIGHT = "#d97706"
#: The 3D view's ground (web/src/scene.ts SKY) and how far other curves fade towards it (looks.ts FADE).
SKY, FADE = (0xE9, 0xEE, 0xF3), 0.6


def faded(hex_colour: str) -> str:
    """``hex_colour`` mixed with SKY by FADE per channel, rounded half up (as the page does)."""
    rgb = [int(hex_colour[i:i + 2], 16) for i in (1, 3, 5)]
    return "#" + "".join(f"{int(a + FADE * (b - a) + 0.5):02x}" for a, b in zip(rgb, SKY, strict=True))


@pytest.fixture
def uxi28(workspace):
    shutil.copy(examples.path("web/U.XI.28.uc"), workspace / "U.XI.28.uc")
    return "U.XI.28.uc"


def wait_server_mesh(page: Any) -> None:
    """Wait until the server's mesh of the current geometry is drawn (and the page's tubes hidden)."""
    page.wait_for_function("""() => {
        const s = window.auszug.store, sc = window.auszug.views.scene;
        return !!s.mesh && !!s.geometry && s.mesh.revision === s.geometry.revision
          && sc.getObjectByName('meshes').children.length > 0 && !sc.getObjectByName('drag-tubes').visible;
    }""", timeout=30000)
    page.evaluate("() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))")


def member_colours(page: Any, group: str) -> dict[int, set[str]]:
    """The material colours of the visible members in ``group``, per basic curve."""
    pairs = page.evaluate(f"""() => window.auszug.views.scene.getObjectByName('{group}').children
        .filter((o) => o.visible && o.userData.basic >= 0)
        .map((o) => [o.userData.basic, '#' + o.material.color.getHexString()])""")
    out: dict[int, set[str]] = {}
    for b, c in pairs:
        out.setdefault(b, set()).add(c)
    return out


def palette(page: Any) -> dict[int, str]:
    return dict(enumerate(page.evaluate("() => [0, 1, 2, 3].map((i) => window.auszug.store.color(i))")))


def view3d_pixels(page: Any) -> Any:
    """The 3D view's pixels as an (h, w, 3) uint8 array, from a screenshot."""
    import matplotlib.image
    import numpy as np

    box = page.evaluate("""() => { const v = window.auszug.views, r = v.rect('persp'), b = v.box();
        return {x: b.left + r.x, y: b.top + r.y, width: r.w, height: r.h}; }""")
    png = page.screenshot(clip=box)
    return np.rint(matplotlib.image.imread(io.BytesIO(png), format="png")[..., :3] * 255).astype(int)


def blue(px: Any) -> int:
    """Pixels of curve 0's blue (#0072B2, lit): blue well above red and green."""
    r, g, b = px[..., 0], px[..., 1], px[..., 2]
    return int(((b - r > 60) & (b - g > 20)).sum())


def saturated(px: Any) -> tuple[int, int]:
    """Strongly coloured pixels (channels spread over 100): (warm ones, red > green > blue, as
    the amber highlight and the vermilion; all others)."""
    r, g, b = px[..., 0], px[..., 1], px[..., 2]
    sat = px.max(axis=-1) - px.min(axis=-1) > 100
    warm = sat & (r > g) & (g > b)
    return int(warm.sum()), int((sat & ~warm).sum())


def test_selected_curve_is_highlighted_in_the_tube_look(studio, uxi28, page):
    open_drawing(page, studio, uxi28)
    assert page.input_value("[data-testid=look-style]") == "tube"   # the default look
    wait_server_mesh(page)
    colours = palette(page)
    assert HIGHLIGHT not in colours.values()
    assert member_colours(page, "meshes") == {b: {c.lower()} for b, c in colours.items()}
    before = view3d_pixels(page)

    page.select_option("[data-testid=side-curve]", "0")
    page.evaluate("() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))")
    assert member_colours(page, "meshes") == {0: {HIGHLIGHT}, **{b: {faded(colours[b].lower())} for b in (1, 2, 3)}}
    after = view3d_pixels(page)
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / "test_selected_curve_is_highlighted_in_the_tube_look-selected.png"))
    # what is drawn: curve 0's blue tubes turn amber (the other curves, vermilion, green and pink,
    # fade towards the ground, so the amber is not confused with the vermilion)
    assert blue(before) > 500, blue(before)
    assert blue(after) < blue(before) / 10, (blue(before), blue(after))
    # the amber tubes are the only strong colour left (the faded ones are pale)
    warm, other = saturated(after)
    assert warm > blue(before) / 2, (warm, blue(before))
    assert other < blue(before) / 20, (other, blue(before))
    assert saturated(before)[1] > blue(before) / 2     # before: blue and green were strong colours

    # an edit: the page's own tubes show the new geometry at once, the selection highlighted too
    page.evaluate("""() => { window.__seen = []; window.auszug.store.on('geometry', () => {
        const d = window.auszug.views.scene.getObjectByName('drag-tubes');
        window.__seen.push({visible: d.visible, n: d.children.length, instances: d.children.map((o) => o.count),
          colours: d.children.map((o) => [o.userData.basic, '#' + o.material.color.getHexString()])});
    }); }""")
    rev = geometry(page)["revision"]
    page.fill("[data-testid=apex-height]", "1.1")
    page.press("[data-testid=apex-height]", "Enter")
    page.wait_for_function(f"() => window.auszug.store.geometry.revision > {rev}")
    seen = page.evaluate("() => window.__seen")[0]
    # four ogees, each drawn once per replica (rotated and mirrored: 8 each, the network's 32 lines)
    assert seen["visible"] and seen["n"] == 4 and seen["instances"] == [8, 8, 8, 8]
    assert {tuple(c) for c in seen["colours"]} == {(0, HIGHLIGHT), *((b, faded(colours[b].lower())) for b in (1, 2, 3))}
    wait_server_mesh(page)
    assert member_colours(page, "meshes")[0] == {HIGHLIGHT}

    # preview shows the design as it is: no highlight, as for the lines
    page.click("[data-testid=mode-preview]")
    page.evaluate("() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))")
    assert member_colours(page, "meshes") == {b: {c.lower()} for b, c in colours.items()}
    page.click("[data-testid=mode-design]")
    page.select_option("[data-testid=side-curve]", "")
    page.evaluate("() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))")
    assert member_colours(page, "meshes") == {b: {c.lower()} for b, c in colours.items()}


def test_drag_tubes_cover_what_the_server_tubes_cover(studio, uxi28, page):
    """While a button is held the page draws its own tubes (strips turned to the camera, shaded
    round): as wide as the server's tubes, so curve 0's blue covers about as many pixels."""
    open_drawing(page, studio, uxi28)
    wait_server_mesh(page)
    served = blue(view3d_pixels(page))
    box = page.locator("#status").bounding_box()
    page.mouse.move(box["x"] + 5, box["y"] + 5)
    page.mouse.down()   # held: the server's mesh waits for the release (looks.ts)
    g = geometry(page)
    rev = g["revision"]
    page.evaluate("(h) => window.auszug.ctx.send({type: 'set_apex_height', curve: 1, height: h})",
                  g["curves"][1]["apex"] * 0.98)
    page.wait_for_function(f"() => window.auszug.views.membersRevision > {rev}")
    page.evaluate("() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))")
    assert page.evaluate("() => window.auszug.views.scene.getObjectByName('drag-tubes').visible")
    assert not page.evaluate("() => window.auszug.views.scene.getObjectByName('meshes').children"
                             ".some((o) => o.visible && o.userData.basic >= 0)")
    drawn = blue(view3d_pixels(page))
    page.mouse.up()
    assert served > 500, served
    assert 0.8 * served < drawn < 1.25 * served, (served, drawn)


def test_tube_look_draws_lines_only_in_views_without_members(studio, uxi28, page):
    """The tube look's members cover the network's lines: the lines are drawn in the top view in
    design mode, in no view in preview mode (members in all three); the curves look draws them in
    every view."""
    open_drawing(page, studio, uxi28)
    seen = """() => { const v = window.auszug.views;
        return ['top', 'persp', 'side'].map((n) =>
          v.network.children.filter((l) => l.layers.test(v.camera(n).layers)).length); }"""
    assert page.evaluate(seen) == [32, 0, 32]   # (the side view shows in preview mode only)
    page.click("[data-testid=mode-preview]")
    assert page.evaluate(seen) == [0, 0, 0]
    page.click("[data-testid=mode-design]")
    page.select_option("[data-testid=look-style]", "curves")
    assert page.evaluate(seen) == [32, 32, 32]
    page.select_option("[data-testid=look-style]", "tube")
    assert page.evaluate(seen) == [32, 0, 32]
