"""What tests/boundary/test_writer_escaping.py checks in Python code, as
tests/boundary/test_template_filters.py checks templates: text that Python code writes into a
file passes through one of swarmvm.boundary.escape's functions.

**A write.** The output layer's one entry, ``write_outputs(folder, files)``, is the sink, and
so is a document of a language of its own printed to standard output (the footprint's Markdown
and JUnit reports given to ``terminal.line``/``lines``: STDOUT_DOCUMENTS; plain-text lines are
terminal text, which the terminal layer escapes). The *writer functions* are found from them: every function of the tree called in the expression
giving ``files`` (or in what the enclosing function assigned to the names that expression uses,
followed back through the function), and then, within each writer function, every function of
the tree called inside a text-building expression or a ``return``. A function of the tree is
one defined in a module of the scanned folders, reached by its name in the same module, a
``from M import f`` or an ``import M as m`` / ``m.f``.

**Text-building expressions** in a writer function: an f-string, ``%`` with a string literal on
its left, ``"...".format(...)``, ``+`` with a string literal on one side, and
``"sep".join(...)``. Each value interpolated into one must be *escaped*:

- a literal, or a call to an escaping function: a public function of swarmvm.boundary.escape
  (one per output context), or ``json.dumps`` (the JSON writer escapes for JSON);
- a number: a ``%d``/``%x``/``%f``-style conversion (or an f-string spec ending in one of
  ``dxXobfeEgG%``), or ``int(...)``, ``len(...)``, ``round(...)``, ``float(...)``, ``abs``,
  ``sum``, arithmetic of numbers, ``str(<number>)``;
- another text-building expression, a choice (``a if c else b``) or a join whose parts are
  escaped; a call to a writer function (its own body is checked);
- a local name every assignment of which, in the function, is escaped (a loop variable over a
  ``range``/``enumerate`` counter is a number).

A text-building expression that is itself (part of) the argument of an escaping function
(``markdown("%s: %s" % (a, b))``) is escaped as a whole. Anything else — a parameter, an
attribute, ``str(x)``, ``%s`` of a name — is unescaped user text as far as the check can tell,
and is reported, unless the line carries a ``# escaped:`` comment saying why the value cannot
hold user text (the test's KNOWN_SAFE list does the same for lines of modules it does not own). Messages (arguments of an exception, of swarmvm.boundary.terminal's
functions) are not writes: the terminal layer escapes them where they are printed."""

import ast
from pathlib import Path
from typing import Iterator, NamedTuple

import swarmvm.boundary.escape as escape

ESCAPING = frozenset(name for name in vars(escape) if not name.startswith("_") and callable(getattr(escape, name))
                     and getattr(getattr(escape, name), "__module__", "") == escape.__name__
                     and name not in ("bounded", "UnsafeText")) | {"json.dumps", "dumps"}
NUMERIC_CALLS = frozenset({"int", "len", "round", "float", "abs", "sum", "ord", "hash", "min", "max", "bool"})
NUMERIC_CONVERSIONS = frozenset("dixXobfFeEgGc%")
# A document printed to standard output in a language of its own (the footprint's Markdown and
# JUnit XML) is a write too: the terminal layer escapes only what a terminal reads, not Markdown
# or XML. (Plain-text reports printed through terminal.line/lines are terminal text, escaped
# there.)
STDOUT_SINKS = frozenset({"terminal.line", "terminal.lines"})
STDOUT_DOCUMENTS = frozenset({("generator/footprint/report.py", "markdown_report"),
                              ("generator/footprint/report.py", "junit_report")})
MESSAGE_CALLS = frozenset({"error", "warn", "note", "fail", "message", "line", "lines", "InputError", "UnsafeText",
                           "ValueError", "TypeError", "FootprintError", "TrialError", "BuildError", "RuntimeError"})


class Unescaped(NamedTuple):
    module: str
    function: str
    line: int
    value: str


