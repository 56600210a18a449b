"""Format registry: one module per file format registers its reader and writer.

Readers take text (or bytes) and a name for messages and return an object;
writers take an object and return text or bytes. Only :func:`load` and
:func:`save` touch paths; :func:`save` writes a temporary file in the target
folder and renames it, so a failed write never leaves a half-written file.
"""

from __future__ import annotations

import errno
import os
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Sequence

from auszug.errors import FormatError
from auszug.limits import check_file_size

__all__ = ["FileFormat", "register", "formats", "format_for", "suffix_of", "kind_of", "suffixes", "stem",
           "load", "save", "atomic_write"]


@dataclass(frozen=True)
class FileFormat:
    """A registered file format.

    Attributes
    ----------
    name : str
        Short name (``"uc"``, ``"json"``, ...).
    suffixes : tuple of str
        File name endings, longest match wins (``".network.json"`` beats ``".json"``).
    kind : str
        What it holds: ``"drawing"``, ``"network"``, ``"figure"``, ``"mesh"``.
    reader : callable or None
        ``reader(text, name) -> object``.
    writer : callable or None
        ``writer(obj, name) -> str | bytes``.
    binary : bool
        Whether the file is bytes.
    """

    name: str
    suffixes: tuple[str, ...]
    kind: str
    reader: Callable[[Any, str], Any] | None = None
    writer: Callable[[Any, str], str | bytes] | None = None
    binary: bool = False

    def write(self, obj: Any, name: str) -> str | bytes:
        """The text or bytes of ``obj`` in this format (``name`` for messages)."""
        if self.writer is None:
            raise FormatError(f"{self.name} files are read only", name)
        return self.writer(obj, name)


_FORMATS: dict[str, FileFormat] = {}


def register(fmt: FileFormat) -> FileFormat:
    """Add ``fmt`` to the registry (replacing one of the same name)."""
    _FORMATS[fmt.name] = fmt
    return fmt


def formats() -> dict[str, FileFormat]:
    """All registered formats by name.

    The built-in formats register themselves when :mod:`auszug.formats` is imported,
    which Python does before it imports this module.
    """
    return dict(_FORMATS)


def format_for(path: str | os.PathLike[str], kind: str | None = None, *, want: str = "read") -> FileFormat:
    """The registered format for ``path`` by its ending (optionally of one kind)."""
    name = os.fspath(path).lower()
    best: tuple[int, FileFormat] | None = None
    for fmt in formats().values():
        if kind is not None and fmt.kind != kind:
            continue
        if want == "read" and fmt.reader is None or want == "write" and fmt.writer is None:
            continue
        for suf in fmt.suffixes:
            if name.endswith(suf) and (best is None or len(suf) > best[0]):
                best = (len(suf), fmt)
    if best is None:
        known = sorted({s for f in formats().values() if kind in (None, f.kind) for s in f.suffixes})
        raise FormatError(f"unknown file type; expected one of {', '.join(known)}", os.fspath(path))
    return best[1]


def _ending(path: str | os.PathLike[str]) -> tuple[str, list[FileFormat]]:
    """The longest registered ending of ``path``'s name and the formats with it (registration order)."""
    name = os.path.basename(os.fspath(path)).lower()
    best, fmts = "", list[FileFormat]()
    for fmt in formats().values():
        for suf in fmt.suffixes:
            if name.endswith(suf) and len(suf) >= len(best):
                if len(suf) > len(best):
                    best, fmts = suf, []
                fmts.append(fmt)
    return best, fmts


def suffix_of(path: str | os.PathLike[str], kind: str | None = None) -> str | None:
    """The registered ending that decides ``path``'s format, or None.

    The longest registered ending of the name counts (``".network.json"``
    beats ``".json"``); with ``kind``, only if a format of that kind has it,
    so ``x.network.json`` is a network, not a ``.json`` drawing. This is how
    the commands and the studio recognise drawing files: a newly registered
    drawing format is picked up everywhere.

    Examples
    --------
    >>> suffix_of("U.XI.28.UC", "drawing"), suffix_of("a/b.network.json", "drawing")
    ('.uc', None)
    >>> suffix_of("b.network.json"), suffix_of("notes.txt")
    ('.network.json', None)
    """
    best, fmts = _ending(path)
    if not best or kind is not None and all(f.kind != kind for f in fmts):
        return None
    return best


def kind_of(path: str | os.PathLike[str]) -> str | None:
    """What a file of this name holds (``"drawing"``, ``"network"``, ...), None for an unknown ending.

    Where formats of several kinds share the ending, the first registered wins
    (as in :func:`format_for` without a kind).

    Examples
    --------
    >>> kind_of("tn-2.uc"), kind_of("tn-2.network.json"), kind_of("w.tracery.json"), kind_of("x.glb")
    ('drawing', 'network', 'tracery', 'mesh')
    """
    best, fmts = _ending(path)
    return fmts[0].kind if best else None


