// Files (#file-tools): gallery, open local, save, export, autosave recovery (#banner).
import type { Ctx } from "./context";

export function initFiles(ctx: Ctx): void {
  void ctx;
}
