"""End to end, the tracery page: every style in 2D and 3D, a value change, a refused value at its field,
save and reopen, exports, undo / redo and the URL (docs/studio.md, "Tracery page")."""

from __future__ import annotations

import math
import tomllib
from typing import Any
from urllib.parse import quote

import numpy as np
import pytest

from auszug.tracery import build, builtin_styles, load_style

from .e2e import SHOTS, browser, needs_browser, page, studio  # noqa: F401  (fixtures)

pytestmark = needs_browser

SHOWN = "() => window.auszugTracery && window.auszugTracery.shown()"


def open_tracery(page: Any, studio: Any, query: str = "") -> dict:
    page.goto(f"{studio.url}tracery.html{query}")
    page.wait_for_function(f"() => {{ const s = ({SHOWN})(); return s && s.regions.length > 0; }}", timeout=30000)
    return shown(page)


def shown(page: Any) -> dict:
    return page.evaluate(SHOWN)


def state(page: Any) -> dict:
    return page.evaluate("() => window.auszugTracery.state()")


def frames(page: Any) -> int:
    return int(page.evaluate("() => window.auszugTracery.view3d.frames"))


def scene_extent(page: Any) -> list[float]:
    """The bounding box of the vertices the 3D view holds (read from its buffer, not from the message)."""
    return page.evaluate("""() => {
        const v = window.auszugTracery.view3d, g = v.geometry, p = g.getAttribute('position').array;
        const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
        // the vertices the drawn triangles use (the buffers are kept between edits, larger than the mesh)
        const drawn = g.getIndex().array.subarray(g.drawRange.start, g.drawRange.start + g.drawRange.count);
        const used = new Set(Array.from(drawn));
        if (used.size !== v.used) return null;
        for (let i = 0; i < 3 * v.used; i += 3) for (let k = 0; k < 3; k++) {
          lo[k] = Math.min(lo[k], p[i + k]); hi[k] = Math.max(hi[k], p[i + k]); }
        return [...lo, ...hi];
    }""")


def svg_paths(page: Any) -> list[dict]:
    return page.evaluate("""() => [...document.querySelectorAll('[data-testid=tracery-svg] path')].map(
        (p) => ({id: p.dataset.id, role: p.dataset.role, d: p.getAttribute('d')}))""")


def field(page: Any, key: str) -> Any:
    return page.locator(f"[data-testid='field-{key}']")


def set_field(page: Any, key: str, text: str) -> None:
    f = field(page, key)
    f.fill(text)
    f.press("Enter")


def wait_value(page: Any, item: str) -> dict:
    page.wait_for_function(f"() => window.auszugTracery.state().values.includes({item!r})", timeout=20000)
    page.evaluate("() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))")
    return shown(page)


def shot(page: Any, name: str) -> None:
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / f"tracery_{name}.png"))


