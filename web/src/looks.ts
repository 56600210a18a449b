// Looks (#look-tools): the members' style (curves, tube, bar, ribbon) and the faces (none, every
// loop, or picked loops). Meshes come from the server (get_mesh) after each geometry revision,
// debounced, one request at a time; replies older than the geometry or for other looks are
// dropped. Members show in the 3D view (and in every view in preview mode), coloured per basic
// curve (store.color); picking faces: click a loop in the 3D view (or the top view in preview).
import "./looks.css";
import * as THREE from "three";
import type { Ctx } from "./context";
import type { FacesMode, Style } from "./looks-types";
import { Debouncer, LoopView, MeshView, pickLoop, type ScreenLoop } from "./meshes";
import { SELECTED, SKY, VIEW_LAYER, type ViewName } from "./scene";
import { DragTubes } from "./tubes";
import type { Looks } from "./store";

const STYLES: Record<Style, string> = { curves: "curves", tube: "tubes", bar: "bars", ribbon: "ribbons" };
const FACES: Record<FacesMode, string> = { none: "no faces", auto: "all faces", picked: "pick faces" };
/** A pointer that moves less than this between press and release clicks (CSS pixels). */
const CLICK_SLOP = 4;

/** A toolbar select of `options` (value -> text). */
function select<T extends string>(parent: HTMLElement, testid: string, title: string, options: Record<T, string>,
  onChange: (v: T) => void): HTMLSelectElement {
  const el = document.createElement("select");
  el.dataset.testid = testid;
  el.title = title;
  for (const [value, text] of Object.entries(options) as [T, string][]) el.add(new Option(text, value));
  el.addEventListener("change", () => onChange(el.value as T));
  parent.appendChild(el);
  return el;
}

/** What a mesh request depends on besides the geometry. */
function meshKey(l: Looks): string {
  return `${l.style}|${l.faces}|${l.faces === "picked" ? [...l.loops].sort((a, b) => a - b).join(",") : ""}`;
}

/** Steps along each member of the 3D view's meshes (exports choose their own): the server's default
 * 64 doubled the triangles a software renderer draws per frame (U.XI.28's tubes: 163 856) for no
 * difference seen at the view's size. */
export const VIEW_SEGMENTS = 32;

/** How far the members of curves other than the selected one are faded towards the 3D view's ground. */
export const FADE = 0.6;

/** `hex` (#rrggbb) mixed with the 3D view's ground colour SKY by FADE, per 8-bit channel, rounded. */
export function faded(hex: string): string {
  const c = parseInt(hex.slice(1), 16);
  const out = [16, 8, 0].map((sh) => {
    const a = (c >> sh) & 255, b = (SKY >> sh) & 255;
    return Math.round(a + FADE * (b - a));
  });
  return "#" + out.map((v) => v.toString(16).padStart(2, "0")).join("");
}

const wantsMesh = (l: Looks) => l.style !== "curves" || l.faces !== "none";

