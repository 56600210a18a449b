// One WebGL renderer, several views (scissored regions of one canvas), rendered on demand.
// Design mode: the top view (left) and a perspective view (right), split where the user dragged the
// handle between them (store.split). Preview mode: perspective, top and side (front elevation) views
// side by side (paper Fig. C.7). The 3D view opens on a raised three-quarter view framing the
// model's bounding box, and refits (keeping the user's direction) only when the model grows out of it.
// The network's lines share one BufferGeometry per basic piece; replicas are Line objects
// placed by the sent transforms (instances, not copies). An edit that keeps the layout (a drag)
// rewrites the buffers in place, so no GPU resources are created or leaked per edit.
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import { fitDistance } from "./camerafit";
import { perFrame } from "./frames";
import { layoutKey, transforms, view } from "./geometry";
import type { Geometry } from "./protocol";
import { sceneLights } from "./shading";
import { SPLIT, type Mode, type Store } from "./store";

export type ViewName = "top" | "persp" | "side";

/** three.js layers: 0 is seen by every view; these only by one. */
export const VIEW_LAYER: Record<ViewName, number> = { top: 1, persp: 2, side: 3 };

/** A view's region in CSS pixels, relative to the viewport element's top left. */
export interface Rect {
  x: number;
  y: number;
  w: number;
  h: number;
}

/** Each mode's views as [start, end] fractions of the viewport's width; `split`: the design mode's. */
function layout(mode: Mode, split: number): Partial<Record<ViewName, [number, number]>> {
  return mode === "design" ? { top: [0, split], persp: [split, 1] }
    : { persp: [0, 1 / 3], top: [1 / 3, 2 / 3], side: [2 / 3, 1] };
}

/** The 3D view's opening direction: elevation above the ground and azimuth from the front (-y), degrees. */
export const VIEW3D = { elevation: 35, azimuth: 35, fill: 0.8 } as const;
/** The colour of the selected curve's lines and members (design mode). */
export const SELECTED = "#d97706";
/** Clear colours: the drawing views (paper) and the 3D view (a cooler, lighter ground for the coloured tubes). */
const PAPER = 0xf4f1ea;
export const SKY = 0xe9eef3;

export class Views {
  readonly renderer: THREE.WebGLRenderer;
  readonly scene = new THREE.Scene();
  readonly top = new THREE.OrthographicCamera(-1, 1, 1, -1, -1e4, 1e4);
  readonly persp = new THREE.PerspectiveCamera(35, 1, 0.01, 1e5);
  readonly side = new THREE.OrthographicCamera(-1, 1, 1, -1, -1e4, 1e4);
  readonly orbit: OrbitControls;
  /** The network's lines (one child per replica). */
  readonly network = new THREE.Group();
  /** Top view: world units per CSS pixel and the world point at the view's centre. */
  topScale = 0.01;
  topCenter = new THREE.Vector2(0, 0);
  bounds = new THREE.Box3(new THREE.Vector3(-1, -1, 0), new THREE.Vector3(1, 1, 1));
  /** performance.now() when the last frame was drawn, and how many frames so far. */
  lastFrameAt = 0;
  frames = 0;
  /** How often the 3D view was refitted because the model grew out of it (for tests). */
  refits = 0;
  /** The geometry revision the 3D view's members (lines, or the looks' meshes) show (for the timings). */
  membersRevision = 0;
  /** The views the network's lines are drawn in (null: every view). */
  private lineViews: readonly ViewName[] | null = null;
  private mode: Mode = "design";
  private layout = "";
  private geoms: THREE.BufferGeometry[] = [];
  private materials = new Map<string, THREE.LineBasicMaterial>();
  private topListeners = new Set<() => void>();
  private frameListeners = new Set<() => void>();
  private fittedPath: string | null = null;
  private framing = new Map<Mode, { topScale: number; topCenter: THREE.Vector2; position: THREE.Vector3; target: THREE.Vector3 }>();
  private labels: Record<ViewName, HTMLElement>;
  /** The viewport element's size in CSS pixels and its client box (null: read it again),
   * kept from the last resize: reading them while the DOM has changed would force a layout. */
  private size = { w: 1, h: 1 };
  private hostBox: DOMRect | null = null;
  private splitHandle!: HTMLElement;

