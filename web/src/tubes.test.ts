import * as THREE from "three";
import { describe, expect, it } from "vitest";
import type { Geometry } from "./protocol";
import { DragTubes, ringCount, strided, sweepTube, tubeIndices, tubeRadius } from "./tubes";

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

describe("sweepTube", () => {
  it("puts every ring at the radius from its point, normal to the tangent, with unit outward normals", () => {
    const n = 40, k = 12, r = 0.125, pts = helix(n);
    const pos = new Float32Array(3 * n * k), nrm = new Float32Array(3 * n * k);
    sweepTube(pts, r, k, pos, nrm);
    for (let i = 0; i < n; i++) {
      const c = at(pts, i);
      const t = at(pts, Math.min(i + 1, n - 1)).sub(at(pts, Math.max(i - 1, 0))).normalize();
      for (let j = 0; j < k; j++) {
        const d = at(pos, i * k + j).sub(c);
        expect(d.length()).toBeCloseTo(r, 6);
        expect(Math.abs(d.dot(t))).toBeLessThan(1e-6);
        const m = at(nrm, i * k + j);
        expect(m.length()).toBeCloseTo(1, 6);
        expect(m.distanceTo(d.divideScalar(r))).toBeLessThan(1e-5);
      }
    }
  });

  it("does not twist along a planar curve (rotation minimising)", () => {
    // a half circle of radius 5 in the plane z = 1: a rotation-minimising frame keeps a constant
    // angle with the plane's normal, so ring point 0 has the same z offset all along
    const n = 33, k = 8, pts = new Float32Array(3 * n);
    for (let i = 0; i < n; i++) {
      const a = (Math.PI * i) / (n - 1);
      pts.set([5 * Math.sin(a), 5 - 5 * Math.cos(a), 1], 3 * i);
    }
    const pos = new Float32Array(3 * n * k), nrm = new Float32Array(3 * n * k);
    sweepTube(pts, 0.5, k, pos, nrm);
    const z0 = nrm[2];
    for (let i = 0; i < n; i++) expect(Math.abs(nrm[3 * i * k + 2] - z0)).toBeLessThan(1e-5);
  });

  it("twists with a helix as a rotation-minimising frame must, not with a fixed axis", () => {
    // a frame made from a fixed axis would keep ring point 0's angle with the tangent's plane
    // fixed; rotation minimising, its change from ring to ring is orthogonal to the tangent
    const n = 200, k = 4, pts = helix(n);
    const pos = new Float32Array(3 * n * k), nrm = new Float32Array(3 * n * k);
    sweepTube(pts, 0.1, k, pos, nrm);
    for (let i = 1; i + 1 < n; i++) {
      const t = at(pts, i + 1).sub(at(pts, i - 1)).normalize();
      const dr = at(nrm, (i + 1) * k).sub(at(nrm, (i - 1) * k));
      // d r / ds has no component along the normal plane's own rotation about t: (dr . (t x r)) ~ 0
      const side = t.clone().cross(at(nrm, i * k));
      expect(Math.abs(dr.dot(side))).toBeLessThan(2e-3);
    }
  });
});

describe("tubeIndices", () => {
  it("winds every triangle of a straight tube outwards and uses every vertex", () => {
    const n = 5, k = 6, pts = new Float32Array(3 * n);
    for (let i = 0; i < n; i++) pts.set([i, 0, 0], 3 * i);
    const pos = new Float32Array(3 * n * k), nrm = new Float32Array(3 * n * k);
    sweepTube(pts, 1, k, pos, nrm);
    const idx = tubeIndices(n, k);
    expect(idx.length).toBe((n - 1) * k * 2 * 3);
    expect(new Set(idx).size).toBe(n * k);
    for (let f = 0; f < idx.length; f += 3) {
      const a = at(pos, idx[f]), b = at(pos, idx[f + 1]), c = at(pos, idx[f + 2]);
      const normal = b.clone().sub(a).cross(c.clone().sub(a));
      const centroid = a.add(b).add(c).divideScalar(3);
      const radial = new THREE.Vector3(0, centroid.y, centroid.z);
      expect(normal.dot(radial)).toBeGreaterThan(0);
    }
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
  it("instances a piece per handedness and rewrites its buffers in place on the next edit", () => {
    const red = new THREE.MeshStandardMaterial({ color: "#ff0000" });
    const tubes = new DragTubes(() => red, 8, 1);
    const a = geometry(0);
    tubes.update(a.msg, a.data);
    const meshes = tubes.group.children as THREE.InstancedMesh[];
    expect(meshes.map((m) => m.count)).toEqual([1, 1]);
    // the mirrored replica shares positions and normals, its triangles wound the other way
    expect(meshes[1].geometry.getAttribute("position")).toBe(meshes[0].geometry.getAttribute("position"));
    const i0 = meshes[0].geometry.index!.array, i1 = meshes[1].geometry.index!.array;
    expect([i1[0], i1[1], i1[2]]).toEqual([i0[0], i0[2], i0[1]]);
    expect(meshes[1].instanceMatrix.array[0]).toBe(-1);
    const pos = meshes[0].geometry.getAttribute("position") as THREE.BufferAttribute;
    const x0 = pos.array[0];
    const b = geometry(0.25);
    tubes.update(b.msg, b.data);
    expect(tubes.group.children).toEqual(meshes);
    expect(meshes[0].geometry.getAttribute("position")).toBe(pos);
    expect(pos.array[0]).toBeCloseTo(x0 + 0.25, 6);   // ring 0 moved with the first point
    tubes.clear();
    expect(tubes.group.children.length).toBe(0);
  });
});
