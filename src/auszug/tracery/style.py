"""Window styles: structure separate from appearance (Havemann and Fellner 2004, sec. 3.6).

The prototype window's regions fall into four groups: the main arch, the
sub-arches, the circle and the fillets. A style picks, per group, a
*decoration* (what fills the region) and a *profile* (how its border is cut
into the stone), plus the window parameters and the wall the window sits in.
Styles compose (``extends``: a style overrides another one key by key) and
nest (a sub-arch decorated as a ``window`` is refined by another style, to any
depth: their Fig. 20 f-h). This replaces the authors' 27 KB GML style
library; the built-in styles reproduce their Fig. 20 a-h (``auszug tracery
--list``).

A style is a TOML (or JSON) table::

    name = "fig20c"
    extends = "fig20b"            # optional: a built-in name or a path
    description = "pointed foils, the elaborate profile of Fig. 18"

    [params]                      # WindowParams (drawing units)
    span = 2.0
    height = 4.0
    excess = 1.25
    drop = 0.2
    outer = 0.1
    inner = 0.05

    [wall]                        # the wall the window is set into (3D)
    thickness = 0.9
    slab = 0.35                   # thickness of the tracery plate
    margin = 0.6                  # wall around the arch
    profile = "splay"             # reveal of the arch in the wall (a wall profile)

    [arch]                        # the main arch: window | plain | trefoil
    decoration = "window"
    profile = "chamfer"           # the light's profile when plain or trefoil

    [sub-arch]                    # plain | trefoil | window
    decoration = "trefoil"
    profile = "chamfer"
    split = 0.6                   # trefoil: where the cusps sit on the arcs
    lobe = 0.55                   # trefoil: side lobe radius / half span
    upper = 0.35                  # trefoil: upper lobe closing radius / arch radius
    window = "fig20d"             # window: the nested style (name, path or inline table)

    [circle]                      # plain | rosette
    decoration = "rosette"
    profile = "chamfer"           # the circle's profile (a recess round the rosette)
    foils = 3
    pointed = true
    displacement = 1.15
    orientation = "standing"      # standing | lying
    foil-profile = "fig18"        # the rosette opening's profile

    [fillet]                      # plain | blind
    decoration = "plain"
    profile = "chamfer"

    [profiles.my-profile]         # profiles usable by name in this style
    points = [[0, 0], [0.5, 0.5], [0.5, 2]]

Profiles are looked up in the style's ``[profiles]``, then in the built-in
library (:func:`builtin_profiles`).

Examples
--------
>>> from auszug.tracery.style import builtin_style, builtin_styles
>>> s = builtin_style("fig20d")
>>> s.circle.foils, s.sub_arch.decoration
(4, 'trefoil')
>>> s.with_overrides({"circle.foils": 6, "excess": 1.0}).circle.foils
6
"""

from __future__ import annotations

import copy
import json
import tomllib
from dataclasses import dataclass, field
from functools import lru_cache
from importlib.resources import files
from pathlib import Path
from typing import Any, Mapping

from auszug.errors import FormatError
from auszug.limits import LIMITS, check_file_size, check_text_size
from auszug.tracery._checks import ParameterError, choice, integer, number
from auszug.tracery.profile import Moulding, profile_from_data
from auszug.tracery.rosette import ORIENTATIONS
from auszug.tracery.window import WindowParams

__all__ = [
    "Style", "ArchGroup", "CircleGroup", "FilletGroup", "Wall",
    "builtin_styles", "builtin_style", "builtin_profiles", "load_style", "parse_style",
    "style_from_data", "style_data", "refine", "parse_overrides", "DEFAULTS",
]  # fmt: skip

ARCH_DECORATIONS = ("window", "plain", "trefoil")
SUB_ARCH_DECORATIONS = ("plain", "trefoil", "window")
CIRCLE_DECORATIONS = ("plain", "rosette")
FILLET_DECORATIONS = ("plain", "blind")
#: Deepest nesting of windows in windows.
MAX_NESTING = 6

#: The defaults every style starts from.
DEFAULTS: dict[str, Any] = {
    "name": "",
    "description": "",
    "params": WindowParams().as_dict(),
    "wall": {"thickness": 0.9, "slab": 0.35, "margin": 0.6, "profile": "splay"},
    "arch": {"decoration": "window", "profile": "chamfer", "split": 0.6, "lobe": 0.55, "upper": 0.35},
    "sub-arch": {"decoration": "plain", "profile": "chamfer", "split": 0.6, "lobe": 0.55, "upper": 0.35,
                 "window": None},
    "circle": {"decoration": "plain", "profile": "chamfer", "foils": 4, "pointed": False,
               "displacement": 1.15, "orientation": "standing", "foil-profile": "chamfer"},
    "fillet": {"decoration": "plain", "profile": "chamfer"},
    "profiles": {},
}
_TOP = set(DEFAULTS) | {"extends"}


