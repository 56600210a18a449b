"""Apply a style to the prototype construction: the window's 2D structure, to any depth.

:func:`build` plays the part of the authors' ``gothic-window-style``: it
constructs the prototype window, then hands each group's regions to the
group's decoration (plain light, pointed trefoil, rosette, blind recess, or a
whole window nested in a sub-arch, recursively).

A nested window fills the floor of its sub-arch's recess (the sub-arch's
opening offset by its profile's final inset). Its parameters are the parent's
scaled by the ratio of the spans, its sub-arches keep the parent's excess.

Examples
--------
>>> from auszug.tracery import build
>>> t = build("fig20a")
>>> [r.group for r in t.regions]
['arch', 'sub-arch', 'sub-arch', 'circle', 'fillet', 'fillet', 'fillet', 'fillet']
>>> build("fig20h").depth
3
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any, Mapping

import numpy as np

from auszug.errors import GeometryError
from auszug.geometry import Arc, Curve, Line
from auszug.geometry.offset import offset_curves
from auszug.tracery._checks import ParameterError
from auszug.tracery.arch import PointedArch, trefoil_arch
from auszug.tracery.model import Region, Tracery
from auszug.tracery.rosette import rosette
from auszug.tracery.style import Style, builtin_style, load_style
from auszug.tracery.window import CELLS, GROUP, WindowParams, prototype

__all__ = ["build", "structure"]


def structure(params: WindowParams | None = None, **kw: float) -> Tracery:
    """The bare prototype structure: the paper's eight polygons, all lights with a flat profile.

    Examples
    --------
    >>> t = structure(span=2, height=4, excess=1.25, drop=0.2, outer=0.1, inner=0.05)
    >>> len(t.regions), [len(t.group(g)) for g in ("arch", "sub-arch", "circle", "fillet")]
    (8, [1, 2, 1, 4])
    """
    p = params if params is not None else WindowParams()
    if kw:
        p = replace(p, **kw)
    st = builtin_style("fig20a").with_overrides({f"params.{k}": v for k, v in p.as_dict().items()})
    return build(st)


def build(style: Style | str, params: WindowParams | None = None,
          overrides: Mapping[str, Any] | None = None) -> Tracery:
    """The 2D structure of the window ``style`` makes.

    Parameters
    ----------
    style : Style or str
        A style, or a built-in style name or style file.
    params : WindowParams, optional
        Window parameters replacing the style's.
    overrides : mapping, optional
        Dotted style keys to override (``{"circle.foils": 6}``).

    Returns
    -------
    Tracery

    Raises
    ------
    ParameterError
        If a parameter is out of range; in a nested window the name carries
        the window's path (``arch/sub-arch-left: drop``).
    """
    st = load_style(style) if isinstance(style, str) else style
    if overrides:
        st = st.with_overrides(overrides)
    p = params if params is not None else st.params
    out: list[Region] = []
    a = p.arch()
    f = p.outer + p.inner
    out.append(Region("arch", "arch", 0, a.curves(), "frame", f, st.wall.profile, 0.0))
    _window(a, p, st, 0, "arch", "arch", 0.0, out, {})
    final = [r if r.origin == (0.0, 0.0) else
             Region(r.id, r.group, r.depth, _shifted(r.curves, *r.origin), r.role, r.border, r.profile, r.face,
                    r.template, r.origin)
             for r in out]
    return Tracery(tuple(final), p, st)


def _shifted(curves: tuple[Curve, ...], dx: float, dy: float) -> tuple[Curve, ...]:
    """``curves`` translated by (dx, dy), built without re-validation (they are valid already)."""
    d = np.array((dx, dy))
    out: list[Curve] = []
    for c in curves:
        n = object.__new__(type(c))
        # the fields set as the frozen dataclasses' own __init__ leaves them (no __slots__)
        if isinstance(c, Arc):
            n.__dict__.update(center=c.center + d, radius=c.radius, theta0=c.theta0, sweep=c.sweep)
        else:
            assert isinstance(c, Line)
            n.__dict__.update(p0=c.p0 + d, p1=c.p1 + d, _len=c._len)
        out.append(n)
    return tuple(out)


def _placed(rel: list[Region], prefix: str, dx: float, dy: float) -> list[Region]:
    """Regions computed at the origin (ids relative) placed at (dx, dy) under ``prefix``.

    Only the origin moves here; the curves stay in their template's frame until
    :func:`build` shifts each region once, at the end.
    """
    return [Region(f"{prefix}/{r.id}", r.group, r.depth, r.curves, r.role, r.border, r.profile, r.face,
                   r.template, (r.origin[0] + dx, r.origin[1] + dy)) for r in rel]


def _name(prefix: str, name: str) -> str:
    """A parameter name with the path of the nested window it belongs to (none for the outer one)."""
    return name if prefix == "arch" else f"{prefix}: {name}"


def _prefixed(err: ParameterError, prefix: str) -> ParameterError:
    if prefix == "arch":
        return err
    return ParameterError(_name(prefix, err.name), err.value, err.valid)


def _window(a: PointedArch, p: WindowParams, st: Style, depth: int, prefix: str, where: str, face: float,
            out: list[Region], memo: dict[Any, Any]) -> None:
    """Append the regions filling the arch region ``a`` (the window's tracery).

    Windows are symmetric, so congruent windows (the same style and shape at
    the same depth, as the sub-windows of a recursive style) are constructed
    once at the origin and translated into place. ``memo`` holds those region lists
    by shape key, and under ``"templates"`` a one-item list counting the templates.
    """
    dx, dy = p.x, p.y
    key = (id(st), depth, face, p.span, p.height, p.excess, p.drop, p.outer, p.inner,
           a.left - dx, a.right - dx, a.springing - dy, a.excess, (a.bottom or 0.0) - dy)
    rel = memo.get(key)
    if rel is None:
        rel = []
        a0 = PointedArch(a.left - dx, a.right - dx, a.springing - dy, a.excess,
                         None if a.bottom is None else a.bottom - dy)
        _window_at_origin(a0, replace(p, x=0.0, y=0.0), st, depth, where, face, rel, memo)
        counter = memo.setdefault("templates", [0])
        fresh = []
        for r in rel:
            if r.template < 0:
                r = replace(r, template=counter[0])
                counter[0] += 1
            fresh.append(r)
        rel = memo[key] = fresh
    out.extend(_placed(rel, prefix, dx, dy))


def _window_at_origin(a: PointedArch, p: WindowParams, st: Style, depth: int, where: str, face: float,
                      out: list[Region], memo: dict[Any, Any]) -> None:
    """The regions of one window, ids relative to the window (``where`` names it in errors)."""
    prefix = where  # in error messages
    b = p.inner
    deco = st.arch.decoration
    if deco in ("plain", "trefoil"):
        try:
            light = a.offset(p.outer + p.inner)
            curves = light.curves() if deco == "plain" else trefoil_arch(
                light, st.arch.split, st.arch.lobe, st.arch.upper)
        except ParameterError as e:
            raise _prefixed(e, prefix) from None
        out.append(Region("light", "light", depth, curves, "light", b, st.arch.profile, face))
        return
    try:
        w = prototype(p, arch=None if depth == 0 else a)
    except ParameterError as e:
        raise _prefixed(e, prefix) from None
    regions = w.regions
    for name in CELLS:
        rid = name
        group = GROUP[name]
        if group == "sub-arch":
            g = st.sub_arch
            opening = w.sub_region(name)
            if g.decoration == "plain":
                out.append(Region(rid, group, depth, opening.curves(), "light", b, g.profile, face))
            elif g.decoration == "trefoil":
                try:
                    curves = trefoil_arch(opening, g.split, g.lobe, g.upper)
                except ParameterError as e:
                    raise _prefixed(ParameterError(f"sub-arch.{e.name}", e.value, e.valid), prefix) from None
                out.append(Region(rid, group, depth, curves, "light", b, g.profile, face))
            else:
                out.append(Region(rid, group, depth, opening.curves(), "frame", b, g.profile, face))
                assert g.window is not None
                try:
                    floor = opening.offset(g.profile.inset * b)
                except ParameterError:
                    raise ParameterError(_name(prefix, "sub-arch.profile"), g.profile.name,
                                         "a recess profile whose floor fits in the sub-arch") from None
                k = floor.span / a.span
                assert floor.bottom is not None  # sub-arches stand on the window's sill
                q = WindowParams(span=floor.span, height=floor.springing - floor.bottom, excess=p.excess,
                                 drop=p.drop * k, outer=p.outer * k, inner=p.inner * k,
                                 x=floor.mid, y=floor.bottom)
                _window(floor, q, g.window, depth + 1, rid, f"{where}/{rid}", face + g.profile.depth * b,
                        out, memo)
        elif group == "circle":
            g2 = st.circle
            if g2.decoration == "plain":
                out.append(Region(rid, group, depth, regions[name], "light", b, g2.profile, face))
                continue
            out.append(Region(rid, group, depth, regions[name], "frame", b, g2.profile, face))
            r_floor = w.circle_radius - b - g2.profile.inset * b
            if r_floor <= 2.0 * b:
                raise ParameterError(_name(prefix, "circle.profile"), g2.profile.name,
                                     "a recess profile that leaves room for the rosette")
            loops = rosette(w.circle_center, r_floor, g2.foils, g2.pointed, g2.displacement, g2.orientation)
            floor_face = face + g2.profile.depth * b
            for i, loop in enumerate(loops):
                try:
                    curves = offset_curves(loop, b, closed=True).curves
                except GeometryError as e:
                    raise ParameterError(_name(prefix, "circle.foils"), g2.foils,
                                         "fewer foils (each foil must be wider than two borders)", str(e)) from None
                suffix = "" if len(loops) == 1 else f"-{i + 1}"
                out.append(Region(f"{rid}/rosette{suffix}", "rosette", depth, curves, "light", b,
                                  g2.foil_profile, floor_face))
        else:
            g3 = st.fillet
            role = "light" if g3.decoration == "plain" else "blind"
            out.append(Region(rid, group, depth, regions[name], role, b, g3.profile, face))
