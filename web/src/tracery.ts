// The tracery page: pick a window style (Fig. 20 a-h, the prototype, or a style file of the workspace),
// edit its values in fields, see the 2D structure (SVG, exact arcs) and a 3D preview (three.js, the design
// page's 3D look: raised three-quarter camera, fitted), save the style and export the window.
// The server builds every state from scratch (stateless, src/auszug/studio/tracery.py): a refused value
// is shown at its field and nothing changes; undo / redo and the URL hold the page's states.
import "./style.css";
import "./fielderror.css";
import "./tracery.css";
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import { Connection, socketUrl } from "./connection";
import { clearFieldError, showFieldError } from "./fielderror";
import { perFrame } from "./frames";
import { vertexNormals } from "./meshnormals";
import type { ClientMessage, ServerMessage, Styles, TraceryField, TraceryGeometry } from "./protocol";
import { VIEW3D } from "./scene";
import { vertexColourMaterial } from "./shading";
import { shadeVertices, type Lighting } from "./vertexlight";
import { installShortcuts, registerShortcut } from "./shortcuts";
import { History, readTraceryUrl, withValue, writeTraceryUrl, type TraceryState } from "./tracerystate";
import { button } from "./ui";
import { fitDistance } from "./camerafit";

/** One change's timeline (performance.now()), for the speed benchmark and the tests. */
export interface TraceryTiming {
  id: number;
  input: number;
  sent: number;
  received: number;
  svg: number;
  /** The 3D buffers rewritten (normals and vertex colours computed), the frame started, the frame drawn. */
  meshed: number;
  frame: number;
  rendered: number;
  build_ms: number;
  mesh_ms: number;
}

const statusEl = document.getElementById("status")!;
function status(text: string, error = false): void {
  statusEl.textContent = text;
  statusEl.classList.toggle("error", error);
}

let state: TraceryState = readTraceryUrl(window.location.search);
let shown: TraceryGeometry | null = null;
const history = new History();
const timings: TraceryTiming[] = [];
let pending: TraceryTiming | null = null;

const conn = new Connection(socketUrl(window.location), {
  message(_msg: ServerMessage) {
    // replies are awaited by their requests
  },
  opened(again) {
    document.body.dataset.connected = "true";
    if (!again) void listStyles();
    void go(state, "open");
  },
  closed() {
    document.body.dataset.connected = "false";
    status("disconnected from the studio server; reconnecting...", true);
  },
});

// ---------------------------------------------------------------- toolbar

const pages = document.getElementById("page-tools")!;
const toDesign = document.createElement("a");
toDesign.href = "./";
toDesign.textContent = "Design";
toDesign.className = "page-link";
toDesign.dataset.testid = "page-design";
toDesign.title = "The design page (Gothic microarchitecture)";
pages.appendChild(toDesign);
const here = document.createElement("span");
here.textContent = "Tracery";
here.className = "page-link current";
here.dataset.testid = "page-tracery";
pages.appendChild(here);

const styleTools = document.getElementById("style-tools")!;
const picker = document.createElement("select");
picker.dataset.testid = "tracery-style";
picker.title = "The window style: a built-in style, the prototype, or a style file of the workspace";
styleTools.append("style ", picker);

async function listStyles(): Promise<void> {
  const r = await conn.request({ type: "list_styles" });
  const msg = r.msg as Styles;
  picker.replaceChildren();
  const builtin = document.createElement("optgroup");
  builtin.label = "built-in";
  for (const [i, name] of msg.builtin.entries()) builtin.appendChild(new Option(`${name}: ${msg.descriptions[i]}`, `style:${name}`));
  builtin.appendChild(new Option("prototype: the paper's eight polygons", "style:prototype"));
  picker.appendChild(builtin);
  if (msg.workspace.length) {
    const files = document.createElement("optgroup");
    files.label = "workspace";
    for (const p of msg.workspace) files.appendChild(new Option(p, `path:${p}`));
    picker.appendChild(files);
  }
  syncPicker();
}

