import { describe, expect, it } from "vitest";
import { networkObject, replicaCount, replicaPoints, view } from "./geometry";
import type { Geometry } from "./protocol";

// One basic piece (two points) with two replicas: the identity and a quarter turn about (1, 0).
const data = new Float32Array([
  2, 0, 0, 3, 0, 1, // points (2 x 3)
  1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, // identity
  0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 1, -1, 0, 1, // rotate 90 degrees about (1, 0), column-major
]);
const msg: Geometry = {
  revision: 1, path: "x.uc", name: "x", n_curves: 1, n_replicas: 2,
  pieces: [{
    basic: 0, segment: 0, layer: 0, kind: "ogee",
    points: { offset: 0, shape: [2, 3] }, transforms: { offset: 6, shape: [2, 16] },
    labels: ["r0", "r1"], prc: null,
  }],
  intersections: [], bounds: [0, 0, 0, 3, 1, 1], can_undo: false, can_redo: false,
  binary_floats: data.length, id: 0, protocol: 1, type: "geometry",
};

describe("geometry", () => {
  it("slices arrays by reference and refuses out-of-range ones", () => {
    expect(Array.from(view(data, msg.pieces[0].points))).toEqual([2, 0, 0, 3, 0, 1]);
    expect(() => view(data, { offset: 35, shape: [2, 3] })).toThrow(RangeError);
  });

  it("applies replica transforms about the centre, keeping heights", () => {
    expect(Array.from(replicaPoints(data, msg.pieces[0], 0))).toEqual([2, 0, 0, 3, 0, 1]);
    // (2, 0) -> (1, 1) and (3, 0) -> (1, 2) under a quarter turn about (1, 0); z unchanged
    expect(Array.from(replicaPoints(data, msg.pieces[0], 1))).toEqual([1, 1, 0, 1, 2, 1]);
  });

  it("makes one line per replica sharing one geometry", () => {
    const g = networkObject(msg, data);
    expect(replicaCount(msg)).toBe(2);
    expect(g.children.length).toBe(2);
    const [a, b] = g.children as unknown as { geometry: unknown; name: string }[];
    expect(a.geometry).toBe(b.geometry);
    expect(b.name).toBe("0/r1");
  });
});