class _Module(NamedTuple):
    path: str
    tree: ast.Module
    lines: list[str]
    functions: dict[str, ast.FunctionDef]
    imported: dict[str, tuple[str, str]]     # local name -> (module path, function name) or (module path, "")
    constants: dict[str, ast.expr]           # module-level names assigned once: their value


def _module_path(root: Path, folders: tuple[str, ...], current: Path, node: ast.ImportFrom) -> Path | None:
    """The file a relative or ``swarmvm.`` import names, when it is in the tree."""
    if node.level:
        base = current.parent
        for _ in range(node.level - 1):
            base = base.parent
    elif node.module and node.module.split(".")[0] == "swarmvm":
        base = root / "generator"
    else:
        return None
    parts = (node.module or "").split(".")
    if not node.level:
        parts = parts[1:]
        if parts and parts[0] == "studies":
            base, parts = root / "studies", parts[1:]
    target = base.joinpath(*parts) if parts else base
    return target


def load_tree(root: Path, folders: tuple[str, ...]) -> dict[str, _Module]:
    modules: dict[str, _Module] = {}
    for folder in folders:
        for path in sorted((root / folder).rglob("*.py")):
            source = path.read_text(encoding="utf-8")
            modules[path.relative_to(root).as_posix()] = _parse(root, folders, path, source)
    return modules


def _parse(root: Path, folders: tuple[str, ...], path: Path, source: str) -> _Module:
    tree = ast.parse(source)
    functions = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}
    imported: dict[str, tuple[str, str]] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            target = _module_path(root, folders, path, node)
            if target is None:
                continue
            for alias in node.names:
                local = alias.asname or alias.name
                as_module = target / alias.name
                if (as_module.with_suffix(".py")).is_file():
                    imported[local] = (as_module.with_suffix(".py").relative_to(root).as_posix(), "")
                elif (as_module / "__init__.py").is_file():
                    imported[local] = ((as_module / "__init__.py").relative_to(root).as_posix(), "")
                elif target.with_suffix(".py").is_file():
                    imported[local] = (target.with_suffix(".py").relative_to(root).as_posix(), alias.name)
                elif (target / "__init__.py").is_file():
                    imported[local] = ((target / "__init__.py").relative_to(root).as_posix(), alias.name)
    assigned: dict[str, list[ast.expr]] = {}
    for node in tree.body:
        names = node.targets if isinstance(node, ast.Assign) else [node.target] if isinstance(node, ast.AnnAssign) else []
        value = getattr(node, "value", None)
        for name in names:
            if isinstance(name, ast.Name) and value is not None:
                assigned.setdefault(name.id, []).append(value)
    constants = {name: values[0] for name, values in assigned.items() if len(values) == 1}
    try:
        rel = path.relative_to(root).as_posix()
    except ValueError:
        rel = path.as_posix()
    return _Module(rel, tree, source.splitlines(), functions, imported, constants)


def _resolve(modules: dict[str, _Module], module: _Module, func: ast.expr) -> tuple[str, str] | None:
    """(module path, function name) of a call's target when it is a function of the tree."""
    if isinstance(func, ast.Name):
        if func.id in module.functions:
            return module.path, func.id
        target = module.imported.get(func.id)
        if target and target[1] and target[0] in modules and target[1] in modules[target[0]].functions:
            return target
    if isinstance(func, ast.Attribute) and isinstance(func.value, ast.Name):
        target = module.imported.get(func.value.id)
        if target and not target[1] and target[0] in modules and func.attr in modules[target[0]].functions:
            return target[0], func.attr
    return None


def _enclosing_functions(tree: ast.AST) -> Iterator[ast.FunctionDef]:
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            yield node  # type: ignore[misc]


