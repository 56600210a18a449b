// Design mode, top view: the SVG overlay (#top-overlay) over the three.js top view. It shows the
// symmetry guides, the PRC and intersection markers, the curves' points and handles and the curve
// being drawn, and turns clicks and drags into edit messages; the server answers each with new
// geometry (so every edit is undoable). Elements are pooled and updated in place, once a frame.
import { DragSender, RAW_UPDATES } from "./dragsender";
import { perFrame } from "./frames";
import { newDragId } from "./gesture";
import "./topview.css";
import type { Ctx } from "./context";
import { view } from "./geometry";
import type { CurveInfo, DrawCurve, Geometry, MoveHandle, MoveVertex } from "./protocol";
import { registerShortcut } from "./shortcuts";
import { wrapWords } from "./wrap";
import type { Store, Tool } from "./store";
import {
  arcPoints, guideLines, images, mirrorAxis, pickCurve, pickTarget, replicaMatrices, replicaVertices, snap, symmetryMatrices,
  targetRank,
  type CurveSymmetry, type Mat2, type PickPiece, type Snap, type SnapTargets, type Vec,
} from "./snapping";

export type MirrorRule = NonNullable<DrawCurve["mirror"]>;
export const MIRROR_RULES: readonly MirrorRule[] = ["none", "first point", "last point", "y axis"];

const NS = "http://www.w3.org/2000/svg";
/** Pixel tolerances: snapping, picking a curve, and the movement that turns a press into a drag. */
const SNAP_PX = 8, PICK_PX = 6, DRAG_PX = 3;
type DrawTool = Exclude<Tool, "select">;

const TOOLS: { tool: Tool; label: string; key: string; title: string }[] = [
  { tool: "select", label: "Select", key: "v", title: "Select curves, drag points, click intersections (V)" },
  { tool: "line", label: "Line", key: "l", title: "Draw a line: click the ground point, then the apex (L)" },
  { tool: "arc", label: "Arc", key: "a",
    title: "Draw an arc: ground point, apex, then drag (or click) where the tangent aims (A)" },
  { tool: "free", label: "Free end", key: "e",
    title: "Draw a curve with a free end: ground point, apex, free end (E)" },
];

const HINTS: Record<DrawTool, string[]> = {
  line: ["click the ground point", "click the apex"],
  arc: ["click the ground point", "press at the apex and drag where the tangent aims", "click where the tangent aims"],
  free: ["click the ground point", "click the apex", "click the free end"],
};

/** What a press on a point or handle drags. */
type DragTarget =
  | { kind: "vertex"; curve: number; vertex: number }
  | { kind: "handle"; curve: number; segment: number; handle: number };

interface Drag {
  target: DragTarget;
  x: number;
  y: number;
  moved: boolean;
  /** Where the dragged point is shown (the latest position, ahead of the server's reply). */
  pos: Vec | null;
  released: boolean;
  targets: SnapTargets;
  /** The drag number its edits carry (one undo step). */
  gesture: number;
  /** Whether pointerrawupdate events come for it (then pointermove is ignored). */
  raw: boolean;
}

interface Draft {
  tool: DrawTool;
  pts: Vec[];
  /** The arc's tangent handle once set; `needHandle` while it is awaited. */
  handle: Vec | null;
  needHandle: boolean;
  /** The press at the apex of an arc, whose drag sets the handle. */
  press: { x: number; y: number; moved: boolean } | null;
}

function make<K extends keyof SVGElementTagNameMap>(parent: Element, tag: K, cls = ""): SVGElementTagNameMap[K] {
  const e = document.createElementNS(NS, tag);
  if (cls) e.setAttribute("class", cls);
  parent.appendChild(e);
  return e;
}

/** Elements of one kind under one group, created and removed only when their number changes. */
class Pool<K extends keyof SVGElementTagNameMap> {
  readonly items: SVGElementTagNameMap[K][] = [];
  constructor(private parent: SVGGElement, private tag: K, private cls: string,
    private setup: (e: SVGElementTagNameMap[K]) => void = () => {}) {}

  take(n: number): SVGElementTagNameMap[K][] {
    while (this.items.length < n) {
      const e = make(this.parent, this.tag, this.cls);
      this.setup(e);
      this.items.push(e);
    }
    while (this.items.length > n) this.items.pop()!.remove();
    return this.items;
  }
}

const f2 = (v: number) => v.toFixed(2);

/** Which point a drag edit moves. */
const moveKey = (m: MoveVertex | MoveHandle) =>
  m.type === "move_vertex" ? `v${m.curve}.${m.vertex}` : `h${m.curve}.${m.segment}.${m.handle}`;

