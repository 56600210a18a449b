// The plane math of the design tools, on [x, y] pairs in drawing units (no DOM): symmetry
// images, guide lines, snapping, picking a replica polyline, and the arc of a curve being drawn.
// The replicas of existing curves use the matrices the server sends with each curve
// (`CurveInfo.replicas`, the curve network's groups), so a snapped point equals Python's replica
// point; only a curve still being drawn, which the server has not seen, is previewed with
// `symmetryMatrices` (pinned to Python's by web/src/replicas.fixture.json).

export type Vec = [number, number];
/** A 2x2 matrix, row-major: [a, b, c, d] maps (x, y) to (a x + b y, c x + d y). */
export type Mat2 = [number, number, number, number];

/** A line through `origin` along the unit vector `dir`. */
export interface Line {
  origin: Vec;
  dir: Vec;
}

/** The symmetry of one basic curve, as CurveInfo gives it (`axis` null: no mirror). */
export interface CurveSymmetry {
  fold: number;
  axis: readonly number[] | null;
  center: readonly number[];
}

export interface SnapTargets {
  points: Vec[];
  lines: Line[];
}

export interface Snap {
  p: Vec;
  /** What the point snapped to (null: nothing within the tolerance). */
  kind: "point" | "line" | null;
}

/** What the server sends about a curve's replicas: row-major 2x2 matrices about `center`, r0 first. */
export interface CurveReplicas {
  replicas: readonly (readonly number[])[];
  center: readonly number[];
}

/** The sent replica matrices of a curve (CurveInfo.replicas) as Mat2s, in the server's order. */
export function replicaMatrices(c: CurveReplicas): Mat2[] {
  return c.replicas.map((m) => [m[0], m[1], m[2], m[3]]);
}

/** Linear parts of C_n (+ the mirror along `axis`) in the order r0, r0m, r1, r1m, ...: R^k, R^k Q.
 * For the preview of a curve being drawn only: existing curves come with their matrices
 * from the server (`replicaMatrices`). */
export function symmetryMatrices(fold: number, axis: readonly number[] | null): Mat2[] {
  const rots: Mat2[] = [];
  for (let k = 0; k < fold; k++) {
    let c: number, s: number;
    if ((4 * k) % fold === 0) {
      // multiples of 90 degrees: exact 0 and +-1, as in Python
      const q = ((4 * k) / fold) % 4;
      c = [1, 0, -1, 0][q];
      s = [0, 1, 0, -1][q];
    } else {
      const ang = (2 * Math.PI * k) / fold;
      c = Math.cos(ang);
      s = Math.sin(ang);
    }
    rots.push([c, -s, s, c]);
  }
  if (!axis) return rots;
  const len = Math.hypot(axis[0], axis[1]);
  const ux = axis[0] / len, uy = axis[1] / len;
  const q: Mat2 = [2 * ux * ux - 1, 2 * ux * uy, 2 * uy * ux, 2 * uy * uy - 1];
  return rots.flatMap((r) => [r, mul(r, q)]);
}

function mul(a: Mat2, b: Mat2): Mat2 {
  return [a[0] * b[0] + a[1] * b[2], a[0] * b[1] + a[1] * b[3], a[2] * b[0] + a[3] * b[2], a[2] * b[1] + a[3] * b[3]];
}

/** The images of `p` under c + M (p - c) for every matrix (the first, the identity, is `p` itself). */
export function images(p: readonly number[], center: readonly number[], mats: Mat2[]): Vec[] {
  const dx = p[0] - center[0], dy = p[1] - center[1];
  return mats.map((m, k) =>
    k === 0 ? [p[0], p[1]] : [m[0] * dx + m[1] * dy + center[0], m[2] * dx + m[3] * dy + center[1]]);
}

