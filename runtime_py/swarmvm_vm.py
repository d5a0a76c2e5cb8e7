"""swarmvm Python VM: evolves compiled supervisors from a swarmvm table image.

Standard library only, so it can be copied onto a robot as it is, together with
swarmvm_format.py (the image format and its reader, re-exported here: Image, ImageError,
crc16, FORMAT_VERSION). It implements the execution semantics of docs/semantics.md exactly:
like the other runtimes (C, C++), it is checked trace for trace against the plain reference VM
(swarmvm_reference.py, written to be read beside that page; robots need not have it). The
tables come from a table image (docs/image-format.md), either compiled into a generated module
as a bytes literal or read from a ``.svm`` file: both go through :meth:`Image.parse`, so
"compiled in" and "loaded" are one code path. For speed, a VM writes its step out for its
bindings and options (VM._bound, by swarmvm_step_source.py, copied beside it) and compiles it
once; docs/api.md says what else the step and the load do ahead of time, and what they gained.
"""

from __future__ import annotations

__all__ = ["CallbackError", "FORMAT_VERSION", "Image", "ImageError", "UnboundEvents", "VM", "XorShift32", "callback_stem", "crc16",
           "SCT", "SCTPub", "format_trace_line", "read_file", "replay", "replay_lines"]

import functools
import hashlib
import operator
import os
import random
import types
from typing import TYPE_CHECKING, Any, Callable, Iterable, Iterator, Optional, Protocol, Sequence, Tuple, Union, cast

if TYPE_CHECKING:   # mypy reads the format and the step writer as the package's modules; the VM imports the copies beside it
    from runtime_py.swarmvm_format import (FORMAT_VERSION, MAX_SOURCE_FILE_SIZE, Q15_ONE, ErrorCode, Image, ImageError,
                                           crc16, read_file)
    from runtime_py.swarmvm_step_source import canonical_step, exact_step
else:
    from swarmvm_format import (FORMAT_VERSION, MAX_SOURCE_FILE_SIZE, Q15_ONE, ErrorCode, Image, ImageError, crc16,
                                read_file)
    from swarmvm_step_source import canonical_step, exact_step

INPUT_MODES = ("level", "edge")
CONTROL_MODES = ("after-inputs", "if-quiet")
POLICIES = ("uniform", "first", "weighted", "learned")
MAX_VIOLATIONS = 0xFFFFFFFF     # the violation counter stops here on every runtime (docs/semantics.md)

# A callback is called with the data bound with it; a check's result counts as true or false. (Any
# callable: one with more parameters defaulted, as ``lambda data, event=event: ...``, is one too.)
Callback = Callable[..., Any]
Act = Tuple[Callback, Any]                      # an event's bound (action, data)
Plan = Tuple[list[Optional[Act]], bool]         # VM._bound: per event its Act or None; a controllable event?
Column = list[Optional[int]]                    # a supervisor's successor of each of its states on one event
Successors = Tuple[Tuple[int, Column], ...]     # per event: (supervisor, column) of each supervisor that has it
Gate = Tuple[int, list[int]]                    # (supervisor, the controllable events it allows in each state)


class Learner(Protocol):
    """What policy ``learned`` asks (swarmvm_learn.py): one of ``enabled``, chosen for ``vm``,
    the VM or the reference VM (swarmvm_reference.ReferenceVM), which show the same state."""

    def choose(self, vm: Bindings, enabled: Sequence[int]) -> int: ...


def callback_stem(name: str) -> str:
    """The part of a callback's name that names its event (``on_<stem>``, ``check_<stem>``), in
    every target: the bare name, except that the receive side of a public event, ``_x``, is
    ``received_x`` (C++ reserves identifiers with ``__``). The generator names every generated
    identifier by this rule (generator/compiler/naming.py) and refuses models where two events share one."""
    return "received" + name if name.startswith("_") else name


class UnboundEvents(LookupError):
    """Strict mode: uncontrollable events without a check (they could never occur)."""

    def __init__(self, names: list[str]) -> None:
        super().__init__("no check bound for " + ", ".join(names))
        self.names = names


class CallbackError(RuntimeError):
    """A check, an action or the violation hook raised; the original exception is ``__cause__``.

    The policy (docs/semantics.md, "Callbacks that raise"): a check that raises ends the step
    before any transition, so the VM is as it was before the step; an action that raises ends
    the step after its own event's transition, which stays applied (the supervisors have moved;
    the robot's side of it failed). Either way the next ``step()`` runs normally."""

    def __init__(self, event: str, kind: str, cause: BaseException) -> None:
        super().__init__("the %s of %s raised %s: %s" % (kind, event, type(cause).__name__, cause))
        self.event, self.kind = event, kind


