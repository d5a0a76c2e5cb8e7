"""Graphviz pictures of what runs on the robot: each local supervisor and, up to a size limit,
the product of all of them (their conjunction), explored under the state budget.

Controllable events are solid edges, uncontrollable ones dashed (the legend says so); the
initial state has an arrow from a point; public events are bold. Nodes and edges are written in
canonical order, so the ``.dot`` text is deterministic; ``.svg`` comes from Graphviz' ``dot``
(Debian package ``graphviz``)."""

import shutil
import subprocess
from typing import Dict, List, Optional, Sequence, Tuple

from ..boundary.errors import InputError
from ..boundary.escape import dot_string, dot_text
from ..compiler.model import Model
from .product import TRANSITIONS_PER_STATE, Budget, Conjunction, OverBudget, Product, explore

LEGEND = ('  label="%s\\nsolid: controllable   dashed: uncontrollable   bold: public   '
          'arrow from the dot: initial state"; labelloc=b; fontname="Helvetica";')


def _edge_style(model: Model, event: int) -> str:
    style = "solid" if model.controllable[event] else "dashed"
    return style + (",bold" if model.public[event] else "")


def _graph(title: str, model: Model, labels: Sequence[str], edges: Sequence[Sequence[Tuple[int, int]]]) -> str:
    lines = ["digraph %s {" % dot_string(title), "  rankdir=LR;", '  node [shape=circle, fontname="Helvetica"];',
             '  edge [fontname="Helvetica"];', LEGEND % dot_text(title), "  init [shape=point];"]
    lines += ["  q%d [label=%s];" % (q, dot_string(label)) for q, label in enumerate(labels)]
    lines.append("  init -> q0;")
    for q, row in enumerate(edges):
        for event, target in row:
            lines.append('  q%d -> q%d [label=%s, style="%s"];' % (q, target, dot_string(model.events[event]),
                                                                    _edge_style(model, event)))
    lines.append("}")
    return "\n".join(lines) + "\n"


def supervisor_dot(model: Model, sup: int, title: str) -> str:
    """Local supervisor ``sup`` as a Graphviz digraph."""
    states = model.supervisors[sup].states
    return _graph(title, model, [str(q) for q in range(len(states))],
                  [[(e, t) for e, t, _ in row] for row in states])


def product_dot(model: Model, product: Product, title: str) -> str:
    """The product as a Graphviz digraph; a state is labelled by its vector of local states."""
    labels = ["(%s)" % ",".join(map(str, v)) for v in product.vectors]
    return _graph(title, model, labels, product.edges)


def dot_to_svg(dot: str, where: str) -> bytes:
    """Render with Graphviz' ``dot -Tsvg``; InputError naming the package if it is missing."""
    binary = shutil.which("dot")
    if binary is None:
        raise InputError(where, "--format", "svg needs Graphviz' dot (Debian: apt-get install graphviz)")
    run = subprocess.run([binary, "-Tsvg"], input=dot.encode(), capture_output=True, check=False)
    if run.returncode != 0:
        raise InputError(where, "dot", "Graphviz failed: %s" % run.stderr.decode(errors="replace").strip())
    return run.stdout


def drawable_product(model: Model, product_limit: int, max_states: int) -> Optional[Product]:
    """The product when it has at most ``product_limit`` states, else None (it is not drawn).
    Finding out explores at most ``max_states`` states (:class:`Budget`): a ``product_limit``
    over that budget is refused when the product is bigger than the budget."""
    try:
        return explore(Conjunction.of(model), Budget(model.source, min(product_limit, max_states),
                                                     max_transitions=max_states * TRANSITIONS_PER_STATE))
    except OverBudget as exc:
        if exc.figure == "states" and product_limit <= max_states:
            return None              # over product_limit: too big to be worth a picture
        raise


def picture_files(model: Model, name: str, product: Optional[Product], svg: bool) -> Dict[str, bytes]:
    """{file name: bytes}: ``<name>_<i>.dot`` per supervisor and ``<name>_product.dot`` if
    ``product`` is given; rendered to ``.svg`` when ``svg``."""
    graphs: List[Tuple[str, str]] = [("%s_%d" % (name, s), supervisor_dot(model, s, "%s supervisor %d" % (name, s)))
                                     for s in range(len(model.supervisors))]
    if product is not None:
        graphs.append(("%s_product" % name, product_dot(model, product, "%s product" % name)))
    if svg:
        return {stem + ".svg": dot_to_svg(text, model.source) for stem, text in graphs}
    return {stem + ".dot": text.encode() for stem, text in graphs}