@pytest.mark.parametrize("name", [*builtin_styles(), "prototype"])
def test_each_style_shows_its_regions_in_2d_and_its_window_in_3d(studio, page, name):
    open_tracery(page, studio)
    page.select_option("[data-testid=tracery-style]", f"style:{name}")
    page.wait_for_function(f"() => window.auszugTracery.shown().style === {name!r}", timeout=30000)
    page.evaluate("() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)))")
    s = shown(page)
    t = build("fig20a" if name == "prototype" else name)
    # the SVG holds every region of the style, with its exact arcs (one A command per arc, at least)
    paths = svg_paths(page)
    assert [p["id"] for p in paths] == [r.id for r in t.regions]
    n_arcs = sum(type(c).__name__ == "Arc" for r in t.regions for c in r.curves)
    assert sum(p["d"].count("A") for p in paths) >= n_arcs > 0
    assert s["n_lights"] == len(t.lights) and s["depth"] == t.depth
    # 2D: the arch is `span` wide and its apex sits at height + span/2 sqrt(4 excess - 1) (pointed arch by excess)
    span, height, excess = t.params.span, t.params.height, t.params.excess
    x0, y0, x1, y1 = s["bounds"]
    assert x1 - x0 == pytest.approx(span, abs=1e-9)
    assert y1 == pytest.approx(height + span / 2 * math.sqrt(4 * excess - 1), abs=1e-6)
    # 3D: the view holds the window's front half in its wall (front face at -t/2, the middle plane at 0) and
    # draws the back half as its mirror image in the middle plane
    lo_hi = scene_extent(page)
    thick = t.style.wall.thickness
    assert lo_hi[1] == pytest.approx(-thick / 2, abs=1e-6) and lo_hi[4] == pytest.approx(0.0, abs=1e-9)
    assert page.evaluate("""() => { const v = window.auszugTracery.view3d, g = v.geometry, b = v.back.geometry;
        return b.getAttribute('position') === g.getAttribute('position') && b.getIndex() === g.getIndex()
          && b.getAttribute('color') !== g.getAttribute('color') && v.back.scale.toArray().join() === '1,-1,1'; }""")
    assert lo_hi[3] - lo_hi[0] == pytest.approx(span + 2 * t.style.wall.margin, abs=1e-5)
    assert s["indices"]["shape"][0] > 0 and frames(page) > 0
    # every vertex is shaded, front and back (a colour buffer left from the previous style's smaller mesh
    # drew black); the back half (shaded when first drawn: the camera goes behind the wall, and back) is
    # shaded as the mirror image it is, not with the front's colours
    assert page.evaluate("""() => { const v = window.auszugTracery.view3d, g = v.geometry;
        const front = v.camera.position.clone();
        v.camera.position.y = 2 * v.orbit.target.y - front.y;
        v.render();
        const drawnBack = v.back.visible;
        v.camera.position.copy(front);
        v.render();
        if (!drawnBack || v.back.visible) return false;
        const drawn = 3 * window.auszugTracery.shown().indices.shape[0];
        let differ = 0;
        for (const geo of [g, v.back.geometry]) {
          const c = geo.getAttribute('color');
          if (c.count !== g.getAttribute('position').count || geo.drawRange.count !== drawn) return false;
          for (let i = 0; i < v.used; i++) {
            if (!(Math.min(c.getX(i), c.getY(i), c.getZ(i)) > 0.01)) return false;
          }
        }
        const p = g.getAttribute('position'), y0 = p.getY(0);
        const c = g.getAttribute('color'), cb = v.back.geometry.getAttribute('color');
        for (let i = 0; i < v.used; i++) if (p.getY(i) === y0 && Math.abs(c.getX(i) - cb.getX(i)) > 0.05) differ++;
        return differ > 0; }""")
    # the camera: the design page's raised three-quarter view (35 degrees up, 35 round), the window inside it
    cam = page.evaluate("""() => { const v = window.auszugTracery.view3d, p = v.camera.position, t = v.orbit.target;
        return {d: [p.x - t.x, p.y - t.y, p.z - t.z], inside: v.inView()}; }""")
    d = np.array(cam["d"]) / np.linalg.norm(cam["d"])
    assert math.degrees(math.asin(d[2])) == pytest.approx(35.0, abs=1e-3)
    assert math.degrees(math.atan2(d[0], -d[1])) == pytest.approx(35.0, abs=1e-3)
    assert cam["inside"]
    shot(page, f"style_{name}")
    # a value changed in this style: the 2D and the 3D view follow (the arch 2.5 wide, the wall with it)
    f0 = frames(page)
    set_field(page, "params.span", "2.5")
    after = wait_value(page, "params.span=2.5")
    assert after["bounds"][2] - after["bounds"][0] == pytest.approx(2.5, abs=1e-9)
    ext = scene_extent(page)
    assert ext[3] - ext[0] == pytest.approx(2.5 + 2 * t.style.wall.margin, abs=1e-5)
    assert frames(page) > f0 and len(svg_paths(page)) == len(t.regions)