class XorShift32:
    """The one pseudo-random generator of every runtime (Marsaglia's xorshift32, 13/17/5).

    Cheap on an 8-bit AVR and specified bit for bit, so a seed gives the same choices on every
    target. Seed 0 (a fixed point of xorshift) is replaced by 0x9E3779B9."""

    def __init__(self, seed: int = 1) -> None:
        self.state = (seed & 0xFFFFFFFF) or 0x9E3779B9

    def next(self) -> int:
        x = self.state
        x ^= (x << 13) & 0xFFFFFFFF
        x ^= x >> 17
        x ^= (x << 5) & 0xFFFFFFFF
        self.state = x
        return x

    def below(self, n: int) -> int:
        """An index in [0, n) for n < 65536: the top 16 bits scaled by n, no division."""
        return ((self.next() >> 16) * n) >> 16


def _bits(mask: int) -> list[int]:
    """Indices of the set bits of ``mask``, lowest first (canonical event order): one pass per
    set bit, not per bit."""
    out = []
    while mask:
        low = mask & -mask
        out.append(low.bit_length() - 1)
        mask ^= low
    return out


def check_options(inputs: str, control: str, policy: str, learner: Optional[Learner]) -> None:
    """ValueError unless the run options are among those of docs/semantics.md ("Options
    summary"), and policy ``learned`` has its learner: the options of every Python VM."""
    if inputs not in INPUT_MODES:
        raise ValueError("inputs must be one of %s" % (INPUT_MODES,))
    if control not in CONTROL_MODES:
        raise ValueError("control must be one of %s" % (CONTROL_MODES,))
    if policy not in POLICIES:
        raise ValueError("policy must be one of %s" % (POLICIES,))
    if policy == "learned" and learner is None:
        raise ValueError("policy 'learned' needs a learner")


class Bindings:
    """The callbacks of a VM and the rules that bind them (docs/semantics.md, "Callbacks"):
    ``actions``, ``checks`` and ``data`` by event index, over ``image``. The VM and the
    reference VM (swarmvm_reference.py) bind alike by being both of this class; each says what
    a change of binding means to its step (``_replan``)."""

    image: Image
    num_events: int
    strict: bool
    input_order: list[int]
    actions: dict[int, Callback]
    checks: dict[int, Callback]
    data: dict[int, Any]
    _bindings_checked: bool

    def _replan(self) -> None:
        """Called after every bind: what the step prepared for the bindings is stale."""

    def _index(self, event: Union[int, str]) -> int:
        if isinstance(event, int):
            if not 0 <= event < self.num_events:
                raise KeyError("event index %d out of range (0..%d)" % (event, self.num_events - 1))
            return event
        return self.image.event_index(event)

    def bind(self, event: Union[int, str], action: Optional[Callback] = None, check: Optional[Callback] = None,
             data: Any = None) -> None:
        """Bind an action and/or a check to an event given by name (``EV_x`` or ``x``) or index.

        A name the supervisor does not have is an error (KeyError), never event 0."""
        index = self._index(event)
        if check is not None and self.image.controllable >> index & 1:
            raise ValueError("%s is controllable: it takes an action, not a check" % self.image.event_name(index))
        if action is not None:
            self.actions[index] = action
        if check is not None:
            self.checks[index] = check
        self.data[index] = data
        self._bindings_checked = False
        self._replan()

    def bind_controller(self, controller: object) -> None:
        """Bind ``on_<stem>`` and ``check_<stem>`` methods of an object, by event name
        (:func:`callback_stem`: ``check_received_x`` for the message event ``EV__x``)."""
        for e in range(self.num_events):
            stem = callback_stem(self.image.event_name(e)[3:])
            action = getattr(controller, "on_" + stem, None)
            check = getattr(controller, "check_" + stem, None)
            if not self.image.controllable >> e & 1 or check is None:
                self.bind(e, action=action, check=check)
            else:
                self.bind(e, action=action)

    def unbound_checks(self) -> list[str]:
        """Names of uncontrollable events with no check (they can never occur)."""
        return [self.image.event_name(e) for e in self.input_order if e not in self.checks]

    def _check_bindings(self) -> None:
        """Strict mode, before a step: every uncontrollable event has a check."""
        if self.unbound_checks():
            raise UnboundEvents(self.unbound_checks())
        self._bindings_checked = True

    def _rebind(self, new: Image) -> list[str]:
        """The callbacks moved to image ``new`` by name, for a load (``load`` of each VM);
        KeyError for a name ``new`` lacks, or UnboundEvents in strict mode when a check is
        missing, before anything changes. Returns the uncontrollable events of ``new`` left
        without a check."""
        old_names = {e: self.image.event_name(e) for e in set(self.actions) | set(self.checks)}
        if old_names and new.names is None and self.image.names is not None:
            raise KeyError("the new image carries no event names to rebind callbacks by")
        mapping = {e: new.event_index(name) for e, name in old_names.items()} if self.image.names else {}
        checks = {mapping.get(e, e): f for e, f in self.checks.items()}
        everything = (1 << new.num_events) - 1
        missing = [new.event_name(e) for e in _bits(everything & ~new.controllable) if e not in checks]
        if self.strict and missing:
            raise UnboundEvents(missing)
        self.actions = {mapping.get(e, e): f for e, f in self.actions.items()}
        self.checks = checks
        self.data = {mapping.get(e, e): d for e, d in self.data.items()}
        return missing


