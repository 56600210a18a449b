import type * as THREE from "three";
import { afterEach, beforeEach, describe, expect, it, vi } from "vitest";
import { Debouncer, MeshView, pickLoop, pieceArrays, reversedWinding, splitHandedness, type ScreenLoop } from "./meshes";
import type { MeshGeometry } from "./protocol";

// One triangle (3 vertices, 1 face) with two instances (identity, shifted by x + 1), and faces.
function frame(index = 2): { msg: MeshGeometry; buffer: ArrayBuffer } {
  const buffer = new ArrayBuffer(4 * (9 + 3 + 32 + 9 + 3 + 16));
  const f = new Float32Array(buffer), u = new Uint32Array(buffer);
  f.set([0, 0, 0, 1, 0, 0, 0, 1, 0], 0);
  u.set([0, 1, index], 9);
  f.set([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], 12);
  f.set([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1], 28);
  f.set([0, 0, 1, 1, 0, 1, 0, 1, 1], 44);
  u.set([0, 2, 1], 53);
  f.set([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], 56);
  const msg: MeshGeometry = {
    revision: 3, style: "tube", faces: 1, converged: true, residual: 0, binary_floats: 72, id: 1, type: "mesh",
    pieces: [
      { basic: 0, name: "0/ogee0", positions: { offset: 0, shape: [3, 3], dtype: "f4" },
        indices: { offset: 9, shape: [1, 3], dtype: "u4" }, transforms: { offset: 12, shape: [2, 16], dtype: "f4" } },
      { basic: -1, name: "faces", positions: { offset: 44, shape: [3, 3], dtype: "f4" },
        indices: { offset: 53, shape: [1, 3], dtype: "u4" }, transforms: { offset: 56, shape: [1, 16], dtype: "f4" } },
    ],
  };
  return { msg, buffer };
}

describe("pieceArrays", () => {
  it("slices positions, indices and transforms as views", () => {
    const { msg, buffer } = frame();
    const [members, faces] = pieceArrays(msg, buffer);
    expect(members.count).toBe(2);
    expect(Array.from(members.indices)).toEqual([0, 1, 2]);
    expect(members.matrices[16 + 12]).toBe(1); // the second instance's x translation
    expect(members.positions.buffer).toBe(buffer);
    expect(faces.basic).toBe(-1);
    expect(Array.from(faces.indices)).toEqual([0, 2, 1]);
  });

  it("refuses indices past the vertices and wrong dtypes", () => {
    const bad = frame(3);
    expect(() => pieceArrays(bad.msg, bad.buffer)).toThrow(/index 3/);
    const { msg, buffer } = frame();
    msg.pieces[0].indices.dtype = "f4";
    expect(() => pieceArrays(msg, buffer)).toThrow(RangeError);
  });
});

describe("MeshView", () => {
  it("draws each piece as one instanced mesh and reuses its buffers for a reply of the same sizes", () => {
    const view = new MeshView(() => "#7a2e1d");
    const { msg, buffer } = frame();
    view.show(msg, buffer);
    expect(view.counts).toEqual([2, 1]);
    const first = view.group.children[0];
    new Float32Array(buffer)[3] = 2; // move a vertex
    view.show(msg, buffer);
    expect(view.group.children[0]).toBe(first);
    const pos = (first as unknown as { geometry: { getAttribute(n: string): { array: Float32Array } } }).geometry;
    expect(pos.getAttribute("position").array[3]).toBe(2);
    view.clear();
    expect(view.group.children.length).toBe(0);
  });

  it("draws mirrored instances from a geometry wound the other way that shares positions and normals", () => {
    const view = new MeshView(() => "#7a2e1d");
    const { msg, buffer } = frame();
    new Float32Array(buffer)[28] = -1; // the second instance mirrors x
    view.show(msg, buffer);
    expect(view.counts).toEqual([2, 1]);
    const [rot, mir] = view.group.children as unknown as { count: number; geometry: THREE.BufferGeometry }[];
    expect([rot.count, mir.count]).toEqual([1, 1]);
    expect(mir.geometry.getAttribute("position")).toBe(rot.geometry.getAttribute("position"));
    expect(mir.geometry.getAttribute("normal")).toBe(rot.geometry.getAttribute("normal"));
    expect(Array.from(mir.geometry.index!.array)).toEqual([0, 2, 1]);
  });
});

describe("handedness", () => {
  it("splits rotations from mirror images and reverses windings", () => {
    const id = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
    const quarter = [0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 2, 0, 0, 1];
    const mirror = [1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
    const { proper, mirrored } = splitHandedness(new Float32Array([...id, ...mirror, ...quarter]));
    expect(Array.from(proper)).toEqual([...id, ...quarter]);
    expect(Array.from(mirrored)).toEqual(mirror);
    expect(Array.from(reversedWinding(new Uint32Array([0, 1, 2, 3, 4, 5])))).toEqual([0, 2, 1, 3, 5, 4]);
  });
});

describe("Debouncer", () => {
  beforeEach(() => vi.useFakeTimers());
  afterEach(() => vi.useRealTimers());

  it("asks once after the last change and never twice at a time", async () => {
    const replies: (() => void)[] = [];
    const run = vi.fn(() => new Promise<void>((r) => replies.push(r)));
    const d = new Debouncer(run, 120);
    d.poke();
    await vi.advanceTimersByTimeAsync(100);
    d.poke(); // postpones
    await vi.advanceTimersByTimeAsync(100);
    expect(run).toHaveBeenCalledTimes(0);
    await vi.advanceTimersByTimeAsync(20);
    expect(run).toHaveBeenCalledTimes(1);
    d.poke();
    d.poke();
    await vi.advanceTimersByTimeAsync(500); // the timer fires while the first is in flight
    expect(run).toHaveBeenCalledTimes(1);
    expect(d.inFlight).toBe(true);
    replies[0]();
    await vi.advanceTimersByTimeAsync(0);
    expect(run).toHaveBeenCalledTimes(2); // asked again at once for the change during the flight
    replies[1]();
    await vi.advanceTimersByTimeAsync(500);
    expect(run).toHaveBeenCalledTimes(2);
  });

  it("keeps going after a failed request and forgets cancelled changes", async () => {
    const run = vi.fn(() => Promise.reject(new Error("no")));
    const d = new Debouncer(run, 50);
    d.poke();
    await vi.advanceTimersByTimeAsync(50);
    expect(run).toHaveBeenCalledTimes(1);
    expect(d.inFlight).toBe(false);
    d.poke();
    d.cancel();
    await vi.advanceTimersByTimeAsync(100);
    expect(run).toHaveBeenCalledTimes(1);
  });
});

describe("pickLoop", () => {
  const square = (x: number, y: number, s: number): ScreenLoop => ({
    boundary: [[x, y], [x + s, y], [x + s, y + s], [x, y + s]], centre: [x + s / 2, y + s / 2],
  });
  const loops = [square(0, 0, 100), square(10, 10, 30), square(200, 0, 50)];

  it("prefers a centre, then the smallest loop around the click, then a near boundary", () => {
    expect(pickLoop(loops, [52, 48])).toBe(0); // the big square's centre
    expect(pickLoop(loops, [15, 15])).toBe(1); // inside both squares: the smaller
    expect(pickLoop(loops, [80, 80])).toBe(0);
    expect(pickLoop(loops, [195, 20])).toBe(2); // 5 px left of the third's edge
    expect(pickLoop(loops, [150, 300])).toBeNull();
  });
});
