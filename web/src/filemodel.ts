// The file tools' pure parts (no DOM): gallery groups and search, file names, the document's
// title, the recovery time, and export requests built from the looks.
import type { Export, Files, Geometry } from "./protocol";
import type { Looks } from "./store";

/** One drawing in the gallery: `path` is what open (workspace) or open_example (example) takes. */
export interface Card {
  kind: "workspace" | "example";
  path: string;
  /** The file name without its folder and extension, e.g. "U.XI.28". */
  label: string;
  /** The extension shown next to the label, e.g. ".uc". */
  ext: string;
}

export interface Group {
  /** "Workspace", "Workspace · sub", "Examples · teaching-sheet", ... */
  title: string;
  cards: Card[];
}

const natural = (a: string, b: string) => a.localeCompare(b, "en", { numeric: true, sensitivity: "base" });

/** The bundled examples' folders in the order the gallery shows them (others follow, sorted). */
const EXAMPLE_FOLDERS = ["teaching-sheet", "web", "legacy"];

function byFolder(a: string, b: string): number {
  const rank = (dir: string) => {
    const i = EXAMPLE_FOLDERS.indexOf(dir.split("/")[0]);
    return i < 0 ? EXAMPLE_FOLDERS.length : i;
  };
  return rank(a) - rank(b) || natural(a, b);
}

function card(kind: Card["kind"], path: string): Card {
  const base = path.slice(path.lastIndexOf("/") + 1);
  const m = /^(.*?)((?:\.network)?\.[^.]+)$/.exec(base);
  return { kind, path, label: m && m[1] ? m[1] : base, ext: m && m[1] ? m[2] : "" };
}

function folder(path: string): string {
  const i = path.lastIndexOf("/");
  return i < 0 ? "" : path.slice(0, i);
}

/** Whether every word of `filter` occurs in `path` (case-insensitive). */
export function matches(path: string, filter: string): boolean {
  const p = path.toLowerCase();
  return filter.toLowerCase().split(/\s+/).filter(Boolean).every((w) => p.includes(w));
}

/**
 * The gallery: workspace drawings first, then the examples (teaching sheet, web, legacy), one
 * group per folder, each in natural order (tn-2 before tn-11); only drawings matching `filter`;
 * no empty groups.
 */
export function galleryGroups(files: Pick<Files, "workspace" | "examples">, filter = ""): Group[] {
  const groups = new Map<string, Group>();
  const add = (kind: Card["kind"], paths: string[], prefix: string, rootTitle: string) => {
    const keys = [...new Set(paths.map(folder))].sort(kind === "example" ? byFolder : natural);
    for (const dir of keys) {
      const cards = paths.filter((p) => folder(p) === dir && matches(p, filter)).sort(natural).map((p) => card(kind, p));
      if (cards.length) groups.set(`${kind}:${dir}`, { title: dir ? `${prefix} · ${dir}` : rootTitle, cards });
    }
  };
  add("workspace", files.workspace, "Workspace", "Workspace");
  add("example", files.examples, "Examples", "Examples");
  return [...groups.values()];
}

/** Formats a drawing can be saved in. */
export type DrawingExt = ".json" | ".uc";

/** The extension of a typed file name, if it is a drawing format. */
export function drawingExt(name: string): DrawingExt | null {
  const m = /\.(json|uc)$/i.exec(name.trim());
  return m ? (`.${m[1].toLowerCase()}` as DrawingExt) : null;
}

/**
 * The workspace path to save to, from a typed name and the chosen format: trimmed, leading
 * slashes dropped, the extension replaced by `ext`. Null when no name is left.
 */
export function savePath(name: string, ext: DrawingExt): string | null {
  const stem = name.trim().replace(/^[/\\]+/, "").replace(/\.(json|uc)$/i, "").trim();
  if (!stem || /[/\\]$/.test(stem)) return null;
  return stem + ext;
}

/** What the document is called: its workspace path, else its name (examples, uploads, new drawings). */
export function documentName(g: Pick<Geometry, "path" | "name">): string {
  return g.path || g.name || "untitled";
}

/** The name shown in the toolbar and the browser tab: "tn-2.uc •" while unsaved. */
export function documentLabel(g: Pick<Geometry, "path" | "name" | "dirty">): string {
  return documentName(g) + (g.dirty ? " •" : "");
}

/** The name offered when saving a document for the first time (or under another name). */
export function suggestedName(g: Pick<Geometry, "path" | "name">): string {
  if (g.path) return g.path;
  const stem = (g.name || "untitled").replace(/[/\\]/g, "-");
  return `${stem}.json`;
}

/** `Geometry.recoverable` (the autosave's ISO time) as a local date and time; other text as it is. */
export function recoveryTime(recoverable: string, locale?: string): string {
  const ms = Date.parse(recoverable);
  if (!Number.isFinite(ms)) return recoverable;
  return new Date(ms).toLocaleString(locale, { dateStyle: "medium", timeStyle: "short" });
}

/** What the Export menu offers. */
export type ExportChoice = "glb" | "obj" | "stl" | "ply" | "svg" | "network.json";

/** Formats whose file is a triangle mesh (the looks' members and faces). */
export const MESH_FORMATS: readonly ExportChoice[] = ["glb", "obj", "stl", "ply"];

/** A mesh export's resolution: steps along each member and points round a tube (null: the server's
 * defaults, 200 and 40; 64 steps for a printable solid). Bars and ribbons keep their 4 corners. */
export type Resolution = "fine" | "medium" | "light" | "draft";
export const RESOLUTIONS: Record<Resolution, { label: string; segments: number | null; around: number | null }> = {
  fine: { label: "fine (200 steps, 40 round)", segments: null, around: null },
  medium: { label: "medium (96 steps, 16 round)", segments: 96, around: 16 },
  light: { label: "light (48 steps, 10 round)", segments: 48, around: 10 },
  draft: { label: "draft (24 steps, 6 round)", segments: 24, around: 6 },
};

/**
 * The export request for a menu choice. Meshes take the looks' style (the "curves" look has no
 * cross-section: bars, the server's default), faces and picked loops; glb and obj also the
 * colours per basic curve as shown; `solid` (stl only) asks for one watertight, printable solid;
 * `resolution` sets the steps along the members and, for tubes, the points round them.
 */
export function exportRequest(format: ExportChoice, looks: Looks, colors: string[], solid: boolean,
  resolution: Resolution = "fine"): Export {
  if (!MESH_FORMATS.includes(format)) return { type: "export", format };
  const msg: Export = {
    type: "export",
    format,
    style: looks.style === "curves" ? "bar" : looks.style,
    faces: looks.faces,
    loops: looks.faces === "picked" ? looks.loops : [],
  };
  if (format === "glb" || format === "obj") msg.colors = colors;
  if (format === "stl" && solid) msg.solid = true;
  const r = RESOLUTIONS[resolution];
  if (r.segments !== null) msg.segments = r.segments;
  if (r.around !== null && msg.style === "tube") msg.around = r.around;
  return msg;
}
