"""Studio speed in headless chromium (issue: studio). Prints a table; not a test.

The studio is served by uvicorn on 127.0.0.1 (in this process) and driven by Debian's chromium
through Playwright with software WebGL (--disable-gpu), as the authors' demo was measured
(tests/data/reference/anchor/README.md). Every edit is sent by the page itself over its
WebSocket; the clock is the page's performance.now():

- edit -> geometry in the page: from sending the edit message until the page has the new
  Geometry and every listener (scene buffers, overlays, panels) has run. Measured at a drag's
  pace (one edit per 16.7 ms, as a 60 Hz mouse sends them) and back to back (each edit right
  after the previous one's frame, while chromium still composites it on the same 2 cores). Target: median <= 2 ms
  for a top-view point drag on U.XI.28 (demo: 1.2 ms point drag, 4.2 ms apex drag).
- edit + rendered frame: the same plus the next animation frame drawn and finished on the GPU
  (gl.readPixels forces completion). Target <= 20 ms (demo: 17-23 ms).
- first load: navigation start to the first frame showing the drawing. Target < 1.5 s.
- GPU resources (renderer.info): geometries, textures and shader programs after the first
  edit, after 1000 edits and after 10 s idle. Target: no growth (the demo leaks a texture a frame).

Usage: python benchmarks/bench_studio.py [--drawing web/U.XI.28.uc] [--edits 1000] [--idle 10] [--looks STYLE]
       python benchmarks/bench_studio.py --diagnose ROUNDS   (each part of the page's share of an edit)
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import shutil
import statistics
import sys
import tempfile
import threading
import time
from pathlib import Path

from auszug import examples

CHROMIUM = "/usr/bin/chromium"
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
        "--disable-sync", "--no-first-run"]
#: The authors' demo (ms), from tests/data/reference/anchor/README.md.
ANCHOR = {"point drag": 1.2, "apex drag": 4.2, "frame": "17-23"}

# Runs in the page: n edits of one kind, one at a time, each after the previous one's frame was
# drawn (so no frame runs while an edit is timed); returns [geometry ms, frame ms] per edit.
# Each edit goes to a new position, so no edit finds its result in the engine's caches.
EDITS_JS = """
async ({kind, n, period}) => {
  // every edit moves to a new place (no two drawings alike: no cached intersections reused)
  const seed = (window.__benchSeed = (window.__benchSeed || 0) + n);
  const a = window.auszug, g0 = a.store.geometry, c = g0.curves[0];
  const last = c.vertices.length - 1, [x, y] = c.vertices[last], h = c.apex;
  const gl = a.views.renderer.getContext(), px = new Uint8Array(4);
  const out = [], start = performance.now();
  for (let k = 0; k < n; k++) {
    const msg = kind === "point drag"
      ? {type: "move_vertex", curve: 0, vertex: last, xy: [x + 1e-3 * Math.sin(0.37 * (seed + k)), y]}
      : {type: "set_apex_height", curve: 0, height: h * (1 - 0.01 * Math.abs(Math.sin(0.37 * (seed + k))))};
    const got = new Promise((res) => { const off = a.store.on("geometry", () => { off(); res(performance.now()); }); });
    if (period) {  // at a drag's pace: one edit per pointer event of a 60 Hz mouse
      const due = start + k * period - performance.now();
      if (due > 0) await new Promise((res) => setTimeout(res, due));
    }
    const t0 = performance.now();
    a.ctx.send(msg);
    const t1 = await got;
    await new Promise((res) => requestAnimationFrame(() => res()));  // the views' frame runs first
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
    const t2 = performance.now();
    out.push([t1 - t0, t2 - t0]);
  }
  return out;
}
"""

# Runs in the page: where curve 0's last vertex is (client pixels), and whether pressing there
# grabs that vertex (a drag of it then follows the mouse).
GRAB_JS = """() => {
  const a = window.auszug, v = a.views, c = a.store.geometry.curves[0], k = c.vertices.length - 1;
  const r = v.rect('top'), b = v.host.getBoundingClientRect(), [sx, sy] = v.topToScreen(...c.vertices[k]);
  const x = b.left + r.x + sx, y = b.top + r.y + sy, e = document.elementFromPoint(x, y);
  const grabs = !!e && e.dataset.role === 'vertex' && e.dataset.curve === '0' && e.dataset.vertex === String(k);
  return {x, y, grabs, what: e ? e.outerHTML.slice(0, 120) : null};
}"""

# Diagnosis (--hide): parts of the page taken out of the frames (the page still computes them).
HIDE_JS = """(parts) => {
  const hide = {
    canvas: ['canvas'], side: ['#side-panel'],
    markers: ['#top-overlay .marks', '#top-overlay .prcs', '#top-overlay .dots'],
  };
  for (const p of parts) {
    if (!hide[p]) throw new Error('--hide: no part ' + p + ' (canvas, side, markers)');
    for (const sel of hide[p]) document.querySelectorAll(sel).forEach((e) => { e.style.visibility = 'hidden'; });
  }
}"""

INFO_JS = """() => {
  const i = window.auszug.views.renderer.info;
  return {geometries: i.memory.geometries, textures: i.memory.textures, programs: (i.programs || []).length};
}"""


def serve(workspace: Path) -> tuple[str, object, threading.Thread]:
    import uvicorn

    from auszug.cli.studio import bind_local, server_config
    from auszug.studio.server import create_app

    sock = bind_local(0)
    server = uvicorn.Server(server_config(create_app(workspace), lifespan="off"))
    th = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    th.start()
    while not server.started:
        time.sleep(0.02)
    return f"http://127.0.0.1:{sock.getsockname()[1]}/", server, th


# Runs in the page: the centre of curve 0's apex marker in the side view (curve 0 selected).
APEX_JS = """() => {
  const e = document.querySelector('[data-testid=apex-marker] .shape');
  if (!e) return null;
  const b = e.getBoundingClientRect();
  return {x: b.left + b.width / 2, y: b.top + b.height / 2};
}"""


def open_drawing(page, url: str, name: str) -> None:
    """Navigate ``page`` to the studio at ``url`` with drawing ``name`` and wait for its first frame."""
    page.goto(f"{url}?open={name}&style=curves")  # the looks are set later (--looks)
    page.wait_for_function("() => window.auszug && window.auszug.timings.length > 0 "
                           "&& window.auszug.timings[0].rendered > 0", timeout=30000)


def move_mouse(page, x0: float, y0: float, reps: int, apex: bool = False, period_s: float = 1 / 60) -> None:
    """Press at (x0, y0) with Alt held (no snapping), move ``reps`` times, one move every
    ``period_s`` to a fresh spot near it (``apex``: up and down by a few pixels), release."""
    page.mouse.move(x0, y0)
    page.keyboard.down("Alt")
    page.mouse.down()
    start = time.perf_counter()
    for k in range(1, reps + 1):
        due = start + k * period_s - time.perf_counter()
        if due > 0:
            time.sleep(due)
        if apex:
            page.mouse.move(x0, y0 - 3 - 3 * math.sin(0.37 * k))
        else:
            page.mouse.move(x0 + 4 * math.sin(0.37 * k), y0 + 4 * math.cos(0.23 * k))
    page.mouse.up()
    page.keyboard.up("Alt")
    page.wait_for_timeout(300)


def grab_point(page, apex: bool = False) -> tuple[float, float]:
    """Where to press: curve 0's last vertex in the top view, or (``apex``) its apex marker in the side view."""
    if apex:
        grab = page.evaluate(APEX_JS)
        if grab is None:
            raise SystemExit("apex drag: the side view shows no apex marker (select curve 0 first)")
    else:
        grab = page.evaluate(GRAB_JS)
        if not grab["grabs"]:
            raise SystemExit(f"mouse drag: pressing at curve 0's last vertex does not grab it ({grab['what']})")
    return grab["x"], grab["y"]


