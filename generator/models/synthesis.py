"""Local modular synthesis through libFAUDES: run a synthesis script on plants and
specifications and return the exported local supervisors as one supervisor set.

``Sync`` is libFAUDES' ``Parallel``; ``SupC(G, K)`` is ``SupCon`` (the supremal controllable
and non-blocking sublanguage of K with respect to G). Where K has events G lacks, G is first
extended by those events as self-loops in every state (the plant does not constrain them),
and K likewise by G's events it lacks (the specification does not constrain them);
``Minimize`` is ``StateMin``. Event flags (controllable, public) come from the input files,
which must agree on them."""

import os
from typing import Any, Dict, List, Sequence

from ..boundary.errors import InputError
from ..compiler.model import LocalSupervisor, Supervisors
from ..readers.automata import load_automata
from ..readers.synth_script import Step, SynthScript
from .faudes_bridge import libfaudes, local_from_system, system_from_local
from .product import DEFAULT_MAX_STATES, Budget, Conjunction, explore, state_bound


def _self_looped(system: Any, other: Any) -> Any:
    """``system`` extended by the events of ``other`` it lacks, each a self-loop in every state
    and controllable as in ``other``."""
    _, alphabet, own_controllable, _, _, _ = system.ToLists()
    _, others, controllable, _, _, _ = other.ToLists()
    missing = sorted(set(others) - set(alphabet))
    if not missing:
        return system
    extended = libfaudes().System(system)
    names = libfaudes().EventSet()
    for name in missing:
        names.Insert(name)
    libfaudes().SelfLoop(extended, names)          # (libFAUDES drops the event flags here: set them again)
    for name in set(own_controllable) | (set(missing) & set(controllable)):
        extended.SetControllable(name)
    return extended


def _refuse_over_budget(args: List[Any], budget: Budget) -> None:
    """InputError when the product of the libFAUDES systems ``args`` is over ``budget``, checked
    before libFAUDES composes them (a libFAUDES call cannot be interrupted). The product of
    their state counts bounds it; only past the budget is the reachable product explored, here,
    under the budget. (SupC's arguments, self-looped, compose as a conjunction does: an event
    outside an automaton's alphabet is never blocked by it.)"""
    if budget.surely_within(state_bound([system.Size() for system in args])):
        return
    factors = [local_from_system(system)[1] for system in args]
    index = {name: i for i, name in enumerate(sorted(frozenset().union(*(f.alphabet for f in factors))))}
    explore(Conjunction(len(index), [frozenset(index[e] for e in f.alphabet) for f in factors],
                        [[{index[t.event]: t.target for t in row} for row in f.states] for f in factors],
                        tuple(f.initial for f in factors)), budget)


def _apply(step: Step, args: List[Any], budget: Budget) -> Any:
    """``step`` on libFAUDES systems ``args``; each composition (a Sync composes its arguments
    one at a time, SupC its plant and specification) is sized against ``budget`` first."""
    result = libfaudes().System()
    if step.op == "sync":
        _refuse_over_budget(args[:2], budget)
        libfaudes().Parallel(args[0], args[1], result)
        for more in args[2:]:
            _refuse_over_budget([result, more], budget)
            composed = libfaudes().System()
            libfaudes().Parallel(result, more, composed)
            result = composed
    elif step.op == "supc":
        plant, spec = args
        _refuse_over_budget(args, budget)
        libfaudes().SupCon(_self_looped(plant, spec), _self_looped(spec, plant), result)
    else:
        libfaudes().StateMin(args[0], result)
    return result


def models_by_name(paths: Sequence[str]) -> Dict[str, str]:
    """{file stem: path}: a script names each model by its file's stem (``G1.xml`` is G1)."""
    models: Dict[str, str] = {}
    for path in paths:
        stem = os.path.splitext(os.path.basename(path))[0]
        if stem in models:
            raise InputError(path, "", "a second model named %s (also %s)" % (stem, models[stem]))
        models[stem] = path
    return models


def synthesise(script: SynthScript, models: Dict[str, str], exports: Sequence[str] = (),
               minimise: bool = False, max_states: int = DEFAULT_MAX_STATES) -> Supervisors:
    """Run ``script`` with ``models`` ({name: automaton file}); return the supervisors named by
    ``exports`` (else the script's ``export``, else every name a SupC assigned), each
    minimised if ``minimise``. Raises InputError on bad models, a script that fails, or a
    step whose product is over ``max_states`` states (before libFAUDES runs it)."""
    names = sorted(models)
    inputs = load_automata([models[n] for n in names])
    env = {name: system_from_local(local, inputs.controllable) for name, local in zip(names, inputs.supervisors)}
    supc_order: List[str] = []
    for step in script.steps:
        missing = [a for a in step.args if a not in env]
        if missing:
            raise InputError(script.source, missing[0], "neither a model given nor assigned above", "line %d" % step.line)
        result = _apply(step, [env[a] for a in step.args], Budget(
            script.source, max_states, "the product of %s" % ", ".join(step.args), where="line %d" % step.line))
        if result.Size() == 0:
            raise InputError(script.source, step.target, "the result is empty (no %s exists)" % (
                "supervisor" if step.op == "supc" else "behaviour"), "line %d" % step.line)
        env[step.target] = result
        if step.op == "supc" and step.target not in supc_order:
            supc_order.append(step.target)
    chosen = list(exports or script.exports or supc_order)
    if not chosen:
        raise InputError(script.source, "export", "no supervisor to export (no SupC and no export given)")
    supervisors: list[LocalSupervisor] = []
    events: list[str] = []
    for name in chosen:
        if name not in env:
            raise InputError(script.source, "export", "%s is not a model or a result of the script" % name)
        system = env[name]
        if minimise:
            system = _apply(Step(name, "min", (name,), 0), [system], Budget(script.source, max_states))
        declared, local = local_from_system(system)
        supervisors.append(local)
        events.extend(e for e in sorted(declared) if e not in events)
    return Supervisors(source=os.path.basename(script.source), events=events,
                       controllable={e: inputs.controllable[e] for e in events},
                       public={e: inputs.public[e] for e in events}, supervisors=supervisors)
