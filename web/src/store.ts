// The page's state: the document's latest geometry (from the server, the single source of
// geometry), what the user selected and chose, and a tiny event bus. No DOM, no three.js.
import type { FacesMode, Style } from "./looks-types";
import type { Geometry, Loops, MeshGeometry } from "./protocol";

export type Mode = "design" | "preview";
export type Tool = "select" | "line" | "arc" | "free";

export interface Looks {
  style: Style;
  faces: FacesMode;
  /** Loop indices (from the last Loops reply) filled when faces == "picked". */
  loops: number[];
  /** `#rrggbb` per basic curve; missing entries use the curve's colour from the server (CurveInfo.color). */
  colors: string[];
}

export interface StoreEvents {
  /** A new Geometry arrived (open, edit, undo, redo, another tab's edit). */
  geometry: Geometry;
  /** The selected basic curve changed (null: none). */
  selection: number | null;
  mode: Mode;
  tool: Tool;
  looks: Looks;
  mesh: MeshGeometry;
  loops: Loops;
  /** A one-line message for the status bar; `error` marks failures. */
  status: { text: string; error: boolean };
  /** The active layer (new curves go there; the side view snaps to its heights). */
  layer: number;
  /** Design mode: where the top view ends and the 3D view begins (a fraction of the viewport's width). */
  split: number;
}

/** The design mode's split between the top view and the 3D view: default and limits (fractions of the width). */
export const SPLIT = { default: 0.5, min: 0.2, max: 0.8 } as const;

type Listener<T> = (value: T) => void;

/** The colour of a basic curve the geometry does not (yet) list. */
export const NO_COLOR = "#808080";

export class Store {
  geometry: Geometry | null = null;
  /** The float32 view of the binary frame that came with `geometry`. */
  data: Float32Array = new Float32Array(0);
  /** The raw binary frame (u4 arrays are read from it too). */
  buffer: ArrayBuffer = new ArrayBuffer(0);
  mesh: MeshGeometry | null = null;
  meshBuffer: ArrayBuffer = new ArrayBuffer(0);
  loops: Loops | null = null;
  loopsBuffer: ArrayBuffer = new ArrayBuffer(0);
  selection: number | null = null;
  layer = 0;
  mode: Mode = "design";
  tool: Tool = "select";
  looks: Looks = { style: "tube", faces: "none", loops: [], colors: [] };
  split: number = SPLIT.default;
  private listeners = new Map<keyof StoreEvents, Set<Listener<never>>>();

  on<K extends keyof StoreEvents>(event: K, fn: Listener<StoreEvents[K]>): () => void {
    let set = this.listeners.get(event);
    if (!set) this.listeners.set(event, (set = new Set()));
    set.add(fn as Listener<never>);
    return () => set!.delete(fn as Listener<never>);
  }

  emit<K extends keyof StoreEvents>(event: K, value: StoreEvents[K]): void {
    for (const fn of this.listeners.get(event) ?? []) (fn as Listener<StoreEvents[K]>)(value);
  }

  setGeometry(msg: Geometry, buffer: ArrayBuffer): void {
    this.geometry = msg;
    this.buffer = buffer;
    this.data = new Float32Array(buffer);
    if (this.selection !== null && this.selection >= msg.n_curves) this.select(null);
    const nLayers = Math.max(1, msg.layers.length);
    if (this.layer >= nLayers) this.setLayer(nLayers - 1);
    this.emit("geometry", msg);
  }

  setMesh(msg: MeshGeometry, buffer: ArrayBuffer): void {
    this.mesh = msg;
    this.meshBuffer = buffer;
    this.emit("mesh", msg);
  }

  setLoops(msg: Loops, buffer: ArrayBuffer): void {
    this.loops = msg;
    this.loopsBuffer = buffer;
    this.emit("loops", msg);
  }

  select(curve: number | null): void {
    if (curve === this.selection) return;
    this.selection = curve;
    this.emit("selection", curve);
  }

  setMode(mode: Mode): void {
    if (mode === this.mode) return;
    this.mode = mode;
    this.emit("mode", mode);
  }

  setTool(tool: Tool): void {
    if (tool === this.tool) return;
    this.tool = tool;
    this.emit("tool", tool);
  }

  setLayer(layer: number): void {
    if (layer === this.layer) return;
    this.layer = layer;
    this.emit("layer", layer);
  }

  /** Set the design mode's split (clamped to SPLIT.min..SPLIT.max). */
  setSplit(split: number): void {
    const s = Math.min(SPLIT.max, Math.max(SPLIT.min, split));
    if (!Number.isFinite(s) || s === this.split) return;
    this.split = s;
    this.emit("split", s);
  }

  setLooks(change: Partial<Looks>): void {
    this.looks = { ...this.looks, ...change };
    this.emit("looks", this.looks);
  }

  /** The colour of basic curve `i` as lower-case `#rrggbb` (as colour inputs and three.js write it): the
   * user's choice, else the server's (one palette, auszug.formats.palette). */
  color(i: number): string {
    return (this.looks.colors[i] || this.geometry?.curves[i]?.color || NO_COLOR).toLowerCase();
  }

  status(text: string, error = false): void {
    this.emit("status", { text, error });
  }
}
