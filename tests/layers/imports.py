"""The project's Python modules and what each imports, read from the source with ``ast`` (no
module is run): the graph the layer tests walk.

A module's name is the one it is imported by: generator/x.py is ``swarmvm.x``, studies/a/b.py
``swarmvm.studies.a.b``; the runtime files (runtime_py/) and firmware's scripts import each
other by file name, as on a robot, so theirs is the bare file stem."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]

# Folder -> the package its files are imported in ("" for files imported by their bare stem).
FOLDERS = {"generator": "swarmvm", "studies": "swarmvm.studies", "runtime_py": "", "firmware": ""}


def module_files() -> dict[str, Path]:
    """Every Python module of FOLDERS, by module name."""
    found = {}
    for folder, package in FOLDERS.items():
        for path in sorted((ROOT / folder).rglob("*.py")):
            parts = list(path.relative_to(ROOT / folder).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts.pop()
            if package:
                found[".".join([package, *parts])] = path
            elif parts:                                 # not the folder's own __init__.py
                found[parts[-1]] = path
    return found


def _is_package(name: str, files: dict[str, Path]) -> bool:
    return name in files and files[name].name == "__init__.py"


def _type_checking_only(node: ast.AST) -> bool:
    """An ``if TYPE_CHECKING:`` block: read by type checkers, never run."""
    return isinstance(node, ast.If) and ast.unparse(node.test) in ("TYPE_CHECKING", "typing.TYPE_CHECKING")


def _run_nodes(tree: ast.AST) -> list[ast.AST]:
    """Every node of ``tree`` outside ``if TYPE_CHECKING:`` blocks."""
    nodes, todo = [], [tree]
    while todo:
        node = todo.pop()
        nodes.append(node)
        todo.extend(child for child in ast.iter_child_nodes(node) if not _type_checking_only(child))
    return nodes


def imported_names(name: str, path: Path, files: dict[str, Path]) -> set[str]:
    """The modules ``name`` imports anywhere in its body (inside functions too: an import run
    late is still a dependency), as absolute names: ``from .x import y`` gives ``pkg.x``, and
    ``pkg.x.y`` as well when y is a module. Imports under ``if TYPE_CHECKING:`` are left out."""
    package = name if _is_package(name, files) else name.rpartition(".")[0]
    found = set()
    for node in _run_nodes(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[:len(base) - (node.level - 1)]
                origin = ".".join(base + ([node.module] if node.module else []))
            else:
                origin = node.module or ""
            found.add(origin)
            found.update(origin + "." + alias.name for alias in node.names
                         if origin + "." + alias.name in files)
    return found


def import_graph() -> dict[str, set[str]]:
    """Module -> the project's modules it imports (imports of anything else left out)."""
    files = module_files()
    return {name: {other for other in imported_names(name, path, files) if other in files and other != name}
            for name, path in files.items()}


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The graph's strongly connected components of more than one module (Tarjan's algorithm,
    iterative): each is a set of modules that import one another, in a cycle."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph[child]))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
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
