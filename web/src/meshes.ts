// The looks' meshes (tube, bar, ribbon members, minimal-surface faces) from MeshGeometry, and the
// network's loops for picking faces. Each MeshPiece is one BufferGeometry drawn by an
// InstancedMesh with the piece's transforms (instances, not copies). A reply with the same sizes
// rewrites the buffers in place; any other disposes everything it replaces, so repeated edits
// never add GPU resources.
import * as THREE from "three";
import { viewAny } from "./geometry";
import { memberMaterial } from "./shading";
import type { ArrayRef, Loops, MeshGeometry } from "./protocol";

/** The colour of faces (basic -1): a light stone. */
export const STONE = "#d9cfbd";
/** Loop outlines are drawn scaled by this about their centres. */
const LOOP_INSET = 0.93;

/** One mesh piece's arrays, sliced out of the binary frame (views, not copies). */
export interface PieceArrays {
  basic: number;
  name: string;
  /** (n, 3) vertex positions. */
  positions: Float32Array;
  /** (m, 3) triangle vertex indices, each < n. */
  indices: Uint32Array;
  /** (k, 16) column-major 4x4 matrices, one per instance. */
  matrices: Float32Array;
  count: number;
}

function typed(buffer: ArrayBuffer, ref: ArrayRef, dtype: "f4" | "u4", cols: number, what: string) {
  if (ref.dtype !== dtype || ref.shape.length !== 2 || ref.shape[1] !== cols) {
    throw new RangeError(`${what}: expected (n, ${cols}) ${dtype}, got ${JSON.stringify(ref.shape)} ${ref.dtype}`);
  }
  return viewAny(buffer, ref);
}

/** The arrays of every piece of a MeshGeometry; throws on shapes, dtypes or indices that do not fit. */
export function pieceArrays(msg: MeshGeometry, buffer: ArrayBuffer): PieceArrays[] {
  return msg.pieces.map((p) => {
    const positions = typed(buffer, p.positions, "f4", 3, `${p.name}.positions`) as Float32Array;
    const indices = typed(buffer, p.indices, "u4", 3, `${p.name}.indices`) as Uint32Array;
    const matrices = typed(buffer, p.transforms, "f4", 16, `${p.name}.transforms`) as Float32Array;
    const n = positions.length / 3;
    for (const i of indices) {
      if (i >= n) throw new RangeError(`${p.name}: index ${i} outside its ${n} vertices`);
    }
    return { basic: p.basic, name: p.name, positions, indices, matrices, count: p.transforms.shape[0] };
  });
}

/**
 * Asks for something derived from the geometry (a mesh, the loops): `delayMs` after the last
 * change, with never more than one request in flight; a change during a request asks again as
 * soon as it is answered.
 */
export class Debouncer {
  private timer: ReturnType<typeof setTimeout> | null = null;
  private busy = false;
  private again = false;

  constructor(private run: () => Promise<unknown>, private delayMs = 120) {}

  /** Something changed: ask `delayMs` from now (a later change postpones it). */
  poke(): void {
    if (this.timer !== null) clearTimeout(this.timer);
    this.timer = setTimeout(() => {
      this.timer = null;
      this.fire();
    }, this.delayMs);
  }

  /** Forget a pending ask (a request in flight still completes). */
  cancel(): void {
    if (this.timer !== null) clearTimeout(this.timer);
    this.timer = null;
    this.again = false;
  }

  get inFlight(): boolean {
    return this.busy;
  }

  private fire(): void {
    if (this.busy) {
      this.again = true;
      return;
    }
    this.again = false;
    this.busy = true;
    Promise.resolve()
      .then(this.run)
      .catch(() => undefined) // the requester reports errors; the next change asks again
      .finally(() => {
        this.busy = false;
        if (this.again && this.timer === null) this.fire();
      });
  }
}

/** A loop as seen in one view: its boundary and centre in screen pixels. */
export interface ScreenLoop {
  boundary: [number, number][];
  centre: [number, number];
}

