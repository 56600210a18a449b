"""End to end, files: the gallery, local files, save and reload, export, autosave recovery,
two tabs on one file, the help overlay, shortcuts and text fields, the background image."""

from __future__ import annotations

import dataclasses
import math
import shutil
import time
from pathlib import Path

import pytest

from auszug import examples
from auszug.formats import load
from auszug.microarch import build
from auszug.studio.session import curve_infos

from .e2e import Studio, browser, geometry, needs_browser, open_drawing, page, studio, wait_revision  # noqa: F401  (fixtures)

pytestmark = needs_browser

TOP_VIEW = "() => [window.auszug.views.topCenter.x, window.auszug.views.topCenter.y, window.auszug.views.topScale]"


def wait_connected(page) -> None:
    page.wait_for_function("() => document.body.dataset.connected === 'true'")


def close(a, b, where: str = "") -> None:
    """``a`` equals ``b`` (JSON-like values; numbers to 1e-6)."""
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        assert math.isclose(a, b, rel_tol=1e-6, abs_tol=1e-6), f"{where}: {a} != {b}"
    elif isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        assert len(a) == len(b), f"{where}: {len(a)} != {len(b)} items"
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            close(x, y, f"{where}[{i}]")
    elif isinstance(a, dict) and isinstance(b, dict):
        assert a.keys() == b.keys(), f"{where}: fields {sorted(a)} != {sorted(b)}"
        for k in a:
            close(a[k], b[k], f"{where}.{k}")
    else:
        assert a == b, f"{where}: {a!r} != {b!r}"


def same_drawing(page_curves: list[dict], path: Path) -> None:
    """The page's CurveInfo fields equal those of the drawing in ``path``."""
    expected = [dataclasses.asdict(c) for c in curve_infos(load(path))]
    close([{k: v for k, v in c.items() if k != "name"} for c in page_curves],
          [{k: v for k, v in c.items() if k != "name"} for c in expected], "curves")


def shortcut(page, keys: str) -> None:
    """Press ``keys`` with the focus on no text field (where shortcuts are off)."""
    page.evaluate("() => document.activeElement && document.activeElement.blur()")
    page.keyboard.press(keys)


def set_apex(page, height: float) -> dict:
    """Set basic curve 0's apex height in the side panel; the Geometry that results."""
    before = geometry(page)["revision"]
    page.select_option("[data-testid=side-curve]", "0")
    page.fill("[data-testid=apex-height]", str(height))
    page.press("[data-testid=apex-height]", "Enter")
    g = wait_revision(page, before)
    assert g["curves"][0]["apex"] == pytest.approx(height)
    return g


def test_gallery_opens_an_example(studio, page):
    page.goto(studio.url)
    wait_connected(page)
    page.click("[data-testid=open]")
    cards = page.locator("[data-testid=gallery-card]")
    cards.first.wait_for()
    workspace = page.locator("[data-testid=gallery-card][data-kind=workspace]")
    assert sorted(workspace.evaluate_all("els => els.map(e => e.dataset.path)")) == ["tn-11.uc", "tn-2.uc"]
    titles = page.locator("dialog[data-testid=gallery] h3").evaluate_all("els => els.map(e => e.textContent)")
    assert {"Examples · teaching-sheet", "Examples · web", "Examples · legacy"} <= set(titles)
    assert cards.count() == 2 + len(examples.names())
    page.screenshot(path=str(_shots() / "gallery.png"))
    # the search box filters
    page.fill("[data-testid=gallery-search]", "xi.28")
    paths = cards.evaluate_all("els => els.map(e => e.dataset.path)")
    assert "web/U.XI.28.uc" in paths and all("xi.28" in p.lower() for p in paths)
    page.click("[data-testid=gallery-card][data-path='web/U.XI.28.uc']")
    page.wait_for_function("() => window.auszug.store.geometry !== null")
    expect = load(examples.path("web/U.XI.28.uc"))
    g = geometry(page)
    assert g["n_curves"] == len(expect.curves)
    assert g["n_replicas"] == len(list(build(expect).curves()))
    assert g["path"] == "" and not g["dirty"]
    assert not page.locator("dialog[data-testid=gallery]").is_visible()
    assert page.locator("[data-testid=doc-name]").inner_text() == "U.XI.28"
    assert page.title().startswith("U.XI.28")


def test_open_a_local_file(studio, page, tmp_path):
    page.goto(studio.url)
    wait_connected(page)
    src = examples.path("legacy/U.XI.17.uc")
    page.click("[data-testid=open]")  # the gallery opens local files too
    with page.expect_file_chooser() as chooser:
        page.click("[data-testid=gallery-local]")
    chooser.value.set_files(str(src))
    page.wait_for_function("() => window.auszug.store.geometry !== null")
    assert page.locator("dialog[data-testid=gallery]").is_hidden()
    g = geometry(page)
    d = load(src)
    assert g["n_curves"] == len(d.curves) and g["n_replicas"] == len(list(build(d).curves()))
    same_drawing(g["curves"], src)
    assert g["path"] == ""


