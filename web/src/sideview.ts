// The side view of the selected basic curve (#side-panel) and the layers (#layer-panel).
// The side view plots the curve's pieces as (x, z), x the top-view arc length along the curve
// from its ground point, at one scale on both axes. The apex, the PRCs, a post's top and the
// layers' bottom lines drag vertically, snapping to the other heights of the drawing (Alt: no
// snapping); a drag keeps at most one edit in flight and sends the latest value when the reply
// comes, and the scale stays put until the drag's last reply. Only heights change: the server
// keeps the top view as it is.
import { DragSender, RAW_UPDATES } from "./dragsender";
import { perFrame } from "./frames";
import { newDragId } from "./gesture";
import "./sideview.css";
import type { Ctx } from "./context";
import { view } from "./geometry";
import type { ClientMessage, Geometry } from "./protocol";
import { atField } from "./fielderror";

const SVG = "http://www.w3.org/2000/svg";
const HEIGHT = 260;
const MARGIN = { left: 38, right: 40, top: 12, bottom: 22 };
/** How close (CSS pixels) a dragged height snaps to another. */
const SNAP_PX = 6;

/** The selected curve laid out along x; every polyline is (x, z). */
interface SideLayout {
  length: number;
  paths: { kind: string; pts: [number, number][] }[];
  /** x of each apex vertex. */
  apexes: number[];
  prcs: { segment: number; x: number; z: number }[];
  /** x of each post. */
  posts: number[];
  /** The ogees' PRCs as fractions of their top-view length from the ground. */
  prcFractions: number[];
}

function nearestVertex(vertices: [number, number][], x: number, y: number): number {
  let best = 0, bestD = Infinity;
  vertices.forEach((v, i) => {
    const d = Math.hypot(v[0] - x, v[1] - y);
    if (d < bestD) [best, bestD] = [i, d];
  });
  return best;
}

/** Lay out curve `curve`'s pieces so that it reads left to right from its ground point. */
function sideLayout(g: Geometry, data: Float32Array, curve: number): SideLayout {
  const info = g.curves[curve];
  const V = info.vertices, n = V.length;
  const pieces = g.pieces.filter((p) => p.basic === curve);
  const len = V.slice(1).map((v, i) => Math.hypot(v[0] - V[i][0], v[1] - V[i][1]));
  for (const p of pieces) {
    if (p.segment < 0 || p.kind === "decoration") continue;
    const s = view(data, p.side);
    len[p.segment] = s[s.length - 2];
  }
  // vertex order along x: reversed when only the last vertex is a ground point
  const order = [...Array(n).keys()];
  if (info.marks[0] !== "ground" && info.marks[n - 1] === "ground") order.reverse();
  const X = new Array<number>(n).fill(0);
  for (let m = 1; m < n; m++) X[order[m]] = X[order[m - 1]] + len[Math.min(order[m - 1], order[m])];
  const out: SideLayout = { length: X[order[n - 1]], paths: [], apexes: [], prcs: [], posts: [], prcFractions: [] };
  for (const p of pieces) {
    const pts = view(data, p.points), side = view(data, p.side);
    if (p.segment < 0) { // vertical: a post or pillar at one of the curve's vertices
      const x = X[nearestVertex(V, pts[0], pts[1])];
      out.paths.push({ kind: p.kind, pts: [[x, side[1]], [x, side[side.length - 1]]] });
      if (p.kind === "post") out.posts.push(x);
      continue;
    }
    const a = p.segment, b = p.segment + 1;
    const start = Math.hypot(pts[0] - V[a][0], pts[1] - V[a][1]) <= Math.hypot(pts[0] - V[b][0], pts[1] - V[b][1]) ? a : b;
    const dir = Math.sign(X[start === a ? b : a] - X[start]) || 1;
    const path: [number, number][] = [];
    for (let i = 0; i < side.length; i += 2) path.push([X[start] + dir * side[i], side[i + 1]]);
    out.paths.push({ kind: p.kind, pts: path });
    if (p.kind === "ogee" && p.prc && p.prc_s !== null) {
      out.prcs.push({ segment: p.segment, x: X[start] + dir * p.prc_s, z: p.prc[2] });
      out.prcFractions.push(p.prc_s / Math.max(len[p.segment], 1e-12));
    }
  }
  info.marks.forEach((m, i) => { if (m === "apex") out.apexes.push(X[i]); });
  return out;
}

