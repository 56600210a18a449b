"""The one home for size limits: what auszug accepts, everywhere, and why.

Every reader (``.uc``, native JSON, network JSON, tracery JSON, style TOML),
the drawing model's constructors (so the Python API and the studio's edits),
and the command line check their input against the single instance
:data:`LIMITS`. A value beyond a limit is refused with an
:class:`~auszug.errors.AuszugError` naming the file, the line, the value and
the limit; nothing is allowed to run for minutes, fill the memory, or write
infinities. The limits are far above anything in the published corpus (fold
15, 7 curves, 5 layers, coordinates within 15) and chosen so that the
largest accepted input of any command stays below 2 GB of memory
(``tests/test_limits.py`` runs them under that limit). ``docs/limits.md``
tabulates them.

Examples
--------
>>> from auszug.limits import LIMITS, shown
>>> LIMITS.fold
1024
>>> shown("x" * 200)  # doctest: +ELLIPSIS
"'xxxxxxxx...xxx' (200 characters)"
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, fields
from typing import Any

__all__ = ["Limits", "LIMITS", "shown", "clip", "check_file_size", "check_text_size", "check_number",
           "beyond_coordinate", "check_count", "table"]


@dataclass(frozen=True)
class Limits:
    """The documented limits (see the module notes and ``docs/limits.md``).

    Attributes
    ----------
    fold : int
        Largest rotation fold n of a basic curve's symmetry C_n. A drawing is
        built and intersected replica by replica, so the work grows with n
        (and with n squared for the top-view intersections); fold 1e5 took
        over a minute and fold 1e9 all 24 GB of a machine. The corpus uses at
        most 15; 1024 is finer than any carved object and builds in seconds.
    layers : int
        Most layers in a drawing (largest ``level`` + 1). The layer bottoms
        are a list with one entry per layer: ``level 1e99`` hung ``info``
        while it grew. The corpus has 5.
    curves : int
        Most basic curves in a drawing. Algorithm 1 and the intersections
        compare every pair of curves; the corpus has at most 7.
    segments : int
        Most top-view segments, summed over the drawing's basic curves (and
        most points of one legacy curve): each is a side view to fit and a
        piece to sample.
    network_curves : int
        Most curves of the network (segments times the order of their
        symmetry group, mirror included). This bounds the memory of a build
        whatever the mix of fold and segments: 65 536 curves of 65 samples
        are 100 MB of points.
    samples : int
        Most samples per curve piece (``--samples``). 100 000 000 was killed
        for memory; 10 000 is a point every 0.01 % of a curve, far finer than
        a screen or a printer resolves.
    network_points : int
        Most points of a sampled network (every replica of every curve,
        whether sampled by tolerance or by ``--samples``). The writers hold a
        network's text or mesh in memory, about 400 bytes per point: the
        default export of a fold-1024 mirrored curve (4.2 M points) peaked at
        1.6 GB. 2 M points keep every export below 1 GB; a coarser
        ``--tolerance`` or fewer ``--samples`` bring a larger network within it.
    coordinate : float
        Largest magnitude of a coordinate or height (drawing units). Meshes
        are written as float32 (GLB, STL, PLY), whose largest value is 3.4e38
        and whose resolution is 6e-8 relative: a drawing scaled to 1e90 wrote
        a GLB of infinities. Within 1e6 the geometry kernel's squared
        distances stay exact to well below its tolerances, float32 meshes
        keep 0.06 units of resolution at the very edge, and a drawing in
        millimetres can still span a kilometre.
    mesh_triangles : int
        Most triangles (and vertices) of a mesh: read from a file (STL, PLY,
        glTF, OBJ; checked on the counts a header declares before any array
        is made: a PLY header can claim 1e11 vertices in a few bytes), or
        made by ``mesh`` (estimated before each stage runs: members from
        curves x segments x profile points, faces from the loops x
        resolution squared). A mesh costs about 120 bytes a triangle at its
        peak (the default mesh of a fold-1024 drawing, 3.3 M triangles, peaked
        at 0.47 GB); ``--segments 10000`` on it ran out of memory.
    face_solid_curves : int
        Most network curves (replicas counted) for ``mesh --faces`` and
        ``--solid``: the loop search and the solid's union compare curves
        pairwise. Measured on tn-2 at fold 256 (512 curves): ``--solid`` 82 s
        and 0.66 GB; ``--faces auto`` there was 188 s and 5.2 GB before the
        triangle estimate refused it.
    faces : int
        Most faces (loops) of ``mesh --faces``, bounded before the loops are
        searched by the cycle rank of the network's graph. Finding the loops
        grows faster than their number (tn-2 at fold 64: 3 008 loops in 5 s;
        fold 128: 12 160 in 34 s), and each is a minimal surface to mesh.
    pixels : int
        Largest width or height of a rendered picture, in pixels. A 16 384 px
        square RGBA image is 1 GB in matplotlib; ``render --width 100000``
        was a MemoryError traceback.
    sweep_faces : int
        Most triangles of a mesh given to sweep analysis (``auszug sweeps``,
        :func:`auszug.sweeps.detect`). Cutting and weighing is linear in
        vertices x planes, but the refined plane search keeps every cut curve
        in memory (about 50 bytes per cut point, some 10 000 planes): the
        paper's largest mesh has 200 000 vertices (400 000 triangles); a
        million triangles stays below 2 GB. 2 M are refused before any work.
    sweep_steps : int
        Most steps of a sweep grown along its path at each end
        (``SweepParams.grow_steps``) and most parallel cuts on each side of a
        translational sweep (``SweepParams.translation_steps``). Each step cuts
        the mesh a few times (about 5 ms at 32k vertices), and a grown sweep
        stops where the mesh ends; 10 000 steps are at most about a minute
        per sweep, far beyond any mesh at the steps of 1-3 % of its diameter
        that a sweep takes.
    sketch_strokes : int
        Most strokes of a sketch given to lifting (``auszug lift``,
        :func:`auszug.lifting.lift`); checked before crossings are searched.
        The bundled examples have 6-8.
    sketch_segments : int
        Most Bezier segments of all strokes of a sketch given to lifting
        (a polyline point or an SVG path command is one). Finding the
        crossings and building the solves grows faster than linearly: two
        strokes of 8 000 segments each lifted in 43 s and 886 MB, of 2 048
        each (4 096 in all) in 10 s and 155 MB (2 cores, shared).
    sketch_crossings : int
        Most crossings between strokes of a sketch given to lifting. Each
        solve is a Newton iteration over every crossing and cue pair, and the
        time grows faster than quadratically (docs/limits.md): the 100-curve
        benchmark sketch (a vase of 96 x 4 curves, 384 crossings) lifts in
        69-76 s, a grid of 20 x 20 straight strokes (400 crossings, whose
        solves do not converge) in 445 s on a loaded 2-core machine. The bundled examples have 8-15.
    lift_steps : int
        Largest iteration count of lifting's parameters
        (``LiftParams.rounds``, ``robust_rounds``, ``newton_iterations``;
        defaults 8, 3 and 60), refused when the parameters are made
        (``auszug lift --set``): a lift's time grows with rounds times Newton
        steps per solve, so the limit keeps it within about 20 times the
        default's worst case.
    file_bytes : int
        Largest input file, checked before it is read. A 200 MB file cost
        7.7 GB of memory and 68 s; the largest corpus file is 3 KB, and 64 MB
        is a million curves of text.
    quoted : int
        Characters of a user's value quoted in an error message; longer values
        are shown shortened, with their length. A 200 MB token made an 839 MB
        message.
    message : int
        Characters of an error message at most (the rest is cut).
    mesh_segments : int
        Most steps along each member of a studio mesh (``get_mesh``, ``export``).
    tube_around : int
        Most points round a tube's profile in a studio export (at least 3).
    edit_seconds : float
        Longest time one studio change (an edit, undo, redo or recovery, with
        its geometry) may take, in seconds. It runs in a worker thread, so
        the other tabs are answered meanwhile; past this budget it is given
        up and the drawing stays as it was. The slowest edit within the
        other limits measured here (fold 1019 on U.XI.28) takes 0.8 s.
    autosave_offers : int
        Set-aside autosaves kept per document file (the newest; the studio
        offers only the newest, the older ones are for recovery by hand).
    autosave_offer_days : float
        Days a set-aside autosave that was neither restored nor replaced is
        kept (by the time it was written), checked when the studio starts and
        whenever it sets an autosave aside.
    """

    fold: int = 1024
    layers: int = 64
    curves: int = 1024
    segments: int = 8192
    network_curves: int = 65536
    samples: int = 10_000
    network_points: int = 2_000_000
    coordinate: float = 1e6
    mesh_triangles: int = 8_000_000
    face_solid_curves: int = 512
    faces: int = 16384
    pixels: int = 16384
    sweep_faces: int = 1_000_000
    sweep_steps: int = 10_000
    sketch_strokes: int = 256
    sketch_segments: int = 4096
    sketch_crossings: int = 400
    lift_steps: int = 100
    file_bytes: int = 64 * 1024 * 1024
    quoted: int = 80
    message: int = 2000
    mesh_segments: int = 1000
    tube_around: int = 64
    edit_seconds: float = 20.0
    autosave_offers: int = 3
    autosave_offer_days: float = 30.0


#: The limits in force.
LIMITS = Limits()


def shown(value: Any, width: int | None = None) -> str:
    """``repr(value)`` for a message, at most ``width`` characters (default :attr:`Limits.quoted`).

    Examples
    --------
    >>> shown(1e308)
    '1e+308'
    >>> shown("ab")
    "'ab'"
    """
    w = LIMITS.quoted if width is None else width
    if isinstance(value, str) and len(value) > w:
        return repr(value[: w - 8] + "..." + value[-3:]) + f" ({len(value)} characters)"
    if isinstance(value, (bytes, list, tuple, dict)) and len(value) > w:
        return f"a {type(value).__name__} of {len(value)} items"
    if isinstance(value, float):
        text = f"{value:.6g}"
    elif isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 10**15:
        text = f"{float(value):.6g}"
    else:
        text = repr(value)
    return text if len(text) <= w else text[: w - 3] + "..."


def clip(message: str) -> str:
    """``message`` cut to :attr:`Limits.message` characters."""
    n = LIMITS.message
    return message if len(message) <= n else message[: n - 30] + f"... ({len(message)} characters)"


def _mb(n: int) -> str:
    return f"{n / 2**20:.0f} MB" if n >= 2**20 else f"{n} bytes"


def check_file_size(path: str | os.PathLike[str], name: str | None = None) -> None:
    """Refuse a file larger than :attr:`Limits.file_bytes` before reading it (``name`` for messages).

    Raises
    ------
    FormatError
        Naming the file, its size and the limit. A missing file passes (the
        read that follows reports it).
    """
    from auszug.errors import FormatError

    try:
        size = os.stat(path).st_size
    except OSError:
        return
    if size > LIMITS.file_bytes:
        raise FormatError(f"file of {_mb(size)} is larger than the limit of {_mb(LIMITS.file_bytes)} "
                          "(auszug.limits.LIMITS.file_bytes)", name or os.fspath(path))


def check_text_size(text: str | bytes, path: str | None) -> None:
    """Refuse text longer than :attr:`Limits.file_bytes` (readers given text, not a path)."""
    from auszug.errors import FormatError

    if len(text) > LIMITS.file_bytes:
        raise FormatError(f"text of {_mb(len(text))} is larger than the limit of {_mb(LIMITS.file_bytes)} "
                          "(auszug.limits.LIMITS.file_bytes)", path)


def check_number(what: str, value: float, limit: float | None = None) -> float:
    """``value`` if finite and within +-``limit`` (default :attr:`Limits.coordinate`).

    Raises
    ------
    DrawingError
        Naming ``what``, the value and the limit.

    Examples
    --------
    >>> check_number("height", 2.5)
    2.5
    >>> check_number("height", 1e90)
    Traceback (most recent call last):
    ...
    auszug.errors.DrawingError: height 1e+90 is beyond the limit of +-1e+06 (auszug.limits.LIMITS.coordinate)
    """
    from auszug.errors import DrawingError

    lim = LIMITS.coordinate if limit is None else limit
    v = float(value)
    if not math.isfinite(v):
        raise DrawingError(f"{what} must be a finite number, got {shown(v)}")
    if abs(v) > lim:
        raise DrawingError(f"{what} {shown(v)} is beyond the limit of +-{lim:g} (auszug.limits.LIMITS.coordinate)")
    return v


def beyond_coordinate(largest: float) -> str | None:
    """The problem with a coordinate of magnitude ``largest``; None within :attr:`Limits.coordinate`.

    Examples
    --------
    >>> beyond_coordinate(2e6)
    'coordinate 2e+06 is beyond the limit of +-1e+06 (auszug.limits.LIMITS.coordinate)'
    >>> beyond_coordinate(1e6) is None
    True
    """
    if largest <= LIMITS.coordinate:
        return None
    return f"coordinate {largest:g} is beyond the limit of +-{LIMITS.coordinate:g} (auszug.limits.LIMITS.coordinate)"


def check_count(what: str, n: int, name: str) -> None:
    """Refuse a count ``n`` above the limit ``name`` (a field of :class:`Limits`).

    Raises
    ------
    DrawingError
        ``"{what} {n} is above the limit of {limit} (auszug.limits.LIMITS.{name})"``.
    """
    from auszug.errors import DrawingError

    lim = getattr(LIMITS, name)
    if n > lim:
        raise DrawingError(f"{what} {shown(n)} is above the limit of {lim} (auszug.limits.LIMITS.{name})")


def table() -> list[tuple[str, Any, str]]:
    """(name, value, first line of its reason) of every limit, for docs and ``--help``."""
    doc = Limits.__doc__ or ""
    out = []
    for f in fields(Limits):
        reason = ""
        marker = f"    {f.name} :"
        if marker in doc:
            reason = doc.split(marker, 1)[1].split("\n", 2)[1].strip()
        out.append((f.name, getattr(LIMITS, f.name), reason))
    return out
