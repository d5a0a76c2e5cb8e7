"""What counts as opening a file, for tests/layers/test_file_access.py: one AST walk over a module
that lists every call that opens, reads or writes a file by name.

A *file access* is a call of one of these (what Python and the libraries swarmvm uses give to
reach a file by its path):

- ``open``, ``io.open``, ``codecs.open``, ``os.open``, ``os.fdopen``, the ``tempfile`` functions
  that make a file (``mkstemp``, ``NamedTemporaryFile``, ...), and any ``X.open(...)``
  (``Path.open``, ``Image.open``, ``tarfile.open``), unless its first argument is an
  ``io.BytesIO(...)`` (memory, not a file);
- ``X.read_text``, ``X.read_bytes``, ``X.write_text``, ``X.write_bytes`` (``pathlib``,
  ``importlib.resources``);
- ``json.load``, ``json.dump``, ``tomllib.load``, ``pickle.load``, ``pickle.dump``, and
  ``yaml.<any>`` given a stream (an ``open(...)`` argument, or ``yaml.dump`` with two);
- ``shutil.copy``, ``copy2``, ``copyfile``, ``copytree``, ``move``;
- the libraries' writers and readers by path: ``X.savefig``, ``X.to_csv``, ``X.to_parquet``,
  ``X.to_json``, ``X.read_csv``, ``X.read_parquet``, ``X.read_json``, ``np.save``/``savez``/
  ``load`` — unless the first argument is absent (``to_csv()`` returns the text) or is memory:
  an ``io.BytesIO(...)`` call, or a name the same function bound to one.

Each access is reported as (module path relative to the root, the enclosing function's
qualified name, the call as written up to its parentheses, line)."""

import ast
from pathlib import Path
from typing import Iterator, NamedTuple

OPENERS = {"open", "io.open", "codecs.open", "os.open", "os.fdopen", "tempfile.mkstemp", "tempfile.NamedTemporaryFile",
           "tempfile.TemporaryFile", "tempfile.SpooledTemporaryFile"}
PATH_METHODS = {"read_text", "read_bytes", "write_text", "write_bytes"}
STREAM_FUNCTIONS = {"json.load", "json.dump", "tomllib.load", "pickle.load", "pickle.dump"}
SHUTIL = {"shutil.copy", "shutil.copy2", "shutil.copyfile", "shutil.copytree", "shutil.move"}
BY_PATH_METHODS = {"savefig", "to_csv", "to_parquet", "to_json", "read_csv", "read_parquet", "read_json"}
NUMPY = {"np.save", "np.savez", "np.load", "numpy.save", "numpy.savez", "numpy.load"}


class Access(NamedTuple):
    module: str
    function: str
    call: str
    line: int


def _is_memory(node: ast.expr, memory_names: set[str]) -> bool:
    """A BytesIO made right there, or a name bound to one in the same function."""
    if isinstance(node, ast.Call) and ast.unparse(node.func) in ("io.BytesIO", "BytesIO", "io.StringIO", "StringIO"):
        return True
    return isinstance(node, ast.Name) and node.id in memory_names


def _first_argument(call: ast.Call) -> ast.expr | None:
    if call.args:
        return call.args[0]
    for keyword in call.keywords:
        if keyword.arg in ("fname", "path", "path_or_buf", "file", "filepath_or_buffer", "fp"):
            return keyword.value
    return None


def _is_access(call: ast.Call, memory_names: set[str]) -> bool:
    name = ast.unparse(call.func)
    first = _first_argument(call)
    if name in OPENERS or name in STREAM_FUNCTIONS or name in SHUTIL:
        return True
    if isinstance(call.func, ast.Attribute):
        attribute = call.func.attr
        if attribute == "open":
            return first is None or not _is_memory(first, memory_names)
        if attribute in PATH_METHODS:
            return True
        if attribute in BY_PATH_METHODS or name in NUMPY:
            return first is not None and not _is_memory(first, memory_names) and not (
                isinstance(first, ast.Constant) and first.value is None)
        if name.startswith("yaml."):
            streamed = any(isinstance(a, ast.Call) and ast.unparse(a.func) == "open" for a in call.args)
            return streamed or (attribute.startswith("dump") and len(call.args) >= 2)
    return False


def accesses(source: str, module: str) -> Iterator[Access]:
    """Every file access (this module's docstring) in ``source``."""
    tree = ast.parse(source)

    def walk(node: ast.AST, scope: list[str], memory_names: set[str]) -> Iterator[Access]:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                names = set(memory_names)
                if not isinstance(child, ast.ClassDef):
                    for inner in ast.walk(child):
                        if isinstance(inner, ast.Assign) and _is_memory(inner.value, set()):
                            names.update(t.id for t in inner.targets if isinstance(t, ast.Name))
                yield from walk(child, scope + [child.name], names)
                continue
            if isinstance(child, ast.Call) and _is_access(child, memory_names):
                yield Access(module, ".".join(scope) or "<module>", ast.unparse(child.func), child.lineno)
            yield from walk(child, scope, memory_names)

    module_memory = {t.id for inner in ast.walk(tree) if isinstance(inner, ast.Assign) and _is_memory(inner.value, set())
                     for t in inner.targets if isinstance(t, ast.Name)}
    yield from walk(tree, [], module_memory)


def tree_accesses(root: Path, folders: tuple[str, ...]) -> list[Access]:
    """Every file access in every module under ``root``'s ``folders``."""
    found: list[Access] = []
    for folder in folders:
        for path in sorted((root / folder).rglob("*.py")):
            found += accesses(path.read_text(encoding="utf-8"), path.relative_to(root).as_posix())
    return found