/** SVG pixels of (x, z): px = ox + k x, py = oy - k z (also on the svg's data-k, data-ox, data-oy). */
interface SideMap {
  k: number;
  ox: number;
  oy: number;
}

/** The map that shows [xLo, xHi] x [zLo, zHi] centred in the plot area, at one scale. */
function fitMap(width: number, xLo: number, xHi: number, zLo: number, zHi: number): SideMap {
  const w = width - MARGIN.left - MARGIN.right, h = HEIGHT - MARGIN.top - MARGIN.bottom;
  const k = Math.min(w / Math.max(xHi - xLo, 1e-9), h / Math.max(zHi - zLo, 1e-9));
  return { k, ox: MARGIN.left + w / 2 - (k * (xLo + xHi)) / 2, oy: MARGIN.top + h / 2 + (k * (zLo + zHi)) / 2 };
}

/** A round grid step near `span` / 5. */
function gridStep(span: number): number {
  const raw = span / 5, p = 10 ** Math.floor(Math.log10(raw));
  return [1, 2, 5, 10].map((f) => f * p).find((s) => s >= raw) ?? 10 * p;
}

const fmt = (z: number) => String(Number(z.toFixed(3)));

/** A height the dragged one may snap to. */
interface Target {
  z: number;
  label: string;
}

/** The heights of the drawing, leaving out the curves `skip` says and layer `skipLayer`'s bottom. */
function targets(g: Geometry, skip: (curve: number) => boolean, skipLayer: number | null): Target[] {
  const out: Target[] = [];
  g.curves.forEach((c, i) => {
    if (skip(i)) return;
    out.push({ z: c.apex, label: `apex of curve ${i}` });
    if (c.post_top !== null) out.push({ z: c.post_top, label: `post of curve ${i}` });
  });
  for (const p of g.pieces) if (p.prc && !skip(p.basic)) out.push({ z: p.prc[2], label: `PRC of curve ${p.basic}` });
  g.layers.forEach((z, l) => { if (l !== skipLayer) out.push({ z, label: `bottom of layer ${l}` }); });
  return out;
}

type DragKind = { what: "apex" } | { what: "prc"; segment: number } | { what: "post" } | { what: "bottom"; layer: number };

interface Drag {
  kind: DragKind;
  curve: number;
  z: number;
  /** Drag values stay above this (an apex above its bottom, a post above its apex). */
  floor: number;
  targets: Target[];
  snap: Target | null;
  /** The drag number its edits carry (one undo step). */
  gesture: number;
  /** The side view's top in client pixels (read once: the panel does not move during a drag). */
  top: number;
  /** Whether pointerrawupdate events come for it (then pointermove is ignored). */
  raw: boolean;
}

function el<K extends keyof HTMLElementTagNameMap>(tag: K, cls = "", text = ""): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  if (cls) e.className = cls;
  if (text) e.textContent = text;
  return e;
}

function svgEl(parent: Element, tag: string, attrs: Record<string, string | number>, cls = ""): SVGElement {
  const e = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, String(v));
  if (cls) e.setAttribute("class", cls);
  parent.appendChild(e);
  return e;
}

function numberInput(testid: string, step: string): HTMLInputElement {
  const i = el("input");
  i.type = "number";
  i.step = step;
  i.dataset.testid = testid;
  return i;
}

/** Set an input's value unless the user is typing in it. */
function setValue(input: HTMLInputElement, value: string): void {
  if (document.activeElement !== input) input.value = value;
}

export function initSideView(ctx: Ctx): void {
  initSide(ctx);
  initLayers(ctx);
}

