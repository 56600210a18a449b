// A background image in the top view for tracing: load, move, scale, opacity.
import type { Ctx } from "./context";

export function initBackground(ctx: Ctx): void {
  void ctx;
}