/** Set an attribute only when its value changes: a marker that stays put costs no style,
 * paint or raster work (most markers of a drawing stay put while one point is dragged). */
function attr(e: Element, name: string, value: string): void {
  if (e.getAttribute(name) !== value) e.setAttribute(name, value);
}

/** The same for data-* attributes. */
function data(e: SVGElement, values: Record<string, string>): void {
  for (const k in values) if (e.dataset[k] !== values[k]) e.dataset[k] = values[k];
}

function setTitle(e: SVGElement, text: string): void {
  const t = e.firstChild as SVGTitleElement;
  if (t.textContent !== text) t.textContent = text;
}

const withTitle = (e: SVGElement) => void make(e, "title");

/** What a pooled marker or dot last had written besides its position (class, data-*, title, r,
 * fill), per element: a marker whose description is unchanged is only moved, with no DOM reads
 * (a drag redraws every marker once a frame, and most of them keep their description). Only
 * renderMarkers and renderDots write these attributes of their pools' elements. */
const described = new WeakMap<Element, string>();

/** Run `write` unless `e` was last described by `key`. */
function describe(e: Element, key: string, write: () => void): void {
  if (described.get(e) === key) return;
  described.set(e, key);
  write();
}

/** World (x, y) -> overlay pixels. */
type Px = (p: readonly number[]) => [number, number];

function placeCircle(e: SVGCircleElement, [x, y]: [number, number]): void {
  attr(e, "cx", f2(x));
  attr(e, "cy", f2(y));
}

function placeLine(e: SVGLineElement, [x1, y1]: [number, number], [x2, y2]: [number, number]): void {
  attr(e, "x1", f2(x1));
  attr(e, "y1", f2(y1));
  attr(e, "x2", f2(x2));
  attr(e, "y2", f2(y2));
}

class TopView {
  private readonly store: Store;
  private readonly svg: SVGSVGElement;
  private readonly g: Record<"guides" | "prc" | "marks" | "dots" | "sel" | "draft" | "legend" | "hint", SVGGElement>;
  private readonly guides: Pool<"line">;
  private readonly axis: SVGLineElement;
  private readonly centre: SVGPathElement;
  private readonly prcs: Pool<"rect">;
  private readonly marks: Pool<"circle">;
  private readonly dots: Pool<"circle">;
  private readonly tangents: Pool<"line">;
  private readonly handles: Pool<"circle">;
  private readonly draftPath: SVGPathElement;
  private readonly draftReplicas: SVGPathElement;
  private readonly draftPoints: Pool<"circle">;
  private readonly snapMark: SVGCircleElement;
  private readonly hint: SVGTextElement;
  private hintKey = "";
  private readonly toolButtons = new Map<Tool, HTMLButtonElement>();
  private readonly drawOptions: HTMLSpanElement;
  private readonly foldInput: HTMLInputElement;
  private readonly mirrorSelect: HTMLSelectElement;
  private readonly snapButton: HTMLButtonElement;

  /** Symmetry options for new curves; the fold follows the last curve until the user sets it. */
  private fold = 1;
  private foldTouched = false;
  private mirror: MirrorRule = "none";
  private snapOn = true;
  private draft: Draft | null = null;
  private cursor: Vec | null = null;
  private lastSnap: Snap | null = null;
  private drag: Drag | null = null;
  /** A press on an intersection marker: a click puts the PRC there; if a point lies under it too,
   * moving the press drags that point instead. */
  private press: { index: number; x: number; y: number; point: SVGElement | null; ev: PointerEvent } | null = null;
  /** The drag's edits: sent at once, one awaiting its reply, at most one a frame. */
  private readonly sender: DragSender<MoveVertex | MoveHandle>;
  /** Redraws the overlay at the next animation frame (once, however often asked). */
  private readonly later = perFrame(() => this.render());
  private full = true;
  /** Per geometry: symmetry matrices per basic curve and the pieces for picking. */
  private mats: Mat2[][] = [];
  private pick: PickPiece[] = [];

