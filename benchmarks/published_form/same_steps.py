"""What the published VM and swarmvm must both do over the side-by-side benchmark's event script
(benchmarks/flash_vs_published.py), from the Python reference VM (runtime_py/swarmvm_reference.py,
the conformance oracle), so that their costs per step are those of the same transitions.

Why it is needed: the two VMs draw their choice differently (the published VM takes the
``RANDOM() % n``-th enabled event, swarmvm's uniform policy ``((r >> 16) * n) >> 16`` with
its own xorshift32), so left alone they soon walk different paths and their costs per step are
not of the same work. The published VM draws from the application's generator (kilolib's
``rand_soft`` on a Kilobot); the benchmark's application replays, as that generator, the
position among the enabled events of the one swarmvm's generator chose at that step
(``Expected.draws``). With the events numbered in swarmvm's input order (``published_order``)
both VMs then apply the same inputs in the same order and choose the same event, and each
program folds the events it fired into a digest (``digest``) that the benchmark compares with
the reference's: a run that took other transitions fails it."""

from dataclasses import dataclass
from typing import Any, Iterable

from swarmvm.compiler.runtime_files import reference_vm

# FNV-1a, 32 bits: what the programs fold each step's fired events into (the program's
# side in benchmarks/published_form/side_by_side.py, app_fold).
FNV_OFFSET = 2166136261
FNV_PRIME = 16777619
MASK32 = 0xFFFFFFFF


def fold(digest: int, byte: int) -> int:
    return ((digest ^ byte) * FNV_PRIME) & MASK32


def digest(steps: Iterable[Iterable[int]]) -> int:
    """Each step's fired events (canonical index + 1, in the order they fired), then a 0 that
    ends the step: two runs that fired other events, in another order or at another step differ."""
    value = FNV_OFFSET
    for fired in steps:
        for event in fired:
            value = fold(value, event + 1)
        value = fold(value, 0)
    return value


@dataclass(frozen=True)
class Expected:
    """The reference's run of one script: ``draws[k]`` the position, among step k's enabled
    events in event order, of the one chosen (0 when none was); ``fired`` the events fired
    over the script and ``digest`` their digest; ``input_order`` the order swarmvm polls and
    applies the uncontrollable events in (canonical indices: public ones first)."""

    draws: tuple[int, ...]
    fired: int
    digest: int
    input_order: tuple[int, ...]


def expected(image: bytes, rows: list[set[int]], inputs: str, control: str, policy: str, seed: int) -> Expected:
    """The reference VM run over ``rows`` (each the uncontrollable events whose check is true
    at that step) with the benchmark's options and seed, from reset."""
    position = [0]

    class Recording(reference_vm().ReferenceVM):  # type: ignore[misc]   # a module loaded at run time
        """The reference VM, noting where in the enabled list its selection (step 6) chose."""

        def _select_event(self, enabled: list[int]) -> Any:
            chosen = super()._select_event(enabled)
            position[0] = enabled.index(chosen)
            return chosen

    machine = Recording(image, inputs=inputs, control=control, policy=policy, seed=seed)
    current: list[set[int]] = [set()]
    for event in machine.input_order:
        machine.bind(event, check=lambda _data, event=event: event in current[0])
    machine.reset()
    draws, steps = [], []
    for row in rows:
        current[0], position[0] = row, 0
        steps.append(list(machine.step()))
        draws.append(position[0])
    return Expected(tuple(draws), sum(len(s) for s in steps), digest(steps), tuple(machine.input_order))


def published_order(input_order: Iterable[int], controllable: Iterable[int]) -> list[int]:
    """The canonical indices in the numbering the published tables are written in: the
    uncontrollable events in swarmvm's input order (the published VM polls and applies them in
    index order), then the controllable ones in event order (it lists the enabled ones in index
    order, as swarmvm does in event order)."""
    return [*input_order, *sorted(controllable)]