def mouse_drag(
    page, reps: int, period_s: float = 1 / 60, apex: bool = False
) -> tuple[list[float], list[float], list[float]]:
    """A real drag by the mouse (:func:`move_mouse`) of curve 0's last vertex in the top view, or
    (``apex``) of its apex marker in the side view. Per edit (ms): input event -> geometry in the
    page, send -> geometry, input event -> the next frame drawn with it (its draw calls issued)."""
    x0, y0 = grab_point(page, apex)
    page.evaluate("() => { window.auszug.timings.length = 0; }")
    move_mouse(page, x0, y0, reps, apex, period_s)
    t = [e for e in page.evaluate("() => window.auszug.timings") if e["input"] > 0]
    if len(t) < reps // 2:
        raise SystemExit(f"mouse drag: only {len(t)} of {reps} moves sent an edit")
    return ([e["applied"] - e["input"] for e in t], [e["applied"] - e["sent"] for e in t],
            [e["rendered"] - e["input"] for e in t if e["rendered"] > 0])


DIAGNOSIS = (("everything drawn", ()), ("WebGL canvas hidden", ("canvas",)),
             ("canvas, side view and top-view markers hidden", ("canvas", "side", "markers")))


def diagnose(browser, url: str, name: str, reps: int, rounds: int) -> int:
    """The top-view mouse drag with parts of the page hidden, in alternating rounds; prints a table."""
    res: dict[str, list[list[float]]] = {label: [[], []] for label, _ in DIAGNOSIS}
    for r in range(rounds):
        for label, parts in (DIAGNOSIS if r % 2 == 0 else DIAGNOSIS[::-1]):
            page = browser.new_page(viewport={"width": 1280, "height": 800})
            open_drawing(page, url, name)
            page.evaluate(EDITS_JS, {"kind": "point drag", "n": 20, "period": 0})  # warm up
            page.evaluate("() => window.auszug.store.select(0)")   # its vertex: a handle, not a marker
            page.wait_for_timeout(100)
            page.evaluate(HIDE_JS, list(parts))
            di, ds, _ = mouse_drag(page, reps)
            res[label][0] += di
            res[label][1] += ds
            page.close()
    print(f"diagnosis: top-view point drag by the mouse on {name}, {rounds} alternating rounds of {reps} moves, "
          f"{time.strftime('%Y-%m-%d')}, load average {os.getloadavg()[0]:.1f}")
    print()
    print("| page | pointer event -> geometry: median (ms) | p90 | edit sent -> geometry: median (ms) | p90 |")
    print("|---|---|---|---|---|")
    for label, (di, ds) in res.items():
        print(f"| {label} | {statistics.median(di):.2f} | {pct(di, 0.9):.2f} "
              f"| {statistics.median(ds):.2f} | {pct(ds, 0.9):.2f} |")
    return 0


