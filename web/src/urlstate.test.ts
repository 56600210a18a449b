import { describe, expect, it } from "vitest";
import { readUrlState, writeUrlState } from "./urlstate";

describe("url state", () => {
  it("round trips every field", () => {
    const s = { open: "sub/tn 2.uc", doc: "0123456789abcdef", style: "ribbon", faces: "picked", mode: "preview", split: 0.375 } as const;
    expect(readUrlState(writeUrlState("", s))).toEqual(s);
  });
  it("leaves defaults and empty values out and keeps other parameters", () => {
    expect(writeUrlState("?x=1&open=a.uc", { open: "", doc: "", style: "tube", faces: "none", mode: "design", split: 0.5 }))
      .toBe("?x=1");
  });
  it("ignores malformed values", () => {
    expect(readUrlState("?doc=../../etc&style=neon&faces=all&mode=x&split=0.9")).toEqual(
      { open: "", doc: "", style: null, faces: null, mode: null, split: null });
    expect(readUrlState("?split=1e-1").split).toBe(null);
    expect(readUrlState("?split=.25").split).toBe(0.25);
  });
  it("writes the split rounded, and a non-default style", () => {
    const s = { open: "", doc: "", style: "curves", faces: "none", mode: "design", split: 0.6666666 } as const;
    expect(writeUrlState("", s)).toBe("?style=curves&split=0.667");
  });
});
