import { describe, expect, it } from "vitest";
import fixture from "./replicas.fixture.json";
import {
  arcPoints, guideLines, images, mirrorAxis, pickCurve, projectOnLine, replicaMatrices, replicaVertices,
  pickTarget, segmentDistance, snap, symmetryMatrices, targetRank, type Vec,
} from "./snapping";

describe("symmetry", () => {
  it("orders r0, r0m, r1, r1m with exact quarter turns", () => {
    // SymmetryGroup(2, True, axis=(1, 0)).matrices() in Python: r0, r0m = diag(1, -1), r1 = -I, r1m
    const plain = (ms: number[][]) => ms.map((m) => m.map((v) => v + 0)); // -0 -> 0
    expect(plain(symmetryMatrices(2, [1, 0]))).toEqual([[1, 0, 0, 1], [1, 0, 0, -1], [-1, 0, 0, -1], [-1, 0, 0, 1]]);
    expect(plain(symmetryMatrices(4, null))[1]).toEqual([0, -1, 1, 0]);
    const m = symmetryMatrices(3, null)[1];
    expect(m[0]).toBeCloseTo(-0.5, 15);
    expect(m[2]).toBeCloseTo(Math.sqrt(3) / 2, 15);
  });

  it("maps points about the centre; the identity image is the point itself", () => {
    // SymmetryGroup(2, center=(1, 1)).apply([0, 0]) == [[0, 0], [2, 2]]
    expect(images([0, 0], [1, 1], symmetryMatrices(2, null))).toEqual([[0, 0], [2, 2]]);
    expect(images([0.1, 0.2], [0, 0], symmetryMatrices(4, [0, 1]))).toEqual([
      [0.1, 0.2], [-0.1, 0.2], [-0.2, 0.1], [-0.2, -0.1], [-0.1, -0.2], [0.1, -0.2], [0.2, -0.1], [0.2, 0.1],
    ]);
  });

  it("lists every replica vertex with the server's matrices, skipping one curve", () => {
    // CurveInfo.replicas as the server sends them: C_2 about (0, 0), C_1 (the identity only), and a
    // quarter turn about (1, 1) that the page must use as given
    const curves = [
      { vertices: [[1, 0], [2, 0]], replicas: [[1, 0, 0, 1], [-1, 0, 0, -1]], center: [0, 0] },
      { vertices: [[0, 3], [0, 4]], replicas: [[1, 0, 0, 1]], center: [0, 0] },
      { vertices: [[2, 1]], replicas: [[1, 0, 0, 1], [0, -1, 1, 0]], center: [1, 1] },
    ];
    expect(replicaVertices(curves)).toEqual([[1, 0], [-1, 0], [2, 0], [-2, 0], [0, 3], [0, 4], [2, 1], [1, 2]]);
    expect(replicaVertices(curves, 0)).toEqual([[0, 3], [0, 4], [2, 1], [1, 2]]);
    expect(replicaMatrices(curves[2])).toEqual([[1, 0, 0, 1], [0, -1, 1, 0]]);
  });

  it("previews a curve being drawn with Python's matrices (web/src/replicas.fixture.json)", () => {
    // geometry.symmetry.SymmetryGroup(fold, mirror, axis=axis).matrices() for many folds and axes
    expect(fixture.length).toBeGreaterThan(40);
    for (const c of fixture) {
      const got = symmetryMatrices(c.fold, c.axis);
      expect(got.length).toBe(c.matrices.length);
      got.forEach((m, k) => m.forEach((v, i) => expect(v).toBeCloseTo(c.matrices[k][i], 14)));
    }
  });

  it("derives a new curve's mirror axis from its rule", () => {
    expect(mirrorAxis("none", [0, 0], [1, 1], [2, 2])).toBeNull();
    expect(mirrorAxis("y axis", [0, 0], null, null)).toEqual([0, 1]);
    expect(mirrorAxis("first point", [1, 0], [3, 1], [5, 5])).toEqual([2, 1]);
    expect(mirrorAxis("last point", [0, 0], [3, 1], null)).toBeNull();
    expect(mirrorAxis("first point", [0, 0], [0, 0], null)).toBeNull();
  });
});

