"""swarmvm's Python API: every verb of the command line as a typed function (docs/api.md).

The command line (``swarmvm.cli.commands``) only parses options, calls these and prints; scripts,
notebooks and other tools call them directly. Bad input raises :class:`InputError` (one line
naming file, key and place); nothing here writes a file unless its name says so.

Errors (docs/api.md): every public function checks its arguments first (one rule per parameter,
:func:`swarmvm.boundary.arguments.checked`). An argument of the wrong type (a str where a list of paths
is expected, a ``Path`` where a str is) raises TypeError: the calling program is wrong. A value
the function cannot use (no file, a count out of range, nan, an unknown target, format or mode,
a file name holding NUL) raises InputError naming the parameter, as bad input on the command
line does; so does anything wrong in or about a file (missing, unreadable, malformed)."""

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Iterator, Sequence

from .boundary.arguments import (
    checked,
    file_name,
    file_names,
    flag,
    instance,
    integer,
    maybe_file_names,
    number,
    one_of,
    optional,
    text,
    texts,
)
from .boundary.errors import InputError, read_input
from .boundary.output import write_outputs
from .compiler import pipeline
from .compiler.model import Model
from .compiler.naming import file_stem
from .compiler.pipeline import Compiled, compile_inputs, compile_spec
from .compiler.runtime_files import python_app, python_vm
from .compiler.user_files import Drift, drift
from .footprint import measure as fp
from .footprint import report as fp_report
from .footprint.budget import Budgets, read_budgets
from .footprint.cycles import measure_cycles
from .footprint.delta import read_baseline
from .footprint.sidecar import sidecar_of
from .footprint.stack import STEP_ROOT, measure_stack, parse_frames, parse_indirect
from .inspector.page import Inspection, write_page
from .models import properties
from .models.equivalence import compare, format_difference
from .models.export import FORMATS, export_files
from .models.product import DEFAULT_MAX_STATES, TRANSITIONS_PER_STATE
from .models.properties import format_report
from .models.synthesis import models_by_name, synthesise
from .readers import event_script as script
from .readers.event_script import read_script_rows
from .readers.synth_script import read_synth_script
from .targets import TARGETS, generate
from .targets import c as c_target
from .compat.switch import VARIANTS, Switch, switch_project

__all__ = ["InputError", "Compiled", "CheckRow", "load", "compile_model", "check", "read_image",
           "parse_image", "write_image", "Generated", "generate_target", "learned_pairs", "script_lines", "make_script",
           "trace", "measure_footprint", "footprint_report", "check_properties", "equivalent", "export", "write_export",
           "synthesise_models", "inspect", "compat_switch", "TARGETS", "DEFAULT_MAX_STATES", "TRANSITIONS_PER_STATE"]

if TYPE_CHECKING:   # mypy reads the source tree, where the runtime is the folder runtime_py/
    from runtime_py import swarmvm_vm as _vm
    from runtime_py.swarmvm_vm import Image
else:
    _vm = python_vm()

# The rules of parameters several functions share (swarmvm.boundary.arguments).
_NAME = optional(text)
_TARGET = one_of(TARGETS, "target")
_MAX_STATES = integer(1)
_SEED = integer(0, python_app().SEED_MAX)          # the VM's 32-bit generator (swarmvm.cli.options.SEED)
_SYNTH_FORMATS = ("yaml", "gen")

load = checked(paths=file_names)(pipeline.load)


@dataclass(frozen=True)
class CheckRow:
    """What ``swarmvm check`` prints for one file: counts as read, and the file's size."""
    file: str
    events: int
    supervisors: int
    states: int
    transitions: int
    bytes: int


@checked(inputs=file_names, name=_NAME, names=flag)
def compile_model(inputs: Sequence[str], name: str | None = None, names: bool = True) -> Compiled:
    """Load, validate, canonicalise, build tables and pack the image of one supervisor set
    (one supervisor.yaml, or Nadzoru 2 XML automata)."""
    return compile_inputs(list(inputs), name=name, names=names)


@checked(data=instance((bytes, bytearray, memoryview), "bytes"), source=text)
def parse_image(data: bytes, source: str = "<image>") -> "Image":
    """A table image from bytes, checked (magic, version, checksum, bounds)."""
    try:
        return _vm.Image.parse(data)
    except _vm.ImageError as exc:
        raise InputError(source, "image", str(exc))