function inside(p: [number, number], poly: [number, number][]): boolean {
  let hit = false;
  for (let i = 0, j = poly.length - 1; i < poly.length; j = i++) {
    const [xi, yi] = poly[i], [xj, yj] = poly[j];
    if (yi > p[1] !== yj > p[1] && p[0] < ((xj - xi) * (p[1] - yi)) / (yj - yi) + xi) hit = !hit;
  }
  return hit;
}

function area(poly: [number, number][]): number {
  let a = 0;
  for (let i = 0, j = poly.length - 1; i < poly.length; j = i++) a += poly[j][0] * poly[i][1] - poly[i][0] * poly[j][1];
  return Math.abs(a) / 2;
}

function segmentDistance(p: [number, number], a: [number, number], b: [number, number]): number {
  const dx = b[0] - a[0], dy = b[1] - a[1];
  const len2 = dx * dx + dy * dy;
  const t = len2 > 0 ? Math.max(0, Math.min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2)) : 0;
  return Math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

/**
 * The loop a click at `p` means (an index into `loops`), or null: a centre within `tol` pixels,
 * else the smallest loop around the click, else the nearest boundary within `tol`.
 */
export function pickLoop(loops: ScreenLoop[], p: [number, number], tol = 12): number | null {
  let best: number | null = null, bestD = tol;
  loops.forEach((l, i) => {
    const d = Math.hypot(l.centre[0] - p[0], l.centre[1] - p[1]);
    if (d <= bestD) [best, bestD] = [i, d];
  });
  if (best !== null) return best;
  let bestA = Infinity;
  loops.forEach((l, i) => {
    if (l.boundary.length < 3 || !inside(p, l.boundary)) return;
    const a = area(l.boundary);
    if (a < bestA) [best, bestA] = [i, a];
  });
  if (best !== null) return best;
  loops.forEach((l, i) => {
    for (let k = 0; k < l.boundary.length; k++) {
      const d = segmentDistance(p, l.boundary[k], l.boundary[(k + 1) % l.boundary.length]);
      if (d <= bestD) [best, bestD] = [i, d];
    }
  });
  return best;
}

/** Show an object to exactly the given three.js layers. */
function setLayers(obj: THREE.Object3D, layers: readonly number[]): void {
  obj.layers.disableAll();
  for (const l of layers) obj.layers.enable(l);
}

/**
 * The instance matrices (k x 16) split by handedness: rotations, and mirror images (negative
 * determinant), which turn a triangle's winding around.
 */
export function splitHandedness(matrices: Float32Array): { proper: Float32Array; mirrored: Float32Array } {
  const proper: number[] = [], mirrored: number[] = [];
  for (let i = 0; i < matrices.length; i += 16) {
    const m = matrices.subarray(i, i + 16);
    const det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[4] * (m[1] * m[10] - m[2] * m[9]) + m[8] * (m[1] * m[6] - m[2] * m[5]);
    (det < 0 ? mirrored : proper).push(...m);
  }
  return { proper: new Float32Array(proper), mirrored: new Float32Array(mirrored) };
}

/** Triangle indices with every triangle's winding reversed. */
export function reversedWinding(indices: Uint32Array, out: Uint32Array = new Uint32Array(indices.length)): Uint32Array {
  for (let i = 0; i < indices.length; i += 3) {
    out[i] = indices[i];
    out[i + 1] = indices[i + 2];
    out[i + 2] = indices[i + 1];
  }
  return out;
}

/**
 * One mesh piece on the GPU: its geometry and the InstancedMesh of its rotated replicas; mirrored
 * replicas are a second InstancedMesh of a geometry that shares the positions and normals but
 * winds its triangles the other way, so that both stay front-facing and lit from outside.
 */
interface Entry {
  basic: number;
  /** Sizes that a reply must match to be written in place. */
  sizes: string;
  geoms: THREE.BufferGeometry[];
  meshes: THREE.InstancedMesh[];
}

function sizes(a: PieceArrays, split: { proper: Float32Array; mirrored: Float32Array }): string {
  return `${a.basic}:${a.positions.length}/${a.indices.length}/${split.proper.length}/${split.mirrored.length}`;
}

/** The members and faces of the last MeshGeometry, coloured per basic curve. */
export class MeshView {
  readonly group = new THREE.Group();
  private entries: Entry[] = [];
  private materials = new Map<string, THREE.Material & { color: THREE.Color }>();
  private style = "";
  private layers: readonly number[] = [0];