describe("guides and snapping", () => {
  it("gives n lines pi / n apart, the first along the axis", () => {
    const lines = guideLines({ fold: 2, axis: [0, 2], center: [1, 1] });
    expect(lines.length).toBe(2);
    expect(lines[0]).toEqual({ origin: [1, 1], dir: [0, 1] });
    expect(lines[1].dir[0]).toBeCloseTo(-1, 15);
    expect(lines[1].dir[1]).toBeCloseTo(0, 15);
    expect(guideLines({ fold: 1, axis: null, center: [0, 0] })).toEqual([{ origin: [0, 0], dir: [1, 0] }]);
  });

  it("projects onto a line", () => {
    expect(projectOnLine([3, 4], { origin: [0, 1], dir: [1, 0] })).toEqual([3, 1]);
    expect(projectOnLine([2, 0], { origin: [0, 0], dir: [Math.SQRT1_2, Math.SQRT1_2] })[0]).toBeCloseTo(1, 15);
  });

  it("prefers the nearest point, then the nearest line, within the tolerance", () => {
    const line = { origin: [0, 5] as Vec, dir: [1, 0] as Vec };
    const targets = { points: [[0, 0], [1, 0], [1.05, 0]] as Vec[], lines: [line] };
    expect(snap([1.04, 0.01], targets, 0.1)).toEqual({ p: [1.05, 0], kind: "point" });
    expect(snap([0.5, 4.95], targets, 0.1)).toEqual({ p: [0.5, 5], kind: "line" });
    expect(snap([0.5, 0.5], targets, 0.1)).toEqual({ p: [0.5, 0.5], kind: null });
    // a point within the tolerance wins over a nearer line
    expect(snap([0.02, 4.97], { points: [[0, 5.05]], lines: targets.lines }, 0.1).p).toEqual([0, 5.05]);
  });
});

describe("picking", () => {
  it("measures the distance to a segment", () => {
    expect(segmentDistance([0, 1], -1, 0, 1, 0)).toBe(1);
    expect(segmentDistance([3, 4], -1, 0, 0, 0)).toBe(5);
    expect(segmentDistance([3, 4], 0, 0, 0, 0)).toBe(5);
  });

  it("finds the replica whose polyline passes nearest", () => {
    const id = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
    const rot90 = [0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]; // column-major: (x, y) -> (-y, x)
    const piece = { basic: 3, points: [1, 0, 0, 2, 0, 1], transforms: [...id, ...rot90] };
    expect(pickCurve([1.5, 0.05], [piece], 0.1)).toEqual({ basic: 3, replica: 0 });
    expect(pickCurve([0.04, 1.5], [piece], 0.1)).toEqual({ basic: 3, replica: 1 });
    expect(pickCurve([0.5, 0.5], [piece], 0.1)).toBeNull();
  });
});

describe("arc of a drawn curve", () => {
  it("leaves a along the handle and ends at b", () => {
    // tangent at (0, 0) along +y, ending at (2, 0): the half circle about (1, 0) through (1, 1)
    const pts = arcPoints([0, 0], [0, 5], [2, 0], 4);
    expect(pts.length).toBe(5);
    expect(pts[0][0]).toBeCloseTo(0, 15);
    expect(pts[2][0]).toBeCloseTo(1, 15);
    expect(pts[2][1]).toBeCloseTo(1, 15);
    expect(pts[4]).toEqual([2, 0]);
    // the mirror image turns the other way
    expect(arcPoints([0, 0], [0, -5], [2, 0], 4)[2][1]).toBeCloseTo(-1, 15);
  });

  it("is the chord when the handle is on the line", () => {
    expect(arcPoints([0, 0], [1, 1], [2, 2])).toEqual([[0, 0], [2, 2]]);
  });
});

describe("pickTarget", () => {
  const at = (x: number, y: number, rank: number) => ({ x, y, rank });
  it("prefers the selected curve's marker over a faded one lying on top and over its own vertex", () => {
    const ts = [at(100, 100, targetRank("intersection", false)), at(101, 100, targetRank("intersection", true)),
      at(100, 101, targetRank("vertex", true))];
    expect(pickTarget(100, 100, ts)).toBe(1);
  });
  it("takes clicks within 8 px (a 16 px target), not beyond", () => {
    const ts = [at(0, 0, 1)];
    expect(pickTarget(7.9, 0, ts)).toBe(0);
    expect(pickTarget(0, 8, ts)).toBe(0);
    expect(pickTarget(8.1, 0, ts)).toBe(-1);
  });
  it("takes the nearest of equal ranks", () => {
    expect(pickTarget(5, 0, [at(0, 0, 2), at(6, 0, 2)])).toBe(1);
  });
});