@dataclass(frozen=True)
class Wall:
    """The wall the window is set into (3D only).

    Attributes
    ----------
    thickness : float
        Wall thickness.
    slab : float
        Thickness of the tracery plate, centred in the wall (< thickness).
    margin : float
        Wall left round the arch (sides, above the apex, below the sill).
    profile : Moulding
        The reveal of the arch in the wall, a wall profile in units of the
        frame width (outer + inner) across and of the reveal depth along.
    """

    thickness: float
    slab: float
    margin: float
    profile: Moulding


@dataclass(frozen=True)
class ArchGroup:
    """Decoration and profile of the main arch or the sub-arches.

    Attributes
    ----------
    decoration : str
        ``"window"`` (refined as a prototype window; for sub-arches: by the
        nested style ``window``), ``"plain"`` (a pointed-arch light) or
        ``"trefoil"`` (a pointed trefoil light).
    profile : Moulding
        The light's profile; for ``"window"`` the recess the nested window
        sits in.
    split, lobe, upper : float
        The pointed trefoil's parameters (:func:`auszug.tracery.arch.trefoil_arch`).
    window : Style or None
        The nested window's style (sub-arches decorated as ``"window"``).
    """

    decoration: str
    profile: Moulding
    split: float
    lobe: float
    upper: float
    window: Style | None = None


@dataclass(frozen=True)
class CircleGroup:
    """Decoration and profile of the circle.

    Attributes
    ----------
    decoration : str
        ``"plain"`` (a round light) or ``"rosette"``.
    profile : Moulding
        The round light's profile, or the recess round the rosette.
    foils : int
    pointed : bool
    displacement : float
    orientation : str
        See :func:`auszug.tracery.rosette.rosette`.
    foil_profile : Moulding
        The rosette opening's profile.
    """

    decoration: str
    profile: Moulding
    foils: int
    pointed: bool
    displacement: float
    orientation: str
    foil_profile: Moulding


@dataclass(frozen=True)
class FilletGroup:
    """Decoration (``"plain"`` light or ``"blind"`` recess) and profile of the fillets."""

    decoration: str
    profile: Moulding


@dataclass(frozen=True, eq=False)
class Style:
    """A window style: parameters, wall, and per group a decoration and a profile.

    Build one with :func:`builtin_style`, :func:`load_style`,
    :func:`parse_style` or :func:`style_from_data`; derive others with
    :meth:`with_overrides` and :func:`refine`.

    Attributes
    ----------
    name, description : str
    params : WindowParams
    wall : Wall
    arch, sub_arch : ArchGroup
    circle : CircleGroup
    fillet : FilletGroup
    data : dict
        The complete table the style was made from (defaults and ``extends``
        merged in, nested styles inline); :func:`style_from_data` of it gives
        the same style.
    """

    name: str
    description: str
    params: WindowParams
    wall: Wall
    arch: ArchGroup
    sub_arch: ArchGroup
    circle: CircleGroup
    fillet: FilletGroup
    data: dict[str, Any] = field(repr=False)

    def with_overrides(self, overrides: Mapping[str, Any]) -> Style:
        """A new style with dotted keys overridden (``"excess"``, ``"circle.foils"``, ...).

        A bare window parameter name (``excess``) means ``params.excess``.

        Raises
        ------
        ParameterError
            For an unknown key or an invalid value.
        """
        data = copy.deepcopy(self.data)
        for key, value in overrides.items():
            _set_dotted(data, key, value)
        return style_from_data(data)

    def depth(self) -> int:
        """Levels of nested windows below this one (0: sub-arches are not refined)."""
        if self.arch.decoration != "window" or self.sub_arch.decoration != "window" or self.sub_arch.window is None:
            return 0
        return 1 + self.sub_arch.window.depth()


def _merge(base: dict[str, Any], over: Mapping[str, Any]) -> dict[str, Any]:
    """Deep merge: tables merge key by key, everything else is replaced."""
    out = dict(base)
    for k, v in over.items():
        if isinstance(v, Mapping) and isinstance(out.get(k), Mapping) and k != "window":
            out[k] = _merge(dict(out[k]), v)
        else:
            out[k] = copy.deepcopy(v)
    return out