class _Option:
    """A run option of :class:`VM` (inputs, control, policy, strict) that the step is written
    out for (VM._bound) rather than reads per step: setting one makes the VM plan again."""

    def __set_name__(self, owner: type, name: str) -> None:
        self.slot = "_" + name

    def __get__(self, vm: Optional[VM], owner: Optional[type] = None) -> Any:
        return self if vm is None else getattr(vm, self.slot)

    def __set__(self, vm: VM, value: object) -> None:
        setattr(vm, self.slot, value)
        vm._replan()


class VM(Bindings):
    """The virtual machine: current states, inputs, generator, callbacks; ``step()`` evolves it.

    Options (docs/semantics.md): ``inputs`` level|edge, ``control`` after-inputs|if-quiet,
    ``policy`` uniform|first|weighted|learned (learned takes ``learner``, an object with
    ``choose(vm, enabled)`` returning one of ``enabled``), ``seed`` for the generator,
    ``priority`` (event names, highest first) for ``first``. ``step`` is written out for the
    bindings and options in force and installed on the VM (see _bound)."""

    inputs, control, policy, strict = _Option(), _Option(), _Option(), _Option()
    _plan: Plan | None     # see _bound

    def __init__(self, image: Union[Image, bytes], inputs: str = "level", control: str = "after-inputs",
                 policy: str = "uniform", seed: int = 1, priority: Optional[Sequence[Union[int, str]]] = None,
                 learner: Optional[Learner] = None, on_violation: Optional[Callable[[int, int], Any]] = None,
                 strict: bool = False) -> None:
        check_options(inputs, control, policy, learner)
        self._inputs, self._control, self._policy, self._strict = inputs, control, policy, strict
        self.seed, self.learner, self.on_violation = seed, learner, on_violation
        self._priority = priority
        self.actions, self.checks, self.data = {}, {}, {}
        self._loads = 0     # images loaded since: a step that sees it change ends (apply_inputs_lines, _fire)
        self._in_hook = False   # on_violation is running: it may not load (_violate)
        self._install(image if isinstance(image, Image) else Image.parse(image))
        self.reset()

    # -- tables -------------------------------------------------------------------------------
    def _install(self, image: Image) -> None:
        """Derive the per-state lookup structures the step uses from an image."""
        self.image = image
        events = self.num_events = image.num_events
        controllable, public = image.controllable, image.public
        uncontrollable = ((1 << events) - 1) & ~controllable
        # Check order: public uncontrollable events first, then private ones, each by name.
        self.input_order = _bits(uncontrollable & public) + _bits(uncontrollable & ~public)
        # Per event, for each supervisor whose alphabet holds it: (supervisor, the successor of
        # each of its states on the event, None where undefined): one list index per move.
        # The gates: the supervisors that can disable a controllable event, each with the
        # controllable events it allows in each of its states (the enabled set is their AND).
        successors: list[Successors] = [()] * events
        gates: list[Gate] = []
        inputs_total = True     # no state leaves an uncontrollable event of its alphabet undefined
        targets, state_defined = image.targets, image.state_defined
        pairs = list(zip(state_defined, image.state_first))     # each state's (defined events, first successor)
        for sup, first, count, alphabet in zip(range(image.num_supervisors), image.sup_first_state,
                                               image.sup_num_states, image.sup_alphabet):
            defined = state_defined[first:first + count]
            everywhere = functools.reduce(operator.and_, defined) & alphabet   # events no state leaves undefined
            if controllable & alphabet & ~everywhere:     # it can disable a controllable event
                outside = controllable & ~alphabet      # the controllable events it cannot disable
                gates.append((sup, [(mask & controllable) | outside for mask in defined]))
            if alphabet & ~controllable & ~everywhere:
                inputs_total = False
            states = pairs[first:first + count]
            # A column per event, one comprehension each: the successor is at the event's rank
            # among the state's defined events (no Python loop per transition).
            rest = alphabet
            while rest:     # each event of the alphabet (as _bits), lowest first
                bit = rest & -rest
                rest ^= bit
                below = bit - 1
                successors[below.bit_length()] += ((sup, [targets[base + (mask & below).bit_count()] if mask & bit
                                                          else None for mask, base in states]),)
        self.successors = successors
        # When no state of any supervisor leaves an uncontrollable event undefined, no input can
        # violate, and the step moves the inputs by these successors without a check (else None).
        self._total = successors if inputs_total else None
        self._gates = tuple(gates)
        self._moves: Optional[list[list[dict[int, int]]]] = None
        self._replan()
        self._enabled_sets: dict[int, Tuple[int, ...]] = {}     # mask of enabled events -> those events, in canonical order
        # One supervisor: per state, its enabled events and the state after each (_sole_entry).
        self._sole: list[Optional[Tuple[Tuple[int, ...], Tuple[Optional[int], ...]]]] | None = (
            [None] * image.sup_num_states[0] if image.num_supervisors == 1 else None)
        # Rank of each event for policy "first": listed events first, the rest by name.
        self.rank = self._ranks() if self._priority else list(range(events))

    def _ranks(self) -> list[int]:
        """Each event's rank for policy "first": the events of ``priority`` first, in its order,
        then the others by name."""
        listed = [self._index(name) for name in self._priority or ()]
        return [listed.index(e) if e in listed else len(listed) + e for e in range(self.num_events)]

    @property
    def moves(self) -> list[list[dict[int, int]]]:
        """Per supervisor, per state: {event: successor}, built from ``successors`` on first use
        (the step does not use it)."""
        if self._moves is None:
            moves: list[list[dict[int, int]]] = [[{} for _ in range(count)] for count in self.image.sup_num_states]
            for event, pairs in enumerate(self.successors):
                for sup, column in pairs:
                    for local, target in enumerate(column):
                        if target is not None:
                            moves[sup][local][event] = target
            self._moves = moves
        return self._moves

    def load(self, image: Union[Image, bytes]) -> list[str]:
        """Swap in a new table image between two steps; states restart from its initial states.
        An action may load one during a step, which then ends after that action: nothing else
        fires in it (the inputs were polled, and the choice would be made, for the old image).
        A check may not (C++ refuses it; here the step would go on with the old image's tables),
        nor ``on_violation`` (RuntimeError).

        Callbacks bound by name are rebound by name; a name the new image lacks raises
        ``KeyError`` before anything changes, so the VM keeps running the logic it had. Returns
        the new image's uncontrollable events left without a check (reported before the image
        is activated; in strict mode the image is refused with :class:`UnboundEvents`)."""
        if self._in_hook:
            raise RuntimeError("on_violation cannot load an image: load it after step() returns")
        new = image if isinstance(image, Image) else Image.parse(image)
        missing = self._rebind(new)
        self._loads += 1
        self._install(new)
        self.reset()
        return missing

    # -- running ------------------------------------------------------------------------------
    def reset(self) -> None:
        """Back to the initial states, cleared inputs and counters, generator re-seeded."""
        self.states = list(self.image.sup_initial)
        self._bindings_checked = False
        self.previous = 0
        self.violations = 0
        self.rng = XorShift32(self.seed)

    def _enabled_set(self) -> int:
        """5. Enabled set, as a mask: the controllable events every supervisor allows in its
        state, an AND over the gates (the written-out step ANDs them inline: enabled_set_line)."""
        mask, states = self.image.controllable, self.states
        for sup, masks in self._gates:
            mask &= masks[states[sup]]
        return mask

    def enabled(self) -> list[int]:
        """Controllable events enabled by every supervisor, in canonical order."""
        return _bits(self._enabled_set())

    def _enabled_events(self, mask: int) -> Tuple[int, ...]:
        """The events of an enabled ``mask``, a tuple in canonical order, remembered per mask."""
        enabled = self._enabled_sets[mask] = tuple(_bits(mask))
        return enabled

    def _sole_entry(self) -> Tuple[Tuple[int, ...], Tuple[Optional[int], ...]]:
        """(the enabled events at the state of a one-supervisor image, its state after each),
        remembered in ``_sole``: such a model has few states, so every one met is kept. An
        event outside the supervisor's alphabet leaves it where it is."""
        state = self.states[0]
        enabled = tuple(_bits(self._enabled_set()))
        afters = tuple(pairs[0][1][state] if pairs else state for pairs in map(self.successors.__getitem__, enabled))
        table = self._sole
        assert table is not None, "only the step of a one-supervisor image asks"
        entry = table[state] = (enabled, afters)
        return entry

    def _choose(self, fired: list[int]) -> list[int]:
        """The rest of a step whose plan a callback replaced while the inputs fired (a rebind or
        a change of option): one enabled controllable event chosen and fired as the written-out
        step does, out of line, from the VM as it now is; returns ``fired`` with it."""
        enabled = self.enabled()
        if enabled:
            choice = self._select_event(enabled)
            self._fire((choice,), self._bound()[0])
            fired.append(choice)
        return fired

    def _bound(self) -> Plan:
        """The plan: what the step needs of the bindings, the options and the tables, made
        after a bind, a load or a change of option. It is (per event its (action, data) or None,
        whether there is a controllable event); making it also writes the step out for it
        (swarmvm_step_source.canonical_step) and installs that on the VM, where ``vm.step`` finds it before the class's."""
        plan = self._plan
        if plan is None:
            checks, actions, data = self.checks, self.actions, self.data
            polls = [(e, checks[e], data.get(e)) for e in self.input_order if e in checks]
            acts: list[Optional[Act]] = [(actions[e], data.get(e)) if e in actions else None
                                         for e in range(self.num_events)]
            chooses = bool(self.image.controllable)
            plan = self._plan = (acts, chooses)
            sole = self._sole is not None
            columns = [pairs[0][1] if pairs else None for pairs in self.successors] if sole else None
            parts = dict(plan=plan, acts=acts, checks=[c for _, c, _ in polls], datas=[d for _, _, d in polls],
                         successors=self.successors, columns=columns, table=self._sole,
                         controllable=self.image.controllable, gates=self._gates, sets=self._enabled_sets,
                         event_name=self.image.event_name, CallbackError=CallbackError, loads=self._loads)
            make = canonical_step(tuple(parts), tuple(e for e, _, _ in polls), self.inputs == "edge",
                            self.control == "if-quiet", self.policy == "uniform", bool(self.strict), chooses,
                            self._total is not None, sole, tuple(sup for sup, _ in self._gates))
            self.__dict__["step"] = types.MethodType(make(**parts), self)
        return plan

    def _replan(self) -> None:
        """Drop the plan and the step written out for it."""
        self._plan = None
        self.__dict__.pop("step", None)

    def _fire(self, events: Iterable[int], acts: Sequence[Optional[Act]]) -> None:
        """Fire ``events`` in order: for each, every supervisor whose alphabet holds it moves (or
        counts a violation), then its action from ``acts`` (the bound plan's) runs. A callback
        may rebind or set ``states``: what it changed holds for the events after it; an action
        that loads an image ends the firing there (as apply_inputs_lines)."""
        states, successors, loads = self.states, self.successors, self._loads
        for event in events:
            for sup, successor in successors[event]:
                target = successor[states[sup]]
                if target is not None:
                    states[sup] = target
                    continue
                self._violate(event, sup)
                states, acts = self.states, self._bound()[0]
            act = acts[event]
            if act is not None:
                self._act(event, act)
                if self._loads != loads:
                    return
                states, acts = self.states, self._bound()[0]

    def _violate(self, event: int, sup: int) -> None:
        """Supervisor ``sup`` has no move on ``event``: count a violation (the counter stops at
        MAX_VIOLATIONS) and tell ``on_violation``, which may rebind or set ``states`` but not
        load an image (``load`` refuses: the other supervisors of the event are still to move)."""
        if self.violations != MAX_VIOLATIONS:
            self.violations += 1
        if self.on_violation is not None:
            self._in_hook = True
            try:
                self.on_violation(event, sup)
            except Exception as exc:    # ends the step here, as in C++ (docs/semantics.md)
                raise CallbackError(self.image.event_name(event), "violation hook", exc) from exc
            finally:
                self._in_hook = False

    def _act(self, event: int, act: Act) -> None:
        """Run an event's bound (action, data); CallbackError if the action raises."""
        try:
            act[0](act[1])
        except Exception as exc:
            raise CallbackError(self.image.event_name(event), "action", exc) from exc

    def _apply(self, event: int) -> None:
        """Fire one event (the conformance tests re-derive enabled sets with it)."""
        self._fire((event,), self._bound()[0])

    def _weight(self, event: int) -> int:
        """The event's Q15 weight: the product of its probability in each supervisor that has
        it, read from the image's probability section where the state's successors are."""
        image = self.image
        weight = Q15_ONE
        if image.probs is not None:
            below = (1 << event) - 1
            for sup, _ in self.successors[event]:
                g = image.sup_first_state[sup] + self.states[sup]
                weight = (weight * image.probs[image.state_first[g] + (image.state_defined[g] & below).bit_count()]) >> 15
        return weight

    def _select_event(self, enabled: Sequence[int]) -> int:
        """One of the enabled controllable events, by the VM's policy (enabled is non-empty)."""
        if self.policy == "first":
            return min(enabled, key=self.rank.__getitem__)
        if self.policy == "learned":
            return cast(Learner, self.learner).choose(self, enabled)     # (check_options: given with the policy)
        if len(enabled) == 1:
            return enabled[0]
        if self.policy == "uniform":
            return enabled[self.rng.below(len(enabled))]
        weights = [self._weight(e) for e in enabled]
        total = sum(weights)
        if total == 0:
            return enabled[self.rng.below(len(enabled))]
        pick = self.rng.next() % total
        for event, weight in zip(enabled, weights):
            if pick < weight:
                return event
            pick -= weight
        raise AssertionError("unreachable: pick below total")

    def step(self) -> list[int]:
        """One VM step; returns the events that fired, in order (indices). This runs once per
        plan: making the plan (_bound) installs the step written out for it, which runs from
        then on."""
        self._bound()
        return self.step()