function syncPicker(): void {
  const want = state.path ? `path:${state.path}` : `style:${state.style}`;
  if (![...picker.options].some((o) => o.value === want)) {
    picker.appendChild(new Option(state.path || state.style, want));
  }
  picker.value = want;
}

picker.addEventListener("change", (ev) => {
  const v = picker.value;
  const next: TraceryState = v.startsWith("path:") ? { style: "", path: v.slice(5), values: [] }
    : { style: v.slice(6), path: "", values: [] };
  void change(next, ev.timeStamp, picker);
});

const historyTools = document.getElementById("history-tools")!;
const undoB = button(historyTools, "Undo", "Undo (Ctrl+Z)", "undo", () => void step("undo"));
const redoB = button(historyTools, "Redo", "Redo (Ctrl+Shift+Z)", "redo", () => void step("redo"));
function syncHistory(): void {
  undoB.disabled = !history.canUndo;
  redoB.disabled = !history.canRedo;
}
syncHistory();
registerShortcut({ key: "z", ctrl: true, description: "Undo", run: () => void step("undo") });
registerShortcut({ key: "z", ctrl: true, shift: true, description: "Redo", run: () => void step("redo") });
registerShortcut({ key: "y", ctrl: true, description: "Redo", run: () => void step("redo") });

const saveTools = document.getElementById("save-tools")!;
const saveName = document.createElement("input");
saveName.type = "text";
saveName.placeholder = "my-window.toml";
saveName.size = 16;
saveName.dataset.testid = "tracery-save-name";
saveName.title = "A file name in the workspace, ending in .toml or .json";
saveTools.appendChild(saveName);
button(saveTools, "Save style", "Save the style (TOML or JSON) to the workspace", "tracery-save", () => void save());
for (const f of ["glb", "obj", "stl", "svg", "json"] as const) {
  button(saveTools, f.toUpperCase(), f === "svg" ? "Export the 2D drawing (exact arcs)" : f === "json" ?
    "Export the 2D structure (.tracery.json)" : `Export the finished window as one watertight mesh (.${f})`,
  `tracery-export-${f}`, () => void exportAs(f));
}

// ---------------------------------------------------------------- fields
const fieldsEl = document.getElementById("fields")!;
const inputs = new Map<string, HTMLInputElement | HTMLSelectElement>();

function fieldText(f: TraceryField): string {
  return typeof f.value === "number" ? String(f.value) : String(f.value);
}

function buildFields(fields: TraceryField[]): void {
  const same = fields.length === inputs.size && fields.every((f) => inputs.has(f.key));
  if (!same) {
    fieldsEl.replaceChildren();
    inputs.clear();
    let group = "";
    let box: HTMLElement = fieldsEl;
    for (const f of fields) {
      if (f.group !== group) {
        group = f.group;
        box = document.createElement("section");
        const h = document.createElement("h2");
        h.textContent = group;
        box.appendChild(h);
        fieldsEl.appendChild(box);
      }
      const row = document.createElement("div");
      row.className = "row";
      const label = document.createElement("label");
      label.textContent = f.label;
      label.title = f.key;
      let input: HTMLInputElement | HTMLSelectElement;
      if (f.kind === "choice") {
        input = document.createElement("select");
      } else {
        input = document.createElement("input");
        if (f.kind === "bool") input.type = "checkbox";
        else {
          input.type = "text";
          input.inputMode = "decimal";
          input.size = 8;
        }
      }
      input.dataset.testid = `field-${f.key}`;
      input.dataset.key = f.key;
      input.addEventListener("change", (ev) => onField(f.key, input, ev.timeStamp));
      if (input instanceof HTMLInputElement && input.type === "text") {
        input.addEventListener("keydown", (ev) => {
          if (ev.key === "Enter") {
            ev.preventDefault();
            input.blur(); // commits (change) and hands the keyboard back
          }
        });
      }
      label.appendChild(input);
      row.appendChild(label);
      box.appendChild(row);
      inputs.set(f.key, input);
    }
  }
  for (const f of fields) {
    const input = inputs.get(f.key)!;
    if (input instanceof HTMLSelectElement) {
      const opts = f.options.join("\u0000");
      if (input.dataset.options !== opts) {
        input.replaceChildren(...f.options.map((o) => new Option(o, o)));
        input.dataset.options = opts;
      }
      input.value = String(f.value);
    } else if (input.type === "checkbox") input.checked = Boolean(f.value);
    else if (document.activeElement !== input || !input.getAttribute("aria-invalid")) input.value = fieldText(f);
  }
}

