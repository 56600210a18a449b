// Framing a perspective camera on a set of points: the one computation behind the design page's
// 3D view (scene.ts, fit3d) and the tracery page's (tracery.ts, fit).
import * as THREE from "three";

/** The camera's axes for a view looking along -`back`, z up: `right` and `up` (a view straight
 * down takes x as right). All unit vectors. */
export function viewAxes(back: THREE.Vector3): { back: THREE.Vector3; right: THREE.Vector3; up: THREE.Vector3 } {
  const b = back.clone().normalize();
  const right = new THREE.Vector3(0, 0, 1).cross(b);
  if (right.lengthSq() < 1e-12) right.set(1, 0, 0);
  right.normalize();
  return { back: b, right, up: b.clone().cross(right) };
}

/** The distance from `center` along `back` at which a camera of vertical field of view `fovDeg`
 * and `aspect` (width / height) sees every point within `fill` of its half width and half height:
 * a point at (x, y) across and z towards the camera stays inside when d >= z + |x| / tan. */
export function fitDistance(points: Iterable<THREE.Vector3>, center: THREE.Vector3, back: THREE.Vector3,
                            fovDeg: number, aspect: number, fill: number): number {
  const { back: b, right, up } = viewAxes(back);
  const tanV = Math.tan(THREE.MathUtils.degToRad(fovDeg) / 2) * fill, tanH = tanV * aspect;
  const p = new THREE.Vector3();
  let d = 1e-6;
  for (const q of points) {
    p.copy(q).sub(center);
    const z = p.dot(b);
    d = Math.max(d, z + Math.abs(p.dot(right)) / tanH, z + Math.abs(p.dot(up)) / tanV);
  }
  return d;
}
