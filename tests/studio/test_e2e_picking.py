"""End to end, picking (issue 13 section 3): at a crossing of two curves a click sets the selected
curve's PRC even where the other curve's faded marker lies on top; markers take clicks over 16 px;
a click that changes nothing leaves no undo step."""

from __future__ import annotations

import numpy as np
import pytest

from auszug.formats import load
from auszug.microarch import edit

from .e2e import browser, geometry, needs_browser, open_drawing, page, studio, top_to_client, wait_revision  # noqa: F401
from .test_e2e_design import overlay_ready, select_curve

pytestmark = needs_browser


def _crossing(g: dict) -> tuple[int, dict]:
    """A marker of a lower curve (a) at a point where a higher curve (b) has one too (drawn on top),
    away from a's end points and its PRC."""
    ms = g["intersections"]
    for m in ms:
        a = m["curve"]
        ends = np.array(g["curves"][a]["vertices"])
        if np.linalg.norm(ends - m["point"], axis=1).min() < 0.05:
            continue
        prcs = [p["prc"] for p in g["pieces"] if p["basic"] == a and p["prc"] and p["segment"] == m["segment"]]
        if prcs and np.linalg.norm(np.subtract(m["point"], prcs[0][:2])) < 0.05:
            continue
        if any(o["curve"] > a and np.linalg.norm(np.subtract(o["point"], m["point"])) < 1e-9 for o in ms):
            return a, m
    raise AssertionError("no crossing of two curves in this drawing")


def _selected_crossing(studio, workspace, page):
    """tn-11 open with curve ``a`` selected; its crossing marker ``m`` and where it is on screen."""
    drawing = load(workspace / "tn-11.uc")
    g = open_drawing(page, studio, "tn-11.uc")
    a, m = _crossing(g)
    select_curve(page, drawing, a)
    overlay_ready(page)
    return drawing, g, a, m, top_to_client(page, *m["point"])


def test_crossing_sets_the_selected_curves_prc_and_a_repeat_is_no_undo_step(studio, workspace, page):
    drawing, g, a, m, (x, y) = _selected_crossing(studio, workspace, page)
    # the other curve's faded marker is the element on top there
    top = page.evaluate(f"() => document.elementFromPoint({x}, {y}).dataset.curve")
    assert top != str(a)
    page.mouse.click(x + 6.5, y)          # 6.5 px off the centre: inside a 16 px target
    g1 = wait_revision(page, g["revision"])
    assert page.evaluate("() => window.auszug.store.selection") == a
    expected = edit.set_prc_at(drawing, a, tuple(m["point"]), m["segment"]).curves[a].prc[m["segment"]]
    assert g1["curves"][a]["prc"][m["segment"]] == pytest.approx(expected, abs=1e-12)
    assert g1["can_undo"]
    # the same click again changes nothing: no new revision, no undo step
    overlay_ready(page)
    page.mouse.click(x, y)
    page.wait_for_timeout(400)
    assert geometry(page)["revision"] == g1["revision"]
    page.evaluate("() => document.activeElement && document.activeElement.blur()")
    page.keyboard.press("Control+z")
    g2 = wait_revision(page, g1["revision"])
    assert g2["curves"][a]["prc"] == g["curves"][a]["prc"] and not g2["can_undo"]


def test_a_marker_takes_no_clicks_beyond_8_px(studio, workspace, page):
    drawing, g, a, m, (x, y) = _selected_crossing(studio, workspace, page)
    ends = [top_to_client(page, *v) for c in g["curves"] for v in c["vertices"]]
    marks = [top_to_client(page, *o["point"]) for o in g["intersections"]]
    # a spot 9.5 px away from this marker, not within 8 px of any other point target either
    for ang in np.linspace(0, 2 * np.pi, 24, endpoint=False):
        px, py = x + 9.5 * np.cos(ang), y + 9.5 * np.sin(ang)
        if min(np.hypot(px - qx, py - qy) for qx, qy in ends + marks) > 9:
            break
    else:
        raise AssertionError("no free spot around this marker")
    page.mouse.click(px, py)
    page.wait_for_timeout(400)
    assert geometry(page)["revision"] == g["revision"]


def test_enter_in_a_number_field_commits_and_hands_back_the_keyboard(studio, workspace, page):
    """After Enter in the apex field the focus leaves it: Ctrl+Z undoes the edit (not the field's
    text) and the field shows the drawing's value again."""
    original = load(workspace / "tn-2.uc").apex_height(0)
    g = open_drawing(page, studio, "tn-2.uc")
    page.select_option("[data-testid=side-curve]", "0")
    field = page.locator("[data-testid=apex-height]")
    field.fill("2.4")
    field.press("Enter")
    g1 = wait_revision(page, g["revision"])
    assert g1["curves"][0]["apex"] == pytest.approx(2.4)
    page.wait_for_function("() => document.activeElement.dataset.testid !== 'apex-height'")
    page.keyboard.press("Control+z")      # no blur by the test: the page must have handed the keys back
    g2 = wait_revision(page, g1["revision"])
    assert g2["curves"][0]["apex"] == pytest.approx(original) and not g2["can_undo"]
    page.wait_for_function("() => document.querySelector('[data-testid=apex-height]').value !== '2.4'")
    assert float(field.input_value()) == pytest.approx(original, abs=5e-4)   # the field shows 3 decimals


