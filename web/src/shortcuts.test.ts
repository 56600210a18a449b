import { describe, expect, it } from "vitest";
import { match, type Shortcut } from "./shortcuts";

const run = () => {};
const list: Shortcut[] = [
  { key: "p", description: "Preview mode", run },
  { key: "?", description: "Show this help", run },
  { key: "z", ctrl: true, description: "Undo", run },
  { key: "z", ctrl: true, shift: true, description: "Redo", run },
];

/** A keydown as the browser gives it, from `target` (document.body when not typing). */
function key(k: string, target: object, mods: { ctrl?: boolean; shift?: boolean } = {}): KeyboardEvent {
  return { key: k, ctrlKey: !!mods.ctrl, metaKey: false, shiftKey: !!mods.shift, target } as unknown as KeyboardEvent;
}

const body = { tagName: "BODY", isContentEditable: false };
const field = (tagName: string, type = "") => ({ tagName, type, isContentEditable: false });

describe("match", () => {
  it("finds the shortcut of a key outside text fields", () => {
    expect(match(key("p", body), list)?.description).toBe("Preview mode");
    expect(match(key("?", body, { shift: true }), list)?.description).toBe("Show this help");
    expect(match(key("Z", body, { ctrl: true, shift: true }), list)?.description).toBe("Redo");
    expect(match(key("z", body, { ctrl: true }), list)?.description).toBe("Undo");
    expect(match(key("z", body), list)).toBeNull();
  });

  it("fires nothing while typing in a text field", () => {
    for (const target of [field("INPUT", "text"), field("INPUT", "search"), field("INPUT", "number"), field("TEXTAREA"),
      { tagName: "DIV", isContentEditable: true }]) {
      expect(match(key("p", target), list)).toBeNull();
      expect(match(key("?", target, { shift: true }), list)).toBeNull();
      expect(match(key("z", target, { ctrl: true }), list)).toBeNull();
    }
  });

  it("still fires from buttons, checkboxes and sliders", () => {
    for (const target of [field("BUTTON"), field("INPUT", "checkbox"), field("INPUT", "range")]) {
      expect(match(key("p", target), list)?.description).toBe("Preview mode");
    }
  });
});
