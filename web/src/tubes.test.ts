import * as THREE from "three";
import { describe, expect, it } from "vitest";
import type { Geometry } from "./protocol";
import { DragTubes, ringCount, strided, stripIndices, stripVertices, tubeRadius } from "./tubes";

/** n points of a helix of radius 2 and pitch 3 about the z axis, 1.5 turns, flattened. */
function helix(n: number): Float32Array {
  const out = new Float32Array(3 * n);
  for (let i = 0; i < n; i++) {
    const a = (3 * Math.PI * i) / (n - 1);
    out.set([2 * Math.cos(a), 2 * Math.sin(a), (3 * a) / (2 * Math.PI)], 3 * i);
  }
  return out;
}

function at(a: Float32Array, i: number): THREE.Vector3 {
  return new THREE.Vector3(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
}

describe("stripVertices", () => {
  it("doubles every point, with the unit tangent of central differences and offsets -r, +r", () => {
    const n = 40, r = 0.125, pts = helix(n);
    const pos = new Float32Array(6 * n), tan = new Float32Array(6 * n), across = new Float32Array(2 * n);
    stripVertices(pts, r, pos, tan, across);
    for (let i = 0; i < n; i++) {
      const t = at(pts, Math.min(i + 1, n - 1)).sub(at(pts, Math.max(i - 1, 0))).normalize();
      for (const side of [0, 1]) {
        expect(at(pos, 2 * i + side).distanceTo(at(pts, i))).toBe(0);
        expect(at(tan, 2 * i + side).distanceTo(t)).toBeLessThan(1e-6);
        expect(across[2 * i + side]).toBe(side ? r : -r);
      }
    }
  });

  it("keeps the previous tangent where the neighbours coincide, +z before any", () => {
    const pts = new Float32Array([1, 1, 1, 1, 1, 1, 1, 1, 1, 2, 1, 1, 2, 1, 1, 2, 1, 1]);
    const pos = new Float32Array(36), tan = new Float32Array(36), across = new Float32Array(12);
    stripVertices(pts, 1, pos, tan, across);
    const t = Array.from({ length: 6 }, (_, i) => Array.from(tan.subarray(6 * i, 6 * i + 3)));
    expect(t).toEqual([[0, 0, 1], [0, 0, 1], [1, 0, 0], [1, 0, 0], [1, 0, 0], [1, 0, 0]]);
  });
});

/** A vertex of the strip as tubeStripMaterial's vertex shader places it for an eye at `eye`. */
function shaded(pos: Float32Array, tan: Float32Array, across: Float32Array, i: number, eye: THREE.Vector3): THREE.Vector3 {
  const p = at(pos, i), t = at(tan, i).normalize();
  const s = t.clone().cross(eye.clone().sub(p).normalize()).normalize();
  return p.addScaledVector(s, across[i]);
}

describe("stripIndices", () => {
  it("covers every step with two triangles as wide as the tube, facing the eye unless seen end on", () => {
    const n = 30, pts = helix(n);
    const pos = new Float32Array(6 * n), tan = new Float32Array(6 * n), across = new Float32Array(2 * n);
    stripVertices(pts, 0.1, pos, tan, across);
    const idx = stripIndices(n);
    expect(idx.length).toBe((n - 1) * 2 * 3);
    expect(new Set(idx).size).toBe(2 * n);
    let folded = 0;
    for (const eye of [new THREE.Vector3(20, -30, 12), new THREE.Vector3(-5, 40, -20), new THREE.Vector3(0, 0, 50)]) {
      for (let f = 0; f < idx.length; f += 3) {
        const [a, b, c] = [0, 1, 2].map((j) => shaded(pos, tan, across, idx[f + j], eye));
        const normal = b.clone().sub(a).cross(c.clone().sub(a));
        const centroid = a.clone().add(b).add(c).divideScalar(3);
        // facing the eye wherever the axis is not seen almost end on (there a strip may fold over,
        // hence DoubleSide in the material)
        const endOn = [0, 1, 2].some((j) => Math.abs(at(tan, idx[f + j]).dot(eye.clone().sub(centroid).normalize())) > 0.9);
        if (!endOn) expect(normal.dot(eye.clone().sub(centroid))).toBeGreaterThan(0);
        else folded++;
        // as wide as the tube: each triangle has an edge across, of length 2 r
        const widths = [[a, b], [b, c], [c, a]].map(([p, q]) => p.distanceTo(q));
        expect(widths.some((w) => Math.abs(w - 0.2) < 1e-5)).toBe(true);
      }
    }
    expect(folded).toBeLessThan(3 * (n - 1));   // most triangles were checked (fewer than half end on)
  });
});

describe("strided", () => {
  it("takes every stride-th point and always the last", () => {
    const pts = new Float32Array([0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0, 4, 0, 0, 5, 0, 0]);
    expect(ringCount(6, 2)).toBe(4);
    expect(Array.from(strided(pts, 2)).filter((_, i) => i % 3 === 0)).toEqual([0, 2, 4, 5]);
    expect(Array.from(strided(pts, 1)).filter((_, i) => i % 3 === 0)).toEqual([0, 1, 2, 3, 4, 5]);
    expect(Array.from(strided(pts, 5)).filter((_, i) => i % 3 === 0)).toEqual([0, 5]);
    expect(ringCount(7, 2)).toBe(4);
    expect(ringCount(1, 2)).toBe(1);
  });
});

describe("tubeRadius", () => {
  it("is half of 1.2 % of the bounding-box diagonal", () => {
    expect(tubeRadius([0, 0, 0, 3, 4, 12])).toBeCloseTo(0.078, 12);
  });
});

/** A geometry of one 3-point piece with an identity and a mirrored (x -> -x) replica. */
function geometry(dx: number): { msg: Geometry; data: Float32Array } {
  const data = new Float32Array(9 + 32);
  data.set([dx, 0, 0, 1, 0, 0.5, 2, 0, 1], 0);
  data.set([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], 9);
  data.set([-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1], 25);
  const msg = {
    bounds: [-2, 0, 0, 2, 0, 1],
    pieces: [{ basic: 0, kind: "ogee", labels: ["r0", "m0"], points: { offset: 0, shape: [3, 3], dtype: "f4" },
      transforms: { offset: 9, shape: [2, 16], dtype: "f4" } }],
  } as unknown as Geometry;
  return { msg, data };
}

describe("DragTubes", () => {
  it("instances a piece with all its transforms and rewrites its buffers in place on the next edit", () => {
    const tubes = new DragTubes(() => "#ff0000", 1);
    const a = geometry(0);
    tubes.update(a.msg, a.data);
    const meshes = tubes.group.children as THREE.InstancedMesh[];
    expect(meshes.map((m) => m.count)).toEqual([2]);
    expect(Array.from(meshes[0].instanceMatrix.array)).toEqual(Array.from(a.data.subarray(9, 41)));
    expect("#" + (meshes[0].material as THREE.ShaderMaterial & { color: THREE.Color }).color.getHexString()).toBe("#ff0000");
    const pos = meshes[0].geometry.getAttribute("position") as THREE.BufferAttribute;
    const across = meshes[0].geometry.getAttribute("across") as THREE.BufferAttribute;
    expect(pos.count).toBe(6);   // three stations, each twice
    const r = tubeRadius(a.msg.bounds);   // 0.006 sqrt(17): half of 1.2 % of the diagonal
    expect(Array.from(across.array)).toEqual([-r, r, -r, r, -r, r].map(Math.fround));
    const x0 = pos.array[0];
    const b = geometry(0.25);
    tubes.update(b.msg, b.data);
    expect(tubes.group.children).toEqual(meshes);
    expect(meshes[0].geometry.getAttribute("position")).toBe(pos);
    expect(pos.array[0]).toBeCloseTo(x0 + 0.25, 6);   // station 0 moved with the first point
    tubes.clear();
    expect(tubes.group.children.length).toBe(0);
  });
});
