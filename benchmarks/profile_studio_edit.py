"""Where the design page's time goes per edit (issue 13): listeners, the frame, the main thread.

Diagnosis, not a benchmark with targets (bench_studio.py measures those). On U.XI.28 in headless
chromium with software WebGL (the benchmark's setup), three measurements:

- ``listeners``: each ``geometry`` listener, ``store.setGeometry``, the message handler and
  ``views.render`` timed with the page's clock (wrapped in the page, medians per edit), for 100
  edits sent by the page at 60 Hz and a 200-move mouse drag; plus each edit's sent -> received
  (round trip and waiting for the main thread) and received -> applied (every listener run).
- ``frame``: ``views.render()`` + a 1-pixel ``gl.readPixels`` (the GPU work finished) during a
  held drag, as shown and with the drag tubes, the lines or everything hidden; draw calls and
  primitives of one frame.
- ``trace``: a Chrome trace of a 200-move mouse drag: self and total ms per move of the busiest
  trace events on the renderer's main thread, the GPU process and the compositors.

Usage: ``python benchmarks/profile_studio_edit.py [--style tube|curves] [--what listeners,frame,trace]``.
"""

from __future__ import annotations

import argparse
import collections
import json
import shutil
import statistics
import sys
import tempfile
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).parent))
import bench_studio as bench

DRAWING = "web/U.XI.28.uc"

# Runs in the page: wrap every geometry listener, setGeometry, the socket's receive and views.render
# with timers (window.__acc: label -> ms per call).
INSTRUMENT_JS = """() => {
  const a = window.auszug, s = a.store, acc = (window.__acc = {});
  const add = (k, dt) => (acc[k] ??= []).push(dt);
  const timed = (label, fn) => (...args) => {
    const t = performance.now(), r = fn(...args);
    add(label, performance.now() - t);
    return r;
  };
  const set = s.listeners.get('geometry'), fns = [...set];
  set.clear();
  fns.forEach((fn, i) => {
    const src = fn.toString().slice(0, 60).replace(/\\s+/g, ' ');
    set.add(timed('geometry listener #' + i + ': ' + src, fn));
  });
  a.views.render = timed('views.render (three.js, every view)', a.views.render.bind(a.views));
  a.conn.receive = timed('conn.receive (unpack + handler + listeners)', a.conn.receive.bind(a.conn));
  s.setGeometry = timed('store.setGeometry (every listener)', s.setGeometry.bind(s));
}"""

FRAME_JS = """async ({n}) => {
  const a = window.auszug, v = a.views, sc = v.scene, r = v.renderer, gl = r.getContext(), px = new Uint8Array(4);
  const tubes = sc.getObjectByName('drag-tubes'), net = v.network;
  const variants = {
    'as shown': () => {},
    'drag tubes hidden': () => { if (tubes) tubes.visible = false; },
    'lines hidden': () => { net.visible = false; },
    'everything hidden (clears only)': () => { sc.children.forEach((c) => { c.visible = false; }); },
  };
  const out = {};
  for (const [name, hide] of Object.entries(variants)) {
    const vis = sc.children.map((c) => c.visible), tv = tubes ? tubes.visible : false;
    hide();
    const xs = [];
    for (let k = 0; k < n; k++) {
      await new Promise((res) => setTimeout(res, 20));
      const t = performance.now();
      v.render();
      gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
      xs.push(performance.now() - t);
    }
    sc.children.forEach((c, i) => { c.visible = vis[i]; });
    if (tubes) tubes.visible = tv;
    xs.sort((p, q) => p - q);
    out[name] = [xs[n >> 1], xs[Math.floor(0.9 * n)]];
  }
  r.info.autoReset = false;
  r.info.reset();
  v.render();
  const info = {...r.info.render};
  r.info.autoReset = true;
  return {times: out, canvas: [r.domElement.width, r.domElement.height], calls: info.calls,
    triangles: info.triangles, lines: info.lines, lineObjects: net.children.length};
}"""


def median_p90(xs: list[float]) -> tuple[float, float]:
    s = sorted(xs)
    return statistics.median(s), s[min(len(s) - 1, int(0.9 * len(s)))]


def print_listeners(page, title: str) -> None:
    acc = page.evaluate("() => window.__acc")
    t = page.evaluate("() => window.auszug.timings")
    rt = median_p90([e["received"] - e["sent"] for e in t])
    ap = median_p90([e["applied"] - e["received"] for e in t])
    print(f"\n{title} ({len(t)} edits): sent -> received {rt[0]:.2f} ms median (p90 {rt[1]:.2f}), "
          f"received -> applied {ap[0]:.2f} (p90 {ap[1]:.2f})\n")
    print("| part | median (ms) | p90 | calls |")
    print("|---|---|---|---|")
    for k, xs in sorted(acc.items(), key=lambda kv: -sum(kv[1])):
        m, p = median_p90(xs)
        print(f"| {k.replace('|', '/')} | {m:.2f} | {p:.2f} | {len(xs)} |")
    page.evaluate("() => { for (const k in window.__acc) window.__acc[k] = []; window.auszug.timings.length = 0; }")