def test_a_value_change_redraws_2d_and_3d_and_goes_into_the_url(studio, page):
    before = open_tracery(page, studio, "?style=fig20h")
    ext0 = scene_extent(page)
    f0 = frames(page)
    assert before["bounds"][2] - before["bounds"][0] == pytest.approx(2.0)
    page.evaluate("() => { window.keptPaths = [...document.querySelectorAll('[data-testid=tracery-svg] path')]; }")
    set_field(page, "params.span", "3")
    after = wait_value(page, "params.span=3")
    # the SVG's path elements are kept and their shapes rewritten in place, every one of them
    assert page.evaluate("""() => { const now = [...document.querySelectorAll('[data-testid=tracery-svg] path')];
        return now.length === window.keptPaths.length && now.every((p, i) => p === window.keptPaths[i]); }""")
    now_d = [p["d"] for p in svg_paths(page)]
    assert now_d == [r["d"] for r in after["regions"]] != [r["d"] for r in before["regions"]]
    # 2D: the arch is 3 wide now; 3D: the wall (margin and reveal fixed) grew by exactly the span's 1
    assert after["bounds"][2] - after["bounds"][0] == pytest.approx(3.0, abs=1e-9)
    ext1 = scene_extent(page)
    assert (ext1[3] - ext1[0]) - (ext0[3] - ext0[0]) == pytest.approx(1.0, abs=1e-5)
    assert frames(page) > f0
    assert "v=params.span%3D3" in page.url and "style=fig20h" in page.url
    assert field(page, "params.span").input_value() == "3"
    shot(page, "span_3")
    # a choice: lying rosettes in the circles (the rosette regions' borders change, not their number)
    paths0 = {p["id"]: p["d"] for p in svg_paths(page)}
    page.select_option("[data-testid='field-circle.orientation']", "lying")
    after2 = wait_value(page, 'circle.orientation="lying"')
    assert len(after2["regions"]) == len(after["regions"])
    changed = [p["id"] for p in svg_paths(page) if p["d"] != paths0[p["id"]]]
    assert changed and all("rosette" in i for i in changed)


def test_a_refused_value_is_explained_at_its_field_and_changes_nothing(studio, page):
    open_tracery(page, studio, "?style=fig20b")
    set_field(page, "circle.foils", "5")
    good = wait_value(page, "circle.foils=5")
    paths, ext, url, st = svg_paths(page), scene_extent(page), page.url, state(page)
    for key, bad in (("params.excess", "1e300"), ("params.inner", "0.3"), ("circle.foils", "1"), ("params.span", "x")):
        n = int(page.evaluate("() => Number(document.body.dataset.refused || 0)"))
        set_field(page, key, bad)
        page.wait_for_function(f"() => Number(document.body.dataset.refused || 0) > {n}", timeout=20000)
        msg = page.locator(f"[data-testid=field-error][data-for='field-{key}']")
        assert msg.is_visible()
        text = msg.text_content()
        assert key.split(".")[-1] in text, text
        assert field(page, key).get_attribute("aria-invalid") == "true"
        # nothing changed: the state, the URL, the 2D paths and the 3D buffer
        assert state(page) == st and page.url == url
        assert svg_paths(page) == paths and scene_extent(page) == ext
        assert shown(page)["values"] == st["values"]
        if key == "params.excess":
            shot(page, "refused_excess")
        # back to the good value: the message goes, the window is the same as before
        value = field_value(good, key)
        set_field(page, key, str(value))
        wait_value(page, f"{key}={value}")
        assert not page.locator(f"[data-testid=field-error][data-for='field-{key}']").count()
        assert field(page, key).get_attribute("aria-invalid") is None
        assert svg_paths(page) == paths and scene_extent(page) == ext
        st, url = state(page), page.url


def field_value(s: dict, key: str) -> Any:
    return next(f["value"] for f in s["fields"] if f["key"] == key)