export function initLooks(ctx: Ctx): void {
  const { store, views } = ctx;
  const bar = document.getElementById("look-tools")!;
  const style = select(bar, "look-style", "How the members are drawn", STYLES, (v) => store.setLooks({ style: v }));
  const faces = select(bar, "look-faces", "Fill the network's loops with minimal surfaces: none, all, " +
    "or the loops you click (in the 3D view; in preview also the top view)", FACES, (v) => store.setLooks({ faces: v }));
  style.value = store.looks.style;   // the URL may have set them (main.ts)
  faces.value = store.looks.faces;
  const info = document.createElement("span");
  info.className = "look-info";
  info.dataset.testid = "look-info";
  bar.appendChild(info);

  // the selected curve's members are highlighted as its lines are, the others faded towards the
  // 3D view's ground so that the highlight reads beside the palette's oranges (design mode only)
  const memberColor = (b: number): string => {
    const sel = store.mode === "design" ? store.selection : null;
    return sel === null ? store.color(b) : b === sel ? SELECTED : faded(store.color(b));
  };
  const meshes = new MeshView(memberColor);
  const loops = new LoopView();
  // the tube look's tubes while the drawing changes, swept in the page (tubes.ts), until the
  // server's mesh of the current revision replaces them
  const dragTubes = new DragTubes(memberColor);
  views.scene.add(meshes.group, dragTubes.group, loops.group);
  /** Sweep the page's tubes of the current geometry and show them instead of the server's (stale) members. */
  const showDragTubes = (): void => {
    const g = store.geometry;
    if (!g) return;
    dragTubes.update(g, store.data);
    dragTubes.group.visible = true;
    meshes.showMembers(false);
    views.membersRevision = g.revision;
  };

  /** Meshes show in the 3D view; in preview mode in all three. */
  const layers = (): number[] =>
    store.mode === "preview" ? [VIEW_LAYER.persp, VIEW_LAYER.top, VIEW_LAYER.side] : [VIEW_LAYER.persp];
  /** The tube look's members cover the lines on their axes (the page's drag tubes lie on them):
   * lines only in the views that show no members; the other looks show the lines everywhere. */
  const syncLines = (): void => {
    const shown = layers();
    views.setLineViews(store.looks.style === "tube"
      ? (["top", "persp", "side"] as ViewName[]).filter((v) => !shown.includes(VIEW_LAYER[v])) : null);
  };
  /** Loops are picked in the 3D view, and in the top view in preview mode (in design it is the design tools'). */
  const pickViews = (): ViewName[] => (store.mode === "preview" ? ["persp", "top"] : ["persp"]);

  let sentKey = "";
  const meshRequests = new Debouncer(() => {
    sentKey = meshKey(store.looks);
    const l = store.looks;
    info.textContent = "meshing...";
    return ctx.request({ type: "get_mesh", style: l.style, faces: l.faces, loops: l.faces === "picked" ? l.loops : [],
      segments: VIEW_SEGMENTS })
      .catch((e) => {
        info.textContent = ""; // the status bar says why
        throw e;
      });
  });
  const loopRequests = new Debouncer(() => ctx.request({ type: "get_loops" }));

  let lastKey = meshKey(store.looks);
  // a drag's edits (a button held) show the page's tubes; the server's mesh is asked for on release
  let held = false, refineOnRelease = false;
  window.addEventListener("pointerdown", () => { held = true; }, { capture: true });
  const release = () => {
    held = false;
    if (refineOnRelease && wantsMesh(store.looks) && store.geometry) meshRequests.poke();
    refineOnRelease = false;
  };
  window.addEventListener("pointerup", release, { capture: true });
  window.addEventListener("pointercancel", release, { capture: true });
  store.on("geometry", (g) => {
    if (store.looks.style === "curves") views.membersRevision = g.revision;
    if (store.looks.style === "tube") showDragTubes();
    if (held && store.looks.style === "tube") refineOnRelease = true;
    else if (wantsMesh(store.looks)) meshRequests.poke();
    if (store.looks.faces === "picked") loopRequests.poke();
  });
  store.on("looks", (l) => {
    style.value = l.style;
    faces.value = l.faces;
    const key = meshKey(l);
    if (key !== lastKey) {
      const wasPicking = lastKey.split("|")[1] === "picked";
      lastKey = key;
      if (wantsMesh(l) && store.geometry) meshRequests.poke();
      if (!wantsMesh(l)) {
        meshRequests.cancel();
        meshes.clear();
        info.textContent = "";
      }
      if (l.style === "tube") showDragTubes();
      else {
        dragTubes.clear();
        if (l.style === "curves" && store.geometry) views.membersRevision = store.geometry.revision;
      }
      if (l.faces === "picked" && !wasPicking && store.geometry) loopRequests.poke();
      if (l.faces !== "picked") {
        loopRequests.cancel();
        loops.clear();
      }
    }
    syncLines();
    meshes.recolor();
    dragTubes.recolor();
    loops.setPicked(l.loops);
    views.requestRender();
  });
  store.on("mesh", (m) => {
    const current = store.geometry?.revision ?? 0;
    if (!wantsMesh(store.looks) || m.revision < current || sentKey !== meshKey(store.looks)) return;
    meshes.show(m, store.meshBuffer);
    meshes.showMembers(true);
    dragTubes.group.visible = false;
    views.membersRevision = m.revision;
    info.textContent = store.looks.faces === "none" ? "" :
      `${m.faces} faces${m.converged ? "" : ` (not converged: ${m.residual.toPrecision(2)})`}`;
    views.requestRender();
  });
  store.on("loops", (m) => {
    if (store.looks.faces !== "picked" || m.revision < (store.geometry?.revision ?? 0)) return;
    loops.show(m, store.loopsBuffer, store.looks.loops);
    views.requestRender();
  });
  store.on("selection", () => {
    meshes.recolor();
    dragTubes.recolor();
    views.requestRender();
  });
  store.on("mode", () => {
    meshes.recolor();
    dragTubes.recolor();
    meshes.setLayers(layers());
    dragTubes.setLayers(layers());
    syncLines();
    loops.setLayers(pickViews().map((v) => VIEW_LAYER[v]));
    views.requestRender();
  });
  meshes.setLayers(layers());
  dragTubes.setLayers(layers());
  syncLines();
  loops.setLayers(pickViews().map((v) => VIEW_LAYER[v]));

  // ---- picking loops: a click (no drag) toggles the loop under the pointer
  let down: { x: number; y: number } | null = null;
  views.host.addEventListener("pointerdown", (ev) => {
    down = ev.button === 0 ? { x: ev.clientX, y: ev.clientY } : null;
  }, { capture: true });
  views.host.addEventListener("pointerup", (ev) => {
    const start = down;
    down = null;
    if (!start || store.looks.faces !== "picked" || !loops.loops.length) return;
    if (Math.hypot(ev.clientX - start.x, ev.clientY - start.y) > CLICK_SLOP) return;
    const v = views.viewAt(ev.clientX, ev.clientY);
    if (!v || !pickViews().includes(v)) return;
    const p = new THREE.Vector3();
    const screen: ScreenLoop[] = loops.loops.map((l) => {
      const boundary: [number, number][] = [];
      for (let i = 0; i < l.boundary.length; i += 3) {
        boundary.push(views.worldToClient(v, p.set(l.boundary[i], l.boundary[i + 1], l.boundary[i + 2]))!);
      }
      return { boundary, centre: views.worldToClient(v, l.centre)! };
    });
    const hit = pickLoop(screen, [ev.clientX, ev.clientY]);
    if (hit === null) return;
    const index = loops.loops[hit].index;
    const picked = store.looks.loops.includes(index)
      ? store.looks.loops.filter((i) => i !== index) : [...store.looks.loops, index];
    store.setLooks({ loops: picked });
  }, { capture: true });
}
