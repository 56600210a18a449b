// The background image's placement (pure): where it sits in the top view, fitting, scaling
// about a point, hit tests, and the per-document record kept in localStorage.

/** The image's placement in drawing units: centre (x, y), width (the height follows the image). */
export interface Placement {
  x: number;
  y: number;
  width: number;
  opacity: number;
  visible: boolean;
}

/** The placement that fits an image of `aspect` (height / width) into 90 % of a view region. */
export function fit(cx: number, cy: number, viewW: number, viewH: number, aspect: number): Placement {
  const width = 0.9 * Math.min(viewW, viewH / aspect);
  return { x: cx, y: cy, width, opacity: 0.5, visible: true };
}

/** `p` scaled by `factor` about the drawing point (px, py), which stays where it is on the image. */
export function scaleAbout(p: Placement, px: number, py: number, factor: number): Placement {
  return { ...p, x: px + (p.x - px) * factor, y: py + (p.y - py) * factor, width: p.width * factor };
}

/** Whether the drawing point (px, py) lies on the image. */
export function contains(p: Placement, aspect: number, px: number, py: number): boolean {
  return Math.abs(px - p.x) <= p.width / 2 && Math.abs(py - p.y) <= (p.width * aspect) / 2;
}

/** The localStorage key of a document's placement (by its workspace path, else its name). */
export function storageKey(doc: { path: string; name: string }): string {
  return `auszug.background:${doc.path || `name:${doc.name}`}`;
}

/** A stored placement, or null when `text` is missing or not a valid one. */
export function parsePlacement(text: string | null): Placement | null {
  if (!text) return null;
  let v: unknown;
  try {
    v = JSON.parse(text);
  } catch {
    return null;
  }
  const o = v as Record<string, unknown>;
  const num = (k: string) => typeof o?.[k] === "number" && Number.isFinite(o[k]);
  if (!num("x") || !num("y") || !num("width") || !num("opacity") || typeof o.visible !== "boolean") return null;
  const p = o as unknown as Placement;
  if (p.width <= 0) return null;
  return { x: p.x, y: p.y, width: p.width, opacity: Math.min(1, Math.max(0, p.opacity)), visible: p.visible };
}
