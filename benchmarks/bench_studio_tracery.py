"""The tracery page's speed in headless chromium (issue 13, section 5). Prints a table; not a test.

The studio is served by uvicorn on 127.0.0.1 (in this process) and driven by Debian's chromium
through Playwright with software WebGL (--disable-gpu), as ``bench_studio.py`` measures the design
page. A change is a value typed into a field of the tracery page (``params.excess``, each time a
new value, so nothing is cached), committed by its ``change`` event; the clock is the page's
performance.now(), from the event's ``timeStamp`` to:

- the reply in the page (the server built the structure and the preview mesh; ``build_ms`` and
  ``mesh_ms`` are the server's own share);
- the 2D view redrawn (the SVG's paths rewritten);
- the next 3D frame drawn with the new mesh and finished (gl.readPixels).

Target: <= 50 ms for Fig. 20h. Also, in-process for comparison: ``build`` and the preview mesh
against the finished watertight mesh (``window_mesh``) that exports use; first load; GPU resources.

Usage: python benchmarks/bench_studio_tracery.py [--style fig20h] [--changes 60] [--keyboard 20]
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from bench_studio import ARGS, CHROMIUM, pct, serve

# Runs in the page: n changes of params.excess through the field's change event, each after the previous
# one's frame; returns [reply, svg, frame] ms from the event per change, and the server's shares.
CHANGES_JS = """
async ({n, base, cycle}) => {
  const T = window.auszugTracery, input = document.querySelector("[data-testid='field-params.excess']");
  const v = T.view3d, gl = v.renderer.getContext(), px = new Uint8Array(4), out = [];
  for (let k = 0; k < n; k++) {
    const before = T.timings.length;
    const kk = cycle ? k % cycle : k;   // cycle: the same few values again (undo / redo)
    input.value = String(base + 0.2 * Math.abs(Math.sin(0.37 * (kk + 1))) + 1e-4 * kk);
    const ev = new Event("change");
    input.dispatchEvent(ev);
    // the frame with the new mesh: waited for by the view's frame listeners (the page's own frame
    // callbacks, or the frameListeners set of pages before onFrame), then finished by readPixels
    await new Promise((r) => {
      const done = () => { if (T.timings.length > before) { stop(); r(); } };
      const stop = v.onFrame ? v.onFrame(done) : (v.frameListeners.add(done), () => v.frameListeners.delete(done));
    });
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
    const done = performance.now(), t = T.timings[T.timings.length - 1];
    out.push([t.received - ev.timeStamp, t.svg - ev.timeStamp, done - ev.timeStamp, t.build_ms, t.mesh_ms,
              t.svg - t.received, t.meshed - t.svg, t.frame - t.meshed, done - t.frame, t.rendered - t.frame,
              done - t.rendered]);
  }
  return out;
}
"""

MEMORY_JS = """() => { const i = window.auszugTracery.view3d.renderer.info;
  return {geometries: i.memory.geometries, textures: i.memory.textures, programs: (i.programs || []).length}; }"""


def in_process(style: str, reps: int = 15) -> dict[str, float]:
    """Median ms of the structure, the preview mesh and the finished mesh, in this process."""
    from auszug.studio import protocol as P
    from auszug.studio.tracery import build_message, window_style
    from auszug.tracery import build, load_style, window_mesh
    from auszug.tracery.preview import preview_mesh

    st = load_style(style)
    out: dict[str, list[float]] = {"build": [], "preview mesh": [], "finished mesh (window_mesh)": [],
                                   "whole server job (style, build, preview, paths, encoding)": []}
    for k in range(reps):
        s = st.with_overrides({"params.excess": 1.1 + 0.01 * k})
        t0 = time.perf_counter()
        t = build(s)
        t1 = time.perf_counter()
        preview_mesh(t)
        t2 = time.perf_counter()
        if k < 5:
            window_mesh(t)
        t3 = time.perf_counter()
        out["build"].append((t1 - t0) * 1e3)
        out["preview mesh"].append((t2 - t1) * 1e3)
        if k < 5:
            out["finished mesh (window_mesh)"].append((t3 - t2) * 1e3)
        values = [f"params.excess={1.2 + 0.01 * k}"]
        t4 = time.perf_counter()
        msg, payload = build_message(window_style(None, style, "", values), style, "", values)
        P.pack(P.encode(msg), payload)
        out["whole server job (style, build, preview, paths, encoding)"].append((time.perf_counter() - t4) * 1e3)
    return {k: statistics.median(v) for k, v in out.items()}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--style", default="fig20h")
    ap.add_argument("--changes", type=int, default=60)
    ap.add_argument("--keyboard", type=int, default=20, help="changes typed with Playwright's keyboard")
    args = ap.parse_args(argv)
    from playwright.sync_api import sync_playwright

    print(f"# tracery page, {args.style}; {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
          f"load average {os.getloadavg()[0]:.1f} at the start")
    with tempfile.TemporaryDirectory() as tmp, sync_playwright() as pw:
        url, server, th = serve(Path(tmp))
        browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
        page = browser.new_page(viewport={"width": 1280, "height": 800})
        loads = []
        for _ in range(3):
            t0 = time.perf_counter()
            page.goto(f"{url}tracery.html?style={args.style}")
            page.wait_for_function("() => window.auszugTracery && window.auszugTracery.view3d.frames > 0 "
                                   "&& window.auszugTracery.shown()", timeout=60000)
            loads.append((time.perf_counter() - t0) * 1e3)
        page.evaluate(CHANGES_JS, {"n": 5, "base": 1.0, "cycle": 0})   # warm up
        mem0 = page.evaluate(MEMORY_JS)
        rows = page.evaluate(CHANGES_JS, {"n": args.changes, "base": 1.0, "cycle": 0})
        mem1 = page.evaluate(MEMORY_JS)
        load = os.getloadavg()[0]
        cols = list(zip(*rows, strict=True))
        names = ["change event -> reply in the page", "change event -> 2D view redrawn",
                 "change event -> 3D frame drawn (gl.readPixels)", "  server: build (structure)",
                 "  server: preview mesh", "  page: fields and 2D view", "  page: 3D buffers and normals",
                 "  page: waiting for the animation frame", "  page: drawing the 3D frame",
                 "    renderer.render (three.js, WebGL calls)", "    finishing it (gl.readPixels)"]
        print(f"\n| {args.style}, {args.changes} changes of excess (field change event) | median (ms) | p90 | target |")
        print("|---|---|---|---|")
        for name, col in zip(names, cols, strict=True):
            target = "<= 50" if name.startswith("change event -> 3D frame") else ""
            print(f"| {name} | {statistics.median(col):.1f} | {pct(list(col), 0.9):.1f} | {target} |")
        # two values in turn (as undo / redo): built once, then from the server's cache if it has one
        again = page.evaluate(CHANGES_JS, {"n": 20, "base": 0.9, "cycle": 2})[2:]
        print(f"| the same two values in turn (18, as undo / redo): change event -> 3D frame drawn | "
              f"{statistics.median(r[2] for r in again):.1f} | {pct([r[2] for r in again], 0.9):.1f} | <= 50 |")
        # real keys: fill the field, Enter commits it
        kb = []
        field = page.locator("[data-testid='field-params.excess']")
        for k in range(args.keyboard):
            n0 = page.evaluate("() => window.auszugTracery.timings.length")
            field.fill(f"{1.05 + 0.01 * k:.4f}")
            field.press("Enter")
            page.wait_for_function(f"() => window.auszugTracery.timings.length > {n0}", timeout=60000)
            t = page.evaluate("() => { const t = window.auszugTracery.timings.at(-1); return t.rendered - t.input; }")
            kb.append(t)
        if kb:
            print(f"| typed + Enter ({len(kb)}, Playwright keyboard): change event -> 3D frame drawn | "
                  f"{statistics.median(kb):.1f} | {pct(kb, 0.9):.1f} | <= 50 |")
        print(f"\nload average during the runs: {load:.1f} (2 cores)")
        first = ", ".join(f"{x:.0f}" for x in loads)
        print(f"\n| first load (navigation to the first 3D frame) | {first} ms | target < 1000 ms |")
        print(f"\n| GPU resources | geometries | textures | programs |\n|---|---|---|---|\n"
              f"| after 5 changes | {mem0['geometries']} | {mem0['textures']} | {mem0['programs']} |\n"
              f"| after {args.changes} more | {mem1['geometries']} | {mem1['textures']} | {mem1['programs']} |")
        browser.close()
        server.should_exit = True  # type: ignore[attr-defined]
        th.join(10)
    ip = in_process(args.style)
    print(f"\n| in-process, {args.style} (median ms) | " + " | ".join(ip) + " |")
    print("|---|" + "---|" * len(ip))
    print("| | " + " | ".join(f"{v:.1f}" for v in ip.values()) + f" |\n(load average {os.getloadavg()[0]:.1f})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