/** Every vertex of every replica of the given curves (segment endpoints), skipping curve `skip`. */
export function replicaVertices(curves: readonly (CurveReplicas & { vertices: readonly number[][] })[],
  skip = -1): Vec[] {
  const out: Vec[] = [];
  curves.forEach((c, i) => {
    if (i === skip) return;
    const mats = replicaMatrices(c);
    for (const v of c.vertices) out.push(...images(v, c.center, mats));
  });
  return out;
}

/** The mirror axis a new curve gets from the rule (null: none, or no axis yet / a zero one). */
export function mirrorAxis(rule: string, center: readonly number[], first: Vec | null, last: Vec | null): Vec | null {
  if (rule === "y axis") return [0, 1];
  const p = rule === "first point" ? first : rule === "last point" ? last : null;
  if (!p) return null;
  const a: Vec = [p[0] - center[0], p[1] - center[1]];
  return Math.hypot(a[0], a[1]) > 1e-12 ? a : null;
}

/** The guides of C_n: n lines through the centre, pi / n apart (2 n rays), the first along the axis
 * (or the x axis without a mirror). With a mirror these are the group's mirror lines. */
export function guideLines(sym: CurveSymmetry): Line[] {
  const a = sym.axis;
  const theta0 = a ? Math.atan2(a[1], a[0]) : 0;
  const out: Line[] = [];
  for (let k = 0; k < sym.fold; k++) {
    const t = theta0 + (Math.PI * k) / sym.fold;
    const dir: Vec = k === 0 && a ? unit(a) : [Math.cos(t), Math.sin(t)];
    out.push({ origin: [sym.center[0], sym.center[1]], dir });
  }
  return out;
}

function unit(a: readonly number[]): Vec {
  const l = Math.hypot(a[0], a[1]);
  return [a[0] / l, a[1] / l];
}

/** The point of `line` nearest to `p`. */
export function projectOnLine(p: Vec, line: Line): Vec {
  const t = (p[0] - line.origin[0]) * line.dir[0] + (p[1] - line.origin[1]) * line.dir[1];
  return [line.origin[0] + t * line.dir[0], line.origin[1] + t * line.dir[1]];
}

/** Snap `p` to the nearest target point within `tol`, else to the nearest line within `tol`. */
export function snap(p: Vec, targets: SnapTargets, tol: number): Snap {
  let best: Vec | null = null, bestD = tol;
  for (const q of targets.points) {
    const d = Math.hypot(q[0] - p[0], q[1] - p[1]);
    if (d <= bestD) { best = q; bestD = d; }
  }
  if (best) return { p: [best[0], best[1]], kind: "point" };
  let proj: Vec | null = null;
  bestD = tol;
  for (const l of targets.lines) {
    const q = projectOnLine(p, l);
    const d = Math.hypot(q[0] - p[0], q[1] - p[1]);
    if (d <= bestD) { proj = q; bestD = d; }
  }
  if (proj) return { p: proj, kind: "line" };
  return { p: [p[0], p[1]], kind: null };
}

/** Distance from `p` to the segment ab. */
export function segmentDistance(p: Vec, ax: number, ay: number, bx: number, by: number): number {
  const dx = bx - ax, dy = by - ay;
  const l2 = dx * dx + dy * dy;
  const t = l2 > 0 ? Math.max(0, Math.min(1, ((p[0] - ax) * dx + (p[1] - ay) * dy) / l2)) : 0;
  return Math.hypot(p[0] - ax - t * dx, p[1] - ay - t * dy);
}

/** One basic piece for picking: (n, 3) points and (k, 16) column-major transforms, flat. */
export interface PickPiece {
  basic: number;
  points: ArrayLike<number>;
  transforms: ArrayLike<number>;
}

