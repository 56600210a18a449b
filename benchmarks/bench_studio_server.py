"""Studio server speed (issue: the studio, speed). Prints markdown tables; not a test.

1. The server-side path of one edit, in-process: decode the client's JSON,
   apply the edit to the shared document (one network build), compute the
   geometry message and its float32 payload, encode the JSON text. A
   top-view point drag (``move_vertex`` of curve 0's last point by a fresh
   small step every time, so no intersection is cached from an earlier
   step, as in a real drag) and an apex-height drag (``set_apex_height`` of
   curve 0), on U.XI.28, tn-2 and the chancel (web/3d-scan-final.uc).
   Target: well under 1 ms, so that the page can show the new geometry in
   <= 2 ms end to end. The authors' demo: 1.2 ms (point drag) and 4.2 ms
   (apex drag) per edit in the page (tests/data/reference/anchor/README.md).
2. The WebSocket round trip through a real uvicorn on 127.0.0.1 (a separate
   process, as the browser is): send the edit, receive the geometry and its
   payload (one binary frame, ``protocol.pack``), with the ``websockets``
   client; and the same in headless chromium (Playwright, /usr/bin/chromium,
   if present), where the page also parses the JSON and views the payload as
   Float32Arrays (everything but drawing).
3. The transport alone: chromium <-> the same uvicorn configuration with an
   echo app that does no studio work, replies of 16 B to 50 kB (the least an
   edit can cost in the page before the server computes anything).
4. The cost of a worker-thread hop (``asyncio.to_thread``), which the server
   skips for quick edits.

Usage: python benchmarks/bench_studio_server.py [--reps N] [--ws-reps N] [--browser-reps N] [--markdown]
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from auszug import examples
from auszug.formats import load
from auszug.studio import protocol as P
from auszug.studio.session import Document, Workspace

DRAWINGS = {"U.XI.28": "web/U.XI.28.uc", "tn-2": "teaching-sheet/tn-2.uc", "chancel": "web/3d-scan-final.uc"}
EDITS = ("point drag", "apex drag")
#: The authors' demo per edit (ms), from tests/data/reference/anchor/README.md.
ANCHOR = {"point drag": 1.2, "apex drag": 4.2}
TARGET_PAGE_MS = 2.0


def edit_messages(drawing, kind: str, start: int):
    """An endless stream of edit messages (JSON text) of one kind, each with fresh values."""
    c = drawing.curves[0]
    v = len(c.vertices) - 1
    x, y = c.vertices[v]
    h = drawing.apex_height(0)
    size = max(1e-9, float(np.abs(np.array(c.vertices)).max()))
    k = start
    while True:
        k += 1
        # small steps that never repeat (a cache of earlier steps would flatter the drag)
        if kind == "point drag":
            msg = {"type": "move_vertex", "curve": 0, "vertex": v,
                   "xy": [x + size * 1e-3 * np.sin(k * 0.37), y + size * 1e-3 * np.cos(k * 0.23)], "id": k}
        else:
            msg = {"type": "set_apex_height", "curve": 0, "height": h * (1.0 - 0.01 * abs(np.sin(k * 0.37))),
                   "id": k}
        yield json.dumps(msg)


def server_path(name: str, kind: str, reps: int) -> dict[str, float]:
    """Median and p90 (ms) of decode -> apply -> geometry -> encode, and the parts' medians."""
    d = load(examples.path(DRAWINGS[name]))
    doc = Document(Workspace(Path(tempfile.gettempdir())), d, name=name)
    msgs = edit_messages(d, kind, 1000 if kind == "point drag" else 5000)
    parts: dict[str, list[float]] = {"decode": [], "edit + build": [], "geometry": [], "encode": [], "total": []}
    for i in range(reps + 20):
        text = next(msgs)
        t0 = time.perf_counter()
        msg = P.decode(text)
        t1 = time.perf_counter()
        doc.apply(msg)
        t2 = time.perf_counter()
        frames, payload = doc.frames()
        t3 = time.perf_counter()
        out = frames.text(msg.id)
        t4 = time.perf_counter()
        if i >= 20:  # warm-up: imports, first builds of the other curves
            for key, dt in zip(parts, (t1 - t0, t2 - t1, t3 - t2, t4 - t3, t4 - t0), strict=True):
                parts[key].append(dt * 1e3)
        doc.undo_stack.clear()
    res = {k: statistics.median(v) for k, v in parts.items()}
    res["p90"] = float(np.percentile(parts["total"], 90))
    res["json_bytes"] = len(out)
    res["payload_bytes"] = len(payload)
    return res


