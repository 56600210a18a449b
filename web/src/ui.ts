// Small DOM helpers shared by the studio's pages (main.ts, tracery.ts).

/** A toolbar button with its label, tooltip and test id, appended to `parent`. */
export function button(parent: HTMLElement, text: string, title: string, testid: string,
                       onClick: () => void): HTMLButtonElement {
  const b = document.createElement("button");
  b.textContent = text;
  b.title = title;
  b.dataset.testid = testid;
  b.addEventListener("click", onClick);
  parent.appendChild(b);
  return b;
}
