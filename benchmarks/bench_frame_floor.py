"""The floor of "pointer event -> frame" in headless chromium, for any page (issue 13). Prints a table.

Issue 13 measures the studio from a pointer event to the first animation frame that shows the
geometry the event produced (`bench_studio.py`). This script measures what no front end can go
below in the same set-up (Debian's chromium, headless, --disable-gpu, Playwright's mouse at 60 Hz,
the page's performance.now()), with pages that draw nothing:

The page listens to pointerrawupdate where chromium has it (the studio does: it comes as the input
arrives, where pointermove waits for the next frame), else to pointermove; the table names which.

1. *local*: a bare page; each pointer event is answered at once in the page (no network, no
   drawing); the time from the event's timeStamp to the next requestAnimationFrame callback.
2. *round trip*: each pointer event sends a 16-byte WebSocket message to an echo endpoint of a
   uvicorn server configured as the studio's (127.0.0.1, TCP_NODELAY); the time from the event to
   the first animation frame after the echo arrived (the first frame that could show a reply).
3. *round trip, drawn at once*: the same, but the time to the echo's arrival itself (a page that
   draws the moment data arrives; the compositor still shows it at its next frame).

A frame that shows the result of a server's reply can come no sooner than (2); the studio's figure
adds its server work (~1 ms for a U.XI.28 point drag) and its own frame.

Usage: python benchmarks/bench_frame_floor.py [--moves 300] [--rounds 2]
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import statistics
import threading
import time

CHROMIUM = "/usr/bin/chromium"
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
        "--disable-sync", "--no-first-run"]

PAGE = """<!doctype html><html><body style="margin:0"><div id="pad" style="width:800px;height:600px"></div>
<script>
window.rec = [];
let mode = "local", ws = null, pendingEvent = null;
window.setMode = (m) => new Promise((res) => {
  mode = m; window.rec = [];
  if (m === "local") { res(); return; }
  if (ws) { res(); return; }
  ws = new WebSocket(`ws://${location.host}/echo`);
  ws.binaryType = "arraybuffer";
  ws.onopen = () => res();
  ws.onmessage = (m) => {
    const arrived = performance.now(), t = new Float64Array(m.data)[0];
    requestAnimationFrame((now) => window.rec.push({event: t, arrived, frame: performance.now()}));
  };
});
// pointerrawupdate where the browser has it (Chromium in a secure context such as 127.0.0.1), as the
// studio listens: it comes as the input arrives, not aligned to the next frame as pointermove is
const EVENT = "onpointerrawupdate" in window ? "pointerrawupdate" : "pointermove";
window.eventName = EVENT;
document.getElementById("pad").addEventListener(EVENT, (e) => {
  if (mode === "local") {
    const t = e.timeStamp;
    requestAnimationFrame(() => window.rec.push({event: t, arrived: t, frame: performance.now()}));
  } else if (ws && ws.readyState === 1) {
    const b = new Float64Array(2); b[0] = e.timeStamp; ws.send(b.buffer);
  }
});
</script></body></html>"""


def serve() -> tuple[str, object]:
    import uvicorn
    from starlette.applications import Starlette
    from starlette.responses import HTMLResponse
    from starlette.routing import Route, WebSocketRoute
    from starlette.websockets import WebSocket

    from auszug.cli.studio import bind_local, server_config

    async def index(request: object) -> HTMLResponse:
        return HTMLResponse(PAGE)

    async def echo(ws: WebSocket) -> None:
        await ws.accept()
        try:
            while True:
                await ws.send_bytes(await ws.receive_bytes())
        except Exception:
            return

    app = Starlette(routes=[Route("/", index), WebSocketRoute("/echo", echo)])
    sock = bind_local(0)
    server = uvicorn.Server(server_config(app, lifespan="off"))
    threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True).start()
    while not server.started:
        time.sleep(0.02)
    return f"http://127.0.0.1:{sock.getsockname()[1]}/", server


def drag(page, moves: int) -> None:
    page.mouse.move(200, 200)
    page.mouse.down()
    start = time.perf_counter()
    for k in range(1, moves + 1):
        due = start + k / 60 - time.perf_counter()
        if due > 0:
            time.sleep(due)
        page.mouse.move(400 + 150 * math.sin(0.37 * k), 300 + 150 * math.cos(0.23 * k))
    page.mouse.up()
    page.wait_for_timeout(200)


def stats(xs: list[float]) -> tuple[float, float]:
    xs = sorted(xs)
    return statistics.median(xs), xs[min(len(xs) - 1, int(0.9 * len(xs)))]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--moves", type=int, default=300)
    ap.add_argument("--rounds", type=int, default=2)
    args = ap.parse_args()
    from playwright.sync_api import sync_playwright

    url, server = serve()
    print(f"# bench_frame_floor: Python {platform.python_version()}, {os.cpu_count()} cores, "
          f"load average {os.getloadavg()[0]:.1f} at the start")
    rows: dict[str, list[float]] = {"local": [], "round trip": [], "round trip, drawn at once": []}
    event = "pointermove"
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS, headless=True)
        page = browser.new_page(viewport={"width": 1280, "height": 800})
        page.goto(url)
        event = page.evaluate("window.eventName")
        for _ in range(args.rounds):
            for mode in ("local", "ws"):
                page.evaluate(f"window.setMode({mode!r})")
                drag(page, args.moves)
                rec = page.evaluate("window.rec")
                if mode == "local":
                    rows["local"] += [r["frame"] - r["event"] for r in rec]
                else:
                    rows["round trip"] += [r["frame"] - r["event"] for r in rec]
                    rows["round trip, drawn at once"] += [r["arrived"] - r["event"] for r in rec]
        browser.close()
    server.should_exit = True  # type: ignore[attr-defined]
    print(f"| {event} -> (ms) | events | median | p90 |")
    print("|---|---|---|---|")
    for name, xs in rows.items():
        med, p90 = stats(xs)
        what = {"local": "next animation frame, nothing sent",
                "round trip": "first animation frame after a WebSocket echo",
                "round trip, drawn at once": "the echo's arrival"}[name]
        print(f"| {what} | {len(xs)} | {med:.2f} | {p90:.2f} |")
    print(f"# load average {os.getloadavg()[0]:.1f} at the end; issue 13's target for the studio: "
          "median <= 8.5 ms, p90 <= 25 ms")


if __name__ == "__main__":
    main()
