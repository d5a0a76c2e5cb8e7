"""Automata to and from libFAUDES (``faudes`` on PyPI), the one conversion swarmvm has.

Synthesis runs libFAUDES' own operations on these generators, and the tests use libFAUDES as
an independent oracle on swarmvm's languages; both go through :func:`build_system`. In
libFAUDES an event is named with Nadzoru's ``EV_`` prefix (libFAUDES refuses an empty symbol,
which Nadzoru 2 allows); states are named ``s0, s1, ...`` by their index in the automaton."""

import contextlib
import importlib
import io
from functools import lru_cache
from types import ModuleType
from typing import Any, Dict, Iterable, List, Optional, Tuple

from ..compiler.model import LocalSupervisor, Model, Transition
from ..readers.supervisor_yaml import bare_name


@lru_cache(maxsize=None)
def libfaudes() -> ModuleType:
    """The ``faudes`` module, imported on first use: only synthesis needs it, and its import
    prints warnings on standard output (no matplotlib or pillow), which would otherwise end up
    in every command's output."""
    with contextlib.redirect_stdout(io.StringIO()):
        return importlib.import_module("faudes")


def faudes_name(event: str) -> str:
    """The libFAUDES symbol of a bare event name."""
    return "EV_" + event


def build_system(events: Iterable[Tuple[str, bool]], num_states: int, initial: int,
                 marked: Optional[Iterable[int]], transitions: Iterable[Tuple[int, str, int]]) -> Any:
    """A libFAUDES System (a generator with controllability flags). ``events``: (name,
    controllable); ``marked`` None marks every state (a closed language)."""
    system = libfaudes().System()
    for name, controllable in events:
        system.InsEvent(faudes_name(name))
        if controllable:
            system.SetControllable(faudes_name(name))
    for q in range(num_states):
        system.InsState("s%d" % q)
    system.SetInitState("s%d" % initial)
    for q in range(num_states) if marked is None else marked:
        system.SetMarkedState("s%d" % q)
    for source, event, target in transitions:
        system.SetTransition("s%d" % source, faudes_name(event), "s%d" % target)
    return system


def system_from_local(local: LocalSupervisor, controllable: Dict[str, bool]) -> Any:
    """A supervisor or automaton as read (marking kept) -> libFAUDES System."""
    transitions = [(q, t.event, t.target) for q, row in enumerate(local.states) for t in row]
    return build_system(sorted((e, controllable[e]) for e in local.alphabet), len(local.states),
                        local.initial, None if local.marked is None else sorted(local.marked), transitions)


def system_from_model(model: Model, sup: int) -> Any:
    """Local supervisor ``sup`` of a canonical model -> libFAUDES System (closed language)."""
    local = model.supervisors[sup]
    transitions = [(q, model.events[e], target) for q, row in enumerate(local.states) for e, target, _ in row]
    return build_system(((model.events[e], model.controllable[e]) for e in sorted(local.alphabet)),
                        len(local.states), 0, None, transitions)


def local_from_system(system: Any) -> Tuple[Dict[str, bool], LocalSupervisor]:
    """A deterministic libFAUDES System with at most one initial state -> ({event:
    controllable}, LocalSupervisor with its marking), states in libFAUDES' order."""
    states, alphabet, controllable, delta, initial, marked = system.ToLists()
    index = {q: i for i, q in enumerate(states)}
    rows: List[List[Transition]] = [[] for _ in states]
    for source, event, target in delta:
        rows[index[source]].append(Transition(bare_name(event), index[target]))
    events = {bare_name(name): name in set(controllable) for name in alphabet}
    start = index[initial[0]] if initial else 0
    return events, LocalSupervisor(frozenset(events), start, rows, frozenset(index[q] for q in marked))
