"""Gothic window tracery (Havemann and Fellner 2004): styles, 2D structure, meshes, pictures.

STYLE is a built-in style name (see --list), a style file (.toml or .json),
or "prototype": the bare prototype window of the paper, whose structure is the
paper's eight polygons (1 arch, 2 sub-arches, 1 circle, 4 fillets). The
ending of OUT picks what is written:

  .json, .tracery.json   the 2D structure: every region as a polygon and as
                         its exact lines and arcs ({"format": "auszug.tracery"})
  .svg                   a drawing of the 2D structure with exact arcs
  .glb .obj .stl .ply    one watertight manifold mesh of the window in its wall
  .png                   a rendered picture of that mesh

Without -o a summary is printed. --set overrides any style key
(NAME=VALUE, NAME a window parameter such as excess, or GROUP.KEY such as
circle.foils); the parameter options (--span, --excess, ...) are shortcuts.

examples:
  auszug tracery --list
  auszug tracery prototype --span 2 --height 4 --excess 1.25 --drop 0.2 --outer 0.1 --inner 0.05 -o window.json
  auszug tracery fig20h -o fig20h.glb
  auszug tracery fig20d --set circle.foils=6 --set excess=1.0 -o window.svg
  auszug tracery fig20c --depth 2 -o recursive.png
  auszug tracery --gallery gallery/
"""

from __future__ import annotations

import argparse
import io
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from auszug.cli import _common
from auszug.limits import LIMITS, shown

HELP = "Gothic window tracery: styles, 2D structure (.json/.svg), meshes (.glb/.obj/.stl/.ply), pictures"

#: Output endings and what they hold.
STRUCTURE = (".tracery.json", ".json")
DRAWING = (".svg",)
MESH = (".glb", ".obj", ".stl", ".ply")
PICTURE = (".png",)
PARAMS = ("span", "height", "excess", "drop", "outer", "inner")


def add_args(parser: argparse.ArgumentParser) -> None:
    """Options of ``auszug tracery``."""
    parser.add_argument("style", metavar="STYLE", nargs="?",
                        help="a built-in style name, a style file (.toml/.json), or 'prototype'")
    parser.add_argument("-o", "--output", metavar="OUT",
                        help="output file: .json, .svg, .glb, .obj, .stl, .ply or .png")
    parser.add_argument("--list", action="store_true", help="list the built-in styles and profiles, then exit")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="override a style key, e.g. excess=1.0 or circle.foils=6 (repeatable)")
    g = parser.add_argument_group("window parameters (shortcuts for --set)")
    for name, text in (("span", "width between the jambs"), ("height", "height of the jambs"),
                       ("excess", "radius over span of the arches (0.5 round, 1 equilateral)"),
                       ("drop", "how far the sub-arches spring below the arch"),
                       ("outer", "offset of the ensemble from the outer arch"),
                       ("inner", "border width of every region")):
        g.add_argument(f"--{name}", type=_common.finite, default=None, metavar="X", help=text)
    m = parser.add_argument_group("3D")
    m.add_argument("--depth", type=_common.at_least(0), default=None, metavar="N",
                   help="refine the sub-arches as windows of the same style, N levels deep")
    m.add_argument("--subdivide", type=_common.at_least(0), default=0, metavar="K",
                   help="Catmull-Clark steps on the profiles, creases kept (0-4, default 0)")
    m.add_argument("--width", type=_common.pixels, default=800, metavar="PX",
                   help="picture width in pixels (.png, default 800)")
    m.add_argument("--view", nargs=2, type=_common.finite, default=(-20.0, 10.0), metavar=("AZ", "EL"),
                   help="picture view direction in degrees (default -20 10)")
    parser.add_argument("--gallery", metavar="DIR",
                        help="write pictures of every built-in style and of the paper's Fig. 19 into DIR")


def _style(args: argparse.Namespace) -> Any:
    from auszug.tracery.style import builtin_style, load_style, refine

    if args.style is None:
        from auszug.errors import DrawingError

        raise DrawingError("a STYLE is required (a built-in name, a style file, or 'prototype'); see --list")
    over = _overrides(args)
    if args.style == "prototype":
        st = _overridden(builtin_style("fig20a"), {"name": "prototype", **over})
    else:
        with _about_style(args):
            st = load_style(args.style)
            if over:
                st = _overridden(st, over)
    if args.depth is not None:
        st = refine(st, args.depth)
    return st


