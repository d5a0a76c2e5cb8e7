"""The fast Python VM's step written out as source text, one writer per stage of the step.

swarmvm_vm.VM does not loop over its tables at run time: for its bindings and options in force
it writes its step out as one Python function (the plan, VM._bound) and compiles it once. This
module is that writer, apart from the VM so that each numbered stage of docs/semantics.md "One
step" has its own writer named as the other runtimes name the stage (the table "One step in
each runtime" there): :func:`poll_lines` (1), :func:`occurrence_lines` (2),
:func:`apply_inputs_lines` (3), :func:`control_continues_lines` (4), :func:`enabled_set_lines`
(5) and :func:`select_event_lines` (6), put together by :func:`canonical_step`; the published
(Nadzoru 2) step of SCT's exact mode by :func:`exact_step`. The out-of-line helpers the written
step calls (``vm._violate``, ``vm._act``, ``vm._select_event``...) are the VM's.

Standard library only, copied onto a robot beside swarmvm_vm.py; the written code depends on the
events and options alone, never on the callbacks, which the VM passes to ``make`` by name.
"""

from __future__ import annotations

__all__ = ["COMPILED", "MAX_COMPILED", "apply_inputs_lines", "canonical_step", "check_args", "compiled",
           "control_continues_lines", "enabled_set_line", "enabled_set_lines", "exact_choice_lines", "exact_inputs_lines",
           "exact_step", "gate_lines", "occurrence_lines", "poll_lines", "select_event_lines"]

import hashlib
import linecache
import types
from typing import Any, Sequence, Tuple

COMPILED: dict[Tuple[object, ...], types.FunctionType] = {}    # key -> the compiled maker of a written-out step
MAX_COMPILED = 64


def check_args(count: int) -> str:
    """The parameters of a written-out poll: each check and its data as a default argument."""
    return "".join(", c%d=checks[%d], d%d=datas[%d]" % (i, i, i, i) for i in range(count))


def poll_lines(events: Sequence[int], wrap: bool) -> list[str]:
    """1. Poll: source lines that make ``fired``: each check ``c<i>`` called with its data
    ``d<i>`` once, in order, and the event of each check that is true added; ``wrap``: a check
    that raises raises CallbackError naming its event (``event_name``), else the exception as it
    is. Written out check by check because a loop over the checks cost a sixth of a step on
    models with many inputs; a single check makes its list in one expression. ``fired.append``
    is called as a method, not through a bound ``add``: CPython 3.11 and later run a list's
    append called so without a call frame, at half the cost."""
    if len(events) == 1:
        body = ["e = %d" % events[0]] if wrap else []
        body += ["fired = [%d] if c0(d0) else []" % events[0]]
    else:
        body = ["fired = []"]
        body += [line for i, event in enumerate(events)
                 for line in (["e = %d" % event] if wrap else []) + ["if c%d(d%d):" % (i, i),
                                                                     "    fired.append(%d)" % event]]
    if not wrap:
        return body
    return (["e = -1", "try:"] + ["    " + line for line in body]
            + ["except Exception as exc:", "    raise CallbackError(event_name(e), 'check', exc) from exc"])


def occurrence_lines(edge: bool) -> list[str]:
    """2. Occurrence: with edge inputs, the lines that keep in ``fired`` the events whose check
    was not true at the previous step (``vm.previous``, a mask) and remember this step's; with
    level inputs every polled true event occurs, and there is nothing to write."""
    if not edge:
        return []
    return ["previous, current = vm.previous, sum(1 << event for event in fired)",
            "fired = [event for event in fired if not previous >> event & 1]",
            "vm.previous = current"]


def compiled(key: Tuple[object, ...], parameters: Sequence[str], lines: list[str]) -> types.FunctionType:
    """The function ``make(*parameters)`` whose body is the source ``lines``, compiled once per
    ``key`` (the code depends on the events and options alone, not on the callbacks):
    COMPILED. The caller passes the parameters by name (``make(**parts)``), so the names are
    written once, in its own code. The source is compiled under a file name of its own
    (``<swarmvm canonical step ...>``, ``<swarmvm exact step ...>``: the kind, ``key[0]``, and
    a digest of the text) whose lines ``linecache`` holds, so that a traceback through a
    written-out step shows the lines it ran."""
    make = COMPILED.get(key)
    if make is None:
        source = "".join(line + "\n" for line in ["def make(%s):" % ", ".join(parameters)]
                         + ["    " + line for line in lines])
        filename = "<swarmvm %s step %s>" % (key[0], hashlib.sha256(source.encode()).hexdigest()[:12])
        namespace: dict[str, Any] = {}
        exec(compile(source, filename, "exec"), namespace)
        if len(COMPILED) >= MAX_COMPILED:
            for old in COMPILED.values():
                linecache.cache.pop(old.__code__.co_filename, None)
            COMPILED.clear()
        linecache.cache[filename] = (len(source), None, source.splitlines(True), filename)
        make = COMPILED[key] = namespace["make"]
    return make


