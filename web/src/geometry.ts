// Geometry messages -> typed arrays and three.js objects. Pure functions over the
// protocol's types; the only three.js objects made here are lines sharing one
// BufferGeometry per basic piece, placed by the replica transforms (instances,
// not copies).
import * as THREE from "three";
import type { ArrayRef, Geometry, PieceGeometry } from "./protocol";

/** The float32 values of `ref` in the binary frame (a view, not a copy). */
export function view(data: Float32Array, ref: ArrayRef): Float32Array {
  const size = ref.shape.reduce((a, b) => a * b, 1);
  if (ref.offset < 0 || ref.offset + size > data.length) {
    throw new RangeError(`array [${ref.offset}, ${ref.offset + size}) outside a frame of ${data.length} floats`);
  }
  return data.subarray(ref.offset, ref.offset + size);
}

/** Number of replicas (network curves) a geometry message describes. */
export function replicaCount(msg: Geometry): number {
  return msg.pieces.reduce((n, p) => n + p.transforms.shape[0], 0);
}

/** The transforms of a piece as three.js matrices (column-major, as sent). */
export function transforms(data: Float32Array, piece: PieceGeometry): THREE.Matrix4[] {
  const t = view(data, piece.transforms);
  const out: THREE.Matrix4[] = [];
  for (let k = 0; k < piece.transforms.shape[0]; k++) {
    out.push(new THREE.Matrix4().fromArray(t, 16 * k));
  }
  return out;
}

/** Replica `k` of a piece's points (n x 3 floats), computed on the CPU (for picking and tests). */
export function replicaPoints(data: Float32Array, piece: PieceGeometry, k: number): Float32Array {
  const pts = view(data, piece.points);
  const m = transforms(data, piece)[k];
  const out = new Float32Array(pts.length);
  const v = new THREE.Vector3();
  for (let i = 0; i < pts.length; i += 3) {
    v.set(pts[i], pts[i + 1], pts[i + 2]).applyMatrix4(m);
    out[i] = v.x;
    out[i + 1] = v.y;
    out[i + 2] = v.z;
  }
  return out;
}

const KIND_COLORS: Record<string, number> = { ogee: 0x7a2e1d, free_end: 0x1d4e7a, level: 0x3b6e2b };

/** A group of lines: one shared BufferGeometry per basic piece, one Line per replica. */
export function networkObject(msg: Geometry, data: Float32Array): THREE.Group {
  const group = new THREE.Group();
  group.name = "network";
  for (const piece of msg.pieces) {
    const geom = new THREE.BufferGeometry();
    geom.setAttribute("position", new THREE.BufferAttribute(view(data, piece.points), 3));
    const mat = new THREE.LineBasicMaterial({ color: KIND_COLORS[piece.kind] ?? 0x444444 });
    transforms(data, piece).forEach((m, k) => {
      const line = new THREE.Line(geom, mat);
      line.name = `${piece.basic}/${piece.labels[k]}`;
      line.matrixAutoUpdate = false;
      line.matrix.copy(m);
      group.add(line);
    });
  }
  return group;
}