# ---------------------------------------------------------------- the WebSocket round trip


def serve(workspace: str) -> None:
    """Run the studio app on 127.0.0.1 (any free port); print the port, serve until killed."""
    import uvicorn

    from auszug.cli.studio import bind_local, server_config
    from auszug.studio.server import create_app

    sock = bind_local(0)   # as `auszug studio` binds (TCP_NODELAY) and configures uvicorn
    print(sock.getsockname()[1], flush=True)
    uvicorn.Server(server_config(create_app(Path(workspace)))).run(sockets=[sock])


async def _round_trips(port: int, name: str, kind: str, reps: int) -> list[float]:
    import websockets

    d = load(examples.path(DRAWINGS[name]))
    async with websockets.connect(f"ws://127.0.0.1:{port}/ws", max_size=None, compression=None) as ws:
        await ws.send(json.dumps({"type": "open_example", "name": DRAWINGS[name], "id": 1}))
        P.unpack(await ws.recv())
        msgs = edit_messages(d, kind, 1000 if kind == "point drag" else 5000)
        out = []
        for i in range(reps + 20):
            text = next(msgs)
            t0 = time.perf_counter()
            await ws.send(text)
            reply = await ws.recv()
            dt = time.perf_counter() - t0
            if not isinstance(reply, bytes):
                raise RuntimeError(f"unexpected reply {reply[:200]}")
            head, payload = P.unpack(reply)
            if head.get("type") != "geometry" or len(payload) != 4 * head["binary_floats"]:
                raise RuntimeError(f"unexpected reply {str(head)[:200]}")
            if i >= 20:
                out.append(dt * 1e3)
        return out


def websocket_round_trips(reps: int, browser_reps: int) -> tuple[dict, dict | None]:
    """(median, p90) ms of edit -> geometry and its payload over a real uvicorn, per drawing and edit.

    First with the ``websockets`` client, then in headless chromium if it is there.
    """
    with tempfile.TemporaryDirectory() as tmp:
        proc = subprocess.Popen([sys.executable, __file__, "--serve", tmp], stdout=subprocess.PIPE, text=True)
        try:
            port = int(proc.stdout.readline())
            res = {}
            for name in DRAWINGS:
                for kind in EDITS:
                    ts = asyncio.run(_round_trips(port, name, kind, reps))
                    res[(name, kind)] = (statistics.median(ts), float(np.percentile(ts, 90)))
            page = browser_round_trips(port, browser_reps) if browser_reps else None
            return res, page
        finally:
            proc.terminate()
            proc.wait(10)


CHROMIUM = Path("/usr/bin/chromium")

# In the page: send a prepared edit, wait for the geometry (its JSON parsed, its payload viewed as
# Float32Array, one view per piece array, as the front end does); no rendering.
_PAGE_JS = """
async ({url, open, edits}) => {
  const ws = new WebSocket(url);
  ws.binaryType = "arraybuffer";
  await new Promise((ok, bad) => { ws.onopen = ok; ws.onerror = bad; });
  let done = null;
  ws.onmessage = (ev) => {
    if (typeof ev.data === "string") {
      done(JSON.parse(ev.data));
      return;
    }
    // [uint32 JSON length n][n bytes of JSON][payload] (protocol.pack)
    const len = new DataView(ev.data).getUint32(0, true);
    const head = JSON.parse(new TextDecoder().decode(new Uint8Array(ev.data, 4, len)));
    const f = new Float32Array(ev.data.slice(4 + len));
    let n = 0;
    for (const p of head.pieces || []) {
      for (const r of [p.points, p.side, p.transforms]) {
        n += f.subarray(r.offset, r.offset + r.shape[0] * r.shape[1]).length;
      }
    }
    done(head);
  };
  const ask = (text) => new Promise((ok) => { done = ok; ws.send(text); });
  await ask(open);
  const ts = [];
  for (const text of edits) {
    const t0 = performance.now();
    const h = await ask(text);
    ts.push(performance.now() - t0);
    if (h.type !== "geometry") throw new Error(JSON.stringify(h));
  }
  ws.close();
  return ts;
}
"""