@checked(path=file_name)
def read_image(path: str) -> "Image":
    """A table image (``.svm``) from a file, checked like :func:`parse_image`."""
    return parse_image(read_input(path), path)


@checked(paths=file_names, target=optional(_TARGET), name=_NAME)
def check(paths: Sequence[str], target: str | None = None, name: str | None = None) -> tuple[list[CheckRow], list[str]]:
    """Validate each file (supervisor or ``.svm`` image): its row (the file named as given, so that
    two roles' supervisor.yaml rows differ), and the models' warnings.
    With ``target``, each supervisor must also pass that target's own rules (its code is
    rendered in memory, as ``gen`` would with ``name``, and nothing is written)."""
    rows: list[CheckRow] = []
    warnings: list[str] = []
    for path in paths:
        file = path
        if path.endswith(".svm"):
            image = read_image(path)
            rows.append(CheckRow(file, image.num_events, image.num_supervisors, len(image.state_defined),
                                 len(image.targets), len(image.raw)))
            continue
        spec = load([path])
        compiled = compile_spec(spec, [path], name=name)
        if target is not None:
            generate(compiled, target)
        warnings += compiled.model.warnings
        events, supervisors, states, transitions = spec.counts()
        rows.append(CheckRow(file, events, supervisors, states, transitions, spec.size_bytes))
    return rows, warnings


@checked(inputs=file_names, output=file_name, names=flag)
def write_image(inputs: Sequence[str], output: str, names: bool = True) -> Compiled:
    """Compile and write the table image to ``output`` (atomically). A supervisor.yaml is read
    as the published VMs read it, and its image carries what their exact mode needs (pipeline's
    ``packed_image``: docs/compat.md)."""
    compiled = compile_inputs(list(inputs), names=names, published=True)
    target = Path(output).absolute()
    write_outputs(target.parent, {target.name: (compiled.packed_image, False)})
    return compiled


@checked(compiled=instance(Compiled, "a Compiled"), target=_TARGET, specs=texts)
def learned_pairs(compiled: Compiled, target: str, specs: Sequence[str]) -> list[dict[str, str]]:
    """``YES/NO`` specifications of learned checks as [{yes, no}] of bare event names: two
    distinct uncontrollable events of the model, each in one pair only (docs/learning.md)."""
    model, source = compiled.model, compiled.model.source
    if specs and not TARGETS[target].learned_templates:
        raise InputError(source, "--learned-check", "target %s does not generate learned checks" % target)
    pairs, used = [], set()
    for spec in specs:
        names = [n[3:] if n.startswith("EV_") else n for n in spec.split("/")]
        if len(names) != 2 or names[0] == names[1]:
            raise InputError(source, "--learned-check", "%r is not YES/NO (two different event names)" % spec)
        for bare in names:
            if bare not in model.events:
                raise InputError(source, "--learned-check", "no event named %r" % bare)
            if model.controllable[model.events.index(bare)]:
                raise InputError(source, "--learned-check", "%s is controllable: only checks can be learned" % bare)
            if bare in used:
                raise InputError(source, "--learned-check", "%s is in two learned checks" % bare)
            used.add(bare)
        pairs.append(dict(yes=names[0], no=names[1]))
    return pairs


@dataclass(frozen=True)
class Generated:
    """What ``generate_target`` did: the compiled model, the paths written, and the kept user
    files that no longer match the model (user_files.Drift)."""
    compiled: Compiled
    written: list[str]
    drifts: list[Drift]


