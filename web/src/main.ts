// The studio's entry point: state, connection, views, and the modules that fill the page.
import "./style.css";
import { initBackground } from "./background";
import { Connection, socketUrl, type Reply } from "./connection";
import type { Ctx } from "./context";
import { initCurvePanel } from "./curvepanel";
import { initFiles } from "./files";
import { replicaCount } from "./geometry";
import { initHelp } from "./help";
import { initLooks } from "./looks";
import { PROTOCOL_VERSION, type ClientMessage, type Geometry, type ServerMessage } from "./protocol";
import { Views } from "./scene";
import { installShortcuts, registerShortcut } from "./shortcuts";
import { initSideView } from "./sideview";
import { Store, type Mode } from "./store";
import { initTopView } from "./topview";
import { readUrlState, writeUrlState } from "./urlstate";
import { button } from "./ui";

/** One edit's timeline (performance.now() values), for the speed benchmark and the e2e tests. */
export interface EditTiming {
  id: number;
  revision: number;
  /** The timeStamp of the user input the edit answers (0 when none was given). */
  input: number;
  sent: number;
  received: number;
  applied: number;
  rendered: number;
  /** The first frame whose 3D members (lines, or tubes/bars/ribbons in those looks) show this
   * revision or a later one (0: not yet). */
  shown: number;
}

const store = new Store();
const statusEl = document.getElementById("status")!;
const timings: EditTiming[] = [];
let receivedAt = 0;

function statusText(msg: Geometry): string {
  const n = replicaCount(msg);
  const trues = msg.intersections.filter((x) => x.true).length;
  let text = `${msg.path || msg.name || "untitled"}${msg.dirty ? " (unsaved)" : ""}: ${msg.n_curves} basic curves, ` +
    `${n} replicas, ${trues} true / ${msg.intersections.length - trues} false intersections`;
  if (msg.protocol !== PROTOCOL_VERSION) text += ` (server protocol ${msg.protocol}, page ${PROTOCOL_VERSION}: reload)`;
  return text;
}

store.on("status", ({ text, error }) => {
  if (statusEl.textContent !== text) statusEl.textContent = text;
  statusEl.classList.toggle("error", error);
});

/** Set a data-* attribute of the status bar only when it changes (tests read them). */
function statusData(key: string, value: string): void {
  if (statusEl.dataset[key] !== value) statusEl.dataset[key] = value;
}

const conn = new Connection(socketUrl(window.location), {
  message(msg: ServerMessage, binary: ArrayBuffer | null) {
    receivedAt = performance.now();
    switch (msg.type) {
      case "geometry": {
        store.setGeometry(msg, binary!);
        const sent = conn.sentAt.get(msg.id);
        if (sent !== undefined) {
          const t: EditTiming = { id: msg.id, revision: msg.revision, input: conn.inputAt.get(msg.id) ?? 0, sent, received: receivedAt,
            applied: performance.now(), rendered: 0, shown: 0 };
          timings.push(t);
          if (timings.length > 5000) timings.splice(0, 1000);
        }
        statusData("replicas", String(replicaCount(msg)));
        statusData("revision", String(msg.revision));
        statusData("curves", String(msg.n_curves));
        store.status(statusText(msg));
        break;
      }
      case "mesh":
        store.setMesh(msg, binary!);
        break;
      case "loops":
        store.setLoops(msg, binary!);
        break;
      case "error":
        store.status(msg.message, true);
        break;
      case "saved":
        store.status(`saved ${msg.path}`);
        break;
      default:
        break; // files, exported: awaited by their requesters
    }
  },
  opened(again) {
    document.body.dataset.connected = "true";
    if (store.geometry) store.status(statusText(store.geometry));
    else store.status("connected: open a drawing (Open..., Ctrl+O) or start a new one (New)");
    // a reconnecting tab (or a reload, from the URL) asks for its own document back: the server still
    // has it, or restores it from the autosave this document wrote (docs/studio.md, "Resume")
    const g = store.geometry;
    if (again && g) conn.send({ type: "resume", doc: g.doc, path: g.path });
    else if (!again) {
      const u = readUrlState(window.location.search);
      if (u.doc) conn.send({ type: "resume", doc: u.doc, path: u.open });
      else if (u.open) conn.send({ type: "open", path: u.open });
    }
  },
  closed() {
    document.body.dataset.connected = "false";
    store.status("disconnected from the studio server; reconnecting...", true);
  },
});