def browser_round_trips(port: int, reps: int) -> dict[tuple[str, str], tuple[float, float]] | None:
    """(median, p90) ms in headless chromium (Playwright), or None without chromium or Playwright."""
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        return None
    if not CHROMIUM.is_file():
        return None
    res = {}
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=str(CHROMIUM), args=["--no-sandbox", "--disable-gpu"])
        page = browser.new_page()
        page.goto(f"http://127.0.0.1:{port}/bench-blank")   # same origin, no front end loaded
        for name in DRAWINGS:
            d = load(examples.path(DRAWINGS[name]))
            for kind in EDITS:
                msgs = edit_messages(d, kind, 1000 if kind == "point drag" else 5000)
                edits = [next(msgs) for _ in range(reps + 20)]
                ts = page.evaluate(_PAGE_JS, {"url": f"ws://127.0.0.1:{port}/ws", "edits": edits,
                                              "open": json.dumps({"type": "open_example",
                                                                  "name": DRAWINGS[name], "id": 1})})[20:]
                res[(name, kind)] = (statistics.median(ts), float(np.percentile(ts, 90)))
        browser.close()
    return res


# In the page: ask an echo server for a reply of `size` bytes, n times; ms per round trip.
_ECHO_JS = """
async ({url, n, size}) => {
  const ws = new WebSocket(url);
  ws.binaryType = "arraybuffer";
  await new Promise((ok, bad) => { ws.onopen = ok; ws.onerror = bad; });
  let done = null;
  ws.onmessage = (ev) => done(ev.data);
  const ts = [];
  for (let k = 0; k < n; k++) {
    const t0 = performance.now();
    await new Promise((ok) => { done = ok; ws.send(String(size)); });
    ts.push(performance.now() - t0);
  }
  ws.close();
  return ts;
}
"""


def transport_floor(
    reps: int, sizes: tuple[int, ...] = (16, 1000, 13000, 50000)
) -> dict[int, tuple[float, float]] | None:
    """(median, p90) ms of chromium <-> uvicorn round trips that do no studio work at all: an
    echo app (same uvicorn configuration, same socket) answers each message with a binary frame
    of ``size`` bytes. The least any edit can cost in the page, before the server computes."""
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        return None
    if not CHROMIUM.is_file():
        return None
    import threading

    import uvicorn
    from starlette.applications import Starlette
    from starlette.responses import HTMLResponse
    from starlette.routing import Route, WebSocketRoute

    from auszug.cli.studio import bind_local, server_config

    async def echo(ws) -> None:
        await ws.accept()
        while True:
            m = await ws.receive()
            if m["type"] == "websocket.disconnect":
                return
            await ws.send({"type": "websocket.send", "bytes": b"\0" * int(m.get("text") or 0)})

    app = Starlette(routes=[WebSocketRoute("/ws", echo), Route("/", lambda _r: HTMLResponse("<p>echo</p>"))])
    sock = bind_local(0)
    port = sock.getsockname()[1]
    server = uvicorn.Server(server_config(app, lifespan="off"))
    th = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    th.start()
    while not server.started:
        time.sleep(0.02)
    res = {}
    try:
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=str(CHROMIUM), args=["--no-sandbox", "--disable-gpu"])
            page = browser.new_page()
            page.goto(f"http://127.0.0.1:{port}/")
            for size in sizes:
                ts = page.evaluate(_ECHO_JS, {"url": f"ws://127.0.0.1:{port}/ws", "n": reps + 50, "size": size})[50:]
                res[size] = (statistics.median(ts), float(np.percentile(ts, 90)))
            browser.close()
    finally:
        server.should_exit = True
        th.join(10)
    return res


