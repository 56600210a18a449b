// Files (#file-tools): new, the gallery of workspace drawings and bundled examples (which also
// opens a file from this computer), save, save as, export (a download of the server's file); the
// document's name in the toolbar and the tab title ("name •" while unsaved); #banner: autosave
// recovery, reconnecting.
import "./files.css";
import type { Ctx } from "./context";
import { Modal, Popover, button } from "./dialog";
import {
  type Card, type DrawingExt, type ExportChoice, MESH_FORMATS, documentLabel, documentName, drawingExt, exportRequest,
  galleryGroups, RESOLUTIONS, type Resolution, recoveryTime, savePath, suggestedName,
} from "./filemodel";
import { MAX_MESSAGE_BYTES, type ClientMessage, type Exported, type Files, type Geometry, type Thumbnail } from "./protocol";
import { registerShortcut } from "./shortcuts";

const EXPORTS: { format: ExportChoice; label: string }[] = [
  { format: "glb", label: "glTF binary (.glb)" },
  { format: "obj", label: "Wavefront OBJ (.obj)" },
  { format: "stl", label: "STL (.stl)" },
  { format: "ply", label: "PLY (.ply)" },
  { format: "svg", label: "Top and side views (.svg)" },
  { format: "network.json", label: "Curve network (.network.json)" },
];

