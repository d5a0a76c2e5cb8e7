"""What the generated Python apps share (``python3 -m <name>_app`` of the python and pipuck
targets): their command-line options, reading an event script, and the fixed-rate loop.
Copied as it is into every generated Python and Pi-puck target; standard library only.

One parser for both apps, so the same option means the same thing on a laptop and on a robot,
and ``--help`` answers before anything steps."""

import argparse
import os
import sys
import time
from typing import TYPE_CHECKING, Callable, FrozenSet, Iterable, List, Optional, TypedDict, TypeVar

if TYPE_CHECKING:   # mypy reads the VM as the package's module; an app imports the copy beside it
    from runtime_py import swarmvm_vm
else:
    import swarmvm_vm

STDIN = "-"     # the script name that means standard input, as for ``swarmvm trace --script``
# An app's event script is read whole: 16 MiB holds over a million steps of a few events each
# (docs/limits.md); a longer one is refused in one line, not read.
MAX_SCRIPT_BYTES = 16 << 20

# The facts the compiler's command line states too (swarmvm.cli): defined here, in the runtime a
# robot carries without the compiler, and imported by the compiler (runtime_files.python_app).
SEED_MAX = 0xFFFFFFFF   # the VM's generator (swarmvm_vm.XorShift32) takes a 32-bit seed: every --seed is 0..this
# The policies a --policy option offers: every one but "learned", whose learner object no command
# line can give.
OPTION_POLICIES = tuple(policy for policy in swarmvm_vm.POLICIES if policy != "learned")

Row = FrozenSet[str]    # one step of an event script: the ``EV_`` names of the events that occur
Number = TypeVar("Number", int, float)


def _in_range(convert: Callable[[str], Number], low: Number, high: Number, what: str) -> Callable[[str], Number]:
    """An argparse type: text that ``convert`` reads as a number from ``low`` to ``high`` (nan
    and infinity never are); anything else is a usage error saying ``what`` was expected."""
    def read(text: str) -> Number:
        try:
            value: Optional[Number] = convert(text)
        except ValueError:
            value = None
        if value is None or not low <= value <= high:
            raise argparse.ArgumentTypeError("%r is not %s" % (text, what))
        return value
    return read


_steps = _in_range(int, 1, float("inf"), "a positive number of steps")
_period = _in_range(float, 0.0, sys.float_info.max, "a number of seconds (0 or more)")
_seed = _in_range(int, 0, SEED_MAX, "a seed (0 to %d)" % SEED_MAX)


class VMOptions(TypedDict):
    """The keyword arguments of ``swarmvm_vm.VM`` an app's options decide."""
    seed: int
    inputs: str
    control: str
    policy: str


def parser(description: str, script_help: str) -> argparse.ArgumentParser:
    """The options every app takes: --steps, --period, --seed, --inputs, --control, --policy,
    --script (``script_help`` says where its events go), --trace. An app adds its own."""
    options = argparse.ArgumentParser(description=description)
    options.add_argument("--steps", type=_steps, help="stop after this many steps (default: run until stopped)")
    options.add_argument("--period", type=_period, default=0.1, help="seconds per step (default: 0.1)")
    options.add_argument("--seed", type=_seed, default=1,
                         help="seed of the VM's generator, which chooses among enabled controllable events "
                              "(default: 1)")
    options.add_argument("--inputs", choices=swarmvm_vm.INPUT_MODES, default="level",
                         help="an uncontrollable event occurs in every step its check is true, or only in the "
                              "step it becomes true (default: level)")
    options.add_argument("--control", choices=swarmvm_vm.CONTROL_MODES, default="after-inputs",
                         help="choose a controllable event in every step, or only in a step without inputs "
                              "(default: after-inputs)")
    options.add_argument("--policy", choices=OPTION_POLICIES, default="uniform",
                         help="how the VM chooses among enabled controllable events (default: uniform)")
    options.add_argument("--script", metavar="FILE", help=script_help + " ('-': standard input)")
    options.add_argument("--trace", action="store_true",
                         help="print the canonical trace line of each step (as swarmvm trace prints it)")
    return options


