"""End to end, design mode: drawing, selecting, symmetry, dragging, PRC by click, undo, delete, snapping.

Every interaction is a real mouse or keyboard event at the screen position of a drawing point
(``top_to_client``); results are read from the page's Geometry and compared with what
:mod:`auszug.microarch` computes for the same drawing in Python.
"""

from __future__ import annotations

import shutil

import numpy as np
import pytest

from auszug import examples
from auszug.formats import load, save
from auszug.microarch import Drawing, build, edit

from .e2e import (  # noqa: F401  (fixtures)
    browser,
    geometry,
    needs_browser,
    open_drawing,
    page,
    studio,
    top_to_client,
    wait_revision,
)

pytestmark = needs_browser


@pytest.fixture
def empty(workspace):
    """An empty drawing in the workspace (native JSON)."""
    save(Drawing(()), workspace / "empty.json")
    return "empty.json"


def scale(page) -> float:
    """Drawing units per CSS pixel in the top view."""
    return page.evaluate("() => window.auszug.views.topScale")


def click(page, x: float, y: float) -> None:
    page.mouse.click(*top_to_client(page, x, y))


def replicas(drawing: Drawing) -> int:
    return len(list(build(drawing).curves()))


def hit_at(page, x: float, y: float) -> str:
    """What a press at drawing point (x, y) lands on: the overlay itself, or a marker/point's test id or role."""
    cx, cy = top_to_client(page, x, y)
    return page.evaluate(f"""() => {{
        const e = document.elementFromPoint({cx}, {cy});
        return e.id === 'top-overlay' ? 'overlay' : (e.dataset.testid || e.dataset.role || e.tagName);
    }}""")


def select_curve(page, drawing: Drawing, curve: int) -> None:
    """Click the basic curve's top view where no marker or point covers it; it gets selected."""
    piece = next(p for p in build(drawing).pieces if p.basic == curve and p.top is not None)
    n = len(piece.points)
    # the centres of every marker and point: a press within 8 px of one picks it (a 16 px target)
    targets = page.evaluate("""() => [...document.querySelectorAll(
        '#top-overlay [data-testid], #top-overlay [data-role]')].map((e) => {
        const b = e.getBoundingClientRect();
        return [b.left + b.width / 2, b.top + b.height / 2];
    })""")
    for t in (0.3, 0.4, 0.6, 0.7, 0.2, 0.8, 0.35, 0.45, 0.55, 0.65, 0.25, 0.75):
        x, y = piece.points[int(t * (n - 1)), :2]
        cx, cy = top_to_client(page, x, y)
        if any(abs(cx - tx) < 12 and abs(cy - ty) < 12 for tx, ty in targets):
            continue
        if hit_at(page, x, y) == "overlay":
            click(page, x, y)
            page.wait_for_function(f"() => window.auszug.store.selection === {curve}")
            return
    raise AssertionError(f"curve {curve}: no free spot to click")


def overlay_ready(page) -> None:
    """Wait until the overlay has drawn the current geometry (it redraws once a frame)."""
    page.evaluate("() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))")


def test_draw_line_arc_and_free_end_by_clicks(studio, empty, page):
    g = open_drawing(page, studio, empty)
    assert g["n_curves"] == 0
    tol = 1.5 * scale(page)  # a pixel and a half, in drawing units
    # line: ground point, apex
    page.keyboard.press("l")
    a, b = (0.3, 0.5), (-0.25, 0.3)
    click(page, *a)
    click(page, *b)
    g = wait_revision(page, g["revision"])
    assert g["n_curves"] == 1
    c = g["curves"][0]
    np.testing.assert_allclose(c["vertices"], [a, b], atol=tol)
    assert c["marks"] == ["ground", "apex"] and c["handles"] == [[]]
    assert (c["fold"], c["mirror"], c["layer"]) == (1, "none", 0)
    assert page.evaluate("() => window.auszug.store.selection") == 0  # the new curve is selected
    # arc: ground point, then press at the apex and drag where the tangent aims
    page.locator("[data-testid=tool-arc]").click()
    a2, b2, h = (0.5, -0.4), (-0.1, -0.6), (0.2, -0.15)
    click(page, *a2)
    page.mouse.move(*top_to_client(page, *b2))
    page.mouse.down()
    page.mouse.move(*top_to_client(page, *h), steps=6)
    page.mouse.up()
    g = wait_revision(page, g["revision"])
    c = g["curves"][1]
    np.testing.assert_allclose(c["vertices"], [a2, b2], atol=tol)
    np.testing.assert_allclose(c["handles"][0], [h], atol=tol)
    # free end: ground point, apex, free end
    page.keyboard.press("e")
    pts = [(-0.6, 0.7), (-0.7, -0.3), (-0.45, -0.15)]
    for p in pts:
        click(page, *p)
    g = wait_revision(page, g["revision"])
    c = g["curves"][2]
    np.testing.assert_allclose(c["vertices"], pts, atol=tol)
    assert c["marks"] == ["ground", "apex", "free"] and c["handles"] == [[], []]
    # Escape drops a half-drawn curve
    page.keyboard.press("l")
    click(page, 0.6, 0.6)
    page.keyboard.press("Escape")
    click(page, 0.65, 0.75)
    overlay_ready(page)
    assert geometry(page)["n_curves"] == 3
    assert page.locator("#top-overlay .draft-point").count() == 1  # only the new first point


