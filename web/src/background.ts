// A background image in the top view for tracing (#extra-tools): load a PNG or JPEG, move it
// (x, y, or Shift+drag on it), scale it (width, slider, or Shift+wheel), opacity, show/hide,
// remove. A textured plane seen by the top view only, under the curves. Its placement is kept
// per document in localStorage (the image itself is not: load it again).
import * as THREE from "three";
import "./background.css";
import { contains, fit, parsePlacement, scaleAbout, storageKey, type Placement } from "./bgmodel";
import type { Ctx } from "./context";
import { Popover, button } from "./dialog";
import { VIEW_LAYER } from "./scene";

/** The size slider spans 1/10 to 10 times the drawing's extent (log scale). */
const SLIDER_DECADES = 1;

export function initBackground(ctx: Ctx): void {
  const { store, views } = ctx;
  const toggle = button("Background", "A background image to trace in the top view", "background", () => pop.toggle());
  document.getElementById("extra-tools")!.appendChild(toggle);
  const pop = new Popover(toggle, "background-popover");
  pop.el.classList.add("background-popover");
  pop.el.innerHTML = `
    <h3>Background image</h3>
    <input type="file" accept="image/png,image/jpeg" hidden data-testid="background-input">
    <div class="row"><button type="button" data-testid="background-load">Load image…</button>
      <label class="show"><input type="checkbox" name="visible" checked data-testid="background-visible"> show</label>
      <button type="button" data-testid="background-remove">Remove</button></div>
    <div class="grid">
      <label>x <input type="number" name="x" step="any" data-testid="background-x"></label>
      <label>y <input type="number" name="y" step="any" data-testid="background-y"></label>
      <label>width <input type="number" name="width" step="any" min="0" data-testid="background-width"></label>
      <input type="range" name="size" min="${-SLIDER_DECADES}" max="${SLIDER_DECADES}" step="0.01"
        aria-label="size" data-testid="background-size">
      <label class="wide">opacity <input type="range" name="opacity" min="0" max="1" step="0.01" data-testid="background-opacity"></label>
    </div>
    <p class="hint">In the top view: Shift+drag the image to move it, Shift+wheel to scale it.</p>`;
  const q = <T extends HTMLElement>(sel: string) => pop.el.querySelector(sel) as T;
  const fileInput = q<HTMLInputElement>("input[type=file]");
  const input = (name: string) => q<HTMLInputElement>(`input[name=${name}]`);
  const [xIn, yIn, widthIn, sizeIn, opacityIn, visibleIn] = ["x", "y", "width", "size", "opacity", "visible"].map(input);
  const removeButton = q<HTMLButtonElement>("[data-testid=background-remove]");
  const controls = [xIn, yIn, widthIn, sizeIn, opacityIn, visibleIn, removeButton];

  let mesh: THREE.Mesh<THREE.PlaneGeometry, THREE.MeshBasicMaterial> | null = null;
  let aspect = 1; // the image's height / width
  let place: Placement | null = null;
  let docKey = "";

  /** The drawing's extent in the top view (what the size slider is relative to). */
  const extent = () => {
    const s = views.bounds.getSize(new THREE.Vector3());
    return Math.max(s.x, s.y, 1e-6);
  };

  /** Show `place` on the plane and in the controls (but `typing`, the one it came from); keep it. */
  function apply(typing?: HTMLInputElement): void {
    const on = !!mesh && !!place;
    for (const c of controls) c.disabled = !on;
    toggle.classList.toggle("active", on);
    if (!mesh || !place) return;
    const b = views.bounds, diagonal = b.getSize(new THREE.Vector3()).length();
    mesh.position.set(place.x, place.y, b.min.z - Math.max(0.02 * diagonal, 1e-3));
    mesh.scale.set(place.width, place.width * aspect, 1);
    mesh.material.opacity = place.opacity;
    mesh.visible = place.visible;
    const show = (el: HTMLInputElement, v: number, digits: number) => {
      if (el !== typing) el.value = String(Number(v.toFixed(digits)));
    };
    show(xIn, place.x, 4);
    show(yIn, place.y, 4);
    show(widthIn, place.width, 4);
    show(sizeIn, Math.log10(place.width / extent()), 2);
    show(opacityIn, place.opacity, 2);
    visibleIn.checked = place.visible;
    if (docKey) {
      try {
        localStorage.setItem(docKey, JSON.stringify(place));
      } catch {
        // storage full or disabled: the placement is simply not remembered
      }
    }
    views.requestRender();
  }

  function change(p: Partial<Placement>, typing?: HTMLInputElement): void {
    if (!place) return;
    place = { ...place, ...p };
    apply(typing);
  }

  function stored(): Placement | null {
    try {
      return docKey ? parsePlacement(localStorage.getItem(docKey)) : null;
    } catch {
      return null;
    }
  }

  async function load(file: File): Promise<void> {
    const url = URL.createObjectURL(file);
    let texture: THREE.Texture;
    try {
      texture = await new THREE.TextureLoader().loadAsync(url);
    } catch {
      store.status(`${file.name}: not an image the browser can read (PNG or JPEG)`, true);
      return;
    } finally {
      URL.revokeObjectURL(url); // the decoded image stays with the texture
    }
    remove();
    texture.colorSpace = THREE.SRGBColorSpace;
    const img = texture.image as HTMLImageElement;
    aspect = img.height / Math.max(img.width, 1);
    const material = new THREE.MeshBasicMaterial({
      map: texture, transparent: true, depthWrite: false, side: THREE.DoubleSide, toneMapped: false,
    });
    mesh = new THREE.Mesh(new THREE.PlaneGeometry(1, 1), material);
    mesh.name = "background";
    mesh.layers.set(VIEW_LAYER.top); // the top view only
    mesh.renderOrder = -1; // before the (transparent) faces; the curves' depth keeps them on top
    views.scene.add(mesh);
    const r = views.rect("top");
    const fitted = fit(views.topCenter.x, views.topCenter.y, (r?.w ?? 1) * views.topScale, (r?.h ?? 1) * views.topScale, aspect);
    place = { ...(stored() ?? fitted), visible: true };
    apply();
    store.status(`background image ${file.name} (${img.width} x ${img.height} px)`);
  }

  /** Take the plane out and free its texture, geometry and material (on the GPU too). */
  function remove(): void {
    if (!mesh) return;
    views.scene.remove(mesh);
    mesh.geometry.dispose();
    mesh.material.map?.dispose();
    mesh.material.dispose();
    mesh = null;
    place = null;
    apply();
    views.requestRender();
  }

  q<HTMLButtonElement>("[data-testid=background-load]").addEventListener("click", () => fileInput.click());
  fileInput.addEventListener("change", () => {
    const file = fileInput.files?.[0];
    fileInput.value = "";
    if (file) void load(file);
  });
  removeButton.addEventListener("click", remove);
  const number = (el: HTMLInputElement, key: "x" | "y" | "width") => el.addEventListener("input", () => {
    const v = el.valueAsNumber;
    if (Number.isFinite(v) && (key !== "width" || v > 0)) change({ [key]: v }, el);
  });
  number(xIn, "x");
  number(yIn, "y");
  number(widthIn, "width");
  sizeIn.addEventListener("input", () => change({ width: extent() * 10 ** sizeIn.valueAsNumber }, sizeIn));
  opacityIn.addEventListener("input", () => change({ opacity: opacityIn.valueAsNumber }, opacityIn));
  visibleIn.addEventListener("change", () => change({ visible: visibleIn.checked }));
  // typed values are shown rounded once the field is left
  for (const el of [xIn, yIn, widthIn]) el.addEventListener("blur", () => apply());

  // Another document: its own remembered placement, else this one is remembered for it too.
  // New geometry also moves the plane under the drawing's new lowest point.
  store.on("geometry", (g) => {
    const key = storageKey(g);
    if (key !== docKey) {
      docKey = key;
      const s = stored();
      if (s && place) place = s;
    }
    apply();
  });

  // ---- Shift+drag on the image moves it; Shift+wheel over the top view scales it about the pointer.
  // Listening on the viewport in the capture phase comes before the top view's own pan and zoom.
  const host = views.host;
  const topPoint = (ev: MouseEvent): [number, number] => {
    const r = views.rect("top")!, b = views.box();
    return views.screenToTop(ev.clientX - b.left - r.x, ev.clientY - b.top - r.y);
  };
  const active = (ev: MouseEvent) => ev.shiftKey && !!mesh && !!place && place.visible &&
    views.viewAt(ev.clientX, ev.clientY) === "top";
  let drag: { x: number; y: number; from: Placement } | null = null;
  host.addEventListener("pointerdown", (ev) => {
    if (ev.button !== 0 || !active(ev)) return;
    const [x, y] = topPoint(ev);
    if (!contains(place!, aspect, x, y)) return;
    ev.preventDefault();
    ev.stopPropagation();
    drag = { x, y, from: place! };
  }, { capture: true });
  window.addEventListener("pointermove", (ev) => {
    if (!drag) return;
    const [x, y] = topPoint(ev);
    change({ x: drag.from.x + x - drag.x, y: drag.from.y + y - drag.y });
  });
  window.addEventListener("pointerup", () => { drag = null; });
  host.addEventListener("wheel", (ev) => {
    if (!active(ev)) return;
    ev.preventDefault();
    ev.stopPropagation();
    const [x, y] = topPoint(ev);
    // with Shift, some systems turn the wheel into a horizontal scroll
    place = scaleAbout(place!, x, y, Math.exp(-(ev.deltaY || ev.deltaX) * 0.0015));
    apply();
  }, { capture: true, passive: false });

  apply();
}
