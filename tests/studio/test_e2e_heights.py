"""End to end, heights: the side view's apex, PRC and bottom drags, layers, decoration and post, preview.

Every interaction is a real mouse or keyboard event; pixels convert to heights through the side
view's own mapping (the svg's data-k, data-ox, data-oy: px = ox + k s, py = oy - k z).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from auszug.formats import load
from auszug.microarch import build, edit
from auszug.studio.session import curve_infos

from .e2e import browser, geometry, needs_browser, open_drawing, page, studio, wait_revision  # noqa: F401  (fixtures)

pytestmark = needs_browser


def side_map(page: Any) -> dict:
    """The side view's mapping and the svg's client position, once it shows the current geometry
    and selection (it redraws once a frame)."""
    page.wait_for_function("""() => {
        const s = document.querySelector('[data-testid=side-svg]'), st = window.auszug.store;
        return !!st.geometry && s.dataset.revision === String(st.geometry.revision)
            && s.dataset.curve === String(st.selection);
    }""")
    # two frames later any redraw the last geometry asked for has happened
    page.evaluate("() => new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(ok)))")
    return page.evaluate("""() => {
        const s = document.querySelector('[data-testid=side-svg]'), b = s.getBoundingClientRect();
        return {k: +s.dataset.k, ox: +s.dataset.ox, oy: +s.dataset.oy, left: b.left, top: b.top};
    }""")


def z_at(m: dict, client_y: float) -> float:
    """The height at client pixel row ``client_y`` of the side view."""
    return (m["oy"] - (client_y - m["top"])) / m["k"]


def centre(page: Any, testid: str) -> tuple[float, float]:
    """The centre of the first element with ``testid``, measured in the page in one go (the side
    view rebuilds its markers when it redraws)."""
    xy = page.wait_for_function("""(testid) => {
        const e = document.querySelector(`[data-testid=${testid}]`);
        const b = e ? e.getBoundingClientRect() : null;
        return b && b.width > 0 ? [b.left + b.width / 2, b.top + b.height / 2] : null;
    }""", arg=testid).json_value()
    return float(xy[0]), float(xy[1])


def drag(page: Any, x: float, y: float, y2: float, alt: bool = False) -> None:
    """Press at (x, y), move in steps to (x, y2), release (Alt held throughout if asked)."""
    if alt:
        page.keyboard.down("Alt")
    page.mouse.move(x, y)
    page.mouse.down()
    page.mouse.move(x, (y + y2) / 2, steps=5)
    page.mouse.move(x, y2, steps=5)
    page.mouse.up()
    if alt:
        page.keyboard.up("Alt")


def wait_for(page: Any, condition: str, timeout: float = 10000) -> dict:
    """Wait until ``condition`` (JS, with ``g`` the page's Geometry) holds; that Geometry."""
    page.wait_for_function(f"() => {{ const g = window.auszug.store.geometry; return !!g && ({condition}); }}",
                           timeout=timeout)
    return geometry(page)


def settle(page: Any) -> dict:
    """Wait until no edit is in flight or waiting (the coalesced drag has sent its last value)."""
    page.wait_for_function("() => window.auszug.conn.waiting.size === 0")
    return geometry(page)


def top_view(g: dict) -> list:
    return [(c["vertices"], c["handles"]) for c in g["curves"]]


def piece_xy(page: Any) -> list[list[float]]:
    """The top-view (x, y) of every basic piece's samples."""
    return page.evaluate("""() => {
        const s = window.auszug.store;
        return s.geometry.pieces.map((p) => {
            const a = s.data.subarray(p.points.offset, p.points.offset + p.points.shape[0] * 3);
            return Array.from(a).filter((_, i) => i % 3 !== 2);
        });
    }""")


def test_drag_apex_sets_the_dragged_height_and_keeps_the_top_view(studio, page):
    g0 = open_drawing(page, studio, "tn-2.uc")
    page.select_option("[data-testid=side-curve]", "0")
    m = side_map(page)
    x, y = centre(page, "apex-marker")
    assert abs(z_at(m, y) - g0["curves"][0]["apex"]) < 1 / m["k"], "the marker sits at the apex height"
    xy0 = piece_xy(page)
    y2 = y - 40
    drag(page, x, y, y2)
    expected = z_at(m, y2)
    g = wait_for(page, f"Math.abs(g.curves[0].apex - {expected}) < {1 / m['k']}")
    g = settle(page)
    assert abs(g["curves"][0]["apex"] - expected) < 1 / m["k"]
    assert g["curves"][0]["apex"] > g0["curves"][0]["apex"] + 30 / m["k"]
    assert top_view(g) == top_view(g0), "a side-view edit moved a top-view vertex or handle"
    for a, b in zip(piece_xy(page), xy0, strict=True):
        np.testing.assert_allclose(a, b, atol=1e-6)
    # the view re-fits after the drag: the marker is at the new apex
    m = side_map(page)
    assert abs(z_at(m, centre(page, "apex-marker")[1]) - g["curves"][0]["apex"]) < 1 / m["k"]
    # the whole drag is one undo step
    page.keyboard.press("Control+z")
    g = wait_for(page, f"g.revision > {g['revision']}")
    assert g["curves"][0]["apex"] == g0["curves"][0]["apex"] and not g["can_undo"]


def test_drag_prc_moves_the_apex_as_python_computes_it(studio, workspace, page):
    g0 = open_drawing(page, studio, "tn-2.uc")
    page.select_option("[data-testid=side-curve]", "0")
    m = side_map(page)
    x, y = centre(page, "prc-marker")
    prc0 = g0["pieces"][0]["prc"][2]
    assert abs(z_at(m, y) - prc0) < 1 / m["k"]
    y2 = y - 25
    drag(page, x, y, y2)
    expected = z_at(m, y2)
    wait_for(page, f"Math.abs(g.pieces[0].prc[2] - {expected}) < {1 / m['k']}")
    g = settle(page)
    z = g["pieces"][0]["prc"][2]
    assert abs(z - expected) < 1 / m["k"]
    apex = curve_infos(edit.set_prc_height(load(workspace / "tn-2.uc"), 0, z))[0].apex
    assert abs(g["curves"][0]["apex"] - apex) < 1e-4 * apex  # the PRC's height went through float32
    assert top_view(g) == top_view(g0)


def test_layers_add_set_bottom_drag_move_remove(studio, page):
    from playwright.sync_api import expect

    g0 = open_drawing(page, studio, "tn-2.uc")
    apex = g0["curves"][0]["apex"]
    page.select_option("[data-testid=side-curve]", "0")
    page.click("[data-testid=add-layer]")
    g = wait_for(page, "g.layers.length === 2")
    assert g["layers"][1] == apex, "a new layer starts at the highest apex below"
    page.fill("[data-testid=layer-bottom-1]", "0.5")
    page.press("[data-testid=layer-bottom-1]", "Enter")
    g = wait_for(page, "g.layers[1] === 0.5")

    # drag layer 1's bottom line to 3 px from curve 0's apex: it snaps there
    m = side_map(page)
    x = m["left"] + 60
    y = m["top"] + m["oy"] - m["k"] * 0.5
    y_apex = m["top"] + m["oy"] - m["k"] * apex
    drag(page, x, y, y_apex + 3)
    wait_for(page, f"g.layers[1] === {apex}")
    g = settle(page)
    assert g["layers"][1] == apex
    # with Alt held there is no snapping
    m = side_map(page)
    y = m["top"] + m["oy"] - m["k"] * apex
    y2 = m["top"] + m["oy"] - m["k"] * 0.4
    drag(page, x, y, y2, alt=True)
    expected = z_at(m, y2)
    wait_for(page, f"Math.abs(g.layers[1] - {expected}) < {1 / m['k']}")
    g = settle(page)
    bottom = g["layers"][1]
    assert abs(bottom - expected) < 1 / m["k"]

    # move the selected curve up to layer 1, make layer 1 active, remove the empty layer 0
    page.click("[data-testid=layer-move-1]")
    g = wait_for(page, "g.curves[0].layer === 1")
    assert g["curves"][0]["bottom"] == bottom and g["curves"][0]["apex"] == apex
    # the store changes before the panel re-renders: wait for the counts (they failed once in CI read at once)
    expect(page.locator("[data-testid=layer-count-1]")).to_have_text("1 curve")
    expect(page.locator("[data-testid=layer-count-0]")).to_have_text("0 curves")
    page.check("[data-testid=layer-active-1]")
    assert page.evaluate("() => window.auszug.store.layer") == 1
    page.click("[data-testid=layer-remove-0]")  # empty: no question asked
    g = wait_for(page, "g.layers.length === 1")
    assert g["layers"] == [bottom] and g["curves"][0]["layer"] == 0
    assert page.evaluate("() => window.auszug.store.layer") == 0

    # removing a layer with curves asks first; declining keeps it
    page.click("[data-testid=add-layer]")
    wait_for(page, "g.layers.length === 2")
    page.once("dialog", lambda d: d.dismiss())
    page.click("[data-testid=layer-remove-0]")
    page.wait_for_timeout(300)
    assert len(geometry(page)["layers"]) == 2
    page.once("dialog", lambda d: d.accept())
    page.click("[data-testid=layer-remove-0]")
    g = wait_for(page, "g.layers.length === 1")
    assert g["n_curves"] == 0


def test_decoration_and_post(studio, workspace, page):
    g0 = open_drawing(page, studio, "tn-2.uc")
    page.select_option("[data-testid=side-curve]", "0")
    assert {p["kind"] for p in g0["pieces"]} == {"ogee"}
    page.click("[data-testid=decoration-toggle]")
    g = wait_for(page, "g.pieces.some((p) => p.kind === 'decoration')")
    assert g["curves"][0]["decoration"] and g["curves"][0]["decoration_at"] is None
    page.focus("[data-testid=decoration-at]")
    page.keyboard.press("PageUp")  # the slider, by keyboard: the meeting point moves
    g = wait_for(page, "g.curves[0].decoration_at !== null")
    g = settle(page)
    assert 0 < g["curves"][0]["decoration_at"] < g["curves"][0]["prc"][0]
    assert page.locator(".side-svg path.decoration").count() == 1

    page.click("[data-testid=post-toggle]")
    g = wait_for(page, "g.pieces.some((p) => p.kind === 'post')")
    c = g["curves"][0]
    assert abs(c["post_top"] - (c["apex"] + 0.25 * (c["apex"] - c["bottom"]))) < 1e-9
    page.fill("[data-testid=post-top]", "2.5")
    page.press("[data-testid=post-top]", "Enter")
    g = wait_for(page, "g.curves[0].post_top === 2.5")
    post = next(p for p in g["pieces"] if p["kind"] == "post")
    posts = [c for c in build(edit.set_post(load(workspace / "tn-2.uc"), 0, 2.5)).curves() if c.kind == "post"]
    assert post["transforms"]["shape"][0] == len(posts) > 0
    # drag the post's top down 20 px
    m = side_map(page)
    x, y = centre(page, "post-top-marker")
    drag(page, x, y, y + 20)
    expected = z_at(m, y + 20)
    g = wait_for(page, f"Math.abs(g.curves[0].post_top - {expected}) < {1 / m['k']}")
    assert top_view(g) == top_view(g0)

    page.click("[data-testid=post-toggle]")
    page.click("[data-testid=decoration-toggle]")
    g = wait_for(page, "g.pieces.every((p) => p.kind === 'ogee') && !g.curves[0].decoration")
    assert g["curves"][0]["post_top"] is None


def test_side_view_asks_for_a_curve(studio, page):
    open_drawing(page, studio, "tn-11.uc")
    assert page.locator(".side-hint").is_visible()
    assert not page.locator("[data-testid=side-svg]").is_visible()
    page.select_option("[data-testid=side-curve]", "1")
    assert page.evaluate("() => window.auszug.store.selection") == 1
    # the side view draws the curve's markers on its next frame (not at once under load)
    page.wait_for_selector("[data-testid=apex-marker]", state="attached")
    assert page.locator("[data-testid=apex-marker]").count() >= 1
    assert page.locator("[data-testid=prc-marker]").count() >= 1


def test_preview_draws_all_three_views(studio, page, tmp_path):
    open_drawing(page, studio, "tn-2.uc")
    page.click("[data-testid=mode-preview]")
    page.wait_for_function("() => document.body.classList.contains('preview')")
    page.evaluate("() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))")
    rects = page.evaluate("() => ['persp', 'top', 'side'].map((v) => window.auszug.views.rect(v))")
    shot = tmp_path / "preview.png"
    page.locator("canvas").screenshot(path=str(shot))
    import matplotlib.image

    img = matplotlib.image.imread(shot)[..., :3]
    ink = np.abs(img - np.array([0xF4, 0xF1, 0xEA]) / 255).max(axis=-1) > 0.15
    for name, r in zip(("3D", "top", "side"), rects, strict=True):
        view = ink[40 : r["h"] - 10, r["x"] + 4 : r["x"] + r["w"] - 4]
        rows, cols = np.nonzero(view)
        assert view.sum() > 200, f"{name} view draws {view.sum()} ink pixels"
        # framed: the drawing fills a good part of the view and is not cut at its edges
        assert cols.max() - cols.min() > 0.4 * r["w"], f"{name} view: drawing {cols.max() - cols.min()} px wide"
        assert cols.min() > 2 and cols.max() < view.shape[1] - 3, f"{name} view cuts the drawing"
    page.click("[data-testid=mode-design]")
    assert not page.evaluate("() => document.body.classList.contains('preview')")