def suffixes(kind: str | None = None) -> list[str]:
    """Every registered ending (of formats of ``kind``), once each, in registration order.

    Examples
    --------
    >>> suffixes("drawing")
    ['.uc', '.json']
    """
    return list(dict.fromkeys(s for f in formats().values() if kind in (None, f.kind) for s in f.suffixes))


def stem(path: str | os.PathLike[str], kind: str | None = None) -> str:
    """The file name without its :func:`suffix_of` ending (of ``kind``), else without its last ending.

    A name that is only an ending keeps it.

    Examples
    --------
    >>> stem("corpus/U.XI.28.fixed.uc", "drawing"), stem("tn-2.network.json"), stem("tn-2.network.json", "drawing")
    ('U.XI.28.fixed', 'tn-2', 'tn-2.network')
    >>> stem(".uc"), stem("notes.txt")
    ('.uc', 'notes')
    """
    name = os.path.basename(os.fspath(path))
    suf = suffix_of(name, kind)
    if suf and len(name) > len(suf):
        return name[: len(name) - len(suf)]
    return Path(name).stem or name


def load(path: str | os.PathLike[str], kind: str | None = "drawing") -> Any:
    """Read ``path`` with the format its name says."""
    p = Path(path)
    fmt = format_for(p, kind)
    check_file_size(p)
    try:
        data: Any = p.read_bytes() if fmt.binary else p.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise FormatError("no such file", str(p)) from None
    except IsADirectoryError:
        raise FormatError("is a folder, not a file", str(p)) from None
    except UnicodeDecodeError as e:
        raise FormatError(f"not a text file ({e.reason} at byte {e.start})", str(p)) from None
    assert fmt.reader is not None
    return fmt.reader(data, str(p))


def save(obj: Any, path: str | os.PathLike[str], kind: str | None = None) -> Path:
    """Write ``obj`` to ``path`` in the format its name says, atomically."""
    p = Path(path)
    fmt = format_for(p, kind, want="write")
    assert fmt.writer is not None
    data = fmt.writer(obj, p.name)
    atomic_write(p, data)
    return p


def atomic_write(path: str | os.PathLike[str], data: str | bytes) -> None:
    """Write ``data`` to a temporary file beside ``path``, then rename it over ``path``.

    Raises
    ------
    OSError
        Whose ``filename`` is ``path`` (not the temporary file).
    """
    p = Path(path)
    raw = data.encode("utf-8") if isinstance(data, str) else data
    try:
        _replace_with(p, raw)
    except OSError as e:  # name the file the user asked for, not the temporary one
        raise type(e)(e.errno, f"cannot write ({e.strerror or e})", str(p)) from None


def atomic_write_all(items: Sequence[tuple[str | os.PathLike[str], str | bytes]]) -> None:
    """Write several files all or nothing: each to a temporary file beside it, then rename them all.

    If writing any temporary file fails, every temporary file is removed and no target is
    touched. If a rename fails (rare: the temporary files are beside their targets), the targets
    already renamed in this call are removed as well, so no partial set of outputs is left.

    Raises
    ------
    OSError
        Whose ``filename`` is the target that failed (not its temporary file).
    """
    staged: list[tuple[str, Path]] = []
    done: list[Path] = []
    current = Path(".")
    try:
        for path, data in items:
            current = Path(path)
            current.parent.mkdir(parents=True, exist_ok=True)
            if current.is_dir():
                raise IsADirectoryError(errno.EISDIR, "is a folder", str(current))
            raw = data.encode("utf-8") if isinstance(data, str) else data
            fd, tmp = tempfile.mkstemp(prefix=f".{current.name}.", suffix=".tmp", dir=current.parent)
            staged.append((tmp, current))
            umask = os.umask(0)
            os.umask(umask)
            os.fchmod(fd, 0o666 & ~umask)
            with os.fdopen(fd, "wb") as fh:
                fh.write(raw)
        for tmp, target in staged:
            current = target
            os.replace(tmp, target)
            done.append(target)
    except BaseException as e:
        for tmp, _ in staged:
            try:
                os.unlink(tmp)
            except FileNotFoundError:
                pass
        for target in done:
            try:
                os.unlink(target)
            except FileNotFoundError:
                pass
        if isinstance(e, OSError) and not isinstance(e, IsADirectoryError):
            raise type(e)(e.errno, f"cannot write ({e.strerror or e})", str(current)) from None
        raise


def _replace_with(p: Path, raw: bytes) -> None:
    p.parent.mkdir(parents=True, exist_ok=True)
    if p.is_dir():
        raise IsADirectoryError(errno.EISDIR, "is a folder", str(p))
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".tmp", dir=p.parent)
    try:
        umask = os.umask(0)
        os.umask(umask)
        os.fchmod(fd, 0o666 & ~umask)  # mkstemp makes 0600; give the file the usual mode
        with os.fdopen(fd, "wb") as fh:
            fh.write(raw)
        os.replace(tmp, p)
    except BaseException:
        try:
            os.unlink(tmp)
        except FileNotFoundError:
            pass
        raise
