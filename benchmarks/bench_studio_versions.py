"""The studio page of two versions side by side (issue: studio, speed). Prints tables; not a test.

Each version (a git revision, or the working tree) is served by its own process from its own
source tree and built front end; one headless chromium (software WebGL, as bench_studio.py)
drives both, in alternating rounds, so both see the same machine. Measured on U.XI.28:

- edits sent by the page (bench_studio.py's loop): edit -> geometry in the page, and + the next
  frame finished;
- real mouse drags at 60 Hz (Alt held: no snapping), timed by hooks this script puts into the
  page (so versions without their own input timings are timed alike): from the pointer event
  whose position an edit carries to the page having its geometry (every listener run). A
  top-view drag of curve 0's last vertex, then a side-view drag of its apex.

A revision is checked out with ``git worktree`` under a temporary folder and its front end built
with the repository's web/node_modules. Usage:

    python benchmarks/bench_studio_versions.py [--before REV] [--after REV] [--reps N] [--rounds N]

(defaults: --before HEAD~1, --after the working tree as it is, with its built front end).
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import bench_studio as B

from auszug import examples

REPO = Path(__file__).resolve().parent.parent

# Serves one version: its own auszug on PYTHONPATH, its own front end (AUSZUG_STUDIO_STATIC).
SERVE = r'''
import sys
from pathlib import Path
import uvicorn
from auszug.cli.studio import bind_local
from auszug.studio.server import create_app
try:
    from auszug.cli.studio import server_config
    cfg = server_config(create_app(Path(sys.argv[1])), lifespan="off")
except ImportError:   # versions before server_config
    cfg = uvicorn.Config(create_app(Path(sys.argv[1])), log_level="warning", lifespan="off")
sock = bind_local(0)
print(sock.getsockname()[1], flush=True)
uvicorn.Server(cfg).run(sockets=[sock])
'''

# The harness's own timing: the latest pointer event before an edit is sent is the one whose
# position the edit carries; its geometry counts once every earlier listener has run.
HOOK = """() => {
  const a = window.auszug; window.__lat = []; let last = 0; const at = new Map();
  for (const t of ['pointerrawupdate', 'pointermove']) {
    window.addEventListener(t, (e) => { if (e.timeStamp > last) last = e.timeStamp; }, true);
  }
  const send = a.conn.send.bind(a.conn);
  a.conn.send = (msg, ...rest) => {
    const id = send(msg, ...rest);
    if (msg.type === 'move_vertex' || msg.type === 'set_apex_height') at.set(id, last);
    return id;
  };
  window.__frame = []; const waiting = [];
  a.store.on('geometry', (g) => {
    if (at.has(g.id)) {
      window.__lat.push(performance.now() - at.get(g.id));
      waiting.push([g.revision, at.get(g.id)]);
      at.delete(g.id);
    }
  });
  // pointer event -> the first frame whose 3D members show that geometry: the lines (curves look),
  // else the members of that revision (the page's views.membersRevision, or in versions without it
  // the server's mesh, the only members they draw)
  const shown = () => a.views.membersRevision !== undefined ? a.views.membersRevision
    : a.store.looks.style === 'curves' ? a.store.geometry.revision : (a.store.mesh ? a.store.mesh.revision : 0);
  a.views.onFrame(() => {
    const rev = shown(), now = performance.now();
    while (waiting.length && waiting[0][0] <= rev) window.__frame.push(now - waiting.shift()[1]);
  });
}"""


def checkout(rev: str, tmp: Path) -> tuple[Path, Path]:
    """(source folder, built front end) of ``rev`` ("" = the working tree as it is)."""
    if not rev:
        return REPO / "src", REPO / "src" / "auszug" / "studio" / "static"
    tree = tmp / f"tree-{rev.replace('/', '_').replace('~', '_')}"
    subprocess.run(["git", "-C", str(REPO), "worktree", "add", "--detach", "-q", str(tree), rev], check=True)
    (tree / "web" / "node_modules").symlink_to(REPO / "web" / "node_modules")
    static = tmp / f"static-{tree.name}"
    subprocess.run(["npx", "vite", "build", "--outDir", str(static), "--emptyOutDir", "--logLevel", "warn"],
                   cwd=tree / "web", check=True)
    return tree / "src", static


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", default="HEAD~1", help="git revision (default HEAD~1)")
    ap.add_argument("--after", default="", help="git revision (default: the working tree)")
    ap.add_argument("--reps", type=int, default=150, help="edits per kind and round")
    ap.add_argument("--rounds", type=int, default=4, help="alternating rounds per version")
    ap.add_argument("--style", default="curves", help="the look the pages open in (curves, tube, ...)")
    ap.add_argument("--mouse-only", action="store_true", help="only the mouse drags (no edits sent by the page)")
    a = ap.parse_args(argv)
    from playwright.sync_api import sync_playwright

    tmp = Path(tempfile.mkdtemp(prefix="auszug-versions-"))
    ws = tmp / "ws"
    ws.mkdir()
    shutil.copy(examples.path("web/U.XI.28.uc"), ws / "U.XI.28.uc")
    names = {"before": a.before, "after": a.after or "working tree"}
    procs, urls = {}, {}
    kinds = [("point drag", 1000 / 60), ("point drag", 0.0), ("apex drag", 1000 / 60)]
    sent = {(n, k, p): [] for n in names for k, p in kinds}
    mouse = {(n, k): [] for n in names for k in ("point", "apex")}
    frame = {(n, k): [] for n in names for k in ("point", "apex")}
    try:
        for name, rev in (("before", a.before), ("after", a.after)):
            src, static = checkout(rev, tmp)
            env = dict(os.environ, PYTHONPATH=str(src), AUSZUG_STUDIO_STATIC=str(static))
            procs[name] = subprocess.Popen([sys.executable, "-c", SERVE, str(ws)], stdout=subprocess.PIPE,
                                           text=True, env=env)
            urls[name] = f"http://127.0.0.1:{int(procs[name].stdout.readline())}/"
        with sync_playwright() as pw:
            browser = pw.chromium.launch(executable_path=B.CHROMIUM, args=B.ARGS)
            for r in range(a.rounds):
                for name in (("before", "after") if r % 2 == 0 else ("after", "before")):
                    page = browser.new_page(viewport={"width": 1280, "height": 800})
                    B.open_drawing(page, urls[name], "U.XI.28.uc", a.style)
                    page.evaluate(B.EDITS_JS, {"kind": "point drag", "n": 20, "period": 0})
                    for k, p in ([] if a.mouse_only else kinds):
                        sent[(name, k, p)] += page.evaluate(B.EDITS_JS, {"kind": k, "n": a.reps, "period": p})
                    page.evaluate(HOOK)
                    B.move_mouse(page, *B.grab_point(page), a.reps)
                    page.wait_for_timeout(1500)   # the tubes of the drag's last edit
                    mouse[(name, "point")] += page.evaluate("() => window.__lat.splice(0)")
                    frame[(name, "point")] += page.evaluate("() => window.__frame.splice(0)")
                    B.move_mouse(page, *B.grab_point(page, apex=True), a.reps, apex=True)
                    page.wait_for_timeout(1500)
                    mouse[(name, "apex")] += page.evaluate("() => window.__lat.splice(0)")
                    frame[(name, "apex")] += page.evaluate("() => window.__frame.splice(0)")
                    page.close()
            browser.close()
    finally:
        for p in procs.values():
            p.terminate()
            p.wait(10)
        for t in tmp.glob("tree-*"):
            subprocess.run(["git", "-C", str(REPO), "worktree", "remove", "--force", str(t)], check=False)
        shutil.rmtree(tmp, ignore_errors=True)

    print(f"studio versions on U.XI.28, headless chromium, {os.cpu_count()} cores, {time.strftime('%Y-%m-%d')}, "
          f"load average {os.getloadavg()[0]:.1f}; before = {names['before']}, after = {names['after']}; "
          f"{a.rounds} alternating rounds; look {a.style}")
    print()
    print("| edit sent by the page | before: to geometry (ms) | + frame | after: to geometry (ms) | + frame |")
    print("|---|---|---|---|---|")
    for k, p in ([] if a.mouse_only else kinds):
        b, n = sent[("before", k, p)], sent[("after", k, p)]
        pace = "at a 60 Hz pace" if p else "back to back"
        print(f"| {k}, {pace} | {statistics.median(x for x, _ in b):.2f} | {statistics.median(f for _, f in b):.2f} | "
              f"{statistics.median(x for x, _ in n):.2f} | {statistics.median(f for _, f in n):.2f} |")
    print()
    print("| mouse drag (60 Hz): pointer event -> geometry in page | before: median (ms) | p90 "
          "| after: median (ms) | p90 |")
    print("|---|---|---|---|---|")
    for k, label in (("point", "top-view point drag"), ("apex", "side-view apex drag")):
        b, n = mouse[("before", k)], mouse[("after", k)]
        print(f"| {label} ({len(b)} / {len(n)} edits) | {statistics.median(b):.2f} | {B.pct(b, 0.9):.2f} | "
              f"{statistics.median(n):.2f} | {B.pct(n, 0.9):.2f} |")
    print()
    print(f"| mouse drag (60 Hz): pointer event -> first frame showing it in the 3D view (look {a.style}) "
          "| before: median (ms) | p90 | after: median (ms) | p90 |")
    print("|---|---|---|---|---|")
    for k, label in (("point", "top-view point drag"), ("apex", "side-view apex drag")):
        b, n = frame[("before", k)], frame[("after", k)]
        if not b or not n:
            print(f"| {label} ({len(b)} / {len(n)} edits) | | | | |")
            continue
        print(f"| {label} ({len(b)} / {len(n)} edits) | {statistics.median(b):.2f} | {B.pct(b, 0.9):.2f} | "
              f"{statistics.median(n):.2f} | {B.pct(n, 0.9):.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
