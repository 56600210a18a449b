// The selected curve's properties (#curve-panel): symmetry (fold, mirror), layer, colour, its
// points (mark and coordinates, editable) and delete. Built once; values are updated in place
// (never under the user's cursor: a focused field keeps what is being typed).
import { perFrame } from "./frames";
import "./curvepanel.css";
import type { Ctx } from "./context";
import type { ClientMessage, Geometry } from "./protocol";
import { atField } from "./fielderror";
import { registerShortcut } from "./shortcuts";
import { MIRROR_RULES, type MirrorRule } from "./topview";

/** A new element (appended to `parent` if given). */
function el<K extends keyof HTMLElementTagNameMap>(parent: HTMLElement | null, tag: K,
  props: Partial<HTMLElementTagNameMap[K]> = {}, testid = ""): HTMLElementTagNameMap[K] {
  const e: HTMLElement = Object.assign(document.createElement(tag), props);
  if (testid) e.dataset.testid = testid;
  parent?.appendChild(e);
  return e as HTMLElementTagNameMap[K];
}

/** A labelled control in `parent`; the control. */
function field<E extends HTMLElement>(parent: HTMLElement, text: string, control: E): E {
  el(parent, "label", { className: "field" }).append(text, control);
  return control;
}

/** Set a control's value unless the user is editing it (`force`: even then). */
function show(input: HTMLInputElement | HTMLSelectElement, value: string, force = false): void {
  if ((force || document.activeElement !== input) && input.value !== value) input.value = value;
}