  constructor(readonly host: HTMLElement, private store: Store) {
    // MSAA doubles the cost of a frame on a software renderer (headless chromium's SwiftShader,
    // llvmpipe): keep it for real GPUs only. The drawing buffer is not preserved: every frame
    // draws all views anyway, and a preserved buffer costs the compositor a copy per frame
    // (on U.XI.28 a mouse drag's edit came 0.35-0.7 ms later with it, bench_studio.py).
    this.renderer = new THREE.WebGLRenderer({ antialias: !softwareRenderer(), preserveDrawingBuffer: false });
    this.renderer.setPixelRatio(window.devicePixelRatio);
    this.renderer.setClearColor(PAPER);
    this.renderer.setScissorTest(true);
    this.renderer.domElement.dataset.testid = "canvas";
    host.prepend(this.renderer.domElement);
    this.network.name = "network";
    this.scene.add(this.network);
    // a sky light and two directional lights: no side of a member goes dark (the palette's colours read)
    this.scene.add(...sceneLights());   // shading.ts: the members' material lights itself the same way
    this.top.up.set(0, 1, 0);
    this.persp.up.set(0, 0, 1);
    this.side.up.set(0, 0, 1);
    for (const v of ["top", "persp", "side"] as ViewName[]) this.camera(v).layers.enable(VIEW_LAYER[v]);
    this.orbit = new OrbitControls(this.persp, this.renderer.domElement);
    this.orbit.enabled = false; // enabled while the pointer is over the perspective view
    this.orbit.addEventListener("change", () => this.requestRender());
    const labels = host.querySelector("#view-labels") as HTMLElement;
    const label = (text: string) => {
      const el = document.createElement("div");
      el.className = "label";
      el.textContent = text;
      labels.appendChild(el);
      return el;
    };
    this.labels = { top: label("top"), persp: label("3D"), side: label("side") };
    this.installTopControls();
    this.installSplitHandle();
    new ResizeObserver(() => this.resize()).observe(host);
    // the box moves without a resize when the page scrolls or the window resizes
    const stale = () => { this.hostBox = null; };
    window.addEventListener("resize", stale);
    window.addEventListener("scroll", stale, true);
    store.on("geometry", (g) => this.showGeometry(g));
    store.on("selection", () => this.recolor());
    store.on("looks", () => this.recolor());
    store.on("mode", (m) => this.setMode(m));
    store.on("split", () => this.resize());
    this.resize();
  }

  camera(v: ViewName): THREE.Camera {
    return v === "top" ? this.top : v === "persp" ? this.persp : this.side;
  }

  /** The region of view `v` (null when the current mode does not show it). */
  rect(v: ViewName): Rect | null {
    const span = layout(this.mode, this.store.split)[v];
    if (!span) return null;
    const { w, h } = this.size;
    const x0 = Math.round(span[0] * w), x1 = Math.round(span[1] * w);
    return { x: x0, y: 0, w: x1 - x0, h };
  }

  /** The viewport element's box in client coordinates. Cached: read once after a resize or
   * scroll, never in the middle of a frame's DOM updates (that would force a layout). */
  box(): DOMRect {
    return (this.hostBox ??= this.host.getBoundingClientRect());
  }

  /** The view under a point given in client coordinates. */
  viewAt(clientX: number, clientY: number): ViewName | null {
    const b = this.box();
    const x = clientX - b.left, y = clientY - b.top;
    for (const v of ["top", "persp", "side"] as ViewName[]) {
      const r = this.rect(v);
      if (r && x >= r.x && x < r.x + r.w && y >= r.y && y < r.y + r.h) return v;
    }
    return null;
  }

  /** Top view: world (x, y) -> CSS pixels relative to the top view's region. */
  topToScreen(x: number, y: number): [number, number] {
    const r = this.rect("top") ?? { x: 0, y: 0, w: 1, h: 1 };
    return [r.w / 2 + (x - this.topCenter.x) / this.topScale, r.h / 2 - (y - this.topCenter.y) / this.topScale];
  }

