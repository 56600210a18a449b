// The side view of the selected curve (#side-panel) and the layers (#layer-panel).
import type { Ctx } from "./context";

export function initSideView(ctx: Ctx): void {
  void ctx;
}