def test_fold_and_mirror_in_panel(studio, workspace, page):
    drawing = load(workspace / "tn-2.uc")
    g = open_drawing(page, studio, "tn-2.uc")
    select_curve(page, drawing, 0)
    page.locator("[data-testid=mirror-select]").select_option("none")
    g = wait_revision(page, g["revision"])
    assert g["n_replicas"] == 4
    fold = page.locator("[data-testid=fold-input]")
    fold.fill("8")
    fold.press("Enter")
    g = wait_revision(page, g["revision"])
    expected = edit.set_symmetry(drawing, 0, fold=8, mirror="none")
    assert g["n_replicas"] == 8 == replicas(expected)
    page.locator("[data-testid=mirror-select]").select_option("first point")
    g = wait_revision(page, g["revision"])
    expected = edit.set_symmetry(expected, 0, mirror="first point")
    assert g["n_replicas"] == 16 == replicas(expected)
    assert page.evaluate("() => window.auszug.views.network.children.length") == 16
    overlay_ready(page)
    # the guides: 8 lines through the centre (16 rays) and the mirror axis through the first point
    assert page.locator("#top-overlay line.guide:not(.axis)").count() == 8
    assert page.locator("#top-overlay line.guide.axis").is_visible()
    # intersection markers for every replica of the basic curve
    assert page.locator("[data-testid=intersection]").count() == 16 * len(g["intersections"])


def test_layer_and_colour_in_panel(studio, workspace, page):
    drawing = load(workspace / "tn-2.uc")
    g = open_drawing(page, studio, "tn-2.uc")
    for bottom in (1.0, 2.5):  # set-up: layers 1 and 2 (above the apex, 1.82)
        page.evaluate(f"() => window.auszug.ctx.request({{type: 'add_layer', bottom: {bottom}}})")
        g = wait_revision(page, g["revision"])
    select_curve(page, drawing, 0)
    layer = page.locator("[data-testid=layer-select]")
    from playwright.sync_api import expect

    # the panel redraws once a frame: wait for it to list the new layers
    expect(layer.locator("option")).to_have_text(["0 (bottom 0)", "1 (bottom 1)", "2 (bottom 2.5)"])
    layer.select_option("2")  # refused by the server: the select shows the curve's layer again
    page.wait_for_function("() => document.getElementById('status').classList.contains('error')")
    page.wait_for_function("() => document.querySelector('[data-testid=layer-select]').value === '0'")
    layer.select_option("1")
    g = wait_revision(page, g["revision"])
    assert g["curves"][0]["layer"] == 1
    expected = edit.set_layer(edit.add_layer(edit.add_layer(drawing, 1.0), 2.5), 0, 1)
    assert g["n_replicas"] == replicas(expected)
    page.locator("[data-testid=curve-color]").fill("#1f77b4")
    assert page.evaluate("() => window.auszug.store.looks.colors[0]") == "#1f77b4"
    assert page.evaluate("() => window.auszug.store.color(0)") == "#1f77b4"


def test_drag_vertex(studio, workspace, page):
    drawing = load(workspace / "tn-2.uc")
    g = open_drawing(page, studio, "tn-2.uc")
    select_curve(page, drawing, 0)
    v0, apex = g["curves"][0]["vertices"]
    target = (0.8, 0.25)  # away from every snap target
    page.mouse.move(*top_to_client(page, *apex))
    page.mouse.down()
    page.mouse.move(*top_to_client(page, *target), steps=12)
    page.mouse.up()
    tol = 1.0 * scale(page)
    page.wait_for_function(f"""() => {{
        const v = window.auszug.store.geometry.curves[0].vertices[1];
        return Math.hypot(v[0] - {target[0]}, v[1] - {target[1]}) <= {tol};
    }}""")
    g = geometry(page)
    assert g["curves"][0]["vertices"][0] == v0
    np.testing.assert_allclose(g["curves"][0]["vertices"][1], target, atol=tol)
    assert g["n_replicas"] == replicas(edit.move_vertex(drawing, 0, 1, tuple(g["curves"][0]["vertices"][1])))


