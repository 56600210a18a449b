"""End to end, no lost work (issue 13 section 1): a server killed with SIGKILL in the middle of a
drag, reloads, two unsaved tabs of one name, "Save as" in one of two tabs."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from auszug.formats import load

from .e2e import browser, geometry, needs_browser, open_drawing, page, studio, top_to_client, wait_revision  # noqa: F401
from .test_e2e_design import select_curve
from .test_e2e_files import set_apex, shortcut, wait_connected

pytestmark = needs_browser


class ServerProcess:
    """``auszug studio`` as its own process (so it can be killed with SIGKILL) on a fixed port."""

    def __init__(self, workspace: Path, port: int = 0) -> None:
        if port == 0:
            import socket

            with socket.socket() as s:
                s.bind(("127.0.0.1", 0))
                port = s.getsockname()[1]
        self.port = port
        self.url = f"http://127.0.0.1:{port}/"
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "auszug", "studio", "--workspace", str(workspace), "--port", str(port),
             "--no-browser"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        import urllib.request

        deadline = time.monotonic() + 30
        while True:
            try:
                urllib.request.urlopen(self.url, timeout=1).close()
                return
            except OSError:
                assert self.proc.poll() is None, self.proc.stderr.read().decode() if self.proc.stderr else ""
                assert time.monotonic() < deadline, "the studio did not start"
                time.sleep(0.1)

    def kill9(self) -> None:
        os.kill(self.proc.pid, signal.SIGKILL)
        self.proc.wait(10)

    def stop(self) -> None:
        if self.proc.poll() is None:
            self.proc.terminate()
            self.proc.wait(10)


def _wait_file(p: Path, check=lambda p: True, timeout: float = 10) -> None:
    deadline = time.monotonic() + timeout
    while True:
        try:
            if p.is_file() and check(p):
                return
        except Exception:   # a file being replaced
            pass
        assert time.monotonic() < deadline, f"{p} did not appear"
        time.sleep(0.05)


def test_kill9_in_the_middle_of_a_drag_loses_nothing(workspace, browser):
    drawing = load(workspace / "tn-2.uc")
    server = ServerProcess(workspace)
    ctx = browser.new_context(viewport={"width": 1280, "height": 800})
    try:
        pg = ctx.new_page()
        errors: list[str] = []
        pg.on("pageerror", lambda e: errors.append(str(e)))
        g = open_drawing(pg, server, "tn-2.uc")   # type: ignore[arg-type]  # has .url
        doc = g["doc"]
        select_curve(pg, drawing, 0)
        before = g["curves"][0]["vertices"][1]
        pg.mouse.move(*top_to_client(pg, *before))
        pg.mouse.down()
        pg.keyboard.down("Alt")
        for k in range(1, 6):
            pg.mouse.move(*top_to_client(pg, before[0] - 0.02 * k, before[1] + 0.025 * k))
            pg.wait_for_timeout(30)
        moved = [before[0] - 0.1, before[1] + 0.125]
        pg.wait_for_function(f"""() => {{ const v = window.auszug.store.geometry.curves[0].vertices[1];
            return Math.abs(v[0] - {moved[0]}) < 0.01 && Math.abs(v[1] - {moved[1]}) < 0.01; }}""")
        autosave = workspace / ".auszug" / "autosave" / "tn-2.uc.json"
        _wait_file(autosave, lambda p: abs(load(p).curves[0].vertices[1][0] - moved[0]) < 0.01)
        server.kill9()                              # the mouse is still down
        pg.wait_for_function("() => document.body.dataset.connected === 'false'")
        server = ServerProcess(workspace, server.port)
        pg.wait_for_function("() => document.body.dataset.connected === 'true'", timeout=30000)
        pg.wait_for_function(f"() => window.auszug.store.geometry.doc === '{doc}' "
                             "&& window.auszug.store.geometry.dirty")
        g = geometry(pg)
        v = g["curves"][0]["vertices"][1]
        assert abs(v[0] - moved[0]) < 0.01 and abs(v[1] - moved[1]) < 0.01
        assert g["path"] == "tn-2.uc" and g["dirty"] and g["can_undo"] and not g["recoverable"]
        assert pg.locator("#banner").is_hidden()
        # the drag goes on against the new server, from the restored drawing
        end = [before[0] - 0.16, before[1] + 0.2]
        for k in range(6, 9):
            pg.mouse.move(*top_to_client(pg, before[0] - 0.02 * k, before[1] + 0.025 * k))
            pg.wait_for_timeout(30)
        pg.mouse.up()
        pg.keyboard.up("Alt")
        pg.wait_for_function(f"""() => {{ const v = window.auszug.store.geometry.curves[0].vertices[1];
            return Math.abs(v[0] - {end[0]}) < 0.01 && Math.abs(v[1] - {end[1]}) < 0.01; }}""")
        assert not errors
        # undo: back to the restored drawing (the restore is one undo step), then to the file
        r0 = geometry(pg)["revision"]
        shortcut(pg, "Control+z")
        g = wait_revision(pg, r0)
        assert abs(g["curves"][0]["vertices"][1][0] - moved[0]) < 0.01
        shortcut(pg, "Control+z")
        g = wait_revision(pg, g["revision"])
        assert g["curves"][0]["vertices"][1] == pytest.approx(before) and not g["dirty"]
    finally:
        ctx.close()
        server.stop()


def test_reload_restores_the_document_and_the_looks(studio, page):
    page.goto(studio.url)
    wait_connected(page)
    page.click("[data-testid=open]")
    page.locator("[data-testid=gallery-card][data-path='teaching-sheet/tn-2.uc']").click()
    page.wait_for_function("() => window.auszug.store.geometry !== null")
    g = set_apex(page, 2.4)
    page.select_option("[data-testid=look-style]", "bar")
    page.wait_for_function("() => new URLSearchParams(location.search).get('style') === 'bar'")
    assert f"doc={g['doc']}" in page.url
    page.reload()
    page.wait_for_function("() => window.auszug && window.auszug.store.geometry !== null")
    g2 = geometry(page)
    assert (g2["doc"], g2["path"], g2["dirty"]) == (g["doc"], "", True)
    assert g2["curves"][0]["apex"] == pytest.approx(2.4)
    assert page.locator("[data-testid=look-style]").input_value() == "bar"
    assert page.evaluate("() => window.auszug.store.looks.style") == "bar"


def test_two_tabs_on_one_example_keep_their_own_work(studio, page):
    other = page.context.new_page()
    gs = []
    for pg, h in ((page, 2.3), (other, 2.6)):
        pg.goto(studio.url)
        wait_connected(pg)
        pg.click("[data-testid=open]")
        pg.locator("[data-testid=gallery-card][data-path='teaching-sheet/tn-2.uc']").click()
        pg.wait_for_function("() => window.auszug.store.geometry !== null")
        gs.append(set_apex(pg, h))
    assert gs[0]["doc"] != gs[1]["doc"]
    for pg, h in ((page, 2.3), (other, 2.6)):
        pg.reload()
        pg.wait_for_function("() => window.auszug && window.auszug.store.geometry !== null")
        assert geometry(pg)["curves"][0]["apex"] == pytest.approx(h)


def test_save_as_in_one_tab_leaves_the_other_on_its_file(studio, workspace, page):
    other = page.context.new_page()
    open_drawing(page, studio, "tn-2.uc")
    open_drawing(other, studio, "tn-2.uc")
    g = set_apex(page, 2.2)
    wait_revision(other, g["revision"] - 1)
    shortcut(page, "Control+Shift+S")
    page.fill("[data-testid=name-input]", "copy")
    page.select_option("[data-testid=name-format]", ".json")
    page.click("[data-testid=name-ok]")
    page.wait_for_function("() => window.auszug.store.geometry.path === 'copy.json'")
    other.wait_for_timeout(300)
    g2 = geometry(other)
    assert g2["path"] == "tn-2.uc" and g2["dirty"]
    assert other.locator("[data-testid=doc-name]").inner_text() == "tn-2.uc •"
    assert load(workspace / "copy.json").curves[0].height == pytest.approx(2.2)
