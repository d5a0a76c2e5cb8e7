"""swarmvm's reference VM: the step of docs/semantics.md written out plainly, to be read beside it.

Each section of docs/semantics.md has its code here, in the page's order: "Model" (the input
order, reading a transition from the image), "One step" (a method per numbered step, called in
order by :meth:`ReferenceVM.step`), "Selection policies", "Callbacks", "Callbacks that raise" and
"Reset and swap". The tables are read from the image as docs/image-format.md lays them out
(:class:`swarmvm_format.Image`), with no table derived from them, no code written at run time
and nothing done for speed.

This is the oracle of the conformance suite (tests/conformance/): every runtime, the fast Python
VM (swarmvm_vm.VM) included, must print this VM's trace. It takes the fast VM's options and
callbacks and binds them by the same rules (swarmvm_vm.Bindings); it draws from the one
generator (swarmvm_vm.XorShift32) and raises the same errors. It is not copied onto robots (a
Python target ships swarmvm_vm.py): it is several times slower, and meant to be read.
Like the other runtime files it imports its neighbours by their top-level names.
"""

from __future__ import annotations

__all__ = ["ReferenceVM"]

from typing import TYPE_CHECKING, Any, Callable, Optional, Sequence, Union, cast

if TYPE_CHECKING:   # mypy reads its neighbours as the package's modules; the VM imports the copies beside it
    from runtime_py.swarmvm_format import Q15_ONE, Image
    from runtime_py.swarmvm_vm import MAX_VIOLATIONS, Bindings, CallbackError, Learner, XorShift32, check_options
else:
    from swarmvm_format import Q15_ONE, Image
    from swarmvm_vm import MAX_VIOLATIONS, Bindings, CallbackError, XorShift32, check_options


