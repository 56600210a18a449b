"""Turn drawings into meshes: members swept along the curves, minimal-surface faces, printable solids.

A network file (.network.json, from `auszug build` or `auszug lift`) stands
for its drawing: its exact curves are meshed with their symmetry.

One drawing and OUT a file: the ending of OUT picks the format (.glb, .gltf,
.obj with its .mtl, .stl, .ply), or a shaded picture of the mesh (.png,
.svg, .pdf). Several drawings or a folder (searched recursively): OUT is a
folder and every drawing gives OUT/<subfolder>/<stem>.glb, or the --format
chosen; a progress bar shows on a terminal. Without -o the output goes to
<stem>.glb in the current folder.

--style picks the members' cross-section: tube (round), bar (square, the
authors' look), ribbon (a flat band in the curve's vertical surface), or a
profile JSON file of lines and arcs (see docs/meshing.md), in drawing
units. --faces auto fills every closed loop of the network with a converged
minimal surface; --faces LOOPS.json fills given loops (a list of loops, each
a list of [x, y, z] points on the network's nodes). --solid unites
everything into one watertight solid for 3D printing (faces get a
thickness; --base adds a plate), and reports its volume.

examples:
  auszug mesh U.XI.28.uc -o U.XI.28.glb
  auszug mesh U.XI.28.uc --style tube --faces auto -o U.XI.28.obj
  auszug mesh tn-1.uc --style bar --solid --base -o tn-1.stl
  auszug mesh corpus/ --style ribbon -o meshes/ --format ply
  auszug mesh tn-9.uc --style moulding.json -o tn-9.png
  auszug mesh vase.network.json --style tube -o vase.glb
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path
from typing import Any

from auszug.cli import _common
from auszug.limits import check_file_size

HELP = "sweep members along the curves, fill faces, make solids (.glb .obj .stl .ply)"
MESH_FORMATS = ("glb", "gltf", "obj", "stl", "ply")
FIGURES = (".png", ".svg", ".pdf")


def add_args(parser: argparse.ArgumentParser) -> None:
    """Options of ``auszug mesh``."""
    parser.add_argument("drawings", nargs="+", metavar="DRAWING",
                        help="drawing files (.uc, .json), network files (.network.json) or folders of drawings")
    parser.add_argument("-o", "--output", metavar="OUT",
                        help="output file (one drawing) or folder (several drawings or a folder)")
    parser.add_argument("--format", choices=MESH_FORMATS, default=None,
                        help="output format in a folder, or without -o (default glb)")
    g = parser.add_argument_group("members")
    g.add_argument("--style", default="bar", metavar="tube|bar|ribbon|PROFILE.json",
                   help="cross-section of the members (default bar)")
    g.add_argument("--size", type=_common.finite, default=None, metavar="S",
                   help="tube diameter / bar side / ribbon width over 3, drawing units "
                        "(default 1.2%% of the drawing's bounding-box diagonal)")
    g.add_argument("--segments", type=_common.at_least(1), default=None, metavar="N",
                   help="steps along each curve (default 200; 64 for --solid, 48 for a picture)")
    g.add_argument("--around", type=_common.at_least(2), default=None, metavar="N",
                   help="points around the profile (default 40 for tubes, 4 for bars)")
    f = parser.add_argument_group("faces and solids")
    f.add_argument("--faces", default="none", metavar="auto|none|LOOPS.json",
                   help="fill the network's loops with minimal surfaces (default none)")
    f.add_argument("--face-resolution", type=_common.at_least(12), default=96, metavar="N",
                   help="boundary points per face (default 96)")
    f.add_argument("--solid", action="store_true", help="unite everything into one watertight solid")
    f.add_argument("--thickness", type=_common.positive, default=None, metavar="T",
                   help="face thickness in the solid (default half the profile)")
    f.add_argument("--base", action="store_true", help="add a base plate to the solid")
    _common.add_network_args(parser)


def _is_folder_target(out: str | None) -> bool:
    return out is not None and (Path(out).is_dir() or out.endswith(("/", os.sep)))


def _suffix(path: Path) -> str:
    name = path.name.lower()
    for s in FIGURES + tuple("." + f for f in MESH_FORMATS):
        if name.endswith(s):
            return s
    from auszug.errors import FormatError

    raise FormatError("unknown mesh file type; expected .glb, .gltf, .obj, .stl, .ply "
                      "(or .png, .svg, .pdf for a picture)", str(path))


def _profile_file(args: argparse.Namespace) -> Any:
    """The Profile of a --style PROFILE.json file."""
    from auszug.errors import FormatError, GeometryError
    from auszug.meshing.profile import STYLES, from_dict

    path = Path(args.style)
    if not path.suffix.lower() == ".json":
        raise FormatError(f"--style must be one of {', '.join(STYLES)} or a profile .json file, "
                          f"got {args.style!r}")
    check_file_size(path)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise FormatError("no such profile file", str(path)) from None
    except json.JSONDecodeError as e:
        raise FormatError(f"not JSON: {e.msg}", str(path), e.lineno) from None
    try:
        return from_dict(data, around=args.around or 40)
    except GeometryError as e:
        raise FormatError(str(e), str(path)) from None


def _loops(args: argparse.Namespace, net: Any) -> Any:
    from auszug.errors import FormatError
    from auszug.meshing import loop_through, network_graph

    if args.faces == "none":
        return None
    if args.faces == "auto":
        return "auto"
    path = Path(args.faces)
    check_file_size(path)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise FormatError("no such loops file (or give --faces auto)", str(path)) from None
    except json.JSONDecodeError as e:
        raise FormatError(f"not JSON: {e.msg}", str(path), e.lineno) from None
    if not isinstance(data, list) or not all(isinstance(lp, list) for lp in data):
        raise FormatError("expected a list of loops, each a list of [x, y, z] points", str(path))
    graph = network_graph(net)
    with _common.about(path):
        return [loop_through(graph, lp) for lp in data]


def look_of(args: argparse.Namespace, net: Any) -> Any:
    """The :class:`~auszug.meshing.Look` of the options (profile and loops files read here)."""
    from auszug.meshing import Look
    from auszug.meshing.profile import STYLES

    builtin = args.style in STYLES
    style = args.style if builtin else _profile_file(args)
    loops = _loops(args, net)
    segments = args.segments
    if segments is None and args.picture and not args.solid:
        segments = 48
    return Look(style=style,
                size=args.size if builtin else None, around=args.around if builtin else None,
                faces="none" if loops is None else loops if loops == "auto" else tuple(loops),
                resolution=args.face_resolution, segments=segments, solid=args.solid,
                thickness=args.thickness, base=args.base)


def _make(src: Path, args: argparse.Namespace) -> tuple[Any, dict]:
    """The mesh (or solid) of one drawing and a summary."""
    from auszug.meshing import mesh_network

    nf = _common.network_of(src, args, networks=True)
    net = nf.network
    with _common.about(src):
        r = mesh_network(net, look_of(args, net))
    info: dict[str, Any] = {}
    if r.faces is not None:
        info.update(faces=len(r.faces.faces), converged=r.faces.converged, residual=r.faces.residual)
    if r.solid is not None:
        info.update(volume=r.solid.volume, watertight=r.solid.watertight, shells=r.solid.components)
    return r.mesh, info


def _write(mesh: Any, out: Path) -> None:
    from auszug.formats import atomic_write, save
    from auszug.formats.mesh_obj import mtl

    suf = _suffix(out)
    with _common.about(out):
        if suf in FIGURES:
            atomic_write(out, _picture(mesh, suf.lstrip(".")))
            return
        save(mesh, out, kind="mesh")
        if suf == ".obj":
            atomic_write(out.with_suffix(".mtl"), mtl(mesh))


def _picture(mesh: Any, fmt: str, size_px: int = 1000) -> bytes:
    """A shaded perspective picture of the mesh (matplotlib, Agg)."""
    import io

    import matplotlib
    import numpy as np

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    from auszug.formats.mesh_obj import part_colour
    from auszug.meshing.mesh import triangle_normals

    fig = Figure(figsize=(size_px / 100, size_px / 100), dpi=100, facecolor="white")
    ax = fig.add_subplot(111, projection="3d")
    v, f = mesh.vertices, mesh.faces
    rgb = np.tile(np.array([0.8, 0.68, 0.4]), (len(f), 1))
    for p in mesh.parts:
        rgb[p.faces[0]:p.faces[1]] = part_colour(p)
    light = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    shade = 0.35 + 0.65 * np.abs(triangle_normals(v, f) @ light)
    ax.add_collection3d(Poly3DCollection(v[f], facecolors=np.clip(rgb * shade[:, None], 0, 1), edgecolors="none"))
    lo, hi = v.min(0), v.max(0)
    c, r = (lo + hi) / 2, float((hi - lo).max()) / 2 or 1.0
    ax.set_xlim(c[0] - r, c[0] + r)
    ax.set_ylim(c[1] - r, c[1] + r)
    ax.set_zlim(c[2] - r, c[2] + r)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(22, -60)
    ax.set_axis_off()
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, bbox_inches="tight")
    return buf.getvalue()


def _report(out: Path, mesh: Any, info: dict) -> str:
    bits = [f"wrote {out}", f"{mesh.n_vertices} vertices", f"{mesh.n_faces} triangles"]
    if "faces" in info:
        bits.append(f"{info['faces']} faces ({'converged' if info['converged'] else 'NOT converged'}, "
                    f"residual {info['residual']:.1e})")
    if "volume" in info:
        bits.append(f"volume {info['volume']:.6g}" + (", watertight" if info["watertight"] else ", NOT watertight")
                    + (f", {info['shells']} shells" if info["shells"] != 1 else ""))
    return "; ".join(bits)


def run(args: argparse.Namespace) -> int:
    """Make and write the meshes; return 0, or 2 if any drawing failed."""
    from auszug.errors import FormatError
    from auszug.meshing.profile import STYLES

    if args.style not in STYLES and not args.style.lower().endswith(".json"):
        raise FormatError(f"--style must be one of {', '.join(STYLES)} or a profile .json file, "
                          f"got {args.style!r}")
    items = _common.find_drawings(args.drawings)
    several = len(items) > 1 or any(Path(d).is_dir() for d in args.drawings)
    fmt = "." + (args.format or "glb")
    if not several and not _is_folder_target(args.output):
        src = items[0][0]
        out = Path(args.output) if args.output else Path(_common.stem(src) + fmt)
        if args.format and _suffix(out) != fmt:
            raise FormatError(f"--format {args.format} does not match the file ending of the output", str(out))
        args.picture = _suffix(out) in FIGURES
        mesh, info = _make(src, args)
        _write(mesh, out)
        print(_report(out, mesh, info))
        return 0
    out_dir = Path(args.output) if args.output else Path(".")
    if out_dir.exists() and not out_dir.is_dir():
        raise FormatError("several drawings need an output folder, but this is a file", str(out_dir))
    jobs = [(src, out_dir / rel / (_common.stem(src) + fmt)) for src, rel in items]
    args.picture = False
    lines: list[str] = []

    def one(src: Path, dst: Path) -> None:
        mesh, info = _make(src, args)
        _write(mesh, dst)
        lines.append(_report(dst, mesh, info))

    errors = _common.run_jobs(jobs, "meshing", one)
    for ln in lines:
        print(ln)
    for msg in errors:
        print(f"auszug: {msg}", file=sys.stderr)
    print(f"wrote {len(jobs) - len(errors)} of {len(jobs)} meshes to {out_dir}"
          + (f" ({len(errors)} failed)" if errors else ""))
    return 2 if errors else 0
