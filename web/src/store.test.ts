import { describe, expect, it } from "vitest";
import type { CurveInfo, Geometry } from "./protocol";
import { NO_COLOR, Store } from "./store";

/** A geometry message with curves of the given server colours (the fields colour() reads). */
function geometry(colors: string[]): Geometry {
  const curves = colors.map((color) => ({ color }) as CurveInfo);
  return { curves, n_curves: curves.length } as Geometry;
}

describe("curve colours", () => {
  it("come from the server's palette unless the user chose one", () => {
    const s = new Store();
    expect(s.color(0)).toBe(NO_COLOR);                       // no geometry yet
    s.geometry = geometry(["#0072B2", "#D55E00"]);           // auszug.formats.palette.PALETTE[:2]
    expect([s.color(0), s.color(1), s.color(2)]).toEqual(["#0072b2", "#d55e00", NO_COLOR]);
    s.setLooks({ colors: ["", "#AABBCC"] });
    expect([s.color(0), s.color(1)]).toEqual(["#0072b2", "#aabbcc"]);
  });
});
