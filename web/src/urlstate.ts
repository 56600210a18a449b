// What the page's URL remembers, so a reload (or a copied link) comes back to the same place:
// the open document (`open`: its workspace path; `doc`: its id, which resumes an unsaved drawing
// from its autosave), the looks (`style`, `faces`), the mode and the design mode's split between the
// top and 3D views (`split`, the top view's fraction of the width, 0.2-0.8). Pure functions; main.ts applies them.
import type { FacesMode, Style } from "./looks-types";

export interface UrlState {
  open: string;
  doc: string;
  style: Style | null;
  faces: FacesMode | null;
  mode: "design" | "preview" | null;
  split: number | null;
}

const SPLIT_MIN = 0.2, SPLIT_MAX = 0.8, SPLIT_DEFAULT = 0.5;

const STYLES: readonly Style[] = ["curves", "tube", "bar", "ribbon"];
const FACES: readonly FacesMode[] = ["none", "auto", "picked"];
const MODES = ["design", "preview"] as const;
const DOC = /^[0-9a-f]{16}$/;

function oneOf<T extends string>(value: string | null, options: readonly T[]): T | null {
  return value !== null && (options as readonly string[]).includes(value) ? (value as T) : null;
}

/** The state in a URL's query (`location.search`); unknown or malformed values are ignored. */
export function readUrlState(search: string): UrlState {
  const q = new URLSearchParams(search);
  const doc = q.get("doc") ?? "";
  return {
    open: q.get("open") ?? "",
    doc: DOC.test(doc) ? doc : "",
    style: oneOf(q.get("style"), STYLES),
    faces: oneOf(q.get("faces"), FACES),
    mode: oneOf(q.get("mode"), MODES),
    split: readSplit(q.get("split")),
  };
}

function readSplit(value: string | null): number | null {
  if (value === null || !/^0?\.\d{1,4}$/.test(value)) return null;
  const s = Number(value);
  return s >= SPLIT_MIN && s <= SPLIT_MAX ? s : null;
}

/** `search` with the state written in (other parameters kept; defaults and empty values left out). */
export function writeUrlState(search: string, s: UrlState): string {
  const q = new URLSearchParams(search);
  const set = (key: string, value: string | null, fallback = "") => {
    if (value && value !== fallback) q.set(key, value);
    else q.delete(key);
  };
  set("open", s.open);
  set("doc", s.doc);
  set("style", s.style, "tube");
  set("faces", s.faces, "none");
  set("mode", s.mode, "design");
  set("split", s.split === null ? null : s.split.toFixed(3).replace(/0+$/, ""), SPLIT_DEFAULT.toFixed(3).replace(/0+$/, ""));
  const text = q.toString();
  return text ? `?${text}` : "";
}
