import { describe, expect, it } from "vitest";
import { History, readTraceryUrl, withValue, writeTraceryUrl } from "./tracerystate";

describe("tracery state", () => {
  it("replaces a key's value in place", () => {
    expect(withValue(["a=1", "b=2"], "a", "3")).toEqual(["a=3", "b=2"]);
    expect(withValue(["a=1"], "b", "2")).toEqual(["a=1", "b=2"]);
  });

  it("round-trips through the URL and keeps other parameters", () => {
    const s = { style: "fig20h", path: "", values: ["params.excess=1.2", "circle.orientation=lying"] };
    const search = writeTraceryUrl("?x=1", s);
    expect(search.startsWith("?x=1&")).toBe(true);
    expect(readTraceryUrl(search)).toEqual(s);
    const f = { style: "", path: "styles/my window.toml", values: [] };
    expect(readTraceryUrl(writeTraceryUrl("", f))).toEqual(f);
  });

  it("ignores malformed parts", () => {
    expect(readTraceryUrl("?style=<script>&v=novalue&v=a%3D1")).toEqual({ style: "fig20a", path: "", values: ["a=1"] });
  });

  it("undoes and redoes whole states, only when committed", () => {
    const h = new History();
    const a = { style: "fig20a", path: "", values: [] }, b = { style: "fig20a", path: "", values: ["x=1"] };
    h.push(a);
    const u = h.undo(b)!;
    expect(u.target).toEqual(a);
    expect(h.canRedo).toBe(false);
    u.commit();
    expect(h.canUndo).toBe(false);
    const r = h.redo(a)!;
    expect(r.target).toEqual(b);
    r.commit();
    expect(h.canUndo).toBe(true);
  });
});