@checked(inputs=file_names, target=_TARGET, outdir=file_name, name=_NAME, learned=texts, sct_header=_NAME)
def generate_target(inputs: Sequence[str], target: str, outdir: str, name: str | None = None,
                    learned: Sequence[str] = (), sct_header: str | None = None) -> Generated:
    """Generate a target's sources into ``outdir`` (all files or none). Files ``gen`` owns are
    rewritten; user files that exist are kept, and compared with a fresh skeleton: where they
    drifted, the skeleton is written beside them as ``<file>.new``. ``sct_header``: also a
    header of that name for a published program's include (a C target; swarmvm.targets.c.sct_header)."""
    compiled = compile_model(inputs, name=name)
    files = generate(compiled, target, learned_checks=learned_pairs(compiled, target, learned))
    if sct_header is not None:
        header, data = c_target.sct_header(compiled, TARGETS[target], sct_header, files)
        files[header] = (data, False)
    drifts = []
    generated = [data for data, keep in files.values() if not keep]
    for rel, (data, keep) in sorted(files.items()):
        path = Path(outdir) / rel
        found = drift(path, data, compiled.name, generated) if keep and path.is_file() else None
        if found:
            drifts.append(found)
            files[rel + ".new"] = (data, False)
    return Generated(compiled, write_outputs(outdir, files), drifts)


@checked(inputs=file_names, steps=integer(1), seed=_SEED, density=number(0, 1))
def script_lines(inputs: Sequence[str], steps: int, seed: int, density: float = 0.25) -> Iterator[str]:
    """The lines (without newlines) of a reproducible random event script (docs/conformance.md)
    for a supervisor, produced as they are read. The supervisor is compiled first, so bad input
    raises InputError here, before any line."""
    compiled = compile_model(inputs)
    return script.script_lines(script.random_rows(compiled.tables, steps, seed, density), compiled.model.events)


@checked(inputs=file_names, steps=integer(1), seed=_SEED, density=number(0, 1))
def make_script(inputs: Sequence[str], steps: int, seed: int, density: float = 0.25) -> str:
    """A reproducible random event script (docs/conformance.md) for a supervisor, as text."""
    return "".join(line + "\n" for line in script_lines(inputs, steps, seed, density))


def _image_of(inputs: Sequence[str]) -> "Image":
    if len(inputs) == 1 and inputs[0].endswith(".svm"):
        return read_image(inputs[0])
    return _vm.Image.parse(compile_model(inputs).image)


@checked(inputs=file_names, script_path=file_name, seed=_SEED, input_mode=one_of(_vm.INPUT_MODES, "input mode"),
         control=one_of(_vm.CONTROL_MODES, "control mode"), policy=one_of(python_app().OPTION_POLICIES, "policy"))
def trace(inputs: Sequence[str], script_path: str, seed: int = 1, input_mode: str = "level",
          control: str = "after-inputs", policy: str = "uniform") -> Iterator[str]:
    """The canonical trace lines of the reference VM replaying an event script, produced as
    they are read (a script of millions of steps in constant memory); bad input raises
    InputError here, before the first line (``script_path`` ``-``, standard input: past its
    first errors.MAX_BYTES, when the bad line is reached).

    ``inputs`` is a supervisor or one ``.svm`` image (which must carry event names)."""
    image = _image_of(inputs)
    if image.names is None:
        raise InputError(inputs[0], "image", "carries no event names; scripts name events")
    rows = read_script_rows(script_path, image.names, image.controllable)
    machine = _vm.VM(image, inputs=input_mode, control=control, policy=policy, seed=seed)
    return _vm.replay_lines(machine, rows)