  /** Top view: CSS pixels relative to the top view's region -> world (x, y). */
  screenToTop(px: number, py: number): [number, number] {
    const r = this.rect("top") ?? { x: 0, y: 0, w: 1, h: 1 };
    return [this.topCenter.x + (px - r.w / 2) * this.topScale, this.topCenter.y - (py - r.h / 2) * this.topScale];
  }

  /** Any view: a world point -> client coordinates (for tests and overlays). */
  worldToClient(v: ViewName, p: THREE.Vector3): [number, number] | null {
    const r = this.rect(v);
    if (!r) return null;
    const q = p.clone().project(this.camera(v));
    const b = this.box();
    return [b.left + r.x + ((q.x + 1) / 2) * r.w, b.top + r.y + ((1 - q.y) / 2) * r.h];
  }

  /** Called whenever the top view's mapping changes (pan, zoom, resize, mode). */
  onTopChange(fn: () => void): () => void {
    this.topListeners.add(fn);
    return () => this.topListeners.delete(fn);
  }

  /** Called after every drawn frame. */
  onFrame(fn: () => void): () => void {
    this.frameListeners.add(fn);
    return () => this.frameListeners.delete(fn);
  }

  /** Draw the network's lines only in `views` (null: in every view). The tube look's members
   * cover their lines (looks.ts): a software renderer pays for every line segment drawn. */
  setLineViews(views: readonly ViewName[] | null): void {
    this.lineViews = views;
    for (const line of this.network.children) this.setLineLayers(line);
    this.requestRender();
  }

  private setLineLayers(line: THREE.Object3D): void {
    if (!this.lineViews) {
      line.layers.set(0);
      return;
    }
    line.layers.disableAll();
    for (const v of this.lineViews) line.layers.enable(VIEW_LAYER[v]);
  }

  /** Fit the top view (and the 3D cameras) to the drawing's bounds. */
  fit(): void {
    const b = this.bounds;
    const size = b.getSize(new THREE.Vector3());
    const c = b.getCenter(new THREE.Vector3());
    const r = this.rect("top");
    if (r) {
      const span = Math.max(size.x / Math.max(r.w, 1), size.y / Math.max(r.h, 1), 1e-6);
      this.topScale = 1.2 * span;
      this.topCenter.set(c.x, c.y);
    }
    const el = THREE.MathUtils.degToRad(VIEW3D.elevation), az = THREE.MathUtils.degToRad(VIEW3D.azimuth);
    this.fit3d(new THREE.Vector3(Math.cos(el) * Math.sin(az), -Math.cos(el) * Math.cos(az), Math.sin(el)));
  }

  /** Every point of the network's lines in world coordinates (all replicas); the bounding box's
   * corners when there are none. */
  private modelPoints(): THREE.Vector3[] {
    const out: THREE.Vector3[] = [];
    for (const child of this.network.children as THREE.Line[]) {
      const pos = child.geometry.getAttribute("position") as THREE.BufferAttribute;
      for (let i = 0; i < pos.count; i++) out.push(new THREE.Vector3().fromBufferAttribute(pos, i).applyMatrix4(child.matrix));
    }
    if (out.length) return out;
    const b = this.bounds;
    for (let i = 0; i < 8; i++) {
      out.push(new THREE.Vector3(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z));
    }
    return out;
  }

  /** Frame the 3D view on the model, looking along -`dir` at its bounding box's centre: the
   * curves' projection reaches VIEW3D.fill of the half view's width or height, whichever binds. */
  fit3d(dir: THREE.Vector3): void {
    const c = this.bounds.getCenter(new THREE.Vector3());
    const persp = this.rect("persp");
    const aspect = persp ? persp.w / Math.max(persp.h, 1) : 1;
    const back = dir.clone().normalize();
    const d = fitDistance(this.modelPoints(), c, back, this.persp.fov, aspect, VIEW3D.fill);
    this.persp.position.copy(c).addScaledVector(back, d);
    this.persp.near = d / 1000;
    this.persp.far = d * 100;
    this.orbit.target.copy(c);
    this.orbit.update();
    this.updateCameras();
  }

