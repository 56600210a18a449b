// Design mode, top view: the SVG overlay (#top-overlay) over the three.js top view.
// Owner: the design-tools work (drawing, selecting, dragging, snapping, guides, markers).
import type { Ctx } from "./context";

export function initTopView(ctx: Ctx): void {
  void ctx;
}