@checked(elfs=file_names, indirect=texts, cycles=optional(file_name), frames=texts)
def measure_footprint(elfs: Sequence[str], indirect: Sequence[str] = (), cycles: str | None = None,
                      frames: Sequence[str] = ()) -> list[fp.Footprint]:
    """Flash, static RAM and worst-case stack of linked VM images (docs/footprint.md); ``indirect``:
    ``CALLER=TARGET,...`` declarations of what an indirect call in CALLER may reach; ``cycles``:
    an event script each image runs in the emulator for its cycles per step (its checks answered
    through the dispatch declared for ``svm_step``). The declarations of the image's target record
    (``elf.indirect``: what the generated program's own indirect calls reach) come first, so a
    generated project needs none of its own, nor do those of the sidecar gen wrote beside it
    (``X.footprint.json`` beside ``X.elf``, refused when it is not of this image's build:
    swarmvm.footprint.sidecar); ``indirect`` adds to them, and ``cycles`` may name that sidecar,
    whose event script it runs. ``frames``: ``FUNCTION=BYTES``
    declarations of the frames of functions with no .su entry whose code does not make theirs certain."""
    from elftools.common.exceptions import ELFError
    given = parse_indirect(indirect)
    declared_frames = parse_frames(frames)
    rows = []
    for path in elfs:
        try:
            footprint = fp.measure(path)
            record = TARGETS[footprint.target].elf
            calls = parse_indirect(record.indirect if record is not None else ())
            sidecar = sidecar_of(path, footprint.target, footprint.tables_sha256)     # gen's, beside the ELF
            beside = parse_indirect(sidecar.indirect, sidecar.path) if sidecar is not None else {}
            for caller, targets in (*beside.items(), *given.items()):
                calls[caller] = tuple(dict.fromkeys(calls.get(caller, ()) + targets))
            footprint.indirect = calls
            footprint.frames = declared_frames
            footprint.stack = measure_stack(path, footprint.target, calls, frames=declared_frames)
            if cycles is not None:
                footprint.cycles = measure_cycles(path, footprint.target, fp.table_image(path), cycles,
                                                  calls.get(STEP_ROOT, ()))
            rows.append(footprint)
        except ELFError as exc:
            raise fp.FootprintError("%s: not an ELF image (%s)" % (path, exc))
        except OSError as exc:
            raise fp.FootprintError("%s: cannot read file (%s)" % (path, exc.strerror))
        except InputError as exc:     # the input layer's refusal: missing, a FIFO, a device, too large
            raise fp.FootprintError(str(exc)) from None
    return rows


@checked(elfs=file_names, budget=optional(file_name), baseline=optional(file_name),
         fail_on_growth=optional(number(0, float("inf"))), limits=instance(fp.Limits, "a swarmvm.footprint.measure.Limits"),
         indirect=texts, cycles=optional(file_name), frames=texts, symbols=optional(integer(1)))
def footprint_report(elfs: Sequence[str], budget: str | None = None, baseline: str | None = None,
                     fail_on_growth: float | None = None, limits: fp.Limits = fp.Limits(),
                     indirect: Sequence[str] = (), cycles: str | None = None,
                     frames: Sequence[str] = (), symbols: int | None = None) -> fp_report.FootprintReport:
    """The footprint of linked images checked against ``limits`` and the budgets of the TOML file
    ``budget`` (``[tool.swarmvm.footprint]`` of a ``pyproject.toml``), compared with the JSON report
    ``baseline``, each column's growth judged against ``fail_on_growth`` per cent, indirect calls
    resolved by the ``indirect`` declarations, each image run with the event script ``cycles``
    for its cycles per step (measure_footprint); the files are read first, so a bad one raises
    InputError before any image is measured (docs/footprint.md).
    ``swarmvm.footprint.report`` writes it as Markdown, JUnit XML or JSON; ``failures()`` is empty
    when it passes. ``symbols``: the N largest section and symbol changes of each row against the
    baseline (as Bloaty's ``-d sections,symbols``)."""
    if fail_on_growth is not None and baseline is None:
        raise InputError("", "fail_on_growth", "growth is measured against a baseline: give one")
    if symbols is not None and baseline is None:
        raise InputError("", "symbols", "the section and symbol changes are against a baseline: give one")
    budgets = read_budgets(budget) if budget is not None else Budgets()
    old = read_baseline(baseline) if baseline is not None else None
    parse_indirect(indirect)
    parse_frames(frames)
    return fp_report.build(measure_footprint(elfs, indirect, cycles, frames), limits, budgets, old, fail_on_growth,
                           symbols)


@checked(paths=file_names, max_states=_MAX_STATES, all_findings=flag)
def check_properties(paths: Sequence[str], max_states: int = DEFAULT_MAX_STATES,
                     all_findings: bool = False) -> list[str]:
    """The design checks of each supervisor set (docs/models.md), one report per file, listing
    the first three findings of each check (every one with ``all_findings``); a set whose
    product is over ``max_states`` states is refused (docs/limits.md)."""
    examples = None if all_findings else 3
    return [format_report(path, properties.check_properties(compile_model([path]).model, max_states), examples)
            for path in paths]