def test_drag_handles_bend_a_line_into_an_arc(studio, workspace, page):
    drawing = load(workspace / "tn-2.uc")
    # the targets below lie clear of every marker at the top view's scale with this split (at the
    # default half-and-half split an intersection marker is within 8 px of (0.25, -0.2) and wins)
    g = open_drawing(page, studio, "tn-2.uc&split=0.62")
    select_curve(page, drawing, 0)
    tol = 1.0 * scale(page)
    mid = np.mean(g["curves"][0]["vertices"], axis=0)
    overlay_ready(page)
    assert hit_at(page, *mid) == "handle"  # the line's bend handle
    for start, target in ((mid, (0.25, -0.2)), ((0.25, -0.2), (0.3, -0.12))):
        page.mouse.move(*top_to_client(page, *start))
        page.mouse.down()
        page.mouse.move(*top_to_client(page, *target), steps=8)
        page.mouse.up()
        page.wait_for_function(f"""() => {{
            const h = window.auszug.store.geometry.curves[0].handles[0];
            return h.length === 1 && Math.hypot(h[0][0] - {target[0]}, h[0][1] - {target[1]}) <= {tol};
        }}""")
    g = geometry(page)
    bent = edit.move_handle(drawing, 0, 0, 0, tuple(g["curves"][0]["handles"][0][0]))
    assert bent.curves[0].segments[0].kind == "arc"
    assert g["n_replicas"] == replicas(bent)
    overlay_ready(page)
    assert page.locator("#top-overlay line.tangent").count() == 1  # from the first point to the handle


def test_click_intersection_sets_prc(studio, workspace, page):
    drawing = load(workspace / "tn-2.uc")
    g = open_drawing(page, studio, "tn-2.uc")
    c = g["curves"][0]
    ends = np.array(c["vertices"])
    prc = next(p["prc"] for p in g["pieces"] if p["prc"])
    # a true intersection of the basic curve that is neither an end point nor the current PRC
    i, m = next((i, m) for i, m in enumerate(g["intersections"])
                if m["true"] and np.linalg.norm(ends - m["point"], axis=1).min() > 0.05
                and np.linalg.norm(np.subtract(m["point"], prc[:2])) > 0.05)
    overlay_ready(page)
    marker = page.locator(f"[data-testid=intersection][data-index='{i}'][data-replica='0']")
    assert marker.get_attribute("data-true") == "true"
    assert (marker.get_attribute("data-curve"), marker.get_attribute("data-segment")) == ("0", "0")
    assert hit_at(page, *m["point"]) == "intersection"
    click(page, *m["point"])
    g = wait_revision(page, g["revision"])
    expected = edit.set_prc_at(drawing, 0, tuple(m["point"]), 0).curves[0].prc[0]
    assert g["curves"][0]["prc"][0] == pytest.approx(expected, abs=1e-12)
    assert g["curves"][0]["prc"][0] != pytest.approx(c["prc"][0], abs=1e-3)
    # the PRC marker moved there
    new_prc = next(p["prc"] for p in g["pieces"] if p["prc"])
    np.testing.assert_allclose(new_prc[:2], m["point"], atol=1e-6)
    overlay_ready(page)
    box = page.locator("[data-testid=prc][data-replica='0']").bounding_box()
    cx, cy = top_to_client(page, *m["point"])
    assert abs(box["x"] + box["width"] / 2 - cx) < 1 and abs(box["y"] + box["height"] / 2 - cy) < 1


def test_undo_redo_restores_vertices(studio, workspace, page):
    drawing = load(workspace / "tn-2.uc")
    g = open_drawing(page, studio, "tn-2.uc")
    select_curve(page, drawing, 0)
    before = g["curves"][0]["vertices"]
    page.mouse.move(*top_to_client(page, *before[1]))
    page.mouse.down()
    page.keyboard.down("Alt")  # no snapping: the point follows the mouse
    for k in range(1, 9):  # a drag of many steps: many edits, one undo step
        page.mouse.move(*top_to_client(page, before[1][0] - 0.02 * k, before[1][1] + 0.025 * k))
        page.wait_for_timeout(30)
    page.mouse.up()
    page.keyboard.up("Alt")
    end = [before[1][0] - 0.16, before[1][1] + 0.2]
    page.wait_for_function(f"""() => {{
        const v = window.auszug.store.geometry.curves[0].vertices[1];
        return Math.abs(v[0] - {end[0]}) < 0.01 && Math.abs(v[1] - {end[1]}) < 0.01; }}""")
    g = geometry(page)
    after = g["curves"][0]["vertices"]
    assert g["revision"] > 0 and after != before and g["can_undo"]
    page.keyboard.press("Control+z")
    g = wait_revision(page, g["revision"])
    assert g["curves"][0]["vertices"] == before and g["can_redo"] and not g["can_undo"]
    page.keyboard.press("Control+Shift+Z")
    g = wait_revision(page, g["revision"])
    assert g["curves"][0]["vertices"] == after