  constructor(private readonly ctx: Ctx) {
    this.store = ctx.store;
    this.sender = new DragSender({
      request: (m, input) => this.ctx.request(m, input),
      key: moveKey,
      idle: () => { if (this.drag?.released) { this.drag = null; this.schedule(false); } },
    });
    this.svg = document.getElementById("top-overlay") as unknown as SVGSVGElement;
    const group = (cls: string) => make(this.svg, "g", cls);
    this.g = {
      guides: group("guides passive"), prc: group("prcs passive"), marks: group("marks"), dots: group("dots"),
      sel: group("selected"), draft: group("draft passive"), legend: group("legend passive"), hint: group("passive"),
    };
    this.g.hint.setAttribute("transform", "translate(10 44)");
    this.guides = new Pool(this.g.guides, "line", "guide");
    this.axis = make(this.g.guides, "line", "guide axis");
    this.centre = make(this.g.guides, "path", "centre");
    this.prcs = new Pool(this.g.prc, "rect", "prc", (e) => {
      e.dataset.testid = "prc";
      for (const [k, v] of [["x", "-5"], ["y", "-5"], ["width", "10"], ["height", "10"]]) e.setAttribute(k, v);
    });
    this.marks = new Pool(this.g.marks, "circle", "intersection hit", (e) => {
      e.dataset.testid = "intersection";
      withTitle(e);
    });
    this.dots = new Pool(this.g.dots, "circle", "dot hit", (e) => {
      e.dataset.role = "vertex";
      e.setAttribute("r", "3");
      withTitle(e);
    });
    this.tangents = new Pool(this.g.sel, "line", "tangent passive");
    this.handles = new Pool(this.g.sel, "circle", "handle hit", withTitle);
    this.draftReplicas = make(this.g.draft, "path", "draft-replicas");
    this.draftPath = make(this.g.draft, "path", "draft-curve");
    this.draftPoints = new Pool(this.g.draft, "circle", "draft-point", (e) => e.setAttribute("r", "3.5"));
    this.snapMark = make(this.g.draft, "circle", "snap");
    this.snapMark.setAttribute("r", "7");
    this.hint = make(this.g.hint, "text", "hint");
    this.buildLegend();

    const bar = document.getElementById("draw-tools")!;
    for (const t of TOOLS) {
      const b = document.createElement("button");
      b.textContent = t.label;
      b.title = t.title;
      b.dataset.testid = `tool-${t.tool}`;
      b.addEventListener("click", () => this.store.setTool(t.tool));
      bar.appendChild(b);
      this.toolButtons.set(t.tool, b);
      registerShortcut({ key: t.key, description: `${t.label} tool`, run: () => this.store.setTool(t.tool) });
    }
    // the options of new curves, shown while a drawing tool is active
    this.drawOptions = document.createElement("span");
    this.drawOptions.className = "draw-options";
    bar.appendChild(this.drawOptions);
    const label = (text: string, control: HTMLElement, title: string) => {
      const l = document.createElement("label");
      l.title = title;
      l.append(text, control);
      this.drawOptions.appendChild(l);
    };
    this.foldInput = document.createElement("input");
    Object.assign(this.foldInput, { type: "number", min: "1", max: "64", step: "1", value: "1" });
    this.foldInput.dataset.testid = "draw-fold";
    this.foldInput.addEventListener("change", () => {
      const n = Math.round(Number(this.foldInput.value));
      if (n >= 1 && n <= 64) { this.fold = n; this.foldTouched = true; }
      this.foldInput.value = String(this.fold);
      this.schedule();
    });
    label("fold", this.foldInput, "Rotation fold of new curves");
    this.mirrorSelect = document.createElement("select");
    this.mirrorSelect.dataset.testid = "draw-mirror";
    for (const m of MIRROR_RULES) this.mirrorSelect.add(new Option(m, m));
    this.mirrorSelect.addEventListener("change", () => {
      this.mirror = this.mirrorSelect.value as MirrorRule;
      this.schedule();
    });
    label("mirror", this.mirrorSelect, "Mirror of new curves: none, through the first or last point, the y axis");
    this.snapButton = document.createElement("button");
    this.snapButton.textContent = "Snap";
    this.snapButton.title = "Snap to the centre, replica end points and guide lines (hold Alt to suspend)";
    this.snapButton.dataset.testid = "snap-toggle";
    this.snapButton.addEventListener("click", () => {
      this.snapOn = !this.snapOn;
      this.syncTools();
    });
    bar.appendChild(this.snapButton);
    registerShortcut({ key: "Escape", description: "Cancel drawing, then back to the select tool, then deselect",
      run: () => this.escape() });

    this.svg.addEventListener("pointerdown", (e) => this.down(e));
    // A drag follows pointerrawupdate where the browser has it: it comes as soon as the mouse
    // moves, while pointermove waits for the next animation frame (up to 16 ms later), so the
    // edit goes out at once and its geometry is usually back before that frame is drawn.
    // (pointermove still drives a drag that gets no raw updates, whatever the reason)
    if (RAW_UPDATES) {
      this.svg.addEventListener("pointerrawupdate", ((e: PointerEvent) => {
        if (this.drag) this.drag.raw = true;
        this.dragMove(e);
      }) as EventListener);
    }
    this.svg.addEventListener("pointermove", (e) => this.move(e));
    this.svg.addEventListener("pointerup", (e) => this.up(e));
    this.svg.addEventListener("pointercancel", (e) => this.up(e));
    this.svg.addEventListener("pointerleave", () => {
      if (this.drag) return;
      this.cursor = this.lastSnap = null;
      this.schedule(false);
    });

    this.store.on("geometry", (g) => this.geometry(g));
    this.store.on("selection", () => this.schedule());
    this.store.on("looks", () => this.schedule());
    this.store.on("tool", () => { this.draft = null; this.syncTools(); this.schedule(); });
    this.store.on("mode", () => { this.draft = null; this.schedule(); });
    ctx.views.onTopChange(() => this.schedule());
    this.syncTools();
    this.schedule();
  }