function valueOf(input: HTMLInputElement | HTMLSelectElement): string {
  if (input instanceof HTMLInputElement && input.type === "checkbox") return String(input.checked);
  const v = input.value.trim();
  // numbers and true/false as TOML reads them; anything else as a TOML string
  if (/^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(v) || v === "true" || v === "false") return v;
  return JSON.stringify(v);
}

function onField(key: string, input: HTMLInputElement | HTMLSelectElement, at: number): void {
  const next = { ...state, values: withValue(state.values, key, valueOf(input)) };
  void change(next, at, input);
}

// ---------------------------------------------------------------- building
let seq = 0;

/** Ask the server for `next`; show it if it builds (the newest request wins), else the message at `at`. */
async function change(next: TraceryState, input: number, at: HTMLElement | null): Promise<boolean> {
  const before = state;
  const ok = await go(next, "change", input, at);
  if (ok) {
    history.push(before);
    syncHistory();
  }
  return ok;
}

async function step(which: "undo" | "redo"): Promise<void> {
  const s = which === "undo" ? history.undo(state) : history.redo(state);
  if (!s) return;
  if (await go(s.target, which)) {
    s.commit();
    syncHistory();
  }
}

async function go(next: TraceryState, why: string, input = 0, at: HTMLElement | null = null): Promise<boolean> {
  const mine = ++seq;
  const msg: ClientMessage = { type: "tracery_build", style: next.style, path: next.path, values: next.values };
  const sent = performance.now();
  let r;
  try {
    r = await conn.request(msg, input);
  } catch (e) {
    if (at) showFieldError(at, (e as Error).message);
    status((e as Error).message, true);
    if (at === picker) syncPicker();
    return false;
  }
  if (mine !== seq && why !== "open") return false; // a newer request is on its way
  const reply = r.msg;
  if (reply.type === "tracery_refused") {
    if (at) showFieldError(at, reply.message);
    status(reply.message, true);
    if (at === picker) syncPicker();
    document.body.dataset.refused = String(Number(document.body.dataset.refused ?? 0) + 1);
    return false;
  }
  if (reply.type !== "tracery") return false;
  if (at) clearFieldError(at);
  for (const el of inputs.values()) clearFieldError(el);
  pending = { id: reply.id, input, sent, received: performance.now(), svg: 0, meshed: 0, frame: 0, rendered: 0, build_ms: reply.build_ms, mesh_ms: reply.mesh_ms };
  state = { style: next.style, path: next.path, values: reply.values };
  show(reply, r.binary!);
  const search = writeTraceryUrl(window.location.search, state);
  if (search !== window.location.search) window.history.replaceState(null, "", window.location.pathname + search);
  syncPicker();
  return true;
}

function show(msg: TraceryGeometry, binary: ArrayBuffer): void {
  shown = msg;
  buildFields(msg.fields);
  drawSvg(msg);
  if (pending) pending.svg = performance.now();
  view3d.setMesh(msg, binary); // and draws the frame (the timing's `meshed`, `frame` and `rendered`)
  document.body.dataset.regions = String(msg.regions.length);
  status(`${msg.path || msg.name}: ${msg.regions.length} regions, ${msg.n_lights} lights, depth ${msg.depth}; ` +
    `${msg.cached ? "from the server's cache (built in" : "built in"} ${msg.build_ms.toFixed(1)} ms, ` +
    `preview mesh ${msg.mesh_ms.toFixed(1)} ms${msg.cached ? ")" : ""} ` +
    `(${msg.indices.shape[0]} triangles; exports are the finished watertight mesh)`);
}