def thread_hop(reps: int = 2000) -> float:
    """Median ms of ``await asyncio.to_thread(noop)``."""
    async def run() -> list[float]:
        ts = []
        for _ in range(reps):
            t0 = time.perf_counter()
            await asyncio.to_thread(lambda: None)
            ts.append(time.perf_counter() - t0)
        return ts
    return statistics.median(asyncio.run(run())[50:]) * 1e3


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reps", type=int, default=400, help="edits per drawing and kind, in-process")
    ap.add_argument("--ws-reps", type=int, default=300, help="round trips per drawing and kind")
    ap.add_argument("--browser-reps", type=int, default=300,
                    help="round trips per drawing and kind in headless chromium (0: skip)")
    ap.add_argument("--markdown", action="store_true", help="also print the RESULTS.md paragraph")
    ap.add_argument("--serve", metavar="WORKSPACE", help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    if a.serve:
        serve(a.serve)
        return 0
    load_avg = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"# machine: {platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}, "
          f"{platform.platform()}; {time.strftime('%Y-%m-%d')}; load average {load_avg:.1f}")
    print(f"# server path: median of {a.reps} edits each; WebSocket: median of {a.ws_reps}"
          " round trips each\n")
    rows = {(n, k): server_path(n, k, a.reps) for n in DRAWINGS for k in EDITS}
    print("| server edit path (ms) | median | p90 | decode | edit + build | geometry | encode | JSON / payload bytes |")
    print("|---|---|---|---|---|---|---|---|")
    for (n, k), r in rows.items():
        print(f"| {n}, {k} | {r['total']:.3f} | {r['p90']:.3f} | {r['decode']:.3f} | {r['edit + build']:.3f} | "
              f"{r['geometry']:.3f} | {r['encode']:.3f} | {r['json_bytes']} / {r['payload_bytes']} |")
    ws, page = websocket_round_trips(a.ws_reps, a.browser_reps)
    print("\n| round trip through uvicorn on 127.0.0.1 (ms) | websockets client: median | p90 | "
          "chromium page: median | p90 | target in the page | authors' demo |")
    print("|---|---|---|---|---|---|---|")
    for (n, k), (med, p90) in ws.items():
        pm = f"{page[(n, k)][0]:.3f} | {page[(n, k)][1]:.3f}" if page else "- | -"
        print(f"| {n}, {k} | {med:.3f} | {p90:.3f} | {pm} | <= {TARGET_PAGE_MS} | {ANCHOR[k]} |")
    if page is None:
        print("\n(no chromium page measured: needs Playwright and /usr/bin/chromium)")
    floor = transport_floor(a.browser_reps) if a.browser_reps else None
    if floor:
        u = rows[("U.XI.28", "point drag")]
        print("\n| chromium <-> uvicorn, no studio work (echo of N bytes) (ms) | median | p90 |")
        print("|---|---|---|")
        for size, (med, p90) in floor.items():
            print(f"| reply of {size} bytes | {med:.3f} | {p90:.3f} |")
        print(f"(a U.XI.28 point drag's reply is {u['json_bytes'] + u['payload_bytes']} bytes)")
    hop = thread_hop()
    print(f"\n| asyncio.to_thread hop | {hop:.3f} ms median | (quick edits run on the event loop instead) |")
    if a.markdown:
        u = rows[("U.XI.28", "point drag")]
        inpage = f", in the page {page[('U.XI.28', 'point drag')][0]:.2f} ms" if page else ""
        print(f"\nU.XI.28 point drag: server path {u['total']:.2f} ms median, WebSocket round trip "
              f"{ws[('U.XI.28', 'point drag')][0]:.2f} ms{inpage}; target <= {TARGET_PAGE_MS} ms in the page.")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