  // ------------------------------------------------------------------ state

  private geometry(g: Geometry): void {
    this.mats = g.curves.map(replicaMatrices);   // the server's, as the network's groups give them
    this.pick = g.pieces.map((p) => ({
      basic: p.basic, points: view(this.store.data, p.points), transforms: view(this.store.data, p.transforms),
    }));
    if (!this.foldTouched && g.curves.length) {
      this.fold = g.curves[g.curves.length - 1].fold;
      this.foldInput.value = String(this.fold);
    }
    this.schedule();
  }

  private syncTools(): void {
    for (const [t, b] of this.toolButtons) b.setAttribute("aria-pressed", String(this.store.tool === t));
    this.drawOptions.hidden = this.store.tool === "select";
    this.snapButton.setAttribute("aria-pressed", String(this.snapOn));
  }

  private escape(): void {
    if (this.draft) this.draft = null;
    else if (this.store.tool !== "select") this.store.setTool("select");
    else this.store.select(null);
    this.schedule(false);
  }

  /** The symmetry the guides show: the curve being drawn's, else the selected curve's, else the new curves'. */
  private guideSymmetry(): CurveSymmetry {
    const g = this.store.geometry, sel = this.store.selection;
    if (this.store.tool === "select" && g && sel !== null && g.curves[sel]) return g.curves[sel];
    // a draft's last point is known once only the arc's handle is awaited (other tools finish there)
    const pts = this.draft?.pts ?? [], last = this.draft?.needHandle ? pts[pts.length - 1] : null;
    return { fold: this.fold, axis: mirrorAxis(this.mirror, [0, 0], pts[0] ?? null, last), center: [0, 0] };
  }

  /** Snap targets: the centres, every replica vertex (but of curve `skip`) and the guide lines. */
  private targets(skip = -1): SnapTargets {
    const curves = this.store.geometry?.curves ?? [];
    const centres: Vec[] = [[0, 0], ...curves.map((c) => [c.center[0], c.center[1]] as Vec)];
    return { points: [...centres, ...replicaVertices(curves, skip)], lines: guideLines(this.guideSymmetry()) };
  }

  // ------------------------------------------------------------------ pointer

  /** Overlay pixels of a pointer event (the overlay covers the top view's region of the viewport). */
  private local(ev: PointerEvent): [number, number] {
    const views = this.ctx.views, b = views.box(), r = views.rect("top") ?? { x: 0, y: 0, w: 0, h: 0 };
    return [ev.clientX - b.left - r.x, ev.clientY - b.top - r.y];
  }

  private world(ev: PointerEvent): Vec {
    const [x, y] = this.local(ev);
    return this.ctx.views.screenToTop(x, y);
  }

  private snapped(ev: PointerEvent, targets: SnapTargets): Snap {
    const p = this.world(ev);
    if (!this.snapOn || ev.altKey) return { p, kind: null };
    return snap(p, targets, SNAP_PX * this.ctx.views.topScale);
  }

  private down(ev: PointerEvent): void {
    if (ev.defaultPrevented || ev.button !== 0 || !this.store.geometry) return; // panning, or not loaded
    if (this.store.tool !== "select") return this.drawDown(ev);
    const el = this.targetAt(ev);
    const d = el?.dataset ?? {};
    if (d.testid === "intersection") {
      this.press = { index: Number(d.index), x: ev.clientX, y: ev.clientY, point: this.targetAt(ev, true), ev };
      return;
    }
    this.startDrag(ev, d);
  }

