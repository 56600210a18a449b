import { describe, expect, it } from "vitest";
import { wrapWords } from "./wrap";

describe("wrapWords", () => {
  it("keeps every word, in order, within the line length", () => {
    const text = "Drag points and handles; click an intersection to put the PRC there. Delete removes the curve.";
    const lines = wrapWords(text, 40);
    expect(lines.join(" ")).toBe(text);
    for (const line of lines) expect(line.length).toBeLessThanOrEqual(40);
    expect(lines).toEqual([
      "Drag points and handles; click an",
      "intersection to put the PRC there.",
      "Delete removes the curve.",
    ]);
  });
  it("leaves a short text on one line and a long word alone", () => {
    expect(wrapWords("Esc cancels.", 40)).toEqual(["Esc cancels."]);
    expect(wrapWords("a abcdefghij b", 5)).toEqual(["a", "abcdefghij", "b"]);
    expect(wrapWords("", 5)).toEqual([]);
  });
});