def test_edit_save_reload_save_as(studio, workspace, page):
    tn11 = (workspace / "tn-11.uc").read_bytes()
    open_drawing(page, studio, "tn-2.uc")
    g = set_apex(page, 2.5)
    assert g["dirty"]
    page.wait_for_function("() => document.title.startsWith('tn-2.uc •')")
    assert page.locator("[data-testid=doc-name]").inner_text() == "tn-2.uc •"
    # Ctrl+S saves where the drawing came from
    shortcut(page, "Control+s")
    page.wait_for_function("() => !window.auszug.store.geometry.dirty")
    assert page.title().startswith("tn-2.uc —")
    same_drawing(geometry(page)["curves"], workspace / "tn-2.uc")
    assert load(workspace / "tn-2.uc").apex_height(0) == pytest.approx(2.5)
    # a reload shows the saved drawing
    page.reload()
    page.wait_for_function("() => window.auszug.store.geometry !== null")
    g = geometry(page)
    assert g["path"] == "tn-2.uc" and not g["dirty"]
    same_drawing(g["curves"], workspace / "tn-2.uc")
    # Save as (Ctrl+Shift+S): a name and a format; the document is the new file from then on
    shortcut(page, "Control+Shift+S")
    page.fill("[data-testid=name-input]", "copy")
    page.select_option("[data-testid=name-format]", ".uc")
    page.click("[data-testid=name-ok]")
    page.wait_for_function("() => window.auszug.store.geometry.path === 'copy.uc'")
    same_drawing(geometry(page)["curves"], workspace / "copy.uc")
    # saving over another file asks twice
    page.click("[data-testid=save-as]")
    page.fill("[data-testid=name-input]", "tn-11.uc")
    page.click("[data-testid=name-ok]")
    assert "exists" in page.locator("dialog[data-testid=name-dialog] .message").inner_text()
    page.keyboard.press("Escape")
    assert geometry(page)["path"] == "copy.uc"
    assert (workspace / "tn-11.uc").read_bytes() == tn11


def test_new_drawing_is_saved_under_its_name(studio, workspace, page):
    page.goto(studio.url)
    wait_connected(page)
    page.click("[data-testid=new]")
    page.fill("[data-testid=name-input]", "pinnacle")
    page.click("[data-testid=name-ok]")
    page.wait_for_function("() => window.auszug.store.geometry && window.auszug.store.geometry.name === 'pinnacle'")
    assert geometry(page)["n_curves"] == 0
    page.click("[data-testid=save]")  # not saved yet: asks for a file name, suggesting the drawing's
    assert page.input_value("[data-testid=name-input]") == "pinnacle.json"
    page.click("[data-testid=name-ok]")
    page.wait_for_function("() => window.auszug.store.geometry.path === 'pinnacle.json'")
    assert load(workspace / "pinnacle.json").curves == ()


def test_export_glb_and_printable_stl(studio, page, tmp_path):
    import trimesh

    open_drawing(page, studio, "tn-2.uc")
    page.click("[data-testid=export]")
    page.screenshot(path=str(_shots() / "export_menu.png"))
    with page.expect_download() as dl:
        page.click("[data-testid=export-glb]")
    assert dl.value.suggested_filename.endswith(".glb")
    glb = tmp_path / dl.value.suggested_filename
    dl.value.save_as(glb)
    mesh = trimesh.load(glb, force="mesh")
    assert len(mesh.faces) > 0
    # Ctrl+E opens the menu; a printable STL of the tubes look is one watertight solid
    page.select_option("[data-testid=look-style]", "tube")
    shortcut(page, "Control+e")
    page.check("[data-testid=export-solid]")
    with page.expect_download(timeout=120000) as dl:
        page.click("[data-testid=export-stl]")
    stl = tmp_path / dl.value.suggested_filename
    dl.value.save_as(stl)
    solid = trimesh.load(stl, force="mesh")
    assert len(solid.faces) > 0 and solid.is_watertight