  /** The point target (marker, point, handle) a press at `ev` takes, by rank (snapping.pickTarget);
   * `pointsOnly`: the best point or handle. */
  private targetAt(ev: PointerEvent, pointsOnly = false): SVGElement | null {
    const r = this.svg.getBoundingClientRect(), sel = this.store.selection;
    const els = Array.from(this.svg.querySelectorAll<SVGCircleElement>("circle.hit"))
      .filter((e) => !pointsOnly || e.dataset.role === "vertex" || e.dataset.role === "handle");
    const i = pickTarget(ev.clientX - r.left, ev.clientY - r.top, els.map((e) => ({
      x: Number(e.getAttribute("cx")), y: Number(e.getAttribute("cy")),
      rank: targetRank(e.dataset.testid === "intersection" ? "intersection" : e.dataset.role === "handle" ? "handle" : "vertex",
        sel !== null && Number(e.dataset.curve) === sel),
    })));
    return i >= 0 ? els[i] : null;
  }

  /** Start dragging the point or handle `d` describes, else select the curve under the pointer. */
  private startDrag(ev: PointerEvent, d: DOMStringMap): void {
    const curve = Number(d.curve);
    if (d.role === "vertex" || d.role === "handle") {
      const target: DragTarget = d.role === "vertex"
        ? { kind: "vertex", curve, vertex: Number(d.vertex) }
        : { kind: "handle", curve, segment: Number(d.segment), handle: Number(d.handle) };
      this.store.select(curve);
      this.drag = { target, x: ev.clientX, y: ev.clientY, moved: false, pos: null, released: false,
        targets: this.targets(curve), gesture: newDragId(), raw: false };
      this.sender.begin();
      this.svg.setPointerCapture(ev.pointerId);
    } else {
      const hit = pickCurve(this.world(ev), this.pick, PICK_PX * this.ctx.views.topScale);
      this.store.select(hit ? hit.basic : null);
    }
  }

  /** A pointer move during a drag of a point or handle: queue its edit. */
  private dragMove(ev: PointerEvent): void {
    const drag = this.drag;
    if (!drag || drag.released) return;
    if (!drag.moved && Math.hypot(ev.clientX - drag.x, ev.clientY - drag.y) < DRAG_PX) return;
    drag.moved = true;
    this.lastSnap = this.snapped(ev, drag.targets);
    drag.pos = this.lastSnap.p;
    const t = drag.target, xy = drag.pos;
    this.sender.push(t.kind === "vertex"
      ? { type: "move_vertex", curve: t.curve, vertex: t.vertex, xy, drag: drag.gesture }
      : { type: "move_handle", curve: t.curve, segment: t.segment, handle: t.handle, xy, drag: drag.gesture },
    ev.timeStamp);
    this.schedule(false);
  }

  private move(ev: PointerEvent): void {
    const drag = this.drag;
    if (drag && !drag.released) {
      if (!drag.raw) this.dragMove(ev);
      return;
    }
    const press = this.press;
    if (press?.point && Math.hypot(ev.clientX - press.x, ev.clientY - press.y) >= DRAG_PX) {
      this.press = null;   // a marker on a point: moving the press drags the point
      this.startDrag(press.ev, press.point.dataset);
      if (this.drag) this.dragMove(ev);
      return;
    }
    if (this.store.tool === "select") {
      const over = !!pickCurve(this.world(ev), this.pick, PICK_PX * this.ctx.views.topScale);
      this.svg.classList.toggle("over-curve", over);
      return;
    }
    this.lastSnap = this.snapped(ev, this.targets());
    this.cursor = this.lastSnap.p;
    const dpress = this.draft?.press;
    if (dpress && (dpress.moved || Math.hypot(ev.clientX - dpress.x, ev.clientY - dpress.y) >= DRAG_PX)) {
      dpress.moved = true;
      this.draft!.handle = this.cursor;
    }
    this.schedule(false);
  }

  private up(ev: PointerEvent): void {
    const drag = this.drag;
    if (drag && !drag.released) {
      drag.released = true;
      if (!this.sender.pending) this.drag = null;
      this.lastSnap = null;
      this.schedule(false);
    }
    const press = this.press;
    this.press = null;
    const g = this.store.geometry;
    if (press && g && Math.hypot(ev.clientX - press.x, ev.clientY - press.y) < DRAG_PX) {
      const m = g.intersections[press.index];
      if (m) {
        this.store.select(m.curve);
        this.ctx.request({ type: "set_prc_at", curve: m.curve, segment: m.segment, point: m.point }).catch(() => {});
      }
    }
    const d = this.draft;
    if (d?.press) {
      const moved = d.press.moved;
      d.press = null;
      if (moved) this.finishDraft();
    }
  }