  /** Whether every point of the model is in front of the 3D camera and inside its view. */
  inView3d(): boolean {
    this.updateCameras();
    this.persp.updateMatrixWorld();
    const q = new THREE.Vector3();
    const inv = this.persp.matrixWorldInverse;
    for (const p of this.modelPoints()) {
      if (q.copy(p).applyMatrix4(inv).z >= 0) return false; // behind the camera
      p.project(this.persp);
      if (Math.abs(p.x) > 1 || Math.abs(p.y) > 1) return false;
    }
    return true;
  }

  /** Draw at the next animation frame (once, however often asked). */
  readonly requestRender = perFrame(() => this.render());

  /** Draw every view of the current mode now. */
  render(): void {
    this.updateCameras();
    const h = this.size.h;
    for (const v of ["top", "persp", "side"] as ViewName[]) {
      const r = this.rect(v);
      this.labels[v].hidden = !r;
      if (!r) continue;
      this.labels[v].style.left = `${r.x + 8}px`;
      this.labels[v].style.top = "6px";
      const y = h - r.y - r.h; // WebGL's origin is the bottom left
      this.renderer.setViewport(r.x, y, r.w, r.h);
      this.renderer.setScissor(r.x, y, r.w, r.h);
      this.renderer.setClearColor(v === "persp" ? SKY : PAPER);
      this.renderer.render(this.scene, this.camera(v));
    }
    this.lastFrameAt = performance.now();
    this.frames++;
    for (const fn of this.frameListeners) fn();
  }

  /** Each mode keeps its own framing (fitted the first time the mode shows a drawing). */
  private setMode(mode: Mode): void {
    this.framing.set(this.mode, { topScale: this.topScale, topCenter: this.topCenter.clone(),
      position: this.persp.position.clone(), target: this.orbit.target.clone() });
    this.mode = mode;
    document.body.classList.toggle("preview", mode === "preview");
    this.recolor();
    const f = this.framing.get(mode);
    if (f) {
      this.topScale = f.topScale;
      this.topCenter.copy(f.topCenter);
      this.persp.position.copy(f.position);
      this.orbit.target.copy(f.target);
      this.orbit.update();
    } else {
      this.fit();
    }
    this.resize();
  }

  /** The design mode's handle between the top and 3D views: drag it to move the split (store.split,
   * kept in the URL); a double click puts it back in the middle. */
  private installSplitHandle(): void {
    const handle = document.createElement("div");
    handle.className = "split-handle";
    handle.dataset.testid = "split-handle";
    handle.title = "Drag to resize the top and 3D views (double click: half and half)";
    handle.setAttribute("role", "separator");
    handle.setAttribute("aria-orientation", "vertical");
    this.host.appendChild(handle);
    this.splitHandle = handle;
    let dragging = false;
    handle.addEventListener("pointerdown", (ev) => {
      if (ev.button !== 0) return;
      dragging = true;
      handle.setPointerCapture(ev.pointerId);
      ev.preventDefault();
      ev.stopPropagation();
    });
    handle.addEventListener("pointermove", (ev) => {
      if (!dragging) return;
      const b = this.box();
      this.store.setSplit((ev.clientX - b.left) / Math.max(b.width, 1));
    });
    const end = (ev: PointerEvent) => {
      if (!dragging) return;
      dragging = false;
      if (handle.hasPointerCapture(ev.pointerId)) handle.releasePointerCapture(ev.pointerId);
    };
    handle.addEventListener("pointerup", end);
    handle.addEventListener("pointercancel", end);
    handle.addEventListener("dblclick", () => this.store.setSplit(SPLIT.default));
  }

  private placeSplitHandle(): void {
    const top = this.rect("top"), persp = this.rect("persp");
    const show = this.mode === "design" && !!top && !!persp;
    this.splitHandle.hidden = !show;
    if (show) this.splitHandle.style.left = `${persp!.x}px`;
  }

