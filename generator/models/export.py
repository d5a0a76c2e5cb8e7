"""Write a canonical supervisor set back out: Nadzoru 2's ``supervisor.yaml`` (events sorted by
name, states breadth-first, so two exports of one model are byte-identical) and libFAUDES'
token format (one ``.gen`` per local supervisor, every state marked: a supervisor's language
is closed; public events in a ``% swarmvm public:`` comment, as libFAUDES has no such flag). Both read back into an equivalent set (tests/models/test_export.py)."""

from fractions import Fraction
from typing import Dict, Iterable, List, Union

from ..boundary.escape import comment, gen_string, identifier_part
from ..compiler.model import Model
from .pictures import drawable_product, picture_files
from .product import DEFAULT_MAX_STATES


def _flat(values: Iterable[object]) -> str:
    return "[ %s ]" % ", ".join(str(v) for v in values)


def _probability(p: Fraction) -> str:
    return repr(float(p))


def _event(name: str) -> str:
    """An event as a plain YAML scalar: ``EV_`` and a name the readers allow (letters, digits,
    ``_``), checked by swarmvm.boundary.escape, so no name can need quoting or end the flow list."""
    return "EV_" + identifier_part(name)


def to_yaml(model: Model) -> str:
    """The model as a Nadzoru 2 ``supervisor.yaml`` (newer spelling: ``ev_public``)."""
    n = len(model.events)
    data: List[Union[int, str]] = []          # counts and targets, and the events as written
    positions: List[int] = []
    prob_data: List[Union[int, str]] = []     # counts, and the probabilities as written
    prob_positions: List[int] = []
    for sup in model.supervisors:
        positions.append(len(data))
        prob_positions.append(len(prob_data))
        for row in sup.states:
            data.append(len(row))
            for event, target, _ in row:
                data.extend((_event(model.events[event]), target >> 8, target & 0xFF))
            probs = [p for e, _, p in row if model.controllable[e]]
            prob_data.append(len(probs))
            prob_data.extend(_probability(p if p is not None else Fraction(1)) for p in probs)
    lines = [
        "",
        "num_events: %d" % n,
        "num_supervisors: %d" % len(model.supervisors),
        "events: %s" % _flat(_event(e) for e in model.events),
        "ev_controllable: %s" % _flat(int(c) for c in model.controllable),
        "ev_public: %s" % _flat(int(p) for p in model.public),
        "sup_events: [ %s ]" % ", ".join(
            "[%s]" % ", ".join(str(int(e in sup.alphabet)) for e in range(n)) for sup in model.supervisors),
        "sup_init_state: %s" % _flat(0 for _ in model.supervisors),
        "sup_current_state: %s" % _flat(0 for _ in model.supervisors),
        "sup_data_pos: %s" % _flat(positions),
        "sup_data: %s" % _flat(data),
    ]
    if model.probabilistic:
        lines += ["sup_data_prob_pos: %s" % _flat(prob_positions), "sup_data_prob: %s" % _flat(prob_data)]
    return "\n".join(lines) + "\n"


def to_gen(model: Model, sup: int, name: str) -> str:
    """Local supervisor ``sup`` in libFAUDES' token format (readable by ``faudes.System``)."""
    local = model.supervisors[sup]
    alphabet = []
    for e in sorted(local.alphabet):
        alphabet.append(gen_string(model.events[e]) + (" +C+" if model.controllable[e] else ""))
    states = " ".join(gen_string("s%d" % q) for q in range(len(local.states)))
    trans = ["%s %s %s" % (gen_string("s%d" % q), gen_string(model.events[e]), gen_string("s%d" % t))
             for q, row in enumerate(local.states) for e, t, _ in row]
    public = [gen_string(model.events[e]) for e in sorted(local.alphabet) if model.public[e]]
    return "\n".join([
        '<Generator name=%s ftype="System">' % gen_string(name),
        "% " + "written by swarmvm from %s, supervisor %d; every state is marked" % (comment(model.source), sup),
        *(["% swarmvm public: " + " ".join(public)] if public else []),
        "<Alphabet>", *alphabet, "</Alphabet>",
        "<States>", states, "</States>",
        "<TransRel>", *trans, "</TransRel>",
        "<InitStates>", gen_string("s0"), "</InitStates>",
        "<MarkedStates>", states, "</MarkedStates>",
        "</Generator>", ""])


def gen_files(model: Model, name: str) -> Dict[str, bytes]:
    """{file name: bytes}: ``<name>_<i>.gen`` per local supervisor."""
    return {"%s_%d.gen" % (name, s): to_gen(model, s, "%s_%d" % (name, s)).encode()
            for s in range(len(model.supervisors))}


FORMATS = ("yaml", "gen", "dot", "svg")


def export_files(model: Model, name: str, fmt: str, product_limit: int = 200,
                 max_states: int = DEFAULT_MAX_STATES) -> Dict[str, bytes]:
    """{file name: bytes} of ``model`` in ``fmt``: ``<name>.yaml``; one ``<name>_<i>.gen`` per
    supervisor; or pictures of each supervisor and, when it has at most ``product_limit``
    states, of their product (``<name>_product``), found within the ``max_states`` budget."""
    if fmt == "yaml":
        return {name + ".yaml": to_yaml(model).encode()}
    if fmt == "gen":
        return gen_files(model, name)
    return picture_files(model, name, drawable_product(model, product_limit, max_states), svg=fmt == "svg")
