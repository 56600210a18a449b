import * as THREE from "three";
import { describe, expect, it } from "vitest";
import { fitDistance, viewAxes } from "./camerafit";

describe("fitDistance", () => {
  it("frames a cube seen head-on exactly at the field of view's edge", () => {
    const pts: THREE.Vector3[] = [];
    for (let i = 0; i < 8; i++) pts.push(new THREE.Vector3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
    // looking along -y at a cube of half size 1, fov 90 deg, fill 1, aspect 1: the near face (z = 1
    // towards the camera) at |x| = 1 binds: d = 1 + 1 / tan(45 deg) = 2
    const d = fitDistance(pts, new THREE.Vector3(), new THREE.Vector3(0, -1, 0), 90, 1, 1);
    expect(d).toBeCloseTo(2, 12);
    // a wide view (aspect 2) is bound by the height; a fill of 0.5 doubles the distance term
    expect(fitDistance(pts, new THREE.Vector3(), new THREE.Vector3(0, -1, 0), 90, 2, 1)).toBeCloseTo(2, 12);
    expect(fitDistance(pts, new THREE.Vector3(), new THREE.Vector3(0, -1, 0), 90, 1, 0.5)).toBeCloseTo(3, 12);
  });

  it("keeps every point inside the view it computes", () => {
    const pts = [new THREE.Vector3(3, -1, 0.5), new THREE.Vector3(-2, 4, 1), new THREE.Vector3(0.5, 0.5, -3)];
    const c = new THREE.Vector3(0.2, 0.3, -0.4), back = new THREE.Vector3(0.4, -0.7, 0.6);
    const cam = new THREE.PerspectiveCamera(40, 1.5, 0.01, 1000);
    const d = fitDistance(pts, c, back, 40, 1.5, 0.9);
    const { back: b, up } = viewAxes(back);
    cam.position.copy(c).addScaledVector(b, d);
    cam.up.copy(up);
    cam.lookAt(c);
    cam.updateMatrixWorld();
    let edge = 0;
    for (const p of pts) {
      const q = p.clone().project(cam);
      edge = Math.max(edge, Math.abs(q.x), Math.abs(q.y));
    }
    expect(edge).toBeCloseTo(0.9, 9);   // the binding point lands exactly at the fill
  });

  it("takes x as right for a view straight down", () => {
    const { right, up } = viewAxes(new THREE.Vector3(0, 0, 1));
    expect(right.toArray()).toEqual([1, 0, 0]);
    expect(up.x).toBeCloseTo(0, 12);
    expect(Math.abs(up.y)).toBeCloseTo(1, 12);
  });
});
