"""The package's layout rules, read from the import statements of src/auszug.

Every ``import`` and ``from ... import`` counts, at module level or inside a function
(a lazy import is still a dependency), except under ``if TYPE_CHECKING:``.

The flow: geometry is the kernel and imports no other part; the domain packages
(microarch, tracery, meshing) build on it and never on the file formats, the command
line or the studio; formats serve cli and studio and never import them.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[1] / "src"
PACKAGE = SRC / "auszug"


@dataclass(frozen=True)
class Import:
    """One imported name: ``module`` is the full dotted module, ``name`` a name taken from it (or None)."""

    importer: str
    path: Path
    line: int
    module: str
    name: str | None


def _module_name(path: Path) -> tuple[str, bool]:
    parts = list(path.relative_to(SRC).with_suffix("").parts)
    is_pkg = parts[-1] == "__init__"
    if is_pkg:
        parts.pop()
    return ".".join(parts), is_pkg


def _type_checking_nodes(tree: ast.AST) -> set[int]:
    skip: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            skip |= {id(n) for stmt in node.body for n in ast.walk(stmt)}
    return skip


@cache
def modules() -> dict[str, Path]:
    return {_module_name(p)[0]: p for p in sorted(PACKAGE.rglob("*.py"))}


@cache
def imports() -> tuple[Import, ...]:
    out = []
    for mod, path in modules().items():
        _, is_pkg = _module_name(path)
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        skip = _type_checking_nodes(tree)
        for node in ast.walk(tree):
            if id(node) in skip:
                continue
            if isinstance(node, ast.Import):
                out += [Import(mod, path, node.lineno, a.name, None) for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = mod.split(".") if is_pkg else mod.split(".")[:-1]
                    base = base[: len(base) - (node.level - 1)]
                    target = ".".join(base + ([node.module] if node.module else []))
                else:
                    target = node.module or ""
                out += [Import(mod, path, node.lineno, target, a.name) for a in node.names]
    return tuple(i for i in out if i.module == "auszug" or i.module.startswith("auszug."))


def _targets(imp: Import) -> str:
    """The module an import reads: ``from pkg import sub`` reads the submodule ``pkg.sub``."""
    if imp.name is not None and f"{imp.module}.{imp.name}" in modules():
        return f"{imp.module}.{imp.name}"
    return imp.module


def _part(module: str) -> str:
    """The part of auszug a module belongs to: ``auszug.meshing.sweep`` -> ``meshing``."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else ""


def _where(imp: Import) -> str:
    what = imp.module if imp.name is None else f"{imp.module}.{imp.name}"
    return f"{imp.path.relative_to(SRC.parent)}:{imp.line} imports {what}"


def test_the_scan_sees_the_package():
    mods = modules()
    assert {"auszug.geometry.intersect", "auszug.meshing.sweep", "auszug.formats.uc", "auszug.cli"} <= set(mods)
    assert any(_part(_targets(i)) == "geometry" for i in imports() if _part(i.importer) == "microarch")


FLOW = {
    "geometry": {"microarch", "tracery", "meshing", "lifting", "sweeps", "formats", "cli", "studio"},
    "microarch": {"formats", "cli", "studio"},
    "tracery": {"formats", "cli", "studio"},
    "lifting": {"microarch", "tracery", "meshing", "sweeps", "formats", "cli", "studio"},
    "meshing": {"sweeps", "formats", "cli", "studio"},
    "sweeps": {"microarch", "tracery", "lifting", "formats", "cli", "studio"},
    "formats": {"cli", "studio"},
}


@pytest.mark.parametrize("part", sorted(FLOW))
def test_imports_flow_one_way(part):
    bad = [_where(i) for i in imports() if _part(i.importer) == part and _part(_targets(i)) in FLOW[part]]
    assert not bad, f"auszug.{part} must not import {', '.join(sorted(FLOW[part]))}:\n" + "\n".join(bad)


def test_meshing_never_imports_microarch():
    """Meshing works on networks of curves, whoever made them (code only: doctest examples may build one)."""
    bad = [_where(i) for i in imports() if _part(i.importer) == "meshing" and _part(_targets(i)) == "microarch"]
    assert not bad, "auszug.meshing must not import auszug.microarch:\n" + "\n".join(bad)


def test_tracery_reads_meshing_through_its_public_api():
    """Tracery's mouldings are values of meshing's sweep model: it imports names from ``auszug.meshing``
    (the package, and only names in its ``__all__``), never meshing's modules or internals."""
    import auszug.meshing

    public = set(auszug.meshing.__all__)
    bad = [_where(i) for i in imports() if _part(i.importer) == "tracery" and _part(_targets(i)) == "meshing"
           and not (i.module == "auszug.meshing" and i.name in public)]
    assert not bad, "auszug.tracery must import meshing's public names from auszug.meshing:\n" + "\n".join(bad)


def _private(module: str, name: str | None) -> str | None:
    """The dotted prefix that owns the first private part of ``module.name``, or None if all public.

    ``auszug.geometry._tolerance`` is owned by ``auszug.geometry``; ``auszug.geometry.intersect._prim``
    by ``auszug.geometry.intersect``'s package ``auszug.geometry``.
    """
    parts = module.split(".") + ([name] if name else [])
    for k, p in enumerate(parts):
        if p.startswith("_") and not (p.startswith("__") and p.endswith("__")):
            owner = parts[:k]
            if ".".join(owner) not in modules() or modules()[".".join(owner)].name != "__init__.py":
                owner = owner[:-1]  # a private name of a module belongs to the module's package
            return ".".join(owner)
    return None


def test_no_private_names_across_packages():
    bad = []
    for i in imports():
        owner = _private(i.module, i.name)
        if owner is not None and not (i.importer == owner or i.importer.startswith(owner + ".")):
            bad.append(_where(i))
    assert not bad, "private names are for their own package; make them public:\n" + "\n".join(bad)


def test_no_import_cycles():
    edges: dict[str, set[str]] = {m: set() for m in modules()}
    for i in imports():
        t = _targets(i)
        if t in edges and t != i.importer:
            edges[i.importer].add(t)
    # a package's __init__ importing its own modules is how packages work; a module importing
    # its own package back (or any other loop) is a cycle
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    cycles: list[list[str]] = []

    def visit(v: str) -> None:  # Tarjan's strongly connected components
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(edges[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                cycles.append(sorted(comp))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    assert not cycles, "import cycles:\n" + "\n".join(
        " <-> ".join(c) + "\n  " + "\n  ".join(f"{v} -> {sorted(edges[v] & set(c))}" for v in c) for c in cycles
    )