def apply_inputs_lines(sole: bool, total: bool, cut: list[str]) -> list[str]:
    """3. Apply inputs: source lines that fire the inputs in ``fired``: each supervisor that has
    the event moves (``total``: no input can violate, so no check for a missing move), then its
    action runs. ``sole``: the image has one supervisor, whose state is ``states[0]`` and whose
    column of each event is ``columns[event]`` (None outside its alphabet). An action that loads
    an image (``vm._loads`` is no longer the plan's ``loads``) ends the step with the lines
    ``cut``: what fired up to its event stands, nothing else fires (docs/semantics.md, "Reset
    and swap")."""
    cut = ["if vm._loads != loads:"] + ["    " + line for line in cut]
    if sole:
        body = ["    for event in fired:",
                "        column = columns[event]",
                "        if column is not None:",
                "            target = column[states[0]]"]
        indent, sup = "            ", "0"
    else:
        body = ["    for event in fired:",
                "        for sup, column in successors[event]:",
                "            target = column[states[sup]]"]
        indent, sup = "            ", "sup"
    if total:
        body += [indent + "states[%s] = target" % sup]
    else:
        body += [indent + "if target is None:",
                 indent + "    vm._violate(event, %s)" % sup,
                 indent + "    states, a = vm.states, (vm._plan or vm._bound())[0]",
                 indent + "else:",
                 indent + "    states[%s] = target" % sup]
    return body + ["        if a[event] is not None:",
                   "            vm._act(event, a[event])"] + ["            " + line for line in cut] + [
                   "            states, a = vm.states, (vm._plan or vm._bound())[0]"]


def control_continues_lines(quiet: bool, chooses: bool) -> list[str]:
    """4. Control phase, inside the step's ``if fired:``: with if-quiet control (or no
    controllable event to choose) the step ends after its inputs; else it goes on, out of line
    (VM._choose) when a callback replaced the plan while the inputs fired."""
    if quiet or not chooses:
        return ["    return fired"]
    return ["    if vm._plan is not plan:",
            "        return vm._choose(fired)"]


def enabled_set_line(gate_sups: Sequence[int]) -> str:
    """The source line that makes ``mask``, the controllable events every supervisor allows in
    its state: an AND over the gates (``g<i>``, the masks by state of supervisor
    ``gate_sups[i]``) written out, no loop (VM._enabled_set is the same, out of line)."""
    return "mask = controllable" + "".join(" & g%d[states[%d]]" % (i, sup) for i, sup in enumerate(gate_sups))


def gate_lines(gate_sups: Sequence[int]) -> list[str]:
    """The lines of ``make`` that name each gate's masks ``g<i>`` for enabled_set_line."""
    return ["g%d = gates[%d][1]" % (i, i) for i in range(len(gate_sups))]


def enabled_set_lines(sole: bool, gate_sups: Sequence[int]) -> list[str]:
    """5. Enabled set: source lines that make ``enabled``, the enabled controllable events in
    event order: for one supervisor (``sole``) its state's entry in ``table`` with the state
    after each (``afters``; VM._sole_entry), else the events of the ANDed ``mask``, remembered
    per mask in ``sets`` (VM._enabled_events)."""
    if sole:
        return ["entry = table[states[0]]",
                "enabled, afters = entry or vm._sole_entry()"]
    return [enabled_set_line(gate_sups),
            "enabled = sets.get(mask)",
            "if enabled is None:",
            "    enabled = vm._enabled_events(mask)"]