def format_trace_line(step: int, names: Sequence[str], states: Sequence[int], violations: int) -> str:
    """One line of the canonical trace (docs/conformance.md): step, events, states, violations."""
    return "%d %s %s %d" % (step, ",".join(names) or "-", ",".join(str(s) for s in states), violations)


def replay_lines(vm: VM, rows: Iterable[Iterable[int]]) -> Iterator[str]:
    """Run ``vm`` from reset on an event script (an iterable of sets of event indices, one per
    step), producing the canonical trace lines one step at a time (constant memory). This is
    the reference conformance harness: the C and C++ harnesses do exactly this and must print
    the same lines."""
    script: dict[str, Iterable[int]] = {"row": set()}
    for event in vm.input_order:
        vm.bind(event, check=lambda _data, event=event: event in script["row"])
    vm.reset()
    name = vm.image.event_name
    for number, row in enumerate(rows, 1):
        script["row"] = row
        fired = vm.step()
        yield format_trace_line(number, [name(e) for e in fired], vm.states, vm.violations)


def replay(vm: VM, rows: Iterable[Iterable[int]]) -> list[str]:
    """The lines of :func:`replay_lines`, as a list."""
    return list(replay_lines(vm, rows))


_RANDINT = random.randint     # the standard one: the exact step makes its draw without calling it


