// The help overlay (#extra-tools button, "?" key): every registered shortcut.
import type { Ctx } from "./context";

export function initHelp(ctx: Ctx): void {
  void ctx;
}
