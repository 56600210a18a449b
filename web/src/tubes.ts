// Tubes drawn by the page around the geometry's own polylines, for the tube look while the drawing
// changes: a drag's every edit shows its tubes in the frame that shows its lines, without waiting
// for the server's mesh (debounced, Looks); the server's mesh (the one the exports use) replaces
// them as soon as it arrives for the current revision. Each tube is a strip along the polyline
// that the vertex shader turns to face the camera and the fragment shader shades as a round tube
// (shading.ts, tubeStripMaterial): two triangles per step along the curve, against 12 for a swept
// tube of 6 points round, as software WebGL (headless chromium's SwiftShader) pays per triangle
// and per shaded pixel (a frame of U.XI.28's tubes 27 -> 13 ms: benchmarks/RESULTS.md, 2026-12-03,
// branch studio-frame). The strips are open at the ends and
// lie on the curves (their depth is the axis'). Each geometry piece is one BufferGeometry drawn
// by one InstancedMesh with the piece's transforms (a strip faces the camera whatever the
// transform's handedness); an edit that keeps the layout rewrites the buffers in place (no GPU
// resources per edit).
import * as THREE from "three";
import { layoutKey, view } from "./geometry";
import type { Geometry } from "./protocol";
import { tubeStripMaterial } from "./shading";

/** Along a piece, every DRAG_STRIDE-th point of its polyline (and its last) is a station of its strip. */
export const DRAG_STRIDE = 2;
/** Tube diameter as a share of the bounding-box diagonal: the server's default member size
 * (auszug.meshing.sweep.default_size). */
export const SIZE_SHARE = 0.012;

/** The tube radius of a geometry's bounds [x0, y0, z0, x1, y1, z1]: half the default member size. */
export function tubeRadius(bounds: readonly number[]): number {
  const d = Math.hypot(bounds[3] - bounds[0], bounds[4] - bounds[1], bounds[5] - bounds[2]);
  return (SIZE_SHARE * d) / 2;
}

/** Every `stride`-th point of `points` ((n, 3) flattened) and the last: the stations of a tube. */
export function strided(points: Float32Array, stride: number, out?: Float32Array): Float32Array {
  const n = points.length / 3, m = ringCount(n, stride);
  const res = out ?? new Float32Array(3 * m);
  for (let i = 0; i < m; i++) {
    const k = 3 * Math.min(i * stride, n - 1);
    res[3 * i] = points[k]; res[3 * i + 1] = points[k + 1]; res[3 * i + 2] = points[k + 2];
  }
  return res;
}

/** The stations of a tube along `n` points taking every `stride`-th (and the last). */
export function ringCount(n: number, stride: number): number {
  return n <= 1 ? n : Math.ceil((n - 1) / stride) + 1;
}

/**
 * Triangles of a strip along `n` stations (vertices 2 i and 2 i + 1 at station i, the first on the
 * side `-radius`, the second on `+radius`): ((n - 1) * 2, 3) flattened, each facing the camera
 * once the vertex shader has turned the strip (tubeStripMaterial).
 */
export function stripIndices(n: number): Uint32Array {
  const out = new Uint32Array(Math.max(n - 1, 0) * 6);
  for (let i = 0, o = 0; i + 1 < n; i++, o += 6) {
    const a = 2 * i, b = a + 1, c = a + 2, d = a + 3;
    out[o] = a; out[o + 1] = b; out[o + 2] = c;
    out[o + 3] = b; out[o + 4] = d; out[o + 5] = c;
  }
  return out;
}

/**
 * A strip's vertices along the polyline `points` ((n, 3) flattened): each point twice in `pos`
 * ((2 n, 3)), the unit tangent there twice in `tan` ((2 n, 3): central differences, one-sided
 * at the ends; where the neighbours coincide, the previous station's, or +z at the start) and
 * the signed offsets -`radius`, +`radius` in `across` ((2 n,)). The vertex shader moves each
 * vertex by its offset along the direction normal to the tangent and to the line of sight.
 */
export function stripVertices(points: Float32Array, radius: number, pos: Float32Array, tan: Float32Array,
  across: Float32Array): void {
  const n = points.length / 3;
  let tx = 0, ty = 0, tz = 1;
  for (let i = 0; i < n; i++) {
    const a = 3 * Math.max(i - 1, 0), b = 3 * Math.min(i + 1, n - 1);
    const dx = points[b] - points[a], dy = points[b + 1] - points[a + 1], dz = points[b + 2] - points[a + 2];
    const len = Math.hypot(dx, dy, dz);
    if (len > 0) { tx = dx / len; ty = dy / len; tz = dz / len; }
    for (let side = 0; side < 2; side++) {
      const o = 3 * (2 * i + side);
      pos[o] = points[3 * i]; pos[o + 1] = points[3 * i + 1]; pos[o + 2] = points[3 * i + 2];
      tan[o] = tx; tan[o + 1] = ty; tan[o + 2] = tz;
      across[2 * i + side] = side ? radius : -radius;
    }
  }
}