export function initFiles(ctx: Ctx): void {
  const { store } = ctx;
  const tools = document.getElementById("file-tools")!;

  // ---- toolbar
  const localInput = document.createElement("input");
  localInput.type = "file";
  localInput.accept = ".uc,.json";
  localInput.hidden = true;
  localInput.dataset.testid = "open-local-input";
  localInput.addEventListener("change", () => {
    const file = localInput.files?.[0];
    localInput.value = ""; // picking the same file again opens it again
    if (file) void openLocal(file);
  });
  const saveButton = button("Save", "Save the drawing (Ctrl+S)", "save", () => void save(false));
  const saveAsButton = button("Save as…", "Save under another name, as .json or .uc (Ctrl+Shift+S)", "save-as",
    () => void save(true));
  const exportButton = button("Export ▾", "Download a mesh, SVG or the curve network (Ctrl+E)", "export",
    () => exportMenu.toggle());
  const docName = document.createElement("span");
  docName.className = "doc-name";
  docName.dataset.testid = "doc-name";
  tools.append(
    button("New", "Start an empty drawing", "new", () => void newDrawing()),
    button("Open…", "Open a drawing of the workspace, a bundled example or a file from this computer (Ctrl+O)", "open",
      () => void openGallery()),
    localInput, saveButton, saveAsButton, exportButton, docName,
  );
  const needsDocument = [saveButton, saveAsButton, exportButton];
  for (const b of needsDocument) b.disabled = true;

  store.on("geometry", (g) => {
    for (const b of needsDocument) b.disabled = false;
    // written only when they change: an edit's geometry mostly leaves them as they are
    const label = documentLabel(g);
    const tip = g.dirty ? `${documentName(g)}: unsaved changes (the studio autosaves them)` : documentName(g);
    if (docName.textContent !== label) docName.textContent = label;
    if (docName.title !== tip) docName.title = tip;
    if (document.title !== `${label} — auszug studio`) document.title = `${label} — auszug studio`;
    renderBanner();
  });

  /** A request whose failure is already shown in the status bar: resolves to null then. */
  const tryRequest = (msg: ClientMessage) => ctx.request(msg).catch(() => null);

  // ---- asking for a name (new drawing, save, save as)
  const nameDialog = new Modal("name-dialog", "");
  const nameForm = document.createElement("form");
  nameForm.innerHTML = `
    <label class="field"><span class="field-label"></span>
      <input type="text" name="name" required autocomplete="off" spellcheck="false" data-testid="name-input"></label>
    <label class="field format"><span class="field-label">Format</span>
      <select name="format" data-testid="name-format">
        <option value=".json">auszug drawing, lossless (.json)</option>
        <option value=".uc">web demo drawing (.uc)</option>
      </select></label>
    <p class="message" role="status"></p>
    <div class="actions"><button type="button" value="cancel">Cancel</button>
      <button type="submit" class="primary" data-testid="name-ok"></button></div>`;
  nameDialog.body.appendChild(nameForm);
  const nameInput = nameForm.querySelector("input")!;
  const formatSelect = nameForm.querySelector("select")!;
  const formatField = nameForm.querySelector(".format") as HTMLElement;
  const nameMessage = nameForm.querySelector(".message") as HTMLElement;
  const nameOk = nameForm.querySelector("[type=submit]") as HTMLButtonElement;
  nameForm.querySelector("[value=cancel]")!.addEventListener("click", () => nameDialog.close());
  // typing an extension picks the format
  nameInput.addEventListener("input", () => {
    const ext = drawingExt(nameInput.value);
    if (ext) formatSelect.value = ext;
  });

  interface NameQuestion {
    title: string;
    label: string;
    value: string;
    action: string;
    /** Ask for a drawing format too; the answer is then a workspace path with that extension. */
    format: boolean;
    /** Paths that exist already: choosing one asks for a second confirmation. */
    existing?: Promise<ReadonlySet<string>>;
    /** What is wrong with an answer, or null. */
    problem?(answer: string): string | null;
  }

  /** The name the user chose, or null when they cancelled. */
  function askName(q: NameQuestion): Promise<string | null> {
    nameDialog.setTitle(q.title);
    (nameForm.querySelector(".field-label") as HTMLElement).textContent = q.label;
    nameInput.value = q.value;
    formatField.hidden = !q.format;
    formatSelect.value = drawingExt(q.value) ?? ".json";
    nameOk.textContent = q.action;
    nameMessage.textContent = "";
    nameMessage.classList.remove("error");
    nameDialog.open();
    nameInput.focus();
    // select the stem, so typing replaces the name but keeps the extension
    const ext = q.format ? drawingExt(q.value) : null;
    nameInput.setSelectionRange(0, q.value.length - (ext ? ext.length : 0));
    let confirmed = "";
    return new Promise((resolve) => {
      const submit = async (ev: Event) => {
        ev.preventDefault();
        const answer = q.format ? savePath(nameInput.value, formatSelect.value as DrawingExt) : nameInput.value.trim();
        const problem = !answer ? "Type a file name." : q.problem?.(answer);
        if (!answer || problem) {
          nameMessage.textContent = problem ?? "";
          nameMessage.classList.add("error");
          return;
        }
        if ((await q.existing)?.has(answer) && confirmed !== answer) {
          confirmed = answer;
          nameMessage.textContent = `${answer} exists in the workspace: ${q.action} again to replace it.`;
          nameMessage.classList.add("error");
          return;
        }
        done(answer);
      };
      const done = (answer: string | null) => {
        nameForm.removeEventListener("submit", submit);
        nameDialog.el.removeEventListener("close", cancel);
        if (nameDialog.isOpen) nameDialog.close();
        resolve(answer);
      };
      const cancel = () => {
        if (!nameDialog.isOpen) done(null); // not a late "close" of an earlier question
      };
      nameForm.addEventListener("submit", submit);
      nameDialog.el.addEventListener("close", cancel);
    });
  }

  async function newDrawing(): Promise<void> {
    const name = await askName({
      title: "New drawing", label: "Name", value: "untitled", action: "Create", format: false,
      problem: (n) => (/[/\\]/.test(n) ? "A name without folders (save it into a folder later)." : null),
    });
    if (name) await tryRequest({ type: "new_drawing", name });
  }

  /** Save where the document came from; a document without a workspace file (or Save as) asks where. */
  async function save(as: boolean): Promise<void> {
    const g = store.geometry;
    if (!g) return;
    let path = g.path;
    if (as || !path) {
      const existing = tryRequest({ type: "list_files" }).then((r) => {
        const paths = new Set(r ? (r.msg as Files).workspace : []);
        paths.delete(g.path);
        return paths;
      });
      const answer = await askName({
        title: as ? "Save as" : "Save the drawing", label: "File name in the workspace", value: suggestedName(g),
        action: "Save", format: true, existing,
      });
      if (!answer) return;
      path = answer;
    }
    await tryRequest({ type: "save", path });
  }

  // ---- the gallery
  const gallery = new Modal("gallery", "Open a drawing");
  gallery.el.classList.add("gallery");
  const top = document.createElement("div");
  top.className = "gallery-top";
  const search = document.createElement("input");
  search.type = "search";
  search.placeholder = "Search drawings";
  search.setAttribute("aria-label", "Search drawings");
  search.dataset.testid = "gallery-search";
  top.append(search, button("Open file from this computer…", "Open a .uc or .json file from this computer",
    "gallery-local", () => localInput.click()));
  const galleryMessage = document.createElement("p");
  galleryMessage.className = "message";
  galleryMessage.setAttribute("role", "status");
  const groupsEl = document.createElement("div");
  groupsEl.className = "gallery-groups";
  // workspace entries the server skipped (a link loop, an unreadable folder): said, not hidden
  const notesEl = document.createElement("ul");
  notesEl.className = "gallery-notes";
  notesEl.dataset.testid = "gallery-notes";
  gallery.body.append(top, galleryMessage, groupsEl, notesEl);
  let listing: Files | null = null;

  // thumbnails: each card's top view (get_thumbnail, an SVG shown as an image, so it runs no script),
  // asked for one at a time in the gallery's order; examples are kept, workspace files asked again
  // each time the gallery opens (they may have changed)
  const thumbs = new Map<string, string>();   // key -> data: URL ("" while asked, "-" when it failed)
  const thumbKey = (c: Card) => `${c.kind}:${c.path}`;
  let thumbRun = 0;
  async function loadThumbnails(cards: [Card, HTMLImageElement][]): Promise<void> {
    const run = ++thumbRun;
    for (const [c, img] of cards) {
      if (run !== thumbRun || !gallery.isOpen) return;
      const key = thumbKey(c);
      let url = thumbs.get(key);
      if (url === undefined) {
        thumbs.set(key, "");
        try {
          const reply = await ctx.conn.request(c.kind === "example"
            ? { type: "get_thumbnail", example: c.path } : { type: "get_thumbnail", path: c.path });
          url = `data:image/svg+xml;charset=utf-8,${encodeURIComponent((reply.msg as Thumbnail).svg)}`;
        } catch {
          url = "-";   // unreadable drawing: the card stays without a picture (opening it says why)
        }
        thumbs.set(key, url);
      }
      if (url && url !== "-") img.src = url;
    }
  }

  function renderGallery(): void {
    groupsEl.replaceChildren();
    notesEl.replaceChildren();
    if (!listing) return;
    for (const note of listing.notes) {
      const li = document.createElement("li");
      li.textContent = note;
      notesEl.appendChild(li);
    }
    const groups = galleryGroups(listing, search.value);
    galleryMessage.classList.remove("error");
    galleryMessage.textContent = groups.length ? "" : `No drawing matches “${search.value.trim()}”.`;
    const current = store.geometry?.path;
    const pictures: [Card, HTMLImageElement][] = [];
    for (const group of groups) {
      const section = document.createElement("section");
      const h = document.createElement("h3");
      h.textContent = group.title;
      const cards = document.createElement("div");
      cards.className = "cards";
      for (const c of group.cards) {
        const b = document.createElement("button");
        b.type = "button";
        b.className = "card";
        b.dataset.testid = "gallery-card";
        b.dataset.kind = c.kind;
        b.dataset.path = c.path;
        b.title = c.kind === "example" ? `bundled example ${c.path}` : c.path;
        if (c.kind === "workspace" && c.path === current) b.classList.add("current");
        const name = document.createElement("span");
        name.className = "card-name";
        name.textContent = c.label;
        const ext = document.createElement("span");
        ext.className = "card-ext";
        ext.textContent = c.ext;
        const img = document.createElement("img");
        img.className = "card-thumb";
        img.dataset.testid = "gallery-thumb";
        img.width = img.height = 96;
        img.alt = "";
        pictures.push([c, img]);
        b.append(img, name, ext);
        b.addEventListener("click", () => void openCard(c, b));
        cards.appendChild(b);
      }
      section.append(h, cards);
      groupsEl.appendChild(section);
    }
    void loadThumbnails(pictures);
  }

  async function openGallery(): Promise<void> {
    gallery.open();
    search.value = "";
    search.focus();
    listing = null;
    for (const key of [...thumbs.keys()]) if (key.startsWith("workspace:")) thumbs.delete(key);
    renderGallery();
    galleryMessage.textContent = "Loading…";
    try {
      const reply = await ctx.request({ type: "list_files" });
      listing = reply.msg as Files;
      renderGallery();
    } catch (e) {
      galleryMessage.textContent = `Could not list the drawings: ${(e as Error).message}`;
      galleryMessage.classList.add("error");
    }
  }

  async function openCard(c: Card, el: HTMLButtonElement): Promise<void> {
    el.classList.add("busy");
    groupsEl.setAttribute("aria-busy", "true");
    const msg: ClientMessage = c.kind === "workspace" ? { type: "open", path: c.path } : { type: "open_example", name: c.path };
    try {
      await ctx.request(msg);
      gallery.close();
    } catch (e) {
      galleryMessage.textContent = `Could not open ${c.path}: ${(e as Error).message}`;
      galleryMessage.classList.add("error");
    } finally {
      el.classList.remove("busy");
      groupsEl.removeAttribute("aria-busy");
    }
  }

  search.addEventListener("input", renderGallery);
  search.addEventListener("keydown", (ev) => {
    if (ev.key !== "Enter") return;
    const first = groupsEl.querySelector<HTMLButtonElement>(".card");
    if (first) first.click();
  });

  // ---- a local file: its text goes to the server, which reads it by its name's format
  async function openLocal(file: File): Promise<void> {
    const msg: ClientMessage = { type: "open_text", name: file.name, text: await file.text() };
    const bytes = new TextEncoder().encode(JSON.stringify(msg)).length;
    if (bytes > MAX_MESSAGE_BYTES) {
      store.status(`${file.name} is too large to open here (${Math.ceil(bytes / 1024)} KiB; the limit is ` +
        `${MAX_MESSAGE_BYTES / 1024} KiB): copy it into the workspace folder and open it from there`, true);
      return;
    }
    if (await tryRequest(msg)) gallery.close();
  }

  // ---- export: the Exported reply's binary frame becomes a download
  const exportMenu = new Popover(exportButton, "export-menu", { menu: true });
  exportMenu.el.classList.add("export-menu");
  exportMenu.el.setAttribute("role", "menu");
  const solid = document.createElement("input");
  solid.type = "checkbox";
  solid.dataset.testid = "export-solid";
  // the mesh exports' resolution (light meshes for games and the web; fine for renders and prints)
  const resRow = document.createElement("div");
  resRow.className = "row";
  const resLabel = document.createElement("label");
  resLabel.title = "Steps along each member and points round a tube in glb, obj, stl and ply";
  const resolution = document.createElement("select");
  resolution.dataset.testid = "export-resolution";
  for (const [value, r] of Object.entries(RESOLUTIONS)) resolution.add(new Option(r.label, value));
  resLabel.append("mesh ", resolution);
  resRow.appendChild(resLabel);
  exportMenu.el.appendChild(resRow);
  for (const { format, label } of EXPORTS) {
    const row = document.createElement("div");
    row.className = "row";
    const b = button(label, MESH_FORMATS.includes(format) ? "Members and faces as shown by the looks" : "",
      `export-${format}`, () => void doExport(format));
    b.setAttribute("role", "menuitem");
    row.appendChild(b);
    if (format === "stl") {
      const l = document.createElement("label");
      l.title = "One watertight solid (members and faces united), ready for a slicer";
      l.append(solid, " printable solid");
      row.appendChild(l);
    }
    exportMenu.el.appendChild(row);
  }

  async function doExport(format: ExportChoice): Promise<void> {
    const g = store.geometry;
    if (!g) return;
    exportMenu.close();
    const colors = Array.from({ length: g.n_curves }, (_, i) => store.color(i));
    store.status(`exporting ${format}…`);
    const reply = await tryRequest(exportRequest(format, store.looks, colors, solid.checked,
      resolution.value as Resolution));
    if (!reply || !reply.binary) return;
    const { name, mime, size } = reply.msg as Exported;
    download(reply.binary, name, mime);
    store.status(`exported ${name} (${size < 1024 ? `${size} bytes` : `${Math.ceil(size / 1024)} KiB`})`);
  }

  // ---- the banner: reconnecting, or an autosave to restore
  const banner = document.getElementById("banner")!;
  let dismissed = "";
  const recoveryKey = (g: Geometry) => `${documentName(g)}\u0000${g.recoverable}`;

  let bannerShows: string | null = null;

  function renderBanner(): void {
    const g = store.geometry;
    // rebuilt only when what it shows changes (every edit's geometry calls this)
    const shows = `${document.body.dataset.connected}\u0000${g ? recoveryKey(g) : ""}\u0000${dismissed}`;
    if (shows === bannerShows) return;
    bannerShows = shows;
    banner.replaceChildren();
    delete banner.dataset.state;
    if (document.body.dataset.connected === "false") {
      banner.dataset.state = "reconnecting";
      banner.textContent = "Lost the connection to the studio server: reconnecting…";
    } else if (g && g.recoverable && recoveryKey(g) !== dismissed) {
      banner.dataset.state = "recovery";
      const text = document.createElement("span");
      text.textContent = `Unsaved changes from ${recoveryTime(g.recoverable)} were recovered from autosave.`;
      const restore = button("Restore", "Replace the drawing by its autosaved version",
        "recover", () => void tryRequest({ type: "recover" }));
      const discard = button("Discard", "Keep the drawing as it is", "recover-discard", () => {
        dismissed = recoveryKey(g);
        renderBanner();
      });
      banner.append(text, restore, discard);
    }
    banner.dataset.testid = "banner";
    banner.hidden = !banner.dataset.state;
  }
  // main.ts marks the connection on <body data-connected>
  new MutationObserver(renderBanner).observe(document.body, { attributes: true, attributeFilter: ["data-connected"] });

  // ---- shortcuts
  registerShortcut({ key: "s", ctrl: true, description: "Save", run: () => void save(false) });
  registerShortcut({ key: "s", ctrl: true, shift: true, description: "Save as", run: () => void save(true) });
  registerShortcut({ key: "o", ctrl: true, description: "Open a drawing (gallery)", run: () => void openGallery() });
  registerShortcut({
    key: "e", ctrl: true, description: "Export", run: () => {
      if (exportButton.disabled) return;
      exportMenu.open();
      exportMenu.el.querySelector("button")!.focus();
    },
  });
}

/** Hand bytes to the browser as a download called `name`. */
function download(data: ArrayBuffer, name: string, mime: string): void {
  const url = URL.createObjectURL(new Blob([data], { type: mime }));
  const a = document.createElement("a");
  a.href = url;
  a.download = name;
  a.hidden = true;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 60_000); // revoking at once may cancel the download
}