// ---------------------------------------------------------------- 2D
const svgHost = document.getElementById("tracery-2d")!;
const SVGNS = "http://www.w3.org/2000/svg";
const svg = document.createElementNS(SVGNS, "svg");
svg.dataset.testid = "tracery-svg";
const flip = document.createElementNS(SVGNS, "g");
flip.setAttribute("transform", "scale(1,-1)");
svg.appendChild(flip);
svgHost.appendChild(svg);
const FILL: Record<string, string> = { light: "#a9c9e8", blind: "#b3a997" };
const FRAME = ["#e4ddd2", "#d9d1c4"];

/** Set attribute `name` of `el` to `value` unless it has it already (an unchanged path is not redrawn). */
function setAttr(el: Element, name: string, value: string): void {
  if (el.getAttribute(name) !== value) el.setAttribute(name, value);
}

/** The regions as SVG paths. The path elements are kept between edits and their attributes updated in
 * place (most edits change the `d` of every path and nothing else), not replaced. */
function drawSvg(msg: TraceryGeometry): void {
  const [x0, y0, x1, y1] = msg.bounds;
  const m = 0.05 * Math.max(x1 - x0, y1 - y0);
  setAttr(svg, "viewBox", `${x0 - m} ${-(y1 + m)} ${x1 - x0 + 2 * m} ${y1 - y0 + 2 * m}`);
  const sw = String(0.003 * (x1 - x0));
  while (flip.childElementCount > msg.regions.length) flip.lastElementChild!.remove();
  for (const [i, r] of msg.regions.entries()) {
    let p = flip.children[i] as SVGPathElement | undefined;
    if (!p) {
      p = document.createElementNS(SVGNS, "path");
      p.setAttribute("stroke", "#3b3530");
      p.appendChild(document.createElementNS(SVGNS, "title"));
      flip.appendChild(p);
    }
    setAttr(p, "d", r.d);
    setAttr(p, "fill", r.group === "arch" && r.depth === 0 ? "#cfc6b8" : r.role === "frame" ? FRAME[r.depth % 2] : FILL[r.role] ?? "#ccc");
    setAttr(p, "stroke-width", sw);
    if (p.dataset.id !== r.id) p.dataset.id = r.id;
    if (p.dataset.group !== r.group) p.dataset.group = r.group;
    if (p.dataset.role !== r.role) p.dataset.role = r.role;
    const title = `${r.id} (${r.group}, ${r.role})`;
    const t = p.firstElementChild!;
    if (t.textContent !== title) t.textContent = title;
  }
}

// ---------------------------------------------------------------- 3D
const SKY = 0xe9eef3;

class View3d {
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly camera = new THREE.PerspectiveCamera(35, 1, 0.01, 1e5);
  readonly orbit: OrbitControls;
  readonly geometry = new THREE.BufferGeometry();
  /** The back half's: the same positions and indices, its own colours (shaded with mirrored normals). */
  readonly backGeometry = new THREE.BufferGeometry();
  readonly mesh: THREE.Mesh;
  /** The back half: the front half mirrored in the middle plane y = 0 (the same buffers). */
  readonly back: THREE.Mesh;
  readonly lighting: Lighting;
  /** Vertex normals of the current mesh (CPU only: the shading is per vertex). */
  private normals = new Float32Array(0);
  /** Whether the back half's colours are those of the current mesh (shaded when it is first shown). */
  private backShaded = false;
  lastFrameAt = 0;
  frames = 0;
  /** How many vertices of the buffers the current mesh uses. */
  used = 0;
  private fittedFor = "";
  private bounds = new THREE.Box3();
  private frameListeners = new Set<() => void>();

