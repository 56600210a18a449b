// Overlays shared by the file tools, the help and the background image: modal dialogs (native
// <dialog> in #dialogs: Escape closes, the page behind is inert, no shortcut reaches the page)
// and popovers anchored below a toolbar button (non-modal: shortcuts keep working).
import "./dialog.css";

/** A modal dialog with a title bar and a close button; fill `body`. */
export class Modal {
  readonly el: HTMLDialogElement;
  readonly body: HTMLElement;
  private heading: HTMLElement;

  /** `closeKeys`: keys that close it besides Escape (e.g. the help's "?"). */
  constructor(testid: string, title: string, closeKeys: string[] = []) {
    this.el = document.createElement("dialog");
    this.el.className = "modal";
    this.el.tabIndex = -1;
    this.el.dataset.testid = testid;
    this.el.setAttribute("aria-label", title);
    const head = document.createElement("header");
    const h = (this.heading = document.createElement("h2"));
    h.textContent = title;
    const close = document.createElement("button");
    close.type = "button";
    close.className = "close";
    close.textContent = "×";
    close.title = "Close (Esc)";
    close.addEventListener("click", () => this.close());
    head.append(h, close);
    this.body = document.createElement("div");
    this.body.className = "modal-body";
    this.el.append(head, this.body);
    // the page's shortcuts listen on window: keys pressed in a modal stay in it (once closed, the
    // focus may rest on the dialog for a moment: keys pass then)
    this.el.addEventListener("keydown", (ev) => {
      if (!this.el.open) return;
      ev.stopPropagation();
      if (closeKeys.includes(ev.key) && !isTextField(ev.target)) {
        ev.preventDefault();
        this.close();
      }
    });
    // a click on the backdrop (outside the box) closes
    this.el.addEventListener("click", (ev) => {
      if (ev.target === this.el) this.close();
    });
    document.getElementById("dialogs")!.appendChild(this.el);
  }

  get isOpen(): boolean {
    return this.el.open;
  }

  setTitle(title: string): void {
    this.heading.textContent = title;
    this.el.setAttribute("aria-label", title);
  }

  /** Show it; the dialog itself has the focus (callers may move it to a field). */
  open(): void {
    if (!this.el.open) this.el.showModal();
    this.el.focus();
  }

  close(): void {
    this.el.close();
  }
}

function isTextField(t: EventTarget | null): boolean {
  return t instanceof HTMLInputElement || t instanceof HTMLTextAreaElement;
}

export interface PopoverOptions {
  /** A menu: a click elsewhere closes it. */
  menu?: boolean;
}

/** A box that opens below `anchor`, kept in the window; Escape inside it closes it. */
export class Popover {
  readonly el: HTMLElement;

  constructor(readonly anchor: HTMLElement, testid: string, options: PopoverOptions = {}) {
    this.el = document.createElement("div");
    this.el.className = "popover";
    this.el.dataset.testid = testid;
    this.el.hidden = true;
    this.el.addEventListener("keydown", (ev) => {
      if (ev.key !== "Escape") return;
      ev.stopPropagation();
      this.close();
      anchor.focus();
    });
    if (options.menu) {
      document.addEventListener("pointerdown", (ev) => {
        const t = ev.target as Node;
        if (!this.el.contains(t) && !anchor.contains(t)) this.close();
      }, { capture: true });
    }
    anchor.setAttribute("aria-expanded", "false");
    document.body.appendChild(this.el);
    window.addEventListener("resize", () => this.place());
  }

  get isOpen(): boolean {
    return !this.el.hidden;
  }

  open(): void {
    this.el.hidden = false;
    this.anchor.setAttribute("aria-expanded", "true");
    this.place();
  }

  close(): void {
    if (this.el.hidden) return;
    this.el.hidden = true;
    this.anchor.setAttribute("aria-expanded", "false");
  }

  toggle(): void {
    if (this.isOpen) this.close();
    else this.open();
  }

  /** Below the anchor, from its left edge, inside the window. */
  private place(): void {
    if (this.el.hidden) return;
    const a = this.anchor.getBoundingClientRect();
    const w = this.el.offsetWidth;
    this.el.style.top = `${a.bottom + 4}px`;
    this.el.style.left = `${Math.max(4, Math.min(a.left, window.innerWidth - w - 4))}px`;
  }
}

/** A toolbar-style button. */
export function button(text: string, title: string, testid: string, onClick: () => void): HTMLButtonElement {
  const b = document.createElement("button");
  b.type = "button";
  b.textContent = text;
  b.title = title;
  b.dataset.testid = testid;
  b.addEventListener("click", onClick);
  return b;
}
