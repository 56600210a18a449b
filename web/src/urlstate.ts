// What the page's URL remembers, so a reload (or a copied link) comes back to the same place:
// the open document (`open`: its workspace path; `doc`: its id, which resumes an unsaved drawing
// from its autosave), the looks (`style`, `faces`) and the mode. Pure functions; main.ts applies them.
import type { FacesMode, Style } from "./looks-types";

export interface UrlState {
  open: string;
  doc: string;
  style: Style | null;
  faces: FacesMode | null;
  mode: "design" | "preview" | null;
}

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
  };
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
  set("style", s.style, "curves");
  set("faces", s.faces, "none");
  set("mode", s.mode, "design");
  const text = q.toString();
  return text ? `?${text}` : "";
}