  constructor(readonly host: HTMLElement) {
    this.renderer = new THREE.WebGLRenderer({ antialias: !/SwiftShader|llvmpipe/i.test(rendererName()), preserveDrawingBuffer: false });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    this.renderer.setClearColor(SKY);
    this.renderer.domElement.dataset.testid = "tracery-canvas";
    host.appendChild(this.renderer.domElement);
    this.camera.up.set(0, 0, 1);
    // Lambert shading (matte stone), computed per vertex (vertexlight.ts) and drawn unlit with vertex
    // colours: on a software renderer the fragment shader is a frame's cost (bench_studio_tracery.py).
    // The lights are fixed in the world (they do not follow the camera), as three.js lights would be:
    // a hemisphere light along +y (three.js's default light position), a sun and a fill light.
    const rgb = (hex: number, k: number): [number, number, number] => {
      const c = new THREE.Color(hex); // sRGB hex -> linear working colour space
      return [k * c.r, k * c.g, k * c.b];
    };
    const toward = (x: number, y: number, z: number): [number, number, number] => {
      const l = Math.hypot(x, y, z);
      return [x / l, y / l, z / l];
    };
    this.lighting = {
      albedo: rgb(0xcfc6b8, 1),
      hemisphere: { up: [0, 1, 0], sky: rgb(0xffffff, 1.6), ground: rgb(0xb8b0a0, 1.6) },
      directional: [{ toward: toward(0.6, -1, 1.6), color: rgb(0xffffff, 1.5) },
        { toward: toward(-1, 0.8, 0.4), color: rgb(0xffffff, 0.6) }],
    };
    // front faces only: the preview's triangles face out of the stone (tracery/preview.py, tested), the
    // mirrored back half included (three.js flips the winding of a mirrored object)
    // (the colours encoded to sRGB per vertex, not per pixel: shading.ts, vertexColourMaterial)
    const material = vertexColourMaterial(THREE.FrontSide);
    this.mesh = new THREE.Mesh(this.geometry, material);
    this.mesh.name = "window";
    this.back = new THREE.Mesh(this.backGeometry, material);
    this.back.name = "window-back";
    this.back.scale.set(1, -1, 1);
    this.scene.add(this.mesh, this.back);
    this.orbit = new OrbitControls(this.camera, this.renderer.domElement);
    this.orbit.addEventListener("change", () => this.requestRender());
    new ResizeObserver(() => this.resize()).observe(host);
    this.resize();
  }

  resize(): void {
    const w = Math.max(this.host.clientWidth, 1), h = Math.max(this.host.clientHeight, 1);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.requestRender();
  }

