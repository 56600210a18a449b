// Looks (#look-tools): curves, tube, bar, ribbon, colours, faces; meshes from MeshGeometry.
import type { Ctx } from "./context";

export function initLooks(ctx: Ctx): void {
  void ctx;
}