def test_autosave_is_offered_after_a_restart(workspace, browser):
    first = Studio(workspace)
    ctx = browser.new_context(viewport={"width": 1280, "height": 800})
    try:
        pg = ctx.new_page()
        open_drawing(pg, first, "tn-2.uc")
        set_apex(pg, 2.75)
        autosave = workspace / ".auszug" / "autosave" / "tn-2.uc.json"
        deadline = time.monotonic() + 10
        while not autosave.is_file():
            assert time.monotonic() < deadline, "no autosave"
            time.sleep(0.05)
        first.stop()
        # the open page notices and says it reconnects
        pg.wait_for_function("() => document.getElementById('banner').dataset.state === 'reconnecting'")
        assert "reconnecting" in pg.locator("#banner").inner_text()
        pg.close()
        second = Studio(workspace)
        try:
            pg = ctx.new_page()
            g = open_drawing(pg, second, "tn-2.uc")
            assert g["recoverable"] and not g["dirty"]
            assert g["curves"][0]["apex"] != pytest.approx(2.75)
            banner = pg.locator("#banner")
            banner.wait_for()
            assert "recovered from autosave" in banner.inner_text()
            pg.screenshot(path=str(_shots() / "autosave_offered.png"))
            pg.click("[data-testid=recover]")
            g = wait_revision(pg, g["revision"])
            assert g["curves"][0]["apex"] == pytest.approx(2.75) and g["dirty"] and not g["recoverable"]
            assert banner.is_hidden()
        finally:
            second.stop()
    finally:
        ctx.close()


def _shots() -> Path:
    from .e2e import SHOTS

    SHOTS.mkdir(parents=True, exist_ok=True)
    return SHOTS


def test_two_tabs_share_the_file(studio, page):
    other = page.context.new_page()
    open_drawing(page, studio, "tn-2.uc")
    open_drawing(other, studio, "tn-2.uc")
    g = set_apex(page, 2.2)
    g2 = wait_revision(other, g["revision"] - 1)
    assert g2["revision"] == g["revision"]
    close(g2["curves"], g["curves"], "curves")
    same = "() => Array.from(window.auszug.store.data)"
    assert other.evaluate(same) == page.evaluate(same)
    assert other.locator("[data-testid=doc-name]").inner_text() == "tn-2.uc •"


def test_help_lists_shortcuts_and_text_fields_swallow_them(studio, page):
    open_drawing(page, studio, "tn-2.uc")
    help_dialog = page.locator("dialog[data-testid=help]")
    page.keyboard.press("?")
    help_dialog.wait_for()
    text = help_dialog.inner_text()
    for entry in ("Undo", "Redo", "Save", "Preview mode", "Wheel"):
        assert entry in text
    page.screenshot(path=str(_shots() / "help.png"))
    page.keyboard.press("Escape")
    assert help_dialog.is_hidden()
    page.keyboard.press("F1")
    help_dialog.wait_for()
    page.keyboard.press("Escape")
    # typing in the gallery's search box: no mode switch, no help
    page.click("[data-testid=open]")
    page.locator("[data-testid=gallery-search]").press_sequentially("p?d")
    assert page.input_value("[data-testid=gallery-search]") == "p?d"
    assert page.evaluate("() => window.auszug.store.mode") == "design" and help_dialog.is_hidden()
    page.keyboard.press("Escape")  # clears the search box first, then closes the gallery
    assert page.input_value("[data-testid=gallery-search]") == ""
    page.keyboard.press("Escape")
    assert page.locator("dialog[data-testid=gallery]").is_hidden()
    # a popover is not modal: with a button focused in it, shortcuts fire (its text fields: see
    # test_background_image)
    page.click("[data-testid=background]")
    page.locator("[data-testid=background-load]").focus()
    page.keyboard.press("p")
    assert page.evaluate("() => window.auszug.store.mode") == "preview"