@pytest.mark.parametrize("value", ["1e300", "1e120"])
def test_a_refused_value_is_explained_at_its_field(studio, workspace, page, value):
    """Issue 13 section 2: an apex beyond the limits is refused, said at the field, and changes nothing."""
    g = open_drawing(page, studio, "tn-2.uc")
    page.select_option("[data-testid=side-curve]", "0")
    field = page.locator("[data-testid=apex-height]")
    field.fill(value)
    field.press("Enter")
    msg = page.locator("[data-testid=field-error][data-for=apex-height]")
    msg.wait_for()
    assert "apex height" in msg.inner_text() and "beyond the limit of +-1e+06" in msg.inner_text()
    assert field.get_attribute("aria-invalid") == "true"
    g1 = geometry(page)
    assert g1["revision"] == g["revision"] and not g1["can_undo"] and not g1["dirty"]
    page.wait_for_function("() => document.querySelector('[data-testid=apex-height]').value !== '" + value + "'")
    assert float(field.input_value()) == pytest.approx(g["curves"][0]["apex"], abs=5e-4)   # back to the drawing's
    field.fill("2.4")                      # typing clears the message; a good value goes through
    assert msg.count() == 0 or not msg.is_visible()
    field.press("Enter")
    assert wait_revision(page, g["revision"])["curves"][0]["apex"] == pytest.approx(2.4)


@pytest.mark.parametrize(("testid", "value", "says"), [
    ("fold-input", "2000", "rotation fold 2000 is above the limit of 1024"),
    ("point-x-0", "1e7", "beyond the limit of +-1e+06"),
])
def test_curve_panel_refusals_show_at_the_field(studio, workspace, page, testid, value, says):
    drawing = load(workspace / "tn-2.uc")
    g = open_drawing(page, studio, "tn-2.uc")
    select_curve(page, drawing, 0)
    field = page.locator(f"[data-testid={testid}]")
    field.fill(value)
    field.press("Enter")
    msg = page.locator(f"[data-testid=field-error][data-for={testid}]")
    msg.wait_for()
    assert says in msg.inner_text(), msg.inner_text()
    g1 = geometry(page)
    assert g1["revision"] == g["revision"] and not g1["can_undo"]


def test_two_tabs_dragging_at_once_one_undo_takes_back_whole_drags(studio, workspace, page):
    """Two tabs drag points of one document at the same time (their edits interleave): an undo
    never lands in the middle of a drag (issue 13: it took back a single edit of the other's drag)."""
    drawing = load(workspace / "tn-2.uc")
    other = page.context.new_page()
    g0 = open_drawing(page, studio, "tn-2.uc")
    open_drawing(other, studio, "tn-2.uc")
    for pg in (page, other):
        select_curve(pg, drawing, 0)
    v1, v0 = g0["curves"][0]["vertices"][1], g0["curves"][0]["vertices"][0]
    page.mouse.move(*top_to_client(page, *v1))
    page.mouse.down()
    other.mouse.move(*top_to_client(other, *v0))
    other.mouse.down()
    for pg in (page, other):
        pg.keyboard.down("Alt")
    for k in range(1, 7):
        page.mouse.move(*top_to_client(page, v1[0] - 0.02 * k, v1[1] + 0.02 * k))
        page.wait_for_timeout(40)
        other.mouse.move(*top_to_client(other, v0[0] + 0.015 * k, v0[1] - 0.01 * k))
        other.wait_for_timeout(40)
    for pg in (page, other):
        pg.mouse.up()
        pg.keyboard.up("Alt")
    page.wait_for_function(f"""() => {{ const v = window.auszug.store.geometry.curves[0].vertices;
        return Math.abs(v[1][0] - {v1[0] - 0.12}) < 0.01 && Math.abs(v[0][0] - {v0[0] + 0.09}) < 0.01; }}""")
    page.wait_for_timeout(300)
    g = geometry(page)
    page.keyboard.press("Control+z")
    g1 = wait_revision(page, g["revision"])
    # nothing of either drag is left half-done: back to the file (both drags were one step) ...
    assert g1["curves"][0]["vertices"] == g0["curves"][0]["vertices"] and not g1["can_undo"]
    other.wait_for_function(f"() => window.auszug.store.geometry.revision >= {g1['revision']}")
    assert geometry(other)["curves"][0]["vertices"] == g0["curves"][0]["vertices"]
