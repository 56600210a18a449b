"""Studio speed in headless chromium (issues: studio, 13). Prints tables, the headline last; not a test.

The studio is served by uvicorn on 127.0.0.1 (in this process) and driven by Debian's chromium
through Playwright with software WebGL (--disable-gpu), as the authors' demo was measured (the
reference outputs' anchor README; its figures are copied into ANCHOR below). The clock is the
page's performance.now(). Each drawing (default U.XI.28 and the chancel) is measured in each look
(default tube, the studio's default, and curves), in a fresh page:

- HEADLINE, issue 13: a real mouse drag at 60 Hz (Alt held, no snapping), from the pointer event
  to the first frame whose 3D view shows the geometry that event produced: the lines in the
  curves look, the tubes in the tube look (the page's own drag tubes; the server's full mesh
  follows on release: "refined", last pointer event -> that mesh on screen). Targets: U.XI.28
  point drag median <= 8.5 ms (half the demo's 17 ms) and p90 <= 25 ms; chancel median <= 20 ms.
  The same for an apex drag in the side view (no target).
- pointer event -> geometry in the page (every listener run) and edit sent -> geometry.
- edits sent by the page itself (on the first drawing): edit -> geometry, and -> the first frame
  showing it finished on the GPU (gl.readPixels), at a 60 Hz pace and back to back.
- first load: navigation start to the first frame showing the drawing (target < 1 s).
- GPU resources (renderer.info) after the first edit, 1000 edits and 10 s idle: no growth.

The load average at the start and the end is printed: on a shared machine every figure grows
with it. Usage:
       python benchmarks/bench_studio.py [--drawings A,B] [--styles tube,curves] [--reps 200]
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
from typing import Any

from auszug import examples

CHROMIUM = "/usr/bin/chromium"
ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
        "--disable-sync", "--no-first-run"]
#: The authors' demo (ms), copied from the reference outputs' README (anchor/README.md, "Measured
#: speed of the demo"): an edit in the page, and an edit plus one rendered frame.
ANCHOR = {"point drag": 1.2, "apex drag": 4.2, "frame": "17-23"}
#: Issue 13's targets, pointer event -> frame (ms): median at most half the demo's 17 ms and p90 for
#: the U.XI.28 point drag; median for the chancel.
TARGET = {"median": 8.5, "p90": 25.0, "chancel median": 20.0}
#: The chancel (56 replicas), the issue's large drawing.
CHANCEL = "web/3d-scan-final.uc"

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
    const got = new Promise((res) => {
      const off = a.store.on("geometry", (g) => { off(); res([performance.now(), g.revision]); });
    });
    if (period) {  // at a drag's pace: one edit per pointer event of a 60 Hz mouse
      const due = start + k * period - performance.now();
      if (due > 0) await new Promise((res) => setTimeout(res, due));
    }
    const t0 = performance.now();
    a.ctx.send(msg);
    const [t1, rev] = await got;
    // the first frame whose 3D members show this revision (lines; tubes in the tube look); pages
    // from before views.membersRevision (bench_studio_versions.py): the next frame
    await new Promise((res) => {
      const off = a.views.onFrame(() => {
        if (a.views.membersRevision === undefined || a.views.membersRevision >= rev) { off(); res(); }
      });
    });
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


def open_drawing(page, url: str, name: str, style: str = "curves") -> None:
    """Navigate ``page`` to the studio at ``url`` with drawing ``name`` in the look ``style`` and
    wait for its first frame."""
    page.goto(f"{url}?open={name}&style={style}")
    page.wait_for_function("() => window.auszug && window.auszug.timings.length > 0 "
                           "&& window.auszug.timings[0].rendered > 0", timeout=30000)


def move_mouse(page, x0: float, y0: float, reps: int, apex: bool = False, period_s: float = 1 / 60,
               settle: bool = True) -> None:
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
    if settle:
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


# Runs in the page right after a drag's release: ms from the last pointer event to the first frame
# showing the server's mesh of the final geometry (the refined tubes), or null in the curves look.
REFINED_JS = """async () => {
  const a = window.auszug, s = a.store;
  if (s.looks.style === 'curves') return null;
  const input = Math.max(...a.timings.map((e) => e.input));
  await new Promise((res) => {
    const check = () => !!s.mesh && s.mesh.revision === s.geometry.revision
      && a.views.membersRevision >= s.mesh.revision;
    const off = a.views.onFrame(() => { if (check()) { off(); res(); } });
    a.views.requestRender();
  });
  return performance.now() - input;
}"""


def mouse_drag(page, reps: int, period_s: float = 1 / 60, apex: bool = False) -> dict[str, list[float]]:
    """A real drag by the mouse (:func:`move_mouse`) of curve 0's last vertex in the top view, or
    (``apex``) of its apex marker in the side view. Per edit (ms): ``geometry``: input event ->
    geometry in the page; ``sent``: edit sent -> geometry; ``frame``: input event -> the first
    frame whose 3D members (lines, or tubes in the tube look) show that geometry (or a later one).
    ``refined``: the last input event -> the server's mesh of the final geometry on screen."""
    x0, y0 = grab_point(page, apex)
    page.evaluate("() => { window.auszug.timings.length = 0; }")
    move_mouse(page, x0, y0, reps, apex, period_s, settle=False)
    refined = page.evaluate(REFINED_JS)
    page.wait_for_timeout(300)
    t = [e for e in page.evaluate("() => window.auszug.timings") if e["input"] > 0]
    if len(t) < reps // 2:
        raise SystemExit(f"mouse drag: only {len(t)} of {reps} moves sent an edit")
    return {"geometry": [e["applied"] - e["input"] for e in t], "sent": [e["applied"] - e["sent"] for e in t],
            "frame": [e["shown"] - e["input"] for e in t if e["shown"] > 0],
            "refined": [] if refined is None else [refined]}


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
            d = mouse_drag(page, reps)
            res[label][0] += d["geometry"]
            res[label][1] += d["sent"]
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