def test_background_image(studio, page, tmp_path):
    import matplotlib.pyplot as plt
    import numpy as np

    png = tmp_path / "scan.png"
    img = np.zeros((60, 100, 3))
    img[..., 0] = np.linspace(0, 1, 100)
    img[10:50, 20:80, 2] = 1
    plt.imsave(png, img)
    open_drawing(page, studio, "tn-2.uc")
    textures = "() => window.auszug.views.renderer.info.memory.textures"
    frame = ("() => new Promise(r => { window.auszug.views.requestRender(); "
             "requestAnimationFrame(() => requestAnimationFrame(r)); })")
    page.evaluate(frame)
    before = page.evaluate(textures)
    page.click("[data-testid=background]")
    page.set_input_files("[data-testid=background-input]", str(png))
    page.wait_for_function("() => window.auszug.views.scene.getObjectByName('background')")
    page.evaluate(frame)
    assert page.evaluate(textures) == before + 1
    plane = page.evaluate("""() => {
        const m = window.auszug.views.scene.getObjectByName('background'), v = window.auszug.views;
        return { w: m.material.map.image.width, h: m.material.map.image.height, mask: m.layers.mask,
                 seenByTop: m.layers.test(v.top.layers), seenBy3D: m.layers.test(v.persp.layers),
                 z: m.position.z, minZ: v.bounds.min.z, x: m.position.x, y: m.position.y,
                 sx: m.scale.x, sy: m.scale.y, depthWrite: m.material.depthWrite };
    }""")
    assert (plane["w"], plane["h"]) == (100, 60)
    assert plane["seenByTop"] and not plane["seenBy3D"] and not plane["depthWrite"]
    assert plane["z"] < plane["minZ"]
    assert plane["sy"] == pytest.approx(0.6 * plane["sx"])
    # typing in its fields fires no shortcut
    page.fill("[data-testid=background-x]", "")
    page.locator("[data-testid=background-x]").press_sequentially("0.25p?")
    assert page.evaluate("() => window.auszug.store.mode") == "design"
    assert page.locator("dialog[data-testid=help]").is_hidden()
    x = page.evaluate("() => window.auszug.views.scene.getObjectByName('background').position.x")
    assert x == pytest.approx(0.25)
    # Shift+drag on the image moves it by the drag in drawing units; the top view does not pan
    view = page.evaluate(TOP_VIEW)
    from .e2e import top_to_client

    x0, y0 = top_to_client(page, 0.25, 0.0)
    page.keyboard.down("Shift")
    page.mouse.move(x0, y0)
    page.mouse.down()
    page.mouse.move(x0 + 50, y0 + 20, steps=4)
    page.mouse.up()
    page.keyboard.up("Shift")
    moved = page.evaluate("() => window.auszug.views.scene.getObjectByName('background').position.toArray()")
    assert moved[0] == pytest.approx(0.25 + 50 * view[2], abs=1e-6)
    assert moved[1] == pytest.approx(-20 * view[2], abs=1e-6)
    assert float(page.input_value("[data-testid=background-x]")) == pytest.approx(moved[0], abs=1e-4)
    assert page.evaluate(TOP_VIEW) == view
    page.screenshot(path=str(_shots() / "background.png"))
    # the placement is kept for this document: after a reload, the image goes back there
    stored = page.evaluate("() => JSON.parse(localStorage.getItem('auszug.background:tn-2.uc'))")
    assert stored["x"] == pytest.approx(moved[0]) and stored["y"] == pytest.approx(moved[1])
    page.reload()
    page.wait_for_function("() => window.auszug.store.geometry !== null")
    page.click("[data-testid=background]")
    page.set_input_files("[data-testid=background-input]", str(png))
    page.wait_for_function("() => window.auszug.views.scene.getObjectByName('background')")
    again = page.evaluate("() => window.auszug.views.scene.getObjectByName('background').position.toArray()")
    assert again[:2] == pytest.approx(moved[:2])
    page.evaluate(frame)
    before = page.evaluate(textures) - 1
    # remove frees the texture
    page.click("[data-testid=background-remove]")
    page.evaluate(frame)
    assert page.evaluate("() => window.auszug.views.scene.getObjectByName('background')") is None
    assert page.evaluate(textures) == before


def test_gallery_cards_show_thumbnails_of_the_top_view(studio, workspace, page):
    from urllib.parse import unquote

    from auszug.studio.thumbnails import thumbnail_svg

    page.goto(studio.url)
    wait_connected(page)
    page.click("[data-testid=open]")
    page.locator("[data-testid=gallery-card]").first.wait_for()
    n = 2 + len(examples.names())
    # every card gets its picture, one request at a time, decoded by the browser as a 96 px image
    page.wait_for_function(f"""() => {{
        const imgs = [...document.querySelectorAll('[data-testid=gallery-thumb]')];
        return imgs.length === {n} && imgs.every((i) => i.complete && i.naturalWidth === 96);
    }}""", timeout=60000)
    page.screenshot(path=str(_shots() / "gallery_thumbnails.png"))
    srcs = dict(page.locator("[data-testid=gallery-card]").evaluate_all(
        "els => els.map(e => [e.dataset.kind + ':' + e.dataset.path, e.querySelector('img').src])"))
    prefix = "data:image/svg+xml;charset=utf-8,"
    for key, drawing in (("workspace:tn-2.uc", load(workspace / "tn-2.uc")),
                         ("example:web/U.XI.28.uc", load(examples.path("web/U.XI.28.uc")))):
        assert srcs[key].startswith(prefix)
        assert unquote(srcs[key][len(prefix):]) == thumbnail_svg(build(drawing)), key
    # a changed workspace file gets a new picture the next time the gallery opens
    shutil.copy(examples.path("web/U.XI.28.uc"), workspace / "tn-2.uc")
    page.keyboard.press("Escape")
    page.keyboard.press("Escape")
    page.click("[data-testid=open]")
    page.wait_for_function("""() => {
        const i = document.querySelector('[data-testid=gallery-card][data-path="tn-2.uc"] img');
        const j = document.querySelector('[data-testid=gallery-card][data-path="web/U.XI.28.uc"] img');
        return i && j && i.src && i.src === j.src;
    }""", timeout=30000)