  /** A click of a drawing tool: the next point of the curve (or the arc's handle). */
  private drawDown(ev: PointerEvent): void {
    const tool = this.store.tool as DrawTool;
    const p = this.snapped(ev, this.targets()).p;
    if (this.draft?.tool !== tool) this.draft = { tool, pts: [], handle: null, needHandle: false, press: null };
    const d = this.draft;
    this.cursor = p;
    if (d.needHandle) {
      d.handle = p;
      return this.finishDraft();
    }
    const last = d.pts[d.pts.length - 1];
    // a second click on the same spot (a double click) adds nothing
    if (last && Math.hypot(p[0] - last[0], p[1] - last[1]) < DRAG_PX * this.ctx.views.topScale) return;
    d.pts.push(p);
    this.schedule(); // the guides may follow the first point
    if (d.pts.length < (tool === "free" ? 3 : 2)) return;
    if (tool !== "arc") return this.finishDraft();
    d.needHandle = true;
    d.press = { x: ev.clientX, y: ev.clientY, moved: false };
    this.svg.setPointerCapture(ev.pointerId);
  }

  private finishDraft(): void {
    const d = this.draft!;
    this.draft = null;
    const msg: DrawCurve = {
      type: "draw_curve",
      vertices: d.pts,
      handles: d.tool === "arc" ? [[d.handle!]] : d.pts.slice(1).map(() => []),
      marks: d.tool === "free" ? ["ground", "apex", "free"] : ["ground", "apex"],
      fold: this.fold,
      mirror: this.mirror,
      layer: this.store.layer,
    };
    this.schedule();
    this.ctx.request(msg).then(() => {
      const g = this.store.geometry;
      if (g) this.store.select(g.n_curves - 1);
    }, () => {});
  }

  // ------------------------------------------------------------------ drawing the overlay

  /** Redraw at the next frame; `full` also redraws guides, markers and dots (else only the live parts). */
  private schedule(full = true): void {
    this.full ||= full;
    this.later();
  }

  private render(): void {
    const r = this.ctx.views.rect("top");
    const shown = !!r && this.store.mode === "design";
    this.svg.style.display = shown ? "" : "none";
    if (!shown) return;
    Object.assign(this.svg.style, { left: `${r.x}px`, top: `${r.y}px`, width: `${r.w}px`, height: `${r.h}px` });
    const drawing = this.store.tool !== "select";
    this.svg.classList.add("design");
    this.svg.classList.toggle("drawing", drawing);
    if (drawing) this.svg.classList.remove("over-curve");
    // the top view's mapping, read once: world (x, y) -> overlay pixels
    const views = this.ctx.views;
    const [ox, oy] = views.topToScreen(0, 0);
    const sx = views.topToScreen(1, 0)[0] - ox, sy = views.topToScreen(0, 1)[1] - oy;
    const px: Px = (p) => [ox + sx * p[0], oy + sy * p[1]];
    if (this.full) {
      this.full = false;
      this.renderGuides(px, r.w, r.h);
      this.renderMarkers(px);
      this.renderDots(px);
    }
    this.renderSelected(px);
    this.renderDraft(px);
    this.g.legend.setAttribute("transform", `translate(10 ${r.h - 14})`);
    const hint = this.hintText();
    const perLine = Math.max(20, Math.floor((r.w - 20) / HINT_CHAR_PX));
    const key = `${perLine}|${hint}`;
    if (this.hintKey !== key) {
      this.hintKey = key;
      this.hint.replaceChildren();
      wrapWords(hint, perLine).forEach((line, i) => {
        const span = make(this.hint, "tspan");
        span.setAttribute("x", "0");
        span.setAttribute("dy", i === 0 ? "0" : "1.25em");
        span.textContent = line;
      });
    }
  }

  private renderGuides(px: Px, w: number, h: number): void {
    const sym = this.guideSymmetry();
    const [cx, cy] = px(sym.center);
    const reach = Math.hypot(w, h) + Math.hypot(cx - w / 2, cy - h / 2);
    const place = (e: SVGLineElement, dir: readonly number[]) => {
      const [dx, dy] = px(dir), [zx, zy] = px([0, 0]);
      const l = Math.hypot(dx - zx, dy - zy) || 1, ux = (reach * (dx - zx)) / l, uy = (reach * (dy - zy)) / l;
      placeLine(e, [cx - ux, cy - uy], [cx + ux, cy + uy]);
    };
    const lines = guideLines(sym);
    this.guides.take(lines.length).forEach((e, k) => place(e, lines[k].dir));
    this.axis.style.display = sym.axis ? "" : "none";
    if (sym.axis) place(this.axis, sym.axis);
    this.centre.setAttribute("d", `M${f2(cx - 6)} ${f2(cy)}h12M${f2(cx)} ${f2(cy - 6)}v12`);
  }

