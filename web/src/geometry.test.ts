import { describe, expect, it } from "vitest";
import { layoutKey, replicaCount, replicaPoints, transforms, view, viewAny } from "./geometry";
import type { Geometry } from "./protocol";

// One basic piece (two points) with two replicas: the identity and a quarter turn about (1, 0).
const data = new Float32Array([
  2, 0, 0, 3, 0, 1, // points (2 x 3)
  1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, // identity
  0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 1, -1, 0, 1, // rotate 90 degrees about (1, 0), column-major
  0, 0, 1, 1, // side view (2 x 2)
]);
const msg: Geometry = {
  revision: 1, path: "x.uc", name: "x", n_curves: 1, n_replicas: 2,
  pieces: [{
    basic: 0, segment: 0, layer: 0, kind: "ogee",
    points: { offset: 0, shape: [2, 3], dtype: "f4" }, transforms: { offset: 6, shape: [2, 16], dtype: "f4" },
    side: { offset: 38, shape: [2, 2], dtype: "f4" }, labels: ["r0", "r1"], prc: null, prc_s: null,
  }],
  intersections: [], curves: [], layers: [0], bounds: [0, 0, 0, 3, 1, 1], can_undo: false, can_redo: false,
  dirty: false, recoverable: "", doc: "0123456789abcdef", binary_floats: data.length, id: 0, protocol: 2, type: "geometry",
};

describe("geometry", () => {
  it("slices arrays by reference and refuses out-of-range ones", () => {
    expect(Array.from(view(data, msg.pieces[0].points))).toEqual([2, 0, 0, 3, 0, 1]);
    expect(() => view(data, { offset: 41, shape: [2, 3], dtype: "f4" })).toThrow(RangeError);
  });

  it("reads u4 and f4 arrays from one buffer", () => {
    const buf = new ArrayBuffer(16);
    new Float32Array(buf, 0, 2).set([1.5, -2]);
    new Uint32Array(buf, 8, 2).set([7, 4000000000]);
    expect(Array.from(viewAny(buf, { offset: 0, shape: [2], dtype: "f4" }))).toEqual([1.5, -2]);
    expect(Array.from(viewAny(buf, { offset: 2, shape: [2], dtype: "u4" }))).toEqual([7, 4000000000]);
    expect(() => viewAny(buf, { offset: 3, shape: [2], dtype: "u4" })).toThrow(RangeError);
  });

  it("applies replica transforms about the centre, keeping heights", () => {
    expect(Array.from(replicaPoints(data, msg.pieces[0], 0))).toEqual([2, 0, 0, 3, 0, 1]);
    // (2, 0) -> (1, 1) and (3, 0) -> (1, 2) under a quarter turn about (1, 0); z unchanged
    expect(Array.from(replicaPoints(data, msg.pieces[0], 1))).toEqual([1, 1, 0, 1, 2, 1]);
    expect(transforms(data, msg.pieces[0]).length).toBe(2);
  });

  it("counts replicas and keys the layout by piece sizes", () => {
    expect(replicaCount(msg)).toBe(2);
    const moved = { ...msg, pieces: [{ ...msg.pieces[0], points: { ...msg.pieces[0].points, shape: [3, 3] } }] };
    expect(layoutKey(moved)).not.toBe(layoutKey(msg));
    expect(layoutKey({ ...msg, revision: 2 })).toBe(layoutKey(msg));
  });
});
