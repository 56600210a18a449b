"""Regenerate docs/img/studio.png: the studio on U.XI.28 in headless chromium, as the e2e tests run it.

The default tube look with every loop filled by a minimal surface, curve 0 selected (its side
view, its members highlighted), 1280 x 800. Needs the built front end (`make web`) and
/usr/bin/chromium.

Usage: .venv/bin/python docs/img/make_studio_png.py [OUT.png]   (default docs/img/studio.png)
"""

from __future__ import annotations

import shutil
import sys
import tempfile
import threading
import time
from pathlib import Path

from auszug import examples

HERE = Path(__file__).resolve().parent
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
        "--disable-sync", "--no-first-run"]


def main(argv: list[str]) -> int:
    import uvicorn
    from playwright.sync_api import sync_playwright

    from auszug.cli.studio import bind_local, server_config
    from auszug.studio.server import create_app

    out = Path(argv[0]) if argv else HERE / "studio.png"
    ws = Path(tempfile.mkdtemp(prefix="auszug-shot-"))
    shutil.copy(examples.path("web/U.XI.28.uc"), ws / "U.XI.28.uc")
    sock = bind_local(0)
    server = uvicorn.Server(server_config(create_app(ws), lifespan="off"))
    th = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    th.start()
    while not server.started:
        time.sleep(0.02)
    try:
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
            page = browser.new_page(viewport={"width": 1280, "height": 800})
            page.goto(f"http://127.0.0.1:{sock.getsockname()[1]}/?open=U.XI.28.uc&style=tube&faces=auto")
            page.wait_for_function("() => window.auszug && window.auszug.store.geometry !== null", timeout=30000)
            page.select_option("[data-testid=side-curve]", "0")
            page.wait_for_function("""() => { const s = window.auszug.store, m = s.mesh;
                return !!m && m.revision === s.geometry.revision && m.faces > 0
                  && !window.auszug.views.scene.getObjectByName('drag-tubes').visible; }""", timeout=60000)
            page.evaluate("() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))")
            page.mouse.move(1, 790)   # no hover effects in the picture
            page.wait_for_timeout(300)
            page.screenshot(path=str(out))
            browser.close()
    finally:
        server.should_exit = True
        th.join(10)
        shutil.rmtree(ws, ignore_errors=True)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