def _set_dotted(data: dict[str, Any], key: str, value: Any) -> None:
    parts = key.split(".")
    if len(parts) == 1 and parts[0] in DEFAULTS["params"]:
        parts = ["params", parts[0]]
    if parts[0] not in DEFAULTS or (parts[0] in ("name", "description") and len(parts) > 1):
        raise ParameterError(key, value, "a style key: a window parameter (" + ", ".join(DEFAULTS["params"])
                             + ") or GROUP.KEY with GROUP in params, wall, arch, sub-arch, circle, fillet")
    node = data
    for p in parts[:-1]:
        nxt = node.get(p)
        if nxt is None and p == "window":
            nxt = {}
        if isinstance(nxt, str):
            nxt = _resolve_ref(nxt, None, ())
        if not isinstance(nxt, dict):
            raise ParameterError(key, value, f"a key inside a table; {p!r} is not a table")
        node[p] = nxt = dict(nxt)
        node = nxt
    if isinstance(node, dict) and parts[-1] not in node and node is not data.get("profiles"):
        known = sorted(node)
        raise ParameterError(key, value, "one of " + ", ".join(".".join(parts[:-1] + [k]) for k in known))
    node[parts[-1]] = value


def parse_overrides(items: list[str]) -> dict[str, Any]:
    """``["excess=1.0", "circle.pointed=true"]`` -> ``{"excess": 1.0, "circle.pointed": True}``.

    Values are read as TOML values (numbers, true/false, quoted strings,
    arrays); anything else is taken as a plain string.

    Examples
    --------
    >>> parse_overrides(["excess=1.0", "circle.orientation=lying", "circle.pointed=true"])
    {'excess': 1.0, 'circle.orientation': 'lying', 'circle.pointed': True}
    """
    out: dict[str, Any] = {}
    for item in items:
        if "=" not in item:
            raise ParameterError("--set", item, "NAME=VALUE")
        k, v = item.split("=", 1)
        k = k.strip()
        try:
            out[k] = tomllib.loads(f"v = {v.strip()}")["v"]
        except tomllib.TOMLDecodeError:
            out[k] = v.strip()
    return out


# -- library -----------------------------------------------------------------------------

def _library():
    return files("auszug.tracery") / "styles"


@lru_cache(maxsize=1)
def builtin_profiles() -> dict[str, Moulding]:
    """The built-in profiles by name (``styles/profiles.toml``)."""
    raw = tomllib.loads((_library() / "profiles.toml").read_text(encoding="utf-8"))
    return {k: profile_from_data(k, v) for k, v in raw.items()}


def builtin_styles() -> dict[str, str]:
    """Names and one-line descriptions of the built-in styles, sorted by name.

    Examples
    --------
    >>> list(builtin_styles())[:3]
    ['fig20a', 'fig20b', 'fig20c']
    """
    out = {}
    for entry in _library().iterdir():
        if entry.name.endswith(".toml") and entry.name != "profiles.toml":
            name = entry.name[: -len(".toml")]
            out[name] = builtin_style(name).description.strip().splitlines()[0]
    return dict(sorted(out.items()))


@lru_cache(maxsize=64)
def _builtin_data(name: str) -> dict[str, Any]:
    entry = _library() / f"{name}.toml"
    if not entry.is_file():
        raise KeyError(name)
    return style_data(entry.read_text(encoding="utf-8"), f"{name}.toml", ".toml")


def builtin_style(name: str) -> Style:
    """The built-in style ``name`` (see :func:`builtin_styles`).

    Raises
    ------
    ParameterError
        For an unknown name (the message lists the known ones).
    """
    return style_from_data(_resolve_ref(name, None, ()))


def style_data(text: str, source: str, suffix: str) -> dict[str, Any]:
    """The raw table of a style file's text, before ``extends`` is resolved and values are checked.

    Parameters
    ----------
    text : str
        The file's text (size-checked here).
    source : str
        How errors name the file.
    suffix : str
        ``".json"`` for JSON, anything else for TOML.

    Raises
    ------
    FormatError
        Text too large, not valid TOML/JSON, not a table, or an empty table.
    """
    check_text_size(text, source)
    try:
        if suffix == ".json":
            data = json.loads(text)
        else:
            data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise FormatError(f"not valid TOML: {e}", source) from None
    except json.JSONDecodeError as e:
        raise FormatError(f"not valid JSON: {e.msg}", source, e.lineno) from None
    if not isinstance(data, dict):
        raise FormatError("a style must be a table (a JSON object)", source)
    if not data:
        raise FormatError("empty style: it sets no key; write extends = \"fig20a\" (or another built-in "
                          "style, see auszug tracery --list) for that style's window", source)
    return data