  constructor(private color: (basic: number) => string) {
    this.group.name = "meshes";
  }

  /** The number of instances per piece, in the order of the last reply (for tests). */
  get counts(): number[] {
    return this.entries.map((e) => e.meshes.reduce((n, m) => n + m.count, 0));
  }

  show(msg: MeshGeometry, buffer: ArrayBuffer): void {
    const arrays = pieceArrays(msg, buffer);
    const splits = arrays.map((a) => splitHandedness(a.matrices));
    const same = msg.style === this.style && arrays.length === this.entries.length &&
      arrays.every((a, i) => this.entries[i].sizes === sizes(a, splits[i]));
    if (same) {
      arrays.forEach((a, i) => this.rewrite(this.entries[i], a, splits[i]));
    } else {
      this.clear();
      this.style = msg.style;
      arrays.forEach((a, i) => this.add(a, splits[i]));
    }
  }

  private add(a: PieceArrays, split: { proper: Float32Array; mirrored: Float32Array }): void {
    const geom = new THREE.BufferGeometry();
    geom.setAttribute("position", new THREE.BufferAttribute(a.positions.slice(), 3));
    geom.setIndex(new THREE.BufferAttribute(a.indices.slice(), 1));
    geom.computeVertexNormals();
    const entry: Entry = { basic: a.basic, sizes: sizes(a, split), geoms: [geom], meshes: [] };
    if (split.mirrored.length) {
      const flipped = new THREE.BufferGeometry();
      flipped.setAttribute("position", geom.getAttribute("position"));
      flipped.setAttribute("normal", geom.getAttribute("normal"));
      flipped.setIndex(new THREE.BufferAttribute(reversedWinding(a.indices), 1));
      entry.geoms.push(flipped);
    }
    [split.proper, split.mirrored].forEach((matrices, j) => {
      if (!matrices.length) return;
      const mesh = new THREE.InstancedMesh(entry.geoms[j], this.material(a.basic), matrices.length / 16);
      (mesh.instanceMatrix.array as Float32Array).set(matrices);
      mesh.name = a.name;
      mesh.userData.basic = a.basic;
      mesh.frustumCulled = false; // the instances' bounds change with every edit
      setLayers(mesh, this.layers);
      this.group.add(mesh);
      entry.meshes.push(mesh);
    });
    this.entries.push(entry);
  }

  private rewrite(e: Entry, a: PieceArrays, split: { proper: Float32Array; mirrored: Float32Array }): void {
    const [geom, flipped] = e.geoms;
    const pos = geom.getAttribute("position") as THREE.BufferAttribute;
    (pos.array as Float32Array).set(a.positions);
    pos.needsUpdate = true;
    (geom.index!.array as Uint32Array).set(a.indices);
    geom.index!.needsUpdate = true;
    geom.computeVertexNormals(); // rewrites the shared normals in place
    if (flipped) {
      reversedWinding(a.indices, flipped.index!.array as Uint32Array);
      flipped.index!.needsUpdate = true;
    }
    const matrices = [split.proper, split.mirrored].filter((m) => m.length);
    e.meshes.forEach((mesh, j) => {
      (mesh.instanceMatrix.array as Float32Array).set(matrices[j]);
      mesh.instanceMatrix.needsUpdate = true;
    });
  }

  /** Re-apply the colours (after the looks' colours changed). */
  recolor(): void {
    for (const e of this.entries) for (const m of e.meshes) m.material = this.material(e.basic);
  }

  setLayers(layers: readonly number[]): void {
    this.layers = layers;
    for (const e of this.entries) for (const m of e.meshes) setLayers(m, layers);
  }

  /** Remove and dispose every mesh (materials are kept for reuse). */
  clear(): void {
    for (const e of this.entries) {
      for (const g of e.geoms) g.dispose();
      for (const m of e.meshes) m.dispose();
    }
    this.group.clear();
    this.entries = [];
    this.style = "";
  }

  /** Show or hide the members (basic >= 0; the faces stay). */
  showMembers(on: boolean): void {
    for (const e of this.entries) if (e.basic >= 0) for (const m of e.meshes) m.visible = on;
  }