def test_save_as_toml_and_json_reopens_to_the_same_window(studio, page):
    open_tracery(page, studio, "?style=fig20b")
    set_field(page, "circle.foils", "6")
    wait_value(page, "circle.foils=6")
    set_field(page, "params.excess", "1.1")
    shown_before = wait_value(page, "params.excess=1.1")
    paths = svg_paths(page)
    for target in ("styles/six.toml", "six.style.json"):
        page.fill("[data-testid=tracery-save-name]", target)
        page.click("[data-testid=tracery-save]")
        page.wait_for_function(f"() => document.body.dataset.saved === {target!r}", timeout=20000)
        file = studio.workspace / target
        if target.endswith(".toml"):
            data = tomllib.loads(file.read_text())
            assert data["circle"]["foils"] == 6 and data["params"]["excess"] == 1.1
        st = load_style(file)
        assert st.circle.foils == 6 and st.params.excess == 1.1
        t = build(st)
        from auszug.tracery.draw import path_data

        # the file reopens to exactly the window the page showed (the same exact borders)
        assert [(r.id, path_data(r.curves)) for r in t.regions] == [(p["id"], p["d"]) for p in paths]
        # the page now shows the file, reopened by the server, the same window
        page.wait_for_function(f"() => window.auszugTracery.state().path === {target!r}", timeout=20000)
        assert svg_paths(page) == paths
        assert not list(file.parent.glob("*.tmp*"))
    assert shown_before["values"] == ["circle.foils=6", "params.excess=1.1"]
    # the workspace's style files are in the picker
    opts = page.eval_on_selector_all("[data-testid=tracery-style] option", "os => os.map((o) => o.value)")
    assert "path:styles/six.toml" in opts and "path:six.style.json" in opts
    # a name without .toml/.json is refused at the name field, nothing written
    page.fill("[data-testid=tracery-save-name]", "bad.txt")
    page.click("[data-testid=tracery-save]")
    assert page.locator("[data-testid=field-error][data-for=tracery-save-name]").is_visible()
    assert not (studio.workspace / "bad.txt").exists()
    shot(page, "saved")


@pytest.mark.parametrize("fmt", ["glb", "stl"])
def test_export_is_one_watertight_mesh_of_the_window(studio, page, fmt, tmp_path):
    import trimesh

    s = open_tracery(page, studio, "?style=fig20c&v=params.span%3D2.5")
    with page.expect_download(timeout=120000) as dl:
        page.click(f"[data-testid=tracery-export-{fmt}]")
    out = tmp_path / dl.value.suggested_filename
    dl.value.save_as(out)
    assert out.suffix == f".{fmt}"
    m = trimesh.load(out, force="mesh")
    assert m.is_watertight and m.is_winding_consistent and m.volume > 0
    lo, hi = m.bounds
    # glTF is y up: the window's depth (the wall's thickness) is its z there
    depth = (hi - lo)[2] if fmt == "glb" else (hi - lo)[1]
    assert depth == pytest.approx(0.9, abs=1e-5)
    # the wall: the span and the margin on both sides, as the preview shows it
    assert (hi - lo)[0] == pytest.approx(2.5 + 2 * 0.6, abs=1e-5)
    assert s["mesh_bounds"][3] - s["mesh_bounds"][0] == pytest.approx(2.5 + 2 * 0.6, abs=1e-5)


def test_undo_redo_and_the_url_restore_the_page(studio, page):
    open_tracery(page, studio, "?style=fig20d&v=circle.foils%3D6&v=params.excess%3D1.1")
    assert field(page, "circle.foils").input_value() == "6"
    assert field(page, "params.excess").input_value() == "1.1"
    first = svg_paths(page)
    set_field(page, "params.height", "5")
    wait_value(page, "params.height=5")
    second = svg_paths(page)
    assert second != first
    page.click("[data-testid=undo]")
    page.wait_for_function("() => !window.auszugTracery.state().values.some((v) => v.startsWith('params.height'))")
    assert svg_paths(page) == first and "params.height" not in page.url
    page.click("[data-testid=redo]")
    wait_value(page, "params.height=5")
    assert svg_paths(page) == second
    # a reload (or the copied URL) comes back to the same window
    url = page.url
    page.reload()
    page.wait_for_function("() => window.auszugTracery && window.auszugTracery.shown()", timeout=30000)
    assert svg_paths(page) == second and page.url == url
    assert field(page, "params.height").input_value() == "5"
    shot(page, "url_restored")