def _resolve_ref(ref: Any, base: Path | None, stack: tuple[str, ...], what: str = "style") -> dict[str, Any]:
    """The fully merged data of a style reference: a name, a path or an inline table.

    ``what`` is the key that holds the reference (``"style"``, ``"extends"``,
    ``"sub-arch.window"``), named when it is none of these.
    """
    if isinstance(ref, Mapping):
        data, here, key = dict(ref), base, None
    elif isinstance(ref, str):
        key = ref
        if key in stack:
            raise ParameterError("extends", ref, "a style that does not refer to itself",
                                 " -> ".join((*stack, key)))
        data, here = _read_ref(ref, base)
    else:
        raise ParameterError(what, ref, "a style name, a file path or a table")
    if len(stack) > 4 * MAX_NESTING:
        raise ParameterError("window", ref, f"styles nested at most {MAX_NESTING} deep")
    unknown = set(data) - _TOP
    if unknown:
        raise ParameterError(sorted(unknown)[0], data[sorted(unknown)[0]],
                             "a style key among " + ", ".join(sorted(_TOP)))
    parent = data.get("extends")
    st = (*stack, key) if key else stack
    merged = _resolve_ref(parent, here, st, "extends") if parent is not None else copy.deepcopy(DEFAULTS)
    own = {k: v for k, v in data.items() if k != "extends"}
    if "name" not in own:
        own["name"] = key if key and "/" not in key and not key.endswith((".toml", ".json")) else (
            Path(key).stem if key else merged.get("name", ""))
    if "description" not in own and parent is not None:
        own["description"] = merged.get("description", "")
    out = _merge(merged, own)
    sub = out.get("sub-arch", {})
    if not isinstance(sub, Mapping):
        raise ParameterError("sub-arch", sub, "a table")
    win = sub.get("window")
    if win is not None:
        # nested styles: inline, fully merged, so that the data is self-contained
        sub = dict(sub)
        sub["window"] = _resolve_ref(win, here, st, "sub-arch.window")
        out["sub-arch"] = sub
    return out


def _read_ref(ref: str, base: Path | None) -> tuple[dict[str, Any], Path | None]:
    """Read a style by path (relative to ``base``) or built-in name."""
    for cand in ([base / ref] if base is not None else []) + [Path(ref)]:
        if cand.suffix.lower() in (".toml", ".json") and cand.is_file():
            check_file_size(cand)
            return style_data(cand.read_text(encoding="utf-8"), str(cand), cand.suffix.lower()), cand.parent
    try:
        return copy.deepcopy(_builtin_data(ref)), None
    except KeyError:
        pass
    known = ", ".join(builtin_styles())
    raise ParameterError("style", ref, f"a built-in style ({known}) or a .toml/.json file")


def load_style(ref: str | Path) -> Style:
    """A style by built-in name or from a TOML/JSON file.

    ``extends`` and ``window`` references inside a file are resolved relative
    to the file, then among the built-in styles. (Reading style files is the
    one place of :mod:`auszug.tracery` that touches files.)

    Examples
    --------
    >>> load_style("fig20f").sub_arch.window.name
    'fig20d'
    """
    return style_from_data(_resolve_ref(str(ref), None, ()))


def parse_style(text: str, suffix: str = ".toml", source: str = "<style>") -> Style:
    r"""A style from TOML (or JSON with ``suffix=".json"``) text.

    Examples
    --------
    >>> s = parse_style('extends = "fig20b"\n[circle]\nfoils = 6\norientation = "lying"\n')
    >>> s.circle.foils, s.circle.orientation, s.circle.decoration
    (6, 'lying', 'rosette')
    """
    return style_from_data(_resolve_ref(style_data(text, source, suffix), None, ()))


# -- validation --------------------------------------------------------------------------

def _profile(name: str, ref: Any, local: Mapping[str, Any], wall: bool = False) -> Moulding:
    if isinstance(ref, (list, Mapping)):
        p = profile_from_data(name, ref)
    elif isinstance(ref, str):
        if ref in local:
            p = profile_from_data(ref, local[ref])
        else:
            lib = builtin_profiles()
            if ref not in lib:
                raise ParameterError(name, ref, "a profile among " + ", ".join(sorted({*lib, *local})))
            p = lib[ref]
    else:
        raise ParameterError(name, ref, "a profile name or a list of [s, t] points")
    if p.wall != wall:
        raise ParameterError(name, ref, "a wall profile (s <= 0, ending at (0, 1))" if wall
                             else "a region profile (not a wall profile)")
    return p


