// Keyboard shortcuts, registered by the modules that own them; the help overlay lists them.
// No shortcut fires while the user types in a text field.
import { isTyping } from "./scene";

export interface Shortcut {
  /** KeyboardEvent.key, compared case-insensitively (e.g. "z", "Delete", "?"). */
  key: string;
  ctrl?: boolean;
  shift?: boolean;
  /** Shown in the help overlay, e.g. "Undo". */
  description: string;
  run(ev: KeyboardEvent): void;
}

const registry: Shortcut[] = [];

export function registerShortcut(s: Shortcut): void {
  registry.push(s);
}

export function shortcuts(): readonly Shortcut[] {
  return registry;
}

/** How a shortcut is written in the help overlay, e.g. "Ctrl+Shift+Z". */
export function describeKeys(s: Shortcut): string {
  const k = s.key.length === 1 ? s.key.toUpperCase() : s.key;
  return [s.ctrl ? "Ctrl" : "", s.shift ? "Shift" : "", k].filter(Boolean).join("+");
}

/** The shortcut an event triggers, if any (null while typing in a text field). */
export function match(ev: KeyboardEvent, list: readonly Shortcut[] = registry): Shortcut | null {
  if (isTyping(ev)) return null;
  const ctrl = ev.ctrlKey || ev.metaKey;
  for (const s of list) {
    if (s.key.toLowerCase() !== ev.key.toLowerCase()) continue;
    if (!!s.ctrl !== ctrl) continue;
    // "?" and other shifted symbols: shift is part of the key itself
    if (s.key.length === 1 && /[a-z0-9]/i.test(s.key) && !!s.shift !== ev.shiftKey) continue;
    return s;
  }
  return null;
}

/** Whether Enter in `el` commits its value and hands the keyboard back to the shortcuts: the number
 * and text fields of the panels (not those of dialogs, whose Enter is their own). */
export function commitsOnEnter(el: Element | null): el is HTMLInputElement {
  return el instanceof HTMLInputElement && (el.type === "number" || el.type === "text") && !el.closest("dialog");
}

export function installShortcuts(): void {
  // Enter in a panel's field commits it (its change event) and leaves the field, so Ctrl+Z undoes the
  // edit instead of the field's text, the other shortcuts work again and the field follows the drawing
  window.addEventListener("keydown", (ev) => {
    const el = ev.target as Element | null;
    if (ev.key === "Enter" && !ev.isComposing && commitsOnEnter(el)) setTimeout(() => el.blur(), 0);
  });
  window.addEventListener("keydown", (ev) => {
    const s = match(ev);
    if (!s) return;
    ev.preventDefault();
    s.run(ev);
  });
}
