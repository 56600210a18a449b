// Tubes swept in the page around the geometry's own polylines, for the tube look while the drawing
// changes: a drag's every edit shows its tubes in the frame that shows its lines, without waiting
// for the server's mesh (debounced, Looks). They are coarser (DRAG_AROUND points round the
// profile, every DRAG_STRIDE-th point of the polyline along it) and open at the ends; the server's mesh (the one
// the exports use) replaces them as soon as it arrives for the current revision. Each geometry
// piece is one BufferGeometry drawn by InstancedMeshes with the piece's transforms; an edit that
// keeps the layout rewrites the buffers in place (no GPU resources per edit).
import * as THREE from "three";
import { layoutKey, view } from "./geometry";
import { reversedWinding, splitHandedness } from "./meshes";
import type { Geometry } from "./protocol";

/** Points round a tube's profile while the page sweeps it (the server's tubes have 40). */
export const DRAG_AROUND = 6;
/** Along a piece, every DRAG_STRIDE-th point of its polyline (and its last) is a ring. */
export const DRAG_STRIDE = 2;
/** Tube diameter as a share of the bounding-box diagonal: the server's default member size
 * (auszug.meshing.sweep.default_size). */
export const SIZE_SHARE = 0.012;

/** The tube radius of a geometry's bounds [x0, y0, z0, x1, y1, z1]: half the default member size. */
export function tubeRadius(bounds: readonly number[]): number {
  const d = Math.hypot(bounds[3] - bounds[0], bounds[4] - bounds[1], bounds[5] - bounds[2]);
  return (SIZE_SHARE * d) / 2;
}

/** Every `stride`-th point of `points` ((n, 3) flattened) and the last: the rings of a tube. */
export function strided(points: Float32Array, stride: number, out?: Float32Array): Float32Array {
  const n = points.length / 3, m = ringCount(n, stride);
  const res = out ?? new Float32Array(3 * m);
  for (let i = 0; i < m; i++) {
    const k = 3 * Math.min(i * stride, n - 1);
    res[3 * i] = points[k]; res[3 * i + 1] = points[k + 1]; res[3 * i + 2] = points[k + 2];
  }
  return res;
}

/** The rings of a tube along `n` points taking every `stride`-th (and the last). */
export function ringCount(n: number, stride: number): number {
  return n <= 1 ? n : Math.ceil((n - 1) / stride) + 1;
}

/**
 * Triangles of a tube of `n` rings of `k` points (vertex i * k + j: ring i, point j), wound so
 * that they face outwards for the frames `sweepTube` uses: ((n - 1) * k * 2, 3) flattened.
 */
export function tubeIndices(n: number, k: number): Uint32Array {
  const out = new Uint32Array(Math.max(n - 1, 0) * k * 6);
  let o = 0;
  for (let i = 0; i + 1 < n; i++) {
    for (let j = 0; j < k; j++) {
      const a = i * k + j, b = i * k + ((j + 1) % k), c = a + k, d = b + k;
      out[o++] = a; out[o++] = b; out[o++] = c;
      out[o++] = b; out[o++] = d; out[o++] = c;
    }
  }
  return out;
}

/**
 * Sweep a circle of `radius` with `k` points along the polyline `points` ((n, 3) flattened):
 * ring i lies in the plane through point i normal to the tangent there (central differences,
 * one-sided at the ends), its frames rotation minimising (double reflection). Writes (n * k, 3)
 * positions and unit outward normals into `pos` and `nrm` (each at least 3 n k long).
 */
export function sweepTube(points: Float32Array, radius: number, k: number, pos: Float32Array, nrm: Float32Array): void {
  const n = points.length / 3;
  const t = new THREE.Vector3(), tPrev = new THREE.Vector3(), u = new THREE.Vector3(), w = new THREE.Vector3();
  const v1 = new THREE.Vector3(), r = new THREE.Vector3(), rL = new THREE.Vector3(), tL = new THREE.Vector3();
  const p = new THREE.Vector3(), q = new THREE.Vector3();
  const tangent = (i: number, out: THREE.Vector3) => {
    const a = Math.max(i - 1, 0), b = Math.min(i + 1, n - 1);
    out.set(points[3 * b] - points[3 * a], points[3 * b + 1] - points[3 * a + 1], points[3 * b + 2] - points[3 * a + 2]);
    const len = out.length();
    return len > 0 ? out.divideScalar(len) : null;
  };
  for (let i = 0; i < n; i++) {
    if (!tangent(i, t)) t.copy(i > 0 ? tPrev : new THREE.Vector3(0, 0, 1));
    if (i === 0) {
      // any normal to the first tangent: the world axis least along it, made perpendicular
      const ax = Math.abs(t.x), ay = Math.abs(t.y), az = Math.abs(t.z);
      r.set(ax <= ay && ax <= az ? 1 : 0, ay < ax && ay <= az ? 1 : 0, az < ax && az < ay ? 1 : 0);
      r.addScaledVector(t, -r.dot(t)).normalize();
    } else {
      // double reflection (Wang, Juettler, Zheng, Liu 2008): carry the previous frame's normal over
      p.set(points[3 * i], points[3 * i + 1], points[3 * i + 2]);
      q.set(points[3 * i - 3], points[3 * i - 2], points[3 * i - 1]);
      v1.subVectors(p, q);
      const c1 = v1.dot(v1);
      if (c1 > 0) {
        rL.copy(r).addScaledVector(v1, (-2 / c1) * v1.dot(r));
        tL.copy(tPrev).addScaledVector(v1, (-2 / c1) * v1.dot(tPrev));
        const v2 = w.subVectors(t, tL), c2 = v2.dot(v2);
        r.copy(rL);
        if (c2 > 0) r.addScaledVector(v2, (-2 / c2) * v2.dot(rL));
      }
      r.addScaledVector(t, -r.dot(t)).normalize();   // against rounding drift
    }
    u.crossVectors(t, r);   // r, u, t: right handed
    const px = points[3 * i], py = points[3 * i + 1], pz = points[3 * i + 2];
    for (let j = 0; j < k; j++) {
      const a = (2 * Math.PI * j) / k, ca = Math.cos(a), sa = Math.sin(a);
      const nx = ca * r.x + sa * u.x, ny = ca * r.y + sa * u.y, nz = ca * r.z + sa * u.z;
      const o = 3 * (i * k + j);
      nrm[o] = nx; nrm[o + 1] = ny; nrm[o + 2] = nz;
      pos[o] = px + radius * nx; pos[o + 1] = py + radius * ny; pos[o + 2] = pz + radius * nz;
    }
    tPrev.copy(t);
  }
}