interface Entry {
  basic: number;
  geom: THREE.BufferGeometry;
  mesh: THREE.InstancedMesh;
}

/** The page's own tubes of the last geometry, coloured like the server's meshes. */
export class DragTubes {
  readonly group = new THREE.Group();
  private entries: Entry[] = [];
  private layout = "";
  private layers: readonly number[] = [0];
  private materials = new Map<string, THREE.ShaderMaterial & { color: THREE.Color }>();
  private stations: Float32Array = new Float32Array(0);

  /** `color`: a basic curve's colour (#rrggbb) as the server's members show it. */
  constructor(private color: (basic: number) => string, private stride = DRAG_STRIDE) {
    this.group.name = "drag-tubes";
  }

  /** Draw the tubes of `msg` (its points in `data`), in place when the layout is unchanged. */
  update(msg: Geometry, data: Float32Array): void {
    const radius = tubeRadius(msg.bounds);
    const key = layoutKey(msg);
    const same = key === this.layout && this.entries.length === msg.pieces.length &&
      msg.pieces.every((p, i) => this.entries[i].mesh.count === p.transforms.shape[0]);
    if (!same) this.rebuild(msg);
    msg.pieces.forEach((p, i) => {
      const { geom, mesh } = this.entries[i];
      const pos = geom.getAttribute("position") as THREE.BufferAttribute;
      const tan = geom.getAttribute("axisTangent") as THREE.BufferAttribute;
      const across = geom.getAttribute("across") as THREE.BufferAttribute;
      const pts = view(data, p.points), n = ringCount(pts.length / 3, this.stride);
      if (this.stations.length < 3 * n) this.stations = new Float32Array(3 * n);
      const stations = strided(pts, this.stride, this.stations.subarray(0, 3 * n));
      stripVertices(stations, radius, pos.array as Float32Array, tan.array as Float32Array, across.array as Float32Array);
      pos.needsUpdate = tan.needsUpdate = across.needsUpdate = true;
      (mesh.instanceMatrix.array as Float32Array).set(view(data, p.transforms));
      mesh.instanceMatrix.needsUpdate = true;
    });
  }

  private rebuild(msg: Geometry): void {
    this.clear();
    for (const p of msg.pieces) {
      const n = ringCount(p.points.shape[0], this.stride);
      const geom = new THREE.BufferGeometry();
      geom.setAttribute("position", new THREE.BufferAttribute(new Float32Array(6 * n), 3));
      geom.setAttribute("axisTangent", new THREE.BufferAttribute(new Float32Array(6 * n), 3));
      geom.setAttribute("across", new THREE.BufferAttribute(new Float32Array(2 * n), 1));
      geom.setIndex(new THREE.BufferAttribute(stripIndices(n), 1));
      const mesh = new THREE.InstancedMesh(geom, this.material(p.basic), p.transforms.shape[0]);
      mesh.name = `${p.basic}/${p.kind}`;
      mesh.userData.basic = p.basic;
      mesh.frustumCulled = false;
      this.setObjectLayers(mesh);
      this.group.add(mesh);
      this.entries.push({ basic: p.basic, geom, mesh });
    }
    this.layout = layoutKey(msg);
  }

  /** The material of basic curve `basic`'s tubes (shared per colour). */
  private material(basic: number): THREE.ShaderMaterial & { color: THREE.Color } {
    const c = this.color(basic);
    let m = this.materials.get(c);
    if (!m) this.materials.set(c, (m = tubeStripMaterial(c)));
    return m;
  }

  /** Re-apply the colours (selection, looks). */
  recolor(): void {
    for (const e of this.entries) e.mesh.material = this.material(e.basic);
  }

  setLayers(layers: readonly number[]): void {
    this.layers = layers;
    for (const e of this.entries) this.setObjectLayers(e.mesh);
  }

  private setObjectLayers(o: THREE.Object3D): void {
    o.layers.disableAll();
    for (const l of this.layers) o.layers.enable(l);
  }

  /** Remove and dispose every tube (materials are kept for reuse). */
  clear(): void {
    for (const e of this.entries) {
      e.geom.dispose();
      e.mesh.dispose();
    }
    this.group.clear();
    this.entries = [];
    this.layout = "";
  }
}
