"""The package's architecture, enforced: no import cycles, dependencies point down the layers,
and no function or module grows past what one reader can hold.

Imports are read with ``ast``: module-level and function-level imports both count, imports
under ``if TYPE_CHECKING:`` do not (they never run). The layers, lowest first:

    model <- cache <- sources <- engine <- rules, outputs, engines <- server, lsp, mcp <- cli

A module may import its own layer and the layers below it; ``rules``, ``outputs`` and
``engines`` do not import each other (the E rules read the engines' outcomes through the
``confirmation`` document view). The package facade (``urdflint/__init__.py``) wires the
engine's document views and may be imported from ``rules`` upwards.
"""

from __future__ import annotations

import ast
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.conftest import ROOT

# where each installed package's sources live (see [tool.setuptools] package-dir)
SOURCE_DIRS = {"urdflint": ROOT / "urdflint", "urdflint.rules": ROOT / "rules",
               "urdflint.server": ROOT / "server"}  # fmt: skip
LAYERS = {
    "urdflint.model": 0,
    "urdflint.cache": 0.5,
    "urdflint.sources": 1,
    "urdflint.engine": 2,
    "urdflint.rules": 3,
    "urdflint.outputs": 3,
    "urdflint.engines": 3,
    "urdflint.server": 4,
    "urdflint.lsp": 4,
    "urdflint.mcp": 4,
    "urdflint.cli": 5,
}
FACADE_RANK = 2.5  # urdflint/__init__.py: importable from rules and outputs upwards
MAX_FUNCTION_LINES = 60
MAX_MODULE_LINES = 400


def modules() -> dict[str, Path]:
    found: dict[str, Path] = {}
    for package, folder in SOURCE_DIRS.items():
        for path in sorted(folder.rglob("*.py")):
            if "__pycache__" in path.parts:
                continue
            if package == "urdflint" and path.relative_to(folder).parts[0] in ("rules", "server"):
                continue
            parts = list(path.relative_to(folder).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts.pop()
            found[".".join([package, *parts])] = path
    return found


MODULES = modules()


def _is_type_checking(test: ast.expr) -> bool:
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _import_nodes(tree: ast.AST) -> Iterator[ast.Import | ast.ImportFrom]:
    """Every import that can run: anywhere in the module except under ``if TYPE_CHECKING``."""
    stack: list[ast.AST] = [tree]
    while stack:
        node = stack.pop()
        if isinstance(node, ast.If) and _is_type_checking(node.test):
            stack.extend(node.orelse)
            continue
        if isinstance(node, ast.Import | ast.ImportFrom):
            yield node
        stack.extend(ast.iter_child_nodes(node))


def imports_of(name: str, path: Path) -> set[str]:
    """The package modules ``name`` imports (the most specific module each import names)."""
    is_package = path.name == "__init__.py"
    found: set[str] = set()
    for node in _import_nodes(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        else:
            base = node.module or ""
            if node.level:
                anchor = name.split(".") if is_package else name.split(".")[:-1]
                anchor = anchor[: len(anchor) - (node.level - 1)]
                base = ".".join([*anchor, base] if base else anchor)
            targets = [f"{base}.{alias.name}" if f"{base}.{alias.name}" in MODULES else base
                       for alias in node.names]  # fmt: skip
        for target in targets:
            while target and target not in MODULES and "." in target:
                target = target.rsplit(".", 1)[0]
            if target in MODULES and target != name:
                found.add(target)
    return found


GRAPH = {name: imports_of(name, path) for name, path in MODULES.items()}


def layer(name: str) -> tuple[str, float] | None:
    if name == "urdflint":
        return "urdflint", FACADE_RANK
    for prefix, rank in LAYERS.items():
        if name == prefix or name.startswith(prefix + "."):
            return prefix, rank
    return None


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components with more than one module (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    found: list[list[str]] = []
    counter = 0
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph[start])))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            advanced = False
            for child in children:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph.get(child, ())))))
                    advanced = True
                    break
                if child in on_stack:
                    low[node] = min(low[node], index[child])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    found.append(sorted(component))
    return found


def test_the_package_is_found_where_expected() -> None:
    assert {"urdflint.model.document", "urdflint.engine.linter", "urdflint.cli",
            "urdflint.rules", "urdflint.server.app"} <= set(MODULES)  # fmt: skip
    assert all(layer(name) is not None for name in MODULES if name != "urdflint.__main__")


def test_no_module_imports_another_in_a_cycle() -> None:
    assert cycles(GRAPH) == []


def test_dependencies_point_down_the_layers() -> None:
    wrong: list[str] = []
    for name, targets in GRAPH.items():
        mine = layer(name)
        if mine is None or name == "urdflint":
            continue
        for target in sorted(targets):
            theirs = layer(target)
            if theirs is None:
                continue
            if theirs[1] > mine[1] or (theirs[1] == mine[1] and theirs[0] != mine[0]):
                wrong.append(f"{name} ({mine[0]}) imports {target} ({theirs[0]})")
    assert wrong == []


def test_the_checker_sees_cycles_and_type_checking_blocks(tmp_path: Path) -> None:
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert cycles({"a": {"b"}, "b": set()}) == []
    source = tmp_path / "m.py"
    source.write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from urdflint.cli import main\n"
        "def f():\n    from urdflint.engine import linter\n"
    )
    assert imports_of("urdflint.model.m", source) == {"urdflint.engine.linter"}


def _functions(tree: ast.AST) -> Iterator[ast.FunctionDef | ast.AsyncFunctionDef]:
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            yield node


@pytest.mark.parametrize("name", sorted(MODULES))
def test_functions_and_modules_stay_short(name: str) -> None:
    path = MODULES[name]
    text = path.read_text(encoding="utf-8")
    assert len(text.splitlines()) <= MAX_MODULE_LINES, f"{path} is over {MAX_MODULE_LINES} lines"
    long = [
        f"{fn.name} ({fn.end_lineno - fn.lineno + 1} lines)"  # type: ignore[operator]
        for fn in _functions(ast.parse(text))
        if fn.end_lineno - fn.lineno + 1 > MAX_FUNCTION_LINES  # type: ignore[operator]
    ]
    assert long == []


def test_every_module_imports_on_its_own() -> None:
    """Each engine module imported first, with no other urdflint module loaded before it (the
    rules are imported by test_registry): one interpreter forgets every ``urdflint`` module
    between two imports, so an import that works only after another module fails here."""
    import subprocess
    import sys

    names = [n for n in sorted(MODULES) if n != "urdflint.__main__"
             and not n.startswith("urdflint.rules.")]  # fmt: skip
    script = (
        "import importlib, sys, traceback\n"
        "for name in sys.argv[1:]:\n"
        "    for loaded in [m for m in sys.modules if m.split('.')[0] == 'urdflint']:\n"
        "        del sys.modules[loaded]\n"
        "    try:\n"
        "        importlib.import_module(name)\n"
        "    except Exception:\n"
        "        print(name + ': ' + traceback.format_exc().strip().splitlines()[-1])\n"
    )
    proc = subprocess.run([sys.executable, "-c", script, *names], capture_output=True,
                          text=True, cwd=ROOT)  # fmt: skip
    assert proc.returncode == 0, proc.stderr
    failed = proc.stdout.splitlines()
    assert failed == []