def pct(xs: list[float], q: float) -> float:
    s = sorted(xs)
    return s[min(len(s) - 1, int(q * len(s)))]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--drawing", default="web/U.XI.28.uc", help="bundled drawing (default web/U.XI.28.uc)")
    ap.add_argument("--reps", type=int, default=200, help="timed edits per kind (default 200)")
    ap.add_argument("--edits", type=int, default=1000, help="edits for the GPU-resource check (default 1000)")
    ap.add_argument("--idle", type=float, default=10.0, help="idle seconds for the GPU-resource check")
    ap.add_argument("--looks", default="curves",
                    help="looks style while measuring resources (curves, tube, bar, ribbon)")
    ap.add_argument("--diagnose", type=int, default=0, metavar="ROUNDS",
                    help="only the diagnosis: the mouse drag with parts of the page hidden (nothing; the "
                    "WebGL canvas; canvas, side view and the top view's markers), in ROUNDS alternating "
                    "rounds of fresh pages, so every variant sees the same machine")
    args = ap.parse_args(argv)
    from playwright.sync_api import sync_playwright

    from auszug.studio.server import static_dir

    if not (static_dir() / "index.html").is_file():
        print(f"the studio front end is not built ({static_dir()}); run `make web`", file=sys.stderr)
        return 2
    ws = Path(tempfile.mkdtemp(prefix="auszug-bench-"))
    name = Path(args.drawing).name
    shutil.copy(examples.path(args.drawing), ws / name)
    url, server, th = serve(ws)
    rows = []
    try:
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
            if args.diagnose:
                return diagnose(browser, url, name, args.reps, args.diagnose)
            page = browser.new_page(viewport={"width": 1280, "height": 800})
            loads = []
            for _ in range(3):
                open_drawing(page, url, name)
                loads.append(page.evaluate("() => window.auszug.timings[0].rendered"))
            page.evaluate(EDITS_JS, {"kind": "point drag", "n": 20, "period": 0})  # warm up
            for kind in ("point drag", "apex drag"):
                for pace, period in (("at a 60 Hz drag's pace", 1000 / 60), ("back to back", 0)):
                    res = page.evaluate(EDITS_JS, {"kind": kind, "n": args.reps, "period": period})
                    g = [a for a, _ in res]
                    f = [b for _, b in res]
                    rows.append((f"{kind}, {pace}", kind, statistics.median(g), pct(g, 0.9),
                                 statistics.median(f), pct(f, 0.9)))
            drag = mouse_drag(page, args.reps)   # last: it leaves curve 0 selected
            page.wait_for_timeout(200)
            apex = mouse_drag(page, args.reps, apex=True)
            if args.looks != "curves":
                page.evaluate(f"() => window.auszug.store.setLooks({{style: '{args.looks}'}})")
                page.wait_for_timeout(1500)
            page.evaluate(EDITS_JS, {"kind": "point drag", "n": 1, "period": 0})
            info0 = page.evaluate(INFO_JS)
            page.evaluate(EDITS_JS, {"kind": "point drag", "n": args.edits, "period": 0})
            if args.looks != "curves":
                page.wait_for_timeout(1500)
            info1 = page.evaluate(INFO_JS)
            frames0 = page.evaluate("() => window.auszug.views.frames")
            page.wait_for_timeout(int(args.idle * 1000))
            info2 = page.evaluate(INFO_JS)
            frames1 = page.evaluate("() => window.auszug.views.frames")
            browser.close()
    finally:
        server.should_exit = True
        th.join(10)
        shutil.rmtree(ws, ignore_errors=True)

    print(f"studio speed: {args.drawing} in headless chromium {platform.machine()}, {os.cpu_count()} cores, "
          f"Python {platform.python_version()}, {time.strftime('%Y-%m-%d')}")
    print()
    print("| edit | to geometry in page: median (ms) | p90 | + rendered frame: median (ms) | p90 | target "
          "| authors' demo (ms) |")
    print("|---|---|---|---|---|---|---|")
    for label, kind, gm, g9, fm, f9 in rows:
        print(f"| {label} | {gm:.2f} | {g9:.2f} | {fm:.2f} | {f9:.2f} | <= 2 (point drag), <= 20 with frame | "
              f"{ANCHOR[kind]} ({ANCHOR['frame']} with frame) |")
    di, ds, dr = drag
    print()
    print("| top-view point drag by the mouse (60 Hz, real pointer events) | median (ms) | p90 | target "
          "| authors' demo (ms) |")
    print("|---|---|---|---|---|")
    print(f"| pointer event -> geometry in page | {statistics.median(di):.2f} | {pct(di, 0.9):.2f} | <= 2 "
          f"| {ANCHOR['point drag']} |")
    print(f"| edit sent -> geometry in page | {statistics.median(ds):.2f} | {pct(ds, 0.9):.2f} | | |")
    print(f"| pointer event -> next frame drawn with it | {statistics.median(dr):.2f} | {pct(dr, 0.9):.2f} | <= 20 "
          f"| {ANCHOR['frame']} |")
    print(f"({len(di)} edits of {args.reps} moves)")
    ai, as_, ar = apex
    print()
    print("| side-view apex drag by the mouse (60 Hz, curve 0 selected) | median (ms) | p90 | target "
          "| authors' demo (ms) |")
    print("|---|---|---|---|---|")
    print(f"| pointer event -> geometry in page | {statistics.median(ai):.2f} | {pct(ai, 0.9):.2f} | "
          f"| {ANCHOR['apex drag']} |")
    print(f"| edit sent -> geometry in page | {statistics.median(as_):.2f} | {pct(as_, 0.9):.2f} | | |")
    print(f"| pointer event -> next frame drawn with it | {statistics.median(ar):.2f} | {pct(ar, 0.9):.2f} | <= 20 "
          f"| {ANCHOR['frame']} |")
    print(f"({len(ai)} edits of {args.reps} moves)")
    print()
    print(f"| first load (navigation to first frame) | {', '.join(f'{t:.0f}' for t in loads)} ms | target < 1500 ms |")
    print()
    print(f"| GPU resources (looks: {args.looks}) | geometries | textures | programs |")
    print("|---|---|---|---|")
    print(f"| after the first edit | {info0['geometries']} | {info0['textures']} | {info0['programs']} |")
    print(f"| after {args.edits} more edits | {info1['geometries']} | {info1['textures']} | {info1['programs']} |")
    print(f"| after {args.idle:g} s idle ({frames1 - frames0} frames drawn) | {info2['geometries']} | "
          f"{info2['textures']} | {info2['programs']} |")
    grew = any(info2[k] > info0[k] or info1[k] > info0[k] for k in info0)
    print()
    print("GPU resources grew: " + ("YES" if grew else "no"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