  /** The preview mesh of `msg` (positions and indices in the payload); the buffers are replaced, the
   * old ones disposed, so GPU resources do not grow with edits. */
  setMesh(msg: TraceryGeometry, binary: ArrayBuffer): void {
    const nv = msg.positions.shape[0], nt = msg.indices.shape[0];
    const pos = new Float32Array(binary, msg.positions.offset * 4, nv * 3);
    const idx = new Uint32Array(binary, msg.indices.offset * 4, nt * 3);
    // The buffers are kept between edits (a quarter larger than needed, the rest unused): an edit
    // rewrites them in place (bufferSubData), where new buffers would cost the software renderer a
    // new vertex array and uploads of their whole size. They grow (new buffers, the old ones freed)
    // only when a mesh does not fit.
    // 16-bit indices while the vertices fit them: half the bytes to upload after an edit
    let P = this.geometry.getAttribute("position") as THREE.BufferAttribute | undefined;
    let I = this.geometry.getIndex();
    if (!P || !I || P.array.length < 3 * nv || I.array.length < 3 * nt) {
      const cv = Math.ceil(1.25 * nv), ct = Math.ceil(1.25 * nt);
      this.geometry.dispose();
      this.backGeometry.dispose();
      P = new THREE.BufferAttribute(new Float32Array(3 * cv), 3);
      I = new THREE.BufferAttribute(cv <= 65536 ? new Uint16Array(3 * ct) : new Uint32Array(3 * ct), 1);
      this.normals = new Float32Array(3 * cv);
      for (const g of [this.geometry, this.backGeometry]) {
        g.setAttribute("position", P);
        g.setAttribute("color", new THREE.BufferAttribute(new Float32Array(3 * cv), 3));
        g.setIndex(I);
      }
    }
    const C = this.geometry.getAttribute("color") as THREE.BufferAttribute;
    (P.array as Float32Array).set(pos);
    (I.array as Uint16Array | Uint32Array).set(idx);
    vertexNormals(pos, idx, nv, nt, this.normals);
    shadeVertices(this.normals, nv, this.lighting, C.array as Float32Array);
    for (const [attr, n] of [[P, 3 * nv], [C, 3 * nv], [I, 3 * nt]] as [THREE.BufferAttribute, number][]) this.upload(attr, n);
    this.backShaded = false;
    this.used = nv;
    const [a, b, c, d, e, f] = msg.mesh_bounds;
    for (const g of [this.geometry, this.backGeometry]) {
      g.setDrawRange(0, 3 * nt);
      g.boundingBox = new THREE.Box3(new THREE.Vector3(a, b, c), new THREE.Vector3(d, e, f));
      g.boundingSphere = g.boundingBox.getBoundingSphere(new THREE.Sphere());
    }
    // the whole window: the front half and its mirror image
    this.bounds.set(new THREE.Vector3(a, b, c), new THREE.Vector3(d, Math.max(e, -b), f));
    const key = `${msg.style}\u0000${msg.path}`;
    if (key !== this.fittedFor || !this.inView()) {
      this.fittedFor = key;
      this.fit();
    }
    if (pending) pending.meshed = performance.now();
    // drawn now, not at the next animation frame: the canvas is shown at the browser's next frame either
    // way, and the software renderer's work is then done before it rather than inside it
    this.render();
  }

  private upload(attr: THREE.BufferAttribute, n: number): void {
    attr.clearUpdateRanges();
    attr.addUpdateRange(0, n);
    attr.needsUpdate = true;
  }

  /** The back half's colours for the current mesh, computed and uploaded when it is first drawn. */
  private shadeBack(): void {
    const CB = this.backGeometry.getAttribute("color") as THREE.BufferAttribute;
    shadeVertices(this.normals, this.used, this.lighting, CB.array as Float32Array, true);
    this.upload(CB, 3 * this.used);
    this.backShaded = true;
  }

  private corners(): THREE.Vector3[] {
    const b = this.bounds, out: THREE.Vector3[] = [];
    for (let i = 0; i < 8; i++) out.push(new THREE.Vector3(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z));
    return out;
  }

  /** The design page's opening view (VIEW3D: 35° up, 35° round from the front), framing the window. */
  fit(): void {
    const el = THREE.MathUtils.degToRad(VIEW3D.elevation), az = THREE.MathUtils.degToRad(VIEW3D.azimuth);
    const back = new THREE.Vector3(Math.cos(el) * Math.sin(az), -Math.cos(el) * Math.cos(az), Math.sin(el)).normalize();
    const c = this.bounds.getCenter(new THREE.Vector3());
    const d = fitDistance(this.corners(), c, back, this.camera.fov, this.camera.aspect, VIEW3D.fill);
    this.camera.position.copy(c).addScaledVector(back, d);
    this.camera.near = d / 1000;
    this.camera.far = d * 100;
    this.camera.updateProjectionMatrix();
    this.orbit.target.copy(c);
    this.orbit.update();
  }

