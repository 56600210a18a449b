// Geometry messages -> typed arrays and matrices. Pure functions over the protocol's types
// (no DOM): slicing the binary frame, replica transforms, CPU-side replicas for picking.
import * as THREE from "three";
import type { ArrayRef, Geometry, PieceGeometry } from "./protocol";

function size(ref: ArrayRef): number {
  return ref.shape.reduce((a, b) => a * b, 1);
}

function check(ref: ArrayRef, n: number, length: number): void {
  if (ref.offset < 0 || ref.offset + n > length) {
    throw new RangeError(`array [${ref.offset}, ${ref.offset + n}) outside a frame of ${length} values`);
  }
}

/** The float32 values of `ref` in the binary frame (a view, not a copy). */
export function view(data: Float32Array, ref: ArrayRef): Float32Array {
  const n = size(ref);
  check(ref, n, data.length);
  return data.subarray(ref.offset, ref.offset + n);
}

/** The values of `ref` (f4 or u4) in a binary frame given as its ArrayBuffer (a view, not a copy). */
export function viewAny(buffer: ArrayBuffer, ref: ArrayRef): Float32Array | Uint32Array {
  const n = size(ref);
  check(ref, n, buffer.byteLength / 4);
  return ref.dtype === "u4" ? new Uint32Array(buffer, 4 * ref.offset, n) : new Float32Array(buffer, 4 * ref.offset, n);
}

/** Number of replicas (network curves) a geometry message describes. */
export function replicaCount(msg: Geometry): number {
  return msg.pieces.reduce((n, p) => n + p.transforms.shape[0], 0);
}

/** The transforms of a piece as three.js matrices (column-major, as sent). */
export function transforms(data: Float32Array, piece: { transforms: ArrayRef }): THREE.Matrix4[] {
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

/** A key that is equal for two geometry messages whose pieces have the same sizes and owners. */
export function layoutKey(msg: Geometry): string {
  return msg.pieces.map((p) => `${p.basic}.${p.kind}.${p.points.shape[0]}.${p.transforms.shape[0]}`).join("|");
}
