// The help overlay ("?" in #extra-tools, the "?" key or F1): every registered shortcut, grouped,
// and the mouse gestures of the views. Rendered each time it opens, so every module's shortcuts
// are there whenever they were registered.
import "./help.css";
import type { Ctx } from "./context";
import { Modal, button } from "./dialog";
import { helpGroups } from "./helpmodel";
import { registerShortcut, shortcuts } from "./shortcuts";

const GESTURES: [string, string][] = [
  ["Wheel", "zoom the top view about the pointer"],
  ["Right or middle drag, Space + drag", "pan the top view"],
  ["Drag in the 3D view", "orbit; right drag pans, wheel zooms"],
  ["Alt (hold)", "suspend snapping while drawing or dragging"],
  ["Shift + drag on the background image", "move the image"],
  ["Shift + wheel over the top view", "scale the background image about the pointer"],
];

export function initHelp(_ctx: Ctx): void {
  const help = new Modal("help", "Keyboard shortcuts and mouse", ["?", "F1"]);
  help.el.classList.add("help");

  /** A table of (keys, what they do); each key of "Ctrl+Shift+Z" in its own <kbd>. */
  function shortcutTable(rows: { keys: string[]; description: string }[]): HTMLTableElement {
    const t = document.createElement("table");
    for (const { keys, description } of rows) {
      const tr = t.insertRow();
      const k = tr.insertCell();
      k.className = "keys";
      keys.forEach((combo, i) => {
        if (i) k.append(" or ");
        const span = document.createElement("span");
        span.className = "combo";
        combo.split(/\+(?!$)/).forEach((part, j) => {
          if (j) span.append("+");
          const kbd = document.createElement("kbd");
          kbd.textContent = part;
          span.appendChild(kbd);
        });
        k.appendChild(span);
      });
      tr.insertCell().textContent = description;
    }
    return t;
  }

  function gestureTable(): HTMLTableElement {
    const t = document.createElement("table");
    t.className = "gestures";
    for (const [what, does] of GESTURES) {
      const tr = t.insertRow();
      tr.insertCell().textContent = what;
      tr.insertCell().textContent = does;
      tr.cells[0].className = "keys";
    }
    return t;
  }

  function render(): void {
    help.body.replaceChildren();
    const cols = document.createElement("div");
    cols.className = "help-columns";
    for (const g of helpGroups(shortcuts())) {
      const section = document.createElement("section");
      const h = document.createElement("h3");
      h.textContent = g.title;
      section.append(h, shortcutTable(g.rows));
      cols.appendChild(section);
    }
    const mouse = document.createElement("section");
    const h = document.createElement("h3");
    h.textContent = "Mouse";
    mouse.append(h, gestureTable());
    cols.appendChild(mouse);
    const note = document.createElement("p");
    note.className = "help-note";
    note.textContent = "Esc closes a dialog or menu. Shortcuts are off while you type in a text field.";
    help.body.append(cols, note);
  }

  const open = () => {
    render();
    help.open();
  };
  document.getElementById("extra-tools")!.appendChild(
    button("?", "Keyboard shortcuts and mouse gestures (?, F1)", "help", open));
  registerShortcut({ key: "?", description: "Show this help", run: open });
  registerShortcut({ key: "F1", description: "Show this help", run: open });
}
