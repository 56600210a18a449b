"""The end-to-end harness: the studio served by uvicorn in a thread, Debian's chromium driven by Playwright.

`make test` installs /usr/bin/chromium when it is missing and builds the front end; Playwright's
own browser downloads are never used. Each scenario saves a screenshot under ``out/e2e/`` (look
at them). Pages expose ``window.auszug`` (store, views, conn, timings) for reading state and
mapping drawing coordinates to screen pixels; every interaction itself goes through real mouse
and keyboard events.
"""

from __future__ import annotations

import os
import re
import threading
import time
from pathlib import Path
from typing import Any

import pytest

from auszug.cli.studio import bind_local, server_config
from auszug.studio.server import create_app, static_dir
from tests.conftest import REPO

CHROMIUM = Path("/usr/bin/chromium")
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
        "--disable-sync", "--no-first-run"]
#: Where the scenario screenshots go.
SHOTS = Path(os.environ.get("AUSZUG_E2E_SHOTS", REPO / "out" / "e2e"))

needs_browser = pytest.mark.skipif(
    not os.environ.get("AUSZUG_REQUIRE_NODE") and not (CHROMIUM.is_file() and (static_dir() / "index.html").is_file()),
    reason="needs /usr/bin/chromium and the built front end (make test provides both)",
)


class Studio:
    """A running studio server on a free port of 127.0.0.1."""

    def __init__(self, workspace: Path, drawing: str | None = None) -> None:
        import uvicorn

        self.workspace = workspace
        self.sock = bind_local(0)
        self.port = self.sock.getsockname()[1]
        self.url = f"http://127.0.0.1:{self.port}/"
        self.server = uvicorn.Server(server_config(create_app(workspace, drawing), lifespan="off"))
        self.thread = threading.Thread(target=self.server.run, kwargs={"sockets": [self.sock]}, daemon=True)
        self.thread.start()
        deadline = time.monotonic() + 20
        while not self.server.started:
            assert time.monotonic() < deadline, "uvicorn did not start"
            time.sleep(0.02)

    def stop(self) -> None:
        self.server.should_exit = True
        self.thread.join(10)
        self.sock.close()


_RUNNING: dict[str, Any] = {}


def _chromium() -> Any:
    """The process's one Playwright and chromium, started on first use.

    Test modules import the fixtures below, so pytest registers the session fixture once per
    module; a second sync Playwright in the same thread would fail, hence one per process.
    """
    if "browser" not in _RUNNING:
        from playwright.sync_api import sync_playwright

        pw = sync_playwright().start()
        _RUNNING["playwright"] = pw
        _RUNNING["browser"] = pw.chromium.launch(executable_path=str(CHROMIUM), args=ARGS)
    return _RUNNING["browser"]


def close_chromium() -> None:
    """Stop the process's chromium and Playwright (tests/studio/conftest.py calls it at the end)."""
    if "browser" in _RUNNING:
        _RUNNING.pop("browser").close()
        _RUNNING.pop("playwright").stop()


@pytest.fixture(scope="session")
def browser():
    """One chromium for the whole run (each test gets its own page)."""
    return _chromium()


@pytest.fixture
def studio(workspace):
    """The studio on the ``workspace`` fixture's folder (no drawing opened on connect)."""
    s = Studio(workspace)
    yield s
    s.stop()


def _shot_name(nodeid: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", nodeid.split("::", 1)[-1]).strip("_") + ".png"


@pytest.fixture
def page(browser, request):
    """A fresh page (1280 x 800); page errors fail the test; a screenshot is saved at the end."""
    ctx = browser.new_context(viewport={"width": 1280, "height": 800}, accept_downloads=True)
    pg = ctx.new_page()
    errors: list[str] = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    pg.errors = errors  # type: ignore[attr-defined]  # the tests read the page's errors from it
    yield pg
    SHOTS.mkdir(parents=True, exist_ok=True)
    try:
        pg.screenshot(path=str(SHOTS / _shot_name(request.node.nodeid)))
    finally:
        ctx.close()
    assert not errors, f"errors in the page: {errors}"


def open_drawing(page: Any, studio: Studio, path: str, timeout: float = 20000) -> dict:
    """Load the studio page with ``?open=path`` and wait for its geometry; the Geometry message."""
    page.goto(f"{studio.url}?open={path}")
    page.wait_for_function("() => window.auszug && window.auszug.store.geometry !== null", timeout=timeout)
    return geometry(page)


def geometry(page: Any) -> dict:
    """The page's current Geometry message (as JSON)."""
    return page.evaluate("() => window.auszug.store.geometry")


def wait_revision(page: Any, after: int, timeout: float = 10000) -> dict:
    """Wait until the page shows a geometry newer than revision ``after``; that Geometry."""
    page.wait_for_function(f"() => window.auszug.store.geometry && window.auszug.store.geometry.revision > {after}",
                           timeout=timeout)
    return geometry(page)


def top_to_client(page: Any, x: float, y: float) -> tuple[float, float]:
    """Client pixel coordinates of drawing point (x, y) in the top view."""
    px, py = page.evaluate(f"""() => {{
        const v = window.auszug.views, r = v.rect('top'), b = v.host.getBoundingClientRect();
        const [sx, sy] = v.topToScreen({x}, {y});
        return [b.left + r.x + sx, b.top + r.y + sy];
    }}""")
    return float(px), float(py)