def hold_drag(page) -> tuple[float, float]:
    """Press on curve 0's last vertex (Alt held) and move a little: the page shows its drag tubes."""
    x0, y0 = bench.grab_point(page)
    page.mouse.move(x0, y0)
    page.keyboard.down("Alt")
    page.mouse.down()
    for k in range(5):
        page.mouse.move(x0 + k + 3, y0 + k)
        page.wait_for_timeout(50)
    page.wait_for_timeout(300)
    return x0, y0


def trace_summary(events: list[dict[str, Any]], moves: int, top: int = 20) -> None:
    names = {(e["pid"], e["tid"]): e["args"]["name"] for e in events
             if e.get("ph") == "M" and e.get("name") == "thread_name"}
    by_thread: dict[tuple[int, int], list[dict[str, Any]]] = collections.defaultdict(list)
    for e in events:
        if e.get("ph") == "X" and "dur" in e:
            by_thread[(e["pid"], e["tid"])].append(e)
    for key, es in by_thread.items():
        name = names.get(key, str(key))
        if name not in ("CrRendererMain", "CrGpuMain", "VizCompositorThread", "Compositor"):
            continue
        es.sort(key=lambda e: (e["ts"], -e["dur"]))
        own: collections.Counter[str] = collections.Counter()
        total: collections.Counter[str] = collections.Counter()
        stack: list[dict[str, Any]] = []
        for e in es:
            while stack and stack[-1]["ts"] + stack[-1]["dur"] <= e["ts"]:
                stack.pop()
            if stack:
                own[stack[-1]["name"]] -= e["dur"]
            own[e["name"]] += e["dur"]
            total[e["name"]] += e["dur"]
            stack.append(e)
        print(f"\n{name}: ms per move, self / total\n")
        print("| event | self | total |")
        print("|---|---|---|")
        for k, v in own.most_common(top):
            print(f"| {k} | {v / 1000 / moves:.2f} | {total[k] / 1000 / moves:.2f} |")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--style", default="tube", choices=["tube", "curves"])
    ap.add_argument("--what", default="listeners,frame,trace")
    ap.add_argument("--moves", type=int, default=200)
    args = ap.parse_args(argv)
    what = set(args.what.split(","))
    from playwright.sync_api import sync_playwright

    ws = Path(tempfile.mkdtemp())
    shutil.copy(bench.examples.path(DRAWING), ws / Path(DRAWING).name)
    url, server, _ = bench.serve(ws)
    with open("/proc/loadavg") as f:
        print(f"look {args.style}; load average at the start {f.read().split()[0]}")
    try:
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=bench.CHROMIUM, args=bench.ARGS)
            page = browser.new_page(viewport={"width": 1280, "height": 800})
            bench.open_drawing(page, url, Path(DRAWING).name, args.style)
            page.wait_for_timeout(500)
            if "listeners" in what:
                page.evaluate(INSTRUMENT_JS)
                page.evaluate("() => { window.auszug.timings.length = 0; }")
                page.evaluate(bench.EDITS_JS, {"kind": "point drag", "n": 100, "period": 1000 / 60})
                print_listeners(page, "Edits sent by the page at 60 Hz")
                x0, y0 = bench.grab_point(page)
                bench.move_mouse(page, x0, y0, args.moves)
                print_listeners(page, f"Mouse drag, {args.moves} moves at 60 Hz")
            if "frame" in what:
                hold_drag(page)
                f = page.evaluate(FRAME_JS, {"n": 30})
                page.mouse.up()
                page.keyboard.up("Alt")
                print(f"\nOne frame during a held drag (render + 1-pixel readPixels), canvas {f['canvas']}, "
                      f"{f['calls']} draw calls, {f['triangles']} triangles, {f['lines']} line segments, "
                      f"{f['lineObjects']} line objects\n")
                print("| frame | median (ms) | p90 |")
                print("|---|---|---|")
                for k, (m, q) in f["times"].items():
                    print(f"| {k} | {m:.2f} | {q:.2f} |")
                page.wait_for_timeout(500)
            if "trace" in what:
                x0, y0 = bench.grab_point(page)
                browser.start_tracing(page=page, categories=["devtools.timeline", "toplevel", "blink", "gpu", "cc",
                                                             "viz", "disabled-by-default-devtools.timeline"])
                bench.move_mouse(page, x0, y0, args.moves)
                data = json.loads(browser.stop_tracing())
                trace_summary(data["traceEvents"] if isinstance(data, dict) else data, args.moves)
            browser.close()
    finally:
        server.should_exit = True  # type: ignore[attr-defined]
    with open("/proc/loadavg") as f:
        print(f"\nload average at the end {f.read().split()[0]}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