def _assignments(function: ast.FunctionDef) -> dict[str, list[ast.expr]]:
    """Each local name's assigned values (loop and comprehension targets: their iterables)."""
    found: dict[str, list[ast.expr]] = {}
    for node in ast.walk(function):
        pairs: list[tuple[ast.expr, ast.expr]] = []
        if isinstance(node, ast.Assign):
            pairs = [(t, node.value) for t in node.targets]
        elif isinstance(node, (ast.AnnAssign, ast.AugAssign)) and node.value is not None:
            pairs = [(node.target, node.value)]
        elif isinstance(node, (ast.For, ast.comprehension)):
            pairs = [(node.target, node.iter)]
        elif isinstance(node, ast.NamedExpr):
            pairs = [(node.target, node.value)]
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and \
                node.func.attr in ("append", "extend", "insert", "add") and node.args:
            pairs = [(node.func.value, node.args[-1] if node.func.attr != "extend" else node.args[0])]
        for target, value in pairs:
            for name in ast.walk(target):
                if isinstance(name, ast.Name):
                    found.setdefault(name.id, []).append(value)
    return found


def _calls_feeding(expr: ast.expr, assigned: dict[str, list[ast.expr]]) -> Iterator[ast.Call]:
    """Calls in ``expr`` and, followed back through the function, in what its names were assigned."""
    seen: set[str] = set()
    todo = [expr]
    while todo:
        node = todo.pop()
        for inner in ast.walk(node):
            if isinstance(inner, ast.Call):
                yield inner
            if isinstance(inner, ast.Name) and inner.id not in seen:
                seen.add(inner.id)
                todo.extend(assigned.get(inner.id, []))


# Packages the search for writer functions does not enter: the readers and the compiler make
# models and images, not text for a file (what the compiler writes as text, it writes through
# templates: tests/boundary/test_template_filters.py), and the boundary is the layer itself.
NOT_WRITERS = ("generator/readers/", "generator/compiler/", "generator/boundary/")


def writer_functions(modules: dict[str, _Module]) -> set[tuple[str, str]]:
    """Every writer function of the tree (this module's docstring)."""
    found = _writer_functions(modules)
    return {(path, name) for path, name in found if not path.startswith(NOT_WRITERS)}


def _writer_functions(modules: dict[str, _Module]) -> set[tuple[str, str]]:
    writers: set[tuple[str, str]] = set()
    todo: list[tuple[str, str]] = []
    for module in modules.values():
        for function in _enclosing_functions(module.tree):
            assigned = _assignments(function)
            for call in ast.walk(function):
                if not isinstance(call, ast.Call):
                    continue
                sink = ast.unparse(call.func)
                documents_only = sink in STDOUT_SINKS
                if sink.split(".")[-1] == "write_outputs" and len(call.args) >= 2:
                    written = call.args[1]
                elif documents_only and call.args:
                    written = call.args[0]
                else:
                    continue
                if True:
                    for inner in _calls_feeding(written, assigned):
                        target = _resolve(modules, module, inner.func)
                        if documents_only and target not in STDOUT_DOCUMENTS:
                            continue
                        if target and target not in writers and not target[0].startswith(NOT_WRITERS):
                            writers.add(target)
                            todo.append(target)
    while todo:
        path, name = todo.pop()
        module = modules[path]
        function = module.functions[name]
        assigned = _assignments(function)
        roots = [n for n in ast.walk(function) if _is_text_building(n) or isinstance(n, ast.Return)]
        for root in roots:
            value = root.value if isinstance(root, ast.Return) else root
            if value is None:
                continue
            for inner in _calls_feeding(value, assigned):  # type: ignore[arg-type]
                target = _resolve(modules, module, inner.func)
                if target and target not in writers and not target[0].startswith(NOT_WRITERS):
                    writers.add(target)
                    todo.append(target)
    return writers


def _is_str(node: ast.expr) -> bool:
    return isinstance(node, ast.Constant) and isinstance(node.value, str)