export function initCurvePanel(ctx: Ctx): void {
  const { store } = ctx;
  const root = document.getElementById("curve-panel")!;
  const title = el(root, "h2", { textContent: "Curve" });
  const empty = el(root, "p", { className: "muted",
    textContent: "No curve selected: click a curve in the top view, or draw one (L line, A arc, E free end)." });
  const body = el(root, "div", { className: "curve-body" });

  const sym = el(body, "div", { className: "row" });
  const fold = field(sym, "fold", el(null, "input",
    { type: "number", min: "1", step: "1", title: "Rotation fold n (the limit is auszug.limits.LIMITS.fold)" }, "fold-input"));
  const mirror = field(sym, "mirror", el(null, "select",
    { title: "Mirror: none, through the first or last point, or the y axis" }, "mirror-select"));
  for (const m of MIRROR_RULES) mirror.add(new Option(m, m));
  const fixed = new Option("fixed axis", "fixed");
  fixed.disabled = true;
  mirror.add(fixed);

  const look = el(body, "div", { className: "row" });
  const layer = field(look, "layer", el(null, "select", { title: "The curve's layer" }, "layer-select"));
  const color = field(look, "colour", el(null, "input",
    { type: "color", title: "Colour of the curve and its replicas" }, "curve-color"));

  const info = el(body, "p", { className: "muted" }, "curve-info");
  const table = el(body, "table", { className: "points" }, "curve-points");
  const del = el(body, "button", { textContent: "Delete curve", title: "Remove the curve and its replicas (Delete)" },
    "delete-curve");

  /** Send an edit; a refused one puts the controls back to the drawing's values (the status bar says why). */
  const edit = (msg: ClientMessage, input?: HTMLElement) => {
    const r = ctx.request(msg);
    if (input) atField(input, r, () => update(true));
    else void r.catch(() => update(true));
  };
  const selected = (): number | null => {
    const g = store.geometry, s = store.selection;
    return g && s !== null && s < g.curves.length ? s : null;
  };

  fold.addEventListener("change", () => {
    const s = selected(), n = Math.round(Number(fold.value));
    if (s === null) return;
    if (!Number.isFinite(n)) { fold.value = String(store.geometry!.curves[s].fold); return; }
    // the server checks the fold against auszug.limits (the refusal shows at the field)
    if (n !== store.geometry!.curves[s].fold) edit({ type: "set_symmetry", curve: s, fold: n }, fold);
  });
  mirror.addEventListener("change", () => {
    const s = selected();
    if (s !== null) edit({ type: "set_symmetry", curve: s, mirror: mirror.value as MirrorRule });
  });
  layer.addEventListener("change", () => {
    const s = selected();
    if (s !== null) edit({ type: "set_layer", curve: s, layer: Number(layer.value) });
  });
  color.addEventListener("input", () => {
    const s = selected();
    if (s === null) return;
    const n = store.geometry!.n_curves;
    const colors = Array.from({ length: Math.max(n, store.looks.colors.length) }, (_, i) => store.color(i));
    colors[s] = color.value;
    store.setLooks({ colors });
  });
  const remove = () => {
    const s = selected();
    if (s === null) return;
    store.select(null);
    if (store.looks.colors.length > s) store.setLooks({ colors: store.looks.colors.filter((_, i) => i !== s) });
    edit({ type: "remove_curve", curve: s });
  };
  del.addEventListener("click", remove);
  registerShortcut({ key: "Delete", description: "Delete the selected curve", run: remove });
  registerShortcut({ key: "Backspace", description: "Delete the selected curve", run: remove });

  // one row per point: index, mark, x, y (a changed coordinate moves the point)
  let rows: { mark: HTMLElement; x: HTMLInputElement; y: HTMLInputElement }[] = [];
  const buildRows = (n: number) => {
    table.replaceChildren();
    const head = el(table, "tr");
    for (const h of ["#", "mark", "x", "y"]) el(head, "th", { textContent: h });
    rows = Array.from({ length: n }, (_, k) => {
      const tr = el(table, "tr");
      el(tr, "td", { textContent: String(k) });
      const mark = el(tr, "td");
      const coord = (axis: 0 | 1) => {
        const input = el(el(tr, "td"), "input", { type: "number", step: "any" }, `point-${"xy"[axis]}-${k}`);
        input.addEventListener("change", () => {
          const s = selected(), v = Number(input.value);
          if (s === null || input.value === "" || !Number.isFinite(v)) return;
          const xy = [...store.geometry!.curves[s].vertices[k]] as [number, number];
          xy[axis] = v;
          edit({ type: "move_vertex", curve: s, vertex: k, xy }, input);
        });
        return input;
      };
      return { mark, x: coord(0), y: coord(1) };
    });
  };

  const update = (force = false) => {
    const g: Geometry | null = store.geometry, s = selected();
    empty.hidden = s !== null;
    body.hidden = s === null;
    if (s === null || !g) {
      title.textContent = "Curve";
      return;
    }
    const c = g.curves[s];
    title.textContent = `Curve ${s}${c.name ? ` (${c.name})` : ""}`;
    show(fold, String(c.fold), force);
    fixed.hidden = c.mirror !== "fixed";
    show(mirror, c.mirror, force);
    const names = g.layers.map((z, i) => `${i} (bottom ${+z.toFixed(4)})`);
    if ([...layer.options].map((o) => o.text).join("\n") !== names.join("\n")) {
      layer.replaceChildren(...names.map((name, i) => new Option(name, String(i))));
    }
    show(layer, String(c.layer), force);
    show(color, store.color(s));
    const replicas = Math.max(0, ...g.pieces.filter((p) => p.basic === s).map((p) => p.transforms.shape[0]));
    info.textContent = `${replicas} ${replicas === 1 ? "replica" : "replicas"} · apex at ${+c.apex.toFixed(4)}` +
      ` · layer bottom ${+c.bottom.toFixed(4)}`;
    if (rows.length !== c.vertices.length) buildRows(c.vertices.length);
    c.vertices.forEach((v, k) => {
      rows[k].mark.textContent = c.marks[k];
      show(rows[k].x, String(+v[0].toFixed(6)), force);
      show(rows[k].y, String(+v[1].toFixed(6)), force);
    });
  };
  // once a frame: a drag's geometry stream never forces a layout in the middle of the listeners
  const schedule = perFrame(() => update());
  store.on("geometry", schedule);
  store.on("selection", schedule);
  store.on("looks", schedule);
  update();
}