def vm_options(args: argparse.Namespace) -> VMOptions:
    """The VM's options among parsed ``args``, as keyword arguments of ``swarmvm_vm.VM``."""
    return VMOptions(seed=args.seed, inputs=args.inputs, control=args.control, policy=args.policy)


def read_script(path: str, events: Iterable[str]) -> List[Row]:
    """Rows (sets of ``EV_`` names) of an event script (docs/conformance.md), ``-`` read from
    standard input; an unknown name or an unreadable file ends the app with one line."""
    try:
        if path == STDIN:
            text = sys.stdin.read(MAX_SCRIPT_BYTES + 1)     # bounded as a file is
            if len(text) > MAX_SCRIPT_BYTES:
                raise SystemExit("%s: cannot read the script (over %d characters)" % (path, MAX_SCRIPT_BYTES))
            lines = text.splitlines()
        else:
            raw = swarmvm_vm.read_file(path, MAX_SCRIPT_BYTES)     # the runtime's input layer: regular files, bounded
            if len(raw) > MAX_SCRIPT_BYTES:
                raise SystemExit("%s: cannot read the script (over %d bytes)" % (path, MAX_SCRIPT_BYTES))
            lines = raw.decode("utf-8").splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise SystemExit("%s: cannot read the script (%s)" % (path, getattr(exc, "strerror", None) or exc))
    rows: List[Row] = []
    for number, line in enumerate(lines, 1):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        names = frozenset() if line == "-" else frozenset(line.split())
        unknown = sorted(names - set(events))
        if unknown:
            raise SystemExit("%s:%d: unknown event %s" % (path, number, unknown[0]))
        rows.append(names)
    return rows


class ScriptedEvents:
    """The uncontrollable events of an event script: those of row ``n`` occur at step ``n``,
    none after the script's end."""

    def __init__(self, rows: Iterable[Row] = ()) -> None:
        self._rows = list(rows)
        self.row: Row = frozenset()

    def begin_step(self, number: int) -> None:
        self.row = self._rows[number - 1] if number <= len(self._rows) else frozenset()

    def occurred(self, name: str) -> bool:
        return name in self.row

    def bind(self, vm: swarmvm_vm.VM) -> None:
        """Make the script decide every uncontrollable event of ``vm`` (their checks replaced;
        the actions stay)."""
        for event in vm.input_order:
            vm.bind(event, check=lambda _data, name=vm.image.event_name(event): name in self.row)


def run(vm: swarmvm_vm.VM, period: float = 0.1, steps: Optional[int] = None, trace: bool = False,
        begin_step: Optional[Callable[[int], None]] = None) -> None:
    """Step the VM at a fixed rate, every ``period`` seconds (forever, or ``steps`` times),
    calling ``begin_step(n)`` before step ``n`` when given; Ctrl-C ends it with a line saying
    how many steps ran, not a traceback.

    Deadlines advance by ``period`` from the start, so a slow step does not shift the ones
    after it. With ``trace`` every step prints its canonical trace line (docs/conformance.md)."""
    program = os.path.basename(sys.argv[0])
    number = 0
    try:
        if steps is None:       # it may print nothing else: say that it runs, and how to stop it
            print("%s: stepping the VM until stopped (Ctrl-C; --steps N stops after N steps, --help lists "
                  "the options)" % program, file=sys.stderr, flush=True)
        deadline = time.monotonic()
        while steps is None or number < steps:
            number += 1
            if begin_step is not None:
                begin_step(number)
            fired = vm.step()
            if trace:
                names = [vm.image.event_name(e) for e in fired]
                print(swarmvm_vm.format_trace_line(number, names, vm.states, vm.violations), flush=True)
            deadline += period
            time.sleep(max(0.0, deadline - time.monotonic()))
    except KeyboardInterrupt:
        print("%s: stopped in step %d" % (program, number), file=sys.stderr, flush=True)
