import { describe, expect, it } from "vitest";
import { readUrlState, writeUrlState } from "./urlstate";

describe("url state", () => {
  it("round trips every field", () => {
    const s = { open: "sub/tn 2.uc", doc: "0123456789abcdef", style: "tube", faces: "picked", mode: "preview" } as const;
    expect(readUrlState(writeUrlState("", s))).toEqual(s);
  });
  it("leaves defaults and empty values out and keeps other parameters", () => {
    expect(writeUrlState("?x=1&open=a.uc", { open: "", doc: "", style: "curves", faces: "none", mode: "design" }))
      .toBe("?x=1");
  });
  it("ignores malformed values", () => {
    expect(readUrlState("?doc=../../etc&style=neon&faces=all&mode=x")).toEqual(
      { open: "", doc: "", style: null, faces: null, mode: null });
  });
});