@checked(a=file_name, b=file_name, max_states=_MAX_STATES)
def equivalent(a: str, b: str, max_states: int = DEFAULT_MAX_STATES) -> tuple[bool, str]:
    """Whether supervisor sets A and B have the same events and conjunction language, and the
    report (a shortest distinguishing event sequence when not); refused past ``max_states``
    pairs of product states explored (docs/limits.md)."""
    difference = compare(compile_model([a]).model, compile_model([b]).model, max_states)
    return difference is None, format_difference(a, b, difference)


@checked(model=instance(Model, "a Model"), name=text, fmt=one_of(FORMATS, "format"), output=file_name,
         product_limit=integer(0), max_states=_MAX_STATES)
def write_export(model: Model, name: str, fmt: str, output: str, product_limit: int = 200,
                 max_states: int = DEFAULT_MAX_STATES) -> list[str]:
    """Write a model as ``fmt`` (export.FORMATS): yaml to the file ``output``, the others into
    the directory ``output``. The paths written."""
    files = export_files(model, name, fmt, product_limit, max_states)
    if fmt == "yaml":
        target = Path(output)
        return write_outputs(target.parent, {target.name: (files[name + ".yaml"], False)})
    return write_outputs(output, {rel: (data, False) for rel, data in files.items()})


@checked(inputs=file_names, fmt=one_of(FORMATS, "format"), output=file_name, name=_NAME, product_limit=integer(0),
         max_states=_MAX_STATES)
def export(inputs: Sequence[str], fmt: str, output: str, name: str | None = None,
           product_limit: int = 200, max_states: int = DEFAULT_MAX_STATES) -> tuple[Compiled, list[str]]:
    """Write a supervisor set as Nadzoru 2 YAML, libFAUDES .gen or Graphviz pictures (the
    product drawn up to ``product_limit`` states, explored within ``max_states``)."""
    compiled = compile_model(inputs, name=name)
    return compiled, write_export(compiled.model, file_stem(compiled.stem, compiled.source), fmt, output, product_limit,
                                  max_states)


@checked(models=file_names, script_path=optional(file_name), statements=texts, exports=texts, minimise=flag,
         fmt=one_of(_SYNTH_FORMATS, "format"), output=file_name, max_states=_MAX_STATES)
def synthesise_models(models: Sequence[str], script_path: str | None, statements: Sequence[str],
                      exports: Sequence[str], minimise: bool, fmt: str, output: str,
                      max_states: int = DEFAULT_MAX_STATES) -> list[str]:
    """Local modular synthesis (libFAUDES) from plants and specifications by a script
    (docs/models.md); writes the supervisor set as ``fmt`` and returns the paths written. A
    step whose product is over ``max_states`` states is refused before libFAUDES runs it."""
    script = read_synth_script(script_path, statements)
    spec = synthesise(script, models_by_name(list(models)), exports, minimise, max_states)
    compiled = compile_spec(spec, [output])       # files named after the output
    return write_export(compiled.model, file_stem(compiled.stem, output, "--output"), fmt, output, 0)


@checked(supervisor=file_name, traces=maybe_file_names, output=file_name, name=_NAME, compare=flag, first_step=integer(1))
def inspect(supervisor: str, traces: Sequence[str], output: str, name: str | None = None, compare: bool = False,
            first_step: int = 1) -> Inspection:
    """Write the inspector's page (docs/inspect.md) to ``output``: one self-contained HTML file
    drawing the supervisors and replaying the canonical traces (one per robot; ``compare``: two,
    with the first step where they differ), from step ``first_step`` on, titled ``name`` (default:
    the supervisor's file stem). Every trace is read and checked before the page is written."""
    if compare and len(traces) != 2:
        raise InputError("", "compare", "compares exactly two traces, got %d" % len(traces))
    compiled = compile_model([supervisor])
    return write_page(compiled.model, compiled.stem if name is None else name, traces, output, compare, first_step)


@checked(project=file_name, variant=optional(one_of(VARIANTS, "variant")))
def compat_switch(project: str, variant: str | None = None) -> Switch:
    """Switch the OpenSwarm ARGoS project in the folder ``project`` (the one holding ``src/``)
    from the published VM to swarmvm's sct.h, editing its build files and includes as they are
    (swarmvm.compat.switch; docs/compat.md): every changed file written, or none. Run
    again, it writes nothing. ``variant`` ("default" or "mhsc") overrides the published variant
    read from the project."""
    return switch_project(Path(project), variant)