class SCT:
    """Nadzoru 2's Python VM API over :class:`VM`, so published controllers run unchanged: swap
    ``from sct import SCT`` for ``from swarmvm_vm import SCT`` (docs/compat.md).

    ``SCT(path)`` takes the ``supervisor.yaml`` itself when the swarmvm compiler is installed,
    else the ``.svm`` that ``swarmvm pack`` writes beside it (a robot without YAML support), or a
    ``.svm`` path. ``EV`` maps ``EV_x`` names to indices; ``add_callback(EV['EV_x'], callback,
    check, data)`` and ``run_step()`` behave as the published VM's.

    Exact mode (the default) is the published step to the bit: every check in the file's event
    order before any transition; the events whose check was true applied in that order, each
    callback right after its transition; then one enabled controllable event, the k-th in file
    order with ``k = random.randint(0, 1000000000) % n`` from the global ``random`` module.
    Indices are the file's. It needs the file's event order, which only the YAML file gives: an
    image alone refuses it (ValueError). ``exact=False`` runs the canonical VM step
    (docs/semantics.md; indices by name, public events first, swarmvm's own generator, the
    options of :class:`VM`): faster, and independent of the order an export happened to use."""

    _public_first = False

    def __init__(self, filename: str, exact: bool = True, **options: Any) -> None:
        image, file_events, file_states = _compat_image(filename)
        if exact and file_states is None:
            raise ValueError("%s: exact mode needs the supervisor file's event order, which this image does not "
                             "keep (made from automata, or with --no-names); give the supervisor.yaml, or exact=False"
                             % filename)
        self.vm = VM(image, **options)
        self.exact = exact
        self._file_states = file_states if exact else None
        # Index a caller sees -> canonical index: the file's order in exact mode, else the image's;
        # the names EV holds: the file's as written in exact mode, else swarmvm's (EV_<name>).
        # (file_events is None only with file_states, which exact mode has: checked above.)
        self._canonical: list[int] = cast("list[int]", file_events) if exact else list(range(image.num_events))
        written = image.source.written if exact and image.source is not None else None
        self.EV = {(written[c] if written else image.event_name(c)): i for i, c in enumerate(self._canonical)}
        if exact and image.source is not None:      # the published VMs start from sup_current_state
            if any(s >= n for s, n in zip(image.source.start, image.sup_num_states)):
                raise ImageError(ErrorCode.LAYOUT, "%s: image source section: a start state outside its supervisor"
                                 % filename)
            self.vm.states[:] = image.source.start
        self.ev_controllable = [image.controllable >> c & 1 for c in self._canonical]
        self.num_events = image.num_events
        self.num_supervisors = image.num_supervisors
        self.last_events: list[int] = []
        self.input_buffer: list[int] = []
        if exact:
            self._checks_order = [i for i in range(len(self._canonical)) if not self.ev_controllable[i]]
            self._file_index = [0] * len(self._canonical)
            for i, c in enumerate(self._canonical):
                self._file_index[c] = i
            self._private = [0 if image.public >> c & 1 else 1 for c in self._canonical]     # by file index
            self._orders: dict[int, list[Tuple[int, int]]] = {}     # enabled mask -> _file_order's list
            # one supervisor: per state, _sole_entry's (or None until met)
            self._sole_table: list[Optional[Tuple[list[int], Column, list[int]]]] = []
            self._sole_columns: list[Column] = []   # one supervisor: per file event, its state after each state
            self._file_successors: list[Successors] = []    # per file event, VM.successors of its canonical index
            self._tables_of: Optional[Image] = None         # the image the four above were made for

    @property
    def sup_current_state(self) -> list[int]:
        """Each supervisor's state: numbered as in the file in exact mode, else canonically."""
        if self._file_states is None:
            return self.vm.states
        return [numbers[state] for numbers, state in zip(self._file_states, self.vm.states)]

    def add_callback(self, event: int, clbk: Optional[Callback], ci: Optional[Callback], sup_data: Any) -> None:
        """Register the event's callback, check and data. Exact mode, as published: registering
        again replaces all three (None included), and a check on a controllable event is
        accepted and, as the published step polls uncontrollable events only, never called.
        Canonical mode binds (VM.bind) and leaves a controllable event's check out."""
        canonical = self._canonical[event]
        controllable = self.vm.image.controllable >> canonical & 1
        if self.exact:
            self.vm.actions.pop(canonical, None)
            self.vm.checks.pop(canonical, None)
        self.vm.bind(canonical, action=clbk, check=None if controllable else ci, data=sup_data)

    def run_step(self) -> None:
        """One step; ``last_events`` are the events it applied and ``input_buffer`` the
        uncontrollable ones whose check was true (indices as in ``EV``). In exact mode this
        runs once per plan of the VM: it installs the step written out for it (_plan_exact)."""
        if self.exact:
            self._plan_exact()
        else:
            self.__dict__["run_step"] = types.MethodType(_canonical_run_step, self)
        return self.run_step()

    def _plan_exact(self) -> None:
        """Write the exact step out for the VM's current plan (swarmvm_step_source.exact_step) and install it on
        this object, where ``run_step`` finds it before the class's; it plans again when the
        VM's plan changes."""
        vm, canonical = self.vm, self._canonical
        vm_plan = vm._plan or vm._bound()
        polls = [(i, vm.checks[canonical[i]], vm.data.get(canonical[i]))
                 for i in self._checks_order if canonical[i] in vm.checks]
        sole = vm.image.num_supervisors == 1
        if self._tables_of is not vm.image:
            self._tables_of = vm.image
            self._orders.clear()
            self._sole_table = [None] * vm.image.sup_num_states[0] if sole else []
            self._sole_columns = [self._column(c) for c in canonical] if sole else []
            self._file_successors = [vm.successors[c] for c in canonical]
        gate_sups = () if sole else tuple(sup for sup, _ in vm._gates)
        acting = any(vm_plan[0][canonical[event]] is not None for event, _, _ in polls)
        parts = dict(vm_plan=vm_plan, acts=vm_plan[0], checks=[c for _, c, _ in polls], datas=[d for _, _, d in polls],
                     canonical=canonical, successors=vm.successors, file_successors=self._file_successors,
                     columns=self._sole_columns, table=self._sole_table, controllable=vm.image.controllable,
                     gates=vm._gates, private=self._private, orders=self._orders, rnd=random, randint=_RANDINT,
                     getrandbits=random.getrandbits, loads=vm._loads)
        make = exact_step(tuple(parts), tuple(event for event, _, _ in polls), self._public_first, vm_plan[1],
                              vm._total is not None, sole, acting, gate_sups)
        self.__dict__["run_step"] = types.MethodType(make(**parts), self)

    def _column(self, event: int) -> Column:
        """A one-supervisor image's state after each of its states on canonical ``event``: its
        column, None where undefined; a column that stays for an event outside its alphabet."""
        pairs = self.vm.successors[event]
        return pairs[0][1] if pairs else list(range(self.vm.image.sup_num_states[0]))

    def _file_order(self, mask: int) -> list[Tuple[int, int]]:
        """The enabled events of ``mask`` in file order, as (file index, canonical index) pairs,
        remembered per mask: the published choice takes the k-th of them."""
        order = self._orders[mask] = sorted((self._file_index[e], e) for e in _bits(mask))
        return order

    def _sole_entry(self, state: int) -> Tuple[list[int], Column, list[int]]:
        """(the enabled controllable events of a one-supervisor image at ``state`` in file order,
        the state after each, each one's canonical index), remembered in ``_sole_table``: the
        published choice takes the k-th of each."""
        columns, controllable = self._sole_columns, self.vm.image.controllable
        order = [f for f, c in enumerate(self._canonical) if controllable >> c & 1 and columns[f][state] is not None]
        entry = self._sole_table[state] = (order, [columns[f][state] for f in order],
                                           [self._canonical[f] for f in order])
        return entry

    def _choose(self, inputs: list[int]) -> None:
        """The published choice of a step whose VM plan a callback replaced while the inputs
        fired (a rebind or a change of option), out of line, from the VM as it now is: ``randint`` itself
        draws (the written-out step makes the same number without calling it)."""
        vm = self.vm
        order = sorted((self._file_index[e], e) for e in vm.enabled())
        if order:
            choice, event = order[random.randint(0, 1000000000) % len(order)]
            vm._fire((event,), vm._bound()[0])
            self.last_events = inputs + [choice]
        else:
            self.last_events = inputs[:]

    def get_events(self) -> Tuple[dict[str, int], list[int]]:
        return self.EV, self.ev_controllable