  private resize(): void {
    const w = this.host.clientWidth, h = this.host.clientHeight;
    this.size = { w, h };
    this.hostBox = null;
    this.renderer.setSize(w, h, false);
    this.placeSplitHandle();
    this.updateCameras();
    for (const fn of this.topListeners) fn();
    this.requestRender();
  }

  private updateCameras(): void {
    const top = this.rect("top");
    if (top) {
      const hw = (top.w / 2) * this.topScale, hh = (top.h / 2) * this.topScale;
      this.top.left = -hw; this.top.right = hw; this.top.top = hh; this.top.bottom = -hh;
      this.top.position.set(this.topCenter.x, this.topCenter.y, this.bounds.max.z + 100);
      this.top.lookAt(this.topCenter.x, this.topCenter.y, 0);
      this.top.updateProjectionMatrix();
    }
    const persp = this.rect("persp");
    if (persp) {
      this.persp.aspect = persp.w / Math.max(persp.h, 1);
      this.persp.updateProjectionMatrix();
    }
    const side = this.rect("side");
    if (side) {
      const b = this.bounds, c = b.getCenter(new THREE.Vector3()), s = b.getSize(new THREE.Vector3());
      const scale = 1.2 * Math.max(s.x / Math.max(side.w, 1), s.z / Math.max(side.h, 1), 1e-6);
      const hw = (side.w / 2) * scale, hh = (side.h / 2) * scale;
      this.side.left = -hw; this.side.right = hw; this.side.top = hh; this.side.bottom = -hh;
      this.side.position.set(c.x, b.min.y - 100, c.z);
      this.side.lookAt(c.x, c.y, c.z);
      this.side.updateProjectionMatrix();
    }
  }

  private topChanged(): void {
    this.updateCameras();
    for (const fn of this.topListeners) fn();
    this.requestRender();
  }

  /** Wheel zooms about the cursor; the middle or right button (or space + left) pans the top view. */
  private installTopControls(): void {
    const el = this.renderer.domElement;
    const overlay = this.host.querySelector("#top-overlay") as SVGElement | null;
    const zoom = (ev: WheelEvent) => {
      if (this.viewAt(ev.clientX, ev.clientY) !== "top") return;
      ev.preventDefault();
      const r = this.rect("top")!, b = this.box();
      const px = ev.clientX - b.left - r.x, py = ev.clientY - b.top - r.y;
      const [wx, wy] = this.screenToTop(px, py);
      const f = Math.exp(ev.deltaY * 0.0015);
      this.topScale *= f;
      this.topCenter.set(wx - (wx - this.topCenter.x) * f, wy - (wy - this.topCenter.y) * f);
      this.topChanged();
    };
    let panning: { x: number; y: number } | null = null;
    let space = false;
    window.addEventListener("keydown", (e) => { if (e.code === "Space" && !isTyping(e)) space = true; });
    window.addEventListener("keyup", (e) => { if (e.code === "Space") space = false; });
    const down = (ev: PointerEvent) => {
      const v = this.viewAt(ev.clientX, ev.clientY);
      this.orbit.enabled = v === "persp";
      if (v !== "top") return;
      if (ev.button === 1 || ev.button === 2 || (ev.button === 0 && space)) {
        panning = { x: ev.clientX, y: ev.clientY };
        ev.preventDefault();
        ev.stopPropagation();
      }
    };
    const move = (ev: PointerEvent) => {
      if (!panning) {
        this.orbit.enabled = this.viewAt(ev.clientX, ev.clientY) === "persp";
        return;
      }
      this.topCenter.x -= (ev.clientX - panning.x) * this.topScale;
      this.topCenter.y += (ev.clientY - panning.y) * this.topScale;
      panning = { x: ev.clientX, y: ev.clientY };
      this.topChanged();
    };
    const up = () => { panning = null; };
    for (const target of [el, overlay].filter(Boolean) as (HTMLElement | SVGElement)[]) {
      target.addEventListener("wheel", zoom as EventListener, { passive: false });
      target.addEventListener("pointerdown", down as EventListener, { capture: true });
      target.addEventListener("contextmenu", (e) => e.preventDefault());
    }
    window.addEventListener("pointermove", move);
    window.addEventListener("pointerup", up);
  }