def _is_text_building(node: ast.AST) -> bool:
    if isinstance(node, ast.JoinedStr):
        return True
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mod) and _is_str(node.left):
        return True
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add) and (_is_str(node.left) or _is_str(node.right)):
        return True
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr in ("format", "join") \
            and _is_str(node.func.value):
        return True
    return False


def _percent_conversions(template: str) -> list[str]:
    """The conversion letters of a %-format string, in order (``%%`` left out)."""
    conversions, i = [], 0
    while i < len(template):
        if template[i] == "%":
            j = i + 1
            while j < len(template) and template[j] in "#0- +.*0123456789()abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_" \
                    and not template[j].isalpha():
                j += 1
            if j < len(template) and template[j] != "%":
                conversions.append(template[j])
            i = j + 1
        else:
            i += 1
    return conversions


class _Checker:
    def __init__(self, modules: dict[str, _Module], writers: set[tuple[str, str]], module: _Module,
                 function: ast.FunctionDef) -> None:
        self.modules, self.writers, self.module, self.function = modules, writers, module, function
        self.assigned = _assignments(function)
        self.parameters = {a.arg for a in function.args.args + function.args.kwonlyargs + function.args.posonlyargs}
        self.checking: set[str] = set()

    def numeric(self, node: ast.expr) -> bool:
        if isinstance(node, ast.Constant):
            return isinstance(node.value, (int, float)) and not isinstance(node.value, bool) or node.value is None
        if isinstance(node, ast.Call):
            name = ast.unparse(node.func)
            return name in NUMERIC_CALLS
        if isinstance(node, ast.BinOp) and not _is_text_building(node):
            return self.numeric(node.left) and self.numeric(node.right)
        if isinstance(node, ast.UnaryOp):
            return self.numeric(node.operand)
        if isinstance(node, ast.Name):
            return self._name(node.id, self.numeric)
        return False

    def _name(self, name: str, test: "object") -> bool:
        if name in self.checking:
            return False
        if name not in self.parameters and name not in self.assigned and name in self.module.constants:
            self.checking.add(name)
            try:
                return bool(test(self.module.constants[name]))  # type: ignore[operator]
            finally:
                self.checking.discard(name)
        if name in self.parameters or name not in self.assigned:
            return False
        self.checking.add(name)
        try:
            values = self.assigned[name]
            ok = []
            for value in values:
                if isinstance(value, ast.Call) and ast.unparse(value.func) in ("range", "enumerate") and test == self.numeric:
                    ok.append(True)
                else:
                    ok.append(test(value))  # type: ignore[operator]
            return all(ok)
        finally:
            self.checking.discard(name)

    def escaped(self, node: ast.expr) -> bool:
        if isinstance(node, ast.Constant) or _is_text_building(node):
            return True         # (a text-building expression's parts are checked where it stands)
        if self.numeric(node):
            return True
        if isinstance(node, ast.Call):
            name = ast.unparse(node.func)
            if name.split(".")[-1] in ESCAPING and (name.split(".")[0] in ("escape", "json") or "." not in name):
                return True
            if name == "str" and node.args and self.numeric(node.args[0]):
                return True
            if isinstance(node.func, ast.Attribute) and node.func.attr == "encode":
                return self.escaped(node.func.value)
            target = _resolve(self.modules, self.module, node.func)
            if target and target in self.writers:
                return True
            if _is_text_building(node):
                return not list(self.unescaped_parts(node))
            return False
        if isinstance(node, ast.IfExp):
            return self.escaped(node.body) and self.escaped(node.orelse)
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
            return self.escaped(node.left) and self.escaped(node.right)
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult):     # "---|" * len(head)
            return (self.escaped(node.left) and self.numeric(node.right)) or (
                self.numeric(node.left) and self.escaped(node.right))
        if isinstance(node, (ast.JoinedStr, ast.BinOp)) and _is_text_building(node):
            return not list(self.unescaped_parts(node))
        if isinstance(node, (ast.GeneratorExp, ast.ListComp)):
            return self.escaped(node.elt)
        if isinstance(node, (ast.List, ast.Tuple)):
            return all(self.escaped(e) for e in node.elts)
        if isinstance(node, ast.Starred):
            return self.escaped(node.value)
        if isinstance(node, ast.Name):
            return self._name(node.id, self.escaped)
        return False

    def unescaped_parts(self, node: ast.AST) -> Iterator[ast.expr]:
        """The values interpolated into one text-building expression that are not escaped."""
        if isinstance(node, ast.JoinedStr):
            for part in node.values:
                if isinstance(part, ast.FormattedValue):
                    spec = ast.unparse(part.format_spec) if part.format_spec else ""
                    if spec[-2:-1] in NUMERIC_CONVERSIONS and spec:
                        continue
                    if not self.escaped(part.value):
                        yield part.value
        elif isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mod):
            assert isinstance(node.left, ast.Constant)
            conversions = _percent_conversions(str(node.left.value))
            values = node.right.elts if isinstance(node.right, ast.Tuple) else [node.right]
            for conversion, value in zip(conversions, values):
                if conversion in NUMERIC_CONVERSIONS and conversion != "c":
                    continue
                if not self.escaped(value):
                    yield value
        elif isinstance(node, ast.BinOp):
            for side in (node.left, node.right):
                if not self.escaped(side):
                    yield side
        elif isinstance(node, ast.Call):
            for value in list(node.args) + [k.value for k in node.keywords]:
                if not self.escaped(value):
                    yield value