/** The basic curve and replica whose top-view polyline passes nearest `p`, if within `tol`. */
export function pickCurve(p: Vec, pieces: readonly PickPiece[], tol: number):
  { basic: number; replica: number } | null {
  let best: { basic: number; replica: number } | null = null, bestD = tol;
  for (const pc of pieces) {
    const pts = pc.points, t = pc.transforms, n = pts.length / 3;
    for (let k = 0; k < t.length / 16; k++) {
      const o = 16 * k, a = t[o], b = t[o + 4], c = t[o + 1], d = t[o + 5], e = t[o + 12], f = t[o + 13];
      // the z column is ignored: the top view drops z
      let px = a * pts[0] + b * pts[1] + e, py = c * pts[0] + d * pts[1] + f;
      for (let i = 0; i < n; i++) {
        const x = a * pts[3 * i] + b * pts[3 * i + 1] + e, y = c * pts[3 * i] + d * pts[3 * i + 1] + f;
        const dist = segmentDistance(p, px, py, x, y);
        if (dist <= bestD) { bestD = dist; best = { basic: pc.basic, replica: k }; }
        px = x; py = y;
      }
    }
  }
  return best;
}

/** `n` + 1 points of the arc from `a` to `b` whose tangent at `a` aims at `h` (edit.draw_curve's
 * arc); the chord when `h` is on the line ab. */
export function arcPoints(a: Vec, h: Vec, b: Vec, n = 48): Vec[] {
  const dx = h[0] - a[0], dy = h[1] - a[1];
  const cx = b[0] - a[0], cy = b[1] - a[1];
  const dl = Math.hypot(dx, dy), cl2 = cx * cx + cy * cy;
  const cross = dx * cy - dy * cx; // > 0: b lies left of the tangent, the arc turns left
  if (dl === 0 || cl2 === 0 || Math.abs(cross) <= 1e-9 * dl * Math.sqrt(cl2)) return [[a[0], a[1]], [b[0], b[1]]];
  // centre o = a + r nrm with nrm the left normal of the tangent; |o - b| = |r| gives r
  const nx = -dy / dl, ny = dx / dl;
  const r = cl2 / (2 * (nx * cx + ny * cy));
  const ox = a[0] + r * nx, oy = a[1] + r * ny;
  const t0 = Math.atan2(a[1] - oy, a[0] - ox);
  let sweep = Math.atan2(b[1] - oy, b[0] - ox) - t0;
  if (cross > 0) { while (sweep <= 0) sweep += 2 * Math.PI; } else { while (sweep >= 0) sweep -= 2 * Math.PI; }
  const R = Math.abs(r), out: Vec[] = [];
  for (let i = 0; i <= n; i++) {
    const t = t0 + (sweep * i) / n;
    out.push(i === n ? [b[0], b[1]] : [ox + R * Math.cos(t), oy + R * Math.sin(t)]);
  }
  return out;
}

/** A point target under the pointer: its screen position (CSS px) and its rank (higher wins). */
export interface Target { x: number; y: number; rank: number }

/** Half the size of a point target (CSS px): every marker and point takes clicks over 2 * 8 = 16 px. */
export const TARGET_PX = 8;

/** Rank of a target in the top view: the selected curve's markers first (the paper's core action:
 * a click on a crossing puts that curve's PRC there), then the selected curve's points and handles,
 * then the other curves' markers, then their points. */
export function targetRank(kind: "intersection" | "vertex" | "handle", selected: boolean): number {
  if (kind === "intersection") return selected ? 4 : 2;
  return selected ? 3 : 1;
}

/** The index of the target that takes a press at (x, y): the highest rank within `radius`, the
 * nearest among equals; -1 if none. */
export function pickTarget(x: number, y: number, targets: readonly Target[], radius = TARGET_PX): number {
  let best = -1, bestRank = -Infinity, bestD = Infinity;
  targets.forEach((t, i) => {
    const d = Math.hypot(t.x - x, t.y - y);
    if (d > radius) return;
    if (t.rank > bestRank || (t.rank === bestRank && d < bestD)) {
      best = i;
      bestRank = t.rank;
      bestD = d;
    }
  });
  return best;
}