interface Entry {
  basic: number;
  geoms: THREE.BufferGeometry[];
  meshes: THREE.InstancedMesh[];
}

/** The page's own tubes of the last geometry, coloured like the server's meshes. */
export class DragTubes {
  readonly group = new THREE.Group();
  private entries: Entry[] = [];
  private layout = "";
  private layers: readonly number[] = [0];

  private rings: Float32Array = new Float32Array(0);

  constructor(private material: (basic: number) => THREE.Material, private around = DRAG_AROUND,
    private stride = DRAG_STRIDE) {
    this.group.name = "drag-tubes";
  }

  /** Sweep the tubes of `msg` (its points in `data`), in place when the layout is unchanged. */
  update(msg: Geometry, data: Float32Array): void {
    const radius = tubeRadius(msg.bounds);
    const key = layoutKey(msg);
    const splits = msg.pieces.map((p) => splitHandedness(view(data, p.transforms)));
    const sameCounts = splits.every((s, i) => {
      const e = this.entries[i];
      return !!e && e.meshes.length === (s.proper.length ? 1 : 0) + (s.mirrored.length ? 1 : 0) &&
        e.meshes.every((m, j) => m.count * 16 === [s.proper, s.mirrored].filter((x) => x.length)[j].length);
    });
    if (key !== this.layout || !sameCounts) this.rebuild(msg, data, splits);
    msg.pieces.forEach((p, i) => {
      const e = this.entries[i];
      const pos = e.geoms[0].getAttribute("position") as THREE.BufferAttribute;
      const nrm = e.geoms[0].getAttribute("normal") as THREE.BufferAttribute;
      const pts = view(data, p.points), n = ringCount(pts.length / 3, this.stride);
      if (this.rings.length < 3 * n) this.rings = new Float32Array(3 * n);
      const rings = strided(pts, this.stride, this.rings.subarray(0, 3 * n));
      sweepTube(rings, radius, this.around, pos.array as Float32Array, nrm.array as Float32Array);
      pos.needsUpdate = true;
      nrm.needsUpdate = true;
      const matrices = [splits[i].proper, splits[i].mirrored].filter((m) => m.length);
      e.meshes.forEach((mesh, j) => {
        (mesh.instanceMatrix.array as Float32Array).set(matrices[j]);
        mesh.instanceMatrix.needsUpdate = true;
      });
    });
  }

  private rebuild(msg: Geometry, data: Float32Array, splits: { proper: Float32Array; mirrored: Float32Array }[]): void {
    this.clear();
    const k = this.around;
    msg.pieces.forEach((p, i) => {
      const n = ringCount(p.points.shape[0], this.stride);
      const geom = new THREE.BufferGeometry();
      geom.setAttribute("position", new THREE.BufferAttribute(new Float32Array(3 * n * k), 3));
      geom.setAttribute("normal", new THREE.BufferAttribute(new Float32Array(3 * n * k), 3));
      const indices = tubeIndices(n, k);
      geom.setIndex(new THREE.BufferAttribute(indices, 1));
      const entry: Entry = { basic: p.basic, geoms: [geom], meshes: [] };
      if (splits[i].mirrored.length) {
        const flipped = new THREE.BufferGeometry();
        flipped.setAttribute("position", geom.getAttribute("position"));
        flipped.setAttribute("normal", geom.getAttribute("normal"));
        flipped.setIndex(new THREE.BufferAttribute(reversedWinding(indices), 1));
        entry.geoms.push(flipped);
      }
      [splits[i].proper, splits[i].mirrored].forEach((matrices, j) => {
        if (!matrices.length) return;
        const mesh = new THREE.InstancedMesh(entry.geoms[j], this.material(p.basic), matrices.length / 16);
        mesh.name = `${p.basic}/${p.kind}`;
        mesh.userData.basic = p.basic;
        mesh.frustumCulled = false;
        this.setObjectLayers(mesh);
        this.group.add(mesh);
        entry.meshes.push(mesh);
      });
      this.entries.push(entry);
    });
    this.layout = layoutKey(msg);
  }

  /** Re-apply the materials (colours, selection). */
  recolor(): void {
    for (const e of this.entries) for (const m of e.meshes) m.material = this.material(e.basic);
  }

  setLayers(layers: readonly number[]): void {
    this.layers = layers;
    for (const e of this.entries) for (const m of e.meshes) this.setObjectLayers(m);
  }

  private setObjectLayers(o: THREE.Object3D): void {
    o.layers.disableAll();
    for (const l of this.layers) o.layers.enable(l);
  }

  /** Remove and dispose every tube. */
  clear(): void {
    for (const e of this.entries) {
      for (const g of e.geoms) g.dispose();
      for (const m of e.meshes) m.dispose();
    }
    this.group.clear();
    this.entries = [];
    this.layout = "";
  }
}
