"""End to end: Debian's chromium (driven by Playwright) opens the studio served by uvicorn.

`make test` installs /usr/bin/chromium when it is missing; Playwright's own
browser downloads are never used.
"""

from __future__ import annotations

import os
import socket
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from auszug.formats import load
from auszug.microarch import build
from auszug.studio.server import create_app, static_dir

CHROMIUM = Path("/usr/bin/chromium")
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
        "--disable-sync", "--no-first-run"]

pytestmark = pytest.mark.skipif(
    not os.environ.get("AUSZUG_REQUIRE_NODE") and not (CHROMIUM.is_file() and (static_dir() / "index.html").is_file()),
    reason="needs /usr/bin/chromium and the built front end (make test provides both)",
)


@pytest.fixture
def studio_url(workspace):
    """The studio on tn-2.uc, served by uvicorn on a free port of 127.0.0.1 in a thread."""
    import uvicorn

    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    sock.bind(("127.0.0.1", 0))
    port = sock.getsockname()[1]
    server = uvicorn.Server(uvicorn.Config(create_app(workspace, "tn-2.uc"), log_level="warning",
                                           lifespan="off"))
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    deadline = time.monotonic() + 20
    while not server.started:
        assert time.monotonic() < deadline, "uvicorn did not start"
        time.sleep(0.02)
    yield f"http://127.0.0.1:{port}/"
    server.should_exit = True
    thread.join(10)
    sock.close()


def test_studio_renders_drawing(studio_url, workspace, tmp_path):
    from playwright.sync_api import sync_playwright

    expected = len(list(build(load(workspace / "tn-2.uc")).curves()))
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=str(CHROMIUM), args=ARGS)
        try:
            page = browser.new_page(viewport={"width": 1000, "height": 500})
            errors: list[str] = []
            page.on("pageerror", lambda e: errors.append(str(e)))
            page.goto(studio_url)
            status = page.locator("#status[data-replicas]")
            status.wait_for(timeout=20000)
            assert status.get_attribute("data-replicas") == str(expected)
            assert f"{expected} replicas" in status.inner_text()
            box = page.locator("canvas").bounding_box()
            assert box is not None and box["width"] > 900 and box["height"] > 400
            shot = tmp_path / "studio.png"
            page.screenshot(path=str(shot))
            assert not errors, errors
        finally:
            browser.close()
    import matplotlib.image

    img = matplotlib.image.imread(shot)[..., :3]
    background = np.array([0xF4, 0xF1, 0xEA]) / 255
    ink = np.abs(img - background).max(axis=-1) > 0.15
    h, w = ink.shape
    body = ink[60 : h - 60]  # leave out the labels and the status line
    left, right = body[:, : w // 2].sum(), body[:, w // 2 :].sum()
    assert left > 200 and right > 200, f"lines drawn: top view {left} px, 3D view {right} px"
