// A refused value is explained at its field (not only in the status bar): the server's message in a
// line under the field (role alert), the field marked aria-invalid, until the field changes again or
// an edit from it succeeds.
import "./fielderror.css";

const messages = new WeakMap<HTMLElement, HTMLElement>();

/** Show `message` at `input`. */
export function showFieldError(input: HTMLElement, message: string): void {
  let m = messages.get(input);
  if (!m) {
    m = document.createElement("div");
    m.className = "field-error";
    m.setAttribute("role", "alert");
    m.dataset.testid = "field-error";
    m.dataset.for = input.dataset.testid ?? "";
    messages.set(input, m);
    input.addEventListener("input", () => clearFieldError(input));
  }
  m.textContent = message;
  input.setAttribute("aria-invalid", "true");
  input.title = message;
  (input.closest("label, .row, table, div") ?? input).insertAdjacentElement("afterend", m);
}

/** Remove the message of `input`, if any. */
export function clearFieldError(input: HTMLElement): void {
  const m = messages.get(input);
  if (m?.isConnected) m.remove();
  if (input.getAttribute("aria-invalid")) {
    input.removeAttribute("aria-invalid");
    input.title = "";
  }
}

/** `request`'s outcome at `input`: its error shown there (then `failed()`), a success clears it. */
export function atField(input: HTMLElement, request: Promise<unknown>, failed: () => void = () => undefined): void {
  request.then(() => clearFieldError(input), (e: Error) => {
    showFieldError(input, e.message);
    failed();
  });
}
