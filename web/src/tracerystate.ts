// The tracery page's state: a style (built-in name or "prototype") or a workspace style file, and
// the values set on it (`KEY=VALUE`, as `auszug tracery --set` reads them). The server keeps no tracery
// state, so this is all there is: it goes into the URL, and undo / redo are a list of them.
// Pure functions; tracery.ts applies them.

export interface TraceryState {
  style: string;
  path: string;
  values: string[];
}

export const DEFAULT_STATE: TraceryState = { style: "fig20a", path: "", values: [] };
const NAME = /^[A-Za-z0-9_.-]{1,64}$/;

/** `values` with `key` set to `value` (a later value of a key replaces the earlier one, in place). */
export function withValue(values: readonly string[], key: string, value: string): string[] {
  const out = values.filter((v) => v.slice(0, v.indexOf("=")) !== key);
  const at = values.findIndex((v) => v.slice(0, v.indexOf("=")) === key);
  const item = `${key}=${value}`;
  if (at < 0) return [...out, item];
  out.splice(Math.min(at, out.length), 0, item);
  return out;
}

/** The state in a URL's query (`style`, `path`, `v` repeated); malformed parts are ignored. */
export function readTraceryUrl(search: string): TraceryState {
  const q = new URLSearchParams(search);
  const style = q.get("style") ?? "";
  const path = q.get("path") ?? "";
  const values = q.getAll("v").filter((v) => v.indexOf("=") > 0).slice(0, 64);
  return { style: NAME.test(style) ? style : path ? "" : DEFAULT_STATE.style, path, values };
}

/** `search` with the tracery state written into it (other parameters kept). */
export function writeTraceryUrl(search: string, s: TraceryState): string {
  const q = new URLSearchParams(search);
  for (const k of ["style", "path", "v"]) q.delete(k);
  if (s.path) q.set("path", s.path);
  else q.set("style", s.style);
  for (const v of s.values) q.append("v", v);
  const text = q.toString();
  return text ? `?${text}` : "";
}

/** Undo / redo of whole states: `push` after a change the server accepted. */
export class History {
  private past: TraceryState[] = [];
  private future: TraceryState[] = [];
  constructor(private limit = 200) {}

  get canUndo(): boolean {
    return this.past.length > 0;
  }

  get canRedo(): boolean {
    return this.future.length > 0;
  }

  /** Remember `before` (the state the accepted change replaced). */
  push(before: TraceryState): void {
    this.past.push(before);
    if (this.past.length > this.limit) this.past.shift();
    this.future = [];
  }

  /** The state to go back to from `now` (null: none); `commit` it once the server built it. */
  undo(now: TraceryState): { target: TraceryState; commit(): void } | null {
    const target = this.past[this.past.length - 1];
    if (!target) return null;
    return { target, commit: () => { this.past.pop(); this.future.push(now); } };
  }

  redo(now: TraceryState): { target: TraceryState; commit(): void } | null {
    const target = this.future[this.future.length - 1];
    if (!target) return null;
    return { target, commit: () => { this.future.pop(); this.past.push(now); } };
  }
}