  /** The material of basic curve `basic`'s members in `style` (faces: basic -1), shared. */
  material(basic: number, style: string = this.style): THREE.Material & { color: THREE.Color } {
    const color = basic < 0 ? STONE : this.color(basic);
    // faces and ribbons are seen from both sides; bars have flat sides; tubes are lit per vertex
    const doubleSided = basic < 0 || style === "ribbon";
    const flat = basic >= 0 && style === "bar";
    const gouraud = basic >= 0 && style === "tube";
    const key = `${color}|${doubleSided}|${flat}|${gouraud}`;
    let m = this.materials.get(key);
    if (!m && gouraud) {
      m = memberMaterial(color) as THREE.ShaderMaterial & { color: THREE.Color };
      this.materials.set(key, m);
    } else if (!m) {
      m = new THREE.MeshStandardMaterial({
        color, roughness: 0.75, metalness: 0.05, flatShading: flat,
        side: doubleSided ? THREE.DoubleSide : THREE.FrontSide,
      });
      this.materials.set(key, m);
    }
    return m;
  }
}

/** The loops faces can fill: boundaries and centres, the picked ones highlighted. */
export class LoopView {
  readonly group = new THREE.Group();
  /** (n, 3) boundary points and the centre of each loop of the last reply. */
  loops: { index: number; boundary: Float32Array; centre: THREE.Vector3 }[] = [];
  private geoms: THREE.BufferGeometry[] = [];
  private lines: THREE.LineLoop[] = [];
  private dots: THREE.Points[] = [];
  private plain = new THREE.LineBasicMaterial({ color: "#9a8f7c" });
  private picked = new THREE.LineBasicMaterial({ color: "#d97706" });
  private dotPlain = new THREE.PointsMaterial({ color: "#9a8f7c", size: 6, sizeAttenuation: false });
  private dotPicked = new THREE.PointsMaterial({ color: "#d97706", size: 8, sizeAttenuation: false });
  private layers: readonly number[] = [0];

  constructor() {
    this.group.name = "loops";
  }

  show(msg: Loops, buffer: ArrayBuffer, picked: readonly number[]): void {
    this.clear();
    for (const l of msg.loops) {
      const boundary = viewAny(buffer, l.boundary) as Float32Array;
      const centre = new THREE.Vector3(l.centre[0], l.centre[1], l.centre[2]);
      this.loops.push({ index: l.index, boundary, centre });
      // drawn a little inside the curves that bound it, so that loops sharing a curve read apart
      const inset = boundary.slice();
      for (let i = 0; i < inset.length; i++) inset[i] = l.centre[i % 3] + LOOP_INSET * (inset[i] - l.centre[i % 3]);
      const geom = new THREE.BufferGeometry();
      geom.setAttribute("position", new THREE.BufferAttribute(inset, 3));
      const dotGeom = new THREE.BufferGeometry();
      dotGeom.setAttribute("position", new THREE.BufferAttribute(new Float32Array(centre.toArray()), 3));
      this.geoms.push(geom, dotGeom);
      const line = new THREE.LineLoop(geom, this.plain);
      const dot = new THREE.Points(dotGeom, this.dotPlain);
      for (const o of [line, dot]) {
        o.userData.index = l.index;
        o.frustumCulled = false;
        setLayers(o, this.layers);
        this.group.add(o);
      }
      this.lines.push(line);
      this.dots.push(dot);
    }
    this.setPicked(picked);
  }

  setPicked(picked: readonly number[]): void {
    const on = new Set(picked);
    this.lines.forEach((l) => (l.material = on.has(l.userData.index) ? this.picked : this.plain));
    this.dots.forEach((d) => (d.material = on.has(d.userData.index) ? this.dotPicked : this.dotPlain));
  }

  setLayers(layers: readonly number[]): void {
    this.layers = layers;
    for (const o of this.group.children) setLayers(o, layers);
  }

  clear(): void {
    for (const g of this.geoms) g.dispose();
    this.group.clear();
    this.geoms = [];
    this.lines = [];
    this.dots = [];
    this.loops = [];
  }
}