def _canonical_run_step(sct: SCT) -> None:
    """SCT.run_step with ``exact=False``, installed on the object by the first run_step: the
    VM's step, whose events are its inputs, then at most one controllable event."""
    fired = sct.last_events = sct.vm.step()
    sct.input_buffer = fired[:-1] if fired and sct.ev_controllable[fired[-1]] else fired[:]


class SCTPub(SCT):
    """The published ``SCTPub``: as :class:`SCT`, but in exact mode the public (shared) events
    whose check was true are applied before the private ones (checks still run in file order).
    In canonical mode every swarmvm step applies public events first anyway."""

    _public_first = True


def _compat_image(filename: str) -> Tuple[Image, Optional[list[int]], Optional[list[list[int]]]]:
    """(image, the canonical index of each of the file's events in file order, each supervisor's
    file state numbers by canonical state) for :class:`SCT`; the last two None when the image
    has no order section. A YAML path is compiled in memory, as the published VMs read it
    (``swarmvm pack``'s image), when it exists and the swarmvm compiler can be imported;
    otherwise the ``.svm`` beside it is read (_image_beside), as is a ``.svm`` path."""
    image: Optional[Image] = None
    if filename.endswith(".yaml") and os.path.exists(filename):
        try:
            from swarmvm.compiler.pipeline import compile_inputs
        except ImportError:
            pass
        else:
            image = Image.parse(compile_inputs([filename], name="sct", published=True).packed_image)
    if image is None:
        image = _image_beside(filename) if filename.endswith(".yaml") else Image.load(filename)
    if image.order is None or image.names is None or image.state_order is None:
        return image, None, None
    file_events = [0] * image.num_events
    for event, position in enumerate(image.order):
        file_events[position] = event
    file_states = [image.state_order[first:first + count]
                   for first, count in zip(image.sup_first_state, image.sup_num_states)]
    return image, file_events, file_states


def _image_beside(yaml_path: str) -> Image:
    """The image ``x.svm`` for ``x.yaml``, never stale: FileNotFoundError when it is missing,
    ValueError when it records the digest of the YAML file it was packed from (docs/compat.md,
    "Never stale") and the file beside it now has other bytes; both name the two files and
    the command that fixes it."""
    image_path = yaml_path[:-5] + ".svm"
    fix = ": run swarmvm pack %s -o %s" % (yaml_path, image_path)
    if not os.path.exists(image_path):
        raise FileNotFoundError("cannot read table image %s for %s%s" % (image_path, yaml_path, fix))
    image = Image.load(image_path)
    if image.source is not None and os.path.exists(yaml_path):
        # (read_file: a FIFO or a device under the YAML's name is refused, never waited on; a
        # file over the compiler's input limit cannot be the one packed, and its digest differs)
        if hashlib.sha256(read_file(yaml_path, MAX_SOURCE_FILE_SIZE)).digest() != image.source.digest:
            raise ValueError("%s is stale: it was packed from another version of %s%s" % (image_path, yaml_path, fix))
    return image