  /** Intersection markers and PRCs, for every replica of their basic curve. */
  private renderMarkers(px: Px): void {
    const g = this.store.geometry, sel = this.store.selection;
    const ints = g?.intersections ?? [];
    const n = ints.reduce((a, m) => a + (this.mats[m.curve]?.length ?? 0), 0);
    const marks = this.marks.take(n);
    let j = 0;
    ints.forEach((m, i) => {
      const c = g!.curves[m.curve], faded = sel !== null && sel !== m.curve;
      const id = `${m.true}|${m.curve}|${m.other_curve}|${m.replica}|${m.segment}|${i}|${faded}`;
      images(m.point, c.center, this.mats[m.curve]).forEach((p, k) => {
        const e = marks[j++];
        placeCircle(e, px(p));
        describe(e, `${id}|${k}`, () => {
          attr(e, "r", k === 0 ? "4.5" : "3.5");
          attr(e, "class", `intersection hit ${m.true}${faded ? " faded" : ""}`);
          data(e, { true: String(m.true), curve: String(m.curve), segment: String(m.segment),
            replica: String(k), index: String(i) });
          setTitle(e, `${m.true ? "true" : "false"} intersection of curve ${m.curve} with curve ${m.other_curve} ` +
            `${m.replica}: click to put the PRC here`);
        });
      });
    });
    const prcs = g?.pieces.filter((p) => p.prc) ?? [];
    const rects = this.prcs.take(prcs.reduce((a, p) => a + this.mats[p.basic].length, 0));
    j = 0;
    for (const p of prcs) {
      const c = g!.curves[p.basic];
      images(p.prc!, c.center, this.mats[p.basic]).forEach((q, k) => {
        const e = rects[j++], [x, y] = px(q);
        attr(e, "transform", `translate(${f2(x)} ${f2(y)}) rotate(45)`);
        attr(e, "class", sel !== null && sel !== p.basic ? "prc faded" : "prc");
        data(e, { curve: String(p.basic), segment: String(p.segment), replica: String(k) });
      });
    }
  }

  /** Small dots on the vertices of every basic curve but the selected one (which gets handles). */
  private renderDots(px: Px): void {
    const curves = this.store.geometry?.curves ?? [], sel = this.store.selection;
    const n = curves.reduce((a, c, i) => a + (i === sel ? 0 : c.vertices.length), 0);
    const dots = this.dots.take(n);
    let j = 0;
    curves.forEach((c, i) => {
      if (i === sel) return;
      const color = this.store.color(i);
      c.vertices.forEach((v, k) => {
        const e = dots[j++];
        placeCircle(e, px(v));
        describe(e, `${i}|${k}|${c.marks[k]}|${color}`, () => {
          attr(e, "fill", color);
          attr(e, "class", `dot hit mark-${c.marks[k]}`);
          data(e, { curve: String(i), vertex: String(k) });
          setTitle(e, `curve ${i}, ${c.marks[k]} point ${k}: drag to move`);
        });
      });
    });
  }

  /** The selected curve's points, tangent handles and tangent lines (a dragged point where it is dragged). */
  private renderSelected(px: Px): void {
    const g = this.store.geometry, sel = this.store.selection;
    const c: CurveInfo | undefined = sel !== null ? g?.curves[sel] : undefined;
    if (sel === null || !c) {
      this.handles.take(0);
      this.tangents.take(0);
      return;
    }
    const drag = this.drag?.pos && this.drag.target.curve === sel ? this.drag : null;
    const t = drag?.target;
    const verts = c.vertices.map((v, k): Vec =>
      (t?.kind === "vertex" && t.vertex === k ? drag!.pos! : [v[0], v[1]]));
    const hs = c.handles.map((list, s) => list.map((h, k): Vec =>
      (t?.kind === "handle" && t.segment === s && t.handle === k ? drag!.pos! : [h[0], h[1]])));
    // a handle dragged off a line segment makes it an arc before the server says so
    if (t?.kind === "handle" && hs[t.segment].length === 0) hs[t.segment] = [drag!.pos!];
    const items: { p: Vec; cls: string; data: Record<string, string>; tip: string }[] = [];
    const lines: [Vec, Vec][] = [];
    hs.forEach((list, s) => {
      const a = verts[s], b = verts[s + 1];
      const handle = (p: Vec, k: number, cls: string, tip: string) => items.push({ p, cls,
        data: { role: "handle", segment: String(s), handle: String(k) }, tip: `segment ${s}: ${tip}` });
      if (list.length === 0) {
        handle([(a[0] + b[0]) / 2, (a[1] + b[1]) / 2], 0, "bend", "drag to bend the line into an arc");
      }
      list.forEach((h, k) => {
        // an arc's tangent at a aims at its handle; a Bezier's inner points hang off a and b
        lines.push([k === 1 ? b : a, h]);
        handle(h, k, "tangent-handle",
          list.length === 1 ? "where the tangent at the first point aims" : `control point ${k + 1}`);
      });
    });
    verts.forEach((v, k) => items.push({ p: v, cls: `vertex mark-${c.marks[k]}`,
      data: { role: "vertex", vertex: String(k) },
      tip: `${c.marks[k]} point ${k} (${v[0].toFixed(4)}, ${v[1].toFixed(4)}): drag to move` }));
    this.tangents.take(lines.length).forEach((e, i) => placeLine(e, px(lines[i][0]), px(lines[i][1])));
    this.handles.take(items.length).forEach((e, i) => {
      const it = items[i];
      placeCircle(e, px(it.p));
      attr(e, "r", it.cls === "bend" ? "4" : "5.5");
      attr(e, "class", `handle hit ${it.cls}`);
      delete e.dataset.vertex;
      delete e.dataset.segment;
      delete e.dataset.handle;
      Object.assign(e.dataset, { curve: String(sel), ...it.data });
      setTitle(e, it.tip);
    });
  }

