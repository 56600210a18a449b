import { describe, expect, it } from "vitest";
import {
  documentLabel, drawingExt, exportRequest, galleryGroups, matches, recoveryTime, savePath, suggestedName,
} from "./filemodel";
import type { Looks } from "./store";

const files = {
  workspace: ["tn-2.uc", "sub/mine.json", "a.json"],
  examples: ["web/U.XI.28.uc", "teaching-sheet/tn-11.uc", "teaching-sheet/tn-2.uc", "web/weird_ones/flower.uc", "legacy/U.XI.15.uc"],
};

describe("galleryGroups", () => {
  it("groups by folder: workspace, teaching sheet, web, legacy; in natural order", () => {
    const groups = galleryGroups(files);
    expect(groups.map((g) => g.title)).toEqual([
      "Workspace", "Workspace · sub", "Examples · teaching-sheet", "Examples · web", "Examples · web/weird_ones",
      "Examples · legacy",
    ]);
    expect(groups[0].cards.map((c) => c.path)).toEqual(["a.json", "tn-2.uc"]);
    expect(groups[2].cards.map((c) => c.label)).toEqual(["tn-2", "tn-11"]);
    expect(groups[3].cards[0]).toEqual({ kind: "example", path: "web/U.XI.28.uc", label: "U.XI.28", ext: ".uc" });
  });

  it("keeps only matching drawings and drops empty groups", () => {
    const groups = galleryGroups(files, "TN 11");
    expect(groups).toEqual([{ title: "Examples · teaching-sheet",
      cards: [{ kind: "example", path: "teaching-sheet/tn-11.uc", label: "tn-11", ext: ".uc" }] }]);
    expect(galleryGroups(files, "nothing like it")).toEqual([]);
    expect(matches("web/U.XI.28.uc", "  ")).toBe(true);
  });
});

describe("file names", () => {
  it("takes the format from the name or the choice", () => {
    expect(drawingExt("x.UC")).toBe(".uc");
    expect(drawingExt("x.txt")).toBeNull();
    expect(savePath(" pinnacle ", ".json")).toBe("pinnacle.json");
    expect(savePath("pinnacle.json", ".uc")).toBe("pinnacle.uc");
    expect(savePath("/sub/p.uc", ".uc")).toBe("sub/p.uc");
    expect(savePath(".json", ".json")).toBeNull();
    expect(savePath("sub/", ".json")).toBeNull();
  });

  it("names the document and marks unsaved changes", () => {
    expect(documentLabel({ path: "tn-2.uc", name: "tn-2", dirty: true })).toBe("tn-2.uc •");
    expect(documentLabel({ path: "", name: "U.XI.28", dirty: false })).toBe("U.XI.28");
    expect(documentLabel({ path: "", name: "", dirty: false })).toBe("untitled");
    expect(suggestedName({ path: "", name: "U.XI.28" })).toBe("U.XI.28.json");
    expect(suggestedName({ path: "sub/a.uc", name: "a" })).toBe("sub/a.uc");
  });
});

describe("recoveryTime", () => {
  it("reads the server's ISO time and keeps anything else", () => {
    const iso = "2026-03-04T05:06:07+01:00";
    expect(recoveryTime(iso, "en-GB")).toBe(new Date(iso).toLocaleString("en-GB", { dateStyle: "medium", timeStyle: "short" }));
    expect(recoveryTime(iso, "en-GB")).toMatch(/2026/);
    expect(recoveryTime("a while ago")).toBe("a while ago");
  });
});

describe("exportRequest", () => {
  const looks: Looks = { style: "curves", faces: "picked", loops: [2, 5], colors: [] };
  const colors = ["#112233", "#445566"];

  it("sends the looks with mesh formats", () => {
    expect(exportRequest("glb", looks, colors, true)).toEqual({
      type: "export", format: "glb", style: "bar", faces: "picked", loops: [2, 5], colors,
    });
    expect(exportRequest("stl", { ...looks, style: "tube", faces: "auto" }, colors, true)).toEqual({
      type: "export", format: "stl", style: "tube", faces: "auto", loops: [], solid: true,
    });
    expect(exportRequest("stl", looks, colors, false).solid).toBeUndefined();
  });

  it("sends the resolution: steps always, points round only for tubes; fine sends neither", () => {
    const tube = { ...looks, style: "tube" as const, faces: "none" as const };
    expect(exportRequest("glb", tube, colors, false, "light")).toEqual({
      type: "export", format: "glb", style: "tube", faces: "none", loops: [], colors, segments: 48, around: 10,
    });
    const bar = exportRequest("obj", looks, colors, false, "draft");
    expect([bar.segments, bar.around]).toEqual([24, undefined]);
    const fine = exportRequest("glb", tube, colors, false, "fine");
    expect([fine.segments, fine.around]).toEqual([undefined, undefined]);
    expect(exportRequest("svg", tube, colors, false, "draft")).toEqual({ type: "export", format: "svg" });
  });

  it("sends nothing else with drawings and networks", () => {
    expect(exportRequest("svg", looks, colors, true)).toEqual({ type: "export", format: "svg" });
    expect(exportRequest("network.json", looks, colors, false)).toEqual({ type: "export", format: "network.json" });
  });
});