def test_select_and_delete(studio, workspace, page):
    drawing = load(workspace / "tn-11.uc")
    g = open_drawing(page, studio, "tn-11.uc")
    select_curve(page, drawing, 1)
    assert page.locator("#curve-panel h2").inner_text().lower() == "curve 1"
    assert page.locator("[data-testid=point-x-0]").input_value() == str(round(g["curves"][1]["vertices"][0][0], 6))
    page.keyboard.press("Delete")
    g = wait_revision(page, g["revision"])
    expected = edit.remove_curve(drawing, 1)
    assert g["n_curves"] == 2 and g["n_replicas"] == replicas(expected)
    assert [c["vertices"] for c in g["curves"]] == [[list(v) for v in c.vertices] for c in expected.curves]
    assert page.evaluate("() => window.auszug.store.selection") is None
    # clicking empty space deselects; the delete button removes the selected curve too
    select_curve(page, expected, 0)
    click(page, 0.0, 0.9)
    page.wait_for_function("() => window.auszug.store.selection === null")
    select_curve(page, expected, 0)
    page.locator("[data-testid=delete-curve]").click()
    g = wait_revision(page, g["revision"])
    assert g["n_curves"] == 1


def test_snapping(studio, workspace, page):
    drawing = load(workspace / "tn-2.uc")
    g = open_drawing(page, studio, "tn-2.uc")
    sym = drawing.curves[0].symmetry
    apex = np.asarray(drawing.curves[0].vertices[1])
    target = next(q for q in sym.apply(apex) if abs(q[0]) < 1e-9 and q[1] > 0)  # the apex turned by 90 degrees
    page.keyboard.press("l")
    s = scale(page)
    cx, cy = top_to_client(page, *target)
    page.mouse.click(cx + 3, cy - 4)  # 5 px off a replica's end point
    end = (0.3, 0.75)
    ex, ey = top_to_client(page, *end)
    page.mouse.click(ex + 3, ey)  # off the guides: no snap
    g = wait_revision(page, g["revision"])
    start = g["curves"][1]["vertices"][0]
    assert start == pytest.approx(list(target), abs=1e-12)
    np.testing.assert_allclose(g["curves"][1]["vertices"][1], (end[0] + 3 * s, end[1]), atol=1.5 * s)
    # near the 45 degree guide line: the point lands on it; with Alt held it does not snap
    page.keyboard.press("l")
    near = np.array([0.5, 0.5]) + 4 * s * np.array([0.7071, -0.7071])
    click(page, *near)
    page.keyboard.down("Alt")
    click(page, *(near + [0.1, -0.35]))
    page.keyboard.up("Alt")
    g = wait_revision(page, g["revision"])
    p, q = g["curves"][2]["vertices"]
    assert p[0] == pytest.approx(p[1], abs=1e-12) and p[0] == pytest.approx(0.5, abs=1.5 * s)
    np.testing.assert_allclose(q, near + [0.1, -0.35], atol=1.5 * s)


def test_drag_is_coalesced(studio, workspace, page):
    shutil.copy(examples.path("web/U.XI.28.uc"), workspace / "U.XI.28.uc")
    drawing = load(workspace / "U.XI.28.uc")
    g = open_drawing(page, studio, "U.XI.28.uc")
    select_curve(page, drawing, 0)
    apex = g["curves"][0]["vertices"][1]
    page.evaluate("() => { window.auszug.timings.length = 0; }")
    page.mouse.move(*top_to_client(page, *apex))
    page.keyboard.down("Alt")  # no snapping: the point follows the mouse
    page.mouse.down()
    for k in range(1, 41):
        page.mouse.move(*top_to_client(page, apex[0] + 0.004 * k, apex[1] + 0.002 * k))
    page.mouse.up()
    page.keyboard.up("Alt")
    end, tol = (apex[0] + 0.16, apex[1] + 0.08), 1.5 * scale(page)
    page.wait_for_function(f"""() => {{
        const v = window.auszug.store.geometry.curves[0].vertices[1];
        return Math.hypot(v[0] - {end[0]}, v[1] - {end[1]}) < {tol};
    }}""")
    t = page.evaluate("() => window.auszug.timings")
    assert 2 <= len(t) <= 41
    # one edit awaits its reply at a time
    assert all(b["sent"] >= a["received"] for a, b in zip(t, t[1:], strict=False))
    # each edit knows the pointer event it answers (pointerrawupdate: sent without waiting for a frame)
    assert all(0 < e["input"] <= e["sent"] for e in t)
    # how fast: benchmarks/bench_studio.py (timings are measured there, not asserted in tests)