  /** The curve being drawn up to the cursor, its replicas, and where the cursor snapped. */
  private renderDraft(px: Px): void {
    const d = this.draft, cur = this.cursor;
    const live = this.store.tool !== "select" ? this.lastSnap : this.drag?.pos ? this.lastSnap : null;
    this.snapMark.style.display = live?.kind ? "" : "none";
    if (live?.kind) {
      placeCircle(this.snapMark, px(live.p));
      this.snapMark.setAttribute("class", `snap ${live.kind}`);
    }
    let pts: Vec[] = d ? [...d.pts] : [];
    if (d && d.tool === "arc" && d.pts.length === 2) {
      const h = d.handle ?? cur;
      pts = h ? arcPoints(d.pts[0], h, d.pts[1]) : pts;
    } else if (d && cur) pts.push(cur);
    this.draftPoints.take(d ? d.pts.length : 0).forEach((e, i) => placeCircle(e, px(d!.pts[i])));
    const path = (list: readonly Vec[]) => list.map((p, i) => {
      const [x, y] = px(p);
      return `${i ? "L" : "M"}${f2(x)} ${f2(y)}`;
    }).join("");
    this.draftPath.setAttribute("d", pts.length > 1 ? path(pts) : "");
    let replicas = "";
    if (pts.length > 1) {
      const mats = symmetryMatrices(this.fold, mirrorAxis(this.mirror, [0, 0], pts[0], pts[pts.length - 1]));
      const imgs = pts.map((p) => images(p, [0, 0], mats));
      for (let k = 1; k < mats.length; k++) replicas += path(imgs.map((i) => i[k]));
    }
    this.draftReplicas.setAttribute("d", replicas);
  }

  private hintText(): string {
    const d = this.draft, tool = this.store.tool;
    if (tool === "select") {
      return this.store.selection === null
        ? "Click a curve to select it. Draw with L (line), A (arc), E (free end)."
        : "Drag points and handles; click an intersection to put the PRC there. Delete removes the curve.";
    }
    const steps = HINTS[tool];
    const step = !d ? 0 : d.needHandle ? (d.press ? 1 : 2) : d.pts.length;
    const name = TOOLS.find((t) => t.tool === tool)!.label;
    return `${name}: ${steps[Math.min(step, steps.length - 1)]}. Esc cancels, Alt suspends snapping.`;
  }

  private buildLegend(): void {
    const g = this.g.legend;
    const entry = (x: number, shape: SVGElement, text: string, turn = "") => {
      shape.setAttribute("transform", `translate(${x} -4)${turn}`);
      const t = make(g, "text");
      t.setAttribute("x", String(x + 10));
      t.textContent = text;
    };
    const trueDot = make(g, "circle", "intersection true");
    trueDot.setAttribute("r", "4.5");
    entry(4, trueDot, "true intersection");
    const falseRing = make(g, "circle", "intersection false");
    falseRing.setAttribute("r", "4.5");
    entry(122, falseRing, "false intersection");
    const prc = make(g, "rect", "prc");
    for (const [k, v] of [["x", "-4"], ["y", "-4"], ["width", "8"], ["height", "8"]]) prc.setAttribute(k, v);
    entry(245, prc, "PRC (click to move)", " rotate(45)");
  }
}

/** Average width of a hint character in px (12 px sans-serif), to wrap without measuring text. */
const HINT_CHAR_PX = 6.6;

export function initTopView(ctx: Ctx): void {
  new TopView(ctx);
}