def select_event_lines(uniform: bool, sole: bool) -> list[str]:
    """6. Selection: source lines that fire one of the enabled controllable events: the uniform
    policy's draw (XorShift32.next, the generator's one definition, called; its number scaled to
    an index as XorShift32.below does, whose call would cost the step a second frame) or the
    VM's ``_select_event``, then the event's move, from the remembered states after it
    (``afters``, when ``sole``) or every supervisor's column, and its action."""
    body = ["if enabled:"]
    if uniform:
        body += ["    n = len(enabled)",
                 "    k = 0 if n == 1 else ((vm.rng.next() >> 16) * n) >> 16",
                 "    choice = enabled[k]"]
    else:
        body += ["    choice = vm._select_event(enabled)", "    k = enabled.index(choice)"]
    act = ["if a[choice] is not None:", "    vm._act(choice, a[choice])"]
    if sole:
        body += ["    states[0] = afters[k]"] + ["    " + line for line in act]
    else:
        body += ["    for sup, column in successors[choice]:",
                 "        states[sup] = column[states[sup]]"] + ["    " + line for line in act]
    return body + ["    fired.append(choice)"]


def canonical_step(parameters: Tuple[str, ...], events: Tuple[int, ...], edge: bool, quiet: bool, uniform: bool,
                   strict: bool, chooses: bool, total: bool, sole: bool, gate_sups: Tuple[int, ...]) -> types.FunctionType:
    """The maker of a VM's step written out for its plan (``make`` takes ``parameters``, the
    names of the parts of VM._bound's plan): the step of docs/semantics.md stage by stage with
    the options as they are (edge inputs, if-quiet control, uniform policy, strict, a
    controllable event to choose), the inputs moved without a check when none can violate
    (``total``), and, for an image of one supervisor (``sole``), its state read as one integer
    and the enabled events of each of its states in a list (VM._sole_entry). One frame per
    step, the plan's parts its locals: on the smallest models the step is mostly that fixed
    cost. A step whose plan is gone when it is called (a caller kept ``vm.step`` across a bind)
    hands over to the VM's current one; a callback that rebinds makes a new plan, and after the
    inputs a step whose plan is gone chooses out of line (VM._choose), from the VM as it then
    is; a callback that loads an image ends the step (apply_inputs_lines)."""
    body = ["if vm._plan is not plan:      # bound again since: a caller kept this step (vm.step)",
            "    vm._bound()",
            "    return vm.step()"]
    body += ["if not vm._bindings_checked:", "    vm._check_bindings()"] if strict else []
    body += poll_lines(events, True)
    body += ["a = acts"]
    body += occurrence_lines(edge)
    body += ["states = vm.states", "if fired:"] + apply_inputs_lines(sole, total, ["return fired[:fired.index(event) + 1]"])
    body += control_continues_lines(quiet, chooses)
    if chooses:
        body += enabled_set_lines(sole, gate_sups) + select_event_lines(uniform, sole)
    body += ["return fired"]
    key = ("canonical", parameters, events, edge, quiet, uniform, strict, chooses, total, sole, gate_sups)
    return compiled(key, parameters, gate_lines(gate_sups) + ["def step(vm%s):" % check_args(len(events))]
                    + ["    " + line for line in body] + ["return step"])


def exact_inputs_lines(sole: bool, total: bool, public_first: bool, acting: bool) -> list[str]:
    """Source lines of the exact step that apply the inputs in ``fired`` (file indices; SCTPub:
    public ones first, ``private`` by file index), each action right after its event's moves,
    as apply_inputs_lines does for the canonical step but without mapping the step's events to
    file order: ``canonical`` maps an event for its moves and its action. ``sole``: one
    supervisor, whose state is the local ``s`` and whose column of each event is
    ``columns[event]`` (by file index; an event outside its alphabet has a column that stays).
    An action that loads an image ends the step there; one that rebinds leaves the rest of the
    step to SCT._choose (its ``vm._plan is not vm_plan`` below). When no input can violate
    (``total``) and none has an action (``acting`` false: the plan's actions, which nothing can
    change while only moves run), the moves alone, by file index (``file_successors``): what
    published controllers mostly are, actions on the controllable events, checks on the others."""
    lines = ["if fired:"] + (["    fired.sort(key=private.__getitem__)"] if public_first else [])
    if total and not acting:
        lines += ["    for event in fired:"]
        lines += ["        s = columns[event][s]", "    states[0] = s"] if sole else [
            "        for sup, column in file_successors[event]:",
            "            states[sup] = column[states[sup]]"]
        return lines + ["    sct.input_buffer = fired", "else:", "    sct.input_buffer = fired"]
    lines += ["    for event in fired:", "        c = canonical[event]"]
    if sole:
        move = ["s = columns[event][s]"] if total else [
            "target = columns[event][s]",
            "if target is None:",
            "    states[0] = s",
            "    vm._violate(c, 0)",
            "    states, a = vm.states, (vm._plan or vm._bound())[0]",
            "    s = states[0]",
            "else:",
            "    s = target"]
        save, load = ["    states[0] = s"], ["    s = states[0]"]
    else:
        move = ["for sup, column in successors[c]:", "    target = column[states[sup]]"]
        move += ["    states[sup] = target"] if total else [
            "    if target is None:",
            "        vm._violate(c, sup)",
            "        states, a = vm.states, (vm._plan or vm._bound())[0]",
            "    else:",
            "        states[sup] = target"]
        save = load = []
    lines += ["        " + line for line in move + ["if a[c] is not None:"] + save + [
        "    vm._act(c, a[c])",
        "    if vm._loads != loads:",
        "        sct.input_buffer = fired[:fired.index(event) + 1]",
        "        sct.last_events = fired[:fired.index(event) + 1]",
        "        return",
        "    states, a = vm.states, (vm._plan or vm._bound())[0]"] + load]
    return lines + (["    states[0] = s"] if sole else []) + [
        "    sct.input_buffer = fired",
        "    if vm._plan is not vm_plan:",
        "        return sct._choose(fired)",
        "else:",
        "    sct.input_buffer = fired"]