def page_edits(page, n: int) -> list[tuple[str, float, float, float, float]]:
    """Edits sent by the page itself (:data:`EDITS_JS`): per kind and pace, the medians and p90s of
    edit -> geometry and edit -> first frame showing it (ms)."""
    rows = []
    for kind in ("point drag", "apex drag"):
        for pace, period in (("at a 60 Hz drag's pace", 1000 / 60), ("back to back", 0)):
            res = page.evaluate(EDITS_JS, {"kind": kind, "n": n, "period": period})
            g = [a for a, _ in res]
            f = [b for _, b in res]
            rows.append((f"{kind}, {pace}", statistics.median(g), pct(g, 0.9), statistics.median(f), pct(f, 0.9)))
    return rows


def target(drawing: str, kind: str) -> tuple[str, Any]:
    """The issue's target for pointer event -> frame (text, and a check of (median, p90)) or ("", None)."""
    if kind != "point drag":
        return "", None
    if Path(drawing).name == Path(CHANCEL).name:
        return f"median <= {TARGET['chancel median']:g}", lambda m, p: m <= TARGET["chancel median"]
    return (f"median <= {TARGET['median']:g}, p90 <= {TARGET['p90']:g}",
            lambda m, p: m <= TARGET["median"] and p <= TARGET["p90"])


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--drawings", default=f"web/U.XI.28.uc,{CHANCEL}",
                    help=f"bundled drawings, comma separated (default web/U.XI.28.uc,{CHANCEL})")
    ap.add_argument("--styles", default="tube,curves",
                    help="looks to measure in, comma separated (default tube,curves)")
    ap.add_argument("--reps", type=int, default=200, help="mouse moves per drag (default 200)")
    ap.add_argument("--page-edits", type=int, default=100,
                    help="edits sent by the page per row, on the first drawing (default 100; 0: none)")
    ap.add_argument("--edits", type=int, default=1000, help="edits for the GPU-resource check (default 1000)")
    ap.add_argument("--idle", type=float, default=10.0, help="idle seconds for the GPU-resource check")
    ap.add_argument("--looks", default="tube",
                    help="looks style for first load and the GPU resources (curves, tube, bar, ribbon; default tube)")
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
    drawings = [d for d in args.drawings.split(",") if d]
    styles = [s for s in args.styles.split(",") if s]
    ws = Path(tempfile.mkdtemp(prefix="auszug-bench-"))
    for d in drawings:
        shutil.copy(examples.path(d), ws / Path(d).name)
    load0 = os.getloadavg()[0]
    url, server, th = serve(ws)
    drags: dict[tuple[str, str], tuple[dict, dict]] = {}
    rows: dict[str, list] = {}
    try:
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=CHROMIUM, args=ARGS)
            if args.diagnose:
                return diagnose(browser, url, Path(drawings[0]).name, args.reps, args.diagnose)
            for d in drawings:
                for style in styles:
                    page = browser.new_page(viewport={"width": 1280, "height": 800})
                    open_drawing(page, url, Path(d).name, style)
                    page.evaluate(EDITS_JS, {"kind": "point drag", "n": 20, "period": 0})  # warm up
                    if d == drawings[0] and args.page_edits:
                        rows[style] = page_edits(page, args.page_edits)
                    drag = mouse_drag(page, args.reps)   # it leaves curve 0 selected
                    page.wait_for_timeout(200)
                    drags[d, style] = (drag, mouse_drag(page, args.reps, apex=True))
                    page.close()
            page = browser.new_page(viewport={"width": 1280, "height": 800})
            name = Path(drawings[0]).name
            loads = []
            for _ in range(3):
                open_drawing(page, url, name, args.looks)
                loads.append(page.evaluate("() => window.auszug.timings[0].rendered"))
            page.wait_for_timeout(1500)
            page.evaluate(EDITS_JS, {"kind": "point drag", "n": 1, "period": 0})
            page.wait_for_timeout(1000)
            info0 = page.evaluate(INFO_JS)
            page.evaluate(EDITS_JS, {"kind": "point drag", "n": args.edits, "period": 0})
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
    load1 = os.getloadavg()[0]

    print(f"studio speed in headless chromium (software WebGL), {platform.machine()}, {os.cpu_count()} cores, "
          f"Python {platform.python_version()}, {time.strftime('%Y-%m-%d %H:%M')}, "
          f"load average {load0:.1f} at the start, {load1:.1f} at the end")
    for style, rs in rows.items():
        print()
        print(f"Edits sent by the page on {drawings[0]}, look {style} ({args.page_edits} per row):")
        print()
        print("| edit | to geometry in page: median (ms) | p90 | to the frame showing it: median (ms) | p90 "
              "| authors' demo (ms) |")
        print("|---|---|---|---|---|---|")
        for label, gm, g9, fm, f9 in rs:
            kind = label.split(",")[0]
            print(f"| {label} | {gm:.2f} | {g9:.2f} | {fm:.2f} | {f9:.2f} "
                  f"| {ANCHOR[kind]} ({ANCHOR['frame']} with frame) |")
    print()
    print("Mouse drags (60 Hz real pointer events, Alt held), pointer event -> geometry in the page:")
    print()
    print("| drawing | look | drag | to geometry: median (ms) | p90 | edit sent -> geometry: median (ms) | p90 "
          "| edits |")
    print("|---|---|---|---|---|---|---|---|")
    for (d, style), pair in drags.items():
        for kind, r in zip(("point drag", "apex drag"), pair, strict=True):
            print(f"| {Path(d).name} | {style} | {kind} | {statistics.median(r['geometry']):.2f} "
                  f"| {pct(r['geometry'], 0.9):.2f} | {statistics.median(r['sent']):.2f} | {pct(r['sent'], 0.9):.2f} "
                  f"| {len(r['geometry'])} of {args.reps} |")
    print()
    print(f"| first load, look {args.looks} (navigation to first frame) | {', '.join(f'{t:.0f}' for t in loads)} ms "
          f"| target < 1000 ms |")
    print()
    print(f"| GPU resources (look {args.looks}) | geometries | textures | programs |")
    print("|---|---|---|---|")
    print(f"| after the first edit | {info0['geometries']} | {info0['textures']} | {info0['programs']} |")
    print(f"| after {args.edits} more edits | {info1['geometries']} | {info1['textures']} | {info1['programs']} |")
    print(f"| after {args.idle:g} s idle ({frames1 - frames0} frames drawn) | {info2['geometries']} | "
          f"{info2['textures']} | {info2['programs']} |")
    grew = any(info2[k] > info0[k] or info1[k] > info0[k] for k in info0)
    print(f"GPU resources grew: {'YES' if grew else 'no'}")
    print()
    print("HEADLINE: pointer event -> the first frame on screen whose 3D view shows the new geometry (lines in the "
          "curves look, tubes in the tube look), mouse drags at 60 Hz; refined: the last pointer event -> the "
          f"server's full mesh on screen; load average {load0:.1f} -> {load1:.1f}")
    print()
    print("| drawing | look | drag | median (ms) | p90 (ms) | frames | target | met | refined (ms) "
          "| authors' demo (ms) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for (d, style), pair in drags.items():
        for kind, r in zip(("point drag", "apex drag"), pair, strict=True):
            f = r["frame"]
            m, p9 = (statistics.median(f), pct(f, 0.9)) if f else (math.nan, math.nan)
            text, ok = target(d, kind)
            met = "" if ok is None else ("yes" if f and ok(m, p9) else "NO")
            ref = f"{r['refined'][0]:.0f}" if r["refined"] else ""
            print(f"| {Path(d).name} | {style} | {kind} | {m:.2f} | {p9:.2f} | {len(f)} of {len(r['geometry'])} "
                  f"| {text} | {met} | {ref} | {ANCHOR['frame']} (geometry alone {ANCHOR[kind]}) |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
