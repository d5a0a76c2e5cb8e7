"""Every value a template writes passes through one of swarmvm.boundary.escape's filters (issue 23).

The check reads each template's syntax tree: an expression printed by ``{{ }}`` must end in an
escaping filter, be a constant, a macro call (whose body is checked the same way), or a choice
or concatenation of such. A template that prints a raw value fails here, before any model
reaches it, whatever the value would have been."""

from pathlib import Path

import jinja2
import pytest
from jinja2 import nodes

from swarmvm.boundary.escape import FILTERS
from swarmvm.compiler.render import ENV

TEMPLATES = Path(__file__).resolve().parents[2] / "templates"
# The escape module's filters, and render's bytes-to-hexadecimal filter (its input is bytes).
ESCAPING = frozenset(FILTERS) | {"c_bytes"}


def _callables(tree: nodes.Template) -> set[str]:
    """Names a template may call to print: its macros, its imported template modules, ``caller``."""
    names = {macro.name for macro in tree.find_all(nodes.Macro)} | {"caller"}
    names |= {node.target for node in tree.find_all(nodes.Import)}
    for macro in tree.find_all(nodes.Macro):      # macros passed in as arguments (``action_body``)
        names |= {arg.name for arg in macro.args}
    return names


def _escaped(node: nodes.Expr, callables: set[str]) -> bool:
    if isinstance(node, nodes.Const):
        return True
    if isinstance(node, nodes.Filter):
        return node.name in ESCAPING
    if isinstance(node, nodes.CondExpr):
        return _escaped(node.expr1, callables) and (node.expr2 is None or _escaped(node.expr2, callables))
    if isinstance(node, nodes.Concat):
        return all(_escaped(part, callables) for part in node.nodes)
    if isinstance(node, nodes.Call):
        callee = node.node
        root = callee.node if isinstance(callee, nodes.Getattr) else callee
        return isinstance(root, nodes.Name) and root.name in callables
    return False


def raw_outputs(source: str) -> list[str]:
    """The ``{{ }}`` expressions of a template's source that print a value through no escaping
    filter, as (line: expression type) strings."""
    tree = ENV.parse(source)
    callables = _callables(tree)
    found = []
    for output in tree.find_all(nodes.Output):
        for node in output.nodes:
            if isinstance(node, nodes.TemplateData):
                continue
            if not _escaped(node, callables):
                found.append("line %d: %s" % (node.lineno, type(node).__name__))
    return found


@pytest.mark.parametrize("template", sorted(str(p.relative_to(TEMPLATES)) for p in TEMPLATES.glob("*/*.j2")))
def test_every_printed_value_is_escaped(template):
    assert raw_outputs((TEMPLATES / template).read_text(encoding="utf-8")) == []


@pytest.mark.parametrize("source", [
    "{{ name }}", "/* {{ banner }} */", "{{ name | upper }}", "{{ e.message[:9] }}",
    "{{ 'x' ~ source }}", "{{ name if x else banner }}", "{{ name.split('_') | join }}",
    "{{ format(x) }}", "{{ '%s' | format(name) }}",
])
def test_a_raw_value_is_found(source):
    assert raw_outputs(source), source


@pytest.mark.parametrize("source", [
    "{{ name | ident }}", "{{ banner | comment }}", "{{ 1 if p else 0 }}", "{{ ('# ' ~ f | comment) if f else '' }}",
    "{% macro k(e) %}{{ e | ident }}{% endmacro %}{{ k(x) }}", "{% import 'c/_macros.j2' as m %}{{ m.kind(e) }}",
])
def test_an_escaped_value_passes(source):
    assert raw_outputs(source) == []


def test_every_filter_the_check_allows_is_registered():
    assert ESCAPING <= set(ENV.filters)
    with pytest.raises(jinja2.TemplateAssertionError):     # an unknown filter is refused at compile
        ENV.from_string("{{ name | no_such_filter }}")