class ReferenceVM(Bindings):
    """A VM over one table image, run by :meth:`step` as docs/semantics.md says, step by step.

    The constructor takes the options of swarmvm_vm.VM ("Options summary": ``inputs``,
    ``control``, ``policy``, ``seed``; with ``priority`` for policy ``first``, ``learner`` for
    ``learned``, the ``on_violation`` hook and ``strict``), and ``bind`` (from Bindings) the same
    callbacks. Observable as the fast VM is: ``states``, ``violations``, ``rng``, ``step()``'s
    list of fired events, ``enabled()``, ``load()``, ``reset()``; options may be changed
    between steps by assigning them."""

    previous: set[int]      # the events whose check was true at the previous step (reset)
    states: list[int]
    violations: int
    rng: XorShift32
    input_order: list[int]

    def __init__(self, image: Union[Image, bytes], inputs: str = "level", control: str = "after-inputs",
                 policy: str = "uniform", seed: int = 1, priority: Optional[Sequence[Union[int, str]]] = None,
                 learner: Optional[Learner] = None, on_violation: Optional[Callable[[int, int], Any]] = None,
                 strict: bool = False) -> None:
        check_options(inputs, control, policy, learner)
        self.inputs, self.control, self.policy, self.strict = inputs, control, policy, strict
        self.seed, self.priority, self.learner, self.on_violation = seed, priority, learner, on_violation
        self.actions, self.checks, self.data = {}, {}, {}
        self._loads = 0             # images loaded so far: an action that loads one ends the step
        self._in_hook = False       # on_violation is running, and may not load an image
        self._use(image if isinstance(image, Image) else Image.parse(image))
        self.reset()

    # -- Model ------------------------------------------------------------------------------------
    def _use(self, image: Image) -> None:
        """Run ``image`` from now on. The *input order* ("One step", 1. Poll): the public
        uncontrollable events, then the private ones, each group in event order."""
        self.image = image
        self.num_events = image.num_events
        uncontrollable = [e for e in range(image.num_events) if not self._controllable(e)]
        self.input_order = ([e for e in uncontrollable if self._public(e)]
                            + [e for e in uncontrollable if not self._public(e)])
        self._first = [self._index(name) for name in self.priority or ()]     # policy first's listed events

    def _controllable(self, event: int) -> bool:
        return bool(self.image.controllable >> event & 1)

    def _public(self, event: int) -> bool:
        return bool(self.image.public >> event & 1)

    def _in_alphabet(self, sup: int, event: int) -> bool:
        return bool(self.image.sup_alphabet[sup] >> event & 1)

    def _transition(self, sup: int, event: int) -> Optional[int]:
        """Where supervisor ``sup``'s transition on ``event`` from its current state is kept in
        the image (its index in ``targets`` and ``probs``), or None if it has none. The
        successors of a state follow each other in event order, from its ``state_first``."""
        image = self.image
        state = image.sup_first_state[sup] + self.states[sup]
        defined = image.state_defined[state]
        if not defined >> event & 1:
            return None
        earlier = defined & ((1 << event) - 1)      # the state's defined events before this one
        return image.state_first[state] + bin(earlier).count("1")

    # -- One step -------------------------------------------------------------------------------
    def step(self) -> list[int]:
        """One step ("One step", 1 to 6); returns the events that fired, in the order they were
        applied. In strict mode it refuses to step while a check is missing ("Callbacks")."""
        if self.strict:
            self._check_bindings()
        loads = self._loads
        polled = self._poll()                           # 1
        occurred = self._occurrence(polled)             # 2
        fired = self._apply_inputs(occurred, loads)     # 3
        if self._loads != loads or not self._control_continues(fired):      # 4
            return fired
        enabled = self._enabled_set()                   # 5
        if enabled:                                     # 6
            choice = self._select_event(enabled)
            self._fire(choice)
            fired.append(choice)
        return fired

    def _poll(self) -> list[int]:
        """1. Poll: the uncontrollable events whose check returns true, each check called once,
        in input order. An event without a check never occurs. A check that raises ends the
        step before anything changed ("Callbacks that raise")."""
        true = []
        for event in self.input_order:
            check = self.checks.get(event)
            if check is None:
                continue
            try:
                if check(self.data.get(event)):
                    true.append(event)
            except Exception as exc:
                raise CallbackError(self.image.event_name(event), "check", exc) from exc
        return true

    def _occurrence(self, polled: list[int]) -> list[int]:
        """2. Occurrence: with level inputs, every event whose check was true; with edge inputs,
        those whose check was not true at the previous step (remembered in ``previous``)."""
        if self.inputs == "level":
            occurred = polled
        else:
            occurred = [event for event in polled if event not in self.previous]
        self.previous = set(polled)
        return occurred

    def _apply_inputs(self, occurred: list[int], loads: int) -> list[int]:
        """3. Apply inputs: each occurring event in input order, moves then action (_fire). An
        action that loads an image ends the step after its own event ("Reset and swap")."""
        fired = []
        for event in occurred:
            self._fire(event)
            fired.append(event)
            if self._loads != loads:
                break
        return fired

    def _control_continues(self, fired: list[int]) -> bool:
        """4. Control phase: with ``if-quiet`` the step ends when an input occurred."""
        return self.control == "after-inputs" or not fired

    def enabled(self) -> list[int]:
        """The enabled set as the fast VM shows it (its ``enabled()``): step 5's events."""
        return self._enabled_set()

    def _enabled_set(self) -> list[int]:
        """5. Enabled set: the controllable events, in event order, that every supervisor either
        does not have in its alphabet or has a transition on from its current state."""
        return [event for event in range(self.num_events)
                if self._controllable(event)
                and all(not self._in_alphabet(sup, event) or self._transition(sup, event) is not None
                        for sup in range(self.image.num_supervisors))]

    def _select_event(self, enabled: list[int]) -> int:
        """6. Selection: one of the (non-empty) enabled events, by the policy ("Selection
        policies")."""
        if self.policy == "first":
            return min(enabled, key=self._rank)
        if self.policy == "learned":
            return cast("Learner", self.learner).choose(self, enabled)   # (check_options: given with the policy)
        if len(enabled) == 1:
            return enabled[0]
        if self.policy == "uniform":
            return self._uniform(enabled)
        return self._weighted(enabled)

    # -- applying an event (steps 3 and 6) --------------------------------------------------------
    def _fire(self, event: int) -> None:
        """Every supervisor whose alphabet holds ``event`` moves along its transition; one with
        none keeps its state and counts a violation (_violate); then the event's action runs."""
        for sup in range(self.image.num_supervisors):
            if self._in_alphabet(sup, event):
                at = self._transition(sup, event)
                if at is None:
                    self._violate(event, sup)
                else:
                    self.states[sup] = self.image.targets[at]
        self._act(event)

    def _violate(self, event: int, sup: int) -> None:
        """The violation counter grows by one, stopping at its 32-bit maximum, and the
        ``on_violation(event, sup)`` hook is told; a hook that raises ends the step there
        ("Callbacks that raise"), and may not load an image ("Reset and swap")."""
        if self.violations < MAX_VIOLATIONS:
            self.violations += 1
        if self.on_violation is None:
            return
        self._in_hook = True
        try:
            self.on_violation(event, sup)
        except Exception as exc:
            raise CallbackError(self.image.event_name(event), "violation hook", exc) from exc
        finally:
            self._in_hook = False

    def _act(self, event: int) -> None:
        """The event's action, if bound, with its data; one that raises ends the step after its
        event's moves, which stay applied ("Callbacks that raise")."""
        action = self.actions.get(event)
        if action is None:
            return
        try:
            action(self.data.get(event))
        except Exception as exc:
            raise CallbackError(self.image.event_name(event), "action", exc) from exc

    # -- Selection policies -------------------------------------------------------------------
    def _rank(self, event: int) -> int:
        """Policy ``first``: the events listed in ``priority`` first, in its order (named when
        the image is taken: _use), then the others in event order."""
        listed = self._first
        return listed.index(event) if event in listed else len(listed) + event

    def _uniform(self, enabled: list[int]) -> int:
        """Policy ``uniform`` with two or more events: ``en[((next() >> 16) * n) >> 16]``."""
        return enabled[self.rng.below(len(enabled))]

    def _weight(self, event: int) -> int:
        """The event's Q15 weight: 1.0 times, for each supervisor whose alphabet holds it in
        supervisor order, the probability of its transition from the current state (1.0 in an
        image without probabilities), each product shifted back to Q15."""
        weight = Q15_ONE
        for sup in range(self.image.num_supervisors):
            at = self._transition(sup, event) if self._in_alphabet(sup, event) else None
            if at is not None:      # (an enabled event's: every supervisor that has it has the move)
                probability = Q15_ONE if self.image.probs is None else self.image.probs[at]
                weight = (weight * probability) >> 15
        return weight

    def _weighted(self, enabled: list[int]) -> int:
        """Policy ``weighted`` with two or more events: as ``uniform`` when every weight is 0,
        else the event where ``next() mod total`` falls among the weights, in event order."""
        weights = [self._weight(event) for event in enabled]
        total = sum(weights)
        if total == 0:
            return self._uniform(enabled)
        pick = self.rng.next() % total
        for event, weight in zip(enabled, weights):
            if pick < weight:
                return event
            pick -= weight
        raise AssertionError("unreachable: pick is below the total of the weights")

    # -- Reset and swap -----------------------------------------------------------------------
    def reset(self) -> None:
        """Every supervisor back to its initial state, the remembered check values and the
        violation counter cleared, the generator ("The pseudo-random generator") re-seeded."""
        self.states = list(self.image.sup_initial)
        self.previous = set()
        self.violations = 0
        self.rng = XorShift32(self.seed)
        self._bindings_checked = False

    def load(self, image: Union[Image, bytes]) -> list[str]:
        """Swap in a new image: callbacks bound by name are rebound by name (a name the new image
        lacks is refused, the VM keeping its logic), then a reset. Returns the new image's
        uncontrollable events left without a check (in strict mode the image is refused). An
        action may load during a step, which then ends with that action; the violation hook may
        not (RuntimeError). A check that loads is not looked for (the fast VM does not either)."""
        if self._in_hook:
            raise RuntimeError("on_violation cannot load an image: load it after step() returns")
        new = image if isinstance(image, Image) else Image.parse(image)
        missing = self._rebind(new)
        self._loads += 1
        self._use(new)
        self.reset()
        return missing