  private material(color: string): THREE.LineBasicMaterial {
    let m = this.materials.get(color);
    if (!m) this.materials.set(color, (m = new THREE.LineBasicMaterial({ color })));
    return m;
  }

  private recolor(): void {
    const sel = this.mode === "preview" ? null : this.store.selection; // preview shows the design as it is
    for (const child of this.network.children as THREE.Line[]) {
      const basic = child.userData.basic as number;
      child.material = this.material(basic === sel ? SELECTED : this.store.color(basic));
    }
    this.requestRender();
  }

  /** New geometry: rewrite the buffers in place when the layout is unchanged, else rebuild. */
  showGeometry(msg: Geometry): void {
    const data = this.store.data;
    const key = layoutKey(msg);
    if (key === this.layout && this.geoms.length === msg.pieces.length) {
      let child = 0;
      msg.pieces.forEach((p, i) => {
        const attr = this.geoms[i].getAttribute("position") as THREE.BufferAttribute;
        (attr.array as Float32Array).set(view(data, p.points));
        attr.needsUpdate = true;
        this.geoms[i].computeBoundingSphere();
        for (const m of transforms(data, p)) {
          const line = this.network.children[child++];
          line.matrix.copy(m);
          line.matrixWorldNeedsUpdate = true;
        }
      });
    } else {
      this.network.clear();
      for (const g of this.geoms) g.dispose();
      this.geoms = [];
      for (const p of msg.pieces) {
        const geom = new THREE.BufferGeometry();
        geom.setAttribute("position", new THREE.BufferAttribute(view(data, p.points).slice(), 3));
        this.geoms.push(geom);
        transforms(data, p).forEach((m, k) => {
          const line = new THREE.Line(geom, this.material(this.store.color(p.basic)));
          line.name = `${p.basic}/${p.labels[k]}`;
          line.userData.basic = p.basic;
          line.matrixAutoUpdate = false;
          line.matrix.copy(m);
          this.setLineLayers(line);
          this.network.add(line);
        });
      }
      this.layout = key;
      this.recolor();
    }
    const b = msg.bounds;
    const before = this.bounds.clone();
    this.bounds.set(new THREE.Vector3(b[0], b[1], b[2]), new THREE.Vector3(b[3], b[4], b[5]));
    if (this.bounds.isEmpty() || msg.n_curves === 0) {
      this.bounds.set(new THREE.Vector3(-1, -1, 0), new THREE.Vector3(1, 1, 1));
    }
    if (this.fittedPath !== msg.path + "\u0000" + msg.name) {
      this.fittedPath = msg.path + "\u0000" + msg.name;
      this.framing.clear();
      this.fit();
      for (const fn of this.topListeners) fn();
    } else if (!before.containsBox(this.bounds) && this.rect("persp") && !this.inView3d()) {
      // the model grew out of the 3D view: frame it again from where the user looks; any other
      // edit keeps the user's camera
      this.fit3d(this.persp.position.clone().sub(this.orbit.target));
      this.refits++;
    }
    this.requestRender();
  }
}

/** Whether WebGL runs on a software rasteriser (no GPU), judged from a throwaway context. */
export function softwareRenderer(): boolean {
  const gl = document.createElement("canvas").getContext("webgl2");
  if (!gl) return true;
  const ext = gl.getExtension("WEBGL_debug_renderer_info");
  const name = String(ext ? gl.getParameter(ext.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER));
  gl.getExtension("WEBGL_lose_context")?.loseContext();
  return /swiftshader|llvmpipe|softpipe|software/i.test(name);
}

/** Whether a key event comes from a text field (no shortcut may fire then). */
export function isTyping(ev: Event): boolean {
  const t = ev.target as HTMLElement | null;
  if (!t || !t.tagName) return false;
  if (t.isContentEditable) return true;
  if (t.tagName === "TEXTAREA" || t.tagName === "SELECT") return true;
  if (t.tagName !== "INPUT") return false;
  const type = (t as HTMLInputElement).type;
  return !["button", "checkbox", "radio", "range", "color", "file", "submit", "reset"].includes(type);
}