def exact_choice_lines(sole: bool, gate_sups: Sequence[int]) -> list[str]:
    """Source lines of the published choice: the enabled controllable events in file order (one
    supervisor: its state's entry in ``table``, SCT._sole_entry; else per enabled mask,
    SCT._file_order), the k-th with ``k = random.randint(0, 1000000000) % n`` drawn as CPython's
    randint makes it (randint -> randrange -> _randbelow_with_getrandbits: ``getrandbits(30)``
    until at most 10^9) without randint's three Python-level calls while ``randint`` is the
    standard one (tests/python/test_sct_exact.py compares the random state step by step), then
    its moves and its action; ``last_events`` the inputs and it, a list of its own."""
    if sole:
        lines = ["order, afters, events = table[s] or sct._sole_entry(s)"]
    else:
        lines = [enabled_set_line(gate_sups),
                 "order = orders.get(mask)",
                 "if order is None:",
                 "    order = sct._file_order(mask)"]
    lines += ["if order:",
              "    if rnd.randint is randint:",
              "        draw = getrandbits(30)",
              "        while draw > 1000000000:",
              "            draw = getrandbits(30)",
              "    else:",
              "        draw = rnd.randint(0, 1000000000)"]
    if sole:
        lines += ["    k = draw % len(order)",
                  "    states[0] = afters[k]",
                  "    event = events[k]",
                  "    choice = order[k]"]
    else:
        lines += ["    choice, event = order[draw % len(order)]",
                  "    for sup, column in successors[event]:",
                  "        states[sup] = column[states[sup]]"]
    return lines + ["    if a[event] is not None:",
                    "        vm._act(event, a[event])",
                    "    sct.last_events = [*fired, choice]",
                    "    return",
                    "sct.last_events = fired[:]"]


def exact_step(parameters: Tuple[str, ...], events: Tuple[int, ...], public_first: bool, chooses: bool, total: bool,
               sole: bool, acting: bool, gate_sups: Tuple[int, ...]) -> types.FunctionType:
    """The maker of SCT exact mode's step written out for a plan of its VM (as canonical_step;
    ``make`` takes ``parameters``, the names of SCT._plan_exact's parts), in the file's event
    indices throughout, so nothing is mapped to file order per step: the checks of file events
    ``events`` polled in file order (raising as in the published VM), the true ones applied
    (exact_inputs_lines), then, when there are controllable events, the published choice
    (exact_choice_lines). ``sole``: one supervisor, whose state the step keeps in a local and
    whose enabled events in file order it reads per state. A callback that rebinds while the
    inputs fire: the choice is made out of line (SCT._choose); ``acting``: some polled input has
    an action."""
    body = ["vm = sct.vm",
            "if vm._plan is not vm_plan:",
            "    sct._plan_exact()",
            "    return sct.run_step()"] + poll_lines(events, False)
    body += ["a = acts", "states = vm.states"] + (["s = states[0]"] if sole else [])
    body += exact_inputs_lines(sole, total, public_first, acting)
    body += exact_choice_lines(sole, gate_sups) if chooses else ["sct.last_events = fired[:]"]
    return compiled(("exact", parameters, events, public_first, chooses, total, sole, acting, gate_sups), parameters,
                    gate_lines(gate_sups) + ["def run_step(sct%s):" % check_args(len(events))]
                    + ["    " + line for line in body] + ["return run_step"])