  /** Whether the whole preview is inside the view. */
  inView(): boolean {
    this.camera.updateMatrixWorld();
    for (const p of this.corners()) {
      p.project(this.camera);
      if (Math.abs(p.x) > 1 || Math.abs(p.y) > 1 || p.z > 1) return false;
    }
    return true;
  }

  /** Calls `fn` after every frame drawn; returns the function that stops it. */
  onFrame(fn: () => void): () => void {
    this.frameListeners.add(fn);
    return () => this.frameListeners.delete(fn);
  }

  readonly requestRender = perFrame(() => this.render());

  render(): void {
    if (pending && !pending.rendered) pending.frame = performance.now();
    // seen from the front, the back half shows only through the lights: it is drawn when the camera is
    // behind the middle plane, which halves a frame's triangles in the usual views
    this.back.visible = this.camera.position.y > 0;
    if (this.back.visible && !this.backShaded) this.shadeBack();
    this.renderer.render(this.scene, this.camera);
    this.lastFrameAt = performance.now();
    this.frames++;
    if (pending && !pending.rendered) {
      pending.rendered = this.lastFrameAt;
      timings.push(pending);
      if (timings.length > 2000) timings.splice(0, 500);
      pending = null;
    }
    for (const fn of this.frameListeners) fn();
  }
}

function rendererName(): string {
  try {
    const gl = document.createElement("canvas").getContext("webgl2");
    const ext = gl?.getExtension("WEBGL_debug_renderer_info");
    return ext && gl ? String(gl.getParameter(ext.UNMASKED_RENDERER_WEBGL)) : "";
  } catch {
    return "";
  }
}

const view3d = new View3d(document.getElementById("tracery-3d")!);
registerShortcut({ key: "f", description: "Fit the 3D view to the window", run: () => { view3d.fit(); view3d.requestRender(); } });

// ---------------------------------------------------------------- save and export
async function save(): Promise<void> {
  const target = saveName.value.trim();
  if (!/\.(toml|json)$/i.test(target)) {
    showFieldError(saveName, "a file name in the workspace ending in .toml or .json");
    return;
  }
  const r = await conn.request({ type: "tracery_save", target, style: state.style, path: state.path, values: state.values })
    .catch((e: Error) => { showFieldError(saveName, e.message); return null; });
  if (!r) return;
  if (r.msg.type === "tracery_refused") {
    showFieldError(saveName, r.msg.message);
    return;
  }
  if (r.msg.type !== "saved") return;
  clearFieldError(saveName);
  const saved = r.msg.path;
  await listStyles();
  // from now on the page shows the saved file (its values are in it)
  await change({ style: "", path: saved, values: [] }, 0, null);
  status(`saved ${saved}`);
  document.body.dataset.saved = saved;
}

async function exportAs(format: "glb" | "obj" | "stl" | "svg" | "json"): Promise<void> {
  status(`exporting ${format}...`);
  const r = await conn.request({ type: "tracery_export", format, style: state.style, path: state.path, values: state.values })
    .catch((e: Error) => { status(e.message, true); return null; });
  if (!r) return;
  if (r.msg.type === "tracery_refused") {
    status(r.msg.message, true);
    return;
  }
  if (r.msg.type !== "exported" || !r.binary) return;
  const blob = new Blob([r.binary], { type: r.msg.mime });
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = r.msg.name;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
  status(`exported ${r.msg.name} (${r.msg.size} bytes)`);
}

installShortcuts();

// The hook the end-to-end tests and the speed benchmark read (no effect on the page).
declare global {
  interface Window {
    auszugTracery: {
      conn: Connection; view3d: View3d; timings: TraceryTiming[];
      state(): TraceryState; shown(): TraceryGeometry | null;
      change(next: TraceryState): Promise<boolean>;
    };
  }
}
window.auszugTracery = {
  conn, view3d, timings, state: () => state, shown: () => shown,
  change: (next) => change(next, performance.now(), null),
};