function initSide(ctx: Ctx): void {
  const { store } = ctx;
  const panel = document.getElementById("side-panel")!;
  const head = el("div", "side-head");
  const title = el("h2", "", "Side view");
  const curveSelect = el("select");
  curveSelect.dataset.testid = "side-curve";
  curveSelect.title = "The curve whose side view is shown (also selected by clicking it in the top view)";
  curveSelect.addEventListener("change", () => store.select(curveSelect.value === "" ? null : Number(curveSelect.value)));
  head.append(title, curveSelect);
  const hint = el("p", "side-hint", "Select a curve to edit its heights.");
  const svg = document.createElementNS(SVG, "svg");
  let svgWidth = 0;   // its width in CSS pixels (0 while hidden), from the resize observer below
  svg.setAttribute("class", "side-svg");
  svg.dataset.testid = "side-svg";
  const readout = el("div", "side-readout");
  const controls = el("div", "side-controls");

  const apexRow = el("label", "row", "apex ");
  const apexInput = numberInput("apex-height", "0.01");
  apexRow.appendChild(apexInput);
  const decoRow = el("label", "row");
  const decoToggle = el("input");
  decoToggle.type = "checkbox";
  decoToggle.dataset.testid = "decoration-toggle";
  const decoAt = el("input");
  decoAt.type = "range";
  decoAt.min = "0";
  decoAt.max = "1000";
  decoAt.dataset.testid = "decoration-at";
  decoAt.title = "Where the decoration's two arcs meet, between the ground and the PRC";
  decoRow.append(decoToggle, " decoration ", decoAt);
  const postRow = el("label", "row");
  const postToggle = el("input");
  postToggle.type = "checkbox";
  postToggle.dataset.testid = "post-toggle";
  const postTop = numberInput("post-top", "0.01");
  postRow.append(postToggle, " post, top ", postTop);
  controls.append(apexRow, decoRow, postRow);
  panel.append(head, hint, svg, readout, controls);

  let map: SideMap = { k: 1, ox: 0, oy: 0 };
  let frozen = false; // the scale stays while a drag's edits are on their way
  let drag: Drag | null = null;
  let decoGesture = 0;   // the decoration slider's drag number while it moves
  let lay: SideLayout | null = null;
  const sender = new DragSender<ClientMessage>({
    request: (m, input) => ctx.request(m, input),
    idle: () => {
      if (!drag && frozen) {
        frozen = false;
        draw();
      }
    },
  });
  const px = (x: number) => map.ox + map.k * x;
  const pz = (z: number) => map.oy - map.k * z;
  const selected = (): number | null => {
    const g = store.geometry, c = store.selection;
    return g && c !== null && c < g.n_curves ? c : null;
  };

  function syncCurveSelect(g: Geometry | null): void {
    const n = g ? g.n_curves : 0;
    if (curveSelect.options.length !== n + 1) {
      curveSelect.replaceChildren(new Option("—", ""));
      for (let i = 0; i < n; i++) curveSelect.add(new Option(`curve ${i}${g!.curves[i].name ? `: ${g!.curves[i].name}` : ""}`, String(i)));
    }
    curveSelect.value = store.selection === null ? "" : String(store.selection);
  }

  function startDrag(ev: PointerEvent, kind: DragKind, z: number): void {
    const g = store.geometry, c = selected();
    if (ev.button !== 0 || !g || c === null) return;
    ev.preventDefault();
    ev.stopPropagation();
    const info = g.curves[c];
    const onePx = 1 / map.k;
    const floor = kind.what === "bottom" ? -Infinity : kind.what === "post" ? info.apex + onePx : info.bottom + onePx;
    const t = kind.what === "bottom"
      ? targets(g, (i) => g.curves[i].layer === kind.layer, kind.layer)
      : targets(g, (i) => i === c, null);
    drag = { kind, curve: c, z, floor, targets: t, snap: null, gesture: newDragId(), top: svg.getBoundingClientRect().top, raw: false };
    frozen = true;
    sender.begin();
    draw();
  }

  function dragMessage(d: Drag): ClientMessage {
    switch (d.kind.what) {
      case "apex": return { type: "set_apex_height", curve: d.curve, height: d.z, drag: d.gesture };
      case "prc": return { type: "set_prc_height", curve: d.curve, z: d.z, segment: d.kind.segment, drag: d.gesture };
      case "post": return { type: "set_post", curve: d.curve, top: d.z, drag: d.gesture };
      case "bottom": return { type: "set_layer_bottom", layer: d.kind.layer, z: d.z, drag: d.gesture };
    }
  }

  // pointerrawupdate where the browser has it: the edit goes out without waiting for a frame
  // (pointermove still drives a drag that gets no raw updates, whatever the reason)
  const dragMove = (ev: PointerEvent) => {
    if (!drag) return;
    const z = Math.max(drag.floor, (map.oy - (ev.clientY - drag.top)) / map.k);
    let snap: Target | null = null;
    if (!ev.altKey) {
      for (const t of drag.targets) {
        const d = Math.abs(t.z - z);
        if (t.z >= drag.floor && d <= SNAP_PX / map.k && (!snap || d < Math.abs(snap.z - z))) snap = t;
      }
    }
    drag.snap = snap;
    drag.z = snap ? snap.z : z;
    sender.push(dragMessage(drag), ev.timeStamp);
    later();   // the marker follows at the next frame (raw updates may come far more often)
  };
  if (RAW_UPDATES) {
    window.addEventListener("pointerrawupdate", ((ev: PointerEvent) => {
      if (drag) drag.raw = true;
      dragMove(ev);
    }) as EventListener);
  }
  window.addEventListener("pointermove", (ev) => { if (drag && !drag.raw) dragMove(ev); });
  const endDrag = () => {
    if (!drag) return;
    drag = null;
    if (!sender.pending) frozen = false;
    draw();
  };
  window.addEventListener("pointerup", endDrag);
  window.addEventListener("pointercancel", endDrag);

  /** A draggable marker: a visible shape and a larger invisible hit area. */
  function marker(shape: "circle" | "diamond" | "square", x: number, z: number, testid: string, title: string,
    kind: DragKind, extra: Record<string, string> = {}): void {
    const g = svgEl(svg, "g", { transform: `translate(${px(x)},${pz(z)})` }, `marker ${kind.what}`);
    g.dataset.testid = testid;
    for (const [k, v] of Object.entries(extra)) g.dataset[k] = v;
    svgEl(g, "title", {}).textContent = title;
    if (shape === "circle") svgEl(g, "circle", { r: 5 }, "shape");
    else if (shape === "diamond") svgEl(g, "path", { d: "M0,-6L6,0L0,6L-6,0Z" }, "shape");
    else svgEl(g, "rect", { x: -4.5, y: -4.5, width: 9, height: 9 }, "shape");
    svgEl(g, "circle", { r: 10 }, "hit");
    g.addEventListener("pointerdown", (ev) => startDrag(ev as PointerEvent, kind, z));
  }

  function draw(): void {
    const g = store.geometry, c = selected();
    syncCurveSelect(g);
    const on = g !== null && c !== null;
    hint.hidden = on;
    svg.style.display = on ? "" : "none";
    readout.hidden = controls.hidden = !on;
    const width = svgWidth; // 0 while the panel is hidden (preview mode)
    if (!on || width <= 0) return;
    const info = g.curves[c];
    lay = sideLayout(g, store.data, c);
    const zs = [g.bounds[2], g.bounds[5], ...g.layers];
    let zLo = Math.min(...zs), zHi = Math.max(...zs);
    if (!(zHi - zLo > 1e-9)) zHi = zLo + 1;
    const pad = 0.06 * (zHi - zLo), xPad = 0.04 * lay.length;
    if (!frozen) map = fitMap(width, -xPad, lay.length + xPad, zLo - pad, zHi + pad);
    svg.setAttribute("height", String(HEIGHT));
    svg.dataset.revision = String(g.revision);   // what it shows (tests wait for it: it redraws once a frame)
    svg.dataset.curve = String(c);
    svg.dataset.k = String(map.k);
    svg.dataset.ox = String(map.ox);
    svg.dataset.oy = String(map.oy);
    svg.replaceChildren();

    // grid and axes over the plot area
    const x0 = MARGIN.left, x1 = width - MARGIN.right, y0 = MARGIN.top, y1 = HEIGHT - MARGIN.bottom;
    const step = gridStep(Math.max((x1 - x0) / map.k, (y1 - y0) / map.k));
    const grid = svgEl(svg, "g", {}, "grid");
    for (let z = Math.ceil((map.oy - y1) / map.k / step) * step; pz(z) >= y0; z += step) {
      svgEl(grid, "line", { x1: x0, x2: x1, y1: pz(z), y2: pz(z) });
      svgEl(grid, "text", { x: x0 - 4, y: pz(z) + 3.5, "text-anchor": "end" }, "tick").textContent = fmt(z);
    }
    for (let x = Math.ceil((x0 - map.ox) / map.k / step) * step; px(x) <= x1; x += step) {
      svgEl(grid, "line", { x1: px(x), x2: px(x), y1: y0, y2: y1 });
      svgEl(grid, "text", { x: px(x), y: y1 + 13, "text-anchor": "middle" }, "tick").textContent = fmt(x);
    }
    svgEl(svg, "rect", { x: x0, y: y0, width: x1 - x0, height: y1 - y0 }, "frame");
    svgEl(svg, "text", { x: x1 + 2, y: y1 + 13 }, "tick").textContent = "s";
    svgEl(svg, "text", { x: x0 - 4, y: y0 - 2, "text-anchor": "end" }, "tick").textContent = "z";

    // the layers' bottom lines (drag: set_layer_bottom)
    g.layers.forEach((bz, l) => {
      const z = drag?.kind.what === "bottom" && drag.kind.layer === l ? drag.z : bz;
      const line = svgEl(svg, "g", {}, `bottom${l === info.layer ? " own" : ""}`);
      line.dataset.testid = `bottom-line-${l}`;
      svgEl(line, "title", {}).textContent = `bottom of layer ${l}: ${fmt(bz)} (drag to move)`;
      svgEl(line, "line", { x1: x0, x2: x1, y1: pz(z), y2: pz(z) }, "shape");
      svgEl(line, "line", { x1: x0, x2: x1, y1: pz(z), y2: pz(z) }, "hit");
      svgEl(line, "text", { x: x1 + 3, y: pz(z) + 3.5 }, "tick").textContent = `L${l}`;
      line.addEventListener("pointerdown", (ev) => startDrag(ev as PointerEvent, { what: "bottom", layer: l }, bz));
    });

    // the heights of the other curves, as ticks on the right edge
    for (const t of targets(g, (i) => i === c, -1)) {
      if (!t.label.startsWith("bottom")) {
        svgEl(svg, "line", { x1: x1 - 6, x2: x1, y1: pz(t.z), y2: pz(t.z) }, "other");
      }
    }

    // the chords A^s B^s (Remark 1: a PRC lies on its ogee's chord), then the pieces
    const color = store.color(c);
    for (const p of lay.paths) {
      if (p.kind !== "ogee") continue;
      const [a, b] = [p.pts[0], p.pts[p.pts.length - 1]];
      svgEl(svg, "line", { x1: px(a[0]), y1: pz(a[1]), x2: px(b[0]), y2: pz(b[1]) }, "chord");
    }
    for (const p of lay.paths) {
      const d = p.pts.map(([x, z], i) => `${i ? "L" : "M"}${px(x).toFixed(2)},${pz(z).toFixed(2)}`).join("");
      const path = svgEl(svg, "path", { d, stroke: color }, `piece ${p.kind}`);
      path.dataset.kind = p.kind;
    }

    // markers
    for (const x of lay.posts) {
      if (info.post_top === null) break;
      const z = drag?.kind.what === "post" ? drag.z : info.post_top;
      marker("square", x, z, "post-top-marker", `post top ${fmt(info.post_top)} (drag)`, { what: "post" });
    }
    for (const p of lay.prcs) {
      const kind: DragKind = { what: "prc", segment: p.segment };
      marker("diamond", p.x, p.z, "prc-marker", `PRC at ${fmt(p.z)} (drag: the apex follows)`, kind,
        { segment: String(p.segment) });
    }
    for (const x of lay.apexes) {
      const z = drag?.kind.what === "apex" ? drag.z : info.apex;
      marker("circle", x, z, "apex-marker", `apex ${fmt(info.apex)} (drag)`, { what: "apex" });
    }

    // while dragging: the heights it may snap to, and the guide at the dragged height
    if (drag) {
      for (const t of drag.targets) svgEl(svg, "line", { x1: x0, x2: x1, y1: pz(t.z), y2: pz(t.z) }, "target");
      svgEl(svg, "line", { x1: x0, x2: x1, y1: pz(drag.z), y2: pz(drag.z) }, `guide${drag.snap ? " snapped" : ""}`);
      const label = svgEl(svg, "text", { x: x0 + 4, y: pz(drag.z) - 4 }, "guide-label");
      label.textContent = `${fmt(drag.z)}${drag.snap ? ` = ${drag.snap.label}` : ""}`;
    }

    // readout and controls
    const prcText = lay.prcs.map((p) => fmt(p.z)).join(", ");
    readout.textContent = `apex ${fmt(info.apex)}${prcText ? ` · PRC ${prcText}` : ""} · layer ${info.layer}, ` +
      `bottom ${fmt(info.bottom)}${info.post_top !== null ? ` · post ${fmt(info.post_top)}` : ""}`;
    setValue(apexInput, fmt(info.apex));
    const hasOgee = lay.prcs.length > 0;
    decoToggle.checked = info.decoration;
    decoToggle.disabled = !hasOgee;
    decoAt.disabled = !info.decoration;
    const [lo, hi] = decorationRange(lay);
    const at = info.decoration_at ?? (lo + hi) / 2;
    if (document.activeElement !== decoAt) decoAt.value = String(Math.round((1000 * (at - lo)) / (hi - lo)));
    postToggle.checked = info.post_top !== null;
    postTop.disabled = info.post_top === null;
    setValue(postTop, info.post_top === null ? "" : fmt(info.post_top));
  }

  /** The decoration's meeting point may lie anywhere strictly between the ground and the lowest PRC. */
  function decorationRange(l: SideLayout): [number, number] {
    const f = Math.min(1, ...l.prcFractions);
    return [0.02 * f, 0.98 * f];
  }

  apexInput.addEventListener("change", () => {
    const c = selected(), v = Number(apexInput.value);
    if (c !== null && apexInput.value !== "" && Number.isFinite(v)) {
      atField(apexInput, ctx.request({ type: "set_apex_height", curve: c, height: v }), draw);
    }
  });
  decoToggle.addEventListener("change", () => {
    const c = selected();
    if (c !== null) void ctx.request({ type: "set_decoration", curve: c, on: decoToggle.checked, at: null }).catch(draw);
  });
  decoAt.addEventListener("input", () => {
    const c = selected();
    if (c === null || !lay) return;
    const [lo, hi] = decorationRange(lay);
    sender.begin();
    decoGesture ||= newDragId();
    sender.push({ type: "set_decoration", curve: c, on: true, at: lo + ((hi - lo) * Number(decoAt.value)) / 1000,
      drag: decoGesture });
  });
  decoAt.addEventListener("change", () => { decoGesture = 0; });  // the slider was let go
  postToggle.addEventListener("change", () => {
    const c = selected(), g = store.geometry;
    if (c === null || !g) return;
    const info = g.curves[c];
    const top = postToggle.checked ? info.apex + 0.25 * Math.max(info.apex - info.bottom, 1e-3) : null;
    void ctx.request({ type: "set_post", curve: c, top }).catch(draw);
  });
  postTop.addEventListener("change", () => {
    const c = selected(), v = Number(postTop.value);
    if (c !== null && postTop.value !== "" && Number.isFinite(v)) atField(postTop, ctx.request({ type: "set_post", curve: c, top: v }), draw);
  });

  // store events redraw once a frame (a drag's stream of geometry costs one redraw per frame);
  // the side view's own drags redraw at once
  const later = perFrame(draw);
  store.on("geometry", later);
  store.on("selection", later);
  store.on("looks", later);
  // the width is kept from the resize observer: reading it in draw would force a layout
  new ResizeObserver((entries) => {
    svgWidth = entries[entries.length - 1].borderBoxSize?.[0]?.inlineSize ?? svg.getBoundingClientRect().width;
    later();
  }).observe(svg);
  draw();
}

