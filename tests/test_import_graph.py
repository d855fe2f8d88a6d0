"""The import graph of ``ssl_marl`` and ``train``: no cycles, and data flows one way.

Every import statement counts (module level, inside functions, under ``TYPE_CHECKING``):
``import a.b`` imports ``a.b``; ``from pkg import name`` imports ``pkg`` unless ``pkg.name``
is itself a module, in which case it imports that submodule. Only edges between the
project's own modules are kept (a package is the module of its ``__init__.py``).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("ssl_marl", "train")
# physics -> envs -> skills -> plays -> decisions -> runners -> bridge; train/ above all of them.
LAYERS = ("physics", "envs", "skills", "plays", "decisions", "runners", "bridge")


def module_files() -> dict[str, Path]:
    """Dotted module name -> file, for every module of the project's packages."""
    out: dict[str, Path] = {}
    for pkg in PACKAGES:
        for path in sorted((ROOT / pkg).rglob("*.py")):
            parts = list(path.relative_to(ROOT).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts = parts[:-1]
            out[".".join(parts)] = path
    return out


def _resolve(module: str, node: ast.ImportFrom, is_package: bool) -> str:
    if not node.level:
        return node.module or ""
    base = module.split(".")
    base = base if is_package else base[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def import_graph() -> dict[str, set[str]]:
    """Module -> the project modules its import statements name."""
    files = module_files()
    graph: dict[str, set[str]] = {}
    for module, path in files.items():
        edges: set[str] = set()
        is_package = path.name == "__init__.py"
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Import):
                edges.update(a.name for a in node.names)
            elif isinstance(node, ast.ImportFrom):
                target = _resolve(module, node, is_package)
                for alias in node.names:
                    sub = f"{target}.{alias.name}"
                    edges.add(sub if sub in files else target)
        graph[module] = {e for e in edges if e in files and e != module}
    return graph


def strongly_connected(graph: dict[str, set[str]]) -> list[list[str]]:
    """Tarjan's algorithm: the components with more than one module (the cycles)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
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
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_the_graph_sees_lazy_and_type_checking_imports(tmp_path):
    tree = ast.parse("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import a.b\n"
                     "def f():\n    from . import c\n")
    names = {n.__class__.__name__ for n in ast.walk(tree) if isinstance(n, (ast.Import, ast.ImportFrom))}
    assert names == {"Import", "ImportFrom"}  # ast.walk reaches nested statements


def test_no_import_cycles():
    cycles = strongly_connected(import_graph())
    assert not cycles, "import cycles:\n" + "\n".join(" <-> ".join(c) for c in cycles)


def test_cycle_finder_finds_a_cycle():
    assert strongly_connected({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]


@pytest.mark.parametrize("lower", LAYERS)
def test_lower_layers_import_nothing_above_them(lower):
    """physics -> envs -> skills -> plays -> decisions -> runners -> bridge, and ``train`` above all.

    The one allowed upward edge is the CLI's ``train`` command, which forwards to
    ``train.__main__`` lazily (importing the library never loads the trainer)."""
    graph = import_graph()
    above = LAYERS[LAYERS.index(lower) + 1:]
    bad = []
    for module, edges in graph.items():
        if not module.startswith(f"ssl_marl.{lower}"):
            continue
        for e in edges:
            if e.startswith("train") or any(e.startswith(f"ssl_marl.{a}") for a in above):
                bad.append(f"{module} -> {e}")
    assert not bad, "imports against the data flow:\n" + "\n".join(sorted(bad))
