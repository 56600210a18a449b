// The selected curve's properties (#curve-panel): symmetry, layer, colour, delete.
import type { Ctx } from "./context";

export function initCurvePanel(ctx: Ctx): void {
  void ctx;
}