function initLayers(ctx: Ctx): void {
  const { store } = ctx;
  const panel = document.getElementById("layer-panel")!;
  const head = el("div", "side-head");
  const add = el("button", "", "Add layer");
  add.dataset.testid = "add-layer";
  add.title = "Add a layer on top (its bottom: the highest apex of the top layer)";
  add.addEventListener("click", () => void ctx.request({ type: "add_layer", bottom: null }).catch(() => undefined));
  head.append(el("h2", "", "Layers"), add);
  const list = el("ol", "layers");
  list.dataset.testid = "layers";
  panel.append(head, list);
  let structure = "";
  const inputs: HTMLInputElement[] = [];

  function draw(): void {
    const g = store.geometry;
    if (!g) {
      list.replaceChildren();
      structure = "";
      return;
    }
    const counts = g.layers.map((_, l) => g.curves.filter((c) => c.layer === l).length);
    const sel = store.selection !== null && store.selection < g.n_curves ? store.selection : null;
    const selLayer = sel === null ? -1 : g.curves[sel].layer;
    const key = `${counts.join(",")}|${store.layer}|${selLayer}`;
    if (key !== structure) {
      structure = key;
      inputs.length = 0;
      list.replaceChildren();
      for (let l = g.layers.length - 1; l >= 0; l--) { // the top layer first, as in an elevation
        const row = el("li", l === store.layer ? "layer active" : "layer");
        row.dataset.testid = `layer-${l}`;
        const active = el("input");
        active.type = "radio";
        active.name = "active-layer";
        active.checked = l === store.layer;
        active.dataset.testid = `layer-active-${l}`;
        active.title = "New curves are drawn on the active layer";
        active.addEventListener("change", () => store.setLayer(l));
        const name = el("label", "name");
        name.append(active, ` ${l}`);
        const bottom = numberInput(`layer-bottom-${l}`, "0.1");
        bottom.title = `Bottom height of layer ${l}`;
        bottom.addEventListener("change", () => {
          const v = Number(bottom.value);
          if (bottom.value !== "" && Number.isFinite(v)) atField(bottom, ctx.request({ type: "set_layer_bottom", layer: l, z: v }), draw);
        });
        inputs[l] = bottom;
        const count = el("span", "count", `${counts[l]} curve${counts[l] === 1 ? "" : "s"}`);
        count.dataset.testid = `layer-count-${l}`;
        const move = el("button", "", "Move here");
        move.dataset.testid = `layer-move-${l}`;
        move.title = "Move the selected curve to this layer";
        move.disabled = sel === null || selLayer === l;
        move.addEventListener("click", () => {
          if (sel !== null) void ctx.request({ type: "set_layer", curve: sel, layer: l }).catch(() => undefined);
        });
        const remove = el("button", "remove", "×");
        remove.dataset.testid = `layer-remove-${l}`;
        remove.title = "Remove this layer and its curves";
        remove.disabled = g.layers.length <= 1;
        remove.addEventListener("click", () => {
          const n = counts[l];
          if (n > 0 && !window.confirm(`Remove layer ${l} and its ${n} curve${n === 1 ? "" : "s"}?`)) return;
          void ctx.request({ type: "remove_layer", layer: l }).catch(() => undefined);
        });
        row.append(name, bottom, count, move, remove);
        list.appendChild(row);
      }
    }
    g.layers.forEach((z, l) => setValue(inputs[l], fmt(z)));
  }

  const later = perFrame(draw);
  store.on("geometry", later);
  store.on("layer", later);
  store.on("selection", later);
  draw();
}
