import { describe, expect, it } from "vitest";
import { helpGroups } from "./helpmodel";
import type { Shortcut } from "./shortcuts";

const run = () => {};

describe("helpGroups", () => {
  it("groups shortcuts by what they do and merges the keys of one action", () => {
    const list: Shortcut[] = [
      { key: "d", description: "Design mode", run },
      { key: "z", ctrl: true, description: "Undo", run },
      { key: "z", ctrl: true, shift: true, description: "Redo", run },
      { key: "y", ctrl: true, description: "Redo", run },
      { key: "l", description: "Line tool", run },
      { key: "s", ctrl: true, description: "Save", run },
      { key: "?", description: "Show this help", run },
      { key: "F1", description: "Show this help", run },
    ];
    expect(helpGroups(list)).toEqual([
      { title: "Files", rows: [{ description: "Save", keys: ["Ctrl+S"] }] },
      { title: "Edit", rows: [{ description: "Undo", keys: ["Ctrl+Z"] }, { description: "Redo", keys: ["Ctrl+Shift+Z", "Ctrl+Y"] }] },
      { title: "Tools", rows: [{ description: "Line tool", keys: ["L"] }] },
      { title: "View", rows: [{ description: "Design mode", keys: ["D"] }, { description: "Show this help", keys: ["?", "F1"] }] },
    ]);
  });

  it("has no empty groups", () => {
    expect(helpGroups([])).toEqual([]);
  });
});