const views = new Views(document.getElementById("viewport")!, store);
views.onFrame(() => {
  const last = timings[timings.length - 1];
  if (last && !last.rendered) last.rendered = views.lastFrameAt;
  for (let i = timings.length - 1; i >= 0 && !timings[i].shown; i--) {
    if (timings[i].revision <= views.membersRevision) timings[i].shown = views.lastFrameAt;
  }
});

const ctx: Ctx = {
  store,
  conn,
  views,
  send: (msg: ClientMessage) => conn.send(msg),
  request: (msg: ClientMessage, input?: number): Promise<Reply> =>
    conn.request(msg, input).catch((e: Error) => {
      store.status(e.message, true);
      throw e;
    }),
};

// ---- modes and history (the rest of the toolbar belongs to the modules)

const modeTools = document.getElementById("mode-tools")!;
// the other page of the studio: window tracery (tracery.html, tracery.ts)
const toTracery = document.createElement("a");
toTracery.href = "./tracery.html";
toTracery.textContent = "Tracery";
toTracery.className = "page-link";
toTracery.title = "The tracery page: Gothic window tracery (Fig. 20 a-h), live 2D and 3D";
toTracery.dataset.testid = "page-tracery";
modeTools.before(toTracery);
const modeButtons: Record<Mode, HTMLButtonElement> = {
  design: button(modeTools, "Design", "Design mode: top view editing (D)", "mode-design", () => store.setMode("design")),
  preview: button(modeTools, "Preview", "Preview mode: 3D, top and side views (P)", "mode-preview", () => store.setMode("preview")),
};
const syncMode = () => {
  for (const [m, b] of Object.entries(modeButtons)) b.setAttribute("aria-pressed", String(store.mode === m));
};
store.on("mode", syncMode);
syncMode();
registerShortcut({ key: "d", description: "Design mode", run: () => store.setMode("design") });
registerShortcut({ key: "p", description: "Preview mode", run: () => store.setMode("preview") });

const history = document.getElementById("history-tools")!;
const undo = button(history, "Undo", "Undo (Ctrl+Z)", "undo", () => conn.send({ type: "undo" }));
const redo = button(history, "Redo", "Redo (Ctrl+Shift+Z)", "redo", () => conn.send({ type: "redo" }));
undo.disabled = redo.disabled = true;
store.on("geometry", (g) => {
  undo.disabled = !g.can_undo;
  redo.disabled = !g.can_redo;
});
registerShortcut({ key: "z", ctrl: true, description: "Undo", run: () => conn.send({ type: "undo" }) });
registerShortcut({ key: "z", ctrl: true, shift: true, description: "Redo", run: () => conn.send({ type: "redo" }) });
registerShortcut({ key: "y", ctrl: true, description: "Redo", run: () => conn.send({ type: "redo" }) });
registerShortcut({ key: "f", description: "Fit the views to the drawing", run: () => { views.fit(); views.requestRender(); } });

// the URL keeps the open document, the looks and the mode (a reload restores them)
const fromUrl = readUrlState(window.location.search);
if (fromUrl.style) store.setLooks({ style: fromUrl.style });
if (fromUrl.faces) store.setLooks({ faces: fromUrl.faces });
if (fromUrl.mode) store.setMode(fromUrl.mode);
if (fromUrl.split !== null) store.setSplit(fromUrl.split);
function syncUrl(): void {
  const g = store.geometry;
  const search = writeUrlState(window.location.search, {
    open: g?.path ?? fromUrl.open, doc: g?.doc ?? fromUrl.doc, style: store.looks.style, faces: store.looks.faces,
    mode: store.mode, split: store.split,
  });
  if (search !== window.location.search) window.history.replaceState(null, "", window.location.pathname + search);
}
store.on("geometry", syncUrl);
store.on("looks", syncUrl);
store.on("mode", syncUrl);
store.on("split", syncUrl);

initTopView(ctx);
initCurvePanel(ctx);
initSideView(ctx);
initLooks(ctx);
initFiles(ctx);
initBackground(ctx);
initHelp(ctx);
installShortcuts();

// The hook the end-to-end tests and the speed benchmark read (no effect on the app).
declare global {
  interface Window {
    auszug: { store: Store; views: Views; conn: Connection; timings: EditTiming[]; ctx: Ctx };
  }
}
window.auszug = { store, views, conn, timings, ctx };
views.requestRender();
