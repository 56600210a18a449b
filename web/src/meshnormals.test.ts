import { describe, expect, it } from "vitest";
import { vertexNormals } from "./meshnormals";

describe("vertexNormals", () => {
  it("gives a flat square's normal at each vertex, and leaves the rest of the buffer alone", () => {
    // a unit square in the x-z plane, counter-clockwise seen from -y: normal (0, -1, 0)
    const pos = new Float32Array([0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1, 9, 9, 9]);
    const idx = new Uint32Array([0, 1, 2, 0, 2, 3, 4, 4, 4]);
    const out = new Float32Array(15).fill(7);
    vertexNormals(pos, idx, 4, 2, out);
    for (let i = 0; i < 4; i++) expect(Array.from(out.slice(3 * i, 3 * i + 3))).toEqual([0, -1, 0]);
    expect(Array.from(out.slice(12))).toEqual([7, 7, 7]);
  });

  it("weights faces by their area at a shared vertex", () => {
    // two triangles at vertex 0: a big one in the x-y plane (normal +z), a small one in the x-z plane (-y)
    const pos = new Float32Array([0, 0, 0, 2, 0, 0, 0, 2, 0, 1, 0, 0, 0, 0, 1]);
    const idx = new Uint32Array([0, 1, 2, 0, 3, 4]);
    const out = new Float32Array(15);
    vertexNormals(pos, idx, 5, 2, out);
    const n = Array.from(out.slice(0, 3));
    expect(n[0]).toBeCloseTo(0);
    expect(n[1]).toBeCloseTo(-1 / Math.hypot(1, 4));
    expect(n[2]).toBeCloseTo(4 / Math.hypot(1, 4));
  });
});