def _in_message(parents: dict[ast.AST, ast.AST], node: ast.AST) -> bool:
    """Inside an exception's or a terminal function's arguments (escaped where printed)."""
    while node in parents:
        node = parents[node]
        if isinstance(node, ast.Call) and ast.unparse(node.func).split(".")[-1] in MESSAGE_CALLS:
            return True
        if isinstance(node, ast.Raise):
            return True
    return False


def _inside_escaping_call(parents: dict[ast.AST, ast.AST], node: ast.AST) -> bool:
    """Built as (part of) the argument of an escaping function: ``markdown("%s: %s" % (a, b))``
    escapes the whole text, so its parts need no escaping of their own."""
    while node in parents:
        node = parents[node]
        if isinstance(node, ast.Call):
            name = ast.unparse(node.func)
            if name.split(".")[-1] in ESCAPING and (name.split(".")[0] in ("escape", "json") or "." not in name):
                return True
            if not _is_text_building(node):
                return False
        elif not isinstance(node, (ast.BinOp, ast.JoinedStr, ast.FormattedValue, ast.Tuple, ast.List, ast.IfExp,
                                   ast.GeneratorExp, ast.ListComp, ast.comprehension, ast.BoolOp, ast.keyword)):
            return False
    return False


def unescaped(modules: dict[str, _Module], writers: set[tuple[str, str]] | None = None) -> list[Unescaped]:
    """Every unescaped value written by a writer function (this module's docstring)."""
    writers = writer_functions(modules) if writers is None else writers
    found = []
    for path, name in sorted(writers):
        module = modules[path]
        function = module.functions[name]
        parents = {child: parent for parent in ast.walk(function) for child in ast.iter_child_nodes(parent)}
        checker = _Checker(modules, writers, module, function)
        for node in ast.walk(function):
            if not _is_text_building(node) or _in_message(parents, node) or _inside_escaping_call(parents, node):
                continue
            for value in checker.unescaped_parts(node):
                line = module.lines[value.lineno - 1]
                if "# escaped:" in line:
                    continue
                found.append(Unescaped(path, name, value.lineno, ast.unparse(value)))
    return sorted(set(found))


def check_source(source: str, name: str = "synthetic.py") -> list[Unescaped]:
    """The check run on one module alone (its own write_outputs calls are its sinks)."""
    root = Path("/nonexistent")
    module = _parse(root, (), root / name, source)
    modules = {module.path: module}
    return unescaped(modules)