def _table(data: Mapping[str, Any], key: str) -> dict[str, Any]:
    t = data.get(key)
    if not isinstance(t, Mapping):
        raise ParameterError(key, t, "a table")
    unknown = set(t) - set(DEFAULTS[key])
    if unknown:
        u = sorted(unknown)[0]
        raise ParameterError(f"{key}.{u}", t[u], "a key among " + ", ".join(sorted(DEFAULTS[key])))
    return dict(t)


def style_from_data(data: Mapping[str, Any], _depth: int = 0) -> Style:
    """Validate a complete style table (as :attr:`Style.data` holds) into a :class:`Style`.

    Missing keys take the :data:`DEFAULTS`.
    """
    if _depth > MAX_NESTING:
        raise ParameterError("sub-arch.window", "...", f"windows nested at most {MAX_NESTING} deep")
    data = _merge(copy.deepcopy(DEFAULTS), data)
    unknown = set(data) - _TOP
    if unknown:
        raise ParameterError(sorted(unknown)[0], "...", "a style key among " + ", ".join(sorted(_TOP)))
    local = data.get("profiles") or {}
    if not isinstance(local, Mapping):
        raise ParameterError("profiles", local, "a table of profiles")
    params = WindowParams.from_mapping(_table(data, "params"))
    w = _table(data, "wall")
    thick = number("wall.thickness", w["thickness"], 0.0, LIMITS.coordinate, lo_open=True)
    wall = Wall(
        thick,
        number("wall.slab", w["slab"], 0.0, thick, lo_open=True, hi_open=True),
        number("wall.margin", w["margin"], 0.0, LIMITS.coordinate, lo_open=True),
        _profile("wall.profile", w["profile"], local, wall=True),
    )
    groups = {}
    for key, decos in (("arch", ARCH_DECORATIONS), ("sub-arch", SUB_ARCH_DECORATIONS)):
        g = _table(data, key)
        deco = choice(f"{key}.decoration", g["decoration"], decos)
        nested = None
        if key == "sub-arch" and deco == "window":
            if g.get("window") is None:
                raise ParameterError("sub-arch.window", None, "the nested window's style (a name, path or table)")
            ref = g["window"]
            nested = style_from_data(_resolve_ref(ref, None, (), "sub-arch.window") if not isinstance(ref, Mapping)
                                     else ref,
                                     _depth + 1)
        groups[key] = ArchGroup(
            deco, _profile(f"{key}.profile", g["profile"], local),
            number(f"{key}.split", g["split"], 0.0, 1.0, lo_open=True, hi_open=True),
            number(f"{key}.lobe", g["lobe"], 0.0, 1.0, lo_open=True, hi_open=True),
            number(f"{key}.upper", g["upper"], 0.0, 1.0, lo_open=True, hi_open=True),
            nested,
        )
    c = _table(data, "circle")
    if not isinstance(c["pointed"], bool):
        raise ParameterError("circle.pointed", c["pointed"], "true or false")
    circle = CircleGroup(
        choice("circle.decoration", c["decoration"], CIRCLE_DECORATIONS),
        _profile("circle.profile", c["profile"], local),
        integer("circle.foils", c["foils"], 2, LIMITS.fold),
        c["pointed"],
        number("circle.displacement", c["displacement"], 1.0, 3.0, lo_open=True),
        choice("circle.orientation", c["orientation"], ORIENTATIONS),
        _profile("circle.foil-profile", c["foil-profile"], local),
    )
    f = _table(data, "fillet")
    fillet = FilletGroup(choice("fillet.decoration", f["decoration"], FILLET_DECORATIONS),
                         _profile("fillet.profile", f["profile"], local))
    return Style(str(data.get("name", "")), str(data.get("description", "")), params, wall,
                 groups["arch"], groups["sub-arch"], circle, fillet, dict(data))


def refine(style: Style, depth: int) -> Style:
    """The style with its sub-arches refined as windows of the same style, ``depth`` levels deep.

    At the deepest level the sub-arches keep the style's own sub-arch
    decoration. ``refine(s, 0)`` is ``s``.

    Examples
    --------
    >>> refine(builtin_style("fig20c"), 2).depth()
    2
    """
    depth = integer("depth", depth, 0, MAX_NESTING)
    data = copy.deepcopy(style.data)
    data["arch"] = dict(data["arch"], decoration="window")
    leaf = copy.deepcopy(data)
    cur = leaf
    for _ in range(depth):
        nxt = copy.deepcopy(data)
        nxt["sub-arch"] = dict(nxt["sub-arch"], decoration="window", window=cur)
        cur = nxt
    out = style_from_data(cur)
    return out
