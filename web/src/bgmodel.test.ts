import { describe, expect, it } from "vitest";
import { contains, fit, parsePlacement, scaleAbout, storageKey } from "./bgmodel";

describe("background placement", () => {
  it("fits a wide or a tall image into the view", () => {
    expect(fit(1, 2, 10, 4, 0.5)).toEqual({ x: 1, y: 2, width: 7.2, opacity: 0.5, visible: true }); // height-bound
    expect(fit(0, 0, 10, 40, 2).width).toBeCloseTo(9); // width-bound
  });

  it("scales about a point that stays put", () => {
    const p = { x: 0, y: 0, width: 2, opacity: 1, visible: true };
    const q = scaleAbout(p, 1, 1, 2);
    expect(q).toEqual({ x: -1, y: -1, width: 4, opacity: 1, visible: true });
    // the image point under (1, 1) -- the top right corner of p -- is still under it
    expect([q.x + q.width / 2, q.y + q.width / 2]).toEqual([1, 1]);
  });

  it("hit-tests the image", () => {
    const p = { x: 0, y: 0, width: 2, opacity: 1, visible: true };
    expect(contains(p, 0.5, 0.9, 0.4)).toBe(true);
    expect(contains(p, 0.5, 0.9, 0.6)).toBe(false);
  });

  it("is stored per document", () => {
    expect(storageKey({ path: "sub/a.uc", name: "a" })).toBe("auszug.background:sub/a.uc");
    expect(storageKey({ path: "", name: "U.XI.28" })).toBe("auszug.background:name:U.XI.28");
    const p = { x: 1, y: -2, width: 3, opacity: 0.4, visible: false };
    expect(parsePlacement(JSON.stringify(p))).toEqual(p);
    expect(parsePlacement(JSON.stringify({ ...p, opacity: 7 }))?.opacity).toBe(1);
    for (const bad of [null, "", "{", "null", "[]", JSON.stringify({ ...p, width: 0 }), JSON.stringify({ ...p, x: "1" })]) {
      expect(parsePlacement(bad)).toBeNull();
    }
  });
});
