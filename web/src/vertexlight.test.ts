import { describe, expect, it } from "vitest";
import { shadeVertices, type Lighting } from "./vertexlight";

// a grey-free case worked by hand: albedo (pi, pi/2, 0) cancels the 1/pi of the Lambert term
const LIGHT: Lighting = {
  albedo: [Math.PI, Math.PI / 2, 0],
  hemisphere: { up: [0, 0, 1], sky: [1, 1, 1], ground: [0.2, 0.4, 0.6] },
  directional: [{ toward: [0, -0.6, 0.8], color: [2, 3, 4] }],
};

function shade(normals: number[], light = LIGHT, mirrorY = false): number[] {
  const n = normals.length / 3;
  const out = new Float32Array(normals.length + 3).fill(-1);
  shadeVertices(new Float32Array(normals), n, light, out, mirrorY);
  expect(Array.from(out.slice(-3))).toEqual([-1, -1, -1]); // past nVerts: untouched
  return Array.from(out.slice(0, -3));
}

describe("shadeVertices", () => {
  it("is the sky plus the directional light for a normal facing both", () => {
    // n = (0, -0.6, 0.8): the light head on (cos 1), hemisphere weight 0.5 * 0.8 + 0.5 = 0.9
    const [r, g, b] = shade([0, -0.6, 0.8]);
    const hemi = [0.2 + 0.8 * 0.9, 0.4 + 0.6 * 0.9, 0.6 + 0.4 * 0.9];
    expect(r).toBeCloseTo(1 * (hemi[0] + 2), 6);
    expect(g).toBeCloseTo(0.5 * (hemi[1] + 3), 6);
    expect(b).toBe(0);
  });

  it("gives a normal facing away from the light the hemisphere only, and straight down the ground", () => {
    const [r, g] = shade([0, 0, -1]);   // cos -0.8: no direct light; weight 0: the ground colour
    expect(r).toBeCloseTo(0.2, 6);
    expect(g).toBeCloseTo(0.5 * 0.4, 6);
    const [r2] = shade([1, 0, 0]);       // sideways: cos 0, weight 0.5
    expect(r2).toBeCloseTo(0.6, 6);
  });

  it("adds lights: two lights give the sum of each alone (less the hemisphere counted twice)", () => {
    const other = { toward: [1, 0, 0] as const, color: [0.5, 0.25, 1] as const };
    const n = [0.6, -0.48, 0.64];   // unit; faces both lights
    const both = shade(n, { ...LIGHT, directional: [...LIGHT.directional, other] });
    const one = shade(n);
    const two = shade(n, { ...LIGHT, directional: [other] });
    const none = shade(n, { ...LIGHT, directional: [] });
    for (let c = 0; c < 3; c++) expect(both[c]).toBeCloseTo(one[c] + two[c] - none[c], 6);
  });

  it("with mirrorY shades the normals mirrored in y = 0", () => {
    const n = [0.36, 0.48, 0.8, 0, -1, 0, 0.6, 0.8, 0];
    const mirrored = n.map((x, i) => (i % 3 === 1 ? -x : x));
    const a = shade(n, LIGHT, true), b = shade(mirrored);
    for (let i = 0; i < a.length; i++) expect(a[i]).toBeCloseTo(b[i], 6);
    // and it matters: the light is in front (-y), so the mirrored normal (0, +1, 0) of (0, -1, 0) is darker
    expect(a[4]).toBeLessThan(shade(n)[4]);
  });
});