def _overrides(args: argparse.Namespace) -> dict[str, Any]:
    """The ``--set`` values and window parameter options, as style keys."""
    from auszug.tracery.style import parse_overrides

    over = parse_overrides(args.set)
    for name in PARAMS:
        v = getattr(args, name)
        if v is not None:
            over[f"params.{name}"] = v
    return over


def _overridden(st: Any, over: dict[str, Any]) -> Any:
    """``st.with_overrides(over)``, errors blamed as :func:`_blame_sets` says."""
    with _blame_sets(over):
        return st.with_overrides(over)


@contextmanager
def _blame_sets(over: dict[str, Any]) -> Iterator[None]:
    """An error about a key the user did not set (a misfit it caused) also names the overrides."""
    from auszug.errors import DrawingError
    from auszug.tracery import ParameterError

    try:
        yield
    except ParameterError as e:
        given = {k.split(".")[-1] for k in over if k != "name"}
        if not given or e.name.split(".")[-1] in given:
            raise
        sets = ", ".join(f"{k}={shown(v)}" for k, v in over.items() if k != "name")
        raise DrawingError(f"{e} (with {sets})") from None


def _about_style(args: argparse.Namespace) -> Any:
    """Name the style file in errors of the block (nothing for a built-in style)."""
    return _common.about(args.style) if Path(args.style).suffix in (".toml", ".json") else _nullctx()


class _nullctx:
    def __enter__(self) -> None:
        return None

    def __exit__(self, *exc: object) -> None:
        return None


def _kind(out: Path) -> str:
    name = out.name.lower()
    for kind, sufs in (("structure", STRUCTURE), ("drawing", DRAWING), ("mesh", MESH), ("picture", PICTURE)):
        if name.endswith(sufs):
            return kind
    from auszug.errors import FormatError

    raise FormatError("unknown output type; expected .json, .svg, .glb, .obj, .stl, .ply or .png", str(out))


def png_bytes(image: Any) -> bytes:
    """PNG bytes of an RGB array."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    plt.imsave(buf, image, format="png")
    return buf.getvalue()


def run(args: argparse.Namespace) -> int:
    """Write the requested output (or list, or summarise); return 0."""
    if args.list:
        from auszug.tracery.style import builtin_profiles, builtin_styles

        print("built-in styles:")
        for name, text in builtin_styles().items():
            print(f"  {name:<10} {text}")
        print("profiles:")
        for name, p in builtin_profiles().items():
            print(f"  {name:<10} {'wall ' if p.wall else ''}{len(p.points)} points, depth {p.depth:g}")
        return 0
    if args.gallery:
        from auszug.formats import atomic_write
        from auszug.tracery.gallery import gallery

        folder = Path(args.gallery)
        for name, data in gallery(width=min(args.width, 600)).items():
            atomic_write(folder / name, data)
            print(f"wrote {folder / name}")
        return 0
    from auszug.formats import atomic_write
    from auszug.tracery.build import build

    st = _style(args)
    with _about_style(args), _blame_sets(_overrides(args)):
        t = build(st)
    if not args.output:
        groups: dict[str, int] = {}
        for r in t.regions:
            groups[r.group] = groups.get(r.group, 0) + 1
        print(f"style {st.name}: {len(t.regions)} regions, depth {t.depth}, {len(t.lights)} lights")
        for g, n in groups.items():
            print(f"  {g:<9} {n}")
        return 0
    out = Path(args.output)
    kind = _kind(out)
    with _common.about(out):
        if kind == "structure":
            from auszug.formats import save

            save(t, out, kind="tracery")
        elif kind == "drawing":
            from auszug.tracery.draw import svg

            atomic_write(out, svg(t))
        else:
            from auszug.tracery.mesh import window_mesh

            # a mesh that cannot be made is the style's fault, not the output's
            with _about_style(args), _blame_sets(_overrides(args)):
                m = window_mesh(t, subdivide=args.subdivide)
            if kind == "mesh":
                from auszug.formats import save

                save(m, out, kind="mesh")
                if out.suffix.lower() == ".obj":
                    from auszug.formats.mesh_obj import mtl

                    atomic_write(out.with_suffix(".mtl"), mtl(m))
            else:
                from auszug.tracery.render import shade

                lo, hi = m.bounds()
                height = int(args.width * (hi[2] - lo[2]) / max(hi[0] - lo[0], 1e-9) * 1.05)
                img = shade(m.vertices, m.faces, args.width, min(max(height, 50), LIMITS.pixels),
                            azimuth=args.view[0],
                            elevation=args.view[1])
                atomic_write(out, png_bytes(img))
    print(f"wrote {out}")
    return 0