def test_the_pages_link_to_each_other(studio, page):
    page.goto(studio.url)
    page.click("[data-testid=page-tracery]")
    page.wait_for_function(f"() => {{ const s = ({SHOWN})(); return s && s.regions.length > 0; }}", timeout=30000)
    assert "tracery.html" in page.url and shown(page)["style"] == "fig20a"
    page.click("[data-testid=page-design]")
    page.wait_for_function("() => window.auszug && window.auszug.store", timeout=30000)
    assert "tracery" not in page.url


def test_a_style_file_from_the_workspace_opens(studio, page):
    (studio.workspace / "w.toml").write_text('extends = "fig20b"\n[circle]\nfoils = 5\n')
    open_tracery(page, studio, f"?path={quote('w.toml')}")
    assert field(page, "circle.foils").input_value() == "5"
    assert shown(page)["name"] == "w"
    # a broken one: the message at the picker, the page keeps its window
    (studio.workspace / "bad.toml").write_text("[circle\n")
    paths = svg_paths(page)
    ok = page.evaluate("() => window.auszugTracery.change({style: '', path: 'bad.toml', values: []})")
    assert ok is False and svg_paths(page) == paths
    assert "bad.toml" in page.locator("#status").text_content()


def test_the_3d_view_draws_each_vertex_colour_encoded_to_srgb(studio, page):
    """The 3D view's pixels are its vertex colours (linear RGB, the lighting) encoded to sRGB: read
    at the centre of the largest triangle on screen whose three vertices have one colour."""
    open_tracery(page, studio)
    res = page.evaluate("""() => { const v = window.auszugTracery.view3d, g = v.geometry, r = v.renderer;
        const p = g.getAttribute('position'), c = g.getAttribute('color'), idx = g.getIndex().array;
        const n = 3 * window.auszugTracery.shown().indices.shape[0], gl = r.getContext();
        const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
        v.camera.updateMatrixWorld();
        const P = (i) => p.array.slice(3 * i, 3 * i + 3), C = (i) => c.array.slice(3 * i, 3 * i + 3);
        const screen = (q) => { const s = new v.camera.position.constructor(...q).project(v.camera);
          return [(s.x + 1) / 2 * w, (s.y + 1) / 2 * h]; };
        let best = null, area = 0;
        for (let f = 0; f < n; f += 3) {
          const [a, b, d] = [idx[f], idx[f + 1], idx[f + 2]];
          const ca = C(a);
          if (![b, d].every((i) => C(i).every((x, k) => Math.abs(x - ca[k]) < 1e-7))) continue;
          const [A, B, D] = [a, b, d].map((i) => screen(P(i)));
          const s = ((B[0] - A[0]) * (D[1] - A[1]) - (D[0] - A[0]) * (B[1] - A[1])) / 2;
          const at = [(A[0] + B[0] + D[0]) / 3, (A[1] + B[1] + D[1]) / 3];
          if (s > area) { area = s; best = {colour: Array.from(ca), at}; }
        }
        v.render();
        const px = new Uint8Array(4);
        gl.readPixels(Math.floor(best.at[0]), Math.floor(best.at[1]), 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
        return {...best, area, pixel: Array.from(px)}; }""")
    assert res["area"] > 200, res    # a large flat face in view (pixels)

    def srgb(x: float) -> float:
        return 12.92 * x if x <= 0.0031308 else 1.055 * x ** (1 / 2.4) - 0.055

    want = [round(255 * srgb(x)) for x in res["colour"]]
    assert all(abs(a - b) <= 2 for a, b in zip(res["pixel"][:3], want, strict=True)), (res, want)
